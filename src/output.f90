!> output -- column text files, the run log and the summary.
!>
!> Every file starts with '#' lines naming each column and its unit; data are
!> written with (*(1x,es24.16e3)) so real64 round-trips, and flushed each
!> increment so a run that stops early keeps what it computed.
module output
   use kinds, only: dp
   use hermite, only: n_gauss, gauss_xi, hermite_shape
   use mesh, only: element_dofs
   use element, only: v_dofs, w_dofs
   use section, only: ih_strain, ih_statev
   use model, only: model_type, state_type, gauss_position
   use tools, only: tool_sample
   implicit none
   private
   public :: output_files, open_outputs, write_row, write_strains, write_summary_line, &
             close_outputs, make_directory, fmt_row, write_tools, open_snapshots, write_snapshot

   character(len=*), parameter :: fmt_row = '(*(1x,es24.16e3))'

   !> Units of the files kept open through a run.
   type :: output_files
      character(len=:), allocatable :: dir
      integer :: lock = -1, pull = -1
      integer :: snapshots = -1, n_snapshots = 0  ! snapshots.dat (&control snapshot_every)
      ! (units from NEWUNIT are negative and never -1: -1 marks a file not open)
   end type output_files

   !> The column header of the strain files (strain_*.dat, snapshots.dat).
   character(len=*), parameter :: strain_columns = &
      '# 1:s/h (reference position) 2:x/h 3:y/h (current centreline) 4:lambda-1'// &
      ' 5:ln(lambda) 6:top_fibre_log_strain 7:bottom_fibre_log_strain'// &
      ' 8:thickness_log_strain(mid-surface) 9:max_equivalent_plastic_strain(through thickness)'// &
      ' 10:rho*h (bending strain) 11:N/(E h) 12:M/(E h^2)'// &
      ' 13:localization_indicator (smallest eigenvalue of the scaled section tangent, <= 0: localized)'

contains

   !> MAKE_DIRECTORY: create a directory and its parents (mkdir -p).
   !>  path  [in]  directory
   !>  stat  [out] 0 on success
   subroutine make_directory(path, stat)
      character(len=*), intent(in) :: path
      integer, intent(out) :: stat
      integer :: cstat
      call execute_command_line('mkdir -p "'//trim(path)//'"', exitstat=stat, cmdstat=cstat)
      if (cstat /= 0) stat = cstat
   end subroutine make_directory

   !> OPEN_OUTPUTS: create the output directory, open lock.dat and pull.dat and
   !> write their headers.
   !>  dir    [in]  output directory
   !>  title  [in]  run title (echoed in the headers)
   !>  out    [out] the open files
   !>  errmsg [out] '' on success
   subroutine open_outputs(dir, title, out, errmsg)
      character(len=*), intent(in) :: dir, title
      type(output_files), intent(out) :: out
      character(len=*), intent(out) :: errmsg
      integer :: stat
      errmsg = ''
      out%dir = trim(dir)
      call make_directory(out%dir, stat)
      if (stat /= 0) then
         errmsg = 'cannot create output directory '//out%dir
         return
      end if
      open (newunit=out%lock, file=out%dir//'/lock.dat', status='replace', action='write', iostat=stat)
      if (stat == 0) open (newunit=out%pull, file=out%dir//'/pull.dat', status='replace', &
                           action='write', iostat=stat)
      if (stat /= 0) then
         errmsg = 'cannot write in output directory '//out%dir
         return
      end if
      write (out%lock, '(a)') '# drawbead locking: '//trim(title), &
         '# 1:H/h 2:F/(E h) 3:F[N/mm] 4:newton_iterations 5:dH/h 6:min_localization_indicator[-]'// &
         ' 7:max_penetration/h 8:N/(E h) 9:N[N/mm]', &
         '# F = upward force of the lower tool on the sheet per unit width (punch force);'// &
         ' N = horizontal reaction at the right edge'
      write (out%pull, '(a)') '# drawbead pulling: '//trim(title), &
         '# 1:delta/h 2:N/(E h) 3:N[N/mm] 4:newton_iterations 5:d(delta)/h 6:min_localization_indicator[-]'// &
         ' 7:lift/(E h) 8:lift[N/mm] 9:max_penetration/h 10:F/(E h)', &
         '# N = restraining force (horizontal reaction at the right edge) per unit width;'// &
         ' lift = vertical force of the sheet opening the binder (on the upper tool)'
      flush (out%lock)
      flush (out%pull)
   end subroutine open_outputs

   !> WRITE_ROW: one data row, flushed.
   subroutine write_row(unit, values)
      integer, intent(in) :: unit
      real(dp), intent(in) :: values(:)
      write (unit, fmt_row) values
      flush (unit)
   end subroutine write_row

   !> WRITE_SUMMARY_LINE: 'key = value' with a real value, or 'none' if absent.
   subroutine write_summary_line(unit, key, value, present_flag)
      integer, intent(in) :: unit
      character(len=*), intent(in) :: key
      real(dp), intent(in) :: value
      logical, intent(in) :: present_flag
      character(len=32) :: buf
      if (present_flag) then
         write (buf, '(es24.16e3)') value
         write (unit, '(a)') key//' = '//trim(adjustl(buf))
      else
         write (unit, '(a)') key//' = none'
      end if
   end subroutine write_summary_line

   !> WRITE_STRAINS: strain distribution over the sheet, one row per Gauss point.
   !>  path  [in] file to write
   !>  m, s  [in] model and converged state
   !>  what  [in] text for the header ('after locking' ...)
   subroutine write_strains(path, m, s, what)
      character(len=*), intent(in) :: path, what
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      integer :: unit, stat
      open (newunit=unit, file=path, status='replace', action='write', iostat=stat)
      if (stat /= 0) return
      write (unit, '(a)') '# drawbead strain distribution '//trim(what), strain_columns
      call write_strain_rows(unit, m, s)
      close (unit)
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
      character(len=32) :: buf
      errmsg = ''
      open (newunit=out%snapshots, file=out%dir//'/snapshots.dat', status='replace', &
            action='write', iostat=stat)
      if (stat /= 0) then
         errmsg = 'cannot write in output directory '//out%dir
         out%snapshots = -1
         return
      end if
      write (buf, '(g0.6)') every
      write (out%snapshots, '(a)') '# drawbead strain snapshots: '//trim(title), &
         '# one block (gnuplot index 0, 1, ...) at the first converged increment at or past'// &
         ' each multiple of '//trim(buf)//'h of H (locking) and of delta (pulling);'// &
         ' each block opens with a line: # block K phase load/h increment', strain_columns
      out%n_snapshots = 0
      flush (out%snapshots)
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
      if (out%snapshots == -1) return
      if (out%n_snapshots > 0) write (out%snapshots, '(/)')
      write (out%snapshots, '(a,i0,1x,a,1x,es24.16e3,1x,i0)') '# block ', out%n_snapshots, phase, &
         load_over_h, increment
      call write_strain_rows(out%snapshots, m, s)
      flush (out%snapshots)
      out%n_snapshots = out%n_snapshots + 1
   end subroutine write_snapshot

   !> WRITE_STRAIN_ROWS: the rows of a strain file, one per Gauss point
   !> (columns: strain_columns).
   !>  unit  [in] open file
   !>  m, s  [in] model and converged state
   subroutine write_strain_rows(unit, m, s)
      integer, intent(in) :: unit
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      integer :: e, ig, dofs(8), mid
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
            write (unit, fmt_row) gauss_position(m, e, ig)/h, (gauss_position(m, e, ig) + v)/h, &
               w/h, eps, log(1.0_dp + eps), top, bot, e22, epmax, s%gpn(2, ig, e)*h, &
               s%gpn(3, ig, e)/(m%youngs*h), s%gpn(4, ig, e)/(m%youngs*h*h), s%indicator(ig, e)
         end do
      end do
   end subroutine write_strain_rows

   !> WRITE_TOOLS: the tools' centreline surfaces at the lower tool's rise H,
   !> sampled at 400 points each, upper tool first, a blank line between
   !> (gnuplot: plot 'tools_lock.dat' index 0 / index 1, or both as one).
   !>  path   [in] file to write
   !>  m      [in] model (tools)
   !>  shift  [in] the lower tool's rise H, mm
   !>  what   [in] text for the header
   subroutine write_tools(path, m, shift, what)
      character(len=*), intent(in) :: path, what
      type(model_type), intent(in) :: m
      real(dp), intent(in) :: shift
      integer, parameter :: n = 400
      real(dp) :: xy(2, n)
      integer :: unit, it, k, stat
      if (.not. m%has_tools) return
      open (newunit=unit, file=path, status='replace', action='write', iostat=stat)
      if (stat /= 0) return
      write (unit, '(a)') '# drawbead tool surfaces (centreline surfaces: the physical surfaces'// &
         ' offset by h/2 toward the sheet) '//trim(what), &
         '# 1:x/h 2:y/h ; block 0 = upper (female) tool, block 1 = lower (male) tool'
      do it = 1, 2
         call tool_sample(m%tool(it), n, xy)
         if (it == 2) xy(2, :) = xy(2, :) + shift
         if (it == 2) write (unit, '(a)') '', ''
         do k = 1, n
            write (unit, fmt_row) xy(:, k)/m%thickness
         end do
      end do
      close (unit)
   end subroutine write_tools

   !> CLOSE_OUTPUTS: close the files kept open.
   subroutine close_outputs(out)
      type(output_files), intent(inout) :: out
      ! NEWUNIT numbers are negative and never -1, the value of a closed file
      if (out%lock /= -1) close (out%lock)
      if (out%pull /= -1) close (out%pull)
      if (out%snapshots /= -1) close (out%snapshots)
      out%lock = -1
      out%pull = -1
      out%snapshots = -1
   end subroutine close_outputs
end module output
