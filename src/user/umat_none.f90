!> umat_none -- what bin/drawbead links in place of a user's UMAT when it is
!> built without UMAT= (see module law_umat and the Makefile): a umat that
!> computes nothing and says so, and user_umat_linked() = .false., which
!> set-up asks so that a deck naming the user model is an input error.
!> Not part of the library.

!> UMAT: the error path.  Reached only if set-up let a user model through
!> in a binary without one: writes one *ERROR* line (module errors) naming the
!> cure, asks for a zero increment (pnewdt = 0, the UMAT contract's signal
!> of a programming error), and changes nothing else.
!>  stress, statev, sse, spd, scd [in,out] left as they are
!>  ddsdde, rpl, ddsddt, drplde, drpldt [out] 0
!>  pnewdt [in,out] 0
!>  every other argument [in] not used (the list is module law_umat's)
subroutine umat(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, &
                stran, dstran, time, dtime, temp, dtemp, predef, dpred, cmname, ndi, &
                nshr, ntens, nstatv, props, nprops, coords, drot, pnewdt, celent, dfgrd0, &
                dfgrd1, noel, npt, layer, kspt, kstep, kinc)
   use kinds, only: dp
   use errors, only: print_error
   implicit none
   character(len=80), intent(in) :: cmname
   integer, intent(in) :: ndi, nshr, ntens, nstatv, nprops, noel, npt, layer, kspt, kstep, kinc
   real(dp), intent(inout) :: stress(ntens), statev(nstatv), sse, spd, scd, pnewdt
   real(dp), intent(out) :: ddsdde(ntens, ntens), rpl, ddsddt(ntens), drplde(ntens), drpldt
   real(dp), intent(in) :: stran(ntens), dstran(ntens), time(2), dtime, temp, dtemp, predef(1), &
                           dpred(1), props(nprops), coords(3), drot(3, 3), celent, &
                           dfgrd0(3, 3), dfgrd1(3, 3)

   ! The arguments this error path does not need are named once here, so
   ! that the compiler does not report them as unused.
   associate (u1 => stress, u2 => statev, u3 => sse, u4 => spd, u5 => scd, u6 => stran, &
              u7 => dstran, u8 => time, u9 => dtime, u10 => temp, u11 => dtemp, u12 => predef, &
              u13 => dpred, u14 => cmname, u15 => ndi, u16 => nshr, u17 => props, &
              u18 => coords, u19 => drot, u20 => celent, u21 => dfgrd0, u22 => dfgrd1, &
              u23 => noel, u24 => npt, u25 => layer, u26 => kspt, u27 => kstep, u28 => kinc)
   end associate

   call print_error('this program holds no user material routine; build it with: '// &
                    'make UMAT=path/to/umat.f90', 'umat')
   ddsdde = 0.0_dp
   rpl = 0.0_dp
   ddsddt = 0.0_dp
   drplde = 0.0_dp
   drpldt = 0.0_dp
   pnewdt = 0.0_dp
end subroutine umat

!> USER_UMAT_LINKED: .false.: umat is the error path above.
logical function user_umat_linked()
   implicit none
   user_umat_linked = .false.
end function user_umat_linked
