!> The machine's practical limits for the benchmark (scripts/bench/bench.sh):
!>   kcreep_blas_bench dgemm N        GFLOP/s of an N x N x N dgemm (median of 3)
!>   kcreep_blas_bench dgetrf N...    seconds and GFLOP/s of dgetrf on random N x N matrices (median of 3)
!> One line per measurement: "<routine> <n> <seconds> <gflops>".
program blas_bench
  use, intrinsic :: iso_fortran_env, only: real64, int64, output_unit, error_unit
  use kcreep_bench_support, only: median
  implicit none
  interface
    subroutine dgemm(ta, tb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc)
      import :: real64
      character(len=1), intent(in) :: ta, tb
      integer, intent(in) :: m, n, k, lda, ldb, ldc
      real(real64), intent(in) :: alpha, beta, a(lda, *), b(ldb, *)
      real(real64), intent(inout) :: c(ldc, *)
    end subroutine dgemm
    subroutine dgetrf(m, n, a, lda, ipiv, info)
      import :: real64
      integer, intent(in) :: m, n, lda
      real(real64), intent(inout) :: a(lda, *)
      integer, intent(out) :: ipiv(*), info
    end subroutine dgetrf
  end interface
  integer, parameter :: repeats = 3
  character(len=32) :: routine, arg
  integer :: i, n, ios

  if (command_argument_count() < 2) then
    write (error_unit, '(a)') 'usage: kcreep_blas_bench dgemm N | dgetrf N [N ...]'
    error stop 2
  end if
  call get_command_argument(1, routine)
  do i = 2, command_argument_count()
    call get_command_argument(i, arg)
    read (arg, *, iostat=ios) n
    if (ios /= 0 .or. n < 1) then
      write (error_unit, '(a)') 'kcreep_blas_bench: bad size '//trim(arg)
      error stop 2
    end if
    select case (routine)
    case ('dgemm')
      call time_dgemm(n)
    case ('dgetrf')
      call time_dgetrf(n)
    case default
      write (error_unit, '(a)') 'kcreep_blas_bench: unknown routine '//trim(routine)
      error stop 2
    end select
  end do

contains

  subroutine time_dgemm(n)
    integer, intent(in) :: n
    real(real64), allocatable :: a(:, :), b(:, :), c(:, :)
    real(real64) :: t(repeats)
    integer :: r
    integer(int64) :: t0, t1, rate
    allocate (a(n, n), b(n, n), c(n, n))
    call random_number(a)
    call random_number(b)
    c = 0
    do r = 1, repeats
      call system_clock(t0, rate)
      call dgemm('N', 'N', n, n, n, 1.0_real64, a, n, b, n, 0.0_real64, c, n)
      call system_clock(t1)
      t(r) = real(t1 - t0, real64) / rate
    end do
    call report('dgemm', n, median(t), 2 * real(n, real64)**3)
  end subroutine time_dgemm

  subroutine time_dgetrf(n)
    integer, intent(in) :: n
    real(real64), allocatable :: a(:, :), a0(:, :)
    integer, allocatable :: ipiv(:)
    real(real64) :: t(repeats)
    integer :: r, info
    integer(int64) :: t0, t1, rate
    allocate (a0(n, n), ipiv(n))
    call random_number(a0)
    do r = 1, repeats
      a = a0
      call system_clock(t0, rate)
      call dgetrf(n, n, a, n, ipiv, info)
      call system_clock(t1)
      t(r) = real(t1 - t0, real64) / rate
    end do
    call report('dgetrf', n, median(t), 2 * real(n, real64)**3 / 3)
  end subroutine time_dgetrf

  subroutine report(name, n, seconds, flops)
    character(len=*), intent(in) :: name
    integer, intent(in) :: n
    real(real64), intent(in) :: seconds, flops
    write (output_unit, '(a, 1x, i0, 1x, f10.4, 1x, f8.2)') name, n, seconds, flops / seconds / 1e9_real64
  end subroutine report


end program blas_bench
