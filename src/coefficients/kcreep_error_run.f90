!> Runs under error control (&solver target_error): the levels of
!> kcreep_error_control, the extrapolated coefficients and their error
!> estimates, or the estimate of a single given grid.
!>
!> target > 0 on an ellipse without a given grid: kcreep chooses near-square
!>   grids, levels 16, 20, 24, 28, 32, 36, 40, 48 cells across the shorter
!>   axis, and doubles them (reusing the levels it has) while an estimate is
!>   above its target, at most max_refinements times and while the finest level
!>   stays within max_level_cells.
!> target > 0 on a mask: every cell is split into k x k subcells, k = 1, 2, 3, 4
!>   (the staircase is the patch the user gave; it is not smoothed).
!> a given grid (ellipse with mx, my; CONTACT's grid) or target = 0: the grid
!>   as given, and as estimate the difference to the grid with twice the cell
!>   size (ellipse) or half the cell size (mask, CONTACT), see
!>   kcreep_error_control single_grid_estimate, split_grid_estimate.
module kcreep_error_run
  use, intrinsic :: iso_fortran_env, only: real64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
  use kcreep_status, only: status_t
  use kcreep_strings, only: itoa, rtoa
  use patch_grid, only: patch_t, ellipse_patch
  use namelist_input, only: config_t
  use creep_run, only: run_case
  use mesh_extrapolation, only: refined_patch
  use table_output, only: run_record_t
  use kcreep_error_control
  implicit none
  private
  public :: run_controlled, max_level_cells

  !> The finest level kcreep chooses has at most this many patch cells
  !> (an a/b = 10 ellipse at 96 cells across is 72,000 cells, 15 s on the
  !> iterative path; 48 across, 18,000 cells, 2 s).
  integer, parameter :: max_level_cells = 40000
  !> Base levels on an ellipse (cells across the shorter axis).
  integer, parameter :: base_levels(8) = [16, 20, 24, 28, 32, 36, 40, 48]
  !> Split factors of a mask.
  integer, parameter :: mask_factors(4) = [1, 2, 3, 4]
  !> Power of c in f_ij = G c^p C_ij.
  integer, parameter :: c_power(3, 3) = reshape([2, 2, 3, 2, 2, 3, 3, 3, 4], [3, 3])

contains

  !> err(1:3): estimated relative errors of C11, C22, C23 (NaN: no estimate).
  !> given_grid: the user gave the grid (ellipse mx, my, or shape 'contact'):
  !> it is used as given.
  subroutine run_controlled(cfg, patch, target, given_grid, record, traction, err, warnings, status)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(inout) :: patch
    real(real64), intent(in) :: target
    logical, intent(in) :: given_grid
    type(run_record_t), intent(out) :: record
    real(real64), allocatable, intent(out) :: traction(:, :)
    real(real64), intent(out) :: err(3)
    character(len=400), allocatable, intent(out) :: warnings(:)
    type(status_t), intent(inout) :: status

    if (target > 0 .and. .not. given_grid) then
      if (patch%kind == 'ellipse') then
        call run_ellipse_levels(cfg, patch, target, record, traction, err, warnings, status)
      else
        call run_mask_levels(cfg, patch, record, traction, err, warnings, status)
      end if
    else
      call run_single(cfg, patch, record, traction, err, warnings, status)
    end if
    if (status%failed()) return
    call add_uncertain(record, err, target, warnings)
  end subroutine run_controlled

  !> The given grid and its error estimate from one auxiliary grid.
  subroutine run_single(cfg, patch, record, traction, err, warnings, status)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(inout) :: patch
    type(run_record_t), intent(out) :: record
    real(real64), allocatable, intent(out) :: traction(:, :)
    real(real64), intent(out) :: err(3)
    character(len=400), allocatable, intent(out) :: warnings(:)
    type(status_t), intent(inout) :: status
    type(patch_t) :: aux
    type(run_record_t) :: aux_record
    real(real64), allocatable :: aux_traction(:, :)
    character(len=400), allocatable :: aux_warnings(:)
    character(len=400) :: line
    real(real64) :: q, q_aux, area_error
    integer :: i, across

    call run_case(cfg, patch, record, traction, warnings, status)
    if (status%failed()) return
    err = ieee_value(1.0_real64, ieee_quiet_nan)
    if (patch%kind == 'ellipse') then
      across = min(patch%mx, patch%my) / 2
      if (across < min_estimate_cells) then
        line = 'no error estimate: the grid with twice the cell size would have '//itoa(across)// &
               ' cells across, fewer than '//itoa(min_estimate_cells)//' (the grid is too coarse to judge itself)'
        warnings = [warnings, line]
        return
      end if
      call ellipse_patch(patch%semi_a, patch%semi_b, max(1, nint(patch%mx / 2.0_real64)), &
                         max(1, nint(patch%my / 2.0_real64)), aux, status)
    else
      if (4 * patch%n > max_level_cells .and. patch%n > 0) then
        line = 'no error estimate: the grid with every cell split in 2 x 2 would have '//itoa(4 * patch%n)// &
               ' cells, more than '//itoa(max_level_cells)
        warnings = [warnings, line]
        return
      end if
      call refined_patch(patch, 2, aux, status)
    end if
    if (status%failed()) return
    call run_case(cfg, aux, aux_record, aux_traction, aux_warnings, status)
    if (status%failed()) return
    record%t_assemble = record%t_assemble + aux_record%t_assemble
    record%t_factor = record%t_factor + aux_record%t_factor
    record%t_solve = record%t_solve + aux_record%t_solve
    record%t_total = record%t_total + aux_record%t_total
    q = area_ratio(patch)
    q_aux = area_ratio(aux)
    do i = 1, 3
      associate (p => merge(2, 3, i < 3))
        if (patch%kind == 'ellipse') then
          area_error = q**(p / 2.0_real64) - 1
          err(i) = single_grid_estimate(record%cn(i) * q**(p / 2.0_real64), &
                                        aux_record%cn(i) * q_aux**(p / 2.0_real64), area_error)
        else
          err(i) = split_grid_estimate(record%cn(i), aux_record%cn(i))
        end if
      end associate
    end do
  end subroutine run_single

  !> Ellipse levels chosen by kcreep, refined until the estimates meet the target.
  subroutine run_ellipse_levels(cfg, patch, target, record, traction, err, warnings, status)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(inout) :: patch
    real(real64), intent(in) :: target
    type(run_record_t), intent(out) :: record
    real(real64), allocatable, intent(out) :: traction(:, :)
    real(real64), intent(out) :: err(3)
    character(len=400), allocatable, intent(out) :: warnings(:)
    type(status_t), intent(inout) :: status
    integer, allocatable :: done(:)
    real(real64), allocatable :: fnorm(:, :, :)    !< (3, 3, level) area-normalised f
    integer :: refinement, k, mx, my, scale
    integer, allocatable :: want(:), idx(:)
    character(len=400) :: line
    real(real64) :: t(4)

    allocate (done(0), fnorm(3, 3, 0), warnings(0))
    t = 0
    do refinement = 0, max_refinements
      scale = 2**refinement
      want = base_levels * scale
      if (refinement > 0) then
        ! the finest new level must stay within the budget (pi/4 of the grid is inside)
        call ellipse_level_grid(patch%semi_a, patch%semi_b, want(size(want)), mx, my)
        if (0.79_real64 * mx * my > max_level_cells) then
          line = 'error control: refining to '//itoa(mx)//' x '//itoa(my)//' cells would exceed '// &
                 itoa(max_level_cells)//' patch cells; stopped at '//itoa(want(size(want)) / 2)//' cells across'
          warnings = [warnings, line]
          exit
        end if
      end if
      do k = 1, size(want)
        if (any(done == want(k))) cycle
        call ellipse_level_grid(patch%semi_a, patch%semi_b, want(k), mx, my)
        call run_level(cfg, patch, mx, my, want(k), record, traction, fnorm, warnings, t, status)
        if (status%failed()) return
        done = [done, want(k)]
      end do
      idx = [(findloc(done, want(k), 1), k=1, size(want))]
      call fit_levels(1.0_real64 / want, fnorm(:, :, idx), record, err)
      if (within_target(err, coefficient_targets(target))) exit
    end do
    ! report the finest level's grid (the last one run is the finest)
    call ellipse_level_grid(patch%semi_a, patch%semi_b, maxval(done), mx, my)
    call ellipse_patch(patch%semi_a, patch%semi_b, mx, my, patch, status)
    call finish_record(patch, record, t)
    line = 'error control: '//itoa(size(want))//' grids of '//itoa(want(1))//' to '//itoa(want(size(want)))// &
           ' cells across the shorter axis (near-square cells, backward differences as configured), '// &
           'extrapolated to zero cell size with first order'
    warnings = [line, warnings]
  end subroutine run_ellipse_levels

  !> Mask levels: every cell split into k x k subcells.
  subroutine run_mask_levels(cfg, patch, record, traction, err, warnings, status)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(inout) :: patch
    type(run_record_t), intent(out) :: record
    real(real64), allocatable, intent(out) :: traction(:, :)
    real(real64), intent(out) :: err(3)
    character(len=400), allocatable, intent(out) :: warnings(:)
    type(status_t), intent(inout) :: status
    type(patch_t) :: coarse, level_patch
    real(real64), allocatable :: fnorm(:, :, :)
    integer :: k, used
    character(len=400) :: line
    real(real64) :: t(4)

    allocate (fnorm(3, 3, 0), warnings(0))
    t = 0
    coarse = patch
    used = 0
    do k = 1, size(mask_factors)
      if (mask_factors(k) > 1 .and. patch%n * mask_factors(k)**2 > max_level_cells .and. used >= 2) exit
      if (mask_factors(k) == 1) then
        level_patch = coarse
      else
        call refined_patch(coarse, mask_factors(k), level_patch, status)
        if (status%failed()) return
      end if
      call run_level(cfg, level_patch, 0, 0, mask_factors(k), record, traction, fnorm, warnings, t, status)
      if (status%failed()) return
      used = k
    end do
    call fit_levels(1.0_real64 / mask_factors(1:used), fnorm, record, err)
    patch = level_patch
    call finish_record(patch, record, t)
    line = 'error control: the mask with every cell split into k x k subcells, k = 1 to '//itoa(mask_factors(used))// &
           ' (the staircase is the patch given), extrapolated to zero cell size with first order'
    if (used < size(mask_factors)) line = trim(line)//'; finer splits would exceed '//itoa(max_level_cells)//' cells'
    warnings = [line, warnings]
  end subroutine run_mask_levels

  !> One level: solve, keep its normalised f and its warnings.
  subroutine run_level(cfg, patch, mx, my, label, record, traction, fnorm, warnings, t, status)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(in) :: patch
    integer, intent(in) :: mx, my, label
    type(run_record_t), intent(inout) :: record
    real(real64), allocatable, intent(inout) :: traction(:, :)
    real(real64), allocatable, intent(inout) :: fnorm(:, :, :)
    character(len=400), allocatable, intent(inout) :: warnings(:)
    real(real64), intent(inout) :: t(4)
    type(status_t), intent(inout) :: status
    type(patch_t) :: level_patch
    character(len=400), allocatable :: level_warnings(:)
    character(len=400) :: line
    real(real64) :: q
    real(real64), allocatable :: f(:, :, :)
    integer :: i

    if (mx > 0) then
      call ellipse_patch(patch%semi_a, patch%semi_b, mx, my, level_patch, status)
      if (status%failed()) return
    else
      level_patch = patch
    end if
    call run_case(cfg, level_patch, record, traction, level_warnings, status)
    if (status%failed()) return
    t = t + [record%t_assemble, record%t_factor, record%t_solve, record%t_total]
    q = area_ratio(level_patch)
    allocate (f(3, 3, size(fnorm, 3) + 1))
    f(:, :, 1:size(fnorm, 3)) = fnorm
    f(:, :, size(f, 3)) = record%f * q**(c_power / 2.0_real64)
    call move_alloc(f, fnorm)
    do i = 1, size(level_warnings)
      line = 'level '//itoa(label)//' ('//itoa(level_patch%mx)//' x '//itoa(level_patch%my)//'): '// &
             trim(level_warnings(i))
      warnings = [warnings, line]
    end do
  end subroutine run_level

  !> The fit of every f entry; the record gets the limits, err those of C11, C22, C23.
  subroutine fit_levels(h, fnorm, record, err)
    real(real64), intent(in) :: h(:), fnorm(:, :, :)
    type(run_record_t), intent(inout) :: record
    real(real64), intent(out) :: err(3)
    real(real64) :: limit, rel
    integer :: i, j
    do j = 1, 3
      do i = 1, 3
        if (any(ieee_is_nan(fnorm(i, j, :)))) then
          record%f(i, j) = ieee_value(1.0_real64, ieee_quiet_nan)
          cycle
        end if
        call level_estimate(h, fnorm(i, j, :), limit, rel)
        record%f(i, j) = limit
        if (i == 1 .and. j == 1) err(1) = rel
        if (i == 2 .and. j == 2) err(2) = rel
        if (i == 2 .and. j == 3) err(3) = rel
      end do
    end do
    ! an unrequested load case leaves NaN: no estimate
    if (any(ieee_is_nan(fnorm(1, 1, :)))) err(1) = ieee_value(1.0_real64, ieee_quiet_nan)
    if (any(ieee_is_nan(fnorm(2, 2, :)))) err(2) = ieee_value(1.0_real64, ieee_quiet_nan)
    if (any(ieee_is_nan(fnorm(2, 3, :)))) err(3) = ieee_value(1.0_real64, ieee_quiet_nan)
  end subroutine fit_levels

  !> record%f holds limits normalised by c_s (the staircase's own c): rescale to
  !> the patch's c (ellipse: sqrt(ab); mask: unchanged) and set the c's and times.
  subroutine finish_record(patch, record, t)
    type(patch_t), intent(in) :: patch
    type(run_record_t), intent(inout) :: record
    real(real64), intent(in) :: t(4)
    record%mx = patch%mx
    record%my = patch%my
    record%n = patch%n
    record%c = patch%equivalent_radius()
    record%cn = [record%f(1, 1) / (record%g * record%c**2), record%f(2, 2) / (record%g * record%c**2), &
                 record%f(2, 3) / (record%g * record%c**3)]
    record%t_assemble = t(1)
    record%t_factor = t(2)
    record%t_solve = t(3)
    record%t_total = t(4)
  end subroutine finish_record

  !> (area the coefficients refer to) / (area of the cells): pi a b / staircase for an ellipse, 1 otherwise.
  pure real(real64) function area_ratio(patch)
    type(patch_t), intent(in) :: patch
    real(real64), parameter :: pi = acos(-1.0_real64)
    if (patch%kind == 'ellipse') then
      area_ratio = pi * patch%semi_a * patch%semi_b / patch%area()
    else
      area_ratio = 1
    end if
  end function area_ratio

  !> 'uncertain' in the verdict, with its warning, when an estimate misses its target.
  subroutine add_uncertain(record, err, target, warnings)
    type(run_record_t), intent(inout) :: record
    real(real64), intent(in) :: err(3), target
    character(len=400), allocatable, intent(inout) :: warnings(:)
    character(len=400) :: line
    real(real64) :: targets(3)
    if (len(uncertain_flag(err, target)) == 0) return
    targets = coefficient_targets(target)
    if (record%verdict == 'ok') then
      record%verdict = 'uncertain'
    else
      record%verdict = record%verdict//',uncertain'
    end if
    line = 'uncertain: estimated relative errors of C11, C22, C23 '//rtoa(err(1))//', '//rtoa(err(2))//', '// &
           rtoa(err(3))//' against targets '//rtoa(targets(1))//', '//rtoa(targets(2))//', '//rtoa(targets(3))// &
           ' (target_error; C23 gets 3 times it)'
    warnings = [warnings, line]
  end subroutine add_uncertain

end module kcreep_error_run
