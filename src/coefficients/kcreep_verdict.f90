!> The verdict on a solved patch: codes (bits) and words for the table's
!> verdict column, with one warning sentence for each problem found. The
!> limits are measured (each says where).
module kcreep_verdict
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_strings, only: rtoa, itoa
  use kcreep_patch, only: patch_t
  use kcreep_assembly, only: scheme_t, n_load_cases
  use kcreep_dense, only: dense_diagnostics_t
  use kcreep_solver_options, only: solver_options_t
  use kcreep_creep_matrix, only: traction_coherence
  implicit none
  private
  public :: judge, verdict_code, message_length
  public :: coherence_limit, rcond_limit, backward_error_limit, alpha_edge_limit, coarse_cells
  public :: verdict_ok, verdict_degenerate, verdict_nonphysical, verdict_alpha_edge, verdict_coarse, &
            verdict_ill_conditioned, verdict_inaccurate, verdict_uncertain, verdict_words

  integer, parameter :: message_length = 400

  !> Verdict codes: bits of the flags; 0 is 'ok'. verdict_words(k) is the
  !> word of bit k-1 in the table's verdict column.
  integer, parameter :: verdict_ok = 0, verdict_degenerate = 1, verdict_nonphysical = 2, &
                        verdict_alpha_edge = 4, verdict_coarse = 8, verdict_ill_conditioned = 16, &
                        verdict_inaccurate = 32, verdict_uncertain = 64
  character(len=*), parameter :: verdict_words(7) = [character(len=15) :: 'degenerate', 'nonphysical', &
                                                     'alpha-edge', 'coarse', 'ill-conditioned', 'inaccurate', &
                                                     'uncertain']

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
  !> (tests/scenario/test_solver_paths.py), so 1e-10 keeps them good to about 1e-9.
  real(real64), parameter :: iterative_residual_limit = 1e-10_real64

contains

  !> The code of a verdict word (0 for an unknown word).
  pure integer function verdict_code(word)
    character(len=*), intent(in) :: word
    integer :: k
    verdict_code = 0
    do k = 1, size(verdict_words)
      if (trim(verdict_words(k)) == word) verdict_code = 2**(k - 1)
    end do
  end function verdict_code

  !> The verdict column and the warnings that explain it.
  !> solve: the solver options of the solve; when kcreep chose the GMRES
  !> tolerance itself (the caller gave none), a residual within 10 times it is
  !> what was asked for and not flagged.
  subroutine judge(scheme, requested, patch, traction, f, diag, solve, flags, verdict_text, warnings)
    type(scheme_t), intent(in) :: scheme
    logical, intent(in) :: requested(n_load_cases)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: traction(:, :)
    real(real64), intent(in) :: f(3, 3)
    type(dense_diagnostics_t), intent(in) :: diag
    type(solver_options_t), intent(in) :: solve
    integer, intent(out) :: flags
    character(len=:), allocatable, intent(out) :: verdict_text
    character(len=message_length), allocatable, intent(inout) :: warnings(:)
    real(real64) :: coherence, residual_limit
    integer :: n
    character(len=:), allocatable :: verdict

    n = patch%n
    flags = verdict_ok
    verdict = ''
    residual_limit = iterative_residual_limit
    if (.not. solve%tolerance_given) residual_limit = max(residual_limit, 10 * solve%tolerance)
    if (requested(1)) then
      coherence = traction_coherence(traction(1:n, 1))
      if (coherence < coherence_limit) then
        call flag('degenerate', 'the xi traction changes sign over the patch (|sum px|/sum|px| = '// &
                  rtoa(coherence)//'): the discrete solution oscillates and f11 is unreliable'// &
                  trim(hint()))
      end if
    end if
    if (requested(2)) then
      coherence = traction_coherence(traction(n + 1:2 * n, 2))
      if (coherence < coherence_limit) then
        call flag('degenerate', 'the eta traction changes sign over the patch (|sum py|/sum|py| = '// &
                  rtoa(coherence)//'): the discrete solution oscillates and f22 is unreliable'// &
                  trim(hint()))
      end if
    end if
    if ((requested(1) .and. .not. f(1, 1) > 0) .or. &
        (requested(2) .and. .not. f(2, 2) > 0)) then
      call flag('nonphysical', 'f11 or f22 is not positive: the traction does not oppose the creepage'// &
                trim(hint()))
    end if
    if (scheme%name == 'collocation' .and. abs(scheme%alpha) >= alpha_edge_limit) then
      call flag('alpha-edge', 'alpha = '//rtoa(scheme%alpha)//' puts the collocation point at the cell edge, '// &
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
    else if (.not. diag%backward_error <= residual_limit) then
      ! GMRES has no factorisation to estimate rcond from; its residual is what it reached
      call flag('inaccurate', 'GMRES stopped at relative residual '//rtoa(diag%backward_error)// &
                ': coefficients may be off beyond the 1e-8 level (lower &solver tolerance)')
    end if
    if (len(verdict) == 0) verdict = 'ok'
    verdict_text = verdict

  contains

    subroutine flag(word, text)
      character(len=*), intent(in) :: word, text
      character(len=message_length) :: line
      flags = ior(flags, verdict_code(word))
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
      if (scheme%name /= 'collocation') return
      aspect = patch%dx / patch%dy
      if (scheme%alpha <= 0) then
        text = '; collocation needs alpha > 0 (toward the leading edge), e.g. alpha = 0.5'
      else if (aspect > 1.5_real64 .or. aspect < 1 / 1.5_real64) then
        text = '; the cells are elongated (dx/dy = '//rtoa(aspect)// &
               '): use near-square cells or scheme = ''backward'''
      end if
    end function hint

  end subroutine judge

end module kcreep_verdict
