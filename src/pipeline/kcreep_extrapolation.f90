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
module kcreep_extrapolation
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use kcreep_patch, only: patch_t, ellipse_patch, mask_patch
  use kcreep_dense, only: check_dense_memory
  use kcreep_verdict, only: message_length
  use kcreep_problem, only: problem_t, result_t
  use kcreep_run, only: run_case
  implicit none
  private
  public :: refined_patch, richardson_limit, run_extrapolated, order_min, order_max

  !> Observed orders outside this range are not believed (first order is used).
  real(real64), parameter :: order_min = 0.5_real64, order_max = 3

contains

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
    integer :: level, i, factor, levels, ratio

    allocate (warnings(0))
    levels = problem%extrapolate_levels
    ratio = problem%refine_ratio
    factor = ratio**(levels - 1)
    ! the finest level decides whether the study fits in memory: say so before any work
    call check_dense_memory(int(min(huge(1) / 2.0_real64, real(problem%patch%n, real64) * factor**2)), &
                            problem%solve%memory_limit, status)
    if (status%failed()) then
      status%message = status%message//' (the finest of '//itoa(levels)// &
                       ' extrapolation levels; use a coarser grid, fewer levels or a smaller refine_ratio)'
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
          ! would otherwise spoil the fit (docs/convergence.md, section 2)
          area_ratio = pi * level_patch%semi_a * level_patch%semi_b / level_patch%area()
          values(level, :) = values(level, :) * [area_ratio, area_ratio, area_ratio**1.5_real64]
        end if
        t = t + [level_result%t_assemble, level_result%t_factor, level_result%t_solve, level_result%t_total]
        do i = 1, size(level_result%warnings)
          line = 'level '//itoa(level)//' ('//itoa(level_patch%mx)//' x '//itoa(level_patch%my)//'): '// &
                 trim(level_result%warnings(i))
          warnings = [warnings, line]
        end do
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
    result%warnings = warnings
  end subroutine run_extrapolated

end module kcreep_extrapolation
