!> umat_linear_hardening -- an example of a user's material routine for
!> drawbead: von Mises plasticity with linear isotropic hardening,
!>   sigma_y = sigma0 + H ebar_p,
!> written as for an Abaqus plane-strain element.
!>
!> Build it into the program with
!>   make UMAT=input/umat_linear_hardening.f90
!> and name it in the deck with model = 'umat', umat_props = E, nu,
!> sigma0, H, umat_nstatv = 1, umat_eqps_index = 1 (the argument list, and
!> what drawbead passes in each argument, is written in src/law_umat.f90).
!> It gives the same results as the built-in law with a 'table' curve of
!> the two points (0, sigma0), (1, sigma0 + H), which the last segment
!> extrapolates (tests/unit/test_law_umat.pf checks it).
!>
!> Conventions: NDI = 3, NSHR = 1, NTENS = 4, components (11, 22, 33, 12),
!> engineering shear strain; Kirchhoff stress, logarithmic strain, additive
!> elasto-plasticity, backward Euler (radial return).  The program holds
!> the width strain and drives the thickness strain itself; this routine
!> knows nothing of either.
!>
!> Constants:  props(1) = E, props(2) = nu, props(3) = sigma0, props(4) = H.
!> State variables (NSTATV = 1):  statev(1) ebar_p.
!>
!> Stress update.  Trial sigma_tr = sigma + D dstran; with s_tr its
!> deviator and q_tr = sqrt(3/2 s_tr : s_tr), a plastic increment has
!>   dp = (q_tr - sigma0 - H ebar_p,n)/(3 mu + H),
!>   sigma = sigma_tr - 2 mu dp n,  n = (3/2) s_tr / q_tr,
!> and the consistent tangent (Simo & Hughes 1998, box 3.2)
!>   C = K 1 x 1 + 2 mu theta I_dev - 2 mu theta_bar N x N,
!>   N = s_tr/|s_tr|, theta = 1 - 3 mu dp/q_tr,
!>   theta_bar = 1/(1 + H/(3 mu)) - (1 - theta).
subroutine umat(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, &
                stran, dstran, time, dtime, temp, dtemp, predef, dpred, cmname, ndi, &
                nshr, ntens, nstatv, props, nprops, coords, drot, pnewdt, celent, dfgrd0, &
                dfgrd1, noel, npt, layer, kspt, kstep, kinc)
   use kinds, only: dp
   implicit none
   character(len=80), intent(in) :: cmname
   integer, intent(in) :: ndi, nshr, ntens, nstatv, nprops, noel, npt, layer, kspt, kstep, kinc
   real(dp), intent(inout) :: stress(ntens), statev(nstatv), sse, spd, scd, pnewdt
   real(dp), intent(out) :: ddsdde(ntens, ntens), rpl, ddsddt(ntens), drplde(ntens), drpldt
   real(dp), intent(in) :: stran(ntens), dstran(ntens), time(2), dtime, temp, dtemp, predef(1), &
                           dpred(1), props(nprops), coords(3), drot(3, 3), celent, &
                           dfgrd0(3, 3), dfgrd1(3, 3)

   real(dp), parameter :: tol = 1.0e-12_dp
   real(dp) :: e_mod, nu, sigma0, h, mu, k_bulk, lam, trial(4), dev(4), q_tr, ep_n, sy, dep, &
               nrm(4), theta, theta_bar, s_norm
   integer :: i, j

   ! Arguments this law does not need, named once so that the compiler does
   ! not report them as unused.
   associate (u1 => scd, u2 => stran, u3 => time, u4 => dtime, u5 => temp, u6 => dtemp, &
              u7 => predef, u8 => dpred, u9 => cmname, u10 => coords, u11 => drot, &
              u12 => celent, u13 => dfgrd0, u14 => dfgrd1, u15 => noel, u16 => npt, &
              u17 => layer, u18 => kspt, u19 => kstep, u20 => kinc)
   end associate

   rpl = 0.0_dp
   ddsddt = 0.0_dp
   drplde = 0.0_dp
   drpldt = 0.0_dp
   ddsdde = 0.0_dp
   ! wrong sizes: a programming error, no increment can help
   if (ndi /= 3 .or. nshr /= 1 .or. ntens /= 4 .or. nstatv < 1 .or. nprops < 4) then
      pnewdt = 0.0_dp
      return
   end if

   e_mod = props(1)
   nu = props(2)
   sigma0 = props(3)
   h = props(4)
   mu = e_mod/(2.0_dp*(1.0_dp + nu))
   k_bulk = e_mod/(3.0_dp*(1.0_dp - 2.0_dp*nu))
   lam = k_bulk - 2.0_dp*mu/3.0_dp

   ! the elastic stiffness (engineering shear strain)
   do j = 1, 3
      do i = 1, 3
         ddsdde(i, j) = lam
      end do
      ddsdde(j, j) = lam + 2.0_dp*mu
   end do
   ddsdde(4, 4) = mu

   trial = stress + matmul(ddsdde, dstran)
   dev = trial
   dev(1:3) = trial(1:3) - sum(trial(1:3))/3.0_dp
   s_norm = sqrt(dev(1)**2 + dev(2)**2 + dev(3)**2 + 2.0_dp*dev(4)**2)
   q_tr = sqrt(1.5_dp)*s_norm
   ep_n = statev(1)
   sy = sigma0 + h*ep_n

   if (q_tr <= (1.0_dp + tol)*sy) then
      stress = trial
   else
      dep = (q_tr - sy)/(3.0_dp*mu + h)
      nrm = dev/s_norm
      stress = trial - 2.0_dp*mu*dep*sqrt(1.5_dp)*nrm
      statev(1) = ep_n + dep
      theta = 1.0_dp - 3.0_dp*mu*dep/q_tr
      theta_bar = 1.0_dp/(1.0_dp + h/(3.0_dp*mu)) - (1.0_dp - theta)
      ! C = K 1x1 + 2 mu theta I_dev - 2 mu theta_bar N x N (I_dev's shear
      ! entry is 1/2 with the engineering shear strain)
      do j = 1, 4
         do i = 1, 4
            ddsdde(i, j) = -2.0_dp*mu*theta_bar*nrm(i)*nrm(j)
            if (i <= 3 .and. j <= 3) ddsdde(i, j) = ddsdde(i, j) + k_bulk - 2.0_dp*mu*theta/3.0_dp
         end do
      end do
      do j = 1, 3
         ddsdde(j, j) = ddsdde(j, j) + 2.0_dp*mu*theta
      end do
      ddsdde(4, 4) = ddsdde(4, 4) + mu*theta
      ! plastic work: int sigma_y d ebar_p over the increment (exact, linear)
      spd = spd + dep*(sigma0 + h*(ep_n + 0.5_dp*dep))
   end if
   sse = (stress(1)**2 + stress(2)**2 + stress(3)**2 &
          - 2.0_dp*nu*(stress(1)*stress(2) + stress(2)*stress(3) + stress(1)*stress(3)) &
          + 2.0_dp*(1.0_dp + nu)*stress(4)**2)/(2.0_dp*e_mod)
end subroutine umat
