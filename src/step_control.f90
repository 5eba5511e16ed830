!> step_control -- the size of the next increment of the load parameter
!> (H while locking, delta while pulling): cut back on a Newton failure, redo
!> an increment whose force jumped, grow after easy convergence, shrink
!> after a hard one, resolve fast changes of the phase's force (the
!> closing binder's final squeeze, the first slip over a radius) at about a
!> target relative change per increment, and hold the local error of the
!> path, estimated by the extrapolation of the last two converged states
!> (of the punch force while locking, of the nodal displacements while
!> pulling), to step_tolerance (docs/theory.md §8.3).
module step_control
   use kinds, only: dp
   use phases, only: phase_lock, phase_pull
   use controls, only: controls_type
   implicit none
   private
   public :: judge_force_change, next_increment, cutback_factor, extrapolation_error, judge_error, &
             displacement_error, bound_after_failure, failed_cap, failed_cap_growth, bound_past_section_maximum, &
             branch_early_factor, lock_branch_factor, past_turned_maximum

   !> past a section's maximum load, before the restraining force has turned
   !> toward its maximum (the split at the exit not armed, theory §7.6;
   !> never with refine_neck or a zone of the deck's own), the
   !> increments are at most this many times branch_increment (0.025 h at
   !> its default 0.008 h: the bound before branch_increment existed, and
   !> a step study scales it with the rest): a sheet drawn steadily past
   !> its sections' maxima is not near a tearing point
   !> (bound_past_section_maximum)
   real(dp), parameter :: branch_early_factor = 3.125_dp
   !> while locking past a section's maximum load the increments are at
   !> most this many times branch_increment (0.05 h at its default): the
   !> station distances zbar are updated at each commit (theory §3), so an
   !> increment's thinning strains the fibres of the next one; after an
   !> increment of 0.2 h the attempts that followed it (the last of
   !> locking, then cut-backs) met a residual of 6% of the force scale at
   !> no motion, and the sheet jumped to another branch (theory §8.3)
   !> (bound_past_section_maximum)
   real(dp), parameter :: lock_branch_factor = 6.25_dp
   !> the increment is multiplied by this after a failed or redone increment
   real(dp), parameter :: cutback_factor = 0.25_dp
   !> after a failed attempt of length dt_f the following increments are at
   !> most failed_cap dt_f, the bound growing by failed_cap_growth per
   !> converged increment (bound_after_failure)
   real(dp), parameter :: failed_cap = 0.5_dp, failed_cap_growth = 1.1_dp
   !> an increment whose error estimate exceeds this many times
   !> step_tolerance is redone (its successor would be less than half as long)
   real(dp), parameter :: error_redo_ratio = 4.0_dp
   !> safety factor on the increment the error estimate allows (below it
   !> the increment is shortened)
   real(dp), parameter :: error_safety = 0.8_dp
   !> the error estimate grows an increment by at most this factor
   real(dp), parameter :: max_growth = 2.0_dp

contains

   !> JUDGE_FORCE_CHANGE: the relative change of the phase's force over a
   !> converged increment, the target it is held to, and whether the
   !> increment must be redone smaller.
   !>
   !> The scale of the change is floored at 1e-5 E h.  While locking, F
   !> rising faster than H^5 (its relative change above 5 times that of H)
   !> is the binder squeeze: path dependent, mostly through friction, whose
   !> history is first order in the increment, so it is entered with
   !> squeeze_force_change per increment, and a rise of more than 5 times
   !> that is redone like a jump.  Otherwise a jump of more than half from
   !> an established force (> 1e-4 E h, not the first elastic ramp) is not
   !> resolved and is redone, unless the increment is already within 4
   !> times min_increment.
   !>  ctl         [in]  controls (force-change targets, min_increment)
   !>  phase       [in]  'lock' or 'pull'
   !>  p, dt       [in]  load parameter at the start of the increment, its size
   !>  force       [in]  the phase's force at the end (F locking, N pulling)
   !>  last_force  [in]  the same at the start
   !>  eh          [in]  E h, the force scale
   !>  change      [out] relative change of the force
   !>  target      [out] the change aimed at per increment
   !>  redo        [out] .true.: redo the increment with cutback_factor dt
   pure subroutine judge_force_change(ctl, phase, p, dt, force, last_force, eh, change, target, redo)
      type(controls_type), intent(in) :: ctl
      character(len=*), intent(in) :: phase
      real(dp), intent(in) :: p, dt, force, last_force, eh
      real(dp), intent(out) :: change, target
      logical, intent(out) :: redo
      real(dp) :: jump
      logical :: steep
      change = abs(force - last_force)/max(abs(last_force), abs(force), 1.0e-5_dp*eh)
      steep = phase == phase_lock .and. change > 5.0_dp*dt/(p + dt)
      target = merge(ctl%squeeze_force_change, ctl%max_force_change, steep)
      jump = merge(min(0.5_dp, 5.0_dp*target), 0.5_dp, steep)
      redo = change > jump .and. abs(last_force) > 1.0e-4_dp*eh .and. dt > 4.0_dp*ctl%min_increment
   end subroutine judge_force_change

   !> EXTRAPOLATION_ERROR: the local error estimate of a converged increment:
   !> the distance of the phase's force from its linear extrapolation
   !> through the last two converged states,
   !>   err = |P - P_n - (dt/dt_prev)(P_n - P_(n-1))| / max(|P|, |P_n|, 5e-4 E h),
   !> about (1/2) P'' dt (dt + dt_prev)/P: second order in the increment on
   !> a smooth path, and large where the path turns (a tool face closing on
   !> the sheet, the onset of sliding), which is where the integration of
   !> the path-dependent histories needs short increments (docs/theory.md §8.3).
   !> The floor 5e-4 E h (a fifth of the punch force at full lock of the
   !> paper's beads, 1.9-2.9e-3 E h) holds the error of a small force in
   !> absolute terms: relative to the force itself, the first bending of the
   !> flat sheet (F about H^2) took increments of 0.005h.
   !>  force       [in] P at the end of the increment
   !>  last_force  [in] P_n at its start (the last converged state)
   !>  prev_force  [in] P_(n-1) at the converged state before
   !>  dt, dt_prev [in] the increment and the one before (> 0)
   !>  eh          [in] E h, the force scale
   pure function extrapolation_error(force, last_force, prev_force, dt, dt_prev, eh) result(err)
      real(dp), intent(in) :: force, last_force, prev_force, dt, dt_prev, eh
      real(dp) :: err
      err = abs(force - last_force - (dt/dt_prev)*(last_force - prev_force)) &
            /max(abs(force), abs(last_force), 5.0e-4_dp*eh)
   end function extrapolation_error

   !> DISPLACEMENT_ERROR: the local error estimate of a converged increment
   !> from the nodal displacements: the distance of the converged state from
   !> its linear extrapolation through the last two converged states (the
   !> predictor), relative to the increment's own motion stretched to a load
   !> of h,
   !>   e = |u - u_n - (dt/dt_prev)(u_n - u_(n-1))| dt / (|u - u_n| h),
   !> norms weighted by scale (docs/theory.md §8.3).  On a smooth path u(p)
   !> this is (1/2) (|u''|/|u'|) dt (dt + dt_prev)/h: second order in the
   !> increment like extrapolation_error, zero on a straight path, and
   !> independent of the size of the motion.  A station entering contact or
   !> a small jump between neighbouring equilibrium branches moves a few
   !> nodes by a fraction of the increment's motion, where it moves the
   !> pull force by its whole ±0.5% (which extrapolation_error reads as an
   !> error).  Zero when the increment did not move.
   !>  u           [in] converged displacements at the end of the increment
   !>  u_n         [in] at its start (the last converged state)
   !>  u_prev      [in] at the converged state before
   !>  dt, dt_prev [in] the increment and the one before (> 0)
   !>  h           [in] the length of load that scales the error (the thickness)
   !>  scale       [in] weight of each degree of freedom in the norms
   pure function displacement_error(u, u_n, u_prev, dt, dt_prev, h, scale) result(err)
      real(dp), intent(in) :: u(:), u_n(:), u_prev(:), dt, dt_prev, h, scale(:)
      real(dp) :: err
      real(dp) :: step
      step = norm2(scale*(u - u_n))
      err = 0.0_dp
      if (step <= 0.0_dp) return
      err = norm2(scale*(u - u_n - (dt/dt_prev)*(u_n - u_prev)))*dt/(step*h)
   end function displacement_error

   !> JUDGE_ERROR: whether an increment with the error estimate err must be
   !> redone, and the increment that the estimate allows next.  The error
   !> being second order, the increment that meets step_tolerance is
   !> q dt with q = 0.8 sqrt(tol/err) (0.8 a safety factor), taken within
   !> [cutback_factor, 2] and rounded down to a multiple of 1/32.  Rounded:
   !> err is a difference of nearly equal quantities, known to the Newton
   !> tolerance; an increment sized continuously by it would follow that
   !> noise, and so would the path of the increments and the results (two
   !> builds of the program, whose round-off differs, then disagreed by
   !> 1e-5 where tests/regression holds them to 1e-6).  On the lattice of
   !> 1/32 the noise (about 1e-8 of q) changes the factor only when q lies
   !> that close to a multiple of 1/32.  An estimate above 4 tol is redone,
   !> above tol on the last increment of a phase (final: no later, shorter
   !> increment follows to share the error, and the phase's result, the
   !> punch force at full lock, is read off its end); never within 4
   !> min_increment.  A negative or zero err (no estimate: the first
   !> increment of a phase; a straight path) or step_tolerance = 0 allows
   !> 2 dt.
   !>  ctl     [in]  controls (step_tolerance, min_increment)
   !>  err     [in]  the estimate (extrapolation_error or
   !>                displacement_error), < 0: none
   !>  dt      [in]  the increment just converged
   !>  redo    [out] .true.: redo the increment with dt_err
   !>  dt_err  [out] the increment the estimate allows
   !>  final   [in]  optional, default .false.: the increment ends the phase
   pure subroutine judge_error(ctl, err, dt, redo, dt_err, final)
      type(controls_type), intent(in) :: ctl
      real(dp), intent(in) :: err, dt
      logical, intent(out) :: redo
      real(dp), intent(out) :: dt_err
      logical, intent(in), optional :: final
      real(dp) :: q, ratio
      redo = .false.
      dt_err = max_growth*dt
      if (err <= 0.0_dp .or. ctl%step_tolerance <= 0.0_dp) return
      q = min(max_growth, max(cutback_factor, error_safety*sqrt(ctl%step_tolerance/err)))
      dt_err = (aint(32.0_dp*q)/32.0_dp)*dt
      ratio = error_redo_ratio
      if (present(final)) then
         if (final) ratio = 1.0_dp
      end if
      redo = err > ratio*ctl%step_tolerance .and. dt > 4.0_dp*ctl%min_increment
   end subroutine judge_error

   !> NEXT_INCREMENT: the size of the increment after a converged one.
   !> A force that changed by more than its target scales the increment by
   !> target/change (at least by cutback_factor).  Otherwise, with an error
   !> estimate (dt_err present), the increment it allows, shrunk to 0.6 dt
   !> after 8 or more Newton iterations; without one, 3 Newton iterations or
   !> fewer double it, 4-5 grow it by a quarter, 8 or more shrink it to 0.6.
   !> With shrink = .false. many iterations do not shrink it (past a
   !> section's maximum once the force has turned, past_turned_maximum:
   !> there the iterations do not fall with the increment).
   !> Never above dt_err; always within [min_increment, max_increment].
   !> On the Fig. 9c deck, before the error estimate, the punch force at
   !> full lock was 2.4% below that of a 0.5% target at 10% per increment
   !> in the squeeze, 0.2% at 3%, 0.07% at 2%; with the error estimate
   !> holding the turns of the force path, 4% (the default) keeps it within
   !> 0.12% of a run with every increment quartered.
   !>  ctl         [in]  controls
   !>  dt          [in]  the increment just converged
   !>  change      [in]  relative change of the force over it
   !>  target      [in]  the change aimed at
   !>  force       [in]  the force at its end
   !>  eh          [in]  E h
   !>  iterations  [in]  Newton iterations it took
   !>  dt_err      [in]  optional: the increment the error estimate allows
   !>                    (judge_error)
   !>  shrink      [in]  optional, default .true.: 8 or more iterations
   !>                    shrink the increment
   pure function next_increment(ctl, dt, change, target, force, eh, iterations, dt_err, shrink) result(dt_next)
      type(controls_type), intent(in) :: ctl
      real(dp), intent(in) :: dt, change, target, force, eh
      integer, intent(in) :: iterations
      real(dp), intent(in), optional :: dt_err
      logical, intent(in), optional :: shrink
      real(dp) :: dt_next
      logical :: hard
      hard = iterations >= 8
      if (present(shrink)) hard = hard .and. shrink
      dt_next = dt
      if (change > target .and. abs(force) > 1.0e-4_dp*eh) then
         dt_next = max(cutback_factor, target/change)*dt
      else if (present(dt_err)) then
         dt_next = dt_err
         if (hard) dt_next = min(dt_next, 0.6_dp*dt)
      else if (iterations <= 3) then
         dt_next = 2.0_dp*dt
      else if (iterations <= 5) then
         dt_next = 1.25_dp*dt
      else if (hard) then
         dt_next = 0.6_dp*dt
      end if
      if (present(dt_err)) dt_next = min(dt_next, dt_err)
      dt_next = min(max(dt_next, ctl%min_increment), ctl%max_increment)
   end function next_increment

   !> BOUND_AFTER_FAILURE: the next increment after a converged one, held
   !> below the length of the last failed attempt (docs/theory.md §8.3):
   !> without the bound the step grows straight back to the length that
   !> failed and fails again.
   !>  ctl        [in]    controls (min_increment, max_increment)
   !>  dt         [inout] the next increment (next_increment), bounded by
   !>                     failed_cap dt_failed, not below min_increment
   !>  dt_failed  [inout] the last failed attempt's length (huge: none); it
   !>                     grows by failed_cap_growth, and lapses to huge once
   !>                     failed_cap dt_failed is above max_increment
   pure subroutine bound_after_failure(ctl, dt, dt_failed)
      type(controls_type), intent(in) :: ctl
      real(dp), intent(inout) :: dt, dt_failed
      if (dt_failed >= huge(1.0_dp)) return
      dt = max(min(dt, failed_cap*dt_failed), ctl%min_increment)
      dt_failed = failed_cap_growth*dt_failed
      if (failed_cap*dt_failed > ctl%max_increment) dt_failed = huge(1.0_dp)
   end subroutine bound_after_failure

   !> PAST_SECTION_MAXIMUM: is the sheet, locking or pulling, past a
   !> section's maximum load (the smallest indicator (7.2) of the converged
   !> state at or below 0: a section past its maximum load, under the tool)
   !> with the load-maximum criterion?  There the path is no longer unique
   !> (docs/theory.md §8.3).
   !>  ctl      [in]  controls (tearing criterion)
   !>  min_ind  [in]  the smallest indicator of the converged state
   pure logical function past_section_maximum(ctl, min_ind)
      type(controls_type), intent(in) :: ctl
      real(dp), intent(in) :: min_ind
      past_section_maximum = ctl%tearing_criterion == 'load_maximum' .and. min_ind <= 0.0_dp
   end function past_section_maximum

   !> PAST_TURNED_MAXIMUM: past_section_maximum once the restraining force
   !> has turned toward its maximum.  There Newton's iterations are set by
   !> the thickness points that switch between elastic and plastic from one
   !> iterate to the next, not by the increment's length (docs/theory.md
   !> §8.3: on the clamped decks increments below 1e-3 h took 6.6-7.0
   !> iterations on average, those from 1e-3 h to 4e-3 h 5.3-7.2), so many
   !> iterations do not shrink the next increment (next_increment's
   !> shrink).  The caller applies it with tools only.
   !>  ctl      [in]  controls (tearing criterion)
   !>  phase    [in]  'lock' or 'pull'
   !>  min_ind  [in]  the smallest indicator of the converged state
   !>  turned   [in]  the force has turned toward its maximum (§7.6)
   pure logical function past_turned_maximum(ctl, phase, min_ind, turned)
      type(controls_type), intent(in) :: ctl
      character(len=*), intent(in) :: phase
      real(dp), intent(in) :: min_ind
      logical, intent(in) :: turned
      past_turned_maximum = turned .and. phase == phase_pull .and. past_section_maximum(ctl, min_ind)
   end function past_turned_maximum

   !> BOUND_PAST_SECTION_MAXIMUM: past a section's maximum load
   !> (past_section_maximum) the pull's increment is at most
   !> branch_increment once the restraining force has turned toward its
   !> maximum, and branch_early_factor times it before; the lock's
   !> lock_branch_factor times it (docs/theory.md §8.3): the path is no
   !> longer unique there, and long increments land on another branch than
   !> short ones.  The caller applies it with tools only.
   !>  ctl      [in]    controls (tearing criterion, branch_increment,
   !>                   min_increment)
   !>  phase    [in]    'lock' or 'pull'
   !>  min_ind  [in]    the smallest indicator of the converged state
   !>  turned   [in]    the force has turned toward its maximum (the
   !>                   split at the exit is armed, §7.6)
   !>  dt       [inout] the next increment
   pure subroutine bound_past_section_maximum(ctl, phase, min_ind, turned, dt)
      type(controls_type), intent(in) :: ctl
      character(len=*), intent(in) :: phase
      real(dp), intent(in) :: min_ind
      logical, intent(in) :: turned
      real(dp), intent(inout) :: dt
      real(dp) :: cap
      if (.not. past_section_maximum(ctl, min_ind)) return
      if (phase == phase_lock) then
         cap = lock_branch_factor*ctl%branch_increment
      else
         cap = merge(1.0_dp, branch_early_factor, turned)*ctl%branch_increment
      end if
      dt = max(min(dt, cap), ctl%min_increment)
   end subroutine bound_past_section_maximum

end module step_control
