!> analysis -- the load schedule of a run: locking, pulling, adaptive
!> increments, localization (tearing) detection and the per-increment output.
!>
!> Phase 'lock': the lower tool rises by H (load parameter), right edge held.
!> Phase 'pull': tools held at H = lock depth, right edge pulled by delta.
!> Left edge clamped (v = w = w' = 0) or free (w = w' = 0, axial force
!> -back_tension applied).  DESIGN §1, §7, §8.
module analysis
   use kinds, only: dp, output_unit
   use deck, only: deck_type
   use hermite, only: n_gauss, gauss_wt
   use section, only: ih_sse, ih_spd
   use contact, only: penalty_energy
   use band, only: band_matrix, band_init
   use mesh, only: half_band
   use model, only: model_type, state_type, load_type, load_init, gauss_position
   use solver, only: newton_result, newton_solve, commit_state, newton_ok, newton_cutback, &
                     newton_singular
   use output, only: output_files, write_row, write_strains, write_snapshot
   use errors, only: warn
   use tools, only: tool_level
   implicit none
   private
   public :: run_record, run_phase, phase_load, run_record_init, energy_totals, strain_limit_indicator

   !> What the run has found so far (written to summary.txt).
   type :: run_record
      logical :: localized = .false.
      character(len=8) :: loc_phase = ''
      real(dp) :: load_cr = 0.0_dp, s_star = 0.0_dp
      ! the mesh-objective criterion (strain averaged over tearing_length)
      logical :: nl_localized = .false.
      character(len=8) :: nl_phase = ''
      real(dp) :: nl_load_cr = 0.0_dp, nl_s_star = 0.0_dp
      real(dp) :: peak_force = 0.0_dp, lock_force = 0.0_dp
      real(dp) :: last_lift = 0.0_dp
      integer :: increments = 0, newton_iterations = 0, cutbacks = 0
      integer :: status = 0                       ! 0 ok, 2 no convergence
      character(len=200) :: message = ''
      real(dp), allocatable :: pull_delta(:), pull_force(:)
      integer :: n_pull = 0
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
      real(dp) :: energy_pull_start(4) = 0.0_dp
   end type run_record

contains

   !> RUN_RECORD_INIT: empty record with room for the pull history.
   subroutine run_record_init(rec)
      type(run_record), intent(out) :: rec
      allocate (rec%pull_delta(1024), rec%pull_force(1024))
   end subroutine run_record_init

   !> PHASE_LOAD: boundary conditions and loads of a phase at load parameter p.
   !>  m      [in]  model
   !>  d      [in]  deck (edges, back tension, lock depth)
   !>  phase  [in]  'lock' (p = H) or 'pull' (p = delta)
   !>  p      [in]  load parameter, mm
   !>  ld     [out] the load
   subroutine phase_load(m, d, phase, p, ld)
      type(model_type), intent(in) :: m
      type(deck_type), intent(in) :: d
      character(len=*), intent(in) :: phase
      real(dp), intent(in) :: p
      type(load_type), intent(out) :: ld
      integer :: nr
      call load_init(m, ld)
      nr = m%n_dof - 4
      ! left edge: (v, v', w, w') = dofs 1..4
      ld%fixed([3, 4]) = .true.
      if (d%left_edge == 'clamped') then
         ld%fixed(1) = .true.
      else
         ld%f_ext(1) = -d%back_tension
      end if
      ! right edge: v, w, w'
      ld%fixed(nr + [1, 3, 4]) = .true.
      if (phase == 'pull') then
         ld%u_fixed(nr + 1) = p
         ld%tool_shift = d%lock_depth
      else
         ld%tool_shift = p
      end if
      ! the edges sit on the binder: at y = 0 unless the lower tool's face
      ! under an edge has risen above it (a lock step), never above the upper
      if (m%has_tools) then
         ld%u_fixed(3) = edge_height(m, m%x(1), ld%tool_shift)
         ld%u_fixed(nr + 3) = edge_height(m, m%x(m%n_nodes), ld%tool_shift)
      end if
   end subroutine phase_load

   !> EDGE_HEIGHT: where a sheet edge is held: on the lower tool's face if it
   !> has risen above y = 0 (the level of the flat sheet), else at y = 0,
   !> and never above the upper tool's face (DESIGN §1: v, w, w' held; for the
   !> paper's beads both faces meet at y = 0 at full lock, so w = 0).
   !>  m      [in]  model with tools
   !>  x      [in]  reference abscissa of the edge
   !>  shift  [in]  the lower tool's rise H
   pure function edge_height(m, x, shift) result(w)
      type(model_type), intent(in) :: m
      real(dp), intent(in) :: x, shift
      real(dp) :: w
      w = min(max(tool_level(m%tool(2), x) + shift, 0.0_dp), tool_level(m%tool(1), x))
   end function edge_height

   !> RUN_PHASE: advance the load parameter from p0 to p1 with adaptive
   !> increments; commit, check localization and write a row per increment.
   !>  m     [in]  model
   !>  d     [in]  deck (increments, tolerances, stop_at_localization)
   !>  s     [in,out] state, converged at p0 on entry
   !>  phase [in]  'lock' or 'pull'
   !>  p0,p1 [in]  start and end of the load parameter
   !>  out   [in,out] open output files (snapshots.dat counts its blocks)
   !>  rec   [in,out] run record
   subroutine run_phase(m, d, s, phase, p0, p1, out, rec)
      type(model_type), intent(in) :: m
      type(deck_type), intent(in) :: d
      type(state_type), intent(inout) :: s
      character(len=*), intent(in) :: phase
      real(dp), intent(in) :: p0, p1
      type(output_files), intent(inout) :: out
      type(run_record), intent(inout) :: rec
      type(band_matrix) :: kb
      real(dp) :: nl_old(n_gauss*m%n_el), nl_new(n_gauss*m%n_el)
      type(load_type) :: ld
      type(newton_result) :: nr
      real(dp) :: p, dt, dt_prev, h, eh, r(m%n_dof), u_prev(m%n_dof), ind_old(n_gauss, m%n_el)
      real(dp) :: reaction, punch, lift, pen, frac, min_ind, force, force_change, target, jump, rho_h
      real(dp) :: next_snapshot
      integer :: k_cr, fold_at(2)
      logical :: have_prev, steep
      character(len=16) :: tag
      character(len=200) :: msg
      h = m%thickness
      eh = m%youngs*h
      call band_init(kb, m%n_dof, half_band, half_band)
      p = p0
      dt = d%initial_increment
      ! the force doing work on the load parameter: F while locking (starts
      ! at 0 on the flat sheet), N while pulling (the reaction reached so far)
      rec%last_conjugate = 0.0_dp
      if (phase == 'pull' .and. allocated(rec%reactions)) rec%last_conjugate = rec%reactions(m%n_dof - 3)
      nl_old = strain_limit_indicator(m, s%gpn(1, :, :), d%tearing_length*h)
      if (phase == 'pull') then
         rec%work_pull_start = rec%work
         call energy_totals(m, s, rec%energy_pull_start)
      end if
      dt_prev = dt
      have_prev = .false.
      next_snapshot = p0 + d%snapshot_every*h
      do while (p < p1 - 1.0e-12_dp*h)
         dt = min(dt, p1 - p)
         call phase_load(m, d, phase, p + dt, ld)
         if (have_prev .and. d%predictor) then
            s%u1 = s%u + (dt/dt_prev)*(s%u - u_prev)
         else
            s%u1 = s%u
         end if
         call newton_solve(m, s, ld, kb, r, d%max_iterations, d%tolerance, nr, &
                           count_states=d%log_residuals)
         rec%newton_iterations = rec%newton_iterations + nr%iterations
         if (nr%status /= newton_ok) then
            rec%cutbacks = rec%cutbacks + 1
            select case (nr%status)
            case (newton_cutback)
               write (tag, '(a,f5.2)') 'pnewdt ', nr%pnewdt
            case (newton_singular)
               tag = 'singular'
            case default
               tag = 'diverged'
            end select
            write (output_unit, '(a5,1x,a,es10.3,a,i3,a,es9.2,2a)') phase, 'cutback  d/h=', dt/h, &
               '  it', nr%iterations, '  res', nr%residual(max(nr%iterations - 1, 0)), '  ', trim(tag)
            dt = 0.25_dp*dt
            s%u1 = s%u
            if (dt < d%min_increment) then
               write (rec%message, '(3a,es10.3,a)') 'no convergence in ', phase, &
                  ' at load/h = ', p/h, ': increment below min_increment'
               ! past the paper's tearing point the sheet may have no nearby
               ! equilibrium: that ends the run normally (the neck has formed)
               if (rec%localized .and. d%stop_at_localization) return
               rec%status = 2
               return
            end if
            cycle
         end if
         ! forces: N = internal force at the pulled dof, F = lower tool upward
         ! force on the sheet, lift = upward force of the sheet on the upper tool
         reaction = r(m%n_dof - 3)
         punch = s%tool_force(2, 2)
         lift = -s%tool_force(2, 1)
         ! relative change of the phase's force in this increment (scale
         ! floored at 1e-5 E h): a jump of more than half from an established
         ! force (> 1e-4 E h, so not the first elastic ramp) is not resolved
         ! (the closing binder's final squeeze): redo the increment smaller
         force = merge(punch, reaction, phase == 'lock')
         force_change = abs(force - rec%last_conjugate)/ &
                        max(abs(rec%last_conjugate), abs(force), 1.0e-5_dp*eh)
         ! While locking, F rising faster than H^5 (its relative change above
         ! 5 times that of H) is the binder squeeze: path dependent, mostly
         ! through friction, whose history is first order in the increment
         ! (the sheet slides over the tools while the faces flatten it; the
         ! numbers are at the step control below), so it is entered with
         ! squeeze_force_change per increment, and a rise of more than 5
         ! times that is redone like a jump.
         steep = phase == 'lock' .and. force_change > 5.0_dp*dt/(p + dt)
         target = merge(d%squeeze_force_change, d%max_force_change, steep)
         jump = merge(min(0.5_dp, 5.0_dp*target), 0.5_dp, steep)
         if (force_change > jump .and. abs(rec%last_conjugate) > 1.0e-4_dp*eh .and. &
             dt > 4.0_dp*d%min_increment) then
            rec%cutbacks = rec%cutbacks + 1
            write (output_unit, '(a5,1x,a,es10.3,a,f6.2)') phase, 'cutback  d/h=', dt/h, &
               '  force jump', force_change
            dt = 0.25_dp*dt
            s%u1 = s%u
            cycle
         end if
         ind_old = s%indicator
         u_prev = s%u
         dt_prev = dt
         call commit_state(m, s, ld%tool_shift)
         p = p + dt
         rec%increments = rec%increments + 1
         pen = 0.0_dp
         if (m%has_tools) pen = max(0.0_dp, maxval(s%cn(8, :, :, :)))/h
         ! penetrations above 0.05h mean the penalty is too soft for the
         ! forces at hand (DESIGN §5): warn once per run
         if (pen > 0.05_dp .and. rec%max_penetration <= 0.05_dp) then
            write (msg, '(a,es9.3,a,es10.3,a)') 'penetration ', pen, 'h > 0.05h at load/h = ', &
               p/h, ' in '//phase//': raise &tools penalty'
            call warn(msg)
         end if
         rec%max_penetration = max(rec%max_penetration, pen)
         ! a Gauss station bent to a radius below fold_curvature thicknesses
         ! (|rho| h > fold_curvature, default 1) has folded: the shell theory
         ! assumes h/R << 1, the paper's beads bend the sheet to h/R <= 0.36,
         ! and such folds are hinges one or two elements wide whose forces
         ! depend on the mesh (README, Known differences): warn once per run
         if (.not. rec%folded) then
            fold_at = maxloc(abs(s%gpn(2, :, :)))
            rho_h = abs(s%gpn(2, fold_at(1), fold_at(2)))*h
            if (rho_h > d%fold_curvature) then
               rec%folded = .true.
               rec%fold_phase = phase
               rec%fold_load = p
               rec%fold_s = gauss_position(m, fold_at(2), fold_at(1))
               write (msg, '(a,f6.2,a,f8.3,a,es10.3,a)') 'the sheet folds: |rho| h = ', &
                  rho_h, ' at s/h = ', rec%fold_s/h, ', load/h = ', p/h, &
                  ' in '//phase//': beyond the shell theory, later results depend on the mesh'
               call warn(msg)
            end if
         end if
         min_ind = minval(s%indicator)
         ! localization (3.1): the first Gauss station whose indicator crosses
         ! zero, interpolated linearly inside the increment (the paper's
         ! pointwise criterion) ...
         if (.not. rec%localized) then
            call first_crossing(reshape(ind_old, [size(ind_old)]), &
                                reshape(s%indicator, [size(ind_old)]), frac, k_cr)
            if (k_cr > 0) then
               rec%localized = .true.
               rec%loc_phase = phase
               rec%load_cr = p - dt + frac*dt
               rec%s_star = gauss_position(m, (k_cr - 1)/n_gauss + 1, mod(k_cr - 1, n_gauss) + 1)
               call write_strains(out%dir//'/strain_localization.dat', m, s, &
                                  'at the increment where the paper''s criterion was met')
            end if
         end if
         ! ... and the mesh-objective one: the mid-surface strain averaged
         ! over tearing_length*h reaches the plane-strain maximum-load strain
         nl_new = strain_limit_indicator(m, s%gpn(1, :, :), d%tearing_length*h)
         if (.not. rec%nl_localized) then
            call first_crossing(nl_old, nl_new, frac, k_cr)
            if (k_cr > 0) then
               rec%nl_localized = .true.
               rec%nl_phase = phase
               rec%nl_load_cr = p - dt + frac*dt
               rec%nl_s_star = gauss_position(m, (k_cr - 1)/n_gauss + 1, mod(k_cr - 1, n_gauss) + 1)
            end if
         end if
         nl_old = nl_new
         ! external work, trapezoidal in each increment: the reactions on the
         ! prescribed motions (the pull N d(delta), an edge following the
         ! binder), the rising lower tool (F dH) and the dead loads
         if (.not. allocated(rec%reactions)) then
            allocate (rec%reactions(m%n_dof))
            rec%reactions = 0.0_dp
         end if
         rec%work = rec%work + 0.5_dp*dot_product(merge(rec%reactions + r, 0.0_dp, ld%fixed), &
                                                  s%u - u_prev) &
                    + dot_product(ld%f_ext, s%u - u_prev)
         if (phase == 'lock') rec%work = rec%work + 0.5_dp*dt*(rec%last_conjugate + punch)
         rec%reactions = r
         rec%last_conjugate = force
         if (phase == 'lock') then
            rec%lock_force = punch
            call write_row(out%lock, [p/h, punch/eh, punch, real(nr%iterations, dp), dt/h, &
                                      min_ind, pen, reaction/eh, reaction])
         else
            rec%peak_force = max(rec%peak_force, reaction)
            rec%last_lift = lift
            call record_pull(rec, p, reaction)
            call write_row(out%pull, [p/h, reaction/eh, reaction, real(nr%iterations, dp), &
                                      dt/h, min_ind, lift/eh, lift, pen, punch/eh])
         end if
         ! LOCALIZED once the paper's criterion has been met, NONLOCAL once the
         ! mesh-objective one has
         write (output_unit, '(a5,i6,a,es11.4,a,es9.2,a,i3,a,es9.2,a,es10.3,a,es11.4,2a)') &
            phase, rec%increments, '  load/h=', p/h, '  d/h=', dt/h, '  it', nr%iterations, &
            '  res', nr%residual(nr%iterations), '  loc', min_ind, '  force/Eh=', &
            force/eh, merge(' LOCALIZED', '          ', rec%localized), &
            merge(' NONLOCAL', '         ', rec%nl_localized)
         if (d%log_residuals) then
            write (output_unit, '(a,*(es9.2))') '      residuals:', nr%residual(0:nr%iterations)
            write (output_unit, '(a,*(i9))') '      plastic:  ', nr%plastic(0:nr%iterations)
            write (output_unit, '(a,*(i9))') '      switched: ', nr%switched(0:nr%iterations)
         end if
         ! a strain snapshot at the first converged state at or past each
         ! multiple of snapshot_every h (one per increment however many it passed)
         if (d%snapshot_every > 0.0_dp .and. p >= next_snapshot - 1.0e-9_dp*h) then
            call write_snapshot(out, m, s, phase, p/h, rec%increments)
            ! (the same slack of 1e-9 h as the test above: a state just short
            ! of a multiple counts as past it, and the next one is then due)
            next_snapshot = p0 + (aint((p - p0 + 1.0e-9_dp*h)/(d%snapshot_every*h)) + 1.0_dp)* &
                            d%snapshot_every*h
         end if
         ! stop once both tearing criteria have been met
         if (rec%localized .and. rec%nl_localized .and. d%stop_at_localization) return
         ! grow after easy convergence, shrink after a hard one; and resolve
         ! fast changes of the force (the closing binder's final squeeze, the
         ! first slip over a radius): about target per increment.  On the
         ! Fig. 9c deck the punch force at full lock is 2.4% below that of a
         ! 0.5% target at 10% per increment in the squeeze, 0.2% at 3%, 0.07%
         ! at 2% and 0.04% at 1% (1.4 times the locking increments of 2%);
         ! at 10% it is only 0.1% below with mu = 0.
         if (force_change > target .and. abs(rec%last_conjugate) > 1.0e-4_dp*eh) then
            dt = max(max(0.25_dp, target/force_change)*dt, d%min_increment)
         else if (nr%iterations <= 3) then
            dt = min(2.0_dp*dt, d%max_increment)
         else if (nr%iterations <= 5) then
            dt = min(1.25_dp*dt, d%max_increment)
         else if (nr%iterations >= 8) then
            dt = max(0.6_dp*dt, d%min_increment)
         end if
         have_prev = .true.
      end do
   end subroutine run_phase

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
      real(dp) :: g(size(eps))
      real(dp) :: xs(size(eps)), pw(0:size(eps)), pg(0:size(eps)), wt
      integer :: e, ig, k, lo, hi, n
      n = size(eps)
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

   !> ENERGY_TOTALS: stored and dissipated energies of the converged state per
   !> unit width (N mm/mm): elastic, plastic (the material's sse and spd
   !> integrated over the sheet), penalty (k d^2/2 over the contact stations)
   !> and friction dissipation.
   !>  m, s    [in]  model and converged state
   !>  energy  [out] (elastic, plastic, penalty, friction)
   pure subroutine energy_totals(m, s, energy)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      real(dp), intent(out) :: energy(4)
      real(dp) :: dv
      integer :: e, ig, it
      energy = 0.0_dp
      do e = 1, m%n_el
         do ig = 1, n_gauss
            dv = gauss_wt(ig)*(m%x(e + 1) - m%x(e))
            energy(1) = energy(1) + dv*dot_product(m%wz, s%hn(:, ih_sse, ig, e))
            energy(2) = energy(2) + dv*dot_product(m%wz, s%hn(:, ih_spd, ig, e))
            if (m%has_tools) then
               do it = 1, 2
                  energy(3) = energy(3) + dv*penalty_energy(m%penalty, m%contact_smoothing, &
                                                           s%cn(8, ig, e, it))
                  energy(4) = energy(4) + dv*s%cn(7, ig, e, it)
               end do
            end if
         end do
      end do
   end subroutine energy_totals

   !> RECORD_PULL: append (delta, N) to the pull history, growing it as needed.
   subroutine record_pull(rec, delta, force)
      type(run_record), intent(inout) :: rec
      real(dp), intent(in) :: delta, force
      real(dp), allocatable :: tmp(:)
      if (rec%n_pull == size(rec%pull_delta)) then
         allocate (tmp(2*rec%n_pull))
         tmp(1:rec%n_pull) = rec%pull_delta
         call move_alloc(tmp, rec%pull_delta)
         allocate (tmp(2*rec%n_pull))
         tmp(1:rec%n_pull) = rec%pull_force
         call move_alloc(tmp, rec%pull_force)
      end if
      rec%n_pull = rec%n_pull + 1
      rec%pull_delta(rec%n_pull) = delta
      rec%pull_force(rec%n_pull) = force
   end subroutine record_pull
end module analysis
