!> material_j2 -- the built-in elasto-plastic material (J2 / Hill 1948) for
!> one through-thickness station of a plane-strain sheet (docs/theory.md §4), as a
!> UMAT with the Abaqus argument list and as a vectorized block routine.
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
!>     - hardening: Swift, Voce, or a piecewise-linear table (module
!>       hardening).
!>   Elastic predictor; beyond the yield surface backward-Euler return
!>   mapping (docs/theory.md §4)
!>     sigma = sigma_trial - dp D n(sigma),   sbar(sigma) = sigma_y(ep_n + dp),
!>     n = d sbar / d sigma = P sigma / sbar,  P = [[1, -r], [-r, 1]], r = R/(1+R),
!>   and its consistent (algorithmic) tangent.
!>
!> Conventions (NDI = 2, NSHR = 0, NTENS = 2)
!>   stress(1:2) = (sigma11, sigma33);  strain (eps11, eps33); the thickness
!>   direction 22 carries sigma22 = 0 and its strain is a state variable.
!>   State variables statev(1:n_statev):
!>     statev(isv_eqps)      ebar_p, equivalent plastic strain;
!>     statev(isv_eps22)     eps22, total thickness log strain;
!>     statev(isv_sigma33)   sigma33 (copy for output);
!>     statev(isv_tangent)   continuum tangent d sigma11 / d eps11 at fixed
!>                           eps33 (alpha of (A.1): plastic only if the
!>                           increment was plastic);
!>     statev(isv_flow_stress), statev(isv_hardening_slope)
!>                           sigma_y(ebar_p) and its slope H', cached so that
!>                           an elastic call evaluates no hardening law
!>                           (statev(isv_flow_stress) <= 0: not yet known,
!>                           computed on entry; the all-zero virgin state is
!>                           therefore valid).
!>   Material constants props(:): props(ip_youngs) = E, props(ip_poisson) =
!>   nu, props(ip_r_value) = R, then the hardening law: its id at
!>   props(ip_law) and its constants after it (layout in module hardening).
!>
!> Call check_props once at set-up: umat trusts its constants (it is called
!> ~1e6 times per run) and only guards against out-of-bounds access.
module material_j2
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use hardening, only: ip_youngs, ip_poisson, ip_r_value, ip_law, flow_stress, flow_stress_block, plastic_work, law_sizes_ok, &
                        check_law_props
   use text, only: itoa, num
   use return_mapping, only: return_map_block
   implicit none
   private

   public :: n_statev, isv_eqps, isv_eps22, isv_sigma33, isv_tangent, isv_flow_stress, &
             isv_hardening_slope, ip_youngs, ip_poisson, ip_r_value
   public :: umat, umat_block, umat_block_to, hill_equivalent, check_props

   !> places of the state variables in statev (module header)
   integer, parameter :: isv_eqps = 1, isv_eps22 = 2, isv_sigma33 = 3, isv_tangent = 4, &
                         isv_flow_stress = 5, isv_hardening_slope = 6
   !> number of state variables umat needs
   integer, parameter :: n_statev = 6

   !> a trial state with sbar_trial <= (1 + tol_yield) sigma_y is elastic:
   !> a converged plastic state re-entered with a zero strain increment must
   !> not start a spurious return mapping on round-off.
   real(dp), parameter :: tol_yield = 1.0e-12_dp
   !> increment ratio requested from the caller when the local solve fails
   real(dp), parameter :: pnewdt_cut = 0.5_dp

contains

   !> UMAT: stress update of one material point for one increment of log
   !> strain, with the Abaqus UMAT argument list (order as in CalculiX
   !> umat.f).  What the program passes in each argument, and the contract
   !> of a user's routine with the same list, is written in module law_umat
   !> (whose contract is NTENS = 4; this built-in routine keeps the
   !> plane-stress NTENS = 2 list for its own tests).
   !>
   !> Given the start-of-increment stress and state and the log-strain
   !> increment, returns the end-of-increment stress and state and the
   !> consistent tangent of the law of the module header.  The width strain
   !> increment dstran(2) is honoured as given (the section passes 0: plane
   !> strain).  The work is done by umat_block with a block of one.
   !>
   !> stress  [in,out] (ntens) Kirchhoff stress (sigma11, sigma33): start of
   !>                  the increment on entry, end on exit.
   !> statev  [in,out] (nstatv >= n_statev) state variables (module header);
   !>                  statev(isv_tangent) at the end: E/(1-nu^2) for an
   !>                  elastic or unloading increment, elasto-plastic (A.1)
   !>                  with alpha = 1 for a plastic one.
   !> ddsdde  [out]    (ntens, ntens) consistent tangent d sigma_end /
   !>                  d dstran (symmetric); D for an elastic increment.
   !> sse     [in,out] elastic strain energy density at the end of the
   !>                  increment, (s11^2 + s33^2 - 2 nu s11 s33)/(2E).
   !> spd     [in,out] plastic dissipation density, accumulated:
   !>                  spd = spd + int sigma_y d ep over the increment (exact:
   !>                  W(ep_n + dp) - W(ep_n), W the integral of the curve).
   !> scd     [in,out] creep dissipation: not used, left as it is.
   !> rpl, ddsddt, drplde, drpldt [out] heat generation and its
   !>                  derivatives: 0 (a mechanical law).
   !> stran   [in]     (ntens) total log strain at the start of the
   !>                  increment: not used (the stress is the state of this
   !>                  additive model).
   !> dstran  [in]     (ntens) log strain increment (deps11, deps33).
   !> time, dtime, temp, dtemp, predef, dpred, cmname [in] not used
   !>                  (rate-independent, isothermal, one material).
   !> ndi, nshr, ntens [in] 2, 0, 2: anything else is a programming error
   !>                  (see pnewdt).
   !> nstatv  [in]     size of statev.
   !> props   [in]     (nprops) material constants (module header).
   !> nprops  [in]     size of props.
   !> coords, drot, celent, dfgrd0, dfgrd1, noel, npt, layer, kspt, kstep,
   !> kinc    [in]     not used (a homogeneous law in the fibre frame).
   !> pnewdt  [in,out] untouched on success.  If the local Newton fails
   !>                  (no convergence, non-positive flow stress, non-finite
   !>                  value): pnewdt = min(pnewdt, 0.5), and stress,
   !>                  statev, sse, spd are returned unchanged (ddsdde = D).
   !>                  If nprops or nstatv is too small for the law or the
   !>                  component counts are not (2, 0, 2) (a programming
   !>                  error; check_props catches the first): pnewdt =
   !>                  min(pnewdt, 0), nothing changed, ddsdde = 0.
   pure subroutine umat(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, &
                        stran, dstran, time, dtime, temp, dtemp, predef, dpred, cmname, ndi, &
                        nshr, ntens, nstatv, props, nprops, coords, drot, pnewdt, celent, dfgrd0, &
                        dfgrd1, noel, npt, layer, kspt, kstep, kinc)
      character(len=80), intent(in) :: cmname
      integer, intent(in) :: ndi, nshr, ntens, nstatv, nprops, noel, npt, layer, kspt, kstep, kinc
      real(dp), intent(inout) :: stress(ntens), statev(nstatv), sse, spd, scd, pnewdt
      real(dp), intent(out) :: ddsdde(ntens, ntens), rpl, ddsddt(ntens), drplde(ntens), drpldt
      real(dp), intent(in) :: stran(ntens), dstran(ntens), time(2), dtime, temp, dtemp, predef(1), &
                              dpred(1), props(nprops), coords(3), drot(3, 3), celent, &
                              dfgrd0(3, 3), dfgrd1(3, 3)

      real(dp) :: b_stress(1, 2), b_statev(1, nstatv), b_ddsdde(1, 2, 2), b_sse(1), b_spd(1)
      real(dp) :: b_dstran(1, 2)

      ! The arguments the header marks "not used" are named once here, so
      ! that the compiler does not report them as unused.
      associate (u1 => scd, u2 => stran, u3 => time, u4 => dtime, u5 => temp, u6 => dtemp, &
                 u7 => predef, u8 => dpred, u9 => cmname, u10 => coords, u11 => drot, &
                 u12 => celent, u13 => dfgrd0, u14 => dfgrd1, u15 => noel, u16 => npt, &
                 u17 => layer, u18 => kspt, u19 => kstep, u20 => kinc)
      end associate

      rpl = 0.0_dp
      ddsddt = 0.0_dp
      drplde = 0.0_dp
      drpldt = 0.0_dp
      if (ndi /= 2 .or. nshr /= 0 .or. ntens /= 2) then
         ddsdde = 0.0_dp
         pnewdt = min(pnewdt, 0.0_dp)
         return
      end if
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
   !> at once, the block index first (the layout of Abaqus/Explicit's VUMAT),
   !> in place: umat_block_to with the start state copied aside (see there).
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
      real(dp) :: stress_n(nblock, 2), statev_n(nblock, nstatv), sse_n(nblock), spd_n(nblock)

      stress_n = stress
      statev_n = statev
      sse_n = sse
      spd_n = spd
      call umat_block_to(nblock, stress_n, statev_n, sse_n, spd_n, stress, statev, ddsdde, sse, &
                         spd, dstran, props, nprops, nstatv, pnewdt)
   end subroutine umat_block

   !> UMAT_BLOCK_TO: the stress update of umat for a block of material
   !> points at once, the block index first (the layout of Abaqus/Explicit's
   !> VUMAT), from the start state in stress_n ... spd_n into the end state
   !> in stress ... spd (distinct arrays): every output is written once and
   !> the start state is read where it is, so the section needs no copy of
   !> its converged history into the trial one (umat_block is the in-place
   !> form).
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
   !> stress_n [in]    (nblock, 2) Kirchhoff stress (sigma11, sigma33) per
   !>                  point at the start of the increment.
   !> statev_n [in]    (nblock, nstatv) state variables per point (see umat)
   !>                  at the start.
   !> sse_n   [in]     (nblock) elastic strain energy density at the start
   !>                  (read only if the update fails).
   !> spd_n   [in]     (nblock) plastic dissipation density at the start.
   !> stress  [out]    (nblock, 2) the stress at the end of the increment.
   !> statev  [out]    (nblock, nstatv) the state variables at the end.
   !> ddsdde  [out]    (nblock, 2, 2) consistent tangent per point.
   !> sse     [out]    (nblock) elastic strain energy density at the end.
   !> spd     [out]    (nblock) plastic dissipation density at the end.
   !> dstran  [in]     (nblock, 2) log strain increment (deps11, deps33).
   !> props   [in]     material constants, shared by the block (see umat).
   !> nprops  [in]     size of props.
   !> nstatv  [in]     second extent of statev.
   !> pnewdt  [in,out] as for umat; if the return mapping fails at any point,
   !>                  pnewdt = min(pnewdt, 0.5) and stress, statev, sse, spd
   !>                  of the whole block are the start state (ddsdde = D).
   pure subroutine umat_block_to(nblock, stress_n, statev_n, sse_n, spd_n, stress, statev, &
                                 ddsdde, sse, spd, dstran, props, nprops, nstatv, pnewdt)
      integer, intent(in) :: nblock, nprops, nstatv
      real(dp), intent(in) :: stress_n(nblock, 2), statev_n(nblock, nstatv), sse_n(nblock), &
                              spd_n(nblock)
      real(dp), intent(out) :: stress(nblock, 2)
      real(dp), intent(out) :: statev(nblock, nstatv)
      real(dp), intent(out) :: ddsdde(nblock, 2, 2)
      real(dp), intent(out) :: sse(nblock)
      real(dp), intent(out) :: spd(nblock)
      real(dp), intent(in) :: dstran(nblock, 2)
      real(dp), intent(in) :: props(nprops)
      real(dp), intent(inout) :: pnewdt

      real(dp) :: e_mod, nu, r_value, r, e_ps, d12, hill_a, hill_b, c_e, c_nu
      real(dp), dimension(nblock) :: seq2_tr
      ! packed plastic points (index j; idx(j) is the point of the block)
      integer :: idx(nblock), np, j, k
      real(dp), dimension(nblock) :: s_tr, t_tr, ep_n, sy_p, h_p, seq_p, q_s, q_t, seq, &
                                     dp_inc, sy_end, h_end, sig1, sig2, c11, c12, c22, ct11, &
                                     eps22, sse_p, spd_p, sig_n1, sig_n2
      real(dp) :: f1, f2, a11, a12, a22, rdet, x11, x12, x22, xn1, xn2, rden, dsig1, dsig2, rs, gs
      logical :: ok

      ! sizes only (the values are check_props's job, done once at set-up)
      if (nstatv < n_statev .or. .not. law_sizes_ok(props, nprops)) then
         ddsdde = 0.0_dp
         pnewdt = min(pnewdt, 0.0_dp)
         ! a failed update returns the start state
         stress = stress_n
         statev = statev_n
         sse = sse_n
         spd = spd_n
         return
      end if

      e_mod = props(ip_youngs)
      nu = props(ip_poisson)
      r_value = props(ip_r_value)
      r = r_value/(1.0_dp + r_value)
      e_ps = e_mod/(1.0_dp - nu**2)
      d12 = e_ps*nu
      ! sbar^2 = (hill_a (s11 + s33)^2 + hill_b (s11 - s33)^2), see hill_equivalent
      hill_a = 1.0_dp/(2.0_dp*(1.0_dp + r_value))
      hill_b = (1.0_dp + 2.0_dp*r_value)*hill_a
      ! the compliance C = D^-1 = [[1, -nu], [-nu, 1]]/E
      c_e = 1.0_dp/e_mod
      c_nu = nu/e_mod

      ! D at every point: the tangent of an elastic point, and of the whole
      ! block if it fails (the plastic points are overwritten at the end)
      ddsdde(:, 1, 1) = e_ps
      ddsdde(:, 2, 1) = d12
      ddsdde(:, 1, 2) = d12
      ddsdde(:, 2, 2) = e_ps

      ! Elastic predictor; the flow stress comes from the cache statev(isv_flow_stress)
      ! and statev(isv_hardening_slope), which a virgin point
      ! (statev(isv_flow_stress) <= 0) has not filled yet.  The trial stress
      ! and the flow stress at the start go straight into the outputs (the
      ! end state of an elastic point; the plastic points are overwritten at
      ! the end): a copy loop of its own becomes a memcpy call per column,
      ! which for a block of 21 points costs more than the copy itself.
      do k = 1, nblock
         stress(k, 1) = stress_n(k, 1) + e_ps*dstran(k, 1) + d12*dstran(k, 2)
         stress(k, 2) = stress_n(k, 2) + d12*dstran(k, 1) + e_ps*dstran(k, 2)
         ! sbar_trial^2: its root is needed only where the point yields
         seq2_tr(k) = hill_a*(stress(k, 1) + stress(k, 2))**2 + hill_b*(stress(k, 1) - stress(k, 2))**2
         statev(k, isv_flow_stress) = statev_n(k, isv_flow_stress)
         statev(k, isv_hardening_slope) = statev_n(k, isv_hardening_slope)
      end do
      do k = 1, nblock
         if (.not. statev(k, isv_flow_stress) > 0.0_dp) &
            call flow_stress(statev_n(k, isv_eqps), props, nprops, statev(k, isv_flow_stress), &
                             statev(k, isv_hardening_slope))
      end do

      ! Points whose trial state lies outside the yield surface.  A trial
      ! state with sbar_trial <= (1 + tol_yield) sigma_y is elastic (also
      ! elastic unloading); a NaN is not, so that the checks below fail it.
      ! Compared squared (sbar_trial^2 <= ((1 + tol_yield) sigma_y)^2 with
      ! sigma_y > 0), without a root per point; a point with sigma_y <= 0
      ! goes to the checks below, which fail it.
      np = 0
      do k = 1, nblock
         if (.not. (seq2_tr(k) <= ((1.0_dp + tol_yield)*statev(k, isv_flow_stress))**2 .and. &
                    statev(k, isv_flow_stress) > 0.0_dp)) then
            np = np + 1
            idx(np) = k
         end if
      end do
      ok = .true.
      do j = 1, np
         k = idx(j)
         s_tr(j) = stress(k, 1) + stress(k, 2)
         t_tr(j) = stress(k, 1) - stress(k, 2)
         ep_n(j) = statev_n(k, isv_eqps)
         sig_n1(j) = stress_n(k, 1)
         sig_n2(j) = stress_n(k, 2)
         eps22(j) = statev_n(k, isv_eps22)
         spd_p(j) = spd_n(k)
         sy_p(j) = statev(k, isv_flow_stress)
         h_p(j) = statev(k, isv_hardening_slope)
         seq_p(j) = sqrt(seq2_tr(k))
         ok = ok .and. statev(k, isv_flow_stress) > 0.0_dp .and. ieee_is_finite(stress(k, 1)) .and. &
              ieee_is_finite(stress(k, 2))
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
         ! a failed update returns the start state
         stress = stress_n
         statev = statev_n
         sse = sse_n
         spd = spd_n
         return
      end if

      ! End states of the plastic points, packed.
      do j = 1, np
         ! flow direction n = P sigma / sbar (hill_normal).  The tangent
         ! below takes 1/sbar, 1/det and 1/den once each (it had nine
         ! divisions).  n itself keeps its two divisions: multiplying by
         ! 1/sbar there moves eps22, hence zbar, by an ulp, which is enough to
         ! flip cc_fig5a's localization station between mirror images
         ! (s* = +-6.83 h, a round-off tie of the symmetric lock)
         rs = 1.0_dp/seq(j)
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
         gs = dp_inc(j)*rs
         a11 = c_e + gs*(1.0_dp - f1**2)
         a22 = c_e + gs*(1.0_dp - f2**2)
         a12 = -c_nu + gs*(-r - f1*f2)
         rdet = 1.0_dp/(a11*a22 - a12*a12)
         x11 = a22*rdet
         x22 = a11*rdet
         x12 = -a12*rdet
         xn1 = x11*f1 + x12*f2
         xn2 = x12*f1 + x22*f2
         rden = 1.0_dp/(f1*xn1 + f2*xn2 + h_end(j))
         c11(j) = x11 - xn1*xn1*rden
         c12(j) = x12 - xn1*xn2*rden
         c22(j) = x22 - xn2*xn2*rden
         ! Continuum tangent (A.1) with alpha = 1, (1,1) entry (eps33 fixed):
         ! D - (D n)(D n)^T / (n^T D n + H').
         xn1 = e_ps*f1 + d12*f2
         xn2 = d12*f1 + e_ps*f2
         ct11(j) = e_ps - xn1**2/(f1*xn1 + f2*xn2 + h_end(j))
         ! Thickness strain, docs/theory.md §4: elastic part from sigma22 = 0, plastic
         ! part from plastic incompressibility of (A.3):
         ! d eps22 = -(nu/E)(d s11 + d s33) - d eps11p - d eps33p.
         dsig1 = sig1(j) - sig_n1(j)
         dsig2 = sig2(j) - sig_n2(j)
         eps22(j) = eps22(j) - c_nu*(dsig1 + dsig2) - dp_inc(j)*(f1 + f2)
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
      ! d eps22 = -(nu/E)(d s11 + d s33) (docs/theory.md §4, no plastic part).
      do k = 1, nblock
         statev(k, isv_eqps) = statev_n(k, isv_eqps)
         statev(k, isv_eps22) = statev_n(k, isv_eps22) &
                                - c_nu*(stress(k, 1) - stress_n(k, 1) + stress(k, 2) - stress_n(k, 2))
         statev(k, isv_sigma33) = stress(k, 2)
         statev(k, isv_tangent) = e_ps
         sse(k) = elastic_energy(stress(k, 1), stress(k, 2), e_mod, nu)
         spd(k) = spd_n(k)
      end do
      ! state variables beyond the law's (a caller's larger statev) pass through
      if (nstatv > n_statev) statev(:, n_statev + 1:) = statev_n(:, n_statev + 1:)
      do j = 1, np
         k = idx(j)
         stress(k, 1) = sig1(j)
         stress(k, 2) = sig2(j)
         statev(k, isv_eqps) = ep_n(j) + dp_inc(j)
         statev(k, isv_eps22) = eps22(j)
         statev(k, isv_sigma33) = sig2(j)
         statev(k, isv_tangent) = ct11(j)
         statev(k, isv_flow_stress) = sy_end(j)
         statev(k, isv_hardening_slope) = h_end(j)
         sse(k) = sse_p(j)
         spd(k) = spd_p(j)
         ddsdde(k, 1, 1) = c11(j)
         ddsdde(k, 2, 1) = c12(j)
         ddsdde(k, 1, 2) = c12(j)
         ddsdde(k, 2, 2) = c22(j)
      end do
   end subroutine umat_block_to
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
   !> Validate the material constants for umat: the elastic constants here,
   !> the hardening law in module hardening (check_law_props).
   !>
   !> props  [in] material constants (module header).
   !> nprops [in] size of props.
   !> Returns '' if valid, otherwise a message naming the first bad entry,
   !> e.g. "props(2) = nu = 0.5: must satisfy -1 < nu < 0.5".
   pure function check_props(props, nprops) result(msg)
      integer, intent(in) :: nprops
      real(dp), intent(in) :: props(nprops)
      character(len=:), allocatable :: msg

      integer :: i

      msg = ''
      if (nprops < ip_law) then
         msg = 'need at least ' // itoa(ip_law) // ' props (E, nu, R, law id), got ' &
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
      if (.not. props(ip_youngs) > 0.0_dp) then
         msg = 'props(' // itoa(ip_youngs) // ') = E = ' // num(props(ip_youngs)) // ': must be > 0'
      else if (.not. (props(ip_poisson) > -1.0_dp .and. props(ip_poisson) < 0.5_dp)) then
         msg = 'props(' // itoa(ip_poisson) // ') = nu = ' // num(props(ip_poisson)) &
               // ': must satisfy -1 < nu < 0.5'
      else if (.not. props(ip_r_value) > 0.0_dp) then
         msg = 'props(' // itoa(ip_r_value) // ') = R = ' // num(props(ip_r_value)) // ': must be > 0'
      else
         msg = check_law_props(props, nprops)
      end if
   end function check_props
end module material_j2
