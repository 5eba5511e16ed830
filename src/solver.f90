!> solver -- global assembly, Newton-Raphson per increment, commit (docs/theory.md §8).
!>
!> The residual is r = f_int(u) - f_ext: internal forces of the elements plus
!> contact and friction forces of the tools, minus dead loads and the end moment.
!> Prescribed dofs are imposed on the trial state before the first iteration,
!> their equations replaced by du_i = 0.
!> Besides r, assemble estimates per dof the round-off that r carries (the
!> floor below which no double-precision state can bring it; docs/theory.md
!> (8.2)): relative to the forces it grows as the cube of the number of
!> elements, and Newton takes a residual at that floor as converged.
module solver
   use kinds, only: dp
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use hermite, only: n_gauss, gauss_xi, gauss_wt, hermite_shape
   use mesh, only: element_dofs, half_band, node_dof, dof_v_slope, dof_w_slope, is_slope_dof
   use band, only: band_matrix, band_init, band_zero, band_add, band_fix_dof, band_solve
   use element, only: element_internal, v_dofs, w_dofs, element_gradients, outer8
   use kinematics, only: strain_measures
   use section, only: section_localization, section_update_zbar, col_eqps, ih_spd, ih_strain
   use model, only: model_type, state_type, load_type
   use contact, only: contact_station, face_offset, ich_active
   implicit none
   private
   public :: newton_result, assemble, newton_solve, commit_state, max_newton_history, &
             newton_ok, newton_diverged, newton_cutback, newton_singular, newton_solve_failed, &
             default_threads, element_roundoff, station_roundoff

   integer, parameter :: max_newton_history = 100
   !> newton_result%status: converged; diverged or too many iterations; a
   !> material point or contact station asked for a smaller increment; the
   !> tangent was singular; the linear solve failed otherwise (a size or
   !> argument error: not cured by a smaller increment)
   integer, parameter :: newton_ok = 0, newton_diverged = 1, newton_cutback = 2, &
                         newton_singular = 3, newton_solve_failed = 4

   !> What one Newton solve did.
   type :: newton_result
      integer :: status = newton_ok
      integer :: iterations = 0
      real(dp) :: residual(0:max_newton_history) = 0.0_dp ! scaled residual per iteration
      ! the residual's round-off floor per iteration, scaled like the
      ! residual (8.2): the test is against max(tol, round_off)
      real(dp) :: round_off(0:max_newton_history) = 0.0_dp
      integer :: solve_info = 0                            ! band_solve's info when it failed
      integer :: assemblies = 0                            ! calls of assemble (line search included)
      real(dp) :: pnewdt = 1.0_dp                          ! cut factor asked for (1: none)
      ! with count_states: the material points plastic in each iterate (their
      ! equivalent plastic strain above the converged one), and those that
      ! changed between plastic and elastic since the previous iterate (each
      ! change is a kink of the residual that Newton crosses; 0 otherwise)
      integer :: plastic(0:max_newton_history) = 0
      integer :: switched(0:max_newton_history) = 0
      ! iterations whose correction changed the number of stations in
      ! contact (a solve that fails with most of its iterations so is
      ! chattering between contact sets: analysis's failed_attempt says so)
      integer :: contact_changes = 0
   end type newton_result

contains

   !> DEFAULT_THREADS: the number of threads of the assembly when the user
   !> has not chosen one: one, unless OMP_NUM_THREADS is set (then OpenMP
   !> takes it).  Threads pay only on free cores; on a busy machine a run
   !> with more threads than free cores is many times slower, since its
   !> threads meet at every assembly (docs/performance.md).  The results
   !> do not depend on the number.  Called once by the main program, before
   !> any parallel loop; without OpenMP it does nothing.
   subroutine default_threads()
      !$ use omp_lib, only: omp_set_num_threads
      integer :: length, stat
      call get_environment_variable('OMP_NUM_THREADS', length=length, status=stat)
      !$ if (stat /= 0 .or. length == 0) call omp_set_num_threads(1)
   end subroutine default_threads

   !> ASSEMBLE: residual and tangent of the whole sheet at the trial state s%u1.
   !>
   !> The elements are computed in parallel (OpenMP; OMP_NUM_THREADS threads)
   !> into per-element arrays, then added to the band matrix, the residual,
   !> the force scale and the tool forces serially in element order: the sums
   !> are formed in the same order whatever the number of threads, so the
   !> results are the same bit for bit (docs/performance.md).  A user's UMAT
   !> is not known to be thread safe: with one the elements run serially.
   !> As in a serial loop, the first element (in element order) that asks for
   !> a cut decides pnewdt, and nothing after it is added; the trial state
   !> (h1, c1, gp) is then not to be used.
   !>  m      [in]  model
   !>  s      [in,out] state: h1, c1 and gp are rewritten from hn, cn and u1
   !>                (a law with starts_from_trial first reads h1's equivalent
   !>                plastic strain, the last trial's: section_response)
   !>  ld     [in]  applied loads and tool position
   !>  kb     [in,out] band tangent (allocated by the caller), overwritten
   !>  r      [out] residual f_int - f_ext at every dof (reactions at fixed dofs)
   !>  f_scale [out] norm of the internal forces (force scale for convergence)
   !>  pnewdt [out] < 1 if a material point or contact station asks for a cut
   !>  r_floor [out] optional: per dof, the round-off r carries at this state
   !>                (element_roundoff, station_roundoff, and eps |f_ext|;
   !>                at fixed dofs too), for the convergence test (8.2)
   subroutine assemble(m, s, ld, kb, r, f_scale, pnewdt, r_floor)
      type(model_type), intent(in) :: m
      type(state_type), intent(inout) :: s
      type(load_type), intent(in) :: ld
      type(band_matrix), intent(inout) :: kb
      real(dp), intent(out) :: r(:), f_scale
      real(dp), intent(out) :: pnewdt
      real(dp), intent(out), optional :: r_floor(:)
      ! per element: residual, tangent, the two parts of its force-scale
      ! term, its pnewdt, per Gauss station and tool the force on the
      ! tool's account (dv fc) and whether the station is in contact, and
      ! the round-off of its residual
      ! (on the heap: a large mesh must not overflow the stack)
      real(dp), allocatable :: re_all(:, :), ke_all(:, :, :), fs_all(:, :), pn_all(:), &
                               ft_all(:, :, :, :), rf_all(:, :)
      logical, allocatable :: on_all(:, :, :)
      real(dp) :: shifts(2)
      integer :: e, ig, it, stat
      logical :: threads
      call band_zero(kb)
      r = 0.0_dp
      pnewdt = 1.0_dp
      f_scale = 0.0_dp
      shifts = [0.0_dp, ld%tool_shift]
      s%tool_force = 0.0_dp
      s%n_contact = 0
      allocate (re_all(8, m%n_el), ke_all(8, 8, m%n_el), fs_all(2, m%n_el), pn_all(m%n_el), &
                ft_all(2, n_gauss, 2, m%n_el), on_all(n_gauss, 2, m%n_el), rf_all(8, m%n_el))
      ! the dead loads cancel internal forces at their dofs: a rounding of
      ! the difference (the end moment's part is added with it, below)
      if (present(r_floor)) r_floor = epsilon(1.0_dp)*abs(ld%f_ext)
      threads = m%material%thread_safe
      ! each element writes only its own columns of h1, c1, gp and the
      ! work arrays.  A static schedule gives each thread the same block of
      ! elements in every assembly and in the commit, so that its part of
      ! the history stays in its core's cache: 8-17% faster on the paper
      ! decks than dynamic chunks of 4 elements, which balance the plastic
      ! and contact elements better but move elements between the cores
      !$omp parallel do if (threads) default(none) schedule(static) &
      !$omp shared(m, s, shifts, re_all, ke_all, fs_all, pn_all, ft_all, on_all, rf_all)
      do e = 1, m%n_el
         call assemble_element(m, e, shifts, s%u1, s%hn(:, :, :, e), s%h1(:, :, :, e), &
                               s%cn(:, :, e, :), s%c1(:, :, e, :), s%gp(:, :, e), &
                               re_all(:, e), ke_all(:, :, e), fs_all(:, e), pn_all(e), &
                               ft_all(:, :, :, e), on_all(:, :, e), rf_all(:, e))
      end do
      !$omp end parallel do
      do e = 1, m%n_el
         if (pn_all(e) < 1.0_dp) then
            pnewdt = pn_all(e)
            return
         end if
         f_scale = f_scale + fs_all(1, e) + fs_all(2, e)
         if (m%has_tools) then
            do ig = 1, n_gauss
               do it = 1, 2
                  if (.not. on_all(ig, it, e)) cycle
                  s%n_contact = s%n_contact + 1
                  s%tool_force(:, it) = s%tool_force(:, it) + ft_all(:, ig, it, e)
               end do
            end do
         end if
         call band_add(kb, element_dofs(e), ke_all(:, :, e), stat)
         r(element_dofs(e)) = r(element_dofs(e)) + re_all(:, e)
         if (present(r_floor)) r_floor(element_dofs(e)) = r_floor(element_dofs(e)) + rf_all(:, e)
      end do
      r = r - ld%f_ext
      if (ld%moment_node > 0) then
         if (present(r_floor)) then
            call add_end_moment(ld%moment_node, ld%moment, s%u1, r, kb, r_floor)
         else
            call add_end_moment(ld%moment_node, ld%moment, s%u1, r, kb)
         end if
      end if
      f_scale = sqrt(f_scale + sum(ld%f_ext**2) + (ld%moment/m%thickness)**2)
   end subroutine assemble

   !> ASSEMBLE_ELEMENT: residual and tangent of element e with its contact
   !> stations, at the trial dofs u1 (assemble adds them up).
   !>  m       [in]  model
   !>  e       [in]  the element
   !>  shifts  [in]  vertical shift of tool 1, 2
   !>  u1      [in]  trial dofs of the whole sheet
   !>  hn, h1  [in], [in,out] the element's converged and trial section
   !>                histories (npt, n_hist, n_gauss); h1 on entry the last
   !>                trial's (section_response)
   !>  cn, c1  [in], [out] its stations' converged and trial contact histories
   !>                (n_chist, n_gauss, 2 tools)
   !>  gp      [out] per Gauss point: eps, rho, N, M
   !>  re, ke  [out] element residual f_int - f_contact (8) and tangent (8, 8)
   !>  fs      [out] its terms of the force scale: sum of squared forces,
   !>                sum of squared moments over the thickness
   !>  pnewdt  [out] < 1 if a material point asks for a cut (then the other
   !>                outputs are not to be used)
   !>  ft      [out] (2, n_gauss, 2) force of each station on each tool's
   !>                account, dv fc (0 out of contact)
   !>  on      [out] (n_gauss, 2) the station is in contact with the tool
   !>  rf      [out] (8) the round-off of re: element_roundoff plus the
   !>                station_roundoff of its stations in contact
   subroutine assemble_element(m, e, shifts, u1, hn, h1, cn, c1, gp, re, ke, fs, pnewdt, ft, on, rf)
      type(model_type), intent(in) :: m
      integer, intent(in) :: e
      real(dp), intent(in) :: shifts(2), u1(:)
      real(dp), contiguous, intent(in) :: hn(:, :, :)
      real(dp), contiguous, intent(inout) :: h1(:, :, :)
      real(dp), intent(in) :: cn(:, :, :)
      real(dp), intent(inout) :: c1(:, :, :)
      real(dp), intent(out) :: gp(:, :), re(8), ke(8, 8), fs(2), pnewdt, ft(2, n_gauss, 2)
      logical, intent(out) :: on(n_gauss, 2)
      real(dp), intent(out) :: rf(8)
      real(dp) :: le, ul(8), nv(4), dn(4), d2n(4), nm(2, 8), p(2), pg(2, n_gauss)
      real(dp) :: fc(2, n_gauss, 2), kc(2, 2, n_gauss, 2), dv, fn, dfn(2)
      ! the face offset (docs/theory.md §5.1) and what carries it into the tangent
      real(dp) :: offset(n_gauss, 2), doff(8, n_gauss, 2), dfdd(2, n_gauss, 2), dfndd, gk(4), gmk(4, 8), &
                  epsk, rhok, depsk(4), drhok(4), d2ek(4, 4), d2rk(4, 4), ode, odr
      real(dp) :: nmg(2, 8, n_gauss), face_force(2, n_gauss), dface_force(8, 2, n_gauss)
      ! the element dofs of the displacement components v and w
      integer, parameter :: dof_block(4, 2) = reshape([v_dofs, w_dofs], [4, 2])
      integer :: ig, it, ia, ib, dofs(8)
      pnewdt = 1.0_dp
      fs = 0.0_dp
      ft = 0.0_dp
      on = .false.
      rf = 0.0_dp
      dofs = element_dofs(e)
      le = m%x(e + 1) - m%x(e)
      ul = u1(dofs)
      ! contact first: with the contact section its normal forces load the
      ! faces of the element's Gauss stations (tool 1, the upper tool, the
      ! top face; tool 2 the bottom face)
      face_force = 0.0_dp
      dface_force = 0.0_dp
      if (m%has_tools) then
         do ig = 1, n_gauss
            call hermite_shape(gauss_xi(ig), le, nv, dn, d2n)
            nm = 0.0_dp
            nm(1, v_dofs) = nv
            nm(2, w_dofs) = nv
            nmg(:, :, ig) = nm
            p = matmul(nm, ul)
            p(1) = p(1) + m%x(e) + gauss_xi(ig)*le
            pg(:, ig) = p
            ! the faces' offsets toward the centreline and their gradients on
            ! the element dofs (docs/theory.md §5.1, contact's face_offset):
            ! each face from the trial stretch and bending strain (the
            ! reference faces: none, and no gradient to carry)
            offset(ig, :) = 0.0_dp
            if (m%current_faces) then
               call element_gradients(gauss_xi(ig), le, ul, gk, gmk)
               call strain_measures(gk, epsk, rhok, depsk, drhok, d2ek, d2rk)
               do it = 1, 2
                  call face_offset(m%thickness, epsk, rhok, it == 1, offset(ig, it), ode, odr)
                  doff(:, ig, it) = matmul(ode*depsk + odr*drhok, gmk)
               end do
            end if
            do it = 1, 2
               ! the face against the tool: the top (tool 1) or the bottom
               ! (tool 2), its converged log stretch ln Lambda (contact_station
               ! takes its exponential where a pressure needs it)
               call contact_station(m%tool(it), shifts(it), m%penalty, m%contact_smoothing, m%friction, &
                                    hn(merge(size(hn, 1), 1, it == 1), ih_strain, ig), p, cn(:, ig, it), &
                                    c1(:, ig, it), fc(:, ig, it), kc(:, :, ig, it), fn, dfn, &
                                    offset=offset(ig, it), dfdd=dfdd(:, ig, it), dfndd=dfndd)
               if (m%contact_section .and. fn > 0.0_dp) then
                  face_force(3 - it, ig) = fn
                  dface_force(:, 3 - it, ig) = matmul(dfn, nm)
                  ! and through the face offset
                  if (m%current_faces) dface_force(:, 3 - it, ig) = dface_force(:, 3 - it, ig) &
                                                                   - dfndd*doff(:, ig, it)
               end if
            end do
         end do
      end if
      call element_internal(le, ul, m%wz, m%material, hn, h1, re, ke, gp, pnewdt, &
                            face_force, dface_force, m%gradient, m%gradient_curve)
      if (pnewdt < 1.0_dp) return
      rf = element_roundoff(ke, ul, le)
      ! moments (slope dofs) enter the force scale divided by the thickness
      fs(1) = sum(re(1:8:2)**2)
      fs(2) = sum((re(2:8:2)/m%thickness)**2)
      if (m%has_tools) then
         do ig = 1, n_gauss
            dv = gauss_wt(ig)*le
            do it = 1, 2
               ! a station out of contact contributes nothing
               if (c1(ich_active, ig, it) < 0.5_dp) cycle
               on(ig, it) = .true.
               ! the tool pushes the sheet with fc: it enters r = f_int - f_ext with -
               re = re - dv*matmul(fc(:, ig, it), nmg(:, :, ig))
               rf = rf + station_roundoff(nmg(:, :, ig), kc(:, :, ig, it), pg(:, ig), dv)
               ft(:, ig, it) = dv*fc(:, ig, it)
               ! - dv N^T kc N, N = [nv on the v dofs; nv on the w dofs]:
               ! block (a, b) is kc(a, b) nv nv^T
               nv = nmg(1, v_dofs, ig)
               do ib = 1, 2
                  do ia = 1, 2
                     ke(dof_block(:, ia), dof_block(:, ib)) = ke(dof_block(:, ia), dof_block(:, ib)) &
                        - dv*outer4(nv, kc(ia, ib, ig, it)*nv)
                  end do
               end do
               ! the force's dependence on the face offset: d = d(p) - offset(u_e)
               if (m%current_faces) ke = ke + dv*outer8(matmul(dfdd(:, ig, it), nmg(:, :, ig)), doff(:, ig, it))
            end do
         end do
      end if
   end subroutine assemble_element

   !> OUTER4: the outer product a b^T of two 4-vectors.
   pure function outer4(a, b) result(c)
      real(dp), intent(in) :: a(4), b(4)
      real(dp) :: c(4, 4)
      integer :: j
      do j = 1, 4
         c(:, j) = a*b(j)
      end do
   end function outer4

   !> ELEMENT_ROUNDOFF: the round-off of an element's residual re(u_e),
   !> eps |K_e| (|u_e| + |x_e - x_c|) entry by entry: the change of re when
   !> each of its inputs is rounded by eps relative (a first-order bound;
   !> docs/theory.md §8.2).  The inputs are the nodal displacements, which
   !> the strains take through differences over the element (v', w'' ~
   !> u/le, u/le^2: their rounding is relative to u, not to the strain), and
   !> the reference geometry, which enters as the 1 of the stretch 1 + v':
   !> the field x - x_c relative to the element's centre, which the Hermite
   !> shape functions carry exactly with nodal values -le/2, le/2 and slopes
   !> 1.  So the floor grows as E h^3 |w|/le^3 per transverse dof: the
   !> cube of the number of elements.
   !>  ke [in] the element tangent (8, 8), d re/d u_e
   !>  ul [in] the element's dofs (8): v, v', w, w' at node 1, then node 2
   !>  le [in] the element's length
   !>  rf [result] (8) the round-off of each entry of re
   pure function element_roundoff(ke, ul, le) result(rf)
      real(dp), intent(in) :: ke(8, 8), ul(8), le
      real(dp) :: rf(8)
      real(dp) :: a(8)
      a = abs(ul) + [0.5_dp*le, 1.0_dp, 0.0_dp, 0.0_dp, 0.5_dp*le, 1.0_dp, 0.0_dp, 0.0_dp]
      rf = epsilon(1.0_dp)*matmul(abs(ke), a)
   end function element_roundoff

   !> STATION_ROUNDOFF: the round-off of a contact station's part of the
   !> element residual, dv N^T fc(p): the station's gap is measured from
   !> its position p = (x + v, w), rounded relative to p itself (to about
   !> eps |x|, not eps |v|), so dv eps |N|^T |kc| |p|.
   !>  nm [in] (2, 8) the shape functions at the station, p = p_ref + nm u_e
   !>  kc [in] (2, 2) the station's stiffness d fc/d p
   !>  p  [in] (2) the station's position
   !>  dv [in] the station's length (Gauss weight times le)
   !>  rf [result] (8) the round-off of each entry of the element residual
   pure function station_roundoff(nm, kc, p, dv) result(rf)
      real(dp), intent(in) :: nm(2, 8), kc(2, 2), p(2), dv
      real(dp) :: rf(8)
      rf = epsilon(1.0_dp)*dv*matmul(matmul(abs(kc), abs(p)), abs(nm))
   end function station_roundoff

   !> ADD_END_MOMENT: a conservative end moment M at node n, external work
   !> M theta with theta = atan2(w', 1 + v') the rotation of the tangent.
   !> Adds -M dtheta/dq to r and -M d2theta/dq2 to the tangent.
   !>  n       [in]  the node
   !>  moment  [in]  M
   !>  u       [in]  the dofs
   !>  r       [in,out] residual
   !>  kb      [in,out] band tangent
   !>  r_floor [in,out] optional: the round-off of r, eps |M dtheta/dq| added
   subroutine add_end_moment(n, moment, u, r, kb, r_floor)
      integer, intent(in) :: n
      real(dp), intent(in) :: moment, u(:)
      real(dp), intent(inout) :: r(:)
      type(band_matrix), intent(inout) :: kb
      real(dp), intent(inout), optional :: r_floor(:)
      real(dp) :: a, b, q, dth(2), d2th(2, 2)
      integer :: dofs(2), stat
      dofs = [node_dof(n, dof_v_slope), node_dof(n, dof_w_slope)]
      a = 1.0_dp + u(dofs(1))
      b = u(dofs(2))
      q = a*a + b*b
      dth = [-b/q, a/q]
      d2th(1, 1) = 2.0_dp*a*b/q**2
      d2th(2, 2) = -2.0_dp*a*b/q**2
      d2th(1, 2) = (b*b - a*a)/q**2
      d2th(2, 1) = d2th(1, 2)
      r(dofs) = r(dofs) - moment*dth
      if (present(r_floor)) r_floor(dofs) = r_floor(dofs) + epsilon(1.0_dp)*abs(moment*dth)
      call band_add(kb, dofs, -moment*d2th, stat)
   end subroutine add_end_moment

   !> NEWTON_SOLVE: equilibrium at the loads ld, starting from the trial s%u1
   !> (the caller may put a predictor there); prescribed dofs reach their
   !> values through the first linear solve.
   !> Converged when the scaled residual is below tol, or below its
   !> round-off floor where that is higher (a fine mesh), and the last scaled
   !> correction below sqrt(tol): residual ||r_free|| / force scale,
   !> correction max |du|/h over displacement dofs and max |du| over slopes
   !> (docs/theory.md (8.2)).
   !>  m, s, ld  [in], [in,out], [in]
   !>  kb        [in,out] work band matrix (allocated once by the caller)
   !>  r         [out] residual at the solution (reactions at fixed dofs)
   !>  max_iter  [in]  iteration limit
   !>  tol       [in]  tolerance
   !>  res       [out] what happened
   !>  count_states [in]  optional: count the plastic material points of
   !>                      every iterate and their changes (res%plastic,
   !>                      res%switched)
   subroutine newton_solve(m, s, ld, kb, r, max_iter, tol, res, count_states)
      type(model_type), intent(in) :: m
      type(state_type), intent(inout) :: s
      type(load_type), intent(in) :: ld
      type(band_matrix), intent(inout) :: kb
      real(dp), intent(out) :: r(:)
      integer, intent(in) :: max_iter
      real(dp), intent(in) :: tol
      type(newton_result), intent(out) :: res
      logical, intent(in), optional :: count_states
      real(dp) :: f_scale, pnewdt, rnorm, cnorm, floor_norm
      ! on the heap: a large mesh must not overflow the stack (-fstack-arrays)
      real(dp), allocatable :: du(:), r_floor(:)
      integer :: it, i, info, backtrack, k
      real(dp) :: g0, g1, alpha
      integer :: n_contact_prev
      ! the column that grows where a station yields: the equivalent plastic
      ! strain, or the plastic work for a law without one
      integer :: i_plastic
      logical :: counting
      logical, allocatable :: plastic(:, :, :), was_plastic(:, :, :)
      counting = .false.
      if (present(count_states)) counting = count_states
      i_plastic = col_eqps(m%material)
      if (i_plastic == 0) i_plastic = ih_spd
      allocate (du(size(r)), r_floor(size(r)))
      ! the state counts only with count_states (empty otherwise)
      k = merge(m%npt, 0, counting)
      allocate (plastic(k, n_gauss, m%n_el), was_plastic(k, n_gauss, m%n_el))
      cnorm = huge(1.0_dp)
      do it = 0, min(max_iter, max_newton_history)
         n_contact_prev = s%n_contact
         call assemble(m, s, ld, kb, r, f_scale, pnewdt, r_floor)
         res%assemblies = res%assemblies + 1
         res%iterations = it
         ! line search along the last correction du where the step changed
         ! the set of contact stations (the residual is not smooth there):
         ! accept the full step unless the work of the new residual on du,
         ! g1 = du.r(u + du), exceeds that of the old, g0 = du.r(u) (a far
         ! overshoot, e.g. a station thrown deep into a tool); then take the
         ! secant step g0/(g0 - g1), clamped to [0.1, 1].  An iterate that a
         ! material point cannot take (a fibre inverted, a failed return
         ! map) is halved back instead.  At most three tries.
         backtrack = 0
         g1 = 0.0_dp
         if (it > 0) g1 = dot_product(du, merge(0.0_dp, r, ld%fixed))
         do while (it > 0 .and. backtrack < 3)
            if (pnewdt >= 1.0_dp) then
               if (s%n_contact == n_contact_prev .or. abs(g1) <= abs(g0)) exit
            end if
            backtrack = backtrack + 1
            if (pnewdt < 1.0_dp) then
               alpha = 0.5_dp
            else
               alpha = min(1.0_dp, max(0.1_dp, g0/(g0 - g1)))
               if (alpha >= 1.0_dp) exit
            end if
            s%u1 = s%u1 - (1.0_dp - alpha)*du
            du = alpha*du
            g0 = alpha*g0
            call assemble(m, s, ld, kb, r, f_scale, pnewdt, r_floor)
            res%assemblies = res%assemblies + 1
            g1 = dot_product(du, merge(0.0_dp, r, ld%fixed))
         end do
         if (it > 0 .and. s%n_contact /= n_contact_prev) res%contact_changes = res%contact_changes + 1
         rnorm = scaled_norm(m, ld, r, f_scale)
         if (pnewdt < 1.0_dp) then
            res%pnewdt = pnewdt
            res%status = newton_cutback
            return
         end if
         res%residual(it) = rnorm
         floor_norm = scaled_norm(m, ld, r_floor, f_scale)
         res%round_off(it) = floor_norm
         if (counting) then
            plastic(:, :, :) = s%h1(:, i_plastic, :, :) > s%hn(:, i_plastic, :, :)
            res%plastic(it) = count(plastic)
            if (it > 0) res%switched(it) = count(plastic .neqv. was_plastic)
            was_plastic(:, :, :) = plastic
         end if
         if (.not. ieee_is_finite(rnorm)) then
            res%status = newton_diverged
            return
         end if
         ! the residual at tol and the last correction at sqrt(tol): with
         ! quadratic convergence the error left is then O(tol) as well.  On
         ! a fine mesh the residual's round-off can lie above tol (it grows
         ! as n_el^3: 2e-7 with 4000 elements on bead A): no double-precision
         ! state has a smaller residual, Newton's corrections fall below the
         ! displacements' last bit while the residual wanders at that level,
         ! and the attempt would end as diverged; a residual at the floor is
         ! converged (docs/theory.md §8.2).  Where the floor is below tol
         ! (every ordinary mesh: 1e-12 with 80 elements) nothing changes.
         if (it > 0 .and. rnorm <= max(tol, floor_norm) .and. cnorm <= sqrt(tol)) then
            res%status = newton_ok
            return
         end if
         if (it == max_iter) then
            res%status = newton_diverged
            return
         end if
         if (it >= 5) then
            ! growing twice in a row after the first iterations: diverging
            if (rnorm > res%residual(max(it - 1, 0)) .and. &
                res%residual(max(it - 1, 0)) > res%residual(max(it - 2, 0))) then
               res%status = newton_diverged
               return
            end if
         end if
         ! prescribed dofs: their equation is du_i = u_fixed_i - u1_i, so the
         ! first solve carries the prescribed increment into the whole sheet
         ! with the tangent of the converged state (the jump is not forced
         ! into the edge element before the first solve)
         du = merge(ld%u_fixed - s%u1, -r, ld%fixed)
         do i = 1, size(du)
            if (ld%fixed(i)) call band_fix_dof(kb, i)
         end do
         call band_solve(kb, du, info)
         if (info /= 0) then
            res%status = merge(newton_singular, newton_solve_failed, info > 0)
            res%solve_info = info
            return
         end if
         g0 = dot_product(du, merge(0.0_dp, r, ld%fixed))
         s%u1 = s%u1 + du
         cnorm = 0.0_dp
         do i = 1, size(du)
            if (is_slope_dof(i)) then
               cnorm = max(cnorm, abs(du(i)))
            else
               cnorm = max(cnorm, abs(du(i))/m%thickness)
            end if
         end do
      end do
      res%status = newton_diverged
   end subroutine newton_solve

   !> SCALED_NORM: ||r|| over the free dofs, moments divided by the thickness,
   !> relative to the force scale (floored at 1e-12 E h).
   pure function scaled_norm(m, ld, r, f_scale) result(rnorm)
      type(model_type), intent(in) :: m
      type(load_type), intent(in) :: ld
      real(dp), intent(in) :: r(:), f_scale
      real(dp) :: rnorm
      integer :: i
      rnorm = 0.0_dp
      do i = 1, size(r)
         if (ld%fixed(i)) cycle
         if (is_slope_dof(i)) then
            rnorm = rnorm + (r(i)/m%thickness)**2
         else
            rnorm = rnorm + r(i)**2
         end if
      end do
      rnorm = sqrt(rnorm)/max(f_scale, 1.0e-12_dp*m%youngs*m%thickness)
   end function scaled_norm

   !> COMMIT_STATE: accept the trial state as converged; update the lagged
   !> station distances and the localization indicator of every Gauss station.
   !>  m  [in]  model
   !>  s  [in,out] state: u <- u1, hn <- h1, cn <- c1 (the contact histories,
   !>              integrated to the trial state by contact_station), gpn <- gp;
   !>              h1, c1 and gp are exchanged with them, so they hold the
   !>              previous converged state until the next assemble rewrites them
   !>              (whose equivalent plastic strain is not above hn's: the next
   !>              section update starts its return at the trial, section_response)
   !>  shift [in] the lower tool's rise at this state
   subroutine commit_state(m, s, shift)
      type(model_type), intent(in) :: m
      type(state_type), intent(inout) :: s
      real(dp), intent(in) :: shift
      integer :: e, ig
      real(dp), allocatable :: swap4(:, :, :, :), swap3(:, :, :)
      ! each element's stations are independent: in parallel, with the
      ! elements on the threads as in assemble (static schedule)
      !$omp parallel do default(none) schedule(static) private(ig) shared(m, s)
      do e = 1, m%n_el
         do ig = 1, n_gauss
            s%indicator(ig, e) = section_localization(m%wz, s%h1(:, :, ig, e), &
                                                      m%thickness, m%material)
            call section_update_zbar(m%z, m%material, s%h1(:, :, ig, e))
         end do
      end do
      !$omp end parallel do
      ! the trial arrays become the converged ones by exchanging them, not
      ! by copying (the history is the largest array of a run): the trial
      ! arrays then hold the previous converged state, which the next
      ! assemble overwrites; it reads only their equivalent plastic strain
      ! first, not above the converged one (section_response's dp_start)
      call move_alloc(s%hn, swap4)
      call move_alloc(s%h1, s%hn)
      call move_alloc(swap4, s%h1)
      call move_alloc(s%cn, swap4)
      call move_alloc(s%c1, s%cn)
      call move_alloc(swap4, s%c1)
      call move_alloc(s%gpn, swap3)
      call move_alloc(s%gp, s%gpn)
      call move_alloc(swap3, s%gp)
      s%u = s%u1
      s%shift = shift
   end subroutine commit_state
end module solver
