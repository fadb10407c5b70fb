!> The creep matrix of a staircase (the grid cells whose centres lie inside a
!> shape) referred to the shape itself: an ellipse (the estimate of a grid
!> given as is, kcreep_error_run), or a contact area (a gap's,
!> kcreep_region: the moments of its zero level; the normal grid's estimate,
!> kcreep_gap_levels). The shape enters through its moment reference
!> (moment_reference_t: centre and the semi-axes of the ellipse with its
!> second moments).
!>
!> The staircase is compared with the ellipse of the same second moments of
!> area about the reference centre: semi-axes a_s = 2 sqrt(Ixx / A), b_s = 2 sqrt(Iyy / A)
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
  use kcreep_region, only: region_t, contour_moments
  use kcreep_creep_matrix, only: centre_transfer
  use kcreep_table_interpolation, only: table_coefficients, table_ratio_range, table_nu_range
  implicit none
  private
  public :: staircase_semi_axes, aspect_slopes, ellipse_normalised
  public :: moment_reference_t, contour_reference

  !> What a staircase is referred to: the shape's centre and the semi-axes
  !> of the ellipse with its second moments. own_centre: the staircase's
  !> moments are taken about its own centroid, and its f moved from there to
  !> the shape's centre; an ellipse's symmetric staircase is centred on the
  !> ellipse already.
  type :: moment_reference_t
    real(real64) :: centre(2) = 0, semi_a = 0, semi_b = 0
    logical :: own_centre = .false.
  end type moment_reference_t

  !> Power of c in f_ij = G c^p C_ij.
  integer, parameter :: c_power(3, 3) = reshape([2, 2, 3, 2, 2, 3, 3, 3, 4], [3, 3])
  !> Which of the table's C11 C22 C23 C33 gives the slope of each entry (the
  !> off-diagonal force entries vanish on an ellipse about its centre).
  integer, parameter :: slope_of(3, 3) = reshape([1, 1, 1, 1, 2, 3, 1, 3, 4], [3, 3])

contains

  !> The reference of an ellipse patch: its ellipse.
  pure function ellipse_reference(patch) result(ref)
    type(patch_t), intent(in) :: patch
    type(moment_reference_t) :: ref
    ref = moment_reference_t(patch%ellipse_centre(), patch%semi_a, patch%semi_b, .false.)
  end function ellipse_reference

  !> The reference of a contact area: the moments of its zero level itself
  !> (kcreep_region contour_moments), not of a staircase of it; a level's
  !> moments about its own centroid.
  pure function contour_reference(region) result(ref)
    type(region_t), intent(in) :: region
    type(moment_reference_t) :: ref
    real(real64) :: m(5)
    m = contour_moments(region)
    ref%centre = m(2:3)
    ref%semi_a = 2 * sqrt(m(4) / m(1))
    ref%semi_b = 2 * sqrt(m(5) / m(1))
    ref%own_centre = .true.
  end function contour_reference

  !> Semi-axes of the ellipse with the staircase's area moments about the
  !> ellipse's centre (patch: an ellipse patch).
  pure subroutine staircase_semi_axes(patch, a_s, b_s)
    type(patch_t), intent(in) :: patch
    real(real64), intent(out) :: a_s, b_s
    call moment_semi_axes(patch, patch%ellipse_centre(), a_s, b_s)
  end subroutine staircase_semi_axes

  !> Semi-axes 2 sqrt(Ixx / A), 2 sqrt(Iyy / A) of the staircase's area
  !> moments about centre (each cell counted with its own dx^2/12, dy^2/12).
  pure subroutine moment_semi_axes(patch, centre, a_s, b_s)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: centre(2)
    real(real64), intent(out) :: a_s, b_s
    real(real64) :: m(2)
    m = patch%second_moments(centre)
    a_s = 2 * sqrt(m(1) / patch%n)
    b_s = 2 * sqrt(m(2) / patch%n)
  end subroutine moment_semi_axes

  !> d ln C / d ln(a/b) of C11 C22 C23 C33 from the refined table, by a central
  !> difference (one-sided at the table's ends; nu beyond them clamped).
  !> Beyond the table's longest ellipse (a/b = 10) the slope is continued
  !> linearly in ln(a/b), from its change over the table's last
  !> slope_extension_base in ln(a/b), up to a/b = slope_extension_limit and
  !> held there: the slopes still grow at a/b = 10 (C11 0.62, 0.64, 0.66,
  !> 0.68, 0.69 between solved ellipses a/b = 8, 10, 12, 14, 17, 20 at nu =
  !> 0.28), the continued slope is within 2.4 % of those differences where the
  !> one held at a/b = 10 was 4-9 % low (docs/accuracy.md, "Ellipses"). The
  !> slope turns a change of a contact area's aspect ratio into one of its
  !> C's (the normal grid's estimate, kcreep_gap_levels) and scales a given
  !> ellipse grid's correction for its staircase's aspect ratio.
  pure function aspect_slopes(a_over_b, nu) result(slope)
    real(real64), intent(in) :: a_over_b, nu
    real(real64) :: slope(4)
    real(real64), parameter :: step = 0.01_real64   ! in ln(a/b)
    real(real64), parameter :: slope_extension_base = 0.3_real64, slope_extension_limit = 20
    real(real64) :: r, lo, hi, c_lo(4), c_hi(4), rel(4), nu_in, below(4)
    type(status_t) :: status
    r = min(max(a_over_b, table_ratio_range(1)), table_ratio_range(2))
    nu_in = min(max(nu, table_nu_range(1)), table_nu_range(2))
    lo = max(r * exp(-step), table_ratio_range(1))
    hi = min(r * exp(step), table_ratio_range(2))
    call table_coefficients(lo, nu_in, c_lo, rel, status)
    call table_coefficients(hi, nu_in, c_hi, rel, status)
    slope = (log(c_hi) - log(c_lo)) / log(hi / lo)
    if (a_over_b > table_ratio_range(2)) then
      call table_coefficients(r * exp(-slope_extension_base - step), nu_in, c_lo, rel, status)
      call table_coefficients(r * exp(-slope_extension_base), nu_in, c_hi, rel, status)
      below = (log(c_hi) - log(c_lo)) / step
      slope = slope + (slope - below) / slope_extension_base * log(min(a_over_b, slope_extension_limit) / r)
    end if
  end function aspect_slopes

  !> f of an ellipse's staircase `patch` (about the origin, where the patch
  !> was placed) referred to the ellipse.
  pure function ellipse_normalised(patch, nu, f) result(fn)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: nu, f(3, 3)
    real(real64) :: fn(3, 3)
    fn = referred_f(patch, ellipse_reference(patch), nu, f)
  end function ellipse_normalised

  !> f of the staircase `patch` (about the origin) referred to the shape
  !> `ref` describes: taken to the reference centre, scaled entry by entry
  !> for the staircase's size and aspect ratio against the reference's,
  !> taken back. NaN columns (creepages not requested) stay NaN.
  pure function referred_f(patch, ref, nu, f) result(fn)
    type(patch_t), intent(in) :: patch
    type(moment_reference_t), intent(in) :: ref
    real(real64), intent(in) :: nu, f(3, 3)
    real(real64) :: fn(3, 3)
    real(real64) :: a_s, b_s, slope(4), log_scale, log_aspect, t(3, 3), t_inv(3, 3), f0(3, 3), own(2)
    logical :: missing(3, 3)
    integer :: i, j

    own = ref%centre
    if (ref%own_centre) own = patch%centroid()
    call moment_semi_axes(patch, own, a_s, b_s)
    slope = aspect_slopes(ref%semi_a / ref%semi_b, nu)
    log_scale = 0.5_real64 * log(ref%semi_a * ref%semi_b / (a_s * b_s))
    log_aspect = log((a_s / b_s) / (ref%semi_a / ref%semi_b))
    ! f = T' f0 T (kcreep_creep_matrix centre_transfer)
    t = centre_transfer(ref%centre)
    t_inv = centre_transfer(-own)
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
  end function referred_f

end module kcreep_staircase_normalisation
