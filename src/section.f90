!> section -- through-thickness integration of the sheet: N, M and C (2.16), (2.17).
!>
!> A Gauss station of the shell carries npt material points (Simpson stations,
!> paper §4) at reference distance z_k, current distance zbar_k (lagged,
!> docs/theory.md §3).  Fibre stretch Lambda_k = 1 + eps + zbar_k rho; the material gets the
!> log-strain increment ln(Lambda_k/Lambda_k,old) with the width strain held.
!>
!> The history of the section is hist(npt, hist_size(law)), one row per
!> material point (the block layout of the laws' updates: every station's
!> value of one variable is contiguous):
!>   hist(:, ih_strain)    converged fibre log strain ln Lambda_k (kept as
!>                         a logarithm: one log per station and call)
!>   hist(:, ih_zbar)      current distance from the mid-surface (lagged)
!>   hist(:, ih_stress:+1) Kirchhoff stress (tau_11, tau_33)
!>   hist(:, ih_sse), (:, ih_spd) elastic energy and plastic work densities
!>   hist(:, ih_stress22)  the prescribed thickness stress tau22 of the last
!>                         update (0 with the paper's plane-stress section)
!>   hist(:, ih_work22)    work density of tau22 on the thickness strain,
!>                         int tau22 d eps22 (trapezoidal per increment): the
!>                         energy the contact pressure puts into the material
!>                         besides the shell's N d eps + M d rho
!>   hist(:, ih_statev:)   the material law's n_state state variables (its
!>                         own layout, module material_law), among them
!>   hist(:, col_eqps(law))    equivalent plastic strain (0: the law has none)
!>   hist(:, col_eps22(law))   thickness log strain
!>   hist(:, col_tangent(law)) continuum tangent d tau11 / d eps11
!>
!> The thickness stress (docs/theory.md §12).  With the contact section a
!> Gauss station in contact gets the normal tractions of the tools on its
!> faces, face_stress = (tau22 on the bottom face z = -h/2, on the top face
!> z = +h/2), compressive negative, and tau22 varies linearly in zbar between
!> them; the law takes it as a prescribed stress.  A station whose face
!> stresses are zero now and were zero at the last converged state runs the
!> paper's plane-stress update unchanged.
module section
   use kinds, only: dp
   use material_law, only: material_law_type
   implicit none
   private
   public :: ih_strain, ih_zbar, ih_stress, ih_sse, ih_spd, ih_stress22, ih_work22, ih_statev, &
             hist_size, col_eqps, col_eps22, col_tangent, section_init, section_response, &
             section_localization, section_update_zbar

   !> the columns of the history that are the section's own (module header)
   integer, parameter :: ih_strain = 1, ih_zbar = 2, ih_stress = 3, ih_sse = 5, &
                         ih_spd = 6, ih_stress22 = 7, ih_work22 = 8, ih_statev = 9

contains

   !> HIST_SIZE: the number of history columns a section of this law needs.
   pure integer function hist_size(law)
      class(material_law_type), intent(in) :: law
      hist_size = ih_statev - 1 + law%n_state
   end function hist_size

   !> COL_EQPS: the history column of the equivalent plastic strain (0: the
   !> law has none).
   pure integer function col_eqps(law)
      class(material_law_type), intent(in) :: law
      col_eqps = 0
      if (law%isv_eqps > 0) col_eqps = ih_statev - 1 + law%isv_eqps
   end function col_eqps

   !> COL_EPS22: the history column of the thickness log strain.
   pure integer function col_eps22(law)
      class(material_law_type), intent(in) :: law
      col_eps22 = ih_statev - 1 + law%isv_eps22
   end function col_eps22

   !> COL_TANGENT: the history column of the continuum tangent.
   pure integer function col_tangent(law)
      class(material_law_type), intent(in) :: law
      col_tangent = ih_statev - 1 + law%isv_tangent
   end function col_tangent

   !> SECTION_INIT: history of an undeformed, stress-free section.
   !>  z     [in]  reference station positions
   !>  hist  [out] history (npt, n_hist), one row per station
   pure subroutine section_init(z, hist)
      real(dp), intent(in) :: z(:)
      real(dp), intent(out) :: hist(:, :)
      hist = 0.0_dp
      hist(:, ih_strain) = 0.0_dp
      hist(:, ih_zbar) = z
   end subroutine section_init

   !> SECTION_RESPONSE: section forces and tangent for given (eps, rho), (2.16)-(2.17).
   !>  eps, rho [in]  axial and bending strains at this Gauss station
   !>  wz       [in]  Simpson weights (reference thickness), sum = h
   !>  mat      [in]  the material (built-in or a user's UMAT)
   !>  hn       [in]  converged history of the stations
   !>  h1       [in,out] trial history at (eps, rho); on entry the last
   !>                 trial's, read only by a law that starts its return
   !>                 there (material_law's starts_from_trial)
   !>  force    [out] N = sum w tau/Lambda
   !>  moment   [out] M = sum w tau zbar/Lambda
   !>  c        [out] C(2,2): dN/deps, dN/drho = dM/deps, dM/drho (consistent)
   !>  pnewdt   [in,out] set < 1 when a fibre inverts or the material asks
   !>  face_stress [in] tau22 on the (bottom, top) face, <= 0 (module header);
   !>                   (0, 0): the paper's plane-stress section
   !>  cs       [out] C_s(2,2): d(N, M)/d(face_stress) at fixed (eps, rho):
   !>                 cs(1, :) = dN/d(bottom, top), cs(2, :) = dM/d(bottom, top)
   subroutine section_response(eps, rho, wz, mat, hn, h1, force, moment, c, pnewdt, &
                               face_stress, cs)
      real(dp), intent(in) :: eps, rho, wz(:)
      class(material_law_type), intent(in) :: mat
      real(dp), contiguous, intent(in) :: hn(:, :)
      real(dp), contiguous, intent(inout) :: h1(:, :)
      real(dp), intent(out) :: force, moment, c(2, 2)
      real(dp), intent(inout) :: pnewdt
      real(dp), intent(in) :: face_stress(2)
      real(dp), intent(out) :: cs(2, 2)
      integer :: k, npt, last, ie22
      real(dp) :: lam(size(wz)), log_lam(size(wz)), dstran(size(wz), 2)
      real(dp) :: ddsdde(size(wz), 2, 2), s22(size(wz)), zeta(size(wz)), dsig(size(wz)), &
                  dp_start(size(wz))
      real(dp) :: zb, tau, wl, wl2
      integer :: ieq
      logical :: with_s22
      npt = size(wz)
      last = ih_statev - 1 + mat%n_state
      ! where a law that asks for it may start its return: the equivalent
      ! plastic strain increment of the last trial (after a commit the
      ! histories' difference is <= 0: none; after a cut-back it is the
      ! rejected attempt's, usually above the root: the return's bracket
      ! takes it)
      ieq = col_eqps(mat)
      do k = 1, npt
         dp_start(k) = 0.0_dp
      end do
      if (mat%starts_from_trial .and. ieq > 0) then
         do k = 1, npt
            dp_start(k) = max(h1(k, ieq) - hn(k, ieq), 0.0_dp)
         end do
      end if
      force = 0.0_dp
      moment = 0.0_dp
      c = 0.0_dp
      cs = 0.0_dp
      do k = 1, npt
         lam(k) = 1.0_dp + eps + hn(k, ih_zbar)*rho
      end do
      if (any(lam <= 0.05_dp)) then
         ! a fibre shortened to nothing: the increment is far too large
         h1 = hn
         pnewdt = min(pnewdt, 0.25_dp)
         return
      end if
      do k = 1, npt
         log_lam(k) = log(lam(k))
         dstran(k, 1) = log_lam(k) - hn(k, ih_strain)
         dstran(k, 2) = 0.0_dp
      end do
      with_s22 = any(abs(face_stress) > 0.0_dp) .or. any(abs(hn(:, ih_stress22)) > 0.0_dp)
      if (.not. with_s22) then
         ! the law reads the converged history where it is and writes the
         ! trial one (update_to; law_j2 writes every column once, with no
         ! copy of hn into h1 first)
         call mat%update_to(npt, hn(:, ih_stress:ih_stress + 1), hn(:, ih_statev:last), &
                            hn(:, ih_sse), hn(:, ih_spd), h1(:, ih_stress:ih_stress + 1), &
                            h1(:, ih_statev:last), h1(:, ih_sse), h1(:, ih_spd), ddsdde, &
                            hn(:, ih_strain), dstran, hn(:, ih_zbar), pnewdt, dp_start=dp_start)
         if (pnewdt < 1.0_dp) then
            h1 = hn
            return
         end if
         do k = 1, npt
            h1(k, ih_zbar) = hn(k, ih_zbar)
            h1(k, ih_stress22) = hn(k, ih_stress22)
            h1(k, ih_work22) = hn(k, ih_work22)
         end do
      else
         h1 = hn
         ! tau22 linear in zbar between the faces (docs/theory.md §12)
         do k = 1, npt
            zeta(k) = (hn(k, ih_zbar) - hn(1, ih_zbar))/(hn(npt, ih_zbar) - hn(1, ih_zbar))
            s22(k) = (1.0_dp - zeta(k))*face_stress(1) + zeta(k)*face_stress(2)
         end do
         call mat%update(npt, h1(:, ih_stress:ih_stress + 1), h1(:, ih_statev:last), ddsdde, &
                         h1(:, ih_sse), h1(:, ih_spd), hn(:, ih_strain), dstran, hn(:, ih_zbar), &
                         pnewdt, hn(:, ih_stress22), s22, dsig, dp_start=dp_start)
         if (pnewdt < 1.0_dp) then
            ! (a failed update leaves no partial trial behind: dp_start)
            h1 = hn
            return
         end if
         ie22 = col_eps22(mat)
         do k = 1, npt
            h1(k, ih_stress22) = s22(k)
            h1(k, ih_work22) = hn(k, ih_work22) + 0.5_dp*(hn(k, ih_stress22) + s22(k)) &
                               *(h1(k, ie22) - hn(k, ie22))
            wl = wz(k)*dsig(k)/lam(k)
            cs(1, 1) = cs(1, 1) + wl*(1.0_dp - zeta(k))
            cs(1, 2) = cs(1, 2) + wl*zeta(k)
            cs(2, 1) = cs(2, 1) + wl*(1.0_dp - zeta(k))*hn(k, ih_zbar)
            cs(2, 2) = cs(2, 2) + wl*zeta(k)*hn(k, ih_zbar)
         end do
      end if
      do k = 1, npt
         h1(k, ih_strain) = log_lam(k)
         zb = hn(k, ih_zbar)
         tau = h1(k, ih_stress)
         wl = wz(k)/lam(k)
         wl2 = wl/lam(k)*(ddsdde(k, 1, 1) - tau)
         force = force + wl*tau
         moment = moment + wl*tau*zb
         c(1, 1) = c(1, 1) + wl2
         c(1, 2) = c(1, 2) + wl2*zb
         c(2, 2) = c(2, 2) + wl2*zb*zb
      end do
      c(2, 1) = c(1, 2)
   end subroutine section_response

   !> SECTION_LOCALIZATION: localization indicator of a converged section (3.1),
   !> docs/theory.md §7: the smallest eigenvalue of the section tangent built with the
   !> continuum moduli (plastic where loading, elastic where not), scaled by
   !> its elastic values with the current thickness t,
   !>   c = [C11/(E h), sqrt(12) C12/(E h t); sqrt(12) C12/(E h t), 12 C22/(E h t^2)].
   !> It is <= 0 exactly when C11 <= 0 or det C <= 0.  With this scaling the
   !> two diagonal entries are equal in uniform tension (C12 = 0), so the
   !> smallest eigenvalue has no kink where it crosses zero and the crossing
   !> can be interpolated linearly inside an increment (unscaled, its slope
   !> would jump twelvefold there).
   !>  wz     [in] Simpson weights
   !>  hist   [in] converged history of the stations
   !>  h      [in] thickness (a scale)
   !>  mat    [in] the material law (E the scale; the tangent's column)
   pure function section_localization(wz, hist, h, mat) result(indicator)
      real(dp), intent(in) :: wz(:), hist(:, :), h
      class(material_law_type), intent(in) :: mat
      real(dp) :: indicator
      real(dp) :: e
      integer :: it
      real(dp) :: c11, c12, c22, zb, wl2, t, tr, dt, rt
      real(dp) :: wl(size(wz))
      integer :: k, npt
      npt = size(wz)
      e = mat%youngs
      it = col_tangent(mat)
      t = hist(npt, ih_zbar) - hist(1, ih_zbar)
      rt = sqrt(12.0_dp)/t
      ! w (D - tau)/Lambda^2 with 1/Lambda^2 = exp(-2 ln Lambda): no
      ! division, and a loop without a sum, which vectorizes (libmvec's exp)
      do k = 1, npt
         wl(k) = wz(k)*(hist(k, it) - hist(k, ih_stress))*exp(-2.0_dp*hist(k, ih_strain))
      end do
      c11 = 0.0_dp; c12 = 0.0_dp; c22 = 0.0_dp
      do k = 1, npt
         zb = rt*hist(k, ih_zbar)
         wl2 = wl(k)
         c11 = c11 + wl2
         c12 = c12 + wl2*zb
         c22 = c22 + wl2*zb*zb
      end do
      c11 = c11/(e*h); c12 = c12/(e*h); c22 = c22/(e*h)
      tr = 0.5_dp*(c11 + c22)
      dt = sqrt(0.25_dp*(c11 - c22)**2 + c12*c12)
      indicator = tr - dt
   end function section_localization

   !> SECTION_UPDATE_ZBAR: current station distances from the converged thickness
   !> strains: d zbar/dz = exp(eps_22), trapezoid rule from the mid-surface
   !> station outward (docs/theory.md §3).  Called once per converged increment, so zbar
   !> is lagged one increment.
   !>  z     [in]  reference station positions (odd count, mid station at 0)
   !>  mat   [in]  the material law (the thickness strain's column)
   !>  hist  [in,out] history; column ih_zbar is rewritten
   pure subroutine section_update_zbar(z, mat, hist)
      real(dp), intent(in) :: z(:)
      class(material_law_type), intent(in) :: mat
      real(dp), intent(inout) :: hist(:, :)
      integer :: k, mid, ie22
      real(dp) :: g(size(z))
      mid = (size(z) + 1)/2
      ie22 = col_eps22(mat)
      ! one exp per station (each enters two trapezoids); a loop of its own
      ! so that it vectorizes (libmvec)
      do k = 1, size(z)
         g(k) = exp(hist(k, ie22))
      end do
      hist(mid, ih_zbar) = 0.0_dp
      do k = mid + 1, size(z)
         hist(k, ih_zbar) = hist(k - 1, ih_zbar) + 0.5_dp*(g(k - 1) + g(k))*(z(k) - z(k - 1))
      end do
      do k = mid - 1, 1, -1
         hist(k, ih_zbar) = hist(k + 1, ih_zbar) + 0.5_dp*(g(k + 1) + g(k))*(z(k) - z(k + 1))
      end do
   end subroutine section_update_zbar
end module section
