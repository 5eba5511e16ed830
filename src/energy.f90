!> energy -- the work and energy bookkeeping of a run: the external work,
!> summed increment by increment, against the energy stored and dissipated
!> in the sheet and the contact (summary.txt's energy_* lines; their balance
!> checks the whole chain of element, section, material and contact).
module energy
   use kinds, only: dp
   use hermite, only: n_gauss, gauss_wt
   use section, only: ih_sse, ih_spd, ih_work22, ih_statev
   use contact, only: penalty_energy, ich_penetration, ich_dissipation, ich_offwork
   use model, only: model_type, state_type, load_type
   use element, only: igp_gradient_energy
   use record, only: run_record
   implicit none
   private
   public :: energy_totals, energy_absorbed, add_increment_work, stored_plastic_energy
   public :: n_energy, ien_elastic, ien_plastic, ien_penalty, ien_friction, ien_normal_stress, &
             ien_offset_work

   !> the entries of energy_totals' array
   integer, parameter :: ien_elastic = 1, ien_plastic = 2, ien_penalty = 3, ien_friction = 4, &
                         ien_normal_stress = 5, ien_offset_work = 6, n_energy = 6

contains

   !> ADD_INCREMENT_WORK: external work of one converged increment,
   !> trapezoidal: the reactions on the prescribed motions (the pull
   !> N d(delta), an edge following the binder), the rising lower tool
   !> (F dH while locking) and the dead loads.
   !>  ld       [in]     the increment's load (which dofs are prescribed)
   !>  r        [in]     residual at the end of the increment (reactions at
   !>                    the prescribed dofs)
   !>  du       [in]     the increment's motion u - u_prev
   !>  tool_work [in]    the lower tool's work F dH of the increment (0 when
   !>                    pulling)
   !>  rec      [in,out] work and the reactions kept for the next increment
   subroutine add_increment_work(ld, r, du, tool_work, rec)
      type(load_type), intent(in) :: ld
      real(dp), intent(in) :: r(:), du(:), tool_work
      type(run_record), intent(inout) :: rec
      if (.not. allocated(rec%reactions)) then
         allocate (rec%reactions(size(r)))
         rec%reactions = 0.0_dp
      end if
      rec%work = rec%work + 0.5_dp*dot_product(merge(rec%reactions + r, 0.0_dp, ld%fixed), du) &
                 + dot_product(ld%f_ext, du)
      rec%work = rec%work + tool_work
      rec%reactions = r
   end subroutine add_increment_work

   !> ENERGY_TOTALS: stored and dissipated energies of the converged state per
   !> unit width (N mm/mm): elastic, plastic (the material's sse and spd
   !> integrated over the sheet), penalty (k d^2/2 over the contact stations)
   !> and friction dissipation; and the work of the contact section's
   !> thickness stress on the thickness strain (docs/theory.md §12), an input
   !> of energy the shell's external work does not hold; and with
   !> contact_faces = 'current' the work of the tools' normal forces on the
   !> faces' offsets toward the centreline (contact module), which the
   !> penalty energy k G(d - offset) gives up as the faces move and which
   !> the shell's equations do not see either:
   !>   external work = energy_absorbed(energy).
   !>  m, s    [in]  model and converged state
   !>  energy  [out] (n_energy) named by the ien_* constants: elastic,
   !>                plastic, penalty, friction, normal-stress work, offset work
   pure subroutine energy_totals(m, s, energy)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      real(dp), intent(out) :: energy(n_energy)
      real(dp) :: dv
      integer :: e, ig, it
      energy = 0.0_dp
      do e = 1, m%n_el
         do ig = 1, n_gauss
            dv = gauss_wt(ig)*(m%x(e + 1) - m%x(e))
            ! elastic: the material's and the strain-gradient term's
            energy(ien_elastic) = energy(ien_elastic) + dv*(dot_product(m%wz, s%hn(:, ih_sse, ig, e)) &
                                        + s%gpn(igp_gradient_energy, ig, e))
            energy(ien_plastic) = energy(ien_plastic) + dv*dot_product(m%wz, s%hn(:, ih_spd, ig, e))
            energy(ien_normal_stress) = energy(ien_normal_stress) &
                                        + dv*dot_product(m%wz, s%hn(:, ih_work22, ig, e))
            if (m%has_tools) then
               do it = 1, 2
                  energy(ien_penalty) = energy(ien_penalty) + dv*penalty_energy(m%penalty, m%contact_smoothing, &
                                                           s%cn(ich_penetration, ig, e, it))
                  energy(ien_friction) = energy(ien_friction) + dv*s%cn(ich_dissipation, ig, e, it)
                  energy(ien_offset_work) = energy(ien_offset_work) + dv*s%cn(ich_offwork, ig, e, it)
               end do
            end if
         end do
      end do
   end subroutine energy_totals

   !> ENERGY_ABSORBED: what the external work must equal in energy_totals'
   !> balance (stored and dissipated, less the normal stress's work, plus
   !> the offset work); linear, so that it also takes differences of totals.
   !>  energy  [in] (n_energy) energy_totals' array or a difference of two
   pure function energy_absorbed(energy) result(w)
      real(dp), intent(in) :: energy(n_energy)
      real(dp) :: w
      w = energy(ien_elastic) + energy(ien_plastic) + energy(ien_penalty) + energy(ien_friction) &
          - energy(ien_normal_stress) + energy(ien_offset_work)
   end function energy_absorbed

   !> STORED_PLASTIC_ENERGY: the part of the plastic work that the material's
   !> state stores rather than dissipates (the back stresses of kinematic
   !> hardening, docs/theory.md §13.4: the law's stored_energy), integrated
   !> over the sheet, N mm/mm; 0 for an isotropic law.  The plastic
   !> dissipation is energy_totals' plastic work less this.
   !>  m, s  [in]  model and converged state
   function stored_plastic_energy(m, s) result(w)
      type(model_type), intent(in) :: m
      type(state_type), intent(in) :: s
      real(dp) :: w, dv, ws
      integer :: e, ig, k
      w = 0.0_dp
      do e = 1, m%n_el
         do ig = 1, n_gauss
            dv = gauss_wt(ig)*(m%x(e + 1) - m%x(e))
            ws = 0.0_dp
            do k = 1, m%npt
               ws = ws + m%wz(k)*m%material%stored_energy(s%hn(k, ih_statev:, ig, e))
            end do
            w = w + dv*ws
         end do
      end do
   end function stored_plastic_energy
end module energy
