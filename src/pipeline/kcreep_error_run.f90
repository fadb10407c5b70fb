!> Runs under error control (&solver target_error): the levels of
!> kcreep_refine_estimate, the extrapolated coefficients and their error
!> estimates, or the estimate of a single given grid.
!>
!> target > 0 on an ellipse without a given grid: the ladder of
!>   kcreep_level_ladder (near-square grids, or for targets tighter than the
!>   default cells long in y on an ellipse long in y: ellipse_cells_long_in_y).
!> a gap: kcreep_gap_levels (the normal problem on a fine grid, then the same
!>   ladder on the contact area found).
!> target > 0 on a mask: the same ladder, every cell split into k x k
!>   subcells, k = 1, 2, 3, ... (at most max_split) while the estimates miss
!>   the target and the split patch keeps to the cell budget (the staircase
!>   is the patch the user gave, it is not smoothed).
!> a given grid (ellipse with mx, my; CONTACT's grid) or target = 0: the grid
!>   as given, and as estimate the difference to the grid with twice the cell
!>   size (ellipse) or half the cell size (mask, CONTACT), see
!>   kcreep_refine_estimate single_grid_estimate, split_grid_estimate.
module kcreep_error_run
  use, intrinsic :: iso_fortran_env, only: real64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
  use kcreep_status, only: status_t
  use kcreep_strings, only: itoa, rtoa
  use kcreep_patch, only: patch_t, ellipse_patch, place_like, mask_patch
  use kcreep_problem, only: problem_t, result_t, add_warning, append_prefixed, add_uncertain, level_tolerance, &
                           cell_budget_or
  use kcreep_run, only: run_case, solve_cache_t
  use kcreep_extrapolation, only: refined_patch
  use kcreep_verdict, only: message_length
  use kcreep_refine_estimate
  use kcreep_refine_constants
  use kcreep_staircase_normalisation, only: ellipse_normalised
  use kcreep_gap_levels, only: run_gap_patch
  use kcreep_level_ladder, only: run_shape_levels, ellipse_base_levels, finest_split
  use kcreep_grid_transfer, only: transferred_traction
  implicit none
  private
  public :: run_controlled, controlled_finest_patch

  !> The f entries of C11, C22, C23.
  integer, parameter :: entry_of(2, 3) = reshape([1, 1, 2, 2, 2, 3], [2, 3])

contains

  !> Solve problem under error control: result%err(1:3) are the estimated
  !> relative errors of C11, C22, C23 (NaN: no estimate, a warning says why).
  !> problem%refine_grid: kcreep may choose the grids (ellipse) or split the
  !> cells (mask); otherwise the grid is solved as given.
  subroutine run_controlled(problem, result, status, cache)
    type(problem_t), intent(in) :: problem
    type(result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    type(solve_cache_t), intent(inout), optional :: cache

    if (problem%normal%active) then
      call run_gap_patch(problem, result, status, cache)   ! the geometry is refined: kcreep_gap_levels
    else if (problem%target_error > 0 .and. problem%refine_grid) then
      call run_shape_levels(problem, result, status)   ! an ellipse's levels, or a mask split k x k
    else
      call run_single(problem, result, status, cache)
    end if
    if (status%failed()) return
    if (problem%target_error > 0 .and. .not. problem%refine_grid) then
      call add_uncertain(result, problem%target_error, 'estimated relative errors', given_grid_advice(problem), &
                         solved=problem%requested)
    else
      call add_uncertain(result, problem%target_error, 'estimated relative errors', solved=problem%requested)
    end if
  end subroutine run_controlled

  !> What to change when a grid solved as given misses the target.
  pure function given_grid_advice(problem) result(text)
    type(problem_t), intent(in) :: problem
    character(len=:), allocatable :: text
    character(len=*), parameter :: zero = '; or target_error = 0 takes this grid with its estimate'
    if (problem%normal%active) then
      text = 'the gap''s grid is solved as given (a &patch grid, or contact_inp''s): without a &patch grid '// &
             'kcreep chooses the grids'//zero
    else if (problem%patch%kind == 'ellipse') then
      text = 'the grid is solved as given (mx, my): leave mx, my out and kcreep chooses grids that meet the '// &
             'target'//zero
    else if (problem%patch%kind == 'contact') then
      text = 'CONTACT''s grid is solved as given: a finer grid in CONTACT'//zero
    else
      text = 'the mask''s grid is solved as given: a finer mask'//zero
    end if
  end function given_grid_advice

  !> The given grid and its error estimate from one auxiliary grid.
  subroutine run_single(problem, result, status, cache)
    type(problem_t), intent(in) :: problem
    type(result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    type(solve_cache_t), intent(inout), optional :: cache
    type(problem_t) :: aux
    type(result_t) :: aux_result
    character(len=message_length) :: line
    real(real64) :: f_h(3, 3), f_2h(3, 3)
    integer :: i, across

    call run_case(problem, result, status, cache)
    if (status%failed()) return
    result%err = ieee_value(1.0_real64, ieee_quiet_nan)
    if (.not. problem%estimate_error .and. problem%target_error == 0) return
    aux = problem
    associate (patch => problem%patch)
      if (patch%kind == 'ellipse') then
        across = min(patch%mx, patch%my) / 2
        if (across < min_estimate_cells) then
          line = 'no error estimate: the grid with twice the cell size would have '//itoa(across)// &
                 ' cells across, fewer than '//itoa(min_estimate_cells)//' (the grid is too coarse to judge itself; '// &
                 'give mx, my of at least '//itoa(2 * min_estimate_cells)//')'
          call add_warning(result, line)
          return
        end if
        call ellipse_patch(patch%semi_a, patch%semi_b, max(1, nint(patch%mx / 2.0_real64)), &
                           max(1, nint(patch%my / 2.0_real64)), aux%patch, status)
        call place_like(aux%patch, patch)
      else
        if (4 * patch%n > max_level_cells) then
          line = 'no error estimate: the grid with every cell split in 2 x 2 would have '//itoa(4 * patch%n)// &
                 ' cells, more than '//itoa(max_level_cells)
          call add_warning(result, line)
          return
        end if
        call refined_patch(patch, 2, aux%patch, status)
      end if
      if (status%failed()) return
      call run_case(aux, aux_result, status)
      if (status%failed()) return
      result%t_assemble = result%t_assemble + aux_result%t_assemble
      result%t_factor = result%t_factor + aux_result%t_factor
      result%t_solve = result%t_solve + aux_result%t_solve
      result%t_total = result%t_total + aux_result%t_total
      if (patch%kind == 'ellipse') then
        f_h = ellipse_normalised(patch, problem%nu, result%f)
        f_2h = ellipse_normalised(aux%patch, problem%nu, aux_result%f)
      end if
      do i = 1, 3
        associate (e => entry_of(:, i))
          if (patch%kind == 'ellipse') then
            ! the normalisation's own size is added in full: it is a correction, not a limit
            result%err(i) = single_grid_estimate(f_h(e(1), e(2)), f_2h(e(1), e(2)), &
                                                 f_h(e(1), e(2)) / result%f(e(1), e(2)) - 1)
          else
            result%err(i) = split_grid_estimate(result%cn(i), aux_result%cn(i))
          end if
        end associate
      end do
    end associate
  end subroutine run_single

  !> The largest patch a run under error control may solve (ellipse: the
  !> finest level within the budget; mask: the finest split; a gap: a full
  !> grid of the budget's cells), for the memory a job needs; the problem's
  !> own patch when kcreep chooses no grid.
  subroutine controlled_finest_patch(problem, finest, status)
    type(problem_t), intent(in) :: problem
    type(patch_t), intent(out) :: finest
    type(status_t), intent(inout) :: status
    integer :: cells, mx, my, used
    real(real64) :: budget
    logical :: long_in_y
    finest = problem%patch
    if (.not. (problem%target_error > 0 .and. problem%refine_grid)) return
    if (problem%normal%active) then
      ! a contact area's levels count their whole grid (the area's box)
      ! against the budget (kcreep_level_ladder region_cells): the bound is
      ! a full grid of that many cells
      cells = ceiling(sqrt(cell_budget_or(problem, level_cell_budget(problem%target_error))))
      call mask_patch(spread(spread(.true., 1, cells), 2, cells), 1.0_real64, 1.0_real64, 0.0_real64, 0.0_real64, &
                      'memory bound', finest, status)
      return
    end if
    if (problem%patch%kind == 'ellipse') then
      budget = cell_budget_or(problem, level_cell_budget(problem%target_error))
      long_in_y = ellipse_cells_long_in_y(problem%target_error, problem%scheme%name)
      associate (a => problem%patch%semi_a, b => problem%patch%semi_b)
        cells = maxval(ellipse_base_levels(a, b, budget, long_in_y))
        do
          call ellipse_level_grid(a, b, next_level(cells), mx, my, long_in_y)
          if (ellipse_fill * mx * my > budget) exit
          cells = next_level(cells)
        end do
        call ellipse_level_grid(a, b, cells, mx, my, long_in_y)
        call ellipse_patch(a, b, mx, my, finest, status, blended=.true.)
      end associate
    else
      used = finest_split(problem%patch%n, cell_budget_or(problem, level_cell_budget(problem%target_error)))
      call refined_patch(problem%patch, used, finest, status)
    end if
  end subroutine controlled_finest_patch

end module kcreep_error_run
