!> How the linear systems are solved: dense LU or FFT-accelerated GMRES,
!> and the splits that leave out what the scene does not need.
module kcreep_solver_options
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use kcreep_threads, only: max_threads
  implicit none
  private
  public :: solver_options_t, validate_solver_options

  type :: solver_options_t
    character(len=:), allocatable :: method      !< 'dense', 'iterative' or 'auto'
    real(real64) :: tolerance = 1e-11_real64     !< iterative: relative residual ||b - A x|| / ||b||
    !> The caller set tolerance. When not, the levels of error control stop
    !> GMRES at a residual chosen from the target (kcreep_refine_estimate
    !> level_solver_tolerance) and the verdict judges the residual against it.
    logical :: tolerance_given = .false.
    integer :: max_iterations = 1000             !< iterative: total GMRES iterations per load case
    integer :: restart = 50                      !< iterative: GMRES restart length
    !> iterative: 'circulant' (running sum along the rows and the FFT inverse
    !> of the displacement operator), 'strip' (exact inverse of each row's
    !> block) or 'auto' (circulant, strip for collocation at alpha <= 0)
    character(len=16) :: preconditioner = 'auto'
    !> Solve y-symmetric patches as an even and an odd half-size problem and,
    !> at nu = 0, px and py separately (off only to check the splits).
    logical :: split_systems = .true.
    !> Bytes the solve may allocate (the caller measures what the machine
    !> allows); negative: no limit known, nothing is checked.
    integer(int64) :: memory_limit = -1
    !> Threads of each stage: 0 automatic (the CPUs this process may use
    !> that are free when the stage starts, where the work pays for them:
    !> kcreep_threads), else this many.
    integer :: threads = 0
  end type solver_options_t

contains

  subroutine validate_solver_options(opts, where, status)
    type(solver_options_t), intent(in) :: opts
    character(len=*), intent(in) :: where     !< "input 'file': "
    type(status_t), intent(inout) :: status
    select case (opts%method)
    case ('dense', 'iterative', 'auto')
    case default
      call fail(status, exit_bad_input, where//'&solver method = '''//opts%method// &
                ''' (allowed: ''dense'', ''iterative'', ''auto'')')
    end select
    select case (trim(opts%preconditioner))
    case ('auto', 'circulant', 'strip')
    case default
      call fail(status, exit_bad_input, where//'&solver preconditioner = '''//trim(opts%preconditioner)// &
                ''' (allowed: ''auto'', ''circulant'', ''strip'')')
    end select
    if (.not. (opts%tolerance >= 1e-15_real64 .and. opts%tolerance < 1)) call fail(status, exit_bad_input, &
        where//'&solver tolerance = '//rtoa(opts%tolerance)//' (allowed: 1e-15 <= tolerance < 1)')
    if (opts%max_iterations < 1) call fail(status, exit_bad_input, where//'&solver max_iterations = '// &
        itoa(opts%max_iterations)//' (must be >= 1)')
    if (opts%threads < 0 .or. opts%threads > max_threads) call fail(status, exit_bad_input, where// &
        '&solver threads = '//itoa(opts%threads)//' (allowed: 0 = automatic, or 1 to '//itoa(max_threads)//')')
    if (opts%restart < 1 .or. opts%restart > 1000) call fail(status, exit_bad_input, where// &
        '&solver restart = '//itoa(opts%restart)//' (allowed: 1 to 1000)')
  end subroutine validate_solver_options

end module kcreep_solver_options
