!> friction -- the modified Coulomb law (2.21) of the paper, Oden-Pires type,
!> with one sliding reversal, and its regularizing function (4.3)
!>    phi_eps(x) = (2/pi) atan(x/eps).
!>
!> The tangential traction is t_t = -mu t_n f(u_T) (2.21), i.e. with the
!> penalty normal force k d the friction force magnitude is mu k d f; its
!> direction and the slid distance u_T (2.22) are the contact module's
!> business (docs/theory.md §6).  u_T is measured along the sense of first
!> sliding, so it grows from 0; u_T^m is the largest committed u_T (the
!> reversal point).  The three branches of (2.21):
!>   (1) u_T >= u_T^m                      f = phi(u_T)
!>   (2) u_j <= u_T <= u_T^m               f = phi(u_T^m) - (u_T^m - u_T)/eps
!>   (3) u_T <= u_j                        f = -phi(u_T^m - u_T - eps phi(u_T^m))
!>                                           = -phi(u_j - u_T)
!> with u_j = u_T^m - eps phi(u_T^m), where branch (2) reaches f = 0.
!> Continuity: at u_T = u_T^m (1) and (2) both give phi(u_T^m); at u_T = u_j
!> (2) gives phi(u_T^m) - phi(u_T^m) = 0 and (3) gives -phi(0) = 0.  The slope
!> jumps at u_T^m (phi'(u_T^m) to 1/eps, a reversal is a kink) and, with the
!> atan form, at u_j (1/eps to phi'(0) = 2/(pi eps)).  u_T^m = 0 makes (2)
!> empty and (3) = phi(u_T), the first branch continued to u_T < 0.
!> |f| <= 1 everywhere; f -> 1 for u_T >> eps on (1), f -> -1 for
!> u_j - u_T >> eps on (3).
module friction
   use kinds, only: dp, pi
   implicit none
   private
   public :: phi_eps, dphi_eps, friction_law

contains

   !> PHI_EPS: the regularized sign function (4.3), (2/pi) atan(x/eps).
   !>  x   [in] argument, mm
   !>  eps [in] regularization length, mm (> 0)
   pure elemental real(dp) function phi_eps(x, eps)
      real(dp), intent(in) :: x, eps
      phi_eps = (2.0_dp/pi)*atan(x/eps)
   end function phi_eps

   !> DPHI_EPS: derivative of phi_eps, (2/pi) eps/(eps^2 + x^2).
   !>  x   [in] argument, mm
   !>  eps [in] regularization length, mm (> 0)
   pure elemental real(dp) function dphi_eps(x, eps)
      real(dp), intent(in) :: x, eps
      dphi_eps = (2.0_dp/pi)*eps/(eps*eps + x*x)
   end function dphi_eps

   !> FRICTION_LAW: the friction factor f of (2.21) and its derivative.
   !>  u_t     [in]  slid distance u_T along the sense of first sliding, mm
   !>                (may decrease after a reversal, and become negative)
   !>  u_t_max [in]  u_T^m, the largest committed u_T (>= 0), mm
   !>  eps     [in]  regularization length of (4.3), mm; eps <= 0 gives the
   !>                limit eps -> 0 (rigid-plastic Coulomb: f = +-1, 0 only at
   !>                u_T = u_T^m = 0, df_du = 0)
   !>  f       [out] friction factor, |f| <= 1; the friction traction is
   !>                -mu t_n f along the tangent of first sliding
   !>  df_du   [out] df/du_T (for the consistent tangent; one-sided at the
   !>                kinks: branch (1) at u_T = u_T^m, branch (2) at u_j)
   pure subroutine friction_law(u_t, u_t_max, eps, f, df_du)
      real(dp), intent(in) :: u_t, u_t_max, eps
      real(dp), intent(out) :: f, df_du
      real(dp) :: phim, u_j
      if (eps <= 0.0_dp) then
         df_du = 0.0_dp
         if (u_t >= u_t_max) then
            f = merge(sign(1.0_dp, u_t), 0.0_dp, abs(u_t) > 0.0_dp)
         else
            f = -1.0_dp
         end if
         return
      end if
      if (u_t >= u_t_max) then
         ! branch (1): still sliding in the first sense
         f = phi_eps(u_t, eps)
         df_du = dphi_eps(u_t, eps)
         return
      end if
      phim = phi_eps(u_t_max, eps)
      u_j = u_t_max - eps*phim
      if (u_t >= u_j) then
         ! branch (2): after the reversal, friction unloads linearly
         f = phim - (u_t_max - u_t)/eps
         df_du = 1.0_dp/eps
      else
         ! branch (3): sliding in the reverse sense
         f = -phi_eps(u_j - u_t, eps)
         df_du = dphi_eps(u_j - u_t, eps)
      end if
   end subroutine friction_law

end module friction
