!> exit_state -- the state of the sheet leaving the bead (docs/theory.md
!> §9.1): the thickness and, per thickness point, the equivalent plastic
!> strain and the stresses of the material just past the exit of the last
!> radius at the end of the pull, as a table (exit_state.dat) and as the
!> LS-DYNA cards that put it on the elements of a stamping model
!> downstream of an equivalent bead (exit_state.k, *INITIAL_STRESS_SHELL_SET).
!>
!> The station: the Gauss station of the sheet nearest to exit_offset_over_h
!> thicknesses past the exit of the last radius (remesh's
!> last_radius_exit).  Its material has passed the whole bead when it
!> started (reference position) left of the bead's first radius at the
!> end of the run (the smallest x of a station touching a tool arc,
!> last_radius_exit's x_entry): the
!> files say whether it has; in a steady free-edge draw pulled about the
!> bead's developed length it has.
module exit_state
   use kinds, only: dp
   use hermite, only: n_gauss
   use model, only: model_type, state_type, gauss_position
   use section, only: ih_strain, ih_zbar, ih_stress, ih_stress22, col_eqps, col_eps22
   use contact, only: ich_position
   use remesh, only: last_radius_exit
   use text, only: num
   implicit none
   private
   public :: exit_state_text, exit_offset_over_h

   !> how far past the exit of the last radius the station is, units of h
   real(dp), parameter :: exit_offset_over_h = 3.0_dp

contains

   !> EXIT_STATE_TEXT: the two files' text, or a note when there are no
   !> tools or no station past the exit.
   !>  m, s    [in]  model and converged state (after the pull)
   !>  title   [in]  the run's title
   !>  table   [out] exit_state.dat
   !>  cards   [out] exit_state.k
   !>  found   [out] .false.: no station past the exit (the texts say why)
   subroutine exit_state_text(m, s, title, table, cards, found)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      character(len=*), intent(in) :: title
      character(len=:), allocatable, intent(out) :: table, cards
      logical, intent(out) :: found
      character(len=*), parameter :: nl = achar(10)
      character(len=200) :: row
      real(dp) :: x_exit, x_entry, h, target, best, x, s_ref, t_now, zmid, tk
      integer :: e, ig, be, bg, k, npt, ieq, ie22
      logical :: has_exit, passed
      h = m%thickness
      npt = m%npt
      found = .false.
      table = '# drawbead: the state of the sheet leaving the bead: '//trim(title)//nl
      cards = '$ drawbead: the state of the sheet leaving the bead: '//trim(title)//nl
      call last_radius_exit(m, s, x_exit, has_exit, x_entry)
      if (.not. has_exit) then
         table = table//'# no station touches a tool radius: no bead exit, no state written'//nl
         cards = cards//'$ no station touches a tool radius: no bead exit, no state written'//nl
         return
      end if
      target = x_exit + exit_offset_over_h*h
      best = huge(1.0_dp)
      be = 0
      bg = 0
      do e = 1, m%n_el
         do ig = 1, n_gauss
            x = current_x(m, s, e, ig)
            if (abs(x - target) < best) then
               best = abs(x - target)
               be = e
               bg = ig
            end if
         end do
      end do
      found = .true.
      s_ref = gauss_position(m, be, bg)
      x = current_x(m, s, be, bg)
      passed = s_ref < x_entry
      t_now = s%hn(npt, ih_zbar, bg, be) - s%hn(1, ih_zbar, bg, be)
      zmid = 0.5_dp*(s%hn(npt, ih_zbar, bg, be) + s%hn(1, ih_zbar, bg, be))
      ieq = col_eqps(m%material)
      ie22 = col_eps22(m%material)
      table = table// &
              '# station: s/h = '//num(s_ref/h)//' (reference), x/h = '//num(x/h)//', '// &
              num(exit_offset_over_h)//'h past the exit of the last radius (x/h = '//num(x_exit/h)//')'//nl// &
              '# passed the whole bead: '//merge('yes', 'no ', passed)// &
              ' (its material started left of the first radius, x/h = '//num(x_entry/h)//')'//nl// &
              '# thickness/h = '//num(t_now/h)//', mid-surface thickness log strain = '// &
              num(s%hn((npt + 1)/2, ie22, bg, be))//nl// &
              '# 1:z/h (reference) 2:zbar/h (current) 3:T (LS-DYNA through-thickness coordinate, -1..1)'// &
              ' 4:equivalent_plastic_strain (-1: the law has none) 5:tau11[MPa] (axial) 6:tau22[MPa]'// &
              ' (thickness) 7:tau33[MPa] (width) 8:fibre_log_strain'//nl
      cards = cards// &
              '$ the material '//num(exit_offset_over_h)//'h past the exit of the last radius (s/h = '// &
              num(s_ref/h)//'), passed the whole bead: '//trim(merge('yes', 'no ', passed))//nl// &
              '$ thickness '//num(t_now)//' mm: give it to the shells (*SECTION_SHELL T1..T4 or'// &
              ' *ELEMENT_SHELL_THICKNESS)'//nl// &
              '$ shell axes: x = the drawing direction, y = the bead''s length (width), z = normal;'// &
              ' one in-plane point, the program''s thickness points (LS-DYNA interpolates to its own)'//nl// &
              '$ SHELLSET: the shell set (*SET_SHELL) of the elements downstream of the bead: fill it in'//nl// &
              '*PARAMETER'//nl//'$#  name     value'//nl//'I SHELLSET         0'//nl// &
              '*INITIAL_STRESS_SHELL_SET'//nl// &
              '$#     SID    NPLANE    NTHICK     NHISV    NTENSR     LARGE    NTHINT    NTHHSV'//nl// &
              '&SHELLSET'//repeat(' ', 1)//int10(1)//int10(npt)//int10(0)//int10(0)//int10(0)// &
              int10(0)//int10(0)//nl// &
              '$#       T     SIGXX     SIGYY     SIGZZ     SIGXY     SIGYZ     SIGZX       EPS'//nl
      do k = 1, npt
         tk = 2.0_dp*(s%hn(k, ih_zbar, bg, be) - zmid)/t_now
         write (row, '(8es15.7)') m%z(k)/h, s%hn(k, ih_zbar, bg, be)/h, tk, eqps_of(k), &
            s%hn(k, ih_stress, bg, be), s%hn(k, ih_stress22, bg, be), s%hn(k, ih_stress + 1, bg, be), &
            s%hn(k, ih_strain, bg, be)
         table = table//trim(row)//nl
         cards = cards//real10(tk)//real10(s%hn(k, ih_stress, bg, be))// &
                 real10(s%hn(k, ih_stress + 1, bg, be))//real10(s%hn(k, ih_stress22, bg, be))// &
                 real10(0.0_dp)//real10(0.0_dp)//real10(0.0_dp)//real10(max(eqps_of(k), 0.0_dp))//nl
      end do

   contains

      !> the equivalent plastic strain of point k, -1 when the law has none
      real(dp) function eqps_of(k)
         integer, intent(in) :: k
         eqps_of = -1.0_dp
         if (ieq > 0) eqps_of = s%hn(k, ieq, bg, be)
      end function eqps_of
   end subroutine exit_state_text

   !> The current abscissa of Gauss station ig of element e (the contact
   !> history's position: every station has one, in contact or not).
   real(dp) function current_x(m, s, e, ig)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      integer, intent(in) :: e, ig
      associate (unused => m)
      end associate
      current_x = s%cn(ich_position, ig, e, 1)
   end function current_x


   !> A 10-character integer field.
   function int10(i) result(f)
      integer, intent(in) :: i
      character(len=10) :: f
      write (f, '(i10)') i
   end function int10

   !> A 10-character real field of LS-DYNA's fixed format: five significant
   !> digits with a one-digit exponent (values below 1e-9 in magnitude
   !> written as 0).
   function real10(x) result(f)
      real(dp), intent(in) :: x
      character(len=10) :: f
      if (abs(x) < 1.0e-9_dp) then
         write (f, '(f10.1)') 0.0_dp
      else
         write (f, '(es10.4e1)') x
      end if
   end function real10
end module exit_state
