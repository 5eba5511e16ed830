!> umat_linear_hardening -- an example of a user's material routine for
!> drawbead: von Mises plasticity with linear isotropic hardening,
!>   sigma_y = sigma0 + H ebar_p.
!>
!> Build it into the program with
!>   make UMAT=input/umat_linear_hardening.f90
!> (any file with an external `subroutine umat` of this argument list will
!> do; the list, and what drawbead passes in each argument, is written in
!> src/material.f90).  It gives the same results as the built-in law with
!> a 'table' curve of the two points (0, sigma0), (1, sigma0 + H), which
!> the last segment extrapolates (tests/unit/test_material.pf checks it).
!>
!> Conventions (those of the program): NDI = 2, NSHR = 0, NTENS = 2;
!> components (11, 33) = (axial, width); the thickness direction 22 has
!> sigma22 = 0.  Kirchhoff stress, logarithmic strain, additive
!> elasto-plasticity, backward Euler.
!>
!> Constants:  props(1) = E, props(2) = nu, props(3) = sigma0, props(4) = H.
!> State variables (NSTATV = 6; the program reads 1, 2 and 4, so they must
!> mean what they mean for the built-in law):
!>   statev(1) ebar_p, equivalent plastic strain
!>   statev(2) eps22, total thickness log strain
!>   statev(3) sigma33 (a copy, for output)
!>   statev(4) continuum tangent d sigma11 / d eps11 at fixed eps33
!>             (elastic value after an elastic increment)
!>   statev(5) sigma_y(ebar_p),  statev(6) H
!>
!> Stress update.  Hooke's law in plane stress, D = E/(1 - nu^2) [[1, nu],
!> [nu, 1]], gives the trial stress; beyond the yield surface the end stress
!> is sigma = sigma_trial - dp D n, n = P sigma / sbar, P = [[1, -1/2],
!> [-1/2, 1]], sbar^2 = s11^2 + s33^2 - s11 s33.  In s = s11 + s33 and
!> t = s11 - s33 both D and P are diagonal, so with gamma = dp / sbar
!>   s = s_trial / (1 + gamma E/(2 (1 - nu))),
!>   t = t_trial / (1 + gamma 3E/(2 (1 + nu))),   sbar = sqrt(s^2 + 3 t^2)/2,
!> and the one unknown gamma solves f = sbar - sigma0 - H (ebar_p,n + gamma
!> sbar) = 0 (Newton from gamma = 0).
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
   integer, parameter :: max_iter = 100
   real(dp) :: e_mod, nu, sigma0, h, e_ps, d(2, 2), trial(2), ep_n, sy, seq
   real(dp) :: k_s, k_t, s_tr, t_tr, gam, s, t, f, ds, dt, dseq, dep, n(2), a(2, 2), xi(2, 2)
   real(dp) :: xn(2), dn(2), dsig(2)
   integer :: iter, j

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
   if (ndi /= 2 .or. nshr /= 0 .or. ntens /= 2 .or. nstatv < 6 .or. nprops < 4) then
      pnewdt = 0.0_dp
      return
   end if

   e_mod = props(1)
   nu = props(2)
   sigma0 = props(3)
   h = props(4)
   e_ps = e_mod/(1.0_dp - nu**2)
   d = e_ps*reshape([1.0_dp, nu, nu, 1.0_dp], [2, 2])

   ! elastic predictor
   ep_n = statev(1)
   trial = stress + matmul(d, dstran)
   sy = sigma0 + h*ep_n
   seq = mises(trial)

   if (seq <= (1.0_dp + tol)*sy) then
      ! elastic (or elastic unloading); thickness strain from sigma22 = 0
      dsig = trial - stress
      stress = trial
      ddsdde = d
      statev(2) = statev(2) - nu/e_mod*(dsig(1) + dsig(2))
      statev(3) = stress(2)
      statev(4) = e_ps
      statev(5) = sy
      statev(6) = h
      sse = energy(stress)
      return
   end if

   ! return mapping: Newton on f(gamma), starting from gamma = 0
   k_s = e_mod/(2.0_dp*(1.0_dp - nu))
   k_t = 3.0_dp*e_mod/(2.0_dp*(1.0_dp + nu))
   s_tr = trial(1) + trial(2)
   t_tr = trial(1) - trial(2)
   gam = 0.0_dp
   do iter = 1, max_iter
      s = s_tr/(1.0_dp + gam*k_s)
      t = t_tr/(1.0_dp + gam*k_t)
      seq = sqrt(s**2 + 3.0_dp*t**2)/2.0_dp
      sy = sigma0 + h*(ep_n + gam*seq)
      f = seq - sy
      if (abs(f) <= tol*sy) exit
      ds = -k_s*s/(1.0_dp + gam*k_s)
      dt = -k_t*t/(1.0_dp + gam*k_t)
      dseq = (s*ds + 3.0_dp*t*dt)/(4.0_dp*seq)
      gam = gam - f/(dseq - h*(seq + gam*dseq))
   end do
   if (.not. (abs(f) <= tol*sy) .or. gam <= 0.0_dp) then
      ! no convergence: ask for a smaller increment, change nothing
      pnewdt = min(pnewdt, 0.5_dp)
      ddsdde = d
      return
   end if

   dep = gam*seq
   dsig = [(s + t)/2.0_dp, (s - t)/2.0_dp] - stress
   stress = stress + dsig
   n = [stress(1) - 0.5_dp*stress(2), stress(2) - 0.5_dp*stress(1)]/seq

   ! consistent tangent: Xi = (D^-1 + dp (P - n n^T)/sbar)^-1,
   ! ddsdde = Xi - (Xi n)(Xi n)^T / (n^T Xi n + H)
   a(1, 1) = 1.0_dp/e_mod + dep*(1.0_dp - n(1)**2)/seq
   a(2, 2) = 1.0_dp/e_mod + dep*(1.0_dp - n(2)**2)/seq
   a(1, 2) = -nu/e_mod + dep*(-0.5_dp - n(1)*n(2))/seq
   a(2, 1) = a(1, 2)
   xi = reshape([a(2, 2), -a(2, 1), -a(1, 2), a(1, 1)], [2, 2])/(a(1, 1)*a(2, 2) - a(1, 2)**2)
   xn = matmul(xi, n)
   do j = 1, 2
      ddsdde(:, j) = xi(:, j) - xn*xn(j)/(dot_product(n, xn) + h)
   end do

   ! state: plastic strain, thickness strain (elastic part from sigma22 = 0,
   ! plastic part from incompressibility), continuum tangent (A.1)
   dn = matmul(d, n)
   statev(1) = ep_n + dep
   statev(2) = statev(2) - nu/e_mod*(dsig(1) + dsig(2)) - dep*(n(1) + n(2))
   statev(3) = stress(2)
   statev(4) = e_ps - dn(1)**2/(dot_product(n, dn) + h)
   statev(5) = sigma0 + h*statev(1)
   statev(6) = h
   sse = energy(stress)
   ! dissipation: int sigma_y d ebar_p over the increment
   spd = spd + dep*(sigma0 + h*(ep_n + 0.5_dp*dep))

contains

   !> von Mises equivalent stress with sigma22 = 0.
   pure function mises(sig) result(r)
      real(dp), intent(in) :: sig(2)
      real(dp) :: r
      ! ((s11 + s33)^2 + 3 (s11 - s33)^2)/4 = s11^2 + s33^2 - s11 s33, a sum
      ! of squares: never the root of a negative round-off
      r = sqrt((sig(1) + sig(2))**2 + 3.0_dp*(sig(1) - sig(2))**2)/2.0_dp
   end function mises

   !> elastic energy density (s11^2 + s33^2 - 2 nu s11 s33)/(2E).
   pure function energy(sig) result(w)
      real(dp), intent(in) :: sig(2)
      real(dp) :: w
      w = (sig(1)**2 + sig(2)**2 - 2.0_dp*nu*sig(1)*sig(2))/(2.0_dp*e_mod)
   end function energy

end subroutine umat
