!> material_law -- what the section asks of a material law, as an abstract
!> type: each law (law_j2, law_combined, law_umat) is one module extending
!> it, owning its constants, its state variables and its checks
!> (docs/theory.md §4, §13).
!>
!> Purpose
!>   The section (module section) integrates npt material points through
!>   the thickness.  Per point it keeps the Kirchhoff stress (tau11, tau33),
!>   the elastic energy and plastic work densities and the law's n_state
!>   state variables, and it reads three of them by name: the equivalent
!>   plastic strain (isv_eqps, 0 when the law has none: the outputs then
!>   say so), the total thickness log strain (isv_eps22: the current
!>   thickness) and the continuum tangent d tau11 / d eps11 at fixed
!>   width strain with the thickness stress held (isv_tangent: the
!>   localization indicator (3.1) and the maximum-load strain).  The law
!>   declares n_state and these places when it is built (as FEAP's elements
!>   declare their history, CalculiX's materials their *DEPVAR); the model
!>   sizes the section history from them.
!>
!> The update
!>   update advances a block of n points by one increment: the axial log
!>   strain increment is given, the width strain is held (plane strain) and
!>   the thickness stress tau22 is prescribed (0: the paper's plane-stress
!>   section; a contact pressure: docs/theory.md §12).  It returns the end
!>   stress and state, the consistent tangent d tau11 / d eps11 in
!>   ddsdde(:, 1, 1) (the other entries are the law's to fill or not) and,
!>   with a prescribed tau22, d tau11 / d tau22 at fixed strain.  A law asks
!>   for a smaller increment with pnewdt < 1; the outputs are then not to
!>   be used.
!>
!> A start for the return
!>   Within one increment the global Newton iterations call the update
!>   again and again from the same converged state with strains that
!>   change less and less.  A law whose return mapping iterates on the
!>   equivalent plastic strain increment says so (starts_from_trial); the
!>   section then hands it the increment its last trial reached at each
!>   point (dp_start), where the return may start.  It is a start only: the
!>   root, and with it the stress, the strains and the state, is the same
!>   from any start to the return's tolerance; values a law caches from
!>   its last iterate rather than the root (law_combined's H' and the
!>   continuum tangent built on it) move with the start within about 1e-6.
module material_law
   use kinds, only: dp
   implicit none
   private
   public :: material_law_type, max_load_strain, plane_strain_path, path_step

   !> the increment of the axial log strain along plane_strain_path
   real(dp), parameter :: path_step = 1.0e-4_dp

   !> A material law: the section's view of it (module header).
   type, abstract :: material_law_type
      !> Young's modulus and Poisson's ratio: the elastic scales (section
      !> forces, residual norm, the localization indicator)
      real(dp) :: youngs = 0.0_dp
      real(dp) :: poisson = 0.0_dp
      !> number of state variables per point
      integer :: n_state = 0
      !> places of what the program reads in the state variables (module
      !> header); isv_eqps = 0: the law has no equivalent plastic strain
      integer :: isv_eqps = 0
      integer :: isv_eps22 = 0
      integer :: isv_tangent = 0
      !> the law's name, as the deck gives it (&material model)
      character(len=16) :: name = ''
      !> .false.: the law must not be called from several threads at once
      !> (a user's UMAT, which may keep data of its own); the assembly then
      !> runs on one thread
      logical :: thread_safe = .true.
      !> .true.: update takes dp_start as the start of its return mapping
      !> (module header); the section then reads its last trial history
      logical :: starts_from_trial = .false.
   contains
      procedure(update_interface), deferred :: update
      procedure :: update_to => law_update_to
      procedure :: state_mapped => law_state_mapped
      procedure :: stored_energy => law_stored_energy
      procedure :: stores_energy => law_stores_energy
   end type material_law_type

   abstract interface
      !> UPDATE: the end state of n points after one increment (module
      !> header).
      !>  law     [in]     the law
      !>  n       [in]     number of points
      !>  stress  [in,out] (n, 2) Kirchhoff stress (tau11, tau33), start -> end
      !>  statev  [in,out] (n, law%n_state) state variables, start -> end
      !>  ddsdde  [out]    (n, 2, 2) consistent tangent; (:, 1, 1) is
      !>                   d tau11 / d eps11 with the width strain and tau22 held
      !>  sse     [in,out] (n) elastic energy density
      !>  spd     [in,out] (n) plastic work density (accumulated)
      !>  stran11 [in]     (n) axial log strain at the start of the increment
      !>  dstran  [in]     (n, 2) log strain increment (axial, width = 0)
      !>  zbar    [in]     (n) current distance of each point from the
      !>                   mid-surface
      !>  pnewdt  [in,out] set < 1 to ask for a smaller increment
      !>  s22n, s22 [in]   optional: the prescribed tau22 at the start and the
      !>                   end of the increment; absent: tau22 = 0
      !>  dsig_ds22 [out]  optional, with s22: d tau11 / d tau22 at fixed strain
      !>  dp_start  [in]   optional: (n) the equivalent plastic strain
      !>                   increment of each point's last trial in this
      !>                   increment, >= 0 (0: none), where a law with
      !>                   starts_from_trial may start its return (module header)
      subroutine update_interface(law, n, stress, statev, ddsdde, sse, spd, stran11, dstran, &
                                  zbar, pnewdt, s22n, s22, dsig_ds22, dp_start)
         import :: material_law_type, dp
         class(material_law_type), intent(in) :: law
         integer, intent(in) :: n
         real(dp), intent(inout) :: stress(n, 2), statev(n, law%n_state), sse(n), spd(n)
         real(dp), intent(out) :: ddsdde(n, 2, 2)
         real(dp), intent(in) :: stran11(n), dstran(n, 2), zbar(n)
         real(dp), intent(inout) :: pnewdt
         real(dp), intent(in), optional :: s22n(n), s22(n)
         real(dp), intent(out), optional :: dsig_ds22(n)
         real(dp), intent(in), optional :: dp_start(n)
      end subroutine update_interface
   end interface

contains

   !> LAW_UPDATE_TO: the plane-stress update (tau22 = 0) from a start state
   !> into distinct end arrays (the section's converged and trial
   !> histories, without a copy of the one into the other first).  This
   !> default copies and calls update; a law with an out-of-place update
   !> (law_j2) overrides it.  On failure (pnewdt < 1) the end arrays hold
   !> whatever the law left; the caller restores them.
   !>  law                      [in]  the law
   !>  n                        [in]  number of points
   !>  stress_n, statev_n, sse_n, spd_n [in] the start state
   !>  stress, statev, sse, spd [out] the end state
   !>  ddsdde                   [out] (n, 2, 2) consistent tangent
   !>  stran11, dstran, zbar    [in]  as update
   !>  pnewdt                   [in,out] as update
   !>  dp_start                 [in]  optional, as update
   subroutine law_update_to(law, n, stress_n, statev_n, sse_n, spd_n, stress, statev, sse, spd, &
                            ddsdde, stran11, dstran, zbar, pnewdt, dp_start)
      class(material_law_type), intent(in) :: law
      integer, intent(in) :: n
      real(dp), intent(in) :: stress_n(n, 2), statev_n(n, law%n_state), sse_n(n), spd_n(n)
      real(dp), intent(out) :: stress(n, 2), statev(n, law%n_state), sse(n), spd(n)
      real(dp), intent(out) :: ddsdde(n, 2, 2)
      real(dp), intent(in) :: stran11(n), dstran(n, 2), zbar(n)
      real(dp), intent(inout) :: pnewdt
      real(dp), intent(in), optional :: dp_start(n)
      stress = stress_n
      statev = statev_n
      sse = sse_n
      spd = spd_n
      call law%update(n, stress, statev, ddsdde, sse, spd, stran11, dstran, zbar, pnewdt, &
                      dp_start=dp_start)
   end subroutine law_update_to

   !> LAW_STATE_MAPPED: state variables interpolated between material
   !> points (remesh, docs/theory.md §7.6) made consistent for the next
   !> update.  This default keeps them as mapped; a law with cached values
   !> that belong to the old points (law_j2's flow stress) overrides it.
   !>  law     [in]     the law
   !>  statev  [in,out] (npt, n_state) the mapped state variables of a section
   pure subroutine law_state_mapped(law, statev)
      class(material_law_type), intent(in) :: law
      real(dp), intent(inout) :: statev(:, :)
      associate (unused => law, unused2 => statev)
      end associate
   end subroutine law_state_mapped

   !> LAW_STORED_ENERGY: the energy density a point's state stores besides
   !> the elastic one (the back stresses of kinematic hardening, docs/theory.md
   !> §10): part of the plastic work spd that is not dissipated.  This
   !> default: none.
   !>  law     [in]  the law
   !>  statev  [in]  (n_state) the state variables of one point
   pure function law_stored_energy(law, statev) result(w)
      class(material_law_type), intent(in) :: law
      real(dp), intent(in) :: statev(:)
      real(dp) :: w
      associate (unused => law, unused2 => statev)
      end associate
      w = 0.0_dp
   end function law_stored_energy

   !> LAW_STORES_ENERGY: .true. when the law's state can store energy
   !> (stored_energy not identically 0): summary.txt then reports it.  This
   !> default: .false.
   !>  law  [in]  the law
   pure logical function law_stores_energy(law)
      class(material_law_type), intent(in) :: law
      associate (unused => law)
      end associate
      law_stores_energy = .false.
   end function law_stores_energy

   !> PLANE_STRAIN_PATH: the law driven along plane-strain uniaxial tension
   !> (width strain held, tau22 = 0) from the undeformed state in increments
   !> of path_step of the axial log strain: the path of the maximum load
   !> (max_load_strain) and of the strain-gradient coefficient's curve
   !> (module neck_gradient).
   !>  law      [in]  the law
   !>  n_max    [in]  the increments to drive at most
   !>  eps      [out] (n_max) the log strain at the end of increment i
   !>  tau      [out] (n_max) the axial Kirchhoff stress there
   !>  tangent  [out] (n_max) the continuum tangent d tau/d eps there
   !>                 (statev(isv_tangent))
   !>  n        [out] the increments done: n_max, or fewer where the law
   !>                 asked for a smaller increment (or, with until_max_load,
   !>                 where the maximum load was passed)
   !>  until_max_load [in] optional: .true. stops after the first increment
   !>                 whose tangent is at most its stress (the maximum load
   !>                 passed: all max_load_strain reads)
   subroutine plane_strain_path(law, n_max, eps, tau, tangent, n, until_max_load)
      class(material_law_type), intent(in) :: law
      integer, intent(in) :: n_max
      real(dp), intent(out) :: eps(n_max), tau(n_max), tangent(n_max)
      integer, intent(out) :: n
      logical, intent(in), optional :: until_max_load
      logical :: stop_at_max
      real(dp) :: stress(1, 2), statev(1, law%n_state), ddsdde(1, 2, 2), sse(1), spd(1), pnewdt, e
      integer :: i
      stop_at_max = .false.
      if (present(until_max_load)) stop_at_max = until_max_load
      stress = 0.0_dp
      statev = 0.0_dp
      sse = 0.0_dp
      spd = 0.0_dp
      e = 0.0_dp
      n = 0
      do i = 1, n_max
         pnewdt = 1.0_dp
         call law%update(1, stress, statev, ddsdde, sse, spd, [e], &
                         reshape([path_step, 0.0_dp], [1, 2]), [0.0_dp], pnewdt)
         if (pnewdt < 1.0_dp) return
         e = e + path_step
         n = i
         eps(i) = e
         tau(i) = stress(1, 1)
         tangent(i) = statev(1, law%isv_tangent)
         if (stop_at_max .and. tangent(i) - tau(i) <= 0.0_dp) return
      end do
   end subroutine plane_strain_path

   !> MAX_LOAD_STRAIN: the axial log strain at maximum load in plane-strain
   !> uniaxial tension (width strain held, tau22 = 0), where the continuum
   !> tangent statev(isv_tangent) falls to the stress, d tau/d eps = tau
   !> (docs/theory.md §7): the sheet's forming limit in plane strain (FLD0).
   !> Found by driving the law along the path (plane_strain_path) and
   !> interpolating the crossing.
   !>  law     [in]  the law
   !>  tau_max [out] optional: the axial Kirchhoff stress at that strain (at
   !>                the last strain driven when the maximum is not reached)
   !>  eps_max (result) the strain; huge() if not reached by a log strain
   !>                of 3 or if the law asks for a smaller increment
   function max_load_strain(law, tau_max) result(eps_max)
      class(material_law_type), intent(in) :: law
      real(dp), intent(out), optional :: tau_max
      real(dp) :: eps_max
      integer, parameter :: n_max = 30000
      real(dp), allocatable :: eps(:), tau(:), tangent(:)
      real(dp) :: g, g_old
      integer :: i, n
      allocate (eps(n_max), tau(n_max), tangent(n_max))
      ! (driven only up to the crossing: the path beyond it was 90% of the
      ! drive, and the set-up's largest cost with the combined law)
      call plane_strain_path(law, n_max, eps, tau, tangent, n, until_max_load=.true.)
      eps_max = huge(1.0_dp)
      if (present(tau_max)) tau_max = 0.0_dp
      g_old = 1.0_dp
      do i = 1, n
         if (present(tau_max)) tau_max = tau(i)
         g = tangent(i) - tau(i)
         if (g <= 0.0_dp) then
            eps_max = eps(i) - path_step*g/(g - g_old)
            return
         end if
         g_old = g
      end do
   end function max_load_strain
end module material_law
