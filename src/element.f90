!> element -- the Hermite shell element: residual and consistent tangent.
!>
!> Element dofs, node by node: (v1, v1', w1, w1', v2, v2', w2, w2').
!> Internal virtual work per unit reference length N d(eps) + M d(rho) (2.8)-(2.10):
!>   r = int (N B_eps + M B_rho) ds
!>   K = int (B^T C B + N d2eps/dq2 + M d2rho/dq2) ds        (docs/theory.md §2)
!> with B = d(eps, rho)/dq and 4-point Gauss quadrature (paper §4).
!>
!> Contact section (docs/theory.md §12): a Gauss station pressed by a tool
!> with the normal force f_n per unit reference length carries the face
!> stress tau22 = -f_n/Lambda_f on that face (per unit current face area,
!> Lambda_f = 1 + eps + zbar_f rho the face's stretch); (N, M) then depend on
!> the face stresses, and the tangent gains
!>   int (B_eps (dN/dtau_f) + B_rho (dM/dtau_f)) (d tau_f/dq)^T ds,
!>   d tau_f/dq = -(d f_n/dq)/Lambda_f + f_n/Lambda_f^2 (B_eps + zbar_f B_rho).
module element
   use kinds, only: dp
   use hermite, only: n_gauss, gauss_xi, gauss_wt, hermite_shape
   use kinematics, only: strain_measures
   use section, only: section_response, ih_zbar
   use material_law, only: material_law_type
   use neck_gradient, only: neck_gradient_type, gradient_factor
   implicit none
   private
   public :: element_internal, element_gradients, outer8, v_dofs, w_dofs
   public :: n_gp, igp_strain, igp_curvature, igp_force, igp_moment, igp_gradient_energy

   integer, parameter :: v_dofs(4) = [1, 2, 5, 6], w_dofs(4) = [3, 4, 7, 8]
   !> what element_internal reports per Gauss point, gp(n_gp, n_gauss): the
   !> axial strain eps, the bending strain rho, the section forces N, M, and
   !> the energy of the strain-gradient term per unit reference length
   integer, parameter :: igp_strain = 1, igp_curvature = 2, igp_force = 3, igp_moment = 4, &
                         igp_gradient_energy = 5, n_gp = 5

contains

   !> ELEMENT_GRADIENTS: g = (1 + v', w', v'', w'') at local coordinate xi and
   !> the matrix G = dg/dq (g is affine in the element dofs q).
   !>  xi  [in]  local coordinate in [0, 1]
   !>  le  [in]  element length
   !>  ul  [in]  element dofs
   !>  g   [out] (a, b, c, d)
   !>  gm  [out] G(4, 8)
   pure subroutine element_gradients(xi, le, ul, g, gm)
      real(dp), intent(in) :: xi, le, ul(8)
      real(dp), intent(out) :: g(4), gm(4, 8)
      real(dp) :: n(4), dn(4), d2n(4)
      integer :: k
      call hermite_shape(xi, le, n, dn, d2n)
      gm = 0.0_dp
      gm(1, v_dofs) = dn
      gm(2, w_dofs) = dn
      gm(3, v_dofs) = d2n
      gm(4, w_dofs) = d2n
      ! g = G ul from the non-zero entries of G alone, summed in the order
      ! of matmul(gm, ul) (the zeros add nothing)
      g = 0.0_dp
      do k = 1, 4
         g(1) = g(1) + dn(k)*ul(v_dofs(k))
         g(2) = g(2) + dn(k)*ul(w_dofs(k))
         g(3) = g(3) + d2n(k)*ul(v_dofs(k))
         g(4) = g(4) + d2n(k)*ul(w_dofs(k))
      end do
      g(1) = g(1) + 1.0_dp
   end subroutine element_gradients

   !> ELEMENT_INTERNAL: internal force vector and tangent of one element.
   !>  le     [in]  reference element length
   !>  ul     [in]  element dofs (trial state)
   !>  wz     [in]  Simpson weights through the thickness
   !>  mat    [in]  the material
   !>  hn     [in]  converged history (npt, n_hist, n_gauss)
   !>  h1     [in,out] trial history (on entry the last trial's: section_response)
   !>  re     [out] internal force vector (8)
   !>  ke     [out] tangent (8, 8)
   !>  gp     [out] per Gauss point: eps, rho, N, M, gradient energy (igp_*)
   !>  pnewdt [in,out] < 1 on return if the increment must be cut
   !>  face_force  [in] (2, n_gauss) normal contact force per unit reference
   !>                   length on the (bottom, top) face of each Gauss
   !>                   station, >= 0; all 0: the paper's section
   !>  dface_force [in] (8, 2, n_gauss) its derivative with respect to ul
   !>  gradient    [in] optional: c of the strain-gradient term
   !>                   (1/2) c (d lambda/ds)^2 per unit reference length,
   !>                   N mm (docs/theory.md §12.7), at the maximum load;
   !>                   absent or 0: none
   !>  gradient_curve [in] optional: past the maximum-load strain the
   !>                   coefficient follows the station's stretch (module
   !>                   neck_gradient); absent: c throughout
   subroutine element_internal(le, ul, wz, mat, hn, h1, re, ke, gp, pnewdt, face_force, &
                               dface_force, gradient, gradient_curve)
      real(dp), intent(in) :: le, ul(8), wz(:)
      class(material_law_type), intent(in) :: mat
      real(dp), contiguous, intent(in) :: hn(:, :, :)
      real(dp), contiguous, intent(inout) :: h1(:, :, :)
      real(dp), intent(out) :: re(8), ke(8, 8), gp(n_gp, n_gauss)
      real(dp), intent(inout) :: pnewdt
      real(dp), intent(in) :: face_force(2, n_gauss), dface_force(8, 2, n_gauss)
      real(dp), intent(in), optional :: gradient
      type(neck_gradient_type), intent(in), optional :: gradient_curve
      ! G = dg/dq has two entries per column: column k holds s1(k) in row
      ! row_1(k) (v' or w') and s2(k) in row row_2(k) (v'' or w''), so
      ! B = d(eps, rho)/dq and G^T H G are formed from those entries alone
      integer, parameter :: row_1(8) = [1, 1, 2, 2, 1, 1, 2, 2], row_2(8) = [3, 3, 4, 4, 3, 3, 4, 4]
      real(dp) :: g(4), gm(4, 8), eps, rho, deps(4), drho(4), d2eps(4, 4), d2rho(4, 4)
      real(dp) :: force, moment, c(2, 2), beps(8), brho(8), hg(4, 4), dv, s1(8), s2(8)
      real(dp) :: ca(8), cb(8), hs(4, 8)
      real(dp) :: face_stress(2), cs(2, 2), lam_f(2), zb_f(2), gs(8, 2)
      real(dp) :: gc, gam, dgam(4), d2gam(4, 4), bgam(8), cf, dcf, d2cf
      logical :: follows
      integer :: ig, i, j, f, npt
      gc = 0.0_dp
      if (present(gradient)) gc = gradient
      follows = present(gradient_curve)
      re = 0.0_dp
      ke = 0.0_dp
      gp = 0.0_dp
      npt = size(wz)
      ! (set in the loop where gc > 0, the only place they are read; given
      ! values here so that the optimizer sees no read before a write)
      gam = 0.0_dp
      bgam = 0.0_dp
      cf = 1.0_dp
      dcf = 0.0_dp
      d2cf = 0.0_dp
      do ig = 1, n_gauss
         call element_gradients(gauss_xi(ig), le, ul, g, gm)
         call strain_measures(g, eps, rho, deps, drho, d2eps, d2rho)
         do f = 1, 2
            zb_f(f) = hn(merge(1, npt, f == 1), ih_zbar, ig)
            lam_f(f) = 1.0_dp + eps + zb_f(f)*rho
            face_stress(f) = -face_force(f, ig)/lam_f(f)
         end do
         call section_response(eps, rho, wz, mat, hn(:, :, ig), h1(:, :, ig), &
                               force, moment, c, pnewdt, face_stress, cs)
         if (pnewdt < 1.0_dp) return
         gp(igp_strain, ig) = eps
         gp(igp_curvature, ig) = rho
         gp(igp_force, ig) = force
         gp(igp_moment, ig) = moment
         dv = gauss_wt(ig)*le
         do j = 1, 8
            s1(j) = gm(row_1(j), j)
            s2(j) = gm(row_2(j), j)
            beps(j) = deps(row_1(j))*s1(j) + deps(row_2(j))*s2(j)
            brho(j) = drho(row_1(j))*s1(j) + drho(row_2(j))*s2(j)
         end do
         re = re + dv*(force*beps + moment*brho)
         hg = dv*(force*d2eps + moment*d2rho)
         if (gc > 0.0_dp) then
            ! the strain-gradient term (1/2) c (d lambda/ds)^2 (docs/theory.md
            ! §12.7), c = gc f(lambda), lambda = 1 + eps (its derivatives are
            ! eps's, beps and d2eps): r = c gam gam' + (1/2) c' gam^2 lambda';
            ! K = c (gam' gam'^T + gam gam'') + c' gam (gam' lambda'^T +
            ! lambda' gam'^T) + (1/2) gam^2 (c'' lambda' lambda'^T + c' lambda''),
            ! whose second-derivative parts gam'' and lambda'' join H (and the
            ! sparse G^T H G below), the rank-one parts added after it
            call stretch_gradient(g, gam, dgam, d2gam)
            do j = 1, 8
               bgam(j) = dgam(row_1(j))*s1(j) + dgam(row_2(j))*s2(j)
            end do
            cf = 1.0_dp
            dcf = 0.0_dp
            d2cf = 0.0_dp
            if (follows) call gradient_factor(gradient_curve, 1.0_dp + eps, cf, dcf, d2cf)
            gp(igp_gradient_energy, ig) = 0.5_dp*gc*cf*gam*gam
            re = re + dv*gc*(cf*gam*bgam + 0.5_dp*dcf*gam*gam*beps)
            hg = hg + dv*gc*(cf*gam*d2gam + 0.5_dp*dcf*gam*gam*d2eps)
         end if
         ! H G, column by column, then G^T (H G) row by row
         do j = 1, 8
            hs(:, j) = hg(:, row_1(j))*s1(j) + hg(:, row_2(j))*s2(j)
         end do
         ca = dv*(c(1, 1)*beps + c(1, 2)*brho)
         cb = dv*(c(2, 1)*beps + c(2, 2)*brho)
         if (any(abs(cs) > 0.0_dp)) then
            ! the coupling to the contact pressure (module header)
            do f = 1, 2
               gs(:, f) = -dface_force(:, f, ig)/lam_f(f) &
                          + face_force(f, ig)/lam_f(f)**2*(beps + zb_f(f)*brho)
            end do
            ca = ca + dv*(cs(1, 1)*gs(:, 1) + cs(1, 2)*gs(:, 2))
            cb = cb + dv*(cs(2, 1)*gs(:, 1) + cs(2, 2)*gs(:, 2))
         end if
         do j = 1, 8
            do i = 1, 8
               ke(i, j) = ke(i, j) + beps(i)*ca(j) + brho(i)*cb(j) &
                          + s1(i)*hs(row_1(i), j) + s2(i)*hs(row_2(i), j)
            end do
         end do
         if (gc > 0.0_dp) then
            ke = ke + dv*gc*cf*outer8(bgam, bgam)
            if (follows) ke = ke + dv*gc*(dcf*gam*(outer8(beps, bgam) + outer8(bgam, beps)) &
                                          + 0.5_dp*gam*gam*d2cf*outer8(beps, beps))
         end if
      end do
   end subroutine element_internal

   !> STRETCH_GRADIENT: gamma = d lambda/ds = (a c + b d)/lambda along the
   !> reference centreline and its first and second derivatives with respect
   !> to g = (a, b, c, d) = (1 + v', w', v'', w'').
   !>  g      [in]  (a, b, c, d)
   !>  gam    [out] gamma
   !>  dgam   [out] d gamma/d g
   !>  d2gam  [out] d2 gamma/d g2
   pure subroutine stretch_gradient(g, gam, dgam, d2gam)
      real(dp), intent(in) :: g(4)
      real(dp), intent(out) :: gam, dgam(4), d2gam(4, 4)
      real(dp) :: a, b, c, d, lam, u, l3, l5
      a = g(1); b = g(2); c = g(3); d = g(4)
      lam = sqrt(a*a + b*b)
      u = a*c + b*d
      l3 = 1.0_dp/lam**3
      l5 = l3/(lam*lam)
      gam = u/lam
      dgam = [c/lam - u*a*l3, d/lam - u*b*l3, a/lam, b/lam]
      d2gam = 0.0_dp
      d2gam(1, 1) = -2.0_dp*c*a*l3 - u*l3 + 3.0_dp*u*a*a*l5
      d2gam(2, 2) = -2.0_dp*d*b*l3 - u*l3 + 3.0_dp*u*b*b*l5
      d2gam(1, 2) = -(c*b + d*a)*l3 + 3.0_dp*u*a*b*l5
      d2gam(2, 1) = d2gam(1, 2)
      d2gam(1, 3) = b*b*l3
      d2gam(3, 1) = d2gam(1, 3)
      d2gam(1, 4) = -a*b*l3
      d2gam(4, 1) = d2gam(1, 4)
      d2gam(2, 3) = -a*b*l3
      d2gam(3, 2) = d2gam(2, 3)
      d2gam(2, 4) = a*a*l3
      d2gam(4, 2) = d2gam(2, 4)
   end subroutine stretch_gradient

   !> OUTER8: the outer product a b^T of two 8-vectors.
   pure function outer8(a, b) result(c)
      real(dp), intent(in) :: a(8), b(8)
      real(dp) :: c(8, 8)
      integer :: j
      do j = 1, 8
         c(:, j) = a*b(j)
      end do
   end function outer8
end module element
