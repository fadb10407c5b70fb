!> Closed-form influence coefficients of a uniformly loaded rectangular cell
!> on the tangential displacement difference of two quasi-identical
!> half-spaces (Boussinesq-Cerruti, tangential part).
!>
!> Kernel, with X = x - x', Y = y - y', r = sqrt(X^2 + Y^2):
!>   u_x = 1/(pi G) Int [(1-nu)/r + nu X^2/r^3] p_x + [nu X Y/r^3] p_y
!>   u_y = 1/(pi G) Int [nu X Y/r^3] p_x + [(1-nu)/r + nu Y^2/r^3] p_y
!> A cell has half sizes (a, b); (xr, yr) is the field point relative to the
!> cell centre. All results carry the factor 1/(pi G): they are the exact
!> response to a unit traction on the cell.
module kcreep_influence
  use, intrinsic :: iso_fortran_env, only: real64
  implicit none
  private
  public :: influence_t, cell_displacement, cell_displacement_x_derivative, rectangle_integral
  public :: displacement_offset_table, rectangle_offset_table

  real(real64), parameter :: pi = acos(-1.0_real64)

  !> The three distinct entries of the symmetric 2 x 2 influence block.
  type :: influence_t
    real(real64) :: xx = 0, xy = 0, yy = 0
  end type influence_t

contains

  !> Displacement difference at (xr, yr) from unit traction on the cell:
  !> double integral of the kernel over the rectangle, by the corner rule on
  !> the antiderivatives F(X, Y) with d2F/dXdY = kernel:
  !>   1/r    -> X asinh(Y/|X|) + Y asinh(X/|Y|)
  !>   X^2/r^3 -> Y asinh(X/|Y|),   Y^2/r^3 -> X asinh(Y/|X|),   XY/r^3 -> -r
  !> (the X ln|X| and Y ln|Y| parts of the true antiderivatives cancel in the corner sum).
  elemental type(influence_t) function cell_displacement(xr, yr, a, b, nu, g) result(c)
    real(real64), intent(in) :: xr, yr, a, b, nu, g
    real(real64) :: xs(2), ys(2), sgn, x, y, r, xlog, ylog
    integer :: i, j

    xs = [xr + a, xr - a]
    ys = [yr + b, yr - b]
    do j = 1, 2
      do i = 1, 2
        sgn = merge(1.0_real64, -1.0_real64, i == j)
        x = xs(i)
        y = ys(j)
        r = hypot(x, y)
        xlog = x_asinh_y_over_x(x, y)
        ylog = x_asinh_y_over_x(y, x)
        c%xx = c%xx + sgn * ((1 - nu) * xlog + ylog)
        c%yy = c%yy + sgn * (xlog + (1 - nu) * ylog)
        c%xy = c%xy - sgn * nu * r
      end do
    end do
    c%xx = c%xx / (pi * g)
    c%xy = c%xy / (pi * g)
    c%yy = c%yy / (pi * g)
  end function cell_displacement

  !> x-derivative at (xr, yr) of the displacement difference from unit traction
  !> on the cell. d/dx of the integral over x' is the kernel on the two edges
  !> x' = +-a, integrated over y' in closed form:
  !>   1/r -> asinh(Y/|X|),  X^2/r^3 -> Y/r,  XY/r^3 -> -X/r,  Y^2/r^3 -> asinh(Y/|X|) - Y/r.
  !> Undefined on the edges themselves (xr = +-a): callers keep away from them.
  elemental type(influence_t) function cell_displacement_x_derivative(xr, yr, a, b, nu, g) result(c)
    real(real64), intent(in) :: xr, yr, a, b, nu, g
    real(real64) :: xs(2), ys(2), sgn, x, y, r, s
    integer :: i, j

    xs = [xr + a, xr - a]
    ys = [yr + b, yr - b]
    do j = 1, 2
      do i = 1, 2
        sgn = merge(1.0_real64, -1.0_real64, i == j)
        x = xs(i)
        y = ys(j)
        r = hypot(x, y)
        s = asinh(y / abs(x))
        c%xx = c%xx + sgn * ((1 - nu) * s + nu * y / r)
        c%yy = c%yy + sgn * (s - nu * y / r)
        c%xy = c%xy - sgn * nu * x / r
      end do
    end do
    c%xx = c%xx / (pi * g)
    c%xy = c%xy / (pi * g)
    c%yy = c%yy / (pi * g)
  end function cell_displacement_x_derivative

  !> Int Int dx' dy' / r over the rectangle |x'| <= a, |y'| <= b, seen from
  !> (xr, yr) relative to its centre (r = distance to (x', y')).
  elemental real(real64) function rectangle_integral(xr, yr, a, b) result(s)
    real(real64), intent(in) :: xr, yr, a, b
    real(real64) :: xs(2), ys(2)
    integer :: i, j
    xs = [xr + a, xr - a]
    ys = [yr + b, yr - b]
    s = 0
    do j = 1, 2
      do i = 1, 2
        s = s + merge(1.0_real64, -1.0_real64, i == j) * (x_asinh_y_over_x(xs(i), ys(j)) + x_asinh_y_over_x(ys(j), xs(i)))
      end do
    end do
  end function rectangle_integral

  !> cell_displacement at every centre offset (i dx, j dy), i = 0..nx,
  !> j = 0..ny, of cells dx x dy. Neighbouring offsets share the corners of
  !> the corner rule, so the antiderivatives are taken once per corner, at
  !> ((k - 1/2) dx, (l - 1/2) dy): a quarter of the transcendental calls
  !> of cell_displacement, which dominate building a level's tables.
  pure subroutine displacement_offset_table(nx, ny, dx, dy, nu, g, table)
    integer, intent(in) :: nx, ny
    real(real64), intent(in) :: dx, dy, nu, g
    type(influence_t), intent(out) :: table(0:nx, 0:ny)
    real(real64), allocatable :: xlog(:, :), ylog(:, :), r(:, :)
    real(real64) :: x, y, sx, sy
    integer :: i, j
    allocate (xlog(0:nx + 1, 0:ny + 1), ylog(0:nx + 1, 0:ny + 1), r(0:nx + 1, 0:ny + 1))
    do j = 0, ny + 1
      y = (j - 0.5_real64) * dy
      do i = 0, nx + 1
        x = (i - 0.5_real64) * dx
        xlog(i, j) = x_asinh_y_over_x(x, y)
        ylog(i, j) = x_asinh_y_over_x(y, x)
        r(i, j) = hypot(x, y)
      end do
    end do
    do j = 0, ny
      do i = 0, nx
        sx = corner_sum(xlog, i, j)
        sy = corner_sum(ylog, i, j)
        table(i, j)%xx = ((1 - nu) * sx + sy) / (pi * g)
        table(i, j)%yy = (sx + (1 - nu) * sy) / (pi * g)
        table(i, j)%xy = -nu * corner_sum(r, i, j) / (pi * g)
      end do
    end do
  end subroutine displacement_offset_table

  !> rectangle_integral (a = dx/2, b = dy/2) at every centre offset (i dx,
  !> j dy), i = 0..nx, j = 0..ny, with the corners shared as in
  !> displacement_offset_table.
  pure subroutine rectangle_offset_table(nx, ny, dx, dy, table)
    integer, intent(in) :: nx, ny
    real(real64), intent(in) :: dx, dy
    real(real64), intent(out) :: table(0:nx, 0:ny)
    real(real64), allocatable :: f(:, :)
    real(real64) :: x, y
    integer :: i, j
    allocate (f(0:nx + 1, 0:ny + 1))
    do j = 0, ny + 1
      y = (j - 0.5_real64) * dy
      do i = 0, nx + 1
        x = (i - 0.5_real64) * dx
        f(i, j) = x_asinh_y_over_x(x, y) + x_asinh_y_over_x(y, x)
      end do
    end do
    do j = 0, ny
      do i = 0, nx
        table(i, j) = corner_sum(f, i, j)
      end do
    end do
  end subroutine rectangle_offset_table

  !> The corner rule for the cell at offset (i, j) from antiderivative values
  !> f(k, l) at ((k - 1/2) dx, (l - 1/2) dy): the corners (i + 1/2, j + 1/2)
  !> and (i - 1/2, j - 1/2) count +, the mixed ones - (as in cell_displacement).
  pure real(real64) function corner_sum(f, i, j) result(s)
    real(real64), intent(in) :: f(0:, 0:)
    integer, intent(in) :: i, j
    s = f(i + 1, j + 1) - f(i, j + 1) - f(i + 1, j) + f(i, j)
  end function corner_sum

  !> x asinh(y/|x|), continued by 0 at x = 0.
  elemental real(real64) function x_asinh_y_over_x(x, y) result(v)
    real(real64), intent(in) :: x, y
    if (x == 0) then
      v = 0
    else
      v = x * asinh(y / abs(x))
    end if
  end function x_asinh_y_over_x

end module kcreep_influence
