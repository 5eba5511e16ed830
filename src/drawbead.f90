!> drawbead -- plane-strain analysis of a sheet locked into a drawbead and
!> pulled through it (Triantafyllidis, Maker & Samanta, 1986).
!>
!> A dispatcher: command line -> deck -> set-up (model and controls) ->
!> the runs (module passes: refine_neck's first pass, then locking and
!> pulling) -> summary.txt -> the exit status; nothing after set-up sees
!> the deck, and only this program stops.  Usage and exit status: see
!> `usage` below and docs/user-guide.md.
program drawbead
   use kinds, only: dp, output_unit, error_unit
   use errors, only: error_list, report_errors, print_error, exit_ok, exit_input, &
                     exit_noconvergence, exit_write, exit_interrupted, exit_memory
   use deck, only: deck_type
   use deck_reader, only: read_deck, echo_deck, list_variables
   use setup, only: setup_run
   use controls, only: controls_type
   use model, only: model_type, state_type
   use record, only: run_record, run_ok, run_no_convergence, run_interrupted, run_write_failed, &
                     run_out_of_memory, neck_record
   use passes, only: run_case, place_neck_zone, pass_bad_output_dir, pass_bad_mesh
   use output, only: remove_results, claim_output_dir, column_legend
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
   character(len=:), allocatable :: iomsg, why
   integer :: ios, status
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
   if (ctl%refine_neck) then
      call place_neck_zone(m, ctl, neck, status, why)
      select case (status)
      case (run_ok)
      case (pass_bad_output_dir)
         call output_dir_error(trim(d%deck_file), why)
      case (pass_bad_mesh)
         call print_error(why, 'place_neck_zone')
         call finish('bad input', exit_input)
      case default
         call stop_in_first_pass(trim(ctl%output_dir), status, why)
      end select
   end if
   ! (an earlier run's first pass is not left beside this run's results)
   if (neck%coarse_elements == 0) call clear_first_pass(ctl)
   call run_case(m, ctl, trim(ctl%output_dir), neck, s, rec, errmsg)
   if (len_trim(errmsg) > 0) call output_dir_error(trim(d%deck_file), trim(errmsg))
   call cpu_time(t_end)
   call write_summary(trim(ctl%output_dir)//'/summary.txt', m, s, ctl, rec, t_end - t_start, ios, iomsg)
   if (ios /= 0 .and. rec%status /= run_write_failed) then
      rec%status = run_write_failed
      rec%message = 'cannot write '//iomsg
   end if
   call end_run(rec)

contains

   !> END_RUN: the end of a run by its status: done, or the error and the
   !> exit code (results so far kept).
   !>  rec  [in] the run's record (status, message)
   subroutine end_run(rec)
      type(run_record), intent(in) :: rec
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
   end subroutine end_run

   !> STOP_IN_FIRST_PASS: the first pass of refine_neck stopped early (its
   !> summary.txt and the run's say so, module passes): the error, and the
   !> end with the status's exit code.
   !>  dir      [in] the output directory
   !>  status   [in] run_interrupted, run_write_failed, run_no_convergence or
   !>                run_out_of_memory
   !>  message  [in] why
   subroutine stop_in_first_pass(dir, status, message)
      character(len=*), intent(in) :: dir, message
      integer, intent(in) :: status
      character(len=:), allocatable :: kept
      kept = ' (results so far kept in '//dir//'/coarse)'
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
