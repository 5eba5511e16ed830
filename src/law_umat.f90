!> law_umat -- a user's UMAT as a material law (docs/theory.md §13.3).
!>
!> A user's UMAT
!>   An external (non-module) `subroutine umat(...)` with the argument list
!>   of the interface below (Abaqus order, as in CalculiX umat.f), built in
!>   with `make UMAT=path/to/my_umat.f90`; the examples are
!>   input/umat_linear_hardening.f90 and input/umat_chaboche.f90.  Without
!>   UMAT= the program links src/user/umat_none.f90, whose umat is an
!>   error path, and user_umat_linked() tells which of the two a binary
!>   holds.
!>   Conventions: those of an Abaqus plane-strain element, NDI = 3,
!>   NSHR = 1, NTENS = 4, components (11, 22, 33, 12) = (axial, thickness,
!>   width, shear); Kirchhoff stress, logarithmic strain.  The width strain
!>   is held (plane strain), the shear is 0, and the program drives the
!>   thickness strain until tau22 is the section's prescribed value (0, or
!>   the contact pressure): module normal_law, which calls the routine a
!>   few times per increment from the same start state.  So the routine
!>   must be a function of its start state and strain increment only, as a
!>   UMAT is.
!>   The deck (&material) gives the constants (umat_props), the number of
!>   state variables (umat_nstatv) and which of them is the equivalent
!>   plastic strain (umat_eqps_index, 0: none; the outputs then say so).
!>   The program keeps the thickness strain and the tangents itself.
!>   What the program passes, argument by argument:
!>     stress(4)      [in,out] (tau11, tau22, tau33, 0) at the start; the
!>                             routine returns the end values.
!>     statev(nstatv) [in,out] the user's state variables, all 0 in the
!>                             virgin state.
!>     ddsdde(4,4)    [out]    consistent tangent d stress / d dstran; the
!>                             program uses its normal block (1:3, 1:3).
!>     sse, spd       [in,out] elastic energy and plastic work densities
!>                             (the energy balance reads them).
!>     scd            [in,out] 0 on entry; not kept.
!>     rpl, ddsddt, drplde, drpldt [out] not used.
!>     stran(4)       [in]     (eps11, eps22, 0, 0) at the start.
!>     dstran(4)      [in]     (deps11, deps22, 0, 0).
!>     time(2)        [in]     (0, 0);  dtime [in] 1 (rate-independent).
!>     temp, dtemp    [in]     0, 0;  predef, dpred [in] (0), (0).
!>     cmname         [in]     'UMAT'.
!>     ndi, nshr, ntens [in]   3, 1, 4.
!>     nstatv         [in]     umat_nstatv (at least 1: a zero-length
!>                             array is passed as one unused entry).
!>     props(nprops)  [in]     umat_props as given.
!>     coords(3)      [in]     (0, zbar, 0): the point's current distance
!>                             from the mid-surface.
!>     drot(3,3)      [in]     identity (the fibre frame).
!>     pnewdt         [in,out] 1 on entry; < 1 asks for a smaller increment.
!>     celent         [in]     0;  dfgrd0, dfgrd1 [in] identity.
!>     noel, npt      [in]     0, 0;  layer [in] 1;  kspt [in] the point's
!>                             number through the thickness.
!>     kstep, kinc    [in]     1, 0.
module law_umat
   use kinds, only: dp
   use normal_law, only: normal_law_type, set_normal_layout
   use deck, only: deck_type, umat_props_given
   use deck_checks, only: check_int, fail, at
   use errors, only: error_list
   implicit none
   private
   public :: umat_law_type, umat_law, umat_law_of_deck, umat, user_umat_linked

   !> the largest umat_nstatv accepted
   integer, parameter :: max_nstatv = 1000

   !> A user's UMAT with its constants.
   type, extends(normal_law_type) :: umat_law_type
      !> the user's constants
      real(dp), allocatable :: props(:)
      !> the user's number of state variables
      integer :: nstatv = 0
   contains
      procedure :: point_update => umat_point_update
   end type umat_law_type

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

   !> UMAT_LAW: a user's UMAT with its constants and state size.
   !>  props     [in]  the user's constants, passed to umat as they are
   !>  youngs    [in]  Young's modulus E (a scale, and the elastic first
   !>                  guess of the thickness strain with poisson)
   !>  poisson   [in]  Poisson's ratio
   !>  nstatv    [in]  the user's number of state variables (>= 0)
   !>  isv_eqps  [in]  which of them is the equivalent plastic strain (0: none)
   pure function umat_law(props, youngs, poisson, nstatv, isv_eqps) result(law)
      real(dp), intent(in) :: props(:), youngs, poisson
      integer, intent(in) :: nstatv, isv_eqps
      type(umat_law_type) :: law
      allocate (law%props, source=props)
      law%youngs = youngs
      law%poisson = poisson
      law%nstatv = nstatv
      ! a zero-length state is passed as one unused entry
      call set_normal_layout(law, max(nstatv, 1), isv_eqps)
      law%name = 'umat'
      law%thread_safe = .false.
   end function umat_law

   !> UMAT_LAW_OF_DECK: the law of a deck with model = 'umat': the program
   !> must hold a user's umat; umat_nstatv (0 .. 1000) is required,
   !> umat_eqps_index within 0 .. umat_nstatv (umat_props are checked with
   !> the deck).
   !>  d        [in]     the deck
   !>  errs     [in,out] problems are appended, naming deck, group, variable
   function umat_law_of_deck(d, errs) result(law)
      type(deck_type), intent(in) :: d
      type(error_list), intent(inout) :: errs
      type(umat_law_type) :: law
      character(len=:), allocatable :: p
      integer :: nstatv, ieqps
      p = trim(d%deck_file)
      if (.not. user_umat_linked()) call fail(errs, at(p, 'material', 'model'), &
         "'umat' needs a user UMAT built into the program: make UMAT=path/to/umat.f90")
      nstatv = d%umat_nstatv
      if (nstatv < 0) then
         call fail(errs, at(p, 'material', 'umat_nstatv'), &
                   "must give the user UMAT's number of state variables (NSTATV) with model = 'umat'")
         nstatv = 0
      else if (nstatv > max_nstatv) then
         call fail(errs, at(p, 'material', 'umat_nstatv'), 'must be <= 1000')
         nstatv = 0
      end if
      ieqps = d%umat_eqps_index
      call check_int(errs, at(p, 'material', 'umat_eqps_index'), ieqps, 0)
      if (ieqps > nstatv) call fail(errs, at(p, 'material', 'umat_eqps_index'), &
                                    'must be <= umat_nstatv (a state variable of the UMAT, or 0 for none)')
      if (ieqps < 0 .or. ieqps > nstatv) ieqps = 0
      law = umat_law(d%umat_props(1:umat_props_given(d)), d%youngs_modulus, d%poissons_ratio, &
                     nstatv, ieqps)
   end function umat_law_of_deck

   !> UMAT_POINT_UPDATE: normal_law_type's point_update (arguments there):
   !> the user's umat with the arguments of the module header; the
   !> continuum tangent is the consistent one (a UMAT returns no other).
   subroutine umat_point_update(law, stress, statev, ddsdde, cont, sse, spd, stran, dstran, zbar, &
                                kspt, pnewdt)
      class(umat_law_type), intent(in) :: law
      real(dp), intent(inout) :: stress(3), statev(law%n_inner), sse, spd, pnewdt
      real(dp), intent(out) :: ddsdde(3, 3), cont(3, 3)
      real(dp), intent(in) :: stran(3), dstran(3), zbar
      integer, intent(in) :: kspt
      real(dp), parameter :: identity(3, 3) = reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, &
                                                       0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
      character(len=80), parameter :: cmname = 'UMAT'
      real(dp) :: s(4), dd(4, 4), scd, rpl, ddsddt(4), drplde(4), drpldt
      s = [stress, 0.0_dp]
      scd = 0.0_dp
      call umat(s, statev, dd, sse, spd, scd, rpl, ddsddt, drplde, drpldt, [stran, 0.0_dp], &
                [dstran, 0.0_dp], [0.0_dp, 0.0_dp], 1.0_dp, 0.0_dp, 0.0_dp, [0.0_dp], [0.0_dp], &
                cmname, 3, 1, 4, law%n_inner, law%props, size(law%props), [0.0_dp, zbar, 0.0_dp], &
                identity, pnewdt, 0.0_dp, identity, identity, 0, 0, 1, kspt, 1, 0)
      stress = s(1:3)
      ddsdde = dd(1:3, 1:3)
      cont = ddsdde
   end subroutine umat_point_update
end module law_umat
