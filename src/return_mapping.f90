!> return_mapping -- the backward-Euler return mapping of the built-in
!> J2/Hill law (module material_j2) onto its yield surface, for a block of
!> material points at once: the local Newton iteration, safeguarded by
!> bisection, with the Taylor finish that saves a hardening-law call.
!> docs/theory.md §4.
module return_mapping
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use hardening, only: flow_stress_block, ip_youngs, ip_poisson, ip_r_value
   implicit none
   private
   public :: return_map_block

   !> local Newton: iteration limit and relative tolerance on the yield
   !> residual |sbar - sigma_y| / sigma_y (quadratic convergence reaches it
   !> in a few iterations; the limit only catches a failing solve).
   integer, parameter :: max_newton = 50
   real(dp), parameter :: tol_newton = 1.0e-12_dp
   !> below this relative residual the last Newton step is taken without a
   !> further hardening-law call (return_map): quadratic convergence puts
   !> the next residual near tol_taylor^2 = 1e-14 < tol_newton.
   real(dp), parameter :: tol_taylor = 1.0e-7_dp
contains

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

      real(dp) :: e_mod, nu, r, k_s, k_t, n_far, n_out, n_bad, ds, dt, rq
      real(dp), dimension(n) :: a_s, a_t, k_eff, gam, gam_lo, gam_hi, g, ep
      integer :: iter, j

      e_mod = props(ip_youngs)
      nu = props(ip_poisson)
      r = props(ip_r_value)/(1.0_dp + props(ip_r_value))
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
            ! q_s and q_t from one division: 1/((1 + gamma k_s)(1 + gamma k_t))
            ds = 1.0_dp + gam(j)*k_s
            dt = 1.0_dp + gam(j)*k_t
            rq = 1.0_dp/(ds*dt)
            q_s(j) = dt*rq
            q_t(j) = ds*rq
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

      real(dp) :: dseq, dg, step, gj, lo, hi, far, near, ek
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
         ! g'(gamma) = sbar' - H' (sbar + gamma sbar'),  sbar' < 0;
         ! dseq = sbar sbar' (no division by sbar).
         dseq = -0.5_dp*(a_s(j)*k_s*q_s(j)**3 + a_t(j)*k_t*q_t(j)**3)
         ! Newton on F = g (1 + gamma k_eff), same root and sign as g:
         ! sbar ~ sbar_tr/(1 + gamma k_eff) makes g strongly convex (plain
         ! Newton from gamma = 0 only halves the error per iteration for
         ! large steps), while F is nearly linear (exactly so for a
         ! perfectly plastic material when k_s = k_t).
         ! F'/(1 + gamma k_eff) = g' + g k_eff/(1 + gamma k_eff); dg is that
         ! times sbar (1 + gamma k_eff) > 0, which keeps its sign, so the
         ! step g/(F'/(1 + gamma k_eff)) = g sbar ek/dg takes one division.
         ek = 1.0_dp + gj*k_eff(j)
         dg = (dseq - h_end(j)*(seq(j)**2 + gj*dseq))*ek + g(j)*k_eff(j)*seq(j)
         step = gj - g(j)*seq(j)*ek/merge(dg, -1.0_dp, dg < 0.0_dp)
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
end module return_mapping
