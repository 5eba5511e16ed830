!> tearing -- the criteria read off each converged state: the paper's
!> pointwise loss of positive definiteness of the section tangent (3.1),
!> the mesh-objective averaged-strain measure, and the fold check (a
!> station bent tighter than the shell theory allows).  Each records the
!> first time it is met in the run record.
module tearing
   use kinds, only: dp
   use errors, only: warn
   use hermite, only: n_gauss, gauss_wt
   use element, only: igp_strain, igp_curvature
   use model, only: model_type, state_type, gauss_position
   use record, only: run_record
   implicit none
   private
   public :: check_localization, check_fold, strain_limit_indicator, first_crossing

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
      integer :: fold_at(2)
      real(dp) :: rho_h, h
      character(len=200) :: msg
      if (rec%folded) return
      h = m%thickness
      fold_at = maxloc(abs(s%gpn(igp_curvature, :, :)))
      rho_h = abs(s%gpn(igp_curvature, fold_at(1), fold_at(2)))*h
      if (rho_h <= fold_curvature) return
      rec%folded = .true.
      rec%fold_phase = phase
      rec%fold_load = p
      rec%fold_s = gauss_position(m, fold_at(2), fold_at(1))
      write (msg, '(a,f6.2,a,f8.3,a,es10.3,a)') 'the sheet folds: |rho| h = ', &
         rho_h, ' at s/h = ', rec%fold_s/h, ', load/h = ', p/h, &
         ' in '//phase//': beyond the shell theory, later results depend on the mesh'
      call warn(msg, 'check_fold')
   end subroutine check_fold

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
