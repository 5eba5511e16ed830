!> hardening -- the hardening laws of the built-in material (material_j2)
!> and the reader of a hardening-curve file.
!>
!> Purpose
!>   The uniaxial true stress - natural strain curve sigma_y(ebar_p) and its
!>   slope H' = d sigma_y / d ebar_p, one point at a time (flow_stress) or
!>   for a block of points (flow_stress_block, vectorized), the plastic work
!>   W(ebar_p) = int sigma_y d ebar_p that gives the dissipation, the check
!>   of the law constants, and read_curve_file, which turns a two-column
!>   text file into the points of the table law.
!>
!> Layout of the law in the material constants props(:) of material_j2
!>   props(1:3) are the elastic constants (E, nu, R: see material_j2);
!>   props(ip_law) is the law id, the law constants follow it:
!>     Swift (law_swift):  props(ip_swift_k), (ip_swift_eps0), (ip_swift_n)
!>                         = K, eps0, n;      sigma_y = K (eps0 + ebar_p)^n
!>     Voce (law_voce):    props(ip_voce_sigma0), (ip_voce_q), (ip_voce_b)
!>                         = sigma0, Q, b;    sigma_y = sigma0 + Q (1 - exp(-b ebar_p))
!>     table (law_table):  props(ip_table_m) = m, the number of points, then
!>                         point i = 1..m is (ebar_p_i, sigma_i) =
!>                         (props(ip_table_m + 2i - 1), props(ip_table_m + 2i)),
!>                         ebar_p_1 = 0; linear between the points, the last
!>                         segment extrapolated.
module hardening
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use text, only: itoa, num
   use pair_file, only: read_pairs
   implicit none
   private

   public :: law_swift, law_voce, law_table
   public :: ip_youngs, ip_poisson, ip_r_value, ip_law, ip_law_constants, ip_swift_k, ip_swift_eps0, ip_swift_n, &
             ip_voce_sigma0, ip_voce_q, ip_voce_b, ip_table_m
   public :: flow_stress, flow_stress_block, plastic_work, law_sizes_ok, check_law_props, &
             read_curve_file

   !> hardening law ids (props(ip_law))
   integer, parameter :: law_swift = 1, law_voce = 2, law_table = 3

   !> the layout of the built-in law's props, owned here because both the
   !> return mapping and the UMAT (material_j2, which re-exports the first
   !> three) read it: the elastic constants E, nu, R ...
   integer, parameter :: ip_youngs = 1, ip_poisson = 2, ip_r_value = 3
   !> ... then the law id and its first constant
   integer, parameter :: ip_law = 4, ip_law_constants = ip_law + 1
   !> Swift constants K, eps0, n
   integer, parameter :: ip_swift_k = ip_law_constants, ip_swift_eps0 = ip_law_constants + 1, &
                         ip_swift_n = ip_law_constants + 2
   !> Voce constants sigma0, Q, b
   integer, parameter :: ip_voce_sigma0 = ip_law_constants, ip_voce_q = ip_law_constants + 1, &
                         ip_voce_b = ip_law_constants + 2
   !> table: number of points m; point i at props(ip_table_m + 2i - 1 : ip_table_m + 2i)
   integer, parameter :: ip_table_m = ip_law_constants

contains

   !> Flow stress and hardening modulus at n points (flow_stress, one loop
   !> per law so that the compiler vectorizes the Swift and Voce laws).
   !>
   !> n       [in]  number of points.
   !> ep      [in]  (n) equivalent plastic strains (>= 0).
   !> props   [in]  material constants (module header).
   !> nprops  [in]  size of props.
   !> sigma_y [out] (n) flow stress (0 where flow_stress gives 0).
   !> hardening_modulus [out] (n) d sigma_y / d ebar_p.
   pure subroutine flow_stress_block(n, ep, props, nprops, sigma_y, hardening_modulus)
      integer, intent(in) :: n, nprops
      real(dp), intent(in) :: ep(n)
      real(dp), intent(in) :: props(nprops)
      real(dp), intent(out) :: sigma_y(n), hardening_modulus(n)

      real(dp) :: base, ex
      integer :: j

      if (nprops < ip_law + 3) then
         sigma_y = 0.0_dp
         hardening_modulus = 0.0_dp
         return
      end if
      select case (int(props(ip_law)))
      case (law_swift)
         ! sigma_y = K (eps0 + ep)^n; 0 (a failure for umat) where
         ! eps0 + ep <= 0, as in flow_stress
         do j = 1, n
            base = max(props(ip_swift_eps0) + ep(j), tiny(1.0_dp))
            sigma_y(j) = props(ip_swift_k)*base**props(ip_swift_n)
            sigma_y(j) = merge(sigma_y(j), 0.0_dp, props(ip_swift_eps0) + ep(j) > 0.0_dp)
            hardening_modulus(j) = props(ip_swift_n)*sigma_y(j)/base
         end do
      case (law_voce)
         ! sigma_y = sigma0 + Q (1 - exp(-b ep))
         do j = 1, n
            ex = exp(-props(ip_voce_b)*ep(j))
            sigma_y(j) = props(ip_voce_sigma0) + props(ip_voce_q)*(1.0_dp - ex)
            hardening_modulus(j) = props(ip_voce_q)*props(ip_voce_b)*ex
         end do
      case default
         do j = 1, n
            call flow_stress(ep(j), props, nprops, sigma_y(j), hardening_modulus(j))
         end do
      end select
   end subroutine flow_stress_block

   !> Flow stress and hardening modulus of the uniaxial true stress -
   !> natural strain curve, sigma_y(ebar_p) and d sigma_y / d ebar_p.
   !>
   !> ep                [in]  equivalent plastic strain ebar_p (>= 0).
   !> props             [in]  material constants (module header).
   !> nprops            [in]  size of props.
   !> sigma_y           [out] flow stress.  0 if the law id is unknown, props
   !>                         is too short, or (Swift) eps0 + ep <= 0: umat
   !>                         treats a non-positive flow stress as a failure.
   !> hardening_modulus [out] d sigma_y / d ebar_p (right derivative at a
   !>                         table point; last segment's slope beyond it).
   pure subroutine flow_stress(ep, props, nprops, sigma_y, hardening_modulus)
      integer, intent(in) :: nprops
      real(dp), intent(in) :: ep
      real(dp), intent(in) :: props(nprops)
      real(dp), intent(out) :: sigma_y, hardening_modulus

      real(dp) :: base, ex, slope
      integer :: m, lo, hi, mid, i

      sigma_y = 0.0_dp
      hardening_modulus = 0.0_dp
      if (nprops < ip_law_constants) return

      select case (int(props(ip_law)))
      case (law_swift)
         if (nprops < ip_swift_n) return
         ! sigma_y = K (eps0 + ep)^n
         base = props(ip_swift_eps0) + ep
         if (base <= 0.0_dp) return
         sigma_y = props(ip_swift_k)*base**props(ip_swift_n)
         hardening_modulus = props(ip_swift_n)*sigma_y/base
      case (law_voce)
         if (nprops < ip_voce_b) return
         ! sigma_y = sigma0 + Q (1 - exp(-b ep))
         ex = exp(-props(ip_voce_b)*ep)
         sigma_y = props(ip_voce_sigma0) + props(ip_voce_q)*(1.0_dp - ex)
         hardening_modulus = props(ip_voce_q)*props(ip_voce_b)*ex
      case (law_table)
         m = nint(props(ip_table_m))
         if (m < 2 .or. nprops < ip_table_m + 2*m) return
         ! Point i is (props(ip_table_m + 2i - 1), props(ip_table_m + 2i)).
         ! Binary search for the segment [i, i+1] holding ep; ep below the
         ! first or beyond the last point uses the first / last segment.
         lo = 1
         hi = m
         do while (hi - lo > 1)
            mid = (lo + hi)/2
            if (ep >= props(ip_table_m + 2*mid - 1)) then
               lo = mid
            else
               hi = mid
            end if
         end do
         i = lo
         slope = (props(ip_table_m + 2*i + 2) - props(ip_table_m + 2*i)) &
                 /(props(ip_table_m + 2*i + 1) - props(ip_table_m + 2*i - 1))
         sigma_y = props(ip_table_m + 2*i) + slope*(ep - props(ip_table_m + 2*i - 1))
         hardening_modulus = slope
      case default
         return
      end select
   end subroutine flow_stress

   !> Plastic work per unit volume W(ebar_p) = int_0^ebar_p sigma_y de, up
   !> to a constant of the law (only differences are used): the dissipation
   !> of a plastic increment is W(ep_n + dp) - W(ep_n) (exact, because on the
   !> yield surface sigma : d eps_p = sigma_y(ebar_p) d ebar_p).
   !>   Swift: W = sigma_y (eps0 + ep)/(n + 1)   [+ const]
   !>   Voce:  W = (sigma0 + Q) ep - (sigma_y - sigma0)/b  (W = sigma0 ep if b = 0)
   !>   table: the trapezoids of the segments up to ep (last one extrapolated).
   !>
   !> ep      [in] equivalent plastic strain.
   !> sigma_y [in] flow stress at ep (from flow_stress; saves a law call).
   !> props   [in] material constants (module header).
   !> nprops  [in] size of props.
   pure function plastic_work(ep, sigma_y, props, nprops) result(w)
      integer, intent(in) :: nprops
      real(dp), intent(in) :: ep, sigma_y
      real(dp), intent(in) :: props(nprops)
      real(dp) :: w

      integer :: m, i

      w = 0.0_dp
      select case (int(props(ip_law)))
      case (law_swift)
         w = sigma_y*(props(ip_swift_eps0) + ep)/(props(ip_swift_n) + 1.0_dp)
      case (law_voce)
         if (props(ip_voce_b) > 0.0_dp) then
            w = (props(ip_voce_sigma0) + props(ip_voce_q))*ep &
                - (sigma_y - props(ip_voce_sigma0))/props(ip_voce_b)
         else
            w = props(ip_voce_sigma0)*ep
         end if
      case (law_table)
         ! Point i is (props(ip_table_m + 2i - 1), props(ip_table_m + 2i));
         ! full segments below ep, then the part of the segment holding ep
         ! (ending at sigma_y).
         m = int(props(ip_table_m))
         do i = 1, m - 1
            if (i == m - 1 .or. ep < props(ip_table_m + 2*i + 1)) exit
            w = w + 0.5_dp*(props(ip_table_m + 2*i) + props(ip_table_m + 2*i + 2)) &
                *(props(ip_table_m + 2*i + 1) - props(ip_table_m + 2*i - 1))
         end do
         w = w + 0.5_dp*(props(ip_table_m + 2*i) + sigma_y)*(ep - props(ip_table_m + 2*i - 1))
      end select
   end function plastic_work

   !> .true. if props holds a known law id and all the constants of that law
   !> (no value checks: that is check_law_props's job, done once at set-up).
   !>
   !> props  [in] material constants (module header).
   !> nprops [in] size of props.
   pure function law_sizes_ok(props, nprops) result(ok)
      integer, intent(in) :: nprops
      real(dp), intent(in) :: props(nprops)
      logical :: ok

      ok = .false.
      if (nprops < ip_law) return
      if (.not. abs(props(ip_law)) < 1.0e6_dp) return
      select case (int(props(ip_law)))
      case (law_swift)
         ok = nprops >= ip_swift_n
      case (law_voce)
         ok = nprops >= ip_voce_b
      case (law_table)
         if (nprops < ip_table_m) return
         if (.not. abs(props(ip_table_m)) < 1.0e6_dp) return
         ok = int(props(ip_table_m)) >= 2 .and. nprops >= ip_table_m + 2*int(props(ip_table_m))
      case default
         ok = .false.
      end select
   end function law_sizes_ok

   !> Validate the law id and the law constants (the elastic constants and
   !> the finiteness of every entry are checked by material_j2's check_props,
   !> which calls this).
   !>
   !> props  [in] material constants (module header), size >= ip_law.
   !> nprops [in] size of props.
   !> Returns '' if valid, otherwise a message naming the first bad entry,
   !> e.g. "props(7) = Swift n = -0.1: must be >= 0".
   pure function check_law_props(props, nprops) result(msg)
      integer, intent(in) :: nprops
      real(dp), intent(in) :: props(nprops)
      character(len=:), allocatable :: msg

      integer :: m, i, need

      msg = ''
      if (.not. is_integer(props(ip_law), 1, 3)) then
         msg = at(ip_law) // 'law id = ' // num(props(ip_law)) // ': must be ' // itoa(law_swift) &
               // ' (Swift), ' // itoa(law_voce) // ' (Voce) or ' // itoa(law_table) // ' (table)'
         return
      end if

      select case (nint(props(ip_law)))
      case (law_swift)
         if (nprops < ip_swift_n) then
            msg = 'Swift law needs props(' // itoa(ip_swift_k) // ':' // itoa(ip_swift_n) &
                  // ') = K, eps0, n; got nprops = ' // itoa(nprops)
         else if (.not. props(ip_swift_k) > 0.0_dp) then
            msg = at(ip_swift_k) // 'Swift K = ' // num(props(ip_swift_k)) // ': must be > 0'
         else if (.not. props(ip_swift_eps0) > 0.0_dp) then
            msg = at(ip_swift_eps0) // 'Swift eps0 = ' // num(props(ip_swift_eps0)) // ': must be > 0'
         else if (.not. props(ip_swift_n) >= 0.0_dp) then
            msg = at(ip_swift_n) // 'Swift n = ' // num(props(ip_swift_n)) // ': must be >= 0'
         end if
      case (law_voce)
         if (nprops < ip_voce_b) then
            msg = 'Voce law needs props(' // itoa(ip_voce_sigma0) // ':' // itoa(ip_voce_b) &
                  // ') = sigma0, Q, b; got nprops = ' // itoa(nprops)
         else if (.not. props(ip_voce_sigma0) > 0.0_dp) then
            msg = at(ip_voce_sigma0) // 'Voce sigma0 = ' // num(props(ip_voce_sigma0)) // ': must be > 0'
         else if (.not. props(ip_voce_q) >= 0.0_dp) then
            msg = at(ip_voce_q) // 'Voce Q = ' // num(props(ip_voce_q)) // ': must be >= 0 (no softening)'
         else if (.not. props(ip_voce_b) >= 0.0_dp) then
            msg = at(ip_voce_b) // 'Voce b = ' // num(props(ip_voce_b)) // ': must be >= 0'
         end if
      case (law_table)
         if (nprops < ip_table_m) then
            msg = 'table law needs props(' // itoa(ip_table_m) // ') = m, number of points'
            return
         end if
         if (.not. is_integer(props(ip_table_m), 2, 1000000)) then
            msg = at(ip_table_m) // 'number of table points = ' // num(props(ip_table_m)) &
                  // ': must be a whole number >= 2'
            return
         end if
         m = nint(props(ip_table_m))
         need = ip_table_m + 2*m
         if (nprops < need) then
            msg = 'table law with ' // itoa(m) // ' points needs ' // itoa(need) &
                  // ' props, got ' // itoa(nprops)
            return
         end if
         if (abs(props(ip_table_m + 1)) > 0.0_dp) then
            msg = at(ip_table_m + 1) // 'first table plastic strain = ' // num(props(ip_table_m + 1)) &
                  // ': must be 0'
         else if (.not. props(ip_table_m + 2) > 0.0_dp) then
            msg = at(ip_table_m + 2) // 'first table stress = ' // num(props(ip_table_m + 2)) &
                  // ': must be > 0'
         else
            do i = 2, m
               if (.not. props(ip_table_m + 2*i - 1) > props(ip_table_m + 2*i - 3)) then
                  msg = 'table point ' // itoa(i) // ': plastic strain not increasing (' &
                        // num(props(ip_table_m + 2*i - 1)) // ' after ' &
                        // num(props(ip_table_m + 2*i - 3)) // ')'
                  exit
               else if (.not. props(ip_table_m + 2*i) >= props(ip_table_m + 2*i - 2)) then
                  msg = 'table point ' // itoa(i) // ': stress decreasing (' &
                        // num(props(ip_table_m + 2*i)) // ' after ' &
                        // num(props(ip_table_m + 2*i - 2)) // ')'
                  exit
               end if
            end do
         end if
      end select

   contains

      !> 'props(i) = ', the start of a message about entry i.
      pure function at(i) result(s)
         integer, intent(in) :: i
         character(len=:), allocatable :: s

         s = 'props(' // itoa(i) // ') = '
      end function at

   end function check_law_props

   !> .true. if x is a whole number in [lo, hi].
   !>
   !> x  [in] value.
   !> lo [in] lowest allowed whole number.
   !> hi [in] highest allowed whole number.
   pure logical function is_integer(x, lo, hi)
      real(dp), intent(in) :: x
      integer, intent(in) :: lo, hi

      is_integer = .false.
      if (.not. (x >= real(lo, dp) .and. x <= real(hi, dp))) return
      is_integer = abs(x - real(nint(x), dp)) <= 0.0_dp
   end function is_integer

   !> Read a hardening curve: a text file of two columns, plastic strain and
   !> true stress, one point per line, read by module pair_file (comments,
   !> separators, the bounds on its size).
   !> Checks: every data line holds exactly two numbers; at least 2 points;
   !> the first plastic strain is 0; plastic strain strictly increasing;
   !> stress positive and non-decreasing.  The file is read whole, at most
   !> text's max_input_bytes, lines at most max_line_length characters (a
   !> longer file, /dev/zero, a directory are refused by name).  Never stops
   !> the program.
   !>
   !> path   [in]  file name.
   !> ep     [out] plastic strains (allocated; size 0 on error).
   !> sigma  [out] true stresses (allocated; size 0 on error).
   !> errmsg [out] blank on success, otherwise the file, line and problem,
   !>              e.g. "curve file 'c.txt' line 5: plastic strain not
   !>              increasing (0.10 after 0.12)" (numbers quoted as written
   !>              in the file).  A character variable of any length (like
   !>              iomsg); the message is cut to len(errmsg), so give it
   !>              room (256 or more).
   subroutine read_curve_file(path, ep, sigma, errmsg)
      character(len=*), intent(in) :: path
      real(dp), allocatable, intent(out) :: ep(:), sigma(:)
      character(len=*), intent(out) :: errmsg

      character(len=:), allocatable :: msg, at
      character(len=64), allocatable :: tok(:, :)
      integer, allocatable :: line_no(:)
      integer :: i, j

      call read_pairs(path, 'curve file', 'plastic strain, true stress', ep, sigma, tok, line_no, msg)
      if (len(msg) == 0) then
         do i = 1, size(ep)
            ! (Fortran's .and. may evaluate both sides: the point before is
            ! the point itself for the first)
            j = max(i - 1, 1)
            at = "curve file '" // path // "' line " // itoa(line_no(i)) // ': '
            if (i == 1 .and. abs(ep(1)) > 0.0_dp) then
               msg = at // 'first plastic strain must be 0 (found ' // trim(tok(1, 1)) // ')'
            else if (i > 1 .and. .not. ep(i) > ep(j)) then
               msg = at // 'plastic strain not increasing (' // trim(tok(1, i)) // ' after ' &
                        // trim(tok(1, j)) // ')'
            else if (.not. sigma(i) > 0.0_dp) then
               msg = at // 'stress must be positive (found ' // trim(tok(2, i)) // ')'
            else if (i > 1 .and. .not. sigma(i) >= sigma(j)) then
               msg = at // 'stress decreasing (' // trim(tok(2, i)) // ' after ' &
                        // trim(tok(2, j)) // ')'
            end if
            if (len(msg) > 0) exit
         end do
      end if
      if (len(msg) == 0 .and. size(ep) < 2) then
         msg = "curve file '" // path // "': need at least 2 points, found " // itoa(size(ep))
      end if
      errmsg = msg
      if (len(msg) > 0) then
         deallocate (ep, sigma)
         allocate (ep(0), sigma(0))
      end if
   end subroutine read_curve_file

end module hardening
