!> drawbead -- plane-strain analysis of a sheet locked into a drawbead and
!> pulled through it (Triantafyllidis, Maker & Samanta, 1986).
!>
!> deck -> set-up (model and controls) -> locking -> pulling -> summary;
!> nothing after set-up sees the deck.  Usage and exit status: see `usage`
!> below and docs/user-guide.md.
program drawbead
   use kinds, only: dp, output_unit, error_unit
   use phases, only: phase_lock, phase_pull
   use errors, only: error_list, report_errors, print_error, warn, exit_ok, exit_input, &
                     exit_noconvergence, exit_write, exit_interrupted, exit_memory
   use deck, only: deck_type
   use deck_reader, only: read_deck, echo_deck, list_variables
   use setup, only: setup_run
   use controls, only: controls_type
   use model, only: model_type, state_type, state_init
   use record, only: run_record, run_record_init, run_ok, run_no_convergence, run_interrupted, &
                     run_write_failed, run_out_of_memory, neck_record, split_note
   use mesh, only: neck_zone
   use analysis, only: run_phase
   use text, only: itoa
   use output, only: output_files, open_outputs, close_outputs, write_strains, write_tools, remove_results, &
                     open_snapshots, claim_output_dir, column_legend, write_text_file
   use exit_state, only: exit_state_text
   use summary, only: write_summary
   use os, only: install_stop_handlers
   use solver, only: default_threads
   implicit none
   character(len=*), parameter :: version = '1.1.0'
   !> room for a deck or directory name on the command line (as in the deck)
   integer, parameter :: path_max = 512
   character(len=*), parameter :: usage = 'usage: drawbead DECK.nml [-o|--output DIR]'// &
                                  ' | --list-variables | --columns FILE | --help | --version'
   type(deck_type) :: d
   type(error_list) :: errs
   type(model_type) :: m
   type(controls_type) :: ctl
   type(state_type) :: s
   type(run_record) :: rec
   type(neck_record) :: neck
   character(len=300) :: errmsg
   character(len=path_max) :: path, out_override
   character(len=:), allocatable :: iomsg
   integer :: ios
   real(dp) :: t_start, t_end

   call parse_command_line(path, out_override)
   call install_stop_handlers()
   call default_threads()

   ! set-up: every error of the deck and of the files it names, together
   call read_deck(trim(path), d, errs)
   call setup_run(d, m, ctl, errs)
   if (errs%count > 0) then
      call report_errors(errs, error_unit)
      call finish('bad input', exit_input)
   end if
   if (len_trim(out_override) > 0) then
      d%output_dir = out_override
      ctl%output_dir = out_override
   end if
   ! one run per output directory (a lock released when the program ends)
   call claim_output_dir(trim(ctl%output_dir), errmsg)
   if (len_trim(errmsg) > 0) call output_dir_error(trim(d%deck_file), trim(errmsg))
   call cpu_time(t_start)
   write (output_unit, '(a)') '# drawbead: '//trim(ctl%title)
   call echo_deck(d, output_unit)
   flush (output_unit)

   ! &sheet refine_neck: a first pass on the deck's uniform mesh finds the
   ! neck, and the run proper refines the mesh around it (docs/theory.md §7.5)
   if (d%refine_neck) then
      call place_neck_zone(d, m, ctl, neck)
   else
      call clear_first_pass(ctl)
   end if
   call run_case(m, ctl, trim(ctl%output_dir), neck, s, rec, errmsg)
   if (len_trim(errmsg) > 0) call output_dir_error(trim(d%deck_file), trim(errmsg))
   call cpu_time(t_end)
   call write_summary(trim(ctl%output_dir)//'/summary.txt', m, s, ctl, rec, t_end - t_start, ios, iomsg)
   if (ios /= 0 .and. rec%status /= run_write_failed) then
      rec%status = run_write_failed
      rec%message = 'cannot write '//iomsg
   end if
   select case (rec%status)
   case (run_ok)
      call finish('done', exit_ok)
   case (run_no_convergence)
      call print_error(trim(rec%message), 'run_phase')
      call finish('no convergence (results so far kept)', exit_noconvergence)
   case (run_interrupted)
      call print_error(trim(rec%message), 'run_phase')
      call finish('interrupted (results so far kept)', exit_interrupted)
   case (run_out_of_memory)
      call print_error(trim(rec%message), 'memory')
      call finish('out of memory (results so far kept)', exit_memory)
   case default
      call print_error(trim(rec%message), 'output')
      call finish('a result file could not be written', exit_write)
   end select

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
   !> pass runs the deck on its uniform mesh into <output_dir>/coarse (the
   !> output directory cleared of an earlier run first), stopped at its
   !> tearing point and pulled up to coarse_pull times the deck's pull (on
   !> 80 elements the neck comes up to a third later than the resolved
   !> one); the model is then rebuilt with a zone of elements of
   !> refine_element around that neck (mesh's neck_zone).  Without a neck
   !> in the first pass, or when the uniform elements are no longer than
   !> refine_element, the model stays as it is.  A first pass that stops
   !> early (SIGTERM, a failed write, no convergence within the deck's
   !> pull) ends the program with the run's summary.txt saying so.
   !>  d     [in]     the deck
   !>  m     [in,out] the model of the deck's uniform mesh; on return, the
   !>                 model of the run proper
   !>  ctl   [in]     the controls of the run proper
   !>  neck  [out]    what was done, for the summary
   subroutine place_neck_zone(d, m, ctl, neck)
      type(deck_type), intent(in) :: d
      type(model_type), intent(inout) :: m
      type(controls_type), intent(in) :: ctl
      type(neck_record), intent(out) :: neck
      real(dp), parameter :: coarse_pull = 1.5_dp
      character(len=*), parameter :: sub = '/coarse'
      type(model_type) :: m1
      type(controls_type) :: ctl1, ctl_unused
      type(state_type) :: s1
      type(run_record) :: rec1
      type(output_files) :: out
      character(len=300) :: errmsg
      type(deck_type) :: d2
      type(error_list) :: errs2
      real(dp) :: h, t0, t1, last_pull
      integer :: ios1
      character(len=:), allocatable :: iomsg1
      h = m%thickness
      neck%refinement = 'none'
      if (m%x(2) - m%x(1) <= d%refine_element*h*(1.0_dp + 1.0e-9_dp)) then
         write (output_unit, '(a)') '# drawbead: refine_neck: the uniform elements are no longer than '// &
            'refine_element: no zone'
         call clear_first_pass(ctl)
         return
      end if
      if (len_trim(ctl%output_dir) + len(sub) > len(ctl1%output_dir)) &
         call output_dir_error(trim(d%deck_file), 'longer than the program takes with refine_neck (at most '// &
                               itoa(len(ctl1%output_dir) - len(sub))//' characters, for its '//sub(2:)//' folder)')
      ! the output directory belongs to this run from now on: an earlier
      ! run's results there are removed, and summary.txt says running
      call open_outputs(trim(ctl%output_dir), trim(ctl%title), out, errmsg)
      if (len_trim(errmsg) > 0) call output_dir_error(trim(d%deck_file), trim(errmsg))
      call close_outputs(out)
      m1 = m
      m1%pull_distance = coarse_pull*m%pull_distance
      ctl1 = ctl
      ctl1%stop_at_localization = .true.
      ctl1%output_dir = trim(ctl%output_dir)//sub
      neck%refinement = 'first'
      neck%coarse_elements = m%n_el
      write (output_unit, '(a,i0,a)') '# drawbead: refine_neck: first pass on the uniform mesh (', &
         m%n_el, ' elements) into '//trim(ctl1%output_dir)
      flush (output_unit)
      call cpu_time(t0)
      call run_case(m1, ctl1, trim(ctl1%output_dir), neck, s1, rec1, errmsg)
      if (len_trim(errmsg) > 0) call stop_in_first_pass(m, ctl, neck, run_write_failed, trim(errmsg), 0)
      call cpu_time(t1)
      neck%coarse_assemblies = rec1%assemblies
      rec1%neck = neck
      call write_summary(trim(ctl1%output_dir)//'/summary.txt', m1, s1, ctl1, rec1, t1 - t0, ios1, iomsg1)
      if (ios1 /= 0) call stop_in_first_pass(m, ctl, neck, run_write_failed, 'cannot write '//iomsg1, rec1%assemblies)
      select case (rec1%status)
      case (run_interrupted, run_write_failed, run_out_of_memory)
         call stop_in_first_pass(m, ctl, neck, rec1%status, trim(rec1%message), rec1%assemblies)
      case (run_no_convergence)
         ! past the deck's own pull the first pass only looked for a late
         ! neck; before it, the deck fails on its uniform mesh
         last_pull = -1.0_dp
         if (rec1%n_pull > 0) last_pull = rec1%pull_delta(rec1%n_pull)
         if (.not. rec1%torn .and. last_pull < m%pull_distance) &
            call stop_in_first_pass(m, ctl, neck, run_no_convergence, trim(rec1%message), rec1%assemblies)
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
      ! centred on the uniform mesh's node nearest the neck: a neck station
      ! that moves to the next Gauss station with other increments keeps
      ! its zone (docs/theory.md §7.5)
      neck%zone = neck_zone(m%x(minloc(abs(m%x - rec1%tear_s), 1)), 0.5_dp*(m%x(m%n_nodes) - m%x(1)), h)
      neck%refinement = 'zone'
      d2 = d
      d2%refine_neck = .false.
      d2%refine_from = neck%zone(1)/h
      d2%refine_to = neck%zone(2)/h
      call setup_run(d2, m, ctl_unused, errs2)
      if (errs2%count > 0) then
         call report_errors(errs2, error_unit)
         call finish('bad input', exit_input)
      end if
      write (output_unit, '(a,f0.3,a,f0.3,a,i0,a)') '# drawbead: refine_neck: zone s/h = ', &
         neck%zone(1)/h, ' to ', neck%zone(2)/h, ' (', m%n_el, ' elements)'
      flush (output_unit)
   end subroutine place_neck_zone

   !> STOP_IN_FIRST_PASS: the first pass of refine_neck stopped early: the
   !> run's own summary.txt says so (the flat sheet, no increment of the
   !> run proper, neck_refinement = first), then the program ends with the
   !> status's exit code.
   !>  m           [in] the model of the deck's uniform mesh
   !>  ctl         [in] the controls of the run proper
   !>  neck        [in] the neck record so far
   !>  status      [in] run_interrupted, run_write_failed, run_no_convergence or
   !>                   run_out_of_memory
   !>  message     [in] why
   !>  assemblies  [in] the first pass's assemblies
   subroutine stop_in_first_pass(m, ctl, neck, status, message, assemblies)
      type(model_type), intent(in) :: m
      type(controls_type), intent(in) :: ctl
      type(neck_record), intent(in) :: neck
      integer, intent(in) :: status, assemblies
      character(len=*), intent(in) :: message
      type(state_type) :: s0
      type(run_record) :: rec0
      integer :: ios0
      character(len=:), allocatable :: iomsg0
      character(len=:), allocatable :: kept, alloc_msg
      ! (the flat sheet; with no memory for it the summary says so too)
      call state_init(m, s0, alloc_msg)
      call run_record_init(rec0)
      rec0%status = status
      rec0%message = message
      rec0%neck = neck
      rec0%neck%coarse_assemblies = assemblies
      call write_summary(trim(ctl%output_dir)//'/summary.txt', m, s0, ctl, rec0, 0.0_dp, ios0, iomsg0)
      kept = ' (results so far kept in '//trim(ctl%output_dir)//'/coarse)'
      select case (status)
      case (run_interrupted)
         call print_error(message, 'run_phase')
         call finish('interrupted in the first pass of refine_neck'//kept, exit_interrupted)
      case (run_no_convergence)
         call print_error(message, 'run_phase')
         call finish('no convergence in the first pass of refine_neck'//kept, exit_noconvergence)
      case (run_out_of_memory)
         call print_error(message, 'memory')
         call finish('out of memory in the first pass of refine_neck'//kept, exit_memory)
      case default
         call print_error(message, 'output')
         call finish('a result file of the first pass of refine_neck could not be written', exit_write)
      end select
   end subroutine stop_in_first_pass

   !> OUTPUT_DIR_ERROR: the output directory cannot be used: the error,
   !> naming the deck, its group and variable, and the end (bad input).
   !>  deck_file  [in] the deck
   !>  why        [in] what is wrong
   subroutine output_dir_error(deck_file, why)
      character(len=*), intent(in) :: deck_file, why
      call print_error('deck '''//deck_file//''', group &control, variable output_dir: '//why)
      call finish('bad input', exit_input)
   end subroutine output_dir_error

   !> CLEAR_FIRST_PASS: without a first pass, the results of an earlier
   !> run's first pass (<output_dir>/coarse) are removed, so that none is
   !> left beside this run's.
   !>  ctl  [in]  the controls (output_dir)
   subroutine clear_first_pass(ctl)
      type(controls_type), intent(in) :: ctl
      character(len=300) :: errmsg
      call remove_results(trim(ctl%output_dir)//'/coarse', errmsg)
      if (len_trim(errmsg) > 0) then
         call print_error(trim(errmsg), 'clear_first_pass')
         call finish('a result file could not be written', exit_write)
      end if
   end subroutine clear_first_pass

   !> PARSE_COMMAND_LINE: exactly one deck and at most one -o DIR; --help,
   !> --version and --list-variables answer and stop.  Anything else is an
   !> error with the usage line (exit_input).
   !>  deck_path  [out] the deck
   !>  out_dir    [out] the -o value, '' if not given
   subroutine parse_command_line(deck_path, out_dir)
      character(len=path_max), intent(out) :: deck_path, out_dir
      character(len=:), allocatable :: arg
      integer :: i, n, ios
      deck_path = ''
      out_dir = ''
      n = command_argument_count()
      i = 1
      do while (i <= n)
         arg = argument(i)
         select case (arg)
         case ('-h', '--help')
            write (output_unit, '(a)') usage, &
               '  DECK.nml            the input deck (docs/input-reference.md)', &
               '  -o, --output DIR    write the results in DIR instead of &control output_dir', &
               '  --list-variables    print every deck variable as "group variable type"', &
               '  --columns FILE      print the column header of a result file (lock.dat,'// &
               ' pull.dat, strain_*.dat, snapshots.dat)', &
               '  --help, --version   this text, the version', &
               'exit status: 0 done, 1 bad input, 2 no convergence, 3 a result file could'// &
               ' not be written, 4 interrupted (SIGTERM, SIGINT), 5 out of memory'
            stop
         case ('--version')
            write (output_unit, '(a)') 'drawbead '//version
            stop
         case ('--list-variables')
            call list_variables(output_unit, ios)
            if (ios /= 0) stop exit_write
            stop
         case ('--columns')
            if (i == n) call usage_error('option --columns needs a result file name')
            if (len(column_legend(argument(i + 1))) == 0) call usage_error('--columns: no result '// &
               'file '''//argument(i + 1)//''' (lock.dat, pull.dat, strain_lock.dat, '// &
               'strain_pull.dat, strain_localization.dat, snapshots.dat)')
            write (output_unit, '(a)', iostat=ios) column_legend(argument(i + 1))
            if (ios /= 0) stop exit_write
            stop
         case ('-o', '--output')
            if (i == n) call usage_error('option '//arg//' needs a directory')
            if (len_trim(out_dir) > 0) call usage_error('option '//arg//' given twice')
            i = i + 1
            call take(argument(i), out_dir)
            if (len_trim(out_dir) == 0) call usage_error('option '//arg//' needs a directory')
         case default
            if (len(arg) == 0) then
               call usage_error('an empty argument')
            else if (arg(1:1) == '-') then
               call usage_error('unknown option '//arg)
            else if (len_trim(deck_path) > 0) then
               call usage_error('more than one deck ('''//trim(deck_path)//''' and '''//arg// &
                                '''): run one deck per call')
            end if
            call take(arg, deck_path)
         end select
         i = i + 1
      end do
      if (len_trim(deck_path) == 0) call usage_error('no deck given')
   end subroutine parse_command_line

   !> TAKE: a command-line name into a fixed-length variable; a name that
   !> does not fit is a usage error (never silently cut).
   subroutine take(name, var)
      character(len=*), intent(in) :: name
      character(len=path_max), intent(out) :: var
      if (len(name) >= path_max) call usage_error('a name longer than '// &
                                                  'the program takes: '''//name(1:60)//'...''')
      var = name
   end subroutine take

   !> ARGUMENT: command-line argument i, of any length.
   function argument(i) result(arg)
      integer, intent(in) :: i
      character(len=:), allocatable :: arg
      integer :: n
      call get_command_argument(i, length=n)
      allocate (character(len=n) :: arg)
      if (n > 0) call get_command_argument(i, arg)
   end function argument

   !> USAGE_ERROR: a command-line error and the usage line; exit_input.
   subroutine usage_error(what)
      character(len=*), intent(in) :: what
      call print_error(what, 'drawbead')
      write (error_unit, '(a)') usage
      flush (error_unit)
      stop exit_input
   end subroutine usage_error

   !> FINISH: the log's last line (status and exit code), then stop with
   !> that code.
   !>  status  [in] what became of the run
   !>  code    [in] the exit status (module errors)
   subroutine finish(status, code)
      character(len=*), intent(in) :: status
      integer, intent(in) :: code
      flush (error_unit)
      write (output_unit, '(a,i0)') '# drawbead: '//status//', exit code ', code
      flush (output_unit)
      select case (code)
      case (exit_ok)
         stop
      case (exit_input)
         stop exit_input
      case (exit_noconvergence)
         stop exit_noconvergence
      case (exit_write)
         stop exit_write
      case (exit_interrupted)
         stop exit_interrupted
      case default
         stop exit_memory
      end select
   end subroutine finish
end program drawbead
