!> friction_table -- pressure-dependent friction from a table of pressure
!> against coefficient (the form friction-modelling tools export),
!> linear between the points and constant beyond the first and the last
!> (docs/theory.md §6.1; &tools friction_law = 'table', friction_file).
!>
!> The file: two columns, the contact pressure p (MPa) and the coefficient
!> mu, one point per line, read by module pair_file (as the hardening
!> curve files); at least 2 points, p >= 0 strictly increasing, mu within
!> 0 and 10.
module friction_table
   use kinds, only: dp
   use friction_law, only: friction_law_type
   use text, only: itoa
   use pair_file, only: read_pairs
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
      character(len=:), allocatable :: msg, at
      character(len=64), allocatable :: tok(:, :)
      integer, allocatable :: line_no(:)
      integer :: i, j
      call read_pairs(path, 'friction table', 'pressure in MPa, coefficient', p, mu, tok, line_no, msg)
      if (len(msg) == 0) then
         do i = 1, size(p)
            ! (Fortran's .and. may evaluate both sides: the point before is
            ! the point itself for the first)
            j = max(i - 1, 1)
            at = "friction table '"//path//"' line "//itoa(line_no(i))//': '
            if (.not. p(i) >= 0.0_dp) then
               msg = at//'pressure must be >= 0 (found '//trim(tok(1, i))//')'
            else if (i > 1 .and. .not. p(i) > p(j)) then
               msg = at//'pressure not increasing ('//trim(tok(1, i))//' after '//trim(tok(1, j))//')'
            else if (.not. (mu(i) >= 0.0_dp .and. mu(i) <= 10.0_dp)) then
               msg = at//'coefficient must be within 0 and 10 (found '//trim(tok(2, i))//')'
            end if
            if (len(msg) > 0) exit
         end do
      end if
      if (len(msg) == 0 .and. size(p) < 2) msg = "friction table '"//path// &
                                                 "': need at least 2 points, found "//itoa(size(p))
      errmsg = msg
      if (len(msg) > 0) then
         deallocate (p, mu)
         allocate (p(0), mu(0))
      end if
   end subroutine read_friction_table
end module friction_table
