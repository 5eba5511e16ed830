!> stepper -- the state of one phase's increment loop and the decisions
!> read off it that neither solve nor write.
!>
!> phase_run holds what the loop carries from one increment to the next
!> (the load parameter and its increments, the step control's memory, the
!> last attempt's forces, the work arrays of the mesh).  The driver (module
!> analysis) runs the loop and calls, per increment: its solve (with
!> cutbacks), commit, then record_increment (the run record), its criteria,
!> output rows and console line, decide_split (the neck's refinement,
!> docs/theory.md §7.6) and size_next_increment (§8.3).  What is here is
!> free of I/O, so that the unit tests can call it on made-up states.
module stepper
   use kinds, only: dp
   use phases, only: phase_lock, phase_pull
   use errors, only: alloc_message
   use text, only: itoa
   use hermite, only: n_gauss
   use element, only: igp_strain
   use band, only: band_matrix, band_init
   use mesh, only: half_band, node_dof, dof_v, dof_w, dofs_per_node
   use model, only: model_type, state_type, load_type
   use controls, only: controls_type
   use solver, only: newton_result, newton_cutback, newton_singular
   use record, only: run_record, record_pull, record_lock, run_out_of_memory
   use remesh, only: last_radius_exit, exit_pieces, exit_resplit_before, split_stations
   use tearing, only: strain_limit_indicator
   use load_maximum, only: maximum_approaching
   use step_control, only: next_increment, bound_after_failure, bound_past_section_maximum, past_turned_maximum
   use energy, only: energy_totals, add_increment_work
   implicit none
   private
   public :: phase_run, phase_run_init, phase_run_follow, predict, read_forces, record_increment, &
             watches_maximum, stop_at_tearing, decide_split, note_split, records_after_split, &
             snapshot_due, next_snapshot, failure_tag, size_next_increment

   !> What a phase's increment loop carries between increments (the locals
   !> of the loop; lengths in mm).
   type :: phase_run
      character(len=:), allocatable :: phase ! phase_lock or phase_pull
      real(dp) :: p0 = 0.0_dp, p1 = 0.0_dp   ! start and end of the load parameter
      real(dp) :: p = 0.0_dp                 ! the load parameter of the converged state
      real(dp) :: dt = 0.0_dp                ! the increment tried (after a converged one: its length)
      real(dp) :: dt_prev = 0.0_dp           ! the last converged increment
      real(dp) :: dt_failed = huge(1.0_dp)   ! the last failed attempt's length (huge: none), §8.3
      real(dp) :: dt_err = 0.0_dp            ! the increment the error estimate allows (judge_error)
      real(dp) :: err = -1.0_dp              ! the last attempt's local error estimate (< 0: none)
      real(dp) :: err_redone = -1.0_dp       ! that of the last attempt redone at this load (< 0: none)
      real(dp) :: prev_conjugate = 0.0_dp    ! the phase's force two converged states back (8.4)
      logical :: have_prev = .false.         ! a converged increment of this phase exists
      logical :: settling = .false.          ! split, and no increment converged since (§8.3)
      logical :: have_force_prev = .false.   ! prev_conjugate holds a force
      real(dp) :: next_snapshot = 0.0_dp     ! the load of the next strain snapshot
      real(dp) :: h = 0.0_dp, eh = 0.0_dp    ! thickness, E h
      real(dp) :: ell = 0.0_dp               ! averaging length of the averaged-strain criterion (§7.2)
      integer :: pulled = 0                  ! the pulled dof (the right edge's v)
      integer :: row_iterations = 0          ! Newton iterations since the last row, failed attempts included
      ! the last attempt's forces (§9): N (reaction at the pulled dof), F
      ! (the lower tool on the sheet), the lift on the upper tool, and the
      ! phase's force (F locking, N pulling); its relative change and target
      real(dp) :: reaction = 0.0_dp, punch = 0.0_dp, lift = 0.0_dp, force = 0.0_dp
      real(dp) :: force_change = 0.0_dp, target = 0.0_dp
      ! of the converged state: the smallest indicator (7.2), the largest
      ! penetration over h, the paper's criterion first met in it
      real(dp) :: min_ind = 0.0_dp, pen = 0.0_dp
      logical :: paper_met = .false.
      ! the mesh's work arrays: residual, the converged dofs before the last
      ! increment, the indicator before it, the averaged-strain indicator,
      ! the displacement error's dof weights, the tangent
      real(dp), allocatable :: r(:), u_prev(:), ind_old(:, :), nl_old(:), dof_scale(:)
      type(band_matrix) :: kb
      type(load_type) :: ld                  ! the last attempt's load
      type(newton_result) :: nr              ! the last attempt's Newton solve
   end type phase_run

contains

   !> PHASE_RUN_INIT: a phase's loop at its start: the work arrays of the
   !> mesh, the first increment, the force conjugate to the load parameter
   !> (F while locking, starting at 0 on the flat sheet; N while pulling,
   !> the reaction reached so far), the averaged-strain indicator of the
   !> state, the phase's load maximum not yet looked for (each phase's force
   !> has its own), and at the start of the pull the work and energies there
   !> (docs/theory.md §10).
   !>  pr     [out]    the loop's state
   !>  m      [in]     model
   !>  ctl    [in]     controls (first increment, snapshots, tearing length)
   !>  s      [in]     the state, converged at p0
   !>  phase  [in]     phase_lock or phase_pull
   !>  p0,p1  [in]     start and end of the load parameter, mm
   !>  rec    [in,out] last_conjugate, max_at, the pull's start; status
   !>                  run_out_of_memory and message when the arrays could
   !>                  not be allocated (issue 28, item 6)
   subroutine phase_run_init(pr, m, ctl, s, phase, p0, p1, rec)
      type(phase_run), intent(out) :: pr
      type(model_type), intent(in) :: m
      type(controls_type), intent(in) :: ctl
      type(state_type), intent(in) :: s
      character(len=*), intent(in) :: phase
      real(dp), intent(in) :: p0, p1
      type(run_record), intent(inout) :: rec
      character(len=:), allocatable :: alloc_msg
      integer :: stat
      pr%phase = phase
      pr%p0 = p0
      pr%p1 = p1
      pr%h = m%thickness
      pr%eh = m%youngs*pr%h
      pr%ell = ctl%tearing_length_over_h*pr%h
      allocate (pr%ind_old(n_gauss, m%n_el), stat=stat)
      if (stat == 0) call phase_run_follow(pr, m, alloc_msg)
      if (stat /= 0) alloc_msg = alloc_message('the work arrays of '//itoa(m%n_el)//' elements', &
                                               8.0_dp*real(3*m%n_dof + n_gauss*m%n_el, dp))
      if (len(alloc_msg) > 0) then
         rec%status = run_out_of_memory
         rec%message = 'in '//phase//': '//alloc_msg
         return
      end if
      pr%p = p0
      pr%dt = ctl%initial_increment
      pr%dt_prev = pr%dt
      rec%last_conjugate = 0.0_dp
      if (phase == phase_pull .and. allocated(rec%reactions)) rec%last_conjugate = rec%reactions(pr%pulled)
      pr%nl_old = strain_limit_indicator(m, s%gpn(igp_strain, :, :), pr%ell)
      rec%max_at = 0
      if (phase == phase_pull) then
         rec%work_pull_start = rec%work
         call energy_totals(m, s, rec%energy_pull_start)
      end if
      pr%next_snapshot = p0 + ctl%snapshot_every_over_h*pr%h
   end subroutine phase_run_init

   !> PHASE_RUN_FOLLOW: the loop's arrays of the mesh's size (residual,
   !> previous dofs, dof weights, tangent) and the pulled dof, for the
   !> model's mesh: at the start of a phase and after a split (their values
   !> are set by the caller).
   !>  pr      [in,out] the loop's state
   !>  m       [in]     model
   !>  errmsg  [out]    '' or the message of a failed allocation
   subroutine phase_run_follow(pr, m, errmsg)
      type(phase_run), intent(inout) :: pr
      type(model_type), intent(in) :: m
      character(len=:), allocatable, intent(out) :: errmsg
      integer :: stat
      errmsg = ''
      pr%pulled = node_dof(m%n_nodes, dof_v)
      if (allocated(pr%r)) deallocate (pr%r)
      if (allocated(pr%u_prev)) deallocate (pr%u_prev)
      if (allocated(pr%dof_scale)) deallocate (pr%dof_scale)
      allocate (pr%r(m%n_dof), pr%u_prev(m%n_dof), pr%dof_scale(m%n_dof), stat=stat)
      if (stat /= 0) then
         errmsg = alloc_message('the work arrays of '//itoa(m%n_el)//' elements', 24.0_dp*real(m%n_dof, dp))
         return
      end if
      pr%dof_scale = phase_dof_scale(m)
      call band_init(pr%kb, m%n_dof, half_band, half_band, errmsg)
   end subroutine phase_run_follow

   !> PREDICT: the first iterate of an attempt: the converged state moved on
   !> by the last increment's motion scaled to this one (ctl%predictor),
   !> else the converged state.
   !>  pr   [in]     the loop's state (dt, dt_prev, u_prev)
   !>  ctl  [in]     controls
   !>  s    [in,out] u1 set
   pure subroutine predict(pr, ctl, s)
      type(phase_run), intent(in) :: pr
      type(controls_type), intent(in) :: ctl
      type(state_type), intent(inout) :: s
      if (pr%have_prev .and. ctl%predictor) then
         s%u1 = s%u + (pr%dt/pr%dt_prev)*(s%u - pr%u_prev)
      else
         s%u1 = s%u
      end if
   end subroutine predict

   !> READ_FORCES: the forces of a converged attempt (docs/theory.md §9): N
   !> the internal force at the pulled dof, F the lower tool's upward force
   !> on the sheet, the lift the sheet's upward force on the upper tool,
   !> and the phase's force (F locking, N pulling).
   !>  pr  [in,out] the loop's state: r read, the forces set
   !>  s   [in]     the trial state (tool forces)
   pure subroutine read_forces(pr, s)
      type(phase_run), intent(inout) :: pr
      type(state_type), intent(in) :: s
      pr%reaction = pr%r(pr%pulled)
      pr%punch = s%tool_force(2, 2)
      pr%lift = -s%tool_force(2, 1)
      pr%force = merge(pr%punch, pr%reaction, pr%phase == phase_lock)
   end subroutine read_forces

   !> RECORD_INCREMENT: the run record after a committed increment: the
   !> external work (10.1), the phase's force kept for the next increment's
   !> step control and work, and the phase's history: the punch force at
   !> the lock's end, and the clamped lock's tension when its maximum is
   !> watched (§7.4); the largest and the history of the restraining force,
   !> the lift, while pulling.
   !>  pr       [in,out] the loop's state (prev_conjugate, have_force_prev set)
   !>  s        [in]     the committed state
   !>  watches  [in]     the load-maximum criterion watches this phase
   !>                    (watches_maximum)
   !>  rec      [in,out] the record
   subroutine record_increment(pr, s, watches, rec)
      type(phase_run), intent(inout) :: pr
      type(state_type), intent(in) :: s
      logical, intent(in) :: watches
      type(run_record), intent(inout) :: rec
      real(dp) :: tool_work
      tool_work = 0.0_dp
      if (pr%phase == phase_lock) tool_work = 0.5_dp*pr%dt*(rec%last_conjugate + pr%punch)
      call add_increment_work(pr%ld, pr%r, s%u - pr%u_prev, tool_work, rec)
      pr%prev_conjugate = rec%last_conjugate
      pr%have_force_prev = .true.
      rec%last_conjugate = pr%force
      if (pr%phase == phase_lock) then
         rec%lock_force = pr%punch
         if (watches) call record_lock(rec, pr%p, pr%reaction)
      else
         rec%peak_force = max(rec%peak_force, pr%reaction)
         rec%last_lift = pr%lift
         call record_pull(rec, pr%p, pr%reaction)
      end if
   end subroutine record_increment

   !> WATCHES_MAXIMUM: does the load-maximum criterion (docs/theory.md §7.4)
   !> watch this phase's force?  The pull's restraining force always with
   !> that criterion; the lock's tension with tools and a clamped left edge
   !> (with a free edge the tension is the back tension, a dead load).
   !>  m      [in]  model
   !>  ctl    [in]  controls
   !>  phase  [in]  phase_lock or phase_pull
   pure logical function watches_maximum(m, ctl, phase)
      type(model_type), intent(in) :: m
      type(controls_type), intent(in) :: ctl
      character(len=*), intent(in) :: phase
      watches_maximum = ctl%tearing_criterion == 'load_maximum'
      if (phase == phase_lock) watches_maximum = watches_maximum .and. m%has_tools .and. .not. m%left_edge_free
   end function watches_maximum

   !> STOP_AT_TEARING: does the run stop after this increment (with
   !> stop_at_localization)?  With tearing_criterion = 'section' once both
   !> the paper's and the averaged-strain criteria have been met (the
   !> paper's decks), with 'load_maximum' once the neck is confirmed
   !> (docs/theory.md §7.4).
   !>  ctl  [in]  controls
   !>  rec  [in]  the record
   pure logical function stop_at_tearing(ctl, rec)
      type(controls_type), intent(in) :: ctl
      type(run_record), intent(in) :: rec
      stop_at_tearing = .false.
      if (.not. ctl%stop_at_localization) return
      if (ctl%tearing_criterion == 'section') then
         stop_at_tearing = rec%localized .and. rec%nl_localized
      else
         stop_at_tearing = rec%torn
      end if
   end function stop_at_tearing

   !> DECIDE_SPLIT: is the neck's zone to be split now (docs/theory.md §7.6,
   !> 1-2)?  Only while pulling on a model with m%exit_element > 0.  Once
   !> the restraining force turns toward its maximum (load_maximum's
   !> maximum_approaching on the pull history) the refinement is armed and
   !> the first split is due; from then on a split is due whenever elements
   !> longer than m%exit_element are drawn within exit_resplit_before h of
   !> the exit of the last radius (coarse_near_exit).  The force must be at
   !> least approach_capacity of the sheet's plane-strain load capacity
   !> N* = tau* h exp(-eps*), the largest force per width a uniform strip
   !> carries (docs/theory.md §7.6): a free edge drawing steadily (its force
   !> flattening on a plateau, no neck) stays on its mesh.
   !>  m      [in]     model
   !>  s      [in]     the converged state
   !>  phase  [in]     phase_lock or phase_pull
   !>  rec    [in,out] the pull history; split%armed set when the force turns
   !>  due    [out]    split now
   pure subroutine decide_split(m, s, phase, rec, due)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      character(len=*), intent(in) :: phase
      type(run_record), intent(inout) :: rec
      logical, intent(out) :: due
      due = .false.
      if (phase /= phase_pull .or. .not. m%exit_element > 0.0_dp) return
      if (rec%split%armed) then
         due = coarse_near_exit(m, s)
      else
         rec%split%armed = maximum_approaching(rec%pull_delta(1:rec%n_pull), rec%pull_force(1:rec%n_pull), &
                                               m%thickness, m%max_load_stress*m%thickness*exp(-m%max_load_strain))
         due = rec%split%armed
      end if
   end subroutine decide_split

   !> COARSE_NEAR_EXIT: are elements longer than m%exit_element drawn within
   !> exit_resplit_before h before the exit of the last radius (or within
   !> exit_zone_after h after it)?  Then the neck's zone is split again
   !> (docs/theory.md §7.6).
   !>  m  [in]  model
   !>  s  [in]  converged state
   pure logical function coarse_near_exit(m, s)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      real(dp) :: x_exit
      logical :: found
      call last_radius_exit(m, s, x_exit, found)
      coarse_near_exit = .false.
      if (found) coarse_near_exit = any(exit_pieces(m, s, x_exit, exit_resplit_before) > 1)
   end function coarse_near_exit

   !> NOTE_SPLIT: a split in the record (summary.txt's split_*): its count;
   !> of the first, the phase, the pull, the exit of the last radius, the
   !> span of the split elements and the element count before it; of a
   !> later one, the span widened to hold it.
   !>  rec     [in,out] split
   !>  x       [in]     the node positions before the split, mm
   !>  pieces  [in]     the parts of each element (some > 1)
   !>  p       [in]     the pull, mm
   !>  x_exit  [in]     the exit of the last radius, mm
   pure subroutine note_split(rec, x, pieces, p, x_exit)
      type(run_record), intent(inout) :: rec
      real(dp), intent(in) :: x(:), p, x_exit
      integer, intent(in) :: pieces(:)
      integer :: first, last
      first = findloc(pieces > 1, .true., 1)
      last = findloc(pieces > 1, .true., 1, back=.true.)
      rec%split%count = rec%split%count + 1
      if (rec%split%count == 1) then
         rec%split%phase = phase_pull
         rec%split%load = p
         rec%split%x_exit = x_exit
         rec%split%zone = [x(first), x(last + 1)]
         rec%split%elements_before = size(pieces)
      else
         rec%split%zone = [min(rec%split%zone(1), x(first)), max(rec%split%zone(2), x(last + 1))]
      end if
   end subroutine note_split

   !> RECORDS_AFTER_SPLIT: the load-maximum criterion's candidate after a
   !> split (docs/theory.md §7.6, 4): after the first, the maximum is looked
   !> for on the split mesh's path, from the next pull sample on (the
   !> re-equilibrated force differs from the coarse mesh's by the mapping's
   !> error); after a later one, the candidate's strains follow the mesh.
   !>  rec     [in,out] max_at, split%pull_first, strain_at_max
   !>  pieces  [in]     the parts each element before the split became
   pure subroutine records_after_split(rec, pieces)
      type(run_record), intent(inout) :: rec
      integer, intent(in) :: pieces(:)
      if (rec%split%count == 1) then
         rec%max_at = 0
         rec%split%pull_first = rec%n_pull + 1
         if (allocated(rec%strain_at_max)) deallocate (rec%strain_at_max)
      else if (rec%max_at > 0 .and. allocated(rec%strain_at_max)) then
         rec%strain_at_max = pack(split_stations(pieces, reshape(rec%strain_at_max, [1, n_gauss, size(pieces)])), &
                                  .true.)
      end if
   end subroutine records_after_split

   !> SNAPSHOT_DUE: is a strain snapshot due at this converged state?  At
   !> the first state at or past each multiple of snapshot_every h from the
   !> phase's start (a state short of one by 1e-9 h counts as past it).
   !>  pr   [in]  the loop's state (p, next_snapshot, h)
   !>  ctl  [in]  controls (snapshot_every_over_h; 0: none)
   pure logical function snapshot_due(pr, ctl)
      type(phase_run), intent(in) :: pr
      type(controls_type), intent(in) :: ctl
      snapshot_due = ctl%snapshot_every_over_h > 0.0_dp .and. pr%p >= pr%next_snapshot - 1.0e-9_dp*pr%h
   end function snapshot_due

   !> NEXT_SNAPSHOT: the load of the snapshot after one written at p: the
   !> next multiple of every h from p0 past p (one snapshot per increment
   !> however many multiples it passed; the same slack of 1e-9 h as
   !> snapshot_due, so that a state just short of a multiple counts as past
   !> it and the next one is then due).
   !>  p0     [in]  the phase's start, mm
   !>  p      [in]  the load of the snapshot written, mm
   !>  every  [in]  snapshot_every_over_h (> 0)
   !>  h      [in]  thickness, mm
   pure real(dp) function next_snapshot(p0, p, every, h)
      real(dp), intent(in) :: p0, p, every, h
      next_snapshot = p0 + (aint((p - p0 + 1.0e-9_dp*h)/(every*h)) + 1.0_dp)*every*h
   end function next_snapshot

   !> FAILURE_TAG: why a Newton attempt failed, for the console's cutback
   !> line: the material's cut factor, a singular tangent, a residual
   !> stalled within a few times its round-off floor (docs/theory.md §8.2),
   !> or diverged.
   !>  nr  [in]  the failed solve
   pure function failure_tag(nr) result(tag)
      type(newton_result), intent(in) :: nr
      character(len=16) :: tag
      integer :: last
      select case (nr%status)
      case (newton_cutback)
         write (tag, '(a,f5.2)') 'pnewdt ', nr%pnewdt
      case (newton_singular)
         tag = 'singular'
      case default
         tag = 'diverged'
         last = max(nr%iterations - 1, 0)
         if (nr%residual(last) <= 4.0_dp*nr%round_off(last)) tag = 'round-off'
      end select
   end function failure_tag

   !> SIZE_NEXT_INCREMENT: the increment after a converged one (docs/theory.md
   !> §8.3): by the force's change, the error estimate (when there was one)
   !> and Newton's iterations (step_control's next_increment; not past a
   !> section's maximum once the force has turned, past_turned_maximum),
   !> bounded after a failed attempt and, with tools, past a section's
   !> maximum load.
   !>  pr         [in,out] dt set, have_prev .true.
   !>  ctl        [in]     controls
   !>  has_tools  [in]     the model has tools (a free strip past its
   !>                      maximum load has one path)
   !>  turned     [in]     the restraining force has turned toward its
   !>                      maximum (the split of §7.6 is armed, whether or
   !>                      not the mesh at the exit needed it)
   pure subroutine size_next_increment(pr, ctl, has_tools, turned)
      type(phase_run), intent(inout) :: pr
      type(controls_type), intent(in) :: ctl
      logical, intent(in) :: has_tools, turned
      logical :: shrink
      shrink = .not. (has_tools .and. past_turned_maximum(ctl, pr%phase, pr%min_ind, turned))
      if (pr%err >= 0.0_dp) then
         pr%dt = next_increment(ctl, pr%dt, pr%force_change, pr%target, pr%force, pr%eh, pr%nr%iterations, &
                                pr%dt_err, shrink=shrink)
      else
         pr%dt = next_increment(ctl, pr%dt, pr%force_change, pr%target, pr%force, pr%eh, pr%nr%iterations, &
                                shrink=shrink)
      end if
      call bound_after_failure(ctl, pr%dt, pr%dt_failed)
      if (has_tools) call bound_past_section_maximum(ctl, pr%phase, pr%min_ind, turned, pr%dt)
      pr%have_prev = .true.
   end subroutine size_next_increment

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
end module stepper
