!> bead_builder -- the paper's rectangular drawbead (Fig. 3) as two tool
!> chains (module tools), and the paper's bead A and bead B dimensions.
!>
!> The chains are the surfaces the sheet CENTRELINE touches (tools header):
!> the female (upper) tool with its groove and entry arcs, the male (lower)
!> tool with its flat top and corner arcs, both at rest (H = 0) and centred
!> on x = 0, their binder faces run out to the caller's x_min and x_max.
module bead_builder
   use kinds, only: dp
   use tools, only: segment_type, tool_type, line_segment, arc_segment, tool_init
   implicit none
   private
   public :: build_rectangular_bead, bead_a_over_h, bead_b_over_h

   !> Paper's bead dimensions in units of the sheet thickness h, in the
   !> argument order of build_rectangular_bead: (R1, R2, B1, B2, H1, H2).
   real(dp), parameter :: bead_a_over_h(6) = [4.66_dp, 4.66_dp, 4.16_dp, 8.83_dp, 1.56_dp, 5.66_dp]
   real(dp), parameter :: bead_b_over_h(6) = [4.66_dp, 4.66_dp, 13.0_dp, 18.32_dp, 0.0_dp, 5.66_dp]

contains

   !> BUILD_RECTANGULAR_BEAD: the paper's flat bead (Fig. 3, docs/theory.md §5)
   !> as centreline surfaces, both tools at rest (H = 0), centred on x = 0.
   !>  r1, r2  [in]  corner radii of the male (lower) and female (upper), mm
   !>  b1      [in]  half-width of the male's flat top, mm (>= 0)
   !>  b2      [in]  half-width of the female's groove, mm (> 0)
   !>  h1      [in]  height of the male's vertical sides, mm (>= 0; 0 = none)
   !>  h2      [in]  height of the female's vertical walls, mm (>= 0)
   !>  x_min, x_max [in] ends of both chains (binder faces run out to them);
   !>                must lie beyond both beads: x_min < -max(b1+r1, b2+r2),
   !>                x_max > max(b1+r1, b2+r2)
   !>  upper   [out] female tool, side +1: y = 0 for |x| >= b2+r2, entry arcs
   !>                about (+-(b2+r2), r2), walls x = +-b2 from y = r2 to
   !>                h2+r2, groove bottom y = h2+r2 (sharp concave corners)
   !>  lower   [out] male tool, side -1, at H = 0: top y = 0 for |x| <= b1,
   !>                corner arcs about (+-b1, -r1), sides x = +-(b1+r1) from
   !>                y = -r1 down to -(h1+r1), binder y = -(h1+r1) beyond
   !>                (sharp concave corners).  The caller raises it by H
   !>                (module contact queries it at y - H).
   !>  errmsg  [out] blank on success, else the problem
   !>  stat    [out] optional: 0 on success, 1 on bad input
   !> Zero-length pieces (b1 = 0, h1 = 0, h2 = 0) are left out.
   pure subroutine build_rectangular_bead(r1, r2, b1, b2, h1, h2, x_min, x_max, &
                                          upper, lower, errmsg, stat)
      real(dp), intent(in) :: r1, r2, b1, b2, h1, h2, x_min, x_max
      type(tool_type), intent(out) :: upper, lower
      character(len=*), intent(out) :: errmsg
      integer, intent(out), optional :: stat
      type(segment_type) :: s(9)
      real(dp) :: xo, xi, top, base
      integer :: n, ist
      errmsg = ''
      if (present(stat)) stat = 1
      if (.not. (r1 > 0.0_dp .and. r2 > 0.0_dp)) then
         errmsg = 'rectangular bead: radii R1, R2 must be > 0'
      else if (.not. (b1 >= 0.0_dp .and. b2 > 0.0_dp .and. h1 >= 0.0_dp .and. h2 >= 0.0_dp)) then
         errmsg = 'rectangular bead: need B1 >= 0, B2 > 0, H1 >= 0, H2 >= 0'
      else if (.not. (x_min < -max(b1 + r1, b2 + r2) .and. x_max > max(b1 + r1, b2 + r2))) then
         errmsg = 'rectangular bead: x_min, x_max must lie outside both beads (|x| > max(B1+R1, B2+R2))'
      end if
      if (len_trim(errmsg) > 0) return
      ! female (upper), side +1
      xo = b2 + r2
      top = h2 + r2
      n = 0
      call push(s, n, line_segment([x_min, 0.0_dp], [-xo, 0.0_dp]))
      call push(s, n, arc_segment([-xo, 0.0_dp], [-b2, r2], [-xo, r2], .true.))
      call push(s, n, line_segment([-b2, r2], [-b2, top]))
      call push(s, n, line_segment([-b2, top], [b2, top]))
      call push(s, n, line_segment([b2, top], [b2, r2]))
      call push(s, n, arc_segment([b2, r2], [xo, 0.0_dp], [xo, r2], .true.))
      call push(s, n, line_segment([xo, 0.0_dp], [x_max, 0.0_dp]))
      call tool_init(upper, s(1:n), 1, errmsg, ist)
      if (ist /= 0) then
         errmsg = 'rectangular bead, female: '//errmsg
         return
      end if
      ! male (lower) at H = 0, side -1
      xi = b1 + r1
      base = -(h1 + r1)
      n = 0
      call push(s, n, line_segment([x_min, base], [-xi, base]))
      call push(s, n, line_segment([-xi, base], [-xi, -r1]))
      call push(s, n, arc_segment([-xi, -r1], [-b1, 0.0_dp], [-b1, -r1], .false.))
      call push(s, n, line_segment([-b1, 0.0_dp], [b1, 0.0_dp]))
      call push(s, n, arc_segment([b1, 0.0_dp], [xi, -r1], [b1, -r1], .false.))
      call push(s, n, line_segment([xi, -r1], [xi, base]))
      call push(s, n, line_segment([xi, base], [x_max, base]))
      call tool_init(lower, s(1:n), -1, errmsg, ist)
      if (ist /= 0) then
         errmsg = 'rectangular bead, male: '//errmsg
         return
      end if
      if (present(stat)) stat = 0
   contains
      !> PUSH: append a piece unless it has zero length.
      pure subroutine push(list, k, piece)
         type(segment_type), intent(in out) :: list(:)
         integer, intent(in out) :: k
         type(segment_type), intent(in) :: piece
         if (piece%length <= 0.0_dp) return
         k = k + 1
         list(k) = piece
      end subroutine push
   end subroutine build_rectangular_bead

end module bead_builder
