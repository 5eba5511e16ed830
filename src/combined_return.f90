!> combined_return -- the backward-Euler return mappings of combined
!> hardening (module law_combined; docs/theory.md §13.4, §13.7) on the
!> law's constants: the three-component return with its consistent and
!> continuum tangents (13.3)-(13.5), used where the thickness strain is
!> driven (normal_law, the tests' reference), and the section's block
!> return with tau22 prescribed (13.7)-(13.9).
module combined_return
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use hardening, only: flow_stress, flow_stress_block, ip_youngs, ip_poisson
   use hill, only: hill_matrix, eigen_deviatoric
   implicit none
   private
   public :: combined_constants, combined_constants_of, max_back_stresses, return_map, tangents, &
             mixed_return_block

   !> the largest number of back stresses
   integer, parameter :: max_back_stresses = 3
   !> relative tolerance of the yield residual of the return mapping
   real(dp), parameter :: tol_return = 1.0e-12_dp
   integer, parameter :: max_return_iter = 60
   !> below this relative residual the last Newton step of the block
   !> return is taken without a further hardening-law call (return_mapping's
   !> tol_taylor).  Quadratic convergence puts the yield residual after it
   !> near 1e-10 sigma_y: at most 1.9e-11 measured over the laws_cost
   !> decks (docs/performance.md), far below the global Newton's 1e-8;
   !> 1e-7 took one more pass at most points and 8% more time on them.
   real(dp), parameter :: tol_taylor = 1.0e-5_dp

   !> The constants of combined hardening (law_combined's header).
   type :: combined_constants
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
      !> isotropic elasticity on the normal components: Lame's lambda and
      !> mu, the stiffness and the compliance
      real(dp) :: lam = 0.0_dp, mu = 0.0_dp
      real(dp) :: d(3, 3) = 0.0_dp, cmp(3, 3) = 0.0_dp
   end type combined_constants

contains

   !> COMBINED_CONSTANTS_OF: the constants from the deck's values (the
   !> caller has checked them: E > 0, -1 < nu < 0.5, the isotropic law's
   !> constants, r0, r90 > 0, C_i >= 0, gamma_i >= 0).
   !>  props     [in] the isotropic part's constants (material_j2's layout)
   !>  r0, r90   [in] Lankford coefficients along and across the rolling direction
   !>  rolling   [in] .true.: the sheet is drawn along the rolling direction
   !>  c, gamma  [in] (n_back) the back stresses' constants, n_back <= 3
   pure function combined_constants_of(props, r0, r90, rolling, c, gamma) result(k)
      real(dp), intent(in) :: props(:), r0, r90, c(:), gamma(:)
      logical, intent(in) :: rolling
      type(combined_constants) :: k
      real(dp) :: e, nu
      integer :: i
      allocate (k%props, source=props)
      e = props(ip_youngs)
      nu = props(ip_poisson)
      k%n_back = min(size(c), max_back_stresses)
      k%mu = e/(2.0_dp*(1.0_dp + nu))
      k%lam = e*nu/((1.0_dp + nu)*(1.0_dp - 2.0_dp*nu))
      k%d = k%lam
      do i = 1, 3
         k%d(i, i) = k%lam + 2.0_dp*k%mu
      end do
      call compliance(e, nu, k%cmp)
      k%c(1:k%n_back) = c(1:k%n_back)
      k%gamma(1:k%n_back) = gamma(1:k%n_back)
      k%p = hill_matrix(r0, r90, rolling)
      call eigen_deviatoric(k%p, k%eig_val, k%eig_vec)
   end function combined_constants_of

   !> RETURN_MAP: dp of law_combined's header by Newton's method in a bracket.
   !>  con      [in]  the law's constants
   !>  tr       [in]  (3) trial stress
   !>  alpha_n  [in]  (3, max_back_stresses) back stresses at the start
   !>  p_n      [in]  equivalent plastic strain at the start
   !>  mu       [in]  shear modulus
   !>  dp_inc   [out] the plastic strain increment
   !>  n        [out] (3) the flow direction at the end
   !>  q        [out] Hill's equivalent of xi at the end (= sigma_y)
   !>  sy, hp   [out] the flow stress and its slope at p_n + dp
   !>  ok       [out] .false. when no root was found
   pure subroutine return_map(con, tr, alpha_n, p_n, mu, dp_inc, n, q, sy, hp, ok)
      type(combined_constants), intent(in) :: con
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
         do i = 1, con%n_back
            a = 1.0_dp/(1.0_dp + con%gamma(i)*x)
            ad = -con%gamma(i)*a*a
            xstar = xstar - a*alpha_n(:, i)
            dxstar = dxstar - ad*alpha_n(:, i)
            b = b + (2.0_dp/3.0_dp)*con%c(i)*x*a
            bd = bd + (2.0_dp/3.0_dp)*con%c(i)*a*a
         end do
         call flow_stress(p_n + x, con%props, size(con%props), sy, hp)
         if (.not. sy > 0.0_dp) return
         theta = (2.0_dp*mu*x + b)/sy
         dtheta = (2.0_dp*mu + bd)/sy - (2.0_dp*mu*x + b)*hp/sy**2
         s2 = 0.0_dp
         ds2 = 0.0_dp
         do k = 1, 2
            ck(k) = dot_product(con%eig_vec(:, k), xstar)
            dck(k) = dot_product(con%eig_vec(:, k), dxstar)
            den = 1.0_dp + theta*con%eig_val(k)
            s2 = s2 + con%eig_val(k)*ck(k)**2/den**2
            ds2 = ds2 + 2.0_dp*con%eig_val(k)*(ck(k)*dck(k)/den**2 &
                                                - ck(k)**2*con%eig_val(k)*dtheta/den**3)
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
         den = 1.0_dp + theta*con%eig_val(1)
         dphi = dphi*den + phi*con%eig_val(1)*dtheta
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
      y = con%eig_vec(:, 3)*dot_product(con%eig_vec(:, 3), xstar)
      n = 0.0_dp
      do k = 1, 2
         den = 1.0_dp + theta*con%eig_val(k)
         y = y + con%eig_vec(:, k)*ck(k)/den
         n = n + con%eig_vec(:, k)*con%eig_val(k)*ck(k)/den
      end do
      n = n/q
      ok = dp_inc > 0.0_dp .and. all(ieee_is_finite(n))
   end subroutine return_map

   !> TANGENTS: the consistent and continuum tangents of a plastic
   !> increment (law_combined's header).
   !>  con      [in]  the law's constants
   !>  n, q     [in]  flow direction and Hill's equivalent of xi at the end
   !>  dp_inc   [in]  the plastic strain increment
   !>  hp       [in]  d sigma_y / dp at the end
   !>  alpha_n, alpha [in] the back stresses at the start and the end
   !>  ddsdde   [out] consistent tangent
   !>  cont     [out] continuum tangent
   pure subroutine tangents(con, n, q, dp_inc, hp, alpha_n, alpha, ddsdde, cont)
      type(combined_constants), intent(in) :: con
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
      nn = (con%p - outer(n, n))/q
      b = 0.0_dp
      g = 0.0_dp
      g0 = 0.0_dp
      do i = 1, con%n_back
         a_i = 1.0_dp/(1.0_dp + con%gamma(i)*dp_inc)
         b = b + (2.0_dp/3.0_dp)*con%c(i)*dp_inc*a_i
         g = g - con%gamma(i)*a_i*a_i*alpha_n(:, i) + (2.0_dp/3.0_dp)*con%c(i)*a_i*a_i*n
         g0 = g0 - con%gamma(i)*alpha(:, i) + (2.0_dp/3.0_dp)*con%c(i)*n
      end do
      m = inverse3(eye + b*nn)
      a = con%cmp + dp_inc*matmul(nn, m)
      ai = inverse3(a)
      r = n - dp_inc*matmul(nn, matmul(m, g))
      u = matmul(ai, r)
      v = matmul(n, matmul(m, ai))
      den = hp + dot_product(n, matmul(m, g)) + dot_product(v, r)
      ddsdde = ai - outer(u, v)/den
      dn = matmul(con%d, n)
      cont = con%d - outer(dn, dn)/(hp + dot_product(n, g0) + dot_product(n, dn))
   end subroutine tangents

   !> MIXED_RETURN_BLOCK: the backward-Euler update of np yielding points
   !> with the axial and width strain increments given and tau22
   !> prescribed, solved directly (docs/theory.md §13.7) rather than by
   !> driving the thickness strain around the three-component return
   !> mapping.
   !>
   !> For a given dp the thickness strain increment x follows in closed
   !> form: in the eigenvectors v_k of P (law_combined's header) the return is
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
   !>
   !> The iteration starts from dp0 where it is given (> 0): within an
   !> increment the global Newton iterations call the update again with
   !> strains that change less and less, and the last trial's dp is then
   !> close to the root (material_law's header; on
   !> input/cc_fig5a_beadA_steel_kinematic.nml the passes per block fall
   !> from 3.4 to 2.3).  The root is the same from any start, to the
   !> return's tolerance.
   !>  con      [in]  the law's constants
   !>  np       [in]  number of points
   !>  tr0      [in]  (np, 3) the elastic trial (tau11, tau22, tau33) at x = 0
   !>  pp       [in]  (np) the prescribed tau22 at the end
   !>  ep       [in]  (np) the equivalent plastic strain at the start
   !>  syn, hpn [in]  (np) sigma_y and its slope there
   !>  aa       [in]  (np, 2, max_back_stresses) v_k . alpha_i at the start
   !>  dp0      [in]  (np) where the iteration starts, >= 0 (0: at the trial)
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
   pure subroutine mixed_return_block(con, np, tr0, pp, ep, syn, hpn, aa, dp0, dpv, xv, nv, syv, hpv, &
                                      tau, dd, cpl, tng, ok)
      type(combined_constants), intent(in) :: con
      integer, intent(in) :: np
      real(dp), intent(in) :: tr0(np, 3), pp(np), ep(np), syn(np), hpn(np), &
                              aa(np, 2, max_back_stresses), dp0(np)
      real(dp), intent(out) :: dpv(np), xv(np), nv(np, 3), syv(np), hpv(np), tau(np, 2), &
                               dd(np, 2, 2), cpl(np), tng(np)
      logical, intent(out) :: ok
      real(dp) :: t(np, 2), lo(np), hi(np), step(np), epv(np), g(np, 2), dc0(np, 2), xi(np, 2), kap(np), &
                  theta(np), dtheta(np), beta(np), dbeta(np), phi(np), dphi(np), sys(np), hps(np)
      real(dp) :: n_far, n_out, r, den
      integer :: iter, j, k
      ok = .false.
      do k = 1, 2
         do j = 1, np
            t(j, k) = con%eig_vec(1, k)*tr0(j, 1) + con%eig_vec(2, k)*tr0(j, 2) &
                      + con%eig_vec(3, k)*tr0(j, 3)
         end do
      end do
      do j = 1, np
         dpv(j) = dp0(j)
         lo(j) = 0.0_dp
         hi(j) = huge(1.0_dp)
         syv(j) = syn(j)
         hpv(j) = hpn(j)
      end do
      if (any(dpv > 0.0_dp)) then
         do j = 1, np
            epv(j) = ep(j) + dpv(j)
         end do
         call flow_stress_block(np, epv, con%props, size(con%props), sys, hps)
         ! the points that start at the trial keep the cached values (a
         ! scalar and a block evaluation of the law may differ in the last bit)
         do j = 1, np
            syv(j) = merge(sys(j), syn(j), dpv(j) > 0.0_dp)
            hpv(j) = merge(hps(j), hpn(j), dpv(j) > 0.0_dp)
         end do
         if (.not. all(syv > 0.0_dp .and. syv <= huge(1.0_dp))) return
      end if
      do iter = 1, max_return_iter
         call mixed_eval(con, np, t, tr0(:, 2), pp, aa, dpv, syv, hpv, xv, xi, g, dc0, theta, &
                         dtheta, beta, dbeta, phi, dphi)
         ! (finite: |x| <= huge, false for NaN; one vector loop, no calls)
         if (.not. all(abs(phi) <= huge(1.0_dp) .and. abs(dphi) <= huge(1.0_dp))) return
         if (iter == 1) then
            ! sbar's decay rate (mixed_step): with sbar = sbar_0/(1 + kappa
            ! dp/sigma_y) and r = -sbar'/sbar at the start dp,
            ! kappa = r sigma_y/(1 - r dp); none where that fails
            do j = 1, np
               r = -(dphi(j) + hpv(j))/(phi(j) + syv(j))
               den = 1.0_dp - r*dpv(j)
               kap(j) = merge(max(r*syv(j)/max(den, 0.1_dp), 0.0_dp), 0.0_dp, den > 0.1_dp)
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
            call mixed_eval(con, np, t, tr0(:, 2), pp, aa, dpv, syv, hpv, xv, xi, g, dc0, theta, &
                            dtheta, beta, dbeta, phi, dphi)
            ok = all(abs(phi) <= huge(1.0_dp))
            exit
         end if
         do j = 1, np
            dpv(j) = step(j)
            epv(j) = ep(j) + step(j)
         end do
         call flow_stress_block(np, epv, con%props, size(con%props), syv, hpv)
         if (.not. all(syv > 0.0_dp .and. syv <= huge(1.0_dp))) return
      end do
      if (.not. ok) return
      ok = all(dpv > 0.0_dp)
      if (.not. ok) return
      call mixed_results(con, np, tr0, aa, dpv, xv, xi, g, dc0, syv, hpv, dtheta, beta, dbeta, &
                         nv, tau, dd, cpl, tng)
      ok = all(abs(tau) <= huge(1.0_dp)) .and. all(abs(dd) <= huge(1.0_dp)) .and. &
           all(abs(tng) <= huge(1.0_dp))
   end subroutine mixed_return_block

   !> MIXED_EVAL: the state of mixed_return_block's points at given dp
   !> (the closed forms of its header) and phi with its derivative.
   !>  con      [in]  the law's constants
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
   pure subroutine mixed_eval(con, np, t, tr2, pp, aa, dpv, syv, hpv, xv, xi, g, dc0, theta, &
                              dtheta, beta, dbeta, phi, dphi)
      type(combined_constants), intent(in) :: con
      integer, intent(in) :: np
      real(dp), intent(in) :: t(np, 2), tr2(np), pp(np), aa(np, 2, max_back_stresses), dpv(np), &
                              syv(np), hpv(np)
      real(dp), intent(out) :: xv(np), xi(np, 2), g(np, 2), dc0(np, 2), theta(np), dtheta(np), &
                               beta(np), dbeta(np), phi(np), dphi(np)
      real(dp) :: b(np), bd(np), c0(np, 2), a, ci, gi, mu, l2m, l1, l2, e1, e2, d1, d2, g1, g2, &
                  dg1, dg2, s1, s2, ds1, ds2, num, dnum, dnm, ddnm, dx, r1, r2, dxi1, dxi2, q, rs, &
                  u1, u2, rr
      integer :: i, j
      mu = con%mu
      l2m = con%d(1, 1)
      l1 = con%eig_val(1)
      l2 = con%eig_val(2)
      e1 = con%eig_vec(2, 1)
      e2 = con%eig_vec(2, 2)
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
      do i = 1, con%n_back
         ci = (2.0_dp/3.0_dp)*con%c(i)
         gi = con%gamma(i)
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
   !>  con      [in]  the law's constants
   !>  np    [in]  number of points
   !>  tr0, aa, dpv, xv, xi, g, dc0, syv, hpv, dtheta, beta, dbeta [in]
   !>              as mixed_return_block and mixed_eval at the root
   !>  nv, tau, dd, cpl, tng [out] as mixed_return_block
   pure subroutine mixed_results(con, np, tr0, aa, dpv, xv, xi, g, dc0, syv, hpv, dtheta, beta, &
                                 dbeta, nv, tau, dd, cpl, tng)
      type(combined_constants), intent(in) :: con
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
      mu = con%mu
      lam = con%lam
      l2m = con%d(1, 1)
      l1 = con%eig_val(1)
      l2 = con%eig_val(2)
      v = con%eig_vec(:, 1:2)
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
      do i = 1, con%n_back
         ci = (2.0_dp/3.0_dp)*con%c(i)
         gi = con%gamma(i)
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
end module combined_return
