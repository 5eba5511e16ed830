!> pair_file -- text files of two-column numeric tables (a hardening curve,
!> a friction table): read whole and bounded, one point per line, with the
!> line each came from, for the caller's checks of its own.
!>
!> Blank lines and lines whose first non-blank character is '#' are
!> skipped, as is anything after a '#' on a data line; columns may be
!> separated by blanks, tabs or commas; every data line holds exactly two
!> numbers.  The file is read whole, at most text's max_input_bytes, lines
!> at most max_line_length characters (a longer file, /dev/zero, a
!> directory are refused by name).  Never stops the program.
module pair_file
   use kinds, only: dp
   use text, only: next_line, strip_comment, split_fields, parse_real, itoa, max_input_bytes, &
                   max_line_length
   use os, only: read_file
   implicit none
   private
   public :: read_pairs

contains

   !> READ_PAIRS: the points of a two-column file.
   !>  path    [in]  file name
   !>  what    [in]  what the file is, for the messages ('curve file')
   !>  columns [in]  the two columns' names, for the messages
   !>                ('plastic strain, true stress')
   !>  x, y    [out] the points (allocated; size 0 on error)
   !>  tokens  [out] (2, n) the numbers as written (for the callers' messages)
   !>  line_no [out] (n) the line of each point
   !>  errmsg  [out] '' on success, else "<what> '<path>' line <k>: <problem>"
   subroutine read_pairs(path, what, columns, x, y, tokens, line_no, errmsg)
      character(len=*), intent(in) :: path, what, columns
      real(dp), allocatable, intent(out) :: x(:), y(:)
      character(len=64), allocatable, intent(out) :: tokens(:, :)
      integer, allocatable, intent(out) :: line_no(:)
      character(len=:), allocatable, intent(out) :: errmsg
      character(len=:), allocatable :: contents, why, line, at
      real(dp), allocatable :: tx(:)
      character(len=64), allocatable :: tt(:, :)
      integer, allocatable :: tl(:)
      real(dp) :: v(2)
      integer :: ios, pos, nline, npt, ntok, k, first(2), last(2)
      errmsg = ''
      allocate (x(16), y(16), tokens(2, 16), line_no(16))
      npt = 0
      nline = 0
      call read_file(path, max_input_bytes, contents, ios, why)
      if (ios /= 0) then
         errmsg = 'cannot read '//what//" '"//path//"': "//why
         call empty()
         return
      end if
      pos = 1
      do while (pos <= len(contents))
         call next_line(contents, pos, line)
         nline = nline + 1
         at = what//" '"//path//"' line "//itoa(nline)//': '
         if (len(line) > max_line_length) then
            errmsg = at//'longer than '//itoa(max_line_length)//' characters'
            exit
         end if
         line = strip_comment(line, '#')
         call split_fields(line, first, last, ntok)
         if (ntok == 0) cycle
         if (ntok /= 2) then
            errmsg = at//'expected 2 numbers ('//columns//'), found '//itoa(ntok)// &
                     " fields in '"//trim(adjustl(line))//"'"
            exit
         end if
         do k = 1, 2
            if (.not. parse_real(line(first(k):last(k)), v(k))) then
               errmsg = at//"cannot read '"//line(first(k):last(k))//"' as a number"
               exit
            end if
         end do
         if (len(errmsg) > 0) exit
         if (npt == size(x)) then
            allocate (tx(2*npt))
            tx(:npt) = x(:npt)
            call move_alloc(tx, x)
            allocate (tx(2*npt))
            tx(:npt) = y(:npt)
            call move_alloc(tx, y)
            allocate (tt(2, 2*npt))
            tt(:, :npt) = tokens(:, :npt)
            call move_alloc(tt, tokens)
            allocate (tl(2*npt))
            tl(:npt) = line_no(:npt)
            call move_alloc(tl, line_no)
         end if
         npt = npt + 1
         x(npt) = v(1)
         y(npt) = v(2)
         tokens(1, npt) = line(first(1):last(1))
         tokens(2, npt) = line(first(2):last(2))
         line_no(npt) = nline
      end do
      if (len(errmsg) > 0) then
         call empty()
      else
         x = x(:npt)
         y = y(:npt)
         tokens = tokens(:, :npt)
         line_no = line_no(:npt)
      end if

   contains

      !> On error: empty (allocated) arrays.
      subroutine empty()
         deallocate (x, y, tokens, line_no)
         allocate (x(0), y(0), tokens(2, 0), line_no(0))
      end subroutine empty
   end subroutine read_pairs
end module pair_file
