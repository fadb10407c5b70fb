!> Unit tests of the closed-form influence coefficients.
!>  1. The x-derivative coefficients equal a central difference of the
!>     displacement coefficients (h = 1e-5: truncation ~1e-10, cancellation
!>     ~1e-11; tolerance 1e-7 relative to the largest entry).
!>  2. Parity: xx and yy are even in x and in y (to 1e-14), xy is odd in both
!>     (to 1e-12 of xx: -nu r summed over corners at r = 12 loses ~1e-13).
!>  3. Far field: a cell far away acts as a point load 4ab K(X, Y)
!>     (relative error O((a/R)^2); at R = 200 cells 1e-4 is generous).
!>  4. The offset tables (corners shared between neighbouring offsets) equal
!>     the cell-by-cell functions at every offset of a 300 x 200 grid, to
!>     1e-12 of the own cell's entry (measured: 5e-14 and 9e-14; the corner
!>     sums of far cells cancel alike either way, the two differ only in
!>     how the corner coordinates are rounded).
program test_influence
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_influence, only: influence_t, cell_displacement, cell_displacement_x_derivative, rectangle_integral, &
                              displacement_offset_table, rectangle_offset_table
  use unit_checks, only: checker_t
  implicit none
  type(checker_t) :: t
  real(real64), parameter :: pi = acos(-1.0_real64), nu = 0.3_real64, g = 2.5_real64
  real(real64), parameter :: a = 0.6_real64, b = 0.25_real64, h = 1e-5_real64
  real(real64) :: pts(2, 6), xr, yr, scale, r, x, y
  type(influence_t) :: d, up, um, c1, c2, c3, c4
  integer :: k, i, j
  integer, parameter :: nx = 300, ny = 200
  type(influence_t), allocatable :: table(:, :)
  real(real64), allocatable :: rect(:, :)
  real(real64) :: worst(2)

  pts = reshape([0.3_real64, 0.0_real64, 1.3_real64, 0.7_real64, -2.1_real64, 0.05_real64, &
                 0.0_real64, 3.0_real64, 10.5_real64, -7.2_real64, 0.3_real64, 0.1_real64], [2, 6])
  do k = 1, size(pts, 2)
    xr = pts(1, k)
    yr = pts(2, k)
    d = cell_displacement_x_derivative(xr, yr, a, b, nu, g)
    up = cell_displacement(xr + h, yr, a, b, nu, g)
    um = cell_displacement(xr - h, yr, a, b, nu, g)
    scale = max(abs(d%xx), abs(d%xy), abs(d%yy))
    call t%check(abs(d%xx - (up%xx - um%xx) / (2 * h)) <= 1e-7_real64 * scale, 'derivative xx = central difference')
    call t%check(abs(d%xy - (up%xy - um%xy) / (2 * h)) <= 1e-7_real64 * scale, 'derivative xy = central difference')
    call t%check(abs(d%yy - (up%yy - um%yy) / (2 * h)) <= 1e-7_real64 * scale, 'derivative yy = central difference')

    c1 = cell_displacement(xr, yr, a, b, nu, g)
    c2 = cell_displacement(-xr, yr, a, b, nu, g)
    c3 = cell_displacement(xr, -yr, a, b, nu, g)
    c4 = cell_displacement(-xr, -yr, a, b, nu, g)
    call t%check(abs(c1%xx - c2%xx) <= 1e-14_real64 * abs(c1%xx) .and. abs(c1%xx - c3%xx) <= 1e-14_real64 * abs(c1%xx) &
               .and. abs(c1%yy - c4%yy) <= 1e-14_real64 * abs(c1%yy), 'xx, yy even in x and y (to round-off)')
    call t%check(abs(c1%xy + c2%xy) <= 1e-12_real64 * abs(c1%xx) .and. abs(c1%xy + c3%xy) <= 1e-12_real64 * abs(c1%xx), &
               'xy odd in x and y (to round-off)')
  end do

  x = 200 * a
  y = -130 * b
  r = hypot(x, y)
  c1 = cell_displacement(x, y, a, b, nu, g)
  call t%check(abs(c1%xx / (4 * a * b * ((1 - nu) / r + nu * x**2 / r**3) / (pi * g)) - 1) < 1e-4_real64, 'far field xx')
  call t%check(abs(c1%xy / (4 * a * b * (nu * x * y / r**3) / (pi * g)) - 1) < 1e-4_real64, 'far field xy')
  call t%check(abs(c1%yy / (4 * a * b * ((1 - nu) / r + nu * y**2 / r**3) / (pi * g)) - 1) < 1e-4_real64, 'far field yy')

  allocate (table(0:nx, 0:ny), rect(0:nx, 0:ny))
  call displacement_offset_table(nx, ny, 2 * a, 2 * b, nu, g, table)
  call rectangle_offset_table(nx, ny, 2 * a, 2 * b, rect)
  worst = 0
  do j = 0, ny
    do i = 0, nx
      c1 = cell_displacement(i * 2 * a, j * 2 * b, a, b, nu, g)
      worst(1) = max(worst(1), abs(table(i, j)%xx - c1%xx), abs(table(i, j)%xy - c1%xy), abs(table(i, j)%yy - c1%yy))
      worst(2) = max(worst(2), abs(rect(i, j) - rectangle_integral(i * 2 * a, j * 2 * b, a, b)))
    end do
  end do
  worst = worst / [table(0, 0)%xx, rect(0, 0)]
  print '(a, 2es10.2)', 'offset tables against the cell-by-cell functions, largest difference / own cell: ', worst
  call t%check(worst(1) <= 1e-12_real64, 'displacement_offset_table = cell_displacement at every offset')
  call t%check(worst(2) <= 1e-12_real64, 'rectangle_offset_table = rectangle_integral at every offset')

  call t%finish()

end program test_influence
