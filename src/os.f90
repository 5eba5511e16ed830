!> os -- what the program asks of the operating system, through C
!> interoperability and without a shell: creating the output directory
!> (a path is taken literally, never handed to a shell), the result files
!> written by the system calls creat/write/pwrite/close/unlink, the text
!> of errno, the input files read whole by fopen/fread (a pipe reads like
!> a file: nothing seeks), the lock (flock) by which a run owns its output
!> directory, and the SIGTERM/SIGINT handler that asks the
!> run to stop at the next converged increment.
!>
!> Why result files do not use Fortran I/O: gfortran 12 reports success
!> (iostat = 0) from a FLUSH or CLOSE whose write failed (ENOSPC on a full
!> disk, EFBIG past a size limit; checked with strace), so a run on a full
!> disk would end with truncated files and exit 0.  write(2) returns the
!> error at once.
!>
!> The one piece of global mutable state in the program lives here: the
!> flag the signal handler sets (a handler can reach nothing else).  It is
!> only set by the handler and read by stop_requested.
module os
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_ptr, c_funptr, &
      c_funloc, c_associated, c_f_pointer, c_size_t, c_long
   use kinds, only: dp
   use text, only: itoa, next_line
   implicit none
   private
   public :: make_directory, install_stop_handlers, stop_requested, signal_name
   public :: file_create, file_write, file_write_at, file_close, file_remove
   public :: read_file, file_too_large, lock_file, lock_busy, memory_room

   !> POSIX signal numbers (the same on every Linux architecture)
   integer(c_int), parameter :: sigint = 2, sigterm = 15, sigxfsz = 25
   !> errno of an existing path
   integer(c_int), parameter :: eexist = 17

   !> the signal that asked the run to stop (0: none); set by on_signal
   integer(c_int), volatile, save :: requested = 0

   !> errno of an interrupted system call (retried)
   integer(c_int), parameter :: eintr = 4
   !> errno of a read from a directory, of an input/output error
   integer(c_int), parameter :: eisdir = 21, eio = 5
   !> read_file's stat for a file longer than its limit (not an errno)
   integer, parameter :: file_too_large = -1
   !> lock_file's stat for a lock another process holds (not an errno)
   integer, parameter :: lock_busy = -2
   !> errno of a lock held elsewhere (EWOULDBLOCK = EAGAIN on Linux)
   integer(c_int), parameter :: ewouldblock = 11
   !> flock(2) operation: exclusive, do not wait
   integer(c_int), parameter :: lock_ex = 2, lock_nb = 4

   interface
      function c_creat(path, mode) bind(C, name='creat') result(fd)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), value :: mode
         integer(c_int) :: fd
      end function c_creat
      function c_write(fd, buf, count) bind(C, name='write') result(n)
         import :: c_int, c_char, c_size_t, c_long
         integer(c_int), value :: fd
         character(kind=c_char), intent(in) :: buf(*)
         integer(c_size_t), value :: count
         integer(c_long) :: n
      end function c_write
      function c_pwrite(fd, buf, count, offset) bind(C, name='pwrite') result(n)
         import :: c_int, c_char, c_size_t, c_long
         integer(c_int), value :: fd
         character(kind=c_char), intent(in) :: buf(*)
         integer(c_size_t), value :: count
         integer(c_long), value :: offset
         integer(c_long) :: n
      end function c_pwrite
      function c_close(fd) bind(C, name='close') result(rc)
         import :: c_int
         integer(c_int), value :: fd
         integer(c_int) :: rc
      end function c_close
      function c_unlink(path) bind(C, name='unlink') result(rc)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: rc
      end function c_unlink
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
      function c_fopen(path, mode) bind(C, name='fopen') result(fp)
         import :: c_char, c_ptr
         character(kind=c_char), intent(in) :: path(*), mode(*)
         type(c_ptr) :: fp
      end function c_fopen
      function c_fread(buf, size, count, fp) bind(C, name='fread') result(n)
         import :: c_char, c_size_t, c_ptr
         character(kind=c_char), intent(out) :: buf(*)
         integer(c_size_t), value :: size, count
         type(c_ptr), value :: fp
         integer(c_size_t) :: n
      end function c_fread
      function c_ferror(fp) bind(C, name='ferror') result(rc)
         import :: c_int, c_ptr
         type(c_ptr), value :: fp
         integer(c_int) :: rc
      end function c_ferror
      function c_fclose(fp) bind(C, name='fclose') result(rc)
         import :: c_int, c_ptr
         type(c_ptr), value :: fp
         integer(c_int) :: rc
      end function c_fclose
      function c_fileno(fp) bind(C, name='fileno') result(fd)
         import :: c_int, c_ptr
         type(c_ptr), value :: fp
         integer(c_int) :: fd
      end function c_fileno
      function c_flock(fd, operation) bind(C, name='flock') result(rc)
         import :: c_int
         integer(c_int), value :: fd, operation
         integer(c_int) :: rc
      end function c_flock
      function c_ftruncate(fd, length) bind(C, name='ftruncate') result(rc)
         import :: c_int, c_long
         integer(c_int), value :: fd
         integer(c_long), value :: length
         integer(c_int) :: rc
      end function c_ftruncate
      function c_pread(fd, buf, count, offset) bind(C, name='pread') result(n)
         import :: c_int, c_char, c_size_t, c_long
         integer(c_int), value :: fd
         character(kind=c_char), intent(out) :: buf(*)
         integer(c_size_t), value :: count
         integer(c_long), value :: offset
         integer(c_long) :: n
      end function c_pread
      function c_getrlimit(resource, limits) bind(C, name='getrlimit') result(rc)
         import :: c_int, c_long
         integer(c_int), value :: resource
         integer(c_long), intent(out) :: limits(2)
         integer(c_int) :: rc
      end function c_getrlimit
      function c_getpagesize() bind(C, name='getpagesize') result(n)
         import :: c_int
         integer(c_int) :: n
      end function c_getpagesize
      function c_getpid() bind(C, name='getpid') result(pid)
         import :: c_int
         integer(c_int) :: pid
      end function c_getpid
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

   !> FILE_CREATE: create (or truncate) a file for writing, mode 0666 less
   !> the umask.
   !>  path  [in]  the file
   !>  fd    [out] its descriptor, -1 on failure
   !>  stat  [out] 0, or errno
   !>  msg   [out] the system's reason when stat /= 0
   subroutine file_create(path, fd, stat, msg)
      character(len=*), intent(in) :: path
      integer, intent(out) :: fd, stat
      character(len=:), allocatable, intent(out) :: msg
      msg = ''
      stat = 0
      fd = int(c_creat(trim(path)//c_null_char, int(o'666', c_int)))
      if (fd < 0) then
         stat = errno()
         msg = errno_text(stat)
         fd = -1
      end if
   end subroutine file_create

   !> FILE_WRITE: append text to an open file, all of it (a short write is
   !> continued, an interrupted one retried).
   !>  fd    [in]  descriptor from file_create
   !>  text  [in]  the bytes (lines end with achar(10))
   !>  stat  [out] 0, or errno
   !>  msg   [out] the system's reason when stat /= 0
   subroutine file_write(fd, text, stat, msg)
      integer, intent(in) :: fd
      character(len=*), intent(in) :: text
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: msg
      call write_all(fd, text, -1, stat, msg)
   end subroutine file_write

   !> FILE_WRITE_AT: write text at a byte offset of an open file (pwrite),
   !> without moving its end: a record rewritten in place.
   !>  fd      [in]  descriptor
   !>  text    [in]  the bytes
   !>  offset  [in]  where, in bytes from the start (>= 0)
   !>  stat    [out] 0, or errno
   !>  msg     [out] the system's reason when stat /= 0
   subroutine file_write_at(fd, text, offset, stat, msg)
      integer, intent(in) :: fd, offset
      character(len=*), intent(in) :: text
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: msg
      call write_all(fd, text, offset, stat, msg)
   end subroutine file_write_at

   !> WRITE_ALL: write(2) (offset < 0) or pwrite(2) at offset until every
   !> byte is written; EINTR is retried.
   subroutine write_all(fd, text, offset, stat, msg)
      integer, intent(in) :: fd, offset
      character(len=*), intent(in) :: text
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: msg
      integer :: done
      integer(c_long) :: n
      msg = ''
      stat = 0
      done = 0
      do while (done < len(text))
         if (offset < 0) then
            n = c_write(int(fd, c_int), text(done + 1:), int(len(text) - done, c_size_t))
         else
            n = c_pwrite(int(fd, c_int), text(done + 1:), int(len(text) - done, c_size_t), &
                         int(offset + done, c_long))
         end if
         if (n < 0) then
            stat = errno()
            if (stat == eintr) cycle
            msg = errno_text(stat)
            return
         end if
         done = done + int(n)
      end do
   end subroutine write_all

   !> FILE_CLOSE: close a descriptor (its data is then with the system).
   !>  fd    [in]  descriptor
   !>  stat  [out] 0, or errno
   !>  msg   [out] the system's reason when stat /= 0
   subroutine file_close(fd, stat, msg)
      integer, intent(in) :: fd
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: msg
      msg = ''
      stat = 0
      if (c_close(int(fd, c_int)) /= 0) then
         stat = errno()
         msg = errno_text(stat)
      end if
   end subroutine file_close

   !> FILE_REMOVE: delete a file (unlink); a missing one is no error.
   !>  path  [in]  the file
   !>  stat  [out] 0, or errno
   !>  msg   [out] the system's reason when stat /= 0
   subroutine file_remove(path, stat, msg)
      character(len=*), intent(in) :: path
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: msg
      integer, parameter :: enoent = 2
      msg = ''
      stat = 0
      if (c_unlink(trim(path)//c_null_char) /= 0) then
         stat = errno()
         if (stat == enoent) then
            stat = 0
         else
            msg = errno_text(stat)
         end if
      end if
   end subroutine file_remove

   !> READ_FILE: the whole of an input file as one string, read from its
   !> start to its end (fopen/fread) and never positioned: a pipe,
   !> /dev/stdin or a process substitution (bash's <(...)) reads like a
   !> regular file, where a Fortran rewind or inquire(size=) fails with
   !> "Illegal seek".  At most max_bytes are taken: a longer file (or an
   !> endless one, /dev/zero) is refused after max_bytes + 1 bytes, so that
   !> no input can hang the program or exhaust its memory.
   !>  path       [in]  the file
   !>  max_bytes  [in]  the largest file accepted, bytes (>= 0)
   !>  text       [out] the file's bytes; length 0 when stat /= 0
   !>  stat       [out] 0, an errno, or file_too_large
   !>  msg        [out] the reason when stat /= 0: the system's words,
   !>                   'is a directory, not a file', or 'larger than N
   !>                   bytes, ...'; '' otherwise
   subroutine read_file(path, max_bytes, text, stat, msg)
      character(len=*), intent(in) :: path
      integer, intent(in) :: max_bytes
      character(len=:), allocatable, intent(out) :: text
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: msg
      integer, parameter :: chunk_len = 65536
      character(kind=c_char, len=chunk_len) :: chunk
      character(len=:), allocatable :: buf, grown
      type(c_ptr) :: fp
      integer :: total, n
      text = ''
      msg = ''
      stat = 0
      fp = c_fopen(trim(path)//c_null_char, 'r'//c_null_char)
      if (.not. c_associated(fp)) then
         stat = errno()
         msg = errno_text(stat)
         return
      end if
      allocate (character(len=chunk_len) :: buf)
      total = 0
      do
         n = int(c_fread(chunk, 1_c_size_t, int(chunk_len, c_size_t), fp))
         if (n > 0) then
            ! keep one byte past the limit at most: enough to refuse the file
            n = min(n, max_bytes + 1 - total)
            if (total + n > len(buf)) then
               allocate (character(len=max(2*len(buf), total + n)) :: grown)
               grown(1:total) = buf(1:total)
               call move_alloc(grown, buf)
            end if
            buf(total + 1:total + n) = chunk(1:n)
            total = total + n
         end if
         if (total > max_bytes) then
            stat = file_too_large
            msg = 'larger than '//itoa(max_bytes)//' bytes, the most an input file may have'
            exit
         end if
         if (n < chunk_len) then
            ! a short read: the end of the file, or an error (ferror says)
            if (c_ferror(fp) /= 0) then
               stat = errno()
               if (stat == 0) stat = eio
               msg = errno_text(stat)
               if (stat == eisdir) msg = 'is a directory, not a file'
            end if
            exit
         end if
      end do
      if (c_fclose(fp) /= 0 .and. stat == 0) then
         stat = errno()
         msg = errno_text(stat)
      end if
      if (stat == 0) text = buf(1:total)
   end subroutine read_file

   !> LOCK_FILE: take the exclusive lock (flock, without waiting) of a
   !> file, created if missing, for the rest of the process, and write the
   !> process id in it.  The file stays open until the process ends, and
   !> the system releases the lock then, however the process ends (SIGKILL
   !> included): a lock file left by a killed run is not held by anyone
   !> and never blocks the next run, with no process id to check.
   !>  path   [in]  the lock file
   !>  stat   [out] 0 (the lock is this process's), lock_busy (another
   !>               process holds it), or an errno
   !>  msg    [out] with lock_busy: the holder's process id as written in
   !>               the file ('' if it has not written it yet); with an
   !>               errno: the system's reason; else ''
   subroutine lock_file(path, stat, msg)
      character(len=*), intent(in) :: path
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: msg
      character(kind=c_char, len=24) :: buf
      type(c_ptr) :: fp
      integer(c_int) :: fd, rc
      integer(c_long) :: n
      character(len=:), allocatable :: why
      msg = ''
      stat = 0
      ! "a+": created if missing, never truncated (the holder's id stays),
      ! readable (the holder's id is read from it)
      fp = c_fopen(trim(path)//c_null_char, 'a+'//c_null_char)
      if (.not. c_associated(fp)) then
         stat = errno()
         msg = errno_text(stat)
         return
      end if
      fd = c_fileno(fp)
      if (c_flock(fd, ior(lock_ex, lock_nb)) /= 0) then
         stat = errno()
         if (stat == ewouldblock) then
            stat = lock_busy
            buf = ''
            n = c_pread(fd, buf, int(len(buf), c_size_t), 0_c_long)
            if (n > 0) msg = buf(1:min(int(n), len(buf)))
            if (index(msg, achar(10)) > 0) msg = msg(1:index(msg, achar(10)) - 1)
            if (verify(msg, '0123456789') /= 0) msg = ''
         else
            msg = errno_text(stat)
         end if
         rc = c_fclose(fp)
         return
      end if
      ! the lock is ours: the file says who holds it (fp stays open)
      if (c_ftruncate(fd, 0_c_long) /= 0) then
         stat = errno()
         msg = errno_text(stat)
         return
      end if
      call write_all(int(fd), itoa(int(c_getpid()))//achar(10), -1, stat, why)
      if (stat /= 0) msg = why
   end subroutine lock_file

   !> MEMORY_ROOM: how much more memory this process can have, bytes: the
   !> address-space limit (getrlimit RLIMIT_AS, `ulimit -v`) less what the
   !> process maps already (/proc/self/statm), and the machine's memory
   !> and swap (/proc/meminfo MemTotal + SwapTotal); the smaller of the two
   !> and which it is.  Either is left out when unknown or unlimited.
   !>  room  [out] bytes; huge() when neither is known
   !>  what  [out] 'the address-space limit (ulimit -v)', 'the machine's
   !>              memory and swap', or '' when room = huge()
   subroutine memory_room(room, what)
      real(dp), intent(out) :: room
      character(len=:), allocatable, intent(out) :: what
      !> RLIMIT_AS on Linux
      integer(c_int), parameter :: rlimit_as = 9
      integer(c_long) :: limits(2)
      character(len=:), allocatable :: text, why, line
      real(dp) :: mapped, total, kb
      integer :: stat, pos, k, ios
      room = huge(1.0_dp)
      what = ''
      ! the address-space limit (RLIM_INFINITY reads as -1)
      if (c_getrlimit(rlimit_as, limits) == 0 .and. limits(1) > 0) then
         call read_file('/proc/self/statm', 4096, text, stat, why)
         mapped = 0.0_dp
         if (stat == 0) then
            read (text, *, iostat=ios) mapped
            if (ios /= 0) mapped = 0.0_dp
            mapped = mapped*real(c_getpagesize(), dp)
         end if
         room = real(limits(1), dp) - mapped
         what = 'the address-space limit (ulimit -v)'
      end if
      ! the machine
      call read_file('/proc/meminfo', 65536, text, stat, why)
      if (stat /= 0) return
      total = 0.0_dp
      pos = 1
      do while (pos <= len(text))
         call next_line(text, pos, line)
         k = index(line, ':')
         if (k == 0) cycle
         if (line(1:k) /= 'MemTotal:' .and. line(1:k) /= 'SwapTotal:') cycle
         read (line(k + 1:), *, iostat=ios) kb
         if (ios == 0) total = total + 1024.0_dp*kb
      end do
      if (total > 0.0_dp .and. total < room) then
         room = total
         what = 'the machine''s memory and swap'
      end if
   end subroutine memory_room

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
      if (.not. c_associated(p)) then
         text = 'errno '//itoa(e)
         return
      end if
      n = int(c_strlen(p))
      call c_f_pointer(p, chars, [n])
      allocate (character(len=n) :: text)
      do i = 1, n
         text(i:i) = chars(i)
      end do
   end function errno_text

   !> INSTALL_STOP_HANDLERS: SIGTERM and SIGINT (Ctrl-C) ask the run to stop
   !> at the next converged increment instead of killing it.  SIGXFSZ (a
   !> file grown past the size limit, ulimit -f) is caught and ignored, so
   !> that the write fails with EFBIG and is reported like a full disk
   !> (the run-time library would otherwise die with a backtrace).
   subroutine install_stop_handlers()
      type(c_funptr) :: old
      old = c_signal(sigterm, c_funloc(on_signal))
      old = c_signal(sigint, c_funloc(on_signal))
      old = c_signal(sigxfsz, c_funloc(on_file_size))
   end subroutine install_stop_handlers

   !> ON_FILE_SIZE: the SIGXFSZ handler: nothing (the write reports EFBIG).
   subroutine on_file_size(signum) bind(C)
      integer(c_int), value :: signum
      associate (unused => signum)
      end associate
   end subroutine on_file_size

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
