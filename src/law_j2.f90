!> law_j2 -- the paper's material law as a material_law_type: J2 / Hill 1948
!> normal anisotropy R, isotropic hardening (Swift, Voce or a table), the
!> block return mapping of module material_j2 (docs/theory.md §4).
!>
!> Constants: props as module material_j2 lays them out (E, nu, R, the
!> hardening law id and its constants); checked once by check_props.
!> State variables: material_j2's six (isv_eqps, isv_eps22, isv_sigma33,
!> isv_tangent, and the cached flow stress and hardening slope).
!>
!> A prescribed thickness stress tau22 = p needs no second return mapping.
!> Hill's function and the plastic flow depend on stress differences only,
!> so with s = (tau11 - p, tau33 - p) the yield condition is the
!> plane-stress one in s, and isotropic elasticity gives
!>   d eps11 = (ds11 - nu ds33)/E + (1 - 2 nu) dp/E + d eps11^p
!> (likewise eps33): the update of s is the plane-stress update driven by
!> the strain increments less (1 - 2 nu) dp/E, and
!>   tau = s + p,  d eps22 = d eps22(plane stress, s) + (1 - 2 nu) dp/E.
!> The plastic work s : d eps^p equals tau : d eps^p (the flow is
!> incompressible); the elastic energy is that of the three stresses.  The
!> shift holds only for a law without a back stress: law_combined solves
!> the increment with tau22 prescribed directly (docs/theory.md §13.7), a
!> user's UMAT is driven (module normal_law).
module law_j2
   use kinds, only: dp
   use material_law, only: material_law_type
   use material_j2, only: umat_block, umat_block_to, n_statev, ip_youngs, ip_poisson, isv_eqps, &
                          isv_eps22, isv_sigma33, isv_tangent, isv_flow_stress
   use deck, only: deck_type, is_unset
   use deck_checks, only: fail, at
   use errors, only: error_list
   implicit none
   private
   public :: j2_law_type, j2_law, j2_law_of_deck

   !> The built-in J2/Hill law with its constants.
   type, extends(material_law_type) :: j2_law_type
      !> the constants (layout in material_j2)
      real(dp), allocatable :: props(:)
   contains
      procedure :: update => j2_update
      procedure :: update_to => j2_update_to
      procedure :: state_mapped => j2_state_mapped
   end type j2_law_type

contains

   !> J2_LAW: the law with its constants (check them first with
   !> material_j2's check_props).
   !>  props  [in]  the constants; E = props(ip_youngs), nu = props(ip_poisson)
   pure function j2_law(props) result(law)
      real(dp), intent(in) :: props(:)
      type(j2_law_type) :: law
      allocate (law%props, source=props)
      law%youngs = props(ip_youngs)
      law%poisson = props(ip_poisson)
      law%n_state = n_statev
      law%isv_eqps = isv_eqps
      law%isv_eps22 = isv_eps22
      law%isv_tangent = isv_tangent
      law%name = 'j2'
   end function j2_law

   !> J2_LAW_OF_DECK: the law of a deck with model = 'j2', the other laws'
   !> variables refused (the constants are checked by set-up, with
   !> material_j2's check_props, for every built-in law).
   !>  d        [in]     the deck
   !>  props    [in]     the constants set-up built from it (material_j2's layout)
   !>  errs     [in,out] problems are appended, naming deck, group, variable
   function j2_law_of_deck(d, props, errs) result(law)
      type(deck_type), intent(in) :: d
      real(dp), intent(in) :: props(:)
      type(error_list), intent(inout) :: errs
      type(j2_law_type) :: law
      if (.not. is_unset(d%r0) .or. .not. is_unset(d%r90)) &
         call fail(errs, at(trim(d%deck_file), 'material', trim(merge('r0 ', 'r90', .not. is_unset(d%r0)))), &
                   "needs model = 'combined' (Hill 1948 with r0 and r90); model = 'j2' takes r_value")
      if (any(.not. is_unset(d%kinematic_c)) .or. any(.not. is_unset(d%kinematic_gamma))) &
         call fail(errs, at(trim(d%deck_file), 'material', 'kinematic_c'), &
                   "needs model = 'combined' (back stresses); model = 'j2' hardens isotropically")
      law = j2_law(props)
   end function j2_law_of_deck

   !> J2_UPDATE: material_law_type's update (arguments there): umat_block
   !> on the block, with a prescribed tau22 by the shift of the module header.
   subroutine j2_update(law, n, stress, statev, ddsdde, sse, spd, stran11, dstran, zbar, pnewdt, &
                        s22n, s22, dsig_ds22, dp_start)
      class(j2_law_type), intent(in) :: law
      integer, intent(in) :: n
      real(dp), intent(inout) :: stress(n, 2), statev(n, law%n_state), sse(n), spd(n)
      real(dp), intent(out) :: ddsdde(n, 2, 2)
      real(dp), intent(in) :: stran11(n), dstran(n, 2), zbar(n)
      real(dp), intent(inout) :: pnewdt
      real(dp), intent(in), optional :: s22n(n), s22(n)
      real(dp), intent(out), optional :: dsig_ds22(n)
      real(dp), intent(in), optional :: dp_start(n)
      real(dp) :: c, nu, e, dmod(n, 2), s11, s33, p
      integer :: k
      ! the law is homogeneous and additive: the start strain and the
      ! position do not enter; its return starts from the elastic trial
      ! (starts_from_trial is .false.: dp_start comes as zeros, ignored;
      ! the empty test marks it used, as associate cannot take an absent
      ! optional)
      associate (unused => stran11, unused2 => zbar)
      end associate
      if (present(dp_start)) then
      end if
      if (.not. present(s22)) then
         call umat_block(n, stress, statev, ddsdde, sse, spd, dstran, law%props, size(law%props), &
                         law%n_state, pnewdt)
         return
      end if
      e = law%props(ip_youngs)
      nu = law%props(ip_poisson)
      c = (1.0_dp - 2.0_dp*nu)/e
      do k = 1, n
         stress(k, 1) = stress(k, 1) - s22n(k)
         stress(k, 2) = stress(k, 2) - s22n(k)
         dmod(k, 1) = dstran(k, 1) - c*(s22(k) - s22n(k))
         dmod(k, 2) = dstran(k, 2) - c*(s22(k) - s22n(k))
      end do
      call umat_block(n, stress, statev, ddsdde, sse, spd, dmod, law%props, size(law%props), &
                      law%n_state, pnewdt)
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
         if (present(dsig_ds22)) dsig_ds22(k) = 1.0_dp - c*(ddsdde(k, 1, 1) + ddsdde(k, 1, 2))
      end do
   end subroutine j2_update

   !> J2_UPDATE_TO: material_law_type's update_to (arguments there):
   !> umat_block_to reads the start state where it is and writes every end
   !> array once.
   subroutine j2_update_to(law, n, stress_n, statev_n, sse_n, spd_n, stress, statev, sse, spd, &
                           ddsdde, stran11, dstran, zbar, pnewdt, dp_start)
      class(j2_law_type), intent(in) :: law
      integer, intent(in) :: n
      real(dp), intent(in) :: stress_n(n, 2), statev_n(n, law%n_state), sse_n(n), spd_n(n)
      real(dp), intent(out) :: stress(n, 2), statev(n, law%n_state), sse(n), spd(n)
      real(dp), intent(out) :: ddsdde(n, 2, 2)
      real(dp), intent(in) :: stran11(n), dstran(n, 2), zbar(n)
      real(dp), intent(inout) :: pnewdt
      real(dp), intent(in), optional :: dp_start(n)
      ! (dp_start: as in j2_update)
      associate (unused => stran11, unused2 => zbar)
      end associate
      if (present(dp_start)) then
      end if
      call umat_block_to(n, stress_n, statev_n, sse_n, spd_n, stress, statev, ddsdde, sse, spd, &
                         dstran, law%props, size(law%props), law%n_state, pnewdt)
   end subroutine j2_update_to

   !> J2_STATE_MAPPED: the cached flow stress and hardening slope belong to
   !> the old points' plastic strains, so they are marked unknown
   !> (recomputed from the mapped plastic strain at the next update; with a
   !> hardening curve concave in the plastic strain the interpolated cache
   !> lies below the curve and a trial stress could be judged plastic that
   !> the curve holds elastic).
   !>  law     [in]     the law
   !>  statev  [in,out] (npt, n_state) the mapped state variables
   pure subroutine j2_state_mapped(law, statev)
      class(j2_law_type), intent(in) :: law
      real(dp), intent(inout) :: statev(:, :)
      associate (unused => law)
      end associate
      statev(:, isv_flow_stress) = 0.0_dp
   end subroutine j2_state_mapped
end module law_j2
