!> The refined table's interpolation (kcreep_table_interpolation), checked
!> against what it claims:
!>  - at every row and column the table's value comes back exactly, with the
!>    table's own u/C as the uncertainty and no interpolation error;
!>  - leave-one-out in a/b: each interior row left out, interpolated from the
!>    others at its own a/b and nu, for C11 C22 C23 C33: the stated
!>    uncertainty (table part + interpolation part) must bound |interpolated /
!>    table - 1| in at least 19 of 20 cases per coefficient;
!>  - in nu: one grid (32 cells across the shorter axis) solved at nu = 0,
!>    1/16, ... 1/2; interpolated from the table's columns 0, 0.125, ... 0.5
!>    to the four between, the interpolation part must bound the actual difference in at
!>    least 19 of 20 cases (the nu dependence of one grid is that of the
!>    continuum to well within the differences measured; the same grid at
!>    every nu removes the staircase noise);
!>  - outside the table: refused with a message naming a/b or nu.
!>
!>   test_table_interpolation [all] [levels]
!> 'all': the nu check at all rows instead of 5 and the per-case lines
!> (the tables of docs/accuracy.md, "The refined table of ellipses").
program test_table_interpolation
  use, intrinsic :: iso_fortran_env, only: real64, output_unit
  use kcreep, only: problem_t, result_t, default_problem, ellipse_patch, kcreep_solve, status_t
  use kcreep_refine_estimate, only: ellipse_level_grid
  use kcreep_refined_table_data, only: refined_rows, refined_nu, refined_ratio, refined_c, refined_u
  use kcreep_table_interpolation, only: table_coefficients, interpolate_table
  use unit_checks, only: checker_t
  implicit none
  type(checker_t) :: t
  character(len=3), parameter :: names(4) = ['C11', 'C22', 'C23', 'C33']
  !> rows of the quick nu check: both ends (a/b 0.1, 10), the circle and two between (0.4, 2.5)
  integer, parameter :: quick_rows(5) = [1, 8, 20, 32, 39]
  logical :: all_rows
  character(len=16) :: arg

  all_rows = .false.
  if (command_argument_count() >= 1) then
    call get_command_argument(1, arg)
    all_rows = arg == 'all'
  end if
  call check_nodes()
  call check_leave_one_out()
  call check_refusals()
  call check_nu()
  call t%finish()

contains

  subroutine check_nodes()
    real(real64) :: c(4), rel(4), tab(4), interp(4)
    type(status_t) :: status
    integer :: row, k
    logical :: exact
    exact = .true.
    do row = 1, refined_rows
      do k = 1, size(refined_nu)
        call table_coefficients(refined_ratio(row), refined_nu(k), c, rel, status, tab, interp)
        exact = exact .and. .not. status%failed() .and. all(c == refined_c(:, k, row)) .and. &
                all(tab == refined_u(:, k, row) / refined_c(:, k, row)) .and. all(interp == 0) .and. &
                all(rel == tab)
      end do
    end do
    call t%check(exact, 'the table''s points come back exactly, uncertainty u/C, no interpolation error')
  end subroutine check_nodes

  !> Leave-one-out in a/b over the interior rows (at every nu, per coefficient).
  subroutine check_leave_one_out()
    real(real64) :: value(4), tab(4), interp(4), actual, stated, worst(4), sum_ratio(4)
    integer :: row, k, q, bounded(4), cases, by_interpolation(4)
    logical :: keep(refined_rows)
    bounded = 0
    by_interpolation = 0
    worst = 0
    sum_ratio = 0
    cases = 0
    if (all_rows) write (output_unit, '(a)') '# leave-one-out: a/b nu coefficient actual stated interpolation_part (relative)'
    do row = 2, refined_rows - 1
      keep = .true.
      keep(row) = .false.
      do k = 1, size(refined_nu)
        call interpolate_table(pack(refined_ratio, keep), refined_nu, &
                               refined_c(:, :, pack([(q, q=1, refined_rows)], keep)), &
                               refined_u(:, :, pack([(q, q=1, refined_rows)], keep)), refined_ratio(row), &
                               refined_nu(k), value, tab, interp)
        cases = cases + 1
        do q = 1, 4
          actual = abs(value(q) / refined_c(q, k, row) - 1)
          stated = tab(q) + interp(q)
          if (actual <= stated) bounded(q) = bounded(q) + 1
          if (actual <= interp(q)) by_interpolation(q) = by_interpolation(q) + 1
          worst(q) = max(worst(q), actual / stated)
          sum_ratio(q) = sum_ratio(q) + actual
          if (all_rows) write (output_unit, '(f8.4, f6.2, 1x, a, 3es11.3)') refined_ratio(row), refined_nu(k), &
            names(q), actual, stated, interp(q)
        end do
      end do
    end do
    do q = 1, 4
      write (output_unit, '(a, i0, a, i0, a, f6.3, a, es9.2, a, i0)') 'leave-one-out '//names(q)//': bounded in ', &
        bounded(q), ' of ', cases, ', largest actual/stated ', worst(q), ', mean actual ', sum_ratio(q) / cases, &
        ', by the interpolation part alone in ', by_interpolation(q)
      ! the claim: at least 19 of 20 (measured: docs/accuracy.md, "The refined table of ellipses")
      call t%check(20 * bounded(q) >= 19 * cases, 'leave-one-out in a/b: the stated uncertainty of '//names(q)// &
                   ' bounds the actual error in at least 19 of 20 cases')
    end do
  end subroutine check_leave_one_out

  subroutine check_refusals()
    real(real64) :: c(4), rel(4)
    type(status_t) :: s1, s2, s3, s4
    call table_coefficients(12.0_real64, 0.25_real64, c, rel, s1)
    call t%check(s1%failed() .and. index(s1%message, 'a/b = 12') > 0 .and. index(s1%message, '0.1 <= a/b <= 10') > 0, &
                 'a/b = 12 refused, naming a/b and the range: '//s1%message)
    call table_coefficients(0.099_real64, 0.25_real64, c, rel, s2)
    call t%check(s2%failed() .and. index(s2%message, 'a/b = ') > 0 .and. index(s2%message, '0.1 <= a/b') > 0, &
                 'a/b = 0.099 refused: '//s2%message)
    call table_coefficients(1.0_real64, 0.51_real64, c, rel, s3)
    call t%check(s3%failed() .and. index(s3%message, 'nu = 0.51') > 0 .and. index(s3%message, '0 <= nu <= 0.5') > 0, &
                 'nu = 0.51 refused, naming nu and the range: '//s3%message)
    call table_coefficients(10.0_real64, 0.5_real64, c, rel, s4)
    call t%check(.not. s4%failed() .and. c(1) == refined_c(1, size(refined_nu), refined_rows), &
                 'a/b = 10, nu = 0.5 (the corner) taken')
  end subroutine check_refusals

  !> nu: one grid per a/b at nine nu; the interpolation from the table's five columns to the four between.
  subroutine check_nu()
    integer, parameter :: cells = 32
    real(real64) :: nus(9), solved(4, 9), cv(4, 5, 1), uv(4, 5, 1), value(4), tab(4), interp(4), actual, worst(4)
    integer :: i, row, j, q, bounded(4), cases
    integer, allocatable :: rows(:)
    nus = [(j / 16.0_real64, j=0, 8)]
    if (all_rows) then
      rows = [(i, i=1, refined_rows)]
      write (output_unit, '(a)') '# nu check: a/b nu coefficient actual stated (relative)'
    else
      rows = quick_rows
    end if
    bounded = 0
    worst = 0
    cases = 0
    do i = 1, size(rows)
      row = rows(i)
      do j = 1, 9
        solved(:, j) = solve_ellipse(refined_ratio(row), nus(j), cells)
      end do
      cv(:, :, 1) = solved(:, 1:9:2)
      uv = 0
      do j = 2, 8, 2
        call interpolate_table(refined_ratio(row:row), nus(1:9:2), cv, uv, refined_ratio(row), nus(j), value, tab, &
                               interp)
        cases = cases + 1
        do q = 1, 4
          actual = abs(value(q) / solved(q, j) - 1)
          if (actual <= interp(q)) bounded(q) = bounded(q) + 1
          worst(q) = max(worst(q), actual)
          if (all_rows) write (output_unit, '(f8.4, f7.3, 1x, a, 2es11.3)') refined_ratio(row), nus(j), names(q), &
            actual, interp(q)
        end do
      end do
    end do
    do q = 1, 4
      write (output_unit, '(a, i0, a, i0, a, es9.2)') 'nu interpolation '//names(q)//': bounded in ', bounded(q), &
        ' of ', cases, ', largest actual ', worst(q)
    end do
    ! the claim: at least 19 of 20 over all coefficients (measured at all rows: docs/accuracy.md, "The refined table of ellipses")
    call t%check(20 * sum(bounded) >= 19 * 4 * cases, 'nu: the interpolation error estimate bounds the actual '// &
                 'error in at least 19 of 20 cases')
  end subroutine check_nu

  !> C11 C22 C23 C33 of the ellipse a/b = ratio, c = 1 on the near-square grid, as solved.
  function solve_ellipse(ratio, nu, cells) result(c4)
    real(real64), intent(in) :: ratio, nu
    integer, intent(in) :: cells
    real(real64) :: c4(4)
    type(problem_t) :: problem
    type(result_t) :: result
    type(status_t) :: status
    integer :: mx, my
    problem = default_problem()
    problem%nu = nu
    ! this grid as given, unjudged (the library's default would choose the grids)
    problem%target_error = 0
    problem%refine_grid = .false.
    problem%estimate_error = .false.
    call ellipse_level_grid(sqrt(ratio), 1 / sqrt(ratio), cells, mx, my)
    call ellipse_patch(sqrt(ratio), 1 / sqrt(ratio), mx, my, problem%patch, status)
    call kcreep_solve(problem, result, status)
    call t%check(.not. status%failed(), 'solve a/b = '//trim(real_text(ratio))//', nu = '//trim(real_text(nu)))
    c4 = [result%cn, result%f(3, 3) / (result%g * result%c**4)]
  end function solve_ellipse

  function real_text(x) result(s)
    real(real64), intent(in) :: x
    character(len=16) :: s
    write (s, '(g0.4)') x
  end function real_text

end program test_table_interpolation
