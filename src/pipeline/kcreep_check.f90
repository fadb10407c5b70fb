!> Checks of a problem before any work: every value in its allowed range,
!> with a message naming the variable, its value and what is allowed. The
!> namelist reader has its own checks (naming file and group); these guard
!> the library's other callers (the C and Python bindings).
module kcreep_check
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use kcreep_limits, only: modulus_in_range
  use kcreep_solver_options, only: validate_solver_options
  use kcreep_dense, only: refine_modes
  use kcreep_problem, only: problem_t
  use kcreep_refine_estimate, only: cell_budget_allowed, cell_budget_range
  implicit none
  private
  public :: check_problem, collocation_aspect_limit

  !> Cells longer in x than this (dx/dy) are 'long' for collocation: the
  !> verdict's hint uses the same 1.5 (kcreep_verdict).
  real(real64), parameter :: collocation_aspect_limit = 1.5_real64

contains

  subroutine check_problem(problem, status)
    type(problem_t), intent(in) :: problem
    type(status_t), intent(inout) :: status

    if (problem%patch%n < 1 .or. .not. allocated(problem%patch%inside)) then
      call fail(status, exit_bad_input, 'patch: no cell inside (build it with an ellipse or a mask)')
    else if (.not. modulus_in_range(problem%g)) then
      call fail(status, exit_bad_input, 'g = '//rtoa(problem%g)//' (must be > 0, between 1e-100 and 1e100)')
    else if (.not. (problem%nu >= 0 .and. problem%nu <= 0.5_real64)) then
      call fail(status, exit_bad_input, 'nu = '//rtoa(problem%nu)//' (allowed: 0 <= nu <= 0.5)')
    else if (problem%scheme%name /= 'collocation' .and. problem%scheme%name /= 'backward') then
      call fail(status, exit_bad_input, 'scheme = '''//problem%scheme%name// &
                ''' (allowed: ''collocation'', ''backward'')')
    else if (.not. (abs(problem%scheme%alpha) < 1)) then
      call fail(status, exit_bad_input, 'alpha = '//rtoa(problem%scheme%alpha)// &
                ' (allowed: -1 < alpha < 1, the open interval)')
    else if (.not. (abs(problem%scheme%spin_shift) <= 1)) then
      call fail(status, exit_bad_input, 'spin_shift = '//rtoa(problem%scheme%spin_shift)// &
                ' (allowed: -1 <= spin_shift <= 1 cell)')
    else if (.not. any(problem%requested)) then
      call fail(status, exit_bad_input, 'load cases: none requested (at least one of xi, eta, phi)')
    else if (.not. allocated(problem%refine)) then
      call fail(status, exit_bad_input, 'refine: not set (allowed: auto, always, never, lapack)')
    else if (.not. any(refine_modes == problem%refine)) then
      call fail(status, exit_bad_input, 'refine = '''//problem%refine//''' (allowed: auto, always, never, lapack)')
    else if (problem%extrapolate .and. (problem%extrapolate_levels < 2 .or. problem%extrapolate_levels > 3)) then
      call fail(status, exit_bad_input, 'extrapolate_levels = '//itoa(problem%extrapolate_levels)// &
                ' (allowed: 2 or 3)')
    else if (.not. (problem%target_error >= 0 .and. problem%target_error < 1)) then
      call fail(status, exit_bad_input, 'target_error = '//rtoa(problem%target_error)// &
                ' (allowed: 0 <= target_error < 1; 0: the grid as given)')
    else if (.not. cell_budget_allowed(problem%cell_budget)) then
      call fail(status, exit_bad_input, 'cell_budget = '//rtoa(problem%cell_budget)//' '//cell_budget_range())
    else if (problem%extrapolate .and. (problem%refine_ratio < 2 .or. problem%refine_ratio > 4)) then
      call fail(status, exit_bad_input, 'refine_ratio = '//itoa(problem%refine_ratio)//' (allowed: 2 to 4)')
    end if
    if (status%failed()) return
    ! collocation on cells long in x is unusable (3-12 % off, with or without
    ! extrapolation; docs/accuracy.md): error control refuses it; a grid run
    ! as given (target_error = 0) is allowed and flagged by the verdict
    if (problem%scheme%name == 'collocation' .and. problem%target_error > 0 .and. &
        .not. (problem%refine_grid .and. problem%patch%kind == 'ellipse')) then
      if (problem%patch%dx > collocation_aspect_limit * problem%patch%dy) then
        call fail(status, exit_bad_input, 'scheme = ''collocation'' on cells long in x (dx/dy = '// &
                  rtoa(problem%patch%dx / problem%patch%dy)//', allowed <= '//rtoa(collocation_aspect_limit)// &
                  ' with target_error > 0): use near-square cells, scheme = ''backward'', or target_error = 0 '// &
                  'to run this grid as given')
        return
      end if
    end if
    if (.not. allocated(problem%solve%method)) then
      call fail(status, exit_bad_input, 'method: not set (allowed: dense, iterative, auto, table)')
      return
    end if
    if (problem%solve%method == 'table') then
      ! interpolation in the refined table of ellipses: nothing is solved
      if (problem%patch%kind /= 'ellipse') then
        call fail(status, exit_bad_input, 'method = ''table'' only for ellipses (patch kind '''// &
                  problem%patch%kind//'''): the refined table holds ellipses; use dense, iterative or auto')
      else if (problem%extrapolate) then
        call fail(status, exit_bad_input, 'method = ''table'' takes no extrapolation (nothing is solved): '// &
                  'leave extrapolation off')
      end if
      return
    end if
    call validate_solver_options(problem%solve, '', status)
  end subroutine check_problem

end module kcreep_check
