!> tearing -- the criteria read off each converged state: the paper's
!> pointwise loss of positive definiteness of the section tangent (3.1),
!> the mesh-objective averaged-strain measure, the program's tearing
!> prediction (the maximum of the restraining force confirmed as a neck,
!> docs/theory.md §7.4) and the fold check (a station bent tighter than
!> the shell theory allows).  Each records the first time it is met in
!> the run record.
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
   implicit none
   private
   public :: check_localization, check_fold, strain_limit_indicator, first_crossing
   public :: check_load_maximum, tear_at_snap_back, track_load_maximum, neck_confirmed, &
             load_at_maximum, parabola_vertex
   public :: tear_force_drop, lock_force_drop, neck_strain_rate, tear_confirm_pull, neck_stretch_fraction, station_lengths, &
             set_torn, element_length_at
   public :: maximum_approaching, approach_slope_ratio, fall_duration

   !> A maximum of the restraining force is a neck once the force has fallen
   !> tear_force_drop (relative) below it and either the fastest-stretching
   !> station's log strain has grown by at least neck_strain_rate times the
   !> pull since the maximum, in units of h, or the section tangent has lost
   !> positive definiteness somewhere (docs/theory.md §7.4): a neck about h
   !> long takes the whole pull (rate ~1); steady drawing through a bead
   !> stretches each station by 0.05-0.08 per h of pull.
   real(dp), parameter :: tear_force_drop = 0.01_dp, neck_strain_rate = 0.5_dp
   !> While the bead closes the tension of a clamped sheet falls by up to
   !> about 1% after a flat maximum without any neck, as the tools close
   !> on the wrapped sheet: the continuum's by 0.94% from 90% of full lock
   !> to full lock on bead A with an HSLA steel (thickness strain -0.32 at
   !> both male corners alike), the program's by 1.1-1.5% on 80-640
   !> elements; where the continuum necks while locking the tension falls
   !> 4.5-10% by full lock.  A maximum of the tension is a neck once it
   !> has fallen lock_force_drop below it (docs/theory.md §7.4)
   real(dp), parameter :: lock_force_drop = 0.02_dp
   !> ... and the force has stayed that far below it over a pull of at least
   !> tear_confirm_pull (in h): past the section's maximum load the path may
   !> jump to a neighbouring branch, the force dipping 1-1.5% for a few
   !> thousandths of h and recovering (bead A mu 0, contact section);
   !> a neck's fall lasts 0.1h or more (the continuum's: 0.2h to fall 1%)
   real(dp), parameter :: tear_confirm_pull = 0.05_dp
   !> ... and, in the pull, at least neck_stretch_fraction of the pull since
   !> the maximum has gone into stretching the sheet (the sum over the
   !> stations of their log strain growth times their reference length):
   !> a neck stops the draw-in and takes the pull (0.69-0.80 on the
   !> clamped and the double bead's necks at their confirmation), while a
   !> sheet drawing steadily through the bead takes most of the pull as
   !> inflow, stretching by about its exit strain eps/(1 + eps) of it
   !> (0.25 and 0.34 on the stepped and round beads' dips, which the
   !> continuum draws through without a neck; docs/theory.md §7.4)
   real(dp), parameter :: neck_stretch_fraction = 0.5_dp
   !> The restraining force approaches a neck's maximum once its slope over
   !> the last approach_window h of pull has fallen to approach_slope_ratio
   !> of its slope over [0.05h, 0.15h] while the force is at least
   !> approach_capacity of the sheet's plane-strain capacity tau* h
   !> (docs/theory.md §7.6)
   real(dp), parameter :: approach_slope_ratio = 0.5_dp, approach_window = 0.1_dp, &
                          approach_capacity = 0.6_dp
   !> The tightest tool radius (centreline, in h) the sheet leaves last on
   !> the beads the strain-gradient term's tearing points were checked on
   !> against the continuum is 1.97h (the round bead; 2.62h, 3.28h and
   !> 4.66h besides, all within 0.89-1.13 of the continuum's necks,
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
      ! on coarser elements the neck (width of order h/sqrt(12), §12.7) is
      ! not resolved and the force's maximum comes late: 18-45% on the
      ! continuum-check decks at 0.625-0.75h (docs/validation.md); the
      ! tolerance keeps a zone of exactly 0.1h (its rounded element) quiet
      ! (not in the first pass of refine_neck, which refines there next)
      ! (a maximum of the tension while locking is set by the wrap on the
      ! tool and converges on the uniform mesh: 4.587-4.609h from 80 to 640
      ! elements on tests/regression/decks/lock_tear_hss.nml)
      if (phase == phase_pull .and. rec%tear_element > 0.1_dp*m%thickness*(1.0_dp + 1.0e-6_dp) .and. &
          rec%neck%refinement /= 'first') then
         call warn('tearing point on elements of '//num(anint(1.0e3_dp*rec%tear_element/m%thickness)/1.0e3_dp)// &
                   'h at s = '//num(anint(1.0e2_dp*rec%tear_s/m%thickness)/1.0e2_dp)// &
                   'h: it converges on elements of 0.1h or shorter there (docs/validation.md); '// &
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

   !> TRACK_LOAD_MAXIMUM: one step of the load-maximum criterion on a force
   !> history.  A new largest force (strictly above the one held) becomes
   !> the candidate maximum, with the strain field of that state; past it,
   !> neck_confirmed decides.
   !>  delta, force   [in]     the pull history up to the current state
   !>                          (the current state last)
   !>  strain         [in]     log strain per station in the current state
   !>  ds             [in]     reference length per station, mm (station_lengths)
   !>  pulled         [in]     the load is the pull of the sheet's end: the
   !>                          stretch test applies (not while locking,
   !>                          whose load is the lift)
   !>  h              [in]     thickness (unit of the pull in the rate)
   !>  section_lost   [in]     the section tangent has lost positive
   !>                          definiteness at some station (paper's (3.1))
   !>  max_at         [in,out] index of the candidate maximum (0: none yet)
   !>  strain_at_max  [in,out] strain per station at the candidate
   !>  tear_load      [out]    the interpolated maximum when torn, else 0
   !>  k              [out]    the neck's station when torn, else 0
   !>  drawn_share    [out]    optional: in the pull, once the fall has
   !>                          lasted, the share of the pull since the
   !>                          maximum that stretched the sheet when it is
   !>                          below neck_stretch_fraction (the sheet draws
   !>                          in: not a neck); else -1
   pure subroutine track_load_maximum(delta, force, strain, ds, pulled, h, section_lost, max_at, strain_at_max, &
                                      tear_load, k, drawn_share)
      real(dp), intent(in) :: delta(:), force(:), strain(:), ds(:), h
      logical, intent(in) :: pulled, section_lost
      integer, intent(inout) :: max_at
      real(dp), allocatable, intent(inout) :: strain_at_max(:)
      real(dp), intent(out) :: tear_load
      integer, intent(out) :: k
      real(dp), intent(out), optional :: drawn_share
      real(dp), allocatable :: growth(:)
      real(dp) :: stretched, drop
      integer :: n
      n = size(force)
      k = 0
      tear_load = 0.0_dp
      if (present(drawn_share)) drawn_share = -1.0_dp
      ! (two tests: Fortran's .or. may evaluate force(max_at) with max_at = 0)
      if (max_at == 0) then
         max_at = n
         strain_at_max = strain
         return
      end if
      if (force(n) > force(max_at)) then
         max_at = n
         strain_at_max = strain
         return
      end if
      ! the drop must have lasted tear_confirm_pull
      drop = merge(tear_force_drop, lock_force_drop, pulled)
      if (fall_duration(delta, force, max_at, drop) < tear_confirm_pull*h) return
      growth = strain - strain_at_max
      ! the share of the pull since the maximum taken up as stretch
      stretched = 1.0_dp
      if (pulled) stretched = stretched_share(growth, ds, delta(n) - delta(max_at))
      if (present(drawn_share) .and. stretched < neck_stretch_fraction) drawn_share = stretched
      if (neck_confirmed(force(max_at), force(n), drop, (delta(n) - delta(max_at))/h, growth, &
                         section_lost, stretched)) then
         k = first_near_max(growth)
         tear_load = load_at_maximum(delta, force, max_at, h)
      end if
   end subroutine track_load_maximum

   !> FALL_DURATION: how long the force has stayed drop (relative) below
   !> its maximum: the load from the first sample of the last run of
   !> samples that are all below that threshold to the last sample (0 when
   !> the last is not below it).
   !>  delta, force [in] the history (the current state last)
   !>  max_at       [in] index of the maximum, within the history
   !>  drop         [in] the relative fall
   pure function fall_duration(delta, force, max_at, drop) result(duration)
      real(dp), intent(in) :: delta(:), force(:), drop
      integer, intent(in) :: max_at
      real(dp) :: duration
      integer :: n, j
      n = size(force)
      duration = 0.0_dp
      if (max_at < 1 .or. max_at >= n) return
      if (force(n) > (1.0_dp - drop)*force(max_at)) return
      j = n
      do while (j > max_at + 1)
         if (force(j - 1) > (1.0_dp - drop)*force(max_at)) exit
         j = j - 1
      end do
      duration = delta(n) - delta(j)
   end function fall_duration

   !> NECK_CONFIRMED: is the state past a maximum of the restraining force a
   !> neck?  The force has fallen by drop of the maximum (tear_force_drop
   !> in the pull, lock_force_drop while locking), and
   !> either the log strain of one station has grown by at least
   !> neck_strain_rate per h of pull since the maximum (the strain
   !> concentrates) or the section has lost positive definiteness somewhere
   !> (a station can localize; in uniform tension the whole sheet can), and
   !> the sheet has taken at least neck_stretch_fraction of the pull as
   !> stretch, not as draw-in (docs/theory.md §7.4).
   !>  f_max        [in]  the force at the maximum
   !>  f            [in]  the force now
   !>  drop         [in]  the relative fall that confirms
   !>  pull_over_h  [in]  the pull since the maximum, in units of h
   !>  growth       [in]  the growth of each station's log strain since then
   !>  section_lost [in]  the paper's criterion (3.1) has been met
   !>  stretched    [in]  the share of the pull since the maximum that
   !>                     stretched the sheet (1 while locking)
   pure function neck_confirmed(f_max, f, drop, pull_over_h, growth, section_lost, stretched) result(yes)
      real(dp), intent(in) :: f_max, f, drop, pull_over_h, growth(:), stretched
      logical, intent(in) :: section_lost
      logical :: yes
      logical :: concentrated
      yes = .false.
      if (size(growth) == 0 .or. .not. f_max > 0.0_dp) return
      if (f > (1.0_dp - drop)*f_max) return
      if (stretched < neck_stretch_fraction) return
      concentrated = maxval(growth) > 0.0_dp .and. &
                     maxval(growth) >= neck_strain_rate*max(pull_over_h, 0.0_dp)
      yes = concentrated .or. section_lost
   end function neck_confirmed

   !> LOAD_AT_MAXIMUM: the load parameter at a maximum of a sampled force
   !> history.  Past a section's maximum load the force carries noise (the
   !> path jumping between neighbouring branches: dips of 1-1.5% for a few
   !> thousandths of h, docs/theory.md §7.4), and three samples next to
   !> such a dip put the vertex of a flat maximum anywhere between them.
   !> The vertex of the least-squares parabola through the samples within
   !> top_window h of the largest and within top_band (relative) of its
   !> force, kept within their range, when there are at least four such
   !> samples and the parabola opens downward; otherwise the vertex of the
   !> parabola through the largest sample and its two neighbours, kept
   !> between the neighbours; the sample itself when it is the first or
   !> the last.
   !>  delta, force [in]  the history (increasing delta), mm and N/mm
   !>  i            [in]  index of the largest sample
   !>  h            [in]  thickness, mm
   pure function load_at_maximum(delta, force, i, h) result(x)
      real(dp), intent(in) :: delta(:), force(:), h
      integer, intent(in) :: i
      ! the window only keeps a long plateau out of the fit: the band
      ! decides.  At 0.1h the fit missed much of the top band of a flat
      ! maximum, and halving every increment moved the double bead's vertex
      ! by 4.3% (0.01% at 0.3h; 0.2h to 0.5h move the clamped decks'
      ! vertices by at most 2%: docs/theory.md §7.4)
      real(dp), parameter :: top_band = 0.005_dp, top_window = 0.3_dp
      real(dp) :: x, y, s(0:4), r(0:2), u, lo, hi, a(3, 3), det, c1, c2
      integer :: j, k, n_top
      x = delta(i)
      if (i <= 1 .or. i >= size(delta)) return
      ! the normal equations of y = c0 + c1 u + c2 u^2, u = delta - delta(i)
      s = 0.0_dp
      r = 0.0_dp
      n_top = 0
      lo = delta(i)
      hi = delta(i)
      do j = 1, size(delta)
         if (force(j) < (1.0_dp - top_band)*force(i)) cycle
         if (abs(delta(j) - delta(i)) > top_window*h) cycle
         n_top = n_top + 1
         u = delta(j) - delta(i)
         lo = min(lo, delta(j))
         hi = max(hi, delta(j))
         do k = 0, 4
            s(k) = s(k) + u**k
         end do
         do k = 0, 2
            r(k) = r(k) + force(j)*u**k
         end do
      end do
      if (n_top >= 4) then
         a = reshape([s(0), s(1), s(2), s(1), s(2), s(3), s(2), s(3), s(4)], [3, 3])
         det = det3(a)
         if (abs(det) > 0.0_dp) then
            ! Cramer's rule for c1 and c2
            c1 = det3(reshape([s(0), s(1), s(2), r(0), r(1), r(2), s(2), s(3), s(4)], [3, 3]))/det
            c2 = det3(reshape([s(0), s(1), s(2), s(1), s(2), s(3), r(0), r(1), r(2)], [3, 3]))/det
            if (c2 < 0.0_dp) then
               x = min(max(delta(i) - 0.5_dp*c1/c2, lo), hi)
               return
            end if
         end if
      end if
      call parabola_vertex(delta(i - 1:i + 1), force(i - 1:i + 1), x, y)
      x = min(max(x, delta(i - 1)), delta(i + 1))
   end function load_at_maximum

   !> DET3: the determinant of a 3 x 3 matrix.
   pure function det3(a) result(d)
      real(dp), intent(in) :: a(3, 3)
      real(dp) :: d
      d = a(1, 1)*(a(2, 2)*a(3, 3) - a(2, 3)*a(3, 2)) - a(1, 2)*(a(2, 1)*a(3, 3) - a(2, 3)*a(3, 1)) &
          + a(1, 3)*(a(2, 1)*a(3, 2) - a(2, 2)*a(3, 1))
   end function det3

   !> PARABOLA_VERTEX: vertex of the parabola through three points with
   !> increasing abscissae (Newton's divided differences).  Without
   !> curvature (collinear points), or with abscissae not increasing, the
   !> middle point is returned.
   !>  x, y    [in]  the points
   !>  xv, yv  [out] the vertex
   pure subroutine parabola_vertex(x, y, xv, yv)
      real(dp), intent(in) :: x(3), y(3)
      real(dp), intent(out) :: xv, yv
      real(dp) :: d1, d2, c2
      xv = x(2)
      yv = y(2)
      if (.not. (x(2) > x(1) .and. x(3) > x(2))) return
      d1 = (y(2) - y(1))/(x(2) - x(1))
      d2 = (y(3) - y(2))/(x(3) - x(2))
      c2 = (d2 - d1)/(x(3) - x(1))
      if (.not. abs(c2) > 0.0_dp) return
      ! y = y1 + d1 (x - x1) + c2 (x - x1)(x - x2): y' = 0 at
      xv = 0.5_dp*(x(1) + x(2)) - 0.5_dp*d1/c2
      yv = y(1) + d1*(xv - x(1)) + c2*(xv - x(1))*(xv - x(2))
   end subroutine parabola_vertex

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

   !> FIRST_NEAR_MAX: the first entry within 1e-9 (relative) of the largest
   !> value: on a symmetric sheet two stations tie to round-off, and
   !> round-off must not choose between them.
   !>  v  [in]  the values (not empty)
   pure function first_near_max(v) result(k)
      real(dp), intent(in) :: v(:)
      integer :: k
      real(dp) :: vmax
      vmax = maxval(v)
      k = maxloc(merge(1, 0, v >= vmax - 1.0e-9_dp*abs(vmax)), 1)
   end function first_near_max

   !> STRETCHED_SHARE: the share of a pull that stretched the sheet, the
   !> left side of (7.6) over its pull (docs/theory.md §7.4): the stations'
   !> log-strain growth, where positive, times their reference lengths,
   !> over the pull.
   !>  growth  [in] each station's log-strain growth over the pull
   !>  ds      [in] their reference lengths, mm (station_lengths)
   !>  pull    [in] the pull, mm (> 0)
   pure real(dp) function stretched_share(growth, ds, pull)
      real(dp), intent(in) :: growth(:), ds(:), pull
      stretched_share = sum(max(growth, 0.0_dp)*ds)/max(pull, tiny(1.0_dp))
   end function stretched_share

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

   !> MAXIMUM_APPROACHING: has the restraining force turned toward a neck's
   !> maximum?  Its secant slope over the last approach_window h of pull
   !> (the history interpolated linearly) against the slope over [0.05h,
   !> 0.15h] (past the elastic start of the pull): .true. once the ratio is
   !> at most approach_slope_ratio (or the early slope is not positive) and
   !> the force is at least approach_capacity times the sheet's capacity
   !> tau* h: the section that carries N at the exit of the last radius
   !> then nears its maximum load (docs/theory.md §7.6); a force far below
   !> the capacity (a free edge drawing steadily) is no neck.  Needs a pull
   !> of at least 0.15h + approach_window h (else .false.).
   !>  delta, force  [in] the pull history (ascending delta), mm, N/mm
   !>  h             [in] thickness, mm
   !>  capacity      [in] the sheet's plane-strain capacity tau* h, N/mm
   pure function maximum_approaching(delta, force, h, capacity) result(yes)
      real(dp), intent(in) :: delta(:), force(:), h, capacity
      logical :: yes
      real(dp) :: s_ref, s_now, d
      integer :: n
      yes = .false.
      n = size(delta)
      if (n < 2) return
      d = delta(n)
      if (d < (0.15_dp + approach_window)*h) return
      if (force(n) < approach_capacity*capacity) return
      s_ref = (history_at(0.15_dp*h) - history_at(0.05_dp*h))/(0.1_dp*h)
      s_now = (force(n) - history_at(d - approach_window*h))/(approach_window*h)
      yes = s_ref <= 0.0_dp .or. s_now <= approach_slope_ratio*s_ref
   contains
      !> the force at pull x, linear between the samples around it
      pure function history_at(x) result(f)
         real(dp), intent(in) :: x
         real(dp) :: f
         integer :: i
         i = 2
         do while (i < n .and. delta(i) < x)
            i = i + 1
         end do
         f = force(i - 1) + (force(i) - force(i - 1))*(x - delta(i - 1))/max(delta(i) - delta(i - 1), tiny(1.0_dp))
      end function history_at
   end function maximum_approaching
end module tearing
