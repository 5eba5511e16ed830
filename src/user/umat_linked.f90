!> umat_linked -- linked beside a user's UMAT (make UMAT=..., and the test
!> runner, which links input/umat_linear_hardening.f90): tells set-up that
!> the external umat is a real material routine.  Not part of the library.

!> USER_UMAT_LINKED: .true.: this program holds a user's umat.
logical function user_umat_linked()
   implicit none
   user_umat_linked = .true.
end function user_umat_linked
