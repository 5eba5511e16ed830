!> friction_power -- pressure-dependent friction, a power law held between
!> bounds (docs/theory.md §6.1):
!>   mu(p) = min(mu_max, max(mu_min, mu_ref (p/p_ref)^(m - 1)))
!> (&tools friction = mu_ref, friction_p_ref, friction_m, friction_mu_min,
!> friction_mu_max).  m < 1: the coefficient falls as the pressure rises,
!> as measured on drawbeads and strips (the friction force grows as p^m);
!> m = 1 is Coulomb.
module friction_power
   use kinds, only: dp
   use friction_law, only: friction_law_type
   use deck, only: deck_type, is_unset
   use deck_checks, only: check_real, fail, at
   use errors, only: error_list
   implicit none
   private
   public :: power_friction_type, power_friction, power_friction_of_deck

   !> The power law with its constants.
   type, extends(friction_law_type) :: power_friction_type
      real(dp) :: mu_ref = 0.0_dp     ! the coefficient at p_ref
      real(dp) :: p_ref = 1.0_dp      ! MPa, > 0
      real(dp) :: m = 1.0_dp          ! the exponent of the friction force, > 0
      real(dp) :: mu_min = 0.0_dp     ! the bounds, 0 <= mu_min <= mu_max
      real(dp) :: mu_max = 1.0_dp
   contains
      procedure :: coefficient => power_coefficient
      procedure :: active => power_active
   end type power_friction_type

contains

   !> POWER_FRICTION: the law with its constants (checked by the caller:
   !> mu_ref >= 0, p_ref > 0, m > 0, 0 <= mu_min <= mu_max).
   pure function power_friction(mu_ref, p_ref, m, mu_min, mu_max, eps) result(law)
      real(dp), intent(in) :: mu_ref, p_ref, m, mu_min, mu_max, eps
      type(power_friction_type) :: law
      law%mu_ref = mu_ref
      law%p_ref = p_ref
      law%m = m
      law%mu_min = mu_min
      law%mu_max = mu_max
      law%eps = eps
      law%name = 'power'
   end function power_friction

   !> POWER_FRICTION_OF_DECK: the law of a deck with friction_law = 'power',
   !> its variables checked: friction (mu_ref) >= 0 (the deck's check),
   !> friction_p_ref > 0 and friction_m in (0, 10] required,
   !> 0 <= friction_mu_min <= friction_mu_max <= 10.
   !>  d     [in]     the deck
   !>  errs  [in,out] problems are appended, naming deck, group, variable
   function power_friction_of_deck(d, errs) result(law)
      type(deck_type), intent(in) :: d
      type(error_list), intent(inout) :: errs
      type(power_friction_type) :: law
      character(len=:), allocatable :: p
      integer :: n0
      p = trim(d%deck_file)
      n0 = errs%count
      if (is_unset(d%friction_p_ref)) then
         call fail(errs, at(p, 'tools', 'friction_p_ref'), "must be given with friction_law = 'power' (MPa)")
      else
         call check_real(errs, at(p, 'tools', 'friction_p_ref'), d%friction_p_ref, lo=0.0_dp, &
                         hi=1.0e5_dp, lo_open=.true.)
      end if
      if (is_unset(d%friction_m)) then
         call fail(errs, at(p, 'tools', 'friction_m'), "must be given with friction_law = 'power'")
      else
         call check_real(errs, at(p, 'tools', 'friction_m'), d%friction_m, lo=0.0_dp, hi=10.0_dp, &
                         lo_open=.true.)
      end if
      call check_real(errs, at(p, 'tools', 'friction_mu_min'), d%friction_mu_min, lo=0.0_dp, hi=10.0_dp)
      call check_real(errs, at(p, 'tools', 'friction_mu_max'), d%friction_mu_max, lo=0.0_dp, hi=10.0_dp)
      if (errs%count == n0 .and. d%friction_mu_min > d%friction_mu_max) call fail(errs, &
         at(p, 'tools', 'friction_mu_min'), 'must be <= friction_mu_max')
      if (errs%count > n0) return
      law = power_friction(d%friction, d%friction_p_ref, d%friction_m, d%friction_mu_min, &
                           d%friction_mu_max, d%friction_eps*d%thickness)
   end function power_friction_of_deck

   !> POWER_COEFFICIENT: friction_law_type's coefficient; the slope is 0
   !> where a bound holds.  At p = 0 the law's limit: mu_max for m < 1,
   !> mu_min for m > 1, mu_ref for m = 1 (within the bounds).
   pure subroutine power_coefficient(law, pressure, mu, dmu_dp)
      class(power_friction_type), intent(in) :: law
      real(dp), intent(in) :: pressure
      real(dp), intent(out) :: mu, dmu_dp
      real(dp) :: raw
      dmu_dp = 0.0_dp
      if (.not. pressure > 0.0_dp) then
         if (law%m < 1.0_dp) then
            mu = law%mu_max
         else if (law%m > 1.0_dp) then
            mu = law%mu_min
         else
            mu = min(law%mu_max, max(law%mu_min, law%mu_ref))
         end if
         return
      end if
      raw = law%mu_ref*(pressure/law%p_ref)**(law%m - 1.0_dp)
      if (raw >= law%mu_max) then
         mu = law%mu_max
      else if (raw <= law%mu_min) then
         mu = law%mu_min
      else
         mu = raw
         dmu_dp = (law%m - 1.0_dp)*raw/pressure
      end if
   end subroutine power_coefficient

   !> POWER_ACTIVE: some pressure gives mu > 0.
   pure logical function power_active(law)
      class(power_friction_type), intent(in) :: law
      power_active = law%mu_max > 0.0_dp .and. (law%mu_ref > 0.0_dp .or. law%mu_min > 0.0_dp)
   end function power_active
end module friction_power
