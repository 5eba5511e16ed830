!> phases -- the names of a run's two phases: locking (the lower tool rises
!> by H to the lock depth) and pulling (the right edge is pulled by delta),
!> docs/theory.md §1.  One declaration for every module that tests or
!> writes a phase (the increment loop, the criteria, the records, the
!> outputs, summary.txt's *_phase keys).
module phases
   implicit none
   private
   public :: phase_lock, phase_pull

   character(len=*), parameter :: phase_lock = 'lock'
   character(len=*), parameter :: phase_pull = 'pull'
end module phases
