!> hermite -- C1 Hermite cubic shape functions and the quadrature rules.
!>
!> One scalar field u(x) on an element of length le is interpolated from the
!> nodal values (u1, u1', u2, u2') by the cubic Hermite polynomials (paper §4).
!> The sheet's two fields v and w each use these four functions.
module hermite
   use kinds, only: dp
   implicit none
   private
   public :: n_gauss, gauss_xi, gauss_wt, hermite_shape, simpson_rule

   !> 4-point Gauss-Legendre on [0, 1] (paper §4): exact for degree-7 polynomials.
   integer, parameter :: n_gauss = 4
   real(dp), parameter :: gauss_xi(n_gauss) = 0.5_dp*(1.0_dp + [ &
      -0.8611363115940526_dp, -0.3399810435848563_dp, &
      0.3399810435848563_dp, 0.8611363115940526_dp])
   real(dp), parameter :: gauss_wt(n_gauss) = 0.5_dp*[ &
      0.3478548451374538_dp, 0.6521451548625461_dp, &
      0.6521451548625461_dp, 0.3478548451374538_dp]

contains

   !> HERMITE_SHAPE: shape functions and their x-derivatives at one point.
   !>  xi   [in]  local coordinate in [0, 1]
   !>  le   [in]  element length (reference)
   !>  n    [out] N_i, i = 1..4, multiplying (u1, u1', u2, u2')
   !>  dn   [out] dN_i/dx
   !>  d2n  [out] d2N_i/dx2
   pure subroutine hermite_shape(xi, le, n, dn, d2n)
      real(dp), intent(in) :: xi, le
      real(dp), intent(out) :: n(4), dn(4), d2n(4)
      real(dp) :: x2, x3
      x2 = xi*xi
      x3 = x2*xi
      n = [1.0_dp - 3.0_dp*x2 + 2.0_dp*x3, le*(xi - 2.0_dp*x2 + x3), &
           3.0_dp*x2 - 2.0_dp*x3, le*(x3 - x2)]
      dn = [(-6.0_dp*xi + 6.0_dp*x2)/le, 1.0_dp - 4.0_dp*xi + 3.0_dp*x2, &
            (6.0_dp*xi - 6.0_dp*x2)/le, 3.0_dp*x2 - 2.0_dp*xi]
      d2n = [(-6.0_dp + 12.0_dp*xi)/le**2, (-4.0_dp + 6.0_dp*xi)/le, &
             (6.0_dp - 12.0_dp*xi)/le**2, (6.0_dp*xi - 2.0_dp)/le]
   end subroutine hermite_shape

   !> SIMPSON_RULE: composite Simpson stations and weights through the thickness
   !> (paper §4: 21 points), z from -h/2 to h/2, sum of weights = h.
   !>  npt  [in]  number of stations, odd and >= 3
   !>  h    [in]  thickness
   !>  z    [out] station positions (reference), ascending
   !>  w    [out] weights
   pure subroutine simpson_rule(npt, h, z, w)
      integer, intent(in) :: npt
      real(dp), intent(in) :: h
      real(dp), intent(out) :: z(npt), w(npt)
      integer :: k
      real(dp) :: dz
      dz = h/real(npt - 1, dp)
      do k = 1, npt
         z(k) = -0.5_dp*h + real(k - 1, dp)*dz
         if (k == 1 .or. k == npt) then
            w(k) = dz/3.0_dp
         else if (mod(k, 2) == 0) then
            w(k) = 4.0_dp*dz/3.0_dp
         else
            w(k) = 2.0_dp*dz/3.0_dp
         end if
      end do
   end subroutine simpson_rule
end module hermite
