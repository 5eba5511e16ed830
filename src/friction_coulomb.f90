!> friction_coulomb -- the paper's Coulomb friction as a friction_law_type:
!> a constant coefficient mu (&tools friction), docs/theory.md §6.
module friction_coulomb
   use kinds, only: dp
   use friction_law, only: friction_law_type
   implicit none
   private
   public :: coulomb_friction_type, coulomb_friction

   !> Coulomb friction with its coefficient.
   type, extends(friction_law_type) :: coulomb_friction_type
      real(dp) :: mu = 0.0_dp
   contains
      procedure :: coefficient => coulomb_coefficient
      procedure :: active => coulomb_active
   end type coulomb_friction_type

contains

   !> COULOMB_FRICTION: the law with its coefficient.
   !>  mu   [in] the coefficient (>= 0, the deck's check)
   !>  eps  [in] the regularization length of (4.3), mm
   pure function coulomb_friction(mu, eps) result(law)
      real(dp), intent(in) :: mu, eps
      type(coulomb_friction_type) :: law
      law%mu = mu
      law%eps = eps
      law%name = 'coulomb'
   end function coulomb_friction

   !> COULOMB_COEFFICIENT: friction_law_type's coefficient: mu at every pressure.
   pure subroutine coulomb_coefficient(law, pressure, mu, dmu_dp)
      class(coulomb_friction_type), intent(in) :: law
      real(dp), intent(in) :: pressure
      real(dp), intent(out) :: mu, dmu_dp
      associate (unused => pressure)
      end associate
      mu = law%mu
      dmu_dp = 0.0_dp
   end subroutine coulomb_coefficient

   !> COULOMB_ACTIVE: mu > 0.
   pure logical function coulomb_active(law)
      class(coulomb_friction_type), intent(in) :: law
      coulomb_active = law%mu > 0.0_dp
   end function coulomb_active
end module friction_coulomb
