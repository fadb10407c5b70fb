!> Error control of a patch found by the normal contact problem (shape 'gap').
!>
!> The contact area is where the pressure is positive; its boundary is only
!> resolved by the normal problem on a finer grid (the polynomial evaluated,
!> a gap given on a grid resampled by kcreep_gap gap_resampled). Splitting the
!> cells of one contact area would only refine its staircase.
!>
!> Error control (target_error > 0 and refine_grid): the normal problem on
!> the given grid finds where the contact area is and its hydraulic diameter
!> 4 area / perimeter (contact_diameter); then again on cells twice the
!> fine size over the area's bounding box widened by a margin, and on cells
!> gap_normal_cells across its level_size (kcreep_region) over the area
!> found there, widened likewise (the coarse pressure starts the fine solve;
!> both to gap_normal_tolerance). The cells are square, or longer along a
!> long thin area (normal_cell_shape). The tangential
!> levels (kcreep_level_ladder, the ellipses' ladder) sample the fine
!> contact area with a blended edge (each cell weighted by its part inside
!> the area), so every level describes the same shape, on cells as much
!> longer along the area's longer axis. The ladder's estimate is combined
!> in quadrature with the normal grid's own (normal_grid_estimate, from the
!> changes of the contact area's aspect ratio and centre: fine grid moved
!> by half a cell, and coarse grid to fine). c = sqrt(area / pi) of the fine contact area;
!> FASTSIM's pressure is the fine pressure at the finest level's cells
!> (kcreep_region region_pressure).
!>
!> A single grid (target_error = 0, or refine_grid off): the gap's grid as
!> given, and as estimate gap_single_estimate from the geometry on cells 1.5
!> and 2 times the size, or NaN and a warning when the coarser grid would have
!> fewer than min_estimate_cells cells across the contact area.
module kcreep_gap_levels
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use kcreep_status, only: status_t
  use kcreep_strings, only: itoa, rtoa
  use kcreep_patch, only: patch_t
  use kcreep_gap, only: gap_t, gap_resampled, gap_from_polynomial
  use kcreep_wheel_rail_geometry, only: plane_gap_grid
  use kcreep_problem, only: problem_t, result_t, cell_budget_or
  use kcreep_normal_stage, only: normal_patch, store_normal
  use kcreep_normal_solve, only: normal_result_t
  use kcreep_check, only: check_problem
  use kcreep_run, only: run_case, solve_cache_t
  use kcreep_verdict, only: message_length
  use kcreep_region, only: region_t, sampled_region, region_pressure, contact_diameter, level_size, contour_area
  use kcreep_level_ladder, only: run_shape_levels, region_finest_cells
  use kcreep_solve_memory, only: normal_solve_bytes, region_patch_bytes
  use kcreep_staircase_normalisation, only: moment_reference_t, contour_reference, aspect_slopes
  use kcreep_table_interpolation, only: table_coefficients, table_ratio_range, table_nu_range
  use kcreep_refine_constants
  use kcreep_refine_estimate, only: min_estimate_cells, default_target_error, level_cell_budget
  implicit none
  private
  public :: run_gap_patch, gap_single_estimate, normal_grid_cells, gap_levels_need

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
               ' (the grid is too coarse to judge itself; '//finer_grid()//')'
        result%warnings = [result%warnings, line]
        return
      end if
      box = level_box(gap, result%bbox)
    end associate
    do k = 1, 2
      call level_gap(problem, box, [1, 1] * gap_single_sizes(k) * h, coarse, status)
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
  contains

    !> What the user can set for a finer grid, by where the gap comes from.
    function finer_grid() result(text)
      character(len=:), allocatable :: text
      if (allocated(problem%normal%plane)) then
        text = 'with &wheel_rail set &solver target_error > 0, e.g. 1e-2, and kcreep chooses the grids'
      else if (problem%normal%poly_given) then
        text = 'raise &normal cells_across, or set &solver target_error > 0 and leave the grid to kcreep'
      else
        text = 'give the gap on a finer grid'
      end if
    end function finer_grid

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

  !> The normal problem on a fine grid, then the ladder of kcreep_level_ladder
  !> on the contact area found; its estimates with the normal grid's own
  !> (normal_grid_estimate).
  subroutine run_gap_levels(problem, result, status)
    type(problem_t), intent(in) :: problem
    type(result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    type(patch_t) :: fine, coarse, moved
    type(normal_result_t) :: fine_normal, coarse_normal, moved_normal
    type(region_t) :: region, coarse_region, moved_region
    real(real64) :: box(4)
    real(real64) :: cell(2)   !< the fine normal grid's cell sizes in x and y

    call fine_contact_area(problem, coarse, coarse_normal, fine, fine_normal, box, cell, status)
    if (status%failed()) return
    region = sampled_region(fine, fine_normal%pressure, status)
    if (status%failed()) return
    coarse_region = sampled_region(coarse, coarse_normal%pressure, status, moments_only=.true.)
    if (status%failed()) return
    ! the fine grid once more, moved by half a cell in x and y: how far its
    ! placement alone moves the contact area (normal_grid_estimate); the
    ! fine pressure starts it
    call contact_area_on(problem, box + [cell(1), cell(1), cell(2), cell(2)] / 2, cell, moved, moved_normal, status, &
                         fine, fine_normal%pressure)
    if (status%failed()) return
    moved_region = sampled_region(moved, moved_normal%pressure, status, moments_only=.true.)
    if (status%failed()) return
    call run_shape_levels(problem, result, status, region, &
                          normal_grid_estimate(region, coarse_region, moved_region, problem%nu))
    if (status%failed()) return
    call store_normal(fine_normal, fine, result)
    ! the pressure at the finest level's cells, scaled to the normal force
    ! found (sampling the interpolated pressure moves its sum by about 1e-4)
    result%pressure = region_pressure(region, result%patch)
    result%pressure = result%pressure * (fine_normal%fn / (sum(result%pressure) * result%patch%dx * result%patch%dy))
    result%bbox = region%reference%cells_box()
  end subroutine run_gap_levels

  !> What run_gap_levels needs at its peak, from its contact area on the
  !> fine normal grid (the normal problem solved as run_gap_levels solves
  !> it, the levels not): bytes beside the program's own
  !> (kcreep_solve_memory region_patch_bytes: the larger of the given grid's
  !> normal solve and the ladder's finest level at region_level_cap with the
  !> fine normal grid) and that level's grid cells.
  subroutine gap_levels_need(problem, bytes, box_cells, status)
    type(problem_t), intent(in) :: problem
    integer(int64), intent(out) :: bytes
    real(real64), intent(out) :: box_cells
    type(status_t), intent(inout) :: status
    type(patch_t) :: fine, coarse
    type(normal_result_t) :: fine_normal, coarse_normal
    type(region_t) :: region
    real(real64) :: box(4), cell(2), contact_cells
    bytes = 0
    box_cells = 0
    call fine_contact_area(problem, coarse, coarse_normal, fine, fine_normal, box, cell, status)
    if (status%failed()) return
    region = sampled_region(fine, fine_normal%pressure, status)
    if (status%failed()) return
    call region_finest_cells(problem, region, box_cells, contact_cells)
    bytes = max(normal_solve_bytes(real(problem%normal%gap%mx, real64) * problem%normal%gap%my), &
                region_patch_bytes(real(fine%mx, real64) * fine%my, box_cells, contact_cells))
  end subroutine gap_levels_need

  !> The contact area on the given grid, on a coarse grid of cells 2 cell
  !> over box, and on the fine grid of cells `cell` over box.
  subroutine fine_contact_area(problem, coarse, coarse_normal, fine, fine_normal, box, cell, status)
    type(problem_t), intent(in) :: problem
    type(patch_t), intent(out) :: coarse, fine
    type(normal_result_t), intent(out) :: coarse_normal, fine_normal
    real(real64), intent(out) :: box(4), cell(2)
    type(status_t), intent(inout) :: status
    type(patch_t) :: first, located
    type(normal_result_t) :: nres, located_normal
    real(real64) :: wide(4), target, max_cells, shape(2), m(2)

    ! the contact area on the given grid: its size, where it is, and its
    ! length / width (second moments), which sets the cells' shape
    call normal_patch(problem, first, nres, status)
    if (status%failed()) return
    wide = level_box(problem%normal%gap, first%grid_box())
    target = level_size(first) / gap_normal_cells(problem%target_error)
    m = first%second_moments(first%centroid())
    shape = normal_cell_shape(sqrt(m(1) / m(2)))
    max_cells = normal_grid_cells(problem)
    ! on cells twice the fine ones over the wide box: where the contact is,
    ! to a coarse cell; the fine grid covers only that (a thin strip's box
    ! on the given grid is 2-4 times its area)
    cell = capped_cells(wide, target, max_cells, shape)
    call contact_area_on(problem, wide, 2 * cell, coarse, coarse_normal, status)
    if (status%failed()) return
    box = widened_box(coarse%cells_box(), 2 * cell(1), 2 * cell(2), wide)
    if (any(capped_cells(box, target, max_cells, shape) < cell)) then
      ! a long thin area (a flange contact) is held to max_cells:
      ! the smaller box lets it have smaller cells; the coarse grid follows
      cell = capped_cells(box, target, max_cells, shape)
      located = coarse
      located_normal = coarse_normal
      call contact_area_on(problem, box, 2 * cell, coarse, coarse_normal, status, located, located_normal%pressure)
      if (status%failed()) return
    end if
    ! the coarse pressure starts the fine solve (fewer CG steps)
    call contact_area_on(problem, box, cell, fine, fine_normal, status, coarse, coarse_normal%pressure)
  end subroutine fine_contact_area

  !> The contact area of the normal problem on cells of sizes h(1) x h(2)
  !> over box; from_patch, from_pressure: a coarser solution to start from.
  subroutine contact_area_on(problem, box, h, patch, nres, status, from_patch, from_pressure)
    type(problem_t), intent(in) :: problem
    real(real64), intent(in) :: box(4), h(2)
    type(patch_t), intent(out) :: patch
    type(normal_result_t), intent(out) :: nres
    type(status_t), intent(inout) :: status
    type(patch_t), intent(in), optional :: from_patch
    real(real64), intent(in), optional :: from_pressure(:, :)
    type(problem_t) :: on_grid
    on_grid = problem
    if (.not. problem%normal%options%tolerance_given) on_grid%normal%options%tolerance = gap_normal_tolerance
    call level_gap(problem, box, h, on_grid%normal%gap, status)
    if (status%failed()) return
    if (present(from_patch) .and. present(from_pressure)) then
      call normal_patch(on_grid, patch, nres, status, start=pressure_on(from_patch, from_pressure, on_grid%normal%gap))
    else
      call normal_patch(on_grid, patch, nres, status)
    end if
  end subroutine contact_area_on

  !> A pressure given on the bounding box of `patch` (its cells' grid) on
  !> the cells of the gap's grid: bilinear between the given cell centres,
  !> zero beyond them.
  pure function pressure_on(patch, pressure, gap) result(p)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: pressure(:, :)
    type(gap_t), intent(in) :: gap
    real(real64) :: p(gap%mx, gap%my), fx, fy
    integer :: ix, iy, i, j
    do iy = 1, gap%my
      fy = (gap%cell_y(iy) - patch%y0) / patch%dy + 1
      j = floor(fy)
      do ix = 1, gap%mx
        fx = (gap%cell_x(ix) - patch%x0) / patch%dx + 1
        i = floor(fx)
        p(ix, iy) = (1 - (fx - i)) * (1 - (fy - j)) * at(i, j) + (fx - i) * (1 - (fy - j)) * at(i + 1, j) + &
                    (1 - (fx - i)) * (fy - j) * at(i, j + 1) + (fx - i) * (fy - j) * at(i + 1, j + 1)
      end do
    end do
  contains
    pure real(real64) function at(i, j)
      integer, intent(in) :: i, j
      at = 0
      if (i >= 1 .and. i <= size(pressure, 1) .and. j >= 1 .and. j <= size(pressure, 2)) at = pressure(i, j)
    end function at
  end function pressure_on

  !> Cells across the contact area's hydraulic diameter of the normal
  !> problem's fine grid: gap_normal_cells_at_default at the default target
  !> and looser, gap_normal_cells_below_default for tighter targets.
  pure real(real64) function gap_normal_cells(target) result(cells)
    real(real64), intent(in) :: target
    cells = gap_normal_cells_at_default
    if (target < default_target_error) cells = gap_normal_cells_below_default
  end function gap_normal_cells

  !> The most cells the fine normal grid may have: normal_grid_budget_share
  !> of the level cell budget (the caller's or the target's).
  pure real(real64) function normal_grid_cells(problem) result(cells)
    type(problem_t), intent(in) :: problem
    cells = normal_grid_budget_share * cell_budget_or(problem, level_cell_budget(problem%target_error))
  end function normal_grid_cells

  !> The error the normal problem's grid leaves in C11, C22, C23: the larger
  !> of the fine grid's placement noise (the change of the contact area when
  !> the fine grid is moved by half a cell) and normal_systematic_share of
  !> the change from the coarse grid to the fine one (what a finer grid
  !> still removes).
  function normal_grid_estimate(fine, coarse, moved, nu) result(rel_error)
    type(region_t), intent(in) :: fine, coarse, moved
    real(real64), intent(in) :: nu
    real(real64) :: rel_error(3), slope(4), r_fine, c(4), rel(4), radius
    type(moment_reference_t) :: m_fine
    type(status_t) :: lookup
    m_fine = contour_reference(fine)
    r_fine = m_fine%semi_a / m_fine%semi_b
    slope = aspect_slopes(r_fine, nu)
    call table_coefficients(min(max(r_fine, table_ratio_range(1)), table_ratio_range(2)), &
                            min(max(nu, table_nu_range(1)), table_nu_range(2)), c, rel, lookup)
    radius = sqrt(contour_area(fine) / pi)
    rel_error = max(change_to(moved), normal_systematic_share * change_to(coarse))

  contains

    !> C11, C22, C23 relative change from the fine contact area to `other`:
    !> their aspect ratios (second moments) differ by r(fine) / r(other), and
    !> the C's follow with the refined table's slope d ln C / d ln(a/b)
    !> (their size is normalised out); their centres differ by dx along the
    !> rolling direction, and C23 about a fixed spin centre follows as
    !> C22 dx / (C23 c).
    function change_to(other) result(rel_change)
      type(region_t), intent(in) :: other
      real(real64) :: rel_change(3)
      type(moment_reference_t) :: m_other
      m_other = contour_reference(other)
      rel_change = abs(slope(1:3) * log(r_fine / (m_other%semi_a / m_other%semi_b)))
      rel_change(3) = rel_change(3) + c(2) / c(3) * abs(m_fine%centre(1) - m_other%centre(1)) / radius
    end function change_to

  end function normal_grid_estimate

  !> The region the level grids cover: the contact area's bounding box (cell
  !> edges, xmin xmax ymin ymax) widened by gap_level_margin of its size and two
  !> cells of the given grid on every side, within the given gap's grid.
  pure function level_box(gap, bbox) result(box)
    type(gap_t), intent(in) :: gap
    real(real64), intent(in) :: bbox(4)
    real(real64) :: box(4)
    box = widened_box(bbox, gap%dx, gap%dy, [gap%x0 - gap%dx / 2, gap%x0 + (gap%mx - 0.5_real64) * gap%dx, &
                                             gap%y0 - gap%dy / 2, gap%y0 + (gap%my - 0.5_real64) * gap%dy])
  end function level_box

  !> The normal grids' cells for a contact area `aspect` times as long in x
  !> as in y (below 1: long in y): their length in x and y in units of the
  !> cell across it. Square up to normal_cell_aspect_limit; a longer area's
  !> cells are aspect / normal_cell_aspect_limit times as long along it, so
  !> that its length keeps that many cells per cell across its width.
  pure function normal_cell_shape(aspect) result(shape)
    real(real64), intent(in) :: aspect
    real(real64) :: shape(2)
    shape = 1
    if (aspect > normal_cell_aspect_limit) shape(1) = aspect / normal_cell_aspect_limit
    if (aspect < 1 / normal_cell_aspect_limit) shape(2) = 1 / (aspect * normal_cell_aspect_limit)
  end function normal_cell_shape

  !> The fine normal grid's cell sizes in x and y: shape (normal_cell_shape)
  !> times target, or larger where box would have more than max_cells of
  !> them (a long thin area's box is large for its width; the normal grid's
  !> estimate grows with the cells).
  pure function capped_cells(box, target, max_cells, shape) result(h)
    real(real64), intent(in) :: box(4), target, max_cells, shape(2)
    real(real64) :: h(2)
    h = shape * max(target, sqrt((box(2) - box(1)) * (box(4) - box(3)) / (max_cells * product(shape))))
  end function capped_cells

  !> bbox (xmin xmax ymin ymax) widened by gap_level_margin of its size and
  !> two cells (hx, hy) on every side, within `within`: the contact area
  !> found on those cells is within a cell of a finer grid's.
  pure function widened_box(bbox, hx, hy, within) result(box)
    real(real64), intent(in) :: bbox(4), hx, hy, within(4)
    real(real64) :: box(4), wx, wy
    wx = gap_level_margin * (bbox(2) - bbox(1)) + 2 * hx
    wy = gap_level_margin * (bbox(4) - bbox(3)) + 2 * hy
    box = [max(bbox(1) - wx, within(1)), min(bbox(2) + wx, within(2)), &
           max(bbox(3) - wy, within(3)), min(bbox(4) + wy, within(4))]
  end function widened_box

  !> The undeformed distance on cells of sizes h(1) x h(2) covering box
  !> (centred on it): the polynomial evaluated, or the given grid resampled.
  subroutine level_gap(problem, box, h, gap, status)
    type(problem_t), intent(in) :: problem
    real(real64), intent(in) :: box(4), h(2)
    type(gap_t), intent(out) :: gap
    type(status_t), intent(inout) :: status
    integer :: mx, my
    real(real64) :: x0, y0
    mx = max(1, floor((box(2) - box(1)) / h(1) + 1e-9_real64))
    my = max(1, floor((box(4) - box(3)) / h(2) + 1e-9_real64))
    x0 = (box(1) + box(2)) / 2 - (mx - 1) * h(1) / 2
    y0 = (box(3) + box(4)) / 2 - (my - 1) * h(2) / 2
    if (problem%normal%poly_given) then
      call gap_from_polynomial(problem%normal%poly, mx, my, h(1), h(2), x0, y0, gap, status)
    else if (allocated(problem%normal%plane)) then
      call plane_gap_grid(problem%normal%plane, mx, my, h(1), h(2), x0, y0, gap)
    else
      gap = gap_resampled(problem%normal%gap, mx, my, h(1), h(2), x0, y0)
    end if
  end subroutine level_gap


end module kcreep_gap_levels
