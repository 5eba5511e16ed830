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
   public :: graded_nodes, element_dofs, node_dof, is_slope_dof, dofs_per_node, half_band
   public :: dof_v, dof_v_slope, dof_w, dof_w_slope

   integer, parameter :: dofs_per_node = 4, half_band = 7
   !> a node's dofs in their order: v, dv/ds, w, dw/ds
   integer, parameter :: dof_v = 1, dof_v_slope = 2, dof_w = 3, dof_w_slope = 4

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
