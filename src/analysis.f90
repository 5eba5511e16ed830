!> analysis -- the increment loop of a run: the boundary conditions of
!> each phase, Newton per increment, commit, the criteria read off each
!> converged state and a row of output per increment.
!>
!> Phase 'lock': the lower tool rises by H (load parameter), right edge held.
!> Phase 'pull': tools held at H = lock depth, right edge pulled by delta.
!> Left edge clamped (v = w = w' = 0) or free (w = w' = 0, axial force
!> -back_tension applied).  docs/theory.md §1, §8.1.
module analysis
   use kinds, only: dp, output_unit
   use phases, only: phase_lock, phase_pull
   use errors, only: warn, alloc_message
   use text, only: itoa
   use hermite, only: n_gauss
   use element, only: igp_strain
   use band, only: band_matrix, band_init, band_error_message
   use mesh, only: half_band, node_dof, dof_v, dof_w, dof_w_slope, dofs_per_node
   use model, only: model_type, state_type, load_type, load_init
   use contact, only: ich_penetration
   use controls, only: controls_type
   use record, only: run_record, record_pull, record_lock, run_ok, run_no_convergence, run_interrupted, run_write_failed, &
                     run_out_of_memory, &
                     split_note
   use remesh, only: last_radius_exit, exit_pieces, split_elements, split_field, split_stations, &
                     exit_zone_before, exit_resplit_before
   use solver, only: newton_result, newton_solve, commit_state, assemble, newton_ok, newton_cutback, &
                     newton_singular, newton_solve_failed
   use step_control, only: judge_force_change, next_increment, cutback_factor, extrapolation_error, &
                           judge_error, displacement_error, bound_after_failure, bound_past_section_maximum
   use tearing, only: check_localization, check_fold, strain_limit_indicator, check_load_maximum, &
                      tear_at_snap_back, element_length_at, maximum_approaching
   use energy, only: energy_totals, add_increment_work
   use output, only: output_files, write_row, write_strains, write_snapshot, write_progress
   use os, only: stop_requested, signal_name
   use tools, only: tool_level
   implicit none
   private
   public :: run_phase, phase_load

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
   !> increments; commit, check the criteria and write a row per increment.
   !>  m     [in,out] model (its elements split while pulling, §7.6)
   !>  ctl   [in]  controls (increments, tolerances, criteria, output)
   !>  s     [in,out] state, converged at p0 on entry
   !>  phase [in]  'lock' or 'pull'
   !>  p0,p1 [in]  start and end of the load parameter
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
      type(band_matrix) :: kb
      real(dp), allocatable :: nl_old(:), r(:), u_prev(:), ind_old(:, :), dof_scale(:), x_old(:)
      integer, allocatable :: pieces(:)
      type(load_type) :: ld
      type(newton_result) :: nr
      real(dp) :: p, dt, dt_prev, h, eh, dt_failed
      real(dp) :: reaction, punch, lift, pen, min_ind, force, force_change, target, tool_work
      real(dp) :: next_snapshot, ell, prev_conjugate, err, dt_err, err_redone
      integer :: pulled
      logical :: have_prev, have_force_prev, redo, paper_met, snapped, split_due
      character(len=16) :: tag
      character(len=200) :: msg
      character(len=:), allocatable :: alloc_msg
      integer :: stat
      h = m%thickness
      eh = m%youngs*h
      ell = ctl%tearing_length_over_h*h
      pulled = node_dof(m%n_nodes, dof_v)
      ! the phase's large arrays: a failed allocation stops the run with
      ! status out_of_memory (issue 28, item 6), the results so far kept
      allocate (r(m%n_dof), u_prev(m%n_dof), ind_old(n_gauss, m%n_el), dof_scale(m%n_dof), &
                stat=stat)
      if (stat /= 0) then
         rec%status = run_out_of_memory
         rec%message = 'in '//phase//': '//alloc_message('the work arrays of '//itoa(m%n_el)//' elements', &
                                                         8.0_dp*real(3*m%n_dof + n_gauss*m%n_el, dp))
         return
      end if
      dof_scale = phase_dof_scale(m)
      call band_init(kb, m%n_dof, half_band, half_band, alloc_msg)
      if (len(alloc_msg) > 0) then
         rec%status = run_out_of_memory
         rec%message = 'in '//phase//': '//alloc_msg
         return
      end if
      p = p0
      dt = ctl%initial_increment
      ! the force doing work on the load parameter: F while locking (starts
      ! at 0 on the flat sheet), N while pulling (the reaction reached so far)
      rec%last_conjugate = 0.0_dp
      if (phase == phase_pull .and. allocated(rec%reactions)) rec%last_conjugate = rec%reactions(pulled)
      nl_old = strain_limit_indicator(m, s%gpn(igp_strain, :, :), ell)
      ! each phase's force has its own maximum (the lock's tension, the pull's N)
      rec%max_at = 0
      if (phase == phase_pull) then
         rec%work_pull_start = rec%work
         call energy_totals(m, s, rec%energy_pull_start)
      end if
      dt_prev = dt
      have_prev = .false.
      ! the error estimate of the last attempt redone at this load (< 0: none)
      err_redone = -1.0_dp
      ! the force two converged states back, for the error estimate
      prev_conjugate = 0.0_dp
      have_force_prev = .false.
      dt_failed = huge(1.0_dp)
      next_snapshot = p0 + ctl%snapshot_every_over_h*h
      do while (p < p1 - 1.0e-12_dp*h)
         dt = min(dt, p1 - p)
         call phase_load(m, phase, p + dt, ld)
         if (have_prev .and. ctl%predictor) then
            s%u1 = s%u + (dt/dt_prev)*(s%u - u_prev)
         else
            s%u1 = s%u
         end if
         call newton_solve(m, s, ld, kb, r, ctl%max_iterations, ctl%tolerance, nr, &
                           count_states=ctl%log_residuals)
         rec%newton_iterations = rec%newton_iterations + nr%iterations
         rec%assemblies = rec%assemblies + nr%assemblies
         if (nr%status /= newton_ok) then
            rec%cutbacks = rec%cutbacks + 1
            select case (nr%status)
            case (newton_cutback)
               write (tag, '(a,f5.2)') 'pnewdt ', nr%pnewdt
            case (newton_singular)
               tag = 'singular'
            case default
               tag = 'diverged'
               ! (a residual that ends within a few times its round-off
               ! floor stalled there, docs/theory.md §8.2)
               if (nr%residual(max(nr%iterations - 1, 0)) <= 4.0_dp*nr%round_off(max(nr%iterations - 1, 0))) &
                  tag = 'round-off'
            end select
            write (output_unit, '(a5,1x,a,es10.3,a,i3,a,es9.2,2a)') phase, 'cutback  d/h=', dt/h, &
               '  it', nr%iterations, '  res', nr%residual(max(nr%iterations - 1, 0)), '  ', trim(tag)
            if (nr%status == newton_solve_failed) then
               ! not a property of the increment: cutting it back cannot help
               rec%message = 'in '//phase//': '//band_error_message(nr%solve_info)
               rec%status = run_no_convergence
               return
            end if
            dt_failed = dt
            dt = cutback_factor*dt
            s%u1 = s%u
            if (dt < ctl%min_increment) then
               write (rec%message, '(3a,es10.3,a)') 'no convergence in ', phase, &
                  ' at load/h = ', p/h, ': increment below min_increment'
               ! past the paper's tearing point the sheet may have no nearby
               ! equilibrium: that ends the run normally (the neck has formed);
               ! past a maximum of the pull force it is the tearing point
               ! (docs/theory.md §7.4)
               if (ctl%stop_at_localization) then
                  if (watches_maximum(m, ctl, phase)) call tear_at_snap_back(m, s, phase, rec, snapped)
                  if (rec%localized) return
               end if
               rec%status = run_no_convergence
               return
            end if
            cycle
         end if
         ! forces: N = internal force at the pulled dof, F = lower tool upward
         ! force on the sheet, lift = upward force of the sheet on the upper tool
         reaction = r(pulled)
         punch = s%tool_force(2, 2)
         lift = -s%tool_force(2, 1)
         force = merge(punch, reaction, phase == phase_lock)
         call judge_force_change(ctl, phase, p, dt, force, rec%last_conjugate, eh, &
                                 force_change, target, redo)
         if (redo) then
            rec%cutbacks = rec%cutbacks + 1
            write (output_unit, '(a5,1x,a,es10.3,a,f6.2)') phase, 'cutback  d/h=', dt/h, &
               '  force jump', force_change
            dt = cutback_factor*dt
            s%u1 = s%u
            cycle
         end if
         ! the local error of the path (docs/theory.md §8.3): an increment
         ! where the path turns too fast is redone shorter.  Locking, that of
         ! the punch force (smooth, the result read at full lock); pulling,
         ! that of the displacements (the pull force carries a noise of
         ! stations entering contact and small branch jumps)
         err = -1.0_dp
         if (phase == phase_lock) then
            if (have_force_prev) err = extrapolation_error(force, rec%last_conjugate, prev_conjugate, &
                                                           dt, dt_prev, eh)
         else if (have_prev) then
            err = displacement_error(s%u1, s%u, u_prev, dt, dt_prev, h, dof_scale)
         end if
         call judge_error(ctl, err, dt, redo, dt_err, final=phase == phase_lock .and. p + dt >= p1 - 1.0e-12_dp*h)
         ! a redo shortens the increment by q < 0.8 and a second-order
         ! estimate by at least as much (by q^2 without an earlier increment):
         ! one that kept more than half of its value marks a jump of the path
         ! (the state moving to a neighbouring branch), which no shorter
         ! increment resolves; it is taken as it is (docs/theory.md §8.3)
         if (redo .and. err_redone > 0.0_dp) redo = err <= 0.5_dp*err_redone
         if (redo) then
            err_redone = err
            rec%cutbacks = rec%cutbacks + 1
            write (output_unit, '(a5,1x,a,es10.3,a,es9.2)') phase, 'cutback  d/h=', dt/h, &
               '  error', err
            dt = dt_err
            s%u1 = s%u
            cycle
         end if
         err_redone = -1.0_dp
         ind_old = s%indicator
         u_prev = s%u
         dt_prev = dt
         call commit_state(m, s, ld%tool_shift)
         p = p + dt
         rec%increments = rec%increments + 1
         pen = 0.0_dp
         if (m%has_tools) pen = max(0.0_dp, maxval(s%cn(ich_penetration, :, :, :)))/h
         ! penetrations above 0.05h mean the penalty is too soft for the
         ! forces at hand (docs/theory.md §5): warn once per run
         if (pen > 0.05_dp .and. rec%max_penetration <= 0.05_dp) then
            write (msg, '(a,es9.3,a,es10.3,a)') 'penetration ', pen, 'h > 0.05h at load/h = ', &
               p/h, ' in '//phase//': raise &tools penalty'
            call warn(msg, 'run_phase')
         end if
         rec%max_penetration = max(rec%max_penetration, pen)
         call check_fold(m, s, phase, p, ctl%fold_curvature, rec)
         min_ind = minval(s%indicator)
         call check_localization(m, s, phase, p, dt, ind_old, nl_old, ell, rec, paper_met)
         if (paper_met) call write_strains(out, 'strain_localization.dat', m, s, &
                                           'at the increment where the paper''s criterion was met'// &
                                           split_note(rec, h))
         ! tearing_criterion = 'section': the tearing point is the paper's
         ! (it has no mesh limit in this model, docs/theory.md §7.1: said once)
         if (paper_met .and. ctl%tearing_criterion == 'section') then
            rec%torn = .true.
            rec%tear_phase = rec%loc_phase
            rec%tear_load = rec%load_cr
            rec%tear_s = rec%s_star
            rec%tear_element = element_length_at(m, rec%s_star)
            call warn('tearing point by the paper''s pointwise criterion (tearing_criterion = ''section''): '// &
                      'it has no mesh limit in this model and moves with the mesh (docs/theory.md §7.1)', 'run_phase')
         end if
         tool_work = 0.0_dp
         if (phase == phase_lock) tool_work = 0.5_dp*dt*(rec%last_conjugate + punch)
         call add_increment_work(ld, r, s%u - u_prev, tool_work, rec)
         prev_conjugate = rec%last_conjugate
         have_force_prev = .true.
         rec%last_conjugate = force
         if (phase == phase_lock) then
            rec%lock_force = punch
            ! a clamped sheet can neck while the bead closes: the maximum of
            ! its tension (docs/theory.md §7.4)
            if (watches_maximum(m, ctl, phase)) then
               call record_lock(rec, p, reaction)
               call check_load_maximum(m, s, phase, rec)
            end if
            call write_row(out, out%lock, [p/h, punch/eh, punch, real(nr%iterations, dp), dt/h, &
                                      min_ind, pen, reaction/eh, reaction])
         else
            rec%peak_force = max(rec%peak_force, reaction)
            rec%last_lift = lift
            call record_pull(rec, p, reaction)
            if (watches_maximum(m, ctl, phase)) call check_load_maximum(m, s, phase, rec)
            call write_row(out, out%pull, [p/h, reaction/eh, reaction, real(nr%iterations, dp), &
                                      dt/h, min_ind, lift/eh, lift, pen, punch/eh])
         end if
         ! LOCALIZED once the paper's criterion has been met, NONLOCAL once the
         ! mesh-objective one has
         write (output_unit, '(a5,i6,a,es11.4,a,es9.2,a,i3,a,es9.2,a,es10.3,a,es11.4,2a)') &
            phase, rec%increments, '  load/h=', p/h, '  d/h=', dt/h, '  it', nr%iterations, &
            '  res', nr%residual(nr%iterations), '  loc', min_ind, '  force/Eh=', &
            force/eh, merge(' LOCALIZED', '          ', rec%localized), &
            merge(' NONLOCAL', '         ', rec%nl_localized)
         if (ctl%log_residuals) then
            write (output_unit, '(a,*(es9.2))') '      residuals:', nr%residual(0:nr%iterations)
            write (output_unit, '(a,*(es9.2))') '      round-off:', nr%round_off(0:nr%iterations)
            write (output_unit, '(a,*(i9))') '      plastic:  ', nr%plastic(0:nr%iterations)
            write (output_unit, '(a,*(i9))') '      switched: ', nr%switched(0:nr%iterations)
         end if
         ! a strain snapshot at the first converged state at or past each
         ! multiple of snapshot_every h (one per increment however many it passed)
         if (ctl%snapshot_every_over_h > 0.0_dp .and. p >= next_snapshot - 1.0e-9_dp*h) then
            call write_snapshot(out, m, s, phase, p/h, rec%increments)
            ! (the same slack of 1e-9 h as the test above: a state just short
            ! of a multiple counts as past it, and the next one is then due)
            next_snapshot = p0 + (aint((p - p0 + 1.0e-9_dp*h)/(ctl%snapshot_every_over_h*h)) + &
                                  1.0_dp)*ctl%snapshot_every_over_h*h
         end if
         flush (output_unit)
         call write_progress(out, phase, p/h, rec%increments)
         ! a result that cannot be written stops the run (nothing computed
         ! after it could be kept); a stop asked for by SIGTERM or SIGINT
         ! ends it here, at a converged increment with everything on disk
         if (out%failed) then
            rec%status = run_write_failed
            rec%message = 'cannot write '//out%failure
            return
         end if
         if (stop_requested()) then
            rec%status = run_interrupted
            rec%message = 'interrupted by '//signal_name()//' in '//phase// &
                          ' at a converged increment'
            return
         end if
         ! stop at tearing: with tearing_criterion = 'section' once both the
         ! paper's and the averaged-strain criteria have been met (the
         ! paper's decks), with 'load_maximum' once the neck is confirmed
         if (ctl%stop_at_localization) then
            if (ctl%tearing_criterion == 'section') then
               if (rec%localized .and. rec%nl_localized) return
            else if (rec%torn) then
               return
            end if
         end if
         ! the neck's refinement once the force turns toward its maximum,
         ! and again whenever coarse elements are drawn near the exit
         ! (docs/theory.md §7.6): the split state, re-equilibrated, carries
         ! on; the phase's arrays follow the new mesh (the predictor's last
         ! motion is a Hermite field too, carried exactly, and starts from
         ! the re-equilibrated state)
         split_due = .false.
         if (phase == phase_pull .and. m%exit_element > 0.0_dp) then
            if (rec%split%armed) then
               split_due = coarse_near_exit(m, s)
            else
               rec%split%armed = maximum_approaching(rec%pull_delta(1:rec%n_pull), &
                                                     rec%pull_force(1:rec%n_pull), h, m%max_load_stress*h)
               split_due = rec%split%armed
            end if
         end if
         if (split_due) then
            if (allocated(x_old)) deallocate (x_old)
            allocate (x_old(m%n_nodes))
            x_old = m%x
            ! the last increment's motion, carried to the new mesh below
            u_prev = s%u - u_prev
            call refine_at_exit(m, ctl, s, rec, p, pieces, r)
            if (rec%status /= run_ok) return
            if (any(pieces > 1)) then
               u_prev = s%u - split_field(x_old, pieces, u_prev)
               ! the averaged-strain indicator of the state before the
               ! split, on the new stations: a crossing by the split's own
               ! state is found at the next increment
               nl_old = pack(split_stations(pieces, reshape(nl_old, [1, n_gauss, size(pieces)])), .true.)
               if (rec%split%count == 1) then
                  ! the load maximum is looked for on the split mesh's path
                  rec%max_at = 0
                  rec%split%pull_first = rec%n_pull + 1
                  if (allocated(rec%strain_at_max)) deallocate (rec%strain_at_max)
               else if (rec%max_at > 0 .and. allocated(rec%strain_at_max)) then
                  ! a later split: the candidate's strains follow the mesh
                  rec%strain_at_max = pack(split_stations(pieces, &
                                           reshape(rec%strain_at_max, [1, n_gauss, size(pieces)])), .true.)
               end if
               pulled = node_dof(m%n_nodes, dof_v)
               deallocate (dof_scale)
               allocate (dof_scale(m%n_dof))
               dof_scale = phase_dof_scale(m)
               call band_init(kb, m%n_dof, half_band, half_band, alloc_msg)
               if (len(alloc_msg) > 0) then
                  rec%status = run_out_of_memory
                  rec%message = 'in pull, after the split: '//alloc_msg
                  return
               end if
               rec%reactions = r
               rec%last_conjugate = r(pulled)
               force = r(pulled)
            else
               u_prev = s%u - u_prev
            end if
         end if
         if (err >= 0.0_dp) then
            dt = next_increment(ctl, dt, force_change, target, force, eh, nr%iterations, dt_err)
         else
            dt = next_increment(ctl, dt, force_change, target, force, eh, nr%iterations)
         end if
         call bound_after_failure(ctl, dt, dt_failed)
         ! (under the tools: a free strip past its maximum load has one path)
         if (m%has_tools) call bound_past_section_maximum(ctl, phase, min_ind, h, dt)
         have_prev = .true.
      end do
   end subroutine run_phase

   !> COARSE_NEAR_EXIT: are elements longer than m%exit_element drawn within
   !> exit_resplit_before h before the exit of the last radius (or within
   !> its exit_zone_after h after it)?  Then the neck's zone is split again
   !> (docs/theory.md §7.6).
   !>  m  [in]  model
   !>  s  [in]  converged state
   logical function coarse_near_exit(m, s)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      real(dp) :: x_exit
      logical :: found
      call last_radius_exit(m, s, x_exit, found)
      coarse_near_exit = .false.
      if (found) coarse_near_exit = any(exit_pieces(m, s, x_exit, exit_resplit_before) > 1)
   end function coarse_near_exit

   !> WATCHES_MAXIMUM: does the load-maximum criterion (docs/theory.md §7.4)
   !> watch this phase's force?  The pull's restraining force always with
   !> that criterion; the lock's tension with tools and a clamped left edge
   !> (with a free edge the tension is the back tension, a dead load).
   !>  m      [in]  model
   !>  ctl    [in]  controls
   !>  phase  [in]  'lock' or 'pull'
   pure logical function watches_maximum(m, ctl, phase)
      type(model_type), intent(in) :: m
      type(controls_type), intent(in) :: ctl
      character(len=*), intent(in) :: phase
      watches_maximum = ctl%tearing_criterion == 'load_maximum'
      if (phase == phase_lock) watches_maximum = watches_maximum .and. m%has_tools .and. .not. m%left_edge_free
   end function watches_maximum

   !> PHASE_DOF_SCALE: the weight of each dof in the displacement error
   !> (docs/theory.md §8.3): 1 for v and w (mm), h for the slopes v' and w'.
   !>  m      [in]  model
   pure function phase_dof_scale(m) result(dof_scale)
      type(model_type), intent(in) :: m
      real(dp) :: dof_scale(m%n_dof)
      dof_scale = m%thickness
      dof_scale(node_dof(1, dof_v)::dofs_per_node) = 1.0_dp
      dof_scale(node_dof(1, dof_w)::dofs_per_node) = 1.0_dp
   end function phase_dof_scale

   !> REFINE_AT_EXIT: the neck resolved on the default path (docs/theory.md
   !> §7.6): at a converged state of the pull, the elements around the exit
   !> of the last radius on the pulled side are split into parts of
   !> m%exit_element (remesh), the state is mapped onto them and
   !> re-equilibrated at the same load, and the split is recorded.  Nothing
   !> is split without a station on a radius or when no element there is
   !> longer than the parts (pieces all 1 then).
   !>  m       [in,out] the model; on return the split mesh
   !>  ctl     [in]     the controls (Newton's limits)
   !>  s       [in,out] the converged state, on return the mapped state in
   !>                   equilibrium
   !>  rec     [in,out] the record: split, counts; status and message when
   !>                   the mapped state finds no equilibrium
   !>  p       [in]     the pull, mm
   !>  pieces  [out]    the parts each old element was split into
   !>  r       [in,out] reallocated: the residual of the re-equilibrated state (its
   !>                   reactions at the prescribed dofs), on the new mesh
   subroutine refine_at_exit(m, ctl, s, rec, p, pieces, r)
      type(model_type), intent(inout) :: m
      type(controls_type), intent(in) :: ctl
      type(state_type), intent(inout) :: s
      type(run_record), intent(inout) :: rec
      real(dp), intent(in) :: p
      integer, allocatable, intent(out) :: pieces(:)
      real(dp), allocatable, intent(inout) :: r(:)
      type(load_type) :: ld, ld_step
      type(band_matrix) :: kb
      type(newton_result) :: nr
      real(dp), allocatable :: r0(:), u_mapped(:)
      real(dp) :: x_exit, h, f_scale, pnewdt, alpha, da, force_change, energy_before(5), energy_after(5), work_dead
      logical :: found
      integer :: first, last, steps, stat
      character(len=:), allocatable :: alloc_msg
      h = m%thickness
      allocate (pieces(m%n_el))
      pieces = 1
      call last_radius_exit(m, s, x_exit, found)
      if (.not. found) then
         write (output_unit, '(a)') '# drawbead: refine_exit: no station on a tool radius: the mesh stays as it is'
         return
      end if
      pieces = exit_pieces(m, s, x_exit, exit_zone_before)
      if (all(pieces == 1)) return
      first = findloc(pieces > 1, .true., 1)
      last = findloc(pieces > 1, .true., 1, back=.true.)
      rec%split%count = rec%split%count + 1
      if (rec%split%count == 1) then
         rec%split%phase = phase_pull
         rec%split%load = p
         rec%split%x_exit = x_exit
         rec%split%zone = [m%x(first), m%x(last + 1)]
         rec%split%elements_before = m%n_el
      else
         rec%split%zone = [min(rec%split%zone(1), m%x(first)), max(rec%split%zone(2), m%x(last + 1))]
      end if
      write (output_unit, '(a,f0.4,a,f0.3,a,f0.3,a,f0.3,a,i0,a,i0,a)') '# drawbead: refine_exit: at pull/h = ', &
         p/h, ' the elements from s/h = ', m%x(first)/h, ' to ', m%x(last + 1)/h, &
         ' split (exit of the last radius at x/h = ', x_exit/h, '): ', m%n_el, ' -> ', &
         sum(pieces), ' elements'
      ! the energies the split changes (the stations' densities are
      ! interpolated, and re-equilibration does work against the imbalance
      ! it removes): booked apart, so that the balance still checks the rest
      call energy_totals(m, s, energy_before)
      call split_elements(m, s, pieces, alloc_msg)
      if (len(alloc_msg) > 0) then
         ! (the mesh and the state are those before the split)
         rec%status = run_out_of_memory
         rec%message = 'in pull, splitting the elements at the exit: '//alloc_msg
         pieces = 1
         return
      end if
      rec%split%elements_after = m%n_el
      if (allocated(r)) deallocate (r)
      allocate (u_mapped(m%n_dof), r(m%n_dof), r0(m%n_dof), stat=stat)
      if (stat /= 0) then
         rec%status = run_out_of_memory
         rec%message = 'in pull, after the split: '//alloc_message('the work arrays of '//itoa(m%n_el)// &
                                                                  ' elements', 24.0_dp*real(m%n_dof, dp))
         return
      end if
      u_mapped = s%u
      ! the mapped state in equilibrium at the same load: its imbalance r0
      ! (the mapped stresses are not in equilibrium on the new stations) is
      ! removed gradually, as a load, f_ext + (1 - alpha) r0 with alpha from
      ! 0 (the mapped state, in equilibrium by construction) to 1, each
      ! step committed: mid-pull, with sections past their maximum load on
      ! the radius, a single Newton solve from the mapped state can leave
      ! the branch the run was on (bead A steel at 0.59h: diverged)
      call phase_load(m, phase_pull, p, ld)
      call band_init(kb, m%n_dof, half_band, half_band, alloc_msg)
      if (len(alloc_msg) > 0) then
         rec%status = run_out_of_memory
         rec%message = 'in pull, after the split: '//alloc_msg
         return
      end if
      s%u1 = s%u
      call assemble(m, s, ld, kb, r0, f_scale, pnewdt)
      rec%assemblies = rec%assemblies + 1
      r0 = merge(0.0_dp, r0, ld%fixed)
      ld_step = ld
      alpha = 0.0_dp
      da = 1.0_dp
      steps = 0
      do while (alpha < 1.0_dp .and. pnewdt >= 1.0_dp)
         da = min(da, 1.0_dp - alpha)
         ld_step%f_ext = ld%f_ext + (1.0_dp - (alpha + da))*r0
         s%u1 = s%u
         call newton_solve(m, s, ld_step, kb, r, ctl%max_iterations, ctl%tolerance, nr)
         rec%newton_iterations = rec%newton_iterations + nr%iterations
         rec%assemblies = rec%assemblies + nr%assemblies
         if (nr%status == newton_ok) then
            call commit_state(m, s, ld%tool_shift)
            alpha = alpha + da
            steps = steps + 1
            da = 2.0_dp*da
         else
            da = 0.25_dp*da
            if (da < 1.0_dp/4096.0_dp) exit
         end if
      end do
      if (pnewdt < 1.0_dp) then
         rec%status = run_no_convergence
         rec%message = 'in pull: a material point of the state mapped onto the split mesh cannot be updated:'// &
                       ' set &sheet refine_exit = .false.'
         return
      else if (alpha < 1.0_dp) then
         rec%status = run_no_convergence
         write (rec%message, '(a,f0.4,a)') 'in pull: no equilibrium of the state mapped onto the '// &
            'split mesh (', alpha, ' of its imbalance removed): set &sheet refine_exit = .false.'
         return
      end if
      ! the dead loads' work over the re-equilibration is external work; the
      ! rest of the change of the stored, dissipated and thickness-stress
      ! energies is the split's (docs/theory.md §7.6)
      work_dead = dot_product(ld%f_ext, s%u - u_mapped)
      rec%work = rec%work + work_dead
      call energy_totals(m, s, energy_after)
      rec%split%energy_change = rec%split%energy_change + (sum(energy_after(1:4)) - energy_after(5)) &
                                - (sum(energy_before(1:4)) - energy_before(5)) - work_dead
      force_change = r(node_dof(m%n_nodes, dof_v))/rec%last_conjugate - 1.0_dp
      if (rec%split%count == 1) rec%split%force_change = force_change
      write (output_unit, '(a,i0,a,es9.2,a,f8.5)') '# drawbead: refine_exit: re-equilibrated in ', steps, &
         ' steps, residual ', nr%residual(nr%iterations), ', restraining force changed by ', force_change
   end subroutine refine_at_exit
end module analysis
