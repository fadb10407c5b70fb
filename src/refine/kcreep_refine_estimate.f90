!> Error control in the mesh size: which grids to run for a target error, the
!> extrapolation to zero cell size, the error estimate and the verdict.
!>
!> The model (measured, docs/accuracy.md, "The engine" and the sections after it): with the backward
!> scheme, every coefficient of a ladder's levels behaves as
!>     f(h) = f0 + K h [+ L g(h)] + noise(h),
!> fitted as a regression through the finest levels; the estimate is t95 x
!> the standard error of f0 plus what the model itself leaves uncertain.
!> Sampled shapes (an ellipse, a gap's contact area; levels with a blended
!> edge, kcreep_patch blended_patch): f0 + K h, the model's uncertainty a
!> tenth of the extrapolation (shape_level_estimate; levels from 56 cells
!> across, coarser ones bend with h^2). Split patches (a mask, CONTACT's
!> grid: the same staircase on every level): g = h^1.5, the uncertainty the
!> change of f0 for other orders (split_level_estimate). Measured honesty:
!> docs/accuracy.md.
!>
!> Everything here is pure: the driver runs the levels and calls these.
module kcreep_refine_estimate
  use, intrinsic :: iso_fortran_env, only: real64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use kcreep_strings, only: rtoa
  use kcreep_patch, only: near_square_cells
  use kcreep_refine_constants
  implicit none
  private
  public :: default_target_error, c23_target_factor, min_estimate_cells, nominal_ellipse_cells
  public :: coefficient_targets, ellipse_level_grid, ellipse_cells_long_in_y, next_level, level_cell_budget, student_t95
  public :: cell_budget_allowed, cell_budget_range, level_solver_tolerance
  public :: shape_level_estimate, split_level_estimate
  public :: single_grid_estimate, ellipse_fit_min, ellipse_fit_width
  public :: split_grid_estimate, within_target, uncertain_flag, levels_done


contains

  !> Relative targets of (C11, C22, C23) for a target_error.
  pure function coefficient_targets(target) result(t)
    real(real64), intent(in) :: target
    real(real64) :: t(3)
    t = [target, target, c23_target_factor * target]
  end function coefficient_targets

  !> Grid over [-a, a] x [-b, b] with `cells` cells across the shorter axis:
  !> near-square cells (dx/dy within a rounding step of 1), or, with
  !> long_in_y on an ellipse long in y (a < b), cells x cells, each cell b/a
  !> times as long in y as in x, at most max_cell_aspect times
  !> (ellipse_cells_long_in_y says when).
  pure subroutine ellipse_level_grid(semi_a, semi_b, cells, mx, my, long_in_y)
    real(real64), intent(in) :: semi_a, semi_b
    integer, intent(in) :: cells
    integer, intent(out) :: mx, my
    logical, intent(in), optional :: long_in_y
    logical :: stretch
    stretch = .false.
    if (present(long_in_y)) stretch = long_in_y
    if (semi_a >= semi_b) then
      my = cells
      mx = near_square_cells(cells, semi_a / semi_b)
    else if (stretch) then
      ! at most max_cell_aspect: the longest cells the estimate was checked on
      mx = cells
      my = near_square_cells(cells, semi_b / (semi_a * max_cell_aspect))
    else
      mx = cells
      my = near_square_cells(cells, semi_b / semi_a)
    end if
  end subroutine ellipse_level_grid

  !> Whether kcreep's levels of an ellipse long in y use cells long in y
  !> (ellipse_level_grid): for targets tighter than the default, backward
  !> scheme. The discretisation error's first-order term follows the cell
  !> length in the rolling direction relative to a (the leading edge), not
  !> the cell width across it: the levels' slope K / f0 of C11 is 0.28-0.30
  !> per 1/(cells across a) at a/b = 0.25, 0.5 and 1 alike (measured on
  !> the staircase levels before the blended edge). On an ellipse long in y, near-square cells spend b/a
  !> times the cells on the width; cells x cells over the bounding box give
  !> the same estimates with a/b times the cells (a/b = 0.5: ok at 452 x 452
  !> in 4 s, where near-square cells stopped uncertain at 520 x 1040 after
  !> 11 s). The default target keeps near-square cells, on which its
  !> calibration was made, and collocation is never put on long cells. A
  !> gap's contact area long in y gets them too (kcreep_level_ladder): the
  !> Hertzian gaps a/b = 0.5 and 0.25 end `ok` at 1e-4 in 9.5 and 22 s,
  !> errors within their estimates (49 s for a/b = 0.5 on near-square cells).
  pure logical function ellipse_cells_long_in_y(target, scheme_name)
    real(real64), intent(in) :: target
    character(len=*), intent(in) :: scheme_name
    ellipse_cells_long_in_y = target < default_target_error .and. scheme_name == 'backward'
  end function ellipse_cells_long_in_y

  !> The next finer level after `finest` cells across: about 15 % finer, a
  !> multiple of 4 (48, 56, 64, 72, 84, 96, 112, 128, 148, 172, ...).
  pure integer function next_level(finest) result(cells)
    integer, intent(in) :: finest
    cells = max(finest + 4, 4 * nint(next_level_growth * finest / 4))
  end function next_level

  !> A cell budget the caller may give: 0 (the defaults) or within the range.
  pure logical function cell_budget_allowed(cells)
    real(real64), intent(in) :: cells
    cell_budget_allowed = cells == 0 .or. (cells >= min_cell_budget .and. cells <= max_cell_budget)
  end function cell_budget_allowed

  !> What cell_budget_allowed allows, for error messages.
  pure function cell_budget_range() result(text)
    character(len=:), allocatable :: text
    text = '(allowed: 0, the defaults, or '//rtoa(min_cell_budget)//' to '//rtoa(max_cell_budget)//' patch cells)'
  end function cell_budget_range

  !> GMRES's relative residual on the levels of error control when the caller
  !> gave no tolerance: the levels need their coefficients to a small part of
  !> the target only, and to a small part of the staircase's level-to-level
  !> noise (about 0.5 % / N, 5e-5 at 100 cells across). Measured on the unit
  !> circle (f11, f22, f23 against residual 1e-11): a residual r moves them by
  !> up to about r (1e-4: C23 by 9.5e-5 at target 1e-2; 1e-5: 3e-6; 1e-6:
  !> 7e-7 at 296 and 448 cells across), with 21-23 iterations at 1e-6 instead
  !> of 24-27 at 1e-7 and 37-41 at 1e-11. Hence a hundredth of the target,
  !> and never above 1e-5.
  pure real(real64) function level_solver_tolerance(target) result(tolerance)
    real(real64), intent(in) :: target
    tolerance = min(level_tolerance_share * target, max_level_tolerance)
  end function level_solver_tolerance

  !> The most patch cells a level kcreep chooses may have for this target.
  pure real(real64) function level_cell_budget(target) result(cells)
    real(real64), intent(in) :: target
    if (target >= default_target_error) then
      cells = cells_at_default_target * (default_target_error / target)**0.25_real64
    else
      cells = cells_at_default_target * tight_target_budget_growth**log10(default_target_error / target)
    end if
  end function level_cell_budget

  !> Two-sided 95 % factor of Student's t distribution for dof degrees of freedom.
  pure real(real64) function student_t95(dof) result(t)
    integer, intent(in) :: dof
    real(real64), parameter :: table(10) = [12.706_real64, 4.303_real64, 3.182_real64, 2.776_real64, &
                                            2.571_real64, 2.447_real64, 2.365_real64, 2.306_real64, &
                                            2.262_real64, 2.228_real64]
    if (dof < 1) then
      t = ieee_value(1.0_real64, ieee_quiet_nan)
    else if (dof <= size(table)) then
      t = table(dof)
    else
      t = 1.96_real64 + 2.5_real64 / dof   ! within 1 % of the exact factor beyond 10
    end if
  end function student_t95

  !> Limit and relative 95 % error estimate from the levels of a sampled
  !> shape (at least ellipse_fit_min of them, from 56 cells across), each
  !> with a blended edge: the straight line f0 + K h through them. Coarser
  !> levels bend away from it (L h^2) and are not used.
  !> Estimate: t95 x the standard error of f0 (the scatter), plus
  !> order_margin x the extrapolation's own size |f0 - f(finest)| (the order
  !> is 1 only to within a few per cent; docs/accuracy.md, "The engine").
  pure subroutine shape_level_estimate(h, f, limit, rel_error)
    real(real64), intent(in) :: h(:), f(:)
    real(real64), intent(out) :: limit, rel_error
    real(real64) :: a(size(h), 2), se
    a(:, 1) = 1
    a(:, 2) = h
    call limit_fit(a, f, limit, se)
    rel_error = (student_t95(size(h) - 2) * se + order_margin * abs(limit - f(minloc(h, 1)))) / abs(limit)
  end subroutine shape_level_estimate

  !> Least-squares fit f = f0 + K h + L g; std_error of f0 (NaN without
  !> degrees of freedom left).
  pure subroutine three_column_fit(h, f, g, f0, std_error)
    real(real64), intent(in) :: h(:), f(:), g(:)
    real(real64), intent(out) :: f0, std_error
    real(real64) :: a(size(h), 3)
    a(:, 1) = 1
    a(:, 2) = h
    a(:, 3) = g
    call limit_fit(a, f, f0, std_error)
  end subroutine three_column_fit

  !> Least-squares fit of f by the columns of a, the first being ones: f0 its
  !> coefficient, std_error its standard error from the residual scatter (NaN
  !> without degrees of freedom left). Normal equations on columns scaled to
  !> unit size, solved by Gauss-Jordan elimination (at most a few columns).
  pure subroutine limit_fit(a, f, f0, std_error)
    real(real64), intent(in) :: a(:, :), f(:)
    real(real64), intent(out) :: f0, std_error
    real(real64) :: scaled(size(a, 1), size(a, 2)), scale(size(a, 2))
    real(real64) :: m(size(a, 2), 2 * size(a, 2) + 1), c(size(a, 2)), s2, pivot
    integer :: k, n, i, j, p
    n = size(a, 1)
    k = size(a, 2)
    do j = 1, k
      scale(j) = max(maxval(abs(a(:, j))), tiny(1.0_real64))
      scaled(:, j) = a(:, j) / scale(j)
    end do
    ! [A'A | I | A'f] -> [I | inv(A'A) | c]
    m = 0
    m(:, 1:k) = matmul(transpose(scaled), scaled)
    do j = 1, k
      m(j, k + j) = 1
    end do
    m(:, 2 * k + 1) = matmul(transpose(scaled), f)
    do j = 1, k
      p = j - 1 + maxloc(abs(m(j:k, j)), 1)
      if (p /= j) m([j, p], :) = m([p, j], :)
      pivot = m(j, j)
      m(j, :) = m(j, :) / pivot
      do i = 1, k
        if (i /= j) m(i, :) = m(i, :) - m(i, j) * m(j, :)
      end do
    end do
    c = m(:, 2 * k + 1)
    f0 = c(1) / scale(1)
    if (n > k) then
      s2 = sum((f - matmul(scaled, c))**2) / (n - k)
      std_error = sqrt(s2 * m(1, k + 1)) / scale(1)
    else
      std_error = ieee_value(1.0_real64, ieee_quiet_nan)
    end if
  end subroutine limit_fit

  !> Levels of a split patch (a mask or CONTACT's grid, every cell split
  !> k x k: the same staircase on every level, no level-to-level noise). The
  !> staircase's re-entrant corners bend the convergence: f0 + K h + L h^p
  !> with p between 4/3 and 3/2 (docs/accuracy.md, "Masks"). Limit: the fit
  !> with p = split_order; estimate: the largest change of f0 when p is one
  !> of split_order_range instead (the model's uncertainty) plus t95 x the
  !> standard error of f0 (what the model does not take out). At least 4
  !> levels (one degree of freedom).
  pure subroutine split_level_estimate(h, f, limit, rel_error)
    real(real64), intent(in) :: h(:), f(:)
    real(real64), intent(out) :: limit, rel_error
    real(real64) :: other, se, se_other, spread
    integer :: i
    call three_column_fit(h, f, h**split_order, limit, se)
    spread = 0
    do i = 1, size(split_order_range)
      call three_column_fit(h, f, h**split_order_range(i), other, se_other)
      spread = max(spread, abs(other - limit))
    end do
    rel_error = (spread + student_t95(size(h) - 3) * se) / abs(limit)
  end subroutine split_level_estimate

  !> The error of a coefficient computed on one grid (target_error = 0), from a
  !> second grid with twice the cell size: first order gives f(h) - f0 = f(2h) - f(h);
  !> the factor 2 covers the noise and the h log h term of collocation (measured:
  !> docs/accuracy.md). area_error: the relative difference between the patch
  !> the coefficient refers to and the staircase (0 for masks), added in full.
  pure real(real64) function single_grid_estimate(f_h, f_2h, area_error) result(rel_error)
    real(real64), intent(in) :: f_h, f_2h, area_error
    rel_error = single_grid_factor * abs(f_h - f_2h) / abs(f_h) + abs(area_error)
  end function single_grid_estimate

  !> The error of a coefficient computed on one grid (target_error = 0) from the
  !> grid with every cell split in 2 x 2 (masks, CONTACT's grid: no coarser grid
  !> describes the same patch): first order gives f(h) - f0 = 2 (f(h) - f(h/2)),
  !> and the same factor 2 as single_grid_estimate.
  pure real(real64) function split_grid_estimate(f_h, f_half) result(rel_error)
    real(real64), intent(in) :: f_h, f_half
    rel_error = split_grid_factor * abs(f_h - f_half) / abs(f_h)
  end function split_grid_estimate

  !> Every estimate at or below its target (NaN estimates are not within).
  !> solved: the load cases run (xi, eta, phi); a coefficient whose load case
  !> was not run (C23 without phi) has no estimate and is not waited for.
  pure logical function within_target(rel_error, targets, solved)
    real(real64), intent(in) :: rel_error(:), targets(:)
    logical, intent(in), optional :: solved(:)
    if (present(solved)) then
      within_target = all(rel_error <= targets .or. .not. solved)
    else
      within_target = all(rel_error <= targets)
    end if
  end function within_target

  !> A contact area's ladder can stop short of the target: for every
  !> coefficient whose other estimate (the normal grid's, combined in
  !> quadrature, which the levels cannot reduce) misses its target by itself,
  !> the levels' own estimate meets the target, and every other coefficient
  !> meets it combined. Finer levels would only cost (the row stays
  !> `uncertain`; S1002 at +4.6 mm climbed from 96 to 296 cells across, 2 s,
  !> for a combined C11 of 7.13e-3 -> 6.82e-3 against the normal grid's
  !> 6.81e-3; with this rule it stops at 128).
  pure logical function levels_done(own_error, other_error, targets, solved)
    real(real64), intent(in) :: own_error(3), other_error(3), targets(3)
    logical, intent(in) :: solved(3)
    levels_done = within_target(merge(own_error, sqrt(own_error**2 + other_error**2), other_error > targets), &
                                targets, solved)
  end function levels_done

  !> The verdict flag for a run with estimates rel_error(1:3) of C11, C22, C23:
  !> 'uncertain' when any estimate exceeds its target or is missing (NaN).
  !> target 0 sets no target, but an 'ok' still needs a finite estimate.
  !> solved: the load cases run (within_target); a coefficient whose load
  !> case was not asked for does not make the run uncertain.
  pure function uncertain_flag(rel_error, target, solved) result(flag)
    real(real64), intent(in) :: rel_error(3), target
    logical, intent(in), optional :: solved(3)
    character(len=:), allocatable :: flag
    real(real64) :: targets(3)
    flag = ''
    targets = huge(1.0_real64)
    if (target > 0) targets = coefficient_targets(target)
    if (.not. within_target(rel_error, targets, solved)) flag = 'uncertain'
  end function uncertain_flag

end module kcreep_refine_estimate
