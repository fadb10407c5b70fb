!> Creep coefficients of an ellipse by interpolation in kcreep's refined
!> table (kcreep_refined_table_data, docs/accuracy.md, "The refined table of ellipses"), with
!> a stated relative uncertainty: the table's own (interpolated) plus an
!> estimate of the interpolation error.
!>
!> In a/b, at each tabulated nu: the cubic through the four nearest rows on
!>   ln C against ln(a/b) (rows at g = 0.1, 0.125, 0.15, 0.2, 0.25, ... 1, g = a/b or b/a);
!> in nu, between the columns (0, 0.125, 0.25, 0.375, 0.5): the cubic through
!>   the four nearest on 1/C (the compliance is nearly linear in nu, the
!>   elastic kernel being linear in it).
!> Each interpolation error is estimated as the larger difference to the two
!> quadratics through three of the four nodes (an interpolant of one order
!> less; in an end interval only the one that interpolates there). Measured
!> (docs/accuracy.md, "The refined table of ellipses"): leaving out each interior row and
!> interpolating it from the others, and against direct solves between the
!> columns, these estimates bound the actual error in at least 19 of 20 cases.
!>
!> At a row and a column the table's value is returned exactly.
module kcreep_table_interpolation
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: rtoa
  use kcreep_refined_table_data, only: refined_rows, refined_nu, refined_ratio, refined_c, refined_u
  implicit none
  private
  public :: table_coefficients, interpolate_table, table_ratio_range, table_nu_range

  !> The range the table covers: a/b (Kalker's 0.1 to 10) and nu.
  real(real64), parameter :: table_ratio_range(2) = [refined_ratio(1), refined_ratio(refined_rows)]
  real(real64), parameter :: table_nu_range(2) = [refined_nu(1), refined_nu(size(refined_nu))]

contains

  !> C11, C22, C23, C33 of an ellipse with a/b = a_over_b and Poisson's ratio
  !> nu from the refined table; rel_uncertainty: the relative uncertainty of
  !> each (table + interpolation). Outside the table: an error naming the value.
  pure subroutine table_coefficients(a_over_b, nu, c, rel_uncertainty, status, table_part, interpolation_part)
    real(real64), intent(in) :: a_over_b, nu
    real(real64), intent(out) :: c(4), rel_uncertainty(4)
    type(status_t), intent(inout) :: status
    real(real64), intent(out), optional :: table_part(4), interpolation_part(4)
    real(real64) :: from_table(4), from_interpolation(4)

    c = 0
    rel_uncertainty = 0
    if (.not. (a_over_b >= table_ratio_range(1) .and. a_over_b <= table_ratio_range(2))) then
      call fail(status, exit_bad_input, 'method = ''table'': a/b = '//rtoa(a_over_b)// &
                ' (allowed: 0.1 <= a/b <= 10, the refined table''s range; other ellipses need a solve)')
      return
    end if
    if (.not. (nu >= table_nu_range(1) .and. nu <= table_nu_range(2))) then
      call fail(status, exit_bad_input, 'method = ''table'': nu = '//rtoa(nu)//' (allowed: 0 <= nu <= 0.5)')
      return
    end if
    call interpolate_table(refined_ratio, refined_nu, refined_c, refined_u, a_over_b, nu, c, from_table, &
                           from_interpolation)
    rel_uncertainty = from_table + from_interpolation
    if (present(table_part)) table_part = from_table
    if (present(interpolation_part)) interpolation_part = from_interpolation
  end subroutine table_coefficients

  !> The interpolation itself, on any table with the refined table's layout
  !> (rows ratio(:) increasing, columns nus(:) increasing, each at least 3 long
  !> unless a_over_b is a row or nu a column): the tests leave rows out with it.
  !> a_over_b and nu must lie in the table. table_part: the table's relative
  !> uncertainty carried through the interpolation (|weights| times u/C);
  !> interpolation_part: the estimated relative interpolation error.
  pure subroutine interpolate_table(ratio, nus, c, u, a_over_b, nu, value, table_part, interpolation_part)
    real(real64), intent(in) :: ratio(:), nus(:)
    real(real64), intent(in) :: c(:, :, :), u(:, :, :)   !< c, u: (4, size(nus), size(ratio))
    real(real64), intent(in) :: a_over_b, nu
    real(real64), intent(out) :: value(4), table_part(4), interpolation_part(4)
    real(real64) :: column(4, size(nus)), column_table(4, size(nus)), column_error(4, size(nus))
    real(real64) :: w(4), y
    integer :: k, q, at_nu, first, width

    do k = 1, size(nus)
      call interpolate_ratio(ratio, c(:, k, :), u(:, k, :), a_over_b, column(:, k), column_table(:, k), &
                             column_error(:, k))
    end do
    at_nu = findloc(nus == nu, .true., 1)
    if (at_nu > 0) then
      value = column(:, at_nu)
      table_part = column_table(:, at_nu)
      interpolation_part = column_error(:, at_nu)
      return
    end if
    do q = 1, 4
      ! on 1/C: relative uncertainties of 1/C are those of C
      call nearest_window(nus, nu, first, width)
      call interpolate_nodes(nus(first:first + width - 1), 1 / column(q, first:first + width - 1), nu, y, w, &
                             interpolation_part(q))
      value(q) = 1 / y
      interpolation_part(q) = interpolation_part(q) * value(q)
      table_part(q) = 0
      do k = 1, width
        associate (j => first + k - 1)
          table_part(q) = table_part(q) + abs(w(k)) * column_table(q, j) / column(q, j) * value(q)
          interpolation_part(q) = interpolation_part(q) + abs(w(k)) * column_error(q, j) / column(q, j) * value(q)
        end associate
      end do
    end do
  end subroutine interpolate_table

  !> At one column: cubic in ln(a/b) on ln C, with the table part and the error estimate.
  pure subroutine interpolate_ratio(ratio, c, u, a_over_b, value, table_part, error)
    real(real64), intent(in) :: ratio(:), c(:, :), u(:, :)   !< c, u: (4, size(ratio))
    real(real64), intent(in) :: a_over_b
    real(real64), intent(out) :: value(4), table_part(4), error(4)
    real(real64) :: w(4), y
    integer :: row, q, first, width, k

    row = findloc(ratio == a_over_b, .true., 1)
    if (row > 0) then
      value = c(:, row)
      table_part = u(:, row) / c(:, row)
      error = 0
      return
    end if
    ! (the window is the same in a/b as in ln(a/b))
    call nearest_window(ratio, a_over_b, first, width)
    do q = 1, 4
      call interpolate_nodes(log(ratio(first:first + width - 1)), log(c(q, first:first + width - 1)), &
                             log(a_over_b), y, w, error(q))
      value(q) = exp(y)
      table_part(q) = 0
      do k = 1, width
        table_part(q) = table_part(q) + abs(w(k)) * u(q, first + k - 1) / c(q, first + k - 1)
      end do
    end do
  end subroutine interpolate_ratio

  !> The four nodes nearest x (the interval of x in the middle, but at the
  !> ends; three if there are only three): nodes(first:first + width - 1).
  pure subroutine nearest_window(nodes, x, first, width)
    real(real64), intent(in) :: nodes(:), x
    integer, intent(out) :: first, width
    integer :: m
    m = size(nodes)
    width = min(4, m)
    first = 1
    do while (first < m - width + 1 .and. nodes(first + width / 2) < x)
      first = first + 1
    end do
  end subroutine nearest_window

  !> Lagrange interpolation of y(nodes) at x through all the (three or four)
  !> nodes: value, the weights w(1:size(nodes)), and the error estimate, the
  !> larger difference to the interpolants of one order less through all but
  !> the first or all but the last node (only the one that interpolates at x:
  !> in an end interval the other would extrapolate).
  pure subroutine interpolate_nodes(nodes, y, x, value, w, error)
    real(real64), intent(in) :: nodes(:), y(:), x
    real(real64), intent(out) :: value, w(4)
    real(real64), intent(out) :: error
    integer :: last
    last = size(nodes)
    w = 0
    w(1:last) = lagrange_weights(nodes, x)
    value = sum(w(1:last) * y)
    error = 0
    if (x <= nodes(last - 1)) error = abs(value - sum(lagrange_weights(nodes(1:last - 1), x) * y(1:last - 1)))
    if (x >= nodes(2)) error = max(error, abs(value - sum(lagrange_weights(nodes(2:last), x) * y(2:last))))
  end subroutine interpolate_nodes

  !> Lagrange weights of the nodes at x (exactly 1 and 0 at a node).
  pure function lagrange_weights(nodes, x) result(w)
    real(real64), intent(in) :: nodes(:), x
    real(real64) :: w(size(nodes))
    integer :: i, j
    do i = 1, size(nodes)
      w(i) = 1
      do j = 1, size(nodes)
        if (j /= i) w(i) = w(i) * (x - nodes(j)) / (nodes(i) - nodes(j))
      end do
    end do
  end function lagrange_weights

end module kcreep_table_interpolation
