!> kcreep_table_bench: time per call of method = 'table' (docs/performance.md),
!> best and median of 21 repetitions of CALLS calls (100000 by default) at
!> a/b and nu spread over the table (log-uniform a/b in [0.1, 10], nu in [0, 0.5]):
!>   interpolation   kcreep_table_interpolation table_coefficients alone;
!>   kcreep_solve    the library call with method = 'table' on an ellipse patch
!>                   of M x M cells (default 20; the patch is FASTSIM's grid,
!>                   its flexibilities and equivalent ellipses are computed).
!> Then the stated relative uncertainties of C11 C22 C23 over the first 2000
!> of those points (median and largest), and at how many of them all three
!> meet the default target (1e-3, C23 3e-3), where method = 'auto' answers
!> from the table instead of solving; and the same on a regular grid of 401
!> a/b (log-spaced) x 101 nu over the whole range, with the largest stated
!> uncertainties, and at how many of those the accurate mode's target (1e-4,
!> C23 3e-4) is met (the table's fine rows, docs/accuracy.md, "The refined table of ellipses"). Run it
!> under flock /tmp/kcreep-bench.lock.
!>   kcreep_table_bench [CALLS [M]]
program table_bench
  use, intrinsic :: iso_fortran_env, only: real64, int64, output_unit
  use kcreep, only: problem_t, result_t, default_problem, ellipse_patch, kcreep_solve, status_t
  use kcreep_table_interpolation, only: table_coefficients
  use kcreep_bench_support, only: integer_argument, median
  implicit none
  integer, parameter :: repeats = 21
  integer :: calls, m, k, r, q
  character(len=32) :: arg
  real(real64), allocatable :: ratio(:), nu(:), rel(:, :)
  real(real64) :: c(4), u(4), times(repeats), checksum
  integer(int64) :: t0, t1, rate
  type(problem_t) :: problem
  type(result_t) :: result
  type(status_t) :: status

  calls = integer_argument(1, default=100000)
  m = integer_argument(2, default=20)
  allocate (ratio(calls), nu(calls), rel(4, min(calls, 2000)))
  ! a fixed quasi-random spread (golden-ratio sequences) over the table
  do k = 1, calls
    ratio(k) = 10.0_real64**(2 * modulo(k * 0.6180339887498949_real64, 1.0_real64) - 1)
    nu(k) = 0.5_real64 * modulo(k * 0.7548776662466927_real64, 1.0_real64)
  end do
  call system_clock(count_rate=rate)
  checksum = 0
  do r = 1, repeats
    call system_clock(t0)
    do k = 1, calls
      call table_coefficients(ratio(k), nu(k), c, u, status)
      checksum = checksum + c(1)
    end do
    call system_clock(t1)
    times(r) = real(t1 - t0, real64) / rate / calls
  end do
  call report('interpolation (table_coefficients)', times)
  do k = 1, size(rel, 2)
    call table_coefficients(ratio(k), nu(k), c, rel(:, k), status)
  end do

  problem = default_problem()
  problem%solve%method = 'table'
  do r = 1, repeats
    call system_clock(t0)
    do k = 1, max(1, calls / 100)
      call ellipse_patch(sqrt(ratio(k)), 1 / sqrt(ratio(k)), m, m, problem%patch, status)
      problem%nu = nu(k)
      call kcreep_solve(problem, result, status)
      checksum = checksum + result%cn(1)
    end do
    call system_clock(t1)
    times(r) = real(t1 - t0, real64) / rate / max(1, calls / 100)
  end do
  write (arg, '(i0, a, i0)') m, ' x ', m
  call report('kcreep_solve, method table, patch '//trim(arg)//' (patch built in the loop)', times)
  write (output_unit, '(a, es10.3)') 'checksum ', checksum
  do q = 1, 3
    write (output_unit, '(a, i0, a, 2f8.4)') 'stated relative uncertainty of C', merge(11, merge(22, 23, q == 2), &
      q == 1), ' over the points, median and largest [%]:', 100 * median(rel(q, :)), 100 * maxval(rel(q, :))
  end do
  write (output_unit, '(a, i0, a, i0, a)') 'within the default target (1e-3, C23 3e-3) at ', &
    count(rel(1, :) <= 1e-3_real64 .and. rel(2, :) <= 1e-3_real64 .and. rel(3, :) <= 3e-3_real64), ' of ', &
    size(rel, 2), ' points (method = ''auto'' answers those from the table)'
  call grid_sweep()

contains

  !> The stated uncertainty on a regular 401 x 101 grid of a/b (log-spaced, 0.1 to 10) and nu (0 to 0.5).
  subroutine grid_sweep()
    integer, parameter :: n_ratio = 401, n_nu = 101
    integer :: i, j, within, within_accurate, long_points, long_accurate
    real(real64) :: worst(4), c4(4), r4(4), ratio
    type(status_t) :: sweep_status
    within = 0
    within_accurate = 0
    long_points = 0
    long_accurate = 0
    worst = 0
    do j = 0, n_nu - 1
      do i = 0, n_ratio - 1
        ratio = 10.0_real64**(2 * real(i, real64) / (n_ratio - 1) - 1)
        call table_coefficients(ratio, 0.5_real64 * j / (n_nu - 1), c4, r4, sweep_status)
        worst = max(worst, r4)
        if (r4(1) <= 1e-3_real64 .and. r4(2) <= 1e-3_real64 .and. r4(3) <= 3e-3_real64) within = within + 1
        ! a/b >= 3.33 is where every column of the table's rows is a fine row (docs/accuracy.md, "The refined table of ellipses")
        if (ratio >= 10.0_real64 / 3) long_points = long_points + 1
        if (r4(1) <= 1e-4_real64 .and. r4(2) <= 1e-4_real64 .and. r4(3) <= 3e-4_real64) then
          within_accurate = within_accurate + 1
          if (ratio >= 10.0_real64 / 3) long_accurate = long_accurate + 1
        end if
      end do
    end do
    write (output_unit, '(a, i0, a, i0, a, 3f8.4)') 'grid of 401 a/b x 101 nu: within the default target at ', &
      within, ' of ', n_ratio * n_nu, ' points; largest stated uncertainty of C11 C22 C23 [%]:', 100 * worst(1:3)
    write (output_unit, '(a, i0, a, i0, a)') 'grid of 401 a/b x 101 nu: within the accurate mode''s target '// &
      '(1e-4, C23 3e-4) at ', within_accurate, ' of ', n_ratio * n_nu, ' points'
    write (output_unit, '(a, i0, a, i0, a)') '  of which with a/b >= 3.33 (fine rows only): ', long_accurate, ' of ', &
      long_points, ' points'
  end subroutine grid_sweep

  subroutine report(what, t)
    character(len=*), intent(in) :: what
    real(real64), intent(in) :: t(:)
    write (output_unit, '(a, f10.3, a, f10.3, a)') what//': best ', 1e6_real64 * minval(t), ' us, median ', &
      1e6_real64 * median(t), ' us per call'
  end subroutine report


end program table_bench
