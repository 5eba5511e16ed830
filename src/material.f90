!> material -- the material of the sheet behind one type and one call: the
!> built-in J2/Hill law (material_j2) or a user's UMAT.
!>
!> Purpose
!>   A material_type holds which routine computes the stress (kind) and
!>   its constants (props), and the Young's modulus the program uses as a
!>   scale.  material_update gives the stress update of a block of
!>   through-thickness stations: the built-in law runs its vectorized block
!>   routine (umat_block); a user's material runs the external subroutine
!>   umat, one station at a time, with the full Abaqus argument list.
!>
!> A user's UMAT
!>   An external (non-module) `subroutine umat(...)` with the argument list
!>   of the interface below (Abaqus order, as in CalculiX umat.f), built in
!>   with `make UMAT=path/to/my_umat.f90`; the example is
!>   input/umat_linear_hardening.f90.  Without UMAT= the program links
!>   src/user/umat_none.f90, whose umat is an error path, and
!>   user_umat_linked() tells which of the two a binary holds.
!>   Conventions: NDI = 2, NSHR = 0, NTENS = 2; stress and strain
!>   components (11, 33) = (axial, width); 22 is the thickness direction,
!>   sigma22 = 0.  Kirchhoff stress, logarithmic strain.
!>   What the program passes (material_update), argument by argument:
!>     stress(2)     [in,out] (tau11, tau33) at the start of the increment;
!>                            the routine returns the end values.
!>     statev(nstatv)[in,out] the station's state variables, NSTATV =
!>                            n_statev of material_j2 (6), all 0 in the
!>                            virgin state.  The program reads three of
!>                            them, which a user's routine must keep up to
!>                            date with the meaning they have in
!>                            material_j2: statev(isv_eps22) the total
!>                            thickness log strain (for the current
!>                            thickness), statev(isv_tangent) the continuum
!>                            tangent d sigma11 / d eps11 at fixed eps33
!>                            (for the localization indicator and the
!>                            maximum-load strain), and statev(isv_eqps)
!>                            the equivalent plastic strain (output only:
!>                            plastic-point counts, the largest ebar_p).
!>                            The others are the routine's own.
!>     ddsdde(2,2)   [out]    consistent tangent d stress / d dstran; the
!>                            program uses ddsdde(1,1).
!>     sse, spd      [in,out] elastic energy and plastic dissipation
!>                            densities of the station (kept for output).
!>     scd           [in,out] 0 on entry; not kept.
!>     rpl, ddsddt, drplde, drpldt [out] not used by the program.
!>     stran(2)      [in]     (eps11, eps33) log strain at the start of the
!>                            increment; eps33 = 0 (plane strain).
!>     dstran(2)     [in]     (deps11, 0): the width strain is held.
!>     time(2)       [in]     (0, 0): the program keeps no time.
!>     dtime         [in]     1: one unit of pseudo time per increment (the
!>                            program is rate-independent).
!>     temp, dtemp   [in]     0, 0 (isothermal).
!>     predef, dpred [in]     (0), (0): no field variables.
!>     cmname        [in]     'UMAT'.
!>     ndi, nshr, ntens [in]  2, 0, 2.
!>     nstatv        [in]     n_statev.
!>     props(nprops) [in]     the user's constants, as set-up gave them.
!>     coords(3)     [in]     (0, zbar, 0): only the station's current
!>                            distance from the mid-surface is known here.
!>     drot(3,3)     [in]     identity: the components are in the fibre
!>                            frame already.
!>     pnewdt        [in,out] 1 on entry; a value < 1 on return asks for a
!>                            smaller increment (the rest of the block is
!>                            then skipped).
!>     celent        [in]     0 (not known at this level).
!>     dfgrd0, dfgrd1 [in]    identity: not provided (stran and dstran carry
!>                            the kinematics).
!>     noel, npt     [in]     0, 0 (not known at this level).
!>     layer         [in]     1.
!>     kspt          [in]     the station number through the thickness.
!>     kstep, kinc   [in]     1, 0 (one step; the increment is not known).
module material
   use kinds, only: dp
   use material_j2, only: umat_block, n_statev, ip_youngs, ip_poisson, isv_tangent, isv_eps22, &
                          isv_sigma33, isv_flow_stress
   implicit none
   private

   public :: material_type, material_builtin, material_user, builtin_material, user_material
   public :: material_update, max_load_strain, umat, user_umat_linked, material_state_mapped

   !> values of material_type%kind: the built-in J2/Hill law, a user's UMAT
   integer, parameter :: material_builtin = 1, material_user = 2

   !> The material of a run.
   type :: material_type
      !> material_builtin or material_user
      integer :: kind = material_builtin
      !> Young's modulus E: the scale of the section forces in the
      !> localization indicator, the residual norm and the output
      real(dp) :: youngs = 0.0_dp
      !> the UMAT constants (built-in: layout in material_j2)
      real(dp), allocatable :: props(:)
   end type material_type

   interface
      !> UMAT: a user's material routine (module header), or the error path
      !> of src/user/umat_none.f90 when none is linked.
      subroutine umat(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, &
                      stran, dstran, time, dtime, temp, dtemp, predef, dpred, cmname, ndi, &
                      nshr, ntens, nstatv, props, nprops, coords, drot, pnewdt, celent, dfgrd0, &
                      dfgrd1, noel, npt, layer, kspt, kstep, kinc)
         import :: dp
         character(len=80), intent(in) :: cmname
         integer, intent(in) :: ndi, nshr, ntens, nstatv, nprops, noel, npt, layer, kspt, &
                                kstep, kinc
         real(dp), intent(inout) :: stress(ntens), statev(nstatv), sse, spd, scd, pnewdt
         real(dp), intent(out) :: ddsdde(ntens, ntens), rpl, ddsddt(ntens), drplde(ntens), drpldt
         real(dp), intent(in) :: stran(ntens), dstran(ntens), time(2), dtime, temp, dtemp, &
                                 predef(1), dpred(1), props(nprops), coords(3), drot(3, 3), &
                                 celent, dfgrd0(3, 3), dfgrd1(3, 3)
      end subroutine umat

      !> USER_UMAT_LINKED: .true. when this program holds a user's umat
      !> (built with make UMAT=...), .false. when umat is the error path.
      logical function user_umat_linked()
      end function user_umat_linked
   end interface

contains

   !> BUILTIN_MATERIAL: the built-in J2/Hill law with its constants.
   !>  props  [in]  constants (layout in material_j2; check them with
   !>               material_j2's check_props); E is props(ip_youngs)
   pure function builtin_material(props) result(mat)
      real(dp), intent(in) :: props(:)
      type(material_type) :: mat
      mat%kind = material_builtin
      allocate (mat%props, source=props)
      mat%youngs = props(ip_youngs)
   end function builtin_material

   !> USER_MATERIAL: a user's UMAT with its constants.
   !>  props   [in]  the user's constants, passed to umat as they are
   !>  youngs  [in]  Young's modulus E of the material (a scale only: the
   !>                program never computes a stress with it)
   pure function user_material(props, youngs) result(mat)
      real(dp), intent(in) :: props(:), youngs
      type(material_type) :: mat
      mat%kind = material_user
      allocate (mat%props, source=props)
      mat%youngs = youngs
   end function user_material

   !> MATERIAL_UPDATE: stress update of n stations for one increment.
   !> Built-in: umat_block on the whole block.  User: umat at each station
   !> with the arguments of the module header, in order, until one asks for
   !> a smaller increment.
   !>  mat     [in]     the material
   !>  n       [in]     number of stations
   !>  stress  [in,out] (n, 2) Kirchhoff stress (tau11, tau33), start -> end
   !>  statev  [in,out] (n, n_statev) state variables
   !>  ddsdde  [out]    (n, 2, 2) consistent tangent
   !>  sse     [in,out] (n) elastic energy density
   !>  spd     [in,out] (n) plastic dissipation density
   !>  stran11 [in]     (n) axial log strain at the start of the increment (the
   !>                   width strain is held at 0); read by a user's umat only
   !>  dstran  [in]     (n, 2) log strain increment
   !>  zbar    [in]     (n) current distance of each station from the
   !>                   mid-surface (coords(2) of the user's umat)
   !>  pnewdt  [in,out] set < 1 when a station asks for a smaller increment;
   !>                   the outputs are then not to be used
   !>  s22n, s22 [in]   optional, built-in law only: a prescribed thickness
   !>                   stress tau22 at the start and at the end of the
   !>                   increment (n each; docs/theory.md §12).  Absent: tau22 = 0.
   !>  dsig_ds22 [out]  optional, with s22: d tau11 / d tau22 at fixed strain
   !>                   (consistent), the coupling of the section to the
   !>                   contact pressure
   !>
   !> A prescribed tau22 = p needs no second return mapping.  Hill's function
   !> and the plastic flow depend on stress differences only, so with
   !> s = (tau11 - p, tau33 - p) the yield condition is the plane-stress one
   !> in s, and isotropic elasticity gives
   !>   d eps11 = (ds11 - nu ds33)/E + (1 - 2 nu) dp/E + d eps11^p
   !> (likewise eps33): the update of s is the plane-stress update driven by
   !> the strain increments less (1 - 2 nu) dp/E, and
   !>   tau = s + p,  d eps22 = d eps22(plane stress, s) + (1 - 2 nu) dp/E.
   !> The plastic work s : d eps^p equals tau : d eps^p (the flow is
   !> incompressible); the elastic energy is that of the three stresses.
   subroutine material_update(mat, n, stress, statev, ddsdde, sse, spd, stran11, dstran, zbar, &
                              pnewdt, s22n, s22, dsig_ds22)
      type(material_type), intent(in) :: mat
      integer, intent(in) :: n
      real(dp), intent(inout) :: stress(n, 2), statev(n, n_statev), sse(n), spd(n)
      real(dp), intent(out) :: ddsdde(n, 2, 2)
      real(dp), intent(in) :: stran11(n), dstran(n, 2), zbar(n)
      real(dp), intent(inout) :: pnewdt
      real(dp), intent(in), optional :: s22n(n), s22(n)
      real(dp), intent(out), optional :: dsig_ds22(n)
      real(dp), parameter :: identity(3, 3) = reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, &
                                                       0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
      character(len=80), parameter :: cmname = 'UMAT'
      real(dp) :: s(2), sv(n_statev), dd(2, 2), e, p, scd, rpl, ddsddt(2), drplde(2), drpldt, de(2)
      integer :: k

      if (mat%kind == material_builtin) then
         if (present(s22)) then
            call update_with_s22(mat%props, n, stress, statev, ddsdde, sse, spd, dstran, &
                                 s22n, s22, dsig_ds22, pnewdt)
         else
            call umat_block(n, stress, statev, ddsdde, sse, spd, dstran, mat%props, &
                            size(mat%props), n_statev, pnewdt)
         end if
         return
      end if
      do k = 1, n
         s = stress(k, :)
         sv = statev(k, :)
         e = sse(k)
         p = spd(k)
         scd = 0.0_dp
         ! a row of dstran is strided: the UMAT's explicit-shape DSTRAN gets a copy
         de = dstran(k, :)
         call umat(s, sv, dd, e, p, scd, rpl, ddsddt, drplde, drpldt, [stran11(k), 0.0_dp], de, &
                   [0.0_dp, 0.0_dp], 1.0_dp, 0.0_dp, 0.0_dp, [0.0_dp], [0.0_dp], cmname, 2, 0, 2, &
                   n_statev, mat%props, size(mat%props), [0.0_dp, zbar(k), 0.0_dp], identity, &
                   pnewdt, 0.0_dp, identity, identity, 0, 0, 1, k, 1, 0)
         if (pnewdt < 1.0_dp) return
         stress(k, :) = s
         statev(k, :) = sv
         ddsdde(k, :, :) = dd
         sse(k) = e
         spd(k) = p
      end do
   end subroutine material_update

   !> UPDATE_WITH_S22: the built-in law's update with a prescribed thickness
   !> stress (material_update's header gives the reduction to plane stress).
   !>  props            [in]     the built-in law's constants
   !>  n                [in]     number of stations
   !>  stress ... spd   [in,out] as material_update
   !>  dstran           [in]     (n, 2) log strain increment
   !>  s22n, s22        [in]     (n) tau22 at the start and the end
   !>  dsig_ds22        [out]    (n) d tau11 / d tau22 = 1 - (1 - 2 nu)/E (D11 + D12)
   !>  pnewdt           [in,out] as material_update
   pure subroutine update_with_s22(props, n, stress, statev, ddsdde, sse, spd, dstran, s22n, &
                                   s22, dsig_ds22, pnewdt)
      real(dp), intent(in) :: props(:)
      integer, intent(in) :: n
      real(dp), intent(inout) :: stress(n, 2), statev(n, n_statev), sse(n), spd(n)
      real(dp), intent(out) :: ddsdde(n, 2, 2), dsig_ds22(n)
      real(dp), intent(in) :: dstran(n, 2), s22n(n), s22(n)
      real(dp), intent(inout) :: pnewdt
      real(dp) :: c, nu, e, dmod(n, 2), s11, s33, p
      integer :: k
      e = props(ip_youngs)
      nu = props(ip_poisson)
      c = (1.0_dp - 2.0_dp*nu)/e
      do k = 1, n
         stress(k, 1) = stress(k, 1) - s22n(k)
         stress(k, 2) = stress(k, 2) - s22n(k)
         dmod(k, 1) = dstran(k, 1) - c*(s22(k) - s22n(k))
         dmod(k, 2) = dstran(k, 2) - c*(s22(k) - s22n(k))
      end do
      call umat_block(n, stress, statev, ddsdde, sse, spd, dmod, props, size(props), n_statev, &
                      pnewdt)
      if (pnewdt < 1.0_dp) return
      do k = 1, n
         p = s22(k)
         s11 = stress(k, 1) + p
         s33 = stress(k, 2) + p
         stress(k, 1) = s11
         stress(k, 2) = s33
         statev(k, isv_eps22) = statev(k, isv_eps22) + c*(p - s22n(k))
         statev(k, isv_sigma33) = s33
         sse(k) = (s11**2 + p**2 + s33**2 - 2.0_dp*nu*(s11*p + p*s33 + s11*s33))/(2.0_dp*e)
         dsig_ds22(k) = 1.0_dp - c*(ddsdde(k, 1, 1) + ddsdde(k, 1, 2))
      end do
   end subroutine update_with_s22

   !> MAX_LOAD_STRAIN: the axial log strain at maximum load in plane-strain
   !> uniaxial tension (width strain held, sigma22 = 0), where the continuum
   !> tangent statev(isv_tangent) falls to the stress, d tau/d eps = tau
   !> (docs/theory.md §7): the sheet's forming limit in plane strain (FLD0).  Found
   !> by driving the material (built-in or user) along the path in
   !> increments of 1e-4 and interpolating the crossing.
   !>  mat     [in]  the material
   !>  tau_max [out] optional: the axial Kirchhoff stress at that strain (at
   !>                the last strain driven when the maximum is not reached)
   !>  eps_max (result) the strain; huge() if not reached by a log strain
   !>                of 3 or if the material asks for a smaller increment
   function max_load_strain(mat, tau_max) result(eps_max)
      type(material_type), intent(in) :: mat
      real(dp), intent(out), optional :: tau_max
      real(dp) :: eps_max
      real(dp), parameter :: step = 1.0e-4_dp
      real(dp) :: stress(1, 2), statev(1, n_statev), ddsdde(1, 2, 2), sse(1), spd(1), pnewdt
      real(dp) :: eps, g, g_old
      integer :: i
      stress = 0.0_dp
      statev = 0.0_dp
      sse = 0.0_dp
      spd = 0.0_dp
      eps = 0.0_dp
      g_old = 1.0_dp
      eps_max = huge(1.0_dp)
      if (present(tau_max)) tau_max = 0.0_dp
      do i = 1, 30000
         pnewdt = 1.0_dp
         call material_update(mat, 1, stress, statev, ddsdde, sse, spd, &
                              reshape([eps, 0.0_dp], [1, 2]), reshape([step, 0.0_dp], [1, 2]), &
                              [0.0_dp], pnewdt)
         if (pnewdt < 1.0_dp) return
         eps = eps + step
         if (present(tau_max)) tau_max = stress(1, 1)
         g = statev(1, isv_tangent) - stress(1, 1)
         if (g <= 0.0_dp) then
            eps_max = eps - step*g/(g - g_old)
            return
         end if
         g_old = g
      end do
   end function max_load_strain

   !> MATERIAL_STATE_MAPPED: state variables interpolated between material
   !> points (remesh, docs/theory.md §7.6) made consistent for the next
   !> update: the built-in law's cached flow stress and hardening slope
   !> belong to the old points' plastic strains, so they are marked unknown
   !> (recomputed from the mapped plastic strain at the next update; with a
   !> hardening curve concave in the plastic strain the interpolated cache
   !> lies below the curve and a trial stress could be judged plastic that
   !> the curve holds elastic).  A user's UMAT keeps its state as mapped.
   !>  mat     [in]     the material
   !>  statev  [in,out] (npt, nstatv) the mapped state variables of a section
   pure subroutine material_state_mapped(mat, statev)
      type(material_type), intent(in) :: mat
      real(dp), intent(inout) :: statev(:, :)
      if (mat%kind == material_builtin) statev(:, isv_flow_stress) = 0.0_dp
   end subroutine material_state_mapped
end module material
