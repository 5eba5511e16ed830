!> text -- string and text-file helpers shared by every reader of the
!> program (the deck, the hardening curve file, the profile files) and by
!> the messages that quote numbers.
!>
!> Fields are separated by blanks, tabs, commas or carriage returns (a file
!> written on Windows reads the same); numbers are parsed strictly: only
!> digits, signs, '.', and the exponent letters e/E/d/D, with at least one
!> digit and a finite value, so that list-directed input cannot take '/',
!> 'T', 'nan' or 'inf' as a number.  The module holds no state.
module text
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use, intrinsic :: ieee_exceptions, only: ieee_usual, ieee_get_halting_mode, &
      ieee_set_halting_mode, ieee_set_flag
   use kinds, only: dp
   implicit none
   private
   public :: lower, next_line, first_long_line, strip_comment, split_fields, parse_real
   public :: itoa, num, file_exists
   public :: max_input_bytes, max_line_length

   !> The largest input file (deck, hardening curve, tool profile) the
   !> program reads, bytes (16 MiB: a deck is a few kB, a curve or profile
   !> of a million points fits); anything longer, /dev/zero included, is
   !> refused before it can hang the program or fill its memory
   !> (docs/input-reference.md).
   integer, parameter :: max_input_bytes = 16*1024*1024
   !> The longest line of an input file, characters (a 10 kB title fits)
   integer, parameter :: max_line_length = 65536

contains

   !> LOWER: a copy of a string with A-Z turned into a-z.
   !>  s  [in]  any string
   !>  r  (result) the same length as s
   pure function lower(s) result(r)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: r
      integer :: i, c
      r = s
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (c >= iachar('A') .and. c <= iachar('Z')) r(i:i) = achar(c + 32)
      end do
   end function lower

   !> NEXT_LINE: the line of a text that starts at pos (a file read whole
   !> by os's read_file), without its line feed; pos moves to the next line.
   !> A last line without a line feed is a line.
   !>  text  [in]     the whole text
   !>  pos   [in,out] where the line starts (1 for the first); on return,
   !>                 where the next one starts (> len(text) after the last)
   !>  line  [out]    the line
   pure subroutine next_line(text, pos, line)
      character(len=*), intent(in) :: text
      integer, intent(inout) :: pos
      character(len=:), allocatable, intent(out) :: line
      integer :: k
      k = index(text(pos:), achar(10))
      if (k == 0) then
         line = text(pos:)
         pos = len(text) + 1
      else
         line = text(pos:pos + k - 2)
         pos = pos + k
      end if
   end subroutine next_line

   !> FIRST_LONG_LINE: the number of the first line of a text longer than
   !> max_line_length characters (its line feed not counted), 0 if none.
   !>  text  [in] the whole text
   pure function first_long_line(text) result(lineno)
      character(len=*), intent(in) :: text
      integer :: lineno
      integer :: pos, k, n
      lineno = 0
      pos = 1
      n = 0
      do while (pos <= len(text))
         n = n + 1
         k = index(text(pos:), achar(10))
         if (k == 0) k = len(text) - pos + 2
         if (k - 1 > max_line_length) then
            lineno = n
            return
         end if
         pos = pos + k
      end do
   end function first_long_line

   !> STRIP_COMMENT: the part of a line before a comment marker.
   !>  line    [in]  any text
   !>  marker  [in]  the character that starts a comment ('#')
   !>  r       (result) line up to (not including) the first marker
   pure function strip_comment(line, marker) result(r)
      character(len=*), intent(in) :: line
      character(len=1), intent(in) :: marker
      character(len=:), allocatable :: r
      integer :: k
      k = index(line, marker)
      if (k > 0) then
         r = line(:k - 1)
      else
         r = line
      end if
   end function strip_comment

   !> SPLIT_FIELDS: where the fields of a line are.
   !>  line  [in]  text
   !>  first [out] start of field k in line, for k <= min(ntok, size(first))
   !>  last  [out] end of field k
   !>  ntok  [out] number of fields (all of them, also beyond size(first))
   pure subroutine split_fields(line, first, last, ntok)
      character(len=*), intent(in) :: line
      integer, intent(out) :: first(:), last(:)
      integer, intent(out) :: ntok
      integer :: i, start
      logical :: in_field
      first = 1
      last = 0
      ntok = 0
      in_field = .false.
      start = 1
      do i = 1, len(line) + 1
         if (i <= len(line)) then
            if (.not. is_separator(line(i:i))) then
               if (.not. in_field) start = i
               in_field = .true.
               cycle
            end if
         end if
         if (in_field) then
            ntok = ntok + 1
            if (ntok <= size(first)) then
               first(ntok) = start
               last(ntok) = i - 1
            end if
         end if
         in_field = .false.
      end do
   end subroutine split_fields

   !> IS_SEPARATOR: .true. for a field separator: blank, tab, comma or CR.
   pure logical function is_separator(c)
      character(len=1), intent(in) :: c
      is_separator = c == ' ' .or. c == ',' .or. c == achar(9) .or. c == achar(13)
   end function is_separator

   !> PARSE_REAL: one field as a finite real, strictly (module header).
   !>  tok [in]  the field
   !>  x   [out] its value (0 if it does not parse)
   !>  (result) .true. if tok is a finite number
   logical function parse_real(tok, x)
      character(len=*), intent(in) :: tok
      real(dp), intent(out) :: x
      integer :: ios
      logical :: halting(size(ieee_usual))
      x = 0.0_dp
      parse_real = .false.
      if (len_trim(tok) == 0) return
      if (verify(trim(adjustl(tok)), '0123456789+-.eEdD') /= 0) return
      if (scan(tok, '0123456789') == 0) return
      ! 1e999 overflows inside the run-time library's conversion: it must
      ! become Infinity (rejected below), not a trap in a build with
      ! -ffpe-trap=overflow
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      read (tok, *, iostat=ios) x
      call ieee_set_flag(ieee_usual, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)
      parse_real = ios == 0
      if (parse_real) parse_real = ieee_is_finite(x)
      if (.not. parse_real) x = 0.0_dp
   end function parse_real

   !> ITOA: an integer as text without blanks.
   pure function itoa(i) result(s)
      integer, intent(in) :: i
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function itoa

   !> NUM: a real as short text for messages: about 6 significant digits,
   !> trailing zeros dropped (-5.0, 0.0085, 207000.0, 7.62E-7, NaN, Infinity).
   !>  x  [in]  the value (NaN, Inf allowed)
   pure function num(x) result(s)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=40) :: buf
      character(len=:), allocatable :: expo
      real(dp) :: ax
      integer :: e, k
      if (ieee_is_nan(x)) then
         s = 'NaN'
         return
      else if (.not. ieee_is_finite(x)) then
         s = 'Infinity'
         if (x < 0.0_dp) s = '-Infinity'
         return
      end if
      ax = abs(x)
      expo = ''
      if (.not. ax > 0.0_dp .or. (ax >= 0.1_dp .and. ax < 1.0e6_dp)) then
         write (buf, '(g0.6)') x
         s = trim(adjustl(buf))
      else if (ax >= 1.0e-4_dp .and. ax < 0.1_dp) then
         write (buf, '(f14.10)') x
         s = trim(adjustl(buf))
      else
         write (buf, '(es15.5e3)') x
         s = trim(adjustl(buf))
         e = index(s, 'E')
         k = verify(s(e + 2:), '0')
         if (k == 0) then
            expo = 'E0'
         else
            expo = 'E'//s(e + 1:e + 1)//s(e + 1 + k:)
            if (s(e + 1:e + 1) == '+') expo = 'E'//s(e + 1 + k:)
         end if
         s = s(1:e - 1)
      end if
      if (index(s, '.') > 0) then
         do while (s(len(s):len(s)) == '0')
            s = s(1:len(s) - 1)
         end do
         if (s(len(s):len(s)) == '.') s = s//'0'
      end if
      s = s//expo
   end function num

   !> FILE_EXISTS: .true. when a file of that name exists.
   function file_exists(path) result(yes)
      character(len=*), intent(in) :: path
      logical :: yes
      inquire (file=trim(path), exist=yes)
   end function file_exists

end module text
