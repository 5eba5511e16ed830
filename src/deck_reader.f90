!> deck_reader -- reading an input deck, echoing it and listing its
!> variables.
!>
!> As in WRF: defaults are assigned before reading (the deck_type's
!> initial values), each group is read on its own (order does not
!> matter), a missing group means defaults, every problem is collected into
!> an error_list (nothing stops here) and the resolved values are echoed
!> with write(nml=).  A group that fails to read is re-read one assignment
!> at a time (deck_scan), so that each bad variable is named.
!>
!> The deck file is read once, whole (os's read_file, at most
!> max_input_bytes), and each group is read from its text as found by
!> deck_scan, never from the file again: nothing seeks, so a deck from a
!> pipe, /dev/stdin or bash's <(...) reads like any file.
!>
!> The namelist variables live only in the private per-group routines
!> nml_control ... nml_loading, which copy between them and a deck_type.
module deck_reader
   use, intrinsic :: ieee_exceptions, only: ieee_usual, ieee_get_halting_mode, &
      ieee_set_halting_mode, ieee_set_flag
   use kinds, only: dp
   use errors, only: error_list, add_error, warn
   use text, only: lower, itoa, max_input_bytes, max_line_length, first_long_line
   use os, only: read_file
   use deck, only: deck_type, group_names, resolve_defaults, validate_deck, max_umat_props, &
                   max_kinematic
   use deck_scan, only: group_text, scan_groups, split_assignments, check_repeated, clip, value_problem, &
                        strip_separators, is_letter
   implicit none
   private
   public :: read_deck, echo_deck, list_variables

   !> Internal buffer for writing one group: record length and count.
   integer, parameter :: echo_len = 1024, echo_rows = 64

   !> What a per-group namelist routine does.
   integer, parameter :: act_read_text = 1, act_write = 2

contains

   !> read_deck -- read, resolve and validate an input deck.
   !>
   !> path  [in]     the deck file name.
   !> d     [out]    every input: the values read, defaults for the rest,
   !>                h-scaled defaults resolved, choices lower case.
   !>                Meaningful only when no
   !>                error was added (an unreadable deck leaves the defaults).
   !> errs  [in,out] every problem found is appended (all of them, not only
   !>                the first); warnings are printed to error_unit at once.
   subroutine read_deck(path, d, errs)
      character(len=*), intent(in) :: path
      type(deck_type), intent(out) :: d
      type(error_list), intent(inout) :: errs

      character(len=:), allocatable :: text, why
      type(group_text) :: found(size(group_names))
      integer :: ios, g

      d%deck_file = path
      if (len_trim(path) >= len(d%deck_file)) then
         call add_error(errs, "deck '"//trim(path)//"': file name is too long (at most " &
                        //itoa(len(d%deck_file) - 1)//" characters)")
         call resolve_defaults(d)
         return
      end if

      ! the deck is read once, whole, into memory, and every group is read
      ! from that text: nothing seeks, so a pipe or /dev/stdin is a deck
      ! like any file (a rewind of a pipe is gfortran's "Illegal seek")
      call read_file(path, max_input_bytes, text, ios, why)
      if (ios /= 0) then
         call add_error(errs, "deck '"//trim(path)//"': cannot read the file ("//why//")")
         call resolve_defaults(d)
         return
      end if
      ios = first_long_line(text)
      if (ios > 0) then
         call add_error(errs, "deck '"//trim(path)//"', line "//itoa(ios)//": longer than "// &
                        itoa(max_line_length)//" characters: not a drawbead deck")
         call resolve_defaults(d)
         return
      end if
      call scan_groups(text, path, group_names, found, errs)
      if (.not. any(found%present)) call add_error(errs, "deck '"//trim(path)// &
         "': no namelist group of the program (&control, &sheet, &material, &tools, &loading):"// &
         ' not a drawbead deck')

      do g = 1, size(group_names)
         call read_group(d, trim(group_names(g)), path, found(g), errs)
      end do

      ! a tab in the title reads as a blank; any other control character
      ! in a text value is refused by validate_deck (issue 28, item 8)
      do g = 1, len_trim(d%title)
         if (d%title(g:g) == achar(9)) d%title(g:g) = ' '
      end do
      d%left_edge = lower(adjustl(d%left_edge))
      d%normal_stress = lower(adjustl(d%normal_stress))
      d%tearing_criterion = lower(adjustl(d%tearing_criterion))
      d%hardening = lower(adjustl(d%hardening))
      d%model = lower(adjustl(d%model))
      d%drawing_direction = lower(adjustl(d%drawing_direction))
      d%friction_law = lower(adjustl(d%friction_law))
      d%contact_faces = lower(adjustl(d%contact_faces))
      d%bead = lower(adjustl(d%bead))
      call resolve_defaults(d)
      call validate_deck(d, errs)
   end subroutine read_deck

   !> echo_deck -- write the resolved input as namelist groups.
   !>
   !> The output starts with a `! resolved input` line and is itself a valid
   !> deck (gfortran writes the names in upper case; reading is case-blind).
   !>
   !> d     [in] a deck, normally as returned by read_deck.
   !> unit  [in] an open formatted unit.
   subroutine echo_deck(d, unit)
      type(deck_type), intent(in) :: d
      integer, intent(in) :: unit

      type(deck_type) :: work
      character(len=echo_len) :: lines(echo_rows)
      character(len=512) :: msg
      integer :: g, ios

      work = d
      write (unit, '(a)') '! resolved input'
      if (len_trim(d%deck_file) > 0) write (unit, '(a)') "! deck '"//trim(d%deck_file)//"'"
      do g = 1, size(group_names)
         msg = ''
         call group_io(trim(group_names(g)), work, act_write, '', ios, msg, lines)
         if (ios == 0) then
            call put_lines(unit, lines)
         else
            call warn('echo of group &'//trim(group_names(g))//' failed: '//trim(msg), 'echo_deck')
         end if
      end do
   end subroutine echo_deck

   !> list_variables -- every deck variable, one line each:
   !> `group variable type`, type one of real, integer, logical, text, lower
   !> case, groups in the order they are read.  Taken from the namelists
   !> themselves (a write of each group with its defaults), so the list
   !> cannot go stale; scripts/sweep.sh reads it.
   !>
   !> unit  [in] an open formatted unit.
   !> ios   [out] 0, or the iostat of a failed write.
   subroutine list_variables(unit, ios)
      integer, intent(in) :: unit
      integer, intent(out) :: ios

      type(deck_type) :: defaults
      character(len=echo_len) :: lines(echo_rows)
      character(len=512) :: msg
      character(len=:), allocatable :: name, written, vtype
      integer :: g, k, eq

      do g = 1, size(group_names)
         msg = ''
         call group_io(trim(group_names(g)), defaults, act_write, '', ios, msg, lines)
         if (ios /= 0) return
         do k = 1, size(lines)
            eq = index(lines(k), '=')
            if (eq == 0) cycle
            name = lower(trim(adjustl(lines(k)(1:eq - 1))))
            written = trim(adjustl(lines(k)(eq + 1:)))
            if (written(1:1) == '"') then
               vtype = 'text'
            else if (written(1:1) == 'T' .or. written(1:1) == 'F') then
               vtype = 'logical'
            else if (scan(written, '.E') > 0) then
               vtype = 'real'
            else
               vtype = 'integer'
            end if
            write (unit, '(a)', iostat=ios) trim(group_names(g))//' '//name//' '//vtype
            if (ios /= 0) return
         end do
      end do
   end subroutine list_variables

   !> group_io -- dispatch to the namelist routine of a group.
   !>
   !> group   [in]     group name without '&', lower case.
   !> d       [in,out] the deck; changed only by a successful read.
   !> action  [in]     act_read_text or act_write.
   !> text    [in]     '&group ... /' for act_read_text, else unused.
   !> ios     [out]    iostat of the transfer (0 = success).
   !> msg     [in,out] iomsg of the transfer, set only when ios /= 0.
   !> lines   [out]    act_write: the group as write(nml=) gives it, one
   !>                  record per line (blank padded); else blank.
   subroutine group_io(group, d, action, text, ios, msg, lines)
      character(len=*), intent(in) :: group
      type(deck_type), intent(inout) :: d
      integer, intent(in) :: action
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      character(len=echo_len), intent(out) :: lines(echo_rows)

      logical :: halting(size(ieee_usual))

      ! A value such as 1e999 overflows inside the run-time library's
      ! conversion; it must become +Infinity (rejected by validate), not a
      ! trap in a build with -ffpe-trap=overflow.
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      select case (group)
      case ('control')
         call nml_control(d, action, text, ios, msg, lines)
      case ('sheet')
         call nml_sheet(d, action, text, ios, msg, lines)
      case ('material')
         call nml_material(d, action, text, ios, msg, lines)
      case ('tools')
         call nml_tools(d, action, text, ios, msg, lines)
      case ('loading')
         call nml_loading(d, action, text, ios, msg, lines)
      case default
         ios = -999
         msg = 'no such group &'//group
      end select
      call ieee_set_flag(ieee_usual, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)
   end subroutine group_io

   !> nml_control -- namelist &control (arguments as group_io).
   subroutine nml_control(d, action, text, ios, msg, lines)
      type(deck_type), intent(inout) :: d
      integer, intent(in) :: action
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      character(len=echo_len), intent(out) :: lines(echo_rows)

      character(len=256) :: title
      character(len=512) :: output_dir
      logical :: stop_at_localization, log_residuals, predictor
      real(dp) :: tearing_length, fold_curvature, snapshot_every
      character(len=16) :: tearing_criterion
      namelist /control/ title, output_dir, stop_at_localization, tearing_criterion, tearing_length, &
         fold_curvature, log_residuals, predictor, snapshot_every

      title = d%title
      output_dir = d%output_dir
      stop_at_localization = d%stop_at_localization
      log_residuals = d%log_residuals
      predictor = d%predictor
      tearing_criterion = d%tearing_criterion
      tearing_length = d%tearing_length
      fold_curvature = d%fold_curvature
      snapshot_every = d%snapshot_every
      select case (action)
      case (act_read_text)
         read (text, nml=control, iostat=ios, iomsg=msg)
      case default
         lines = ''
         write (lines, nml=control, delim='quote', iostat=ios, iomsg=msg)
      end select
      if (ios /= 0 .or. action == act_write) return
      d%title = title
      d%output_dir = output_dir
      d%stop_at_localization = stop_at_localization
      d%log_residuals = log_residuals
      d%predictor = predictor
      d%tearing_criterion = tearing_criterion
      d%tearing_length = tearing_length
      d%fold_curvature = fold_curvature
      d%snapshot_every = snapshot_every
   end subroutine nml_control

   !> nml_sheet -- namelist &sheet (arguments as group_io).
   subroutine nml_sheet(d, action, text, ios, msg, lines)
      type(deck_type), intent(inout) :: d
      integer, intent(in) :: action
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      character(len=echo_len), intent(out) :: lines(echo_rows)

      real(dp) :: thickness, length, mesh_beta, back_tension, strain_gradient
      real(dp) :: refine_from, refine_to, refine_element
      integer :: n_elements
      logical :: refine_neck, refine_exit
      character(len=16) :: left_edge, normal_stress
      namelist /sheet/ thickness, length, n_elements, mesh_beta, left_edge, back_tension, &
         normal_stress, strain_gradient, refine_from, refine_to, refine_element, refine_neck, refine_exit

      thickness = d%thickness
      length = d%length
      n_elements = d%n_elements
      mesh_beta = d%mesh_beta
      left_edge = d%left_edge
      back_tension = d%back_tension
      normal_stress = d%normal_stress
      strain_gradient = d%strain_gradient
      refine_from = d%refine_from
      refine_to = d%refine_to
      refine_element = d%refine_element
      refine_neck = d%refine_neck
      refine_exit = d%refine_exit
      select case (action)
      case (act_read_text)
         read (text, nml=sheet, iostat=ios, iomsg=msg)
      case default
         lines = ''
         write (lines, nml=sheet, delim='quote', iostat=ios, iomsg=msg)
      end select
      if (ios /= 0 .or. action == act_write) return
      d%thickness = thickness
      d%length = length
      d%n_elements = n_elements
      d%mesh_beta = mesh_beta
      d%left_edge = left_edge
      d%back_tension = back_tension
      d%normal_stress = normal_stress
      d%strain_gradient = strain_gradient
      d%refine_from = refine_from
      d%refine_to = refine_to
      d%refine_element = refine_element
      d%refine_neck = refine_neck
      d%refine_exit = refine_exit
   end subroutine nml_sheet

   !> nml_material -- namelist &material (arguments as group_io).
   subroutine nml_material(d, action, text, ios, msg, lines)
      type(deck_type), intent(inout) :: d
      integer, intent(in) :: action
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      character(len=echo_len), intent(out) :: lines(echo_rows)

      character(len=16) :: model, hardening, drawing_direction
      real(dp) :: umat_props(max_umat_props)
      integer :: umat_nstatv, umat_eqps_index
      real(dp) :: youngs_modulus, poissons_ratio, r_value, r0, r90
      real(dp) :: swift_k, swift_eps0, swift_n, voce_sigma0, voce_q, voce_b
      real(dp) :: kinematic_c(max_kinematic), kinematic_gamma(max_kinematic)
      character(len=512) :: curve_file
      integer :: thickness_points
      namelist /material/ model, umat_props, umat_nstatv, umat_eqps_index, youngs_modulus, &
         poissons_ratio, r_value, r0, r90, drawing_direction, hardening, &
         swift_k, swift_eps0, swift_n, voce_sigma0, voce_q, voce_b, curve_file, &
         kinematic_c, kinematic_gamma, thickness_points

      model = d%model
      umat_props = d%umat_props
      umat_nstatv = d%umat_nstatv
      umat_eqps_index = d%umat_eqps_index
      r0 = d%r0
      r90 = d%r90
      drawing_direction = d%drawing_direction
      kinematic_c = d%kinematic_c
      kinematic_gamma = d%kinematic_gamma
      youngs_modulus = d%youngs_modulus
      poissons_ratio = d%poissons_ratio
      r_value = d%r_value
      hardening = d%hardening
      swift_k = d%swift_k
      swift_eps0 = d%swift_eps0
      swift_n = d%swift_n
      voce_sigma0 = d%voce_sigma0
      voce_q = d%voce_q
      voce_b = d%voce_b
      curve_file = d%curve_file
      thickness_points = d%thickness_points
      select case (action)
      case (act_read_text)
         read (text, nml=material, iostat=ios, iomsg=msg)
      case default
         lines = ''
         write (lines, nml=material, delim='quote', iostat=ios, iomsg=msg)
      end select
      if (ios /= 0 .or. action == act_write) return
      d%model = model
      d%umat_props = umat_props
      d%umat_nstatv = umat_nstatv
      d%umat_eqps_index = umat_eqps_index
      d%r0 = r0
      d%r90 = r90
      d%drawing_direction = drawing_direction
      d%kinematic_c = kinematic_c
      d%kinematic_gamma = kinematic_gamma
      d%youngs_modulus = youngs_modulus
      d%poissons_ratio = poissons_ratio
      d%r_value = r_value
      d%hardening = hardening
      d%swift_k = swift_k
      d%swift_eps0 = swift_eps0
      d%swift_n = swift_n
      d%voce_sigma0 = voce_sigma0
      d%voce_q = voce_q
      d%voce_b = voce_b
      d%curve_file = curve_file
      d%thickness_points = thickness_points
   end subroutine nml_material

   !> nml_tools -- namelist &tools (arguments as group_io).
   subroutine nml_tools(d, action, text, ios, msg, lines)
      type(deck_type), intent(inout) :: d
      integer, intent(in) :: action
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      character(len=echo_len), intent(out) :: lines(echo_rows)

      character(len=16) :: bead
      real(dp) :: r1, r2, b1, b2, h1, h2
      character(len=512) :: upper_profile, lower_profile
      real(dp) :: penalty, friction, friction_eps, contact_smoothing
      character(len=16) :: friction_law, contact_faces
      character(len=512) :: friction_file
      real(dp) :: friction_p_ref, friction_m, friction_mu_min, friction_mu_max
      namelist /tools/ bead, r1, r2, b1, b2, h1, h2, upper_profile, lower_profile, &
         penalty, friction, friction_eps, contact_smoothing, friction_law, friction_file, &
         friction_p_ref, friction_m, friction_mu_min, friction_mu_max, contact_faces

      bead = d%bead
      r1 = d%r1
      r2 = d%r2
      b1 = d%b1
      b2 = d%b2
      h1 = d%h1
      h2 = d%h2
      upper_profile = d%upper_profile
      lower_profile = d%lower_profile
      penalty = d%penalty
      friction = d%friction
      friction_eps = d%friction_eps
      contact_smoothing = d%contact_smoothing
      friction_law = d%friction_law
      friction_file = d%friction_file
      friction_p_ref = d%friction_p_ref
      friction_m = d%friction_m
      friction_mu_min = d%friction_mu_min
      friction_mu_max = d%friction_mu_max
      contact_faces = d%contact_faces
      select case (action)
      case (act_read_text)
         read (text, nml=tools, iostat=ios, iomsg=msg)
      case default
         lines = ''
         write (lines, nml=tools, delim='quote', iostat=ios, iomsg=msg)
      end select
      if (ios /= 0 .or. action == act_write) return
      d%bead = bead
      d%r1 = r1
      d%r2 = r2
      d%b1 = b1
      d%b2 = b2
      d%h1 = h1
      d%h2 = h2
      d%upper_profile = upper_profile
      d%lower_profile = lower_profile
      d%penalty = penalty
      d%friction = friction
      d%friction_eps = friction_eps
      d%contact_smoothing = contact_smoothing
      d%friction_law = friction_law
      d%friction_file = friction_file
      d%friction_p_ref = friction_p_ref
      d%friction_m = friction_m
      d%friction_mu_min = friction_mu_min
      d%friction_mu_max = friction_mu_max
      d%contact_faces = contact_faces
   end subroutine nml_tools

   !> nml_loading -- namelist &loading (arguments as group_io).
   subroutine nml_loading(d, action, text, ios, msg, lines)
      type(deck_type), intent(inout) :: d
      integer, intent(in) :: action
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      character(len=echo_len), intent(out) :: lines(echo_rows)

      real(dp) :: lock_depth, pull_distance, initial_increment, min_increment, &
                  max_increment, tolerance, squeeze_force_change, max_force_change, step_tolerance, &
                  branch_increment
      integer :: max_iterations
      namelist /loading/ lock_depth, pull_distance, initial_increment, min_increment, &
         max_increment, max_iterations, tolerance, squeeze_force_change, max_force_change, &
         step_tolerance, branch_increment

      lock_depth = d%lock_depth
      pull_distance = d%pull_distance
      initial_increment = d%initial_increment
      min_increment = d%min_increment
      max_increment = d%max_increment
      max_iterations = d%max_iterations
      tolerance = d%tolerance
      squeeze_force_change = d%squeeze_force_change
      max_force_change = d%max_force_change
      step_tolerance = d%step_tolerance
      branch_increment = d%branch_increment
      select case (action)
      case (act_read_text)
         read (text, nml=loading, iostat=ios, iomsg=msg)
      case default
         lines = ''
         write (lines, nml=loading, delim='quote', iostat=ios, iomsg=msg)
      end select
      if (ios /= 0 .or. action == act_write) return
      d%lock_depth = lock_depth
      d%pull_distance = pull_distance
      d%initial_increment = initial_increment
      d%min_increment = min_increment
      d%max_increment = max_increment
      d%max_iterations = max_iterations
      d%tolerance = tolerance
      d%squeeze_force_change = squeeze_force_change
      d%max_force_change = max_force_change
      d%step_tolerance = step_tolerance
      d%branch_increment = branch_increment
   end subroutine nml_loading

   !> put_lines -- write namelist output lines, dropping the blank padding
   !> of quoted strings (`TITLE="abc   ",` becomes `TITLE="abc",`).
   !>
   !> unit   [in] an open formatted unit.
   !> lines  [in] the output of an internal write(nml=, delim='quote').
   subroutine put_lines(unit, lines)
      integer, intent(in) :: unit
      character(len=*), intent(in) :: lines(:)

      integer :: i, k

      do i = 1, size(lines)
         k = len_trim(lines(i))
         if (k == 0) cycle
         if (k >= 3) then
            if (lines(i)(k - 1:k) == '",') then
               write (unit, '(a)') trim(lines(i)(1:k - 2))//'",'
               cycle
            end if
         end if
         write (unit, '(a)') lines(i)(1:k)
      end do
   end subroutine put_lines

   !> read_group -- read one namelist group from the deck's text, diagnosing
   !> errors.
   !>
   !> d      [in,out] the deck; takes the values of the group.
   !> group  [in]     group name, lower case, without '&'.
   !> path   [in]     deck name, for messages.
   !> gt     [in]     what scan_groups found for this group: its body is
   !>                 read (a missing group leaves the defaults).
   !> errs   [in,out] problems are appended.
   subroutine read_group(d, group, path, gt, errs)
      type(deck_type), intent(inout) :: d
      character(len=*), intent(in) :: group
      character(len=*), intent(in) :: path
      type(group_text), intent(in) :: gt
      type(error_list), intent(inout) :: errs

      character(len=echo_len) :: lines(echo_rows)
      character(len=512) :: msg
      integer :: ios, n_before

      if (.not. gt%present) return   ! group absent: defaults
      call check_repeated(group, gt%body, path, errs)
      ! (a value check's error names the variable: no second, nameless one)
      n_before = errs%count
      call check_values(group, gt%body, path, errs)
      msg = ''
      if (gt%terminated) then
         call group_io(group, d, act_read_text, '&'//group//' '//gt%body//' /', ios, msg, lines)
         if (ios == 0) return
      else
         ! the deck ends inside the group (scan_groups ends a group at '/',
         ! '&end' and '&name')
         call add_error(errs, "deck '"//trim(path)//"', group &"//group// &
                        ": no '/' ends the group")
         call group_io(group, d, act_read_text, '&'//group//' '//gt%body//' /', ios, msg, lines)
         if (ios == 0) return
      end if

      call diagnose_group(d, group, gt%body, path, errs)
      if (errs%count == n_before .and. gt%terminated) &
         call add_error(errs, "deck '"//trim(path)//"', group &"//group// &
                        ": cannot read the group ("//trim(msg)//")")
   end subroutine read_group

   !> check_values -- each assignment's value as deck_scan's value_problem
   !> sees it (a null value, a malformed number: what a namelist read
   !> would take silently or blame on no variable), one error per variable.
   !>
   !> group  [in]     group name, lower case.
   !> body   [in]     the group's text without '&group' and '/'.
   !> path   [in]     deck name, for messages.
   !> errs   [in,out] problems are appended.
   subroutine check_values(group, body, path, errs)
      character(len=*), intent(in) :: group, body, path
      type(error_list), intent(inout) :: errs

      integer, allocatable :: starts(:), eqs(:)
      character(len=:), allocatable :: var, why
      integer :: k, last

      call split_assignments(body, starts, eqs)
      do k = 1, size(starts)
         last = len(body)
         if (k < size(starts)) last = starts(k + 1) - 1
         var = lower(trim(body(starts(k):eqs(k) - 1)))
         if (len(var) == 0) cycle   ! diagnose_group names it
         why = value_problem(body(eqs(k) + 1:last))
         if (len(why) > 0) call add_error(errs, "deck '"//trim(path)//"', group &"//group// &
                                          ", variable "//var//": "//why)
      end do
   end subroutine check_values

   !> diagnose_group -- re-read a group one assignment at a time.
   !>
   !> The body is split into `name = value` assignments (split before each
   !> name that precedes an unquoted '='), and each is read alone into the
   !> group's namelist from an internal file. Good assignments are applied to
   !> d, so a bad value leaves only its own variable at the default; each
   !> failing assignment is reported with its variable.
   !>
   !> d      [in,out] the deck; takes every assignment that reads.
   !> group  [in]     group name, lower case.
   !> body   [in]     the group's text without '&group' and '/'.
   !> path   [in]     deck name, for messages.
   !> errs   [in,out] one error per failing assignment or stray text.
   subroutine diagnose_group(d, group, body, path, errs)
      type(deck_type), intent(inout) :: d
      character(len=*), intent(in) :: group
      character(len=*), intent(in) :: body
      character(len=*), intent(in) :: path
      type(error_list), intent(inout) :: errs

      character(len=*), parameter :: no_match = 'Cannot match namelist object name'
      integer, allocatable :: starts(:), eqs(:)
      character(len=:), allocatable :: var, value, why, ctx
      character(len=echo_len) :: lines(echo_rows)
      character(len=512) :: msg, name_msg
      integer :: k, last, ios, name_ios

      call split_assignments(body, starts, eqs)
      ctx = "deck '"//trim(path)//"', group &"//group
      if (size(starts) == 0) then
         if (len_trim(body) > 0) call add_error(errs, ctx//": cannot read '"// &
                                                clip(trim(adjustl(body)))//"'")
         return
      end if
      value = strip_separators(body(1:starts(1) - 1))
      if (len(value) > 0) call add_error(errs, ctx//": unexpected text '"//clip(value)//"'")

      do k = 1, size(starts)
         last = len(body)
         if (k < size(starts)) last = starts(k + 1) - 1
         var = lower(trim(body(starts(k):eqs(k) - 1)))
         value = strip_separators(body(eqs(k) + 1:last))
         if (len(var) == 0) then
            call add_error(errs, ctx//": '=' without a variable name before '"// &
                           clip(value)//"'")
            cycle
         end if
         msg = ''
         call group_io(group, d, act_read_text, '&'//group//' '//body(starts(k):last)//' /', &
                       ios, msg, lines)
         if (ios == 0) cycle

         ! is the name known? a null value ('name = /') reads for any known name
         name_msg = ''
         call group_io(group, d, act_read_text, '&'//group//' '//var//' = /', name_ios, &
                       name_msg, lines)
         if (name_ios /= 0 .and. index(name_msg, no_match) == 1) then
            call add_error(errs, ctx//", variable "//var//": unknown variable ("// &
                           trim(name_msg)//")")
            cycle
         end if
         if (index(msg, no_match) == 1) then
            ! gfortran names the unreadable value as if it were an object name
            why = 'wrong type for this variable'
            if (len(value) > 0) then
               if (is_letter(value(1:1))) &
                  why = 'not a number or a logical; text values must be in quotes'
            end if
            why = why//'; gfortran: '//trim(msg)
         else
            why = trim(msg)
         end if
         call add_error(errs, ctx//", variable "//var//": cannot read value "// &
                        clip(value)//" ("//why//")")
      end do
   end subroutine diagnose_group

end module deck_reader
