!> The one driver of kcreep's level ladders: levels of a shape chosen by
!> kcreep, solved from coarse to fine until the estimates meet the target or
!> the cell budget stops them, or, on a contact area whose normal grid's
!> estimate alone misses the target, until the levels' own estimate meets
!> it (kcreep_refine_estimate levels_done; not on the first fit).
!>
!> The shape is an ellipse (problem%patch, kind 'ellipse') or a contact area
!> found by the normal problem on a fine grid (a kcreep_region). Levels: 56,
!> 64, 72, 84, 96 cells across (an ellipse's shorter axis; a contact area's
!> hydraulic diameter), then one level about 15 % finer at a time
!> (next_level) while an estimate is above its target. Each level has a
!> blended edge (kcreep_patch blended_patch: every cell the shape reaches,
!> weighted by its part inside), so that its f moves smoothly with the
!> cell size; each fit (shape_level_estimate: f0 + K h) runs through the
!> finest ellipse_fit_width levels.
!>
!> A mask's levels are the mask itself with every cell split k x k, k = 1,
!> 2, 3, ... (the staircase is the patch the user gave: it is not smoothed),
!> fitted by split_level_estimate through the finest split_fit_width
!> levels, up to the budget or max_split.
module kcreep_level_ladder
  use, intrinsic :: iso_fortran_env, only: real64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan, ieee_is_finite
  use kcreep_status, only: status_t, fail, exit_numerical
  use kcreep_strings, only: itoa, rtoa
  use kcreep_patch, only: patch_t, ellipse_patch, place_like
  use kcreep_region, only: region_t, region_level_patch, contour_area
  use kcreep_problem, only: problem_t, result_t, append_prefixed, level_tolerance, cell_budget_or, mark_uncertain
  use kcreep_run, only: run_case
  use kcreep_verdict, only: message_length
  use kcreep_fastsim, only: fastsim_flexibilities
  use kcreep_refine_estimate
  use kcreep_refine_constants
  use kcreep_staircase_normalisation, only: moment_reference_t, contour_reference
  use kcreep_grid_transfer, only: transferred_traction
  use kcreep_extrapolation, only: refined_patch
  implicit none
  private
  public :: run_shape_levels, ellipse_base_levels, finest_split, region_level_cap, region_finest_cells

  real(real64), parameter :: pi = acos(-1.0_real64)

contains

  !> The ladder of an ellipse (problem%patch), of the contact area `region`,
  !> or of a mask (problem%patch split k x k); other_error: estimates of
  !> C11, C22, C23 the levels cannot reduce (a contact area's normal grid),
  !> combined with the ladder's own in quadrature (two independent 95 %
  !> bounds; their plain sum bounded the 15 Hertzian gaps at a median
  !> estimate / error of 4.2 on staircase levels; the quadrature on blended
  !> levels bounds 45 of 45, docs/accuracy.md, "Gaps").
  subroutine run_shape_levels(problem, result, status, region, other_error)
    type(problem_t), intent(in) :: problem
    type(result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    type(region_t), intent(in), optional :: region
    real(real64), intent(in), optional :: other_error(3)
    type(problem_t) :: level_problem
    integer, allocatable :: levels(:)              !< cells across, or the split k (the ladder)
    real(real64), allocatable :: fnorm(:, :, :)    !< (3, 3, level) each level's f
    real(real64), allocatable :: guess(:, :)       !< the last level's tractions on this level's cells
    character(len=message_length), allocatable :: warnings(:)
    character(len=message_length) :: line
    integer :: k, finest, first, fit_min, fit_width, j
    real(real64) :: t(4), budget
    real(real64) :: own_error(3)   !< the levels' own estimates of C11, C22, C23 (without other_error)
    logical :: long_in_y
    real(real64) :: cell_shape(2)   !< a contact area's level cells: length in x and y, in units of the square cell
    real(real64) :: level_scale     !< a contact area's cells across on short cells per cells across on long ones
    integer :: first_base           !< the first level the estimate was calibrated at (scaled for a long area)
    integer :: level_cap            !< the finest level the ladder may take (cells across)
    logical :: split          !< a mask: every cell split k x k, the same staircase on every level
    logical :: no_fit         !< the fit gave no number: the finest level's f, no estimate

    allocate (fnorm(3, 3, 0), warnings(0))
    cell_shape = 1
    first_base = base_levels(1)
    level_cap = huge(1)
    t = 0
    level_problem = problem
    call level_tolerance(level_problem)
    budget = cell_budget_or(problem, level_cell_budget(problem%target_error))
    split = .not. present(region) .and. problem%patch%kind /= 'ellipse'
    ! levels of a shape long in y on cells long in y (an ellipse's, a contact area's)
    long_in_y = .not. split .and. ellipse_cells_long_in_y(problem%target_error, problem%scheme%name)
    fit_min = ellipse_fit_min
    fit_width = ellipse_fit_width
    if (split) then
      levels = [(j, j=1, split_min_levels)]
      fit_min = split_min_levels
      fit_width = split_fit_width
      ! the fit amplifies the levels' solver error: a tighter residual (split_tolerance_share)
      if (.not. problem%solve%tolerance_given) level_problem%solve%tolerance = &
        min(level_problem%solve%tolerance, split_tolerance_share * problem%target_error)
    else if (present(region)) then
      cell_shape = region_cell_shape(problem, region)
      ! fewer cells across on short cells: each level keeps the cell count
      ! of cells as long as the area (region_level_scale)
      level_scale = region_level_scale(problem, region)
      first_base = max(min_base_cells, nint(base_levels(1) * level_scale))
      level_cap = scaled_level_cap(problem, region)
      levels = distinct_levels(nint(base_levels * level_scale * &
                                    min(1.0_real64, sqrt(budget / region_cells(region, &
                                    base_levels(size(base_levels)), area_cell_shape(problem, region))))))
    else
      levels = ellipse_base_levels(problem%patch%semi_a, problem%patch%semi_b, budget, long_in_y)
    end if
    k = 1
    do
      call level_patch(levels(k), level_problem%patch, status)
      if (status%failed()) return
      ! the last level's tractions carried over: GMRES starts closer (fewer
      ! iterations); unallocated on the first level, where it counts as absent
      if (k > 1) guess = transferred_traction(result%patch, result%traction, level_problem%patch)
      call run_level(level_problem, levels(k), result, fnorm, warnings, t, status, guess)
      if (status%failed()) return
      if (k == size(levels) .and. k >= fit_min) then
        first = max(1, k - fit_width + 1)
        call fit_levels(1.0_real64 / levels(first:k), fnorm(:, :, first:k), split, result)
        own_error = result%err
        ! the normal grid's error and the levels' are independent: in quadrature
        if (present(other_error)) result%err = sqrt(result%err**2 + other_error**2)
        if (within_target(result%err, coefficient_targets(problem%target_error), problem%requested)) exit
        ! a normal grid that misses the target alone: the levels stop where
        ! their own estimate meets it, but not on the first fit (the 5.8 mm
        ! row's C23 at 96 across: own 0.9e-3, 3.7e-3 from the same row on
        ! levels up to 392; the next level's fit showed it, 4.6e-3)
        if (present(other_error) .and. k > fit_min) then
          if (levels_done(own_error, other_error, coefficient_targets(problem%target_error), problem%requested)) then
            warnings = [warnings, beyond_levels(other_error, levels(k))]
            exit
          end if
        end if
        if (split) then
          finest = levels(k) + 1
        else
          finest = next_level(levels(k))
        end if
        line = stop_reason(finest)
        if (len_trim(line) > 0) then
          warnings = [warnings, line]
          exit
        end if
        levels = [levels, finest]
      end if
      k = k + 1
    end do
    ! a fit that gives no number (never seen since the levels are kept
    ! distinct): the finest level's f without an estimate; no finite level:
    ! a failure, never a row of NaN
    ! (entries of load cases not asked for are NaN on every level: not a failed fit)
    no_fit = any(.not. ieee_is_finite(result%f) .and. ieee_is_finite(fnorm(:, :, size(fnorm, 3))))
    if (.not. any(ieee_is_finite(fnorm(:, :, size(fnorm, 3))))) then
      call fail(status, exit_numerical, 'error control: the finest level ('//itoa(levels(size(levels)))// &
                ' cells across) gave no finite creep force; no coefficients')
      return
    end if
    if (no_fit) then
      result%f = fnorm(:, :, size(fnorm, 3))
      result%err = ieee_value(1.0_real64, ieee_quiet_nan)
    end if
    if (present(region)) result%c = sqrt(contour_area(region) / pi)
    call finish_result(result, t)
    result%warnings = warnings
    if (no_fit) call mark_uncertain(result, 'uncertain: no error estimate: the fit over the levels '// &
                                    itoa(levels(1))//'-'//itoa(levels(size(levels)))//' gave no number; '// &
                                    'the coefficients are the finest level''s')
    ! collocation's levels of a sampled shape tend to a limit 0.07-0.15 % off
    ! the continuum, beyond their estimates (solved ellipses a/b = 0.5 to 5
    ! against the refined table, docs/accuracy.md, "Ellipses"): no `ok`
    if (.not. split .and. problem%scheme%name == 'collocation') &
      call mark_uncertain(result, 'uncertain: the estimate of levels is calibrated for the backward scheme; '// &
                          'with collocation the limit is up to 0.15 % off (scheme = ''backward'' for error control)')
    ! the budget scaled a long shape's levels below the range the estimate
    ! was calibrated on: its estimate is not known to bound the error
    if (.not. split .and. levels(1) < first_base) &
      call mark_uncertain(result, 'uncertain: the cell budget scaled the levels down to '//itoa(levels(1))//'-'// &
                          itoa(levels(size(levels)))//' cells across, below the '//itoa(first_base)// &
                          ' where the estimate was calibrated (&solver cell_budget raises it)')

  contains

    subroutine level_patch(level, patch, status)
      integer, intent(in) :: level
      type(patch_t), intent(out) :: patch
      type(status_t), intent(inout) :: status
      integer :: mx, my
      if (split) then
        call refined_patch(problem%patch, level, patch, status)
      else if (present(region)) then
        call region_level_patch(region, level, cell_shape, patch, status)
      else
        call ellipse_level_grid(problem%patch%semi_a, problem%patch%semi_b, level, mx, my, long_in_y)
        call ellipse_patch(problem%patch%semi_a, problem%patch%semi_b, mx, my, patch, status, blended=.true.)
        if (.not. status%failed()) call place_like(patch, problem%patch)
      end if
    end subroutine level_patch

    !> Why the ladder may not go on to level `level` ('' if it may).
    function stop_reason(level) result(why)
      integer, intent(in) :: level
      character(len=message_length) :: why
      integer :: mx, my
      real(real64) :: patch_cells
      why = ''
      if (split) then
        if (level <= finest_split(problem%patch%n, budget)) return
        if (level > max_split) then
          why = 'error control: stopped at '//itoa(level - 1)//' x '//itoa(level - 1)//' subcells per cell, '// &
                'the finest split kcreep tries (the estimates did not come down to the target)'
        else
          why = 'error control: splitting every cell in '//itoa(level)//' x '//itoa(level)//' would exceed '// &
                'the budget of '//itoa(nint(budget))//' patch cells at target_error '// &
                rtoa(problem%target_error)//', stopped at '//itoa(level - 1)//' x '//itoa(level - 1)// &
                ' (&solver cell_budget raises it)'
        end if
        return
      end if
      if (present(region)) then
        if (level > level_cap) then
          why = 'error control: stopped at '//itoa(levels(size(levels)))//' cells across, the finest level '// &
                'of a contact area when no cell budget is given (the limit --estimate-memory counts; &solver '// &
                'cell_budget lifts it, and the estimate then counts the whole budget)'
          return
        end if
        patch_cells = region_cells(region, level, cell_shape)
      else
        call ellipse_level_grid(problem%patch%semi_a, problem%patch%semi_b, level, mx, my, long_in_y)
        patch_cells = ellipse_fill * mx * my
      end if
      if (patch_cells > budget) &
        why = 'error control: the next level, '//itoa(level)//' cells across ('//itoa(nint(patch_cells))// &
              ' cells), would exceed the budget of '//itoa(nint(budget))//' patch cells at target_error '// &
              rtoa(problem%target_error)//', stopped at '//itoa(levels(size(levels)))// &
              ' cells across (&solver cell_budget raises it)'
    end function stop_reason

  end subroutine run_shape_levels

  !> Why the levels stopped with an estimate above the target: the normal
  !> grid's part (other_error) misses it by itself.
  function beyond_levels(other_error, finest) result(line)
    real(real64), intent(in) :: other_error(3)
    integer, intent(in) :: finest
    character(len=message_length) :: line
    line = 'error control: the normal grid''s own estimate (C11, C22, C23: '//rtoa(other_error(1))//', '// &
           rtoa(other_error(2))//', '//rtoa(other_error(3))//') misses the target, which finer levels cannot '// &
           'change; the levels stopped at '//itoa(finest)//' cells across, where their own estimate meets it'
  end function beyond_levels

  !> The finest split a patch of n cells may get: the largest k with n k^2
  !> within the budget, at most max_split, at least split_min_levels (the
  !> fewest the fit needs).
  pure integer function finest_split(n, budget) result(k)
    integer, intent(in) :: n
    real(real64), intent(in) :: budget
    k = max(split_min_levels, min(max_split, floor(sqrt(budget / max(n, 1)))))
  end function finest_split

  !> The finest level a contact area's ladder may take (cells across):
  !> region_max_level when the caller gave no cell budget and the target is
  !> the default or looser, else no limit but the budget's.
  pure integer function region_level_cap(problem) result(level)
    type(problem_t), intent(in) :: problem
    level = huge(1)
    if (.not. problem%cell_budget > 0 .and. problem%target_error >= default_target_error) level = region_max_level
  end function region_level_cap

  !> The grid cells (its bounding box) and the cells inside of the finest
  !> level a contact area's ladder may reach: at region_level_cap, or the
  !> budget's when that is the smaller (what kcreep_solve_memory counts).
  pure subroutine region_finest_cells(problem, region, box_cells, contact_cells)
    type(problem_t), intent(in) :: problem
    type(region_t), intent(in) :: region
    real(real64), intent(out) :: box_cells, contact_cells
    real(real64) :: shape(2), at_cap
    integer :: cap
    box_cells = cell_budget_or(problem, level_cell_budget(problem%target_error))
    contact_cells = box_cells
    cap = scaled_level_cap(problem, region)
    if (cap == huge(1)) return
    shape = region_cell_shape(problem, region)
    at_cap = region_cells(region, cap, shape)
    if (at_cap < box_cells) then
      box_cells = at_cap
      contact_cells = contour_area(region) * (cap / region%diameter)**2 / product(shape)
    end if
  end subroutine region_finest_cells

  !> A contact area's level cells, length in x and y in units of the square
  !> cell: longer along the area's longer axis, at most region_cell_aspect
  !> times (area_cell_shape, capped).
  pure function region_cell_shape(problem, region) result(cell_shape)
    type(problem_t), intent(in) :: problem
    type(region_t), intent(in) :: region
    real(real64) :: cell_shape(2)
    cell_shape = min(area_cell_shape(problem, region), region_cell_aspect)
  end function region_cell_shape

  !> Cells as much longer along the area's longer axis as the area is long,
  !> up to max_cell_aspect: what a level's cell count is reckoned on
  !> (region_level_scale); collocation is not put on long cells.
  pure function area_cell_shape(problem, region) result(cell_shape)
    type(problem_t), intent(in) :: problem
    type(region_t), intent(in) :: region
    real(real64) :: cell_shape(2)
    type(moment_reference_t) :: ref
    cell_shape = 1
    if (problem%scheme%name /= 'backward') return
    ref = contour_reference(region)
    cell_shape = min(max([ref%semi_a / ref%semi_b, ref%semi_b / ref%semi_a], 1.0_real64), max_cell_aspect)
  end function area_cell_shape

  !> A contact area's levels on region_cell_shape's short cells have this
  !> times the cells across of levels on area_cell_shape's: the same cell
  !> count (1 on an area at most region_cell_aspect times as long as wide).
  pure real(real64) function region_level_scale(problem, region) result(scale)
    type(problem_t), intent(in) :: problem
    type(region_t), intent(in) :: region
    scale = sqrt(product(region_cell_shape(problem, region)) / product(area_cell_shape(problem, region)))
  end function region_level_scale

  !> region_level_cap on a contact area's short cells: scaled like its
  !> levels, so that the finest level keeps the cell count that
  !> --estimate-memory counts.
  pure integer function scaled_level_cap(problem, region) result(level)
    type(problem_t), intent(in) :: problem
    type(region_t), intent(in) :: region
    level = region_level_cap(problem)
    if (level < huge(1)) level = nint(level * region_level_scale(problem, region))
  end function scaled_level_cap

  !> What a contact area's level of `cells` across counts against the budget:
  !> the cells of its grid (the area's bounding box), not only its patch
  !> cells; the iterative solver's transforms run over the whole grid, and a
  !> thin curved area (a flange contact) fills a small part of its box.
  pure real(real64) function region_cells(region, cells, cell_shape)
    type(region_t), intent(in) :: region
    integer, intent(in) :: cells
    real(real64), intent(in) :: cell_shape(2)
    real(real64) :: box(4)
    box = region%reference%grid_box()
    region_cells = (box(2) - box(1)) * (box(4) - box(3)) * (cells / region%diameter)**2 / product(cell_shape)
  end function region_cells

  !> An ellipse's base levels; a long one's scaled down so that the finest keeps to the budget.
  pure function ellipse_base_levels(a, b, budget, long_in_y) result(levels)
    real(real64), intent(in) :: a, b, budget
    logical, intent(in) :: long_in_y
    integer :: levels(size(base_levels)), mx, my
    call ellipse_level_grid(a, b, base_levels(size(base_levels)), mx, my, long_in_y)
    levels = distinct_levels(nint(base_levels * min(1.0_real64, sqrt(budget / (ellipse_fill * mx * my)))))
  end function ellipse_base_levels

  !> Scaled base levels, at least min_base_cells and each at least
  !> min_level_step finer than the one before: the fit f0 + K h needs
  !> distinct h. All clamped to 32 (a thin area of a noisy measured profile
  !> whose box far exceeds the budget: avg_wheel.whl on avg_HR.BAN without
  !> smoothing at shifts 7.5-10 mm) the fit divided by zero and the row's
  !> C's were NaN.
  pure function distinct_levels(scaled) result(levels)
    integer, intent(in) :: scaled(:)
    integer :: levels(size(scaled)), k
    levels = max(min_base_cells, scaled)
    do k = 2, size(levels)
      levels(k) = max(levels(k), levels(k - 1) + min_level_step)
    end do
  end function distinct_levels

  !> One level: solve, keep its f and its warnings; the result is the
  !> level's. guess: tractions to start the iterative solver from.
  subroutine run_level(level_problem, label, result, fnorm, warnings, t, status, guess)
    type(problem_t), intent(in) :: level_problem
    integer, intent(in) :: label
    type(result_t), intent(inout) :: result
    real(real64), allocatable, intent(inout) :: fnorm(:, :, :)
    character(len=message_length), allocatable, intent(inout) :: warnings(:)
    real(real64), intent(inout) :: t(4)
    type(status_t), intent(inout) :: status
    real(real64), intent(in), optional :: guess(:, :)
    real(real64), allocatable :: f(:, :, :)

    call run_case(level_problem, result, status, guess=guess)
    if (status%failed()) return
    t = t + [result%t_assemble, result%t_factor, result%t_solve, result%t_total]
    allocate (f(3, 3, size(fnorm, 3) + 1))
    f(:, :, 1:size(fnorm, 3)) = fnorm
    f(:, :, size(f, 3)) = result%f
    call move_alloc(f, fnorm)
    call append_prefixed(warnings, 'level '//itoa(label)//' ('//itoa(level_problem%patch%mx)//' x '// &
                         itoa(level_problem%patch%my)//'): ', result%warnings)
  end subroutine run_level

  !> The fit of every f entry: the result gets the limits, err those of C11, C22, C23.
  subroutine fit_levels(h, fnorm, split, result)
    real(real64), intent(in) :: h(:), fnorm(:, :, :)
    !> levels of a split patch (split_level_estimate), else of a sampled shape (shape_level_estimate)
    logical, intent(in) :: split
    type(result_t), intent(inout) :: result
    real(real64) :: limit, rel
    integer :: i, j
    result%err = ieee_value(1.0_real64, ieee_quiet_nan)
    do j = 1, 3
      do i = 1, 3
        if (any(ieee_is_nan(fnorm(i, j, :)))) then
          result%f(i, j) = ieee_value(1.0_real64, ieee_quiet_nan)
          cycle
        end if
        if (split) then
          call split_level_estimate(h, fnorm(i, j, :), limit, rel)
        else
          call shape_level_estimate(h, fnorm(i, j, :), limit, rel)
        end if
        result%f(i, j) = limit
        if (i == 1 .and. j == 1) result%err(1) = rel
        if (i == 2 .and. j == 2) result%err(2) = rel
        if (i == 2 .and. j == 3) result%err(3) = rel
      end do
    end do
  end subroutine fit_levels

  !> result%f holds the limits (of the shape; a mask: of its cells). The
  !> C's and summed times; the cells of the answer.
  subroutine finish_result(result, t)
    type(result_t), intent(inout) :: result
    real(real64), intent(in) :: t(4)
    integer, allocatable :: cells(:)
    integer :: k, n
    result%cn = [result%f(1, 1) / (result%g * result%c**2), result%f(2, 2) / (result%g * result%c**2), &
                 result%f(2, 3) / (result%g * result%c**3)]
    ! the finest level's staircase and its tractions stand for the answer's
    ! cells: FASTSIM, exact rolling and the outputs work on whole cells
    n = result%patch%n
    cells = pack([(k, k=1, n)], result%patch%in_staircase())
    result%traction = result%traction([cells, n + cells], :)
    result%patch = result%patch%staircase()
    result%n = result%patch%n
    ! FASTSIM's flexibilities of those cells with the extrapolated f
    result%fastsim = fastsim_flexibilities(result%patch, result%f(1, 1), result%f(2, 2), result%f(2, 3))
    result%t_assemble = t(1)
    result%t_factor = t(2)
    result%t_solve = t(3)
    result%t_total = t(4)
  end subroutine finish_result

end module kcreep_level_ladder
