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
module mesh_extrapolation
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use patch_grid, only: patch_t, ellipse_patch, mask_patch
  use namelist_input, only: config_t
  use dense_solver, only: check_dense_memory
  use creep_run, only: run_case
  use table_output, only: run_record_t
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
  !> On return patch and traction are those of the finest level; the times
  !> are summed over the levels (what the user waits for).
  subroutine run_extrapolated(cfg, patch, record, traction, warnings, status)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(inout) :: patch
    type(run_record_t), intent(out) :: record
    real(real64), allocatable, intent(out) :: traction(:, :)
    character(len=400), allocatable, intent(out) :: warnings(:)
    type(status_t), intent(inout) :: status
    type(patch_t) :: coarse, level_patch
    type(run_record_t) :: level_record
    character(len=400), allocatable :: level_warnings(:)
    character(len=400) :: line
    real(real64) :: values(cfg%extrapolate_levels, 3), t(4), area_ratio
    real(real64), parameter :: pi = acos(-1.0_real64)
    logical :: observed
    integer :: level, i, factor

    allocate (warnings(0))
    coarse = patch
    factor = cfg%refine_ratio**(cfg%extrapolate_levels - 1)
    ! the finest level decides whether the study fits in memory: say so before any work
    call check_dense_memory(int(min(huge(1) / 2.0_real64, real(patch%n, real64) * factor**2)), status)
    if (status%failed()) then
      status%message = status%message//' (the finest of '//itoa(cfg%extrapolate_levels)// &
                       ' extrapolation levels; use a coarser grid, fewer levels or a smaller refine_ratio)'
      return
    end if
    t = 0
    do level = 1, cfg%extrapolate_levels
      factor = cfg%refine_ratio**(level - 1)
      if (factor == 1) then
        level_patch = coarse
      else
        call refined_patch(coarse, factor, level_patch, status)
        if (status%failed()) return
      end if
      call run_case(cfg, level_patch, level_record, traction, level_warnings, status)
      if (status%failed()) return
      values(level, :) = level_record%cn
      if (level_patch%kind == 'ellipse') then
        ! normalise by the staircase's own area: the cells inside the ellipse
        ! cover an area that changes irregularly with the mesh, and that noise
        ! would otherwise spoil the fit (docs/convergence.md, section 2)
        area_ratio = pi * level_patch%semi_a * level_patch%semi_b / level_patch%area()
        values(level, :) = values(level, :) * [area_ratio, area_ratio, area_ratio**1.5_real64]
      end if
      t = t + [level_record%t_assemble, level_record%t_factor, level_record%t_solve, level_record%t_total]
      do i = 1, size(level_warnings)
        line = 'level '//itoa(level)//' ('//itoa(level_patch%mx)//' x '//itoa(level_patch%my)//'): '// &
               trim(level_warnings(i))
        warnings = [warnings, line]
      end do
    end do
    record = level_record
    patch = level_patch
    record%t_assemble = t(1)
    record%t_factor = t(2)
    record%t_solve = t(3)
    record%t_total = t(4)
    record%extrapolated = .true.
    do i = 1, 3
      call richardson_limit(values(:, i), real(cfg%refine_ratio, real64), record%ext(i), &
                            record%ext_error(i), record%ext_order(i), observed)
      if (cfg%extrapolate_levels >= 3 .and. .not. observed) then
        line = 'extrapolation of '//trim(merge('c11', merge('c22', 'c23', i == 2), i == 1))// &
               ': the three levels do not show an order in ['//rtoa(order_min)//', '//rtoa(order_max)// &
               '] (values '//rtoa(values(1, i))//', '//rtoa(values(2, i))//', '//rtoa(values(3, i))// &
               '): first order assumed, trust the error estimate less'
        warnings = [warnings, line]
      end if
    end do
  end subroutine run_extrapolated

end module mesh_extrapolation
