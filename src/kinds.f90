!> kinds -- working precision and shared constants.
!>
!> Every real in drawbead is real(dp); dp is real64 from iso_fortran_env.
module kinds
   use, intrinsic :: iso_fortran_env, only: real64, output_unit, error_unit
   implicit none
   private
   public :: dp, pi, output_unit, error_unit

   integer, parameter :: dp = real64
   real(dp), parameter :: pi = 3.14159265358979323846264338327950288_dp
end module kinds
