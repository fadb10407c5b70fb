!> Kalker's creep coefficients of the linear theory for elliptic patches
!> (Kalker 1990, table E.3; data/kalker-table-E3.dat), interpolated:
!>  - in a/b: cubic Lagrange through the four nearest rows, on ln C against
!>    ln(a/b) (smooth over the whole table, where C spans a factor of 40);
!>  - in nu: the quadratic through nu = 0, 0.25, 0.5;
!>  - outside 0.1 <= a/b <= 10: Kalker's asymptotes for a << b and a >> b.
!> The table has three significant digits; so has anything read from it.
module kcreep_kalker_table
  use, intrinsic :: iso_fortran_env, only: real64
  implicit none
  private
  public :: kalker_coefficients, table_ratio, table_c11, table_c22, table_c23, n_rows

  integer, parameter :: n_rows = 19
  real(real64), parameter :: pi = acos(-1.0_real64)
  real(real64), parameter :: table_nu(3) = [0.0_real64, 0.25_real64, 0.5_real64]
  ! Rows in order of increasing a/b; a/b of each row:
  real(real64), parameter :: table_ratio(n_rows) = [ &
    0.1_real64, 0.2_real64, 0.3_real64, 0.4_real64, 0.5_real64, &
    0.6_real64, 0.7_real64, 0.8_real64, 0.9_real64, 1.0_real64, &
    1/0.9_real64, 1/0.8_real64, 1/0.7_real64, 1/0.6_real64, 1/0.5_real64, &
    1/0.4_real64, 1/0.3_real64, 1/0.2_real64, 1/0.1_real64]
  real(real64), parameter :: table_c11(3, n_rows) = reshape([ &
    2.51_real64, 3.31_real64, 4.85_real64, &
    2.59_real64, 3.37_real64, 4.81_real64, &
    2.68_real64, 3.44_real64, 4.80_real64, &
    2.78_real64, 3.53_real64, 4.82_real64, &
    2.88_real64, 3.62_real64, 4.83_real64, &
    2.98_real64, 3.72_real64, 4.91_real64, &
    3.09_real64, 3.81_real64, 4.97_real64, &
    3.19_real64, 3.91_real64, 5.05_real64, &
    3.29_real64, 4.01_real64, 5.12_real64, &
    3.40_real64, 4.12_real64, 5.20_real64, &
    3.51_real64, 4.22_real64, 5.30_real64, &
    3.65_real64, 4.36_real64, 5.42_real64, &
    3.82_real64, 4.54_real64, 5.58_real64, &
    4.06_real64, 4.78_real64, 5.80_real64, &
    4.37_real64, 5.10_real64, 6.11_real64, &
    4.84_real64, 5.57_real64, 6.57_real64, &
    5.57_real64, 6.34_real64, 7.34_real64, &
    6.96_real64, 7.78_real64, 8.82_real64, &
    10.7_real64, 11.7_real64, 12.9_real64], [3, n_rows])
  real(real64), parameter :: table_c22(3, n_rows) = reshape([ &
    2.51_real64, 2.52_real64, 2.53_real64, &
    2.59_real64, 2.63_real64, 2.66_real64, &
    2.68_real64, 2.75_real64, 2.81_real64, &
    2.78_real64, 2.88_real64, 2.98_real64, &
    2.88_real64, 3.01_real64, 3.14_real64, &
    2.98_real64, 3.14_real64, 3.31_real64, &
    3.09_real64, 3.28_real64, 3.48_real64, &
    3.19_real64, 3.41_real64, 3.65_real64, &
    3.29_real64, 3.54_real64, 3.82_real64, &
    3.40_real64, 3.67_real64, 3.98_real64, &
    3.51_real64, 3.81_real64, 4.16_real64, &
    3.65_real64, 3.99_real64, 4.39_real64, &
    3.82_real64, 4.21_real64, 4.67_real64, &
    4.06_real64, 4.50_real64, 5.04_real64, &
    4.37_real64, 4.90_real64, 5.56_real64, &
    4.84_real64, 5.48_real64, 6.31_real64, &
    5.57_real64, 6.40_real64, 7.51_real64, &
    6.96_real64, 8.14_real64, 9.79_real64, &
    10.7_real64, 12.8_real64, 16.0_real64], [3, n_rows])
  real(real64), parameter :: table_c23(3, n_rows) = reshape([ &
    0.334_real64, 0.473_real64, 0.731_real64, &
    0.483_real64, 0.603_real64, 0.809_real64, &
    0.607_real64, 0.715_real64, 0.889_real64, &
    0.720_real64, 0.823_real64, 0.977_real64, &
    0.827_real64, 0.929_real64, 1.07_real64, &
    0.930_real64, 1.03_real64, 1.18_real64, &
    1.03_real64, 1.14_real64, 1.29_real64, &
    1.13_real64, 1.25_real64, 1.40_real64, &
    1.23_real64, 1.36_real64, 1.51_real64, &
    1.33_real64, 1.47_real64, 1.63_real64, &
    1.44_real64, 1.59_real64, 1.77_real64, &
    1.58_real64, 1.75_real64, 1.94_real64, &
    1.76_real64, 1.95_real64, 2.18_real64, &
    2.01_real64, 2.23_real64, 2.50_real64, &
    2.35_real64, 2.62_real64, 2.96_real64, &
    2.88_real64, 3.24_real64, 3.70_real64, &
    3.79_real64, 4.32_real64, 5.01_real64, &
    5.72_real64, 6.63_real64, 7.89_real64, &
    12.2_real64, 14.6_real64, 18.0_real64], [3, n_rows])

contains

  !> (C11, C22, C23) of Kalker's linear theory for an ellipse with semi-axis
  !> a along the rolling direction, b lateral, and Poisson's ratio nu in [0, 0.5].
  pure function kalker_coefficients(a_over_b, nu) result(c)
    real(real64), intent(in) :: a_over_b, nu
    real(real64) :: c(3)

    if (a_over_b < table_ratio(1)) then
      c = narrow_asymptote(a_over_b, nu)
    else if (a_over_b > table_ratio(n_rows)) then
      c = long_asymptote(1 / a_over_b, nu)
    else
      c = [table_value(table_c11, a_over_b, nu), table_value(table_c22, a_over_b, nu), &
           table_value(table_c23, a_over_b, nu)]
    end if
  end function kalker_coefficients

  !> One coefficient inside the table: in a/b at each tabulated nu, then in nu.
  pure real(real64) function table_value(table, a_over_b, nu) result(v)
    real(real64), intent(in) :: table(3, n_rows), a_over_b, nu
    real(real64) :: at_nu(3)
    integer :: k
    do k = 1, 3
      at_nu(k) = interpolate_ratio(table(k, :), a_over_b)
    end do
    v = quadratic_in_nu(at_nu, nu)
  end function table_value

  !> Cubic Lagrange interpolation of ln(values) in ln(a/b) over the 4 nearest rows.
  pure real(real64) function interpolate_ratio(values, a_over_b) result(v)
    real(real64), intent(in) :: values(n_rows), a_over_b
    real(real64) :: s, nodes(4), weight
    integer :: first, i, j

    s = log(a_over_b)
    first = 1
    do while (first < n_rows - 3 .and. log(table_ratio(first + 2)) < s)
      first = first + 1
    end do
    nodes = log(table_ratio(first:first + 3))
    v = 0
    do i = 1, 4
      weight = 1
      do j = 1, 4
        if (j /= i) weight = weight * (s - nodes(j)) / (nodes(i) - nodes(j))
      end do
      v = v + weight * log(values(first + i - 1))
    end do
    v = exp(v)
  end function interpolate_ratio

  pure real(real64) function quadratic_in_nu(values, nu) result(v)
    real(real64), intent(in) :: values(3), nu
    real(real64) :: weight
    integer :: i, j
    v = 0
    do i = 1, 3
      weight = 1
      do j = 1, 3
        if (j /= i) weight = weight * (nu - table_nu(j)) / (table_nu(i) - table_nu(j))
      end do
      v = v + weight * values(i)
    end do
  end function quadratic_in_nu

  !> a << b, g = a/b.
  pure function narrow_asymptote(g, nu) result(c)
    real(real64), intent(in) :: g, nu
    real(real64) :: c(3)
    c(1) = pi**2 / (4 * (1 - nu))
    c(2) = pi**2 / 4
    c(3) = pi * sqrt(g) / (3 * (1 - nu)) * (1 + nu * (log(16 / g) - 5))
  end function narrow_asymptote

  !> a >> b, g = b/a.
  pure function long_asymptote(g, nu) result(c)
    real(real64), intent(in) :: g, nu
    real(real64) :: c(3), el
    el = log(16 / g**2)
    c(1) = 2 * pi / ((el - 2 * nu) * g) * (1 + (3 - log(4.0_real64)) / (el - 2 * nu))
    c(2) = 2 * pi / g * (1 + (1 - nu) * (3 - log(4.0_real64)) / ((1 - nu) * el + 2 * nu)) &
           / ((1 - nu) * el + 2 * nu)
    c(3) = 2 * pi / (3 * g**1.5_real64 * ((1 - nu) * el - 2 + 4 * nu))
  end function long_asymptote

end module kcreep_kalker_table
