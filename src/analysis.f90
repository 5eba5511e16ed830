!> analysis -- the driver of a run's phases: the boundary conditions of
!> each phase and the increment loop, a stepper with named hooks.
!>
!> Phase 'lock': the lower tool rises by H (load parameter), right edge held.
!> Phase 'pull': tools held at H = lock depth, right edge pulled by delta.
!> Left edge clamped (v = w = w' = 0) or free (w = w' = 0, axial force
!> -back_tension applied).  docs/theory.md §1, §8.1.
!>
!> Per increment (run_phase, docs/theory.md §8): solve_increment (the
!> predictor, Newton, and a cutback or redo of an attempt that failed,
!> jumped or erred, §8.2-8.3), commit_increment (§8.4), the records
!> (stepper's record_increment), check_criteria (§7.1-7.4), write_rows (the
!> result files), console_line, ends_run (a failed write, a signal,
!> tearing), the neck's refinement when stepper's decide_split says so
!> (split_at_exit: the mesh changed by module remesh, §7.6) and the next
!> increment (§8.3).  The loop's state is stepper's phase_run.
module analysis
   use kinds, only: dp, output_unit
   use phases, only: phase_lock, phase_pull
   use errors, only: warn
   use text, only: num, itoa
   use hermite, only: n_gauss
   use band, only: band_error_message
   use mesh, only: node_dof, dof_v, dof_w, dof_w_slope
   use model, only: model_type, state_type, load_type, load_init
   use contact, only: ich_penetration
   use controls, only: controls_type
   use record, only: run_record, run_ok, run_no_convergence, run_interrupted, run_write_failed, &
                     run_out_of_memory, split_note, split_record
   use remesh, only: last_radius_exit, exit_pieces, split_elements, split_field, split_stations, &
                     exit_zone_before, reequilibrate, reequilibration, reeq_material, reeq_no_equilibrium, &
                     reeq_out_of_memory
   use solver, only: newton_solve, commit_state, newton_ok, newton_solve_failed, newton_result
   use step_control, only: judge_force_change, cutback_factor, extrapolation_error, judge_error, &
                           displacement_error
   use tearing, only: check_localization, check_fold, check_load_maximum, tear_at_snap_back, &
                      element_length_at
   use energy, only: energy_totals, energy_absorbed, n_energy
   use output, only: output_files, write_row, write_strains, write_snapshot, write_progress
   use os, only: stop_requested, signal_name
   use tools, only: tool_level
   use stepper, only: phase_run, phase_run_init, phase_run_follow, predict, read_forces, record_increment, &
                      watches_maximum, stop_at_tearing, decide_split, note_split, records_after_split, &
                      snapshot_due, next_snapshot, failure_tag, size_next_increment
   implicit none
   private
   public :: run_phase, phase_load

   !> solve_increment's outcome: the attempt converged and is accepted; it
   !> is to be tried again (shorter); the phase ends (rec%status says why)
   integer, parameter :: attempt_accepted = 0, attempt_retry = 1, attempt_stop = 2

contains

   !> PHASE_LOAD: boundary conditions and loads of a phase at load parameter p.
   !>  m      [in]  model (edges, back tension, lock depth)
   !>  phase  [in]  'lock' (p = H) or 'pull' (p = delta)
   !>  p      [in]  load parameter, mm
   !>  ld     [out] the load
   subroutine phase_load(m, phase, p, ld)
      type(model_type), intent(in) :: m
      character(len=*), intent(in) :: phase
      real(dp), intent(in) :: p
      type(load_type), intent(out) :: ld
      integer :: last
      call load_init(m, ld)
      last = m%n_nodes
      ! left edge: w, w' held; v held (clamped) or under the back tension
      ld%fixed(node_dof(1, dof_w)) = .true.
      ld%fixed(node_dof(1, dof_w_slope)) = .true.
      if (m%left_edge_free) then
         ld%f_ext(node_dof(1, dof_v)) = -m%back_tension
      else
         ld%fixed(node_dof(1, dof_v)) = .true.
      end if
      ! right edge: v, w, w'
      ld%fixed(node_dof(last, dof_v)) = .true.
      ld%fixed(node_dof(last, dof_w)) = .true.
      ld%fixed(node_dof(last, dof_w_slope)) = .true.
      if (phase == phase_pull) then
         ld%u_fixed(node_dof(last, dof_v)) = p
         ld%tool_shift = m%lock_depth
      else
         ld%tool_shift = p
      end if
      ! the edges sit on the binder: at y = 0 unless the lower tool's face
      ! under an edge has risen above it (a lock step), never above the upper
      if (m%has_tools) then
         ld%u_fixed(node_dof(1, dof_w)) = edge_height(m, m%x(1), ld%tool_shift)
         ld%u_fixed(node_dof(last, dof_w)) = edge_height(m, m%x(last), ld%tool_shift)
      end if
   end subroutine phase_load

   !> EDGE_HEIGHT: where a sheet edge is held: on the lower tool's face if it
   !> has risen above y = 0 (the level of the flat sheet), else at y = 0,
   !> and never above the upper tool's face (v, w, w' held; for the paper's
   !> beads both faces meet at y = 0 at full lock, so w = 0).
   !>  m      [in]  model with tools
   !>  x      [in]  reference abscissa of the edge
   !>  shift  [in]  the lower tool's rise H
   pure function edge_height(m, x, shift) result(w)
      type(model_type), intent(in) :: m
      real(dp), intent(in) :: x, shift
      real(dp) :: w
      w = min(max(tool_level(m%tool(2), x) + shift, 0.0_dp), tool_level(m%tool(1), x))
   end function edge_height


   !> RUN_PHASE: advance the load parameter from p0 to p1 with adaptive
   !> increments (docs/theory.md §8); after each converged increment the
   !> records, the criteria, a row of output and a console line; the neck's
   !> refinement when due (§7.6).  The hooks are named in the module header.
   !>  m     [in,out] model (its elements split while pulling, §7.6)
   !>  ctl   [in]  controls (increments, tolerances, criteria, output)
   !>  s     [in,out] state, converged at p0 on entry
   !>  phase [in]  phase_lock or phase_pull
   !>  p0,p1 [in]  start and end of the load parameter, mm
   !>  out   [in,out] open output files (snapshots.dat counts its blocks)
   !>  rec   [in,out] run record
   subroutine run_phase(m, ctl, s, phase, p0, p1, out, rec)
      type(model_type), intent(inout) :: m
      type(controls_type), intent(in) :: ctl
      type(state_type), intent(inout) :: s
      character(len=*), intent(in) :: phase
      real(dp), intent(in) :: p0, p1
      type(output_files), intent(inout) :: out
      type(run_record), intent(inout) :: rec
      type(phase_run) :: pr
      integer :: outcome
      logical :: ends, split_due
      call phase_run_init(pr, m, ctl, s, phase, p0, p1, rec)
      if (rec%status /= run_ok) return
      do while (pr%p < p1 - 1.0e-12_dp*pr%h)
         call solve_increment(pr, m, ctl, s, rec, outcome)
         if (outcome == attempt_stop) return
         if (outcome == attempt_retry) cycle
         call commit_increment(pr, m, s, rec)
         call record_increment(pr, s, watches_maximum(m, ctl, phase), rec)
         call check_criteria(pr, m, ctl, s, rec)
         call write_rows(pr, m, ctl, s, rec, out)
         call console_line(pr, ctl, rec)
         call ends_run(pr, ctl, out, rec, ends)
         if (ends) return
         call decide_split(m, s, phase, rec, split_due)
         if (split_due) then
            call split_at_exit(pr, m, ctl, s, rec)
            if (rec%status /= run_ok) return
         end if
         call size_next_increment(pr, ctl, m%has_tools, rec%split%armed)
      end do
   end subroutine run_phase

   !> SOLVE_INCREMENT: one attempt at the next increment, pr%dt (cut to the
   !> phase's end): the phase's load at p + dt, the predictor, Newton
   !> (§8.2); a failed solve is cut back (failed_attempt); a converged one
   !> has its forces read and is judged (judge_attempt: a force jump or a
   !> local error too large is redone, §8.3).
   !>  pr       [in,out] the loop's state: dt, ld, nr, r, the forces
   !>  m        [in]     model
   !>  ctl      [in]     controls
   !>  s        [in,out] the trial state (u1 back at u after a cutback)
   !>  rec      [in,out] counts; status and message when the phase ends
   !>  outcome  [out]    attempt_accepted, attempt_retry or attempt_stop
   subroutine solve_increment(pr, m, ctl, s, rec, outcome)
      type(phase_run), intent(inout) :: pr
      type(model_type), intent(in) :: m
      type(controls_type), intent(in) :: ctl
      type(state_type), intent(inout) :: s
      type(run_record), intent(inout) :: rec
      integer, intent(out) :: outcome
      pr%dt = min(pr%dt, pr%p1 - pr%p)
      call phase_load(m, pr%phase, pr%p + pr%dt, pr%ld)
      call predict(pr, ctl, s)
      call newton_solve(m, s, pr%ld, pr%kb, pr%r, ctl%max_iterations, ctl%tolerance, pr%nr, &
                        count_states=ctl%log_residuals)
      rec%newton_iterations = rec%newton_iterations + pr%nr%iterations
      pr%row_iterations = pr%row_iterations + pr%nr%iterations
      rec%assemblies = rec%assemblies + pr%nr%assemblies
      if (pr%nr%status /= newton_ok) then
         call failed_attempt(pr, m, ctl, s, rec, outcome)
         return
      end if
      call read_forces(pr, s)
      call judge_attempt(pr, ctl, s, rec, outcome)
   end subroutine solve_increment

   !> FAILED_ATTEMPT: Newton failed (§8.2, §8.3): the increment is cut back
   !> by cutback_factor and its length bounds the next ones; a failure of
   !> the linear solve itself, or an increment below min_increment, ends the
   !> phase with no_convergence -- unless, pulling with stop_at_localization,
   !> the paper's criterion has been met: past tearing the sheet may have no
   !> nearby equilibrium, and the run ends there (past a maximum of the
   !> restraining force the maximum is then the tearing point, the
   !> snap-back of a forming neck, §7.4).  A lock that stops short ends
   !> with no_convergence unless its tearing point has been found: the
   !> pull would start from a bead not closed.
   !>  pr       [in,out] the loop's state: dt, dt_failed
   !>  m        [in]     model
   !>  ctl      [in]     controls
   !>  s        [in,out] u1 back at the converged u
   !>  rec      [in,out] cutbacks; status, message, the tearing point
   !>  outcome  [out]    attempt_retry or attempt_stop
   subroutine failed_attempt(pr, m, ctl, s, rec, outcome)
      type(phase_run), intent(inout) :: pr
      type(model_type), intent(in) :: m
      type(controls_type), intent(in) :: ctl
      type(state_type), intent(inout) :: s
      type(run_record), intent(inout) :: rec
      integer, intent(out) :: outcome
      logical :: snapped
      rec%cutbacks = rec%cutbacks + 1
      write (output_unit, '(a5,1x,a,es10.3,a,i3,a,es9.2,2a)') pr%phase, 'cutback  d/h=', pr%dt/pr%h, &
         '  it', pr%nr%iterations, '  res', pr%nr%residual(max(pr%nr%iterations - 1, 0)), '  ', &
         trim(failure_tag(pr%nr))
      outcome = attempt_stop
      if (pr%nr%status == newton_solve_failed) then
         ! not a property of the increment: cutting it back cannot help
         rec%message = 'in '//pr%phase//': '//band_error_message(pr%nr%solve_info)
         rec%status = run_no_convergence
         return
      end if
      ! right after a split the attempts fail on the mapped state, not on
      ! their length (theory §8.3): they do not bound the increments after
      if (.not. pr%settling) pr%dt_failed = pr%dt
      pr%dt = cutback_factor*pr%dt
      s%u1 = s%u
      if (pr%dt < ctl%min_increment) then
         write (rec%message, '(3a,es10.3,a)') 'no convergence in ', pr%phase, &
            ' at load/h = ', pr%p/pr%h, ': increment below min_increment'
         if (contact_chatter(m, pr%nr)) rec%message = trim(rec%message)//'; the stations in contact kept '// &
            'changing ('//itoa(pr%nr%contact_changes)//' of the last attempt''s '//itoa(pr%nr%iterations)// &
            ' iterations): a sheet grazing a tool over a long span with the sharp contact onset; '// &
            '&tools contact_smoothing = 0.001 (h) lets it converge (docs/theory.md §5)'
         if (ctl%stop_at_localization) then
            ! a pull past the paper's criterion ends where it is (at the
            ! snap-back's tearing point past the force's maximum); a lock
            ! stopped short is no state to pull from: only a tearing point
            ! (confirmed on the last converged state) ends it, and the pull
            ! is then not run
            if (pr%phase == phase_pull) then
               if (watches_maximum(m, ctl, pr%phase)) call tear_at_snap_back(m, s, pr%phase, rec, snapped)
               if (rec%localized) return
            else if (rec%torn) then
               return
            end if
         else if (rec%torn .and. pr%phase == phase_pull .and. ctl%tearing_criterion == 'load_maximum') then
            ! a run asked to go on past its tearing point: past the
            ! load maximum the neck thins on (theory §12.7) until the
            ! shell finds no equilibrium; the sheet has torn, and the run
            ! ends there with its results (theory §7.4)
            rec%stopped_past_tear = .true.
            rec%stopped_past_tear_load = pr%p
            call warn('no equilibrium at pull/h = '//num(pr%p/pr%h)//', past the tearing point (at '// &
                      trim(rec%tear_phase)//'/h = '//num(rec%tear_load/pr%h)//'): the neck has thinned '// &
                      'further than the shell follows; the run ends there, torn (docs/theory.md §7.4)', &
                      'failed_attempt')
            return
         end if
         rec%status = run_no_convergence
         return
      end if
      outcome = attempt_retry
   end subroutine failed_attempt

   !> CONTACT_CHATTER: did a failed Newton solve chatter between contact
   !> sets (docs/theory.md §5)?  With the sharp onset (contact_smoothing =
   !> 0) a sheet lying on a tool face at zero gap over many stations can
   !> have its stations switch in and out of contact from one iterate to
   !> the next without end; most iterations of such a solve change the
   !> number of stations in contact.
   !>  m   [in]  model
   !>  nr  [in]  the failed solve
   pure logical function contact_chatter(m, nr)
      type(model_type), intent(in) :: m
      type(newton_result), intent(in) :: nr
      contact_chatter = m%has_tools .and. .not. m%contact_smoothing > 0.0_dp .and. &
                        nr%iterations >= 6 .and. 2*nr%contact_changes >= nr%iterations
   end function contact_chatter

   !> JUDGE_ATTEMPT: a converged attempt is redone shorter when its force
   !> jumped (step_control's judge_force_change) or its local error is too
   !> large (§8.3): locking, that of the punch force (smooth, the result
   !> read at full lock); pulling, that of the displacements (the pull force
   !> carries a noise of stations entering contact and small branch jumps).
   !> A redo shortens the increment by q < 0.8 and a second-order estimate
   !> by at least as much (by q^2 without an earlier increment): one that
   !> kept more than half of its value marks a jump of the path (the state
   !> moving to a neighbouring branch), which no shorter increment
   !> resolves; it is taken as it is.
   !>  pr       [in,out] the loop's state: force_change, target, err, dt_err,
   !>                    err_redone; dt when redone
   !>  ctl      [in]     controls
   !>  s        [in,out] u1 back at the converged u when redone
   !>  rec      [in,out] cutbacks
   !>  outcome  [out]    attempt_accepted or attempt_retry
   subroutine judge_attempt(pr, ctl, s, rec, outcome)
      type(phase_run), intent(inout) :: pr
      type(controls_type), intent(in) :: ctl
      type(state_type), intent(inout) :: s
      type(run_record), intent(inout) :: rec
      integer, intent(out) :: outcome
      logical :: redo
      outcome = attempt_retry
      call judge_force_change(ctl, pr%phase, pr%p, pr%dt, pr%force, rec%last_conjugate, pr%eh, &
                              pr%force_change, pr%target, redo)
      if (redo) then
         rec%cutbacks = rec%cutbacks + 1
         write (output_unit, '(a5,1x,a,es10.3,a,f6.2)') pr%phase, 'cutback  d/h=', pr%dt/pr%h, &
            '  force jump', pr%force_change
         pr%dt = cutback_factor*pr%dt
         s%u1 = s%u
         return
      end if
      pr%err = -1.0_dp
      if (pr%phase == phase_lock) then
         if (pr%have_force_prev) pr%err = extrapolation_error(pr%force, rec%last_conjugate, pr%prev_conjugate, &
                                                              pr%dt, pr%dt_prev, pr%eh)
      else if (pr%have_prev) then
         pr%err = displacement_error(s%u1, s%u, pr%u_prev, pr%dt, pr%dt_prev, pr%h, pr%dof_scale)
      end if
      call judge_error(ctl, pr%err, pr%dt, redo, pr%dt_err, &
                       final=pr%phase == phase_lock .and. pr%p + pr%dt >= pr%p1 - 1.0e-12_dp*pr%h)
      if (redo .and. pr%err_redone > 0.0_dp) redo = pr%err <= 0.5_dp*pr%err_redone
      if (redo) then
         pr%err_redone = pr%err
         rec%cutbacks = rec%cutbacks + 1
         write (output_unit, '(a5,1x,a,es10.3,a,es9.2)') pr%phase, 'cutback  d/h=', pr%dt/pr%h, &
            '  error', pr%err
         pr%dt = pr%dt_err
         s%u1 = s%u
         return
      end if
      pr%err_redone = -1.0_dp
      outcome = attempt_accepted
   end subroutine judge_attempt

   !> COMMIT_INCREMENT: the accepted attempt becomes the converged state
   !> (§8.4); the converged dofs and indicator before it are kept (the
   !> predictor, the error estimate, the work and the paper's criterion
   !> read them).
   !>  pr   [in,out] p advanced; u_prev, ind_old, dt_prev
   !>  m    [in]     model
   !>  s    [in,out] committed
   !>  rec  [in,out] increments
   subroutine commit_increment(pr, m, s, rec)
      type(phase_run), intent(inout) :: pr
      type(model_type), intent(in) :: m
      type(state_type), intent(inout) :: s
      type(run_record), intent(inout) :: rec
      pr%ind_old = s%indicator
      pr%u_prev = s%u
      pr%dt_prev = pr%dt
      call commit_state(m, s, pr%ld%tool_shift)
      pr%p = pr%p + pr%dt
      pr%settling = .false.
      rec%increments = rec%increments + 1
   end subroutine commit_increment

   !> CHECK_CRITERIA: what the converged state says (after its records):
   !> the penetration (above 0.05h the penalty is too soft for the forces
   !> at hand, §5: warned once per run), the fold check (§7.3), the paper's
   !> and the averaged-strain criteria (§7.1, §7.2), with tearing_criterion
   !> = 'section' the paper's tearing point (no mesh limit in this model,
   !> §7.1: said once), and the load maximum of the watched force (§7.4).
   !>  pr   [in,out] pen, min_ind, paper_met, nl_old
   !>  m    [in]     model
   !>  ctl  [in]     controls
   !>  s    [in]     the converged state
   !>  rec  [in,out] what the criteria found
   subroutine check_criteria(pr, m, ctl, s, rec)
      type(phase_run), intent(inout) :: pr
      type(model_type), intent(in) :: m
      type(controls_type), intent(in) :: ctl
      type(state_type), intent(in) :: s
      type(run_record), intent(inout) :: rec
      character(len=200) :: msg
      pr%pen = 0.0_dp
      if (m%has_tools) pr%pen = max(0.0_dp, maxval(s%cn(ich_penetration, :, :, :)))/pr%h
      if (pr%pen > 0.05_dp .and. rec%max_penetration <= 0.05_dp) then
         write (msg, '(a,es9.3,a,es10.3,a)') 'penetration ', pr%pen, 'h > 0.05h at load/h = ', &
            pr%p/pr%h, ' in '//pr%phase//': raise &tools penalty'
         call warn(msg, 'run_phase')
      end if
      rec%max_penetration = max(rec%max_penetration, pr%pen)
      call check_fold(m, s, pr%phase, pr%p, ctl%fold_curvature, rec)
      pr%min_ind = minval(s%indicator)
      call check_localization(m, s, pr%phase, pr%p, pr%dt, pr%ind_old, pr%nl_old, pr%ell, rec, pr%paper_met)
      if (pr%paper_met .and. ctl%tearing_criterion == 'section') then
         rec%torn = .true.
         rec%tear_phase = rec%loc_phase
         rec%tear_load = rec%load_cr
         rec%tear_s = rec%s_star
         rec%tear_element = element_length_at(m, rec%s_star)
         call warn('tearing point by the paper''s pointwise criterion (tearing_criterion = ''section''): '// &
                   'it has no mesh limit in this model and moves with the mesh (docs/theory.md §7.1)', 'run_phase')
      end if
      if (watches_maximum(m, ctl, pr%phase)) call check_load_maximum(m, s, pr%phase, rec)
   end subroutine check_criteria

   !> WRITE_ROWS: the increment's output: the strain field where the
   !> paper's criterion was first met (strain_localization.dat), a row of
   !> lock.dat or pull.dat (columns declared in module output), a strain
   !> snapshot when due, and summary.txt's progress (last, so that a run
   !> killed at any moment leaves a true summary beside its files).
   !>  pr   [in,out] next_snapshot
   !>  m    [in]     model
   !>  ctl  [in]     controls
   !>  s    [in]     the converged state
   !>  rec  [in]     the record (increments, the split's note)
   !>  out  [in,out] the run's files
   subroutine write_rows(pr, m, ctl, s, rec, out)
      type(phase_run), intent(inout) :: pr
      type(model_type), intent(in) :: m
      type(controls_type), intent(in) :: ctl
      type(state_type), intent(in) :: s
      type(run_record), intent(in) :: rec
      type(output_files), intent(inout) :: out
      real(dp) :: h, eh
      h = pr%h
      eh = pr%eh
      if (pr%paper_met) call write_strains(out, 'strain_localization.dat', m, s, &
                                           'at the increment where the paper''s criterion was met'// &
                                           split_note(rec, h))
      if (pr%phase == phase_lock) then
         call write_row(out, out%lock, [pr%p/h, pr%punch/eh, pr%punch, real(pr%row_iterations, dp), pr%dt/h, &
                                        pr%min_ind, pr%pen, pr%reaction/eh, pr%reaction])
      else
         call write_row(out, out%pull, [pr%p/h, pr%reaction/eh, pr%reaction, real(pr%row_iterations, dp), &
                                        pr%dt/h, pr%min_ind, pr%lift/eh, pr%lift, pr%pen, pr%punch/eh])
      end if
      pr%row_iterations = 0
      if (snapshot_due(pr, ctl)) then
         call write_snapshot(out, m, s, pr%phase, pr%p/h, rec%increments)
         pr%next_snapshot = next_snapshot(pr%p0, pr%p, ctl%snapshot_every_over_h, h)
      end if
      call write_progress(out, pr%phase, pr%p/h, rec%increments)
   end subroutine write_rows

   !> CONSOLE_LINE: the increment's line of the log (LOCALIZED once the
   !> paper's criterion has been met, NONLOCAL once the averaged-strain one
   !> has) and, with log_residuals, Newton's residuals, round-off floors
   !> and the material points' states per iterate (§8.2).
   !>  pr   [in] the loop's state
   !>  ctl  [in] controls
   !>  rec  [in] the record
   subroutine console_line(pr, ctl, rec)
      type(phase_run), intent(in) :: pr
      type(controls_type), intent(in) :: ctl
      type(run_record), intent(in) :: rec
      associate (nr => pr%nr)
         write (output_unit, '(a5,i6,a,es11.4,a,es9.2,a,i3,a,es9.2,a,es10.3,a,es11.4,2a)') &
            pr%phase, rec%increments, '  load/h=', pr%p/pr%h, '  d/h=', pr%dt/pr%h, '  it', nr%iterations, &
            '  res', nr%residual(nr%iterations), '  loc', pr%min_ind, '  force/Eh=', &
            pr%force/pr%eh, merge(' LOCALIZED', '          ', rec%localized), &
            merge(' NONLOCAL', '         ', rec%nl_localized)
         if (ctl%log_residuals) then
            write (output_unit, '(a,*(es9.2))') '      residuals:', nr%residual(0:nr%iterations)
            write (output_unit, '(a,*(es9.2))') '      round-off:', nr%round_off(0:nr%iterations)
            write (output_unit, '(a,*(i9))') '      plastic:  ', nr%plastic(0:nr%iterations)
            write (output_unit, '(a,*(i9))') '      switched: ', nr%switched(0:nr%iterations)
         end if
      end associate
      flush (output_unit)
   end subroutine console_line

   !> ENDS_RUN: does the phase end at this converged increment?  A result
   !> that cannot be written stops the run (nothing computed after it could
   !> be kept); a stop asked for by SIGTERM or SIGINT ends it here, with
   !> everything on disk; and with stop_at_localization the tearing point
   !> (stepper's stop_at_tearing).
   !>  pr    [in]     the loop's state (phase)
   !>  ctl   [in]     controls
   !>  out   [in]     the run's files (a failed write)
   !>  rec   [in,out] status and message of a failed write or a signal
   !>  ends  [out]    the phase ends
   subroutine ends_run(pr, ctl, out, rec, ends)
      type(phase_run), intent(in) :: pr
      type(controls_type), intent(in) :: ctl
      type(output_files), intent(in) :: out
      type(run_record), intent(inout) :: rec
      logical, intent(out) :: ends
      ends = .true.
      if (out%failed) then
         rec%status = run_write_failed
         rec%message = 'cannot write '//out%failure
      else if (stop_requested()) then
         rec%status = run_interrupted
         rec%message = 'interrupted by '//signal_name()//' in '//pr%phase//' at a converged increment'
      else
         ends = stop_at_tearing(ctl, rec)
      end if
   end subroutine ends_run

   !> SPLIT_AT_EXIT: the neck resolved on the default path (docs/theory.md
   !> §7.6), decided by stepper's decide_split: the elements around the
   !> exit of the last radius on the pulled side are split into parts of
   !> m%exit_element (remesh's exit_pieces and split_elements), the mapped
   !> state is re-equilibrated at the same pull (equilibrate_split), and
   !> the loop's state follows the new mesh: its arrays, the averaged-strain
   !> indicator of the state before the split on the new stations (a
   !> crossing by the split's own state is found at the next increment),
   !> the predictor's last motion (a Hermite field too, carried exactly,
   !> from the re-equilibrated state), the load-maximum candidate
   !> (stepper's records_after_split) and the force reached.  Nothing is
   !> split without a station on a radius or when no element there is
   !> longer than the parts.
   !>  pr   [in,out] the loop's state
   !>  m    [in,out] the model; on return the split mesh
   !>  ctl  [in]     controls (Newton's limits)
   !>  s    [in,out] the converged state; on return the mapped state in
   !>                equilibrium
   !> A mapped state that finds no equilibrium (Newton cycling between
   !> points that load and unload, e.g. past a fold) is undone: the mesh,
   !> the state and the loop's state before the split are restored, no
   !> further split is made, and the run goes on on that mesh, its tearing
   !> point then on elements too long for the neck (flagged as such); the
   !> log warns and summary.txt gives the pull at which it happened.
   !>  pr   [in,out] the loop's state
   !>  m    [in,out] the model; on return the split mesh (or, the split
   !>                undone, the mesh before it with m%exit_element = 0)
   !>  ctl  [in]     controls (Newton's limits)
   !>  s    [in,out] the converged state; on return the mapped state in
   !>                equilibrium (or the state before the split)
   !>  rec  [in,out] the split's record and counts; status and message
   !>                when out of memory
   subroutine split_at_exit(pr, m, ctl, s, rec)
      type(phase_run), intent(inout) :: pr
      type(model_type), intent(inout) :: m
      type(controls_type), intent(in) :: ctl
      type(state_type), intent(inout) :: s
      type(run_record), intent(inout) :: rec
      real(dp), allocatable :: motion(:)
      integer, allocatable :: pieces(:)
      real(dp) :: x_exit, energy_before(n_energy), h
      logical :: found
      integer :: first, last
      character(len=:), allocatable :: alloc_msg, failure
      ! what the split changes, kept to undo it
      type(model_type) :: m_before
      type(state_type) :: s_before
      type(phase_run) :: pr_before
      type(split_record) :: split_before
      h = pr%h
      call last_radius_exit(m, s, x_exit, found)
      if (.not. found) then
         write (output_unit, '(a)') '# drawbead: refine_exit: no station on a tool radius: the mesh stays as it is'
         return
      end if
      pieces = exit_pieces(m, s, x_exit, exit_zone_before)
      if (all(pieces == 1)) return
      first = findloc(pieces > 1, .true., 1)
      last = findloc(pieces > 1, .true., 1, back=.true.)
      write (output_unit, '(a,f0.4,a,f0.3,a,f0.3,a,f0.3,a,i0,a,i0,a)') '# drawbead: refine_exit: at pull/h = ', &
         pr%p/h, ' the elements from s/h = ', m%x(first)/h, ' to ', m%x(last + 1)/h, &
         ' split (exit of the last radius at x/h = ', x_exit/h, '): ', m%n_el, ' -> ', sum(pieces), ' elements'
      ! the energies the split changes (the stations' densities are
      ! interpolated, and re-equilibration does work against the imbalance
      ! it removes): booked apart, so that the balance still checks the rest
      call energy_totals(m, s, energy_before)
      motion = s%u - pr%u_prev
      m_before = m
      s_before = s
      pr_before = pr
      split_before = rec%split
      call split_elements(m, s, pieces, alloc_msg)
      if (len(alloc_msg) > 0) then
         ! (the mesh and the state are those before the split)
         rec%status = run_out_of_memory
         rec%message = 'in pull, splitting the elements at the exit: '//alloc_msg
         return
      end if
      ! recorded once done: a split that failed (out of memory) is not one
      call note_split(rec, m_before%x, pieces, pr%p, x_exit)
      rec%split%elements_after = m%n_el
      call phase_run_follow(pr, m, alloc_msg)
      if (len(alloc_msg) > 0) then
         rec%status = run_out_of_memory
         rec%message = 'in pull, after the split: '//alloc_msg
         return
      end if
      call phase_load(m, phase_pull, pr%p, pr%ld)
      call equilibrate_split(pr, m, ctl, s, rec, energy_before, failure)
      if (rec%status /= run_ok) return
      if (len(failure) > 0) then
         ! undone: the mesh before the split, unrefined from here on (the
         ! failed solves' iterations and assemblies stay counted)
         m = m_before
         s = s_before
         pr = pr_before
         rec%split = split_before
         rec%split%abandoned = .true.
         rec%split%abandoned_load = pr%p
         m%exit_element = 0.0_dp
         call warn('at pull/h = '//num(pr%p/h)//' '//failure//': the split is undone and the run '// &
                   'goes on on the mesh before it, not refined at the neck; its tearing point depends '// &
                   'on the mesh (docs/theory.md §7.6)', 'split_at_exit')
         return
      end if
      pr%u_prev = s%u - split_field(m_before%x, pieces, motion)
      pr%nl_old = pack(split_stations(pieces, reshape(pr%nl_old, [1, n_gauss, size(pieces)])), .true.)
      call records_after_split(rec, pieces)
      pr%settling = .true.
      rec%reactions = pr%r
      rec%last_conjugate = pr%r(pr%pulled)
      pr%force = pr%r(pr%pulled)
   end subroutine split_at_exit

   !> EQUILIBRATE_SPLIT: the state mapped onto the split mesh brought into
   !> equilibrium at the pull's load (remesh's reequilibrate, §7.6, 4), and
   !> booked: its Newton iterations and assemblies; the dead loads' work
   !> over it as external work, the rest of the change of the stored,
   !> dissipated and thickness-stress energies as the split's (kept out of
   !> the energy balance, §10); the change of the restraining force.
   !>  pr             [in,out] r: the re-equilibrated state's residual
   !>                          (its reactions); kb, ld on the new mesh
   !>  m              [in]     the model on the split mesh
   !>  ctl            [in]     controls (Newton's limits)
   !>  s              [in,out] the mapped state, on return in equilibrium
   !>  rec            [in,out] counts, work, split's energy and force change;
   !>                          status and message when it fails
   !>  energy_before  [in]     energy_totals before the split
   !>  failure        [out]    '' when in equilibrium; else why not (the
   !>                          caller undoes the split)
   subroutine equilibrate_split(pr, m, ctl, s, rec, energy_before, failure)
      type(phase_run), intent(inout) :: pr
      type(model_type), intent(in) :: m
      type(controls_type), intent(in) :: ctl
      type(state_type), intent(inout) :: s
      type(run_record), intent(inout) :: rec
      real(dp), intent(in) :: energy_before(n_energy)
      character(len=:), allocatable, intent(out) :: failure
      type(reequilibration) :: eq
      real(dp) :: energy_after(n_energy), force_change
      failure = ''
      call reequilibrate(m, s, pr%ld, pr%kb, pr%r, ctl%max_iterations, ctl%tolerance, eq)
      rec%newton_iterations = rec%newton_iterations + eq%iterations
      rec%assemblies = rec%assemblies + eq%assemblies
      select case (eq%status)
      case (reeq_out_of_memory)
         rec%status = run_out_of_memory
         rec%message = 'in pull, after the split: '//eq%errmsg
         return
      case (reeq_material)
         failure = 'a material point of the state mapped onto the split mesh cannot be updated'
         return
      case (reeq_no_equilibrium)
         failure = 'the state mapped onto the split mesh finds no equilibrium ('//num(eq%removed)// &
                   ' of its imbalance removed)'
         return
      end select
      rec%work = rec%work + eq%work_dead
      call energy_totals(m, s, energy_after)
      rec%split%energy_change = rec%split%energy_change + energy_absorbed(energy_after - energy_before) &
                                - eq%work_dead
      force_change = pr%r(pr%pulled)/rec%last_conjugate - 1.0_dp
      if (rec%split%count == 1) rec%split%force_change = force_change
      write (output_unit, '(a,i0,a,es9.2,a,f8.5)') '# drawbead: refine_exit: re-equilibrated in ', eq%steps, &
         ' steps, residual ', eq%residual, ', restraining force changed by ', force_change
   end subroutine equilibrate_split
end module analysis
