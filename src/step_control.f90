!> step_control -- the size of the next increment of the load parameter
!> (H while locking, delta while pulling): cut back on a Newton failure, redo
!> an increment whose force jumped, grow after easy convergence, shrink
!> after a hard one, and resolve fast changes of the phase's force (the
!> closing binder's final squeeze, the first slip over a radius) at about a
!> target relative change per increment (docs/theory.md §8.3).
module step_control
   use kinds, only: dp
   use controls, only: controls_type
   implicit none
   private
   public :: judge_force_change, next_increment, cutback_factor

   !> the increment is multiplied by this after a failed or redone increment
   real(dp), parameter :: cutback_factor = 0.25_dp

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
      steep = phase == 'lock' .and. change > 5.0_dp*dt/(p + dt)
      target = merge(ctl%squeeze_force_change, ctl%max_force_change, steep)
      jump = merge(min(0.5_dp, 5.0_dp*target), 0.5_dp, steep)
      redo = change > jump .and. abs(last_force) > 1.0e-4_dp*eh .and. dt > 4.0_dp*ctl%min_increment
   end subroutine judge_force_change

   !> NEXT_INCREMENT: the size of the increment after a converged one.
   !> A force that changed by more than its target scales the increment by
   !> target/change (at least by cutback_factor); otherwise 3 Newton
   !> iterations or fewer double it, 4-5 grow it by a quarter, 8 or more
   !> shrink it to 0.6; always within [min_increment, max_increment].  On
   !> the Fig. 9c deck the punch force at full lock is 2.4% below that of a
   !> 0.5% target at 10% per increment in the squeeze, 0.2% at 3%, 0.07% at
   !> 2% and 0.04% at 1% (1.4 times the locking increments of 2%), hence
   !> the default squeeze_force_change of 2%.
   !>  ctl         [in]  controls
   !>  dt          [in]  the increment just converged
   !>  change      [in]  relative change of the force over it
   !>  target      [in]  the change aimed at
   !>  force       [in]  the force at its end
   !>  eh          [in]  E h
   !>  iterations  [in]  Newton iterations it took
   pure function next_increment(ctl, dt, change, target, force, eh, iterations) result(dt_next)
      type(controls_type), intent(in) :: ctl
      real(dp), intent(in) :: dt, change, target, force, eh
      integer, intent(in) :: iterations
      real(dp) :: dt_next
      dt_next = dt
      if (change > target .and. abs(force) > 1.0e-4_dp*eh) then
         dt_next = max(max(cutback_factor, target/change)*dt, ctl%min_increment)
      else if (iterations <= 3) then
         dt_next = min(2.0_dp*dt, ctl%max_increment)
      else if (iterations <= 5) then
         dt_next = min(1.25_dp*dt, ctl%max_increment)
      else if (iterations >= 8) then
         dt_next = max(0.6_dp*dt, ctl%min_increment)
      end if
   end function next_increment
end module step_control
