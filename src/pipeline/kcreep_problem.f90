!> What the library is asked (problem_t) and what it answers (result_t).
!>
!> A problem is a patch on its grid, the material, the discretisation scheme,
!> how to solve, and which load cases (xi, eta, phi) are wanted. The result is
!> the 3 x 3 creep-force matrix with everything needed to judge it: the
!> normalised values, the error estimate when one was computed, the solver's
!> diagnostics, the verdict (codes and messages) and, on request, the
!> tractions. Nothing here knows about namelists or files.
module kcreep_problem
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use kcreep_patch, only: patch_t
  use kcreep_assembly, only: scheme_t, n_load_cases
  use kcreep_solver_options, only: solver_options_t
  use kcreep_verdict, only: verdict_ok, verdict_uncertain, message_length
  use kcreep_strings, only: rtoa
  use kcreep_refine_estimate, only: uncertain_flag, coefficient_targets, level_solver_tolerance, default_target_error
  use kcreep_gap, only: gap_t, polynomial_gap_t
  use kcreep_wheel_rail_geometry, only: plane_gap_t
  use kcreep_normal_solve, only: normal_options_t
  use kcreep_equivalent_ellipse, only: equivalent_ellipse_t
  implicit none
  private
  public :: problem_t, result_t, default_problem, normal_problem_t, add_warning, append_prefixed, add_uncertain, &
            mark_uncertain, level_tolerance, cell_budget_or

  !> The normal contact problem that finds the patch: when active, the patch
  !> is the set of cells with positive pressure on the gap's grid (cropped
  !> to its bounding box), and problem%patch is not used.
  type :: normal_problem_t
    logical :: active = .false.
    type(gap_t) :: gap                          !< undeformed distance on its grid
    !> The gap as a function (rx, ry, ...) when it was given so: error control
    !> evaluates it on finer grids; otherwise it resamples gap.
    logical :: poly_given = .false.
    type(polynomial_gap_t) :: poly
    !> The gap in a wheel-rail contact plane (kcreep_wheel_rail_geometry): when
    !> allocated, error control evaluates it on the finer grids instead.
    type(plane_gap_t), allocatable :: plane
    real(real64) :: compliance = 0              !< 1/E*; 0: (1 - nu)/g of the problem's material
    logical :: force_given = .false.            !< normal_force prescribed, else approach
    real(real64) :: approach = 0, normal_force = 0
    type(normal_options_t) :: options
  end type normal_problem_t

  type :: problem_t
    type(patch_t) :: patch
    real(real64) :: g = 1                       !< combined shear modulus
    real(real64) :: nu = 0.25_real64            !< combined Poisson's ratio
    type(scheme_t) :: scheme                    !< 'collocation' (alpha) or 'backward' (spin_shift)
    type(solver_options_t) :: solve             !< dense / iterative / auto, tolerance, splits
    logical :: requested(n_load_cases) = .true. !< load cases xi, eta, phi to solve
    character(len=:), allocatable :: refine     !< dense refinement: 'auto', 'always', 'never', 'lapack'
    logical :: extrapolate = .false.            !< Richardson extrapolation in the mesh size
    integer :: extrapolate_levels = 3, refine_ratio = 2
    !> Relative error aimed at for C11 and C22 (C23: 3 times it); 0: no target,
    !> the grid as given (an error estimate is still made). The same default
    !> (default_target_error, 1e-3) for the program, the library, C and Python.
    real(real64) :: target_error = default_target_error
    !> kcreep may choose the grids (ellipse: near-square cells), split the
    !> cells (mask) or resample the gap to meet target_error; false: the grid
    !> is solved as given (and judged). The C API and Python turn it off for
    !> an ellipse whose grid the caller gives, as the namelist does.
    logical :: refine_grid = .true.
    !> The most patch cells of a level kcreep chooses under error control
    !> (ellipse levels, mask splits, gap levels); 0: the defaults, a run-time
    !> budget (kcreep_refine_estimate level_cell_budget: 160,000 at 1e-3).
    !> Raised for reference work, where minutes per case are acceptable.
    real(real64) :: cell_budget = 0
    !> With target_error = 0: still estimate the error of the given grid (one
    !> more solve on a coarser or split grid). Off only in loops that solve the
    !> same kind of patch over and over and judged its grid once (the C API's
    !> kcreep_set_error_control); the estimate is then NaN.
    logical :: estimate_error = .true.
    !> The point (x, y) about which the spin phi turns and the moment Mz is
    !> taken (the rigid slip is xi - phi (y - ys), eta + phi (x - xs)); the
    !> coordinate origin by default.
    real(real64) :: spin_centre(2) = 0
    type(normal_problem_t) :: normal            !< patch from the normal contact problem
    !> The tractions are wanted (a traction file): method = 'auto' then
    !> solves even where the refined table would meet the target.
    logical :: tractions_wanted = .false.
  end type problem_t

  type :: result_t
    character(len=:), allocatable :: scheme     !< as solved
    integer :: mx = 0, my = 0, n = 0            !< grid and patch cells solved (the finest level)
    real(real64) :: alpha = 0, nu = 0, g = 0    !< alpha NaN for the backward scheme
    real(real64) :: c = 0                       !< normalising length: sqrt(a b), or sqrt(area / pi)
    real(real64) :: f(3, 3) = 0                 !< f(i, j) = f_ij; (Fx, Fy, Mz) = -f (xi, eta, phi)
    real(real64) :: cn(3) = 0                   !< C11, C22, C23
    real(real64) :: klt(3) = 0                  !< Kalker's table E3 for an ellipse, NaN otherwise
    real(real64) :: fastsim(3) = 0              !< FASTSIM flexibilities L1, L2, L3
    real(real64) :: centroid(2) = 0             !< centre of area of the patch cells
    real(real64) :: spin_centre(2) = 0          !< as given in the problem
    !> the equivalent ellipses (same area; a/b of the bounding box, of the second moments) with
    !> Kalker's coefficients and flexibilities (kcreep_equivalent_ellipse)
    type(equivalent_ellipse_t) :: ellipse(2)
    ! Richardson extrapolation (problem%extrapolate): limits, error estimates, orders used
    logical :: extrapolated = .false.
    real(real64) :: ext(3) = 0, ext_error(3) = 0, ext_order(3) = 0
    !> Estimated relative errors of C11, C22, C23 (every run; NaN: no estimate)
    real(real64) :: err(3) = 0
    ! diagnostics of the solve
    character(len=:), allocatable :: method     !< 'dense' or 'iterative'
    integer :: iterations = 0                   !< GMRES iterations, 0 for dense
    integer :: threads = 1                      !< threads the (last) linear solve ran on
    real(real64) :: rcond = 0, backward_error = 0
    real(real64) :: backward_error_initial = 0, relative_residual = 0   !< before refinement
    character(len=:), allocatable :: refine     !< mode and whether it refined
    real(real64) :: t_assemble = 0, t_factor = 0, t_solve = 0, t_total = 0
    real(real64) :: t_operator = 0, t_preconditioner = 0, t_orthogonalise = 0   !< GMRES profile
    ! verdict
    integer :: verdict_flags = verdict_ok
    character(len=:), allocatable :: verdict    !< 'ok' or the words of the flags, comma separated
    character(len=message_length), allocatable :: warnings(:)   !< one sentence per problem found
    type(patch_t) :: patch                      !< the grid solved (the finest level)
    !> (2 n, 3): px (1:n) and py (n+1:2n) of each load case per unit creepage,
    !> NaN for cases not requested; cells numbered as in the patch
    real(real64), allocatable :: traction(:, :)
    ! the normal contact problem (problem%normal%active)
    logical :: normal_solved = .false.
    real(real64) :: fn = 0, approach = 0, pmax = 0   !< total force, approach, maximum pressure
    real(real64) :: normal_residual = 0         !< final complementarity residual (relative)
    integer :: normal_iterations = 0
    real(real64) :: bbox(4) = 0                 !< xmin xmax ymin ymax of the contact cells (cell edges)
    real(real64), allocatable :: pressure(:)    !< per patch cell
  end type result_t

contains

  !> A level of error control: GMRES stops at the target's residual
  !> (level_solver_tolerance) unless the caller gave a tolerance.
  pure subroutine level_tolerance(level_problem)
    type(problem_t), intent(inout) :: level_problem
    if (level_problem%solve%tolerance_given) return
    level_problem%solve%tolerance = max(level_problem%solve%tolerance, &
                                        level_solver_tolerance(level_problem%target_error))
  end subroutine level_tolerance

  !> The most patch cells of a level under error control: the caller's
  !> cell_budget when given, else default_cells (the kind of patch's own).
  pure real(real64) function cell_budget_or(problem, default_cells) result(cells)
    type(problem_t), intent(in) :: problem
    real(real64), intent(in) :: default_cells
    cells = merge(problem%cell_budget, default_cells, problem%cell_budget > 0)
  end function cell_budget_or

  !> A problem with every setting at kcreep's default (no patch yet): the
  !> namelist reader and the C and Python bindings start from this.
  pure function default_problem() result(problem)
    type(problem_t) :: problem
    problem%scheme%name = 'backward'
    ! the same error control as the command line: target_error 1e-3, kcreep
    ! chooses the grids (refine_grid)
    problem%target_error = default_target_error
    problem%refine_grid = .true.
    problem%solve%method = 'auto'
    problem%refine = 'auto'
  end function default_problem

  !> Append one warning to a result (its list may not exist yet).
  pure subroutine add_warning(result, line)
    type(result_t), intent(inout) :: result
    character(len=*), intent(in) :: line
    call append_line(result%warnings, line)
  end subroutine add_warning

  !> 'uncertain' in the verdict, with its warning, when an estimate misses its
  !> target or is missing (target 0 too: an 'ok' needs a finite estimate).
  !> what: the estimates' name in the warning; advice: what could reach the
  !> target (optional, appended).
  pure subroutine add_uncertain(result, target, what, advice, solved)
    type(result_t), intent(inout) :: result
    real(real64), intent(in) :: target
    character(len=*), intent(in) :: what
    character(len=*), intent(in), optional :: advice
    logical, intent(in), optional :: solved(3)   !< load cases xi, eta, phi run (C11, C22, C23's)
    character(len=message_length) :: line
    real(real64) :: targets(3)
    if (len(uncertain_flag(result%err, target, solved)) == 0) return
    targets = coefficient_targets(target)
    if (target > 0) then
      line = 'uncertain: '//what//' of C11, C22, C23 '//estimate(1)//', '//estimate(2)//', '//estimate(3)// &
             ' against targets '//rtoa(targets(1))//', '//rtoa(targets(2))//', '//rtoa(targets(3))// &
             ' (target_error, C23 gets 3 times it)'
    else
      line = 'uncertain: no error estimate of '//missing()//' (target_error = 0 sets no target, but ok needs '// &
             'an estimate)'
    end if
    if (present(advice)) line = trim(line)//': '//advice
    call mark_uncertain(result, line)
  contains
    !> An estimate in words when there is none.
    pure function estimate(i) result(text)
      integer, intent(in) :: i
      character(len=:), allocatable :: text
      if (ieee_is_nan(result%err(i))) then
        text = 'not estimated'
      else
        text = rtoa(result%err(i))
      end if
    end function estimate
    !> 'C11, C23': the coefficients without a finite estimate.
    pure function missing() result(text)
      character(len=:), allocatable :: text
      character(len=3), parameter :: names(3) = ['C11', 'C22', 'C23']
      integer :: i
      text = ''
      do i = 1, 3
        if (present(solved)) then
          if (.not. solved(i)) cycle
        end if
        if (result%err(i) <= huge(1.0_real64)) cycle
        if (len(text) > 0) text = text//', '
        text = text//names(i)
      end do
    end function missing
  end subroutine add_uncertain

  !> 'uncertain' in the verdict (once), with the warning `why`: the estimates
  !> may be within their targets, but they are not known to bound the error.
  pure subroutine mark_uncertain(result, why)
    type(result_t), intent(inout) :: result
    character(len=*), intent(in) :: why
    if (iand(result%verdict_flags, verdict_uncertain) == 0) then
      result%verdict_flags = ior(result%verdict_flags, verdict_uncertain)
      if (result%verdict == 'ok') then
        result%verdict = 'uncertain'
      else
        result%verdict = result%verdict//',uncertain'
      end if
    end if
    call add_warning(result, why)
  end subroutine mark_uncertain

  !> Append a level's warnings to a list, each behind prefix (e.g.
  !> 'level 48 (96 x 96): '); level_warnings may not exist.
  pure subroutine append_prefixed(warnings, prefix, level_warnings)
    character(len=message_length), allocatable, intent(inout) :: warnings(:)
    character(len=*), intent(in) :: prefix
    character(len=message_length), allocatable, intent(in) :: level_warnings(:)
    integer :: i
    if (.not. allocated(level_warnings)) return
    do i = 1, size(level_warnings)
      call append_line(warnings, prefix//trim(level_warnings(i)))
    end do
  end subroutine append_prefixed

  !> Append one line to a list of messages (which may not exist yet).
  pure subroutine append_line(lines, line)
    character(len=message_length), allocatable, intent(inout) :: lines(:)
    character(len=*), intent(in) :: line
    character(len=message_length), allocatable :: grown(:)
    integer :: n
    n = 0
    if (allocated(lines)) n = size(lines)
    ! copied element by element: gfortran's -fcheck=all misreads the length
    ! of an array constructor built from an allocatable component
    allocate (grown(n + 1))
    if (n > 0) grown(1:n) = lines
    grown(n + 1) = line
    call move_alloc(grown, lines)
  end subroutine append_line

end module kcreep_problem
