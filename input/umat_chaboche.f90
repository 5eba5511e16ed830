!> umat_chaboche -- an example of a user's material routine with more state
!> than a scalar: von Mises plasticity with Swift isotropic hardening and
!> two Armstrong-Frederick (Chaboche) back stresses, written as for an
!> Abaqus plane-strain element, independently of the program's own
!> combined-hardening law (src/law_combined.f90), against which
!> tests/umat.sh checks it.
!>
!> Build:  make UMAT=input/umat_chaboche.f90
!> Deck:   &material model = 'umat', umat_props = E, nu, K, eps0, n, C1,
!>         gamma1, C2, gamma2, umat_nstatv = 9, umat_eqps_index = 1 /
!>
!> Conventions: NDI = 3, NSHR = 1, NTENS = 4, components (11, 22, 33, 12),
!> engineering shear strain; Kirchhoff stress, logarithmic strain,
!> additive elasto-plasticity, backward Euler.
!>
!> Constants: props(1:2) = E, nu; props(3:5) = Swift's K, eps0, n
!> (sigma_y = K (eps0 + p)^n); props(6:9) = C1, gamma1, C2, gamma2.
!> State variables (NSTATV = 9): statev(1) p, statev(2:5) alpha_1,
!> statev(6:9) alpha_2 (components 11, 22, 33, 12 of each back stress).
!>
!> Stress update (von Mises: the return is radial).  With
!> a_i = 1/(1 + gamma_i dp), b_i = (2/3) C_i dp a_i, the deviator of
!> xi = sigma - sum alpha_i is s = s* - (2 mu dp + sum b_i) n, with
!> s* = dev(sigma_trial) - sum a_i alpha_i,n and n = (3/2) s*/q*, so the
!> one unknown dp solves
!>   q*(dp) - 3 mu dp - (3/2) sum b_i(dp) - sigma_y(p_n + dp) = 0
!> (Newton; q* depends on dp through the a_i).  The tangent DDSDDE is
!> computed by central differences of the update (step 1e-8 of the strain
!> increment's scale): simple, accurate to some 1e-8, which is all the
!> program's Newton iterations need to converge (at a rate of that order).
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

   real(dp) :: s0(4), sv0(9), sp(4), sm(4), svx(9), de(4), hstep, wx
   integer :: j
   logical :: ok

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
   if (ndi /= 3 .or. nshr /= 1 .or. ntens /= 4 .or. nstatv < 9 .or. nprops < 9) then
      pnewdt = 0.0_dp
      return
   end if
   s0 = stress
   sv0 = statev(1:9)
   call update(s0, sv0, dstran, stress, statev(1:9), spd, ok)
   if (.not. ok) then
      stress = s0
      statev(1:9) = sv0
      pnewdt = min(pnewdt, 0.5_dp)
      return
   end if
   sse = (stress(1)**2 + stress(2)**2 + stress(3)**2 &
          - 2.0_dp*props(2)*(stress(1)*stress(2) + stress(2)*stress(3) + stress(1)*stress(3)) &
          + 2.0_dp*(1.0_dp + props(2))*stress(4)**2)/(2.0_dp*props(1))
   ! the tangent by central differences of the update
   hstep = 1.0e-8_dp*max(maxval(abs(dstran)), 1.0e-3_dp)
   do j = 1, 4
      de = dstran
      de(j) = de(j) + hstep
      wx = 0.0_dp
      call update(s0, sv0, de, sp, svx, wx, ok)
      de(j) = de(j) - 2.0_dp*hstep
      call update(s0, sv0, de, sm, svx, wx, ok)
      ddsdde(:, j) = (sp - sm)/(2.0_dp*hstep)
   end do

contains

   !> The update of the module header from (sig_n, sv_n) by dstr into
   !> (sig, sv); w gets the plastic work of the increment added.
   subroutine update(sig_n, sv_n, dstr, sig, sv, w, ok)
      real(dp), intent(in) :: sig_n(4), sv_n(9), dstr(4)
      real(dp), intent(out) :: sig(4), sv(9)
      real(dp), intent(inout) :: w
      logical, intent(out) :: ok
      real(dp) :: e, nu, mu, lam, tr(4), al(4, 2), c(2), g(2), a(2), b(2), x, s(4), q, sy, hy, f, &
                  df, ds(4), dq, nrm(4), dep(4), al1(4, 2), ep
      integer :: i, it
      e = props(1)
      nu = props(2)
      c = props([6, 8])
      g = props([7, 9])
      mu = e/(2.0_dp*(1.0_dp + nu))
      lam = e*nu/((1.0_dp + nu)*(1.0_dp - 2.0_dp*nu))
      tr(1:3) = sig_n(1:3) + lam*sum(dstr(1:3)) + 2.0_dp*mu*dstr(1:3)
      tr(4) = sig_n(4) + mu*dstr(4)
      al(:, 1) = sv_n(2:5)
      al(:, 2) = sv_n(6:9)
      ep = sv_n(1)
      sig = tr
      sv = sv_n
      ok = .true.
      call deviator(tr - al(:, 1) - al(:, 2), s, q)
      call swift(ep, sy, hy)
      if (q <= (1.0_dp + 1.0e-12_dp)*sy) return
      x = 0.0_dp
      do it = 1, 60
         a = 1.0_dp/(1.0_dp + g*x)
         b = (2.0_dp/3.0_dp)*c*x*a
         call deviator(tr - a(1)*al(:, 1) - a(2)*al(:, 2), s, q)
         call swift(ep + x, sy, hy)
         f = q - 3.0_dp*mu*x - 1.5_dp*sum(b) - sy
         if (abs(f) <= 1.0e-13_dp*sy) exit
         ! d q*/d dp: s* changes by sum gamma_i a_i^2 dev(alpha_i,n)
         call deviator(g(1)*a(1)**2*al(:, 1) + g(2)*a(2)**2*al(:, 2), ds, dq)
         dq = 1.5_dp*(s(1)*ds(1) + s(2)*ds(2) + s(3)*ds(3) + 2.0_dp*s(4)*ds(4))/q
         df = dq - 3.0_dp*mu - sum(c*a*a) - hy
         x = x - f/df
      end do
      ok = abs(f) <= 1.0e-10_dp*sy .and. x > 0.0_dp
      if (.not. ok) return
      nrm = 1.5_dp*s/q
      dep = x*nrm
      ! the shear's engineering strain is twice the tensor one
      dep(4) = 2.0_dp*dep(4)
      sig(1:3) = tr(1:3) - 2.0_dp*mu*x*nrm(1:3)
      sig(4) = tr(4) - 2.0_dp*mu*x*nrm(4)
      do i = 1, 2
         al1(:, i) = a(i)*al(:, i) + b(i)*nrm
      end do
      sv(1) = ep + x
      sv(2:5) = al1(:, 1)
      sv(6:9) = al1(:, 2)
      ! plastic work: the isotropic curve's integral, exact, plus the back
      ! stresses' work by the trapezoid
      w = w + swift_work(ep + x) - swift_work(ep) &
          + sum(0.5_dp*(al(1:3, 1) + al1(1:3, 1) + al(1:3, 2) + al1(1:3, 2))*dep(1:3)) &
          + 0.5_dp*(al(4, 1) + al1(4, 1) + al(4, 2) + al1(4, 2))*dep(4)
   end subroutine update

   !> The deviator of a (11, 22, 33, 12) stress and its von Mises equivalent.
   pure subroutine deviator(t, s, q)
      real(dp), intent(in) :: t(4)
      real(dp), intent(out) :: s(4), q
      s = t
      s(1:3) = t(1:3) - sum(t(1:3))/3.0_dp
      q = sqrt(1.5_dp*(s(1)**2 + s(2)**2 + s(3)**2 + 2.0_dp*s(4)**2))
   end subroutine deviator

   !> Swift's flow stress and slope.
   subroutine swift(p, sy, hy)
      real(dp), intent(in) :: p
      real(dp), intent(out) :: sy, hy
      sy = props(3)*(props(4) + p)**props(5)
      hy = props(5)*sy/(props(4) + p)
   end subroutine swift

   !> The integral of Swift's curve from 0 to p, K/(n+1) ((eps0 + p)^(n+1) - eps0^(n+1)).
   function swift_work(p) result(wk)
      real(dp), intent(in) :: p
      real(dp) :: wk
      wk = props(3)/(props(5) + 1.0_dp)*(props(4) + p)**(props(5) + 1.0_dp)
   end function swift_work
end subroutine umat
