!> summary -- the run's findings as 'key = value' lines (summary.txt).
module summary
   use kinds, only: dp
   use deck, only: deck_type
   use section, only: ih_zbar
   use model, only: model_type, state_type
   use analysis, only: run_record, energy_totals
   use output, only: write_summary_line
   implicit none
   private
   public :: write_summary, steady_force

contains

   !> STEADY_FORCE: plateau of N(delta): reached when the sheet has been pulled
   !> at least 3h and N varied by at most 1% of its final value over the last 2h.
   !>  rec     [in]  run record with the pull history
   !>  h       [in]  thickness
   !>  force   [out] final N when steady
   !>  steady  [out] whether a plateau was reached
   pure subroutine steady_force(rec, h, force, steady)
      type(run_record), intent(in) :: rec
      real(dp), intent(in) :: h
      real(dp), intent(out) :: force
      logical, intent(out) :: steady
      integer :: i, n
      real(dp) :: lo, hi
      steady = .false.
      force = 0.0_dp
      n = rec%n_pull
      if (n < 3) return
      if (rec%pull_delta(n) < 3.0_dp*h) return
      lo = rec%pull_force(n); hi = lo
      do i = n, 1, -1
         if (rec%pull_delta(i) < rec%pull_delta(n) - 2.0_dp*h) exit
         lo = min(lo, rec%pull_force(i))
         hi = max(hi, rec%pull_force(i))
      end do
      force = rec%pull_force(n)
      steady = (hi - lo) <= 0.01_dp*abs(force)
   end subroutine steady_force

   !> WRITE_SUMMARY: write summary.txt.
   !>  path [in] file; m, s, d, rec [in] the run; cpu [in] CPU seconds
   subroutine write_summary(path, m, s, d, rec, cpu)
      character(len=*), intent(in) :: path
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      type(deck_type), intent(in) :: d
      type(run_record), intent(in) :: rec
      real(dp), intent(in) :: cpu
      integer :: u, stat
      real(dp) :: h, eh, fsteady, thinning, energy(4), pull_work
      logical :: steady
      character(len=32) :: status
      open (newunit=u, file=path, status='replace', action='write', iostat=stat)
      if (stat /= 0) return
      h = m%thickness
      eh = m%youngs*h
      if (rec%status /= 0) then
         status = 'no_convergence'
      else if (rec%localized) then
         status = 'localized'
      else
         status = 'completed'
      end if
      call steady_force(rec, h, fsteady, steady)
      thinning = 1.0_dp - minval(s%hn(ih_zbar, m%npt, :, :) - s%hn(ih_zbar, 1, :, :))/h
      write (u, '(a)') '# drawbead summary: '//trim(d%title), 'status = '//trim(status)
      write (u, '(a)') 'localization_phase = '//trim(merge(rec%loc_phase, 'none    ', rec%localized))
      call write_summary_line(u, 'delta_cr_over_h', rec%load_cr/h, rec%localized .and. rec%loc_phase == 'pull')
      call write_summary_line(u, 'lock_cr_over_h', rec%load_cr/h, rec%localized .and. rec%loc_phase == 'lock')
      call write_summary_line(u, 's_star_over_h', rec%s_star/h, rec%localized)
      call write_summary_line(u, 'lock_force_over_Eh', rec%lock_force/eh, m%has_tools)
      call write_summary_line(u, 'peak_force_over_Eh', rec%peak_force/eh, rec%n_pull > 0)
      call write_summary_line(u, 'final_force_over_Eh', rec%last_force/eh, rec%n_pull > 0)
      call write_summary_line(u, 'steady_force_over_Eh', fsteady/eh, steady)
      call write_summary_line(u, 'final_lift_over_Eh', rec%last_lift/eh, rec%n_pull > 0 .and. m%has_tools)
      call write_summary_line(u, 'max_thinning', thinning, .true.)
      call write_summary_line(u, 'max_penetration_over_h', rec%max_penetration, m%has_tools)
      call write_summary_line(u, 'final_delta_over_h', merge(rec%pull_delta(max(rec%n_pull, 1)), &
                              0.0_dp, rec%n_pull > 0)/h, .true.)
      ! energy balance: external work = elastic + plastic + penalty + friction
      call energy_totals(m, s, energy)
      call write_summary_line(u, 'energy_external_work', rec%work, .true.)
      call write_summary_line(u, 'energy_elastic', energy(1), .true.)
      call write_summary_line(u, 'energy_plastic', energy(2), .true.)
      call write_summary_line(u, 'energy_penalty', energy(3), .true.)
      call write_summary_line(u, 'energy_friction', energy(4), .true.)
      call write_summary_line(u, 'energy_balance_error', (rec%work - sum(energy))/max(abs(rec%work), tiny(1.0_dp)), &
                              rec%work > 0.0_dp)
      pull_work = rec%work - rec%work_pull_start
      call write_summary_line(u, 'pull_work', pull_work, rec%n_pull > 0)
      call write_summary_line(u, 'pull_energy_balance_error', &
                              (pull_work - sum(energy - rec%energy_pull_start))/max(abs(pull_work), tiny(1.0_dp)), &
                              rec%n_pull > 0 .and. pull_work > 0.0_dp)
      write (u, '(a,i0)') 'increments = ', rec%increments
      write (u, '(a,i0)') 'newton_iterations = ', rec%newton_iterations
      write (u, '(a,i0)') 'cutbacks = ', rec%cutbacks
      call write_summary_line(u, 'cpu_seconds', cpu, .true.)
      close (u)
   end subroutine write_summary
end module summary
