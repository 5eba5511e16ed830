!> material_j2 -- UMAT-like elasto-plastic material for one through-thickness
!> station of a plane-strain sheet (DESIGN §4).
!>
!> Purpose
!>   Stress update at a material point with thickness stress sigma22 = 0
!>   (plane stress through the thickness) and in-plane components
!>   (sigma11, sigma33) = (axial, width).  Kirchhoff stress, logarithmic
!>   strain, additive elasto-plasticity in these measures:
!>     - isotropic plane-stress Hooke law  D = E/(1-nu^2) [[1, nu], [nu, 1]];
!>     - Hill 1948 normal anisotropy (paper appendix (A.3) with the thickness
!>       stress zero):  sbar^2 = s11^2 + s33^2 - (2R/(1+R)) s11 s33,
!>       R = 1 is von Mises;
!>     - associative flow, isotropic hardening sbar = sigma_y(ebar_p), ebar_p
!>       work conjugate to sbar (sigma : d eps_p = sbar d ebar_p);
!>     - hardening: Swift, Voce, or a piecewise-linear table.
!>   Backward-Euler return mapping, consistent (algorithmic) tangent.
!>
!> Conventions
!>   stress(1:2) = (sigma11, sigma33);  strain (eps11, eps33).
!>   statev(1) = ebar_p, statev(2) = eps22 (total thickness log strain),
!>   statev(3) = sigma33 (copy for output), statev(4) = continuum tangent
!>   d sigma11 / d eps11 at fixed eps33 (alpha of (A.1): plastic only if the
!>   increment was plastic), statev(5:6) = sigma_y(ebar_p) and its slope
!>   H', cached so that an elastic call evaluates no hardening law
!>   (statev(5) <= 0: not yet known, computed on entry; the all-zero virgin
!>   state is therefore valid).
!>   props(1:4) = E, nu, R, law id; then the law constants (see umat).
!>
!> Call check_props once at set-up: umat trusts its constants (it is called
!> ~1e6 times per run) and only guards against out-of-bounds access.
module material_j2
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   implicit none
   private

   public :: n_statev, n_props_fixed, law_swift, law_voce, law_table, max_load_strain
   public :: umat, umat_block, flow_stress, hill_equivalent, check_props, read_curve_file

   !> number of state variables umat needs
   integer, parameter :: n_statev = 6
   !> props entries common to every law: E, nu, R, law id
   integer, parameter :: n_props_fixed = 4
   !> hardening law ids (props(4))
   integer, parameter :: law_swift = 1, law_voce = 2, law_table = 3

   !> local Newton: iteration limit and relative tolerance on the yield
   !> residual |sbar - sigma_y| / sigma_y (quadratic convergence reaches it
   !> in a few iterations; the limit only catches a failing solve).
   integer, parameter :: max_newton = 50
   real(dp), parameter :: tol_newton = 1.0e-12_dp
   !> below this relative residual the last Newton step is taken without a
   !> further hardening-law call (return_map): quadratic convergence puts
   !> the next residual near tol_taylor^2 = 1e-14 < tol_newton.
   real(dp), parameter :: tol_taylor = 1.0e-7_dp
   !> a trial state with sbar_trial <= (1 + tol_yield) sigma_y is elastic:
   !> a converged plastic state re-entered with a zero strain increment must
   !> not start a spurious return mapping on round-off.
   real(dp), parameter :: tol_yield = 1.0e-12_dp
   !> increment ratio requested from the caller when the local solve fails
   real(dp), parameter :: pnewdt_cut = 0.5_dp

contains

   !> UMAT: stress update for one increment of log strain.
   !>
   !> Given the start-of-increment stress and state and the log-strain
   !> increment, returns the end-of-increment stress and state and the
   !> consistent tangent.  Elastic predictor; if the trial state lies
   !> outside the Hill yield surface, backward-Euler return mapping
   !>   sigma = sigma_trial - dp D n(sigma),   sbar(sigma) = sigma_y(ep_n + dp),
   !>   n = d sbar / d sigma = P sigma / sbar,  P = [[1, -r], [-r, 1]],
   !>   r = R/(1+R)
   !> (DESIGN §4).  The width strain increment dstran(2) is honoured as
   !> given (the section passes 0: plane strain).  One material point;
   !> the work is done by umat_block with a block of one.
   !>
   !> stress  [in,out] Kirchhoff stress (sigma11, sigma33): start of the
   !>                  increment on entry, end on exit.
   !> statev  [in,out] state variables (size nstatv >= n_statev):
   !>                  (1) ebar_p, (2) eps22 total thickness log strain,
   !>                  (3) sigma33, (4) continuum tangent dsigma11/deps11 at
   !>                  fixed eps33, end state: E/(1-nu^2) for an elastic or
   !>                  unloading increment, elasto-plastic (A.1) with
   !>                  alpha = 1 for a plastic one, (5:6) sigma_y and H' at
   !>                  ebar_p (a cache; 0 = not yet known).
   !> ddsdde  [out]    consistent tangent d sigma_end / d dstran (2x2,
   !>                  symmetric); D for an elastic increment.
   !> sse     [in,out] elastic strain energy density at the end of the
   !>                  increment, (s11^2 + s33^2 - 2 nu s11 s33)/(2E).
   !> spd     [in,out] plastic dissipation density, accumulated:
   !>                  spd = spd + int sigma_y d ep over the increment (exact: W(ep_n + dp) - W(ep_n)
   !>                  with W the integral of the hardening curve).
   !> stran   [in]     total log strain (eps11, eps33) at the start of the
   !>                  increment.  Not needed: the stress is the state of
   !>                  this additive model.  Kept for the UMAT interface.
   !> dstran  [in]     log strain increment (deps11, deps33).
   !> props   [in]     material constants (size nprops):
   !>                  (1) E, (2) nu, (3) R, (4) law id, then
   !>                  Swift (law_swift): (5:7) = K, eps0, n,
   !>                     sigma_y = K (eps0 + ebar_p)^n;
   !>                  Voce (law_voce): (5:7) = sigma0, Q, b,
   !>                     sigma_y = sigma0 + Q (1 - exp(-b ebar_p));
   !>                  table (law_table): (5) = m, (6:5+2m) = ebar_p_1,
   !>                     sigma_1, ..., ebar_p_m, sigma_m (ebar_p_1 = 0),
   !>                     linear extrapolation of the last segment.
   !> nprops  [in]     size of props.
   !> nstatv  [in]     size of statev.
   !> pnewdt  [in,out] untouched on success.  If the local Newton fails
   !>                  (no convergence, non-positive flow stress, non-finite
   !>                  value): pnewdt = min(pnewdt, 0.5), and stress,
   !>                  statev, sse, spd are returned unchanged (ddsdde = D).
   !>                  If nprops or nstatv is too small for the law (a
   !>                  programming error; check_props catches it):
   !>                  pnewdt = min(pnewdt, 0), nothing changed, ddsdde = 0.
   pure subroutine umat(stress, statev, ddsdde, sse, spd, stran, dstran, props, nprops, &
                        nstatv, pnewdt)
      integer, intent(in) :: nprops, nstatv
      real(dp), intent(inout) :: stress(2)
      real(dp), intent(inout) :: statev(nstatv)
      real(dp), intent(out) :: ddsdde(2, 2)
      real(dp), intent(inout) :: sse
      real(dp), intent(inout) :: spd
      real(dp), intent(in) :: stran(2)
      real(dp), intent(in) :: dstran(2)
      real(dp), intent(in) :: props(nprops)
      real(dp), intent(inout) :: pnewdt

      real(dp) :: b_stress(1, 2), b_statev(1, nstatv), b_ddsdde(1, 2, 2), b_sse(1), b_spd(1)
      real(dp) :: b_dstran(1, 2)

      ! stran is not needed (see header); the associate marks it as read.
      associate (unused => stran)
      end associate

      b_stress(1, :) = stress
      b_statev(1, :) = statev
      b_sse(1) = sse
      b_spd(1) = spd
      b_dstran(1, :) = dstran
      call umat_block(1, b_stress, b_statev, b_ddsdde, b_sse, b_spd, b_dstran, props, nprops, &
                      nstatv, pnewdt)
      stress = b_stress(1, :)
      statev = b_statev(1, :)
      ddsdde = b_ddsdde(1, :, :)
      sse = b_sse(1)
      spd = b_spd(1)
   end subroutine umat

   !> UMAT_BLOCK: the stress update of umat for a block of material points
   !> at once, the block index first (the layout of Abaqus/Explicit's VUMAT).
   !>
   !> The points of a block are independent, so every step is a loop over
   !> the block that the compiler can vectorize (libmvec's pow, log, exp):
   !> the elastic predictor of all points, then the return mapping of the
   !> points that yield, packed together (return_map_block), then the end
   !> states.  Point k gets what umat would give it alone, to the local
   !> tolerance: the block iterates until its slowest point has converged,
   !> so a point may take a full step where alone it would have taken the
   !> Taylor finish (differences of order 1e-12 in the stress, 1e-8 in H'
   !> and the tangents that carry it).
   !>
   !> nblock  [in]     number of material points, >= 1.
   !> stress  [in,out] (nblock, 2) Kirchhoff stress (sigma11, sigma33) per
   !>                  point, start of the increment on entry, end on exit.
   !> statev  [in,out] (nblock, nstatv) state variables per point (see umat).
   !> ddsdde  [out]    (nblock, 2, 2) consistent tangent per point.
   !> sse     [in,out] (nblock) elastic strain energy density (see umat).
   !> spd     [in,out] (nblock) plastic dissipation density (see umat).
   !> dstran  [in]     (nblock, 2) log strain increment (deps11, deps33).
   !> props   [in]     material constants, shared by the block (see umat).
   !> nprops  [in]     size of props.
   !> nstatv  [in]     second extent of statev.
   !> pnewdt  [in,out] as for umat; if the return mapping fails at any point,
   !>                  pnewdt = min(pnewdt, 0.5) and stress, statev, sse, spd
   !>                  of the whole block are returned unchanged (ddsdde = D).
   pure subroutine umat_block(nblock, stress, statev, ddsdde, sse, spd, dstran, props, &
                              nprops, nstatv, pnewdt)
      integer, intent(in) :: nblock, nprops, nstatv
      real(dp), intent(inout) :: stress(nblock, 2)
      real(dp), intent(inout) :: statev(nblock, nstatv)
      real(dp), intent(out) :: ddsdde(nblock, 2, 2)
      real(dp), intent(inout) :: sse(nblock)
      real(dp), intent(inout) :: spd(nblock)
      real(dp), intent(in) :: dstran(nblock, 2)
      real(dp), intent(in) :: props(nprops)
      real(dp), intent(inout) :: pnewdt

      real(dp) :: e_mod, nu, r_value, r, e_ps, d12, hill_a, hill_b
      real(dp), dimension(nblock) :: sig_tr1, sig_tr2, sy_n, h_n, seq_tr
      ! packed plastic points (index j; idx(j) is the point of the block)
      integer :: idx(nblock), np, j, k
      real(dp), dimension(nblock) :: s_tr, t_tr, ep_n, sy_p, h_p, seq_p, q_s, q_t, seq, &
                                     dp_inc, sy_end, h_end, sig1, sig2, c11, c12, c22, ct11, &
                                     eps22, sse_p, spd_p, sig_n1, sig_n2
      real(dp) :: f1, f2, a11, a12, a22, det, x11, x12, x22, xn1, xn2, den, dsig1, dsig2
      logical :: ok

      if (.not. sizes_ok(props, nprops, nstatv)) then
         ddsdde = 0.0_dp
         pnewdt = min(pnewdt, 0.0_dp)
         return
      end if

      e_mod = props(1)
      nu = props(2)
      r_value = props(3)
      r = r_value/(1.0_dp + r_value)
      e_ps = e_mod/(1.0_dp - nu**2)
      d12 = e_ps*nu
      ! sbar^2 = (hill_a (s11 + s33)^2 + hill_b (s11 - s33)^2), see hill_equivalent
      hill_a = 1.0_dp/(2.0_dp*(1.0_dp + r_value))
      hill_b = (1.0_dp + 2.0_dp*r_value)*hill_a

      ! D at every point: the tangent of an elastic point, and of the whole
      ! block if it fails (the plastic points are overwritten at the end)
      ddsdde(:, 1, 1) = e_ps
      ddsdde(:, 2, 1) = d12
      ddsdde(:, 1, 2) = d12
      ddsdde(:, 2, 2) = e_ps

      ! Elastic predictor; the flow stress comes from the cache statev(5:6),
      ! which a virgin point (statev(5) <= 0) has not filled yet.
      do k = 1, nblock
         sig_tr1(k) = stress(k, 1) + e_ps*dstran(k, 1) + d12*dstran(k, 2)
         sig_tr2(k) = stress(k, 2) + d12*dstran(k, 1) + e_ps*dstran(k, 2)
         seq_tr(k) = sqrt(hill_a*(sig_tr1(k) + sig_tr2(k))**2 + hill_b*(sig_tr1(k) - sig_tr2(k))**2)
         sy_n(k) = statev(k, 5)
         h_n(k) = statev(k, 6)
      end do
      do k = 1, nblock
         if (.not. sy_n(k) > 0.0_dp) call flow_stress(statev(k, 1), props, nprops, sy_n(k), h_n(k))
      end do

      ! Points whose trial state lies outside the yield surface.  A trial
      ! state with sbar_trial <= (1 + tol_yield) sigma_y is elastic (also
      ! elastic unloading); a NaN is not, so that the checks below fail it.
      np = 0
      do k = 1, nblock
         if (.not. seq_tr(k) <= (1.0_dp + tol_yield)*sy_n(k)) then
            np = np + 1
            idx(np) = k
         end if
      end do
      ok = .true.
      do j = 1, np
         k = idx(j)
         s_tr(j) = sig_tr1(k) + sig_tr2(k)
         t_tr(j) = sig_tr1(k) - sig_tr2(k)
         ep_n(j) = statev(k, 1)
         sig_n1(j) = stress(k, 1)
         sig_n2(j) = stress(k, 2)
         eps22(j) = statev(k, 2)
         spd_p(j) = spd(k)
         sy_p(j) = sy_n(k)
         h_p(j) = h_n(k)
         seq_p(j) = seq_tr(k)
         ok = ok .and. sy_n(k) > 0.0_dp .and. ieee_is_finite(sig_tr1(k)) .and. &
              ieee_is_finite(sig_tr2(k))
      end do
      if (ok .and. np > 0) call return_map_block(np, s_tr, t_tr, ep_n, sy_p, h_p, seq_p, props, &
                                                 nprops, q_s, q_t, seq, dp_inc, sy_end, h_end, ok)
      if (ok) then
         do j = 1, np
            sig1(j) = 0.5_dp*(s_tr(j)*q_s(j) + t_tr(j)*q_t(j))
            sig2(j) = 0.5_dp*(s_tr(j)*q_s(j) - t_tr(j)*q_t(j))
            ok = ok .and. ieee_is_finite(sig1(j)) .and. ieee_is_finite(sig2(j)) .and. &
                 dp_inc(j) > 0.0_dp
         end do
      end if
      if (.not. ok) then
         pnewdt = min(pnewdt, pnewdt_cut)
         return
      end if

      ! End states of the plastic points, packed.
      do j = 1, np
         ! flow direction n = P sigma / sbar (hill_normal)
         f1 = (sig1(j) - r*sig2(j))/seq(j)
         f2 = (sig2(j) - r*sig1(j))/seq(j)
         ! Consistent (algorithmic) tangent.  Linearising the converged
         ! local system in strain form,
         !   C (sigma - sigma_tr) + dp n(sigma) = 0,  n . d sigma = H' d dp,
         ! with C = D^-1 and d n / d sigma = (P - n n^T)/sbar, gives
         !   d sigma = Xi (d deps - d dp n),  Xi = (C + dp (P - n n^T)/sbar)^-1,
         !   d sigma / d deps = Xi - (Xi n)(Xi n)^T / (n^T Xi n + H'),
         ! the Schur complement of the local Jacobian; symmetric, and equal
         ! to the continuum tangent (A.1) when dp -> 0.  A = Xi^-1 is
         ! symmetric positive definite (C is, and P - n n^T is the Hessian
         ! of the convex sbar), so the explicit 2x2 inverse is safe.
         a11 = 1.0_dp/e_mod + dp_inc(j)*(1.0_dp - f1**2)/seq(j)
         a22 = 1.0_dp/e_mod + dp_inc(j)*(1.0_dp - f2**2)/seq(j)
         a12 = -nu/e_mod + dp_inc(j)*(-r - f1*f2)/seq(j)
         det = a11*a22 - a12*a12
         x11 = a22/det
         x22 = a11/det
         x12 = -a12/det
         xn1 = x11*f1 + x12*f2
         xn2 = x12*f1 + x22*f2
         den = f1*xn1 + f2*xn2 + h_end(j)
         c11(j) = x11 - xn1*xn1/den
         c12(j) = x12 - xn1*xn2/den
         c22(j) = x22 - xn2*xn2/den
         ! Continuum tangent (A.1) with alpha = 1, (1,1) entry (eps33 fixed):
         ! D - (D n)(D n)^T / (n^T D n + H').
         xn1 = e_ps*f1 + d12*f2
         xn2 = d12*f1 + e_ps*f2
         ct11(j) = e_ps - xn1**2/(f1*xn1 + f2*xn2 + h_end(j))
         ! Thickness strain, DESIGN §4: elastic part from sigma22 = 0, plastic
         ! part from plastic incompressibility of (A.3):
         ! d eps22 = -(nu/E)(d s11 + d s33) - d eps11p - d eps33p.
         dsig1 = sig1(j) - sig_n1(j)
         dsig2 = sig2(j) - sig_n2(j)
         eps22(j) = eps22(j) - nu/e_mod*(dsig1 + dsig2) - dp_inc(j)*(f1 + f2)
         sse_p(j) = elastic_energy(sig1(j), sig2(j), e_mod, nu)
      end do
      ! Dissipation: on the yield surface sigma : d eps_p = sbar d ep =
      ! sigma_y(ep) d ep, so the increment dissipates W(ep_n + dp) - W(ep_n),
      ! W the integral of the hardening curve, exact for any increment size.
      do j = 1, np
         spd_p(j) = spd_p(j) + plastic_work(ep_n(j) + dp_inc(j), sy_end(j), props, nprops) &
                    - plastic_work(ep_n(j), sy_p(j), props, nprops)
      end do

      ! Every point as if elastic (the plastic ones are overwritten below).
      ! Thickness strain: plane stress sigma22 = 0 gives
      ! d eps22 = -(nu/E)(d s11 + d s33) (DESIGN §4, no plastic part).
      do k = 1, nblock
         statev(k, 2) = statev(k, 2) - nu/e_mod*(sig_tr1(k) - stress(k, 1) + sig_tr2(k) - stress(k, 2))
         stress(k, 1) = sig_tr1(k)
         stress(k, 2) = sig_tr2(k)
         statev(k, 3) = sig_tr2(k)
         statev(k, 4) = e_ps
         statev(k, 5) = sy_n(k)
         statev(k, 6) = h_n(k)
         sse(k) = elastic_energy(sig_tr1(k), sig_tr2(k), e_mod, nu)
      end do
      do j = 1, np
         k = idx(j)
         stress(k, 1) = sig1(j)
         stress(k, 2) = sig2(j)
         statev(k, 1) = ep_n(j) + dp_inc(j)
         statev(k, 2) = eps22(j)
         statev(k, 3) = sig2(j)
         statev(k, 4) = ct11(j)
         statev(k, 5) = sy_end(j)
         statev(k, 6) = h_end(j)
         sse(k) = sse_p(j)
         spd(k) = spd_p(j)
         ddsdde(k, 1, 1) = c11(j)
         ddsdde(k, 2, 1) = c12(j)
         ddsdde(k, 1, 2) = c12(j)
         ddsdde(k, 2, 2) = c22(j)
      end do
   end subroutine umat_block

   !> Backward-Euler return mapping onto the Hill yield surface, for n
   !> points at once.
   !>
   !> D and P are both of the form a I + b [[0,1],[1,0]], so they share the
   !> eigenvectors (1,1) and (1,-1).  With s = s11 + s33, t = s11 - s33 and
   !> gamma = dp / sbar, sigma = sigma_trial - gamma D P sigma decouples:
   !>   s = s_tr / (1 + gamma k_s),  k_s = E (1 - r)/(1 - nu),
   !>   t = t_tr / (1 + gamma k_t),  k_t = E (1 + r)/(1 + nu),
   !>   sbar^2 = ((1 - r) s^2 + (1 + r) t^2) / 2,
   !> which solves the stress rows of the local system
   !> [sigma - sigma_tr + dp D n; sbar - sigma_y(ep_n + dp)] = 0 exactly and
   !> leaves the scalar equation g(gamma) = sbar(gamma) - sigma_y(ep_n +
   !> gamma sbar(gamma)) = 0 per point.  g is strictly decreasing for a
   !> non-softening curve, g(0) > 0, and g(gamma_hi) <= 0 at
   !> gamma_hi = (sbar_tr/sigma_y(ep_n) - 1)/min(k_s, k_t), so a Newton
   !> iteration safeguarded by bisection in [0, gamma_hi] always converges,
   !> quadratically once in the smooth part of the curve.
   !>
   !> Every point takes a Newton step in every pass (a converged point stays
   !> where it is), so each pass is one vector loop and one vector call of
   !> the hardening law.  The passes end when every point has
   !> |g| <= tol_newton sigma_y; or, once every point not yet there has
   !> |g| <= tol_taylor sigma_y and a Newton step inside its bracket, with
   !> that step and sigma_y carried to it by Taylor's formula (quadratic
   !> convergence leaves a residual near (tol_taylor)^2 sigma_y, below
   !> tol_newton sigma_y), which needs no further law call.
   !>
   !> n      [in]  number of points.
   !> s_tr, t_tr [in] (n) s and t of the trial stress.
   !> ep_n   [in]  (n) equivalent plastic strain at the start of the increment.
   !> sy_n   [in]  (n) sigma_y(ep_n) > 0.
   !> h_n    [in]  (n) d sigma_y / d ebar_p at ep_n (with sy_n: the first
   !>              iterate, gamma = 0, needs no hardening-law call).
   !> seq_tr [in]  (n) sbar of the trial stress, > sy_n.
   !> props  [in]  material constants (see umat).
   !> nprops [in]  size of props.
   !> q_s, q_t [out] (n) 1/(1 + gamma k_s), 1/(1 + gamma k_t) at the solution:
   !>              the end stress is s = s_tr q_s, t = t_tr q_t.
   !> seq    [out] (n) sbar of the end stress (= sy_end to the local tolerance).
   !> dp_inc [out] (n) equivalent plastic strain increment dp > 0.
   !> sy_end [out] (n) sigma_y(ep_n + dp).
   !> h_end  [out] (n) hardening modulus d sigma_y / d ebar_p at ep_n + dp.
   !> ok     [out] .false. if a point did not converge or a non-finite /
   !>              non-positive value appeared; the outputs are then undefined.
   pure subroutine return_map_block(n, s_tr, t_tr, ep_n, sy_n, h_n, seq_tr, props, nprops, &
                                    q_s, q_t, seq, dp_inc, sy_end, h_end, ok)
      integer, intent(in) :: n, nprops
      real(dp), intent(in) :: s_tr(n), t_tr(n), ep_n(n), sy_n(n), h_n(n), seq_tr(n)
      real(dp), intent(in) :: props(nprops)
      real(dp), intent(out) :: q_s(n), q_t(n), seq(n), dp_inc(n), sy_end(n), h_end(n)
      logical, intent(out) :: ok

      real(dp) :: e_mod, nu, r, k_s, k_t, n_far, n_out, n_bad
      real(dp), dimension(n) :: a_s, a_t, k_eff, gam, gam_lo, gam_hi, g, ep
      integer :: iter, j

      e_mod = props(1)
      nu = props(2)
      r = props(3)/(1.0_dp + props(3))
      k_s = e_mod*(1.0_dp - r)/(1.0_dp - nu)
      k_t = e_mod*(1.0_dp + r)/(1.0_dp + nu)
      do j = 1, n
         a_s(j) = (1.0_dp - r)*s_tr(j)**2
         a_t(j) = (1.0_dp + r)*t_tr(j)**2
         ! Effective decay rate of sbar at gamma = 0: sbar'(0) = -k_eff sbar_tr.
         k_eff(j) = (a_s(j)*k_s + a_t(j)*k_t)/(a_s(j) + a_t(j))
         gam_lo(j) = 0.0_dp
         gam_hi(j) = (seq_tr(j)/sy_n(j) - 1.0_dp)/min(k_s, k_t)
         gam(j) = 0.0_dp
         q_s(j) = 1.0_dp
         q_t(j) = 1.0_dp
         seq(j) = seq_tr(j)
         dp_inc(j) = 0.0_dp
         sy_end(j) = sy_n(j)
         h_end(j) = h_n(j)
         g(j) = seq_tr(j) - sy_n(j)
      end do
      ok = .false.
      do iter = 1, max_newton
         ! n_far: number of points not yet at |g| <= tol_newton sigma_y;
         ! n_out: of points too far for the Taylor finish (|g| > tol_taylor
         ! sigma_y, or a bisection step)
         call newton_step_block(n, a_s, a_t, k_s, k_t, k_eff, q_s, q_t, seq, h_end, sy_end, g, &
                                gam, gam_lo, gam_hi, n_far, n_out)
         if (n_far < 0.5_dp) then
            ok = .true.
            exit
         end if
         do j = 1, n
            q_s(j) = 1.0_dp/(1.0_dp + gam(j)*k_s)
            q_t(j) = 1.0_dp/(1.0_dp + gam(j)*k_t)
            seq(j) = sqrt(0.5_dp*(a_s(j)*q_s(j)**2 + a_t(j)*q_t(j)**2))
         end do
         if (n_out < 0.5_dp) then
            ! sigma_y carried to the new point by Taylor's formula (error
            ! H'' d^2/2 with d < 1e-7 sigma_y/H': some 1e-20 relative; H' is
            ! that of a point within d of ep_n + dp)
            do j = 1, n
               sy_end(j) = sy_end(j) + h_end(j)*(gam(j)*seq(j) - dp_inc(j))
               dp_inc(j) = gam(j)*seq(j)
            end do
            ok = .true.
            exit
         end if
         do j = 1, n
            dp_inc(j) = gam(j)*seq(j)
            ep(j) = ep_n(j) + dp_inc(j)
         end do
         call flow_stress_block(n, ep, props, nprops, sy_end, h_end)
         n_bad = 0.0_dp
         do j = 1, n
            g(j) = seq(j) - sy_end(j)
            n_bad = n_bad + merge(0.0_dp, 1.0_dp, sy_end(j) > 0.0_dp .and. abs(g(j)) <= huge(1.0_dp))
         end do
         if (n_bad > 0.5_dp) return
      end do
   end subroutine return_map_block

   !> One safeguarded Newton step of return_map_block at every point (see
   !> there): the bracket [gam_lo, gam_hi] is narrowed by the sign of g, then
   !> gamma takes the Newton step on F = g (1 + gamma k_eff), or bisects
   !> where that step leaves the bracket; a point with |g| <= tol_newton
   !> sigma_y stays where it is.
   !>
   !> n              [in]  number of points.
   !> a_s, a_t       [in]  (n) (1 - r) s_tr^2 and (1 + r) t_tr^2.
   !> k_s, k_t       [in]  decay rates of s and t with gamma.
   !> k_eff          [in]  (n) effective decay rate of sbar at gamma = 0.
   !> q_s, q_t, seq  [in]  (n) 1/(1 + gamma k_s), 1/(1 + gamma k_t) and sbar at gamma.
   !> h_end, sy_end  [in]  (n) H' and sigma_y at ep_n + gamma sbar.
   !> g              [in]  (n) sbar - sigma_y at gamma.
   !> gam            [in,out] (n) gamma: the current iterate in, the next out.
   !> gam_lo, gam_hi [in,out] (n) the bracket of the root.
   !> n_far          [out] number of points not yet at |g| <= tol_newton sigma_y.
   !> n_out          [out] number of points too far for the Taylor finish
   !>                      (|g| > tol_taylor sigma_y, or a bisection step).
   !> Written for gfortran's vectorizer (with -fno-trapping-math): counts as
   !> reals, every array read once into a scalar, and the choice between
   !> keeping gamma and stepping as an exact 0/1 blend, not a merge.
   pure subroutine newton_step_block(n, a_s, a_t, k_s, k_t, k_eff, q_s, q_t, seq, h_end, sy_end, &
                                     g, gam, gam_lo, gam_hi, n_far, n_out)
      integer, intent(in) :: n
      real(dp), intent(in) :: a_s(n), a_t(n), k_s, k_t, k_eff(n), q_s(n), q_t(n), seq(n), h_end(n)
      real(dp), intent(in) :: sy_end(n), g(n)
      real(dp), intent(inout) :: gam(n), gam_lo(n), gam_hi(n)
      real(dp), intent(out) :: n_far, n_out

      real(dp) :: dseq, dg, step, gj, lo, hi, far, near
      integer :: j
      logical :: inside

      n_far = 0.0_dp
      n_out = 0.0_dp
      do j = 1, n
         ! far = 0 (keep gamma) or 1 (step); the blend below is exact
         far = merge(0.0_dp, 1.0_dp, abs(g(j)) <= tol_newton*sy_end(j))
         gj = gam(j)
         lo = gam_lo(j)
         hi = gam_hi(j)
         lo = merge(gj, lo, g(j) > 0.0_dp)
         hi = merge(hi, gj, g(j) > 0.0_dp)
         gam_lo(j) = lo
         gam_hi(j) = hi
         ! g'(gamma) = sbar' - H' (sbar + gamma sbar'),  sbar' < 0.
         dseq = -0.5_dp*(a_s(j)*k_s*q_s(j)**3 + a_t(j)*k_t*q_t(j)**3)/seq(j)
         dg = dseq - h_end(j)*(seq(j) + gj*dseq)
         ! Newton on F = g (1 + gamma k_eff), same root and sign as g:
         ! sbar ~ sbar_tr/(1 + gamma k_eff) makes g strongly convex (plain
         ! Newton from gamma = 0 only halves the error per iteration for
         ! large steps), while F is nearly linear (exactly so for a
         ! perfectly plastic material when k_s = k_t).
         ! F'/(1 + gamma k_eff) = g' + g k_eff/(1 + gamma k_eff).
         dg = dg + g(j)*k_eff(j)/(1.0_dp + gj*k_eff(j))
         step = gj - g(j)/merge(dg, -1.0_dp, dg < 0.0_dp)
         ! Bisection if the Newton step leaves the bracket (kinks of a
         ! tabulated curve).  (merge, not if: one vector loop.)
         inside = dg < 0.0_dp .and. (step > lo) .and. (step < hi)
         step = merge(step, 0.5_dp*(lo + hi), inside)
         gam(j) = gj*(1.0_dp - far) + step*far
         ! near = 1: a Newton step from |g| <= tol_taylor sigma_y
         near = merge(1.0_dp, 0.0_dp, inside)*merge(1.0_dp, 0.0_dp, abs(g(j)) <= tol_taylor*sy_end(j))
         n_far = n_far + far
         n_out = n_out + far*(1.0_dp - near)
      end do
   end subroutine newton_step_block

   !> Flow stress and hardening modulus at n points (flow_stress, one loop
   !> per law so that the compiler vectorizes the Swift and Voce laws).
   !>
   !> n       [in]  number of points.
   !> ep      [in]  (n) equivalent plastic strains (>= 0).
   !> props   [in]  material constants (see umat).
   !> nprops  [in]  size of props.
   !> sigma_y [out] (n) flow stress (0 where flow_stress gives 0).
   !> hardening_modulus [out] (n) d sigma_y / d ebar_p.
   pure subroutine flow_stress_block(n, ep, props, nprops, sigma_y, hardening_modulus)
      integer, intent(in) :: n, nprops
      real(dp), intent(in) :: ep(n)
      real(dp), intent(in) :: props(nprops)
      real(dp), intent(out) :: sigma_y(n), hardening_modulus(n)

      real(dp) :: base, ex
      integer :: j

      if (nprops < n_props_fixed + 3) then
         sigma_y = 0.0_dp
         hardening_modulus = 0.0_dp
         return
      end if
      select case (int(props(4)))
      case (law_swift)
         ! sigma_y = K (eps0 + ep)^n; 0 (a failure for umat) where
         ! eps0 + ep <= 0, as in flow_stress
         do j = 1, n
            base = max(props(6) + ep(j), tiny(1.0_dp))
            sigma_y(j) = props(5)*base**props(7)
            sigma_y(j) = merge(sigma_y(j), 0.0_dp, props(6) + ep(j) > 0.0_dp)
            hardening_modulus(j) = props(7)*sigma_y(j)/base
         end do
      case (law_voce)
         ! sigma_y = sigma0 + Q (1 - exp(-b ep))
         do j = 1, n
            ex = exp(-props(7)*ep(j))
            sigma_y(j) = props(5) + props(6)*(1.0_dp - ex)
            hardening_modulus(j) = props(6)*props(7)*ex
         end do
      case default
         do j = 1, n
            call flow_stress(ep(j), props, nprops, sigma_y(j), hardening_modulus(j))
         end do
      end select
   end subroutine flow_stress_block

   !> Flow stress and hardening modulus of the uniaxial true stress -
   !> natural strain curve, sigma_y(ebar_p) and d sigma_y / d ebar_p.
   !>
   !> ep                [in]  equivalent plastic strain ebar_p (>= 0).
   !> props             [in]  material constants (see umat); props(4) is the
   !>                         law id, law constants from props(5).
   !> nprops            [in]  size of props.
   !> sigma_y           [out] flow stress.  0 if the law id is unknown, props
   !>                         is too short, or (Swift) eps0 + ep <= 0: umat
   !>                         treats a non-positive flow stress as a failure.
   !> hardening_modulus [out] d sigma_y / d ebar_p (right derivative at a
   !>                         table point; last segment's slope beyond it).
   pure subroutine flow_stress(ep, props, nprops, sigma_y, hardening_modulus)
      integer, intent(in) :: nprops
      real(dp), intent(in) :: ep
      real(dp), intent(in) :: props(nprops)
      real(dp), intent(out) :: sigma_y, hardening_modulus

      real(dp) :: base, ex, slope
      integer :: m, lo, hi, mid, i

      sigma_y = 0.0_dp
      hardening_modulus = 0.0_dp
      if (nprops < n_props_fixed + 1) return

      select case (int(props(4)))
      case (law_swift)
         if (nprops < n_props_fixed + 3) return
         ! sigma_y = K (eps0 + ep)^n
         base = props(6) + ep
         if (base <= 0.0_dp) return
         sigma_y = props(5)*base**props(7)
         hardening_modulus = props(7)*sigma_y/base
      case (law_voce)
         if (nprops < n_props_fixed + 3) return
         ! sigma_y = sigma0 + Q (1 - exp(-b ep))
         ex = exp(-props(7)*ep)
         sigma_y = props(5) + props(6)*(1.0_dp - ex)
         hardening_modulus = props(6)*props(7)*ex
      case (law_table)
         m = nint(props(5))
         if (m < 2 .or. nprops < n_props_fixed + 1 + 2*m) return
         ! Points (ebar_p_i, sigma_i) are props(4+2i), props(5+2i).
         ! Binary search for the segment [i, i+1] holding ep; ep below the
         ! first or beyond the last point uses the first / last segment.
         lo = 1
         hi = m
         do while (hi - lo > 1)
            mid = (lo + hi)/2
            if (ep >= props(4 + 2*mid)) then
               lo = mid
            else
               hi = mid
            end if
         end do
         i = lo
         slope = (props(7 + 2*i) - props(5 + 2*i))/(props(6 + 2*i) - props(4 + 2*i))
         sigma_y = props(5 + 2*i) + slope*(ep - props(4 + 2*i))
         hardening_modulus = slope
      case default
         return
      end select
   end subroutine flow_stress

   !> Plastic work per unit volume W(ebar_p) = int_0^ebar_p sigma_y de, up
   !> to a constant of the law (only differences are used): the dissipation
   !> of a plastic increment is W(ep_n + dp) - W(ep_n) (exact, because on the
   !> yield surface sigma : d eps_p = sigma_y(ebar_p) d ebar_p).
   !>   Swift: W = sigma_y (eps0 + ep)/(n + 1)   [+ const]
   !>   Voce:  W = (sigma0 + Q) ep - (sigma_y - sigma0)/b  (W = sigma0 ep if b = 0)
   !>   table: the trapezoids of the segments up to ep (last one extrapolated).
   !>
   !> ep      [in] equivalent plastic strain.
   !> sigma_y [in] flow stress at ep (from flow_stress; saves a law call).
   !> props   [in] material constants (see umat).
   !> nprops  [in] size of props.
   pure function plastic_work(ep, sigma_y, props, nprops) result(w)
      integer, intent(in) :: nprops
      real(dp), intent(in) :: ep, sigma_y
      real(dp), intent(in) :: props(nprops)
      real(dp) :: w

      integer :: m, i

      w = 0.0_dp
      select case (int(props(4)))
      case (law_swift)
         w = sigma_y*(props(6) + ep)/(props(7) + 1.0_dp)
      case (law_voce)
         if (props(7) > 0.0_dp) then
            w = (props(5) + props(6))*ep - (sigma_y - props(5))/props(7)
         else
            w = props(5)*ep
         end if
      case (law_table)
         ! Point i is (props(4+2i), props(5+2i)); full segments below ep,
         ! then the part of the segment holding ep (ending at sigma_y).
         m = int(props(5))
         do i = 1, m - 1
            if (i == m - 1 .or. ep < props(6 + 2*i)) exit
            w = w + 0.5_dp*(props(5 + 2*i) + props(7 + 2*i))*(props(6 + 2*i) - props(4 + 2*i))
         end do
         w = w + 0.5_dp*(props(5 + 2*i) + sigma_y)*(ep - props(4 + 2*i))
      end select
   end function plastic_work

   !> Hill 1948 equivalent stress for normal anisotropy with zero thickness
   !> stress, paper appendix (A.3) with sigma<22> = 0:
   !>   sbar^2 = s11^2 + s33^2 - (2R/(1+R)) s11 s33.
   !> Evaluated as sbar^2 = ((s11 + s33)^2 + (1 + 2R)(s11 - s33)^2)/(2(1 + R)),
   !> a sum of non-negative terms, so it never takes the root of a negative
   !> round-off value.
   !>
   !> stress  [in] (sigma11, sigma33).
   !> r_value [in] Lankford coefficient R > 0 (R = 1: von Mises).
   !> Returns sbar >= 0.
   pure function hill_equivalent(stress, r_value) result(seq)
      real(dp), intent(in) :: stress(2)
      real(dp), intent(in) :: r_value
      real(dp) :: seq

      seq = sqrt(((stress(1) + stress(2))**2 + (1.0_dp + 2.0_dp*r_value)*(stress(1) - stress(2))**2) &
                 /(2.0_dp*(1.0_dp + r_value)))
   end function hill_equivalent

   !> Elastic strain energy density of a plane-stress state,
   !> (1/2) sigma . C sigma = (s11^2 + s33^2 - 2 nu s11 s33)/(2E).
   !>
   !> s11, s33 [in] stress components sigma11, sigma33.
   !> e_mod    [in] Young's modulus E.
   !> nu       [in] Poisson's ratio.
   pure function elastic_energy(s11, s33, e_mod, nu) result(w)
      real(dp), intent(in) :: s11, s33, e_mod, nu
      real(dp) :: w

      w = (s11**2 + s33**2 - 2.0_dp*nu*s11*s33)/(2.0_dp*e_mod)
   end function elastic_energy

   !> .true. if props and statev are long enough for umat (no value checks:
   !> that is check_props's job, done once at set-up).
   !>
   !> props  [in] material constants.
   !> nprops [in] size of props.
   !> nstatv [in] size of statev.
   pure function sizes_ok(props, nprops, nstatv) result(ok)
      integer, intent(in) :: nprops, nstatv
      real(dp), intent(in) :: props(nprops)
      logical :: ok

      ok = .false.
      if (nstatv < n_statev .or. nprops < n_props_fixed) return
      if (.not. abs(props(4)) < 1.0e6_dp) return
      select case (int(props(4)))
      case (law_swift, law_voce)
         ok = nprops >= n_props_fixed + 3
      case (law_table)
         if (nprops < n_props_fixed + 1) return
         if (.not. abs(props(5)) < 1.0e6_dp) return
         ok = int(props(5)) >= 2 .and. nprops >= n_props_fixed + 1 + 2*int(props(5))
      case default
         ok = .false.
      end select
   end function sizes_ok

   !> Validate the material constants for umat.
   !>
   !> props  [in] material constants (see umat).
   !> nprops [in] size of props.
   !> Returns '' if valid, otherwise a message naming the first bad entry,
   !> e.g. "props(2) = nu = 5.000E-01: must satisfy -1 < nu < 0.5".
   pure function check_props(props, nprops) result(msg)
      integer, intent(in) :: nprops
      real(dp), intent(in) :: props(nprops)
      character(len=:), allocatable :: msg

      integer :: law, m, i, need

      msg = ''
      if (nprops < n_props_fixed) then
         msg = 'need at least ' // itoa(n_props_fixed) // ' props (E, nu, R, law id), got ' &
               // itoa(nprops)
         return
      end if
      if (.not. all(ieee_is_finite(props))) then
         do i = 1, nprops
            if (.not. ieee_is_finite(props(i))) exit
         end do
         msg = 'props(' // itoa(i) // ') is not a finite number'
         return
      end if
      if (.not. props(1) > 0.0_dp) then
         msg = 'props(1) = E = ' // rtoa(props(1)) // ': must be > 0'
      else if (.not. (props(2) > -1.0_dp .and. props(2) < 0.5_dp)) then
         msg = 'props(2) = nu = ' // rtoa(props(2)) // ': must satisfy -1 < nu < 0.5'
      else if (.not. props(3) > 0.0_dp) then
         msg = 'props(3) = R = ' // rtoa(props(3)) // ': must be > 0'
      else if (.not. is_integer(props(4), 1, 3)) then
         msg = 'props(4) = law id = ' // rtoa(props(4)) // ': must be ' // itoa(law_swift) &
               // ' (Swift), ' // itoa(law_voce) // ' (Voce) or ' // itoa(law_table) // ' (table)'
      end if
      if (len(msg) > 0) return

      law = nint(props(4))
      select case (law)
      case (law_swift)
         if (nprops < n_props_fixed + 3) then
            msg = 'Swift law needs props(5:7) = K, eps0, n; got nprops = ' // itoa(nprops)
         else if (.not. props(5) > 0.0_dp) then
            msg = 'props(5) = Swift K = ' // rtoa(props(5)) // ': must be > 0'
         else if (.not. props(6) > 0.0_dp) then
            msg = 'props(6) = Swift eps0 = ' // rtoa(props(6)) // ': must be > 0'
         else if (.not. props(7) >= 0.0_dp) then
            msg = 'props(7) = Swift n = ' // rtoa(props(7)) // ': must be >= 0'
         end if
      case (law_voce)
         if (nprops < n_props_fixed + 3) then
            msg = 'Voce law needs props(5:7) = sigma0, Q, b; got nprops = ' // itoa(nprops)
         else if (.not. props(5) > 0.0_dp) then
            msg = 'props(5) = Voce sigma0 = ' // rtoa(props(5)) // ': must be > 0'
         else if (.not. props(6) >= 0.0_dp) then
            msg = 'props(6) = Voce Q = ' // rtoa(props(6)) // ': must be >= 0 (no softening)'
         else if (.not. props(7) >= 0.0_dp) then
            msg = 'props(7) = Voce b = ' // rtoa(props(7)) // ': must be >= 0'
         end if
      case (law_table)
         if (nprops < n_props_fixed + 1) then
            msg = 'table law needs props(5) = m, number of points'
            return
         end if
         if (.not. is_integer(props(5), 2, 1000000)) then
            msg = 'props(5) = number of table points = ' // rtoa(props(5)) &
                  // ': must be a whole number >= 2'
            return
         end if
         m = nint(props(5))
         need = n_props_fixed + 1 + 2*m
         if (nprops < need) then
            msg = 'table law with ' // itoa(m) // ' points needs ' // itoa(need) &
                  // ' props, got ' // itoa(nprops)
            return
         end if
         ! Point i is (props(4+2i), props(5+2i)).
         if (abs(props(6)) > 0.0_dp) then
            msg = 'props(6) = first table plastic strain = ' // rtoa(props(6)) // ': must be 0'
         else if (.not. props(7) > 0.0_dp) then
            msg = 'props(7) = first table stress = ' // rtoa(props(7)) // ': must be > 0'
         else
            do i = 2, m
               if (.not. props(4 + 2*i) > props(2 + 2*i)) then
                  msg = 'table point ' // itoa(i) // ': plastic strain not increasing (' &
                        // rtoa(props(4 + 2*i)) // ' after ' // rtoa(props(2 + 2*i)) // ')'
                  exit
               else if (.not. props(5 + 2*i) >= props(3 + 2*i)) then
                  msg = 'table point ' // itoa(i) // ': stress decreasing (' &
                        // rtoa(props(5 + 2*i)) // ' after ' // rtoa(props(3 + 2*i)) // ')'
                  exit
               end if
            end do
         end if
      end select
   end function check_props

   !> Read a hardening curve: a text file of two columns, plastic strain and
   !> true stress, one point per line.  Blank lines and lines whose first
   !> non-blank character is '#' are skipped, as is anything after a '#' on
   !> a data line; columns may be separated by blanks, tabs or commas.
   !> Checks: every data line holds exactly two numbers; at least 2 points;
   !> the first plastic strain is 0; plastic strain strictly increasing;
   !> stress positive and non-decreasing.  Never stops the program.
   !>
   !> path   [in]  file name.
   !> ep     [out] plastic strains (allocated; size 0 on error).
   !> sigma  [out] true stresses (allocated; size 0 on error).
   !> errmsg [out] blank on success, otherwise the file, line and problem,
   !>              e.g. "curve file 'c.txt' line 5: plastic strain not
   !>              increasing (0.10 after 0.12)" (numbers quoted as written
   !>              in the file).  A character variable of any length (like
   !>              iomsg); the message is cut to len(errmsg), so give it
   !>              room (256 or more).
   subroutine read_curve_file(path, ep, sigma, errmsg)
      character(len=*), intent(in) :: path
      real(dp), allocatable, intent(out) :: ep(:), sigma(:)
      character(len=*), intent(out) :: errmsg

      character(len=:), allocatable :: line, at, msg
      character(len=64) :: tok(2), prev(2)
      character(len=256) :: iomsg
      real(dp), allocatable :: tmp(:)
      real(dp) :: x(2)
      integer :: unit, ios, nline, npt, ntok, k, first(2), last(2)

      msg = ''
      prev = ''
      allocate (ep(16), sigma(16))
      npt = 0
      nline = 0

      open (newunit=unit, file=path, status='old', action='read', form='formatted', &
            iostat=ios, iomsg=iomsg)
      if (ios /= 0) then
         errmsg = "cannot open curve file '" // path // "': " // trim(iomsg)
         call fail()
         return
      end if

      do
         call read_line(unit, line, ios, iomsg)
         if (ios /= 0) exit
         nline = nline + 1
         at = "curve file '" // path // "' line " // itoa(nline) // ': '
         k = index(line, '#')
         if (k > 0) line = line(:k - 1)
         call split_fields(line, first, last, ntok)
         if (ntok == 0) cycle
         if (ntok /= 2) then
            msg = at // 'expected 2 numbers (plastic strain, true stress), found ' &
                     // itoa(ntok) // " fields in '" // trim(adjustl(line)) // "'"
            exit
         end if
         do k = 1, 2
            tok(k) = line(first(k):last(k))
            if (.not. parse_real(line(first(k):last(k)), x(k))) then
               msg = at // "cannot read '" // line(first(k):last(k)) // "' as a number"
               exit
            end if
         end do
         if (len(msg) > 0) exit

         if (npt == 0 .and. abs(x(1)) > 0.0_dp) then
            msg = at // 'first plastic strain must be 0 (found ' // trim(tok(1)) // ')'
         else if (npt > 0 .and. .not. x(1) > ep(max(npt, 1))) then
            msg = at // 'plastic strain not increasing (' // trim(tok(1)) // ' after ' &
                     // trim(prev(1)) // ')'
         else if (.not. x(2) > 0.0_dp) then
            msg = at // 'stress must be positive (found ' // trim(tok(2)) // ')'
         else if (npt > 0 .and. .not. x(2) >= sigma(max(npt, 1))) then
            msg = at // 'stress decreasing (' // trim(tok(2)) // ' after ' &
                     // trim(prev(2)) // ')'
         end if
         if (len(msg) > 0) exit

         if (npt == size(ep)) then
            allocate (tmp(2*npt))
            tmp(:npt) = ep(:npt)
            call move_alloc(tmp, ep)
            allocate (tmp(2*npt))
            tmp(:npt) = sigma(:npt)
            call move_alloc(tmp, sigma)
         end if
         npt = npt + 1
         ep(npt) = x(1)
         sigma(npt) = x(2)
         prev = tok
      end do

      if (len(msg) == 0 .and. .not. is_iostat_end(ios)) then
         msg = "curve file '" // path // "' line " // itoa(nline + 1) // ': read error: ' &
                  // trim(iomsg)
      end if
      if (len(msg) == 0 .and. npt < 2) then
         msg = "curve file '" // path // "': need at least 2 points, found " // itoa(npt)
      end if
      close (unit)
      errmsg = msg
      if (len(msg) > 0) then
         call fail()
      else
         ep = ep(:npt)
         sigma = sigma(:npt)
      end if

   contains

      !> On error: return empty (allocated) arrays.
      subroutine fail()
         if (allocated(ep)) deallocate (ep)
         if (allocated(sigma)) deallocate (sigma)
         allocate (ep(0), sigma(0))
      end subroutine fail

   end subroutine read_curve_file

   !> Read one whole record of any length from a formatted sequential unit.
   !>
   !> unit   [in]  connected unit.
   !> line   [out] the record, without the end-of-record marker.
   !> iostat [out] 0 on success, iostat_end at end of file, else an error.
   !> iomsg  [out] message for a non-zero iostat.
   subroutine read_line(unit, line, iostat, iomsg)
      integer, intent(in) :: unit
      character(len=:), allocatable, intent(out) :: line
      integer, intent(out) :: iostat
      character(len=*), intent(out) :: iomsg

      character(len=256) :: buf
      integer :: nread

      line = ''
      iomsg = ''
      do
         read (unit, '(a)', advance='no', iostat=iostat, iomsg=iomsg, size=nread) buf
         line = line // buf(:nread)
         if (is_iostat_eor(iostat)) then
            iostat = 0
            exit
         end if
         if (iostat /= 0) exit
      end do
   end subroutine read_line

   !> Locate the fields of a line, separated by blanks, tabs or commas.
   !>
   !> line  [in]  text.
   !> first [out] start of field k in line, for k <= min(ntok, size(first)).
   !> last  [out] end of field k.
   !> ntok  [out] number of fields (all of them, also beyond size(first)).
   pure subroutine split_fields(line, first, last, ntok)
      character(len=*), intent(in) :: line
      integer, intent(out) :: first(:), last(:)
      integer, intent(out) :: ntok

      integer :: i, start
      logical :: in_field

      first = 1
      last = 0
      ntok = 0
      in_field = .false.
      start = 1
      do i = 1, len(line) + 1
         if (i <= len(line)) then
            if (.not. is_separator(line(i:i))) then
               if (.not. in_field) start = i
               in_field = .true.
               cycle
            end if
         end if
         if (in_field) then
            ntok = ntok + 1
            if (ntok <= size(first)) then
               first(ntok) = start
               last(ntok) = i - 1
            end if
         end if
         in_field = .false.
      end do
   end subroutine split_fields

   !> .true. for a field separator: blank, tab or comma.
   !>
   !> c [in] one character.
   pure logical function is_separator(c)
      character(len=1), intent(in) :: c

      is_separator = c == ' ' .or. c == ',' .or. c == achar(9) .or. c == achar(13)
   end function is_separator

   !> Parse one field as a finite real.  Only digits, signs, '.', and the
   !> exponent letters e/E/d/D are accepted, with at least one digit, so that
   !> list-directed input cannot take '/', 'T', 'nan' or 'inf' as a value.
   !>
   !> tok [in]  the field.
   !> x   [out] its value (0 if it does not parse).
   !> Returns .true. if tok is a finite number.
   logical function parse_real(tok, x)
      character(len=*), intent(in) :: tok
      real(dp), intent(out) :: x

      integer :: ios
      x = 0.0_dp
      parse_real = .false.
      if (len_trim(tok) == 0) return
      if (verify(trim(tok), '0123456789+-.eEdD') /= 0) return
      if (scan(tok, '0123456789') == 0) return
      read (tok, *, iostat=ios) x
      parse_real = ios == 0 .and. ieee_is_finite(x)
      if (.not. parse_real) x = 0.0_dp
   end function parse_real

   !> .true. if x is a whole number in [lo, hi].
   !>
   !> x  [in] value.
   !> lo [in] lowest allowed whole number.
   !> hi [in] highest allowed whole number.
   pure logical function is_integer(x, lo, hi)
      real(dp), intent(in) :: x
      integer, intent(in) :: lo, hi

      is_integer = .false.
      if (.not. (x >= real(lo, dp) .and. x <= real(hi, dp))) return
      is_integer = abs(x - real(nint(x), dp)) <= 0.0_dp
   end function is_integer

   !> Integer to text, without blanks.
   !>
   !> i [in] value.
   pure function itoa(i) result(s)
      integer, intent(in) :: i
      character(len=:), allocatable :: s

      character(len=16) :: buf

      write (buf, '(i0)') i
      s = trim(buf)
   end function itoa

   !> Real to text, 4 significant digits in exponent form (messages only).
   !>
   !> x [in] value.
   pure function rtoa(x) result(s)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: s

      character(len=32) :: buf

      write (buf, '(es10.3)') x
      s = trim(adjustl(buf))
   end function rtoa

   !> MAX_LOAD_STRAIN: the axial log strain at maximum load in plane-strain
   !> uniaxial tension (width strain held, sigma22 = 0), where the continuum
   !> tangent falls to the stress, d tau/d eps = tau (DESIGN §7): the sheet's
   !> forming limit in plane strain (FLD0).  Found by driving this UMAT along
   !> the path in increments of 1e-4 and interpolating the crossing.
   !>  props   [in]  material constants
   !>  eps_max [out] the strain; huge() if not reached by a log strain of 3
   pure function max_load_strain(props) result(eps_max)
      real(dp), intent(in) :: props(:)
      real(dp) :: eps_max
      real(dp), parameter :: step = 1.0e-4_dp
      real(dp) :: stress(2), statev(n_statev), ddsdde(2, 2), sse, spd, pnewdt, eps, g, g_old
      integer :: i
      stress = 0.0_dp
      statev = 0.0_dp
      sse = 0.0_dp
      spd = 0.0_dp
      eps = 0.0_dp
      g_old = 1.0_dp
      eps_max = huge(1.0_dp)
      do i = 1, 30000
         pnewdt = 1.0_dp
         call umat(stress, statev, ddsdde, sse, spd, [eps, 0.0_dp], [step, 0.0_dp], props, &
                   size(props), n_statev, pnewdt)
         if (pnewdt < 1.0_dp) return
         eps = eps + step
         g = statev(4) - stress(1)
         if (g <= 0.0_dp) then
            eps_max = eps - step*g/(g - g_old)
            return
         end if
         g_old = g
      end do
   end function max_load_strain
end module material_j2
