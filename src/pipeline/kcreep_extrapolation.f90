!> Richardson extrapolation in the mesh size (&solver extrapolate = .true.).
!>
!> The input grid is the coarsest level; level k refines it by refine_ratio**k
!> in both directions: an ellipse gets mx*r**k x my*r**k cells, a mask has
!> every cell split into r**k x r**k subcells (exactly the same geometry).
!> The coefficients of the levels are fitted by f(h) = f0 + K h**p; on an
!> ellipse each level's C11, C22 (C23) are first rescaled by (pi a b / staircase
!> area) (to the power 3/2), i.e. normalised with the cells' own area, which
!> removes the irregular change of the staircase area with the mesh:
!>   3 levels: p is the observed order (the studies measure p ~ 1, see
!>             docs/convergence.md); when the differences change sign or p
!>             falls outside [0.5, 3], p = 1 is used and a warning says so.
!>             Error estimate: |f0 - f0'|, f0' the first-order extrapolation
!>             of the two coarser levels (how far the limit moves when made
!>             one level coarser).
!>   2 levels: p = 1 (the measured order); error estimate |f0 - f_finest|,
!>             the size of the correction itself (no third level to judge it).
!> The rows reported (f, C11 C22 C23) are the finest level's; their estimated
!> error err is |C - C0| + the limit's error, relative to C0, and the verdict
!> is 'uncertain' when it misses target_error, as on every other path.
module kcreep_extrapolation
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use kcreep_patch, only: patch_t, ellipse_patch, mask_patch, place_like
  use kcreep_linear_solve, only: solve_memory_plan
  use kcreep_solve_memory, only: table_bytes
  use kcreep_verdict, only: message_length
  use kcreep_problem, only: problem_t, result_t, append_prefixed, add_uncertain
  use kcreep_run, only: run_case
  implicit none
  private
  public :: refined_patch, richardson_limit, run_extrapolated, order_min, order_max, memory_need

  !> Observed orders outside this range are not believed (first order is used).
  real(real64), parameter :: order_min = 0.5_real64, order_max = 3

contains

  !> Bytes the problem needs at its peak and the solve path of that moment:
  !> each grid it solves (its own, or every extrapolation level) for the
  !> method that grid will take ('auto' decided as run_case will decide it,
  !> with the same memory limit), plus the operator table (about 40 reals per
  !> grid cell); kcreep_solve_memory has the model and its evidence. level: the level of the peak (1 without extrapolation).
  subroutine memory_need(problem, bytes, method, level, status)
    type(problem_t), intent(in) :: problem
    integer(int64), intent(out) :: bytes
    character(len=:), allocatable, intent(out) :: method
    integer, intent(out) :: level
    type(status_t), intent(inout) :: status
    type(patch_t) :: fine
    integer(int64) :: b
    character(len=:), allocatable :: m
    integer :: k, levels
    bytes = -1
    level = 1
    method = ''
    levels = merge(problem%extrapolate_levels, 1, problem%extrapolate)
    do k = 1, levels
      if (k == 1) then
        call solve_memory_plan(problem%solve, problem%nu, problem%patch, problem%requested, b, m)
        b = b + table_bytes(problem%patch)
      else
        call refined_patch(problem%patch, problem%refine_ratio**(k - 1), fine, status)
        if (status%failed()) return
        call solve_memory_plan(problem%solve, problem%nu, fine, problem%requested, b, m)
        b = b + table_bytes(fine)
      end if
      if (b > bytes) then
        bytes = b
        method = m
        level = k
      end if
    end do
  end subroutine memory_need

  !> The patch refined by an integer factor in both directions.
  subroutine refined_patch(patch, factor, fine, status)
    type(patch_t), intent(in) :: patch
    integer, intent(in) :: factor
    type(patch_t), intent(out) :: fine
    type(status_t), intent(inout) :: status
    logical, allocatable :: inside(:, :)
    integer :: ix, iy

    if (patch%kind == 'ellipse') then
      call ellipse_patch(patch%semi_a, patch%semi_b, patch%mx * factor, patch%my * factor, fine, status)
      call place_like(fine, patch)
      return
    end if
    allocate (inside(patch%mx * factor, patch%my * factor))
    do iy = 1, size(inside, 2)
      do ix = 1, size(inside, 1)
        inside(ix, iy) = patch%inside((ix - 1) / factor + 1, (iy - 1) / factor + 1)
      end do
    end do
    ! subcell centres: the first one sits half a subcell in from the old cell's corner
    call mask_patch(inside, patch%dx / factor, patch%dy / factor, &
                    patch%x0 - patch%dx / 2 + patch%dx / (2 * factor), &
                    patch%y0 - patch%dy / 2 + patch%dy / (2 * factor), 'refined mask', fine, status)
    fine%kind = patch%kind
  end subroutine refined_patch

  !> Limit, error estimate and order used, from values f(1:levels) on meshes
  !> refined by ratio from one level to the next (f(levels) the finest).
  pure subroutine richardson_limit(f, ratio, limit, error, order, observed)
    real(real64), intent(in) :: f(:)
    real(real64), intent(in) :: ratio
    real(real64), intent(out) :: limit, error, order
    logical, intent(out) :: observed   !< the order came from the data (3 levels, believable)
    integer :: m
    real(real64) :: d1, d2, first_order_coarse

    m = size(f)
    observed = .false.
    order = 1
    if (m >= 3) then
      d1 = f(m - 1) - f(m - 2)
      d2 = f(m) - f(m - 1)
      if (d1 /= 0 .and. d2 /= 0 .and. (d1 > 0 .eqv. d2 > 0)) then
        order = log(d1 / d2) / log(ratio)
        observed = order >= order_min .and. order <= order_max
      end if
      if (.not. observed) order = 1
    end if
    limit = f(m) + (f(m) - f(m - 1)) / (ratio**order - 1)
    if (m >= 3) then
      first_order_coarse = f(m - 1) + (f(m - 1) - f(m - 2)) / (ratio - 1)
      error = abs(limit - first_order_coarse)
    else
      error = abs(limit - f(m))
    end if
  end subroutine richardson_limit

  !> Run every level and report the finest one with the extrapolated columns.
  !> The result's patch sizes and tractions are those of the finest level;
  !> the times are summed over the levels (what the user waits for).
  subroutine run_extrapolated(problem, result, status)
    type(problem_t), intent(in) :: problem
    type(result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    type(problem_t) :: level_problem
    type(result_t) :: level_result
    character(len=message_length), allocatable :: warnings(:)
    character(len=message_length) :: line
    real(real64) :: values(problem%extrapolate_levels, 3), t(4), area_ratio
    real(real64), parameter :: pi = acos(-1.0_real64)
    logical :: observed
    integer :: level, i, factor, levels, ratio, peak
    integer(int64) :: need
    character(len=:), allocatable :: peak_method

    allocate (warnings(0))
    levels = problem%extrapolate_levels
    ratio = problem%refine_ratio
    factor = ratio**(levels - 1)
    ! every level on the path it will take must fit: say so before any work
    call memory_need(problem, need, peak_method, peak, status)
    if (status%failed()) return
    if (problem%solve%memory_limit > 0 .and. need > problem%solve%memory_limit) then
      call fail(status, exit_bad_input, 'extrapolation level '//itoa(peak)//' of '//itoa(levels)//' ('// &
                itoa(problem%patch%mx * ratio**(peak - 1))//' x '//itoa(problem%patch%my * ratio**(peak - 1))// &
                ' cells, '//peak_method//' solver) needs '//rtoa(real(need, real64) / 2.0_real64**30)// &
                ' GiB, only '//rtoa(real(problem%solve%memory_limit, real64) / 2.0_real64**30)// &
                ' GiB are available (use a coarser grid, fewer levels, a smaller refine_ratio or method = ''auto'')')
      return
    end if
    t = 0
    level_problem = problem
    do level = 1, levels
      factor = ratio**(level - 1)
      if (factor > 1) then
        call refined_patch(problem%patch, factor, level_problem%patch, status)
        if (status%failed()) return
      end if
      call run_case(level_problem, level_result, status)
      if (status%failed()) return
      associate (level_patch => level_problem%patch)
        values(level, :) = level_result%cn
        if (level_patch%kind == 'ellipse') then
          ! normalise by the staircase's own area: the cells inside the ellipse
          ! cover an area that changes irregularly with the mesh, and that noise
          ! would otherwise spoil the fit (docs/convergence.md, "Convergence in the mesh size")
          area_ratio = pi * level_patch%semi_a * level_patch%semi_b / level_patch%area()
          values(level, :) = values(level, :) * [area_ratio, area_ratio, area_ratio**1.5_real64]
        end if
        t = t + [level_result%t_assemble, level_result%t_factor, level_result%t_solve, level_result%t_total]
        call append_prefixed(warnings, 'level '//itoa(level)//' ('//itoa(level_patch%mx)//' x '// &
                             itoa(level_patch%my)//'): ', level_result%warnings)
      end associate
    end do
    result = level_result
    result%t_assemble = t(1)
    result%t_factor = t(2)
    result%t_solve = t(3)
    result%t_total = t(4)
    result%extrapolated = .true.
    do i = 1, 3
      call richardson_limit(values(:, i), real(ratio, real64), result%ext(i), &
                            result%ext_error(i), result%ext_order(i), observed)
      if (levels >= 3 .and. .not. observed) then
        line = 'extrapolation of '//trim(merge('c11', merge('c22', 'c23', i == 2), i == 1))// &
               ': the three levels do not show an order in ['//rtoa(order_min)//', '//rtoa(order_max)// &
               '] (values '//rtoa(values(1, i))//', '//rtoa(values(2, i))//', '//rtoa(values(3, i))// &
               '): first order assumed, trust the error estimate less'
        warnings = [warnings, line]
      end if
    end do
    ! the rows reported are the finest level's: their own error is their
    ! distance to the limit plus the limit's uncertainty (before: 0, and 'ok')
    result%err = (abs(result%cn - result%ext) + result%ext_error) / abs(result%ext)
    result%warnings = warnings
    call add_uncertain(result, problem%target_error, 'the finest level''s estimated relative errors', &
                       'leave extrapolate out (error control)', problem%requested)
  end subroutine run_extrapolated

end module kcreep_extrapolation
