!> summary -- the run's findings as 'key = value' lines (summary.txt).
module summary
   use kinds, only: dp
   use phases, only: phase_lock, phase_pull
   use controls, only: controls_type
   use section, only: ih_zbar
   use model, only: model_type, state_type
   use record, only: run_record, run_ok, run_no_convergence, run_interrupted, run_write_failed, &
                     run_out_of_memory
   use energy, only: energy_totals, energy_absorbed, stored_plastic_energy, n_energy, ien_elastic, ien_plastic, &
                     ien_penalty, ien_friction, ien_normal_stress, ien_offset_work
   use output, only: write_text_file
   use tearing, only: neck_unresolved
   use text, only: itoa
   implicit none
   private
   public :: write_summary, steady_force, summary_value

contains

   !> STEADY_FORCE: plateau of N(delta).  The first window [delta - 2h, delta]
   !> (delta >= 3h) over which N varies by at most 3% of its mean is the
   !> steady state (paper Fig. 9: reached by delta ~ 4h); the force is the
   !> window's mean.  A sheet of finite length has no true steady state (its
   !> free end comes closer to the bead), hence the tolerance.
   !>  rec     [in]  run record with the pull history
   !>  h       [in]  thickness
   !>  force   [out] mean N over the first steady window
   !>  at      [out] delta at the end of that window
   !>  steady  [out] whether a plateau was reached
   pure subroutine steady_force(rec, h, force, at, steady)
      type(run_record), intent(in) :: rec
      real(dp), intent(in) :: h
      real(dp), intent(out) :: force, at
      logical, intent(out) :: steady
      integer :: i, j, n, cnt
      real(dp) :: lo, hi, total
      steady = .false.
      force = 0.0_dp
      at = 0.0_dp
      n = rec%n_pull
      do j = 1, n
         if (rec%pull_delta(j) < 3.0_dp*h) cycle
         lo = huge(1.0_dp); hi = -huge(1.0_dp); total = 0.0_dp; cnt = 0
         do i = j, 1, -1
            if (rec%pull_delta(i) < rec%pull_delta(j) - 2.0_dp*h) exit
            lo = min(lo, rec%pull_force(i))
            hi = max(hi, rec%pull_force(i))
            total = total + rec%pull_force(i)
            cnt = cnt + 1
         end do
         if (cnt >= 3 .and. hi - lo <= 0.03_dp*abs(total/cnt)) then
            steady = .true.
            force = total/cnt
            at = rec%pull_delta(j)
            return
         end if
      end do
   end subroutine steady_force

   !> SUMMARY_VALUE: read one 'key = value' line of a summary file back.
   !>  path   [in]  summary.txt
   !>  key    [in]  the key
   !>  found  [out] .false. if the file or key is missing or the value is 'none'
   !>  value  (result) the number, 0 when not found
   function summary_value(path, key, found) result(value)
      character(len=*), intent(in) :: path, key
      logical, intent(out) :: found
      real(dp) :: value
      character(len=256) :: line
      integer :: u, ios, eq
      value = 0.0_dp
      found = .false.
      open (newunit=u, file=path, status='old', action='read', iostat=ios)
      if (ios /= 0) return
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         eq = index(line, '=')
         if (eq == 0 .or. line(1:1) == '#') cycle
         if (trim(adjustl(line(1:eq - 1))) == key) then
            read (line(eq + 1:), *, iostat=ios) value
            found = ios == 0
            if (.not. found) value = 0.0_dp
            exit
         end if
      end do
      close (u)
   end function summary_value

   !> WRITE_SUMMARY: write summary.txt.
   !>  path [in] file; m, s, ctl, rec [in] the run; cpu [in] CPU seconds
   !>  ios  [out] 0, or errno of the failed create, write or close
   !>  iomsg [out] '<path>: <the system's reason>' when ios /= 0
   subroutine write_summary(path, m, s, ctl, rec, cpu, ios, iomsg)
      character(len=*), intent(in) :: path
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      type(controls_type), intent(in) :: ctl
      type(run_record), intent(in) :: rec
      real(dp), intent(in) :: cpu
      integer, intent(out) :: ios
      character(len=:), allocatable, intent(out) :: iomsg
      character(len=:), allocatable :: text
      real(dp) :: h, eh, fsteady, steady_at, thinning, energy(n_energy), pull_work, de(n_energy), stored
      logical :: split
      logical :: steady
      character(len=32) :: status
      ! (allocate, not text = '': gfortran 12 then warns that text may be
      ! used uninitialized)
      allocate (character(len=0) :: text)
      h = m%thickness
      eh = m%youngs*h
      if (rec%status == run_no_convergence) then
         status = 'no_convergence'
      else if (rec%status == run_interrupted) then
         status = 'interrupted'
      else if (rec%status == run_write_failed) then
         status = 'write_failed'
      else if (rec%status == run_out_of_memory) then
         status = 'out_of_memory'
      else if (rec%torn .and. ctl%tearing_criterion == 'load_maximum') then
         status = 'torn'
      else if (rec%localized) then
         status = 'localized'
      else
         status = 'completed'
      end if
      call steady_force(rec, h, fsteady, steady_at, steady)
      ! (a state that could not be allocated, status out_of_memory: the
      ! flat, unloaded sheet)
      thinning = 0.0_dp
      if (allocated(s%hn)) thinning = 1.0_dp - minval(s%hn(m%npt, ih_zbar, :, :) - s%hn(1, ih_zbar, :, :))/h
      call add(text, '# drawbead summary: '//trim(ctl%title))
      call add(text, 'status = '//trim(status))
      call add(text, 'localization_phase = '// &
         trim(merge(rec%loc_phase, 'none    ', rec%localized)))
      call put(text, 'delta_cr_over_h', rec%load_cr/h, rec%localized .and. rec%loc_phase == phase_pull)
      call put(text, 'lock_cr_over_h', rec%load_cr/h, rec%localized .and. rec%loc_phase == phase_lock)
      call put(text, 's_star_over_h', rec%s_star/h, rec%localized)
      ! the mesh-objective tearing measure: mid-surface strain averaged over
      ! tearing_length reaching the plane-strain maximum-load strain
      call add(text, 'nonlocal_localization_phase = '// &
         trim(merge(rec%nl_phase, 'none    ', rec%nl_localized)))
      call put(text, 'delta_cr_nonlocal_over_h', rec%nl_load_cr/h, &
                              rec%nl_localized .and. rec%nl_phase == phase_pull)
      call put(text, 'lock_cr_nonlocal_over_h', rec%nl_load_cr/h, &
                              rec%nl_localized .and. rec%nl_phase == phase_lock)
      call put(text, 's_star_nonlocal_over_h', rec%nl_s_star/h, rec%nl_localized)
      ! the program's tearing prediction (docs/theory.md §7.4): the load
      ! parameter is H while locking and delta while pulling
      call add(text, 'tearing_criterion = '//trim(ctl%tearing_criterion))
      call add(text, 'tearing_phase = '//trim(merge(rec%tear_phase, 'none    ', rec%torn)))
      call put(text, 'tearing_delta_over_h', rec%tear_load/h, rec%torn .and. rec%tear_phase == phase_pull)
      call put(text, 'tearing_lock_over_h', rec%tear_load/h, rec%torn .and. rec%tear_phase == phase_lock)
      call put(text, 'tearing_s_over_h', rec%tear_s/h, rec%torn)
      call put(text, 'tearing_element_over_h', rec%tear_element/h, rec%torn .and. rec%tear_element > 0.0_dp)
      call put(text, 'tearing_length_over_h', ctl%tearing_length_over_h, .true.)
      ! the paper's pointwise criterion has no mesh limit (§7.1); the load
      ! maximum converges on elements of m%neck_element at the neck (§7.6)
      if (.not. rec%torn) then
         call add(text, 'tearing_mesh_dependent = none')
      else if (ctl%tearing_criterion == 'section' .or. neck_unresolved(m, rec)) then
         call add(text, 'tearing_mesh_dependent = yes')
      else
         call add(text, 'tearing_mesh_dependent = no')
      end if
      call put(text, 'stopped_past_tearing_over_h', rec%stopped_past_tear_load/h, rec%stopped_past_tear)
      call put(text, 'max_load_strain', m%max_load_strain, m%max_load_strain < 1.0e6_dp)
      ! the first state bent tighter than fold_curvature: past it the forces
      ! depend on the mesh (a hinge one or two elements wide)
      call add(text, 'fold_phase = '// &
         trim(merge(rec%fold_phase, 'none    ', rec%folded)))
      call put(text, 'fold_load_over_h', rec%fold_load/h, rec%folded)
      call put(text, 's_fold_over_h', rec%fold_s/h, rec%folded)
      call put(text, 'fold_curvature', ctl%fold_curvature, .true.)
      call put(text, 'lock_force_over_Eh', rec%lock_force/eh, m%has_tools)
      call put(text, 'peak_force_over_Eh', rec%peak_force/eh, rec%n_pull > 0)
      call put(text, 'final_force_over_Eh', merge(rec%pull_force(max(rec%n_pull, 1)), 0.0_dp, rec%n_pull > 0)/eh, &
               rec%n_pull > 0)
      call put(text, 'steady_force_over_Eh', fsteady/eh, steady)
      call put(text, 'steady_reached_at_delta_over_h', steady_at/h, steady)
      call put(text, 'final_lift_over_Eh', rec%last_lift/eh, rec%n_pull > 0 .and. m%has_tools)
      call put(text, 'max_thinning', thinning, .true.)
      call put(text, 'max_penetration_over_h', rec%max_penetration, m%has_tools)
      call put(text, 'final_delta_over_h', merge(rec%pull_delta(max(rec%n_pull, 1)), &
                              0.0_dp, rec%n_pull > 0)/h, .true.)
      ! energy balance: external work + normal-stress work - offset work =
      ! elastic + plastic + penalty + friction (energy_totals)
      energy = 0.0_dp
      if (allocated(s%hn)) call energy_totals(m, s, energy)
      call put(text, 'energy_external_work', rec%work, .true.)
      call put(text, 'energy_elastic', energy(ien_elastic), .true.)
      call put(text, 'energy_plastic', energy(ien_plastic), .true.)
      ! of it stored by the back stresses (kinematic hardening), the rest
      ! dissipated; only for a law that can store energy (the summaries of
      ! the others keep their keys)
      if (m%material%stores_energy()) then
         stored = 0.0_dp
         if (allocated(s%hn)) stored = stored_plastic_energy(m, s)
         call put(text, 'energy_plastic_stored', stored, .true.)
      end if
      call put(text, 'energy_penalty', energy(ien_penalty), .true.)
      call put(text, 'energy_friction', energy(ien_friction), .true.)
      call put(text, 'energy_normal_stress', energy(ien_normal_stress), .true.)
      call put(text, 'energy_offset_work', energy(ien_offset_work), m%current_faces)
      ! (the splits' share of the energies is booked apart, theory §7.6)
      call put(text, 'energy_balance_error', (rec%work - energy_absorbed(energy) + rec%split%energy_change) &
                              /max(abs(rec%work), tiny(1.0_dp)), rec%work > 0.0_dp)
      pull_work = rec%work - rec%work_pull_start
      de = energy - rec%energy_pull_start
      call put(text, 'pull_work', pull_work, rec%n_pull > 0)
      call put(text, 'pull_energy_balance_error', &
                              (pull_work - energy_absorbed(de) + rec%split%energy_change) &
                              /max(abs(pull_work), tiny(1.0_dp)), &
                              rec%n_pull > 0 .and. pull_work > 0.0_dp)
      ! the neck's refined zone (&sheet refine_neck, docs/theory.md §7.5)
      call add(text, 'neck_refinement = '//trim(rec%neck%refinement))
      call put(text, 'coarse_tearing_delta_over_h', rec%neck%coarse_tear_load/h, rec%neck%coarse_torn)
      call put(text, 'coarse_tearing_s_over_h', rec%neck%coarse_tear_s/h, rec%neck%coarse_torn)
      call put(text, 'neck_zone_from_over_h', rec%neck%zone(1)/h, rec%neck%refinement == 'zone')
      call put(text, 'neck_zone_to_over_h', rec%neck%zone(2)/h, rec%neck%refinement == 'zone')
      if (rec%neck%coarse_elements > 0) then
         call add(text, 'coarse_elements = '//itoa(rec%neck%coarse_elements))
         call add(text, 'coarse_assemblies = '//itoa(rec%neck%coarse_assemblies))
      else
         call add(text, 'coarse_elements = none')
         call add(text, 'coarse_assemblies = none')
      end if
      ! the elements split at the exit of the last radius (docs/theory.md §7.6)
      split = rec%split%count > 0
      if (split) then
         call add(text, 'split_phase = '//trim(rec%split%phase))
      else
         call add(text, 'split_phase = none')
      end if
      call put(text, 'split_load_over_h', rec%split%load/h, split)
      call put(text, 'split_exit_x_over_h', rec%split%x_exit/h, split)
      call put(text, 'split_from_over_h', rec%split%zone(1)/h, split)
      call put(text, 'split_to_over_h', rec%split%zone(2)/h, split)
      call put(text, 'split_force_change', rec%split%force_change, split)
      call add(text, 'split_count = '//itoa(rec%split%count))
      call put(text, 'split_energy_change', rec%split%energy_change, split)
      if (split) then
         call add(text, 'split_elements_before = '//itoa(rec%split%elements_before))
      else
         call add(text, 'split_elements_before = none')
      end if
      call put(text, 'split_abandoned_over_h', rec%split%abandoned_load/h, rec%split%abandoned)
      call add(text, 'increments = '//itoa(rec%increments))
      call add(text, 'newton_iterations = '//itoa(rec%newton_iterations))
      call add(text, 'cutbacks = '//itoa(rec%cutbacks))
      call add(text, 'assemblies = '//itoa(rec%assemblies))
      ! the model's count: with a refined zone more than the deck's n_elements
      call add(text, 'elements = '//itoa(m%n_el))
      call put(text, 'cpu_seconds', cpu, .true.)
      call write_text_file(path, text, ios, iomsg)
   end subroutine write_summary

   !> PUT: append one 'key = value' line with a real value, or 'none' if
   !> absent.
   !>  text   [in,out] the summary so far
   !>  key    [in]     the key
   !>  value  [in]     the value
   !>  present_flag [in] .false.: write 'none'
   pure subroutine put(text, key, value, present_flag)
      character(len=:), allocatable, intent(inout) :: text
      character(len=*), intent(in) :: key
      real(dp), intent(in) :: value
      logical, intent(in) :: present_flag
      character(len=32) :: buf
      if (present_flag) then
         write (buf, '(es24.16e3)') value
         call add(text, key//' = '//trim(adjustl(buf)))
      else
         call add(text, key//' = none')
      end if
   end subroutine put

   !> ADD: append one line to the summary.
   !>  text  [in,out] the summary so far
   !>  line  [in]     the line, without its end
   pure subroutine add(text, line)
      character(len=:), allocatable, intent(inout) :: text
      character(len=*), intent(in) :: line
      text = text//line//achar(10)
   end subroutine add
end module summary
