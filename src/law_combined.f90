!> law_combined -- combined hardening: a Hill 1948 yield surface with r0 and
!> r90 whose size follows an isotropic law (Swift, Voce or a table) and
!> whose centre moves with up to three Armstrong-Frederick (Chaboche) back
!> stresses (docs/theory.md §13.4, §13.5).
!>
!> The law, on the three normal components (1 axial = drawing, 2 thickness,
!> 3 width) of the Kirchhoff stress and the logarithmic strain, additive:
!>   xi = tau - sum_i alpha_i,           f = sqrt(xi^T P xi) - sigma_y(p),
!>   d eps_p = dp n,  n = P xi / sqrt(xi^T P xi),
!>   d alpha_i = (2/3) C_i d eps_p - gamma_i alpha_i dp,
!> isotropic elasticity (E, nu).  P is Hill's matrix: with x rolling, y
!> transverse, z normal, sbar^2 = F (sy - sz)^2 + G (sz - sx)^2 + H (sx - sy)^2,
!> r0 = H/G, r90 = H/F, scaled so that the uniaxial yield stress along the
!> drawing direction is sigma_y (the hardening curve is the drawing
!> direction's).  r0 = r90 = R is the paper's normal anisotropy, r0 = r90
!> = 1 von Mises.  C_i = 0 for all i is the isotropic law of law_j2;
!> gamma_i = 0 is linear (Prager) kinematic hardening.  In uniaxial tension
!> (von Mises) the back stress X = (3/2) alpha_11 = C/gamma (1 - exp(-gamma p)).
!>
!> Backward Euler.  With a_i = 1/(1 + gamma_i dp), b_i = (2/3) C_i dp a_i,
!> B = sum b_i and mu the shear modulus (D n = 2 mu n: n is traceless),
!>   xi = xi* - (2 mu dp + B) n,   xi* = tau_trial - sum a_i alpha_i,n,
!> so xi = (I + theta P)^-1 xi*, theta = (2 mu dp + B)/sigma_y(p_n + dp): in
!> the eigenvectors v_k of P (eigenvalues lambda_k, one of them 0, the
!> hydrostatic direction) the one unknown dp solves
!>   phi(dp) = sqrt(sum_k lambda_k c_k^2/(1 + theta lambda_k)^2) - sigma_y = 0,
!>   c_k = v_k . xi*,
!> by Newton's method kept inside a bracket.  The consistent tangent comes
!> from linearising the converged equations (theory §13.4):
!>   N = (P - n n^T)/q,  M = (I + B N)^-1,  A = C + dp N M,
!>   g = sum_i (a_i' alpha_i,n + b_i' n),  r = n - dp N M g,
!>   d tau/d eps = A^-1 - A^-1 r (n^T M A^-1) / (H' + n^T M g + n^T M A^-1 r),
!> C the elastic compliance; the continuum tangent is its dp -> 0 limit.
!> The plastic work of an increment is W(p_n + dp) - W(p_n) (W the integral
!> of the isotropic curve, exact as in law_j2) plus the back stresses'
!> sum_i (alpha_i,n + alpha_i)/2 . d eps_p; the back stresses store
!> sum_i 3/(4 C_i) alpha_i . alpha_i of it (stored_energy), the rest is
!> dissipated.
!>
!> State variables (own, before normal_law's): 1 the equivalent plastic
!> strain p, 2 sigma_y(p) and 3 its slope H'(p) (caches: an elastic
!> increment evaluates no hardening law, and the section's return starts
!> from them; sigma_y = 0 = not known, both computed on entry), then
!> alpha_i (3 normal components each), i = 1 .. n_back.
!>
!> The section's update (update => combined_update) does not drive the
!> thickness strain around point_update (normal_law's way, kept for the
!> law's other callers and as the tests' reference): an elastic predictor
!> for the whole block, then the points that yield returned together with
!> tau22 prescribed, directly (mixed_return_block, docs/theory.md §13.7).
module law_combined
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use normal_law, only: normal_law_type, set_normal_layout
   use hardening, only: flow_stress, plastic_work, ip_youngs, ip_poisson
   use hill, only: hill_square
   use combined_return, only: combined_constants, combined_constants_of, max_back_stresses, &
                              return_map, tangents, mixed_return_block
   use deck, only: deck_type, is_unset, max_kinematic
   use deck_checks, only: check_real, check_choice, fail, at
   use errors, only: error_list
   implicit none
   private
   public :: combined_law_type, combined_law, combined_law_of_deck, &
             isv_p, isv_alpha

   !> places of the own state variables (module header)
   integer, parameter :: isv_p = 1, isv_flow = 2, isv_slope = 3, isv_alpha = 4
   !> a trial state with sbar_trial <= (1 + tol_yield) sigma_y is elastic
   real(dp), parameter :: tol_yield = 1.0e-12_dp

   !> Combined hardening with its constants.
   type, extends(normal_law_type) :: combined_law_type
      !> its constants (module combined_return)
      type(combined_constants) :: k
   contains
      procedure :: point_update => combined_point_update
      procedure :: update => combined_update
      procedure :: stored_energy => combined_stored_energy
      procedure :: stores_energy => combined_stores_energy
      procedure :: state_mapped => combined_state_mapped
   end type combined_law_type

contains

   !> COMBINED_LAW: the law with its constants (the caller has checked
   !> them: E > 0, -1 < nu < 0.5, the isotropic law's constants, r0, r90 > 0,
   !> C_i >= 0, gamma_i >= 0).
   !>  props     [in] the isotropic part's constants (material_j2's layout)
   !>  r0, r90   [in] Lankford coefficients along and across the rolling direction
   !>  rolling   [in] .true.: the sheet is drawn along the rolling direction
   !>  c, gamma  [in] (n_back) the back stresses' constants, n_back <= 3
   pure function combined_law(props, r0, r90, rolling, c, gamma) result(law)
      real(dp), intent(in) :: props(:), r0, r90, c(:), gamma(:)
      logical, intent(in) :: rolling
      type(combined_law_type) :: law
      law%k = combined_constants_of(props, r0, r90, rolling, c, gamma)
      law%youngs = props(ip_youngs)
      law%poisson = props(ip_poisson)
      call set_normal_layout(law, 3 + 3*law%k%n_back, isv_p)
      law%name = 'combined'
      ! the section's update starts its return where the last trial ended
      ! (material_law's header, mixed_return_block)
      law%starts_from_trial = .true.
   end function combined_law

   !> COMBINED_LAW_OF_DECK: the law of a deck with model = 'combined', its
   !> variables checked: r0, r90 (default r_value), drawing_direction,
   !> kinematic_c(i) >= 0 given from i = 1 on without gaps (the number of
   !> back stresses), kinematic_gamma(i) >= 0 (default 0) only where
   !> kinematic_c(i) is given.
   !>  d        [in]     the deck
   !>  props    [in]     the isotropic part's constants set-up built from it
   !>  errs     [in,out] problems are appended, naming deck, group, variable
   !>                   (the isotropic constants are set-up's to check)
   function combined_law_of_deck(d, props, errs) result(law)
      type(deck_type), intent(in) :: d
      real(dp), intent(in) :: props(:)
      type(error_list), intent(inout) :: errs
      type(combined_law_type) :: law
      character(len=:), allocatable :: p
      real(dp) :: r0, r90, c(max_kinematic), gamma(max_kinematic)
      integer :: n, i
      p = trim(d%deck_file)
      r0 = d%r_value
      r90 = d%r_value
      if (.not. is_unset(d%r0)) r0 = d%r0
      if (.not. is_unset(d%r90)) r90 = d%r90
      ! sheet metals have r of 0.2 to 3; past 100 Hill's criterion degenerates
      call check_real(errs, at(p, 'material', 'r0'), r0, lo=0.0_dp, hi=100.0_dp, lo_open=.true.)
      call check_real(errs, at(p, 'material', 'r90'), r90, lo=0.0_dp, hi=100.0_dp, lo_open=.true.)
      call check_choice(errs, at(p, 'material', 'drawing_direction'), d%drawing_direction, &
                        [character(len=16) :: 'rolling', 'transverse'])
      n = 0
      do while (n < max_kinematic)
         if (is_unset(d%kinematic_c(n + 1))) exit
         n = n + 1
      end do
      if (any(.not. is_unset(d%kinematic_c(n + 1:)))) call fail(errs, &
         at(p, 'material', 'kinematic_c'), 'must be given from kinematic_c(1) on without gaps')
      c = 0.0_dp
      gamma = 0.0_dp
      do i = 1, n
         ! up to 1e7 MPa, as youngs_modulus
         call check_real(errs, at(p, 'material', 'kinematic_c('//achar(48 + i)//')'), &
                         d%kinematic_c(i), lo=0.0_dp, hi=1.0e7_dp)
         c(i) = d%kinematic_c(i)
         if (.not. is_unset(d%kinematic_gamma(i))) then
            call check_real(errs, at(p, 'material', 'kinematic_gamma('//achar(48 + i)//')'), &
                            d%kinematic_gamma(i), lo=0.0_dp, hi=1.0e6_dp)
            gamma(i) = d%kinematic_gamma(i)
         end if
      end do
      do i = n + 1, max_kinematic
         if (.not. is_unset(d%kinematic_gamma(i))) call fail(errs, &
            at(p, 'material', 'kinematic_gamma('//achar(48 + i)//')'), &
            'given without kinematic_c('//achar(48 + i)//')')
      end do
      if (errs%count > 0) then
         ! nothing is built from values that may be out of range
         r0 = 1.0_dp
         r90 = 1.0_dp
         c = 0.0_dp
         gamma = 0.0_dp
      end if
      law = combined_law(props, r0, r90, d%drawing_direction /= 'transverse', c(1:n), gamma(1:n))
   end function combined_law_of_deck

   !> COMBINED_POINT_UPDATE: normal_law_type's point_update (arguments
   !> there): elastic predictor, the return mapping of the module header.
   !> A failed return mapping (no convergence, a non-positive flow stress,
   !> a non-finite value) asks for half the increment.
   subroutine combined_point_update(law, stress, statev, ddsdde, cont, sse, spd, stran, dstran, &
                                    zbar, kspt, pnewdt)
      class(combined_law_type), intent(in) :: law
      real(dp), intent(inout) :: stress(3), statev(law%n_inner), sse, spd, pnewdt
      real(dp), intent(out) :: ddsdde(3, 3), cont(3, 3)
      real(dp), intent(in) :: stran(3), dstran(3), zbar
      integer, intent(in) :: kspt
      real(dp) :: mu, e, nu, tr(3), alpha_n(3, max_back_stresses), &
                  xi(3), q, p_n, sy, hp, dp_inc, n(3), alpha(3, max_back_stresses), sig(3), &
                  w, dep(3)
      integer :: i
      logical :: ok
      associate (unused => stran, unused2 => zbar, unused3 => kspt)
      end associate
      e = law%youngs
      nu = law%poisson
      mu = law%k%mu
      tr = stress + matmul(law%k%d, dstran)
      p_n = statev(isv_p)
      do i = 1, law%k%n_back
         alpha_n(:, i) = statev(isv_alpha + 3*(i - 1):isv_alpha + 2 + 3*(i - 1))
      end do
      xi = tr
      do i = 1, law%k%n_back
         xi = xi - alpha_n(:, i)
      end do
      q = sqrt(max(dot_product(xi, matmul(law%k%p, xi)), 0.0_dp))
      sy = statev(isv_flow)
      if (.not. sy > 0.0_dp) then
         call flow_stress(p_n, law%k%props, size(law%k%props), sy, hp)
         statev(isv_flow) = sy
         statev(isv_slope) = hp
      end if
      if (.not. (sy > 0.0_dp .and. all(ieee_is_finite(tr)))) then
         pnewdt = min(pnewdt, 0.5_dp)
         ddsdde = law%k%d
         cont = law%k%d
         return
      end if
      if (q <= (1.0_dp + tol_yield)*sy) then
         stress = tr
         ddsdde = law%k%d
         cont = law%k%d
         sse = elastic_energy(stress(1), stress(2), stress(3), e, nu)
         return
      end if
      call return_map(law%k, tr, alpha_n, p_n, mu, dp_inc, n, q, sy, hp, ok)
      if (.not. ok) then
         pnewdt = min(pnewdt, 0.5_dp)
         ddsdde = law%k%d
         cont = law%k%d
         return
      end if
      sig = tr - 2.0_dp*mu*dp_inc*n
      dep = dp_inc*n
      w = plastic_work(p_n + dp_inc, sy, law%k%props, size(law%k%props)) &
          - plastic_work(p_n, statev(isv_flow), law%k%props, size(law%k%props))
      do i = 1, law%k%n_back
         alpha(:, i) = (alpha_n(:, i) + (2.0_dp/3.0_dp)*law%k%c(i)*dep)/(1.0_dp + law%k%gamma(i)*dp_inc)
         w = w + 0.5_dp*dot_product(alpha_n(:, i) + alpha(:, i), dep)
         statev(isv_alpha + 3*(i - 1):isv_alpha + 2 + 3*(i - 1)) = alpha(:, i)
      end do
      statev(isv_p) = p_n + dp_inc
      statev(isv_flow) = sy
      statev(isv_slope) = hp
      stress = sig
      spd = spd + w
      sse = elastic_energy(stress(1), stress(2), stress(3), e, nu)
      call tangents(law%k, n, q, dp_inc, hp, alpha_n, alpha, ddsdde, cont)
   end subroutine combined_point_update

   !> COMBINED_UPDATE: material_law_type's update (arguments there): the
   !> elastic predictor of the module header for the block, then the points
   !> that yield gathered and returned together by mixed_return_block
   !> (docs/theory.md §13.7).
   subroutine combined_update(law, n, stress, statev, ddsdde, sse, spd, stran11, dstran, zbar, &
                              pnewdt, s22n, s22, dsig_ds22, dp_start)
      class(combined_law_type), intent(in) :: law
      integer, intent(in) :: n
      real(dp), intent(inout) :: stress(n, 2), statev(n, law%n_state), sse(n), spd(n)
      real(dp), intent(out) :: ddsdde(n, 2, 2)
      real(dp), intent(in) :: stran11(n), dstran(n, 2), zbar(n)
      real(dp), intent(inout) :: pnewdt
      real(dp), intent(in), optional :: s22n(n), s22(n)
      real(dp), intent(out), optional :: dsig_ds22(n)
      real(dp), intent(in), optional :: dp_start(n)
      real(dp) :: lam, l2m, e, nu, e_ps, sy, hp, n_bad
      ! every point's elastic trial; the return's start
      real(dp) :: pnv(n), pv(n), xe(n), te(n, 3), xie(n, 3), q2(n), dps(n)
      logical :: elastic(n)
      integer :: k, i, np
      ! the law is rate-independent and the same at every point
      associate (unused => stran11, unused2 => zbar)
      end associate
      e = law%youngs
      nu = law%poisson
      lam = law%k%lam
      l2m = law%k%d(1, 1)
      e_ps = e/(1.0_dp - nu**2)
      ! the elastic trial of every point with the width strain held and
      ! tau22 = p (one vector loop; Hill's sbar^2 = xi . P xi with xi the
      ! trial stress less the back stresses)
      do k = 1, n
         pnv(k) = 0.0_dp
         pv(k) = 0.0_dp
      end do
      if (present(s22)) then
         do k = 1, n
            pnv(k) = s22n(k)
            pv(k) = s22(k)
         end do
      end if
      do k = 1, n
         xe(k) = (pv(k) - pnv(k) - lam*(dstran(k, 1) + dstran(k, 2)))/l2m
         te(k, 1) = stress(k, 1) + l2m*dstran(k, 1) + lam*(xe(k) + dstran(k, 2))
         te(k, 2) = pv(k)
         te(k, 3) = stress(k, 2) + l2m*dstran(k, 2) + lam*(xe(k) + dstran(k, 1))
      end do
      ! xi = the trial less the back stresses (without any: the trial)
      if (law%k%n_back > 0) then
         xie = te
         do i = 1, law%k%n_back
            do k = 1, n
               xie(k, 1) = xie(k, 1) - statev(k, isv_alpha + 3*(i - 1))
               xie(k, 2) = xie(k, 2) - statev(k, isv_alpha + 1 + 3*(i - 1))
               xie(k, 3) = xie(k, 3) - statev(k, isv_alpha + 2 + 3*(i - 1))
            end do
         end do
      end if
      ! the flow stress cache, filled where not known (a virgin or a
      ! remeshed point)
      do k = 1, n
         if (.not. statev(k, isv_flow) > 0.0_dp) then
            call flow_stress(statev(k, isv_p), law%k%props, size(law%k%props), sy, hp)
            statev(k, isv_flow) = sy
            statev(k, isv_slope) = hp
         end if
      end do
      n_bad = 0.0_dp
      if (law%k%n_back > 0) then
         call hill_square(law%k%p, n, xie, q2)
      else
         call hill_square(law%k%p, n, te, q2)
      end if
      do k = 1, n
         sy = statev(k, isv_flow)
         n_bad = n_bad + merge(0.0_dp, 1.0_dp, sy > 0.0_dp .and. abs(te(k, 1)) <= huge(1.0_dp) &
                               .and. abs(te(k, 3)) <= huge(1.0_dp) .and. abs(pv(k)) <= huge(1.0_dp))
         elastic(k) = q2(k) <= ((1.0_dp + tol_yield)*sy)**2
      end do
      if (n_bad > 0.5_dp) then
         pnewdt = min(pnewdt, 0.5_dp)
         return
      end if
      ! the elastic points' end state (the yielding points' is set below)
      do k = 1, n
         if (elastic(k)) then
            stress(k, 1) = te(k, 1)
            stress(k, 2) = te(k, 3)
            statev(k, law%isv_eps22) = statev(k, law%isv_eps22) + xe(k)
            ! the tangents with tau22 held: plane-stress elasticity
            statev(k, law%isv_tangent) = e_ps
            sse(k) = elastic_energy(te(k, 1), te(k, 2), te(k, 3), e, nu)
            ddsdde(k, 1, 1) = e_ps
            ddsdde(k, 1, 2) = nu*e_ps
            ddsdde(k, 2, 1) = nu*e_ps
            ddsdde(k, 2, 2) = e_ps
         end if
      end do
      if (present(dsig_ds22)) then
         do k = 1, n
            if (elastic(k)) dsig_ds22(k) = lam/l2m
         end do
      end if
      np = count(.not. elastic)
      if (np == 0) return
      ! the return's start: the last trial's increment where it is one
      ! (a non-finite or negative value, or one of 1 or more, is none)
      do k = 1, n
         dps(k) = 0.0_dp
      end do
      if (present(dp_start)) then
         do k = 1, n
            dps(k) = merge(dp_start(k), 0.0_dp, dp_start(k) > 0.0_dp .and. dp_start(k) < 1.0_dp)
         end do
      end if
      if (present(dsig_ds22)) then
         call yielding_update(law, n, np, elastic, stress, statev, ddsdde, sse, spd, dstran, pnv, pv, &
                              dps, pnewdt, dsig_ds22)
      else
         call yielding_update(law, n, np, elastic, stress, statev, ddsdde, sse, spd, dstran, pnv, pv, &
                              dps, pnewdt)
      end if
   end subroutine combined_update

   !> YIELDING_UPDATE: combined_update's yielding points, gathered with
   !> their trial at no thickness strain increment, returned together by
   !> mixed_return_block, and their end state written back.
   !>  law                       [in]     the law
   !>  n, np                     [in]     points in the block, yielding points
   !>  elastic                   [in]     (n) .false. at the yielding points
   !>  stress, statev, ddsdde, sse, spd [in,out] the block's (update's)
   !>  dstran                    [in]     (n, 2) the strain increments
   !>  pnv, pv                   [in]     (n) the prescribed tau22 at the start and the end
   !>  dps                       [in]     (n) the return's start, >= 0 (0: the trial)
   !>  pnewdt                    [in,out] < 1 when a point found no root
   !>  dsig_ds22                 [in,out] optional: d tau11 / d tau22
   subroutine yielding_update(law, n, np, elastic, stress, statev, ddsdde, sse, spd, dstran, pnv, &
                              pv, dps, pnewdt, dsig_ds22)
      class(combined_law_type), intent(in) :: law
      integer, intent(in) :: n, np
      logical, intent(in) :: elastic(n)
      real(dp), intent(inout) :: stress(n, 2), statev(n, law%n_state), sse(n), spd(n), &
                                 ddsdde(n, 2, 2), pnewdt
      real(dp), intent(in) :: dstran(n, 2), pnv(n), pv(n), dps(n)
      real(dp), intent(inout), optional :: dsig_ds22(n)
      real(dp) :: tr0(np, 3), pp(np), ep(np), syn(np), hpn(np), aa(np, 2, max_back_stresses), dp0(np), &
                  dpv(np), xv(np), nv(np, 3), syv(np), hpv(np), tau(np, 2), dd(np, 2, 2), &
                  cpl(np), tng(np), w(np), av(np), lam, l2m, a, ci, an, al
      integer :: k, i, j, c, ic, idx(np)
      logical :: ok
      lam = law%k%lam
      l2m = law%k%d(1, 1)
      j = 0
      do k = 1, n
         if (elastic(k)) cycle
         j = j + 1
         idx(j) = k
         tr0(j, 1) = stress(k, 1) + l2m*dstran(k, 1) + lam*dstran(k, 2)
         tr0(j, 2) = pnv(k) + lam*(dstran(k, 1) + dstran(k, 2))
         tr0(j, 3) = stress(k, 2) + lam*dstran(k, 1) + l2m*dstran(k, 2)
         pp(j) = pv(k)
         ep(j) = statev(k, isv_p)
         syn(j) = statev(k, isv_flow)
         hpn(j) = statev(k, isv_slope)
         dp0(j) = dps(k)
      end do
      do i = 1, law%k%n_back
         ic = isv_alpha + 3*(i - 1)
         do j = 1, np
            k = idx(j)
            aa(j, 1, i) = law%k%eig_vec(1, 1)*statev(k, ic) + law%k%eig_vec(2, 1)*statev(k, ic + 1) &
                          + law%k%eig_vec(3, 1)*statev(k, ic + 2)
            aa(j, 2, i) = law%k%eig_vec(1, 2)*statev(k, ic) + law%k%eig_vec(2, 2)*statev(k, ic + 1) &
                          + law%k%eig_vec(3, 2)*statev(k, ic + 2)
         end do
      end do
      call mixed_return_block(law%k, np, tr0, pp, ep, syn, hpn, aa, dp0, dpv, xv, nv, syv, hpv, tau, dd, &
                              cpl, tng, ok)
      if (.not. ok) then
         pnewdt = min(pnewdt, 0.5_dp)
         return
      end if
      do j = 1, np
         w(j) = plastic_work(ep(j) + dpv(j), syv(j), law%k%props, size(law%k%props)) &
                - plastic_work(ep(j), syn(j), law%k%props, size(law%k%props))
      end do
      ! the back stresses, alpha_i = a_i (alpha_i,n + 2/3 C_i dp n), and
      ! their share of the plastic work, sum (alpha_n + alpha)/2 . dp n
      do i = 1, law%k%n_back
         ci = (2.0_dp/3.0_dp)*law%k%c(i)
         do j = 1, np
            av(j) = 1.0_dp/(1.0_dp + law%k%gamma(i)*dpv(j))
         end do
         do c = 1, 3
            ic = isv_alpha + c - 1 + 3*(i - 1)
            do j = 1, np
               k = idx(j)
               a = av(j)
               an = statev(k, ic)
               al = a*(an + ci*dpv(j)*nv(j, c))
               w(j) = w(j) + 0.5_dp*(an + al)*dpv(j)*nv(j, c)
               statev(k, ic) = al
            end do
         end do
      end do
      do j = 1, np
         k = idx(j)
         stress(k, 1) = tau(j, 1)
         stress(k, 2) = tau(j, 2)
         statev(k, isv_p) = ep(j) + dpv(j)
         statev(k, isv_flow) = syv(j)
         statev(k, isv_slope) = hpv(j)
         statev(k, law%isv_eps22) = statev(k, law%isv_eps22) + xv(j)
         statev(k, law%isv_tangent) = tng(j)
         spd(k) = spd(k) + w(j)
         sse(k) = elastic_energy(tau(j, 1), pp(j), tau(j, 2), law%youngs, law%poisson)
         ddsdde(k, :, :) = dd(j, :, :)
         if (present(dsig_ds22)) dsig_ds22(k) = cpl(j)
      end do
   end subroutine yielding_update

   !> COMBINED_STATE_MAPPED: the cached flow stress belongs to the old
   !> points' plastic strains: marked unknown (law_j2's reason).
   pure subroutine combined_state_mapped(law, statev)
      class(combined_law_type), intent(in) :: law
      real(dp), intent(inout) :: statev(:, :)
      associate (unused => law)
      end associate
      statev(:, isv_flow) = 0.0_dp
   end subroutine combined_state_mapped

   !> The stored energy of the back stresses, sum_i 3/(4 C_i) alpha_i . alpha_i.
   pure function combined_stored_energy(law, statev) result(w)
      class(combined_law_type), intent(in) :: law
      real(dp), intent(in) :: statev(:)
      real(dp) :: w
      integer :: i
      w = 0.0_dp
      do i = 1, law%k%n_back
         if (law%k%c(i) > 0.0_dp) w = w + 0.75_dp/law%k%c(i)* &
                                    sum(statev(isv_alpha + 3*(i - 1):isv_alpha + 2 + 3*(i - 1))**2)
      end do
   end function combined_stored_energy

   !> COMBINED_STORES_ENERGY: .true. with a back stress of C > 0.
   pure logical function combined_stores_energy(law)
      class(combined_law_type), intent(in) :: law
      combined_stores_energy = any(law%k%c(1:law%k%n_back) > 0.0_dp)
   end function combined_stores_energy

   !> The elastic energy density of the three normal stresses (elemental on
   !> scalars: the block loops call it without array temporaries).
   elemental function elastic_energy(s1, s2, s3, e, nu) result(w)
      real(dp), intent(in) :: s1, s2, s3, e, nu
      real(dp) :: w
      w = (s1**2 + s2**2 + s3**2 - 2.0_dp*nu*(s1*s2 + s2*s3 + s1*s3))/(2.0_dp*e)
   end function elastic_energy

end module law_combined
