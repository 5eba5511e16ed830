!> mesh -- nodes of the sheet on [-L, L] and dof numbering.
!>
!> Node i carries dofs 4(i-1)+1 .. 4(i-1)+4 = (v, v', w, w'): node-by-node
!> numbering, so an element couples 8 consecutive equations (half-band 7).
module mesh
   use kinds, only: dp
   implicit none
   private
   public :: graded_nodes, element_dofs, dofs_per_node, half_band

   integer, parameter :: dofs_per_node = 4, half_band = 7

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

   !> ELEMENT_DOFS: global equation numbers of element e's eight dofs.
   pure function element_dofs(e) result(dofs)
      integer, intent(in) :: e
      integer :: dofs(2*dofs_per_node), i
      dofs = [(dofs_per_node*(e - 1) + i, i = 1, 2*dofs_per_node)]
   end function element_dofs
end module mesh
