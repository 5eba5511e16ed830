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
!> strain p, 2 sigma_y(p) (a cache: an elastic increment evaluates no
!> hardening law; 0 = not known, computed on entry), then alpha_i (3 normal
!> components each), i = 1 .. n_back.
!>
!> The section's update (normal_law's drive of the thickness strain) is
!> preceded by an elastic predictor for the whole block: with isotropic
!> elasticity the thickness strain of an elastic increment is known,
!> d eps22 = (d tau22 - lambda d eps11)/(lambda + 2 mu) (width held), and a
!> point whose trial state lies inside the yield surface is done with it;
!> only the points that yield are driven.
module law_combined
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use normal_law, only: normal_law_type, set_normal_layout, drive_block_point
   use hardening, only: flow_stress, plastic_work, ip_youngs, ip_poisson
   use deck, only: deck_type, is_unset, max_kinematic
   use deck_checks, only: check_real, check_choice, fail, at
   use errors, only: error_list
   implicit none
   private
   public :: combined_law_type, combined_law, combined_law_of_deck, hill_matrix, max_back_stresses

   !> the largest number of back stresses
   integer, parameter :: max_back_stresses = 3
   !> places of the own state variables (module header)
   integer, parameter :: isv_p = 1, isv_flow = 2, isv_alpha = 3
   !> a trial state with sbar_trial <= (1 + tol_yield) sigma_y is elastic
   real(dp), parameter :: tol_yield = 1.0e-12_dp
   !> relative tolerance of the yield residual of the return mapping
   real(dp), parameter :: tol_return = 1.0e-12_dp
   integer, parameter :: max_return_iter = 60

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
      call set_normal_layout(law, 2 + 3*law%n_back, isv_p)
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
      stress = sig
      spd = spd + w
      sse = elastic_energy(stress, e, nu)
      call tangents(law, n, q, dp_inc, hp, alpha_n, alpha, ddsdde, cont)
   end subroutine combined_point_update

   !> COMBINED_UPDATE: material_law_type's update (arguments there): the
   !> elastic predictor of the module header for the block, normal_law's
   !> drive_thickness for the points that yield.
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
      real(dp) :: lam, l2m, e, nu, e_ps, p_n, p, x, tr(3), xi(3), q, sy, hp
      integer :: k, i
      e = law%youngs
      nu = law%poisson
      lam = law%lam
      l2m = law%d(1, 1)
      e_ps = e/(1.0_dp - nu**2)
      do k = 1, n
         p_n = 0.0_dp
         p = 0.0_dp
         if (present(s22)) then
            p_n = s22n(k)
            p = s22(k)
         end if
         ! the elastic trial with the width strain held and tau22 = p
         x = (p - p_n - lam*(dstran(k, 1) + dstran(k, 2)))/l2m
         tr(1) = stress(k, 1) + l2m*dstran(k, 1) + lam*(x + dstran(k, 2))
         tr(2) = p
         tr(3) = stress(k, 2) + l2m*dstran(k, 2) + lam*(x + dstran(k, 1))
         xi = tr
         do i = 1, law%n_back
            xi = xi - statev(k, isv_alpha + 3*(i - 1):isv_alpha + 2 + 3*(i - 1))
         end do
         q = sqrt(max(dot_product(xi, matmul(law%p, xi)), 0.0_dp))
         sy = statev(k, isv_flow)
         if (.not. sy > 0.0_dp) then
            call flow_stress(statev(k, isv_p), law%props, size(law%props), sy, hp)
            statev(k, isv_flow) = sy
         end if
         if (sy > 0.0_dp .and. q <= (1.0_dp + tol_yield)*sy .and. all(ieee_is_finite(tr))) then
            stress(k, 1) = tr(1)
            stress(k, 2) = tr(3)
            statev(k, law%isv_eps22) = statev(k, law%isv_eps22) + x
            ! the tangents with tau22 held: plane-stress elasticity
            statev(k, law%isv_tangent) = e_ps
            sse(k) = elastic_energy(tr, e, nu)
            ddsdde(k, 1, 1) = e_ps
            ddsdde(k, 1, 2) = nu*e_ps
            ddsdde(k, 2, 1) = nu*e_ps
            ddsdde(k, 2, 2) = e_ps
            if (present(dsig_ds22)) dsig_ds22(k) = lam/l2m
            cycle
         end if
         call drive_block_point(law, k, n, stress, statev, ddsdde, sse, spd, stran11, dstran, zbar, &
                                p_n, p, pnewdt, dsig_ds22)
         if (pnewdt < 1.0_dp) return
      end do
   end subroutine combined_update

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
