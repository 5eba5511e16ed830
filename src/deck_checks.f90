!> deck_checks -- the checks of one deck value, each adding to an error
!> list a message that names the deck, the namelist group and the variable
!> ("deck '<path>', group &<group>, variable <var>: <what is wrong> (got
!> <value>)"); nothing here stops.  Module deck applies them to a whole
!> deck.
module deck_checks
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use errors, only: error_list, add_error
   use text, only: num, itoa, file_exists
   implicit none
   private
   public :: check_real, check_yield, check_int, check_choice, check_profile, check_text_length, &
             check_text_chars, control_char_at, fail, at, is_positive

contains

   !> check_real -- require a finite real within optional bounds.
   !>
   !> errs     [in,out] gets '<ctx>: must be ... (got x)' on failure.
   !> ctx    [in]     "deck '...', group &..., variable ..." (see at).
   !> x        [in]     the value.
   !> lo, hi   [in]     optional lower and upper bounds.
   !> lo_open  [in]     optional, .true.: x > lo required (default x >= lo).
   !> hi_open  [in]     optional, .true.: x < hi required (default x <= hi).
   subroutine check_real(errs, ctx, x, lo, hi, lo_open, hi_open)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx
      real(dp), intent(in) :: x
      real(dp), intent(in), optional :: lo, hi
      logical, intent(in), optional :: lo_open, hi_open

      character(len=:), allocatable :: rule
      logical :: ok, open_lo, open_hi

      if (.not. ieee_is_finite(x)) then
         call fail(errs, ctx, 'must be a finite number (got '//num(x)//')')
         return
      end if
      open_lo = .false.
      open_hi = .false.
      if (present(lo_open)) open_lo = lo_open
      if (present(hi_open)) open_hi = hi_open
      ok = .true.
      rule = ''
      if (present(lo)) then
         if (open_lo) then
            ok = ok .and. x > lo
            rule = '> '//bound_text(lo)
         else
            ok = ok .and. x >= lo
            rule = '>= '//bound_text(lo)
         end if
      end if
      if (present(hi)) then
         if (len(rule) > 0) rule = rule//' and '
         if (open_hi) then
            ok = ok .and. x < hi
            rule = rule//'< '//bound_text(hi)
         else
            ok = ok .and. x <= hi
            rule = rule//'<= '//bound_text(hi)
         end if
      end if
      if (.not. ok) call fail(errs, ctx, 'must be '//rule//' (got '//num(x)//')')
   end subroutine check_real

   !> check_yield -- the initial yield stress must lie between 1e-6 E and E
   !> (a plastic strain of order 1 needs a flow stress far above round-off
   !> of the elastic stresses, and below E for the elastic predictor).
   !> Nothing is said when E or the constants are not finite and positive
   !> (their own checks report them).
   !>
   !> errs   [in,out] gets a message on failure.
   !> ctx    [in]     see at (the constant that sets the yield stress).
   !> sy0    [in]     the initial yield stress, MPa.
   !> e      [in]     Young's modulus, MPa.
   subroutine check_yield(errs, ctx, sy0, e)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx
      real(dp), intent(in) :: sy0, e

      if (.not. (is_positive(sy0) .and. is_positive(e))) return
      if (sy0 < 1.0e-6_dp*e .or. sy0 > e) call fail(errs, ctx, &
         'gives an initial yield stress of '//num(sy0)//' MPa, outside [1e-6 E, E] = ['// &
         num(1.0e-6_dp*e)//', '//num(e)//'] MPa')
   end subroutine check_yield

   !> check_int -- require an integer >= lo.
   !>
   !> errs   [in,out] gets '<ctx>: must be >= lo (got i)' on failure.
   !> ctx    [in]     see at.
   !> i      [in]     the value.
   !> lo     [in]     the lower bound.
   subroutine check_int(errs, ctx, i, lo)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx
      integer, intent(in) :: i, lo

      if (i < lo) call fail(errs, ctx, 'must be >= '//itoa(lo)//' (got '//itoa(i)//')')
   end subroutine check_int

   !> check_choice -- require a (lower-case, left-adjusted) value from a list.
   !>
   !> errs     [in,out] gets '<ctx>: must be one of ... (got ...)' on failure.
   !> ctx      [in]     see at.
   !> value    [in]     the value.
   !> choices  [in]     the allowed values.
   subroutine check_choice(errs, ctx, value, choices)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx
      character(len=*), intent(in) :: value
      character(len=*), intent(in) :: choices(:)

      character(len=:), allocatable :: list
      integer :: k

      if (any(choices == value)) return
      if (control_char_at(value) > 0) return   ! reported by check_text_chars
      list = ''
      do k = 1, size(choices)
         if (k > 1) list = list//', '
         list = list//"'"//trim(choices(k))//"'"
      end do
      call fail(errs, ctx, 'must be one of '//list//" (got '"//trim(value)//"')")
   end subroutine check_choice

   !> check_profile -- require a profile file name that exists.
   !>
   !> errs   [in,out] gets a message on failure.
   !> ctx    [in]     see at.
   !> path   [in]     the file name from the deck.
   subroutine check_profile(errs, ctx, path)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx
      character(len=*), intent(in) :: path

      if (len_trim(path) == 0) then
         call fail(errs, ctx, "must name a file when bead = 'profile'")
      else if (control_char_at(path) > 0) then
         return   ! reported by check_text_chars (the C library would cut the name at a NUL)
      else if (.not. file_exists(path)) then
         call fail(errs, ctx, "file '"//trim(path)//"' not found")
      end if
   end subroutine check_profile

   !> check_text_length -- reject text that filled its variable (truncated).
   !>
   !> errs   [in,out] gets a message on failure.
   !> ctx    [in]     see at.
   !> s      [in]     the text variable.
   subroutine check_text_length(errs, ctx, s)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx
      character(len=*), intent(in) :: s

      if (len_trim(s) >= len(s)) call fail(errs, ctx, 'is too long (at most '// &
                                           itoa(len(s) - 1)//' characters)')
   end subroutine check_text_length

   !> check_text_chars -- reject a text value holding a control character
   !> (codes 0-31 and 127: NUL, a line feed, an escape, ...).  Such a byte
   !> would be copied into summary.txt and the .dat headers (a NUL makes
   !> grep call them binary) or cut a file name short at the C library.
   !> A tab is one too: read_deck has already turned the title's tabs into
   !> blanks, so a tab is refused only in a file name or a choice.
   !>
   !> errs   [in,out] gets a message naming the character and its place.
   !> ctx    [in]     see at.
   !> s      [in]     the text variable.
   subroutine check_text_chars(errs, ctx, s)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx
      character(len=*), intent(in) :: s

      integer :: k, code

      k = control_char_at(s)
      if (k == 0) return
      code = iachar(s(k:k))
      call fail(errs, ctx, 'holds a control character, code '//itoa(code)//' ('//control_name(code)// &
                '), at character '//itoa(k)//': text values may hold printable characters only'// &
                ' (a tab is read as a blank in the title)')
   end subroutine check_text_chars

   !> control_char_at -- the position of the first control character
   !> (codes 0-31 and 127) of s, 0 if there is none.
   pure function control_char_at(s) result(k)
      character(len=*), intent(in) :: s
      integer :: k

      integer :: code

      do k = 1, len(s)
         code = iachar(s(k:k))
         if (code < 32 .or. code == 127) return
      end do
      k = 0
   end function control_char_at

   !> control_name -- the usual name of a control character's code.
   pure function control_name(code) result(name)
      integer, intent(in) :: code
      character(len=:), allocatable :: name

      select case (code)
      case (0)
         name = 'NUL'
      case (9)
         name = 'tab'
      case (10)
         name = 'line feed'
      case (13)
         name = 'carriage return'
      case (27)
         name = 'escape'
      case (127)
         name = 'DEL'
      case default
         name = 'control-'//achar(code + 64)
      end select
   end function control_name

   !> fail -- append '<ctx>: <what>' to an error list.
   !>
   !> errs   [in,out] the list.
   !> ctx    [in]     see at.
   !> what   [in]     what is wrong and what was found.
   subroutine fail(errs, ctx, what)
      type(error_list), intent(inout) :: errs
      character(len=*), intent(in) :: ctx, what

      call add_error(errs, ctx//': '//what)
   end subroutine fail

   !> at -- "deck '<path>', group &<group>, variable <var>".
   pure function at(path, group, var) result(s)
      character(len=*), intent(in) :: path   !< [in] deck file name
      character(len=*), intent(in) :: group  !< [in] group name without '&'
      character(len=*), intent(in) :: var    !< [in] variable name
      character(len=:), allocatable :: s

      s = "deck '"//trim(path)//"', group &"//group//', variable '//var
   end function at

   !> bound_text -- a bound as text: whole numbers without a decimal point.
   pure function bound_text(x) result(s)
      real(dp), intent(in) :: x              !< [in] a finite bound
      character(len=:), allocatable :: s

      if (abs(x) < 1.0e6_dp .and. abs(x - anint(x)) < tiny(x)) then
         s = itoa(nint(x))
      else
         s = num(x)
      end if
   end function bound_text

   !> is_positive -- .true. for a finite x > 0 (safe for NaN and Inf).
   pure function is_positive(x) result(yes)
      real(dp), intent(in) :: x              !< [in] the value
      logical :: yes

      yes = .false.
      if (.not. ieee_is_finite(x)) return
      yes = x > 0.0_dp
   end function is_positive

end module deck_checks
