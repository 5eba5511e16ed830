!> drawbead -- plane-strain analysis of a sheet locked into a drawbead and
!> pulled through it (Triantafyllidis, Maker & Samanta, 1986).
!>
!> Usage: drawbead deck.nml [--output DIR]
!>   --output DIR (or -o DIR) overrides &control output_dir.
!> Exit status: 0 done, 1 bad input, 2 no convergence (results so far kept).
program drawbead
   use kinds, only: dp, output_unit, error_unit
   use errors, only: error_list, report_errors
   use deck, only: deck_type, read_deck, echo_deck, material_props
   use model, only: model_type, state_type, model_init, state_init
   use material, only: builtin_material
   use tools, only: build_rectangular_bead, read_profile
   use analysis, only: run_record, run_record_init, run_phase
   use output, only: output_files, open_outputs, close_outputs, write_strains, write_tools, &
                     open_snapshots
   use summary, only: write_summary
   implicit none
   type(deck_type) :: d
   type(error_list) :: errs
   type(model_type) :: m
   type(state_type) :: s
   type(output_files) :: out
   type(run_record) :: rec
   character(len=512) :: path, arg, out_override
   integer :: iarg
   character(len=300) :: errmsg
   real(dp) :: t_start, t_end, h, margin

   path = ''
   out_override = ''
   iarg = 1
   do while (iarg <= command_argument_count())
      call get_command_argument(iarg, arg)
      if (arg == '--output' .or. arg == '-o') then
         iarg = iarg + 1
         call get_command_argument(iarg, out_override)
      else if (arg(1:1) == '-') then
         write (error_unit, '(a)') '*ERROR* unknown option '//trim(arg)
         path = ''
         exit
      else
         path = arg
      end if
      iarg = iarg + 1
   end do
   if (len_trim(path) == 0) then
      write (error_unit, '(a)') 'usage: drawbead deck.nml [--output DIR]'
      stop 1
   end if
   call read_deck(trim(path), d, errs)
   if (errs%count > 0) then
      call report_errors(errs, error_unit)
      flush (error_unit)
      stop 1
   end if
   if (len_trim(out_override) > 0) d%output_dir = out_override
   call cpu_time(t_start)
   write (output_unit, '(a)') '# drawbead: '//trim(d%title)
   call echo_deck(d, output_unit)

   h = d%thickness
   call model_init(m, d%n_elements, d%length, d%mesh_beta, h, d%thickness_points, &
                   builtin_material(material_props(d)))
   select case (d%bead)
   case ('rectangular')
      margin = 0.5_dp*d%length + 10.0_dp*h
      call build_rectangular_bead(d%r1, d%r2, d%b1, d%b2, d%h1, d%h2, -margin, margin, &
                                  m%tool(1), m%tool(2), errmsg)
      if (len_trim(errmsg) > 0) then
         write (error_unit, '(a)') '*ERROR* deck '''//trim(d%deck_file)//''', group &tools: '// &
            trim(errmsg)
         stop 1
      end if
      m%has_tools = .true.
   case ('profile')
      call read_profile(trim(d%upper_profile), m%tool(1), errmsg)
      if (len_trim(errmsg) == 0 .and. m%tool(1)%side /= 1) &
         errmsg = 'variable upper_profile: '//trim(d%upper_profile)//' is a lower tool (side lower)'
      if (len_trim(errmsg) == 0) call read_profile(trim(d%lower_profile), m%tool(2), errmsg)
      if (len_trim(errmsg) == 0 .and. m%tool(2)%side /= -1) &
         errmsg = 'variable lower_profile: '//trim(d%lower_profile)//' is an upper tool (side upper)'
      if (len_trim(errmsg) > 0) then
         write (error_unit, '(a)') '*ERROR* deck '''//trim(d%deck_file)//''', group &tools: '// &
            trim(errmsg)
         stop 1
      end if
      m%has_tools = .true.
   end select
   m%penalty = d%penalty*d%youngs_modulus/h
   m%friction = d%friction
   m%contact_smoothing = d%contact_smoothing*h
   m%friction_eps = d%friction_eps*h
   call state_init(m, s)
   call run_record_init(rec)

   call open_outputs(trim(d%output_dir), trim(d%title), out, errmsg)
   if (len_trim(errmsg) == 0 .and. d%snapshot_every > 0.0_dp) &
      call open_snapshots(out, trim(d%title), d%snapshot_every, errmsg)
   if (len_trim(errmsg) > 0) then
      write (error_unit, '(a)') '*ERROR* deck '''//trim(d%deck_file)//''', group &control, '// &
         'variable output_dir: '//trim(errmsg)
      stop 1
   end if

   if (m%has_tools .and. d%lock_depth > 0.0_dp) then
      call run_phase(m, d, s, 'lock', 0.0_dp, d%lock_depth, out, rec)
   end if
   call write_strains(trim(d%output_dir)//'/strain_lock.dat', m, s, 'after locking')
   call write_tools(trim(d%output_dir)//'/tools_lock.dat', m, s%shift, 'at the end of locking')
   if (rec%status == 0 .and. .not. (rec%localized .and. d%stop_at_localization)) then
      call run_phase(m, d, s, 'pull', 0.0_dp, d%pull_distance, out, rec)
   end if
   call write_strains(trim(d%output_dir)//'/strain_pull.dat', m, s, 'after pulling')
   call write_tools(trim(d%output_dir)//'/tools_pull.dat', m, s%shift, 'at the end of pulling')
   call close_outputs(out)
   call cpu_time(t_end)
   call write_summary(trim(d%output_dir)//'/summary.txt', m, s, d, rec, t_end - t_start)
   if (rec%status /= 0) then
      write (error_unit, '(a)') '*ERROR* '//trim(rec%message)
      stop 2
   end if
end program drawbead
