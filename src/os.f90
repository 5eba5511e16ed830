!> os -- what the program asks of the operating system, through C
!> interoperability and without a shell: creating the output directory
!> (a path is taken literally, never handed to a shell), the text of errno,
!> and the SIGTERM/SIGINT handler that asks the run to stop at the next
!> converged increment.
!>
!> The one piece of global mutable state in the program lives here: the
!> flag the signal handler sets (a handler can reach nothing else).  It is
!> only set by the handler and read by stop_requested.
module os
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_ptr, c_funptr, &
      c_funloc, c_associated, c_f_pointer, c_size_t
   implicit none
   private
   public :: make_directory, install_stop_handlers, stop_requested, signal_name

   !> POSIX signal numbers (the same on every Linux architecture)
   integer(c_int), parameter :: sigint = 2, sigterm = 15
   !> errno of an existing path
   integer(c_int), parameter :: eexist = 17

   !> the signal that asked the run to stop (0: none); set by on_signal
   integer(c_int), volatile, save :: requested = 0

   interface
      function c_mkdir(path, mode) bind(C, name='mkdir') result(rc)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), value :: mode
         integer(c_int) :: rc
      end function c_mkdir
      function c_errno_location() bind(C, name='__errno_location') result(p)
         import :: c_ptr
         type(c_ptr) :: p
      end function c_errno_location
      function c_strerror(errnum) bind(C, name='strerror') result(p)
         import :: c_int, c_ptr
         integer(c_int), value :: errnum
         type(c_ptr) :: p
      end function c_strerror
      function c_strlen(s) bind(C, name='strlen') result(n)
         import :: c_ptr, c_size_t
         type(c_ptr), value :: s
         integer(c_size_t) :: n
      end function c_strlen
      function c_signal(signum, handler) bind(C, name='signal') result(old)
         import :: c_int, c_funptr
         integer(c_int), value :: signum
         type(c_funptr), value :: handler
         type(c_funptr) :: old
      end function c_signal
   end interface

contains

   !> MAKE_DIRECTORY: create a directory and its missing parents (mkdir -p),
   !> by the mkdir system call; the path is taken literally.
   !>  path  [in]  the directory
   !>  stat  [out] 0 on success (also when it exists), else errno
   !>  msg   [out] the system's reason when stat /= 0 (strerror), else ''
   subroutine make_directory(path, stat, msg)
      character(len=*), intent(in) :: path
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: msg
      integer :: k, n
      logical :: is_dir
      msg = ''
      stat = 0
      n = len_trim(path)
      if (n == 0) return
      ! every prefix ending before a '/', then the whole path
      do k = 2, n
         if (path(k:k) == '/' .and. path(k - 1:k - 1) /= '/') then
            call make_one(path(1:k - 1), stat)
            if (stat /= 0 .and. stat /= eexist) exit
         end if
      end do
      if (stat == 0 .or. stat == eexist) call make_one(path(1:n), stat)
      if (stat == eexist) then
         ! an existing path is fine only if it is a directory
         inquire (file=path(1:n)//'/.', exist=is_dir)
         stat = 0
         if (.not. is_dir) then
            stat = eexist
            msg = 'exists and is not a directory'
            return
         end if
      end if
      if (stat /= 0) msg = errno_text(stat)
   end subroutine make_directory

   !> MAKE_ONE: mkdir of one path, mode 0777 (less the umask).
   !>  path  [in]  the directory
   !>  stat  [out] 0, or errno
   subroutine make_one(path, stat)
      character(len=*), intent(in) :: path
      integer, intent(out) :: stat
      stat = 0
      if (c_mkdir(path//c_null_char, int(o'777', c_int)) /= 0) stat = errno()
   end subroutine make_one

   !> ERRNO: the calling thread's errno.
   function errno() result(e)
      integer :: e
      integer(c_int), pointer :: p
      call c_f_pointer(c_errno_location(), p)
      e = int(p)
   end function errno

   !> ERRNO_TEXT: strerror(e), the system's words for an errno.
   !>  e  [in] errno value
   function errno_text(e) result(text)
      integer, intent(in) :: e
      character(len=:), allocatable :: text
      type(c_ptr) :: p
      character(kind=c_char), pointer :: chars(:)
      integer :: i, n
      p = c_strerror(int(e, c_int))
      text = 'errno '
      if (.not. c_associated(p)) return
      n = int(c_strlen(p))
      call c_f_pointer(p, chars, [n])
      allocate (character(len=n) :: text)
      do i = 1, n
         text(i:i) = chars(i)
      end do
   end function errno_text

   !> INSTALL_STOP_HANDLERS: SIGTERM and SIGINT (Ctrl-C) ask the run to stop
   !> at the next converged increment instead of killing it.
   subroutine install_stop_handlers()
      type(c_funptr) :: old
      old = c_signal(sigterm, c_funloc(on_signal))
      old = c_signal(sigint, c_funloc(on_signal))
   end subroutine install_stop_handlers

   !> ON_SIGNAL: the handler: record the signal, nothing else.
   subroutine on_signal(signum) bind(C)
      integer(c_int), value :: signum
      requested = signum
   end subroutine on_signal

   !> STOP_REQUESTED: .true. once SIGTERM or SIGINT has arrived.
   logical function stop_requested()
      stop_requested = requested /= 0
   end function stop_requested

   !> SIGNAL_NAME: 'SIGTERM', 'SIGINT' or '' for the signal that arrived.
   function signal_name() result(name)
      character(len=:), allocatable :: name
      select case (requested)
      case (sigterm)
         name = 'SIGTERM'
      case (sigint)
         name = 'SIGINT'
      case default
         name = ''
      end select
   end function signal_name
end module os
