!> kinematics -- exact plane finite-rotation strain measures of the shell.
!>
!> With a = 1 + v', b = w', c = v'', d = w'' on a flat reference (kappa = 0):
!>   stretch  lambda = sqrt(a^2 + b^2),   axial strain eps = lambda - 1   (2.3), (2.10)
!>   bending  rho = lambda*kappa_bar = (b c - a d)/(a^2 + b^2)            (2.5), (2.10)
!> rho = -theta' with theta = atan2(b, a), so both vanish for any rigid rotation.
module kinematics
   use kinds, only: dp
   implicit none
   private
   public :: strain_measures

contains

   !> STRAIN_MEASURES: eps, rho and their first and second derivatives with
   !> respect to g = (a, b, c, d).
   !>  g      [in]  (a, b, c, d) = (1 + v', w', v'', w'')
   !>  eps    [out] axial strain lambda - 1
   !>  rho    [out] bending strain (b c - a d)/(a^2 + b^2)
   !>  deps   [out] d eps / d g
   !>  drho   [out] d rho / d g
   !>  d2eps  [out] d2 eps / d g2 (only the (a, b) block is non-zero)
   !>  d2rho  [out] d2 rho / d g2
   pure subroutine strain_measures(g, eps, rho, deps, drho, d2eps, d2rho)
      real(dp), intent(in) :: g(4)
      real(dp), intent(out) :: eps, rho, deps(4), drho(4), d2eps(4, 4), d2rho(4, 4)
      real(dp) :: a, b, c, d, q, iq, iq2, lam, num, dnum(4), d2num(4, 4), dq(4), d2q(4, 4)
      integer :: i, j
      a = g(1); b = g(2); c = g(3); d = g(4)
      q = a*a + b*b
      lam = sqrt(q)
      eps = lam - 1.0_dp
      deps = [a/lam, b/lam, 0.0_dp, 0.0_dp]
      d2eps = 0.0_dp
      d2eps(1, 1) = b*b/(lam*q)
      d2eps(1, 2) = -a*b/(lam*q)
      d2eps(2, 1) = d2eps(1, 2)
      d2eps(2, 2) = a*a/(lam*q)
      ! rho = num/q: quotient rule with num = b c - a d
      num = b*c - a*d
      rho = num/q
      dnum = [-d, c, b, -a]
      d2num = 0.0_dp
      d2num(2, 3) = 1.0_dp; d2num(3, 2) = 1.0_dp
      d2num(1, 4) = -1.0_dp; d2num(4, 1) = -1.0_dp
      dq = [2.0_dp*a, 2.0_dp*b, 0.0_dp, 0.0_dp]
      d2q = 0.0_dp
      d2q(1, 1) = 2.0_dp; d2q(2, 2) = 2.0_dp
      ! powers of 1/q once (the divisions dominated this routine)
      iq = 1.0_dp/q
      iq2 = iq*iq
      drho = dnum*iq - num*dq*iq2
      do j = 1, 4
         do i = 1, 4
            d2rho(i, j) = d2num(i, j)*iq - (dnum(i)*dq(j) + dnum(j)*dq(i) + num*d2q(i, j))*iq2 &
                          + 2.0_dp*num*dq(i)*dq(j)*iq2*iq
         end do
      end do
   end subroutine strain_measures
end module kinematics
