!> errors -- collected input errors, warnings and exit codes.
!>
!> Input errors are not fatal where they are found: each is appended to an
!> error_list, and the main program reports them all at once (FEAP style,
!> one `*ERROR* ...` line each) and stops with exit status exit_input.
!> Warnings are printed at once to error_unit as `*WARNING* ...`.  Every
!> message of the program goes through this module and names where it
!> comes from: the deck, group and variable for input, or the routine
!> (`*WARNING* check_fold: ...`).  Deep routines never stop: they return a
!> status, and only the main program stops, with one of the exit codes
!> below.  The module holds no state; every list belongs to its caller.
module errors
   use kinds, only: dp, error_unit
   implicit none
   private
   public :: exit_ok, exit_input, exit_noconvergence, exit_write, exit_interrupted, exit_memory
   public :: error_message, error_list
   public :: add_error, report_errors, warn, print_error, alloc_message

   !> Exit status of the program: success.
   integer, parameter :: exit_ok = 0
   !> Exit status of the program: the input deck (or a file it names) is bad.
   integer, parameter :: exit_input = 1
   !> Exit status of the program: the increment loop could not converge
   !> (the results so far are kept).
   integer, parameter :: exit_noconvergence = 2
   !> Exit status of the program: a result file could not be written (full
   !> disk, quota, removed directory); the message names the file and the
   !> system's reason.
   integer, parameter :: exit_write = 3
   !> Exit status of the program: SIGTERM or SIGINT stopped the run at a
   !> converged increment (everything so far on disk, status = interrupted).
   integer, parameter :: exit_interrupted = 4
   !> Exit status of the program: an allocation of the run's large arrays
   !> (the state and histories, the band matrix, a phase's or a split's
   !> work arrays) failed although the set-up's memory estimate let the
   !> mesh through; the message names the arrays and their size (the
   !> results so far are kept).
   integer, parameter :: exit_memory = 5

   !> One message of any length.
   type :: error_message
      character(len=:), allocatable :: text
   end type error_message

   !> A growing list of messages: messages(1:count) are in use.
   type :: error_list
      type(error_message), allocatable :: messages(:)
      integer :: count = 0
   end type error_list

contains

   !> add_error -- append a message to an error list.
   !>
   !> list  [in,out] the list; grows as needed, count increases by one.
   !> msg   [in]     the message, without the `*ERROR*` prefix; trailing
   !>                blanks are dropped.
   subroutine add_error(list, msg)
      type(error_list), intent(inout) :: list
      character(len=*), intent(in) :: msg

      type(error_message), allocatable :: grown(:)
      integer :: i

      if (.not. allocated(list%messages)) then
         allocate (list%messages(8))
         list%count = 0
      else if (list%count >= size(list%messages)) then
         allocate (grown(2*size(list%messages)))
         do i = 1, list%count
            call move_alloc(list%messages(i)%text, grown(i)%text)
         end do
         call move_alloc(grown, list%messages)
      end if
      list%count = list%count + 1
      list%messages(list%count)%text = trim(msg)
   end subroutine add_error

   !> report_errors -- print every message of a list as `*ERROR* <msg>`.
   !>
   !> list  [in] the list; nothing is printed when it is empty.
   !> unit  [in] an open formatted unit (usually error_unit).
   subroutine report_errors(list, unit)
      type(error_list), intent(in) :: list
      integer, intent(in) :: unit

      integer :: i

      do i = 1, list%count
         write (unit, '(a)') '*ERROR* '//list%messages(i)%text
      end do
   end subroutine report_errors

   !> warn -- print `*WARNING* [<caller>: ]<msg>` to error_unit at once.
   !>
   !> msg     [in] the warning text; trailing blanks are dropped.  Input
   !>              warnings name the deck, group and variable in it.
   !> caller  [in] optional: the routine that warns.
   subroutine warn(msg, caller)
      character(len=*), intent(in) :: msg
      character(len=*), intent(in), optional :: caller

      write (error_unit, '(a)') '*WARNING* '//prefix(caller)//trim(msg)
   end subroutine warn

   !> print_error -- print `*ERROR* [<caller>: ]<msg>` to error_unit at once
   !> (for the main program's own errors: the command line, the output
   !> directory, a run that could not converge).
   !>
   !> msg     [in] the message; trailing blanks are dropped.
   !> caller  [in] optional: where the error was found.
   subroutine print_error(msg, caller)
      character(len=*), intent(in) :: msg
      character(len=*), intent(in), optional :: caller

      write (error_unit, '(a)') '*ERROR* '//prefix(caller)//trim(msg)
      flush (error_unit)
   end subroutine print_error

   !> alloc_message -- the message of a failed allocation: 'cannot allocate
   !> <what> (<size> MiB): out of memory ...'.  (gfortran 12's errmsg of an
   !> allocate that the system refuses says "Attempt to allocate an
   !> allocated object": it is not passed on.)
   !>
   !> what    [in] the arrays, in words ('the band matrix of 80004
   !>              equations').
   !> bytes   [in] their size in bytes (as a real: it may pass huge(0)).
   pure function alloc_message(what, bytes) result(msg)
      character(len=*), intent(in) :: what
      real(dp), intent(in) :: bytes
      character(len=:), allocatable :: msg

      character(len=32) :: buf

      write (buf, '(f0.1)') bytes/1024.0_dp**2
      msg = 'cannot allocate '//what//' ('//trim(buf)//' MiB): out of memory (the address-space '// &
            'limit, ulimit -v, or the machine); give fewer elements or thickness points, or more memory'
   end function alloc_message

   !> prefix -- '<caller>: ', or '' without a caller.
   pure function prefix(caller) result(p)
      character(len=*), intent(in), optional :: caller
      character(len=:), allocatable :: p

      p = ''
      if (present(caller)) p = trim(caller)//': '
   end function prefix

end module errors
