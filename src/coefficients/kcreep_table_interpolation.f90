!> Creep coefficients of an ellipse by interpolation in kcreep's refined
!> table (kcreep_refined_table_data, docs/accuracy.md sections 5 and 5.1), with
!> a stated relative uncertainty: the table's own (interpolated) plus an
!> estimate of the interpolation error.
!>
!> In a/b, at each tabulated nu: the cubic through the four nearest rows, on
!>   ln C against ln(a/b) (the rows Kalker chose, 0.1 to 10); its error is
!>   estimated as the larger difference to the two quadratics through three of
!>   those four rows (an interpolant of one order less; in the first and last
!>   interval only the one that interpolates there, not extrapolates).
!> In nu, between the three columns 0, 0.25, 0.5: the quadratic of 1/C
!>   (C11, C22, C23: the compliance is nearly linear in nu, the elastic kernel
!>   being linear in it), for C33 the rational (p0 + p1 nu)/(1 + q nu) through
!>   the three columns (C33 is nearly linear in 1/C at small a/b and in C at
!>   large a/b); its error is estimated as the difference to the linear
!>   interpolant (of 1/C; of C for C33) between the two nearest columns.
!> Measured (docs/accuracy.md section 5.1): leaving out each interior row and
!> interpolating it from the others, and against direct solves at nu = 0.125,
!> 0.375, these estimates bound the actual error in at least 19 of 20 cases.
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
  real(real64), parameter :: table_nu_range(2) = [refined_nu(1), refined_nu(3)]

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
    call interpolate_table(refined_ratio, refined_c, refined_u, a_over_b, nu, c, from_table, from_interpolation)
    rel_uncertainty = from_table + from_interpolation
    if (present(table_part)) table_part = from_table
    if (present(interpolation_part)) interpolation_part = from_interpolation
  end subroutine table_coefficients

  !> The interpolation itself, on any table with the refined table's layout
  !> (rows ratio(:) increasing, at least 4 unless a_over_b is a row; columns
  !> nu = 0, 0.25, 0.5): the tests leave rows out with it. a_over_b and nu
  !> must lie in the table. table_part: the table's relative uncertainty
  !> carried through the interpolation (|weights| times u/C); interpolation_part:
  !> the estimated relative interpolation error.
  pure subroutine interpolate_table(ratio, c, u, a_over_b, nu, value, table_part, interpolation_part)
    real(real64), intent(in) :: ratio(:), c(:, :, :), u(:, :, :)   !< c, u: (4, 3, size(ratio))
    real(real64), intent(in) :: a_over_b, nu
    real(real64), intent(out) :: value(4), table_part(4), interpolation_part(4)
    real(real64) :: column(4, 3), column_table(4, 3), column_error(4, 3)
    real(real64) :: by_nu(3, 4), by_nu_table(3, 4), by_nu_error(3, 4)
    integer :: k, q, at_nu

    do k = 1, 3
      call interpolate_ratio(ratio, c(:, k, :), u(:, k, :), a_over_b, column(:, k), column_table(:, k), &
                             column_error(:, k))
    end do
    at_nu = findloc(refined_nu == nu, .true., 1)
    if (at_nu > 0) then
      value = column(:, at_nu)
      table_part = column_table(:, at_nu)
      interpolation_part = column_error(:, at_nu)
      return
    end if
    by_nu = transpose(column)        ! (contiguous per coefficient)
    by_nu_table = transpose(column_table)
    by_nu_error = transpose(column_error)
    do q = 1, 4
      call interpolate_nu(q == 4, by_nu(:, q), by_nu_table(:, q), by_nu_error(:, q), nu, value(q), &
                          table_part(q), interpolation_part(q))
    end do
  end subroutine interpolate_table

  !> At one column: cubic in ln(a/b) on ln C, with the table part and the error estimate.
  pure subroutine interpolate_ratio(ratio, c, u, a_over_b, value, table_part, error)
    real(real64), intent(in) :: ratio(:), c(:, :), u(:, :)   !< c, u: (4, size(ratio))
    real(real64), intent(in) :: a_over_b
    real(real64), intent(out) :: value(4), table_part(4), error(4)
    real(real64) :: s, nodes(4), w(4), w_left(3), w_right(3), y(4), cubic
    integer :: first, m, row, q

    row = findloc(ratio == a_over_b, .true., 1)
    if (row > 0) then
      value = c(:, row)
      table_part = u(:, row) / c(:, row)
      error = 0
      return
    end if
    m = size(ratio)
    s = log(a_over_b)
    ! the four rows around a/b (the interval of a/b in the middle, but at the ends)
    first = 1
    do while (first < m - 3 .and. log(ratio(first + 2)) < s)
      first = first + 1
    end do
    nodes = log(ratio(first:first + 3))
    w = lagrange_weights(nodes, s)
    w_left = lagrange_weights(nodes(1:3), s)
    w_right = lagrange_weights(nodes(2:4), s)
    do q = 1, 4
      y = log(c(q, first:first + 3))
      cubic = sum(w * y)
      value(q) = exp(cubic)
      table_part(q) = sum(abs(w) * u(q, first:first + 3) / c(q, first:first + 3))
      ! the quadratics that interpolate at s (in an end interval, the one that would extrapolate is left out)
      error(q) = 0
      if (s <= nodes(3)) error(q) = abs(cubic - sum(w_left * y(1:3)))
      if (s >= nodes(2)) error(q) = max(error(q), abs(cubic - sum(w_right * y(2:4))))
    end do
  end subroutine interpolate_ratio

  !> Between the columns nu = 0, 0.25, 0.5: quadratic in 1/C, or (rational)
  !> (p0 + p1 nu)/(1 + q nu); the parts carried with the quadratic's weights.
  pure subroutine interpolate_nu(rational, column, column_table, column_error, nu, value, table_part, error)
    logical, intent(in) :: rational
    real(real64), intent(in) :: column(3), column_table(3), column_error(3), nu
    real(real64), intent(out) :: value, table_part, error
    real(real64) :: w(3), linear, t, z(3), q, p1
    integer :: k

    w = lagrange_weights(refined_nu, nu)
    k = merge(1, 2, nu < refined_nu(2))          ! the interval [nu_k, nu_k+1]
    t = (nu - refined_nu(k)) / (refined_nu(k + 1) - refined_nu(k))
    if (rational) then
      associate (v0 => column(1), v1 => column(2), v2 => column(3))
        ! through (0, v0), (1/4, v1), (1/2, v2); the quadratic of C where that has a pole in [0, 1/2]
        value = sum(w * column)
        if (v2 /= v1) then
          q = 2 * (2 * v1 - v0 - v2) / (v2 - v1)
          p1 = 4 * (v1 - v0) + v1 * q
          if (1 + q * refined_nu(3) > 0) value = (v0 + p1 * nu) / (1 + q * nu)
        end if
      end associate
      linear = (1 - t) * column(k) + t * column(k + 1)
      error = abs(value - linear) / abs(value)
      table_part = sum(abs(w) * column * column_table) / abs(value)
      error = error + sum(abs(w) * column * column_error) / abs(value)
    else
      z = 1 / column
      value = 1 / sum(w * z)
      linear = (1 - t) * z(k) + t * z(k + 1)
      error = abs(sum(w * z) - linear) * value
      table_part = sum(abs(w) * z * column_table) * value
      error = error + sum(abs(w) * z * column_error) * value
    end if
  end subroutine interpolate_nu

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
