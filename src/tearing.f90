!> tearing -- the criteria read off each converged state: the paper's
!> pointwise loss of positive definiteness of the section tangent (3.1),
!> the mesh-objective averaged-strain measure, the program's tearing
!> prediction (the maximum of the restraining force confirmed as a neck,
!> docs/theory.md §7.4; the criterion on the force history itself is
!> module load_maximum's) and the fold check (a station bent tighter
!> than the shell theory allows).  Each records the first time it is met
!> in the run record.
module tearing
   use, intrinsic :: iso_fortran_env, only: output_unit
   use kinds, only: dp
   use phases, only: phase_lock, phase_pull
   use errors, only: warn
   use text, only: num
   use hermite, only: n_gauss, gauss_wt
   use element, only: igp_strain, igp_curvature
   use model, only: model_type, state_type, gauss_position
   use record, only: run_record
   use remesh, only: last_radius_exit
   use load_maximum, only: track_load_maximum, load_at_maximum, first_near_max, stretched_share, &
                           neck_stretch_fraction
   implicit none
   private
   public :: check_localization, check_fold, strain_limit_indicator, first_crossing
   public :: check_load_maximum, tear_at_snap_back, station_lengths, set_torn, element_length_at, &
             neck_unresolved

   !> The tightest tool radius (centreline, in h) the sheet leaves last on
   !> the beads the strain-gradient term's tearing points were checked on
   !> against the continuum is 1.97h (the round bead; 2.62h, 3.28h and
   !> 4.66h besides, all within 0.97-1.16 of the continuum's necks,
   !> docs/theory.md §12.7): below validated_exit_radius_over_h the
   !> tearing point warns
   real(dp), parameter :: validated_exit_radius_over_h = 1.9_dp

contains

   !> CHECK_LOCALIZATION: the two tearing criteria over one converged
   !> increment [p - dt, p]; the first station of each to cross zero is
   !> recorded, interpolated linearly inside the increment.
   !>  m, s     [in]     model and the state converged at p
   !>  phase    [in]     'lock' or 'pull'
   !>  p, dt    [in]     load parameter at the end of the increment and its size
   !>  ind_old  [in]     the paper's indicator per station at p - dt
   !>  nl_old   [in,out] the averaged-strain indicator at p - dt; at p on exit
   !>  ell      [in]     averaging length of the mesh-objective measure, mm
   !>  rec      [in,out] localized, loc_phase, load_cr, s_star and the nl_
   !>                    counterparts, set once
   !>  paper_met [out]   .true. when the paper's criterion was first met in
   !>                    this increment
   subroutine check_localization(m, s, phase, p, dt, ind_old, nl_old, ell, rec, paper_met)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      character(len=*), intent(in) :: phase
      real(dp), intent(in) :: p, dt, ind_old(:, :), ell
      real(dp), intent(inout) :: nl_old(:)
      type(run_record), intent(inout) :: rec
      logical, intent(out) :: paper_met
      real(dp) :: frac
      real(dp), allocatable :: nl_new(:), g_old(:), g_new(:)
      integer :: k_cr
      paper_met = .false.
      ! the paper's pointwise criterion (3.1): the first Gauss station whose
      ! indicator crosses zero (the stations as one list, element by element)
      if (.not. rec%localized) then
         g_old = pack(ind_old, .true.)
         g_new = pack(s%indicator, .true.)
         call first_crossing(g_old, g_new, frac, k_cr)
         if (k_cr > 0) then
            rec%localized = .true.
            rec%loc_phase = phase
            rec%load_cr = p - dt + frac*dt
            rec%s_star = station_position(m, k_cr)
            paper_met = .true.
         end if
      end if
      ! the mesh-objective one: the mid-surface strain averaged over ell
      ! reaches the plane-strain maximum-load strain
      nl_new = strain_limit_indicator(m, s%gpn(igp_strain, :, :), ell)
      if (.not. rec%nl_localized) then
         call first_crossing(nl_old, nl_new, frac, k_cr)
         if (k_cr > 0) then
            rec%nl_localized = .true.
            rec%nl_phase = phase
            rec%nl_load_cr = p - dt + frac*dt
            rec%nl_s_star = station_position(m, k_cr)
         end if
      end if
      nl_old = nl_new
   end subroutine check_localization

   !> CHECK_LOAD_MAXIMUM: the load-maximum tearing criterion of a phase
   !> (docs/theory.md §7.4), after the increment's (load, force) has been
   !> appended to that phase's history: while pulling the restraining force
   !> N(delta), read from the split mesh's first sample on (§7.6); while a
   !> clamped sheet is locked its tension N(H) at the right edge.  Track the
   !> largest force and the strain field there; once a neck is confirmed
   !> past it, record the tearing point at the maximum (interpolated) and
   !> where the strain grew most since.
   !>  m, s   [in]     model and the state converged at the last point
   !>  phase  [in]     'lock' or 'pull'
   !>  rec    [in,out] the histories; max_at, strain_at_max; torn,
   !>                  tear_phase, tear_load, tear_s, set once
   subroutine check_load_maximum(m, s, phase, rec)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      character(len=*), intent(in) :: phase
      type(run_record), intent(inout) :: rec
      real(dp) :: load, share
      integer :: k
      if (rec%torn) return
      if (phase == phase_lock) then
         if (rec%n_lock == 0) return
         call track_load_maximum(rec%lock_lift(1:rec%n_lock), rec%lock_tension(1:rec%n_lock), &
                                 pack(log(1.0_dp + s%gpn(igp_strain, :, :)), .true.), station_lengths(m), &
                                 .false., m%thickness, rec%localized, rec%max_at, rec%strain_at_max, load, k)
      else
         associate (k0 => rec%split%pull_first)
            if (rec%n_pull < k0) return
            call track_load_maximum(rec%pull_delta(k0:rec%n_pull), rec%pull_force(k0:rec%n_pull), &
                                    pack(log(1.0_dp + s%gpn(igp_strain, :, :)), .true.), station_lengths(m), &
                                    .true., m%thickness, rec%localized, rec%max_at, rec%strain_at_max, load, k, &
                                    drawn_share=share)
            ! a lasting fall that the stretch test (7.6) holds for a draw-in:
            ! said once per candidate, so that a user reading the dip in
            ! pull.dat knows why it is not a tearing point
            if (share >= 0.0_dp .and. rec%draw_in_noted /= rec%max_at) then
               rec%draw_in_noted = rec%max_at
               write (output_unit, '(a)') '# drawbead: load_maximum: the restraining force has stayed 1% below '// &
                  'its largest (pull/h = '//num(anint(1.0e3_dp*rec%pull_delta(k0 + rec%max_at - 1)/m%thickness) &
                                              /1.0e3_dp)//') but the sheet keeps drawing in: '// &
                  num(anint(1.0e2_dp*share)/1.0e2_dp)//' of the pull since stretched it, a neck takes at least '// &
                  num(neck_stretch_fraction)//' (docs/theory.md (7.6)): not a neck'
            end if
         end associate
      end if
      if (k > 0) call set_torn(m, s, rec, phase, load, k)
   end subroutine check_load_maximum

   !> TEAR_AT_SNAP_BACK: an increment of the pull that cannot converge past
   !> a maximum of the restraining force (check_load_maximum), once the
   !> section has lost positive definiteness somewhere (the paper's
   !> criterion met), is the snap-back of a forming neck: no equilibrium is
   !> near under the prescribed pull (docs/theory.md §7.4), once the sheet
   !> has taken neck_stretch_fraction of the pull since the maximum as
   !> stretch (7.6), as in the confirmation.  The tearing point is then the
   !> maximum, at the station whose strain grew most since it.  Not while
   !> locking: there the confirmation asks the same as a snap-back could
   !> (the tension lock_force_drop below its maximum over tear_confirm_pull
   !> of lift, with the section lost), so a neck that forms as the bead
   !> closes is confirmed on the last converged state before any attempt
   !> fails, and a fall that has not lasted is a jump of the path (§8.3).
   !>  m, s   [in]     model and the last converged state
   !>  phase  [in]     'lock' or 'pull'
   !>  rec    [in,out] as check_load_maximum
   !>  torn   [out]    .true. when the tearing point was recorded here
   subroutine tear_at_snap_back(m, s, phase, rec, torn)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      character(len=*), intent(in) :: phase
      type(run_record), intent(inout) :: rec
      logical, intent(out) :: torn
      real(dp), allocatable :: growth(:), loads(:), forces(:)
      torn = .false.
      if (phase /= phase_pull .or. rec%torn .or. .not. rec%localized) return
      loads = rec%pull_delta(rec%split%pull_first:rec%n_pull)
      forces = rec%pull_force(rec%split%pull_first:rec%n_pull)
      if (rec%max_at == 0 .or. rec%max_at >= size(loads)) return
      growth = pack(log(1.0_dp + s%gpn(igp_strain, :, :)), .true.) - rec%strain_at_max
      ! a sheet still drawing in is not necking (7.6)
      if (stretched_share(growth, station_lengths(m), loads(size(loads)) - loads(rec%max_at)) &
          < neck_stretch_fraction) return
      call set_torn(m, s, rec, phase, load_at_maximum(loads, forces, rec%max_at, m%thickness), &
                    first_near_max(growth))
      torn = .true.
   end subroutine tear_at_snap_back

   !> ELEMENT_LENGTH_AT: the reference length of the element that holds the
   !> reference position s (the first of two that share a node).
   !>  m  [in] model
   !>  s  [in] reference position, mm, within [x(1), x(n_nodes)]
   pure function element_length_at(m, s) result(le)
      type(model_type), intent(in) :: m
      real(dp), intent(in) :: s
      real(dp) :: le
      integer :: e
      e = 1
      do while (e < m%n_el)
         if (s <= m%x(e + 1)) exit
         e = e + 1
      end do
      le = m%x(e + 1) - m%x(e)
   end function element_length_at

   !> SET_TORN: record the tearing point of the load-maximum criterion.
   !> Warn where it is known to be late: on elements too long for the
   !> neck, and, with the contact section's strain-gradient term, on a
   !> pull whose sheet leaves the tools last over a radius tighter than
   !> validated_exit_radius_over_h.
   !>  m      [in]     model
   !>  s      [in]     the state (the tool radius the sheet leaves last)
   !>  rec    [in,out] torn, tear_phase, tear_load, tear_s, tear_element
   !>  phase  [in]     'lock' or 'pull'
   !>  load   [in]     the lift H or the pull delta at tearing, mm
   !>  k      [in]     the station (flat list) where the neck forms
   subroutine set_torn(m, s, rec, phase, load, k)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      type(run_record), intent(inout) :: rec
      character(len=*), intent(in) :: phase
      real(dp), intent(in) :: load
      integer, intent(in) :: k
      real(dp) :: x_exit, radius
      logical :: found
      rec%torn = .true.
      rec%tear_phase = phase
      rec%tear_load = load
      rec%tear_s = station_position(m, k)
      rec%tear_element = element_length_at(m, rec%tear_s)
      ! on coarser elements than m%neck_element the force's maximum comes
      ! late (docs/theory.md §7.6: with the tools on the reference faces
      ! 18-45% on the continuum-check decks at 0.625-0.75h against 0.1h,
      ! with the current faces up to 22% at 1.25h against 0.75h); the
      ! tolerance keeps a zone of exactly that length (its rounded element) quiet
      ! (not in the first pass of refine_neck, which refines there next)
      ! (a maximum of the tension while locking is set by the wrap on the
      ! tool and converges on the uniform mesh: 4.587-4.609h from 80 to 640
      ! elements on tests/regression/decks/lock_tear_hss.nml)
      if (neck_unresolved(m, rec) .and. rec%neck%refinement /= 'first') then
         call warn('tearing point on elements of '//num(anint(1.0e3_dp*rec%tear_element/m%thickness)/1.0e3_dp)// &
                   'h at s = '//num(anint(1.0e2_dp*rec%tear_s/m%thickness)/1.0e2_dp)// &
                   'h: it converges on elements of '//num(m%neck_element/m%thickness)// &
                   'h or shorter there (docs/theory.md §7.6); '// &
                   'refine there (&sheet refine_neck, or refine_from, refine_to, refine_element)', 'set_torn')
      end if
      ! the neck's length (12.9) is checked against the continuum on beads
      ! whose sheet leaves a radius of 1.97h to 4.66h last (docs/theory.md
      ! §12.7); on a tighter one the tearing point is not validated
      if (phase == phase_pull .and. m%gradient > 0.0_dp .and. m%has_tools) then
         call last_radius_exit(m, s, x_exit, found, radius=radius)
         if (found .and. radius < validated_exit_radius_over_h*m%thickness) &
            call warn('tearing point where the sheet leaves a tool radius of '// &
                      num(anint(1.0e2_dp*radius/m%thickness)/1.0e2_dp)//'h, below the 1.97h of the '// &
                      'tightest radius it was checked on against the continuum (docs/theory.md §12.7)', &
                      'set_torn')
      end if
   end subroutine set_torn

   !> NECK_UNRESOLVED: is the tearing point a load maximum in the pull on
   !> an element longer than the model's neck_element, on which it does not
   !> converge (docs/theory.md §7.6)?  (A relative slack keeps an element of
   !> exactly that length, rounded, resolved; a maximum of the tension while
   !> locking converges on the uniform mesh, set_torn.)
   !>  m    [in] model
   !>  rec  [in] the run's record (tear_phase, tear_element)
   pure logical function neck_unresolved(m, rec)
      type(model_type), intent(in) :: m
      type(run_record), intent(in) :: rec
      neck_unresolved = rec%tear_phase == phase_pull .and. rec%tear_element > m%neck_element*(1.0_dp + 1.0e-6_dp)
   end function neck_unresolved

   !> CHECK_FOLD: a Gauss station bent to a radius below 1/fold_curvature
   !> thicknesses (|rho| h > fold_curvature) has folded: the shell theory
   !> assumes h/R << 1 (the paper's beads bend the sheet to h/R <= 0.36),
   !> and such folds are hinges one or two elements wide whose forces depend
   !> on the mesh (docs/validation.md, known differences).  Recorded and
   !> warned once per run.
   !>  m, s            [in]     model and converged state
   !>  phase           [in]     'lock' or 'pull'
   !>  p               [in]     load parameter, mm
   !>  fold_curvature  [in]     the limit on |rho| h
   !>  rec             [in,out] folded, fold_phase, fold_load, fold_s
   subroutine check_fold(m, s, phase, p, fold_curvature, rec)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      character(len=*), intent(in) :: phase
      real(dp), intent(in) :: p, fold_curvature
      type(run_record), intent(inout) :: rec
      integer :: fold_at
      real(dp) :: rho_h, h
      character(len=200) :: msg
      if (rec%folded) return
      h = m%thickness
      ! the first station (element order) within round-off of the largest
      ! |rho|: a symmetric sheet has two, and round-off must not choose
      fold_at = first_near_max(pack(abs(s%gpn(igp_curvature, :, :)), .true.))
      rho_h = maxval(abs(s%gpn(igp_curvature, :, :)))*h
      if (rho_h <= fold_curvature) return
      rec%folded = .true.
      rec%fold_phase = phase
      rec%fold_load = p
      rec%fold_s = station_position(m, fold_at)
      write (msg, '(a,f6.2,a,f8.3,a,es10.3,a)') 'the sheet folds: |rho| h = ', &
         rho_h, ' at s/h = ', rec%fold_s/h, ', load/h = ', p/h, &
         ' in '//phase//': beyond the shell theory, later results depend on the mesh'
      call warn(msg, 'check_fold')
   end subroutine check_fold

   !> STATION_LENGTHS: the reference length each Gauss station stands for,
   !> its element's length times its weight, in the flat list of stations
   !> (k = (e - 1) n_gauss + ig); they sum to the sheet's length.
   !>  m  [in] model
   pure function station_lengths(m) result(ds)
      type(model_type), intent(in) :: m
      real(dp) :: ds(n_gauss*m%n_el)
      integer :: e
      do e = 1, m%n_el
         ds((e - 1)*n_gauss + 1:e*n_gauss) = (m%x(e + 1) - m%x(e))*gauss_wt
      end do
   end function station_lengths

   !> STATION_POSITION: reference abscissa of station k of the flat list
   !> of Gauss stations, element by element (k = (e - 1) n_gauss + ig).
   pure function station_position(m, k) result(xg)
      type(model_type), intent(in) :: m
      integer, intent(in) :: k
      real(dp) :: xg
      integer :: e, ig
      e = (k - 1)/n_gauss + 1
      ig = k - (e - 1)*n_gauss
      xg = gauss_position(m, e, ig)
   end function station_position

   !> FIRST_CROSSING: the station whose indicator crosses zero earliest in
   !> the increment, by linear interpolation between the two states.
   !>  g_old, g_new [in]  indicators at the start and end of the increment
   !>  frac         [out] fraction of the increment at the crossing
   !>  k            [out] the station (0: none crossed)
   pure subroutine first_crossing(g_old, g_new, frac, k)
      real(dp), intent(in) :: g_old(:), g_new(:)
      real(dp), intent(out) :: frac
      integer, intent(out) :: k
      integer :: i
      real(dp) :: f
      k = 0
      frac = 2.0_dp
      do i = 1, size(g_old)
         if (g_old(i) > 0.0_dp .and. g_new(i) <= 0.0_dp) then
            f = g_old(i)/(g_old(i) - g_new(i))
            if (f < frac) then
               frac = f
               k = i
            end if
         end if
      end do
   end subroutine first_crossing

   !> STRAIN_LIMIT_INDICATOR: the mesh-objective tearing measure.  The
   !> mid-surface log strain ln(lambda) is averaged over a reference length
   !> ell centred on each Gauss station (clipped at the sheet's ends, Gauss
   !> weights as quadrature), and the indicator is the margin left to the
   !> material's plane-strain maximum-load strain (FLD0):
   !>    g = eps_max - <ln lambda>_ell,   torn when g <= 0.
   !> A neck in a sheet spans a length of the order of its thickness and the
   !> shell theory resolves nothing shorter, so the average over ell ~ h is
   !> a property of the converged strain field, not of where the stations
   !> fall; in uniform tension it coincides with the paper's criterion.
   !> Sliding window with prefix sums: O(stations).
   !>  m      [in]  model (its max_load_strain)
   !>  eps    [in]  mid-surface strain lambda - 1 at the stations (n_gauss, n_el)
   !>  ell    [in]  averaging length, mm
   pure function strain_limit_indicator(m, eps, ell) result(g)
      type(model_type), intent(in) :: m
      real(dp), intent(in) :: eps(:, :), ell
      real(dp), allocatable :: g(:)
      real(dp), allocatable :: xs(:), pw(:), pg(:)
      real(dp) :: wt
      integer :: e, ig, k, lo, hi, n
      n = size(eps)
      allocate (xs(n), pw(0:n), pg(0:n), g(n))
      pw(0) = 0.0_dp
      pg(0) = 0.0_dp
      do e = 1, m%n_el
         do ig = 1, n_gauss
            k = (e - 1)*n_gauss + ig
            xs(k) = gauss_position(m, e, ig)
            wt = gauss_wt(ig)*(m%x(e + 1) - m%x(e))
            pw(k) = pw(k - 1) + wt
            pg(k) = pg(k - 1) + wt*log(1.0_dp + eps(ig, e))
         end do
      end do
      lo = 1
      hi = 1
      do k = 1, n
         do while (xs(lo) < xs(k) - 0.5_dp*ell)
            lo = lo + 1
         end do
         do while (hi < n)
            if (xs(hi + 1) > xs(k) + 0.5_dp*ell) exit
            hi = hi + 1
         end do
         g(k) = m%max_load_strain - (pg(hi) - pg(lo - 1))/(pw(hi) - pw(lo - 1))
      end do
   end function strain_limit_indicator
end module tearing
