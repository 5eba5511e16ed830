!> setup -- the deck turned into the model and the controls of a run:
!> the material constants (the UMAT props, with the hardening curve file
!> read), the tools (the rectangular builder or the profile files), the
!> contact constants, the load schedule and the step controls.  Every
!> problem found here (curve file, profile files, tool geometry) joins the
!> deck's errors in the one error list, so that a run reports them all
!> together; nothing here stops.  After set-up nothing below the main
!> program uses the deck.
module setup
   use kinds, only: dp
   use errors, only: error_list, add_error
   use text, only: lower, file_exists, num, itoa
   use deck, only: deck_type, umat_props_given
   use controls, only: controls_type
   use model, only: model_type, model_init
   use hardening, only: read_curve_file, law_swift, law_voce, law_table, ip_law, ip_table_m
   use material_j2, only: ip_youngs, ip_poisson, ip_r_value, check_props
   use material_law, only: material_law_type
   use neck_gradient, only: neck_gradient_of
   use law_j2, only: j2_law_of_deck
   use law_combined, only: combined_law_of_deck
   use law_umat, only: umat_law_of_deck
   use friction_law, only: friction_law_type
   use friction_coulomb, only: coulomb_friction
   use friction_table, only: table_friction_of_deck
   use friction_power, only: power_friction_of_deck
   use tools, only: tool_type, tool_sample, seg_arc, seg_line, segment_type
   use tool_distance, only: tool_gap
   use bead_builder, only: build_rectangular_bead
   use profile_io, only: read_profile
   use remesh, only: exit_element_over_h, exit_zone_before, exit_zone_after, &
                     neck_element_current_over_h, neck_element_reference_over_h
   use os, only: memory_room
   use section, only: hist_size
   use contact, only: n_chist
   use element, only: n_gp
   use hermite, only: n_gauss
   use mesh, only: dofs_per_node, half_band
   implicit none
   private
   public :: setup_run, material_constants, material_of_deck, smallest_radius, gradient_coefficient, &
             reference_faces_gradient_factor

   !> The strain-gradient coefficient over the plane-strain bar's with the
   !> tools on the faces h/2 from the centreline (contact_faces =
   !> 'reference'; docs/theory.md §12.7): a neck that forms against a tool
   !> face holding the sheet's inner face is half of the neck of a strip 2h
   !> thick, the held face its plane of symmetry, and (12.11) gives that
   !> strip (2h)^3/h^3 = 8 times the coefficient, half of it per sheet.
   !> With the tools on the current faces (the default with the contact
   !> section) the tool holds the sheet's face itself as the section thins,
   !> and the coefficient is the bar's own (factor 1): measured against the
   !> continuum's necks, theory §12.7.
   real(dp), parameter :: reference_faces_gradient_factor = 4.0_dp

contains

   !> GRADIENT_COEFFICIENT: c of the strain-gradient term (docs/theory.md
   !> §12.7, (12.9)) at strain_gradient = 1, with the tools on the current
   !> faces: the plane-strain bar's tau* h^3/(12 lambda*^6), lambda* =
   !> exp(eps*) (reference_faces_gradient_factor times it with the tools on
   !> the reference faces: setup_run).
   !> A plane-strain strip bifurcates into a long neck of current wave
   !> number k at 4 mu* - sigma = -sigma (k h)^2/12 (Hill and Hutchinson's
   !> equations, to second order in k h); a bar with the energy
   !> U(lambda) + c lambda'^2/2 per reference length does so at the same
   !> state when c = sigma h0^3/(12 lambda^6).  This is c at the maximum
   !> load; past it the element takes the station's own stretch for lambda*
   !> (module neck_gradient).  A material that reaches no maximum load
   !> by a log strain of 3 (eps* = huge) takes eps* = 3.
   !>  tau_star  [in]  the axial Kirchhoff stress at the maximum load, MPa
   !>  eps_star  [in]  the plane-strain maximum-load log strain
   !>  h         [in]  the sheet's thickness, mm
   pure function gradient_coefficient(tau_star, eps_star, h) result(c)
      real(dp), intent(in) :: tau_star, eps_star, h
      real(dp) :: c
      c = tau_star*h**3/12.0_dp*exp(-6.0_dp*min(eps_star, 3.0_dp))
   end function gradient_coefficient

   !> SETUP_RUN: model and controls of a deck.
   !>  d     [in]     the deck as read and checked by read_deck
   !>  m     [out]    the model: mesh, material, tools, contact, schedule;
   !>                 complete only when no error was added
   !>  ctl   [out]    the step and output controls
   !>  errs  [in,out] errors in the files the deck names and in the tool
   !>                 geometry are appended.  With errors already in the
   !>                 list (a bad deck) the files are still read and checked
   !>                 where they exist, but nothing is built from values
   !>                 that may be out of range.
   subroutine setup_run(d, m, ctl, errs)
      type(deck_type), intent(in) :: d
      type(model_type), intent(out) :: m
      type(controls_type), intent(out) :: ctl
      type(error_list), intent(inout) :: errs

      class(material_law_type), allocatable :: mat
      class(friction_law_type), allocatable :: fric
      type(tool_type) :: upper, lower_tool
      logical :: deck_ok, current_neck
      real(dp) :: h
      integer :: n_split

      deck_ok = errs%count == 0
      call material_of_deck(d, deck_ok, mat, errs)
      ! the friction law's file and variables are checked with the rest
      if (d%bead /= 'none') call friction_of_deck(d, fric, errs)
      call tools_of_deck(d, deck_ok, upper, lower_tool, errs)
      if (deck_ok .and. errs%count == 0 .and. d%bead /= 'none') then
         call check_clearance(d, upper, lower_tool, errs)
         call check_sheet_reach(d, upper, lower_tool, errs)
      end if
      call controls_of_deck(d, ctl)
      if (errs%count > 0) return

      h = d%thickness
      ! (with refine_neck the zone comes from a first pass: module passes
      ! re-meshes the model with it, model's model_rezone)
      if (d%refine_element > 0.0_dp .and. .not. d%refine_neck) then
         call model_init(m, d%n_elements, d%length, d%mesh_beta, h, d%thickness_points, mat, &
                         zone=h*[d%refine_from, d%refine_to, d%refine_element])
      else
         call model_init(m, d%n_elements, d%length, d%mesh_beta, h, d%thickness_points, mat)
      end if
      m%has_tools = d%bead /= 'none'
      if (m%has_tools) then
         m%tool(1) = upper
         m%tool(2) = lower_tool
         call check_element_length(d, m%x, upper, lower_tool, errs)
      end if
      ! contact (2.18)-(2.23): the penalty is given as k h / E, the lengths
      ! in units of h
      m%penalty = d%penalty*d%youngs_modulus/h
      if (allocated(fric)) call move_alloc(fric, m%friction)
      m%contact_smoothing = d%contact_smoothing*h
      m%current_faces = d%contact_faces == 'current'
      m%left_edge_free = d%left_edge == 'free'
      m%contact_section = d%normal_stress == 'contact'
      ! the strain-gradient term (docs/theory.md §12.7): the bar's own
      ! coefficient with the tools on the current faces, the half-neck's
      ! with the tools on the reference faces
      m%gradient = d%strain_gradient*gradient_coefficient(m%max_load_stress, m%max_load_strain, h)
      if (.not. m%current_faces) m%gradient = reference_faces_gradient_factor*m%gradient
      if (m%gradient > 0.0_dp) m%gradient_curve = neck_gradient_of(m%material, m%max_load_strain)
      m%back_tension = d%back_tension
      m%lock_depth = d%lock_depth
      m%pull_distance = d%pull_distance
      ! the neck resolved on the default path (docs/theory.md §7.6): a pull
      ! with the contact section and the load-maximum criterion, on a mesh
      ! without a zone of its own
      ! the elements on which the tearing point converges at the neck: the
      ! current faces' length was measured with the contact section and its
      ! strain-gradient term, the reference faces' rule holds otherwise;
      ! the refinement splits into the former, or into 0.08h below the latter
      current_neck = m%current_faces .and. m%contact_section .and. m%gradient > 0.0_dp
      m%neck_element = merge(neck_element_current_over_h, neck_element_reference_over_h, current_neck)*h
      if (d%refine_exit .and. m%has_tools .and. m%contact_section &
          .and. d%tearing_criterion == 'load_maximum' .and. d%pull_distance > 0.0_dp &
          .and. d%lock_depth > 0.0_dp .and. .not. d%refine_neck .and. .not. (d%refine_element > 0.0_dp)) &
         m%exit_element = merge(m%neck_element, exit_element_over_h*h, current_neck)
      ! the memory of the largest mesh the run can have: with refine_exit
      ! the elements split over the window and the material drawn through it
      n_split = 0
      if (m%exit_element > 0.0_dp) n_split = ceiling(min(d%length, (exit_zone_before + exit_zone_after)*h + &
                                                         d%pull_distance)/m%exit_element)
      call check_memory(d, m%n_el + n_split, d%thickness_points, m%n_hist, errs)
   end subroutine setup_run

   !> MATERIAL_OF_DECK: the material law a deck names (&material model),
   !> built by its module from the deck, which checks the law's own
   !> variables.  This is where a law is registered: one line per law.
   !>  d        [in]     the deck
   !>  deck_ok  [in]     .false. when the deck has errors (the constants are
   !>                    then not checked again)
   !>  mat      [out]    the law
   !>  errs     [in,out] problems are appended
   subroutine material_of_deck(d, deck_ok, mat, errs)
      type(deck_type), intent(in) :: d
      logical, intent(in) :: deck_ok
      class(material_law_type), allocatable, intent(out) :: mat
      type(error_list), intent(inout) :: errs
      real(dp), allocatable :: props(:)
      character(len=:), allocatable :: msg
      if (d%model /= 'umat') then
         call material_constants(d, props, errs)
         ! the built-in laws' elastic and isotropic constants, checked once
         ! where the deck and the curve file are good
         if (deck_ok .and. errs%count == 0) then
            msg = check_props(props, size(props))
            if (len_trim(msg) > 0) call add_error(errs, "deck '"//trim(d%deck_file)// &
                                                  "', group &material: "//trim(msg))
         end if
      end if
      select case (trim(d%model))
      case ('combined')
         allocate (mat, source=combined_law_of_deck(d, props, errs))
      case ('umat')
         allocate (mat, source=umat_law_of_deck(d, errs))
      case default
         ! 'j2', and an unknown name (the deck's error already)
         allocate (mat, source=j2_law_of_deck(d, props, errs))
      end select
   end subroutine material_of_deck

   !> FRICTION_OF_DECK: the friction law a deck names (&tools friction_law),
   !> built by its module, which checks the law's own variables.  This is
   !> where a friction law is registered: one line per law.
   !>  d     [in]     the deck
   !>  fric  [out]    the law
   !>  errs  [in,out] problems are appended
   subroutine friction_of_deck(d, fric, errs)
      type(deck_type), intent(in) :: d
      class(friction_law_type), allocatable, intent(out) :: fric
      type(error_list), intent(inout) :: errs
      select case (trim(d%friction_law))
      case ('table')
         allocate (fric, source=table_friction_of_deck(d, errs))
      case ('power')
         allocate (fric, source=power_friction_of_deck(d, errs))
      case default
         ! 'coulomb', and an unknown name (the deck's error already)
         allocate (fric, source=coulomb_friction(d%friction, d%friction_eps*d%thickness))
      end select
   end subroutine friction_of_deck

   !> MATERIAL_CONSTANTS: the UMAT props vector of a deck, the tabulated
   !> curve read from its file for hardening = 'table'.
   !>  d      [in]     a deck (choices lower case)
   !>  props  [out]    props(1) = E, props(2) = nu, props(3) = R,
   !>                  props(4) = law id (law_swift, law_voce, law_table;
   !>                  0 for an unknown law, which the deck's checks report);
   !>                  swift: props(5:7) = K, eps0, n;
   !>                  voce:  props(5:7) = sigma0, Q, b;
   !>                  table: props(5) = m, props(6:5+2m) = ep_1, sigma_1, ...,
   !>                         ep_m, sigma_m (m = 0 when the file is unusable).
   !>  errs   [in,out] the curve file's errors are appended (naming the
   !>                  deck, group and variable); a missing file is the
   !>                  deck's error, not repeated here.
   subroutine material_constants(d, props, errs)
      type(deck_type), intent(in) :: d
      real(dp), allocatable, intent(out) :: props(:)
      type(error_list), intent(inout) :: errs

      real(dp), allocatable :: ep(:), sigma(:)
      character(len=1024) :: emsg
      integer :: i, npt

      select case (trim(lower(adjustl(d%hardening))))
      case ('swift')
         props = [d%youngs_modulus, d%poissons_ratio, d%r_value, real(law_swift, dp), &
                  d%swift_k, d%swift_eps0, d%swift_n]
         ! (the order is material_j2's ip_youngs, ip_poisson, ip_r_value and
         ! hardening's ip_law, then the law's constants)
      case ('voce')
         props = [d%youngs_modulus, d%poissons_ratio, d%r_value, real(law_voce, dp), &
                  d%voce_sigma0, d%voce_q, d%voce_b]
      case ('table')
         npt = 0
         if (readable(d%curve_file)) then
            emsg = ''
            call read_curve_file(trim(d%curve_file), ep, sigma, emsg)
            if (len_trim(emsg) > 0) then
               call add_error(errs, "deck '"//trim(d%deck_file)//"', group &material, "// &
                              'variable curve_file: '//trim(emsg))
            else
               npt = size(ep)
            end if
         end if
         allocate (props(ip_table_m + 2*npt))
         props(ip_youngs) = d%youngs_modulus
         props(ip_poisson) = d%poissons_ratio
         props(ip_r_value) = d%r_value
         props(ip_law) = real(law_table, dp)
         props(ip_table_m) = real(npt, dp)
         do i = 1, npt
            props(ip_table_m + 2*i - 1) = ep(i)
            props(ip_table_m + 2*i) = sigma(i)
         end do
      case default
         props = [d%youngs_modulus, d%poissons_ratio, d%r_value, 0.0_dp, &
                  0.0_dp, 0.0_dp, 0.0_dp]
      end select
   end subroutine material_constants

   !> TOOLS_OF_DECK: the two tools: the rectangular bead built from its
   !> dimensions, or the profile files read.
   !>  d        [in]     the deck
   !>  deck_ok  [in]     .false. when the deck has errors: the builder is
   !>                    then not called (its dimensions may be out of range)
   !>  upper    [out]    the upper (female, fixed) tool
   !>  lower    [out]    the lower (male) tool
   !>  errs     [in,out] geometry and profile-file errors are appended
   subroutine tools_of_deck(d, deck_ok, upper, lower, errs)
      type(deck_type), intent(in) :: d
      logical, intent(in) :: deck_ok
      type(tool_type), intent(out) :: upper, lower
      type(error_list), intent(inout) :: errs

      character(len=1024) :: errmsg
      character(len=:), allocatable :: ctx
      real(dp) :: margin

      ctx = "deck '"//trim(d%deck_file)//"', group &tools: "
      errmsg = ''
      select case (d%bead)
      case ('rectangular')
         if (.not. deck_ok) return
         ! the binder faces reach past the sheet's ends by 10 h, room for it
         ! to slide
         margin = 0.5_dp*d%length + 10.0_dp*d%thickness
         call build_rectangular_bead(d%r1, d%r2, d%b1, d%b2, d%h1, d%h2, -margin, margin, &
                                     upper, lower, errmsg)
         if (len_trim(errmsg) > 0) call add_error(errs, ctx//trim(errmsg))
      case ('profile')
         if (readable(d%upper_profile)) then
            call read_profile(trim(d%upper_profile), upper, errmsg)
            if (len_trim(errmsg) == 0 .and. upper%side /= 1) errmsg = &
               trim(d%upper_profile)//' is a lower tool (side lower)'
            if (len_trim(errmsg) > 0) call add_error(errs, ctx//'variable upper_profile: '//trim(errmsg))
         end if
         errmsg = ''
         if (readable(d%lower_profile)) then
            call read_profile(trim(d%lower_profile), lower, errmsg)
            if (len_trim(errmsg) == 0 .and. lower%side /= -1) errmsg = &
               trim(d%lower_profile)//' is an upper tool (side upper)'
            if (len_trim(errmsg) > 0) call add_error(errs, ctx//'variable lower_profile: '//trim(errmsg))
         end if
      end select
   end subroutine tools_of_deck

   !> CHECK_SHEET_REACH: a sheet whose ends do not lie on the binder faces
   !> is refused: an end inside the bead (a clamped edge in mid-air in the
   !> groove, a sheet that never reaches the binder) is no drawbead.  Each
   !> tool's binder faces are the straight level pieces at its ends (a
   !> tool whose end piece is not level has none there, and is not
   !> checked at that end); each end of the sheet, at +-length/2, must lie
   !> on them at least one thickness from where they end.
   !>  d             [in]     the deck (length, thickness)
   !>  upper, lower  [in]     the tools at rise 0
   !>  errs          [in,out] an error naming &sheet length is appended
   subroutine check_sheet_reach(d, upper, lower, errs)
      type(deck_type), intent(in) :: d
      type(tool_type), intent(in) :: upper, lower
      type(error_list), intent(inout) :: errs
      real(dp) :: reach, half
      reach = max(binder_start(upper), binder_start(lower))
      half = 0.5_dp*d%length
      if (half < reach + d%thickness) call add_error(errs, "deck '"//trim(d%deck_file)// &
         "', group &sheet, variable length: the sheet's ends must lie on the binder faces, at least h"// &
         ' past the bead (its tools leave the binder faces at |x| = '//num(reach)//' mm): length must be >= '// &
         num(2.0_dp*(reach + d%thickness))//' (got '//num(d%length)//')')
   contains
      !> the largest |x| where the tool leaves its binder faces (0: no level end piece)
      pure function binder_start(tool) result(x)
         type(tool_type), intent(in) :: tool
         real(dp) :: x, y0, tol
         integer :: i
         x = 0.0_dp
         tol = 1.0e-9_dp*max(tool%size, 1.0_dp)
         ! from the left end: level straight pieces at the end's height
         y0 = tool%seg(1)%p1(2)
         i = 1
         do while (i <= tool%nseg)
            if (.not. level_at(tool%seg(i), y0, tol)) exit
            i = i + 1
         end do
         if (i > 1 .and. i <= tool%nseg) x = max(x, -tool%seg(i)%p1(1))
         ! from the right end
         y0 = tool%seg(tool%nseg)%p2(2)
         i = tool%nseg
         do while (i >= 1)
            if (.not. level_at(tool%seg(i), y0, tol)) exit
            i = i - 1
         end do
         if (i < tool%nseg .and. i >= 1) x = max(x, tool%seg(i)%p2(1))
      end function binder_start
      pure logical function level_at(sg, y0, tol)
         type(segment_type), intent(in) :: sg
         real(dp), intent(in) :: y0, tol
         level_at = sg%kind == seg_line .and. abs(sg%p1(2) - y0) <= tol .and. abs(sg%p2(2) - y0) <= tol
      end function level_at
   end subroutine check_sheet_reach

   !> CHECK_CLEARANCE: tools that cannot hold the sheet at the lock depth
   !> are refused.  The tools are centreline surfaces (the physical surfaces
   !> offset by h/2 toward the sheet, docs/theory.md §5), so a physical gap
   !> of at least the sheet's thickness everywhere is a centreline gap of at
   !> least 0: no point of either surface may lie inside the other tool
   !> (tool_gap's d > 0) with the lower tool raised by lock_depth.  Each
   !> surface is sampled at 4000 points along its length; 1e-6 h of overlap
   !> is allowed for round-off (the binder faces meet exactly at full lock).
   !>  d             [in]     the deck (dimensions and lock depth, for the message)
   !>  upper, lower  [in]     the tools at rise 0
   !>  errs          [in,out] one error when they cross
   subroutine check_clearance(d, upper, lower, errs)
      type(deck_type), intent(in) :: d
      type(tool_type), intent(in) :: upper, lower
      type(error_list), intent(inout) :: errs
      integer, parameter :: n = 4000
      real(dp) :: xy(2, n), depth, worst, at(2), gap, nrm(2), dn, tng(2), h
      integer :: k, seg
      character(len=:), allocatable :: what
      h = d%thickness
      depth = d%lock_depth
      worst = 0.0_dp
      at = 0.0_dp
      call tool_sample(lower, n, xy)
      do k = 1, n
         call tool_gap(upper, xy(1, k), xy(2, k) + depth, gap, nrm, dn, tng, seg)
         if (gap > worst) then
            worst = gap
            at = [xy(1, k), xy(2, k) + depth]
         end if
      end do
      call tool_sample(upper, n, xy)
      do k = 1, n
         call tool_gap(lower, xy(1, k), xy(2, k) - depth, gap, nrm, dn, tng, seg)
         if (gap > worst) then
            worst = gap
            at = xy(:, k)
         end if
      end do
      if (worst <= 1.0e-6_dp*h) return
      if (d%bead == 'rectangular') then
         what = 'the male tool does not fit its groove (r1 = '//num(d%r1)//', r2 = '//num(d%r2)// &
                ', b1 = '//num(d%b1)//', b2 = '//num(d%b2)//', h1 = '//num(d%h1)//', h2 = '// &
                num(d%h2)//' mm)'
      else
         what = 'the profiles '''//trim(d%upper_profile)//''' and '''//trim(d%lower_profile)// &
                ''' cross'
      end if
      call add_error(errs, "deck '"//trim(d%deck_file)//"', group &tools: "//what// &
                     ' at lock_depth = '//num(depth)//' mm: the tools overlap by '//num(worst)// &
                     ' mm = '//num(worst/h)//' h near (x, y) = ('//num(at(1))//', '//num(at(2))// &
                     ') mm, where the physical gap must be at least the sheet thickness')
   end subroutine check_clearance

   !> CHECK_ELEMENT_LENGTH: a mesh whose elements are longer than the
   !> smallest radius of the tools is refused.  An element is one cubic in
   !> each displacement: bent over a radius shorter than itself it cannot
   !> follow the tool, its nodes cut the corner, and the run still ends
   !> with a confident answer (issue 28: 2 elements of 25 h on bead A's
   !> radii of 4.66 h gave status = localized at delta_cr = 1.43 h against
   !> 2.09 h on 80 elements, with only a penetration warning).  The limit
   !> is the element's length itself (not a fraction of it): the
   !> refine_neck regression deck runs its first pass on elements of 3 h
   !> over radii of 4.66 h, and its neck is where the fine mesh finds it.
   !> The longest element of the whole mesh counts (with mesh_beta > 1
   !> those are at the sheet's ends, which the pull brings toward the
   !> bead).  Tools without arcs (sharp corners only) have no radius to
   !> compare.
   !>  d             [in]     the deck (for the message)
   !>  x             [in]     the mesh's node positions, ascending, mm
   !>  upper, lower  [in]     the tools at rest
   !>  errs          [in,out] one error when an element is too long
   subroutine check_element_length(d, x, upper, lower, errs)
      type(deck_type), intent(in) :: d
      real(dp), intent(in) :: x(:)
      type(tool_type), intent(in) :: upper, lower
      type(error_list), intent(inout) :: errs
      real(dp) :: longest, radius, h
      character(len=:), allocatable :: which
      integer :: n_need
      if (size(x) < 2) return
      h = d%thickness
      longest = maxval(x(2:) - x(:size(x) - 1))
      if (d%bead == 'rectangular') then
         radius = min(d%r1, d%r2)
         which = merge('r1', 'r2', d%r1 <= d%r2)
      else
         radius = min(smallest_radius(upper), smallest_radius(lower))
         if (radius >= huge(1.0_dp)) return
         which = 'the smallest arc of profile '''//trim(merge(d%upper_profile, d%lower_profile, &
                 smallest_radius(upper) <= smallest_radius(lower)))//''''
      end if
      ! 1e-9 relative: an element exactly as long as the radius is allowed
      if (longest <= radius*(1.0_dp + 1.0e-9_dp)) return
      ! graded_nodes' longest element, L (1 - (1 - 2/n)^beta), is at most
      ! 2 L beta / n: this many elements are enough
      n_need = ceiling(d%mesh_beta*d%length/radius)
      call add_error(errs, "deck '"//trim(d%deck_file)//"', group &sheet, variable n_elements: "// &
                     'elements of up to '//num(longest/h)//' h ('//num(longest)//' mm) are longer '// &
                     'than the smallest tool radius, '//num(radius/h)//' h ('//num(radius)//' mm, '// &
                     which//'): the sheet cannot follow the tools; give n_elements >= '// &
                     itoa(n_need)//' for elements no longer than the radius')
   end subroutine check_element_length

   !> RUN_MEMORY: an estimate of the memory a run takes, bytes: the arrays
   !> that grow with the mesh (model's state_init: the material history
   !> hn, h1 and the contact history cn, c1, the station results, the
   !> displacements; solver's per-element work arrays of an assembly; the
   !> band matrix, LDA 3 half_band + 1; the increment loop's vectors; the
   !> text of a strain file, 1504 bytes per element), plus 8 MiB for the
   !> program's fixed part (tools, records, I/O buffers).  On 20000
   !> elements (21 stations) it says 473 MiB beyond what the program maps
   !> at set-up; the run went through under ulimit -v 490000 (462 MiB
   !> beyond) and failed in an allocation under 470000 (453 MiB).
   !>  n_el  [in] elements of the run's mesh
   !>  npt   [in] Simpson stations through the thickness
   !>  n_hist [in] history columns of a section (the law's: section's hist_size)
   pure function run_memory(n_el, npt, n_hist) result(bytes)
      integer, intent(in) :: n_el, npt, n_hist
      real(dp) :: bytes, per_element, per_dof, n_dof
      n_dof = real(dofs_per_node, dp)*real(n_el + 1, dp)
      ! real64 words per element: state, then one assembly's work arrays
      per_element = real(n_gauss, dp)*(2.0_dp*real(npt*n_hist, dp) + 4.0_dp*real(n_chist, dp) + &
                                       2.0_dp*real(n_gp, dp) + 2.0_dp) &
                    + 8.0_dp + 64.0_dp + 3.0_dp + 4.0_dp*real(n_gauss, dp) &
                    + real(n_gauss*npt, dp) &         ! the plastic flags (two logical arrays)
                    + 188.0_dp                         ! the text of a strain file's rows
      ! per dof: u, u1, the band matrix, the increment loop's and loads' vectors
      per_dof = 2.0_dp + real(3*half_band + 1, dp) + 0.5_dp + 6.0_dp
      bytes = 8.0_dp*(per_element*real(n_el, dp) + per_dof*n_dof) + 8.0_dp*1024.0_dp**2
   end function run_memory

   !> CHECK_MEMORY: a mesh whose run cannot fit in the memory this process
   !> may have (os's memory_room: the address-space limit, ulimit -v, or
   !> the machine's memory and swap) is refused at set-up, naming
   !> n_elements and the estimate, instead of failing in an allocation
   !> with a run-time error and a backtrace (issue 28, item 6).
   !>  d      [in]     the deck (for the message)
   !>  n_el   [in]     elements of the run's mesh (more than n_elements
   !>                  with a refined zone)
   !>  npt    [in]     Simpson stations through the thickness
   !>  n_hist [in]     history columns of a section
   !>  errs   [in,out] one error when the run cannot fit
   subroutine check_memory(d, n_el, npt, n_hist, errs)
      type(deck_type), intent(in) :: d
      integer, intent(in) :: n_el, npt, n_hist
      type(error_list), intent(inout) :: errs
      real(dp) :: need, room
      character(len=:), allocatable :: what, mesh
      need = run_memory(n_el, npt, n_hist)
      call memory_room(room, what)
      if (need <= room) return
      mesh = itoa(n_el)//' elements'
      if (n_el /= d%n_elements) mesh = mesh//' with the refined zone or the elements refine_exit may split'
      call add_error(errs, "deck '"//trim(d%deck_file)//"', group &sheet, variable n_elements: "// &
                     'n_elements = '//itoa(d%n_elements)//' ('//mesh//', thickness_points = '// &
                     itoa(npt)//') needs about '//mebibytes(need)//' of memory, more than the '// &
                     mebibytes(max(room, 0.0_dp))//' '//what//' leaves the run: give fewer '// &
                     'elements or thickness points, or more memory')
   end subroutine check_memory

   !> MEBIBYTES: a number of bytes as text in MiB ('123.4 MiB').
   !>  bytes  [in] the number
   pure function mebibytes(bytes) result(text)
      real(dp), intent(in) :: bytes
      character(len=:), allocatable :: text
      character(len=32) :: buf
      write (buf, '(f0.1)') bytes/1024.0_dp**2
      text = trim(buf)//' MiB'
   end function mebibytes

   !> SMALLEST_RADIUS: the smallest arc radius of a tool, mm; huge() when
   !> it has no arc.
   !>  tool  [in] the tool
   pure function smallest_radius(tool) result(r)
      type(tool_type), intent(in) :: tool
      real(dp) :: r
      integer :: k
      r = huge(1.0_dp)
      do k = 1, tool%nseg
         if (tool%seg(k)%kind == seg_arc) r = min(r, tool%seg(k)%radius)
      end do
   end function smallest_radius

   !> CONTROLS_OF_DECK: the step and output controls of a deck.
   !>  d    [in]  the deck
   !>  ctl  [out] the controls
   pure subroutine controls_of_deck(d, ctl)
      type(deck_type), intent(in) :: d
      type(controls_type), intent(out) :: ctl

      ctl%title = d%title
      ctl%output_dir = d%output_dir
      ctl%snapshot_every_over_h = d%snapshot_every
      ctl%log_residuals = d%log_residuals
      ctl%initial_increment = d%initial_increment
      ctl%min_increment = d%min_increment
      ctl%max_increment = d%max_increment
      ctl%max_iterations = d%max_iterations
      ctl%tolerance = d%tolerance
      ctl%max_force_change = d%max_force_change
      ctl%squeeze_force_change = d%squeeze_force_change
      ctl%step_tolerance = d%step_tolerance
      ctl%branch_increment = d%branch_increment
      ctl%predictor = d%predictor
      ctl%stop_at_localization = d%stop_at_localization
      ctl%tearing_criterion = d%tearing_criterion
      ctl%tearing_length_over_h = d%tearing_length
      ctl%fold_curvature = d%fold_curvature
      ctl%refine_neck = d%refine_neck
      ctl%refine_element_over_h = d%refine_element
   end subroutine controls_of_deck

   !> READABLE: .true. for a file name given and existing (a missing one is
   !> the deck's error, reported by validate_deck).
   !>  path  [in] file name from the deck
   function readable(path) result(yes)
      character(len=*), intent(in) :: path
      logical :: yes
      yes = .false.
      if (len_trim(path) == 0) return
      yes = file_exists(path)
   end function readable

end module setup
