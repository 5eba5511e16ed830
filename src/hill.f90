!> hill -- Hill's 1948 quadratic yield function on the three normal
!> components (axial 1, thickness 2, width 3) of a plane-strain section:
!> its matrix P from r0 and r90, P's eigen-pairs, and sbar^2 = x^T P x
!> for a block (docs/theory.md §13.5).
module hill
   use kinds, only: dp
   implicit none
   private
   public :: hill_matrix, eigen_deviatoric, hill_square

contains

   !> HILL_MATRIX: P of sbar^2 = tau^T P tau on (axial, thickness, width)
   !> (module header), the uniaxial yield stress along the drawing direction
   !> 1 (tau^T P tau = tau11^2 for uniaxial tau11).
   !>  r0, r90 [in] Lankford coefficients, > 0
   !>  rolling [in] .true.: drawing along the rolling direction
   pure function hill_matrix(r0, r90, rolling) result(p)
      real(dp), intent(in) :: r0, r90
      logical, intent(in) :: rolling
      real(dp) :: p(3, 3)
      real(dp) :: f, g, h, scale
      g = 1.0_dp/(1.0_dp + r0)
      h = r0/(1.0_dp + r0)
      f = h/r90
      if (rolling) then
         ! x = axial (1), y = width (3), z = thickness (2)
         scale = 1.0_dp/(g + h)
         p(1, :) = [g + h, -g, -h]
         p(2, :) = [-g, f + g, -f]
         p(3, :) = [-h, -f, f + h]
      else
         ! x = width (3), y = axial (1), z = thickness (2)
         scale = 1.0_dp/(f + h)
         p(1, :) = [f + h, -f, -h]
         p(2, :) = [-f, f + g, -g]
         p(3, :) = [-h, -g, g + h]
      end if
      p = scale*p
   end function hill_matrix

   !> EIGEN_DEVIATORIC: eigenvalues and orthonormal eigenvectors of a
   !> symmetric P whose rows sum to 0: (1,1,1)/sqrt(3) with eigenvalue 0 (the
   !> third pair), the other two from P restricted to the deviatoric plane.
   pure subroutine eigen_deviatoric(p, val, vec)
      real(dp), intent(in) :: p(3, 3)
      real(dp), intent(out) :: val(3), vec(3, 3)
      real(dp) :: ea(3), eb(3), paa, pab, pbb, tr, dt, phi, ca, cb
      ea = [1.0_dp, -1.0_dp, 0.0_dp]/sqrt(2.0_dp)
      eb = [1.0_dp, 1.0_dp, -2.0_dp]/sqrt(6.0_dp)
      paa = dot_product(ea, matmul(p, ea))
      pab = dot_product(ea, matmul(p, eb))
      pbb = dot_product(eb, matmul(p, eb))
      tr = 0.5_dp*(paa + pbb)
      dt = sqrt(0.25_dp*(paa - pbb)**2 + pab**2)
      val(1) = tr + dt
      val(2) = tr - dt
      val(3) = 0.0_dp
      ! rotation angle of the eigenvectors in the (ea, eb) plane
      phi = 0.5_dp*atan2(2.0_dp*pab, paa - pbb)
      ca = cos(phi)
      cb = sin(phi)
      vec(:, 1) = ca*ea + cb*eb
      vec(:, 2) = -cb*ea + ca*eb
      vec(:, 3) = [1.0_dp, 1.0_dp, 1.0_dp]/sqrt(3.0_dp)
   end subroutine eigen_deviatoric

   !> HILL_SQUARE: Hill's sbar^2 = x^T P x of n stress vectors.
   !>  p   [in]  (3, 3) Hill's matrix
   !>  n   [in]  number of vectors
   !>  x   [in]  (n, 3) the vectors (axial, thickness, width)
   !>  q2  [out] (n) sbar^2
   pure subroutine hill_square(p, n, x, q2)
      real(dp), intent(in) :: p(3, 3)
      integer, intent(in) :: n
      real(dp), intent(in) :: x(n, 3)
      real(dp), intent(out) :: q2(n)
      integer :: k
      do k = 1, n
         q2(k) = p(1, 1)*x(k, 1)**2 + p(2, 2)*x(k, 2)**2 + p(3, 3)*x(k, 3)**2 &
                 + 2.0_dp*(p(1, 2)*x(k, 1)*x(k, 2) + p(1, 3)*x(k, 1)*x(k, 3) + p(2, 3)*x(k, 2)*x(k, 3))
      end do
   end subroutine hill_square
end module hill
