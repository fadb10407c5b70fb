!> What the benchmark tools share: their integer arguments, and the order
!> statistics of their timings (best, median).
module kcreep_bench_support
  use, intrinsic :: iso_fortran_env, only: real64, error_unit
  implicit none
  private
  public :: integer_argument, sorted, median

contains

  !> Command-line argument `position` read as a whole number; `default` when
  !> it is not given (without a default the argument is required).
  integer function integer_argument(position, default) result(value)
    integer, intent(in) :: position
    integer, intent(in), optional :: default
    character(len=32) :: arg
    integer :: stat
    if (command_argument_count() < position) then
      if (.not. present(default)) call usage_error('argument '//digit(position)//' (a whole number) is missing')
      value = default
      return
    end if
    call get_command_argument(position, arg)
    read (arg, *, iostat=stat) value
    if (stat /= 0) call usage_error('argument '//digit(position)//' = '//trim(arg)//': not a whole number')

  contains

    pure function digit(k) result(text)
      integer, intent(in) :: k
      character(len=12) :: buffer
      character(len=:), allocatable :: text
      write (buffer, '(i0)') k
      text = trim(buffer)
    end function digit

    subroutine usage_error(message)
      character(len=*), intent(in) :: message
      write (error_unit, '(a)') 'error: '//message
      stop 2
    end subroutine usage_error

  end function integer_argument

  !> x in ascending order (insertion sort: the tools' samples are small).
  pure function sorted(x) result(s)
    real(real64), intent(in) :: x(:)
    real(real64) :: s(size(x)), t
    integer :: i, j
    s = x
    do i = 2, size(s)
      t = s(i)
      j = i - 1
      do while (j >= 1)
        if (s(j) <= t) exit
        s(j + 1) = s(j)
        j = j - 1
      end do
      s(j + 1) = t
    end do
  end function sorted

  !> The middle value of x (the upper of the two middle ones for an even count).
  pure real(real64) function median(x)
    real(real64), intent(in) :: x(:)
    real(real64) :: s(size(x))
    s = sorted(x)
    median = s((size(s) + 1) / 2)
  end function median

end module kcreep_bench_support
