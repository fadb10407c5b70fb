!> Benchmark of one GMRES step's FFT work: the system operator and the
!> circulant preconditioner applied to a block of 3 vectors on an n x n
!> unit circle (backward scheme, nu = 0.25), pruned and whole-grid
!> transforms. Prints the median seconds per block apply of each and the
!> largest difference pruned - whole relative to the largest entry.
!>   kcreep_fft_bench n [repeats]      (threads: OMP_NUM_THREADS)
program fft_bench
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_bench_support, only: integer_argument, median
  use kcreep_status, only: status_t
  use kcreep_patch, only: patch_t, ellipse_patch
  use kcreep_assembly, only: scheme_t, operator_table_t, build_operator_table
  use kcreep_fft_operator, only: fft_operator_t, create_fft_operator, apply_fft_operator, destroy_fft_operator
  use kcreep_circulant_preconditioner, only: circulant_preconditioner_t, build_circulant_preconditioner, &
                                            apply_circulant_preconditioner, destroy_circulant_preconditioner
  implicit none
  type(status_t) :: st
  type(patch_t) :: patch
  type(scheme_t) :: scheme
  type(operator_table_t) :: table
  type(fft_operator_t) :: pruned, whole
  type(circulant_preconditioner_t) :: prec
  real(real64), allocatable :: x(:, :), y(:, :), y_whole(:, :)
  integer :: n, repeats

  n = integer_argument(1)
  repeats = integer_argument(2, default=11)
  call ellipse_patch(1.0_real64, 1.0_real64, n, n, patch, st)
  scheme%name = 'backward'
  call build_operator_table(patch, scheme, 0.25_real64, 1.0_real64, table)
  call create_fft_operator(patch, table, 3, pruned)
  call create_fft_operator(patch, table, 3, whole, pruned=.false.)
  call build_circulant_preconditioner(patch, 0.25_real64, 3, prec)
  allocate (x(2 * patch%n, 3), y(2 * patch%n, 3), y_whole(2 * patch%n, 3))
  call random_number(x)

  print '(a, i0, a, i0, a, i0, a)', 'circle ', n, ' x ', n, ' (', patch%n, ' cells), block of 3, median s per apply:'
  print '(a, f9.4)', '  operator, pruned     ', median_time(1)
  print '(a, f9.4)', '  operator, whole grid ', median_time(2)
  print '(a, f9.4)', '  circulant precond.   ', median_time(3)
  call apply_fft_operator(pruned, x, y)
  call apply_fft_operator(whole, x, y_whole)
  print '(a, es9.2)', '  max |pruned - whole| / max |whole| ', maxval(abs(y - y_whole)) / maxval(abs(y_whole))
  call destroy_fft_operator(pruned)
  call destroy_fft_operator(whole)
  call destroy_circulant_preconditioner(prec)

contains

  real(real64) function median_time(which) result(t)
    integer, intent(in) :: which
    real(real64) :: times(repeats)
    integer(int64) :: t0, t1, rate
    integer :: r
    do r = 1, repeats
      call system_clock(t0, rate)
      select case (which)
      case (1)
        call apply_fft_operator(pruned, x, y)
      case (2)
        call apply_fft_operator(whole, x, y)
      case default
        call apply_circulant_preconditioner(prec, x, y)
      end select
      call system_clock(t1)
      times(r) = real(t1 - t0, real64) / rate
    end do
    t = median(times)
  end function median_time

end program fft_bench
