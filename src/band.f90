!> band -- general band matrix in LAPACK storage, assembly and solve.
!>
!> Entry (i, j) of the n x n matrix is held in ab(kl + ku + 1 + i - j, j)
!> with kl rows of fill-in room on top, as dgbsv/dgbtrf require.
!> The matrix is non-symmetric in general (friction), so the LU of dgbtrf.
module band
   use kinds, only: dp
   use errors, only: alloc_message
   use text, only: itoa
   implicit none
   private
   public :: band_matrix, band_init, band_zero, band_add, band_fix_dof, &
             band_solve, band_get, band_matvec, band_error_message, band_size_error

   !> band_solve's info when the sizes do not fit (found before LAPACK is
   !> called; LAPACK's own argument errors are -1 ... -10)
   integer, parameter :: band_size_error = -1000

   type :: band_matrix
      integer :: n = 0, kl = 0, ku = 0, ldab = 0
      real(dp), allocatable :: ab(:, :)
      integer, allocatable :: ipiv(:)
   end type band_matrix

   interface
      subroutine dgbsv(n, kl, ku, nrhs, ab, ldab, ipiv, b, ldb, info)
         import :: dp
         integer, intent(in) :: n, kl, ku, nrhs, ldab, ldb
         real(dp), intent(inout) :: ab(ldab, *), b(ldb, *)
         integer, intent(out) :: ipiv(*), info
      end subroutine dgbsv
   end interface

contains

   !> BAND_INIT: allocate an n x n band matrix with kl sub- and ku super-diagonals.
   !>  a       [out] the matrix, zeroed
   !>  n, kl, ku [in] order and bandwidths (n >= 1, 0 <= kl, ku < n)
   !>  errmsg  [out] optional: '' or, when the allocation failed, the
   !>                message (errors' alloc_message; a is then empty);
   !>                without it a failed allocation stops the program
   subroutine band_init(a, n, kl, ku, errmsg)
      type(band_matrix), intent(out) :: a
      integer, intent(in) :: n, kl, ku
      character(len=:), allocatable, intent(out), optional :: errmsg
      integer :: stat
      a%n = n
      a%kl = min(kl, n - 1)
      a%ku = min(ku, n - 1)
      a%ldab = 2*a%kl + a%ku + 1
      if (present(errmsg)) then
         errmsg = ''
         allocate (a%ab(a%ldab, n), a%ipiv(n), stat=stat)
         if (stat /= 0) then
            errmsg = alloc_message('the band matrix of '//itoa(n)//' equations', &
                                   8.0_dp*real(a%ldab + 1, dp)*real(n, dp))
            return
         end if
      else
         allocate (a%ab(a%ldab, n), a%ipiv(n))
      end if
      a%ab = 0.0_dp
   end subroutine band_init

   !> BAND_ZERO: set every stored entry to zero.
   pure subroutine band_zero(a)
      type(band_matrix), intent(inout) :: a
      a%ab = 0.0_dp
   end subroutine band_zero

   !> BAND_ADD: scatter-add a dense element matrix ke(m, m) on the global dofs.
   !>  a     [in,out] global matrix
   !>  dofs  [in]  global equation numbers of the element dofs (m of them)
   !>  ke    [in]  element matrix; entries falling outside the band are an error
   !>  stat  [out] 0, or 1 if an entry lies outside the band
   pure subroutine band_add(a, dofs, ke, stat)
      type(band_matrix), intent(inout) :: a
      integer, intent(in) :: dofs(:)
      real(dp), intent(in) :: ke(:, :)
      integer, intent(out) :: stat
      integer :: p, q, i, j, off, n
      stat = 0
      off = a%kl + a%ku + 1
      n = size(dofs)
      ! an element's dofs are consecutive (node-by-node numbering): when they
      ! span no more than the band, every entry lies in it (no test per entry)
      if (n <= min(a%kl, a%ku) + 1) then
         if (all(dofs(2:n) - dofs(1:n - 1) == 1)) then
            do q = 1, n
               j = dofs(q)
               do p = 1, n
                  a%ab(off + p - q, j) = a%ab(off + p - q, j) + ke(p, q)
               end do
            end do
            return
         end if
      end if
      do q = 1, size(dofs)
         j = dofs(q)
         do p = 1, size(dofs)
            i = dofs(p)
            if (i - j > a%kl .or. j - i > a%ku) then
               if (abs(ke(p, q)) > 0.0_dp) stat = 1
               cycle
            end if
            a%ab(off + i - j, j) = a%ab(off + i - j, j) + ke(p, q)
         end do
      end do
   end subroutine band_add

   !> BAND_FIX_DOF: replace equation i by u_i = (right-hand side), i.e. zero
   !> row i and put 1 on the diagonal (the column is left: the prescribed
   !> correction is zero, so it multiplies nothing).
   pure subroutine band_fix_dof(a, i)
      type(band_matrix), intent(inout) :: a
      integer, intent(in) :: i
      integer :: j, off
      off = a%kl + a%ku + 1
      do j = max(1, i - a%kl), min(a%n, i + a%ku)
         a%ab(off + i - j, j) = 0.0_dp
      end do
      a%ab(off, i) = 1.0_dp
   end subroutine band_fix_dof

   !> BAND_GET: entry (i, j) of the matrix (zero outside the band).
   pure function band_get(a, i, j) result(aij)
      type(band_matrix), intent(in) :: a
      integer, intent(in) :: i, j
      real(dp) :: aij
      if (i - j > a%kl .or. j - i > a%ku) then
         aij = 0.0_dp
      else
         aij = a%ab(a%kl + a%ku + 1 + i - j, j)
      end if
   end function band_get

   !> BAND_MATVEC: y = A x (before factorization).
   pure subroutine band_matvec(a, x, y)
      type(band_matrix), intent(in) :: a
      real(dp), intent(in) :: x(:)
      real(dp), intent(out) :: y(:)
      integer :: i, j, off
      off = a%kl + a%ku + 1
      y = 0.0_dp
      do j = 1, a%n
         do i = max(1, j - a%ku), min(a%n, j + a%kl)
            y(i) = y(i) + a%ab(off + i - j, j)*x(j)
         end do
      end do
   end subroutine band_matvec

   !> BAND_SOLVE: solve A x = b with LAPACK dgbsv (LU with partial pivoting).
   !> The matrix is overwritten by its factors.
   !>  a     [in,out] matrix; factors on exit
   !>  b     [in,out] right-hand side; solution on exit
   !>  info  [out] 0 success; i > 0: U(i,i) is exactly zero, the matrix is
   !>        singular and b is unchanged in meaning; band_size_error: the
   !>        sizes do not fit (caught here before LAPACK's XERBLA could stop
   !>        the program).  band_error_message turns it into a message.
   subroutine band_solve(a, b, info)
      type(band_matrix), intent(inout) :: a
      real(dp), intent(inout) :: b(:)
      integer, intent(out) :: info
      if (a%n < 1 .or. size(b) /= a%n .or. .not. allocated(a%ab) .or. &
          a%ldab < 2*a%kl + a%ku + 1) then
         info = band_size_error
         return
      end if
      call dgbsv(a%n, a%kl, a%ku, 1, a%ab, a%ldab, a%ipiv, b, a%n, info)
   end subroutine band_solve

   !> BAND_ERROR_MESSAGE: what a non-zero info of band_solve means, the one
   !> place where LAPACK's info is translated.
   !>  info  [in] band_solve's info
   pure function band_error_message(info) result(msg)
      integer, intent(in) :: info
      character(len=:), allocatable :: msg
      character(len=12) :: num
      write (num, '(i0)') abs(info)
      if (info > 0) then
         msg = 'band_solve: the tangent is singular (dgbsv: U('//trim(num)//','//trim(num)// &
               ') is exactly zero)'
      else if (info == band_size_error) then
         msg = 'band_solve: the matrix and right-hand side sizes do not fit (a programming error)'
      else if (info < 0) then
         msg = 'band_solve: dgbsv argument '//trim(num)//' has an illegal value (a programming error)'
      else
         msg = 'band_solve: no error'
      end if
   end function band_error_message
end module band
