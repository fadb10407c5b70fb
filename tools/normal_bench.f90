!> Benchmark of the normal contact solve: Hertz's sphere on an n x n grid
!> (the contact circle spans 80 % of the grid width), force prescribed.
!> Prints one line: n, cells, iterations, FFT products, residual, wall seconds of the
!> solve (best of the repeats), peak resident memory (MiB), and the
!> relative errors of approach and pmax against Hertz.
!>   kcreep_normal_bench n [repeats]
program normal_bench
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t
  use kcreep_hertz, only: hertz_t, hertz_from_force
  use kcreep_gap, only: gap_t, polynomial_gap_t, gap_from_polynomial
  use kcreep_normal_solve, only: normal_options_t, normal_result_t, solve_normal
  use kcreep_bench_support, only: integer_argument
  implicit none
  type(polynomial_gap_t) :: poly
  type(gap_t) :: gap
  type(status_t) :: st
  type(normal_options_t) :: opt
  type(normal_result_t) :: res
  type(hertz_t) :: hz
  integer :: n, repeats, r
  integer(int64) :: t0, t1, rate
  real(real64) :: dx, best

  n = integer_argument(1)
  repeats = integer_argument(2, default=1)
  poly%rx = 1
  poly%ry = 1
  hz = hertz_from_force(0.5_real64, 0.5_real64, 1.0_real64, 1.0_real64)
  dx = 2 * hz%a / (0.8_real64 * n)
  call gap_from_polynomial(poly, n, n, dx, dx, -(n - 1) * dx / 2, -(n - 1) * dx / 2, gap, st)
  best = huge(1.0_real64)
  do r = 1, repeats
    call system_clock(t0, rate)
    call solve_normal(gap%h, dx, dx, 1.0_real64, opt, res, st, normal_force=1.0_real64)
    call system_clock(t1)
    best = min(best, real(t1 - t0, real64) / rate)
  end do
  if (st%failed()) then
    print '(a)', st%message
    error stop 1
  end if
  print '(i0, 1x, i0, 1x, i0, 1x, i0, 1x, es9.2, 1x, f9.3, 1x, f9.1, 2(1x, es9.2))', n, n * n, res%iterations, &
    res%products, res%residual, &
    best, peak_mib(), res%approach / hz%approach - 1, res%pmax / hz%p0 - 1

contains

  real(real64) function peak_mib()
    integer :: u, ios, kb
    character(len=256) :: line
    peak_mib = -1
    open (newunit=u, file='/proc/self/status', status='old', action='read', iostat=ios)
    if (ios /= 0) return
    do
      read (u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (line(1:6) == 'VmHWM:') then
        read (line(7:), *) kb
        peak_mib = kb / 1024.0_real64
      end if
    end do
    close (u)
  end function peak_mib

end program normal_bench
