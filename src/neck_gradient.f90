!> neck_gradient -- how the coefficient of the strain-gradient term
!> (1/2) c (d lambda/ds)^2 (docs/theory.md §12.7) varies with the stretch.
!>
!> The plane-strain bar matches the strip's long-wave neck when
!> c = sigma h0^3/(12 lambda^6) (12.11), sigma and lambda the state of the
!> strip.  Setup gives c at the maximum load (module setup,
!> gradient_coefficient); past the maximum-load strain eps* a station's
!> coefficient follows its own state, c(lambda) = c* (lambda*/lambda)^6
!> tau(ln lambda)/tau*, with tau(eps) the law's axial Kirchhoff stress in
!> plane-strain tension (the path of material_law's max_load_strain),
!> tabulated here.  Below eps* c* is kept: no neck forms there, the term
!> only keeps the strain smooth, and a coefficient that grew as lambda^-6
!> toward lambda = 1 lowered the peak strains after locking by 3-10%,
!> away from the continuum's (docs/theory.md §12.7).  The switch is smooth:
!> the state is taken at eps* + u, u = (x + sqrt(x^2 + w^2))/2,
!> x = ln lambda - eps*, w = gradient_onset_width, so that c and its
!> derivatives (the element's residual and tangent) are continuous.
module neck_gradient
   use kinds, only: dp
   use material_law, only: material_law_type, plane_strain_path, path_step
   implicit none
   private
   public :: neck_gradient_type, neck_gradient_of, gradient_factor, gradient_onset_width, &
             curve_spacing

   !> the log strain over which the coefficient turns from c* to the
   !> stretch's (module header): a twentieth of the steels' eps*
   real(dp), parameter :: gradient_onset_width = 0.01_dp
   !> spacing of the tabulated tau(eps)/tau* past eps* (cubic Hermite
   !> between the points, with the law's own slopes)
   real(dp), parameter :: curve_spacing = 0.01_dp

   !> The stretch dependence of one material's coefficient.
   type :: neck_gradient_type
      !> the maximum-load log strain eps*
      real(dp) :: eps_star = 0.0_dp
      !> tau/tau* and its slope d(tau/tau*)/d eps at eps* + (k - 1)
      !> curve_spacing, k = 1 ... (the last value the law was driven to);
      !> none: tau = tau* throughout
      real(dp), allocatable :: tau(:), slope(:)
   end type neck_gradient_type

contains

   !> NECK_GRADIENT_OF: the stretch dependence of the coefficient of a law:
   !> the law driven along plane-strain tension (material_law's
   !> plane_strain_path, as max_load_strain does) from 0 to eps* + 2 (or a
   !> log strain of 3, or the law's last increment), tau and the continuum
   !> tangent d tau/d eps recorded at eps* + (k - 1) curve_spacing by
   !> linear interpolation between increments.
   !>  law       [in]  the material law
   !>  eps_star  [in]  its maximum-load log strain (material_law's
   !>                  max_load_strain; >= 3: no table, c* throughout)
   function neck_gradient_of(law, eps_star) result(g)
      class(material_law_type), intent(in) :: law
      real(dp), intent(in) :: eps_star
      type(neck_gradient_type) :: g
      real(dp), parameter :: span = 2.0_dp, eps_end = 3.0_dp
      real(dp), allocatable :: eps(:), tau(:), tangent(:)
      real(dp) :: t, grid, e0, tau0, tan0, tau_at(nint(span/curve_spacing) + 1), &
                  slope_at(nint(span/curve_spacing) + 1)
      integer :: i, n, n_path, n_done
      ! (a law without a maximum load by a log strain of 3 has eps* =
      ! huge(): it takes 3, as setup's gradient_coefficient does)
      g%eps_star = min(eps_star, eps_end)
      if (eps_star >= eps_end) then
         allocate (g%tau(0), g%slope(0))
         return
      end if
      n_path = nint(min(eps_star + span, eps_end)/path_step) + 1
      allocate (eps(n_path), tau(n_path), tangent(n_path))
      call plane_strain_path(law, n_path, eps, tau, tangent, n_done)
      n = 0
      grid = eps_star
      e0 = 0.0_dp
      tau0 = 0.0_dp
      tan0 = 0.0_dp
      do i = 1, n_done
         do while (grid <= eps(i) .and. n < size(tau_at))
            t = (grid - e0)/(eps(i) - e0)
            n = n + 1
            tau_at(n) = (1.0_dp - t)*tau0 + t*tau(i)
            slope_at(n) = (1.0_dp - t)*tan0 + t*tangent(i)
            grid = eps_star + n*curve_spacing
         end do
         e0 = eps(i)
         tau0 = tau(i)
         tan0 = tangent(i)
      end do
      if (n < 2 .or. tau_at(1) <= 0.0_dp) then
         allocate (g%tau(0), g%slope(0))
         return
      end if
      g%tau = tau_at(1:n)/tau_at(1)
      g%slope = slope_at(1:n)/tau_at(1)
   end function neck_gradient_of

   !> GRADIENT_FACTOR: c(lambda)/c* (module header) and its first two
   !> derivatives in lambda.
   !>  g         [in]  the stretch dependence (neck_gradient_of)
   !>  lam       [in]  the stretch lambda > 0
   !>  f, df, d2f [out] c/c*, d(c/c*)/d lambda, d2(c/c*)/d lambda^2
   pure subroutine gradient_factor(g, lam, f, df, d2f)
      type(neck_gradient_type), intent(in) :: g
      real(dp), intent(in) :: lam
      real(dp), intent(out) :: f, df, d2f
      real(dp) :: x, r, u, du, d2u, e, tv, tp, tpp, gu, gp, gpp
      x = log(lam) - g%eps_star
      r = sqrt(x*x + gradient_onset_width**2)
      u = 0.5_dp*(x + r)
      du = 0.5_dp*(1.0_dp + x/r)
      d2u = 0.5_dp*gradient_onset_width**2/r**3
      call curve_at(g, u, tv, tp, tpp)
      ! in u: exp(-6 u) tau(eps* + u)/tau*
      e = exp(-6.0_dp*u)
      gu = e*tv
      gp = e*(tp - 6.0_dp*tv)
      gpp = e*(tpp - 12.0_dp*tp + 36.0_dp*tv)
      ! in lambda: du/d lambda = du/dx / lambda
      f = gu
      df = gp*du/lam
      d2f = (gpp*du*du + gp*d2u - gp*du)/lam**2
   end subroutine gradient_factor

   !> CURVE_AT: tau/tau* at eps* + u and its first two derivatives in u:
   !> cubic Hermite between the tabulated points, the last point's value
   !> and slope continued linearly past the table, 1 without a table.
   !>  g            [in]  the stretch dependence
   !>  u            [in]  the strain past eps*, >= 0
   !>  tv, tp, tpp  [out] tau/tau*, its first and second derivatives
   pure subroutine curve_at(g, u, tv, tp, tpp)
      type(neck_gradient_type), intent(in) :: g
      real(dp), intent(in) :: u
      real(dp), intent(out) :: tv, tp, tpp
      real(dp) :: s, y0, y1, m0, m1, h00, h10, h01, h11
      integer :: k, n
      n = size(g%tau)
      if (n < 2) then
         tv = 1.0_dp
         tp = 0.0_dp
         tpp = 0.0_dp
         return
      end if
      k = int(u/curve_spacing) + 1
      if (k >= n) then
         tv = g%tau(n) + g%slope(n)*(u - (n - 1)*curve_spacing)
         tp = g%slope(n)
         tpp = 0.0_dp
         return
      end if
      s = u/curve_spacing - (k - 1)
      y0 = g%tau(k)
      y1 = g%tau(k + 1)
      m0 = g%slope(k)*curve_spacing
      m1 = g%slope(k + 1)*curve_spacing
      h00 = (1.0_dp + 2.0_dp*s)*(1.0_dp - s)**2
      h10 = s*(1.0_dp - s)**2
      h01 = s*s*(3.0_dp - 2.0_dp*s)
      h11 = s*s*(s - 1.0_dp)
      tv = h00*y0 + h10*m0 + h01*y1 + h11*m1
      tp = ((6.0_dp*s*s - 6.0_dp*s)*y0 + (3.0_dp*s*s - 4.0_dp*s + 1.0_dp)*m0 &
            + (6.0_dp*s - 6.0_dp*s*s)*y1 + (3.0_dp*s*s - 2.0_dp*s)*m1)/curve_spacing
      tpp = ((12.0_dp*s - 6.0_dp)*y0 + (6.0_dp*s - 4.0_dp)*m0 &
             + (6.0_dp - 12.0_dp*s)*y1 + (6.0_dp*s - 2.0_dp)*m1)/curve_spacing**2
   end subroutine curve_at
end module neck_gradient
