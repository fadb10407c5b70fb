!> The creep matrix of an ellipse's staircase (the grid cells whose centres
!> lie inside it) referred to the ellipse itself.
!>
!> The staircase is compared with the ellipse of the same second moments of
!> area about the centre: semi-axes a_s = 2 sqrt(Ixx / A), b_s = 2 sqrt(Iyy / A)
!> (each cell counted with its own moment, dx^2/12 and dy^2/12). Its size is
!> taken out as c^p (c = sqrt(ab), p = 2, 3, 4 for the force, force-spin and
!> moment-spin entries), its aspect ratio with the local slope of ln C against
!> ln(a/b) from the refined table. Why: from one level to the next the
!> staircase's area and aspect ratio wander by a fraction of a cell, and the
!> coefficients follow them. Normalising by the area alone left a scatter of
!> 0.03 / 0.03 / 0.07 % (C11 C22 C23, mean over Kalker's 57 ellipses, levels
!> 32 to 148 cells across) about the straight line in the cell size; with the
!> aspect ratio as well, 0.018 / 0.019 / 0.027 % (docs/accuracy.md).
module kcreep_staircase_normalisation
  use, intrinsic :: iso_fortran_env, only: real64
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use kcreep_status, only: status_t
  use kcreep_patch, only: patch_t
  use kcreep_creep_matrix, only: centre_transfer
  use kcreep_table_interpolation, only: table_coefficients, table_ratio_range, table_nu_range
  implicit none
  private
  public :: staircase_semi_axes, staircase_harmonic4, aspect_slopes, ellipse_normalised

  !> Power of c in f_ij = G c^p C_ij.
  integer, parameter :: c_power(3, 3) = reshape([2, 2, 3, 2, 2, 3, 3, 3, 4], [3, 3])
  !> Which of the table's C11 C22 C23 C33 gives the slope of each entry (the
  !> off-diagonal force entries vanish on an ellipse about its centre).
  integer, parameter :: slope_of(3, 3) = reshape([1, 1, 1, 1, 2, 3, 1, 3, 4], [3, 3])

contains

  !> Semi-axes of the ellipse with the staircase's area moments about the
  !> ellipse's centre (patch: an ellipse patch).
  pure subroutine staircase_semi_axes(patch, a_s, b_s)
    type(patch_t), intent(in) :: patch
    real(real64), intent(out) :: a_s, b_s
    real(real64) :: centre(2), ixx, iyy
    centre = patch%ellipse_centre()
    ixx = sum((patch%cell_x(patch%ix) - centre(1))**2) + patch%n * patch%dx**2 / 12
    iyy = sum((patch%cell_y(patch%iy) - centre(2))**2) + patch%n * patch%dy**2 / 12
    a_s = 2 * sqrt(ixx / patch%n)
    b_s = 2 * sqrt(iyy / patch%n)
  end subroutine staircase_semi_axes

  !> The staircase's four-fold harmonic in the ellipse's own coordinates
  !> (X, Y) = ((x - xc)/a, (y - yc)/b): the sum over the cells of
  !> (X^4 - 6 X^2 Y^2 + Y^4) dX dY, zero on the ellipse itself. After the second
  !> moments it is what distinguishes one level's staircase from the next
  !> (the corners of a circle's staircase): fitted as an extra term, it halves
  !> the scatter of the levels again (docs/accuracy.md).
  pure real(real64) function staircase_harmonic4(patch) result(h4)
    type(patch_t), intent(in) :: patch
    real(real64) :: centre(2)
    real(real64), allocatable :: x(:), y(:)
    centre = patch%ellipse_centre()
    x = (patch%cell_x(patch%ix) - centre(1)) / patch%semi_a
    y = (patch%cell_y(patch%iy) - centre(2)) / patch%semi_b
    h4 = sum(x**4 - 6 * x**2 * y**2 + y**4) * (patch%dx / patch%semi_a) * (patch%dy / patch%semi_b)
  end function staircase_harmonic4

  !> d ln C / d ln(a/b) of C11 C22 C23 C33 from the refined table, by a central
  !> difference (one-sided at the table's ends; a/b and nu beyond them clamped:
  !> the slope only scales a correction of a fraction of a cell).
  pure function aspect_slopes(a_over_b, nu) result(slope)
    real(real64), intent(in) :: a_over_b, nu
    real(real64) :: slope(4)
    real(real64), parameter :: step = 0.01_real64   ! in ln(a/b)
    real(real64) :: r, lo, hi, c_lo(4), c_hi(4), rel(4), nu_in
    type(status_t) :: status
    r = min(max(a_over_b, table_ratio_range(1)), table_ratio_range(2))
    nu_in = min(max(nu, table_nu_range(1)), table_nu_range(2))
    lo = max(r * exp(-step), table_ratio_range(1))
    hi = min(r * exp(step), table_ratio_range(2))
    call table_coefficients(lo, nu_in, c_lo, rel, status)
    call table_coefficients(hi, nu_in, c_hi, rel, status)
    slope = (log(c_hi) - log(c_lo)) / log(hi / lo)
  end function aspect_slopes

  !> f of the staircase `patch` (about the origin, where the patch was placed)
  !> referred to its ellipse: taken to the ellipse's centre, scaled entry by
  !> entry, taken back. NaN columns (creepages not requested) stay NaN.
  pure function ellipse_normalised(patch, nu, f) result(fn)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: nu, f(3, 3)
    real(real64) :: fn(3, 3)
    real(real64) :: a_s, b_s, slope(4), log_scale, log_aspect, centre(2), t(3, 3), t_inv(3, 3), f0(3, 3)
    logical :: missing(3, 3)
    integer :: i, j

    call staircase_semi_axes(patch, a_s, b_s)
    slope = aspect_slopes(patch%semi_a / patch%semi_b, nu)
    log_scale = 0.5_real64 * log(patch%semi_a * patch%semi_b / (a_s * b_s))
    log_aspect = log((a_s / b_s) / (patch%semi_a / patch%semi_b))
    ! f = T' f0 T (kcreep_creep_matrix centre_transfer)
    centre = patch%ellipse_centre()
    t = centre_transfer(centre)
    t_inv = centre_transfer(-centre)
    missing = ieee_is_nan(f)
    ! without every column the move is not exact: then scale f where it is
    ! (exact about the centre; the off-centre terms are scaled as the centred)
    if (any(missing)) then
      f0 = f
    else
      f0 = matmul(transpose(t_inv), matmul(f, t_inv))
    end if
    do j = 1, 3
      do i = 1, 3
        f0(i, j) = f0(i, j) * exp(c_power(i, j) * log_scale - slope(slope_of(i, j)) * log_aspect)
      end do
    end do
    if (any(missing)) then
      fn = f0
    else
      fn = matmul(transpose(t), matmul(f0, t))
    end if
  end function ellipse_normalised

end module kcreep_staircase_normalisation
