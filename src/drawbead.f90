!> drawbead -- plane-strain analysis of a sheet locked into a drawbead and
!> pulled through it (Triantafyllidis, Maker & Samanta, 1986).
!>
!> Usage: drawbead deck.nml [--output DIR]
!>        drawbead --list-variables
!>   --output DIR (or -o DIR) overrides &control output_dir;
!>   --list-variables prints every deck variable as `group variable type`.
!> Exit status (module errors): 0 done, 1 bad input, 2 no convergence
!> (results so far kept).
!>
!> deck -> set-up (model and controls) -> locking -> pulling -> summary;
!> nothing after set-up sees the deck.
program drawbead
   use kinds, only: dp, output_unit, error_unit
   use errors, only: error_list, report_errors, print_error, exit_input, exit_noconvergence
   use deck, only: deck_type
   use deck_reader, only: read_deck, echo_deck, list_variables
   use setup, only: setup_run
   use controls, only: controls_type
   use model, only: model_type, state_type, state_init
   use record, only: run_record, run_record_init, run_ok
   use analysis, only: run_phase
   use output, only: output_files, open_outputs, close_outputs, write_strains, write_tools, &
                     open_snapshots
   use summary, only: write_summary
   implicit none
   type(deck_type) :: d
   type(error_list) :: errs
   type(model_type) :: m
   type(controls_type) :: ctl
   type(state_type) :: s
   type(output_files) :: out
   type(run_record) :: rec
   character(len=512) :: path, arg, out_override
   integer :: iarg, ios
   character(len=300) :: errmsg
   real(dp) :: t_start, t_end

   path = ''
   out_override = ''
   iarg = 1
   do while (iarg <= command_argument_count())
      call get_command_argument(iarg, arg)
      if (arg == '--output' .or. arg == '-o') then
         iarg = iarg + 1
         call get_command_argument(iarg, out_override)
      else if (arg == '--list-variables') then
         call list_variables(output_unit, ios)
         if (ios /= 0) stop exit_input
         stop
      else if (arg(1:1) == '-') then
         call print_error('unknown option '//trim(arg), 'drawbead')
         path = ''
         exit
      else
         path = arg
      end if
      iarg = iarg + 1
   end do
   if (len_trim(path) == 0) then
      write (error_unit, '(a)') 'usage: drawbead deck.nml [--output DIR] | drawbead --list-variables'
      flush (error_unit)
      stop exit_input
   end if

   ! set-up: every error of the deck and of the files it names, together
   call read_deck(trim(path), d, errs)
   call setup_run(d, m, ctl, errs)
   if (errs%count > 0) then
      call report_errors(errs, error_unit)
      flush (error_unit)
      stop exit_input
   end if
   if (len_trim(out_override) > 0) then
      d%output_dir = out_override
      ctl%output_dir = out_override
   end if
   call cpu_time(t_start)
   write (output_unit, '(a)') '# drawbead: '//trim(ctl%title)
   call echo_deck(d, output_unit)

   call state_init(m, s)
   call run_record_init(rec)
   call open_outputs(trim(ctl%output_dir), trim(ctl%title), out, errmsg)
   if (len_trim(errmsg) == 0 .and. ctl%snapshot_every_over_h > 0.0_dp) &
      call open_snapshots(out, trim(ctl%title), ctl%snapshot_every_over_h, errmsg)
   if (len_trim(errmsg) > 0) then
      call print_error('deck '''//trim(d%deck_file)//''', group &control, '// &
                       'variable output_dir: '//trim(errmsg))
      stop exit_input
   end if

   if (m%has_tools .and. m%lock_depth > 0.0_dp) then
      call run_phase(m, ctl, s, 'lock', 0.0_dp, m%lock_depth, out, rec)
   end if
   call write_strains(trim(ctl%output_dir)//'/strain_lock.dat', m, s, 'after locking')
   call write_tools(trim(ctl%output_dir)//'/tools_lock.dat', m, s%shift, 'at the end of locking')
   if (rec%status == run_ok .and. .not. (rec%localized .and. ctl%stop_at_localization)) then
      call run_phase(m, ctl, s, 'pull', 0.0_dp, m%pull_distance, out, rec)
   end if
   call write_strains(trim(ctl%output_dir)//'/strain_pull.dat', m, s, 'after pulling')
   call write_tools(trim(ctl%output_dir)//'/tools_pull.dat', m, s%shift, 'at the end of pulling')
   call close_outputs(out)
   call cpu_time(t_end)
   call write_summary(trim(ctl%output_dir)//'/summary.txt', m, s, ctl, rec, t_end - t_start)
   if (rec%status /= run_ok) then
      call print_error(trim(rec%message), 'run_phase')
      stop exit_noconvergence
   end if
end program drawbead
