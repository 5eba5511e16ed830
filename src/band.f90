!> band -- general band matrix in LAPACK storage, assembly and solve.
!>
!> Entry (i, j) of the n x n matrix is held in ab(kl + ku + 1 + i - j, j)
!> with kl rows of fill-in room on top, as dgbsv/dgbtrf require.
!> The matrix is non-symmetric in general (friction), so the LU with
!> partial pivoting of dgbtrf (band_solve: LAPACK's algorithm written out).
module band
   use kinds, only: dp
   implicit none
   private
   public :: band_matrix, band_init, band_zero, band_add, band_fix_dof, &
             band_solve, band_get, band_matvec, band_error_message, band_size_error

   !> band_solve's info when the sizes do not fit (found before anything is
   !> computed; band_error_message also names LAPACK's argument errors,
   !> -1 ... -10, for a caller of dgbsv)
   integer, parameter :: band_size_error = -1000

   type :: band_matrix
      integer :: n = 0, kl = 0, ku = 0, ldab = 0
      real(dp), allocatable :: ab(:, :)
      integer, allocatable :: ipiv(:)
   end type band_matrix

contains

   !> BAND_INIT: allocate an n x n band matrix with kl sub- and ku super-diagonals.
   !>  a   [out] the matrix, zeroed
   !>  n, kl, ku [in] order and bandwidths (n >= 1, 0 <= kl, ku < n)
   subroutine band_init(a, n, kl, ku)
      type(band_matrix), intent(out) :: a
      integer, intent(in) :: n, kl, ku
      a%n = n
      a%kl = min(kl, n - 1)
      a%ku = min(ku, n - 1)
      a%ldab = 2*a%kl + a%ku + 1
      allocate (a%ab(a%ldab, n), a%ipiv(n))
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

   !> BAND_SOLVE: solve A x = b by LU with partial pivoting in the band
   !> storage: LAPACK's dgbsv (unblocked dgbtf2, then dgbtrs) step for step,
   !> written out here because the band is narrow (kl = ku = 7 for the
   !> shell): LAPACK's level-2 BLAS calls per column (idamax, dswap, dscal,
   !> dger on vectors of 7 to 15 entries) cost about three times the
   !> arithmetic (docs/performance.md).  The same pivots and the same
   !> operations in the same order; only the rounding of a*b + c may differ
   !> (the compiler may fuse it), so the solution agrees with dgbsv's to
   !> round-off (tests/unit/test_band.pf checks it against dgbsv).  (Zero
   !> tests are written abs(x) > 0: a NaN pivot is reported as singular,
   !> where dgbsv would carry it into the solution.)
   !> The matrix is overwritten by its factors (LAPACK's layout: U in rows
   !> 1 .. kl + ku + 1, the multipliers below, the row interchanges in ipiv).
   !>  a     [in,out] matrix; factors on exit
   !>  b     [in,out] right-hand side; solution on exit
   !>  info  [out] 0 success; i > 0: U(i,i) is exactly zero, the matrix is
   !>        singular and b is unchanged; band_size_error: the sizes do not
   !>        fit (the matrix is left as it was).  band_error_message turns it
   !>        into a message.
   pure subroutine band_solve(a, b, info)
      type(band_matrix), intent(inout) :: a
      real(dp), intent(inout) :: b(:)
      integer, intent(out) :: info
      if (a%n < 1 .or. size(b) /= a%n .or. .not. allocated(a%ab) .or. &
          a%ldab < 2*a%kl + a%ku + 1) then
         info = band_size_error
         return
      end if
      call band_factor(a%n, a%kl, a%ku, a%ldab, a%ab, a%ipiv, info)
      if (info /= 0) return
      call band_substitute(a%n, a%kl, a%ku, a%ldab, a%ab, a%ipiv, b)
   end subroutine band_solve

   !> BAND_FACTOR: LU factorization with partial pivoting of a band matrix
   !> in LAPACK storage (dgbtf2's algorithm and order of operations).
   !> (Explicit-shape arrays: the compiler knows the columns are contiguous
   !> and vectorizes the column updates.)
   !>  n, kl, ku [in] order and bandwidths
   !>  ldab  [in] leading dimension of ab, >= 2 kl + ku + 1
   !>  ab    [in,out] (ldab, n) the matrix; its factors on exit
   !>  ipiv  [out] row i was interchanged with row ipiv(i)
   !>  info  [out] 0, or the first i with U(i,i) exactly zero
   pure subroutine band_factor(n, kl, ku, ldab, ab, ipiv, info)
      integer, intent(in) :: n, kl, ku, ldab
      real(dp), intent(inout) :: ab(ldab, n)
      integer, intent(out) :: ipiv(n), info
      integer :: i, j, jj, jp, ju, km, kv, off
      real(dp) :: amax, r, temp
      info = 0
      kv = ku + kl
      ! the fill-in rows above the band start at zero
      do j = ku + 2, min(kv, n)
         do i = kv - j + 2, kl
            ab(i, j) = 0.0_dp
         end do
      end do
      ju = 1
      do j = 1, n
         if (j + kv <= n) ab(1:kl, j + kv) = 0.0_dp
         km = min(kl, n - j)
         ! the pivot: the first largest |entry| on and below the diagonal
         jp = 1
         amax = abs(ab(kv + 1, j))
         do i = 2, km + 1
            if (abs(ab(kv + i, j)) > amax) then
               jp = i
               amax = abs(ab(kv + i, j))
            end if
         end do
         ipiv(j) = jp + j - 1
         if (abs(ab(kv + jp, j)) > 0.0_dp) then
            ju = max(ju, min(j + ku + jp - 1, n))
            if (jp /= 1) then
               ! swap rows j and j + jp - 1 over columns j .. ju
               do jj = j, ju
                  off = jj - j
                  temp = ab(kv + jp - off, jj)
                  ab(kv + jp - off, jj) = ab(kv + 1 - off, jj)
                  ab(kv + 1 - off, jj) = temp
               end do
            end if
            if (km > 0) then
               r = 1.0_dp/ab(kv + 1, j)
               ab(kv + 2:kv + km + 1, j) = r*ab(kv + 2:kv + km + 1, j)
               ! rank-1 update of the trailing block (dger with alpha = -1)
               do jj = j + 1, ju
                  off = jj - j
                  temp = -ab(kv + 1 - off, jj)
                  if (.not. abs(temp) > 0.0_dp) cycle
                  do i = 1, km
                     ab(kv + 1 - off + i, jj) = ab(kv + 1 - off + i, jj) + ab(kv + 1 + i, j)*temp
                  end do
               end do
            end if
         else if (info == 0) then
            info = j
         end if
      end do
   end subroutine band_factor

   !> BAND_SUBSTITUTE: solve with the factors of band_factor (dgbtrs for one
   !> right-hand side, no transpose: L then U, the order of dtbsv).
   !>  n, kl, ku [in] order and bandwidths
   !>  ldab  [in] leading dimension of ab
   !>  ab    [in] (ldab, n) the factors
   !>  ipiv  [in] the row interchanges
   !>  b     [in,out] right-hand side; solution on exit
   pure subroutine band_substitute(n, kl, ku, ldab, ab, ipiv, b)
      integer, intent(in) :: n, kl, ku, ldab
      real(dp), intent(in) :: ab(ldab, n)
      integer, intent(in) :: ipiv(n)
      real(dp), intent(inout) :: b(n)
      integer :: i, j, l, lm, kd, k
      real(dp) :: temp
      kd = ku + kl + 1
      do j = 1, n - 1
         lm = min(kl, n - j)
         l = ipiv(j)
         if (l /= j) then
            temp = b(l)
            b(l) = b(j)
            b(j) = temp
         end if
         temp = -b(j)
         if (abs(temp) > 0.0_dp) then
            do i = 1, lm
               b(j + i) = b(j + i) + ab(kd + i, j)*temp
            end do
         end if
      end do
      ! U x = b, U with kl + ku superdiagonals
      k = kl + ku
      do j = n, 1, -1
         if (abs(b(j)) > 0.0_dp) then
            l = k + 1 - j
            b(j) = b(j)/ab(k + 1, j)
            temp = b(j)
            do i = j - 1, max(1, j - k), -1
               b(i) = b(i) - temp*ab(l + i, j)
            end do
         end if
      end do
   end subroutine band_substitute

   !> BAND_ERROR_MESSAGE: what a non-zero info of band_solve means, the one
   !> place where LAPACK's info is translated.
   !>  info  [in] band_solve's info
   pure function band_error_message(info) result(msg)
      integer, intent(in) :: info
      character(len=:), allocatable :: msg
      character(len=12) :: num
      write (num, '(i0)') abs(info)
      if (info > 0) then
         msg = 'band_solve: the tangent is singular (U('//trim(num)//','//trim(num)// &
               ') of its LU factors is exactly zero)'
      else if (info == band_size_error) then
         msg = 'band_solve: the matrix and right-hand side sizes do not fit (a programming error)'
      else if (info < 0) then
         msg = 'band_solve: dgbsv argument '//trim(num)//' has an illegal value (a programming error)'
      else
         msg = 'band_solve: no error'
      end if
   end function band_error_message
end module band
