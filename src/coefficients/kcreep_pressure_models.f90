!> Normal pressure on the patch's grid for FASTSIM, when no normal solve or
!> measured pressure is at hand.
!>  - hertz_pressure: Hertz's semi-ellipsoid p = p0 sqrt(1 - (x/a)^2 - (y/b)^2)
!>    (centred at the origin), on the patch cells, scaled so that the sum over
!>    the cells is Fn (the staircase patch carries the load exactly).
!>  - strip_parabolic_pressure: a MODEL for a bare mask. Each strip segment
!>    [x_t, x_l] of half length s carries p = k (s^2 - (x - x_m)^2) / s: a
!>    parabola vanishing at both ends whose peak k s grows with the segment's
!>    length, as Hertz's semi-ellipse does along a strip of an ellipse
!>    (simple non-Hertzian methods build the pressure strip by strip like
!>    this). k is fixed by Fn. It is not a solution of the normal problem.
!> The values are cell averages of the profile (exact for the parabola).
module kcreep_pressure_models
  use, intrinsic :: iso_fortran_env, only: real64
  implicit none
  private
  public :: hertz_pressure, paraboloid_pressure, strip_parabolic_pressure, scale_to_load

contains

  !> Hertz's semi-ellipsoid with semi-axes a (x), b (y) on the patch cells,
  !> sampled at the cell centres and scaled to total load fn.
  pure function hertz_pressure(inside, dx, dy, x0, y0, semi_a, semi_b, fn) result(pn)
    logical, intent(in) :: inside(:, :)
    real(real64), intent(in) :: dx, dy, x0, y0, semi_a, semi_b, fn
    real(real64) :: pn(size(inside, 1), size(inside, 2))
    real(real64), dimension(size(inside, 1), size(inside, 2)) :: x, y
    call cell_centres(dx, dy, x0, y0, x, y)
    pn = 0
    where (inside) pn = sqrt(max(0.0_real64, 1 - (x / semi_a)**2 - (y / semi_b)**2))
    pn = scale_to_load(pn, dx * dy, fn)
  end function hertz_pressure

  !> Kalker's FASTSIM pressure p = p0 (1 - (x/a)^2 - (y/b)^2) (paraboloid) on the patch cells,
  !> cell averages, scaled to total load fn: with it FASTSIM's curve of pure creepage is, strip
  !> by strip, F = mu Fn_strip (1 - (1 - u)^3) (the classical FASTSIM result).
  pure function paraboloid_pressure(inside, dx, dy, x0, y0, semi_a, semi_b, fn) result(pn)
    logical, intent(in) :: inside(:, :)
    real(real64), intent(in) :: dx, dy, x0, y0, semi_a, semi_b, fn
    real(real64) :: pn(size(inside, 1), size(inside, 2))
    real(real64), dimension(size(inside, 1), size(inside, 2)) :: x, y
    call cell_centres(dx, dy, x0, y0, x, y)
    pn = 0
    where (inside) pn = max(0.0_real64, 1 - (x**2 + dx**2 / 12) / semi_a**2 - (y**2 + dy**2 / 12) / semi_b**2)
    pn = scale_to_load(pn, dx * dy, fn)
  end function paraboloid_pressure

  !> The centres of the grid's cells: x(ix, iy) = x0 + (ix - 1) dx, y(ix, iy) = y0 + (iy - 1) dy.
  pure subroutine cell_centres(dx, dy, x0, y0, x, y)
    real(real64), intent(in) :: dx, dy, x0, y0
    real(real64), intent(out) :: x(:, :), y(:, :)
    integer :: ix, iy
    do iy = 1, size(x, 2)
      do ix = 1, size(x, 1)
        x(ix, iy) = x0 + (ix - 1) * dx
        y(ix, iy) = y0 + (iy - 1) * dy
      end do
    end do
  end subroutine cell_centres

  !> The parabolic strip model (see the module note), cell averages, scaled to fn.
  pure function strip_parabolic_pressure(inside, dx, dy, fn) result(pn)
    logical, intent(in) :: inside(:, :)
    real(real64), intent(in) :: dx, dy, fn
    real(real64) :: pn(size(inside, 1), size(inside, 2))
    integer :: ix, iy, first, last, k, mx
    real(real64) :: s, xm, xc

    mx = size(inside, 1)
    pn = 0
    do iy = 1, size(inside, 2)
      ix = 1
      do while (ix <= mx)
        if (.not. inside(ix, iy)) then
          ix = ix + 1
          cycle
        end if
        first = ix
        do while (ix < mx)
          if (.not. inside(ix + 1, iy)) exit
          ix = ix + 1
        end do
        last = ix
        ! segment in local coordinates: cells first..last, ends at -s and +s
        s = (last - first + 1) * dx / 2
        xm = (first + last) * dx / 2
        do k = first, last
          xc = k * dx - xm                    ! cell centre relative to the midpoint
          ! cell average of (s^2 - x^2) over [xc - dx/2, xc + dx/2]
          pn(k, iy) = (s**2 - xc**2 - dx**2 / 12) / s
        end do
        ix = last + 1
      end do
    end do
    pn = scale_to_load(pn, dx * dy, fn)
  end function strip_parabolic_pressure

  !> p scaled so that sum(p) * cell_area = fn (unchanged when sum(p) = 0).
  pure function scale_to_load(p, cell_area, fn) result(q)
    real(real64), intent(in) :: p(:, :), cell_area, fn
    real(real64) :: q(size(p, 1), size(p, 2))
    real(real64) :: total
    total = sum(p) * cell_area
    if (total > 0) then
      q = p * (fn / total)
    else
      q = p
    end if
  end function scale_to_load

end module kcreep_pressure_models
