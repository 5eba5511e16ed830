!> deck -- the input deck: namelist groups, defaults, validation, echo.
!>
!> A deck is a text file of Fortran namelist groups, in any order, each
!> optional:
!>
!>   &control   title, output_dir, stop_at_localization, tearing_length, fold_curvature,
!>              log_residuals, predictor, snapshot_every
!>   &sheet     thickness, length, n_elements, mesh_beta, left_edge,
!>              back_tension
!>   &material  youngs_modulus, poissons_ratio, r_value, hardening,
!>              swift_k, swift_eps0, swift_n, voce_sigma0, voce_q, voce_b,
!>              curve_file, thickness_points
!>   &tools     bead, r1, r2, b1, b2, h1, h2, upper_profile, lower_profile,
!>              penalty, friction, friction_eps, contact_smoothing
!>   &loading   lock_depth, pull_distance, initial_increment,
!>              min_increment, max_increment, max_iterations, tolerance,
!>              max_force_change, squeeze_force_change
!>
!> Units: lengths mm, stresses MPa, forces per unit width N/mm; penalty is
!> k h / E, friction_eps is in units of h. Text values must be quoted.
!>
!> As in WRF: defaults are assigned before reading, each group is read after
!> a rewind (order does not matter), a missing group means defaults, every
!> problem is collected into an error_list (nothing stops here) and the
!> resolved values can be echoed with write(nml=). Defaults that scale with
!> the thickness h carry the sentinel `unset` until the deck is read and are
!> then resolved, so a value given by the user always wins.
!>
!> File names inside a deck (curve_file, upper_profile, lower_profile) are
!> taken relative to the working directory, as given.
!>
!> The namelist variables live only in the private per-group routines
!> nml_control ... nml_loading, which copy between them and a deck_type;
!> the module holds no mutable state.
module deck
   use, intrinsic :: iso_fortran_env, only: iostat_end
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use, intrinsic :: ieee_exceptions, only: ieee_usual, ieee_get_halting_mode, &
      ieee_set_halting_mode, ieee_set_flag
   use kinds, only: dp
   use errors, only: error_list, add_error, warn
   use hardening, only: read_curve_file
   implicit none
   private
   public :: deck_type, read_deck, echo_deck, material_props, lower

   !> Marks a default that is resolved from the thickness after reading.
   real(dp), parameter :: unset = -huge(1.0_dp)

   !> Default sheet thickness h (mm), 0.030 in.
   real(dp), parameter :: default_thickness = 0.762_dp

   !> The namelist groups, in the order they are read and echoed.
   character(len=8), parameter :: group_names(5) = &
      [character(len=8) :: 'control', 'sheet', 'material', 'tools', 'loading']

   !> Internal buffer for echoing one group: record length and count.
   integer, parameter :: echo_len = 1024, echo_rows = 64

   !> What a per-group namelist routine does.
   integer, parameter :: act_read_unit = 1, act_read_text = 2, act_write = 3

   !> Every input of a run, after read_deck: defaults resolved, string
   !> choices lower case, the tabulated curve loaded for hardening 'table'.
   type :: deck_type
      character(len=512) :: deck_file = ''
      ! &control
      character(len=256) :: title = ''
      character(len=512) :: output_dir = ''          ! '' -> 'out/<deck base name>'
      logical :: stop_at_localization = .true.
      logical :: log_residuals = .false.          ! print each increment's Newton residual sequence
      real(dp) :: tearing_length = 1.0_dp         ! averaging length of the mesh-objective tearing measure, units of h
      real(dp) :: fold_curvature = 1.0_dp         ! |rho| h above which the sheet is reported folded (beyond shell theory)
      logical :: predictor = .true.               ! extrapolate the last increment's motion as first guess
      real(dp) :: snapshot_every = 0.0_dp         ! strain snapshot each time H or delta passes a multiple of it, units of h (0: none)
      ! &sheet
      real(dp) :: thickness = default_thickness       ! h, mm
      real(dp) :: length = unset                      ! 2L, mm; default 50 h
      integer :: n_elements = 80
      real(dp) :: mesh_beta = 1.0_dp                  ! grading exponent (4.2)
      character(len=16) :: left_edge = 'clamped'      ! 'clamped' | 'free'
      real(dp) :: back_tension = 0.0_dp               ! N/mm, with 'free' only
      ! &material
      real(dp) :: youngs_modulus = 207000.0_dp        ! MPa
      real(dp) :: poissons_ratio = 0.3_dp
      real(dp) :: r_value = 1.0_dp                    ! normal anisotropy R
      character(len=16) :: hardening = 'swift'        ! 'swift' | 'voce' | 'table'
      real(dp) :: swift_k = 548.0_dp                  ! K (eps0 + ep)^n, MPa
      real(dp) :: swift_eps0 = 0.0085_dp
      real(dp) :: swift_n = 0.23_dp
      real(dp) :: voce_sigma0 = 183.0_dp              ! sigma0 + Q (1 - exp(-b ep))
      real(dp) :: voce_q = 200.0_dp
      real(dp) :: voce_b = 10.0_dp
      character(len=512) :: curve_file = ''           ! 'table': columns ep, sigma
      integer :: thickness_points = 21                ! Simpson stations, odd >= 3
      ! &tools (r1 ... h2 default to bead A scaled by h)
      character(len=16) :: bead = 'none'              ! 'none' | 'rectangular' | 'profile'
      real(dp) :: r1 = unset                          ! 4.66 h
      real(dp) :: r2 = unset                          ! 4.66 h
      real(dp) :: b1 = unset                          ! 4.16 h
      real(dp) :: b2 = unset                          ! 8.83 h
      real(dp) :: h1 = unset                          ! 1.56 h
      real(dp) :: h2 = unset                          ! 5.66 h
      character(len=512) :: upper_profile = ''
      character(len=512) :: lower_profile = ''
      real(dp) :: penalty = 0.045_dp                  ! k h / E
      real(dp) :: friction = 0.0_dp                   ! mu
      real(dp) :: friction_eps = 0.0333_dp            ! eps of (4.3), units of h
      real(dp) :: contact_smoothing = 0.0_dp          ! penalty onset smoothed over this penetration, units of h (0: sharp, as the paper)
      ! &loading
      real(dp) :: lock_depth = unset                  ! h1 + r1 with bead = 'rectangular', 0 with 'none', required with 'profile'
      real(dp) :: pull_distance = unset               ! 10 h
      real(dp) :: initial_increment = unset           ! 0.05 h
      real(dp) :: min_increment = unset               ! 1e-6 h
      real(dp) :: max_increment = unset               ! 0.1 h
      integer :: max_iterations = 20
      real(dp) :: tolerance = 1.0e-8_dp               ! relative residual and correction
      real(dp) :: max_force_change = 0.1_dp           ! target relative change of F (lock) or N (pull) per increment
      real(dp) :: squeeze_force_change = 0.02_dp      ! the same where F rises faster than H^5 while locking
      ! resolved: the tabulated hardening curve (hardening = 'table')
      real(dp), allocatable :: curve_ep(:), curve_sigma(:)
   end type deck_type

   !> The text of one group as found in the deck file.
   type :: group_text
      logical :: present = .false.
      logical :: terminated = .false.
      character(len=:), allocatable :: body     ! between '&name' and '/'
   end type group_text

contains

   !> read_deck -- read, resolve and validate an input deck.
   !>
   !> path  [in]     the deck file name.
   !> d     [out]    every input: the values read, defaults for the rest,
   !>                h-scaled defaults resolved, choices lower case, and the
   !>                curve for hardening = 'table'. Meaningful only when no
   !>                error was added (an unreadable deck leaves the defaults).
   !> errs  [in,out] every problem found is appended (all of them, not only
   !>                the first); warnings are printed to error_unit at once.
   subroutine read_deck(path, d, errs)
      character(len=*), intent(in) :: path
      type(deck_type), intent(out) :: d
      type(error_list), intent(inout) :: errs

      character(len=:), allocatable :: text
      type(group_text) :: found(size(group_names))
      character(len=512) :: msg
      integer :: u, ios, g

      d%deck_file = path
      if (len_trim(path) >= len(d%deck_file)) then
         call add_error(errs, "deck '"//trim(path)//"': file name is too long (at most " &
                        //inum(len(d%deck_file) - 1)//" characters)")
         call resolve_defaults(d)
         return
      end if

      call load_text(path, text, ios, msg)
      if (ios /= 0) then
         call add_error(errs, "deck '"//trim(path)//"': cannot read the file ("//trim(msg)//")")
         call resolve_defaults(d)
         return
      end if
      call scan_groups(text, path, found, errs)

      msg = ''
      open (newunit=u, file=path, status='old', action='read', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call add_error(errs, "deck '"//trim(path)//"': cannot open the file ("//trim(msg)//")")
         call resolve_defaults(d)
         return
      end if
      do g = 1, size(group_names)
         call read_group(d, trim(group_names(g)), u, path, found(g), errs)
      end do
      close (u)

      d%left_edge = lower(adjustl(d%left_edge))
      d%hardening = lower(adjustl(d%hardening))
      d%bead = lower(adjustl(d%bead))
      call resolve_defaults(d)
      call validate(d, errs)
   end subroutine read_deck

   !> echo_deck -- write the resolved input as namelist groups.
   !>
   !> The output starts with a `# resolved input` line and is itself a valid
   !> deck (gfortran writes the names in upper case; reading is case-blind).
   !>
   !> d     [in] a deck, normally as returned by read_deck.
   !> unit  [in] an open formatted unit.
   subroutine echo_deck(d, unit)
      type(deck_type), intent(in) :: d
      integer, intent(in) :: unit

      type(deck_type) :: work
      character(len=512) :: msg
      integer :: g, ios

      work = d
      write (unit, '(a)') '# resolved input'
      if (len_trim(d%deck_file) > 0) write (unit, '(a)') "# deck '"//trim(d%deck_file)//"'"
      do g = 1, size(group_names)
         msg = ''
         call group_io(trim(group_names(g)), work, act_write, unit, '', ios, msg)
         if (ios /= 0) call warn('echo of group &'//trim(group_names(g))//' failed: '//trim(msg))
      end do
   end subroutine echo_deck

   !> material_props -- the UMAT props vector of a deck.
   !>
   !> d      [in] a deck accepted by read_deck.
   !> props  [out] props(1) = E, props(2) = nu, props(3) = R,
   !>              props(4) = law id (1 swift, 2 voce, 3 table, 0 unknown);
   !>              swift: props(5:7) = K, eps0, n;
   !>              voce:  props(5:7) = sigma0, Q, b;
   !>              table: props(5) = m, props(6:5+2m) = ep_1, sigma_1, ...,
   !>                     ep_m, sigma_m.
   pure function material_props(d) result(props)
      type(deck_type), intent(in) :: d
      real(dp), allocatable :: props(:)

      integer :: i, m

      select case (trim(lower(adjustl(d%hardening))))
      case ('swift')
         props = [d%youngs_modulus, d%poissons_ratio, d%r_value, 1.0_dp, &
                  d%swift_k, d%swift_eps0, d%swift_n]
      case ('voce')
         props = [d%youngs_modulus, d%poissons_ratio, d%r_value, 2.0_dp, &
                  d%voce_sigma0, d%voce_q, d%voce_b]
      case ('table')
         m = 0
         if (allocated(d%curve_ep) .and. allocated(d%curve_sigma)) &
            m = min(size(d%curve_ep), size(d%curve_sigma))
         allocate (props(5 + 2*m))
         props(1:5) = [d%youngs_modulus, d%poissons_ratio, d%r_value, 3.0_dp, real(m, dp)]
         do i = 1, m
            props(4 + 2*i) = d%curve_ep(i)
            props(5 + 2*i) = d%curve_sigma(i)
         end do
      case default
         props = [d%youngs_modulus, d%poissons_ratio, d%r_value, 0.0_dp, &
                  0.0_dp, 0.0_dp, 0.0_dp]
      end select
   end function material_props

   !> lower -- a copy of a string with A-Z turned into a-z.
   !>
   !> s  [in]  any string.
   !> r  [out] the same length as s.
   pure function lower(s) result(r)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: r

      integer :: i, c

      r = s
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (c >= iachar('A') .and. c <= iachar('Z')) r(i:i) = achar(c + 32)
      end do
   end function lower

   ! ---------------------------------------------------------------------
   ! Per-group namelists. Each copies d into its namelist variables, reads
   ! (from a unit or from a one-record internal file) or writes the group,
   ! and after a successful read copies the variables back into d. After a
   ! failed read d is left unchanged.
   ! ---------------------------------------------------------------------

   !> group_io -- dispatch to the namelist routine of a group.
   !>
   !> group   [in]     group name without '&', lower case.
   !> d       [in,out] the deck; changed only by a successful read.
   !> action  [in]     act_read_unit, act_read_text or act_write.
   !> unit    [in]     unit to read or write (unused for act_read_text).
   !> text    [in]     '&group ... /' for act_read_text, else unused.
   !> ios     [out]    iostat of the transfer (0 = success).
   !> msg     [in,out] iomsg of the transfer, set only when ios /= 0.
   subroutine group_io(group, d, action, unit, text, ios, msg)
      character(len=*), intent(in) :: group
      type(deck_type), intent(inout) :: d
      integer, intent(in) :: action, unit
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg

      logical :: halting(size(ieee_usual))

      ! A value such as 1e999 overflows inside the run-time library's
      ! conversion; it must become +Infinity (rejected by validate), not a
      ! trap in a build with -ffpe-trap=overflow.
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      select case (group)
      case ('control')
         call nml_control(d, action, unit, text, ios, msg)
      case ('sheet')
         call nml_sheet(d, action, unit, text, ios, msg)
      case ('material')
         call nml_material(d, action, unit, text, ios, msg)
      case ('tools')
         call nml_tools(d, action, unit, text, ios, msg)
      case ('loading')
         call nml_loading(d, action, unit, text, ios, msg)
      case default
         ios = -999
         msg = 'no such group &'//group
      end select
      call ieee_set_flag(ieee_usual, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)
   end subroutine group_io

   !> nml_control -- namelist &control (arguments as group_io).
   subroutine nml_control(d, action, unit, text, ios, msg)
      type(deck_type), intent(inout) :: d
      integer, intent(in) :: action, unit
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg

      character(len=256) :: title
      character(len=512) :: output_dir
      logical :: stop_at_localization, log_residuals, predictor
      real(dp) :: tearing_length, fold_curvature, snapshot_every
      namelist /control/ title, output_dir, stop_at_localization, tearing_length, fold_curvature, &
         log_residuals, predictor, snapshot_every
      character(len=echo_len) :: lines(echo_rows)

      title = d%title
      output_dir = d%output_dir
      stop_at_localization = d%stop_at_localization
      log_residuals = d%log_residuals
      predictor = d%predictor
      tearing_length = d%tearing_length
      fold_curvature = d%fold_curvature
      snapshot_every = d%snapshot_every
      select case (action)
      case (act_read_unit)
         read (unit, nml=control, iostat=ios, iomsg=msg)
      case (act_read_text)
         read (text, nml=control, iostat=ios, iomsg=msg)
      case default
         lines = ''
         write (lines, nml=control, delim='quote', iostat=ios, iomsg=msg)
         if (ios == 0) call put_lines(unit, lines)
      end select
      if (ios /= 0 .or. action == act_write) return
      d%title = title
      d%output_dir = output_dir
      d%stop_at_localization = stop_at_localization
      d%log_residuals = log_residuals
      d%predictor = predictor
      d%tearing_length = tearing_length
      d%fold_curvature = fold_curvature
      d%snapshot_every = snapshot_every
   end subroutine nml_control

   !> nml_sheet -- namelist &sheet (arguments as group_io).
   subroutine nml_sheet(d, action, unit, text, ios, msg)
      type(deck_type), intent(inout) :: d
      integer, intent(in) :: action, unit
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg

      real(dp) :: thickness, length, mesh_beta, back_tension
      integer :: n_elements
      character(len=16) :: left_edge
      namelist /sheet/ thickness, length, n_elements, mesh_beta, left_edge, back_tension
      character(len=echo_len) :: lines(echo_rows)

      thickness = d%thickness
      length = d%length
      n_elements = d%n_elements
      mesh_beta = d%mesh_beta
      left_edge = d%left_edge
      back_tension = d%back_tension
      select case (action)
      case (act_read_unit)
         read (unit, nml=sheet, iostat=ios, iomsg=msg)
      case (act_read_text)
         read (text, nml=sheet, iostat=ios, iomsg=msg)
      case default
         lines = ''
         write (lines, nml=sheet, delim='quote', iostat=ios, iomsg=msg)
         if (ios == 0) call put_lines(unit, lines)
      end select
      if (ios /= 0 .or. action == act_write) return
      d%thickness = thickness
      d%length = length
      d%n_elements = n_elements
      d%mesh_beta = mesh_beta
      d%left_edge = left_edge
      d%back_tension = back_tension
   end subroutine nml_sheet

   !> nml_material -- namelist &material (arguments as group_io).
   subroutine nml_material(d, action, unit, text, ios, msg)
      type(deck_type), intent(inout) :: d
      integer, intent(in) :: action, unit
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg

      real(dp) :: youngs_modulus, poissons_ratio, r_value
      character(len=16) :: hardening
      real(dp) :: swift_k, swift_eps0, swift_n, voce_sigma0, voce_q, voce_b
      character(len=512) :: curve_file
      integer :: thickness_points
      namelist /material/ youngs_modulus, poissons_ratio, r_value, hardening, &
         swift_k, swift_eps0, swift_n, voce_sigma0, voce_q, voce_b, curve_file, &
         thickness_points
      character(len=echo_len) :: lines(echo_rows)

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
      case (act_read_unit)
         read (unit, nml=material, iostat=ios, iomsg=msg)
      case (act_read_text)
         read (text, nml=material, iostat=ios, iomsg=msg)
      case default
         lines = ''
         write (lines, nml=material, delim='quote', iostat=ios, iomsg=msg)
         if (ios == 0) call put_lines(unit, lines)
      end select
      if (ios /= 0 .or. action == act_write) return
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
   subroutine nml_tools(d, action, unit, text, ios, msg)
      type(deck_type), intent(inout) :: d
      integer, intent(in) :: action, unit
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg

      character(len=16) :: bead
      real(dp) :: r1, r2, b1, b2, h1, h2
      character(len=512) :: upper_profile, lower_profile
      real(dp) :: penalty, friction, friction_eps, contact_smoothing
      namelist /tools/ bead, r1, r2, b1, b2, h1, h2, upper_profile, lower_profile, &
         penalty, friction, friction_eps, contact_smoothing
      character(len=echo_len) :: lines(echo_rows)

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
      select case (action)
      case (act_read_unit)
         read (unit, nml=tools, iostat=ios, iomsg=msg)
      case (act_read_text)
         read (text, nml=tools, iostat=ios, iomsg=msg)
      case default
         lines = ''
         write (lines, nml=tools, delim='quote', iostat=ios, iomsg=msg)
         if (ios == 0) call put_lines(unit, lines)
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
   end subroutine nml_tools

   !> nml_loading -- namelist &loading (arguments as group_io).
   subroutine nml_loading(d, action, unit, text, ios, msg)
      type(deck_type), intent(inout) :: d
      integer, intent(in) :: action, unit
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg

      real(dp) :: lock_depth, pull_distance, initial_increment, min_increment, &
                  max_increment, tolerance, squeeze_force_change, max_force_change
      integer :: max_iterations
      namelist /loading/ lock_depth, pull_distance, initial_increment, min_increment, &
         max_increment, max_iterations, tolerance, squeeze_force_change, max_force_change
      character(len=echo_len) :: lines(echo_rows)

      lock_depth = d%lock_depth
      pull_distance = d%pull_distance
      initial_increment = d%initial_increment
      min_increment = d%min_increment
      max_increment = d%max_increment
      max_iterations = d%max_iterations
      tolerance = d%tolerance
      squeeze_force_change = d%squeeze_force_change
      max_force_change = d%max_force_change
      select case (action)
      case (act_read_unit)
         read (unit, nml=loading, iostat=ios, iomsg=msg)
      case (act_read_text)
         read (text, nml=loading, iostat=ios, iomsg=msg)
      case default
         lines = ''
         write (lines, nml=loading, delim='quote', iostat=ios, iomsg=msg)
         if (ios == 0) call put_lines(unit, lines)
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

   ! ---------------------------------------------------------------------
   ! Reading and diagnosing groups
   ! ---------------------------------------------------------------------

   !> load_text -- the whole of a file as one string.
   !>
   !> path  [in]  file name.
   !> text  [out] the file's bytes (allocated, possibly of length 0).
   !> ios   [out] 0 on success, else the iostat of the failing statement.
   !> msg   [out] the iomsg when ios /= 0.
   subroutine load_text(path, text, ios, msg)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: text
      integer, intent(out) :: ios
      character(len=*), intent(out) :: msg

      integer :: u, n

      msg = ''
      text = ''
      open (newunit=u, file=path, access='stream', form='unformatted', status='old', &
            action='read', iostat=ios, iomsg=msg)
      if (ios /= 0) return
      inquire (unit=u, size=n)
      if (n > 0) then
         deallocate (text)
         allocate (character(len=n) :: text)
         read (u, iostat=ios, iomsg=msg) text
      end if
      close (u)
   end subroutine load_text

   !> scan_groups -- find the text of each known group in a deck.
   !>
   !> Outside groups, '!' starts a comment and anything but '&name' is
   !> skipped. Inside a group, quotes (' or ", doubled to escape) and '!'
   !> comments are honoured and an unquoted '/' ends the group. Line ends,
   !> tabs and comments become blanks in the body.
   !>
   !> text   [in]     the whole deck.
   !> path   [in]     deck name, for messages.
   !> found  [out]    per entry of group_names: present, terminated, body
   !>                 (of the first occurrence).
   !> errs   [in,out] unknown and repeated groups are appended.
   subroutine scan_groups(text, path, found, errs)
      character(len=*), intent(in) :: text
      character(len=*), intent(in) :: path
      type(group_text), intent(out) :: found(:)
      type(error_list), intent(inout) :: errs

      character(len=:), allocatable :: body, name
      character(len=1) :: c, quote
      logical :: in_group
      integer :: i, j, n, g, current

      n = len(text)
      i = 1
      name = ''
      in_group = .false.
      current = 0
      quote = ' '
      body = ''
      do while (i <= n)
         c = text(i:i)
         if (.not. in_group) then
            if (c == '!') then
               i = end_of_line(text, i)
            else if (c == '&') then
               j = i + 1
               do while (j <= n)
                  if (.not. is_name_char(text(j:j))) exit
                  j = j + 1
               end do
               name = lower(text(i + 1:j - 1))
               if (len(name) > 0 .and. name /= 'end') then
                  current = 0
                  do g = 1, size(group_names)
                     if (name == trim(group_names(g))) current = g
                  end do
                  if (current == 0) then
                     call add_error(errs, "deck '"//trim(path)//"', group &"//name// &
                                    ": unknown group (the groups are &control, &sheet, " &
                                    //"&material, &tools and &loading)")
                  else if (found(current)%present) then
                     call add_error(errs, "deck '"//trim(path)//"', group &"//name// &
                                    ": appears more than once (only the first is read)")
                     current = 0
                  else
                     found(current)%present = .true.
                  end if
                  in_group = .true.
                  quote = ' '
                  body = ''
               end if
               i = j
               cycle
            end if
         else
            if (quote /= ' ') then
               if (c == quote) quote = ' '
            else if (c == '"' .or. c == "'") then
               quote = c
            else if (c == '!') then
               i = end_of_line(text, i)
               body = body//' '
               cycle
            else if (c == '/') then
               if (current > 0) then
                  found(current)%terminated = .true.
                  found(current)%body = body
               end if
               in_group = .false.
               i = i + 1
               cycle
            end if
            if (iachar(c) < 32) c = ' '
            body = body//c
         end if
         i = i + 1
      end do
      if (in_group .and. current > 0) found(current)%body = body
      do g = 1, size(found)
         if (.not. allocated(found(g)%body)) found(g)%body = ''
      end do
   end subroutine scan_groups

   !> read_group -- read one namelist group from the deck, diagnosing errors.
   !>
   !> d      [in,out] the deck; takes the values of the group.
   !> group  [in]     group name, lower case, without '&'.
   !> unit   [in]     the deck, open for formatted sequential reading.
   !> path   [in]     deck name, for messages.
   !> gt     [in]     what scan_groups found for this group.
   !> errs   [in,out] problems are appended.
   subroutine read_group(d, group, unit, path, gt, errs)
      type(deck_type), intent(inout) :: d
      character(len=*), intent(in) :: group
      integer, intent(in) :: unit
      character(len=*), intent(in) :: path
      type(group_text), intent(in) :: gt
      type(error_list), intent(inout) :: errs

      character(len=512) :: msg, text_msg
      integer :: ios, n_before

      msg = ''
      rewind (unit)
      call group_io(group, d, act_read_unit, unit, '', ios, msg)
      if (ios == 0) return
      if (ios == iostat_end .and. .not. gt%present) return   ! group absent: defaults

      ! gfortran gives end-of-file when the '/' is on a last line without a
      ! newline: a complete group that reads from its own text is fine.
      if (gt%present .and. gt%terminated) then
         text_msg = ''
         call group_io(group, d, act_read_text, 0, '&'//group//' '//gt%body//' /', ios, text_msg)
         if (ios == 0) return
      end if

      n_before = errs%count
      if (.not. gt%present) then
         call add_error(errs, "deck '"//trim(path)//"', group &"//group// &
                        ": cannot read the group ("//trim(msg)//")")
         return
      end if
      if (.not. gt%terminated) &
         call add_error(errs, "deck '"//trim(path)//"', group &"//group// &
                        ": no '/' ends the group")
      call diagnose_group(d, group, gt%body, path, errs)
      if (errs%count == n_before) &
         call add_error(errs, "deck '"//trim(path)//"', group &"//group// &
                        ": cannot read the group ("//trim(msg)//")")
   end subroutine read_group

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
         call group_io(group, d, act_read_text, 0, '&'//group//' '//body(starts(k):last)//' /', &
                       ios, msg)
         if (ios == 0) cycle

         ! is the name known? a null value ('name = /') reads for any known name
         name_msg = ''
         call group_io(group, d, act_read_text, 0, '&'//group//' '//var//' = /', name_ios, &
                       name_msg)
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

   !> split_assignments -- locate the `name = value` assignments of a body.
   !>
   !> body    [in]  group text.
   !> starts  [out] first character of each assignment's name.
   !> eqs     [out] position of each assignment's unquoted '='.
   pure subroutine split_assignments(body, starts, eqs)
      character(len=*), intent(in) :: body
      integer, allocatable, intent(out) :: starts(:), eqs(:)

      character(len=1) :: c, quote
      integer :: i, j, depth, n

      allocate (starts(0), eqs(0))
      quote = ' '
      do i = 1, len(body)
         c = body(i:i)
         if (quote /= ' ') then
            if (c == quote) quote = ' '
            cycle
         end if
         if (c == '"' .or. c == "'") then
            quote = c
            cycle
         end if
         if (c /= '=') cycle
         ! walk back over blanks, then over the name and any (subscripts)
         j = i - 1
         do while (j >= 1)
            if (body(j:j) /= ' ') exit
            j = j - 1
         end do
         n = j
         depth = 0
         do while (j >= 1)
            if (body(j:j) == ')') then
               depth = depth + 1
            else if (body(j:j) == '(') then
               depth = depth - 1
            else if (depth == 0 .and. .not. is_name_char(body(j:j)) .and. body(j:j) /= '%') then
               exit
            end if
            j = j - 1
         end do
         if (j + 1 > n) then
            starts = [starts, i]       ! no name: an empty one, reported by the caller
         else
            starts = [starts, j + 1]
         end if
         eqs = [eqs, i]
      end do
   end subroutine split_assignments

   ! ---------------------------------------------------------------------
   ! Defaults and validation
   ! ---------------------------------------------------------------------

   !> resolve_defaults -- replace the `unset` sentinels, fill output_dir.
   !>
   !> Scaled by h = thickness (or by the default thickness when the given one
   !> is unusable, so that one bad value does not cause others): length 50 h,
   !> bead A r1 = r2 = 4.66 h, b1 = 4.16 h, b2 = 8.83 h, h1 = 1.56 h,
   !> h2 = 5.66 h, pull_distance 10 h, min_increment 1e-6 h, max_increment
   !> 0.1 h, initial_increment 0.05 h (kept within the min/max increments),
   !> lock_depth h1 + r1 (full lock) with a rectangular bead, 0 without one;
   !> with a profile bead it must be given.
   !>
   !> d  [in,out] the deck as read.
   subroutine resolve_defaults(d)
      type(deck_type), intent(inout) :: d

      real(dp) :: h
      integer :: i

      h = default_thickness
      if (is_positive(d%thickness)) h = d%thickness

      if (is_unset(d%length)) d%length = 50.0_dp*h
      if (is_unset(d%r1)) d%r1 = 4.66_dp*h
      if (is_unset(d%r2)) d%r2 = 4.66_dp*h
      if (is_unset(d%b1)) d%b1 = 4.16_dp*h
      if (is_unset(d%b2)) d%b2 = 8.83_dp*h
      if (is_unset(d%h1)) d%h1 = 1.56_dp*h
      if (is_unset(d%h2)) d%h2 = 5.66_dp*h
      if (is_unset(d%pull_distance)) d%pull_distance = 10.0_dp*h
      if (is_unset(d%min_increment)) d%min_increment = 1.0e-6_dp*h
      ! 0.1h resolves the friction history (which starts at the first
      ! converged state in contact) and the force curves
      if (is_unset(d%max_increment)) d%max_increment = 0.1_dp*h
      if (is_unset(d%initial_increment)) then
         d%initial_increment = 0.05_dp*h
         if (is_positive(d%min_increment)) d%initial_increment = &
            max(d%initial_increment, d%min_increment)
         if (is_positive(d%max_increment)) d%initial_increment = &
            min(d%initial_increment, d%max_increment)
      end if
      ! a profile's full-lock depth is not known here: it must be given
      if (is_unset(d%lock_depth) .and. d%bead /= 'profile') then
         d%lock_depth = 0.0_dp
         if (d%bead /= 'none') then
            if (is_positive(d%h1)) d%lock_depth = d%lock_depth + d%h1
            if (is_positive(d%r1)) d%lock_depth = d%lock_depth + d%r1
         end if
      end if

      if (len_trim(d%output_dir) == 0) then
         d%output_dir = d%deck_file
         i = index(d%output_dir, '/', back=.true.)
         if (i > 0) d%output_dir = d%output_dir(i + 1:)
         i = len_trim(d%output_dir)
         if (i > 4) then
            if (lower(d%output_dir(i - 3:i)) == '.nml') d%output_dir(i - 3:) = ''
         end if
         if (len_trim(d%output_dir) == 0) d%output_dir = 'run'
         d%output_dir = 'out/'//trim(d%output_dir)
      end if
   end subroutine resolve_defaults

   !> validate -- check ranges and consistency of a resolved deck.
   !>
   !> Loads the tabulated curve for hardening = 'table' when its file is
   !> usable. Every problem is reported, naming group and variable.
   !>
   !> d     [in,out] the resolved deck (curve_ep, curve_sigma may be set).
   !> errs  [in,out] problems are appended; warnings go to error_unit.
   subroutine validate(d, errs)
      type(deck_type), intent(inout) :: d
      type(error_list), intent(inout) :: errs

      character(len=:), allocatable :: p
      character(len=1024) :: emsg
      real(dp) :: full

      p = trim(d%deck_file)

      ! &control
      call check_text_length(errs, at(p, 'control', 'title'), d%title)
      call check_text_length(errs, at(p, 'control', 'output_dir'), d%output_dir)
      call check_real(errs, at(p, 'control', 'tearing_length'), d%tearing_length, lo=0.0_dp)
      call check_real(errs, at(p, 'control', 'fold_curvature'), d%fold_curvature, lo=0.0_dp, lo_open=.true.)
      call check_real(errs, at(p, 'control', 'snapshot_every'), d%snapshot_every, lo=0.0_dp)

      ! &sheet
      call check_real(errs, at(p, 'sheet', 'thickness'), d%thickness, lo=0.0_dp, lo_open=.true.)
      call check_real(errs, at(p, 'sheet', 'length'), d%length, lo=0.0_dp, lo_open=.true.)
      if (is_positive(d%thickness) .and. is_positive(d%length)) then
         if (d%length < 10.0_dp*d%thickness) call fail(errs, at(p, 'sheet', 'length'), &
            'must be >= 10 thickness = '//num(10.0_dp*d%thickness)//' (got '//num(d%length)//')')
      end if
      call check_int(errs, at(p, 'sheet', 'n_elements'), d%n_elements, lo=2)
      call check_real(errs, at(p, 'sheet', 'mesh_beta'), d%mesh_beta, lo=1.0_dp, hi=3.0_dp)
      call check_choice(errs, at(p, 'sheet', 'left_edge'), d%left_edge, &
                        [character(len=16) :: 'clamped', 'free'])
      call check_real(errs, at(p, 'sheet', 'back_tension'), d%back_tension, lo=0.0_dp)
      if (d%left_edge == 'clamped' .and. ieee_is_finite(d%back_tension)) then
         if (abs(d%back_tension) > 0.0_dp) call warn(at(p, 'sheet', 'back_tension')// &
            ": ignored with left_edge = 'clamped' (it acts only on a 'free' edge)")
      end if

      ! &material
      call check_real(errs, at(p, 'material', 'youngs_modulus'), d%youngs_modulus, &
                      lo=0.0_dp, lo_open=.true.)
      call check_real(errs, at(p, 'material', 'poissons_ratio'), d%poissons_ratio, &
                      lo=-1.0_dp, hi=0.5_dp, lo_open=.true., hi_open=.true.)
      call check_real(errs, at(p, 'material', 'r_value'), d%r_value, lo=0.0_dp, lo_open=.true.)
      call check_choice(errs, at(p, 'material', 'hardening'), d%hardening, &
                        [character(len=16) :: 'swift', 'voce', 'table'])
      select case (trim(d%hardening))
      case ('swift')
         call check_real(errs, at(p, 'material', 'swift_k'), d%swift_k, lo=0.0_dp, lo_open=.true.)
         call check_real(errs, at(p, 'material', 'swift_eps0'), d%swift_eps0, &
                         lo=0.0_dp, lo_open=.true.)
         call check_real(errs, at(p, 'material', 'swift_n'), d%swift_n, lo=0.0_dp, hi=1.0_dp, &
                         hi_open=.true.)
      case ('voce')
         call check_real(errs, at(p, 'material', 'voce_sigma0'), d%voce_sigma0, &
                         lo=0.0_dp, lo_open=.true.)
         call check_real(errs, at(p, 'material', 'voce_q'), d%voce_q, lo=0.0_dp)
         call check_real(errs, at(p, 'material', 'voce_b'), d%voce_b, lo=0.0_dp)
      case ('table')
         if (len_trim(d%curve_file) == 0) then
            call fail(errs, at(p, 'material', 'curve_file'), &
                      "must name a file when hardening = 'table'")
         else if (.not. file_exists(d%curve_file)) then
            call fail(errs, at(p, 'material', 'curve_file'), &
                      "file '"//trim(d%curve_file)//"' not found")
         else
            emsg = ''
            call read_curve_file(trim(d%curve_file), d%curve_ep, d%curve_sigma, emsg)
            if (len_trim(emsg) > 0) call fail(errs, at(p, 'material', 'curve_file'), trim(emsg))
         end if
      end select
      if (d%hardening /= 'table' .and. len_trim(d%curve_file) > 0) &
         call warn(at(p, 'material', 'curve_file')//": ignored unless hardening = 'table'")
      call check_text_length(errs, at(p, 'material', 'curve_file'), d%curve_file)
      if (d%thickness_points < 3 .or. mod(d%thickness_points, 2) == 0) &
         call fail(errs, at(p, 'material', 'thickness_points'), &
                   'must be odd and >= 3 (got '//inum(d%thickness_points)//')')

      ! &tools
      call check_choice(errs, at(p, 'tools', 'bead'), d%bead, &
                        [character(len=16) :: 'none', 'rectangular', 'profile'])
      select case (trim(d%bead))
      case ('rectangular')
         call check_real(errs, at(p, 'tools', 'r1'), d%r1, lo=0.0_dp, lo_open=.true.)
         call check_real(errs, at(p, 'tools', 'r2'), d%r2, lo=0.0_dp, lo_open=.true.)
         call check_real(errs, at(p, 'tools', 'b1'), d%b1, lo=0.0_dp, lo_open=.true.)
         call check_real(errs, at(p, 'tools', 'b2'), d%b2, lo=0.0_dp, lo_open=.true.)
         call check_real(errs, at(p, 'tools', 'h1'), d%h1, lo=0.0_dp)
         call check_real(errs, at(p, 'tools', 'h2'), d%h2, lo=0.0_dp)
      case ('profile')
         call check_profile(errs, at(p, 'tools', 'upper_profile'), d%upper_profile)
         call check_profile(errs, at(p, 'tools', 'lower_profile'), d%lower_profile)
      end select
      if (d%bead /= 'profile') then
         if (len_trim(d%upper_profile) > 0) &
            call warn(at(p, 'tools', 'upper_profile')//": ignored unless bead = 'profile'")
         if (len_trim(d%lower_profile) > 0) &
            call warn(at(p, 'tools', 'lower_profile')//": ignored unless bead = 'profile'")
      end if
      call check_text_length(errs, at(p, 'tools', 'upper_profile'), d%upper_profile)
      call check_text_length(errs, at(p, 'tools', 'lower_profile'), d%lower_profile)
      call check_real(errs, at(p, 'tools', 'penalty'), d%penalty, lo=0.0_dp, lo_open=.true.)
      call check_real(errs, at(p, 'tools', 'friction'), d%friction, lo=0.0_dp)
      call check_real(errs, at(p, 'tools', 'friction_eps'), d%friction_eps, &
                      lo=0.0_dp, lo_open=.true.)
      call check_real(errs, at(p, 'tools', 'contact_smoothing'), d%contact_smoothing, lo=0.0_dp)

      ! &loading
      if (is_unset(d%lock_depth)) then
         call fail(errs, at(p, 'loading', 'lock_depth'), 'must be given with bead = ''profile'''// &
                   ' (the full-lock depth of the profiles, mm)')
      else
         call check_real(errs, at(p, 'loading', 'lock_depth'), d%lock_depth, lo=0.0_dp)
      end if
      if (d%bead == 'rectangular' .and. ieee_is_finite(d%lock_depth) .and. &
          is_positive(d%r1) .and. ieee_is_finite(d%h1)) then
         full = d%h1 + d%r1
         if (d%lock_depth > full*(1.0_dp + 1.0e-12_dp)) &
            call fail(errs, at(p, 'loading', 'lock_depth'), 'must be <= h1 + r1 = '// &
                      num(full)//' (full lock) (got '//num(d%lock_depth)//')')
      end if
      call check_real(errs, at(p, 'loading', 'pull_distance'), d%pull_distance, lo=0.0_dp)
      call check_real(errs, at(p, 'loading', 'min_increment'), d%min_increment, &
                      lo=0.0_dp, lo_open=.true.)
      call check_real(errs, at(p, 'loading', 'initial_increment'), d%initial_increment, &
                      lo=0.0_dp, lo_open=.true.)
      call check_real(errs, at(p, 'loading', 'max_increment'), d%max_increment, &
                      lo=0.0_dp, lo_open=.true.)
      if (is_positive(d%min_increment) .and. is_positive(d%initial_increment)) then
         if (d%initial_increment < d%min_increment) &
            call fail(errs, at(p, 'loading', 'initial_increment'), 'must be >= min_increment = ' &
                      //num(d%min_increment)//' (got '//num(d%initial_increment)//')')
      end if
      if (is_positive(d%initial_increment) .and. is_positive(d%max_increment)) then
         if (d%max_increment < d%initial_increment) &
            call fail(errs, at(p, 'loading', 'max_increment'), 'must be >= initial_increment = ' &
                      //num(d%initial_increment)//' (got '//num(d%max_increment)//')')
      end if
      call check_int(errs, at(p, 'loading', 'max_iterations'), d%max_iterations, lo=2)
      call check_real(errs, at(p, 'loading', 'tolerance'), d%tolerance, lo=0.0_dp, &
                      hi=1.0e-2_dp, lo_open=.true., hi_open=.true.)
      call check_real(errs, at(p, 'loading', 'squeeze_force_change'), d%squeeze_force_change, &
                      lo=0.0_dp, hi=0.5_dp, lo_open=.true., hi_open=.true.)
      call check_real(errs, at(p, 'loading', 'max_force_change'), d%max_force_change, &
                      lo=0.0_dp, hi=0.5_dp, lo_open=.true., hi_open=.true.)
   end subroutine validate

   !> check_real -- require a finite real within optional bounds.
   !>
   !> errs     [in,out] gets '<ctx>: must be ... (got x)' on failure.
   !> ctx    [in]     "deck '...', group &..., variable ..." (see at).
   !> x        [in]     the value.
   !> lo, hi   [in]     optional lower and upper bounds.
   !> lo_open  [in]     optional, .true.: x > lo required (default x >= lo).
   !> hi_open  [in]     optional, .true.: x < hi required (default x <= hi).
   subroutine check_real(errs, ctx, x, lo, hi, lo_open, hi_open)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx
      real(dp), intent(in) :: x
      real(dp), intent(in), optional :: lo, hi
      logical, intent(in), optional :: lo_open, hi_open

      character(len=:), allocatable :: rule
      logical :: ok, open_lo, open_hi

      if (.not. ieee_is_finite(x)) then
         call fail(errs, ctx, 'must be a finite number (got '//num(x)//')')
         return
      end if
      open_lo = .false.
      open_hi = .false.
      if (present(lo_open)) open_lo = lo_open
      if (present(hi_open)) open_hi = hi_open
      ok = .true.
      rule = ''
      if (present(lo)) then
         if (open_lo) then
            ok = ok .and. x > lo
            rule = '> '//bound_text(lo)
         else
            ok = ok .and. x >= lo
            rule = '>= '//bound_text(lo)
         end if
      end if
      if (present(hi)) then
         if (len(rule) > 0) rule = rule//' and '
         if (open_hi) then
            ok = ok .and. x < hi
            rule = rule//'< '//bound_text(hi)
         else
            ok = ok .and. x <= hi
            rule = rule//'<= '//bound_text(hi)
         end if
      end if
      if (.not. ok) call fail(errs, ctx, 'must be '//rule//' (got '//num(x)//')')
   end subroutine check_real

   !> check_int -- require an integer >= lo.
   !>
   !> errs   [in,out] gets '<ctx>: must be >= lo (got i)' on failure.
   !> ctx  [in]     see at.
   !> i      [in]     the value.
   !> lo     [in]     the lower bound.
   subroutine check_int(errs, ctx, i, lo)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx
      integer, intent(in) :: i, lo

      if (i < lo) call fail(errs, ctx, 'must be >= '//inum(lo)//' (got '//inum(i)//')')
   end subroutine check_int

   !> check_choice -- require a (lower-case, left-adjusted) value from a list.
   !>
   !> errs     [in,out] gets '<ctx>: must be one of ... (got ...)' on failure.
   !> ctx    [in]     see at.
   !> value    [in]     the value.
   !> choices  [in]     the allowed values.
   subroutine check_choice(errs, ctx, value, choices)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx
      character(len=*), intent(in) :: value
      character(len=*), intent(in) :: choices(:)

      character(len=:), allocatable :: list
      integer :: k

      if (any(choices == value)) return
      list = ''
      do k = 1, size(choices)
         if (k > 1) list = list//', '
         list = list//"'"//trim(choices(k))//"'"
      end do
      call fail(errs, ctx, 'must be one of '//list//" (got '"//trim(value)//"')")
   end subroutine check_choice

   !> check_profile -- require a profile file name that exists.
   !>
   !> errs   [in,out] gets a message on failure.
   !> ctx  [in]     see at.
   !> path   [in]     the file name from the deck.
   subroutine check_profile(errs, ctx, path)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx
      character(len=*), intent(in) :: path

      if (len_trim(path) == 0) then
         call fail(errs, ctx, "must name a file when bead = 'profile'")
      else if (.not. file_exists(path)) then
         call fail(errs, ctx, "file '"//trim(path)//"' not found")
      end if
   end subroutine check_profile

   !> check_text_length -- reject text that filled its variable (truncated).
   !>
   !> errs   [in,out] gets a message on failure.
   !> ctx  [in]     see at.
   !> s      [in]     the text variable.
   subroutine check_text_length(errs, ctx, s)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx
      character(len=*), intent(in) :: s

      if (len_trim(s) >= len(s)) call fail(errs, ctx, 'is too long (at most '// &
                                           inum(len(s) - 1)//' characters)')
   end subroutine check_text_length

   !> fail -- append '<ctx>: <what>' to an error list.
   !>
   !> errs   [in,out] the list.
   !> ctx  [in]     see at.
   !> what   [in]     what is wrong and what was found.
   subroutine fail(errs, ctx, what)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx, what

      call add_error(errs, ctx//': '//what)
   end subroutine fail

   ! ---------------------------------------------------------------------
   ! Small helpers
   ! ---------------------------------------------------------------------

   !> at -- "deck '<path>', group &<group>, variable <var>".
   pure function at(path, group, var) result(s)
      character(len=*), intent(in) :: path   !< [in] deck file name
      character(len=*), intent(in) :: group  !< [in] group name without '&'
      character(len=*), intent(in) :: var    !< [in] variable name
      character(len=:), allocatable :: s

      s = "deck '"//trim(path)//"', group &"//group//', variable '//var
   end function at

   !> num -- a real as short text: about 6 significant digits, trailing
   !> zeros dropped (-5.0, 0.0085, 207000.0, 7.62E-7, NaN, Infinity).
   pure function num(x) result(s)
      real(dp), intent(in) :: x              !< [in] the value (NaN, Inf allowed)
      character(len=:), allocatable :: s

      character(len=40) :: buf
      character(len=:), allocatable :: expo
      real(dp) :: ax
      integer :: e, k

      if (ieee_is_nan(x)) then
         s = 'NaN'
         return
      else if (.not. ieee_is_finite(x)) then
         s = 'Infinity'
         if (x < 0.0_dp) s = '-Infinity'
         return
      end if
      ax = abs(x)
      expo = ''
      if (.not. ax > 0.0_dp .or. (ax >= 0.1_dp .and. ax < 1.0e6_dp)) then
         write (buf, '(g0.6)') x
         s = trim(adjustl(buf))
      else if (ax >= 1.0e-4_dp .and. ax < 0.1_dp) then
         write (buf, '(f14.10)') x
         s = trim(adjustl(buf))
      else
         write (buf, '(es15.5e3)') x
         s = trim(adjustl(buf))
         e = index(s, 'E')
         k = verify(s(e + 2:), '0')
         if (k == 0) then
            expo = 'E0'
         else
            expo = 'E'//s(e + 1:e + 1)//s(e + 1 + k:)
            if (s(e + 1:e + 1) == '+') expo = 'E'//s(e + 1 + k:)
         end if
         s = s(1:e - 1)
      end if
      if (index(s, '.') > 0) then
         do while (s(len(s):len(s)) == '0')
            s = s(1:len(s) - 1)
         end do
         if (s(len(s):len(s)) == '.') s = s//'0'
      end if
      s = s//expo
   end function num

   !> bound_text -- a bound as text: whole numbers without a decimal point.
   pure function bound_text(x) result(s)
      real(dp), intent(in) :: x              !< [in] a finite bound
      character(len=:), allocatable :: s

      if (abs(x) < 1.0e6_dp .and. abs(x - anint(x)) < tiny(x)) then
         s = inum(nint(x))
      else
         s = num(x)
      end if
   end function bound_text

   !> inum -- an integer as text without blanks.
   pure function inum(i) result(s)
      integer, intent(in) :: i               !< [in] the value
      character(len=:), allocatable :: s

      character(len=24) :: buf

      write (buf, '(i0)') i
      s = trim(buf)
   end function inum

   !> clip -- text shortened to at most 60 characters for messages.
   pure function clip(s) result(r)
      character(len=*), intent(in) :: s      !< [in] any text
      character(len=:), allocatable :: r

      if (len_trim(s) > 60) then
         r = s(1:57)//'...'
      else
         r = trim(s)
      end if
   end function clip

   !> strip_separators -- text without surrounding blanks and commas.
   pure function strip_separators(s) result(r)
      character(len=*), intent(in) :: s      !< [in] any text
      character(len=:), allocatable :: r

      integer :: i, j

      i = verify(s, ' ,')
      j = verify(s, ' ,', back=.true.)
      if (i == 0) then
         r = ''
      else
         r = s(i:j)
      end if
   end function strip_separators

   !> end_of_line -- index of the next newline at or after i (or len+1).
   pure function end_of_line(text, i) result(j)
      character(len=*), intent(in) :: text   !< [in] the text
      integer, intent(in) :: i               !< [in] start position
      integer :: j

      j = index(text(i:), achar(10))
      if (j == 0) then
         j = len(text) + 1
      else
         j = i + j - 1
      end if
   end function end_of_line

   !> is_name_char -- .true. for a letter, digit or underscore.
   pure function is_name_char(c) result(yes)
      character(len=1), intent(in) :: c      !< [in] one character
      logical :: yes

      yes = is_letter(c) .or. (c >= '0' .and. c <= '9') .or. c == '_'
   end function is_name_char

   !> is_letter -- .true. for A-Z or a-z.
   pure function is_letter(c) result(yes)
      character(len=1), intent(in) :: c      !< [in] one character
      logical :: yes

      yes = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z')
   end function is_letter

   !> is_unset -- .true. for the `unset` sentinel (safe for NaN and Inf).
   pure function is_unset(x) result(yes)
      real(dp), intent(in) :: x              !< [in] the value
      logical :: yes

      yes = .false.
      if (.not. ieee_is_finite(x)) return
      yes = x < -0.5_dp*huge(x)
   end function is_unset

   !> is_positive -- .true. for a finite x > 0 (safe for NaN and Inf).
   pure function is_positive(x) result(yes)
      real(dp), intent(in) :: x              !< [in] the value
      logical :: yes

      yes = .false.
      if (.not. ieee_is_finite(x)) return
      yes = x > 0.0_dp
   end function is_positive

   !> file_exists -- .true. when a file of that name exists.
   function file_exists(path) result(yes)
      character(len=*), intent(in) :: path   !< [in] file name
      logical :: yes

      inquire (file=trim(path), exist=yes)
   end function file_exists

end module deck
