!> controls -- how a run is carried out, apart from what is computed: the
!> increments and Newton's tolerances, the tearing and fold criteria, and
!> what is written.  Set once by module setup from the deck; read by the
!> increment loop (analysis) and the summary.
module controls
   use kinds, only: dp
   implicit none
   private
   public :: controls_type

   !> The step and output controls of a run (lengths in mm unless named
   !> `_over_h`, the sheet thickness being the unit there).
   type :: controls_type
      ! what is written
      character(len=256) :: title = ''
      character(len=512) :: output_dir = ''
      real(dp) :: snapshot_every_over_h = 0.0_dp   ! strain snapshot each multiple of it (0: none)
      logical :: log_residuals = .false.           ! each increment's Newton residuals and state counts
      ! increments (mm of the load parameter) and Newton
      real(dp) :: initial_increment = 0.0_dp
      real(dp) :: min_increment = 0.0_dp
      real(dp) :: max_increment = 0.0_dp
      integer :: max_iterations = 20
      real(dp) :: tolerance = 1.0e-8_dp            ! relative residual; sqrt of it on the correction
      real(dp) :: max_force_change = 0.1_dp        ! target relative change of the phase's force per increment
      real(dp) :: squeeze_force_change = 0.04_dp   ! the same in the binder's squeeze (docs/theory.md §8.3)
      real(dp) :: step_tolerance = 5.0e-3_dp       ! local error of the path per increment (docs/theory.md §8.3; 0: off)
      real(dp) :: branch_increment = 0.0_dp        ! largest increment past a section's maximum load, mm (§8.3)
      logical :: predictor = .true.                ! extrapolate the last increment's motion
      ! tearing and fold criteria
      logical :: stop_at_localization = .true.
      character(len=16) :: tearing_criterion = 'load_maximum'  ! the tearing prediction (docs/theory.md §7.4)
      real(dp) :: tearing_length_over_h = 1.0_dp   ! averaging length of the mesh-objective measure
      real(dp) :: fold_curvature = 1.0_dp          ! |rho| h above which the sheet is reported folded
      ! &sheet refine_neck (docs/theory.md §7.5): a first pass on the
      ! deck's mesh finds the neck, the run proper has a zone of elements
      ! of refine_element_over_h h around it
      logical :: refine_neck = .false.
      real(dp) :: refine_element_over_h = 0.0_dp
   end type controls_type
end module controls
