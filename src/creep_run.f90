!> One kcreep case from configuration to table row: build the operator,
!> solve the requested load cases, derive the coefficients and judge them.
module creep_run
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use kcreep_status, only: status_t
  use kcreep_strings, only: rtoa, itoa
  use patch_grid, only: patch_t
  use namelist_input, only: config_t
  use tang_assembly, only: operator_table_t, build_operator_table, n_load_cases
  use dense_solver, only: dense_diagnostics_t
  use linear_solve, only: solve_load_cases
  use creep_coefficients, only: creep_matrix, normalised, traction_coherence
  use kalker_table, only: kalker_coefficients
  use fastsim_flexibility, only: fastsim_flexibilities
  use table_output, only: run_record_t
  implicit none
  private
  public :: run_case, case_name, coherence_limit, rcond_limit, backward_error_limit, alpha_edge_limit, coarse_cells

  !> Below this, the traction of a pure xi (eta) load changes sign over much of
  !> the patch: no physical full-adhesion solution does that.
  real(real64), parameter :: coherence_limit = 0.5_real64
  !> rcond below this: fewer than about 8 digits of the solution are certain
  !> (forward error <~ berr/rcond with berr ~ 1e-16). Measured (docs/stability.md):
  !> every case of the stability suite has rcond >= 1e-4 except collocation with
  !> alpha -> 0, where rcond levels off at 1.9e-6 (flagged degenerate anyway);
  !> so 1e-8 is four decades below anything a sane input reaches.
  real(real64), parameter :: rcond_limit = 1e-8_real64
  !> Collocation this close to the cell edge (|alpha| >= 0.95): the x-derivative
  !> of the influence coefficients is log-singular at the edge and the
  !> coefficients drift low although rcond and berr stay perfect. Measured on
  !> the unit circle, nu = 0.25, 30 x 30 / 60 x 60 cells: C11 vs Kalker
  !> +4.3/+1.6 % at alpha 0.5, -4.8/-3.6 % at 0.9, -8.1/-5.6 % at 0.95,
  !> -14.7/-9.6 % at 0.99, -22.3/-14.5 % at 0.999.
  real(real64), parameter :: alpha_edge_limit = 0.95_real64
  !> A patch fewer cells across than this (in x or y) is flagged 'coarse': the
  !> discretisation error is tens of percent although the solve is perfect.
  !> Measured on the unit circle, nu = 0.25 (C11 / C23 vs Kalker):
  !> collocation 4: +11/+39 %, 6: +26/+56 %, 8: +13/+31 %, 10: +10/+25 %, 20: +5/+12 %;
  !> backward    4: +1/-24 %,  6: +18/+5 %,  8: +6/-5 %,   10: +5/-4 %,   20: +2/-3 %.
  integer, parameter :: coarse_cells = 10
  !> Backward error above this after refinement: the solve itself is suspect.
  !> Measured: at most 8.4e-16 over the whole stability suite (docs/stability.md).
  real(real64), parameter :: backward_error_limit = 1e-12_real64
  !> The iterative path's final relative residual above this: at the default
  !> tolerance 1e-11 the coefficients agree with the dense LU to <= 1.1e-10
  !> (tests/test_solver_paths.py), so 1e-10 keeps them good to about 1e-9.
  real(real64), parameter :: iterative_residual_limit = 1e-10_real64

contains

  subroutine run_case(cfg, patch, record, traction, warnings, status)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(in) :: patch
    type(run_record_t), intent(out) :: record
    real(real64), allocatable, intent(out) :: traction(:, :)   !< (2n, 3), NaN where not solved
    character(len=400), allocatable, intent(out) :: warnings(:)
    type(status_t), intent(inout) :: status
    type(operator_table_t) :: table
    type(dense_diagnostics_t) :: diag
    integer :: n
    integer(int64) :: t0, t1, rate
    real(real64) :: t_table

    allocate (warnings(0))
    call system_clock(t0, rate)
    n = patch%n
    call build_operator_table(patch, cfg%scheme, cfg%nu, cfg%g, table)
    call system_clock(t1)
    t_table = real(t1 - t0, real64) / rate

    ! dense or iterative, only the systems the requested cases need (linear_solve)
    call solve_load_cases(cfg%solve, cfg%scheme, cfg%nu, patch, table, cfg%requested, cfg%refine, traction, diag, status)
    if (status%failed()) return

    record%case_name = case_name(cfg%input_path)
    record%scheme = cfg%scheme%name
    record%mx = patch%mx
    record%my = patch%my
    record%n = n
    record%alpha = merge(cfg%scheme%alpha, ieee_value(1.0_real64, ieee_quiet_nan), cfg%scheme%name == 'collocation')
    record%nu = cfg%nu
    record%g = cfg%g
    record%c = patch%equivalent_radius()
    record%f = creep_matrix(patch, traction, cfg%requested)
    record%cn = normalised(record%f, cfg%g, record%c)
    record%fastsim = fastsim_flexibilities(patch, record%f(1, 1), record%f(2, 2), record%f(2, 3))
    if (patch%kind == 'ellipse') then
      record%klt = kalker_coefficients(patch%semi_a / patch%semi_b, cfg%nu)
    else
      record%klt = ieee_value(1.0_real64, ieee_quiet_nan)
    end if
    record%rcond = diag%rcond
    record%backward_error = diag%backward_error
    record%backward_error_initial = diag%backward_error_initial
    record%relative_residual = diag%relative_residual
    record%refine = cfg%refine//merge(' (refined)    ', ' (not refined)', diag%refined)
    record%method = diag%method
    record%iterations = diag%iterations
    record%t_assemble = t_table + diag%t_assemble
    record%t_factor = diag%t_factor
    record%t_solve = diag%t_solve
    call system_clock(t1)
    record%t_total = real(t1 - t0, real64) / rate
    call judge(cfg, patch, traction, diag, record, warnings)
  end subroutine run_case

  !> The verdict column and the warnings that explain it.
  subroutine judge(cfg, patch, traction, diag, record, warnings)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: traction(:, :)
    type(dense_diagnostics_t), intent(in) :: diag
    type(run_record_t), intent(inout) :: record
    character(len=400), allocatable, intent(inout) :: warnings(:)
    real(real64) :: coherence
    integer :: n
    character(len=:), allocatable :: verdict

    n = patch%n
    verdict = ''
    if (cfg%requested(1)) then
      coherence = traction_coherence(traction(1:n, 1))
      if (coherence < coherence_limit) then
        call flag('degenerate', 'the xi traction changes sign over the patch (|sum px|/sum|px| = '// &
                  rtoa(coherence)//'): the discrete solution oscillates and f11 is unreliable'// &
                  trim(hint()))
      end if
    end if
    if (cfg%requested(2)) then
      coherence = traction_coherence(traction(n + 1:2 * n, 2))
      if (coherence < coherence_limit) then
        call flag('degenerate', 'the eta traction changes sign over the patch (|sum py|/sum|py| = '// &
                  rtoa(coherence)//'): the discrete solution oscillates and f22 is unreliable'// &
                  trim(hint()))
      end if
    end if
    if ((cfg%requested(1) .and. .not. record%f(1, 1) > 0) .or. &
        (cfg%requested(2) .and. .not. record%f(2, 2) > 0)) then
      call flag('nonphysical', 'f11 or f22 is not positive: the traction does not oppose the creepage'// &
                trim(hint()))
    end if
    if (cfg%scheme%name == 'collocation' .and. abs(cfg%scheme%alpha) >= alpha_edge_limit) then
      call flag('alpha-edge', 'alpha = '//rtoa(cfg%scheme%alpha)//' puts the collocation point at the cell edge, '// &
                'where the influence derivative is log-singular: the coefficients drift low (C11 -8 % at '// &
                'alpha 0.95, -22 % at 0.999 on a 30 x 30 circle); use 0.5 <= alpha <= 0.9')
    end if
    if (min(maxval(patch%ix) - minval(patch%ix), maxval(patch%iy) - minval(patch%iy)) + 1 < coarse_cells) then
      call flag('coarse', 'the patch is '//itoa(maxval(patch%ix) - minval(patch%ix) + 1)//' x '// &
                itoa(maxval(patch%iy) - minval(patch%iy) + 1)//' cells across: with fewer than '// &
                itoa(coarse_cells)//' cells in x or y the discretisation error is 10 to 50 % (C23 worst); refine the grid')
    end if
    if (diag%method == 'dense') then
      if (.not. diag%rcond >= rcond_limit) then
        call flag('ill-conditioned', 'LAPACK rcond = '//rtoa(diag%rcond)// &
                  ': the system is nearly singular, trust only the leading digits')
      end if
      if (.not. diag%backward_error <= backward_error_limit) then   ! NaN too
        call flag('inaccurate', 'backward error '//rtoa(diag%backward_error)// &
                  ' after refinement: the solve did not reach round-off')
      end if
    else if (.not. diag%backward_error <= iterative_residual_limit) then
      ! GMRES has no factorisation to estimate rcond from; its residual is what it reached
      call flag('inaccurate', 'GMRES stopped at relative residual '//rtoa(diag%backward_error)// &
                ': coefficients may be off beyond the 1e-8 level (lower &solver tolerance)')
    end if
    if (len(verdict) == 0) verdict = 'ok'
    record%verdict = verdict

  contains

    subroutine flag(word, text)
      character(len=*), intent(in) :: word, text
      character(len=400) :: line
      if (index(verdict, word) == 0) then
        if (len(verdict) > 0) verdict = verdict//','
        verdict = verdict//word
      end if
      line = text
      warnings = [warnings, line]
    end subroutine flag

    !> What the user can do about it.
    function hint() result(text)
      character(len=200) :: text
      real(real64) :: aspect
      text = ''
      if (cfg%scheme%name /= 'collocation') return
      aspect = patch%dx / patch%dy
      if (cfg%scheme%alpha <= 0) then
        text = '; collocation needs alpha > 0 (toward the leading edge), e.g. alpha = 0.5'
      else if (aspect > 1.5_real64 .or. aspect < 1 / 1.5_real64) then
        text = '; the cells are elongated (dx/dy = '//rtoa(aspect)// &
               '): use near-square cells or scheme = ''backward'''
      end if
    end function hint

  end subroutine judge

  !> Input file name without folder and extension, blanks replaced (a table word).
  pure function case_name(path) result(name)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: name
    integer :: slash, dot, i
    slash = index(path, '/', back=.true.)
    name = path(slash + 1:)
    dot = index(name, '.', back=.true.)
    if (dot > 1) name = name(1:dot - 1)
    do i = 1, len(name)
      if (name(i:i) == ' ' .or. iachar(name(i:i)) < 33) name(i:i) = '_'
    end do
    if (len(name) == 0) name = '-'
  end function case_name

end module creep_run
