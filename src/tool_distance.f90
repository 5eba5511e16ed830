!> tool_distance -- the signed distance of a point to a tool (module
!> tools), its normal, tangent and curvature factor: the geometry of the
!> penalty contact (2.18)-(2.20), docs/theory.md §5, (5.1).
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
module tool_distance
   use kinds, only: dp
   use tools, only: tool_type, segment_type, seg_line, seg_arc, tangent_tol, cross2, normal_of, &
                    in_arc, arc_tangent
   implicit none
   private
   public :: tool_gap

contains

   !> TOOL_GAP: signed penetration, normal, curvature factor and tangent of a
   !> point with respect to a tool (conventions in the module header).
   !>  tool      [in]  the tool (at rest)
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
      p = [x, y]
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
            lbx = max(tool%box(1, i) - p(1), 0.0_dp, p(1) - tool%box(2, i))
            lby = max(tool%box(3, i) - p(2), 0.0_dp, p(2) - tool%box(4, i))
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
   !>  seg   [in]  the piece
   !>  p     [in]  the point, in the coordinates of the stored chain
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
end module tool_distance
