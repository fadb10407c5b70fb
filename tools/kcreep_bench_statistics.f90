!> Order statistics of the benchmark tools' timings (best, median).
module kcreep_bench_statistics
  use, intrinsic :: iso_fortran_env, only: real64
  implicit none
  private
  public :: sorted, median

contains

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

end module kcreep_bench_statistics
