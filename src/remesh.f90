!> remesh -- elements of a converged state split in place (docs/theory.md
!> §7.6): the mesh change of the neck's refinement on the default path.
!>
!> A cubic Hermite element split at interior points carries the same v, w
!> field exactly: its dofs are values and slopes, so the new nodes take the
!> old element's interpolated (v, v', w, w') and every point of the sheet
!> keeps its displacement (split_field).  What lives at the Gauss stations
!> cannot be carried exactly, the new stations lying between the old ones:
!>  - each section history value (stresses, state variables, energies,
!>    zbar) is interpolated linearly in the reference position between the
!>    two old stations around the new one, and held at the outer stations'
!>    values beyond them.  A convex combination of two admissible states
!>    (a convex yield surface, a hardening curve concave in the plastic
!>    strain) is admissible, which a cubic through the four stations would
!>    not guarantee near the element's ends;
!>  - the fibres' converged log strain ln(Lambda_k) is then set to the new
!>    station's own stretch 1 + eps + zbar_k rho, so that the next
!>    increment's strain starts from where the station is (an interpolated
!>    value would enter the next increment as a strain jump);
!>  - a contact station takes the column of the nearest old station (its
!>    sense, slip and dissipation), with its position and gap set to the
!>    new station's own, so that no slip is counted for the move, and in
!>    contact as its gap says (out of contact without a slip history).
!> The mapped state is then re-equilibrated at the same load before the
!> next increment (reequilibrate).  The driver decides when and where
!> (analysis's split_at_exit, stepper's decide_split); the mesh and the
!> state change here.
module remesh
   use kinds, only: dp
   use errors, only: alloc_message
   use text, only: itoa
   use hermite, only: n_gauss, gauss_xi, hermite_shape
   use mesh, only: dofs_per_node, element_dofs, node_dof, dof_v, dof_v_slope, dof_w, dof_w_slope
   use element, only: element_gradients, v_dofs, w_dofs
   use kinematics, only: strain_measures
   use section, only: ih_strain, ih_zbar, ih_statev
   use contact, only: ich_position, ich_penetration, ich_hint, ich_active, ich_slip, ich_slip_max, &
                      ich_sense, ich_traction, ich_offset, face_offset
   use tool_distance, only: tool_gap
   use tools, only: seg_arc
   use model, only: model_type, state_type, load_type
   use band, only: band_matrix
   use solver, only: newton_result, newton_solve, assemble, commit_state, newton_ok
   implicit none
   private
   public :: split_nodes, split_field, station_weights, split_stations, split_elements, exit_pieces, &
             last_radius_exit, reequilibrate, reequilibration
   public :: reeq_ok, reeq_material, reeq_no_equilibrium, reeq_out_of_memory
   public :: exit_element_over_h, exit_zone_before, exit_zone_after, exit_resplit_before, &
             neck_element_current_over_h, neck_element_reference_over_h

   !> The elements on which the restraining force's maximum converges at
   !> the neck (docs/theory.md §7.6), measured on the continuum-checked
   !> necks: with the tools on the current faces (the default) 0.75h (80
   !> uniform elements of 0.48-0.75h tear within 1.5% of refine_neck's zone
   !> of 0.08h; 40 of 0.95-1.5h up to 22% late: neck_element_study), with the
   !> tools on the reference faces 0.1h (§7.5: 18-45% late on 0.625-0.75h).
   real(dp), parameter :: neck_element_current_over_h = 0.75_dp
   real(dp), parameter :: neck_element_reference_over_h = 0.1_dp
   !> The neck's refinement on the default path (docs/theory.md §7.6):
   !> elements of exit_element_over_h h with the tools on the reference
   !> faces (neck_element_current_over_h h on the current faces, which
   !> leaves the shipped meshes whole) over the material whose current
   !> position lies from exit_zone_before h before the exit of the last
   !> radius on the pulled side to exit_zone_after h after it at the time of
   !> the split.  A clamped pull necks in material that is on that radius
   !> when the force turns toward its maximum, 1.2-2.2h before its exit
   !> (bead A and B, steel, uniform and refined meshes), or, with much
   !> friction, in the straight sheet just past it (bead A steel with
   !> mu = 0.2: 1.9-2.2h past the exit; docs/theory.md §7.6).
   real(dp), parameter :: exit_element_over_h = 0.08_dp
   real(dp), parameter :: exit_zone_before = 3.0_dp, exit_zone_after = 2.0_dp
   !> As the pull draws coarse elements toward the exit, they are split
   !> again (over the same window) once one comes within
   !> exit_resplit_before h before it: about every 1.5h of draw
   real(dp), parameter :: exit_resplit_before = 1.5_dp

   !> reequilibration%status: the mapped state is in equilibrium; a material
   !> point of it could not be updated; its imbalance could not be removed
   !> whole; its work arrays could not be allocated
   integer, parameter :: reeq_ok = 0, reeq_material = 1, reeq_no_equilibrium = 2, reeq_out_of_memory = 3

   !> What re-equilibrating a mapped state did (reequilibrate): the
   !> outcome, the committed steps, the fraction of the imbalance removed,
   !> Newton's iterations and the assemblies (for the run's counts), the
   !> last scaled residual, the dead loads' work over it (external work,
   !> docs/theory.md §7.6) and, when out of memory, the message.
   type :: reequilibration
      integer :: status = reeq_ok
      integer :: steps = 0, iterations = 0, assemblies = 0
      real(dp) :: removed = 0.0_dp
      real(dp) :: residual = 0.0_dp
      real(dp) :: work_dead = 0.0_dp
      character(len=:), allocatable :: errmsg
   end type reequilibration

contains

   !> SPLIT_NODES: node positions after splitting each element into equal
   !> parts; the old nodes keep their positions exactly.
   !>  x       [in]  node positions, ascending
   !>  pieces  [in]  (size(x) - 1) parts per element, >= 1
   !>  xn      (result) sum(pieces) + 1 node positions
   pure function split_nodes(x, pieces) result(xn)
      real(dp), intent(in) :: x(:)
      integer, intent(in) :: pieces(:)
      real(dp) :: xn(sum(pieces) + 1)
      integer :: e, j, k
      k = 0
      do e = 1, size(pieces)
         do j = 0, pieces(e) - 1
            k = k + 1
            xn(k) = x(e) + (x(e + 1) - x(e))*real(j, dp)/real(pieces(e), dp)
         end do
      end do
      xn(k + 1) = x(size(x))
   end function split_nodes

   !> SPLIT_FIELD: a nodal dof vector (v, v', w, w' per node) on the split
   !> mesh: the old nodes keep their dofs, a new node at xi = j/pieces(e) of
   !> element e takes the element's Hermite interpolation there (exact: the
   !> field is the same cubic on each part).
   !>  x       [in]  node positions of the old mesh
   !>  pieces  [in]  parts per old element
   !>  u       [in]  dofs of the old mesh, dofs_per_node*size(x)
   !>  un      (result) dofs of the split mesh
   pure function split_field(x, pieces, u) result(un)
      real(dp), intent(in) :: x(:), u(:)
      integer, intent(in) :: pieces(:)
      real(dp) :: un(dofs_per_node*(sum(pieces) + 1))
      real(dp) :: ul(8), nv(4), dn(4), d2n(4), le
      integer :: e, j, k
      k = 0
      do e = 1, size(pieces)
         ul = u(element_dofs(e))
         le = x(e + 1) - x(e)
         do j = 0, pieces(e) - 1
            k = k + 1
            if (j == 0) then
               un(node_dof(k, dof_v):node_dof(k, dof_w_slope)) = ul(1:dofs_per_node)
               cycle
            end if
            call hermite_shape(real(j, dp)/real(pieces(e), dp), le, nv, dn, d2n)
            un(node_dof(k, dof_v)) = dot_product(nv, ul(v_dofs))
            un(node_dof(k, dof_v_slope)) = dot_product(dn, ul(v_dofs))
            un(node_dof(k, dof_w)) = dot_product(nv, ul(w_dofs))
            un(node_dof(k, dof_w_slope)) = dot_product(dn, ul(w_dofs))
         end do
      end do
      k = k + 1
      un(node_dof(k, dof_v):node_dof(k, dof_w_slope)) = u(size(u) - dofs_per_node + 1:)
   end function split_field

   !> STATION_WEIGHTS: linear interpolation between an element's Gauss
   !> stations at local coordinate xi: value = (1 - w) v(i1) + w v(i2);
   !> beyond the outer stations their value (i1 = i2).
   !>  xi      [in]  local coordinate in [0, 1]
   !>  i1, i2  [out] the stations around xi
   !>  w       [out] weight of i2, in [0, 1]
   pure subroutine station_weights(xi, i1, i2, w)
      real(dp), intent(in) :: xi
      integer, intent(out) :: i1, i2
      real(dp), intent(out) :: w
      integer :: i
      w = 0.0_dp
      if (xi <= gauss_xi(1)) then
         i1 = 1
         i2 = 1
         return
      end if
      if (xi >= gauss_xi(n_gauss)) then
         i1 = n_gauss
         i2 = n_gauss
         return
      end if
      i1 = 1
      do i = 1, n_gauss - 1
         if (xi >= gauss_xi(i)) i1 = i
      end do
      i2 = i1 + 1
      w = (xi - gauss_xi(i1))/(gauss_xi(i2) - gauss_xi(i1))
   end subroutine station_weights

   !> SPLIT_STATIONS: values at the Gauss stations on the split mesh, each
   !> interpolated linearly between the old element's stations around it
   !> (station_weights); an element that stays whole keeps its values.
   !>  pieces  [in]  parts per old element
   !>  v       [in]  (n_comp, n_gauss, old elements) values
   !>  vn      (result) (n_comp, n_gauss, sum(pieces))
   pure function split_stations(pieces, v) result(vn)
      integer, intent(in) :: pieces(:)
      real(dp), intent(in) :: v(:, :, :)
      real(dp) :: vn(size(v, 1), n_gauss, sum(pieces))
      real(dp) :: w
      integer :: e, j, f, ig, i1, i2
      f = 0
      do e = 1, size(pieces)
         do j = 1, pieces(e)
            f = f + 1
            if (pieces(e) == 1) then
               vn(:, :, f) = v(:, :, e)
               cycle
            end if
            do ig = 1, n_gauss
               call station_weights((real(j - 1, dp) + gauss_xi(ig))/real(pieces(e), dp), i1, i2, w)
               vn(:, ig, f) = (1.0_dp - w)*v(:, i1, e) + w*v(:, i2, e)
            end do
         end do
      end do
   end function split_stations

   !> SPLIT_ELEMENTS: split element e of a converged state into pieces(e)
   !> equal parts (module header): the model's mesh and the state (dofs,
   !> section and contact histories, Gauss-point results, indicator; trial
   !> copies equal to the converged ones) on the new mesh.  The state is
   !> mapped, not in equilibrium: the caller re-equilibrates it.
   !>  m       [in,out] the model: x, n_el, n_nodes, n_dof of the split mesh
   !>  s       [in,out] the converged state, mapped to the split mesh
   !>  pieces  [in]     m%n_el parts per element, >= 1
   !>  errmsg  [out]    optional: '' or, when the split mesh's arrays could
   !>                   not be allocated, the message naming them and their
   !>                   size (m and s are then unchanged); without it a
   !>                   failed allocation stops the program
   subroutine split_elements(m, s, pieces, errmsg)
      type(model_type), intent(inout) :: m
      type(state_type), intent(inout) :: s
      integer, intent(in) :: pieces(:)
      character(len=:), allocatable, intent(out), optional :: errmsg
      real(dp), allocatable :: xn(:), un(:), u1n(:), hn(:, :, :, :), h1n(:, :, :, :), cn(:, :, :, :), &
                               c1n(:, :, :, :), gpn(:, :, :), gpt(:, :, :), ind(:, :)
      real(dp) :: le, lf, xi, w, ulf(8), g(4), gm(4, 8), eps, rho, deps(4), drho(4), &
                  d2eps(4, 4), d2rho(4, 4), nv(4), dn(4), d2n(4), pos(2), shifts(2), d, nrm(2), curv, t(2), &
                  off, ode, odr
      integer :: e, f, j, ig, i1, i2, it, n_new, seg, stat
      n_new = sum(pieces)
      ! every array of the split mesh at once, before anything is changed
      allocate (xn(n_new + 1), un(dofs_per_node*(n_new + 1)), u1n(dofs_per_node*(n_new + 1)), &
                hn(size(s%hn, 1), size(s%hn, 2), n_gauss, n_new), h1n(size(s%hn, 1), size(s%hn, 2), n_gauss, n_new), &
                cn(size(s%cn, 1), n_gauss, n_new, 2), c1n(size(s%cn, 1), n_gauss, n_new, 2), &
                gpn(size(s%gpn, 1), n_gauss, n_new), gpt(size(s%gpn, 1), n_gauss, n_new), ind(n_gauss, n_new), &
                stat=stat)
      if (present(errmsg)) errmsg = ''
      if (stat /= 0) then
         if (present(errmsg)) then
            errmsg = alloc_message('the state of the split mesh ('//itoa(n_new)//' elements)', 8.0_dp* &
                                   (real(n_gauss, dp)*real(n_new, dp)*(2.0_dp*real(size(s%hn, 1)*size(s%hn, 2), dp) &
                                    + 4.0_dp*real(size(s%cn, 1), dp) + 2.0_dp*real(size(s%gpn, 1), dp) + 1.0_dp) &
                                    + 3.0_dp*real(dofs_per_node*(n_new + 1), dp)))
            return
         end if
         error stop 'split_elements: cannot allocate the split mesh (out of memory)'
      end if
      xn = split_nodes(m%x, pieces)
      un = split_field(m%x, pieces, s%u)
      gpn = split_stations(pieces, s%gpn)
      ind = reshape(split_stations(pieces, reshape(s%indicator, [1, n_gauss, m%n_el])), [n_gauss, n_new])
      shifts = [0.0_dp, s%shift]
      f = 0
      do e = 1, m%n_el
         le = m%x(e + 1) - m%x(e)
         do j = 1, pieces(e)
            f = f + 1
            if (pieces(e) == 1) then
               hn(:, :, :, f) = s%hn(:, :, :, e)
               cn(:, :, f, :) = s%cn(:, :, e, :)
               cycle
            end if
            lf = xn(f + 1) - xn(f)
            ulf = un(element_dofs(f))
            do ig = 1, n_gauss
               xi = (real(j - 1, dp) + gauss_xi(ig))/real(pieces(e), dp)
               call station_weights(xi, i1, i2, w)
               hn(:, :, ig, f) = (1.0_dp - w)*s%hn(:, :, i1, e) + w*s%hn(:, :, i2, e)
               call m%material%state_mapped(hn(:, ih_statev:, ig, f))
               ! the fibres' converged strain: the new station's own stretch
               call element_gradients(gauss_xi(ig), lf, ulf, g, gm)
               call strain_measures(g, eps, rho, deps, drho, d2eps, d2rho)
               hn(:, ih_strain, ig, f) = log(1.0_dp + eps + hn(:, ih_zbar, ig, f)*rho)
               ! contact: the nearest old station's column at the new place
               call hermite_shape(gauss_xi(ig), lf, nv, dn, d2n)
               pos = [xn(f) + gauss_xi(ig)*lf + dot_product(nv, ulf(v_dofs)), dot_product(nv, ulf(w_dofs))]
               do it = 1, 2
                  cn(:, ig, f, it) = s%cn(:, merge(i1, i2, w < 0.5_dp), e, it)
                  cn(ich_position:ich_position + 1, ig, f, it) = [pos(1), pos(2) - shifts(it)]
                  if (.not. m%has_tools) cycle
                  call tool_gap(m%tool(it), pos(1), pos(2) - shifts(it), d, nrm, curv, t, seg, &
                                hint=nint(cn(ich_hint, ig, f, it)))
                  ! the face offset of contact_faces = 'current' at the new
                  ! station (as contact_station measures the penetration)
                  off = 0.0_dp
                  if (m%current_faces) call face_offset(m%thickness, eps, rho, it == 1, off, ode, odr)
                  d = d - off
                  cn(ich_offset, ig, f, it) = off
                  cn(ich_penetration, ig, f, it) = d
                  cn(ich_hint, ig, f, it) = real(seg, dp)
                  ! in contact as its own gap says (contact_station's
                  ! rule): a station out of contact keeps no slip history,
                  ! one in contact keeps its neighbour's
                  if (d > 0.0_dp) then
                     cn(ich_active, ig, f, it) = 1.0_dp
                  else
                     cn([ich_active, ich_slip, ich_slip_max, ich_sense, ich_traction], ig, f, it) = 0.0_dp
                  end if
               end do
            end do
         end do
      end do
      call move_alloc(xn, m%x)
      m%n_el = n_new
      m%n_nodes = n_new + 1
      m%n_dof = dofs_per_node*m%n_nodes
      ! (trial copies into the arrays allocated above: no allocation here)
      u1n = un
      call move_alloc(un, s%u)
      call move_alloc(u1n, s%u1)
      h1n = hn
      call move_alloc(hn, s%hn)
      call move_alloc(h1n, s%h1)
      c1n = cn
      call move_alloc(cn, s%cn)
      call move_alloc(c1n, s%c1)
      gpt = gpn
      call move_alloc(gpn, s%gpn)
      call move_alloc(gpt, s%gp)
      call move_alloc(ind, s%indicator)
   end subroutine split_elements

   !> REEQUILIBRATE: the state mapped onto a split mesh (split_elements)
   !> brought into equilibrium at the same load (docs/theory.md §7.6, 4).
   !> The mapped stresses are not in equilibrium on the new stations: their
   !> imbalance r0 is removed gradually, as a load f_ext + (1 - alpha) r0
   !> with alpha from 0 (the mapped state, in equilibrium by construction)
   !> to 1, each step committed, doubled after a success and quartered
   !> after a failure: mid-pull, with sections past their maximum load on
   !> the radius, a single Newton solve from the mapped state can leave
   !> the branch the run was on (bead A steel at 0.59h: diverged).
   !>  m         [in]     the model on the split mesh
   !>  s         [in,out] the mapped state; on return the last committed
   !>                     step's (in equilibrium when eq%status = reeq_ok)
   !>  ld        [in]     the load at which it is to be in equilibrium, on
   !>                     the split mesh
   !>  kb        [in,out] a band matrix of the split mesh's size (work)
   !>  r         [in,out] the split mesh's size: the residual of the last
   !>                     solve (the reactions at the prescribed dofs)
   !>  max_iter  [in]     Newton's iteration limit
   !>  tol       [in]     Newton's tolerance
   !>  eq        [out]    what was done (module type reequilibration)
   subroutine reequilibrate(m, s, ld, kb, r, max_iter, tol, eq)
      type(model_type), intent(in) :: m
      type(state_type), intent(inout) :: s
      type(load_type), intent(in) :: ld
      type(band_matrix), intent(inout) :: kb
      real(dp), intent(inout) :: r(:)
      integer, intent(in) :: max_iter
      real(dp), intent(in) :: tol
      type(reequilibration), intent(out) :: eq
      type(load_type) :: ld_step
      type(newton_result) :: nr
      real(dp), allocatable :: r0(:), u_mapped(:)
      real(dp) :: f_scale, pnewdt, alpha, da
      integer :: stat
      allocate (r0(m%n_dof), u_mapped(m%n_dof), stat=stat)
      if (stat /= 0) then
         eq%status = reeq_out_of_memory
         eq%errmsg = alloc_message('the work arrays of '//itoa(m%n_el)//' elements', 16.0_dp*real(m%n_dof, dp))
         return
      end if
      u_mapped = s%u
      s%u1 = s%u
      call assemble(m, s, ld, kb, r0, f_scale, pnewdt)
      eq%assemblies = 1
      r0 = merge(0.0_dp, r0, ld%fixed)
      ld_step = ld
      alpha = 0.0_dp
      da = 1.0_dp
      do while (alpha < 1.0_dp .and. pnewdt >= 1.0_dp)
         da = min(da, 1.0_dp - alpha)
         ld_step%f_ext = ld%f_ext + (1.0_dp - (alpha + da))*r0
         s%u1 = s%u
         call newton_solve(m, s, ld_step, kb, r, max_iter, tol, nr)
         eq%iterations = eq%iterations + nr%iterations
         eq%assemblies = eq%assemblies + nr%assemblies
         if (nr%status == newton_ok) then
            call commit_state(m, s, ld%tool_shift)
            alpha = alpha + da
            eq%steps = eq%steps + 1
            da = 2.0_dp*da
         else
            da = 0.25_dp*da
            if (da < 1.0_dp/4096.0_dp) exit
         end if
      end do
      eq%removed = alpha
      eq%residual = nr%residual(nr%iterations)
      if (pnewdt < 1.0_dp) then
         eq%status = reeq_material
      else if (alpha < 1.0_dp) then
         eq%status = reeq_no_equilibrium
      end if
      ! the dead loads' work over the re-equilibration is external work
      eq%work_dead = dot_product(ld%f_ext, s%u - u_mapped)
   end subroutine reequilibrate

   !> LAST_RADIUS_EXIT: the current abscissa of the exit of the last radius
   !> on the pulled side: the largest x of a Gauss station in contact with
   !> an arc of either tool at the converged state.
   !>  m       [in]  the model (with tools)
   !>  s       [in]  the converged state
   !>  x_exit  [out] the abscissa, mm (unset when found is .false.)
   !>  found   [out] .false. when no station touches an arc
   !>  x_entry [out] optional: the smallest such x, the entry of the first
   !>                radius (exit_state)
   !>  radius  [out] optional: the (centreline) radius of the arc touched
   !>                at x_exit, mm (unset when found is .false.)
   pure subroutine last_radius_exit(m, s, x_exit, found, x_entry, radius)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      real(dp), intent(out) :: x_exit
      logical, intent(out) :: found
      real(dp), intent(out), optional :: x_entry, radius
      integer :: e, ig, it, seg
      x_exit = -huge(1.0_dp)
      if (present(x_entry)) x_entry = huge(1.0_dp)
      if (present(radius)) radius = 0.0_dp
      found = .false.
      if (.not. m%has_tools) return
      do e = 1, m%n_el
         do ig = 1, n_gauss
            do it = 1, 2
               if (s%cn(ich_active, ig, e, it) < 0.5_dp .or. s%cn(ich_penetration, ig, e, it) <= 0.0_dp) cycle
               seg = nint(s%cn(ich_hint, ig, e, it))
               if (seg < 1 .or. seg > size(m%tool(it)%seg)) cycle
               if (m%tool(it)%seg(seg)%kind /= seg_arc) cycle
               found = .true.
               if (s%cn(ich_position, ig, e, it) > x_exit .and. present(radius)) &
                  radius = m%tool(it)%seg(seg)%radius
               x_exit = max(x_exit, s%cn(ich_position, ig, e, it))
               if (present(x_entry)) x_entry = min(x_entry, s%cn(ich_position, ig, e, it))
            end do
         end do
      end do
   end subroutine last_radius_exit

   !> EXIT_PIECES: the parts each element is split into for the neck's
   !> refinement (module constants): an element whose current span meets
   !> [x_exit - before h, x_exit + exit_zone_after h] is cut into parts no
   !> longer than m%exit_element; the others stay whole.
   !>  m       [in]  the model (m%exit_element > 0)
   !>  s       [in]  the converged state
   !>  x_exit  [in]  the exit of the last radius (last_radius_exit), mm
   !>  before  [in]  the window's length before the exit, in h
   !>  pieces  (result) m%n_el parts, >= 1
   pure function exit_pieces(m, s, x_exit, before) result(pieces)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      real(dp), intent(in) :: x_exit, before
      integer :: pieces(m%n_el)
      real(dp) :: lo, hi, xa, xb
      integer :: e
      lo = x_exit - before*m%thickness
      hi = x_exit + exit_zone_after*m%thickness
      pieces = 1
      do e = 1, m%n_el
         xa = m%x(e) + s%u(node_dof(e, dof_v))
         xb = m%x(e + 1) + s%u(node_dof(e + 1, dof_v))
         if (xb < lo .or. xa > hi) cycle
         ! (a relative slack: an element of exactly k target lengths gives k)
         pieces(e) = max(1, ceiling((m%x(e + 1) - m%x(e))/m%exit_element*(1.0_dp - 1.0e-9_dp)))
      end do
   end function exit_pieces
end module remesh
