!> deck -- the input deck: its variables and defaults, the defaults that
!> scale with the thickness, and the checks of every value.  Reading,
!> echoing and listing the groups is module deck_reader; the text scanning
!> of a deck is module deck_scan; turning a deck into the model is module
!> setup.
!>
!> A deck is a text file of Fortran namelist groups, in any order, each
!> optional:
!>
!>   &control   title, output_dir, stop_at_localization, tearing_criterion, tearing_length, fold_curvature,
!>              log_residuals, predictor, snapshot_every
!>   &sheet     thickness, length, n_elements, mesh_beta, left_edge, normal_stress,
!>              back_tension, strain_gradient, refine_from, refine_to, refine_element,
!>              refine_neck
!>   &material  model, umat_props, umat_nstatv, umat_eqps_index, youngs_modulus,
!>              poissons_ratio, r_value, r0, r90, drawing_direction, hardening,
!>              swift_k, swift_eps0, swift_n, voce_sigma0, voce_q, voce_b,
!>              curve_file, kinematic_c, kinematic_gamma, thickness_points
!>   &tools     bead, r1, r2, b1, b2, h1, h2, upper_profile, lower_profile,
!>              penalty, friction, friction_eps, contact_smoothing, friction_law,
!>              friction_file, friction_p_ref, friction_m, friction_mu_min,
!>              friction_mu_max, contact_faces
!>   &loading   lock_depth, pull_distance, initial_increment,
!>              min_increment, max_increment, max_iterations, tolerance,
!>              max_force_change, squeeze_force_change, step_tolerance,
!>              branch_increment
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
!> The namelist variables live only in the private per-group routines of
!> deck_reader, which copy between them and a deck_type; the module holds no
!> mutable state.
module deck
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use errors, only: error_list, warn
   use text, only: lower, num, itoa, file_exists
   use deck_checks, only: check_real, check_yield, check_int, check_choice, check_profile, &
                          check_text_length, check_text_chars, control_char_at, fail, at, is_positive
   use bead_builder, only: bead_a_over_h
   use mesh, only: zone_counts, neck_half_width
   implicit none
   private
   public :: deck_type, group_names, resolve_defaults, validate_deck, max_umat_props, &
             umat_props_given, max_kinematic, unset, is_unset

   !> Marks a default that is resolved from the thickness after reading.
   real(dp), parameter :: unset = -huge(1.0_dp)

   !> Default sheet thickness h (mm), 0.030 in.
   real(dp), parameter :: default_thickness = 0.762_dp

   !> The largest mesh accepted (&sheet n_elements).
   integer, parameter :: max_elements = 500000

   !> Room for a user UMAT's constants (&material umat_props).
   integer, parameter :: max_umat_props = 64

   !> Room for back stresses (&material kinematic_c, kinematic_gamma).
   integer, parameter :: max_kinematic = 3

   !> The namelist groups, in the order they are read and echoed.
   character(len=8), parameter :: group_names(5) = &
      [character(len=8) :: 'control', 'sheet', 'material', 'tools', 'loading']

   !> Every input of a run, after read_deck: defaults resolved, string
   !> choices lower case.
   type :: deck_type
      character(len=512) :: deck_file = ''
      ! &control
      character(len=256) :: title = ''
      character(len=512) :: output_dir = ''          ! '' -> 'out/<deck base name>'
      logical :: stop_at_localization = .true.
      logical :: log_residuals = .false.          ! print each increment's Newton residual sequence
      real(dp) :: tearing_length = 1.0_dp         ! averaging length of the mesh-objective tearing measure, units of h
      character(len=16) :: tearing_criterion = 'load_maximum'  ! 'load_maximum' | 'section' (the paper's (3.1))
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
      character(len=16) :: normal_stress = 'contact'  ! 'contact' | 'none' (the paper's plane-stress section)
      real(dp) :: strain_gradient = unset             ! the necking length term; default 1 with 'contact', 0 with 'none'
      real(dp) :: refine_from = 0.0_dp                ! refined zone of the mesh: from s/h (reference position)
      real(dp) :: refine_to = 0.0_dp                  ! ... to s/h
      real(dp) :: refine_element = 0.0_dp            ! element length in the zone, units of h (0: no zone)
      logical :: refine_neck = .false.                ! a coarse pass finds the neck, the run refines around it
      logical :: refine_exit = .true.                 ! split the elements at the last radius's exit after locking
      ! &material
      real(dp) :: youngs_modulus = 207000.0_dp        ! MPa
      real(dp) :: poissons_ratio = 0.3_dp
      real(dp) :: r_value = 1.0_dp                    ! normal anisotropy R
      character(len=16) :: model = 'j2'               ! 'j2' | 'combined' (built in) | 'umat' (make UMAT=...)
      real(dp) :: umat_props(max_umat_props) = unset  ! model = 'umat': the user's PROPS, in order
      integer :: umat_nstatv = -1                     ! model = 'umat': the user's NSTATV (required)
      integer :: umat_eqps_index = 0                  ! model = 'umat': statev index of ebar_p (0: none)
      real(dp) :: r0 = unset                          ! model = 'combined': Lankford r along rolling (default r_value)
      real(dp) :: r90 = unset                         ! ... across rolling (default r_value)
      character(len=16) :: drawing_direction = 'rolling'  ! 'rolling' | 'transverse'
      real(dp) :: kinematic_c(max_kinematic) = unset      ! model = 'combined': C_i of the back stresses, MPa
      real(dp) :: kinematic_gamma(max_kinematic) = unset  ! ... gamma_i (default 0: Prager)
      character(len=16) :: hardening = 'swift'        ! 'swift' | 'voce' | 'table'
      real(dp) :: swift_k = 548.0_dp                  ! K (eps0 + ep)^n, MPa
      real(dp) :: swift_eps0 = 0.0085_dp
      real(dp) :: swift_n = 0.23_dp
      real(dp) :: voce_sigma0 = 183.0_dp              ! sigma0 + Q (1 - exp(-b ep))
      real(dp) :: voce_q = 200.0_dp
      real(dp) :: voce_b = 10.0_dp
      character(len=512) :: curve_file = ''           ! 'table': columns ep, sigma
      integer :: thickness_points = 21                ! Simpson stations, odd >= 3
      ! &tools (r1 ... h2 default to the paper's bead A scaled by h)
      character(len=16) :: bead = 'none'              ! 'none' | 'rectangular' | 'profile'
      real(dp) :: r1 = unset                          ! R1 of bead A (bead_a_over_h) times h
      real(dp) :: r2 = unset                          ! R2 of bead A (bead_a_over_h) times h
      real(dp) :: b1 = unset                          ! B1 of bead A (bead_a_over_h) times h
      real(dp) :: b2 = unset                          ! B2 of bead A (bead_a_over_h) times h
      real(dp) :: h1 = unset                          ! H1 of bead A (bead_a_over_h) times h
      real(dp) :: h2 = unset                          ! H2 of bead A (bead_a_over_h) times h
      character(len=512) :: upper_profile = ''
      character(len=512) :: lower_profile = ''
      real(dp) :: penalty = 0.045_dp                  ! k h / E
      real(dp) :: friction = 0.0_dp                   ! mu ('coulomb'), mu_ref ('power')
      character(len=16) :: friction_law = 'coulomb'   ! 'coulomb' | 'table' | 'power'
      character(len=512) :: friction_file = ''        ! 'table': columns p (MPa), mu
      real(dp) :: friction_p_ref = unset              ! 'power': p_ref, MPa (required)
      real(dp) :: friction_m = unset                  ! 'power': m of mu_ref (p/p_ref)^(m-1) (required)
      real(dp) :: friction_mu_min = 0.0_dp            ! 'power': lower bound of mu
      real(dp) :: friction_mu_max = 1.0_dp            ! 'power': upper bound of mu
      real(dp) :: friction_eps = 0.0333_dp            ! eps of (4.3), units of h
      real(dp) :: contact_smoothing = 0.0_dp          ! penalty onset smoothed over this penetration, units of h (0: sharp, as the paper)
      character(len=16) :: contact_faces = ''          ! 'current' (theory §5.1; default with 'contact') | 'reference' (h/2 from the centreline, the paper; default with 'none')
      ! &loading
      real(dp) :: lock_depth = unset                  ! h1 + r1 with bead = 'rectangular', 0 with 'none', required with 'profile'
      real(dp) :: pull_distance = unset               ! 10 h
      real(dp) :: initial_increment = unset           ! 0.05 h
      real(dp) :: min_increment = unset               ! 1e-6 h
      real(dp) :: max_increment = unset               ! 0.2 h
      real(dp) :: branch_increment = unset            ! 0.008 h: largest increment past a section's maximum load
      integer :: max_iterations = 20
      real(dp) :: tolerance = 1.0e-8_dp               ! relative residual and correction
      real(dp) :: max_force_change = 0.1_dp           ! target relative change of F (lock) or N (pull) per increment
      real(dp) :: squeeze_force_change = 0.04_dp      ! the same where F rises faster than H^5 while locking
      real(dp) :: step_tolerance = 5.0e-3_dp          ! local error of the path per increment (0: off)
   end type deck_type

contains

   ! ---------------------------------------------------------------------
   ! Defaults and validation
   ! ---------------------------------------------------------------------

   !> resolve_defaults -- replace the `unset` sentinels, fill output_dir.
   !>
   !> Scaled by h = thickness (or by the default thickness when the given one
   !> is unusable, so that one bad value does not cause others): length 50 h,
   !> the tools r1 ... h2 of the paper's bead A (bead_a_over_h), pull_distance 10 h, min_increment 1e-6 h, max_increment
   !> 0.2 h, initial_increment 0.05 h (kept within the min/max increments),
   !> lock_depth h1 + r1 (full lock) with a rectangular bead, 0 without one;
   !> with a profile bead it must be given; contact_faces 'current' with
   !> normal_stress = 'contact' and tools, else 'reference'.
   !>
   !> d  [in,out] the deck as read.
   subroutine resolve_defaults(d)
      type(deck_type), intent(inout) :: d

      real(dp) :: h
      integer :: i

      h = default_thickness
      if (is_positive(d%thickness)) h = d%thickness

      if (is_unset(d%length)) d%length = 50.0_dp*h
      if (is_unset(d%strain_gradient)) d%strain_gradient = merge(1.0_dp, 0.0_dp, d%normal_stress == 'contact')
      ! the tools on the sheet's current faces with the contact section and
      ! tools, on faces h/2 from the centreline (the paper's model) without
      ! it (docs/theory.md §5.1, §12.7)
      if (len_trim(d%contact_faces) == 0) then
         d%contact_faces = 'reference'
         if (d%normal_stress == 'contact' .and. d%bead /= 'none') d%contact_faces = 'current'
      end if
      if (is_unset(d%r1)) d%r1 = bead_a_over_h(1)*h
      if (is_unset(d%r2)) d%r2 = bead_a_over_h(2)*h
      if (is_unset(d%b1)) d%b1 = bead_a_over_h(3)*h
      if (is_unset(d%b2)) d%b2 = bead_a_over_h(4)*h
      if (is_unset(d%h1)) d%h1 = bead_a_over_h(5)*h
      if (is_unset(d%h2)) d%h2 = bead_a_over_h(6)*h
      if (is_unset(d%pull_distance)) d%pull_distance = 10.0_dp*h
      ! the neck's zone: elements of 0.08h, below the 0.1h on which the
      ! load maximum converges with the tools on the reference faces
      ! (docs/theory.md §7.5; 0.75h on the current faces, §7.6)
      if (d%refine_neck .and. .not. (abs(d%refine_element) > 0.0_dp)) d%refine_element = 0.08_dp
      if (is_unset(d%min_increment)) d%min_increment = 1.0e-6_dp*h
      ! 0.2h resolves the force curves; where the path turns, the error
      ! estimate of the step control (step_tolerance) shortens it
      ! (docs/theory.md §8.3: 0.3h moved the frictionless lock forces 0.7%)
      if (is_unset(d%max_increment)) d%max_increment = 0.2_dp*h
      ! past a section's maximum load, once the force has turned toward its
      ! maximum, the path is resolved on 0.008h: the tearing points then move
      ! by at most 1.3% when every increment is halved (0.025h: up to 3.2%;
      ! docs/theory.md §8.3)
      if (is_unset(d%branch_increment)) d%branch_increment = 0.008_dp*h
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

   !> validate_deck -- check ranges and consistency of a resolved deck.
   !>
   !> Every problem is reported, naming group and variable.  The files a
   !> deck names must exist; their contents are read and checked by setup.
   !>
   !> d     [in]     the resolved deck.
   !> errs  [in,out] problems are appended; warnings go to error_unit.
   subroutine validate_deck(d, errs)
      type(deck_type), intent(in) :: d
      type(error_list), intent(inout) :: errs

      character(len=:), allocatable :: p
      real(dp) :: full, h_ref, sy0
      integer :: n, k

      p = trim(d%deck_file)
      h_ref = default_thickness
      if (is_positive(d%thickness)) h_ref = d%thickness

      ! &control
      call check_text_length(errs, at(p, 'control', 'title'), d%title)
      call check_text_length(errs, at(p, 'control', 'output_dir'), d%output_dir)
      ! control characters (issue 28, item 8): every text variable
      call check_text_chars(errs, at(p, 'control', 'title'), d%title)
      call check_text_chars(errs, at(p, 'control', 'output_dir'), d%output_dir)
      call check_text_chars(errs, at(p, 'control', 'tearing_criterion'), d%tearing_criterion)
      call check_text_chars(errs, at(p, 'sheet', 'left_edge'), d%left_edge)
      call check_text_chars(errs, at(p, 'sheet', 'normal_stress'), d%normal_stress)
      call check_text_chars(errs, at(p, 'material', 'model'), d%model)
      call check_text_chars(errs, at(p, 'material', 'hardening'), d%hardening)
      call check_text_chars(errs, at(p, 'material', 'curve_file'), d%curve_file)
      call check_text_chars(errs, at(p, 'material', 'drawing_direction'), d%drawing_direction)
      call check_text_chars(errs, at(p, 'tools', 'friction_law'), d%friction_law)
      call check_text_chars(errs, at(p, 'tools', 'contact_faces'), d%contact_faces)
      call check_text_chars(errs, at(p, 'tools', 'friction_file'), d%friction_file)
      call check_text_chars(errs, at(p, 'tools', 'bead'), d%bead)
      call check_text_chars(errs, at(p, 'tools', 'upper_profile'), d%upper_profile)
      call check_text_chars(errs, at(p, 'tools', 'lower_profile'), d%lower_profile)
      call check_real(errs, at(p, 'control', 'tearing_length'), d%tearing_length, lo=0.0_dp)
      call check_choice(errs, at(p, 'control', 'tearing_criterion'), d%tearing_criterion, &
                        [character(len=16) :: 'load_maximum', 'section'])
      call check_real(errs, at(p, 'control', 'fold_curvature'), d%fold_curvature, lo=0.0_dp, lo_open=.true.)
      call check_real(errs, at(p, 'control', 'snapshot_every'), d%snapshot_every, lo=0.0_dp)

      ! &sheet
      call check_real(errs, at(p, 'sheet', 'thickness'), d%thickness, lo=0.0_dp, lo_open=.true.)
      call check_real(errs, at(p, 'sheet', 'length'), d%length, lo=0.0_dp, lo_open=.true.)
      if (is_positive(d%thickness) .and. is_positive(d%length)) then
         if (d%length < 10.0_dp*d%thickness) call fail(errs, at(p, 'sheet', 'length'), &
            'must be >= 10 thickness = '//num(10.0_dp*d%thickness)//' (got '//num(d%length)//')')
         ! the paper's sheets are 40-60 h long; past 1e4 h the shell is a
         ! string whose bending stiffness is round-off (a fuzzed h = 1e-30 mm
         ! never converged)
         if (d%length > 1.0e4_dp*d%thickness) call fail(errs, at(p, 'sheet', 'length'), &
            'must be <= 10000 thickness = '//num(1.0e4_dp*d%thickness)//' (got '//num(d%length)//')')
      end if
      call check_int(errs, at(p, 'sheet', 'n_elements'), d%n_elements, lo=2)
      ! about 18 kB of history per element with 21 stations: the largest
      ! mesh is held to some 9 GB, within this class of machine's memory
      if (d%n_elements > max_elements) call fail(errs, at(p, 'sheet', 'n_elements'), &
         'must be <= '//itoa(max_elements)//' (the largest mesh the program holds in memory; got '// &
         itoa(d%n_elements)//')')
      call check_real(errs, at(p, 'sheet', 'mesh_beta'), d%mesh_beta, lo=1.0_dp, hi=3.0_dp)
      call check_choice(errs, at(p, 'sheet', 'left_edge'), d%left_edge, &
                        [character(len=16) :: 'clamped', 'free'])
      call check_real(errs, at(p, 'sheet', 'back_tension'), d%back_tension, lo=0.0_dp)
      call check_choice(errs, at(p, 'sheet', 'normal_stress'), d%normal_stress, &
                        [character(len=16) :: 'contact', 'none'])
      call check_real(errs, at(p, 'sheet', 'strain_gradient'), d%strain_gradient, lo=0.0_dp, hi=100.0_dp)
      call check_refined_zone(d, p, errs)
      if (d%left_edge == 'clamped' .and. ieee_is_finite(d%back_tension)) then
         if (abs(d%back_tension) > 0.0_dp) call warn(at(p, 'sheet', 'back_tension')// &
            ": ignored with left_edge = 'clamped' (it acts only on a 'free' edge)")
      end if

      ! &material
      ! up to 1e7 MPa (fifty times steel's, eight times diamond's): beyond,
      ! the stresses of a forming strain overflow the material's algebra
      call check_real(errs, at(p, 'material', 'youngs_modulus'), d%youngs_modulus, &
                      lo=0.0_dp, hi=1.0e7_dp, lo_open=.true.)
      call check_real(errs, at(p, 'material', 'poissons_ratio'), d%poissons_ratio, &
                      lo=-1.0_dp, hi=0.5_dp, lo_open=.true., hi_open=.true.)
      ! sheet metals have R of 0.2 to 3; past 100 Hill's criterion degenerates
      call check_real(errs, at(p, 'material', 'r_value'), d%r_value, lo=0.0_dp, hi=100.0_dp, &
                      lo_open=.true.)
      call check_choice(errs, at(p, 'material', 'model'), d%model, &
                        [character(len=16) :: 'j2', 'combined', 'umat'])
      if (d%model == 'umat') then
         n = umat_props_given(d)
         if (n == 0) call fail(errs, at(p, 'material', 'umat_props'), &
                               "must give the user UMAT's constants with model = 'umat'")
         do k = 1, n
            call check_real(errs, at(p, 'material', 'umat_props('//itoa(k)//')'), d%umat_props(k))
         end do
         if (any(.not. is_unset(d%umat_props(n + 1:)))) call fail(errs, &
            at(p, 'material', 'umat_props'), 'must be given from umat_props(1) on without gaps'// &
            ' (entry '//itoa(n + 1)//' is missing)')
         ! hardening, swift_*, voce_*, curve_file are not used: the user's
         ! routine has its own law (youngs_modulus stays the scale of the output)
      else if (any(.not. is_unset(d%umat_props))) then
         call warn(at(p, 'material', 'umat_props')//": ignored unless model = 'umat'")
      end if
      call check_choice(errs, at(p, 'material', 'hardening'), d%hardening, &
                        [character(len=16) :: 'swift', 'voce', 'table'])
      select case (trim(d%hardening))
      case ('swift')
         call check_real(errs, at(p, 'material', 'swift_k'), d%swift_k, lo=0.0_dp, lo_open=.true.)
         call check_real(errs, at(p, 'material', 'swift_eps0'), d%swift_eps0, &
                         lo=0.0_dp, lo_open=.true.)
         call check_real(errs, at(p, 'material', 'swift_n'), d%swift_n, lo=0.0_dp, hi=1.0_dp, &
                         hi_open=.true.)
         ! K eps0^n in logarithms: no overflow for any finite, positive K, eps0
         sy0 = -1.0_dp
         if (is_positive(d%swift_k) .and. is_positive(d%swift_eps0) .and. ieee_is_finite(d%swift_n)) then
            if (abs(d%swift_n) < 1.0_dp) sy0 = exp(min(log(d%swift_k) + d%swift_n*log(d%swift_eps0), &
                                                       700.0_dp))
         end if
         call check_yield(errs, at(p, 'material', 'swift_k'), sy0, d%youngs_modulus)
      case ('voce')
         call check_real(errs, at(p, 'material', 'voce_sigma0'), d%voce_sigma0, &
                         lo=0.0_dp, lo_open=.true.)
         call check_real(errs, at(p, 'material', 'voce_q'), d%voce_q, lo=0.0_dp)
         call check_real(errs, at(p, 'material', 'voce_b'), d%voce_b, lo=0.0_dp)
         call check_yield(errs, at(p, 'material', 'voce_sigma0'), d%voce_sigma0, d%youngs_modulus)
      case ('table')
         if (len_trim(d%curve_file) == 0) then
            call fail(errs, at(p, 'material', 'curve_file'), &
                      "must name a file when hardening = 'table'")
         else if (control_char_at(d%curve_file) == 0) then
            ! (a name with a control character is refused above)
            if (.not. file_exists(d%curve_file)) call fail(errs, at(p, 'material', 'curve_file'), &
                                                            "file '"//trim(d%curve_file)//"' not found")
         end if
      end select
      if (d%hardening /= 'table' .and. len_trim(d%curve_file) > 0) &
         call warn(at(p, 'material', 'curve_file')//": ignored unless hardening = 'table'")
      call check_text_length(errs, at(p, 'material', 'curve_file'), d%curve_file)
      if (d%thickness_points > 101) call fail(errs, at(p, 'material', 'thickness_points'), &
                                              'must be <= 101 (got '//itoa(d%thickness_points)//')')
      if (d%thickness_points < 3 .or. mod(d%thickness_points, 2) == 0) &
         call fail(errs, at(p, 'material', 'thickness_points'), &
                   'must be odd and >= 3 (got '//itoa(d%thickness_points)//')')

      ! &tools
      call check_choice(errs, at(p, 'tools', 'bead'), d%bead, &
                        [character(len=16) :: 'none', 'rectangular', 'profile'])
      select case (trim(d%bead))
      case ('rectangular')
         call check_real(errs, at(p, 'tools', 'r1'), d%r1, lo=0.0_dp, lo_open=.true.)
         call check_real(errs, at(p, 'tools', 'r2'), d%r2, lo=0.0_dp, lo_open=.true.)
         ! the radii are those of the surfaces the mid-surface touches
         ! (docs/theory.md §5): the tool's own corner, r - h/2, must exist
         if (is_positive(d%thickness) .and. is_positive(d%r1)) then
            if (d%r1 <= 0.5_dp*d%thickness) call fail(errs, at(p, 'tools', 'r1'), 'must be > thickness/2 = ' &
               //num(0.5_dp*d%thickness)//': the radius the mid-surface follows, the tool''s own corner'// &
               ' being r1 - h/2 (got '//num(d%r1)//')')
         end if
         if (is_positive(d%thickness) .and. is_positive(d%r2)) then
            if (d%r2 <= 0.5_dp*d%thickness) call fail(errs, at(p, 'tools', 'r2'), 'must be > thickness/2 = ' &
               //num(0.5_dp*d%thickness)//': the radius the mid-surface follows, the tool''s own corner'// &
               ' being r2 - h/2 (got '//num(d%r2)//')')
         end if
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
      call check_choice(errs, at(p, 'tools', 'friction_law'), d%friction_law, &
                        [character(len=16) :: 'coulomb', 'table', 'power'])
      call check_text_length(errs, at(p, 'tools', 'friction_file'), d%friction_file)
      if (d%friction_law /= 'table' .and. len_trim(d%friction_file) > 0) &
         call warn(at(p, 'tools', 'friction_file')//": ignored unless friction_law = 'table'")
      if (d%friction_law == 'table' .and. abs(d%friction) > 0.0_dp) &
         call warn(at(p, 'tools', 'friction')//": ignored with friction_law = 'table' (the table gives mu)")
      call check_real(errs, at(p, 'tools', 'friction_eps'), d%friction_eps, &
                      lo=0.0_dp, lo_open=.true.)
      call check_real(errs, at(p, 'tools', 'contact_smoothing'), d%contact_smoothing, lo=0.0_dp)
      call check_choice(errs, at(p, 'tools', 'contact_faces'), d%contact_faces, &
                        [character(len=16) :: 'reference', 'current'])

      if (d%left_edge == 'free' .and. d%bead == 'none') &
         call fail(errs, at(p, 'sheet', 'left_edge'), "'free' needs tools (bead /= 'none'): "// &
                   'without them nothing holds the sheet and pulling only translates it')

      ! &loading
      if (d%bead == 'none' .and. ieee_is_finite(d%lock_depth)) then
         if (d%lock_depth > 0.0_dp) call fail(errs, at(p, 'loading', 'lock_depth'), &
            "is given with bead = 'none': there are no tools to lock (got "//num(d%lock_depth)//')')
      end if
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
      if (is_positive(d%length)) then
         call check_real(errs, at(p, 'loading', 'pull_distance'), d%pull_distance, lo=0.0_dp, &
                         hi=d%length)
      else
         call check_real(errs, at(p, 'loading', 'pull_distance'), d%pull_distance, lo=0.0_dp)
      end if
      call check_real(errs, at(p, 'loading', 'min_increment'), d%min_increment, &
                      lo=0.0_dp, lo_open=.true.)
      call check_real(errs, at(p, 'loading', 'initial_increment'), d%initial_increment, &
                      lo=0.0_dp, lo_open=.true.)
      ! at least 1e-3 h: a pull over the sheet's length then takes at most
      ! some 1e5 increments
      call check_real(errs, at(p, 'loading', 'max_increment'), d%max_increment, &
                      lo=1.0e-3_dp*h_ref, lo_open=.false.)
      ! at least 1e-4 h: a step study (scripts/convergence.sh -s -f) can
      ! scale the default 0.008 h down by 1/64 and more, and past the
      ! turn a pull to its confirmation stays within some 1e4 increments
      call check_real(errs, at(p, 'loading', 'branch_increment'), d%branch_increment, &
                      lo=1.0e-4_dp*h_ref, lo_open=.false.)
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
      ! at least 1e-14: Newton's last correction must fall below sqrt(tol)
      ! h, which below some 1e-7 h is round-off (a fuzzed 1e-300 never
      ! converged)
      call check_real(errs, at(p, 'loading', 'tolerance'), d%tolerance, lo=1.0e-14_dp, &
                      hi=1.0e-2_dp, hi_open=.true.)
      ! below 0.1% per increment the step control would creep (a fuzzed
      ! 1e-30 ran for ever)
      call check_real(errs, at(p, 'loading', 'squeeze_force_change'), d%squeeze_force_change, &
                      lo=1.0e-3_dp, hi=0.5_dp, hi_open=.true.)
      call check_real(errs, at(p, 'loading', 'max_force_change'), d%max_force_change, &
                      lo=1.0e-3_dp, hi=0.5_dp, hi_open=.true.)
      call check_real(errs, at(p, 'loading', 'step_tolerance'), d%step_tolerance, &
                      lo=0.0_dp, hi=0.5_dp, hi_open=.true.)
      ! 0 (off) or at least 1e-6: below it the increments creep at
      ! min_increment (a fuzzed 1e-10 would have taken hours; 1e-6 takes
      ! fig7b 70 times its shipped time)
      if (d%step_tolerance > 0.0_dp .and. d%step_tolerance < 1.0e-6_dp) &
         call fail(errs, at(p, 'loading', 'step_tolerance'), 'must be 0 (off) or >= 1e-6 (got '// &
                   num(d%step_tolerance)//')')
   end subroutine validate_deck

   !> check_refined_zone -- the refined zone of &sheet (refine_from,
   !> refine_to, refine_element, units of h): with refine_element > 0, a
   !> zone inside the sheet, elements shorter than the uniform mesh's, a
   !> uniform mesh outside (mesh_beta = 1) and a mesh the program holds.
   !> With refine_element = 0 a zone given is ignored, with a warning.
   !>
   !> d     [in]     the resolved deck.
   !> p     [in]     the deck's path.
   !> errs  [in,out] problems are appended.
   subroutine check_refined_zone(d, p, errs)
      type(deck_type), intent(in) :: d
      character(len=*), intent(in) :: p
      type(error_list), intent(inout) :: errs
      real(dp) :: half, coarse
      integer :: counts(3), n_before
      call check_real(errs, at(p, 'sheet', 'refine_element'), d%refine_element, lo=0.0_dp)
      call check_real(errs, at(p, 'sheet', 'refine_from'), d%refine_from)
      call check_real(errs, at(p, 'sheet', 'refine_to'), d%refine_to)
      if (d%refine_neck) then
         call check_neck_zone(d, p, errs)
         return
      end if
      if (.not. (d%refine_element > 0.0_dp)) then
         ! (a negative or NaN refine_element is reported above)
         if (ieee_is_finite(d%refine_from) .and. ieee_is_finite(d%refine_to) &
             .and. .not. (abs(d%refine_element) > 0.0_dp)) then
            if (abs(d%refine_from) > 0.0_dp .or. abs(d%refine_to) > 0.0_dp) call warn(at(p, 'sheet', 'refine_from')// &
               ': the zone is ignored with refine_element = 0 (no refined zone)')
         end if
         return
      end if
      ! the rest needs a valid sheet
      if (.not. (is_positive(d%thickness) .and. is_positive(d%length) .and. d%n_elements >= 2)) return
      if (.not. (ieee_is_finite(d%refine_from) .and. ieee_is_finite(d%refine_to) &
                 .and. ieee_is_finite(d%refine_element))) return
      n_before = errs%count
      half = 0.5_dp*d%length/d%thickness
      coarse = 2.0_dp*half/real(d%n_elements, dp)
      ! the ends of the sheet with a relative tolerance: L/h given in the
      ! deck's digits need not be L/h computed from the two lengths
      call check_real(errs, at(p, 'sheet', 'refine_from'), d%refine_from, lo=-half*(1.0_dp + 1.0e-9_dp), &
                      hi=half, hi_open=.true.)
      call check_real(errs, at(p, 'sheet', 'refine_to'), d%refine_to, lo=d%refine_from, &
                      hi=half*(1.0_dp + 1.0e-9_dp), lo_open=.true.)
      call check_real(errs, at(p, 'sheet', 'refine_element'), d%refine_element, &
                      lo=1.0e-3_dp, hi=coarse, hi_open=.true.)
      if (errs%count == n_before .and. d%refine_to - d%refine_from < d%refine_element) &
         call fail(errs, at(p, 'sheet', 'refine_to'), 'must be at least refine_from + refine_element = '// &
                   num(d%refine_from + d%refine_element)//' (a zone of one element or more; got '// &
                   num(d%refine_to)//')')
      if (abs(d%mesh_beta - 1.0_dp) > 0.0_dp) call fail(errs, at(p, 'sheet', 'mesh_beta'), &
         'must be 1 with a refined zone (refine_element > 0): the zone replaces the grading')
      if (errs%count > n_before) return
      call zone_counts(d%n_elements, half, d%refine_from, d%refine_to, d%refine_element, counts)
      if (sum(counts) > max_elements) call fail(errs, at(p, 'sheet', 'refine_element'), &
         'gives '//itoa(sum(counts))//' elements, more than '//itoa(max_elements)// &
         ' (the largest mesh the program holds in memory)')
   end subroutine check_refined_zone

   !> check_neck_zone -- &sheet refine_neck = .true.: the program places the
   !> zone (docs/theory.md §7.5), so refine_from and refine_to are not given;
   !> the neck is the load maximum of a pull, so the deck needs tools, a
   !> pull and tearing_criterion = 'load_maximum'; refine_element (default
   !> 0.08) is the zone's element, and the refined mesh must fit in memory.
   !>
   !> d     [in]     the resolved deck.
   !> p     [in]     the deck's path.
   !> errs  [in,out] problems are appended.
   subroutine check_neck_zone(d, p, errs)
      type(deck_type), intent(in) :: d
      character(len=*), intent(in) :: p
      type(error_list), intent(inout) :: errs
      real(dp) :: half
      integer :: counts(3)
      if (abs(d%refine_from) > 0.0_dp .or. abs(d%refine_to) > 0.0_dp) &
         call fail(errs, at(p, 'sheet', trim(merge('refine_from', 'refine_to  ', abs(d%refine_from) > 0.0_dp))), &
                   'must not be given with refine_neck = .true.'// &
                   ' (the program places the zone, '//num(neck_half_width)//'h either side of the neck'// &
                   ' of a pass on the uniform mesh); give either refine_neck or refine_from and refine_to')
      if (d%bead == 'none') call fail(errs, at(p, 'sheet', 'refine_neck'), &
                                      "needs tools (bead /= 'none'): the neck is that of a pull through a bead")
      if (d%tearing_criterion /= 'load_maximum') call fail(errs, at(p, 'sheet', 'refine_neck'), &
         "needs &control tearing_criterion = 'load_maximum' (the neck is the pull force's maximum)")
      if (ieee_is_finite(d%pull_distance)) then
         if (.not. (d%pull_distance > 0.0_dp)) call fail(errs, at(p, 'sheet', 'refine_neck'), &
            'needs a pull (&loading pull_distance > 0): the neck is found while pulling')
      end if
      if (abs(d%mesh_beta - 1.0_dp) > 0.0_dp) call fail(errs, at(p, 'sheet', 'mesh_beta'), &
         'must be 1 with refine_neck = .true.: the zone replaces the grading')
      if (.not. (ieee_is_finite(d%refine_element) .and. d%refine_element > 0.0_dp)) return
      ! at least four elements in the zone of 2 neck_half_width h
      call check_real(errs, at(p, 'sheet', 'refine_element'), d%refine_element, lo=1.0e-3_dp, &
                      hi=0.5_dp*neck_half_width)
      if (.not. (is_positive(d%thickness) .and. is_positive(d%length) .and. d%n_elements >= 2)) return
      half = 0.5_dp*d%length/d%thickness
      ! the first pass pulls 1.5 times the pull: on 80 elements of 0.625h
      ! the neck came up to a third late with the tools on the reference
      ! faces (within 1% on the current faces); on longer ones it may not be
      ! found within that (docs/theory.md §7.5)
      if (2.0_dp*half/real(d%n_elements, dp) > 0.75_dp*(1.0_dp + 1.0e-9_dp)) call warn(at(p, 'sheet', 'n_elements')// &
         ': uniform elements of '//num(2.0_dp*half/real(d%n_elements, dp))//'h: refine_neck finds the neck on'// &
         ' elements of 0.75h or shorter (the first pass may miss a neck near the end of the pull on longer ones)')
      ! the largest zone the program can place: a whole one inside the sheet
      call zone_counts(d%n_elements, half, -min(neck_half_width, half), min(neck_half_width, half), &
                       d%refine_element, counts)
      if (sum(counts) > max_elements) call fail(errs, at(p, 'sheet', 'refine_element'), &
         'gives '//itoa(sum(counts))//' elements with refine_neck, more than '//itoa(max_elements)// &
         ' (the largest mesh the program holds in memory)')
   end subroutine check_neck_zone

   !> umat_props_given -- how many of umat_props are given: the entries
   !> before the first unset one.
   pure function umat_props_given(d) result(n)
      type(deck_type), intent(in) :: d       !< [in] the deck
      integer :: n

      n = 0
      do while (n < max_umat_props)
         if (is_unset(d%umat_props(n + 1))) exit
         n = n + 1
      end do
   end function umat_props_given

   !> is_unset -- .true. for the `unset` sentinel (safe for NaN and Inf).
   elemental function is_unset(x) result(yes)
      real(dp), intent(in) :: x              !< [in] the value
      logical :: yes

      yes = .false.
      if (.not. ieee_is_finite(x)) return
      yes = x < -0.5_dp*huge(x)
   end function is_unset

end module deck
