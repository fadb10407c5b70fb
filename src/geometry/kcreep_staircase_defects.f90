!> The quietest grid near a wanted one for an ellipse's staircase.
!>
!> Why: on an ellipse long in x the levels of error control scatter about
!> their straight line in the cell size by more than the accurate mode's
!> target (0.005-0.014 % at 100 cells across, a/b = 5 and 10), and that
!> scatter, not the extrapolation, held its estimate up. Most of it follows
!> how the staircase's row and column ends miss the ellipse
!> (docs/accuracy.md section 6.3, scripts/staircase_defect_study.py):
!>     row j:    d_j = (cells in row j) dx / (2a) - s_j,     s_j = sqrt(1 - Y_j^2)
!>     column i: e_i = (cells in column i) dy / (2b) - t_i,  t_i = sqrt(1 - X_i^2)
!>     end defect = sum_j s_j d_j dy/b  -  0.43 sum_i t_i^(-1/2) e_i dx/a
!> (X, Y cell centres over the semi-axes). It is a sum over cells' ends: it
!> has a smooth part, about proportional to the cell size, which the levels'
!> fit takes out with K h, and a part that jumps from grid to grid, which is
!> the scatter. Among the grids with a few cells fewer across (down to
!> quiet_cells_window of them) and a few columns more or fewer (the cells
!> stay square to quiet_aspect_change), the one whose end defect lies
!> closest to the smooth part is the quietest. Choosing it costs a sum over
!> rows and columns per candidate grid, no solve, and never a grid with more
!> cells than the wanted one.
module kcreep_staircase_defects
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: near_square_cells
  implicit none
  private
  public :: end_defect, quiet_ellipse_grid

  !> Q's weight against R's in the end defect: fitted as two free terms
  !> through levels 56-120, it was -0.42 to -0.47 for every coefficient at
  !> a/b = 0.5 to 10 (docs/accuracy.md section 6.3).
  real(real64), parameter :: column_weight = -0.43_real64
  !> Candidates: from this share of the wanted cells across to all of them.
  real(real64), parameter :: quiet_cells_window = 0.92_real64
  !> Candidates' columns differ from near-square by at most this share of
  !> them (and at most max_column_change): the first-order term follows the
  !> cell size, and a cell 0.5 % longer moves it by 0.5 % of itself, a
  !> hundredth of the scatter taken out.
  real(real64), parameter :: quiet_aspect_change = 0.005_real64
  integer, parameter :: max_column_change = 4
  !> The smooth part is a straight line in 1 / cells fitted over the
  !> candidates' grids from this share of the wanted cells to its inverse.
  real(real64), parameter :: trend_span = 0.8_real64

contains

  !> End defect (see the module's comment) of an ellipse's staircase on the
  !> mx x my grid over its bounding box (the cells whose centres lie inside,
  !> as kcreep_patch ellipse_patch); in X = x/a, Y = y/b it does not depend
  !> on the semi-axes.
  pure real(real64) function end_defect(mx, my) result(defect)
    integer, intent(in) :: mx, my
    real(real64) :: centre, half_length
    integer :: i, j
    defect = 0
    do j = 1, my
      centre = cell_centre(j, my)
      half_length = sqrt(1 - centre**2)
      defect = defect + half_length * (real(inside_count(half_length, mx), real64) / mx - half_length) * 2.0_real64 / my
    end do
    do i = 1, mx
      centre = cell_centre(i, mx)
      half_length = sqrt(1 - centre**2)
      defect = defect + column_weight * (real(inside_count(half_length, my), real64) / my - half_length) &
               / sqrt(half_length) * 2.0_real64 / mx
    end do
  end function end_defect

  !> The quietest grid (cells across the shorter axis b, mx columns) near
  !> wanted_cells across on the ellipse with a >= b (near-square cells: mx
  !> about wanted_cells a / b), with no more grid cells than the wanted one.
  !> The end defect's smooth part is a least-squares line offset + slope / n
  !> through every candidate grid from trend_span wanted_cells to
  !> wanted_cells / trend_span; the chosen grid lies in the narrower window
  !> from quiet_cells_window wanted_cells, so each defect is summed once.
  pure subroutine quiet_ellipse_grid(semi_a, semi_b, wanted_cells, cells, mx)
    real(real64), intent(in) :: semi_a, semi_b
    integer, intent(in) :: wanted_cells
    integer, intent(out) :: cells, mx
    real(real64), allocatable :: defect(:)
    integer, allocatable :: rows(:), columns(:)
    real(real64) :: ratio, slope, offset, distance, best
    integer :: n, k, g, wanted_grid

    ratio = semi_a / semi_b
    allocate (defect(0), rows(0), columns(0))
    do n = max(1, floor(trend_span * wanted_cells)), ceiling(wanted_cells / trend_span)
      do k = -column_change(ratio, n), column_change(ratio, n)
        rows = [rows, n]
        columns = [columns, near_square_cells(n, ratio) + k]
        defect = [defect, end_defect(columns(size(columns)), n)]
      end do
    end do
    call line_in_inverse(rows, defect, slope, offset)

    wanted_grid = near_square_cells(wanted_cells, ratio) * wanted_cells
    cells = wanted_cells
    mx = near_square_cells(wanted_cells, ratio)
    best = huge(1.0_real64)
    do g = 1, size(rows)
      if (rows(g) < ceiling(quiet_cells_window * wanted_cells) .or. rows(g) > wanted_cells) cycle
      if (columns(g) * rows(g) > wanted_grid) cycle
      distance = abs(defect(g) - (offset + slope / rows(g)))
      if (distance < best) then
        best = distance
        cells = rows(g)
        mx = columns(g)
      end if
    end do
  end subroutine quiet_ellipse_grid

  !> Least-squares line d = offset + slope / n.
  pure subroutine line_in_inverse(n, d, slope, offset)
    integer, intent(in) :: n(:)
    real(real64), intent(in) :: d(:)
    real(real64), intent(out) :: slope, offset
    real(real64) :: h(size(n))
    h = 1.0_real64 / n
    slope = (size(h) * sum(h * d) - sum(h) * sum(d)) / (size(h) * sum(h * h) - sum(h)**2)
    offset = (sum(d) - slope * sum(h)) / size(h)
  end subroutine line_in_inverse

  !> How many columns a candidate may add or drop.
  pure integer function column_change(ratio, cells) result(change)
    real(real64), intent(in) :: ratio
    integer, intent(in) :: cells
    change = min(max_column_change, int(quiet_aspect_change * near_square_cells(cells, ratio)))
  end function column_change

  !> Centre of cell i of m across [-1, 1].
  pure real(real64) function cell_centre(i, m) result(centre)
    integer, intent(in) :: i, m
    centre = real(2 * i - 1 - m, real64) / m
  end function cell_centre

  !> Cells of m across [-1, 1] whose centres lie within [-half_length, half_length].
  pure integer function inside_count(half_length, m) result(count)
    real(real64), intent(in) :: half_length
    integer, intent(in) :: m
    integer :: reach
    ! centres at k / m, k = -(m-1), -(m-3), ..., m-1: those with |k| <= reach
    reach = floor(half_length * m)
    if (mod(m - 1, 2) == 0) then
      count = 2 * (reach / 2) + 1
    else
      count = 2 * ((reach + 1) / 2)
    end if
  end function inside_count
end module kcreep_staircase_defects
