!> deck_scan -- the text of a namelist deck, before any namelist read:
!> where each group starts and ends, and the `name = value` assignments of a
!> group's body.  The deck reader (module deck_reader) uses it to find
!> unknown and repeated groups and to re-read a failing group one
!> assignment at a time, so that every bad variable is named.
!>
!> Syntax honoured: outside groups '!' starts a comment and anything but
!> '&name' is skipped; inside a group quotes (' or ", doubled to escape) and
!> '!' comments are honoured and an unquoted '/', '&end' or '$end' (the
!> old dialects' terminators) ends the group; an unquoted '&name' there is
!> a group opened before the last one was closed.
module deck_scan
   use errors, only: error_list, add_error
   use text, only: lower, itoa
   implicit none
   private
   public :: group_text, scan_groups, split_assignments, check_repeated, clip, strip_separators, &
             is_letter, value_problem

   !> The text of one group as found in the deck file.
   type :: group_text
      logical :: present = .false.
      logical :: terminated = .false.
      character(len=:), allocatable :: body     ! between '&name' and '/'
   end type group_text

contains


   !> scan_groups -- find the text of each known group in a deck.
   !>
   !> Outside groups, '!' starts a comment, '&name' opens a group and
   !> anything else but blanks is stray text, reported with its line (the
   !> first three lines of it, then a count). Inside a group, quotes (' or
   !> ", doubled to escape) and '!' comments are honoured and an unquoted
   !> '/', '&end' or '$end' ends the group; an unquoted '&name' ends it too, with an
   !> error (no '/' before it), and opens group name. Line ends, tabs and
   !> comments become blanks in the body.
   !>
   !> text   [in]     the whole deck.
   !> path   [in]     deck name, for messages.
   !> names  [in]     the known groups, lower case, without '&'.
   !> found  [out]    per entry of names: present, terminated, body
   !>                 (of the first occurrence).
   !> errs   [in,out] unknown and repeated groups and stray text are appended.
   subroutine scan_groups(text, path, names, found, errs)
      character(len=*), intent(in) :: text
      character(len=*), intent(in) :: path
      character(len=*), intent(in) :: names(:)
      type(group_text), intent(out) :: found(size(names))
      type(error_list), intent(inout) :: errs

      character(len=:), allocatable :: body, name
      character(len=1) :: c, quote
      logical :: in_group
      integer :: i, j, n, g, current, nb, line, stray

      n = len(text)
      i = 1
      name = ''
      in_group = .false.
      current = 0
      quote = ' '
      ! the body grows in a buffer as long as the deck (no copy per character)
      allocate (character(len=n) :: body)
      nb = 0
      line = 1
      stray = 0
      do while (i <= n)
         c = text(i:i)
         if (c == achar(10)) line = line + 1
         if (.not. in_group) then
            if (c == '!') then
               i = end_of_line(text, i)
               cycle
            else if (c /= '&' .and. c /= ' ' .and. iachar(c) >= 32) then
               stray = stray + 1
               j = end_of_line(text, i)
               if (stray <= 3) call add_error(errs, "deck '"//trim(path)//"', line "//itoa(line)// &
                                              ": text outside any namelist group: '"// &
                                              printable(clip(text(i:j - 1)))//"'")
               i = j
               cycle
            else if (c == '&') then
               j = i + 1
               do while (j <= n)
                  if (.not. is_name_char(text(j:j))) exit
                  j = j + 1
               end do
               name = lower(text(i + 1:j - 1))
               if (len(name) > 0 .and. name /= 'end') then
                  current = 0
                  do g = 1, size(names)
                     if (name == trim(names(g))) current = g
                  end do
                  if (current == 0) then
                     call add_error(errs, "deck '"//trim(path)//"', group &"//name// &
                                    ": unknown group (the groups are &control, &sheet, " &
                                    //"&material, &tools and &loading)")
                  else if (found(current)%present) then
                     call add_error(errs, "deck '"//trim(path)//"', group &"//name// &
                                    ": appears more than once (only the first is read)")
                     current = 0
                  else
                     found(current)%present = .true.
                  end if
                  in_group = .true.
                  quote = ' '
                  nb = 0
               end if
               i = j
               cycle
            end if
         else
            if (quote /= ' ') then
               if (c == quote) quote = ' '
            else if (c == '"' .or. c == "'") then
               quote = c
            else if (c == '!') then
               i = end_of_line(text, i)
               nb = nb + 1
               body(nb:nb) = ' '
               cycle
            else if (c == '/' .or. (c == '$' .and. lower(text(i + 1:min(i + 3, n))) == 'end')) then
               ! '/', or '$end' (another old dialect's terminator, which
               ! gfortran's read honours too)
               call close_group()
               i = i + merge(1, 4, c == '/')
               cycle
            else if (c == '&') then
               ! an unquoted '&' ends the group too: '&end' (the old
               ! dialect's terminator, which gfortran's read honours: the
               ! text after it would otherwise be read as the group's and
               ! never checked), or '&name', a group opened before this one
               ! was closed (an error; the new group is scanned as usual)
               j = i + 1
               do while (j <= n)
                  if (.not. is_name_char(text(j:j))) exit
                  j = j + 1
               end do
               call close_group()
               if (lower(text(i + 1:j - 1)) == 'end') then
                  i = j
               else
                  if (current > 0) call add_error(errs, "deck '"//trim(path)//"', group &"// &
                                                  trim(names(current))//": no '/' ends the group before '"// &
                                                  printable(clip(text(i:j - 1)))//"' (line "//itoa(line)//")")
               end if
               cycle
            end if
            ! a control character separates like a blank; inside quotes a
            ! line end is a blank too (text continued on the next line), any
            ! other is kept, for validate_deck to refuse (issue 28, item 8)
            if (iachar(c) < 32 .and. (quote == ' ' .or. c == achar(10) .or. c == achar(13))) c = ' '
            nb = nb + 1
            body(nb:nb) = c
         end if
         i = i + 1
      end do
      if (stray > 3) call add_error(errs, "deck '"//trim(path)//"': "//itoa(stray - 3)// &
                                    ' more lines of text outside any namelist group')
      if (in_group .and. current > 0) found(current)%body = body(1:nb)
      do g = 1, size(found)
         if (.not. allocated(found(g)%body)) found(g)%body = ''
      end do
   contains
      !> the open group ends here: its body so far, terminated
      subroutine close_group()
         if (current > 0) then
            found(current)%terminated = .true.
            found(current)%body = body(1:nb)
         end if
         in_group = .false.
      end subroutine close_group
   end subroutine scan_groups


   !> check_repeated -- a variable set twice in a group is an error (a
   !> namelist read would silently keep the last value).  Names are
   !> compared in lower case with their subscripts, so x(1) and x(2) differ.
   !>
   !> group  [in]     group name, lower case.
   !> body   [in]     the group's text without '&group' and '/'.
   !> path   [in]     deck name, for messages.
   !> errs   [in,out] one error per repeated variable.
   subroutine check_repeated(group, body, path, errs)
      character(len=*), intent(in) :: group, body, path
      type(error_list), intent(inout) :: errs

      integer, allocatable :: starts(:), eqs(:)
      integer :: k, j
      character(len=:), allocatable :: name

      call split_assignments(body, starts, eqs)
      do k = 2, size(starts)
         name = assigned_name(k)
         if (len(name) == 0) cycle
         do j = 1, k - 1
            if (assigned_name(j) == name) then
               call add_error(errs, "deck '"//trim(path)//"', group &"//group//', variable '// &
                              name//': set more than once (each variable may be given once)')
               exit
            end if
         end do
      end do

   contains

      !> the name (with subscripts, blanks removed, lower case) of assignment i
      function assigned_name(i) result(r)
         integer, intent(in) :: i
         character(len=:), allocatable :: r
         integer :: c
         r = ''
         do c = starts(i), eqs(i) - 1
            if (body(c:c) /= ' ') r = r//body(c:c)
         end do
         r = lower(r)
      end function assigned_name
   end subroutine check_repeated

   !> split_assignments -- locate the `name = value` assignments of a body.
   !>
   !> body    [in]  group text.
   !> starts  [out] first character of each assignment's name.
   !> eqs     [out] position of each assignment's unquoted '='.
   pure subroutine split_assignments(body, starts, eqs)
      character(len=*), intent(in) :: body
      integer, allocatable, intent(out) :: starts(:), eqs(:)

      character(len=1) :: c, quote
      integer :: i, j, depth, n

      allocate (starts(0), eqs(0))
      quote = ' '
      do i = 1, len(body)
         c = body(i:i)
         if (quote /= ' ') then
            if (c == quote) quote = ' '
            cycle
         end if
         if (c == '"' .or. c == "'") then
            quote = c
            cycle
         end if
         if (c /= '=') cycle
         ! walk back over blanks, then over the name and any (subscripts)
         j = i - 1
         do while (j >= 1)
            if (body(j:j) /= ' ') exit
            j = j - 1
         end do
         n = j
         depth = 0
         do while (j >= 1)
            if (body(j:j) == ')') then
               depth = depth + 1
            else if (body(j:j) == '(') then
               depth = depth - 1
            else if (depth == 0 .and. .not. is_name_char(body(j:j)) .and. body(j:j) /= '%') then
               exit
            end if
            j = j - 1
         end do
         if (j + 1 > n) then
            starts = [starts, i]       ! no name: an empty one, reported by the caller
         else
            starts = [starts, j + 1]
         end if
         eqs = [eqs, i]
      end do
   end subroutine split_assignments


   !> value_problem -- what is wrong with the value of one assignment that
   !> gfortran's namelist read does not say: a null value (nothing after
   !> '=', an empty item between commas, 'r*' without a value, or a lone
   !> sign or '.', which the read takes as null and so silently keeps the
   !> default), or a number that is not one ('1e', '1.e+': the read of a
   !> group's only assignment takes them).  Quoted text, items that start
   !> with a letter (T, F, NaN, Inf, unquoted words: the read judges them),
   !> '.t' and '.f' logicals, signed NaN and Inf and numbers of the Fortran
   !> form (is_number), each with an optional 'r*' repeat count, pass.
   !>
   !> value  [in]  the text after '=' up to the next assignment's name
   !>              (its one trailing ',' the separator).
   !> Returns '' or the problem, for a message after the variable's name.
   pure function value_problem(value) result(msg)
      character(len=*), intent(in) :: value
      character(len=:), allocatable :: msg

      character(len=:), allocatable :: v
      integer :: i, j, n
      logical :: want_item
      character(len=1) :: q

      msg = ''
      v = trim(value)
      n = len(v)
      ! the separator before the next name
      if (n > 0) then
         if (v(n:n) == ',') n = n - 1
      end if
      v = trim(v(1:n))
      n = len(v)
      if (verify(v, ' ') == 0) then
         msg = "no value after '=' (a null value would keep the default)"
         return
      end if
      want_item = .true.
      i = 1
      do while (i <= n)
         if (v(i:i) == ' ') then
            i = i + 1
            cycle
         end if
         if (v(i:i) == ',') then
            if (want_item) then
               msg = "an empty item between commas (a null value would keep the default)"
               return
            end if
            want_item = .true.
            i = i + 1
            cycle
         end if
         ! one item: quoted text, or up to the next blank or comma
         if (v(i:i) == '"' .or. v(i:i) == "'") then
            q = v(i:i)
            j = i + 1
            do while (j <= n)
               if (v(j:j) == q) then
                  if (j < n) then
                     if (v(j + 1:j + 1) == q) then
                        j = j + 2
                        cycle
                     end if
                  end if
                  exit
               end if
               j = j + 1
            end do
            i = j + 1
         else
            j = i
            do while (j <= n)
               if (v(j:j) == ' ' .or. v(j:j) == ',') exit
               j = j + 1
            end do
            msg = item_problem(v(i:j - 1))
            if (len(msg) > 0) return
            i = j
         end if
         want_item = .false.
      end do
      if (want_item) msg = "an empty item after the last comma (a null value would keep the default)"
   end function value_problem


   !> item_problem -- value_problem's test of one unquoted item.
   pure function item_problem(item) result(msg)
      character(len=*), intent(in) :: item   !< [in] the item, no blanks or commas
      character(len=:), allocatable :: msg

      character(len=:), allocatable :: body, rest
      integer :: k

      msg = ''
      body = item
      k = index(body, '*')
      if (k > 0) then
         ! r*c: r a repeat count, c the value (none: r nulls)
         if (k == 1 .or. verify(body(1:k - 1), '0123456789') /= 0) return
         body = body(k + 1:)
         if (len(body) == 0) then
            msg = "'"//clip(item)//"' repeats a null value (it would keep the default)"
            return
         end if
      end if
      ! a letter, or a quote after a repeat count (3*'text')
      if (is_letter(body(1:1)) .or. body(1:1) == '"' .or. body(1:1) == "'") return
      if (body(1:1) == '.') then
         if (len(body) == 1) then
            msg = "'.' alone is no value (a null value would keep the default)"
            return
         end if
         ! .t..., .f...: a logical (the read judges the rest)
         if (index('tTfF', body(2:2)) > 0) return
      end if
      rest = body
      if (rest(1:1) == '+' .or. rest(1:1) == '-') rest = rest(2:)
      if (len(rest) == 0) then
         msg = "a sign alone is no value (a null value would keep the default)"
         return
      end if
      if (is_letter(rest(1:1))) then
         if (lower(rest) == 'nan' .or. lower(rest) == 'inf' .or. lower(rest) == 'infinity') return
      end if
      if (.not. is_number(rest)) then
         msg = "'"//clip(item)//"' is not a number"
         ! letters other than an exponent's: text, which must be quoted
         if (scan(lower(rest), 'abcfghijklmnoprstuvwxyz') > 0) msg = msg//' (text values must be in quotes)'
      end if
   end function item_problem


   !> is_number -- digits[.[digits]] or .digits, then an optional exponent:
   !> e, d or q (any case) with an optional sign, or a sign alone, then
   !> digits (gfortran reads 548.0+0 as 548 and 1.0-3 as 1e-3); the sign
   !> before the number removed.
   pure logical function is_number(s)
      character(len=*), intent(in) :: s      !< [in] the text
      integer :: i, n, nd
      is_number = .false.
      n = len(s)
      i = 1
      nd = 0
      do while (i <= n)
         if (s(i:i) < '0' .or. s(i:i) > '9') exit
         i = i + 1
         nd = nd + 1
      end do
      if (i <= n) then
         if (s(i:i) == '.') then
            i = i + 1
            do while (i <= n)
               if (s(i:i) < '0' .or. s(i:i) > '9') exit
               i = i + 1
               nd = nd + 1
            end do
         end if
      end if
      if (nd == 0) return
      if (i > n) then
         is_number = .true.
         return
      end if
      if (index('eEdDqQ', s(i:i)) > 0) then
         i = i + 1
         if (i <= n) then
            if (s(i:i) == '+' .or. s(i:i) == '-') i = i + 1
         end if
      else if (s(i:i) == '+' .or. s(i:i) == '-') then
         i = i + 1
      else
         return
      end if
      if (i > n) return
      is_number = verify(s(i:n), '0123456789') == 0
   end function is_number


   !> clip -- text shortened to at most 60 characters for messages.
   pure function clip(s) result(r)
      character(len=*), intent(in) :: s      !< [in] any text
      character(len=:), allocatable :: r

      if (len_trim(s) > 60) then
         r = s(1:57)//'...'
      else
         r = trim(s)
      end if
   end function clip


   !> strip_separators -- text without surrounding blanks and commas.
   pure function strip_separators(s) result(r)
      character(len=*), intent(in) :: s      !< [in] any text
      character(len=:), allocatable :: r

      integer :: i, j

      i = verify(s, ' ,')
      j = verify(s, ' ,', back=.true.)
      if (i == 0) then
         r = ''
      else
         r = s(i:j)
      end if
   end function strip_separators


   !> end_of_line -- index of the next newline at or after i (or len+1).
   pure function end_of_line(text, i) result(j)
      character(len=*), intent(in) :: text   !< [in] the text
      integer, intent(in) :: i               !< [in] start position
      integer :: j

      j = index(text(i:), achar(10))
      if (j == 0) then
         j = len(text) + 1
      else
         j = i + j - 1
      end if
   end function end_of_line


   !> is_name_char -- .true. for a letter, digit or underscore.
   pure function is_name_char(c) result(yes)
      character(len=1), intent(in) :: c      !< [in] one character
      logical :: yes

      yes = is_letter(c) .or. (c >= '0' .and. c <= '9') .or. c == '_'
   end function is_name_char


   !> printable -- text with every byte outside ' ' .. '~' shown as '?'
   !> (a binary file quoted in a message).
   pure function printable(s) result(r)
      character(len=*), intent(in) :: s      !< [in] any text
      character(len=len(s)) :: r

      integer :: i

      r = s
      do i = 1, len(s)
         if (iachar(s(i:i)) < 32 .or. iachar(s(i:i)) > 126) r(i:i) = '?'
      end do
   end function printable

   !> is_letter -- .true. for A-Z or a-z.
   pure function is_letter(c) result(yes)
      character(len=1), intent(in) :: c      !< [in] one character
      logical :: yes

      yes = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z')
   end function is_letter
end module deck_scan
