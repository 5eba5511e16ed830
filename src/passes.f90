!> passes -- the runs of a model after set-up: one run (locking, then
!> pulling, the result files) and, with &sheet refine_neck, the first pass
!> on the deck's mesh that places the neck's zone (docs/theory.md §7.5).
!> Nothing here sees the deck or stops the program: what went wrong is
!> returned to the main program, which reports it and sets the exit status.
module passes
   use kinds, only: dp, output_unit
   use phases, only: phase_lock, phase_pull
   use errors, only: warn
   use text, only: itoa, num
   use controls, only: controls_type
   use model, only: model_type, state_type, state_init, model_rezone
   use record, only: run_record, run_record_init, run_ok, run_no_convergence, run_interrupted, &
                     run_write_failed, run_out_of_memory, neck_record, split_note
   use mesh, only: neck_zone
   use analysis, only: run_phase
   use output, only: output_files, open_outputs, close_outputs, write_strains, write_tools, &
                     open_snapshots, write_text_file
   use exit_state, only: exit_state_text
   use summary, only: write_summary
   use setup, only: smallest_radius
   implicit none
   private
   public :: run_case, place_neck_zone, pass_bad_output_dir, pass_bad_mesh

   !> place_neck_zone's status beyond the run_* codes of the first pass:
   !> the output directory cannot be used; the zone's mesh cannot follow
   !> the tools (nothing of the run proper is written then)
   integer, parameter :: pass_bad_output_dir = -1, pass_bad_mesh = -2

   !> The first pass pulls up to coarse_pull times the deck's pull: on 80
   !> elements the neck came up to a third later than the resolved one with
   !> the tools on the reference faces (docs/theory.md §7.5)
   real(dp), parameter :: coarse_pull = 1.5_dp
   !> the first pass's folder in the output directory
   character(len=*), parameter :: coarse_dir = '/coarse'

contains

   !> RUN_CASE: one run of a model: locking, then pulling, the result files
   !> in dir (all but summary.txt, which the caller writes).
   !>  m          [in,out] the model; on return that of the end of the run
   !>                   (its elements split while pulling, docs/theory.md §7.6)
   !>  ctl        [in]  the controls
   !>  dir        [in]  the output directory
   !>  neck       [in]  the neck's refined zone, for the summary
   !>  s          [out] the state at the end
   !>  rec        [out] what the run found
   !>  errmsg     [out] '' or why the output directory could not be set up
   !>                   (nothing was run then)
   subroutine run_case(m, ctl, dir, neck, s, rec, errmsg)
      type(model_type), intent(inout) :: m
      type(controls_type), intent(in) :: ctl
      character(len=*), intent(in) :: dir
      type(neck_record), intent(in) :: neck
      type(state_type), intent(out) :: s
      type(run_record), intent(out) :: rec
      character(len=*), intent(out) :: errmsg
      type(output_files) :: out
      character(len=:), allocatable :: alloc_msg
      call run_record_init(rec)
      rec%neck = neck
      call open_outputs(dir, trim(ctl%title), out, errmsg)
      if (len_trim(errmsg) == 0 .and. ctl%snapshot_every_over_h > 0.0_dp) &
         call open_snapshots(out, trim(ctl%title), ctl%snapshot_every_over_h, errmsg)
      if (len_trim(errmsg) > 0) return
      ! the state's histories: the largest arrays of a run (issue 28, item 6)
      call state_init(m, s, alloc_msg)
      if (len(alloc_msg) > 0) then
         rec%status = run_out_of_memory
         rec%message = alloc_msg
         call close_outputs(out)
         return
      end if
      if (m%has_tools .and. m%lock_depth > 0.0_dp) then
         call run_phase(m, ctl, s, phase_lock, 0.0_dp, m%lock_depth, out, rec)
      end if
      call write_strains(out, 'strain_lock.dat', m, s, 'after locking')
      call write_tools(out, 'tools_lock.dat', m, s%shift, 'at the end of locking')
      if (rec%status == run_ok .and. .not. (rec%torn .and. ctl%stop_at_localization)) then
         call run_phase(m, ctl, s, phase_pull, 0.0_dp, m%pull_distance, out, rec)
      end if
      call write_strains(out, 'strain_pull.dat', m, s, 'after pulling'//split_note(rec, m%thickness))
      ! the sheet leaving the bead (docs/theory.md §9.1), after a pull
      if (m%has_tools .and. rec%n_pull > 0 .and. allocated(s%hn)) call write_exit_state(out, m, s, trim(ctl%title))
      call write_tools(out, 'tools_pull.dat', m, s%shift, 'at the end of pulling')
      call close_outputs(out)
      if (out%failed .and. rec%status /= run_write_failed) then
         rec%status = run_write_failed
         rec%message = 'cannot write '//out%failure
      end if
   end subroutine run_case

   !> WRITE_EXIT_STATE: exit_state.dat and exit_state.k in the output
   !> directory (module exit_state); a failed write is the run's failure.
   !>  out    [in,out] the run's files
   !>  m, s   [in]     model and converged state after the pull
   !>  title  [in]     the run's title
   subroutine write_exit_state(out, m, s, title)
      type(output_files), intent(inout) :: out
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      character(len=*), intent(in) :: title
      character(len=:), allocatable :: table, cards, msg
      logical :: found
      integer :: stat
      if (out%failed) return
      call exit_state_text(m, s, title, table, cards, found)
      call write_text_file(out%dir//'/exit_state.dat', table, stat, msg)
      if (stat == 0) call write_text_file(out%dir//'/exit_state.k', cards, stat, msg)
      if (stat /= 0) then
         out%failed = .true.
         out%failure = msg
      end if
   end subroutine write_exit_state

   !> PLACE_NECK_ZONE: &sheet refine_neck (docs/theory.md §7.5).  A first
   !> pass runs the model on its uniform mesh into <output_dir>/coarse
   !> (run_first_pass; the output directory cleared of an earlier run
   !> first); the model is then re-meshed with a zone of elements of
   !> refine_element h around that pass's neck (mesh's neck_zone, model's
   !> model_rezone: the run proper is the run of the deck with that zone
   !> given by hand, without set-up again: only the mesh differs).  Without
   !> a neck in the first pass, or when the uniform elements are no longer
   !> than refine_element, the model stays as it is.
   !>  m        [in,out] the model of the deck's uniform mesh; on return,
   !>                   the model of the run proper
   !>  ctl      [in]     the controls of the run proper
   !>  neck     [out]    what was done, for the summary (coarse_elements > 0
   !>                   once a first pass ran)
   !>  status   [out]    run_ok: go on with m; run_interrupted,
   !>                   run_write_failed, run_no_convergence or
   !>                   run_out_of_memory: the first pass stopped early (the
   !>                   run's summary.txt says so); pass_bad_output_dir:
   !>                   the output directory cannot be used; pass_bad_mesh:
   !>                   the zone's elements are longer than a tool radius
   !>  message  [out]    why, when status /= run_ok
   subroutine place_neck_zone(m, ctl, neck, status, message)
      type(model_type), intent(inout) :: m
      type(controls_type), intent(in) :: ctl
      type(neck_record), intent(out) :: neck
      integer, intent(out) :: status
      character(len=:), allocatable, intent(out) :: message
      type(output_files) :: out
      character(len=300) :: errmsg
      real(dp) :: h, tear_s
      h = m%thickness
      status = run_ok
      message = ''
      neck%refinement = 'none'
      if (m%x(2) - m%x(1) <= ctl%refine_element_over_h*h*(1.0_dp + 1.0e-9_dp)) then
         write (output_unit, '(a)') '# drawbead: refine_neck: the uniform elements are no longer than '// &
            'refine_element: no zone'
         return
      end if
      status = pass_bad_output_dir
      if (len_trim(ctl%output_dir) + len(coarse_dir) > len(ctl%output_dir)) then
         message = 'longer than the program takes with refine_neck (at most '// &
                   itoa(len(ctl%output_dir) - len(coarse_dir))//' characters, for its '//coarse_dir(2:)//' folder)'
         return
      end if
      ! the output directory belongs to this run from now on: an earlier
      ! run's results there are removed, and summary.txt says running
      call open_outputs(trim(ctl%output_dir), trim(ctl%title), out, errmsg)
      if (len_trim(errmsg) > 0) then
         message = trim(errmsg)
         return
      end if
      call close_outputs(out)
      call run_first_pass(m, ctl, neck, tear_s, status, message)
      if (status /= run_ok .or. .not. neck%coarse_torn) return
      ! centred on the uniform mesh's node nearest the neck: a neck station
      ! that moves to the next Gauss station with other increments keeps
      ! its zone (docs/theory.md §7.5)
      neck%zone = neck_zone(m%x(minloc(abs(m%x - tear_s), 1)), 0.5_dp*(m%x(m%n_nodes) - m%x(1)), h)
      neck%refinement = 'zone'
      call model_rezone(m, [neck%zone, ctl%refine_element_over_h*h])
      call check_zone_mesh(m, message)
      if (len(message) > 0) then
         status = pass_bad_mesh
         return
      end if
      write (output_unit, '(a,f0.3,a,f0.3,a,i0,a)') '# drawbead: refine_neck: zone s/h = ', &
         neck%zone(1)/h, ' to ', neck%zone(2)/h, ' (', m%n_el, ' elements)'
      flush (output_unit)
   end subroutine place_neck_zone

   !> RUN_FIRST_PASS: refine_neck's first pass (docs/theory.md §7.5): a copy
   !> of the model pulled up to coarse_pull times its pull, stopped at its
   !> tearing point, into <output_dir>/coarse with its own summary.txt.  A
   !> pass that stops early (SIGTERM, a failed write, no convergence within
   !> the deck's pull) stops the run: the run's summary.txt says so, with
   !> the flat sheet and no increment of the run proper.  One that fails
   !> only in its extra pull beyond the deck's is taken as having found no
   !> neck, with a warning.
   !>  m        [in]     the model of the deck's uniform mesh
   !>  ctl      [in]     the controls of the run proper
   !>  neck     [in,out] refinement, coarse_elements, coarse_assemblies,
   !>                    coarse_torn and the pass's tearing point
   !>  tear_s   [out]    the pass's neck (reference position, mm) when torn
   !>  status   [out]    run_ok, or the pass's status when it stopped early
   !>  message  [out]    why it stopped
   subroutine run_first_pass(m, ctl, neck, tear_s, status, message)
      type(model_type), intent(in) :: m
      type(controls_type), intent(in) :: ctl
      type(neck_record), intent(inout) :: neck
      real(dp), intent(out) :: tear_s
      integer, intent(out) :: status
      character(len=:), allocatable, intent(out) :: message
      type(model_type) :: m1
      type(controls_type) :: ctl1
      type(state_type) :: s1
      type(run_record) :: rec1
      character(len=300) :: errmsg
      real(dp) :: t0, t1, last_pull
      integer :: ios1
      character(len=:), allocatable :: iomsg1
      tear_s = 0.0_dp
      m1 = m
      m1%pull_distance = coarse_pull*m%pull_distance
      ctl1 = ctl
      ctl1%stop_at_localization = .true.
      ctl1%output_dir = trim(ctl%output_dir)//coarse_dir
      neck%refinement = 'first'
      neck%coarse_elements = m%n_el
      write (output_unit, '(a,i0,a)') '# drawbead: refine_neck: first pass on the uniform mesh (', &
         m%n_el, ' elements) into '//trim(ctl1%output_dir)
      flush (output_unit)
      call cpu_time(t0)
      call run_case(m1, ctl1, trim(ctl1%output_dir), neck, s1, rec1, errmsg)
      call cpu_time(t1)
      status = run_ok
      message = ''
      if (len_trim(errmsg) > 0) then
         call first_pass_stopped(m, ctl, neck, run_write_failed, trim(errmsg), status, message)
         return
      end if
      neck%coarse_assemblies = rec1%assemblies
      rec1%neck = neck
      call write_summary(trim(ctl1%output_dir)//'/summary.txt', m1, s1, ctl1, rec1, t1 - t0, ios1, iomsg1)
      if (ios1 /= 0) then
         call first_pass_stopped(m, ctl, neck, run_write_failed, 'cannot write '//iomsg1, status, message)
         return
      end if
      last_pull = -1.0_dp
      if (rec1%n_pull > 0) last_pull = rec1%pull_delta(rec1%n_pull)
      select case (rec1%status)
      case (run_interrupted, run_write_failed, run_out_of_memory)
         call first_pass_stopped(m, ctl, neck, rec1%status, trim(rec1%message), status, message)
         return
      case (run_no_convergence)
         ! past the deck's own pull the first pass only looked for a late
         ! neck; before it, the deck fails on its uniform mesh
         if (.not. rec1%torn .and. last_pull < m%pull_distance) then
            call first_pass_stopped(m, ctl, neck, run_no_convergence, trim(rec1%message), status, message)
            return
         end if
      end select
      neck%coarse_torn = rec1%torn .and. rec1%tear_phase == phase_pull
      if (.not. neck%coarse_torn) then
         neck%refinement = 'none'
         if (rec1%status == run_no_convergence) then
            call warn('no convergence in the first pass past the deck''s pull ('// &
                      trim(rec1%message)//'): no neck found within the pull; the run keeps the uniform mesh', &
                      'place_neck_zone')
         else
            write (output_unit, '(a)') '# drawbead: refine_neck: no neck in the first pass: '// &
               'the run keeps the uniform mesh'
         end if
         return
      end if
      neck%coarse_tear_load = rec1%tear_load
      neck%coarse_tear_s = rec1%tear_s
      tear_s = rec1%tear_s
   end subroutine run_first_pass

   !> FIRST_PASS_STOPPED: the first pass of refine_neck stopped early: the
   !> run's own summary.txt says so (the flat sheet, no increment of the
   !> run proper, neck_refinement = first), and the status is passed on.
   !>  m            [in]  the model of the deck's uniform mesh
   !>  ctl          [in]  the controls of the run proper
   !>  neck         [in]  the neck record so far (the pass's assemblies)
   !>  pass_status  [in]  run_interrupted, run_write_failed,
   !>                     run_no_convergence or run_out_of_memory
   !>  why          [in]  the pass's message
   !>  status       [out] pass_status
   !>  message      [out] why
   subroutine first_pass_stopped(m, ctl, neck, pass_status, why, status, message)
      type(model_type), intent(in) :: m
      type(controls_type), intent(in) :: ctl
      type(neck_record), intent(in) :: neck
      integer, intent(in) :: pass_status
      character(len=*), intent(in) :: why
      integer, intent(out) :: status
      character(len=:), allocatable, intent(out) :: message
      type(state_type) :: s0
      type(run_record) :: rec0
      integer :: ios0
      character(len=:), allocatable :: iomsg0, alloc_msg
      ! (the flat sheet; with no memory for it the summary says so too)
      call state_init(m, s0, alloc_msg)
      call run_record_init(rec0)
      rec0%status = pass_status
      rec0%message = why
      rec0%neck = neck
      call write_summary(trim(ctl%output_dir)//'/summary.txt', m, s0, ctl, rec0, 0.0_dp, ios0, iomsg0)
      status = pass_status
      message = why
   end subroutine first_pass_stopped

   !> CHECK_ZONE_MESH: the zone's mesh must follow the tools as the deck's
   !> did (set-up's check_element_length, issue 28): outside the zone its
   !> elements are those of the uniform mesh rounded to whole elements, up
   !> to 1.5 times as long, and none may be longer than the smallest tool
   !> radius.
   !>  m        [in]  the model on the zone's mesh
   !>  message  [out] '' or what is wrong
   subroutine check_zone_mesh(m, message)
      type(model_type), intent(in) :: m
      character(len=:), allocatable, intent(out) :: message
      real(dp) :: longest, radius, h
      message = ''
      if (.not. m%has_tools) return
      h = m%thickness
      longest = maxval(m%x(2:) - m%x(:m%n_nodes - 1))
      radius = min(smallest_radius(m%tool(1)), smallest_radius(m%tool(2)))
      if (radius >= huge(1.0_dp)) return
      if (longest <= radius*(1.0_dp + 1.0e-9_dp)) return
      message = 'refine_neck: outside the zone the mesh has elements of up to '//num(longest/h)// &
                ' h, longer than the smallest tool radius, '//num(radius/h)//' h: the sheet cannot follow '// &
                'the tools; give more n_elements'
   end subroutine check_zone_mesh
end module passes
