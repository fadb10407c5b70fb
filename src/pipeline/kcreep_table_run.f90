!> &solver method = 'table': an ellipse's creep coefficients interpolated in
!> kcreep's refined table (kcreep_table_interpolation) instead of solved, in
!> microseconds. Nothing is discretised: no tractions (result%traction is not
!> allocated, mx = my = n = 0); result%err holds the table's stated relative
!> uncertainties of C11, C22, C23 and the verdict is 'ok' or 'uncertain'
!> against target_error as on the other paths. The patch is kept in the
!> result for FASTSIM, which needs only a grid and the coefficients.
!>
!> method = 'auto' takes this path too (table_meets_target) for an ellipse
!> whose grids kcreep would choose, when the table's stated uncertainty meets
!> the target: the table holds the continuum limits that such a run would
!> extrapolate to, computed at higher resolution than the run could afford.
module kcreep_table_run
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use kcreep_status, only: status_t
  use kcreep_creep_matrix, only: normalised, centre_transfer
  use kcreep_kalker_table, only: kalker_coefficients
  use kcreep_fastsim, only: fastsim_flexibilities
  use kcreep_equivalent_ellipse, only: equivalent_ellipses
  use kcreep_verdict, only: verdict_ok
  use kcreep_table_interpolation, only: table_coefficients
  use kcreep_problem, only: problem_t, result_t, add_uncertain
  use kcreep_refine_estimate, only: coefficient_targets, within_target
  implicit none
  private
  public :: run_table, table_matrix, table_meets_target

contains

  !> The result of problem%patch (an ellipse; kcreep_check made sure) from the table.
  subroutine run_table(problem, result, status)
    type(problem_t), intent(in) :: problem
    type(result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    real(real64) :: c4(4), rel(4), nan
    integer(int64) :: t0, t1, rate
    integer :: j

    call system_clock(t0, rate)
    nan = ieee_value(1.0_real64, ieee_quiet_nan)
    allocate (result%warnings(0))
    associate (patch => problem%patch)
      call table_coefficients(patch%semi_a / patch%semi_b, problem%nu, c4, rel, status)
      if (status%failed()) return
      result%c = sqrt(patch%semi_a * patch%semi_b)
      ! the ellipse's centre where the patch was placed (the spin centre is the origin here)
      result%centroid = patch%ellipse_centre()
      call table_matrix(c4, rel, problem%g, result%c, result%centroid, result%f, result%err)
      do j = 1, 3
        if (.not. problem%requested(j)) result%f(:, j) = nan
      end do
      result%cn = normalised(result%f, problem%g, result%c)
      result%scheme = 'table'
      result%method = 'table'
      result%refine = 'none'
      result%alpha = nan
      result%nu = problem%nu
      result%g = problem%g
      result%patch = patch
      result%rcond = nan
      result%backward_error = nan
      result%backward_error_initial = nan
      result%relative_residual = nan
      result%fastsim = fastsim_flexibilities(patch, result%f(1, 1), result%f(2, 2), result%f(2, 3))
      result%ellipse = equivalent_ellipses(patch%inside, patch%dx, patch%dy, patch%x0, patch%y0, &
                                           problem%nu, problem%g)
      result%klt = kalker_coefficients(patch%semi_a / patch%semi_b, problem%nu)
    end associate
    result%verdict_flags = verdict_ok
    result%verdict = 'ok'
    call add_uncertain(result, problem%target_error, 'the refined table''s relative uncertainties', &
                       'a solve (method = ''auto'') can reach the target')
    call system_clock(t1)
    result%t_total = real(t1 - t0, real64) / rate
  end subroutine run_table

  !> method = 'auto' answers from the table: an ellipse whose grids kcreep
  !> chooses (refine_grid, target_error > 0), the backward scheme as by
  !> default (the table's limits are the continuum's, which any scheme
  !> converges to, but the paper's collocation, when chosen, is run), no extrapolation
  !> asked for, no tractions wanted, a/b and nu in the table, and the table's
  !> stated uncertainty of C11, C22, C23 within their targets.
  pure logical function table_meets_target(problem) result(meets)
    type(problem_t), intent(in) :: problem
    real(real64) :: c4(4), rel(4)
    type(status_t) :: status
    meets = .false.
    if (.not. allocated(problem%solve%method)) return
    if (problem%solve%method /= 'auto') return
    if (problem%patch%kind /= 'ellipse' .or. .not. problem%refine_grid .or. problem%target_error <= 0) return
    if (problem%extrapolate .or. problem%tractions_wanted .or. problem%normal%active) return
    if (problem%scheme%name /= 'backward' .or. problem%scheme%spin_shift /= 0) return
    call table_coefficients(problem%patch%semi_a / problem%patch%semi_b, problem%nu, c4, rel, status)
    if (status%failed()) return
    meets = within_target(rel(1:3), coefficient_targets(problem%target_error))
  end function table_meets_target

  !> f(3, 3) about the origin of an ellipse centred at centre = (xc, yc) from
  !> the table's C11 C22 C23 C33 (about its centre) and their relative
  !> uncertainties rel; err: the relative uncertainties of f11, f22, f23.
  !> The spin about the origin is a spin about the centre plus the creepages
  !> (xi, eta) = phi (-yc, xc), and Mz about the origin adds xc Fy - yc Fx:
  !> f = T' f0 T with T = [1 0 -yc; 0 1 xc; 0 0 1] (f23 = f0_23 + xc f22, ...).
  pure subroutine table_matrix(c4, rel, g, c, centre, f, err)
    real(real64), intent(in) :: c4(4), rel(4), g, c, centre(2)
    real(real64), intent(out) :: f(3, 3), err(3)
    real(real64) :: f0(3, 3), t(3, 3)
    f0 = 0
    f0(1, 1) = g * c**2 * c4(1)
    f0(2, 2) = g * c**2 * c4(2)
    f0(2, 3) = g * c**3 * c4(3)
    f0(3, 2) = -f0(2, 3)
    f0(3, 3) = g * c**4 * c4(4)
    t = centre_transfer(centre)
    f = matmul(transpose(t), matmul(f0, t))
    err(1:2) = rel(1:2)
    ! f23 = f0_23 + xc f22: the absolute uncertainties add
    err(3) = (abs(f0(2, 3)) * rel(3) + abs(centre(1) * f0(2, 2)) * rel(2)) / abs(f(2, 3))
  end subroutine table_matrix

end module kcreep_table_run
