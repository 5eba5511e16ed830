!> contact -- penalty contact and friction of one sheet station on one tool,
!> (2.18)-(2.23), DESIGN §5-§6.
!>
!> A station at current position p (a Gauss point of the centreline) penetrates
!> a tool by d > 0.  With n the tool's unit normal toward the sheet and t its
!> unit tangent (tools module), the tool pushes the sheet with
!>   f = k d n  -  mu k d f(u_T) sense t                         (2.19), (2.23)
!> per unit reference length (Winkler foundation, k the penalty), where u_T is
!> the distance slid on the tool since the station's contact began (relative
!> to the tool, which may move: p_rel = p - (0, shift)) and f the modified
!> Coulomb law with one reversal (friction module).
!>
!> The Heaviside onset of (2.18) is smoothed over a small penetration delta:
!> the normal pressure is k g(d) with g = d^2/(2 delta) for d < delta and
!> g = d - delta/2 beyond, so the force is C1 in d.  Stations grazing a tool
!> (the sheet lies exactly on both binder faces at full lock) then no longer
!> switch the tangent between 0 and k from one Newton iterate to the next.
!> delta = 0 is the paper's sharp onset.  Penalty energy: k G(d), G' = g.
!>
!> History column ch(n_chist) (model module):
!>   1 active (1: in contact at the last converged state)   2 u_T
!>   3 u_T^m (largest committed u_T)   4 sense of first sliding (+1, -1, 0 unknown)
!>   5,6 position relative to the tool   7 friction dissipation (per ref length)
!>   8 signed penetration d (< 0: the gap)   9 friction traction along t (signed)
!>   10 the tool piece nearest at the last search (a hint that speeds up the
!>      next one; 0 none)

module contact
   use kinds, only: dp
   use tools, only: tool_type, tool_gap
   use friction, only: friction_law
   implicit none
   private
   public :: contact_station, contact_commit, penalty_energy

contains

   !> CONTACT_STATION: contact force on the sheet and its derivative d f/d p.
   !>  tool   [in]  the tool
   !>  shift  [in]  the tool's vertical rigid translation (lower tool: H)
   !>  k      [in]  penalty (force per reference length per unit penetration)
   !>  delta  [in]  smoothing length of the contact onset (0: sharp)
   !>  mu     [in]  friction coefficient
   !>  eps_f  [in]  regularization length eps of (4.3)
   !>  p      [in]  current position of the station
   !>  chn    [in]  converged history
   !>  ch1    [out] trial history
   !>  f      [out] force on the sheet per unit reference length
   !>  kf     [out] d f / d p (non-symmetric with friction)
   pure subroutine contact_station(tool, shift, k, delta, mu, eps_f, p, chn, ch1, f, kf)
      type(tool_type), intent(in) :: tool
      real(dp), intent(in) :: shift, k, delta, mu, eps_f, p(2), chn(:)
      real(dp), intent(out) :: ch1(:), f(2), kf(2, 2)
      real(dp) :: prel(2), d, n(2), t(2), curv, ds, sense, ut, fr, dfr, dslip(2), tt, pn, dpn
      real(dp) :: dut(2)
      integer :: seg
      prel = [p(1), p(2) - shift]
      call tool_gap(tool, prel(1), prel(2), d, n, curv, t, seg, hint=nint(chn(10)))
      f = 0.0_dp
      kf = 0.0_dp
      ch1 = 0.0_dp
      ch1(5:6) = prel
      ch1(7) = chn(7)
      ch1(8) = d
      ch1(10) = real(seg, dp)
      if (d <= 0.0_dp) return
      ch1(1) = 1.0_dp
      ! normal part: f = pn n with pn = k g(d), dd/dp = -n, dn/dp = curv (I - n n^T)
      if (d < delta) then
         pn = k*d*d/(2.0_dp*delta)
         dpn = k*d/delta
      else
         pn = k*(d - 0.5_dp*delta)
         dpn = k
      end if
      f = pn*n
      kf = -dpn*outer(n, n) + pn*curv*outer(t, t)
      ! friction acts once the station's contact history has started, i.e.
      ! it was in contact at the last converged state (DESIGN §6)
      if (mu <= 0.0_dp .or. chn(1) < 0.5_dp) return
      ! friction: slip since the last converged state, measured along t;
      ! d(ds)/dp = t (1 - curv n.(p - p_old)) because t turns on an arc
      ds = dot_product(t, prel - chn(5:6))
      dslip = t*(1.0_dp - curv*dot_product(n, prel - chn(5:6)))
      if (abs(chn(4)) < 0.5_dp) then
         ! in contact, not slid yet: the first non-zero slip sets the sense
         sense = merge(1.0_dp, -1.0_dp, ds >= 0.0_dp)
         ut = abs(ds)
         dut = sense*dslip
      else
         sense = chn(4)
         ut = chn(2) + sense*ds
         dut = sense*dslip
      end if
      ch1(2) = ut
      ch1(3) = chn(3)
      ch1(4) = sense
      call friction_law(ut, chn(3), eps_f, fr, dfr)
      tt = mu*pn*fr*sense
      ch1(9) = tt
      ch1(7) = chn(7) + 0.5_dp*(chn(9) + tt)*ds
      f = f - tt*t
      ! d(tt t)/dp = t (mu sense)(fr dpn dd/dp + pn dfr dut) + tt dt/dp,
      ! dd/dp = -n, dt/dp = -curv n t^T
      kf = kf - mu*sense*outer(t, -fr*dpn*n + pn*dfr*dut) + tt*curv*outer(n, t)
   end subroutine contact_station

   !> CONTACT_COMMIT: at convergence, start or continue a station's history.
   !> A station entering contact starts with u_T = 0 and an unknown sense;
   !> u_T^m keeps the largest committed u_T (the reversal point of (2.21)).
   pure subroutine contact_commit(ch)
      real(dp), intent(inout) :: ch(:)
      if (ch(1) > 0.5_dp) ch(3) = max(ch(3), ch(2))
   end subroutine contact_commit

   !> PENALTY_ENERGY: stored energy k G(d) of a station penetrating by d
   !> (G' = g of the smoothed onset; G = d^2/2 for delta = 0).
   pure function penalty_energy(k, delta, d) result(energy)
      real(dp), intent(in) :: k, delta, d
      real(dp) :: energy
      if (d <= 0.0_dp) then
         energy = 0.0_dp
      else if (d < delta) then
         energy = k*d**3/(6.0_dp*delta)
      else
         energy = k*(0.5_dp*d*d - 0.5_dp*delta*d + delta*delta/6.0_dp)
      end if
   end function penalty_energy

   pure function outer(a, b) result(c)
      real(dp), intent(in) :: a(2), b(2)
      real(dp) :: c(2, 2)
      c(:, 1) = a*b(1)
      c(:, 2) = a*b(2)
   end function outer
end module contact
