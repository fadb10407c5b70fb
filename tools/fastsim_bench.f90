!> kcreep_fastsim_bench: time of a FASTSIM creep curve (100 creepage points by default) on an
!> n x n grid (100 by default): the unit circle with Hertz pressure and Kalker's L, combined
!> creepages from full adhesion to full slip; best and median of 21 repetitions.
!>   kcreep_fastsim_bench [N [POINTS]]
program fastsim_bench
  use, intrinsic :: iso_fortran_env, only: real64, int64, output_unit
  use kcreep_fastsim_forces, only: fastsim_forces, fastsim_result_t, flexibility_weighted, flexibility_aligned, &
                                   flexibility_rule_name
  use kcreep_pressure_models, only: hertz_pressure
  use kcreep_equivalent_ellipse, only: ellipse_flexibilities
  use kcreep_kalker_table, only: kalker_coefficients
  use kcreep_bench_support, only: integer_argument, sorted
  implicit none
  integer, parameter :: repeats = 21
  integer :: n, points, ix, iy, k, r, rule
  logical, allocatable :: inside(:, :)
  real(real64), allocatable :: pn(:, :)
  real(real64) :: dx, x0, flex(3), creep(3), times(repeats), checksum, s
  integer(int64) :: t0, t1, rate
  type(fastsim_result_t) :: res

  n = integer_argument(1, default=100)
  points = integer_argument(2, default=100)
  dx = 2.0_real64 / n
  x0 = -1 + dx / 2
  allocate (inside(n, n))
  do iy = 1, n
    do ix = 1, n
      inside(ix, iy) = (x0 + (ix - 1) * dx)**2 + (x0 + (iy - 1) * dx)**2 <= 1
    end do
  end do
  pn = hertz_pressure(inside, dx, dx, x0, x0, 1.0_real64, 1.0_real64, 1.0_real64)
  flex = ellipse_flexibilities(1.0_real64, 1.0_real64, kalker_coefficients(1.0_real64, 0.25_real64), 1.0_real64)
  call system_clock(count_rate=rate)
  do rule = flexibility_weighted, flexibility_aligned      ! weighted, separate, aligned
    do r = 1, repeats
      checksum = 0
      call system_clock(t0)
      do k = 1, points
        s = 1e-3_real64 * 10**(3.0_real64 * (k - 1) / max(points - 1, 1))   ! 1e-3 .. 1: adhesion to full slip
        creep = s * [0.3_real64, 0.2_real64, 0.1_real64]
        call fastsim_forces(inside, pn, dx, dx, x0, x0, flex, 0.3_real64, creep, 1.0_real64, rule, res)
        checksum = checksum + res%fx + res%fy
      end do
      call system_clock(t1)
      times(r) = real(t1 - t0, real64) / rate
    end do
    times = sorted(times)
    write (output_unit, '(a, i0, a, i0, a, i0, 2a, f9.5, a, f9.5, a, es10.3, a, es12.5)') 'grid ', n, ' x ', n, &
      ', ', points, ' points, rule ', flexibility_rule_name(rule)// &
      ': best ', times(1), ' s, median ', times((repeats + 1) / 2), ' s, per cell and point ', &
      times(1) / (points * count(inside)), ' s; checksum ', checksum
  end do

contains


end program fastsim_bench
