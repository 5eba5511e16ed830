!> friction_law -- what the contact asks of a friction law, as an abstract
!> type: each law (friction_coulomb, friction_table, friction_power) is one
!> module extending it, owning its constants and their checks
!> (docs/theory.md §6, §6.1).
!>
!> The tangential traction of a station in contact is the paper's modified
!> Coulomb law (2.21) with one sliding reversal and the regularization
!> (4.3) of module friction, t_t = -mu(p) t_n f(u_T), where a law gives
!> the coefficient mu against the contact pressure p, the normal traction
!> per unit current face area (docs/theory.md §12), and its slope; the
!> type's traction gives the traction and its derivatives (the consistent
!> tangent) from them.  The sliding history (u_T, u_T^m, the sense, the
!> traction and the dissipation) is the contact's, the same for every law.
module friction_law
   use kinds, only: dp
   use friction, only: friction_factor => friction_law
   implicit none
   private
   public :: friction_law_type

   !> A friction law (module header).
   type, abstract :: friction_law_type
      !> the regularization length eps of (4.3), mm (<= 0: rigid-plastic)
      real(dp) :: eps = 0.0_dp
      !> the law's name, as the deck gives it (&tools friction_law)
      character(len=16) :: name = ''
   contains
      procedure(coefficient_interface), deferred :: coefficient
      procedure(active_interface), deferred :: active
      procedure :: traction => law_traction
   end type friction_law_type

   abstract interface
      !> COEFFICIENT: the friction coefficient at a contact pressure.
      !>  law      [in]  the law
      !>  pressure [in]  the contact pressure p >= 0, MPa
      !>  mu       [out] the coefficient mu(p) >= 0
      !>  dmu_dp   [out] d mu / d p, 1/MPa
      pure subroutine coefficient_interface(law, pressure, mu, dmu_dp)
         import :: friction_law_type, dp
         class(friction_law_type), intent(in) :: law
         real(dp), intent(in) :: pressure
         real(dp), intent(out) :: mu, dmu_dp
      end subroutine coefficient_interface

      !> ACTIVE: .false. when the law gives mu = 0 at every pressure (the
      !> contact then computes no friction at all).
      pure logical function active_interface(law)
         import :: friction_law_type
         class(friction_law_type), intent(in) :: law
      end function active_interface
   end interface
contains

   !> LAW_TRACTION: the friction traction of a station in contact, along the
   !> sense of its first slip, mu(p) p_n f(u_T) ((2.21), docs/theory.md
   !> §6.1), and its derivatives.
   !>  law          [in]  the law
   !>  pn           [in]  the normal force per unit reference length, N/mm
   !>  face_stretch [in]  the stretch of the face in contact (p = pn/face_stretch)
   !>  ut, ut_max   [in]  the slid distance u_T and its largest value u_T^m, mm
   !>  tt           [out] the traction, N/mm
   !>  dtt_dpn      [out] d tt / d pn = (mu + p dmu/dp) f (the stretch held)
   !>  dtt_dut      [out] d tt / d u_T = mu pn df/du_T
   !>  pressure, mu [out] the contact pressure, MPa, and the coefficient there
   pure subroutine law_traction(law, pn, face_stretch, ut, ut_max, tt, dtt_dpn, dtt_dut, pressure, mu)
      class(friction_law_type), intent(in) :: law
      real(dp), intent(in) :: pn, face_stretch, ut, ut_max
      real(dp), intent(out) :: tt, dtt_dpn, dtt_dut, pressure, mu
      real(dp) :: dmu_dp, fr, dfr
      pressure = pn/face_stretch
      call law%coefficient(pressure, mu, dmu_dp)
      call friction_factor(ut, ut_max, law%eps, fr, dfr)
      tt = mu*pn*fr
      dtt_dpn = (mu + pressure*dmu_dp)*fr
      dtt_dut = mu*pn*dfr
   end subroutine law_traction
end module friction_law
