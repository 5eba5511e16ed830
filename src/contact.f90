!> contact -- penalty contact and friction of one sheet station on one tool,
!> (2.18)-(2.23), docs/theory.md §5-§6.
!>
!> A station at current position p (a Gauss point of the centreline) penetrates
!> a tool by d > 0.  With n the tool's unit normal toward the sheet and t its
!> unit tangent (tools module), the tool pushes the sheet with
!>   f = k d n  -  mu k d f(u_T) sense t                         (2.19), (2.23)
!> per unit reference length (Winkler foundation, k the penalty), where u_T is
!> the distance slid on the tool since the station's contact began (relative
!> to the tool, which may move: p_rel = p - (0, shift)) and f the modified
!> Coulomb law with one reversal (friction module).  The coefficient mu is
!> the friction law's (module friction_law): constant (Coulomb) or a
!> function of the contact pressure p = k g(d)/lambda_f, the normal force
!> per unit current length of the face in contact (docs/theory.md §6.1),
!> lambda_f the face's stretch at the last converged state (lagged, as the
!> station distances zbar, §3).
!>
!> The Heaviside onset of (2.18) is smoothed over a small penetration delta:
!> the normal pressure is k g(d) with g = d^2/(2 delta) for d < delta and
!> g = d - delta/2 beyond, so the force is C1 in d.  Stations grazing a tool
!> (the sheet lies exactly on both binder faces at full lock) then no longer
!> switch the tangent between 0 and k from one Newton iterate to the next.
!> delta = 0 is the paper's sharp onset.  Penalty energy: k G(d), G' = g.
!>
!> With &tools contact_faces = 'current' the tool meets the sheet's face at
!> its current place rather than at the reference half-thickness h/2 from
!> the centreline (docs/theory.md §5.1): the caller passes the face's
!> offset toward the centreline (face_offset: the section kept in volume,
!> each face from the trial stretch and bending strain, so that the concave
!> face of a bend, the one a tool radius presses, thickens and the convex
!> one thins), and the penetration is d - offset; the derivatives of the
!> force with respect to d (dfdd, dfndd) let the caller add the offset's
!> dependence on the dofs to the tangent.  The history keeps the offset
!> and the work of the normal force on its change (ich_offset,
!> ich_offwork), an energy the shell's external work does not hold
!> (module energy).
!>
!> The contact history of a station is a column ch(n_chist) (one per Gauss
!> station and tool in the model's state); its entries are named by the
!> ich_* constants below, which every module uses instead of numbers.

module contact
   use kinds, only: dp
   use tools, only: tool_type
   use tool_distance, only: tool_gap
   use friction_law, only: friction_law_type
   implicit none
   private
   public :: contact_station, penalty_energy, face_offset
   public :: n_chist, ich_active, ich_slip, ich_slip_max, ich_sense, ich_position, &
             ich_dissipation, ich_penetration, ich_traction, ich_hint, ich_pressure, ich_mu, &
             ich_offset, ich_offwork

   !> Layout of a station's contact history column ch(n_chist):
   !> 1 when the station is in contact (trial) or was (converged), else 0
   integer, parameter :: ich_active = 1
   !> u_T, the distance slid along the sense of first sliding, mm
   integer, parameter :: ich_slip = 2
   !> u_T^m, the largest u_T of the station's history (the reversal point
   !> of (2.21)), mm
   integer, parameter :: ich_slip_max = 3
   !> sense of first sliding along the tool's tangent: +1, -1, 0 unknown
   integer, parameter :: ich_sense = 4
   !> position (x, y) relative to the tool, mm: two entries,
   !> ch(ich_position:ich_position + 1)
   integer, parameter :: ich_position = 5
   !> friction dissipation per unit reference length, N
   integer, parameter :: ich_dissipation = 7
   !> signed penetration d (< 0: minus the gap), mm
   integer, parameter :: ich_penetration = 8
   !> friction traction along the tangent t (signed), N/mm
   integer, parameter :: ich_traction = 9
   !> the tool piece nearest at the last search (tool_gap's hint; 0 none)
   integer, parameter :: ich_hint = 10
   !> the contact pressure p, MPa, and the friction coefficient mu(p) in use
   integer, parameter :: ich_pressure = 11, ich_mu = 12
   !> the face offset toward the centreline at the state (contact_faces =
   !> 'current'; 0 otherwise), mm, and the work of the normal force on its
   !> change since the start, int fn d(offset), N (per unit reference length)
   integer, parameter :: ich_offset = 13, ich_offwork = 14
   !> length of the column
   integer, parameter :: n_chist = 14

contains

   !> CONTACT_STATION: contact force on the sheet and its derivative d f/d p.
   !>  tool   [in]  the tool
   !>  shift  [in]  the tool's vertical rigid translation (lower tool: H)
   !>  k      [in]  penalty (force per reference length per unit penetration)
   !>  delta  [in]  smoothing length of the contact onset (0: sharp)
   !>  fric   [in]  the friction law (its regularization length eps of (4.3))
   !>  face_log_stretch [in] the log stretch of the sheet's face against
   !>               this tool at the last converged state (pressure =
   !>               force/stretch; its exponential is taken only where a
   !>               pressure needs it: most stations are out of contact)
   !>  p      [in]  current position of the station
   !>  chn    [in]  converged history column (layout: the ich_* constants)
   !>  ch1    [out] trial history column
   !>  f      [out] force on the sheet per unit reference length
   !>  kf     [out] d f / d p (non-symmetric with friction)
   !>  fn     [out] the normal force k g(d) >= 0 alone (the pressure the
   !>               contact section puts on the sheet's face)
   !>  dfn    [out] d fn / d p = -k g'(d) n
   !>  offset [in]  optional: the face's offset toward the centreline, mm
   !>               (module header); absent: 0
   !>  dfdd   [out] optional: d f / d d, the force's derivative with respect
   !>               to the penetration at fixed p (d offset = -d d)
   !>  dfndd  [out] optional: d fn / d d = k g'(d)
   pure subroutine contact_station(tool, shift, k, delta, fric, face_log_stretch, p, chn, ch1, f, kf, &
                                   fn, dfn, offset, dfdd, dfndd)
      type(tool_type), intent(in) :: tool
      class(friction_law_type), intent(in) :: fric
      real(dp), intent(in) :: shift, k, delta, face_log_stretch, p(2), chn(:)
      real(dp), intent(out) :: ch1(:), f(2), kf(2, 2), fn, dfn(2)
      real(dp), intent(in), optional :: offset
      real(dp), intent(out), optional :: dfdd(2), dfndd
      real(dp) :: prel(2), d, n(2), t(2), curv, ds, sense, ut, dslip(2), tt, pn, dpn
      real(dp) :: dut(2), dold, a, utm, trac_old, mu, pressure, dtt_dpn, dtt_dut, dut_dd, face_stretch
      integer :: seg
      prel = [p(1), p(2) - shift]
      call tool_gap(tool, prel(1), prel(2), d, n, curv, t, seg, hint=nint(chn(ich_hint)))
      if (present(offset)) d = d - offset
      f = 0.0_dp
      kf = 0.0_dp
      fn = 0.0_dp
      dfn = 0.0_dp
      if (present(dfdd)) dfdd = 0.0_dp
      if (present(dfndd)) dfndd = 0.0_dp
      ch1 = 0.0_dp
      ch1(ich_position:ich_position + 1) = prel
      ch1(ich_dissipation) = chn(ich_dissipation)
      ch1(ich_penetration) = d
      ch1(ich_hint) = real(seg, dp)
      ! the offset and the work of the normal force on its change
      ! (trapezoidal over the increment; the converged force from the
      ! converged pressure and face stretch)
      if (present(offset)) ch1(ich_offset) = offset
      ! (the stretch enters only with a pressure, converged or new: most
      ! stations are out of contact and skip the exponential)
      face_stretch = 1.0_dp
      if (abs(chn(ich_pressure)) > 0.0_dp .or. d > 0.0_dp) face_stretch = exp(face_log_stretch)
      ch1(ich_offwork) = chn(ich_offwork) &
                         + 0.5_dp*chn(ich_pressure)*face_stretch*(ch1(ich_offset) - chn(ich_offset))
      if (d <= 0.0_dp) return
      ch1(ich_active) = 1.0_dp
      ! normal part: f = pn n with pn = k g(d), dd/dp = -n, dn/dp = curv (I - n n^T)
      if (d < delta) then
         pn = k*d*d/(2.0_dp*delta)
         dpn = k*d/delta
      else
         pn = k*(d - 0.5_dp*delta)
         dpn = k
      end if
      f = pn*n
      kf = -dpn*outer(n, n) + pn*curv*outer(t, t)
      fn = pn
      dfn = -dpn*n
      if (present(dfdd)) dfdd = dpn*n
      if (present(dfndd)) dfndd = dpn
      ch1(ich_pressure) = pn/face_stretch
      ch1(ich_offwork) = ch1(ich_offwork) + 0.5_dp*pn*(ch1(ich_offset) - chn(ich_offset))
      if (.not. fric%active()) return
      ! friction, integrated from the last converged state to the trial one
      ! like a return mapping (docs/theory.md §6): the slip of the increment
      ! is measured along t from the converged position; d(ds)/dp =
      ! t (1 - curv n.(p - p_old)) because t turns on an arc
      ds = dot_product(t, prel - chn(ich_position:ich_position + 1))
      dslip = t*(1.0_dp - curv*dot_product(n, prel - chn(ich_position:ich_position + 1)))
      ! d ds / d d at fixed p (only where the fraction a below depends on d)
      dut_dd = 0.0_dp
      if (chn(ich_active) < 0.5_dp) then
         ! the station entered contact within the increment: its history
         ! starts there, at the fraction a = d/(d - d_old) of the motion
         ! (d linear along the increment), so that only the slip in contact
         ! counts; da/dp = d_old/(d - d_old)^2 n
         dold = min(chn(ich_penetration), 0.0_dp)
         a = d/(d - dold)
         dslip = a*dslip + ds*((dold/(d - dold))/(d - dold))*n
         dut_dd = -ds*((dold/(d - dold))/(d - dold))
         ds = a*ds
      end if
      if (chn(ich_active) < 0.5_dp .or. abs(chn(ich_sense)) < 0.5_dp) then
         ! no slip yet: the first slip sets the sense
         sense = merge(1.0_dp, -1.0_dp, ds >= 0.0_dp)
         ut = abs(ds)
         utm = 0.0_dp
         trac_old = 0.0_dp
      else
         sense = chn(ich_sense)
         ut = chn(ich_slip) + sense*ds
         utm = chn(ich_slip_max)
         trac_old = chn(ich_traction)
      end if
      dut = sense*dslip
      ! (u_T = sense ds + const in both branches above)
      dut_dd = sense*dut_dd
      ch1(ich_slip) = ut
      ! the reversal point of the trial path: the converged one already holds
      ! the largest converged u_T, and u_T is linear along the increment
      ch1(ich_slip_max) = max(utm, ut)
      ch1(ich_sense) = sense
      ! the law's traction along the sense of first slip and its
      ! derivatives (the face's stretch is lagged, so not differentiated)
      call fric%traction(pn, face_stretch, ut, utm, tt, dtt_dpn, dtt_dut, pressure, mu)
      ch1(ich_mu) = mu
      tt = tt*sense
      ch1(ich_traction) = tt
      ch1(ich_dissipation) = chn(ich_dissipation) + 0.5_dp*(trac_old + tt)*ds
      f = f - tt*t
      ! d(tt t)/dp = t (mu sense)(fr dpn dd/dp + pn dfr dut) + tt dt/dp,
      ! dd/dp = -n, dt/dp = -curv n t^T
      kf = kf - sense*outer(t, -dtt_dpn*dpn*n + dtt_dut*dut) + tt*curv*outer(n, t)
      if (present(dfdd)) dfdd = dfdd - sense*(dtt_dpn*dpn + dtt_dut*dut_dd)*t
   end subroutine contact_station

   !> FACE_OFFSET: the offset of a face toward the centreline with &tools
   !> contact_faces = 'current' (docs/theory.md §5.1), and its derivatives.
   !> The section keeps its volume (plane strain, plastically
   !> incompressible; the elastic part, ~1e-3 of the offset, left out) with
   !> the fibre stretch Lambda = lambda + rho zbar of the section module:
   !> d zbar/dz = 1/Lambda, so lambda zbar + rho zbar^2/2 = z and the face
   !> z = +-h/2 lies at |zbar| = h/(lambda + sqrt(lambda^2 +- rho h)); the
   !> offset is h/2 - |zbar|, h/2 (1 - 1/lambda) on a straight sheet.  Past
   !> lambda^2 +- rho h = lambda^2/4 (a bend of radius ~ h/2: a neck's
   !> wrinkle) the root is held at lambda/2.
   !>  h      [in]  reference thickness
   !>  eps    [in]  axial strain lambda - 1
   !>  rho    [in]  bending strain
   !>  top    [in]  the top face (z = +h/2, against tool 1), else the bottom
   !>  off    [out] the offset toward the centreline (< 0: the face lies
   !>               beyond h/2)
   !>  doff_deps, doff_drho [out] its derivatives in eps and rho
   pure subroutine face_offset(h, eps, rho, top, off, doff_deps, doff_drho)
      real(dp), intent(in) :: h, eps, rho
      logical, intent(in) :: top
      real(dp), intent(out) :: off, doff_deps, doff_drho
      real(dp) :: lam, s, arg, q, dd
      lam = 1.0_dp + eps
      s = merge(1.0_dp, -1.0_dp, top)
      arg = lam*lam + s*rho*h
      if (arg >= 0.25_dp*lam*lam) then
         q = sqrt(arg)
         dd = lam + q
         off = 0.5_dp*h - h/dd
         doff_deps = h/dd**2*(1.0_dp + lam/q)
         doff_drho = h/dd**2*(0.5_dp*s*h/q)
      else
         dd = 1.5_dp*lam
         off = 0.5_dp*h - h/dd
         doff_deps = h/dd**2*1.5_dp
         doff_drho = 0.0_dp
      end if
   end subroutine face_offset

   !> PENALTY_ENERGY: stored energy k G(d) of a station penetrating by d
   !> (G' = g of the smoothed onset; G = d^2/2 for delta = 0).
   pure function penalty_energy(k, delta, d) result(energy)
      real(dp), intent(in) :: k, delta, d
      real(dp) :: energy
      if (d <= 0.0_dp) then
         energy = 0.0_dp
      else if (d < delta) then
         energy = k*d**3/(6.0_dp*delta)
      else
         energy = k*(0.5_dp*d*d - 0.5_dp*delta*d + delta*delta/6.0_dp)
      end if
   end function penalty_energy

   !> OUTER: the outer product a b^T of two 2-vectors.
   pure function outer(a, b) result(c)
      real(dp), intent(in) :: a(2), b(2)
      real(dp) :: c(2, 2)
      c(:, 1) = a*b(1)
      c(:, 2) = a*b(2)
   end function outer
end module contact
