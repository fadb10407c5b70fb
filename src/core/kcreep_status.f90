!> Error status passed up the call chain to the one place that reports it.
!>
!> Every routine that can fail takes a `status_t` argument (intent(inout)),
!> sets it with `fail` and returns; callers check `status%failed()`. Only the
!> main program prints the message, as a single line on standard error.
module kcreep_status
  use kcreep_strings, only: one_line
  implicit none
  private
  public :: status_t, fail

  type :: status_t
    integer :: code = 0                       !< 0: fine, otherwise an exit code
    character(len=:), allocatable :: message  !< one line: what, where, value, allowed
  contains
    procedure :: failed
  end type status_t

  integer, parameter, public :: exit_bad_input = 2   !< input file or value wrong
  integer, parameter, public :: exit_numerical = 3   !< solver could not produce a result
  integer, parameter, public :: exit_io = 4          !< output could not be written

contains

  pure logical function failed(self)
    class(status_t), intent(in) :: self
    failed = self%code /= 0
  end function failed

  !> Record an error; the first one wins so that the root cause is reported.
  pure subroutine fail(status, code, message)
    type(status_t), intent(inout) :: status
    integer, intent(in) :: code
    character(len=*), intent(in) :: message
    if (status%code /= 0) return
    status%code = code
    status%message = one_line(message)   ! bad input may carry newlines or control bytes
  end subroutine fail

end module kcreep_status
