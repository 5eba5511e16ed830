!> output -- the column text files of a run.
!>
!> Every file starts with '#' lines naming each column and its unit; data are
!> written with (*(1x,es24.16e3)) so real64 round-trips, and each row goes
!> to the system at once, so a run that stops early keeps what it computed.
!>
!> The output directory belongs to the run: open_outputs creates it (by
!> the mkdir system call, never a shell), removes the result files an
!> earlier run left there (only the names in result_files) and starts
!> summary.txt with status = running, which write_progress keeps true
!> increment by increment until the summary module writes the final one.
!> The files are written through module os (write(2)), because gfortran's
!> own I/O does not report a failed flush: the first failure of any write
!> or close is kept in output_files (failed, failure: the file and the
!> system's reason) and the increment loop stops the run on it.
module output
   use kinds, only: dp
   use hermite, only: n_gauss, gauss_xi, hermite_shape
   use mesh, only: element_dofs
   use element, only: v_dofs, w_dofs, igp_strain, igp_curvature, igp_force, igp_moment
   use section, only: ih_strain, col_eps22, col_eqps, ih_stress22
   use contact, only: ich_active, ich_pressure, ich_mu
   use model, only: model_type, state_type, gauss_position
   use tools, only: tool_sample
   use os, only: make_directory, file_create, file_write, file_write_at, file_close, file_remove, &
                 lock_file, lock_busy
   implicit none
   private
   public :: output_files, open_outputs, write_row, write_strains, close_outputs, fmt_row, &
             write_tools, open_snapshots, write_snapshot, write_progress, result_files, &
             write_text_file, remove_results, claim_output_dir, owner_lock, column_legend

   character(len=*), parameter :: fmt_row = '(*(1x,es24.16e3))'
   character(len=1), parameter :: nl = achar(10)

   !> Every file a run writes in its output directory (removed before the
   !> first increment, so no result of an earlier run is left beside this one's).
   character(len=*), parameter :: result_files(11) = [character(len=23) :: &
      'summary.txt', 'lock.dat', 'pull.dat', 'strain_lock.dat', 'strain_pull.dat', &
      'strain_localization.dat', 'tools_lock.dat', 'tools_pull.dat', 'snapshots.dat', &
      'exit_state.dat', 'exit_state.k']

   !> The file by which a run owns its output directory (module os's
   !> lock_file: held while the run goes, released by the system when it
   !> ends, however it ends).
   character(len=*), parameter :: owner_lock = '.drawbead.lock'

   !> One file of the run held open: its descriptor (-1: not open) and name.
   type :: open_file
      integer :: fd = -1
      character(len=:), allocatable :: path
   end type open_file

   !> The files kept open through a run, and the first failed write.
   type :: output_files
      character(len=:), allocatable :: dir
      type(open_file) :: lock, pull, snapshots, progress
      integer :: n_snapshots = 0                  ! blocks in snapshots.dat (&control snapshot_every)
      logical :: failed = .false.
      character(len=:), allocatable :: failure    ! '<file>: <the system's reason>'
   end type output_files

   !> The column header of lock.dat (after its title line).
   character(len=*), parameter :: lock_columns = &
      '# 1:H/h 2:F/(E h) 3:F[N/mm] 4:newton_iterations 5:dH/h 6:min_localization_indicator[-]'// &
      ' 7:max_penetration/h 8:N/(E h) 9:N[N/mm]'//nl// &
      '# F = upward force of the lower tool on the sheet per unit width (punch force);'// &
      ' N = horizontal reaction at the right edge'
   !> The column header of pull.dat (after its title line).
   character(len=*), parameter :: pull_columns = &
      '# 1:delta/h 2:N/(E h) 3:N[N/mm] 4:newton_iterations 5:d(delta)/h'// &
      ' 6:min_localization_indicator[-] 7:lift/(E h) 8:lift[N/mm] 9:max_penetration/h'// &
      ' 10:F/(E h)'//nl// &
      '# N = restraining force (horizontal reaction at the right edge) per unit width;'// &
      ' lift = vertical force of the sheet opening the binder (on the upper tool)'
   !> The column header of the strain files (strain_*.dat, snapshots.dat).
   character(len=*), parameter :: strain_columns = &
      '# 1:s/h (reference position) 2:x/h 3:y/h (current centreline) 4:lambda-1'// &
      ' 5:ln(lambda) 6:top_fibre_log_strain 7:bottom_fibre_log_strain'// &
      ' 8:thickness_log_strain(mid-surface) 9:max_equivalent_plastic_strain(through thickness; -1: the law has none)'// &
      ' 10:rho*h (bending strain) 11:N/(E h) 12:M/(E h^2)'// &
      ' 13:localization_indicator (smallest eigenvalue of the scaled section tangent, <= 0: localized)'// &
      ' 14:tau22_top[MPa] 15:tau22_bottom[MPa] (thickness stress on the faces: the contact section)'// &
      ' 16:p_upper[MPa] 17:p_lower[MPa] (contact pressure of the upper, lower tool: 0 out of contact)'// &
      ' 18:mu_upper 19:mu_lower (friction coefficient in use there: 0 out of contact)'

contains

   !> COLUMN_LEGEND: the column header lines of a result file, as the
   !> program writes them after the file's title line (`drawbead --columns
   !> FILE` prints them for the scripts, which write files of the same
   !> layout: scripts/continuum_results.py).
   !>  file    [in]  lock.dat, pull.dat, strain_lock.dat, strain_pull.dat,
   !>                strain_localization.dat or snapshots.dat
   !>  legend  [out] the lines ('# ' first, line feeds between them); ''
   !>                for another name
   pure function column_legend(file) result(legend)
      character(len=*), intent(in) :: file
      character(len=:), allocatable :: legend
      select case (file)
      case ('lock.dat')
         legend = lock_columns
      case ('pull.dat')
         legend = pull_columns
      case ('strain_lock.dat', 'strain_pull.dat', 'strain_localization.dat', 'snapshots.dat')
         legend = strain_columns
      case default
         legend = ''
      end select
   end function column_legend

   !> OPEN_OUTPUTS: create the output directory, remove the result files of
   !> an earlier run, start summary.txt (status = running) and open lock.dat
   !> and pull.dat with their headers.
   !>  dir    [in]  output directory
   !>  title  [in]  run title (echoed in the headers)
   !>  out    [out] the open files
   !>  errmsg [out] '' on success, else what failed and why
   subroutine open_outputs(dir, title, out, errmsg)
      character(len=*), intent(in) :: dir, title
      type(output_files), intent(out) :: out
      character(len=*), intent(out) :: errmsg
      character(len=:), allocatable :: why
      integer :: stat
      errmsg = ''
      out%dir = trim(dir)
      call make_directory(out%dir, stat, why)
      if (stat /= 0) then
         errmsg = 'cannot create output directory '//out%dir//': '//why
         return
      end if
      call remove_results(out%dir, errmsg)
      if (len_trim(errmsg) > 0) return
      call open_new(out, 'summary.txt', out%progress)
      call write_progress(out, 'start', 0.0_dp, 0)
      call open_new(out, 'lock.dat', out%lock)
      call put(out, out%lock, '# drawbead locking: '//trim(title)//nl//lock_columns//nl)
      call open_new(out, 'pull.dat', out%pull)
      call put(out, out%pull, '# drawbead pulling: '//trim(title)//nl//pull_columns//nl)
      if (out%failed) errmsg = out%failure
   end subroutine open_outputs

   !> CLAIM_OUTPUT_DIR: the output directory becomes this run's: created
   !> (with its parents) if needed, and its lock file (owner_lock) taken
   !> for the rest of the process.  A second run into a directory a run is
   !> writing is refused, naming the directory and the other run's process
   !> id (two runs into one directory mixed their files: issue 28, item 2).
   !> A lock file left by a run that was killed is free: it does not block.
   !>  dir     [in]  the output directory
   !>  errmsg  [out] '' or why the directory cannot be this run's
   subroutine claim_output_dir(dir, errmsg)
      character(len=*), intent(in) :: dir
      character(len=*), intent(out) :: errmsg
      character(len=:), allocatable :: why, other
      integer :: stat
      errmsg = ''
      call make_directory(trim(dir), stat, why)
      if (stat /= 0) then
         errmsg = 'cannot create output directory '//trim(dir)//': '//why
         return
      end if
      call lock_file(trim(dir)//'/'//owner_lock, stat, why)
      if (stat == lock_busy) then
         other = 'another run of drawbead'
         if (len(why) > 0) other = other//' (process id '//why//')'
         errmsg = 'output directory '//trim(dir)//' is in use by '//other//', which holds '// &
                  trim(dir)//'/'//owner_lock//': wait for it to end, or give another directory (-o DIR)'
      else if (stat /= 0) then
         errmsg = 'cannot lock output directory '//trim(dir)//' ('//trim(dir)//'/'//owner_lock// &
                  '): '//why
      end if
   end subroutine claim_output_dir

   !> REMOVE_RESULTS: remove the result files (result_files) of an earlier
   !> run from a directory, if it has any; a directory that does not exist
   !> (or is not one) has none.
   !>  dir     [in]  the directory
   !>  errmsg  [out] '' or '<file>: <the system's reason>' for a file that
   !>                exists and could not be removed
   subroutine remove_results(dir, errmsg)
      character(len=*), intent(in) :: dir
      character(len=*), intent(out) :: errmsg
      integer, parameter :: enotdir = 20
      character(len=:), allocatable :: why
      integer :: stat, k
      errmsg = ''
      do k = 1, size(result_files)
         call file_remove(dir//'/'//trim(result_files(k)), stat, why)
         if (stat /= 0 .and. stat /= enotdir) then
            errmsg = 'cannot remove '//dir//'/'//trim(result_files(k))//' of an earlier run: '//why
            return
         end if
      end do
   end subroutine remove_results

   !> OPEN_NEW: create a result file of the run's directory.
   !>  out   [in,out] the run's files (a failure is recorded)
   !>  name  [in]     file name inside out%dir
   !>  f     [out]    the open file (fd = -1 when it could not be created)
   subroutine open_new(out, name, f)
      type(output_files), intent(inout) :: out
      character(len=*), intent(in) :: name
      type(open_file), intent(out) :: f
      integer :: stat
      character(len=:), allocatable :: why
      f%path = out%dir//'/'//name
      call file_create(f%path, f%fd, stat, why)
      call record_failure(out, f, stat, why)
   end subroutine open_new

   !> PUT: append text (whole lines) to an open file of the run.
   !>  out   [in,out] the run's files (a failure is recorded)
   !>  f     [in]     the file; nothing is written when it is not open or
   !>                 a write has failed already
   !>  text  [in]     the bytes, lines ended by achar(10)
   subroutine put(out, f, text)
      type(output_files), intent(inout) :: out
      type(open_file), intent(in) :: f
      character(len=*), intent(in) :: text
      integer :: stat
      character(len=:), allocatable :: why
      if (f%fd == -1 .or. out%failed) return
      call file_write(f%fd, text, stat, why)
      call record_failure(out, f, stat, why)
   end subroutine put

   !> RECORD_FAILURE: keep the first failure of the run's files.
   !>  out   [in,out] the run's files
   !>  f     [in]     the file concerned
   !>  stat  [in]     0, or errno
   !>  why   [in]     the system's reason
   subroutine record_failure(out, f, stat, why)
      type(output_files), intent(inout) :: out
      type(open_file), intent(in) :: f
      integer, intent(in) :: stat
      character(len=*), intent(in) :: why
      if (stat == 0 .or. out%failed) return
      out%failed = .true.
      out%failure = f%path//': '//why
   end subroutine record_failure

   !> WRITE_PROGRESS: summary.txt while the run goes: status = running, the
   !> phase and the last converged load, rewritten in place (same length)
   !> after every converged increment, so that a run killed at any moment
   !> leaves a true summary beside its partial files.
   !>  out          [in,out] the run's files
   !>  phase        [in]     'start', 'lock' or 'pull'
   !>  load_over_h  [in]     H/h or delta/h of the last converged state
   !>  increments   [in]     converged increments so far
   subroutine write_progress(out, phase, load_over_h, increments)
      type(output_files), intent(inout) :: out
      character(len=*), intent(in) :: phase
      real(dp), intent(in) :: load_over_h
      integer, intent(in) :: increments
      integer :: stat
      character(len=:), allocatable :: why
      character(len=5) :: padded
      character(len=128) :: buf
      if (out%progress%fd == -1 .or. out%failed) return
      padded = phase
      write (buf, '(a,es24.16e3,a,i10)') 'status = running'//nl//'phase = '//padded//nl// &
         'load_over_h = ', load_over_h, nl//'increments = ', increments
      call file_write_at(out%progress%fd, trim(buf)//nl, 0, stat, why)
      call record_failure(out, out%progress, stat, why)
   end subroutine write_progress

   !> WRITE_ROW: one data row, at once; a failure is recorded in out.
   !>  out     [in,out] the run's files
   !>  f       [in]     an open file of the run (out%lock, out%pull)
   !>  values  [in]     the row
   subroutine write_row(out, f, values)
      type(output_files), intent(inout) :: out
      type(open_file), intent(in) :: f
      real(dp), intent(in) :: values(:)
      character(len=25*size(values)) :: buf
      write (buf, fmt_row) values
      call put(out, f, buf//nl)
   end subroutine write_row

   !> WRITE_TEXT_FILE: a whole file at once (summary.txt), replacing it.
   !>  path  [in]  the file
   !>  text  [in]  its bytes
   !>  stat  [out] 0, or errno of the failed create, write or close
   !>  msg   [out] '<path>: <the system's reason>' when stat /= 0
   subroutine write_text_file(path, text, stat, msg)
      character(len=*), intent(in) :: path, text
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: msg
      integer :: fd, stat2
      character(len=:), allocatable :: why, why2
      msg = ''
      call file_create(path, fd, stat, why)
      if (stat == 0) then
         call file_write(fd, text, stat, why)
         call file_close(fd, stat2, why2)
         if (stat == 0 .and. stat2 /= 0) then
            stat = stat2
            why = why2
         end if
      end if
      if (stat /= 0) msg = path//': '//why
   end subroutine write_text_file

   !> WRITE_STRAINS: strain distribution over the sheet, one row per Gauss point.
   !>  out   [in,out] the run's files (the file goes in out%dir; a failure
   !>                 is recorded)
   !>  name  [in] file name ('strain_lock.dat' ...)
   !>  m, s  [in] model and converged state
   !>  what  [in] text for the header ('after locking' ...)
   subroutine write_strains(out, name, m, s, what)
      type(output_files), intent(inout) :: out
      character(len=*), intent(in) :: name, what
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      type(open_file) :: f
      call open_new(out, name, f)
      call put(out, f, '# drawbead strain distribution '//trim(what)//nl//strain_columns//nl)
      call write_strain_rows(out, f, m, s)
      call close_file(out, f)
   end subroutine write_strains

   !> OPEN_SNAPSHOTS: open snapshots.dat in the output directory and write
   !> its header; the snapshots follow as blocks (write_snapshot).
   !>  out    [in,out] the run's files (out%dir set by open_outputs)
   !>  title  [in]  run title
   !>  every  [in]  the spacing of the snapshots, units of h (for the header)
   !>  errmsg [out] '' on success
   subroutine open_snapshots(out, title, every, errmsg)
      type(output_files), intent(inout) :: out
      character(len=*), intent(in) :: title
      real(dp), intent(in) :: every
      character(len=*), intent(out) :: errmsg
      character(len=32) :: buf
      errmsg = ''
      call open_new(out, 'snapshots.dat', out%snapshots)
      write (buf, '(g0.6)') every
      call put(out, out%snapshots, '# drawbead strain snapshots: '//trim(title)//nl// &
               '# one block (gnuplot index 0, 1, ...) at the first converged increment at or past'// &
               ' each multiple of '//trim(buf)//'h of H (locking) and of delta (pulling);'// &
               ' each block opens with a line: # block K phase load/h increment elements'// &
               ' (its rows are the Gauss stations of that mesh, which &sheet refine_exit splits once'// &
               ' while pulling)'//nl// &
               strain_columns//nl)
      out%n_snapshots = 0
      if (out%failed) errmsg = out%failure
   end subroutine open_snapshots

   !> WRITE_SNAPSHOT: append one block of strain rows to snapshots.dat;
   !> blocks are separated by two blank lines (gnuplot's index).
   !>  out    [in,out] the run's files (nothing is written if not open)
   !>  m, s   [in] model and converged state
   !>  phase  [in] 'lock' or 'pull'
   !>  load_over_h [in] H/h or delta/h of the state
   !>  increment   [in] the run's increment count at the state
   subroutine write_snapshot(out, m, s, phase, load_over_h, increment)
      type(output_files), intent(inout) :: out
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      character(len=*), intent(in) :: phase
      real(dp), intent(in) :: load_over_h
      integer, intent(in) :: increment
      character(len=128) :: buf
      if (out%snapshots%fd == -1) return
      if (out%n_snapshots > 0) call put(out, out%snapshots, nl//nl)
      write (buf, '(a,i0,1x,a,1x,es24.16e3,1x,i0,1x,i0)') '# block ', out%n_snapshots, phase, &
         load_over_h, increment, m%n_el
      call put(out, out%snapshots, trim(buf)//nl)
      call write_strain_rows(out, out%snapshots, m, s)
      out%n_snapshots = out%n_snapshots + 1
   end subroutine write_snapshot

   !> WRITE_STRAIN_ROWS: the rows of a strain file, one per Gauss point
   !> (columns: strain_columns), in one write.
   !>  out   [in,out] the run's files (a failure is recorded)
   !>  f     [in] open file
   !>  m, s  [in] model and converged state
   subroutine write_strain_rows(out, f, m, s)
      type(output_files), intent(inout) :: out
      type(open_file), intent(in) :: f
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      integer, parameter :: row_len = 19*25 + 1
      character(len=:), allocatable :: rows
      integer :: e, ig, dofs(8), mid, k
      real(dp) :: le, nv(4), dn(4), d2n(4), v, w, h, eps, top, bot, e22, epmax
      h = m%thickness
      mid = (m%npt + 1)/2
      allocate (character(len=row_len*n_gauss*m%n_el) :: rows)
      k = 0
      do e = 1, m%n_el
         dofs = element_dofs(e)
         le = m%x(e + 1) - m%x(e)
         do ig = 1, n_gauss
            call hermite_shape(gauss_xi(ig), le, nv, dn, d2n)
            v = dot_product(nv, s%u(dofs(v_dofs)))
            w = dot_product(nv, s%u(dofs(w_dofs)))
            eps = s%gpn(igp_strain, ig, e)
            top = s%hn(m%npt, ih_strain, ig, e)
            bot = s%hn(1, ih_strain, ig, e)
            e22 = s%hn(mid, col_eps22(m%material), ig, e)
            ! a law without an equivalent plastic strain: -1 (the header says so)
            epmax = -1.0_dp
            if (col_eqps(m%material) > 0) epmax = maxval(s%hn(:, col_eqps(m%material), ig, e))
            write (rows(k + 1:k + row_len - 1), fmt_row) gauss_position(m, e, ig)/h, &
               (gauss_position(m, e, ig) + v)/h, &
               w/h, eps, log(1.0_dp + eps), top, bot, e22, epmax, s%gpn(igp_curvature, ig, e)*h, &
               s%gpn(igp_force, ig, e)/(m%youngs*h), s%gpn(igp_moment, ig, e)/(m%youngs*h*h), &
               s%indicator(ig, e), s%hn(m%npt, ih_stress22, ig, e), s%hn(1, ih_stress22, ig, e), &
               merge(s%cn(ich_pressure, ig, e, :), 0.0_dp, s%cn(ich_active, ig, e, :) > 0.5_dp), &
               merge(s%cn(ich_mu, ig, e, :), 0.0_dp, s%cn(ich_active, ig, e, :) > 0.5_dp)
            rows(k + row_len:k + row_len) = nl
            k = k + row_len
         end do
      end do
      call put(out, f, rows)
   end subroutine write_strain_rows

   !> WRITE_TOOLS: the tools' centreline surfaces at the lower tool's rise H,
   !> sampled at 400 points each, upper tool first, a blank line between
   !> (gnuplot: plot 'tools_lock.dat' index 0 / index 1, or both as one).
   !>  out    [in,out] the run's files (a failure is recorded)
   !>  name   [in] file name inside out%dir
   !>  m      [in] model (tools)
   !>  shift  [in] the lower tool's rise H, mm
   !>  what   [in] text for the header
   subroutine write_tools(out, name, m, shift, what)
      type(output_files), intent(inout) :: out
      character(len=*), intent(in) :: name, what
      type(model_type), intent(in) :: m
      real(dp), intent(in) :: shift
      integer, parameter :: n = 400
      real(dp) :: xy(2, n)
      type(open_file) :: f
      integer :: it, k
      if (.not. m%has_tools) return
      call open_new(out, name, f)
      call put(out, f, '# drawbead tool surfaces (centreline surfaces: the physical surfaces'// &
               ' offset by h/2 toward the sheet) '//trim(what)//nl// &
               '# 1:x/h 2:y/h ; block 0 = upper (female) tool, block 1 = lower (male) tool'//nl)
      do it = 1, 2
         call tool_sample(m%tool(it), n, xy)
         if (it == 2) xy(2, :) = xy(2, :) + shift
         if (it == 2) call put(out, f, nl//nl)
         do k = 1, n
            call write_row(out, f, xy(:, k)/m%thickness)
         end do
      end do
      call close_file(out, f)
   end subroutine write_tools

   !> CLOSE_OUTPUTS: close the files kept open (the progress summary too:
   !> the final summary.txt replaces it).
   !>  out  [in,out] the run's files (a failed close is recorded)
   subroutine close_outputs(out)
      type(output_files), intent(inout) :: out
      call close_file(out, out%lock)
      call close_file(out, out%pull)
      call close_file(out, out%snapshots)
      call close_file(out, out%progress)
   end subroutine close_outputs

   !> CLOSE_FILE: close a file of the run if open; fd = -1 after.
   !>  out  [in,out] the run's files (a failed close is recorded)
   !>  f    [in,out] the file
   subroutine close_file(out, f)
      type(output_files), intent(inout) :: out
      type(open_file), intent(inout) :: f
      integer :: stat
      character(len=:), allocatable :: why
      if (f%fd == -1) return
      call file_close(f%fd, stat, why)
      call record_failure(out, f, stat, why)
      f%fd = -1
   end subroutine close_file
end module output
