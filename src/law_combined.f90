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
   use hardening, only: flow_stress, flow_stress_block, plastic_work, ip_youngs, ip_poisson
   use deck, only: deck_type, is_unset, max_kinematic
   use deck_checks, only: check_real, check_choice, fail, at
   use errors, only: error_list
   implicit none
   private
   public :: combined_law_type, combined_law, combined_law_of_deck, hill_matrix, max_back_stresses, &
             isv_p, isv_alpha

   !> the largest number of back stresses
   integer, parameter :: max_back_stresses = 3
   !> places of the own state variables (module header)
   integer, parameter :: isv_p = 1, isv_flow = 2, isv_slope = 3, isv_alpha = 4
   !> a trial state with sbar_trial <= (1 + tol_yield) sigma_y is elastic
   real(dp), parameter :: tol_yield = 1.0e-12_dp
   !> relative tolerance of the yield residual of the return mapping
   real(dp), parameter :: tol_return = 1.0e-12_dp
   integer, parameter :: max_return_iter = 60
   !> below this relative residual the last Newton step of the block
   !> return is taken without a further hardening-law call (return_mapping's
   !> tol_taylor: quadratic convergence puts the next residual near 1e-14)
   real(dp), parameter :: tol_taylor = 1.0e-7_dp

   !> Combined hardening with its constants.
   type, extends(normal_law_type) :: combined_law_type
      !> the isotropic part's constants (material_j2's layout: E, nu, R,
      !> law id, the law's constants; R is not used here)
      real(dp), allocatable :: props(:)
      !> Hill's matrix on (axial, thickness, width) and its eigen-pairs
      real(dp) :: p(3, 3) = 0.0_dp
      real(dp) :: eig_val(3) = 0.0_dp
      real(dp) :: eig_vec(3, 3) = 0.0_dp
      !> the back stresses: number, C_i (MPa) and gamma_i
      integer :: n_back = 0
      real(dp) :: c(max_back_stresses) = 0.0_dp
      real(dp) :: gamma(max_back_stresses) = 0.0_dp
      !> isotropic elasticity on the normal components, set once with the
      !> constants: Lame's lambda and mu, the stiffness and the compliance
      real(dp) :: lam = 0.0_dp, mu = 0.0_dp
      real(dp) :: d(3, 3) = 0.0_dp, cmp(3, 3) = 0.0_dp
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
      integer :: i
      allocate (law%props, source=props)
      law%youngs = props(ip_youngs)
      law%poisson = props(ip_poisson)
      law%n_back = min(size(c), max_back_stresses)
      law%mu = law%youngs/(2.0_dp*(1.0_dp + law%poisson))
      law%lam = law%youngs*law%poisson/((1.0_dp + law%poisson)*(1.0_dp - 2.0_dp*law%poisson))
      law%d = law%lam
      do i = 1, 3
         law%d(i, i) = law%lam + 2.0_dp*law%mu
      end do
      call compliance(law%youngs, law%poisson, law%cmp)
      law%c(1:law%n_back) = c(1:law%n_back)
      law%gamma(1:law%n_back) = gamma(1:law%n_back)
      law%p = hill_matrix(r0, r90, rolling)
      call eigen_deviatoric(law%p, law%eig_val, law%eig_vec)
      call set_normal_layout(law, 3 + 3*law%n_back, isv_p)
      law%name = 'combined'
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

   !> HILL_MATRIX: P of sbar^2 = tau^T P tau on (axial, thickness, width)
   !> (module header), the uniaxial yield stress along the drawing direction
   !> 1 (tau^T P tau = tau11^2 for uniaxial tau11).
   !>  r0, r90 [in] Lankford coefficients, > 0
   !>  rolling [in] .true.: drawing along the rolling direction
   pure function hill_matrix(r0, r90, rolling) result(p)
      real(dp), intent(in) :: r0, r90
      logical, intent(in) :: rolling
      real(dp) :: p(3, 3)
      real(dp) :: f, g, h, scale
      g = 1.0_dp/(1.0_dp + r0)
      h = r0/(1.0_dp + r0)
      f = h/r90
      if (rolling) then
         ! x = axial (1), y = width (3), z = thickness (2)
         scale = 1.0_dp/(g + h)
         p(1, :) = [g + h, -g, -h]
         p(2, :) = [-g, f + g, -f]
         p(3, :) = [-h, -f, f + h]
      else
         ! x = width (3), y = axial (1), z = thickness (2)
         scale = 1.0_dp/(f + h)
         p(1, :) = [f + h, -f, -h]
         p(2, :) = [-f, f + g, -g]
         p(3, :) = [-h, -g, g + h]
      end if
      p = scale*p
   end function hill_matrix

   !> EIGEN_DEVIATORIC: eigenvalues and orthonormal eigenvectors of a
   !> symmetric P whose rows sum to 0: (1,1,1)/sqrt(3) with eigenvalue 0 (the
   !> third pair), the other two from P restricted to the deviatoric plane.
   pure subroutine eigen_deviatoric(p, val, vec)
      real(dp), intent(in) :: p(3, 3)
      real(dp), intent(out) :: val(3), vec(3, 3)
      real(dp) :: ea(3), eb(3), paa, pab, pbb, tr, dt, phi, ca, cb
      ea = [1.0_dp, -1.0_dp, 0.0_dp]/sqrt(2.0_dp)
      eb = [1.0_dp, 1.0_dp, -2.0_dp]/sqrt(6.0_dp)
      paa = dot_product(ea, matmul(p, ea))
      pab = dot_product(ea, matmul(p, eb))
      pbb = dot_product(eb, matmul(p, eb))
      tr = 0.5_dp*(paa + pbb)
      dt = sqrt(0.25_dp*(paa - pbb)**2 + pab**2)
      val(1) = tr + dt
      val(2) = tr - dt
      val(3) = 0.0_dp
      ! rotation angle of the eigenvectors in the (ea, eb) plane
      phi = 0.5_dp*atan2(2.0_dp*pab, paa - pbb)
      ca = cos(phi)
      cb = sin(phi)
      vec(:, 1) = ca*ea + cb*eb
      vec(:, 2) = -cb*ea + ca*eb
      vec(:, 3) = [1.0_dp, 1.0_dp, 1.0_dp]/sqrt(3.0_dp)
   end subroutine eigen_deviatoric

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
      mu = law%mu
      tr = stress + matmul(law%d, dstran)
      p_n = statev(isv_p)
      do i = 1, law%n_back
         alpha_n(:, i) = statev(isv_alpha + 3*(i - 1):isv_alpha + 2 + 3*(i - 1))
      end do
      xi = tr
      do i = 1, law%n_back
         xi = xi - alpha_n(:, i)
      end do
      q = sqrt(max(dot_product(xi, matmul(law%p, xi)), 0.0_dp))
      sy = statev(isv_flow)
      if (.not. sy > 0.0_dp) then
         call flow_stress(p_n, law%props, size(law%props), sy, hp)
         statev(isv_flow) = sy
         statev(isv_slope) = hp
      end if
      if (.not. (sy > 0.0_dp .and. all(ieee_is_finite(tr)))) then
         pnewdt = min(pnewdt, 0.5_dp)
         ddsdde = law%d
         cont = law%d
         return
      end if
      if (q <= (1.0_dp + tol_yield)*sy) then
         stress = tr
         ddsdde = law%d
         cont = law%d
         sse = elastic_energy(stress, e, nu)
         return
      end if
      call return_map(law, tr, alpha_n, p_n, mu, dp_inc, n, q, sy, hp, ok)
      if (.not. ok) then
         pnewdt = min(pnewdt, 0.5_dp)
         ddsdde = law%d
         cont = law%d
         return
      end if
      sig = tr - 2.0_dp*mu*dp_inc*n
      dep = dp_inc*n
      w = plastic_work(p_n + dp_inc, sy, law%props, size(law%props)) &
          - plastic_work(p_n, statev(isv_flow), law%props, size(law%props))
      do i = 1, law%n_back
         alpha(:, i) = (alpha_n(:, i) + (2.0_dp/3.0_dp)*law%c(i)*dep)/(1.0_dp + law%gamma(i)*dp_inc)
         w = w + 0.5_dp*dot_product(alpha_n(:, i) + alpha(:, i), dep)
         statev(isv_alpha + 3*(i - 1):isv_alpha + 2 + 3*(i - 1)) = alpha(:, i)
      end do
      statev(isv_p) = p_n + dp_inc
      statev(isv_flow) = sy
      statev(isv_slope) = hp
      stress = sig
      spd = spd + w
      sse = elastic_energy(stress, e, nu)
      call tangents(law, n, q, dp_inc, hp, alpha_n, alpha, ddsdde, cont)
   end subroutine combined_point_update

   !> COMBINED_UPDATE: material_law_type's update (arguments there): the
   !> elastic predictor of the module header for the block, then the points
   !> that yield gathered and returned together by mixed_return_block
   !> (docs/theory.md §13.7).
   subroutine combined_update(law, n, stress, statev, ddsdde, sse, spd, stran11, dstran, zbar, &
                              pnewdt, s22n, s22, dsig_ds22)
      class(combined_law_type), intent(in) :: law
      integer, intent(in) :: n
      real(dp), intent(inout) :: stress(n, 2), statev(n, law%n_state), sse(n), spd(n)
      real(dp), intent(out) :: ddsdde(n, 2, 2)
      real(dp), intent(in) :: stran11(n), dstran(n, 2), zbar(n)
      real(dp), intent(inout) :: pnewdt
      real(dp), intent(in), optional :: s22n(n), s22(n)
      real(dp), intent(out), optional :: dsig_ds22(n)
      real(dp) :: lam, l2m, e, nu, e_ps, sy, hp, n_bad
      ! every point's elastic trial
      real(dp) :: pnv(n), pv(n), xe(n), te(n, 3), xie(n, 3), q2(n)
      logical :: elastic(n)
      integer :: k, i, np
      ! the law is rate-independent and the same at every point
      associate (unused => stran11, unused2 => zbar)
      end associate
      e = law%youngs
      nu = law%poisson
      lam = law%lam
      l2m = law%d(1, 1)
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
      if (law%n_back > 0) then
         xie = te
         do i = 1, law%n_back
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
            call flow_stress(statev(k, isv_p), law%props, size(law%props), sy, hp)
            statev(k, isv_flow) = sy
            statev(k, isv_slope) = hp
         end if
      end do
      n_bad = 0.0_dp
      if (law%n_back > 0) then
         call hill_square(law%p, n, xie, q2)
      else
         call hill_square(law%p, n, te, q2)
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
            sse(k) = (te(k, 1)**2 + te(k, 2)**2 + te(k, 3)**2 &
                      - 2.0_dp*nu*(te(k, 1)*te(k, 2) + te(k, 2)*te(k, 3) + te(k, 1)*te(k, 3)))/(2.0_dp*e)
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
      if (present(dsig_ds22)) then
         call yielding_update(law, n, np, elastic, stress, statev, ddsdde, sse, spd, dstran, pnv, pv, &
                              pnewdt, dsig_ds22)
      else
         call yielding_update(law, n, np, elastic, stress, statev, ddsdde, sse, spd, dstran, pnv, pv, &
                              pnewdt)
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
   !>  pnewdt                    [in,out] < 1 when a point found no root
   !>  dsig_ds22                 [in,out] optional: d tau11 / d tau22
   subroutine yielding_update(law, n, np, elastic, stress, statev, ddsdde, sse, spd, dstran, pnv, &
                              pv, pnewdt, dsig_ds22)
      class(combined_law_type), intent(in) :: law
      integer, intent(in) :: n, np
      logical, intent(in) :: elastic(n)
      real(dp), intent(inout) :: stress(n, 2), statev(n, law%n_state), sse(n), spd(n), &
                                 ddsdde(n, 2, 2), pnewdt
      real(dp), intent(in) :: dstran(n, 2), pnv(n), pv(n)
      real(dp), intent(inout), optional :: dsig_ds22(n)
      real(dp) :: tr0(np, 3), pp(np), ep(np), syn(np), hpn(np), aa(np, 2, max_back_stresses), &
                  dpv(np), xv(np), nv(np, 3), syv(np), hpv(np), tau(np, 2), dd(np, 2, 2), &
                  cpl(np), tng(np), w(np), lam, l2m, a, ci, an, al, half_compliance
      integer :: k, i, j, c, ic, idx(np)
      logical :: ok
      lam = law%lam
      l2m = law%d(1, 1)
      half_compliance = 0.5_dp/law%youngs
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
      end do
      do i = 1, law%n_back
         ic = isv_alpha + 3*(i - 1)
         do j = 1, np
            k = idx(j)
            aa(j, 1, i) = law%eig_vec(1, 1)*statev(k, ic) + law%eig_vec(2, 1)*statev(k, ic + 1) &
                          + law%eig_vec(3, 1)*statev(k, ic + 2)
            aa(j, 2, i) = law%eig_vec(1, 2)*statev(k, ic) + law%eig_vec(2, 2)*statev(k, ic + 1) &
                          + law%eig_vec(3, 2)*statev(k, ic + 2)
         end do
      end do
      call mixed_return_block(law, np, tr0, pp, ep, syn, hpn, aa, dpv, xv, nv, syv, hpv, tau, dd, &
                              cpl, tng, ok)
      if (.not. ok) then
         pnewdt = min(pnewdt, 0.5_dp)
         return
      end if
      do j = 1, np
         w(j) = plastic_work(ep(j) + dpv(j), syv(j), law%props, size(law%props)) &
                - plastic_work(ep(j), syn(j), law%props, size(law%props))
      end do
      ! the back stresses, alpha_i = a_i (alpha_i,n + 2/3 C_i dp n), and
      ! their share of the plastic work, sum (alpha_n + alpha)/2 . dp n
      do i = 1, law%n_back
         ci = (2.0_dp/3.0_dp)*law%c(i)
         do c = 1, 3
            ic = isv_alpha + c - 1 + 3*(i - 1)
            do j = 1, np
               k = idx(j)
               a = 1.0_dp/(1.0_dp + law%gamma(i)*dpv(j))
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
         sse(k) = (tau(j, 1)**2 + pp(j)**2 + tau(j, 2)**2 - 2.0_dp*law%poisson &
                   *(tau(j, 1)*pp(j) + pp(j)*tau(j, 2) + tau(j, 1)*tau(j, 2)))*half_compliance
         ddsdde(k, :, :) = dd(j, :, :)
         if (present(dsig_ds22)) dsig_ds22(k) = cpl(j)
      end do
   end subroutine yielding_update

   !> MIXED_RETURN_BLOCK: the backward-Euler update of np yielding points
   !> with the axial and width strain increments given and tau22
   !> prescribed, solved directly (docs/theory.md §13.7) rather than by
   !> driving the thickness strain around the three-component return
   !> mapping.
   !>
   !> For a given dp the thickness strain increment x follows in closed
   !> form: in the eigenvectors v_k of P (module header) the return is
   !> diagonal, xi_k = g_k (c_k + x d_k), g_k = 1/(1 + theta lambda_k),
   !> c_k = v_k . (tau^T(0) - sum a_i alpha_i,n), d_k = v_k . D e_2 =
   !> 2 mu v_k,2, with tau^T(0) the elastic trial at x = 0; and tau22 =
   !> tau^T_22(0) + (lambda + 2 mu) x - 2 mu dp n_2, n = P xi / sigma_y =
   !> sum lambda_k xi_k v_k / sigma_y, is affine in x.  The one unknown dp
   !> then solves phi = sqrt(sum lambda_k xi_k^2) - sigma_y = 0, by Newton's
   !> method in a bracket (mixed_step), all points at once: each pass one vector loop and one vector call of the
   !> hardening law, and the last Newton step from |phi| <= tol_taylor
   !> sigma_y taken with sigma_y carried by Taylor's formula (law_j2's
   !> return_map_block).
   !>
   !> The consistent tangent linearises the two equations in (dp, x),
   !>   tau^T_22(0) + (lambda + 2 mu) x - beta sum lambda_k e_k xi_k = p,
   !>   sum lambda_k xi_k^2 = sigma_y^2,    beta = 2 mu dp / sigma_y,
   !> e_k = v_k,2: a 2 x 2 system for d dp, d x per input (eps11, eps33,
   !> p), then d tau = d tau^T(0) + D e_2 d x - 2 mu (d dp n + dp d n).
   !>  law      [in]  the law
   !>  np       [in]  number of points
   !>  tr0      [in]  (np, 3) the elastic trial (tau11, tau22, tau33) at x = 0
   !>  pp       [in]  (np) the prescribed tau22 at the end
   !>  ep       [in]  (np) the equivalent plastic strain at the start
   !>  syn, hpn [in]  (np) sigma_y and its slope there
   !>  aa       [in]  (np, 2, max_back_stresses) v_k . alpha_i at the start
   !>  dpv      [out] (np) the plastic strain increments
   !>  xv       [out] (np) the thickness log strain increments
   !>  nv       [out] (np, 3) the flow directions at the end
   !>  syv, hpv [out] (np) sigma_y and its slope at the end
   !>  tau      [out] (np, 2) tau11, tau33 at the end
   !>  dd       [out] (np, 2, 2) d(tau11, tau33)/d(eps11, eps33), tau22 held
   !>  cpl      [out] (np) d tau11 / d tau22 at fixed eps11, eps33
   !>  tng      [out] (np) the condensed continuum tangent d tau11 / d eps11
   !>  ok       [out] .false.: a point found no root (no convergence, a
   !>                 non-positive flow stress, a non-finite value)
   pure subroutine mixed_return_block(law, np, tr0, pp, ep, syn, hpn, aa, dpv, xv, nv, syv, hpv, &
                                      tau, dd, cpl, tng, ok)
      class(combined_law_type), intent(in) :: law
      integer, intent(in) :: np
      real(dp), intent(in) :: tr0(np, 3), pp(np), ep(np), syn(np), hpn(np), &
                              aa(np, 2, max_back_stresses)
      real(dp), intent(out) :: dpv(np), xv(np), nv(np, 3), syv(np), hpv(np), tau(np, 2), &
                               dd(np, 2, 2), cpl(np), tng(np)
      logical, intent(out) :: ok
      real(dp) :: t(np, 2), lo(np), hi(np), step(np), epv(np), g(np, 2), dc0(np, 2), xi(np, 2), kap(np), &
                  theta(np), dtheta(np), beta(np), dbeta(np), phi(np), dphi(np)
      real(dp) :: n_far, n_out
      integer :: iter, j, k
      do k = 1, 2
         do j = 1, np
            t(j, k) = law%eig_vec(1, k)*tr0(j, 1) + law%eig_vec(2, k)*tr0(j, 2) &
                      + law%eig_vec(3, k)*tr0(j, 3)
         end do
      end do
      do j = 1, np
         dpv(j) = 0.0_dp
         lo(j) = 0.0_dp
         hi(j) = huge(1.0_dp)
         syv(j) = syn(j)
         hpv(j) = hpn(j)
      end do
      ok = .false.
      do iter = 1, max_return_iter
         call mixed_eval(law, np, t, tr0(:, 2), pp, aa, dpv, syv, hpv, xv, xi, g, dc0, theta, &
                         dtheta, beta, dbeta, phi, dphi)
         ! (finite: |x| <= huge, false for NaN; one vector loop, no calls)
         if (.not. all(abs(phi) <= huge(1.0_dp) .and. abs(dphi) <= huge(1.0_dp))) return
         if (iter == 1) then
            ! sbar's decay rate at dp = 0 (mixed_step)
            do j = 1, np
               kap(j) = max(-(dphi(j) + hpv(j))*syv(j)/(phi(j) + syv(j)), 0.0_dp)
            end do
         end if
         call mixed_step(np, phi, dphi, syv, hpv, kap, dpv, lo, hi, step, n_far, n_out)
         if (n_far < 0.5_dp) then
            ok = .true.
            exit
         end if
         if (n_out < 0.5_dp) then
            ! the last Newton step with sigma_y carried by Taylor's formula
            ! (return_mapping's tol_taylor: the next residual near 1e-14)
            do j = 1, np
               syv(j) = syv(j) + hpv(j)*(step(j) - dpv(j))
               dpv(j) = step(j)
            end do
            call mixed_eval(law, np, t, tr0(:, 2), pp, aa, dpv, syv, hpv, xv, xi, g, dc0, theta, &
                            dtheta, beta, dbeta, phi, dphi)
            ok = all(abs(phi) <= huge(1.0_dp))
            exit
         end if
         do j = 1, np
            dpv(j) = step(j)
            epv(j) = ep(j) + step(j)
         end do
         call flow_stress_block(np, epv, law%props, size(law%props), syv, hpv)
         if (.not. all(syv > 0.0_dp .and. syv <= huge(1.0_dp))) return
      end do
      if (.not. ok) return
      ok = all(dpv > 0.0_dp)
      if (.not. ok) return
      call mixed_results(law, np, tr0, aa, dpv, xv, xi, g, dc0, syv, hpv, dtheta, beta, dbeta, &
                         nv, tau, dd, cpl, tng)
      ok = all(abs(tau) <= huge(1.0_dp)) .and. all(abs(dd) <= huge(1.0_dp)) .and. &
           all(abs(tng) <= huge(1.0_dp))
   end subroutine mixed_return_block

   !> MIXED_EVAL: the state of mixed_return_block's points at given dp
   !> (the closed forms of its header) and phi with its derivative.
   !>  law        [in]  the law
   !>  np         [in]  number of points
   !>  t          [in]  (np, 2) v_k . tau^T(0)
   !>  tr2, pp    [in]  (np) tau^T_22(0) and the prescribed tau22
   !>  aa         [in]  (np, 2, max_back_stresses) v_k . alpha_i,n
   !>  dpv, syv, hpv [in] (np) dp, sigma_y(ep + dp) and its slope
   !>  xv         [out] (np) the thickness strain increment
   !>  xi         [out] (np, 2) xi_k
   !>  g, dc0     [out] (np, 2) g_k and d c_k / d dp
   !>  theta, dtheta, beta, dbeta [out] (np) and their derivatives in dp
   !>  phi, dphi  [out] (np) the yield residual and its derivative in dp
   pure subroutine mixed_eval(law, np, t, tr2, pp, aa, dpv, syv, hpv, xv, xi, g, dc0, theta, &
                              dtheta, beta, dbeta, phi, dphi)
      class(combined_law_type), intent(in) :: law
      integer, intent(in) :: np
      real(dp), intent(in) :: t(np, 2), tr2(np), pp(np), aa(np, 2, max_back_stresses), dpv(np), &
                              syv(np), hpv(np)
      real(dp), intent(out) :: xv(np), xi(np, 2), g(np, 2), dc0(np, 2), theta(np), dtheta(np), &
                               beta(np), dbeta(np), phi(np), dphi(np)
      real(dp) :: b(np), bd(np), c0(np, 2), a, ci, gi, mu, l2m, l1, l2, e1, e2, d1, d2, g1, g2, &
                  dg1, dg2, s1, s2, ds1, ds2, num, dnum, dnm, ddnm, dx, r1, r2, dxi1, dxi2, q, rs, &
                  u1, u2, rr
      integer :: i, j
      mu = law%mu
      l2m = law%d(1, 1)
      l1 = law%eig_val(1)
      l2 = law%eig_val(2)
      e1 = law%eig_vec(2, 1)
      e2 = law%eig_vec(2, 2)
      d1 = 2.0_dp*mu*e1
      d2 = 2.0_dp*mu*e2
      do j = 1, np
         b(j) = 0.0_dp
         bd(j) = 0.0_dp
         c0(j, 1) = t(j, 1)
         c0(j, 2) = t(j, 2)
         dc0(j, 1) = 0.0_dp
         dc0(j, 2) = 0.0_dp
      end do
      do i = 1, law%n_back
         ci = (2.0_dp/3.0_dp)*law%c(i)
         gi = law%gamma(i)
         if (gi > 0.0_dp) then
            do j = 1, np
               a = 1.0_dp/(1.0_dp + gi*dpv(j))
               b(j) = b(j) + ci*dpv(j)*a
               bd(j) = bd(j) + ci*a*a
               c0(j, 1) = c0(j, 1) - a*aa(j, 1, i)
               c0(j, 2) = c0(j, 2) - a*aa(j, 2, i)
               dc0(j, 1) = dc0(j, 1) + gi*a*a*aa(j, 1, i)
               dc0(j, 2) = dc0(j, 2) + gi*a*a*aa(j, 2, i)
            end do
         else
            ! Prager: a = 1
            do j = 1, np
               b(j) = b(j) + ci*dpv(j)
               bd(j) = bd(j) + ci
               c0(j, 1) = c0(j, 1) - aa(j, 1, i)
               c0(j, 2) = c0(j, 2) - aa(j, 2, i)
            end do
         end if
      end do
      do j = 1, np
         ! (four divisions per point and pass: 1/sigma_y, g1 and g2 from
         ! one, 1/dnm, 1/q)
         rs = 1.0_dp/syv(j)
         theta(j) = (2.0_dp*mu*dpv(j) + b(j))*rs
         dtheta(j) = (2.0_dp*mu + bd(j) - theta(j)*hpv(j))*rs
         beta(j) = 2.0_dp*mu*dpv(j)*rs
         dbeta(j) = (2.0_dp*mu - beta(j)*hpv(j))*rs
         u1 = 1.0_dp + theta(j)*l1
         u2 = 1.0_dp + theta(j)*l2
         rr = 1.0_dp/(u1*u2)
         g1 = u2*rr
         g2 = u1*rr
         dg1 = -g1*g1*l1*dtheta(j)
         dg2 = -g2*g2*l2*dtheta(j)
         g(j, 1) = g1
         g(j, 2) = g2
         s1 = l1*e1*g1*c0(j, 1) + l2*e2*g2*c0(j, 2)
         s2 = l1*e1*g1*d1 + l2*e2*g2*d2
         ds1 = l1*e1*(dg1*c0(j, 1) + g1*dc0(j, 1)) + l2*e2*(dg2*c0(j, 2) + g2*dc0(j, 2))
         ds2 = l1*e1*dg1*d1 + l2*e2*dg2*d2
         ! tau22 = p: x in closed form at this dp
         num = pp(j) - tr2(j) + beta(j)*s1
         dnum = dbeta(j)*s1 + beta(j)*ds1
         dnm = l2m - beta(j)*s2
         ddnm = -(dbeta(j)*s2 + beta(j)*ds2)
         rr = 1.0_dp/dnm
         xv(j) = num*rr
         dx = (dnum - xv(j)*ddnm)*rr
         r1 = c0(j, 1) + xv(j)*d1
         r2 = c0(j, 2) + xv(j)*d2
         xi(j, 1) = g1*r1
         xi(j, 2) = g2*r2
         dxi1 = dg1*r1 + g1*(dc0(j, 1) + dx*d1)
         dxi2 = dg2*r2 + g2*(dc0(j, 2) + dx*d2)
         q = sqrt(max(l1*xi(j, 1)**2 + l2*xi(j, 2)**2, tiny(1.0_dp)))
         phi(j) = q - syv(j)
         dphi(j) = (l1*xi(j, 1)*dxi1 + l2*xi(j, 2)*dxi2)/q - hpv(j)
      end do
   end subroutine mixed_eval

   !> MIXED_STEP: one safeguarded Newton step of mixed_return_block at
   !> every point (return_mapping's newton_step_block): the bracket
   !> [lo, hi] narrowed by the sign of phi, the Newton step on
   !> F = phi (1 + kappa dp / sigma_y), bisection (or doubling, before a
   !> bracket is known) where it leaves the bracket; a point with
   !> |phi| <= tol_return sigma_y keeps its dp.  kappa is the decay rate of
   !> sbar at dp = 0, sbar ~ sbar_0 / (1 + kappa dp / sigma_y): F is then
   !> nearly linear in dp.  (With the larger rate of the three-component
   !> return, 3 mu for von Mises, where the thickness stress is held the
   !> steps overshoot and a large increment took some 20 bisections.)
   !>  np           [in]  number of points
   !>  phi, dphi    [in]  (np) the residual and its derivative
   !>  syv, hpv     [in]  (np) sigma_y and its slope
   !>  kap          [in]  (np) kappa
   !>  dpv          [in]  (np) dp
   !>  lo, hi       [in,out] (np) the bracket
   !>  step         [out] (np) the next dp
   !>  n_far        [out] points not yet at |phi| <= tol_return sigma_y
   !>  n_out        [out] of these, points too far for the Taylor finish
   pure subroutine mixed_step(np, phi, dphi, syv, hpv, kap, dpv, lo, hi, step, n_far, n_out)
      integer, intent(in) :: np
      real(dp), intent(in) :: phi(np), dphi(np), syv(np), hpv(np), kap(np), dpv(np)
      real(dp), intent(inout) :: lo(np), hi(np)
      real(dp), intent(out) :: step(np), n_far, n_out
      real(dp) :: far, near, f, fd, s, l, h, den, rs
      logical :: inside
      integer :: j
      n_far = 0.0_dp
      n_out = 0.0_dp
      do j = 1, np
         far = merge(0.0_dp, 1.0_dp, abs(phi(j)) <= tol_return*syv(j))
         l = merge(dpv(j), lo(j), phi(j) > 0.0_dp)
         h = merge(hi(j), dpv(j), phi(j) > 0.0_dp)
         lo(j) = l
         hi(j) = h
         rs = 1.0_dp/syv(j)
         den = 1.0_dp + kap(j)*dpv(j)*rs
         f = phi(j)*den
         fd = dphi(j)*den + phi(j)*kap(j)*(1.0_dp - dpv(j)*hpv(j)*rs)*rs
         s = dpv(j) - f/merge(fd, -1.0_dp, fd < 0.0_dp)
         inside = fd < 0.0_dp .and. s > l .and. s < h
         s = merge(s, merge(0.5_dp*(l + h), max(2.0_dp*l, 1.0e-8_dp), h < huge(1.0_dp)), inside)
         step(j) = dpv(j)*(1.0_dp - far) + s*far
         near = merge(1.0_dp, 0.0_dp, inside)*merge(1.0_dp, 0.0_dp, abs(phi(j)) <= tol_taylor*syv(j))
         n_far = n_far + far
         n_out = n_out + far*(1.0_dp - near)
      end do
   end subroutine mixed_step

   !> MIXED_RESULTS: mixed_return_block's end state and tangents at its
   !> root (the linearisation in its header) and the continuum tangent.
   !>  law   [in]  the law
   !>  np    [in]  number of points
   !>  tr0, aa, dpv, xv, xi, g, dc0, syv, hpv, dtheta, beta, dbeta [in]
   !>              as mixed_return_block and mixed_eval at the root
   !>  nv, tau, dd, cpl, tng [out] as mixed_return_block
   pure subroutine mixed_results(law, np, tr0, aa, dpv, xv, xi, g, dc0, syv, hpv, dtheta, beta, &
                                 dbeta, nv, tau, dd, cpl, tng)
      class(combined_law_type), intent(in) :: law
      integer, intent(in) :: np
      real(dp), intent(in) :: tr0(np, 3), aa(np, 2, max_back_stresses), dpv(np), xv(np), &
                              xi(np, 2), g(np, 2), dc0(np, 2), syv(np), hpv(np), dtheta(np), &
                              beta(np), dbeta(np)
      real(dp), intent(out) :: nv(np, 3), tau(np, 2), dd(np, 2, 2), cpl(np), tng(np)
      real(dp) :: mu, lam, l2m, l1, l2, e1, e2, d1, d2, v(3, 2), dtk(2, 3), dtr(3, 3), dpin(3), &
                  ng0(np), nn, s, r1, r2, ddp, ddx, dxi1, dxi2, dn1, dn3, w1, w2, an, a, ci, gi, &
                  den, c11, c12, c22
      ! per point: the 2 x 2 system, 1/sigma_y, the columns d tau11, d tau33
      real(dp), dimension(np) :: a1, a2, b1, b2, a11, a12, a21, a22, rdet, rsy
      real(dp) :: dt1(np, 3), dt3(np, 3)
      integer :: i, j, c
      mu = law%mu
      lam = law%lam
      l2m = law%d(1, 1)
      l1 = law%eig_val(1)
      l2 = law%eig_val(2)
      v = law%eig_vec(:, 1:2)
      e1 = v(2, 1)
      e2 = v(2, 2)
      d1 = 2.0_dp*mu*e1
      d2 = 2.0_dp*mu*e2
      ! the inputs eps11, eps33, p: d(v_k . tau^T(0)), d tau^T(0), d p
      dtk(:, 1) = 2.0_dp*mu*v(1, :)
      dtk(:, 2) = 2.0_dp*mu*v(3, :)
      dtk(:, 3) = 0.0_dp
      dtr(:, 1) = [l2m, lam, lam]
      dtr(:, 2) = [lam, lam, l2m]
      dtr(:, 3) = 0.0_dp
      dpin = [0.0_dp, 0.0_dp, 1.0_dp]
      ! n . g0 of the continuum tangent: sum_i (2/3 C_i n.n - gamma_i alpha_i . n)
      do j = 1, np
         ng0(j) = 0.0_dp
      end do
      do i = 1, law%n_back
         ci = (2.0_dp/3.0_dp)*law%c(i)
         gi = law%gamma(i)
         do j = 1, np
            w1 = l1*xi(j, 1)/syv(j)
            w2 = l2*xi(j, 2)/syv(j)
            nn = w1*w1 + w2*w2
            an = aa(j, 1, i)*w1 + aa(j, 2, i)*w2
            a = 1.0_dp/(1.0_dp + gi*dpv(j))
            ng0(j) = ng0(j) + ci*nn - gi*a*(an + ci*dpv(j)*nn)
         end do
      end do
      do j = 1, np
         rsy(j) = 1.0_dp/syv(j)
         w1 = l1*xi(j, 1)*rsy(j)
         w2 = l2*xi(j, 2)*rsy(j)
         nv(j, 1) = v(1, 1)*w1 + v(1, 2)*w2
         nv(j, 2) = v(2, 1)*w1 + v(2, 2)*w2
         nv(j, 3) = v(3, 1)*w1 + v(3, 2)*w2
         tau(j, 1) = tr0(j, 1) + lam*xv(j) - 2.0_dp*mu*dpv(j)*nv(j, 1)
         tau(j, 2) = tr0(j, 3) + lam*xv(j) - 2.0_dp*mu*dpv(j)*nv(j, 3)
         ! the 2 x 2 system in (d dp, d x): d xi_k = A_k d dp + B_k d x + g_k d t_k
         a1(j) = -g(j, 1)*l1*dtheta(j)*xi(j, 1) + g(j, 1)*dc0(j, 1)
         a2(j) = -g(j, 2)*l2*dtheta(j)*xi(j, 2) + g(j, 2)*dc0(j, 2)
         b1(j) = g(j, 1)*d1
         b2(j) = g(j, 2)*d2
         s = l1*e1*xi(j, 1) + l2*e2*xi(j, 2)
         a11(j) = -(dbeta(j)*s + beta(j)*(l1*e1*a1(j) + l2*e2*a2(j)))
         a12(j) = l2m - beta(j)*(l1*e1*b1(j) + l2*e2*b2(j))
         a21(j) = l1*xi(j, 1)*a1(j) + l2*xi(j, 2)*a2(j) - syv(j)*hpv(j)
         a22(j) = l1*xi(j, 1)*b1(j) + l2*xi(j, 2)*b2(j)
         rdet(j) = 1.0_dp/(a11(j)*a22(j) - a12(j)*a21(j))
         ! the continuum tangent (dp -> 0) condensed with tau22 held; D n =
         ! 2 mu n (n is traceless)
         nn = w1*w1 + w2*w2
         den = hpv(j) + ng0(j) + 2.0_dp*mu*nn
         c11 = l2m - 4.0_dp*mu*mu*nv(j, 1)**2/den
         c12 = lam - 4.0_dp*mu*mu*nv(j, 1)*nv(j, 2)/den
         c22 = l2m - 4.0_dp*mu*mu*nv(j, 2)**2/den
         tng(j) = c11 - c12*c12/c22
      end do
      do c = 1, 3
         do j = 1, np
            r1 = dpin(c) - dtr(2, c) + beta(j)*(l1*e1*g(j, 1)*dtk(1, c) + l2*e2*g(j, 2)*dtk(2, c))
            r2 = -(l1*xi(j, 1)*g(j, 1)*dtk(1, c) + l2*xi(j, 2)*g(j, 2)*dtk(2, c))
            ddp = (r1*a22(j) - a12(j)*r2)*rdet(j)
            ddx = (a11(j)*r2 - a21(j)*r1)*rdet(j)
            dxi1 = a1(j)*ddp + b1(j)*ddx + g(j, 1)*dtk(1, c)
            dxi2 = a2(j)*ddp + b2(j)*ddx + g(j, 2)*dtk(2, c)
            dn1 = (l1*dxi1*v(1, 1) + l2*dxi2*v(1, 2) - nv(j, 1)*hpv(j)*ddp)*rsy(j)
            dn3 = (l1*dxi1*v(3, 1) + l2*dxi2*v(3, 2) - nv(j, 3)*hpv(j)*ddp)*rsy(j)
            dt1(j, c) = dtr(1, c) + lam*ddx - 2.0_dp*mu*(ddp*nv(j, 1) + dpv(j)*dn1)
            dt3(j, c) = dtr(3, c) + lam*ddx - 2.0_dp*mu*(ddp*nv(j, 3) + dpv(j)*dn3)
         end do
      end do
      do j = 1, np
         dd(j, 1, 1) = dt1(j, 1)
         dd(j, 2, 1) = dt3(j, 1)
         dd(j, 1, 2) = dt1(j, 2)
         dd(j, 2, 2) = dt3(j, 2)
         cpl(j) = dt1(j, 3)
      end do
   end subroutine mixed_results

   !> HILL_SQUARE: Hill's sbar^2 = x^T P x of n stress vectors.
   !>  p   [in]  (3, 3) Hill's matrix
   !>  n   [in]  number of vectors
   !>  x   [in]  (n, 3) the vectors (axial, thickness, width)
   !>  q2  [out] (n) sbar^2
   pure subroutine hill_square(p, n, x, q2)
      real(dp), intent(in) :: p(3, 3)
      integer, intent(in) :: n
      real(dp), intent(in) :: x(n, 3)
      real(dp), intent(out) :: q2(n)
      integer :: k
      do k = 1, n
         q2(k) = p(1, 1)*x(k, 1)**2 + p(2, 2)*x(k, 2)**2 + p(3, 3)*x(k, 3)**2 &
                 + 2.0_dp*(p(1, 2)*x(k, 1)*x(k, 2) + p(1, 3)*x(k, 1)*x(k, 3) + p(2, 3)*x(k, 2)*x(k, 3))
      end do
   end subroutine hill_square

   !> COMBINED_STATE_MAPPED: the cached flow stress belongs to the old
   !> points' plastic strains: marked unknown (law_j2's reason).
   pure subroutine combined_state_mapped(law, statev)
      class(combined_law_type), intent(in) :: law
      real(dp), intent(inout) :: statev(:, :)
      associate (unused => law)
      end associate
      statev(:, isv_flow) = 0.0_dp
   end subroutine combined_state_mapped

   !> RETURN_MAP: dp of the module header by Newton's method in a bracket.
   !>  law      [in]  the law
   !>  tr       [in]  (3) trial stress
   !>  alpha_n  [in]  (3, max_back_stresses) back stresses at the start
   !>  p_n      [in]  equivalent plastic strain at the start
   !>  mu       [in]  shear modulus
   !>  dp_inc   [out] the plastic strain increment
   !>  n        [out] (3) the flow direction at the end
   !>  q        [out] Hill's equivalent of xi at the end (= sigma_y)
   !>  sy, hp   [out] the flow stress and its slope at p_n + dp
   !>  ok       [out] .false. when no root was found
   pure subroutine return_map(law, tr, alpha_n, p_n, mu, dp_inc, n, q, sy, hp, ok)
      class(combined_law_type), intent(in) :: law
      real(dp), intent(in) :: tr(3), alpha_n(3, max_back_stresses), p_n, mu
      real(dp), intent(out) :: dp_inc, n(3), q, sy, hp
      logical, intent(out) :: ok
      real(dp) :: lo, hi, x, phi, dphi, ck(2), dck(2), a, ad, b, bd, theta, dtheta, den, &
                  xstar(3), dxstar(3), s2, ds2, y(3)
      integer :: it, i, k
      lo = 0.0_dp
      hi = huge(1.0_dp)
      x = 0.0_dp
      ok = .false.
      do it = 1, max_return_iter
         xstar = tr
         dxstar = 0.0_dp
         b = 0.0_dp
         bd = 0.0_dp
         do i = 1, law%n_back
            a = 1.0_dp/(1.0_dp + law%gamma(i)*x)
            ad = -law%gamma(i)*a*a
            xstar = xstar - a*alpha_n(:, i)
            dxstar = dxstar - ad*alpha_n(:, i)
            b = b + (2.0_dp/3.0_dp)*law%c(i)*x*a
            bd = bd + (2.0_dp/3.0_dp)*law%c(i)*a*a
         end do
         call flow_stress(p_n + x, law%props, size(law%props), sy, hp)
         if (.not. sy > 0.0_dp) return
         theta = (2.0_dp*mu*x + b)/sy
         dtheta = (2.0_dp*mu + bd)/sy - (2.0_dp*mu*x + b)*hp/sy**2
         s2 = 0.0_dp
         ds2 = 0.0_dp
         do k = 1, 2
            ck(k) = dot_product(law%eig_vec(:, k), xstar)
            dck(k) = dot_product(law%eig_vec(:, k), dxstar)
            den = 1.0_dp + theta*law%eig_val(k)
            s2 = s2 + law%eig_val(k)*ck(k)**2/den**2
            ds2 = ds2 + 2.0_dp*law%eig_val(k)*(ck(k)*dck(k)/den**2 &
                                                - ck(k)**2*law%eig_val(k)*dtheta/den**3)
         end do
         q = sqrt(max(s2, 0.0_dp))
         phi = q - sy
         if (.not. ieee_is_finite(phi)) return
         if (abs(phi) <= tol_return*sy .and. it > 1) exit
         if (phi > 0.0_dp) then
            lo = x
         else
            hi = x
         end if
         dphi = ds2/(2.0_dp*max(q, tiny(1.0_dp))) - hp
         ! Newton on (1 + theta lambda_1) phi, which has the root of phi and
         ! is nearly linear in dp (for von Mises exactly the radial
         ! return's q* - sigma_y - (3 mu dp + 3/2 B)): two or three
         ! iterations instead of phi's five or six
         den = 1.0_dp + theta*law%eig_val(1)
         dphi = dphi*den + phi*law%eig_val(1)*dtheta
         phi = phi*den
         if (dphi < 0.0_dp) then
            x = x - phi/dphi
         else
            x = -1.0_dp
         end if
         ! outside the bracket: bisect (or double until a bracket is found)
         if (x <= lo .or. x >= hi) then
            if (hi < huge(1.0_dp)) then
               x = 0.5_dp*(lo + hi)
            else
               x = max(2.0_dp*lo, 1.0e-8_dp)
            end if
         end if
         if (it == max_return_iter) return
      end do
      dp_inc = x
      ! the end state at the root
      y = law%eig_vec(:, 3)*dot_product(law%eig_vec(:, 3), xstar)
      n = 0.0_dp
      do k = 1, 2
         den = 1.0_dp + theta*law%eig_val(k)
         y = y + law%eig_vec(:, k)*ck(k)/den
         n = n + law%eig_vec(:, k)*law%eig_val(k)*ck(k)/den
      end do
      n = n/q
      ok = dp_inc > 0.0_dp .and. all(ieee_is_finite(n))
   end subroutine return_map

   !> TANGENTS: the consistent and continuum tangents of a plastic
   !> increment (module header).
   !>  law      [in]  the law
   !>  n, q     [in]  flow direction and Hill's equivalent of xi at the end
   !>  dp_inc   [in]  the plastic strain increment
   !>  hp       [in]  d sigma_y / dp at the end
   !>  alpha_n, alpha [in] the back stresses at the start and the end
   !>  ddsdde   [out] consistent tangent
   !>  cont     [out] continuum tangent
   pure subroutine tangents(law, n, q, dp_inc, hp, alpha_n, alpha, ddsdde, cont)
      class(combined_law_type), intent(in) :: law
      real(dp), intent(in) :: n(3), q, dp_inc, hp, &
                              alpha_n(3, max_back_stresses), alpha(3, max_back_stresses)
      real(dp), intent(out) :: ddsdde(3, 3), cont(3, 3)
      real(dp) :: nn(3, 3), m(3, 3), a(3, 3), ai(3, 3), g(3), r(3), b, a_i, u(3), v(3), den, &
                  eye(3, 3), dn(3), g0(3)
      integer :: i
      eye = 0.0_dp
      do i = 1, 3
         eye(i, i) = 1.0_dp
      end do
      nn = (law%p - outer(n, n))/q
      b = 0.0_dp
      g = 0.0_dp
      g0 = 0.0_dp
      do i = 1, law%n_back
         a_i = 1.0_dp/(1.0_dp + law%gamma(i)*dp_inc)
         b = b + (2.0_dp/3.0_dp)*law%c(i)*dp_inc*a_i
         g = g - law%gamma(i)*a_i*a_i*alpha_n(:, i) + (2.0_dp/3.0_dp)*law%c(i)*a_i*a_i*n
         g0 = g0 - law%gamma(i)*alpha(:, i) + (2.0_dp/3.0_dp)*law%c(i)*n
      end do
      m = inverse3(eye + b*nn)
      a = law%cmp + dp_inc*matmul(nn, m)
      ai = inverse3(a)
      r = n - dp_inc*matmul(nn, matmul(m, g))
      u = matmul(ai, r)
      v = matmul(n, matmul(m, ai))
      den = hp + dot_product(n, matmul(m, g)) + dot_product(v, r)
      ddsdde = ai - outer(u, v)/den
      dn = matmul(law%d, n)
      cont = law%d - outer(dn, dn)/(hp + dot_product(n, g0) + dot_product(n, dn))
   end subroutine tangents

   !> The stored energy of the back stresses, sum_i 3/(4 C_i) alpha_i . alpha_i.
   pure function combined_stored_energy(law, statev) result(w)
      class(combined_law_type), intent(in) :: law
      real(dp), intent(in) :: statev(:)
      real(dp) :: w
      integer :: i
      w = 0.0_dp
      do i = 1, law%n_back
         if (law%c(i) > 0.0_dp) w = w + 0.75_dp/law%c(i)* &
                                    sum(statev(isv_alpha + 3*(i - 1):isv_alpha + 2 + 3*(i - 1))**2)
      end do
   end function combined_stored_energy

   !> COMBINED_STORES_ENERGY: .true. with a back stress of C > 0.
   pure logical function combined_stores_energy(law)
      class(combined_law_type), intent(in) :: law
      combined_stores_energy = any(law%c(1:law%n_back) > 0.0_dp)
   end function combined_stores_energy

   !> The elastic energy density of the three normal stresses.
   pure function elastic_energy(s, e, nu) result(w)
      real(dp), intent(in) :: s(3), e, nu
      real(dp) :: w
      w = (s(1)**2 + s(2)**2 + s(3)**2 - 2.0_dp*nu*(s(1)*s(2) + s(2)*s(3) + s(1)*s(3)))/(2.0_dp*e)
   end function elastic_energy

   !> The isotropic elastic compliance on the normal components.
   pure subroutine compliance(e, nu, cmp)
      real(dp), intent(in) :: e, nu
      real(dp), intent(out) :: cmp(3, 3)
      cmp = -nu/e
      cmp(1, 1) = 1.0_dp/e
      cmp(2, 2) = 1.0_dp/e
      cmp(3, 3) = 1.0_dp/e
   end subroutine compliance

   pure function outer(a, b) result(c)
      real(dp), intent(in) :: a(3), b(3)
      real(dp) :: c(3, 3)
      integer :: j
      do j = 1, 3
         c(:, j) = a*b(j)
      end do
   end function outer

   !> The inverse of a 3 x 3 matrix by cofactors (the callers' are
   !> invertible: module header).
   pure function inverse3(a) result(b)
      real(dp), intent(in) :: a(3, 3)
      real(dp) :: b(3, 3), det
      b(1, 1) = a(2, 2)*a(3, 3) - a(2, 3)*a(3, 2)
      b(1, 2) = a(1, 3)*a(3, 2) - a(1, 2)*a(3, 3)
      b(1, 3) = a(1, 2)*a(2, 3) - a(1, 3)*a(2, 2)
      b(2, 1) = a(2, 3)*a(3, 1) - a(2, 1)*a(3, 3)
      b(2, 2) = a(1, 1)*a(3, 3) - a(1, 3)*a(3, 1)
      b(2, 3) = a(1, 3)*a(2, 1) - a(1, 1)*a(2, 3)
      b(3, 1) = a(2, 1)*a(3, 2) - a(2, 2)*a(3, 1)
      b(3, 2) = a(1, 2)*a(3, 1) - a(1, 1)*a(3, 2)
      b(3, 3) = a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1)
      det = a(1, 1)*b(1, 1) + a(1, 2)*b(2, 1) + a(1, 3)*b(3, 1)
      b = b/det
   end function inverse3
end module law_combined
