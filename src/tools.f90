!> tools -- rigid tools as chains of straight segments and circular arcs:
!> construction and validation of a chain, its extent, level and sampling.
!> The signed distance of the penalty contact (2.18)-(2.20) is module
!> tool_distance; the rectangular bead of Fig. 3 is built by module
!> bead_builder, profile files are read and written by module profile_io.
!>
!> GEOMETRY.  A tool is a chain of pieces (lines and arcs) describing the
!> surface that the sheet CENTRELINE touches (the physical tool surface offset
!> by h/2 toward the sheet; docs/theory.md §5).  Consecutive pieces share end
!> points, and the chain runs left to right overall (last end x > first start
!> x, first and last pieces heading in +x).  Pieces may go up, down or even
!> back (vertical walls are fine).  The tool's material lies
!>   side = +1 (upper / female tool): on the LEFT of the direction of travel,
!>             i.e. above a piece heading in +x;
!>   side = -1 (lower / male tool):   on the RIGHT of the direction of travel,
!>             i.e. below a piece heading in +x.
!> The chain is not closed: queries beyond its ends see the end pieces
!> continued along their END TANGENT LINES (half-lines).  A profile must
!> therefore cover the whole sheet span with room for the sheet's sliding;
!> the builders extend the binder faces to the caller's x_min, x_max.
!> The chain must not intersect itself (not checked).
!> A tool is stored at rest.  The lower tool's rise H during locking is not
!> part of it: the caller queries the stored chain at (x, y - H) (module
!> contact) and draws it raised by H (module output), so one tool serves
!> every H.
!>
!> arcs (d = sgn (R - |p - c|)).
module tools
   use kinds, only: dp, pi
   use text, only: itoa
   implicit none
   private
   public :: seg_line, seg_arc, segment_type, tool_type
   public :: line_segment, arc_segment, tool_init, check_chain, radius_tol
   public :: tool_sample, tool_level, tangent_tol, cross2, normal_of, in_arc, arc_tangent

   !> kinds of piece
   integer, parameter :: seg_line = 1, seg_arc = 2

   !> half-open angle tolerance (rad) under which a junction counts as smooth
   real(dp), parameter :: tangent_tol = 1.0e-6_dp
   !> relative continuity tolerance of tool_init (times the chain's size)
   real(dp), parameter :: cont_tol_rel = 1.0e-9_dp
   !> an arc's end lies on its circle: |end - centre| = |start - centre|
   !> within this relative tolerance (tool_init and the profile files)
   real(dp), parameter :: radius_tol = 1.0e-6_dp

   !> One piece of a chain.  Lines use p1, p2, t1 (= t2); arcs also centre,
   !> radius, the angles of p1 and p2 about the centre (atan2, in (-pi, pi]),
   !> the sense (+1 ccw, -1 cw) and the signed sweep theta2 - theta1 in the
   !> sense of travel (0 < |sweep| < 2 pi, > 0 for ccw).
   type :: segment_type
      integer :: kind = seg_line
      real(dp) :: p1(2) = 0.0_dp, p2(2) = 0.0_dp       ! start, end point
      real(dp) :: centre(2) = 0.0_dp, radius = 0.0_dp  ! arcs only
      real(dp) :: theta1 = 0.0_dp, theta2 = 0.0_dp     ! arcs only
      real(dp) :: sweep = 0.0_dp                       ! arcs only
      integer :: sense = 0                             ! arcs: +1 ccw, -1 cw
      real(dp) :: length = 0.0_dp
      real(dp) :: t1(2) = 0.0_dp, t2(2) = 0.0_dp       ! unit tangents at p1, p2
      real(dp) :: box(4) = 0.0_dp                      ! x_min, x_max, y_min, y_max
   end type segment_type

   !> A rigid tool at rest: chain of pieces, material side and the chain's
   !> size (the scale of the distance tolerances).  Build with tool_init,
   !> build_rectangular_bead (bead_builder) or read_profile (profile_io),
   !> which validate the chain.
   type :: tool_type
      type(segment_type), allocatable :: seg(:)
      integer :: nseg = 0
      integer :: side = 0              ! +1 upper (material above), -1 lower
      real(dp) :: size = 0.0_dp        ! larger side of the chain's bounding box, mm
      !> (4, nseg) the pieces' boxes (seg(i)%box) side by side: tool_gap
      !> scans them for every station, and a piece's record is 26 words
      real(dp), allocatable :: box(:, :)
   end type tool_type

contains

   ! ------------------------------------------------------------------
   ! construction
   ! ------------------------------------------------------------------

   !> LINE_SEGMENT: a straight piece from p1 to p2.
   !>  p1, p2 [in] start and end point, mm
   !> A zero-length segment is returned with length = 0 (tool_init rejects it).
   pure function line_segment(p1, p2) result(seg)
      real(dp), intent(in) :: p1(2), p2(2)
      type(segment_type) :: seg
      real(dp) :: len
      seg%kind = seg_line
      seg%p1 = p1
      seg%p2 = p2
      len = norm2(p2 - p1)
      seg%length = len
      if (len > 0.0_dp) then
         seg%t1 = (p2 - p1)/len
      else
         seg%t1 = [1.0_dp, 0.0_dp]
      end if
      seg%t2 = seg%t1
      seg%box = [min(p1(1), p2(1)), max(p1(1), p2(1)), min(p1(2), p2(2)), max(p1(2), p2(2))]
   end function line_segment

   !> ARC_SEGMENT: a circular arc from p1 to p2 about centre.
   !>  p1, p2  [in] start and end point, mm
   !>  centre  [in] centre, mm; the radius is |p1 - centre|
   !>  ccw     [in] .true. counter-clockwise from p1 to p2, .false. clockwise
   !> p2 is kept as given (its distance to the centre is checked by tool_init).
   !> A degenerate arc (zero radius or p1 = p2) has length = 0.
   pure function arc_segment(p1, p2, centre, ccw) result(seg)
      real(dp), intent(in) :: p1(2), p2(2), centre(2)
      logical, intent(in) :: ccw
      type(segment_type) :: seg
      real(dp) :: sw, ang
      integer :: k
      seg%kind = seg_arc
      seg%p1 = p1
      seg%p2 = p2
      seg%centre = centre
      seg%radius = norm2(p1 - centre)
      seg%sense = merge(1, -1, ccw)
      seg%box = [min(p1(1), p2(1)), max(p1(1), p2(1)), min(p1(2), p2(2)), max(p1(2), p2(2))]
      if (seg%radius <= 0.0_dp .or. norm2(p2 - centre) <= 0.0_dp) then
         seg%length = 0.0_dp
         seg%t1 = [1.0_dp, 0.0_dp]
         seg%t2 = seg%t1
         return
      end if
      seg%theta1 = atan2(p1(2) - centre(2), p1(1) - centre(1))
      seg%theta2 = atan2(p2(2) - centre(2), p2(1) - centre(1))
      sw = modulo(real(seg%sense, dp)*(seg%theta2 - seg%theta1), 2.0_dp*pi)
      if (norm2(p2 - p1) <= 0.0_dp) sw = 0.0_dp
      seg%sweep = real(seg%sense, dp)*sw
      seg%length = seg%radius*sw
      seg%t1 = arc_tangent(seg, seg%theta1)
      seg%t2 = arc_tangent(seg, seg%theta2)
      ! the axis-extreme points of the circle inside the arc widen the box
      do k = 0, 3
         ang = 0.5_dp*pi*real(k, dp)
         if (in_arc(seg, [cos(ang), sin(ang)])) then
            seg%box(1) = min(seg%box(1), centre(1) + seg%radius*cos(ang))
            seg%box(2) = max(seg%box(2), centre(1) + seg%radius*cos(ang))
            seg%box(3) = min(seg%box(3), centre(2) + seg%radius*sin(ang))
            seg%box(4) = max(seg%box(4), centre(2) + seg%radius*sin(ang))
         end if
      end do
   end function arc_segment

   !> TOOL_INIT: validate a chain and store it in a tool.
   !>  tool   [out] the tool
   !>  segs   [in]  pieces in chain order (from line_segment / arc_segment)
   !>  side   [in]  +1 material above (upper/female), -1 below (lower/male)
   !>  errmsg [out] blank on success, else what is wrong (piece numbered)
   !>  stat   [out] optional: 0 on success, else the number of the bad piece
   !>               (or size(segs)+1 for a whole-chain problem)
   !> Checks: side = +-1; at least one piece; no zero-length piece, no zero
   !> radius, arc end on its circle (1e-6 relative); consecutive pieces
   !> continuous within 1e-9 x size; no cusp (180 degree turn back); the first
   !> and last pieces head in +x; last end x > first start x.
   pure subroutine tool_init(tool, segs, side, errmsg, stat)
      type(tool_type), intent(out) :: tool
      type(segment_type), intent(in) :: segs(:)
      integer, intent(in) :: side
      character(len=*), intent(out) :: errmsg
      integer, intent(out), optional :: stat
      integer :: ibad, i
      real(dp) :: xmn, xmx, ymn, ymx
      call check_chain(segs, side, cont_tol_rel, .true., errmsg, ibad)
      if (present(stat)) stat = ibad
      if (ibad /= 0) return
      tool%nseg = size(segs)
      tool%seg = segs
      allocate (tool%box(4, size(segs)))
      do i = 1, size(segs)
         tool%box(:, i) = segs(i)%box
      end do
      tool%side = side
      call chain_extent(segs, xmn, xmx, ymn, ymx)
      tool%size = max(xmx - xmn, ymx - ymn)
   end subroutine tool_init

   !> CHECK_CHAIN: the validation behind tool_init (also run by read_profile
   !> with its own continuity tolerance, to name the file line of a bad piece).
   !>  segs     [in]  pieces
   !>  side     [in]  material side
   !>  cont_tol [in]  continuity tolerance: relative to the chain size when
   !>                 relative, else in mm
   !>  relative [in]  how cont_tol is read
   !>  errmsg   [out] blank or the problem
   !>  ibad     [out] 0, the bad piece, or size(segs)+1 (whole chain)
   pure subroutine check_chain(segs, side, cont_tol, relative, errmsg, ibad)
      type(segment_type), intent(in) :: segs(:)
      integer, intent(in) :: side
      real(dp), intent(in) :: cont_tol
      logical, intent(in) :: relative
      character(len=*), intent(out) :: errmsg
      integer, intent(out) :: ibad
      real(dp) :: xmn, xmx, ymn, ymx, sz, tol, gap, nsum(2)
      integer :: i, im, n
      errmsg = ''
      ibad = 0
      n = size(segs)
      if (side /= 1 .and. side /= -1) then
         errmsg = 'tool side must be +1 (upper) or -1 (lower)'
         ibad = n + 1
         return
      end if
      if (n < 1) then
         errmsg = 'a tool needs at least one piece'
         ibad = 1
         return
      end if
      call chain_extent(segs, xmn, xmx, ymn, ymx)
      sz = max(xmx - xmn, ymx - ymn, tiny(1.0_dp))
      tol = merge(cont_tol*sz, cont_tol, relative)
      do i = 1, n
         if (segs(i)%kind /= seg_line .and. segs(i)%kind /= seg_arc) then
            errmsg = 'piece '//itoa(i)//': unknown kind'
         else if (segs(i)%kind == seg_arc .and. segs(i)%radius <= 1.0e-12_dp*sz) then
            errmsg = 'piece '//itoa(i)//': zero arc radius'
         else if (segs(i)%length <= 1.0e-12_dp*sz) then
            errmsg = 'piece '//itoa(i)//': zero length'
         else if (segs(i)%kind == seg_arc) then
            if (abs(norm2(segs(i)%p2 - segs(i)%centre) - segs(i)%radius) > &
                radius_tol*segs(i)%radius) then
               errmsg = 'piece '//itoa(i)//': end point not on the arc''s circle '// &
                        '(|end - centre| /= |start - centre|)'
            end if
         end if
         if (len_trim(errmsg) == 0 .and. i > 1) then
            im = max(i - 1, 1)
            gap = norm2(segs(i)%p1 - segs(im)%p2)
            if (gap > tol) then
               write (errmsg, '(a, i0, a, es10.3, a)') 'piece ', i, &
                  ': does not start where the previous piece ends (gap ', gap, ' mm)'
            else
               nsum = normal_of(segs(im)%t2, side) + normal_of(segs(i)%t1, side)
               if (norm2(nsum) < 1.0e-6_dp) errmsg = 'piece '//itoa(i)// &
                  ': turns back on the previous piece (cusp)'
            end if
         end if
         if (len_trim(errmsg) > 0) then
            ibad = i
            return
         end if
      end do
      if (segs(n)%p2(1) <= segs(1)%p1(1)) then
         errmsg = 'the chain must run left to right (last end x > first start x)'
         ibad = n + 1
      else if (segs(1)%t1(1) <= 0.0_dp) then
         errmsg = 'the first piece must head in +x (its tangent line extends the chain to the left)'
         ibad = 1
      else if (segs(n)%t2(1) <= 0.0_dp) then
         errmsg = 'the last piece must head in +x (its tangent line extends the chain to the right)'
         ibad = n
      end if
   end subroutine check_chain

   !> CHAIN_EXTENT: bounding box of a list of pieces.
   pure subroutine chain_extent(segs, xmn, xmx, ymn, ymx)
      type(segment_type), intent(in) :: segs(:)
      real(dp), intent(out) :: xmn, xmx, ymn, ymx
      integer :: i
      xmn = huge(1.0_dp); xmx = -huge(1.0_dp)
      ymn = huge(1.0_dp); ymx = -huge(1.0_dp)
      do i = 1, size(segs)
         xmn = min(xmn, segs(i)%box(1)); xmx = max(xmx, segs(i)%box(2))
         ymn = min(ymn, segs(i)%box(3)); ymx = max(ymx, segs(i)%box(4))
      end do
      if (size(segs) == 0) then
         xmn = 0.0_dp; xmx = 0.0_dp; ymn = 0.0_dp; ymx = 0.0_dp
      end if
   end subroutine chain_extent


   !> TOOL_SAMPLE: n points equally spaced in arc length along the chain
   !> (ends included; the tool at rest), for plotting.
   !>  tool [in]  the tool
   !>  n    [in]  number of points (n >= 1; n = 1 gives the start point)
   !>  xy   [out] xy(:, k) = (x, y) of point k, mm; dimension (2, n)
   pure subroutine tool_sample(tool, n, xy)
      type(tool_type), intent(in) :: tool
      integer, intent(in) :: n
      real(dp), intent(out) :: xy(2, n)
      real(dp) :: total, s, s0, u
      integer :: k, i
      if (n < 1 .or. tool%nseg < 1) return
      total = sum(tool%seg(1:tool%nseg)%length)
      i = 1
      s0 = 0.0_dp
      do k = 1, n
         if (n == 1) then
            s = 0.0_dp
         else
            s = total*real(k - 1, dp)/real(n - 1, dp)
         end if
         do while (i < tool%nseg .and. s > s0 + tool%seg(i)%length)
            s0 = s0 + tool%seg(i)%length
            i = i + 1
         end do
         u = min(max((s - s0)/tool%seg(i)%length, 0.0_dp), 1.0_dp)
         xy(:, k) = piece_point(tool%seg(i), u)
      end do
   end subroutine tool_sample

   !> TOOL_LEVEL: height of the tool surface (at rest) above abscissa x, from
   !> the first piece whose x range contains x, or the end pieces' tangent
   !> lines beyond the chain.  Meant for the binder faces at the sheet's edges.
   !>  tool  [in]  the tool
   !>  x     [in]  abscissa, mm
   !>  y     (result) surface height at x, mm
   pure function tool_level(tool, x) result(y)
      type(tool_type), intent(in) :: tool
      real(dp), intent(in) :: x
      real(dp) :: y, lo, hi, mid, p(2)
      integer :: i, it
      associate (first => tool%seg(1), last => tool%seg(tool%nseg))
         if (x <= first%p1(1)) then
            y = first%p1(2) + (x - first%p1(1))*first%t1(2)/first%t1(1)
            return
         end if
         if (x >= last%p2(1)) then
            y = last%p2(2) + (x - last%p2(1))*last%t2(2)/last%t2(1)
            return
         end if
      end associate
      y = 0.0_dp
      do i = 1, tool%nseg
         associate (sg => tool%seg(i))
            if ((sg%p1(1) - x)*(sg%p2(1) - x) > 0.0_dp) cycle
            ! bisection on the piece parameter for x(u) = x
            lo = 0.0_dp
            hi = 1.0_dp
            do it = 1, 60
               mid = 0.5_dp*(lo + hi)
               p = piece_point(sg, mid)
               if ((p(1) - x)*(sg%p1(1) - x) > 0.0_dp) then
                  lo = mid
               else
                  hi = mid
               end if
            end do
            p = piece_point(sg, 0.5_dp*(lo + hi))
            y = p(2)
            return
         end associate
      end do
   end function tool_level

   !> PIECE_POINT: the point at fraction u (0..1 of the length) of a piece.
   !>  seg [in]  the piece
   !>  u   [in]  fraction of its length (clamped to 0..1)
   !>  pt  (result) the point, mm
   pure function piece_point(seg, u) result(pt)
      type(segment_type), intent(in) :: seg
      real(dp), intent(in) :: u
      real(dp) :: pt(2), ang
      if (u <= 0.0_dp) then
         pt = seg%p1
      else if (u >= 1.0_dp) then
         pt = seg%p2
      else if (seg%kind == seg_line) then
         pt = seg%p1 + u*(seg%p2 - seg%p1)
      else
         ang = seg%theta1 + u*seg%sweep
         pt = seg%centre + seg%radius*[cos(ang), sin(ang)]
      end if
   end function piece_point

   ! ------------------------------------------------------------------
   ! small geometry helpers
   ! ------------------------------------------------------------------

   !> CROSS2: z-component of a x b.
   pure real(dp) function cross2(a, b)
      real(dp), intent(in) :: a(2), b(2)
      cross2 = a(1)*b(2) - a(2)*b(1)
   end function cross2

   !> NORMAL_OF: outward normal for travel direction t: side*(t_y, -t_x).
   pure function normal_of(t, side) result(nrm)
      real(dp), intent(in) :: t(2)
      integer, intent(in) :: side
      real(dp) :: nrm(2)
      nrm = real(side, dp)*[t(2), -t(1)]
   end function normal_of

   !> IN_ARC: does the direction v from an arc's centre point into the arc's
   !> angular range?  The signs of two cross products with the end
   !> directions decide (no angle, so no atan2 in the contact search).
   pure logical function in_arc(seg, v)
      type(segment_type), intent(in) :: seg
      real(dp), intent(in) :: v(2)
      real(dp) :: c1, c2
      ! c1 >= 0: v at most pi past the start in the sense of travel;
      ! c2 >= 0: v at most pi before the end
      c1 = real(seg%sense, dp)*cross2(seg%p1 - seg%centre, v)
      c2 = real(seg%sense, dp)*cross2(v, seg%p2 - seg%centre)
      if (abs(seg%sweep) <= pi) then
         in_arc = c1 >= 0.0_dp .and. c2 >= 0.0_dp
      else
         ! outside is the wedge from the end to the start, less than pi
         in_arc = c1 >= 0.0_dp .or. c2 >= 0.0_dp
      end if
   end function in_arc

   !> ARC_TANGENT: unit tangent of an arc, in its sense, at polar angle ang.
   pure function arc_tangent(seg, ang) result(t)
      type(segment_type), intent(in) :: seg
      real(dp), intent(in) :: ang
      real(dp) :: t(2)
      t = real(seg%sense, dp)*[-sin(ang), cos(ang)]
   end function arc_tangent

end module tools
