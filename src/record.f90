!> record -- what a run has found so far: the tearing and fold points, the
!> forces, the pull history, the counts and the energy bookkeeping.  Filled
!> by the increment loop (analysis, tearing, energy) and written to
!> summary.txt (summary).
module record
   use kinds, only: dp
   implicit none
   private
   public :: run_record, run_record_init, record_pull, record_lock, neck_record, split_record, split_note
   public :: run_ok, run_no_convergence, run_interrupted, run_write_failed, run_out_of_memory

   !> run_record%status: the run went on to its end (or stopped at tearing);
   !> an increment could not converge; SIGTERM or SIGINT stopped it; a
   !> result file could not be written; an allocation failed.
   integer, parameter :: run_ok = 0, run_no_convergence = 2, run_interrupted = 3, &
                         run_write_failed = 4, run_out_of_memory = 5

   !> The neck's refined zone (&sheet refine_neck, docs/theory.md §7.5):
   !> refinement is 'off' (not asked for), 'first' (this is the first pass
   !> on the deck's uniform mesh, or the run stopped in it), 'zone' (the
   !> run's mesh has a zone around the first pass's neck) or 'none' (the
   !> uniform mesh's elements are no longer than the zone's, or the first
   !> pass found no neck); the first pass's tearing point, element count
   !> and assemblies; the zone [s0, s1] (mm, reference positions).
   type :: neck_record
      character(len=8) :: refinement = 'off'
      logical :: coarse_torn = .false.
      real(dp) :: coarse_tear_load = 0.0_dp, coarse_tear_s = 0.0_dp
      real(dp) :: zone(2) = 0.0_dp
      integer :: coarse_elements = 0, coarse_assemblies = 0
   end type neck_record

   !> The neck's refinement on the default path (docs/theory.md §7.6): armed
   !> (the force has turned toward a maximum) and the splits done; of the
   !> first, the phase and load parameter (mm), the exit of the last radius
   !> there (current abscissa, mm); the span of all split elements [s0, s1]
   !> (mm, reference positions), the element counts before the first and
   !> after the last, and the first sample of the pull history on
   !> the split mesh (the load-maximum criterion reads the history from
   !> there: the re-equilibrated state's force differs from the last one
   !> on the coarse mesh by the mapping's error, some 0.5%).
   type :: split_record
      logical :: armed = .false.     ! the force has turned: splits are due
      integer :: count = 0           ! splits done
      character(len=8) :: phase = ''
      real(dp) :: load = 0.0_dp, x_exit = 0.0_dp, zone(2) = 0.0_dp
      integer :: elements_before = 0, elements_after = 0
      integer :: pull_first = 1
      real(dp) :: force_change = 0.0_dp
      ! the change of the stored, dissipated and thickness-stress energies
      ! (N mm/mm) over the splits beyond the dead loads' work: the mapping's
      ! share, kept out of the energy balance
      real(dp) :: energy_change = 0.0_dp
      ! a split whose mapped state found no equilibrium, undone: the run
      ! went on, unrefined, on the mesh before it (docs/theory.md §7.6)
      logical :: abandoned = .false.
      real(dp) :: abandoned_load = 0.0_dp
   end type split_record

   !> What the run has found so far (written to summary.txt).
   type :: run_record
      ! the paper's pointwise criterion (3.1)
      logical :: localized = .false.
      character(len=8) :: loc_phase = ''
      real(dp) :: load_cr = 0.0_dp, s_star = 0.0_dp
      ! the mesh-objective criterion (strain averaged over tearing_length)
      logical :: nl_localized = .false.
      character(len=8) :: nl_phase = ''
      real(dp) :: nl_load_cr = 0.0_dp, nl_s_star = 0.0_dp
      ! the program's tearing prediction (&control tearing_criterion,
      ! docs/theory.md §7.4): phase, load parameter, reference position and
      ! the length of the element there (the load maximum converges on
      ! elements of 0.1h or shorter where the neck forms)
      logical :: torn = .false.
      character(len=8) :: tear_phase = ''
      real(dp) :: tear_load = 0.0_dp, tear_s = 0.0_dp, tear_element = 0.0_dp
      ! a run asked to go on past its tearing point (stop_at_localization =
      ! .false.) that found no equilibrium further on: the pull there (the
      ! neck has thinned further than the shell follows, theory §7.4)
      logical :: stopped_past_tear = .false.
      real(dp) :: stopped_past_tear_load = 0.0_dp
      ! the load-maximum candidate: index in the pull history from
      ! split%pull_first of the largest restraining force so far (0: none
      ! yet) and ln(lambda) at every Gauss station (flat list, element by
      ! element) in that state
      integer :: max_at = 0
      real(dp), allocatable :: strain_at_max(:)
      ! the candidate whose lasting fall the stretch test (7.6) held for a
      ! sheet still drawing in, noted once in the log (0: none)
      integer :: draw_in_noted = 0
      real(dp) :: peak_force = 0.0_dp, lock_force = 0.0_dp
      real(dp) :: last_lift = 0.0_dp
      integer :: increments = 0, newton_iterations = 0, cutbacks = 0
      integer :: assemblies = 0   ! calls of the global assembly (solver's assemble)
      integer :: status = run_ok
      character(len=512) :: message = ''
      real(dp), allocatable :: pull_delta(:), pull_force(:)
      integer :: n_pull = 0
      ! the locking history of a clamped sheet: lift H and the sheet's
      ! tension N at the right edge (the load-maximum criterion of the lock)
      real(dp), allocatable :: lock_lift(:), lock_tension(:)
      integer :: n_lock = 0
      real(dp) :: max_penetration = 0.0_dp
      ! the first converged state folded tighter than fold_curvature (|rho| h)
      logical :: folded = .false.
      character(len=8) :: fold_phase = ''
      real(dp) :: fold_load = 0.0_dp, fold_s = 0.0_dp
      ! energy bookkeeping (N mm per mm of width): external work so far, the
      ! force conjugate to the load parameter at the last increment, and the
      ! work and stored/dissipated energies when pulling started
      real(dp) :: work = 0.0_dp, work_pull_start = 0.0_dp
      real(dp) :: last_conjugate = 0.0_dp
      real(dp), allocatable :: reactions(:)      ! residual (reactions at fixed dofs), last increment
      real(dp) :: energy_pull_start(6) = 0.0_dp   ! energy_totals at the pull's start (energy's n_energy entries)
      ! the neck's refined zone and the first pass that placed it
      type(neck_record) :: neck
      ! the elements split at the exit of the last radius
      type(split_record) :: split
   end type run_record

contains

   !> RUN_RECORD_INIT: empty record with room for the pull history.
   !>  rec  [out] the record
   subroutine run_record_init(rec)
      type(run_record), intent(out) :: rec
      allocate (rec%pull_delta(1024), rec%pull_force(1024), rec%lock_lift(1024), rec%lock_tension(1024))
      ! zeros, not whatever the heap held: a summary of a run with no pull
      ! row still forms pull_force(1)/(E h) (a denormal there raised the
      ! underflow flag the checked build notes)
      rec%pull_delta = 0.0_dp
      rec%pull_force = 0.0_dp
      rec%lock_lift = 0.0_dp
      rec%lock_tension = 0.0_dp
   end subroutine run_record_init

   !> RECORD_PULL: append (delta, N) to the pull history, growing it as needed.
   !>  rec    [in,out] the record
   !>  delta  [in]     pull distance, mm
   !>  force  [in]     restraining force N, N/mm
   subroutine record_pull(rec, delta, force)
      type(run_record), intent(inout) :: rec
      real(dp), intent(in) :: delta, force
      call append(rec%pull_delta, rec%pull_force, rec%n_pull, delta, force)
   end subroutine record_pull

   !> RECORD_LOCK: append (H, N) to the locking history.
   !>  rec    [in,out] the record
   !>  lift   [in]     rise H of the lower tool, mm
   !>  force  [in]     the sheet's tension N at the right edge, N/mm
   subroutine record_lock(rec, lift, force)
      type(run_record), intent(inout) :: rec
      real(dp), intent(in) :: lift, force
      call append(rec%lock_lift, rec%lock_tension, rec%n_lock, lift, force)
   end subroutine record_lock

   !> APPEND: one sample (x, y) after the n held, the arrays doubled when full.
   subroutine append(xs, ys, n, x, y)
      real(dp), allocatable, intent(inout) :: xs(:), ys(:)
      integer, intent(inout) :: n
      real(dp), intent(in) :: x, y
      real(dp), allocatable :: tmp(:)
      if (n == size(xs)) then
         allocate (tmp(2*n))
         tmp(1:n) = xs
         call move_alloc(tmp, xs)
         allocate (tmp(2*n))
         tmp(1:n) = ys
         call move_alloc(tmp, ys)
      end if
      n = n + 1
      xs(n) = x
      ys(n) = y
   end subroutine append

   !> SPLIT_NOTE: what a strain file's header says of a split mesh (its
   !> rows are that mesh's Gauss stations): '' without a split.
   !>  rec  [in] the record
   !>  h    [in] thickness, mm
   function split_note(rec, h) result(note)
      type(run_record), intent(in) :: rec
      real(dp), intent(in) :: h
      character(len=:), allocatable :: note
      character(len=160) :: buf
      note = ''
      if (rec%split%count == 0) return
      write (buf, '(a,f0.4,a,i0,a,i0,a,i0,a)') ' (on the mesh split from pull/h = ', rec%split%load/h, &
         ' on, ', rec%split%count, ' times: ', rec%split%elements_after, ' elements, ', &
         rec%split%elements_before, ' before; the rows follow the mesh, docs/theory.md §7.6)'
      note = trim(buf)
   end function split_note
end module record
