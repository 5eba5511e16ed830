!> funit (lite) -- a small stand-in for pFUnit's `funit` module.
!>
!> Purpose
!>    Lets the tests/test_*.pf suites build and run when pFUnit is not
!>    installed.  tests/pfunit_lite.py turns each `@assertXxx(...)` line into
!>       call assertXxx(..., location=SourceLocation('<file>.pf', <line>)); if (anyExceptions()) return
!>    and writes a driver program that calls funit_run_test for every test.
!>    The generic names and the keyword names (tolerance=, message=,
!>    location=) are pFUnit's, so a suite that builds here builds there.
!>
!> What a failing assertion does
!>    Prints the suite, the test, the .pf file and line, the assertion and
!>    the expected/actual values to standard output, and raises the
!>    module-level failure flag (anyExceptions() returns .true.).  The
!>    generated code then returns from the test; the driver counts the test
!>    as failed and goes on with the next one.
!>
!> Comparisons
!>    assertEqual for reals: pass if |expected - actual| <= tolerance
!>    (elementwise for arrays; tolerance 0 when not given).  NaN never
!>    passes; infinities pass only against the same infinity.  assertRelativelyEqual: pass if |e - a| <= tolerance*|e|; an
!>    expected value of 0 fails (as in pFUnit).  Character strings are
!>    compared exactly after removing leading and trailing blanks (pFUnit's
!>    default).
!>
!> Names of the real funit (reserved here)
!>    pFUnit's `funit` (4.14, built with its defaults, so with fHamcrest)
!>    exports about a hundred names besides the assertions: fHamcrest's
!>    matchers (is, equal_to, not, near, any_of, ...), pFUnit's classes
!>    (Test, TestCase, TestSuite, ...) and procedures (run, initialize, ...).
!>    A test that declares a local of one of these names breaks there: with
!>    gfortran 12 a local `integer :: is` passed as an actual argument is
!>    read as fHamcrest's derived type `Is` ("Derived type 'is' is used as
!>    an actual argument").  So that the same test breaks here first, this
!>    module exports every one of those names too, as an empty derived type
!>    (most of them are derived types there; none of them does anything
!>    here), and tests/pfunit_lite.py puts `use funit` into every procedure
!>    of a converted test, where a local of a reserved name is a plain
!>    compile error ("Symbol 'is' ... conflicts with symbol from module
!>    'funit'").  The only intrinsic among them, NOT, is therefore hidden
!>    in the tests (pFUnit's generic `not` extends it; use IEOR(i, -1)).
!>
!>    Where the list comes from: the installed module of pFUnit 4.14.0
!>    (fArgParse 1.10.0, gFTL-shared 1.11.0, gFTL 1.15.2; cmake -DSKIP_MPI=YES
!>    -DSKIP_OPENMP=YES -DSKIP_ESMF=YES, all else default), listed with
!>       printf 'program p\nuse funit\nend program p\n' > p.f90
!>       gfortran -fsyntax-only -fdump-fortran-original \
!>          -I$PFUNIT_DIR/include p.f90 | sed -n "s/^ *symtree: '\([A-Za-z]\w*\)'.*/\1/p"
!>    (101 names: the 13 this module implements, the 84 below, output_unit,
!>    which is iso_fortran_env's here as there, and the module names funit,
!>    fhamcrest and iso_fortran_env).  The fHamcrest names agree with the
!>    `public` statements of pFUnit's src/funit/fhamcrest/*.F90.  Redo the
!>    listing when pFUnit is upgraded.
!>
!> Standard Fortran 2008 only (no compiler extensions).
module funit
   use, intrinsic :: iso_fortran_env, only: real64, output_unit
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite
   implicit none
   private

   public :: SourceLocation, anyExceptions, throw
   public :: assertEqual, assertTrue, assertFalse
   public :: assertLessThan, assertLessThanOrEqual
   public :: assertGreaterThan, assertGreaterThanOrEqual
   public :: assertRelativelyEqual, assertIsNaN, assertIsFinite
   public :: funit_test_proc, funit_run_test, funit_skip_test, funit_summary
   public :: output_unit

   ! Reserved names of the real funit (see the header): fHamcrest's
   ! matchers, matcher types and assert_that.
   type, public :: AbstractMatcher; end type AbstractMatcher
   type, public :: AllOf; end type AllOf
   type, public :: all_of; end type all_of
   type, public :: AnyOf; end type AnyOf
   type, public :: any_of; end type any_of
   type, public :: array_with_size; end type array_with_size
   type, public :: assert_that; end type assert_that
   type, public :: contains_string; end type contains_string
   type, public :: empty_array; end type empty_array
   type, public :: ends_with; end type ends_with
   type, public :: equal_to; end type equal_to
   type, public :: Every; end type Every
   type, public :: every_item; end type every_item
   type, public :: false; end type false
   type, public :: Is; end type Is
   type, public :: IsArrayWithSize; end type IsArrayWithSize
   type, public :: IsEqual; end type IsEqual
   type, public :: IsNear; end type IsNear
   type, public :: IsNot; end type IsNot
   type, public :: IsRelativelyNear; end type IsRelativelyNear
   type, public :: IsTrueOrFalse; end type IsTrueOrFalse
   type, public :: Matchable; end type Matchable
   type, public :: MatcherDescription; end type MatcherDescription
   type, public :: near; end type near
   type, public :: not; end type not
   type, public :: relatively_near; end type relatively_near
   type, public :: starts_with; end type starts_with
   type, public :: StringContains; end type StringContains
   type, public :: StringDescription; end type StringDescription
   type, public :: StringEndsWith; end type StringEndsWith
   type, public :: StringStartsWith; end type StringStartsWith
   type, public :: true; end type true

   ! Reserved names: pFUnit's classes and procedures (FUnit_Core, FUnit).
   type, public :: AbstractTestParameter; end type AbstractTestParameter
   type, public :: BaseTestRunner; end type BaseTestRunner
   type, public :: catch; end type catch
   type, public :: catchNext; end type catchNext
   type, public :: DebugListener; end type DebugListener
   type, public :: disable; end type disable
   type, public :: Expectation; end type Expectation
   type, public :: finalize; end type finalize
   type, public :: generic_run; end type generic_run
   type, public :: get_context; end type get_context
   type, public :: ignore_all; end type ignore_all
   type, public :: ignore_differences; end type ignore_differences
   type, public :: initialize; end type initialize
   type, public :: keep_all; end type keep_all
   type, public :: ListenerPointer; end type ListenerPointer
   type, public :: LoadTests_interface; end type LoadTests_interface
   type, public :: NameFilter; end type NameFilter
   type, public :: ParallelContext; end type ParallelContext
   type, public :: ParameterizedTestCase; end type ParameterizedTestCase
   type, public :: Predicate; end type Predicate
   type, public :: RemoteRunner; end type RemoteRunner
   type, public :: ResultPrinter; end type ResultPrinter
   type, public :: RobustRunner; end type RobustRunner
   type, public :: run; end type run
   type, public :: SerialContext; end type SerialContext
   type, public :: stub; end type stub
   type, public :: Subject; end type Subject
   type, public :: TapListener; end type TapListener
   type, public :: Test; end type Test
   type, public :: TestAnnotation; end type TestAnnotation
   type, public :: TestCase; end type TestCase
   type, public :: TestListener; end type TestListener
   type, public :: TestListenerVector; end type TestListenerVector
   type, public :: TestMethod; end type TestMethod
   type, public :: TestResult; end type TestResult
   type, public :: TestRunner; end type TestRunner
   type, public :: TestSuite; end type TestSuite
   type, public :: TimeoutAnnotation; end type TimeoutAnnotation
   type, public :: trim_all; end type trim_all
   type, public :: WasCalled; end type WasCalled
   type, public :: WasCalledOnce; end type WasCalledOnce
   type, public :: WasNotCalled; end type WasNotCalled
   type, public :: WhitespaceOptions; end type WhitespaceOptions
   type, public :: XmlPrinter; end type XmlPrinter

   ! Reserved names: pFUnit's assertions that this module does not
   ! implement (pfunit_lite.py rejects their directives).
   type, public :: assertAll; end type assertAll
   type, public :: assertAny; end type assertAny
   type, public :: assertExceptionRaised; end type assertExceptionRaised
   type, public :: assertFail; end type assertFail
   type, public :: assertNone; end type assertNone
   type, public :: assertNotAll; end type assertNotAll
   type, public :: assertNotEqual; end type assertNotEqual
   type, public :: assertSameShape; end type assertSameShape

   integer, parameter :: wp = real64
   character(len=*), parameter :: rfmt = '(a,es24.16e3)'

   !> Where an assertion is written (file and line of the .pf source).
   type :: SourceLocation
      character(len=256) :: fileName = ''
      integer :: lineNumber = 0
   end type SourceLocation

   !> Like pFUnit's KeywordEnforcer: an optional dummy that no actual
   !> argument can match, so that message= must be given by keyword.
   type :: KeywordEnforcer
      private
      integer :: unused = 0
   end type KeywordEnforcer

   abstract interface
      subroutine funit_test_proc()
      end subroutine funit_test_proc
   end interface

   ! As in pFUnit, each real variant comes twice: with a (non-optional)
   ! tolerance, and without one (tolerance 0).
   interface assertEqual
      module procedure assert_equal_int, assert_equal_int_1d
      module procedure assert_equal_int_r64, assert_equal_int_r64_tol
      module procedure assert_equal_r64, assert_equal_r64_tol
      module procedure assert_equal_r64_1d, assert_equal_r64_1d_tol
      module procedure assert_equal_r64_2d, assert_equal_r64_2d_tol
      module procedure assert_equal_r64_0d_1d, assert_equal_r64_0d_1d_tol
      module procedure assert_equal_r64_0d_2d, assert_equal_r64_0d_2d_tol
      module procedure assert_equal_string
   end interface assertEqual

   interface assertRelativelyEqual
      module procedure assert_rel_equal_r64, assert_rel_equal_r64_1d
   end interface assertRelativelyEqual

   interface assertLessThan
      module procedure assert_lt_int, assert_lt_r64
   end interface assertLessThan

   interface assertLessThanOrEqual
      module procedure assert_le_int, assert_le_r64
   end interface assertLessThanOrEqual

   interface assertGreaterThan
      module procedure assert_gt_int, assert_gt_r64
   end interface assertGreaterThan

   interface assertGreaterThanOrEqual
      module procedure assert_ge_int, assert_ge_r64
   end interface assertGreaterThanOrEqual

   ! State of the run
   logical :: failed = .false.                       ! current test has failed
   character(len=:), allocatable :: cur_suite, cur_test, cur_file
   integer :: n_passed = 0, n_failed = 0, n_disabled = 0
   logical :: filter_read = .false.
   character(len=:), allocatable :: filter          ! from the command line

contains

   ! ------------------------------------------------------------------
   ! Running tests
   ! ------------------------------------------------------------------

   !> Run one test: setup, test (unless setup failed), teardown; count it.
   !>   suite, test_name [in]  names printed in failure reports
   !>   pf_file          [in]  .pf file that holds the test
   !>   test             [in]  the test procedure
   !>   setup, teardown  [in]  optional @before / @after procedures
   subroutine funit_run_test(suite, test_name, pf_file, test, setup, teardown)
      character(len=*), intent(in) :: suite, test_name, pf_file
      procedure(funit_test_proc) :: test
      procedure(funit_test_proc), optional :: setup, teardown

      if (.not. selected(suite, test_name)) return
      cur_suite = suite
      cur_test = test_name
      cur_file = pf_file
      failed = .false.
      if (present(setup)) call setup()
      if (.not. failed) call test()
      if (present(teardown)) call teardown()
      if (failed) then
         n_failed = n_failed + 1
      else
         n_passed = n_passed + 1
      end if
      flush (output_unit)
   end subroutine funit_run_test

   !> Count a disabled test (@test, then @disable) without running it.
   subroutine funit_skip_test(suite, test_name)
      character(len=*), intent(in) :: suite, test_name
      if (.not. selected(suite, test_name)) return
      n_disabled = n_disabled + 1
   end subroutine funit_skip_test

   !> Print the result; the LAST line is exactly "N passed, M failed".
   !>   nfail [out]  number of failed tests
   subroutine funit_summary(nfail)
      integer, intent(out) :: nfail
      if (n_disabled > 0) write (output_unit, '(i0,a)') n_disabled, ' disabled'
      write (output_unit, '(i0,a,i0,a)') n_passed, ' passed, ', n_failed, ' failed'
      flush (output_unit)
      nfail = n_failed
   end subroutine funit_summary

   !> The first command-line argument, if any, selects the tests whose
   !> "suite.test" name contains it.
   logical function selected(suite, test_name)
      character(len=*), intent(in) :: suite, test_name
      integer :: n
      if (.not. filter_read) then
         filter_read = .true.
         call get_command_argument(1, length=n)
         allocate (character(len=n) :: filter)
         if (n > 0) call get_command_argument(1, filter)
      end if
      selected = len(filter) == 0 .or. index(suite//'.'//test_name, filter) > 0
   end function selected

   !> .true. once an assertion in the current test has failed.
   logical function anyExceptions()
      anyExceptions = failed
   end function anyExceptions

   !> Fail the current test with a message (like pFUnit's throw).
   subroutine throw(message, location)
      character(len=*), intent(in) :: message
      type(SourceLocation), intent(in), optional :: location
      call fail_header('throw', location)
      write (output_unit, '(2a)') '   message: ', message
   end subroutine throw

   ! ------------------------------------------------------------------
   ! Reporting helpers
   ! ------------------------------------------------------------------

   !> Raise the failure flag and print "FAIL suite.test (file:line) assertion".
   subroutine fail_header(what, location, message)
      character(len=*), intent(in) :: what
      type(SourceLocation), intent(in), optional :: location
      character(len=*), intent(in), optional :: message
      character(len=:), allocatable :: file
      character(len=21) :: line

      failed = .true.
      if (.not. allocated(cur_suite)) then
         cur_suite = '?'
         cur_test = '?'
         cur_file = '?'
      end if
      file = cur_file
      line = ''
      if (present(location)) then
         if (len_trim(location%fileName) > 0) file = trim(location%fileName)
         if (location%lineNumber > 0) write (line, '(a,i0)') ':', location%lineNumber
      end if
      write (output_unit, '(8a)') 'FAIL ', cur_suite, '.', cur_test, &
         ' (', file, trim(line), ')'
      write (output_unit, '(3a)') '   ', what, ' failed'
      if (present(message)) then
         if (len(message) > 0) write (output_unit, '(2a)') '   message:   ', message
      end if
   end subroutine fail_header

   !> |e - a| <= tol without overflow or invalid operations (safe under
   !> -ffpe-trap): halving both sides is exact for normal numbers.
   elemental logical function close_abs(e, a, tol)
      real(wp), intent(in) :: e, a, tol
      if (ieee_is_nan(e) .or. ieee_is_nan(a)) then
         close_abs = .false.
      else if (ieee_is_finite(e) .and. ieee_is_finite(a)) then
         close_abs = abs(0.5_wp*e - 0.5_wp*a) <= 0.5_wp*tol
      else
         close_abs = same_infinity(e, a)
      end if
   end function close_abs

   !> |e - a| <= tol*|e|, and e /= 0.
   elemental logical function close_rel(e, a, tol)
      real(wp), intent(in) :: e, a, tol
      if (ieee_is_nan(e) .or. ieee_is_nan(a)) then
         close_rel = .false.
      else if (.not. abs(e) > 0.0_wp) then
         close_rel = .false.
      else if (ieee_is_finite(e) .and. ieee_is_finite(a)) then
         close_rel = abs(0.5_wp*e - 0.5_wp*a) <= tol*abs(0.5_wp*e)
      else
         close_rel = same_infinity(e, a)
      end if
   end function close_rel

   !> Both e and a are infinite with the same sign (neither is NaN).
   elemental logical function same_infinity(e, a)
      real(wp), intent(in) :: e, a
      same_infinity = .not. (ieee_is_finite(e) .or. ieee_is_finite(a)) &
         .and. ((e > 0.0_wp) .eqv. (a > 0.0_wp))
   end function same_infinity

   subroutine report_real(e, a, tol, tol_name)
      real(wp), intent(in) :: e, a, tol
      character(len=*), intent(in) :: tol_name
      write (output_unit, rfmt) '   expected:  ', e
      write (output_unit, rfmt) '   actual:    ', a
      if (.not. (ieee_is_nan(e) .or. ieee_is_nan(a))) then
         if (ieee_is_finite(e) .and. ieee_is_finite(a)) then
            if (abs(0.5_wp*e - 0.5_wp*a) <= 0.5_wp*huge(e)) &
               write (output_unit, rfmt) '   |e - a|:   ', abs(0.5_wp*e - 0.5_wp*a)*2.0_wp
         end if
      end if
      write (output_unit, rfmt) '   '//tol_name, tol
   end subroutine report_real

   subroutine report_shape(e_shape, a_shape)
      integer, intent(in) :: e_shape(:), a_shape(:)
      write (output_unit, '(a,*(1x,i0))') '   shapes differ: expected', e_shape
      write (output_unit, '(a,*(1x,i0))') '                  actual  ', a_shape
   end subroutine report_shape

   subroutine report_count(nbad, ntot)
      integer, intent(in) :: nbad, ntot
      write (output_unit, '(a,i0,a,i0,a)') '   ', nbad, ' of ', ntot, &
         ' entries differ; first one:'
   end subroutine report_count

   ! ------------------------------------------------------------------
   ! assertTrue / assertFalse
   ! ------------------------------------------------------------------

   subroutine assertTrue(condition, message, location)
      logical, intent(in) :: condition
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (condition) return
      call fail_header('assertTrue', location, message)
      write (output_unit, '(a)') '   expected .true., got .false.'
   end subroutine assertTrue

   subroutine assertFalse(condition, message, location)
      logical, intent(in) :: condition
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (.not. condition) return
      call fail_header('assertFalse', location, message)
      write (output_unit, '(a)') '   expected .false., got .true.'
   end subroutine assertFalse

   ! ------------------------------------------------------------------
   ! assertEqual
   ! ------------------------------------------------------------------

   subroutine assert_equal_int(expected, actual, message, location)
      integer, intent(in) :: expected, actual
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (expected == actual) return
      call fail_header('assertEqual', location, message)
      write (output_unit, '(a,i0)') '   expected:  ', expected
      write (output_unit, '(a,i0)') '   actual:    ', actual
   end subroutine assert_equal_int

   subroutine assert_equal_int_1d(expected, actual, message, location)
      integer, intent(in) :: expected(:), actual(:)
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      integer :: i
      if (size(expected) /= size(actual)) then
         call fail_header('assertEqual', location, message)
         call report_shape(shape(expected), shape(actual))
         return
      end if
      if (all(expected == actual)) return
      call fail_header('assertEqual', location, message)
      call report_count(count(expected /= actual), size(expected))
      do i = 1, size(expected)
         if (expected(i) /= actual(i)) exit
      end do
      write (output_unit, '(a,i0,a,i0)') '   expected(', i, '): ', expected(i)
      write (output_unit, '(a,i0,a,i0)') '   actual(', i, '):   ', actual(i)
   end subroutine assert_equal_int_1d

   subroutine assert_equal_int_r64(expected, actual, message, location)
      integer, intent(in) :: expected
      real(wp), intent(in) :: actual
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call assert_equal_r64_tol(real(expected, wp), actual, 0.0_wp, message, location)
   end subroutine assert_equal_int_r64

   subroutine assert_equal_int_r64_tol(expected, actual, tolerance, message, location)
      integer, intent(in) :: expected
      real(wp), intent(in) :: actual, tolerance
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call assert_equal_r64_tol(real(expected, wp), actual, tolerance, message, location)
   end subroutine assert_equal_int_r64_tol

   subroutine assert_equal_r64(expected, actual, message, location)
      real(wp), intent(in) :: expected, actual
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call assert_equal_r64_tol(expected, actual, 0.0_wp, message, location)
   end subroutine assert_equal_r64

   subroutine assert_equal_r64_tol(expected, actual, tolerance, message, location)
      real(wp), intent(in) :: expected, actual, tolerance
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (close_abs(expected, actual, tolerance)) return
      call fail_header('assertEqual', location, message)
      call report_real(expected, actual, tolerance, 'tolerance: ')
   end subroutine assert_equal_r64_tol

   subroutine assert_equal_r64_1d(expected, actual, message, location)
      real(wp), intent(in) :: expected(:), actual(:)
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call assert_equal_r64_1d_tol(expected, actual, 0.0_wp, message, location)
   end subroutine assert_equal_r64_1d

   subroutine assert_equal_r64_1d_tol(expected, actual, tolerance, message, location)
      real(wp), intent(in) :: expected(:), actual(:), tolerance
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      logical :: ok(size(expected))
      integer :: i
      if (size(expected) /= size(actual)) then
         call fail_header('assertEqual', location, message)
         call report_shape(shape(expected), shape(actual))
         return
      end if
      ok = close_abs(expected, actual, tolerance)
      if (all(ok)) return
      call fail_header('assertEqual', location, message)
      call report_count(count(.not. ok), size(ok))
      do i = 1, size(ok)
         if (.not. ok(i)) exit
      end do
      write (output_unit, '(a,i0,a)') '   at index (', i, ')'
      call report_real(expected(i), actual(i), tolerance, 'tolerance: ')
   end subroutine assert_equal_r64_1d_tol

   subroutine assert_equal_r64_2d(expected, actual, message, location)
      real(wp), intent(in) :: expected(:, :), actual(:, :)
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call assert_equal_r64_2d_tol(expected, actual, 0.0_wp, message, location)
   end subroutine assert_equal_r64_2d

   subroutine assert_equal_r64_2d_tol(expected, actual, tolerance, message, location)
      real(wp), intent(in) :: expected(:, :), actual(:, :), tolerance
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      logical :: ok(size(expected, 1), size(expected, 2))
      integer :: i, j
      if (any(shape(expected) /= shape(actual))) then
         call fail_header('assertEqual', location, message)
         call report_shape(shape(expected), shape(actual))
         return
      end if
      ok = close_abs(expected, actual, tolerance)
      if (all(ok)) return
      call fail_header('assertEqual', location, message)
      call report_count(count(.not. ok), size(ok))
      outer: do j = 1, size(ok, 2)
         do i = 1, size(ok, 1)
            if (.not. ok(i, j)) exit outer
         end do
      end do outer
      write (output_unit, '(a,i0,a,i0,a)') '   at index (', i, ',', j, ')'
      call report_real(expected(i, j), actual(i, j), tolerance, 'tolerance: ')
   end subroutine assert_equal_r64_2d_tol

   subroutine assert_equal_r64_0d_1d(expected, actual, message, location)
      real(wp), intent(in) :: expected, actual(:)
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call assert_equal_r64_1d_tol(spread(expected, 1, size(actual)), actual, &
         0.0_wp, message, location)
   end subroutine assert_equal_r64_0d_1d

   subroutine assert_equal_r64_0d_1d_tol(expected, actual, tolerance, message, location)
      real(wp), intent(in) :: expected, actual(:), tolerance
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call assert_equal_r64_1d_tol(spread(expected, 1, size(actual)), actual, &
         tolerance, message, location)
   end subroutine assert_equal_r64_0d_1d_tol

   subroutine assert_equal_r64_0d_2d(expected, actual, message, location)
      real(wp), intent(in) :: expected, actual(:, :)
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call assert_equal_r64_0d_2d_tol(expected, actual, 0.0_wp, message, location)
   end subroutine assert_equal_r64_0d_2d

   subroutine assert_equal_r64_0d_2d_tol(expected, actual, tolerance, message, location)
      real(wp), intent(in) :: expected, actual(:, :), tolerance
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      real(wp) :: e(size(actual, 1), size(actual, 2))
      e = expected
      call assert_equal_r64_2d_tol(e, actual, tolerance, message, location)
   end subroutine assert_equal_r64_0d_2d_tol

   subroutine assert_equal_string(expected, actual, message, location)
      character(len=*), intent(in) :: expected, actual
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (strip(expected) == strip(actual) .and. &
          len(strip(expected)) == len(strip(actual))) return
      call fail_header('assertEqual', location, message)
      write (output_unit, '(3a)') '   expected:  "', strip(expected), '"'
      write (output_unit, '(3a)') '   actual:    "', strip(actual), '"'
   end subroutine assert_equal_string

   !> text without leading and trailing blanks and tabs
   pure function strip(text) result(stripped)
      character(len=*), intent(in) :: text
      character(len=:), allocatable :: stripped
      integer :: first, last
      first = verify(text, ' '//achar(9))
      last = verify(text, ' '//achar(9), back=.true.)
      if (first == 0) then
         stripped = ''
      else
         stripped = text(first:last)
      end if
   end function strip

   ! ------------------------------------------------------------------
   ! assertRelativelyEqual
   ! ------------------------------------------------------------------

   subroutine assert_rel_equal_r64(expected, actual, tolerance, message, location)
      real(wp), intent(in) :: expected, actual, tolerance
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (close_rel(expected, actual, tolerance)) return
      call fail_header('assertRelativelyEqual', location, message)
      if (.not. abs(expected) > 0.0_wp) write (output_unit, '(a)') &
         '   expected value is 0: a relative tolerance is undefined'
      call report_real(expected, actual, tolerance, 'rel. tol.: ')
   end subroutine assert_rel_equal_r64

   subroutine assert_rel_equal_r64_1d(expected, actual, tolerance, message, location)
      real(wp), intent(in) :: expected(:), actual(:), tolerance
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      logical :: ok(size(expected))
      integer :: i
      if (size(expected) /= size(actual)) then
         call fail_header('assertRelativelyEqual', location, message)
         call report_shape(shape(expected), shape(actual))
         return
      end if
      ok = close_rel(expected, actual, tolerance)
      if (all(ok)) return
      call fail_header('assertRelativelyEqual', location, message)
      call report_count(count(.not. ok), size(ok))
      do i = 1, size(ok)
         if (.not. ok(i)) exit
      end do
      write (output_unit, '(a,i0,a)') '   at index (', i, ')'
      if (.not. abs(expected(i)) > 0.0_wp) write (output_unit, '(a)') &
         '   expected value is 0: a relative tolerance is undefined'
      call report_real(expected(i), actual(i), tolerance, 'rel. tol.: ')
   end subroutine assert_rel_equal_r64_1d

   ! ------------------------------------------------------------------
   ! Ordering: assertLessThan(lhs, rhs) passes if lhs < rhs, and so on;
   ! message= only by keyword (as in pFUnit).
   ! ------------------------------------------------------------------

   subroutine order_fail_int(what, relation, a, b, message, location)
      character(len=*), intent(in) :: what, relation
      integer, intent(in) :: a, b
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call fail_header(what, location, message)
      write (output_unit, '(a,i0,3a,i0)') '   expected ', a, ' ', relation, ' ', b
   end subroutine order_fail_int

   subroutine order_fail_r64(what, relation, a, b, message, location)
      character(len=*), intent(in) :: what, relation
      real(wp), intent(in) :: a, b
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call fail_header(what, location, message)
      write (output_unit, '(3a)') '   expected lhs ', relation, ' rhs with'
      write (output_unit, rfmt) '   lhs: ', a
      write (output_unit, rfmt) '   rhs: ', b
   end subroutine order_fail_r64

   logical function has_nan(a, b)
      real(wp), intent(in) :: a, b
      has_nan = ieee_is_nan(a) .or. ieee_is_nan(b)
   end function has_nan

   subroutine assert_lt_int(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs, rhs
      class(KeywordEnforcer), intent(in), optional :: unused
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(unused)) continue
      if (lhs < rhs) return
      call order_fail_int('assertLessThan', '<', lhs, rhs, message, location)
   end subroutine assert_lt_int

   subroutine assert_le_int(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs, rhs
      class(KeywordEnforcer), intent(in), optional :: unused
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(unused)) continue
      if (lhs <= rhs) return
      call order_fail_int('assertLessThanOrEqual', '<=', lhs, rhs, message, location)
   end subroutine assert_le_int

   subroutine assert_gt_int(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs, rhs
      class(KeywordEnforcer), intent(in), optional :: unused
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(unused)) continue
      if (lhs > rhs) return
      call order_fail_int('assertGreaterThan', '>', lhs, rhs, message, location)
   end subroutine assert_gt_int

   subroutine assert_ge_int(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs, rhs
      class(KeywordEnforcer), intent(in), optional :: unused
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(unused)) continue
      if (lhs >= rhs) return
      call order_fail_int('assertGreaterThanOrEqual', '>=', lhs, rhs, message, location)
   end subroutine assert_ge_int

   subroutine assert_lt_r64(lhs, rhs, unused, message, location)
      real(wp), intent(in) :: lhs, rhs
      class(KeywordEnforcer), intent(in), optional :: unused
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(unused)) continue
      if (.not. has_nan(lhs, rhs)) then
         if (lhs < rhs) return
      end if
      call order_fail_r64('assertLessThan', '<', lhs, rhs, message, location)
   end subroutine assert_lt_r64

   subroutine assert_le_r64(lhs, rhs, unused, message, location)
      real(wp), intent(in) :: lhs, rhs
      class(KeywordEnforcer), intent(in), optional :: unused
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(unused)) continue
      if (.not. has_nan(lhs, rhs)) then
         if (lhs <= rhs) return
      end if
      call order_fail_r64('assertLessThanOrEqual', '<=', lhs, rhs, message, location)
   end subroutine assert_le_r64

   subroutine assert_gt_r64(lhs, rhs, unused, message, location)
      real(wp), intent(in) :: lhs, rhs
      class(KeywordEnforcer), intent(in), optional :: unused
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(unused)) continue
      if (.not. has_nan(lhs, rhs)) then
         if (lhs > rhs) return
      end if
      call order_fail_r64('assertGreaterThan', '>', lhs, rhs, message, location)
   end subroutine assert_gt_r64

   subroutine assert_ge_r64(lhs, rhs, unused, message, location)
      real(wp), intent(in) :: lhs, rhs
      class(KeywordEnforcer), intent(in), optional :: unused
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(unused)) continue
      if (.not. has_nan(lhs, rhs)) then
         if (lhs >= rhs) return
      end if
      call order_fail_r64('assertGreaterThanOrEqual', '>=', lhs, rhs, message, location)
   end subroutine assert_ge_r64

   ! ------------------------------------------------------------------
   ! assertIsNaN / assertIsFinite
   ! ------------------------------------------------------------------

   subroutine assertIsNaN(x, message, location)
      real(wp), intent(in) :: x
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (ieee_is_nan(x)) return
      call fail_header('assertIsNaN', location, message)
      write (output_unit, rfmt) '   value: ', x
   end subroutine assertIsNaN

   subroutine assertIsFinite(x, message, location)
      real(wp), intent(in) :: x
      character(len=*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (ieee_is_finite(x)) return
      call fail_header('assertIsFinite', location, message)
      write (output_unit, rfmt) '   value: ', x
   end subroutine assertIsFinite

end module funit
