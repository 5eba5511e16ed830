!> model -- the two derived types that carry a run: the fixed model and the
!> evolving state (converged and trial copies, FEAP's hn/h1).
module model
   use kinds, only: dp
   use hermite, only: n_gauss, gauss_xi, simpson_rule
   use mesh, only: graded_nodes, zone_counts, zone_nodes, dofs_per_node
   use section, only: hist_size, section_init
   use tools, only: tool_type
   use element, only: n_gp
   use contact, only: n_chist, ich_position
   use material_law, only: material_law_type, max_load_strain
   use friction_law, only: friction_law_type
   use neck_gradient, only: neck_gradient_type
   use errors, only: alloc_message
   use text, only: itoa
   implicit none
   private
   public :: model_type, state_type, load_type, model_init, model_rezone, state_init, load_init, &
             gauss_position

   type :: model_type
      integer :: n_el = 0, n_nodes = 0, n_dof = 0, npt = 0
      real(dp) :: thickness = 0.0_dp, youngs = 0.0_dp
      real(dp), allocatable :: x(:)          ! reference node positions
      real(dp), allocatable :: z(:), wz(:)   ! Simpson stations and weights
      class(material_law_type), allocatable :: material ! the material law (module material_law)
      integer :: n_hist = 0                  ! history columns of a section (section's hist_size)
      real(dp) :: max_load_strain = 0.0_dp   ! plane-strain maximum-load log strain of the material
      real(dp) :: max_load_stress = 0.0_dp   ! the axial Kirchhoff stress there, MPa
      ! tools and contact (bead /= 'none')
      logical :: has_tools = .false.
      type(tool_type) :: tool(2)             ! 1 upper (fixed), 2 lower (moves by H)
      real(dp) :: penalty = 0.0_dp           ! k, N/mm^3 (force per ref length per mm)
      real(dp) :: contact_smoothing = 0.0_dp ! delta, mm: smoothed penalty onset
      logical :: current_faces = .false.     ! the tools meet the sheet's current faces (docs/theory.md §5.1)
      class(friction_law_type), allocatable :: friction ! the friction law (module friction_law)
      logical :: contact_section = .false.   ! the tools' normal forces load the section (docs/theory.md §12)
      real(dp) :: gradient = 0.0_dp          ! c of the strain-gradient term (1/2) c (d lambda/ds)^2, N mm (0: none), at the maximum load
      type(neck_gradient_type) :: gradient_curve ! how c follows the stretch past the maximum-load strain (module neck_gradient)
      ! load schedule: locking to lock_depth, then pulling by pull_distance
      logical :: left_edge_free = .false.    ! v free under the back tension; else clamped
      real(dp) :: back_tension = 0.0_dp      ! N/mm, on a free left edge
      real(dp) :: lock_depth = 0.0_dp        ! H at the end of locking, mm
      real(dp) :: pull_distance = 0.0_dp     ! delta at the end of pulling, mm
      ! the neck's refinement on the default path (docs/theory.md §7.6):
      ! length of the elements split at the exit of the last radius after
      ! locking, mm (0: none)
      real(dp) :: exit_element = 0.0_dp
      ! the longest element on which the restraining force's maximum (the
      ! tearing point of the load-maximum criterion) converges at the neck,
      ! mm (docs/theory.md §7.6): longer ones make it mesh-dependent (set by
      ! setup_run; 0, a model built otherwise: every element is longer)
      real(dp) :: neck_element = 0.0_dp
   end type model_type

   !> What is applied in one increment: prescribed dofs, dead loads, an end
   !> moment (conservative: work M*theta at node moment_node) and the rise of
   !> the lower tool.
   type :: load_type
      logical, allocatable :: fixed(:)
      real(dp), allocatable :: u_fixed(:)
      real(dp), allocatable :: f_ext(:)
      integer :: moment_node = 0
      real(dp) :: moment = 0.0_dp
      real(dp) :: tool_shift = 0.0_dp
   end type load_type

   type :: state_type
      real(dp), allocatable :: u(:), u1(:)               ! converged, trial dofs
      real(dp), allocatable :: hn(:, :, :, :), h1(:, :, :, :) ! (npt, m%n_hist, n_gauss, n_el)
      real(dp), allocatable :: cn(:, :, :, :), c1(:, :, :, :) ! (n_chist, n_gauss, n_el, 2)
      real(dp), allocatable :: gp(:, :, :)               ! (n_gp, n_gauss, n_el): eps, rho, N, M (element's igp_*), trial
      real(dp), allocatable :: gpn(:, :, :)              ! the same, converged
      real(dp), allocatable :: indicator(:, :)           ! localization indicator, converged
      real(dp) :: shift = 0.0_dp                         ! converged lower-tool rise H
      real(dp) :: tool_force(2, 2) = 0.0_dp              ! (x, y) force of tool 1, 2 on the sheet, trial
      integer :: n_contact = 0                           ! stations in contact, trial
   end type state_type

contains

   !> MODEL_INIT: mesh, quadrature and material of a tool-free sheet.
   !>  m        [out] the model
   !>  n_el     [in]  number of elements (of the uniform mesh with zone)
   !>  length   [in]  2L, mm
   !>  beta     [in]  mesh grading exponent (4.2), not used with zone
   !>  h        [in]  thickness, mm
   !>  npt      [in]  Simpson stations through the thickness
   !>  mat      [in]  the material (mat%youngs = E)
   !>  zone     [in]  optional: a refined zone [s0, s1] (mm) with elements of
   !>                 zone(3) mm (mesh's zone_counts); m%n_el is then the count
   subroutine model_init(m, n_el, length, beta, h, npt, mat, zone)
      type(model_type), intent(out) :: m
      integer, intent(in) :: n_el, npt
      real(dp), intent(in) :: length, beta, h
      class(material_law_type), intent(in) :: mat
      real(dp), intent(in), optional :: zone(3)
      m%n_el = n_el
      m%n_nodes = m%n_el + 1
      m%n_dof = dofs_per_node*m%n_nodes
      m%npt = npt
      m%thickness = h
      m%youngs = mat%youngs
      allocate (m%x(m%n_nodes), m%z(npt), m%wz(npt))
      call graded_nodes(n_el, 0.5_dp*length, beta, m%x)
      if (present(zone)) call model_rezone(m, zone)
      call simpson_rule(npt, h, m%z, m%wz)
      allocate (m%material, source=mat)
      m%n_hist = hist_size(mat)
      m%max_load_strain = max_load_strain(mat, m%max_load_stress)
   end subroutine model_init

   !> MODEL_REZONE: the model's mesh replaced by a mesh with a refined zone
   !> [s0, s1] of elements of about zone(3) (mesh's zone_counts and
   !> zone_nodes: outside the zone the element length of the uniform mesh
   !> of m%n_el elements on the model's [-L, L]).  Only the mesh changes:
   !> the material, tools, contact and schedule are the model's.  A deck's
   !> own zone (model_init) and the zone &sheet refine_neck places around
   !> the first pass's neck (docs/theory.md §7.5) are made so, before any
   !> state exists on the mesh.
   !>  m     [in,out] the model on a mesh without a zone (its n_el elements
   !>                 of the deck); on return on the zoned mesh
   !>  zone  [in]     [s0, s1, element length in the zone], mm
   subroutine model_rezone(m, zone)
      type(model_type), intent(inout) :: m
      real(dp), intent(in) :: zone(3)
      integer :: counts(3)
      real(dp) :: half
      half = m%x(m%n_nodes)
      call zone_counts(m%n_el, half, zone(1), zone(2), zone(3), counts)
      m%n_el = sum(counts)
      m%n_nodes = m%n_el + 1
      m%n_dof = dofs_per_node*m%n_nodes
      deallocate (m%x)
      allocate (m%x(m%n_nodes))
      call zone_nodes(counts, half, zone(1), zone(2), m%x)
   end subroutine model_rezone

   !> STATE_INIT: undeformed, stress-free state.
   !>  m       [in]  the model
   !>  s       [out] the state
   !>  errmsg  [out] optional: '' or, when an allocation failed, the message
   !>                naming the arrays and their size (s is then left
   !>                empty); without it a failed allocation stops the
   !>                program
   subroutine state_init(m, s, errmsg)
      type(model_type), intent(in) :: m
      type(state_type), intent(out) :: s
      character(len=:), allocatable, intent(out), optional :: errmsg
      integer :: e, ig, stat
      real(dp) :: per_el
      if (present(errmsg)) then
         errmsg = ''
         ! real64 words of the state per element: the histories (converged
         ! and trial), the contact histories, the Gauss-point results
         per_el = real(n_gauss, dp)*(2.0_dp*real(m%npt*m%n_hist, dp) + 4.0_dp*real(n_chist, dp) + &
                                     2.0_dp*real(n_gp, dp) + 1.0_dp)
         allocate (s%u(m%n_dof), s%u1(m%n_dof), s%hn(m%npt, m%n_hist, n_gauss, m%n_el), &
                   s%h1(m%npt, m%n_hist, n_gauss, m%n_el), s%cn(n_chist, n_gauss, m%n_el, 2), &
                   s%c1(n_chist, n_gauss, m%n_el, 2), s%gp(n_gp, n_gauss, m%n_el), &
                   s%gpn(n_gp, n_gauss, m%n_el), s%indicator(n_gauss, m%n_el), stat=stat)
         if (stat /= 0) then
            errmsg = alloc_message('the state of '//itoa(m%n_el)//' elements (material and contact '// &
                                   'histories hn, h1, cn, c1, station results)', &
                                   8.0_dp*(per_el*real(m%n_el, dp) + 2.0_dp*real(m%n_dof, dp)))
            call release(s)
            return
         end if
      else
         allocate (s%u(m%n_dof), s%u1(m%n_dof))
         allocate (s%hn(m%npt, m%n_hist, n_gauss, m%n_el))
         allocate (s%cn(n_chist, n_gauss, m%n_el, 2))
         allocate (s%gp(n_gp, n_gauss, m%n_el), s%gpn(n_gp, n_gauss, m%n_el), s%indicator(n_gauss, m%n_el))
      end if
      s%u = 0.0_dp
      s%u1 = 0.0_dp
      do e = 1, m%n_el
         do ig = 1, n_gauss
            call section_init(m%z, s%hn(:, :, ig, e))
         end do
      end do
      s%h1 = s%hn
      s%cn = 0.0_dp
      do e = 1, m%n_el
         do ig = 1, n_gauss
            ! the flat sheet at y = 0 (relative to both tools at H = 0)
            s%cn(ich_position, ig, e, :) = gauss_position(m, e, ig)
         end do
      end do
      s%c1 = s%cn
      s%gp = 0.0_dp
      s%gpn = s%gp
      s%indicator = 1.0_dp
   end subroutine state_init

   !> RELEASE: deallocate every array of a state (an empty state).
   !>  s  [in,out] the state
   subroutine release(s)
      type(state_type), intent(inout) :: s
      if (allocated(s%u)) deallocate (s%u)
      if (allocated(s%u1)) deallocate (s%u1)
      if (allocated(s%hn)) deallocate (s%hn)
      if (allocated(s%h1)) deallocate (s%h1)
      if (allocated(s%cn)) deallocate (s%cn)
      if (allocated(s%c1)) deallocate (s%c1)
      if (allocated(s%gp)) deallocate (s%gp)
      if (allocated(s%gpn)) deallocate (s%gpn)
      if (allocated(s%indicator)) deallocate (s%indicator)
   end subroutine release

   !> LOAD_INIT: nothing fixed, no loads.
   subroutine load_init(m, ld)
      type(model_type), intent(in) :: m
      type(load_type), intent(out) :: ld
      allocate (ld%fixed(m%n_dof), ld%u_fixed(m%n_dof), ld%f_ext(m%n_dof))
      ld%fixed = .false.
      ld%u_fixed = 0.0_dp
      ld%f_ext = 0.0_dp
   end subroutine load_init

   !> GAUSS_POSITION: reference abscissa of Gauss point ig of element e.
   pure function gauss_position(m, e, ig) result(xg)
      type(model_type), intent(in) :: m
      integer, intent(in) :: e, ig
      real(dp) :: xg
      xg = m%x(e) + gauss_xi(ig)*(m%x(e + 1) - m%x(e))
   end function gauss_position
end module model
