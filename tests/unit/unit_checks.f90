!> The shared bookkeeping of the Fortran unit tests: count checks, print the
!> failures, and close with the 'N passed, N failed' line CTest logs show.
module unit_checks
  implicit none
  private
  public :: checker_t

  type :: checker_t
    integer :: checks = 0, failures = 0
  contains
    procedure :: check, finish
  end type checker_t

contains

  subroutine check(self, condition, what)
    class(checker_t), intent(inout) :: self
    logical, intent(in) :: condition
    character(len=*), intent(in) :: what
    self%checks = self%checks + 1
    if (condition) then
      print '(a)', 'ok   '//what
    else
      self%failures = self%failures + 1
      print '(a)', 'FAIL '//what
    end if
  end subroutine check

  !> The summary line; a non-zero exit status when anything failed.
  subroutine finish(self)
    class(checker_t), intent(in) :: self
    print '(i0, a, i0, a)', self%checks - self%failures, ' passed, ', self%failures, ' failed'
    if (self%failures > 0) error stop 1
  end subroutine finish

end module unit_checks
