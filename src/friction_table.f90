!> friction_table -- pressure-dependent friction from a table of pressure
!> against coefficient (the form friction-modelling tools export),
!> linear between the points and constant beyond the first and the last
!> (docs/theory.md §6.1; &tools friction_law = 'table', friction_file).
!>
!> The file: two columns, the contact pressure p (MPa) and the coefficient
!> mu, one point per line; blank lines and '#' comments skipped, columns
!> separated by blanks, tabs or commas; at least 2 points, p >= 0 strictly
!> increasing, mu >= 0.  Read whole and bounded (text's max_input_bytes and
!> max_line_length), as the hardening curve files.
module friction_table
   use kinds, only: dp
   use friction_law, only: friction_law_type
   use text, only: next_line, strip_comment, split_fields, parse_real, itoa, max_input_bytes, &
                   max_line_length
   use os, only: read_file
   use deck, only: deck_type
   use deck_checks, only: fail, at
   use errors, only: error_list
   implicit none
   private
   public :: table_friction_type, table_friction, read_friction_table, table_friction_of_deck

   !> The table law with its points.
   type, extends(friction_law_type) :: table_friction_type
      real(dp), allocatable :: p(:), mu(:)
   contains
      procedure :: coefficient => table_coefficient
      procedure :: active => table_active
   end type table_friction_type

contains

   !> TABLE_FRICTION: the law with its points (read_friction_table's).
   pure function table_friction(p, mu, eps) result(law)
      real(dp), intent(in) :: p(:), mu(:), eps
      type(table_friction_type) :: law
      allocate (law%p, source=p)
      allocate (law%mu, source=mu)
      law%eps = eps
      law%name = 'table'
   end function table_friction

   !> TABLE_FRICTION_OF_DECK: the law of a deck with friction_law = 'table':
   !> friction_file required and read (its problems named with the file's
   !> line).
   !>  d     [in]     the deck
   !>  errs  [in,out] problems are appended, naming deck, group, variable
   function table_friction_of_deck(d, errs) result(law)
      type(deck_type), intent(in) :: d
      type(error_list), intent(inout) :: errs
      type(table_friction_type) :: law
      real(dp), allocatable :: p(:), mu(:)
      character(len=1024) :: emsg
      if (len_trim(d%friction_file) == 0) then
         call fail(errs, at(trim(d%deck_file), 'tools', 'friction_file'), &
                   "must name a file with friction_law = 'table'")
         return
      end if
      call read_friction_table(trim(d%friction_file), p, mu, emsg)
      if (len_trim(emsg) > 0) then
         call fail(errs, at(trim(d%deck_file), 'tools', 'friction_file'), trim(emsg))
         return
      end if
      law = table_friction(p, mu, d%friction_eps*d%thickness)
   end function table_friction_of_deck

   !> TABLE_COEFFICIENT: friction_law_type's coefficient: linear between the
   !> points (the slope of the segment holding p; at a point, the segment
   !> above), constant beyond the ends (slope 0).
   pure subroutine table_coefficient(law, pressure, mu, dmu_dp)
      class(table_friction_type), intent(in) :: law
      real(dp), intent(in) :: pressure
      real(dp), intent(out) :: mu, dmu_dp
      integer :: n, lo, hi, mid
      n = size(law%p)
      dmu_dp = 0.0_dp
      if (n == 0) then
         mu = 0.0_dp
         return
      end if
      if (pressure <= law%p(1)) then
         mu = law%mu(1)
         return
      end if
      if (pressure >= law%p(n)) then
         mu = law%mu(n)
         return
      end if
      lo = 1
      hi = n
      do while (hi - lo > 1)
         mid = (lo + hi)/2
         if (pressure >= law%p(mid)) then
            lo = mid
         else
            hi = mid
         end if
      end do
      dmu_dp = (law%mu(hi) - law%mu(lo))/(law%p(hi) - law%p(lo))
      mu = law%mu(lo) + dmu_dp*(pressure - law%p(lo))
   end subroutine table_coefficient

   !> TABLE_ACTIVE: some point has mu > 0.
   pure logical function table_active(law)
      class(table_friction_type), intent(in) :: law
      table_active = .false.
      if (allocated(law%mu)) table_active = any(law%mu > 0.0_dp)
   end function table_active

   !> READ_FRICTION_TABLE: the points of a friction table file (module
   !> header).  Never stops the program.
   !>  path    [in]  file name
   !>  p, mu   [out] the points (allocated; size 0 on error)
   !>  errmsg  [out] blank on success, else the file, line and problem
   subroutine read_friction_table(path, p, mu, errmsg)
      character(len=*), intent(in) :: path
      real(dp), allocatable, intent(out) :: p(:), mu(:)
      character(len=*), intent(out) :: errmsg
      character(len=:), allocatable :: contents, why, line, at, msg
      real(dp), allocatable :: tmp(:)
      real(dp) :: x(2)
      integer :: ios, pos, nline, npt, ntok, k, first(2), last(2)
      msg = ''
      allocate (p(16), mu(16))
      npt = 0
      nline = 0
      call read_file(path, max_input_bytes, contents, ios, why)
      if (ios /= 0) then
         errmsg = "cannot read friction table '"//path//"': "//why
         deallocate (p, mu)
         allocate (p(0), mu(0))
         return
      end if
      pos = 1
      do while (pos <= len(contents))
         call next_line(contents, pos, line)
         nline = nline + 1
         at = "friction table '"//path//"' line "//itoa(nline)//': '
         if (len(line) > max_line_length) then
            msg = at//'longer than '//itoa(max_line_length)//' characters'
            exit
         end if
         line = strip_comment(line, '#')
         call split_fields(line, first, last, ntok)
         if (ntok == 0) cycle
         if (ntok /= 2) then
            msg = at//'expected 2 numbers (pressure in MPa, coefficient), found '//itoa(ntok)// &
                  " fields in '"//trim(adjustl(line))//"'"
            exit
         end if
         do k = 1, 2
            if (.not. parse_real(line(first(k):last(k)), x(k))) then
               msg = at//"cannot read '"//line(first(k):last(k))//"' as a number"
               exit
            end if
         end do
         if (len(msg) > 0) exit
         if (.not. x(1) >= 0.0_dp) then
            msg = at//'pressure must be >= 0 (found '//line(first(1):last(1))//')'
         else if (npt > 0 .and. .not. x(1) > p(max(npt, 1))) then
            msg = at//'pressure not increasing ('//line(first(1):last(1))//' after a larger or equal one)'
         else if (.not. (x(2) >= 0.0_dp .and. x(2) <= 10.0_dp)) then
            msg = at//'coefficient must be within 0 and 10 (found '//line(first(2):last(2))//')'
         end if
         if (len(msg) > 0) exit
         if (npt == size(p)) then
            allocate (tmp(2*npt))
            tmp(:npt) = p(:npt)
            call move_alloc(tmp, p)
            allocate (tmp(2*npt))
            tmp(:npt) = mu(:npt)
            call move_alloc(tmp, mu)
         end if
         npt = npt + 1
         p(npt) = x(1)
         mu(npt) = x(2)
      end do
      if (len(msg) == 0 .and. npt < 2) msg = "friction table '"//path// &
                                              "': need at least 2 points, found "//itoa(npt)
      errmsg = msg
      if (len(msg) > 0) then
         deallocate (p, mu)
         allocate (p(0), mu(0))
      else
         p = p(:npt)
         mu = mu(:npt)
      end if
   end subroutine read_friction_table
end module friction_table
