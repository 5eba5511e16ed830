!> tools -- rigid tools as chains of straight segments and circular arcs:
!> signed distance queries for the penalty contact (2.18)-(2.20), the
!> rectangular bead builder of Fig. 3, and profile files.
!>
!> GEOMETRY.  A tool is a chain of pieces (lines and arcs) describing the
!> surface that the sheet CENTRELINE touches (the physical tool surface offset
!> by h/2 toward the sheet; DESIGN section 5).  Consecutive pieces share end
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
!> tool%shift is a rigid upward translation of the tool (the rise H of the
!> lower tool during locking): a query point (x, y) is compared with the
!> stored chain at (x, y - shift).  Stored geometry (and profile files)
!> describe the tool at shift = 0.
!>
!> SIGN CONVENTIONS of tool_gap (paper (2.18)-(2.20)).  Let q be the point of
!> the surface closest to p = (x, y), and n the unit normal at q pointing OUT
!> of the tool, toward the side where the sheet belongs.  Then
!>    d = -(p - q).n            d > 0: p inside the tool material (penetration)
!>                              d < 0: p outside, |d| is the distance
!>    grad d   = dd/dp   = -n                  (q moves along the surface)
!>    dn/dp    = dn_factor * t t^T = dn_factor (I - n n^T)
!>    hess d   = -dn/dp  = -dn_factor * t t^T
!>    dt/dp    = -dn_factor * n t^T
!> with t the unit tangent along the chain's direction of travel (left to
!> right overall), t = side*(-n_y, n_x), equivalently n = side*(t_y, -t_x).
!> dn_factor = kappa/(1 - kappa d), kappa the signed curvature of the
!> surface at q, positive where the tool is convex toward the sheet:
!>    line:                 0
!>    arc, centre c:        sgn/|p - c|,  sgn = +1 when c lies inside the tool
!>                          (convex: the male's top corners, the female's entry
!>                          corners), -1 when c lies on the sheet side (concave:
!>                          a round groove); sgn = sense*side, sense = +1 ccw
!>    sharp vertex q:       +-1/|p - q|, + at a convex vertex (p outside),
!>                          - at a concave vertex (p inside the material)
!> Paper's link: its n in (2.20) is grad d = -n here, its t_n = -k d H(d) n_paper
!> is the traction on the sheet, = +k d H(d) n.  The penalty energy
!> (k/2) d^2 H(d) of (2.18) gives the force on the sheet point
!>    F = k d H(d) n,   dF/dp = k H(d) (-n n^T + d dn_factor t t^T),
!> and the slip rate of (2.22) is t . (velocity of p relative to the tool).
!> Derivation of grad d: d = -(p - q(p)).n(p); dq/dp maps onto t (q slides
!> along the surface) and n . t = 0, while (p - q) is parallel to n and
!> n . dn/dp = 0 (n is unit), so dd/dp = -n.  For an arc of centre c,
!> n = sgn (p - c)/|p - c| and differentiating a unit vector v/|v| gives
!> (I - n n^T)/|v|, hence dn_factor = sgn/|p - c|.
!>
!> CLOSEST POINT.  Over all pieces (and the two end half-lines) the piece with
!> the smallest unsigned distance wins: a line by projection clamped to the
!> segment, an arc by radial projection when the angle lies in the arc's
!> range, else its nearer end point.  Where the winner's closest point is a
!> shared end point of two pieces:
!>  - tangent-continuous junction (tangents within 1e-6 rad, the normal case
!>    of arcs tangent to lines): the winning piece is continued smoothly past
!>    its end, so d, n, t and dn_factor stay continuous across the junction;
!>  - sharp vertex: n = +-(p - q)/|p - q|, signed by the vertex pseudo-normal
!>    (sum of the two pieces' normals), which gives the correct side for any
!>    turning angle.  Near a concave corner (the female's groove-bottom corners,
!>    the foot of the male's sides) a point inside the material has the
!>    penetration of the nearer face where its projection falls on that face,
!>    and the distance to the corner point in the quadrant behind the corner;
!>    d is continuous everywhere.
!> On the surface d = 0 exactly for lines (d = -(p - a).n) and to rounding for
!> arcs (d = sgn (R - |p - c|)).
!>
!> PROFILE FILES (docs/PROFILE_FORMAT.md).  Plain text, coordinates in mm at
!> shift = 0.  '#' starts a comment (whole line or trailing); blank lines are
!> skipped; keywords are case-insensitive; fields are separated by blanks.
!>    side upper|lower                   first data line, exactly once
!>    line x1 y1 x2 y2                   segment from (x1,y1) to (x2,y2)
!>    arc  x1 y1 x2 y2 xc yc ccw|cw      arc from (x1,y1) to (x2,y2) about the
!>                                       centre (xc,yc), counter-clockwise or
!>                                       clockwise (sense is required; an arc
!>                                       may exceed 180 degrees)
!> Pieces are listed in chain order, left to right overall.  The radius is
!> |start - centre|; |end - centre| must agree within 1e-6 relative.  Each
!> piece must start within 1e-6 mm of the previous piece's end (it is then
!> snapped onto it).  Errors are reported as '<path>:<line>: <what>'.
module tools
   use kinds, only: dp, pi
   implicit none
   private
   public :: seg_line, seg_arc, segment_type, tool_type
   public :: line_segment, arc_segment, tool_init
   public :: tool_gap, tool_sample, tool_level
   public :: build_rectangular_bead, bead_a_over_h, bead_b_over_h
   public :: read_profile, write_profile

   !> kinds of piece
   integer, parameter :: seg_line = 1, seg_arc = 2

   !> Paper's bead dimensions in units of the sheet thickness h, in the
   !> argument order of build_rectangular_bead: (R1, R2, B1, B2, H1, H2).
   real(dp), parameter :: bead_a_over_h(6) = [4.66_dp, 4.66_dp, 4.16_dp, 8.83_dp, 1.56_dp, 5.66_dp]
   real(dp), parameter :: bead_b_over_h(6) = [4.66_dp, 4.66_dp, 13.0_dp, 18.32_dp, 0.0_dp, 5.66_dp]

   !> half-open angle tolerance (rad) under which a junction counts as smooth
   real(dp), parameter :: tangent_tol = 1.0e-6_dp
   !> relative continuity tolerance of tool_init (times the chain's size)
   real(dp), parameter :: cont_tol_rel = 1.0e-9_dp
   !> profile files: continuity tolerance (mm) and radius agreement (relative)
   real(dp), parameter :: file_cont_tol = 1.0e-6_dp, file_radius_tol = 1.0e-6_dp

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

   !> A rigid tool: chain of pieces, material side, rigid upward shift and the
   !> chain's extent (at shift = 0).  Build with tool_init, a builder or
   !> read_profile, which validate the chain.
   type :: tool_type
      type(segment_type), allocatable :: seg(:)
      integer :: nseg = 0
      integer :: side = 0              ! +1 upper (material above), -1 lower
      real(dp) :: shift = 0.0_dp       ! rigid upward translation H
      real(dp) :: x_min = 0.0_dp, x_max = 0.0_dp, y_min = 0.0_dp, y_max = 0.0_dp
      real(dp) :: size = 0.0_dp        ! max(x_max - x_min, y_max - y_min)
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

   !> TOOL_INIT: validate a chain and store it in a tool (shift = 0).
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
      integer :: ibad
      call check_chain(segs, side, cont_tol_rel, .true., errmsg, ibad)
      if (present(stat)) stat = ibad
      if (ibad /= 0) return
      tool%nseg = size(segs)
      tool%seg = segs
      tool%side = side
      tool%shift = 0.0_dp
      call chain_extent(segs, tool%x_min, tool%x_max, tool%y_min, tool%y_max)
      tool%size = max(tool%x_max - tool%x_min, tool%y_max - tool%y_min)
   end subroutine tool_init

   !> CHECK_CHAIN: the validation behind tool_init.
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
      character(len=32) :: num
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
         write (num, '(i0)') i
         if (segs(i)%kind /= seg_line .and. segs(i)%kind /= seg_arc) then
            errmsg = 'piece '//trim(num)//': unknown kind'
         else if (segs(i)%kind == seg_arc .and. segs(i)%radius <= 1.0e-12_dp*sz) then
            errmsg = 'piece '//trim(num)//': zero arc radius'
         else if (segs(i)%length <= 1.0e-12_dp*sz) then
            errmsg = 'piece '//trim(num)//': zero length'
         else if (segs(i)%kind == seg_arc) then
            if (abs(norm2(segs(i)%p2 - segs(i)%centre) - segs(i)%radius) > &
                file_radius_tol*segs(i)%radius) then
               errmsg = 'piece '//trim(num)//': end point not on the arc''s circle '// &
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
               if (norm2(nsum) < 1.0e-6_dp) errmsg = 'piece '//trim(num)// &
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

   ! ------------------------------------------------------------------
   ! queries
   ! ------------------------------------------------------------------

   !> TOOL_GAP: signed penetration, normal, curvature factor and tangent of a
   !> point with respect to a tool (conventions in the module header).
   !>  tool      [in]  the tool (its shift is applied)
   !>  x, y      [in]  current position of the centreline point, mm
   !>  d         [out] signed penetration: > 0 inside the tool material,
   !>                  < 0 outside (minus the distance), 0 on the surface
   !>  normal    [out] unit outward normal of the tool at the closest point,
   !>                  pointing toward the sheet side; dd/dp = -normal
   !>  dn_factor [out] d(normal)/dp = dn_factor * (I - normal normal^T);
   !>                  0 on lines, sgn/|p - centre| on arcs, +-1/|p - q| at
   !>                  sharp vertices
   !>  tangent   [out] unit tangent along the chain's direction of travel,
   !>                  tangent = side*(-normal_y, normal_x)
   !>  seg_index [out] the closest piece: 1..nseg, 0 for the half-line that
   !>                  continues the chain to the left, nseg+1 to the right
   !>  hint      [in]  optional: a piece (1..nseg) likely nearest, e.g. the
   !>                  seg_index of the point's last search; its distance
   !>                  bounds the answer, so that the other pieces are pruned
   !>                  by their boxes at once.  The answer does not depend
   !>                  on it; other values are ignored
   !> No allocation; cost is a loop over the pieces with bounding-box pruning.
   pure subroutine tool_gap(tool, x, y, d, normal, dn_factor, tangent, seg_index, hint)
      type(tool_type), intent(in) :: tool
      real(dp), intent(in) :: x, y
      real(dp), intent(out) :: d, normal(2), dn_factor, tangent(2)
      integer, intent(out) :: seg_index
      integer, intent(in), optional :: hint
      real(dp) :: p(2), best, bound, dist, tol, lbx, lby, tin(2), tout(2), q(2)
      integer :: i, n, clamp, bclamp, ibest
      n = tool%nseg
      p = [x, y - tool%shift]
      tol = 1.0e-12_dp*tool%size
      best = huge(1.0_dp)
      ibest = -1
      bclamp = 0
      ! the half-lines continuing the chain beyond its ends
      if (dot_product(p - tool%seg(1)%p1, tool%seg(1)%t1) < 0.0_dp) then
         best = abs(cross2(tool%seg(1)%t1, p - tool%seg(1)%p1))
         ibest = 0
      end if
      if (dot_product(p - tool%seg(n)%p2, tool%seg(n)%t2) > 0.0_dp) then
         dist = abs(cross2(tool%seg(n)%t2, p - tool%seg(n)%p2))
         if (dist < best) then
            best = dist
            ibest = n + 1
         end if
      end if
      ! the hinted piece's distance (the nearest piece at the station's last
      ! search) bounds the answer, so that the boxes prune the others at
      ! once; the scan in index order, and with it the answer, is unchanged
      bound = best
      if (present(hint)) then
         if (hint >= 1 .and. hint <= n) then
            call piece_distance(tool%seg(hint), p, dist, clamp)
            bound = min(bound, dist)
         end if
      end if
      do i = 1, n
         if (bound < huge(1.0_dp)) then
            lbx = max(tool%seg(i)%box(1) - p(1), 0.0_dp, p(1) - tool%seg(i)%box(2))
            lby = max(tool%seg(i)%box(3) - p(2), 0.0_dp, p(2) - tool%seg(i)%box(4))
            if (lbx*lbx + lby*lby > (min(best, bound) + tol)**2) cycle
         end if
         call piece_distance(tool%seg(i), p, dist, clamp)
         ! a strictly nearer piece wins; on a tie an interior projection beats
         ! an end point (keeps the smooth formulas at tangent junctions)
         if (dist < best - tol .or. (dist <= best + tol .and. bclamp /= 0 .and. clamp == 0)) then
            best = dist
            ibest = i
            bclamp = clamp
         end if
      end do
      seg_index = ibest
      if (ibest == 0) then
         call line_signed(tool%seg(1)%p1, tool%seg(1)%t1, tool%side, p, d, normal, dn_factor, tangent)
      else if (ibest == n + 1) then
         call line_signed(tool%seg(n)%p2, tool%seg(n)%t2, tool%side, p, d, normal, dn_factor, tangent)
      else if (bclamp == 0) then
         call piece_signed(tool%seg(ibest), tool%side, p, d, normal, dn_factor, tangent)
      else
         ! closest point is an end point: find the two pieces meeting there
         if (bclamp == 1) then
            q = tool%seg(ibest)%p1
            tout = tool%seg(ibest)%t1
            if (ibest > 1) then
               tin = tool%seg(ibest - 1)%t2
            else
               tin = tout
            end if
         else
            q = tool%seg(ibest)%p2
            tin = tool%seg(ibest)%t2
            if (ibest < n) then
               tout = tool%seg(ibest + 1)%t1
            else
               tout = tin
            end if
         end if
         if (abs(cross2(tin, tout)) <= tangent_tol .and. dot_product(tin, tout) > 0.0_dp) then
            call piece_signed(tool%seg(ibest), tool%side, p, d, normal, dn_factor, tangent)
         else
            call vertex_signed(q, tin, tout, tool%side, tol, p, d, normal, dn_factor, tangent)
         end if
      end if
   end subroutine tool_gap

   !> PIECE_DISTANCE: unsigned distance from p to a piece and where the
   !> closest point lies.
   !>  seg   [in]  the piece (unshifted coordinates)
   !>  p     [in]  the point (unshifted coordinates)
   !>  dist  [out] distance to the closest point of the piece
   !>  clamp [out] 0 interior projection, 1 the start point, 2 the end point
   pure subroutine piece_distance(seg, p, dist, clamp)
      type(segment_type), intent(in) :: seg
      real(dp), intent(in) :: p(2)
      real(dp), intent(out) :: dist
      integer, intent(out) :: clamp
      real(dp) :: s, v(2), r, d1, d2
      if (seg%kind == seg_line) then
         s = dot_product(p - seg%p1, seg%t1)
         if (s <= 0.0_dp) then
            clamp = 1
            dist = norm2(p - seg%p1)
         else if (s >= seg%length) then
            clamp = 2
            dist = norm2(p - seg%p2)
         else
            clamp = 0
            dist = abs(cross2(seg%t1, p - seg%p1))
         end if
      else
         v = p - seg%centre
         r = norm2(v)
         if (r > 1.0e-14_dp*seg%radius) then
            if (in_arc(seg, v)) then
               clamp = 0
               dist = abs(r - seg%radius)
               return
            end if
         end if
         d1 = norm2(p - seg%p1)
         d2 = norm2(p - seg%p2)
         if (d1 <= d2) then
            clamp = 1
            dist = d1
         else
            clamp = 2
            dist = d2
         end if
      end if
   end subroutine piece_distance

   !> PIECE_SIGNED: signed quantities from a piece's own smooth formulas (the
   !> piece continued past its ends if needed).  Arguments as tool_gap.
   pure subroutine piece_signed(seg, side, p, d, normal, dn_factor, tangent)
      type(segment_type), intent(in) :: seg
      integer, intent(in) :: side
      real(dp), intent(in) :: p(2)
      real(dp), intent(out) :: d, normal(2), dn_factor, tangent(2)
      real(dp) :: v(2), r, sgn
      if (seg%kind == seg_line) then
         call line_signed(seg%p1, seg%t1, side, p, d, normal, dn_factor, tangent)
         return
      end if
      sgn = real(seg%sense*side, dp)
      v = p - seg%centre
      r = norm2(v)
      if (r <= 1.0e-14_dp*seg%radius) then
         ! at the centre: every arc point is equally far; use the start point
         normal = normal_of(seg%t1, side)
         d = sgn*seg%radius
         dn_factor = 0.0_dp
      else
         normal = sgn*v/r
         d = sgn*(seg%radius - r)
         dn_factor = sgn/r
      end if
      tangent = real(side, dp)*[-normal(2), normal(1)]
   end subroutine piece_signed

   !> LINE_SIGNED: signed quantities for the infinite line through a with
   !> unit direction t.  Arguments as tool_gap.
   pure subroutine line_signed(a, t, side, p, d, normal, dn_factor, tangent)
      real(dp), intent(in) :: a(2), t(2), p(2)
      integer, intent(in) :: side
      real(dp), intent(out) :: d, normal(2), dn_factor, tangent(2)
      normal = normal_of(t, side)
      d = -dot_product(p - a, normal)
      dn_factor = 0.0_dp
      tangent = t
   end subroutine line_signed

   !> VERTEX_SIGNED: signed quantities when the closest point is a sharp
   !> vertex q where a piece with end tangent tin meets one with start
   !> tangent tout.  The side of p comes from the pseudo-normal
   !> N = n(tin) + n(tout): p is outside when (p - q).N >= 0.
   !>  tol [in] distance under which p counts as being at q (d = 0,
   !>           normal = N/|N|, dn_factor = 0).  Others as tool_gap.
   pure subroutine vertex_signed(q, tin, tout, side, tol, p, d, normal, dn_factor, tangent)
      real(dp), intent(in) :: q(2), tin(2), tout(2), tol, p(2)
      integer, intent(in) :: side
      real(dp), intent(out) :: d, normal(2), dn_factor, tangent(2)
      real(dp) :: w(2), dist, pn(2), s_out
      pn = normal_of(tin, side) + normal_of(tout, side)
      pn = pn/norm2(pn)
      w = p - q
      dist = norm2(w)
      if (dist <= tol) then
         d = 0.0_dp
         normal = pn
         dn_factor = 0.0_dp
      else
         s_out = merge(1.0_dp, -1.0_dp, dot_product(w, pn) >= 0.0_dp)
         normal = s_out*w/dist
         d = -s_out*dist
         dn_factor = s_out/dist
      end if
      tangent = real(side, dp)*[-normal(2), normal(1)]
   end subroutine vertex_signed

   !> TOOL_SAMPLE: n points equally spaced in arc length along the chain
   !> (ends included, shift applied), for plotting.
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
         xy(2, k) = xy(2, k) + tool%shift
      end do
   end subroutine tool_sample

   !> PIECE_POINT: the point at fraction u (0..1 of the length) of a piece.
   !> TOOL_LEVEL: height of the tool surface (shift 0) above abscissa x, from
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

   ! ------------------------------------------------------------------
   ! builders
   ! ------------------------------------------------------------------

   !> BUILD_RECTANGULAR_BEAD: the paper's flat bead (Fig. 3, DESIGN section 5)
   !> as centreline surfaces, both tools at shift = 0, centred on x = 0.
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
   !>                (sharp concave corners).  Set lower%shift = H to raise it.
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

   ! ------------------------------------------------------------------
   ! profile files
   ! ------------------------------------------------------------------

   !> READ_PROFILE: read a tool from a profile file (format in the module
   !> header and docs/PROFILE_FORMAT.md).  The tool has shift = 0.
   !>  path   [in]  file name
   !>  tool   [out] the tool
   !>  errmsg [out] blank on success, else '<path>:<line>: <what is wrong>'
   !>               (or '<path>: ...' for whole-file problems)
   !>  stat   [out] optional: 0 on success, else 1
   subroutine read_profile(path, tool, errmsg, stat)
      character(len=*), intent(in) :: path
      type(tool_type), intent(out) :: tool
      character(len=*), intent(out) :: errmsg
      integer, intent(out), optional :: stat
      character(len=:), allocatable :: line
      character(len=64) :: tok(12)
      character(len=256) :: iomsg
      type(segment_type), allocatable :: segs(:), tmp(:)
      integer, allocatable :: lineof(:), itmp(:)
      integer :: unit, ios, lineno, ntok, nseg, side, nneed, k, ibad
      real(dp) :: v(6), gap
      character(len=16) :: key
      character(len=400) :: what
      logical :: ok

      errmsg = ''
      if (present(stat)) stat = 1
      open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
      if (ios /= 0) then
         errmsg = trim(path)//': cannot open: '//trim(iomsg)
         return
      end if
      allocate (segs(16), lineof(16))
      nseg = 0
      side = 0
      lineno = 0
      what = ''
      do
         call get_line(unit, line, ios)
         if (ios /= 0) exit
         lineno = lineno + 1
         call split(line, tok, ntok)
         if (ntok == 0) cycle
         key = lower_case(tok(1))
         if (ntok > size(tok)) then
            what = 'too many fields'
         else if (side == 0 .and. key /= 'side') then
            what = 'the first data line must be ''side upper'' or ''side lower'''
         else if (key == 'side') then
            if (side /= 0) then
               what = '''side'' given twice'
            else if (ntok /= 2) then
               what = '''side'' needs one word: upper or lower'
            else if (lower_case(tok(2)) == 'upper') then
               side = 1
            else if (lower_case(tok(2)) == 'lower') then
               side = -1
            else
               what = 'side must be upper or lower, not '''//trim(tok(2))//''''
            end if
         else if (key == 'line' .or. key == 'arc') then
            nneed = merge(4, 6, key == 'line')
            if (key == 'line' .and. ntok /= 1 + nneed) then
               write (what, '(a, i0)') '''line'' needs 4 numbers (x1 y1 x2 y2), found ', ntok - 1
            else if (key == 'arc' .and. ntok /= 2 + nneed) then
               write (what, '(a, i0)') '''arc'' needs 6 numbers and a sense (x1 y1 x2 y2 xc yc ccw|cw), found ', &
                  ntok - 1
            end if
            if (len_trim(what) == 0) then
               do k = 1, nneed
                  call to_real(tok(1 + k), v(k), ok)
                  if (.not. ok) then
                     what = 'not a number: '''//trim(tok(1 + k))//''''
                     exit
                  end if
               end do
            end if
            if (len_trim(what) == 0 .and. key == 'line') then
               if (norm2(v(3:4) - v(1:2)) <= 0.0_dp) what = 'zero-length line'
            else if (len_trim(what) == 0) then
               if (lower_case(tok(8)) /= 'ccw' .and. lower_case(tok(8)) /= 'cw') then
                  what = 'arc sense must be ccw or cw, not '''//trim(tok(8))//''''
               else if (norm2(v(1:2) - v(5:6)) <= 0.0_dp .or. norm2(v(3:4) - v(5:6)) <= 0.0_dp) then
                  what = 'zero arc radius (an end point is the centre)'
               else if (abs(norm2(v(3:4) - v(5:6)) - norm2(v(1:2) - v(5:6))) > &
                        file_radius_tol*norm2(v(1:2) - v(5:6))) then
                  write (what, '(a, es14.7, a, es14.7, a)') 'radius mismatch: |start - centre| = ', &
                     norm2(v(1:2) - v(5:6)), ', |end - centre| = ', norm2(v(3:4) - v(5:6)), ' mm'
               else if (norm2(v(3:4) - v(1:2)) <= 0.0_dp) then
                  what = 'zero-length arc (start = end)'
               end if
            end if
            if (len_trim(what) == 0 .and. nseg > 0) then
               gap = norm2(v(1:2) - segs(nseg)%p2)
               if (gap > file_cont_tol) then
                  write (what, '(a, i0, a, es10.3, a)') 'piece does not start where the piece on line ', &
                     lineof(nseg), ' ends (gap ', gap, ' mm)'
               else
                  v(1:2) = segs(nseg)%p2
               end if
            end if
            if (len_trim(what) == 0) then
               if (nseg == size(segs)) then
                  allocate (tmp(2*nseg), itmp(2*nseg))
                  tmp(1:nseg) = segs
                  itmp(1:nseg) = lineof
                  call move_alloc(tmp, segs)
                  call move_alloc(itmp, lineof)
               end if
               nseg = nseg + 1
               lineof(nseg) = lineno
               if (key == 'line') then
                  segs(nseg) = line_segment(v(1:2), v(3:4))
               else
                  segs(nseg) = arc_segment(v(1:2), v(3:4), v(5:6), lower_case(tok(8)) == 'ccw')
               end if
            end if
         else
            what = 'unknown keyword '''//trim(tok(1))//''' (expected side, line or arc)'
         end if
         if (len_trim(what) > 0) exit
      end do
      close (unit)
      if (len_trim(what) > 0) then
         write (errmsg, '(a, a, i0, a, a)') trim(path), ':', lineno, ': ', trim(what)
         return
      end if
      if (ios > 0) then
         write (errmsg, '(a, a, i0, a)') trim(path), ':', lineno + 1, ': read error'
         return
      end if
      if (side == 0) then
         errmsg = trim(path)//': no ''side upper|lower'' line'
         return
      end if
      if (nseg < 1) then
         errmsg = trim(path)//': no pieces (need at least one line or arc)'
         return
      end if
      call check_chain(segs(1:nseg), side, file_cont_tol, .false., what, ibad)
      if (ibad /= 0) then
         ! name the line of the offending piece (the last one for the chain)
         k = lineof(min(ibad, nseg))
         write (errmsg, '(a, a, i0, a, a)') trim(path), ':', k, ': ', trim(what)
         return
      end if
      call tool_init(tool, segs(1:nseg), side, what, ibad)
      if (ibad /= 0) then
         errmsg = trim(path)//': '//trim(what)
         return
      end if
      if (present(stat)) stat = 0
   end subroutine read_profile

   !> WRITE_PROFILE: write a tool as a profile file (stored geometry, shift
   !> not applied), numbers with 17 significant digits so read_profile gives
   !> back the same pieces.
   !>  path   [in]  file name (replaced if it exists)
   !>  tool   [in]  the tool
   !>  errmsg [out] blank on success, else '<path>: <what>'
   !>  stat   [out] optional: 0 on success, else 1
   !>  header [in]  optional comment lines written after the standard header
   !>               (each prefixed with '# ')
   subroutine write_profile(path, tool, errmsg, stat, header)
      character(len=*), intent(in) :: path
      type(tool_type), intent(in) :: tool
      character(len=*), intent(out) :: errmsg
      integer, intent(out), optional :: stat
      character(len=*), intent(in), optional :: header(:)
      integer :: unit, ios, i
      character(len=256) :: iomsg
      character(len=*), parameter :: fmt_line = '(a, 4(1x, es24.16e3))', &
                                     fmt_arc = '(a, 6(1x, es24.16e3), 1x, a)'
      errmsg = ''
      if (present(stat)) stat = 1
      if (tool%nseg < 1 .or. (tool%side /= 1 .and. tool%side /= -1)) then
         errmsg = trim(path)//': tool is empty or has no side'
         return
      end if
      open (newunit=unit, file=path, status='replace', action='write', iostat=ios, iomsg=iomsg)
      if (ios /= 0) then
         errmsg = trim(path)//': cannot open for writing: '//trim(iomsg)
         return
      end if
      write (unit, '(a)', iostat=ios) '# drawbead tool profile (format: docs/PROFILE_FORMAT.md)'
      write (unit, '(a)', iostat=ios) '# centreline surface in mm at shift 0; pieces left to right'
      if (present(header)) then
         do i = 1, size(header)
            write (unit, '(a)', iostat=ios) '# '//trim(header(i))
         end do
      end if
      write (unit, '(a)', iostat=ios) 'side '//merge('upper', 'lower', tool%side == 1)
      do i = 1, tool%nseg
         if (ios /= 0) exit
         associate (s => tool%seg(i))
            if (s%kind == seg_line) then
               write (unit, fmt_line, iostat=ios, iomsg=iomsg) 'line', s%p1, s%p2
            else
               write (unit, fmt_arc, iostat=ios, iomsg=iomsg) 'arc ', s%p1, s%p2, s%centre, &
                  trim(merge('ccw', 'cw ', s%sense == 1))
            end if
         end associate
      end do
      close (unit)
      if (ios /= 0) then
         errmsg = trim(path)//': write error: '//trim(iomsg)
         return
      end if
      if (present(stat)) stat = 0
   end subroutine write_profile

   !> GET_LINE: read one whole record of any length.
   !>  unit [in]  connected formatted unit
   !>  line [out] the record without its end of line
   !>  ios  [out] 0, or the iostat of end of file / error
   subroutine get_line(unit, line, ios)
      use, intrinsic :: iso_fortran_env, only: iostat_eor, iostat_end
      integer, intent(in) :: unit
      character(len=:), allocatable, intent(out) :: line
      integer, intent(out) :: ios
      character(len=256) :: buf
      integer :: nread
      line = ''
      do
         read (unit, '(a)', advance='no', iostat=ios, size=nread) buf
         line = line//buf(1:nread)
         if (ios == iostat_eor) then
            ios = 0
            exit
         else if (ios == iostat_end .and. len(line) > 0) then
            ios = 0   ! last line without a newline
            exit
         else if (ios /= 0) then
            exit
         end if
      end do
   end subroutine get_line

   !> SPLIT: the blank- or tab-separated fields of a line, '#' comments cut.
   !>  line [in]  the line
   !>  tok  [out] fields (truncated to len(tok))
   !>  ntok [out] number of fields found (may exceed size(tok))
   pure subroutine split(line, tok, ntok)
      character(len=*), intent(in) :: line
      character(len=*), intent(out) :: tok(:)
      integer, intent(out) :: ntok
      integer :: i, n, start
      logical :: blank
      tok = ''
      ntok = 0
      n = index(line, '#') - 1
      if (n < 0) n = len(line)
      start = 0
      do i = 1, n + 1
         if (i <= n) then
            blank = line(i:i) == ' ' .or. line(i:i) == achar(9) .or. line(i:i) == achar(13)
         else
            blank = .true.
         end if
         if (.not. blank .and. start == 0) then
            start = i
         else if (blank .and. start > 0) then
            ntok = ntok + 1
            if (ntok <= size(tok)) tok(ntok) = line(start:i - 1)
            start = 0
         end if
      end do
   end subroutine split

   !> TO_REAL: strict conversion of a field to a real (digits, sign, point,
   !> exponent letter only; list-directed read would accept '1,2' or 'T').
   !>  s  [in]  the field
   !>  x  [out] its value (0 if not ok)
   !>  ok [out] whether s is a number
   subroutine to_real(s, x, ok)
      character(len=*), intent(in) :: s
      real(dp), intent(out) :: x
      logical, intent(out) :: ok
      integer :: ios
      x = 0.0_dp
      ok = len_trim(s) > 0 .and. verify(trim(s), '0123456789+-.eEdD') == 0 .and. &
           scan(s, '0123456789') > 0
      if (.not. ok) return
      read (s, *, iostat=ios) x
      ok = ios == 0
      if (.not. ok) x = 0.0_dp
   end subroutine to_real

   !> LOWER_CASE: ASCII lower-case copy of a word.
   pure function lower_case(s) result(r)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: r
      integer :: i, c
      r = s
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (c >= iachar('A') .and. c <= iachar('Z')) r(i:i) = achar(c + 32)
      end do
   end function lower_case

end module tools
