!> Error control of a patch found by the normal contact problem (shape 'gap').
!>
!> The patch is the set of cells with positive pressure, so a finer grid is a
!> finer geometry: the gap is sampled on smaller cells (the polynomial
!> evaluated, a gap given on a grid resampled by kcreep_gap gap_resampled),
!> the normal problem solved again, and the creep coefficients computed on
!> the contact area found. Splitting the cells of one contact area would only
!> refine its staircase, not its boundary.
!>
!> Levels (target_error > 0 and refine_grid): square cells with N = 24, 28,
!> 32, 36, 40, 44, 48, 56 cells across the contact area's hydraulic diameter
!> 4 area / perimeter (contact_diameter; from a normal solve on the given
!> grid: the diameter of a circle, of each lobe of two round ones), over the
!> bounding box of that contact area widened by a margin; doubled (reusing
!> the levels done) while an estimate is above its target, at most
!> max_refinements times and while the finest level stays within
!> gap_budget_share of the cell budget. Every level's coefficients are normalised by its own
!> contact area (C_ij = f_ij / (G c^p), c = sqrt(area / pi)): the staircase of
!> the contact boundary changes the area irregularly from level to level, and
!> f_ij follows it (measured on a Hertzian gap: this removes 95 % of the
!> scatter about the first-order line, docs/accuracy.md). Each C_ij and the
!> area are fitted by f0 + K h (order fixed at 1) and estimated as in
!> kcreep_refine_estimate level_estimate; the result has c = sqrt(A0 / pi) of
!> the fitted area A0 and f_ij = G c^p C_ij. err(1:3) are the estimates of
!> C11, C22, C23; the f_ij carry in addition p/2 times the area's relative
!> error (the contact area itself converges slowly: about 1 % at 50 cells
!> across).
!>
!> A single grid (target_error = 0, or refine_grid off): the gap's grid as
!> given, and as estimate gap_single_estimate from the geometry on cells 1.5
!> and 2 times the size, or NaN and a warning when the coarser grid would have
!> fewer than min_estimate_cells cells across the contact area.
module kcreep_gap_levels
  use, intrinsic :: iso_fortran_env, only: real64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use kcreep_status, only: status_t
  use kcreep_strings, only: itoa, rtoa
  use kcreep_patch, only: patch_t
  use kcreep_gap, only: gap_t, gap_resampled, gap_from_polynomial
  use kcreep_wheel_rail_geometry, only: plane_gap_grid
  use kcreep_problem, only: problem_t, result_t, append_prefixed, level_tolerance, cell_budget_or
  use kcreep_normal_stage, only: normal_patch, store_normal
  use kcreep_normal_solve, only: normal_result_t
  use kcreep_check, only: check_problem
  use kcreep_run, only: run_case, solve_cache_t
  use kcreep_verdict, only: message_length
  use kcreep_fastsim, only: fastsim_flexibilities
  use kcreep_refine_constants
  use kcreep_refine_estimate, only: level_estimate, within_target, coefficient_targets, min_estimate_cells, &
                                    level_cell_budget
  implicit none
  private
  public :: run_gap_patch, gap_single_estimate

  !> Power of c in f_ij = G c^p C_ij.
  integer, parameter :: c_power(3, 3) = reshape([2, 2, 3, 2, 2, 3, 3, 3, 4], [3, 3])
  real(real64), parameter :: pi = acos(-1.0_real64)

contains

  !> The normal problem, then the creep coefficients of its contact area,
  !> under error control (levels) or on the given grid with its estimate.
  subroutine run_gap_patch(problem, result, status, cache)
    type(problem_t), intent(in) :: problem
    type(result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    type(solve_cache_t), intent(inout), optional :: cache
    if (problem%target_error > 0 .and. problem%refine_grid) then
      call run_gap_levels(problem, result, status)
    else
      call run_gap_single(problem, result, status, cache)
    end if
  end subroutine run_gap_patch

  !> Normal and tangential solve with the undeformed distance gap.
  subroutine solve_gap(problem, gap, result, status, cache)
    type(problem_t), intent(in) :: problem
    type(gap_t), intent(in) :: gap
    type(result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    type(solve_cache_t), intent(inout), optional :: cache
    type(problem_t) :: found
    type(normal_result_t) :: nres
    found = problem
    found%normal%gap = gap
    call normal_patch(found, found%patch, nres, status)
    if (status%failed()) return
    call check_problem(found, status)
    if (status%failed()) return
    call run_case(found, result, status, cache)
    if (status%failed()) return
    call store_normal(nres, found%patch, result)
  end subroutine solve_gap

  !> The given grid and its estimate from the geometry on cells 1.5 and 2 times the size.
  subroutine run_gap_single(problem, result, status, cache)
    type(problem_t), intent(in) :: problem
    type(result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    type(solve_cache_t), intent(inout), optional :: cache
    type(result_t) :: aux(2)
    type(gap_t) :: coarse
    character(len=message_length) :: line
    real(real64) :: across, box(4), h
    integer :: i, k

    call solve_gap(problem, problem%normal%gap, result, status, cache)
    if (status%failed()) return
    result%err = ieee_value(1.0_real64, ieee_quiet_nan)
    if (.not. problem%estimate_error .and. problem%target_error == 0) return
    associate (gap => problem%normal%gap)
      h = sqrt(gap%dx * gap%dy)
      across = contact_diameter(result%patch) / (2 * h)
      if (across < min_estimate_cells) then
        line = 'no error estimate: the geometry on cells twice the size would have '//rtoa(across)// &
               ' cells across the contact area (4 area / perimeter), fewer than '//itoa(min_estimate_cells)// &
               ' (the grid is too coarse to judge itself; refine the gap''s grid, cells_across)'
        result%warnings = [result%warnings, line]
        return
      end if
      box = level_box(gap, result%bbox)
    end associate
    do k = 1, 2
      call level_gap(problem, box, gap_single_sizes(k) * h, coarse, status)
      if (status%failed()) return
      call solve_gap(problem, coarse, aux(k), status)
      if (status%failed()) return
      result%t_assemble = result%t_assemble + aux(k)%t_assemble
      result%t_factor = result%t_factor + aux(k)%t_factor
      result%t_solve = result%t_solve + aux(k)%t_solve
      result%t_total = result%t_total + aux(k)%t_total
    end do
    do i = 1, 3
      result%err(i) = gap_single_estimate(result%cn(i), aux(1)%cn(i), aux(2)%cn(i))
    end do
  end subroutine run_gap_single

  !> The error of a gap patch's coefficient on one grid from the geometry on
  !> cells 1.5 and 2 times the size: to first order f(h) - f0 = f(2h) - f(h) =
  !> 2 (f(1.5h) - f(h)); the larger of the two, times 3 for the noise of the
  !> contact boundary, which moves between the grids (measured on Hertzian gaps,
  !> Rx/Ry = 0.5, 1, 2 at 24 to 64 cells across, 99 cases: factor 2 with the 2h
  !> grid alone bounded 88, this rule 97; docs/accuracy.md).
  pure real(real64) function gap_single_estimate(f_h, f_15h, f_2h) result(rel_error)
    real(real64), intent(in) :: f_h, f_15h, f_2h
    rel_error = gap_single_factor * max(abs(f_h - f_2h), 2 * abs(f_h - f_15h)) / abs(f_h)
  end function gap_single_estimate

  !> Levels of finer geometry, refined until the estimates meet the target.
  subroutine run_gap_levels(problem, result, status)
    type(problem_t), intent(in) :: problem
    type(result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    type(patch_t) :: first
    type(normal_result_t) :: nres
    type(gap_t) :: gap
    integer, allocatable :: done(:), want(:), idx(:)
    real(real64), allocatable :: cnorm(:, :, :), area(:)
    character(len=message_length), allocatable :: warnings(:)
    character(len=message_length) :: line
    real(real64) :: box(4), diameter, t(4), budget
    integer :: refinement, k
    type(problem_t) :: level_problem

    ! the contact area on the given grid: its size and where it is
    call normal_patch(problem, first, nres, status)
    if (status%failed()) return
    diameter = contact_diameter(first)
    box = level_box(problem%normal%gap, first%grid_box())

    allocate (done(0), cnorm(3, 3, 0), area(0), warnings(0))
    t = 0
    budget = cell_budget_or(problem, gap_budget_share * level_cell_budget(problem%target_error))
    level_problem = problem
    call level_tolerance(level_problem)
    do refinement = 0, max_refinements
      want = gap_base_levels * 2**refinement
      if (refinement > 0) then
        ! contact cells of the finest new level: area / h^2
        if (first%area() * (want(size(want)) / diameter)**2 > budget) then
          line = 'error control: refining to '//itoa(want(size(want)))//' cells across the contact area would '// &
                 'exceed about '//itoa(nint(budget))//' contact cells, stopped at '// &
                 itoa(want(size(want)) / 2)//' cells across (&solver cell_budget raises it)'
          warnings = [warnings, line]
          want = gap_base_levels * 2**(refinement - 1)
          exit
        end if
      end if
      do k = 1, size(want)
        if (any(done == want(k))) cycle
        call level_gap(problem, box, diameter / want(k), gap, status)
        if (status%failed()) return
        call run_gap_level(level_problem, gap, want(k), result, cnorm, area, warnings, t, status)
        if (status%failed()) return
        done = [done, want(k)]
      end do
      idx = [(findloc(done, want(k), 1), k=1, size(want))]
      call fit_gap_levels(1.0_real64 / want, cnorm(:, :, idx), area(idx), result)
      if (within_target(result%err, coefficient_targets(problem%target_error))) exit
    end do
    result%t_assemble = t(1)
    result%t_factor = t(2)
    result%t_solve = t(3)
    result%t_total = t(4)
    result%warnings = warnings
  end subroutine run_gap_levels

  !> One level: solve, keep its own-area normalised coefficients, area and warnings.
  subroutine run_gap_level(problem, gap, label, result, cnorm, area, warnings, t, status)
    type(problem_t), intent(in) :: problem
    type(gap_t), intent(in) :: gap
    integer, intent(in) :: label
    type(result_t), intent(inout) :: result
    real(real64), allocatable, intent(inout) :: cnorm(:, :, :), area(:)
    character(len=message_length), allocatable, intent(inout) :: warnings(:)
    real(real64), intent(inout) :: t(4)
    type(status_t), intent(inout) :: status
    real(real64), allocatable :: c(:, :, :)

    call solve_gap(problem, gap, result, status)
    if (status%failed()) return
    t = t + [result%t_assemble, result%t_factor, result%t_solve, result%t_total]
    allocate (c(3, 3, size(cnorm, 3) + 1))
    c(:, :, 1:size(cnorm, 3)) = cnorm
    c(:, :, size(c, 3)) = result%f / (result%g * result%c**c_power)
    call move_alloc(c, cnorm)
    area = [area, pi * result%c**2]
    call append_prefixed(warnings, 'level '//itoa(label)//' (gap grid '//itoa(gap%mx)//' x '//itoa(gap%my)//'): ', &
                         result%warnings)
  end subroutine run_gap_level

  !> The fits: C_ij and the area extrapolated; f_ij = G c^p C_ij with c from
  !> the fitted area; err the estimates of C11, C22, C23.
  subroutine fit_gap_levels(h, cnorm, area, result)
    real(real64), intent(in) :: h(:), cnorm(:, :, :), area(:)
    type(result_t), intent(inout) :: result
    real(real64) :: limit(3, 3), rel(3, 3), a0, rel_area
    integer :: i, j
    do j = 1, 3
      do i = 1, 3
        call level_estimate(h, cnorm(i, j, :), limit(i, j), rel(i, j))
      end do
    end do
    call level_estimate(h, area, a0, rel_area)
    if (.not. (a0 > 0)) a0 = area(minloc(h, 1))   ! a degenerate fit: the finest level's area
    result%c = sqrt(a0 / pi)
    result%f = result%g * result%c**c_power * limit
    result%cn = [limit(1, 1), limit(2, 2), limit(2, 3)]
    result%err = [rel(1, 1), rel(2, 2), rel(2, 3)]
    ! FASTSIM's flexibilities of the finest contact area with the extrapolated f
    result%fastsim = fastsim_flexibilities(result%patch, result%f(1, 1), result%f(2, 2), result%f(2, 3))
  end subroutine fit_gap_levels

  !> The region the level grids cover: the contact area's bounding box (cell
  !> edges, xmin xmax ymin ymax) widened by gap_level_margin of its size and two
  !> cells of the given grid on every side, within the given gap's grid.
  pure function level_box(gap, bbox) result(box)
    type(gap_t), intent(in) :: gap
    real(real64), intent(in) :: bbox(4)
    real(real64) :: box(4), wx, wy
    wx = gap_level_margin * (bbox(2) - bbox(1)) + 2 * gap%dx
    wy = gap_level_margin * (bbox(4) - bbox(3)) + 2 * gap%dy
    box = [max(bbox(1) - wx, gap%x0 - gap%dx / 2), min(bbox(2) + wx, gap%x0 + (gap%mx - 0.5_real64) * gap%dx), &
           max(bbox(3) - wy, gap%y0 - gap%dy / 2), min(bbox(4) + wy, gap%y0 + (gap%my - 0.5_real64) * gap%dy)]
  end function level_box

  !> The undeformed distance on square cells of size h covering box (centred
  !> on it): the polynomial evaluated, or the given grid resampled.
  subroutine level_gap(problem, box, h, gap, status)
    type(problem_t), intent(in) :: problem
    real(real64), intent(in) :: box(4), h
    type(gap_t), intent(out) :: gap
    type(status_t), intent(inout) :: status
    integer :: mx, my
    real(real64) :: x0, y0
    mx = max(1, floor((box(2) - box(1)) / h + 1e-9_real64))
    my = max(1, floor((box(4) - box(3)) / h + 1e-9_real64))
    x0 = (box(1) + box(2)) / 2 - (mx - 1) * h / 2
    y0 = (box(3) + box(4)) / 2 - (my - 1) * h / 2
    if (problem%normal%poly_given) then
      call gap_from_polynomial(problem%normal%poly, mx, my, h, h, x0, y0, gap, status)
    else if (allocated(problem%normal%plane)) then
      call plane_gap_grid(problem%normal%plane, mx, my, h, h, x0, y0, gap)
    else
      gap = gap_resampled(problem%normal%gap, mx, my, h, h, x0, y0)
    end if
  end subroutine level_gap

  !> The size the levels are counted across: 4 area / perimeter of the contact
  !> area (its hydraulic diameter: a circle's diameter, 0.79 times the short axis
  !> of a long ellipse, each lobe's diameter for two equal round lobes), the
  !> perimeter from the staircase's, times pi/4 (the mean ratio of a curve's
  !> length to that of its staircase over all directions).
  pure real(real64) function contact_diameter(patch) result(d)
    type(patch_t), intent(in) :: patch
    logical, allocatable :: inside(:, :)
    integer :: k, edges_x, edges_y
    allocate (inside(0:patch%mx + 1, 0:patch%my + 1))
    inside = .false.
    do k = 1, patch%n
      inside(patch%ix(k), patch%iy(k)) = .true.
    end do
    edges_x = count(inside(0:patch%mx, :) .neqv. inside(1:patch%mx + 1, :))   ! edges of length dy
    edges_y = count(inside(:, 0:patch%my) .neqv. inside(:, 1:patch%my + 1))   ! edges of length dx
    d = 4 * patch%area() / (pi / 4 * (edges_x * patch%dy + edges_y * patch%dx))
  end function contact_diameter

end module kcreep_gap_levels
