!> mesh -- nodes of the sheet on [-L, L] and dof numbering.
!>
!> Node i carries dofs 4(i-1)+1 .. 4(i-1)+4 = (v, v', w, w'): node-by-node
!> numbering, so an element couples 8 consecutive equations (half-band 7).
!> Other modules address a node's dofs through node_dof and the dof_*
!> names, never by arithmetic of their own.
module mesh
   use kinds, only: dp
   implicit none
   private
   public :: graded_nodes, zone_counts, zone_nodes, element_dofs, node_dof, is_slope_dof, dofs_per_node, half_band
   public :: dof_v, dof_v_slope, dof_w, dof_w_slope, neck_zone, neck_half_width

   integer, parameter :: dofs_per_node = 4, half_band = 7
   !> a node's dofs in their order: v, dv/ds, w, dw/ds
   integer, parameter :: dof_v = 1, dof_v_slope = 2, dof_w = 3, dof_w_slope = 4
   !> half width of the refined zone around a neck (&sheet refine_neck), in
   !> units of the thickness (docs/theory.md §7.5)
   real(dp), parameter :: neck_half_width = 2.0_dp

contains

   !> GRADED_NODES: node positions with the power-law grading (4.2),
   !> r_N = A r_0^beta + B applied on each half of [-L, L] so that the mesh is
   !> refined toward the bead at x = 0 (beta = 1: uniform).
   !>  n_el   [in]  number of elements (>= 2)
   !>  half   [in]  half length L
   !>  beta   [in]  grading exponent, 1 <= beta <= 3
   !>  x      [out] n_el + 1 node positions, ascending, x(1) = -L, x(n_el+1) = L
   pure subroutine graded_nodes(n_el, half, beta, x)
      integer, intent(in) :: n_el
      real(dp), intent(in) :: half, beta
      real(dp), intent(out) :: x(n_el + 1)
      integer :: i
      real(dp) :: r0
      do i = 1, n_el + 1
         r0 = -1.0_dp + 2.0_dp*real(i - 1, dp)/real(n_el, dp)
         ! A = L, B = 0 on each half: r = L sign(r0) |r0|^beta
         x(i) = half*sign(abs(r0)**beta, r0)
      end do
      x(1) = -half
      x(n_el + 1) = half
   end subroutine graded_nodes

   !> ZONE_COUNTS: the numbers of elements left of, in and right of a
   !> refined zone [s0, s1] of [-L, L] (docs/theory.md §2): outside it the
   !> uniform mesh's element length 2L/n_el, rounded to whole elements; a
   !> gap of less than half a coarse element to an end of the sheet gets
   !> none, and the zone then reaches that end (so that no sliver element
   !> remains, e.g. from s1 = L given in units of h and rounded in mm);
   !> inside the zone the length zone_h, rounded to whole elements over
   !> the zone so extended (at least one).  The zone serves the neck, whose width is of order
   !> h/sqrt(12) with the strain-gradient term (§12.7): the restraining
   !> force's maximum converges on elements of 0.1h there, while the rest of
   !> the sheet converges on the uniform 0.6h (docs/validation.md).
   !>  n_el    [in]  elements of the uniform mesh (>= 2)
   !>  half    [in]  half length L
   !>  s0, s1  [in]  the zone, -L <= s0 < s1 <= L (reference positions)
   !>  zone_h  [in]  element length in the zone, > 0
   !>  counts  [out] elements left of, in and right of the zone
   pure subroutine zone_counts(n_el, half, s0, s1, zone_h, counts)
      integer, intent(in) :: n_el
      real(dp), intent(in) :: half, s0, s1, zone_h
      integer, intent(out) :: counts(3)
      real(dp) :: coarse, ends(2)
      coarse = 2.0_dp*half/real(n_el, dp)
      counts(1) = max(0, nint((s0 + half)/coarse))
      counts(3) = max(0, nint((half - s1)/coarse))
      call zone_ends(counts, half, s0, s1, ends)
      counts(2) = max(1, nint((ends(2) - ends(1))/zone_h))
   end subroutine zone_counts

   !> ZONE_ENDS: the ends of the refined zone as meshed: s0 and s1, or the
   !> sheet's end on a side without coarse elements (zone_counts).
   !>  counts  [in]  elements left of, in and right of the zone
   !>  half    [in]  half length L
   !>  s0, s1  [in]  the zone as given
   !>  ends    [out] the zone as meshed
   pure subroutine zone_ends(counts, half, s0, s1, ends)
      integer, intent(in) :: counts(3)
      real(dp), intent(in) :: half, s0, s1
      real(dp), intent(out) :: ends(2)
      ends = [merge(-half, s0, counts(1) == 0), merge(half, s1, counts(3) == 0)]
   end subroutine zone_ends

   !> ZONE_NODES: node positions of a mesh with a refined zone: uniform on
   !> [-L, s0], [s0, s1] and [s1, L] with the element counts of zone_counts
   !> (the zone reaching an end where a count is 0).
   !>  counts  [in]  elements left of, in and right of the zone
   !>  half    [in]  half length L
   !>  s0, s1  [in]  the zone
   !>  x       [out] sum(counts) + 1 node positions, ascending, x(1) = -L,
   !>                x(end) = L
   pure subroutine zone_nodes(counts, half, s0, s1, x)
      integer, intent(in) :: counts(3)
      real(dp), intent(in) :: half, s0, s1
      real(dp), intent(out) :: x(sum(counts) + 1)
      real(dp) :: ends(4)
      integer :: part, i, k
      ends(1) = -half
      call zone_ends(counts, half, s0, s1, ends(2:3))
      ends(4) = half
      x(1) = -half
      k = 1
      do part = 1, 3
         do i = 1, counts(part)
            k = k + 1
            x(k) = ends(part) + (ends(part + 1) - ends(part))*real(i, dp)/real(counts(part), dp)
         end do
      end do
      x(k) = half
   end subroutine zone_nodes

   !> NECK_ZONE: the refined zone of &sheet refine_neck (docs/theory.md
   !> §7.5): neck_half_width h either side of a centre (the caller passes
   !> the uniform mesh's node nearest the neck found on it), cut at the
   !> sheet's ends.  On the uniform mesh of the
   !> continuum-check decks the neck's station lies within 0.55h of the one
   !> the refined mesh finds, well inside the zone.
   !>  s_star  [in]  the centre: the neck's place on the uniform mesh
   !>  half    [in]  half length L
   !>  h       [in]  thickness
   !>  zone    (result) [s0, s1], -L <= s0 < s1 <= L
   pure function neck_zone(s_star, half, h) result(zone)
      real(dp), intent(in) :: s_star, half, h
      real(dp) :: zone(2)
      zone(1) = max(-half, min(s_star, half) - neck_half_width*h)
      zone(2) = min(half, max(s_star, -half) + neck_half_width*h)
   end function neck_zone

   !> NODE_DOF: global equation number of dof `which` (dof_v ... dof_w_slope)
   !> of node `node`.
   pure integer function node_dof(node, which)
      integer, intent(in) :: node, which
      node_dof = dofs_per_node*(node - 1) + which
   end function node_dof

   !> IS_SLOPE_DOF: .true. for a slope dof (v' or w', dimensionless; its
   !> conjugate is a moment), .false. for a displacement (v or w).
   pure logical function is_slope_dof(i)
      integer, intent(in) :: i
      integer :: which
      which = i - dofs_per_node*((i - 1)/dofs_per_node)
      is_slope_dof = which == dof_v_slope .or. which == dof_w_slope
   end function is_slope_dof

   !> ELEMENT_DOFS: global equation numbers of element e's eight dofs.
   pure function element_dofs(e) result(dofs)
      integer, intent(in) :: e
      integer :: dofs(2*dofs_per_node), i
      dofs = [(dofs_per_node*(e - 1) + i, i = 1, 2*dofs_per_node)]
   end function element_dofs
end module mesh
