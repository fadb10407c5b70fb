!> Unit tests of the Kalker table interpolation.
!>  1. The embedded table equals data/kalker-table-E3.dat (path in argv 1).
!>  2. At every table row and nu = 0, 0.25, 0.5 the interpolation returns
!>     the table value (to 1e-12: the Lagrange weights are exact there).
!>  3. Between rows the interpolant lies between its neighbours (the table
!>     is monotone in a/b) and, beyond the table, the asymptotes apply.
program test_kalker
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_kalker_table, only: kalker_coefficients, table_ratio, table_c11, table_c22, table_c23, n_rows
  use unit_checks, only: checker_t
  implicit none
  type(checker_t) :: t
  real(real64), parameter :: nus(3) = [0.0_real64, 0.25_real64, 0.5_real64], pi = acos(-1.0_real64)
  real(real64) :: c(3), lo(3), hi(3), g, values(9), mid
  character(len=512) :: path, line
  character(len=8) :: kind
  integer :: unit, ios, row, k

  call get_command_argument(1, path)
  open (newunit=unit, file=trim(path), status='old', action='read', iostat=ios)
  call t%check(ios == 0, 'table file opens')
  row = 0
  do while (ios == 0)
    read (unit, '(a)', iostat=ios) line
    if (ios /= 0) exit
    if (line(1:1) == '#' .or. len_trim(line) == 0) cycle
    row = row + 1
    kind = line(1:3)   ! 'a/b' or 'b/a': a slash would end a list-directed read
    read (line(4:), *) g, values
    call t%check(abs(merge(g, 1 / g, kind == 'a/b') - table_ratio(row)) < 1e-14_real64, 'row ratio')
    call t%check(all(values == [table_c11(:, row), table_c22(:, row), table_c23(:, row)]), 'row values')
  end do
  call t%check(row == n_rows, 'row count')

  do row = 1, n_rows
    do k = 1, 3
      c = kalker_coefficients(table_ratio(row), nus(k))
      call t%check(all(abs(c - [table_c11(k, row), table_c22(k, row), table_c23(k, row)]) <= 1e-12_real64 * c), &
                 'interpolation hits the table nodes')
    end do
  end do
  do row = 1, n_rows - 1
    mid = sqrt(table_ratio(row) * table_ratio(row + 1))
    c = kalker_coefficients(mid, 0.25_real64)
    lo = [table_c11(2, row), table_c22(2, row), table_c23(2, row)]
    hi = [table_c11(2, row + 1), table_c22(2, row + 1), table_c23(2, row + 1)]
    call t%check(all(c >= min(lo, hi) .and. c <= max(lo, hi)), 'interpolant between its neighbours')
  end do
  c = kalker_coefficients(0.01_real64, 0.25_real64)
  call t%check(abs(c(1) - pi**2 / 3) < 1e-12_real64 .and. abs(c(2) - pi**2 / 4) < 1e-12_real64, 'narrow asymptote')
  c = kalker_coefficients(0.0999_real64, 0.25_real64)
  call t%check(abs(c(1) / table_c11(2, 1) - 1) < 0.01_real64, 'asymptote meets the table at a/b = 0.1 (within 1 %)')
  c = kalker_coefficients(10.01_real64, 0.25_real64)
  call t%check(abs(c(1) / table_c11(2, n_rows) - 1) < 0.04_real64, &
             'asymptote meets the table at a/b = 10 (within 4 %: measured 3.5 %)')

  call t%finish()

end program test_kalker
