!> load_maximum -- the program's tearing criterion on the history of the
!> restraining force (of the tension while the bead closes): the largest
!> force held as the candidate, confirmed as a neck once the force has
!> fallen and stayed down, the strain concentrated and, in the pull, the
!> pull taken as stretch; the tearing point the vertex of the parabola
!> fitted to the top of the force; and the turn of the force toward such a
!> maximum that triggers the split at the exit (docs/theory.md §7.4,
!> §7.6).  Pure functions of the histories; module tearing reads them off
!> the model and records the result.
module load_maximum
   use kinds, only: dp
   implicit none
   private
   public :: track_load_maximum, neck_confirmed, load_at_maximum, parabola_vertex, fall_duration, &
             first_near_max, stretched_share, maximum_approaching
   public :: tear_force_drop, lock_force_drop, neck_strain_rate, tear_confirm_pull, neck_stretch_fraction, &
             approach_slope_ratio, approach_capacity

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
   !> both male corners alike), the program's by 1.5-3.0% on 80-640
   !> elements with no station localizing as a neck does; where the
   !> continuum necks while locking the tension falls 9-18% by full lock.
   !> A maximum of the tension is a neck once it has fallen
   !> lock_force_drop below it and a station localizes (docs/theory.md §7.4)
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
   !> approach_capacity of the sheet's plane-strain load capacity
   !> N* = tau* h exp(-eps*) (docs/theory.md §7.6): every neck of the
   !> validation peaks at 0.89-0.96 N*, whatever the material; the free
   !> edges that draw steadily flatten at 0.46-0.69 N*
   real(dp), parameter :: approach_slope_ratio = 0.5_dp, approach_window = 0.1_dp, &
                          approach_capacity = 0.75_dp

contains

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

   !> MAXIMUM_APPROACHING: has the restraining force turned toward a neck's
   !> maximum?  Its secant slope over the last approach_window h of pull
   !> (the history interpolated linearly) against the slope over [0.05h,
   !> 0.15h] (past the elastic start of the pull): .true. once the ratio is
   !> at most approach_slope_ratio (or the early slope is not positive) and
   !> the force is at least approach_capacity times the sheet's capacity
   !> N*: the section that carries N at the exit of the last radius
   !> then nears its maximum load (docs/theory.md §7.6); a force far below
   !> the capacity (a free edge drawing steadily) is no neck.  Needs a pull
   !> of at least 0.15h + approach_window h (else .false.).
   !>  delta, force  [in] the pull history (ascending delta), mm, N/mm
   !>  h             [in] thickness, mm
   !>  capacity      [in] the sheet's plane-strain load capacity
   !>                     N* = tau* h exp(-eps*), N/mm
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
end module load_maximum
