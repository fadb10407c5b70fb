!> kcreep: Kalker's creep coefficients of any contact patch, as a library.
!>
!>   type(problem_t) :: problem          ! patch, material, scheme, solver, load cases
!>   type(result_t)  :: result           ! f(3, 3), C11 C22 C23, error estimate, verdict, ...
!>   type(status_t)  :: status           ! code 0 or the error and its one-line message
!>   call ellipse_patch(2.0_real64, 1.0_real64, 80, 40, problem%patch, status)
!>   call kcreep_solve(problem, result, status)
!>
!> The library prints nothing, reads no environment and writes no files:
!> those belong to its callers (the command line in app/, the C API in
!> src/api, the Python package on top of it).
module kcreep
  use kcreep_status, only: status_t, fail, exit_bad_input, exit_numerical, exit_io
  use kcreep_patch, only: patch_t, ellipse_patch, mask_patch
  use kcreep_assembly, only: scheme_t, n_load_cases, load_case_names
  use kcreep_solver_options, only: solver_options_t
  use kcreep_verdict, only: verdict_ok, verdict_degenerate, verdict_nonphysical, verdict_alpha_edge, &
                            verdict_coarse, verdict_ill_conditioned, verdict_inaccurate, verdict_words, &
                            message_length
  use kcreep_problem, only: problem_t, result_t, default_problem
  use kcreep_check, only: check_problem
  use kcreep_run, only: run_case, solve_cache_t
  use kcreep_extrapolation, only: run_extrapolated
  implicit none
  private
  public :: kcreep_solve, kcreep_version, kcreep_version_number
  public :: problem_t, result_t, default_problem, solve_cache_t, status_t, patch_t, scheme_t, solver_options_t
  public :: ellipse_patch, mask_patch, n_load_cases, load_case_names, message_length
  public :: exit_bad_input, exit_numerical, exit_io
  public :: verdict_ok, verdict_degenerate, verdict_nonphysical, verdict_alpha_edge, verdict_coarse, &
            verdict_ill_conditioned, verdict_inaccurate, verdict_words

  character(len=*), parameter :: kcreep_version = '0.2.0'
  !> The same as one number: 10000 major + 100 minor + patch.
  integer, parameter :: kcreep_version_number = 200

contains

  !> Check the problem, then solve it: on its own grid, or on the levels of a
  !> Richardson extrapolation when problem%extrapolate is set.
  !> cache: kept by the caller between solves on the same grid (the C API's
  !> handle does), so that the operator table is built once.
  subroutine kcreep_solve(problem, result, status, cache)
    type(problem_t), intent(in) :: problem
    type(result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    type(solve_cache_t), intent(inout), optional :: cache

    call check_problem(problem, status)
    if (status%failed()) return
    if (problem%extrapolate) then
      call run_extrapolated(problem, result, status)
    else
      call run_case(problem, result, status, cache)
    end if
  end subroutine kcreep_solve

end module kcreep
