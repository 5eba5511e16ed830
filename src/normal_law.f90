!> normal_law -- a material law given by its update of the three normal
!> components (axial 11, thickness 22, width 33), with the section's
!> conditions met by driving the thickness strain (docs/theory.md §13.2).
!>
!> Purpose
!>   A law that extends normal_law_type supplies point_update: from the
!>   start stress (tau11, tau22, tau33) and its own state, the end stress,
!>   state and the consistent and continuum tangents (3 x 3) for a given
!>   increment of the three normal log strains.  The section holds the
!>   width strain (plane strain) and prescribes tau22 (0 with the paper's
!>   section, the contact pressure with docs/theory.md §12's); this module
!>   finds the thickness strain increment that meets the prescribed tau22
!>   by Newton's method with the law's own d tau22 / d eps22, the way
!>   plane stress is met with a three-dimensional material, so that no
!>   property of the law (an isotropic yield function, no back stress) is
!>   assumed.  The section's tangents are the law's, condensed with tau22
!>   held:
!>     d tau11/d eps11 = D11 - D12 D21/D22,   d tau11/d tau22 = D12/D22.
!>
!> State variables
!>   The law's own n_inner come first (its layout is its own, isv_eqps
!>   among them or 0); this module appends
!>     isv_eps22 = n_inner + 1     total thickness log strain
!>     isv_tangent = n_inner + 2   condensed continuum tangent
!>     n_inner + 3, n_inner + 4    the last converged d eps22 / d eps11 and
!>                                 1 / D22: the first guess of the next
!>                                 Newton solve (not results: a guess)
module normal_law
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use material_law, only: material_law_type
   implicit none
   private
   public :: normal_law_type, set_normal_layout, drive_thickness, drive_block_point

   !> the state variables appended to the law's own (module header)
   integer, parameter :: n_appended = 4
   !> relative tolerance on the prescribed tau22 (of the largest stress
   !> component, at least 1e-6 E).  Measured on bead A with an
   !> Armstrong-Frederick back stress (gamma = 200): at 1e-11 the global
   !> Newton converged linearly (rate 0.4) and the lock took 974 increments
   !> in 30 s without finishing; at 1e-14 quadratically, 19 increments
   real(dp), parameter :: tol_s22 = 1.0e-14_dp
   !> a residual that stalls above tol_s22 (round-off of the law's stress)
   !> is accepted after max_drive_iter iterations if below this
   real(dp), parameter :: tol_s22_floor = 1.0e-11_dp
   !> Newton iterations on the thickness strain before the increment is cut
   integer, parameter :: max_drive_iter = 25

   !> A law of the three normal components (module header).
   type, abstract, extends(material_law_type) :: normal_law_type
      !> the law's own state variables, before the appended ones
      integer :: n_inner = 0
   contains
      procedure(point_update_interface), deferred :: point_update
      procedure :: update => normal_update
   end type normal_law_type

   abstract interface
      !> POINT_UPDATE: one point, one increment of the three normal log
      !> strains (11, 22, 33).
      !>  law     [in]     the law
      !>  stress  [in,out] (3) Kirchhoff stress (tau11, tau22, tau33), start -> end
      !>  statev  [in,out] (n_inner) the law's state variables, start -> end
      !>  ddsdde  [out]    (3, 3) consistent tangent d tau / d deps
      !>  cont    [out]    (3, 3) continuum tangent (the rate form; the
      !>                   consistent one where the law has no other)
      !>  sse     [in,out] elastic energy density (end value)
      !>  spd     [in,out] plastic work density (accumulated)
      !>  stran   [in]     (3) log strain at the start of the increment
      !>  dstran  [in]     (3) log strain increment
      !>  zbar    [in]     current distance of the point from the mid-surface
      !>  kspt    [in]     the point's number through the thickness
      !>  pnewdt  [in,out] set < 1 to ask for a smaller increment
      subroutine point_update_interface(law, stress, statev, ddsdde, cont, sse, spd, stran, &
                                        dstran, zbar, kspt, pnewdt)
         import :: normal_law_type, dp
         class(normal_law_type), intent(in) :: law
         real(dp), intent(inout) :: stress(3), statev(law%n_inner), sse, spd, pnewdt
         real(dp), intent(out) :: ddsdde(3, 3), cont(3, 3)
         real(dp), intent(in) :: stran(3), dstran(3), zbar
         integer, intent(in) :: kspt
      end subroutine point_update_interface
   end interface

contains

   !> SET_NORMAL_LAYOUT: the state layout of a normal law with n_inner
   !> state variables of its own (module header); its constructor calls it.
   !>  law      [in,out] the law
   !>  n_inner  [in]     the law's own state variables
   !>  isv_eqps [in]     place of the equivalent plastic strain among them (0: none)
   pure subroutine set_normal_layout(law, n_inner, isv_eqps)
      class(normal_law_type), intent(inout) :: law
      integer, intent(in) :: n_inner, isv_eqps
      law%n_inner = n_inner
      law%n_state = n_inner + n_appended
      law%isv_eqps = isv_eqps
      law%isv_eps22 = n_inner + 1
      law%isv_tangent = n_inner + 2
   end subroutine set_normal_layout

   !> NORMAL_UPDATE: material_law_type's update (arguments there): each
   !> point by drive_thickness.
   subroutine normal_update(law, n, stress, statev, ddsdde, sse, spd, stran11, dstran, zbar, &
                            pnewdt, s22n, s22, dsig_ds22, dp_start)
      class(normal_law_type), intent(in) :: law
      integer, intent(in) :: n
      real(dp), intent(inout) :: stress(n, 2), statev(n, law%n_state), sse(n), spd(n)
      real(dp), intent(out) :: ddsdde(n, 2, 2)
      real(dp), intent(in) :: stran11(n), dstran(n, 2), zbar(n)
      real(dp), intent(inout) :: pnewdt
      real(dp), intent(in), optional :: s22n(n), s22(n)
      real(dp), intent(out), optional :: dsig_ds22(n)
      real(dp), intent(in), optional :: dp_start(n)
      real(dp) :: p_n, p
      integer :: k
      ! the thickness strain is driven from the elastic trial
      ! (starts_from_trial is .false.: dp_start comes as zeros, ignored;
      ! the empty test marks it used, as associate cannot take an absent
      ! optional)
      if (present(dp_start)) then
      end if
      do k = 1, n
         p_n = 0.0_dp
         p = 0.0_dp
         if (present(s22)) then
            p_n = s22n(k)
            p = s22(k)
         end if
         call drive_block_point(law, k, n, stress, statev, ddsdde, sse, spd, stran11, dstran, zbar, &
                                p_n, p, pnewdt, dsig_ds22)
         if (pnewdt < 1.0_dp) return
      end do
   end subroutine normal_update

   !> DRIVE_BLOCK_POINT: drive_thickness on point k of a block (the arrays
   !> of material_law_type's update), its results written back.
   !>  law                  [in]     the law
   !>  k, n                 [in]     the point, the block's size
   !>  stress ... zbar      [in,out]/[in] the block's arrays (update's)
   !>  p_n, p               [in]     the prescribed tau22 at the start and the end
   !>  pnewdt               [in,out] < 1: the increment is to be cut
   !>  dsig_ds22            [out]    optional: d tau11 / d tau22 of the block
   subroutine drive_block_point(law, k, n, stress, statev, ddsdde, sse, spd, stran11, dstran, zbar, &
                                p_n, p, pnewdt, dsig_ds22)
      class(normal_law_type), intent(in) :: law
      integer, intent(in) :: k, n
      real(dp), intent(inout) :: stress(n, 2), statev(n, law%n_state), sse(n), spd(n)
      real(dp), intent(inout) :: ddsdde(n, 2, 2)
      real(dp), intent(in) :: stran11(n), dstran(n, 2), zbar(n), p_n, p
      real(dp), intent(inout) :: pnewdt
      real(dp), intent(inout), optional :: dsig_ds22(n)
      real(dp) :: s(3), sv(law%n_state), dd(2, 2), coupling, de(2)
      s = [stress(k, 1), p_n, stress(k, 2)]
      sv = statev(k, :)
      ! a row of dstran is strided: a copy, not a compiler's temporary
      de = dstran(k, :)
      call drive_thickness(law, s, sv, dd, coupling, sse(k), spd(k), stran11(k), de, &
                           p, zbar(k), k, pnewdt)
      if (pnewdt < 1.0_dp) return
      stress(k, 1) = s(1)
      stress(k, 2) = s(3)
      statev(k, :) = sv
      ddsdde(k, :, :) = dd
      if (present(dsig_ds22)) dsig_ds22(k) = coupling
   end subroutine drive_block_point

   !> DRIVE_THICKNESS: one point's update with the width strain increment
   !> dstran(2) given and tau22 prescribed: Newton's method on the
   !> thickness strain increment with the law's D22 (module header).
   !>  law      [in]     the law
   !>  stress   [in,out] (3) (tau11, tau22, tau33): start (tau22 the start's
   !>                   prescribed value) -> end (tau22 = s22_end)
   !>  statev   [in,out] (n_state) the point's state variables, start -> end
   !>  ddsdde   [out]    (2, 2) condensed consistent tangent d(tau11, tau33)
   !>                   / d(eps11, eps33) with tau22 held
   !>  coupling [out]    d tau11 / d tau22 at fixed eps11, eps33
   !>  sse, spd [in,out] energy densities
   !>  stran11  [in]     axial log strain at the start (the width's is 0)
   !>  dstran   [in]     (2) increments of the axial and width log strains
   !>  s22_end  [in]     the prescribed tau22 at the end
   !>  zbar     [in]     the point's distance from the mid-surface
   !>  kspt     [in]     the point's number
   !>  pnewdt   [in,out] < 1 when the law asks for it or the Newton solve
   !>                   does not converge (the outputs are then not to be used)
   subroutine drive_thickness(law, stress, statev, ddsdde, coupling, sse, spd, stran11, dstran, &
                              s22_end, zbar, kspt, pnewdt)
      class(normal_law_type), intent(in) :: law
      real(dp), intent(inout) :: stress(3), statev(law%n_state), sse, spd, pnewdt
      real(dp), intent(out) :: ddsdde(2, 2), coupling
      real(dp), intent(in) :: stran11, dstran(2), s22_end, zbar
      integer, intent(in) :: kspt
      real(dp) :: s(3), sv(law%n_inner), dd(3, 3), cont(3, 3), e, w, x, r, scale, ratio, c22, &
                  lam2mu, tol
      integer :: it, i_ratio, i_c22
      ddsdde = 0.0_dp
      coupling = 0.0_dp
      i_ratio = law%n_inner + 3
      i_c22 = law%n_inner + 4
      ratio = statev(i_ratio)
      c22 = statev(i_c22)
      if (.not. c22 > 0.0_dp) then
         ! a virgin point: the elastic guess, d eps22 = (d tau22 - lambda
         ! d eps11)/(lambda + 2 mu) with the width strain held
         lam2mu = law%youngs*(1.0_dp - law%poisson)/((1.0_dp + law%poisson)*(1.0_dp - 2.0_dp*law%poisson))
         ratio = -law%poisson/(1.0_dp - law%poisson)
         c22 = 1.0_dp/lam2mu
      end if
      x = ratio*dstran(1) + c22*(s22_end - stress(2))
      do it = 1, max_drive_iter
         s = stress
         sv = statev(1:law%n_inner)
         e = sse
         w = spd
         call law%point_update(s, sv, dd, cont, e, w, [stran11, statev(law%isv_eps22), 0.0_dp], &
                               [dstran(1), x, dstran(2)], zbar, kspt, pnewdt)
         if (pnewdt < 1.0_dp) return
         if (.not. (ieee_is_finite(s(2)) .and. abs(dd(2, 2)) > 0.0_dp)) exit
         r = s(2) - s22_end
         scale = max(abs(s(1)), abs(s(3)), abs(s22_end), 1.0e-6_dp*law%youngs)
         tol = tol_s22
         if (it == max_drive_iter) tol = tol_s22_floor
         if (abs(r) <= tol*scale) then
            ddsdde(1, 1) = dd(1, 1) - dd(1, 2)*dd(2, 1)/dd(2, 2)
            ddsdde(1, 2) = dd(1, 3) - dd(1, 2)*dd(2, 3)/dd(2, 2)
            ddsdde(2, 1) = dd(3, 1) - dd(3, 2)*dd(2, 1)/dd(2, 2)
            ddsdde(2, 2) = dd(3, 3) - dd(3, 2)*dd(2, 3)/dd(2, 2)
            coupling = dd(1, 2)/dd(2, 2)
            stress = [s(1), s22_end, s(3)]
            statev(1:law%n_inner) = sv
            statev(law%isv_eps22) = statev(law%isv_eps22) + x
            statev(law%isv_tangent) = cont(1, 1) - cont(1, 2)*cont(2, 1)/cont(2, 2)
            if (abs(dstran(1)) > 0.0_dp) statev(i_ratio) = x/dstran(1)
            statev(i_c22) = 1.0_dp/dd(2, 2)
            sse = e
            spd = w
            return
         end if
         x = x - r/dd(2, 2)
      end do
      ! no convergence on the thickness strain: a smaller increment
      pnewdt = min(pnewdt, 0.5_dp)
      ddsdde = 0.0_dp
      coupling = 0.0_dp
   end subroutine drive_thickness
end module normal_law
