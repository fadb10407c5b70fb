!> Equivalent ellipses of a patch: what a user who replaced a non-elliptic
!> patch by an ellipse would get from Kalker's table.
!>  - 'box':     same area, a/b = length/width of the patch's bounding box
!>               (extent of its cells along x over that along y);
!>  - 'moments': same area, a/b = sqrt(Ixx / Iyy), Ixx = Int (x - xg)^2 dA,
!>               Iyy = Int (y - yg)^2 dA about the centroid (an ellipse has
!>               Ixx / Iyy = (a/b)^2), integrated exactly over the cells.
!> With pi a b = area: a = sqrt(area r / pi), b = a / r (r = a/b).
!> The coefficients are Kalker's C11 C22 C23 (table E3, interpolated) at
!> a/b and nu; f11 = G c^2 C11, f22 = G c^2 C22, f23 = G c^3 C23 with
!> c = sqrt(ab) = sqrt(area/pi), the same length kcreep's C use for any
!> patch, so the C compare directly. L1 = 8a/(3 C11 G), L2 = 8a/(3 C22 G),
!> L3 = pi a sqrt(a/b)/(4 C23 G) (Kalker's FASTSIM flexibilities).
module kcreep_equivalent_ellipse
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_kalker_table, only: kalker_coefficients
  implicit none
  private
  public :: equivalent_ellipse_t, equivalent_ellipses, ellipse_flexibilities, patch_moments
  public :: ellipse_box, ellipse_moments

  integer, parameter :: ellipse_box = 1, ellipse_moments = 2
  real(real64), parameter :: pi = acos(-1.0_real64)

  type :: equivalent_ellipse_t
    character(len=8) :: kind = ''            !< 'box' or 'moments'
    real(real64) :: semi_a = 0, semi_b = 0   !< semi-axes along x and y
    real(real64) :: c(3) = 0                 !< Kalker's C11, C22, C23
    real(real64) :: f(3) = 0                 !< f11, f22, f23
    real(real64) :: flex(3) = 0              !< L1, L2, L3
  end type equivalent_ellipse_t

contains

  !> (area, xg, yg, Ixx, Iyy, length, width) of the patch cells
  !> (centre of cell (ix, iy) at (x0 + (ix-1) dx, y0 + (iy-1) dy)).
  pure function patch_moments(inside, dx, dy, x0, y0) result(m)
    logical, intent(in) :: inside(:, :)
    real(real64), intent(in) :: dx, dy, x0, y0
    real(real64) :: m(7)
    real(real64) :: sx, sy, sxx, syy, x, y, da
    integer :: ix, iy, n, ix_lo, ix_hi, iy_lo, iy_hi

    sx = 0; sy = 0; sxx = 0; syy = 0; n = 0
    ix_lo = huge(1); ix_hi = -huge(1); iy_lo = huge(1); iy_hi = -huge(1)
    do iy = 1, size(inside, 2)
      y = y0 + (iy - 1) * dy
      do ix = 1, size(inside, 1)
        if (.not. inside(ix, iy)) cycle
        x = x0 + (ix - 1) * dx
        n = n + 1
        sx = sx + x; sy = sy + y
        sxx = sxx + x**2; syy = syy + y**2
        ix_lo = min(ix_lo, ix); ix_hi = max(ix_hi, ix)
        iy_lo = min(iy_lo, iy); iy_hi = max(iy_hi, iy)
      end do
    end do
    da = dx * dy
    m = 0
    if (n == 0) return
    m(1) = n * da
    m(2) = sx / n
    m(3) = sy / n
    ! second moments about the centroid, each cell integrated exactly (+ d^2/12)
    m(4) = (sxx / n - m(2)**2 + dx**2 / 12) * m(1)
    m(5) = (syy / n - m(3)**2 + dy**2 / 12) * m(1)
    m(6) = (ix_hi - ix_lo + 1) * dx
    m(7) = (iy_hi - iy_lo + 1) * dy
  end function patch_moments

  !> Both equivalent ellipses of a patch at Poisson's ratio nu and modulus g.
  pure function equivalent_ellipses(inside, dx, dy, x0, y0, nu, g) result(e)
    logical, intent(in) :: inside(:, :)
    real(real64), intent(in) :: dx, dy, x0, y0, nu, g
    type(equivalent_ellipse_t) :: e(2)
    real(real64) :: m(7)

    m = patch_moments(inside, dx, dy, x0, y0)
    e(ellipse_box) = one_ellipse('box', m(1), m(6) / m(7), nu, g)
    e(ellipse_moments) = one_ellipse('moments', m(1), sqrt(m(4) / m(5)), nu, g)
  end function equivalent_ellipses

  pure function one_ellipse(kind, area, ratio, nu, g) result(e)
    character(len=*), intent(in) :: kind
    real(real64), intent(in) :: area, ratio, nu, g
    type(equivalent_ellipse_t) :: e
    real(real64) :: c_len

    e%kind = kind
    e%semi_a = sqrt(area * ratio / pi)
    e%semi_b = e%semi_a / ratio
    c_len = sqrt(area / pi)
    e%c = kalker_coefficients(ratio, nu)
    e%f = [g * c_len**2 * e%c(1), g * c_len**2 * e%c(2), g * c_len**3 * e%c(3)]
    e%flex = ellipse_flexibilities(e%semi_a, e%semi_b, e%c, g)
  end function one_ellipse

  !> Kalker's L1, L2, L3 of an ellipse (semi-axes a along x, b) with coefficients c = (C11, C22, C23).
  pure function ellipse_flexibilities(semi_a, semi_b, c, g) result(flex)
    real(real64), intent(in) :: semi_a, semi_b, c(3), g
    real(real64) :: flex(3)
    flex = [8 * semi_a / (3 * c(1) * g), 8 * semi_a / (3 * c(2) * g), &
            pi * semi_a * sqrt(semi_a / semi_b) / (4 * c(3) * g)]
  end function ellipse_flexibilities

end module kcreep_equivalent_ellipse
