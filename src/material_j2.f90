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
   public :: umat, flow_stress, hill_equivalent, check_props, read_curve_file

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
   !> given (the section passes 0: plane strain).
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

      real(dp) :: e_mod, nu, r_value, e_ps, d12
      real(dp) :: sig_tr(2), sig(2), dsig(2), flow(2), dflow(2)
      real(dp) :: ep_n, sy_n, h_n, seq_tr, seq, dp_inc, sy_end, h_end, denom
      logical :: ok

      ! stran is not needed (see header); the associate marks it as read.
      associate (unused => stran)
      end associate

      if (.not. sizes_ok(props, nprops, nstatv)) then
         ddsdde = 0.0_dp
         pnewdt = min(pnewdt, 0.0_dp)
         return
      end if

      e_mod = props(1)
      nu = props(2)
      r_value = props(3)
      e_ps = e_mod/(1.0_dp - nu**2)
      d12 = e_ps*nu

      ! Elastic predictor.
      sig_tr(1) = stress(1) + e_ps*dstran(1) + d12*dstran(2)
      sig_tr(2) = stress(2) + d12*dstran(1) + e_ps*dstran(2)
      ep_n = statev(1)
      if (statev(5) > 0.0_dp) then
         sy_n = statev(5)
         h_n = statev(6)
      else
         call flow_stress(ep_n, props, nprops, sy_n, h_n)
      end if
      seq_tr = hill_equivalent(sig_tr, r_value)

      if (seq_tr <= (1.0_dp + tol_yield)*sy_n) then
         ! Elastic step (also elastic unloading): cheap early return.
         dsig = sig_tr - stress
         ! Thickness strain: plane stress sigma22 = 0 gives
         ! d eps22 = -(nu/E)(d s11 + d s33) (DESIGN §4, no plastic part).
         statev(2) = statev(2) - nu/e_mod*(dsig(1) + dsig(2))
         stress = sig_tr
         statev(3) = stress(2)
         statev(4) = e_ps
         statev(5) = sy_n
         statev(6) = h_n
         sse = elastic_energy(stress, e_mod, nu)
         ddsdde(1, 1) = e_ps
         ddsdde(2, 1) = d12
         ddsdde(1, 2) = d12
         ddsdde(2, 2) = e_ps
         return
      end if

      ! Plastic: backward-Euler return mapping.
      ok = sy_n > 0.0_dp .and. all(ieee_is_finite(sig_tr))
      if (ok) call return_map(sig_tr, ep_n, sy_n, h_n, seq_tr, props, nprops, sig, seq, &
                              dp_inc, sy_end, h_end, ok)
      if (.not. ok) then
         ddsdde = reshape([e_ps, d12, d12, e_ps], [2, 2])
         pnewdt = min(pnewdt, pnewdt_cut)
         return
      end if

      flow = hill_normal(sig, seq, r_value)

      ddsdde = consistent_tangent(seq, flow, dp_inc, h_end, e_mod, nu, r_value)

      ! Continuum tangent (A.1) with alpha = 1, (1,1) entry (eps33 fixed):
      ! D - (D n)(D n)^T / (n^T D n + H').
      dflow(1) = e_ps*flow(1) + d12*flow(2)
      dflow(2) = d12*flow(1) + e_ps*flow(2)
      denom = dot_product(flow, dflow) + h_end
      statev(4) = e_ps - dflow(1)**2/denom

      ! Thickness strain, DESIGN §4: elastic part from sigma22 = 0, plastic
      ! part from plastic incompressibility of (A.3):
      ! d eps22 = -(nu/E)(d s11 + d s33) - d eps11p - d eps33p.
      dsig = sig - stress
      statev(2) = statev(2) - nu/e_mod*(dsig(1) + dsig(2)) - dp_inc*(flow(1) + flow(2))
      statev(1) = ep_n + dp_inc
      statev(5) = sy_end
      statev(6) = h_end
      stress = sig
      statev(3) = stress(2)
      sse = elastic_energy(stress, e_mod, nu)
      ! Dissipation: on the yield surface sigma : d eps_p = sbar d ep = sigma_y(ep) d ep,
      ! so the increment dissipates W(ep_n + dp) - W(ep_n), W the integral of
      ! the hardening curve, exact for any increment size.
      spd = spd + plastic_work(ep_n + dp_inc, sy_end, props, nprops) &
            - plastic_work(ep_n, sy_n, props, nprops)
   end subroutine umat

   !> Backward-Euler return mapping onto the Hill yield surface.
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
   !> gamma sbar(gamma)) = 0.  g is strictly decreasing for a non-softening
   !> curve, g(0) > 0, and g(gamma_hi) <= 0 at
   !> gamma_hi = (sbar_tr/sigma_y(ep_n) - 1)/min(k_s, k_t), so a Newton
   !> iteration safeguarded by bisection in [0, gamma_hi] always converges,
   !> quadratically once in the smooth part of the curve.
   !>
   !> sig_tr [in]  trial stress (s11, s33).
   !> ep_n   [in]  equivalent plastic strain at the start of the increment.
   !> sy_n   [in]  sigma_y(ep_n) > 0.
   !> h_n    [in]  d sigma_y / d ebar_p at ep_n (with sy_n: the first
   !>              iterate, gamma = 0, needs no hardening-law call).
   !> seq_tr [in]  sbar(sig_tr) > sy_n.
   !> props  [in]  material constants (see umat).
   !> nprops [in]  size of props.
   !> sig    [out] end stress on the yield surface.
   !> seq    [out] sbar of the end stress (the last iterate's, = sy_end to
   !>              the local tolerance).
   !> dp_inc [out] equivalent plastic strain increment dp > 0.
   !> sy_end [out] sigma_y(ep_n + dp).
   !> h_end  [out] hardening modulus d sigma_y / d ebar_p at ep_n + dp.
   !> ok     [out] .false. if no convergence or a non-finite / non-positive
   !>              value appeared; sig, dp_inc, h_end are then undefined.
   pure subroutine return_map(sig_tr, ep_n, sy_n, h_n, seq_tr, props, nprops, sig, seq, &
                              dp_inc, sy_end, h_end, ok)
      integer, intent(in) :: nprops
      real(dp), intent(in) :: sig_tr(2), ep_n, sy_n, h_n, seq_tr
      real(dp), intent(in) :: props(nprops)
      real(dp), intent(out) :: sig(2), seq, dp_inc, sy_end, h_end
      logical, intent(out) :: ok

      real(dp) :: e_mod, nu, r, k_s, k_t, k_eff, a_s, a_t, s_tr, t_tr
      real(dp) :: gam, gam_lo, gam_hi, gam_new, q_s, q_t, dseq, g, dg
      integer :: iter
      logical :: last_step

      e_mod = props(1)
      nu = props(2)
      r = props(3)/(1.0_dp + props(3))
      s_tr = sig_tr(1) + sig_tr(2)
      t_tr = sig_tr(1) - sig_tr(2)
      k_s = e_mod*(1.0_dp - r)/(1.0_dp - nu)
      k_t = e_mod*(1.0_dp + r)/(1.0_dp + nu)
      a_s = (1.0_dp - r)*s_tr**2
      a_t = (1.0_dp + r)*t_tr**2
      ! Effective decay rate of sbar at gamma = 0: sbar'(0) = -k_eff sbar_tr.
      k_eff = (a_s*k_s + a_t*k_t)/(a_s + a_t)

      gam_lo = 0.0_dp
      gam_hi = (seq_tr/sy_n - 1.0_dp)/min(k_s, k_t)
      gam = 0.0_dp
      ok = .false.
      sig = sig_tr
      dp_inc = 0.0_dp
      sy_end = sy_n
      h_end = h_n
      last_step = .false.
      do iter = 1, max_newton
         q_s = 1.0_dp/(1.0_dp + gam*k_s)
         q_t = 1.0_dp/(1.0_dp + gam*k_t)
         seq = sqrt(0.5_dp*(a_s*q_s**2 + a_t*q_t**2))
         if (last_step) then
            ! sigma_y carried to the new point by Taylor's formula (error
            ! H'' d^2/2 with d < 1e-7 sigma_y/H': some 1e-20 relative; H' is
            ! that of a point within d of ep_n + dp)
            sy_end = sy_end + h_end*(gam*seq - dp_inc)
            dp_inc = gam*seq
            ok = .true.
            exit
         end if
         dp_inc = gam*seq
         if (iter > 1) call flow_stress(ep_n + dp_inc, props, nprops, sy_end, h_end)
         g = seq - sy_end
         if (.not. (sy_end > 0.0_dp .and. ieee_is_finite(g))) return
         if (abs(g) <= tol_newton*sy_end) then
            ok = .true.
            exit
         end if
         if (g > 0.0_dp) then
            gam_lo = gam
         else
            gam_hi = gam
         end if
         ! g'(gamma) = sbar' - H' (sbar + gamma sbar'),  sbar' < 0.
         dseq = -0.5_dp*(a_s*k_s*q_s**3 + a_t*k_t*q_t**3)/seq
         dg = dseq - h_end*(seq + gam*dseq)
         ! Newton on F = g (1 + gamma k_eff), same root and sign as g:
         ! sbar ~ sbar_tr/(1 + gamma k_eff) makes g strongly convex (plain
         ! Newton from gamma = 0 only halves the error per iteration for
         ! large steps), while F is nearly linear (exactly so for a
         ! perfectly plastic material when k_s = k_t).
         ! F'/(1 + gamma k_eff) = g' + g k_eff/(1 + gamma k_eff).
         dg = dg + g*k_eff/(1.0_dp + gam*k_eff)
         if (dg < 0.0_dp) then
            gam_new = gam - g/dg
         else
            gam_new = gam_lo - 1.0_dp
         end if
         ! Bisection if the Newton step leaves the bracket (kinks of a
         ! tabulated curve).
         if (.not. (gam_new > gam_lo .and. gam_new < gam_hi)) then
            gam_new = 0.5_dp*(gam_lo + gam_hi)
         else
            ! A Newton step from |g| <= tol_taylor sigma_y leaves a residual
            ! of order (g/sigma_y)^2 sigma_y < tol_newton sigma_y: it is the
            ! last one, and needs no further hardening-law call.
            last_step = abs(g) <= tol_taylor*sy_end
         end if
         gam = gam_new
      end do
      if (.not. ok) return

      sig(1) = 0.5_dp*(s_tr*q_s + t_tr*q_t)
      sig(2) = 0.5_dp*(s_tr*q_s - t_tr*q_t)
      ok = all(ieee_is_finite(sig)) .and. dp_inc > 0.0_dp
   end subroutine return_map

   !> Consistent (algorithmic) tangent of the backward-Euler update.
   !>
   !> Linearising the converged local system in strain form,
   !>   C (sigma - sigma_tr) + dp n(sigma) = 0,  n . d sigma = H' d dp,
   !> with C = D^-1 and d n / d sigma = (P - n n^T)/sbar, gives
   !>   d sigma = Xi (d deps - d dp n),  Xi = (C + dp (P - n n^T)/sbar)^-1,
   !>   d sigma / d deps = Xi - (Xi n)(Xi n)^T / (n^T Xi n + H'),
   !> the Schur complement of the local Jacobian; symmetric, and equal to
   !> the continuum tangent (A.1) when dp -> 0.
   !>
   !> seq     [in] sbar of the converged end stress, > 0.
   !> flow    [in] n = P sig / sbar.
   !> dp_inc  [in] equivalent plastic strain increment.
   !> h_end   [in] H' = d sigma_y / d ebar_p at the end state.
   !> e_mod   [in] Young's modulus E.
   !> nu      [in] Poisson's ratio.
   !> r_value [in] Lankford coefficient R.
   !> Returns the 2x2 consistent tangent.
   pure function consistent_tangent(seq, flow, dp_inc, h_end, e_mod, nu, r_value) result(ct)
      real(dp), intent(in) :: seq, flow(2), dp_inc, h_end, e_mod, nu, r_value
      real(dp) :: ct(2, 2)

      real(dp) :: r, a(2, 2), xi(2, 2), xin(2), det

      r = r_value/(1.0_dp + r_value)
      ! A = C + dp (P - n n^T)/sbar, C = (1/E) [[1, -nu], [-nu, 1]].
      a(1, 1) = 1.0_dp/e_mod + dp_inc*(1.0_dp - flow(1)**2)/seq
      a(2, 2) = 1.0_dp/e_mod + dp_inc*(1.0_dp - flow(2)**2)/seq
      a(1, 2) = -nu/e_mod + dp_inc*(-r - flow(1)*flow(2))/seq
      a(2, 1) = a(1, 2)
      ! A is symmetric positive definite (C is, and P - n n^T is the Hessian
      ! of the convex sbar), so the explicit 2x2 inverse is safe.
      det = a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1)
      xi(1, 1) = a(2, 2)/det
      xi(2, 2) = a(1, 1)/det
      xi(1, 2) = -a(1, 2)/det
      xi(2, 1) = xi(1, 2)
      xin = matmul(xi, flow)
      ct(:, 1) = xi(:, 1) - xin*xin(1)/(dot_product(flow, xin) + h_end)
      ct(:, 2) = xi(:, 2) - xin*xin(2)/(dot_product(flow, xin) + h_end)
   end function consistent_tangent

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

   !> Flow direction n = d sbar / d sigma = P sigma / sbar,
   !> P = [[1, -r], [-r, 1]], r = R/(1+R).
   !>
   !> sig     [in] stress (sigma11, sigma33).
   !> seq     [in] sbar(sig) > 0.
   !> r_value [in] Lankford coefficient R.
   !> Returns n (2 components).
   pure function hill_normal(sig, seq, r_value) result(flow)
      real(dp), intent(in) :: sig(2), seq, r_value
      real(dp) :: flow(2)

      real(dp) :: r

      r = r_value/(1.0_dp + r_value)
      flow(1) = (sig(1) - r*sig(2))/seq
      flow(2) = (sig(2) - r*sig(1))/seq
   end function hill_normal

   !> Elastic strain energy density of a plane-stress state,
   !> (1/2) sigma . C sigma = (s11^2 + s33^2 - 2 nu s11 s33)/(2E).
   !>
   !> sig   [in] stress (sigma11, sigma33).
   !> e_mod [in] Young's modulus E.
   !> nu    [in] Poisson's ratio.
   pure function elastic_energy(sig, e_mod, nu) result(w)
      real(dp), intent(in) :: sig(2), e_mod, nu
      real(dp) :: w

      w = (sig(1)**2 + sig(2)**2 - 2.0_dp*nu*sig(1)*sig(2))/(2.0_dp*e_mod)
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
