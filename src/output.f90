!> output -- the column text files of a run.
!>
!> Every file starts with '#' lines naming each column and its unit; data are
!> written with (*(1x,es24.16e3)) so real64 round-trips, and flushed each
!> increment so a run that stops early keeps what it computed.
!>
!> The output directory belongs to the run: open_outputs creates it (by
!> the mkdir system call, never a shell), removes the result files an
!> earlier run left there (only the names in result_files) and starts
!> summary.txt with status = running, which write_progress keeps true
!> increment by increment until the summary module writes the final one.
!> Every write, flush and close checks its status: the first failure is
!> kept in output_files (failed, failure: the file and the system's
!> reason) and the increment loop stops the run on it.
module output
   use kinds, only: dp
   use hermite, only: n_gauss, gauss_xi, hermite_shape
   use mesh, only: element_dofs
   use element, only: v_dofs, w_dofs
   use section, only: ih_strain, ih_statev
   use model, only: model_type, state_type, gauss_position
   use tools, only: tool_sample
   use os, only: make_directory
   implicit none
   private
   public :: output_files, open_outputs, write_row, write_strains, &
             close_outputs, fmt_row, write_tools, open_snapshots, write_snapshot, write_progress, &
             result_files, check_io

   character(len=*), parameter :: fmt_row = '(*(1x,es24.16e3))'

   !> Every file a run writes in its output directory (removed before the
   !> first increment, so no result of an earlier run is left beside this one's).
   character(len=*), parameter :: result_files(9) = [character(len=23) :: &
      'summary.txt', 'lock.dat', 'pull.dat', 'strain_lock.dat', 'strain_pull.dat', &
      'strain_localization.dat', 'tools_lock.dat', 'tools_pull.dat', 'snapshots.dat']

   !> Units of the files kept open through a run, and the first failed write.
   type :: output_files
      character(len=:), allocatable :: dir
      integer :: lock = -1, pull = -1
      integer :: snapshots = -1, n_snapshots = 0  ! snapshots.dat (&control snapshot_every)
      integer :: progress = -1                    ! summary.txt while the run goes
      ! (units from NEWUNIT are negative and never -1: -1 marks a file not open)
      logical :: failed = .false.
      character(len=:), allocatable :: failure    ! '<file>: <the system's reason>'
   end type output_files

   !> The column header of the strain files (strain_*.dat, snapshots.dat).
   character(len=*), parameter :: strain_columns = &
      '# 1:s/h (reference position) 2:x/h 3:y/h (current centreline) 4:lambda-1'// &
      ' 5:ln(lambda) 6:top_fibre_log_strain 7:bottom_fibre_log_strain'// &
      ' 8:thickness_log_strain(mid-surface) 9:max_equivalent_plastic_strain(through thickness)'// &
      ' 10:rho*h (bending strain) 11:N/(E h) 12:M/(E h^2)'// &
      ' 13:localization_indicator (smallest eigenvalue of the scaled section tangent, <= 0: localized)'

contains

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
      character(len=256) :: iomsg
      integer :: stat, k, u
      logical :: exists
      errmsg = ''
      out%dir = trim(dir)
      call make_directory(out%dir, stat, why)
      if (stat /= 0) then
         errmsg = 'cannot create output directory '//out%dir//': '//why
         return
      end if
      do k = 1, size(result_files)
         inquire (file=out%dir//'/'//trim(result_files(k)), exist=exists)
         if (.not. exists) cycle
         open (newunit=u, file=out%dir//'/'//trim(result_files(k)), status='old', iostat=stat, &
               iomsg=iomsg)
         if (stat == 0) close (u, status='delete', iostat=stat, iomsg=iomsg)
         if (stat /= 0) then
            errmsg = 'cannot remove '//out%dir//'/'//trim(result_files(k))//' of an earlier run: '// &
                     trim(iomsg)
            return
         end if
      end do
      call open_new(out, 'summary.txt', out%progress)
      call write_progress(out, 'start', 0.0_dp, 0)
      call open_new(out, 'lock.dat', out%lock)
      call open_new(out, 'pull.dat', out%pull)
      if (out%failed) then
         errmsg = out%failure
         return
      end if
      write (out%lock, '(a)', iostat=stat, iomsg=iomsg) '# drawbead locking: '//trim(title), &
         '# 1:H/h 2:F/(E h) 3:F[N/mm] 4:newton_iterations 5:dH/h 6:min_localization_indicator[-]'// &
         ' 7:max_penetration/h 8:N/(E h) 9:N[N/mm]', &
         '# F = upward force of the lower tool on the sheet per unit width (punch force);'// &
         ' N = horizontal reaction at the right edge'
      call check_io(out, out%lock, stat, iomsg)
      write (out%pull, '(a)', iostat=stat, iomsg=iomsg) '# drawbead pulling: '//trim(title), &
         '# 1:delta/h 2:N/(E h) 3:N[N/mm] 4:newton_iterations 5:d(delta)/h 6:min_localization_indicator[-]'// &
         ' 7:lift/(E h) 8:lift[N/mm] 9:max_penetration/h 10:F/(E h)', &
         '# N = restraining force (horizontal reaction at the right edge) per unit width;'// &
         ' lift = vertical force of the sheet opening the binder (on the upper tool)'
      call check_io(out, out%pull, stat, iomsg)
      flush (out%lock, iostat=stat, iomsg=iomsg)
      call check_io(out, out%lock, stat, iomsg)
      flush (out%pull, iostat=stat, iomsg=iomsg)
      call check_io(out, out%pull, stat, iomsg)
      if (out%failed) errmsg = out%failure
   end subroutine open_outputs

   !> OPEN_NEW: open a new result file of the run's directory for writing.
   !>  out   [in,out] the run's files (a failure is recorded)
   !>  name  [in]     file name inside out%dir
   !>  unit  [out]    its unit, -1 when it could not be opened
   subroutine open_new(out, name, unit)
      type(output_files), intent(inout) :: out
      character(len=*), intent(in) :: name
      integer, intent(out) :: unit
      integer :: stat
      character(len=256) :: iomsg
      open (newunit=unit, file=out%dir//'/'//name, status='replace', action='write', &
            iostat=stat, iomsg=iomsg)
      if (stat /= 0) then
         unit = -1
         if (.not. out%failed) out%failure = out%dir//'/'//name//': '//trim(iomsg)
         out%failed = .true.
      end if
   end subroutine open_new

   !> CHECK_IO: record the first failed transfer on a unit (its file name
   !> and the system's reason).
   !>  out    [in,out] the run's files
   !>  unit   [in]     the unit written, flushed or closed
   !>  stat   [in]     its iostat
   !>  iomsg  [in]     its iomsg
   subroutine check_io(out, unit, stat, iomsg)
      type(output_files), intent(inout) :: out
      integer, intent(in) :: unit, stat
      character(len=*), intent(in) :: iomsg
      character(len=512) :: name
      integer :: ios
      if (stat == 0 .or. out%failed) return
      name = '(a closed unit)'
      inquire (unit=unit, name=name, iostat=ios)
      out%failed = .true.
      out%failure = trim(name)//': '//trim(iomsg)
   end subroutine check_io

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
      character(len=256) :: iomsg
      if (out%progress == -1) return
      rewind (out%progress, iostat=stat, iomsg=iomsg)
      if (stat == 0) write (out%progress, '(a/a,a5/a,es24.16e3/a,i10)', iostat=stat, iomsg=iomsg) &
         'status = running', 'phase = ', phase, 'load_over_h = ', load_over_h, 'increments = ', &
         increments
      if (stat == 0) flush (out%progress, iostat=stat, iomsg=iomsg)
      call check_io(out, out%progress, stat, iomsg)
   end subroutine write_progress

   !> WRITE_ROW: one data row, flushed; a failure is recorded in out.
   !>  out     [in,out] the run's files
   !>  unit    [in]     an open file of the run (out%lock, out%pull)
   !>  values  [in]     the row
   subroutine write_row(out, unit, values)
      type(output_files), intent(inout) :: out
      integer, intent(in) :: unit
      real(dp), intent(in) :: values(:)
      integer :: stat
      character(len=256) :: iomsg
      write (unit, fmt_row, iostat=stat, iomsg=iomsg) values
      if (stat == 0) flush (unit, iostat=stat, iomsg=iomsg)
      call check_io(out, unit, stat, iomsg)
   end subroutine write_row

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
      integer :: unit, stat
      character(len=256) :: iomsg
      call open_new(out, name, unit)
      if (unit == -1) return
      write (unit, '(a)', iostat=stat, iomsg=iomsg) '# drawbead strain distribution '//trim(what), &
         strain_columns
      call check_io(out, unit, stat, iomsg)
      call write_strain_rows(out, unit, m, s)
      close (unit, iostat=stat, iomsg=iomsg)
      call check_io(out, unit, stat, iomsg)
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
      integer :: stat
      character(len=256) :: iomsg
      character(len=32) :: buf
      errmsg = ''
      call open_new(out, 'snapshots.dat', out%snapshots)
      if (out%failed) then
         errmsg = out%failure
         return
      end if
      write (buf, '(g0.6)') every
      write (out%snapshots, '(a)', iostat=stat, iomsg=iomsg) '# drawbead strain snapshots: '// &
         trim(title), &
         '# one block (gnuplot index 0, 1, ...) at the first converged increment at or past'// &
         ' each multiple of '//trim(buf)//'h of H (locking) and of delta (pulling);'// &
         ' each block opens with a line: # block K phase load/h increment', strain_columns
      if (stat == 0) flush (out%snapshots, iostat=stat, iomsg=iomsg)
      call check_io(out, out%snapshots, stat, iomsg)
      out%n_snapshots = 0
      if (out%failed) errmsg = out%failure
   end subroutine open_snapshots

   !> WRITE_SNAPSHOT: append one block of strain rows to snapshots.dat,
   !> flushed; blocks are separated by two blank lines (gnuplot's index).
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
      integer :: stat
      character(len=256) :: iomsg
      if (out%snapshots == -1) return
      stat = 0
      if (out%n_snapshots > 0) write (out%snapshots, '(/)', iostat=stat, iomsg=iomsg)
      if (stat == 0) write (out%snapshots, '(a,i0,1x,a,1x,es24.16e3,1x,i0)', iostat=stat, &
                            iomsg=iomsg) '# block ', out%n_snapshots, phase, load_over_h, increment
      call check_io(out, out%snapshots, stat, iomsg)
      call write_strain_rows(out, out%snapshots, m, s)
      flush (out%snapshots, iostat=stat, iomsg=iomsg)
      call check_io(out, out%snapshots, stat, iomsg)
      out%n_snapshots = out%n_snapshots + 1
   end subroutine write_snapshot

   !> WRITE_STRAIN_ROWS: the rows of a strain file, one per Gauss point
   !> (columns: strain_columns).
   !>  out   [in,out] the run's files (a failure is recorded)
   !>  unit  [in] open file
   !>  m, s  [in] model and converged state
   subroutine write_strain_rows(out, unit, m, s)
      type(output_files), intent(inout) :: out
      integer, intent(in) :: unit
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      integer :: e, ig, dofs(8), mid, stat
      character(len=256) :: iomsg
      real(dp) :: le, nv(4), dn(4), d2n(4), v, w, h, eps, top, bot, e22, epmax
      h = m%thickness
      mid = (m%npt + 1)/2
      do e = 1, m%n_el
         dofs = element_dofs(e)
         le = m%x(e + 1) - m%x(e)
         do ig = 1, n_gauss
            call hermite_shape(gauss_xi(ig), le, nv, dn, d2n)
            v = dot_product(nv, s%u(dofs(v_dofs)))
            w = dot_product(nv, s%u(dofs(w_dofs)))
            eps = s%gpn(1, ig, e)
            top = s%hn(m%npt, ih_strain, ig, e)
            bot = s%hn(1, ih_strain, ig, e)
            e22 = s%hn(mid, ih_statev + 1, ig, e)
            epmax = maxval(s%hn(:, ih_statev, ig, e))
            write (unit, fmt_row, iostat=stat, iomsg=iomsg) gauss_position(m, e, ig)/h, &
               (gauss_position(m, e, ig) + v)/h, &
               w/h, eps, log(1.0_dp + eps), top, bot, e22, epmax, s%gpn(2, ig, e)*h, &
               s%gpn(3, ig, e)/(m%youngs*h), s%gpn(4, ig, e)/(m%youngs*h*h), s%indicator(ig, e)
            call check_io(out, unit, stat, iomsg)
            if (out%failed) return
         end do
      end do
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
      integer :: unit, it, k, stat
      character(len=256) :: iomsg
      if (.not. m%has_tools) return
      call open_new(out, name, unit)
      if (unit == -1) return
      write (unit, '(a)', iostat=stat, iomsg=iomsg) &
         '# drawbead tool surfaces (centreline surfaces: the physical surfaces'// &
         ' offset by h/2 toward the sheet) '//trim(what), &
         '# 1:x/h 2:y/h ; block 0 = upper (female) tool, block 1 = lower (male) tool'
      call check_io(out, unit, stat, iomsg)
      do it = 1, 2
         call tool_sample(m%tool(it), n, xy)
         if (it == 2) xy(2, :) = xy(2, :) + shift
         if (it == 2) write (unit, '(a)', iostat=stat, iomsg=iomsg) '', ''
         call check_io(out, unit, stat, iomsg)
         do k = 1, n
            write (unit, fmt_row, iostat=stat, iomsg=iomsg) xy(:, k)/m%thickness
            call check_io(out, unit, stat, iomsg)
         end do
      end do
      close (unit, iostat=stat, iomsg=iomsg)
      call check_io(out, unit, stat, iomsg)
   end subroutine write_tools

   !> CLOSE_OUTPUTS: close the files kept open (the progress summary too:
   !> the final summary.txt replaces it).
   !>  out  [in,out] the run's files (a failed close is recorded)
   subroutine close_outputs(out)
      type(output_files), intent(inout) :: out
      call close_one(out, out%lock)
      call close_one(out, out%pull)
      call close_one(out, out%snapshots)
      call close_one(out, out%progress)
   end subroutine close_outputs

   !> CLOSE_ONE: close a unit of the run if open (NEWUNIT numbers are
   !> negative and never -1, the value of a closed file); -1 after.
   subroutine close_one(out, unit)
      type(output_files), intent(inout) :: out
      integer, intent(inout) :: unit
      integer :: stat
      character(len=256) :: iomsg
      if (unit == -1) return
      close (unit, iostat=stat, iomsg=iomsg)
      call check_io(out, unit, stat, iomsg)
      unit = -1
   end subroutine close_one
end module output
