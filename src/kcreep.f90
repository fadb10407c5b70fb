!> kcreep: Kalker's creep coefficients of any contact patch, as a library.
!>
!>   type(problem_t) :: problem          ! patch, material, scheme, solver, load cases
!>   type(result_t)  :: result           ! f(3, 3), C11 C22 C23, error estimate, verdict, ...
!>   type(status_t)  :: status           ! code 0 or the error and its one-line message
!>   call ellipse_patch(2.0_real64, 1.0_real64, 80, 40, problem%patch, status)
!>   call kcreep_solve(problem, result, status)
!>
!> The library prints nothing, reads no environment variables and writes no
!> files: those belong to its callers (the command line in app/, the C API
!> in src/api, the Python package on top of it). Only its automatic thread
!> count looks at the machine (kcreep_threads).
module kcreep
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_strings, only: rtoa
  use kcreep_status, only: status_t, fail, exit_bad_input, exit_numerical, exit_io
  use kcreep_patch, only: patch_t, ellipse_patch, mask_patch
  use kcreep_assembly, only: scheme_t, n_load_cases, load_case_names
  use kcreep_solver_options, only: solver_options_t, validate_solver_options
  use kcreep_dense, only: refine_modes
  use kcreep_solve_memory, only: process_bytes, normal_cell_bytes, wheel_rail_shift_bytes, wheel_rail_cell_bytes, &
                                 wheel_rail_row_cell_bytes
  use kcreep_threads, only: team_size, enter_team, leave_team, cells_per_thread_iterative, solve_started, &
                            solve_ended, max_threads, serial_blas, run_team
  use kcreep_verdict, only: verdict_ok, verdict_degenerate, verdict_nonphysical, verdict_alpha_edge, &
                            verdict_coarse, verdict_ill_conditioned, verdict_inaccurate, verdict_uncertain, &
                            verdict_words, &
                            message_length
  use kcreep_problem, only: problem_t, result_t, default_problem, normal_problem_t, cell_budget_or
  use kcreep_normal_solve, only: normal_result_t, normal_options_t
  use kcreep_gap, only: gap_t, polynomial_gap_t, gap_from_array, gap_from_polynomial, auto_grid
  use kcreep_creep_matrix, only: normalised_about
  use kcreep_check, only: check_problem, collocation_aspect_limit
  use kcreep_run, only: run_case, solve_cache_t
  use kcreep_rolling_curve, only: rolling_request_t, rolling_point_t, rolling_curve, default_rolling_tolerance, &
                                 cell_stick, cell_slip, rolling_residual_of, rolling_state_t, release_rolling_state
  use kcreep_fast_build, only: fast_forces_t, build_fast_forces, fast_forces_of
  use kcreep_grid_transfer, only: coarsened_patch
  use kcreep_creep_curve, only: creep_request_t, creep_point_t, creep_map_t, creep_curve, source_names, &
                                source_flexibilities
  use kcreep_fastsim_forces, only: fastsim_forces, fastsim_result_t, flexibility_weighted, flexibility_separate, &
                                  flexibility_aligned, flexibility_rule_name, flexibility_rule_of
  use kcreep_pressure_models, only: hertz_pressure, strip_parabolic_pressure
  use kcreep_equivalent_ellipse, only: equivalent_ellipse_t, equivalent_ellipses
  use kcreep_extrapolation, only: run_extrapolated, memory_need
  use kcreep_error_run, only: run_controlled, controlled_finest_patch
  use kcreep_gap_levels, only: normal_grid_cells, gap_levels_need
  use kcreep_level_ladder, only: region_level_cap
  use kcreep_refine_estimate, only: default_target_error, nominal_ellipse_cells, level_cell_budget
  use kcreep_normal_influence, only: compliance_from_e_nu, combined_g_nu_from_e_nu
  use kcreep_table_run, only: run_table, table_meets_target
  use kcreep_wheel_rail_run, only: wheel_rail_base_cells => base_cells
  use kcreep_wheel_rail_run, only: wheel_rail_setup_t, wheel_rail_row_t, run_wheel_rail, wheel_rail_columns, &
                                   wheel_state_t, check_wheel_rail_setup, max_wheel_rail_shifts, &
                                   most_shifts_at_once, wheel_rail_needs
  use kcreep_wheelset, only: wheelset_row_t, wheelset_columns, run_wheelset
  implicit none
  private
  public :: kcreep_solve, kcreep_memory_need, kcreep_wheel_rail_memory_need
  public :: kcreep_version, kcreep_version_number, max_threads, serial_blas, run_team, enter_team, leave_team
  public :: rolling_request_t, rolling_point_t, rolling_curve, default_rolling_tolerance, cell_stick, cell_slip, &
            rolling_residual_of, rolling_state_t, release_rolling_state
  public :: fast_forces_t, build_fast_forces, fast_forces_of, coarsened_patch
  public :: creep_request_t, creep_point_t, creep_map_t, creep_curve, source_names, source_flexibilities
  public :: validate_solver_options, refine_modes, collocation_aspect_limit, normalised_about
  public :: fastsim_forces, fastsim_result_t, flexibility_weighted, flexibility_separate, flexibility_aligned, &
            flexibility_rule_name, flexibility_rule_of
  public :: compliance_from_e_nu, combined_g_nu_from_e_nu
  public :: hertz_pressure, strip_parabolic_pressure, equivalent_ellipse_t, equivalent_ellipses
  public :: normal_problem_t, normal_options_t, gap_t, polynomial_gap_t, gap_from_array, gap_from_polynomial, auto_grid
  public :: problem_t, result_t, default_problem, solve_cache_t, status_t, patch_t, scheme_t, solver_options_t
  public :: ellipse_patch, mask_patch, n_load_cases, load_case_names, message_length
  public :: exit_bad_input, exit_numerical, exit_io, default_target_error, nominal_ellipse_cells
  public :: verdict_ok, verdict_degenerate, verdict_nonphysical, verdict_alpha_edge, verdict_coarse, &
            verdict_ill_conditioned, verdict_inaccurate, verdict_uncertain, verdict_words
  public :: kcreep_wheel_rail, wheel_rail_setup_t, wheel_rail_row_t, wheel_rail_columns, check_wheel_rail_setup, &
            max_wheel_rail_shifts, default_target_error
  public :: kcreep_wheelset, wheelset_row_t, wheelset_columns, wheel_state_t

  character(len=*), parameter :: kcreep_version = '0.2.0'
  !> The same as one number: 10000 major + 100 minor + patch.
  integer, parameter :: kcreep_version_number = 200

contains

  !> Check the problem, then solve it under error control (kcreep_error_run:
  !> on the levels kcreep chooses, or on the grid given with an error estimate),
  !> or on the levels of the older Richardson extrapolation when problem%extrapolate
  !> is set, or (problem%solve%method = 'table', ellipses) from the refined
  !> table. With problem%normal%active the normal contact problem is solved
  !> first and its contact area is the patch (the pressure comes back in
  !> result%pressure).
  !> cache: kept by the caller between solves on the same grid (the C API's
  !> handle does), so that the operator table is built once.
  subroutine kcreep_solve(problem, result, status, cache)
    type(problem_t), intent(in) :: problem
    type(result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    type(solve_cache_t), intent(inout), optional :: cache

    type(problem_t) :: centred
    integer :: previous_team

    ! the stages outside the linear solves (operator tables, assembly) on a
    ! team for the patch as given; each solve chooses its own (kcreep_threads)
    call solve_started()
    call enter_team(team_size(problem%solve%threads, int(problem%patch%n, int64), cells_per_thread_iterative), &
                    previous_team)
    solve: block
      if (problem%normal%active) then
        ! the patch is the contact area of the normal problem, solved under error
        ! control on grids of finer geometry (kcreep_gap_levels)
        call run_controlled(problem, result, status, cache)
        exit solve
      end if
      call check_problem(problem, status)
      if (status%failed()) exit solve
      if (all(problem%spin_centre == 0)) then
        call solve_as_given(problem)
      else
        ! about another point: solve the patch moved so that the point is the
        ! origin (the operator depends on cell offsets only), then move back
        centred = problem
        centred%patch%x0 = problem%patch%x0 - problem%spin_centre(1)
        centred%patch%y0 = problem%patch%y0 - problem%spin_centre(2)
        call solve_as_given(centred)
        if (status%failed()) exit solve
        result%centroid = result%centroid + problem%spin_centre
        result%patch%x0 = result%patch%x0 + problem%spin_centre(1)
        result%patch%y0 = result%patch%y0 + problem%spin_centre(2)
      end if
      if (status%failed()) exit solve
      result%spin_centre = problem%spin_centre
      call warn_spin_centre_outside(problem%patch, problem%spin_centre, result%warnings)
    end block solve
    call leave_team(previous_team)
    call solve_ended()

  contains

    !> Extrapolation when asked for, else the run under error control (which
    !> solves a given grid as given when the target is 0 or refine_grid off);
    !> method = 'table', or 'auto' where the table meets the target:
    !> interpolation in the refined table, nothing solved.
    subroutine solve_as_given(p)
      type(problem_t), intent(in) :: p
      if (p%solve%method == 'table' .or. table_meets_target(p)) then
        call run_table(p, result, status)
      else if (p%extrapolate) then
        call run_extrapolated(p, result, status)
      else
        call run_controlled(p, result, status, cache)
      end if
    end subroutine solve_as_given

  end subroutine kcreep_solve

  !> The contact table of a wheel on a rail (docs/wheel_rail.md): for each
  !> lateral shift of setup, every contact patch, its contact plane and gap, the
  !> normal problem there and its error-controlled coefficients; one row per
  !> shift and patch. base carries the material, the solver settings, the
  !> target error and the normal solver's options; its patch is not used.
  !> setup is checked first (profiles given, check_wheel_rail_setup). team:
  !> the shifts that ran at once (one per thread). states: each shift's wheel
  !> state, for kcreep_wheelset of the same setup and base.
  subroutine kcreep_wheel_rail(setup, base, rows, status, team, states)
    type(wheel_rail_setup_t), intent(in) :: setup
    type(problem_t), intent(in) :: base
    type(wheel_rail_row_t), allocatable, intent(out) :: rows(:)
    type(status_t), intent(inout) :: status
    integer, intent(out), optional :: team
    type(wheel_state_t), allocatable, intent(out), optional :: states(:)
    if (present(team)) team = 1
    if (.not. (allocated(setup%wheel_y) .and. allocated(setup%rail_y))) then
      call fail(status, exit_bad_input, 'wheel/rail: no wheel or rail profile given')
    else
      call check_wheel_rail_setup(setup, 'wheel/rail: ', status)
    end if
    if (status%failed()) then
      allocate (rows(0))
      return
    end if
    call run_wheel_rail(setup, base, rows, status, team, states)
  end subroutine kcreep_wheel_rail

  !> The wheelset table of setup (docs/wheel_rail.md, Wheelset): per shift
  !> both wheels' rolling radii and contact angles, their difference, the
  !> wheelset's roll and vertical position and the equivalent conicity at
  !> amplitude |shift|; the left wheel mirrored, on setup's left profiles if
  !> given. Needs vertical_force; setup checked as for kcreep_wheel_rail.
  !> states: kcreep_wheel_rail's of the same setup and base (its shifts'
  !> wheel states are then not computed again).
  subroutine kcreep_wheelset(setup, base, table, status, states)
    type(wheel_rail_setup_t), intent(in) :: setup
    type(problem_t), intent(in) :: base
    type(wheelset_row_t), allocatable, intent(out) :: table(:)
    type(status_t), intent(inout) :: status
    type(wheel_state_t), intent(in), optional :: states(:)
    type(wheel_rail_setup_t) :: checked
    checked = setup
    checked%wheelset = .true.
    if (.not. (allocated(setup%wheel_y) .and. allocated(setup%rail_y))) then
      call fail(status, exit_bad_input, 'wheelset: no wheel or rail profile given')
    else
      call check_wheel_rail_setup(checked, 'wheelset: ', status)
    end if
    if (status%failed()) then
      allocate (table(0))
      return
    end if
    call run_wheelset(checked, base, table, status, states)
  end subroutine kcreep_wheelset

  !> Bytes kcreep_solve(problem) needs at its peak and the solve path it takes
  !> there ('dense', 'iterative' or 'table'): the dense subsystem matrix or
  !> the iterative solver's storage, and the operator table, of the grid or
  !> of the finest level error control or extrapolation may choose, and the
  !> process's own resident set (kcreep_solve_memory: the model, measured
  !> against the program's peak RSS, and its evidence).
  subroutine kcreep_memory_need(problem, bytes, method, status)
    type(problem_t), intent(in) :: problem
    integer(int64), intent(out) :: bytes
    character(len=:), allocatable, intent(out) :: method
    type(status_t), intent(inout) :: status
    type(problem_t) :: bounded
    type(patch_t) :: bound
    integer :: level
    integer(int64) :: need
    real(real64) :: cells

    bytes = 0
    method = 'table'
    ! interpolation in the refined table: no operator, no system
    if (problem%solve%method == 'table' .or. table_meets_target(problem)) return
    bounded = problem
    if (problem%normal%active) then
      ! the contact area lies inside the interpenetration area {h < approach}
      ! (the whole grid when the force is given): the tangential solve on that
      ! bound, plus the normal solve's (normal_cell_bytes per grid cell)
      associate (gap => problem%normal%gap)
        if (problem%normal%force_given) then
          call mask_patch(gap%h < huge(1.0_real64), gap%dx, gap%dy, gap%x0, gap%y0, 'gap', bound, status)
        else
          call mask_patch(gap%h < problem%normal%approach, gap%dx, gap%dy, gap%x0, gap%y0, 'gap', bound, status)
        end if
        bytes = normal_cell_bytes * int(gap%mx, int64) * gap%my
      end associate
      if (status%failed()) return
      bounded%extrapolate = .false.
      if (problem%target_error > 0 .and. problem%refine_grid .and. region_level_cap(problem) < huge(1) .and. &
          problem%solve%method /= 'dense') then
        ! error control with its levels held to region_level_cap: the normal
        ! problems solved as the run solves them, the ladder's finest level
        ! counted from the contact area found (kcreep_gap_levels gap_levels_need)
        call gap_levels_need(problem, need, cells, status)
        bytes = process_bytes + need
        method = 'iterative'
        return
      else if (problem%target_error > 0 .and. problem%refine_grid) then
        ! error control (kcreep_gap_levels): the normal problem again on a
        ! fine grid of at most normal_grid_cells, then the levels
        bytes = max(bytes, normal_cell_bytes * int(normal_grid_cells(problem), int64))
        call controlled_finest_patch(problem, bound, status)
        if (status%failed()) return
      end if
    else
      ! under error control: the finest level kcreep may choose
      call controlled_finest_patch(problem, bound, status)
      if (status%failed()) return
    end if
    bounded%patch = bound
    call memory_need(bounded, need, method, level, status)
    bytes = bytes + need + process_bytes
  end subroutine kcreep_memory_need

  !> Bytes the wheel/rail table of setup (&wheel_rail) needs at its peak,
  !> and its solve path there, for the most shifts it may run at once
  !> (most_shifts_at_once). Under error control with the levels held to
  !> region_level_cap (no cell budget given, the default target or looser):
  !> the geometry and normal problems of every shift run as the table runs
  !> them, and each patch's finest level counted from its contact area
  !> (wheel_rail_needs): the largest shifts at once, and what the earlier
  !> rows keep. Otherwise: one patch, a gap first solved on at most
  !> wheel_rail_base_cells x wheel_rail_base_cells cells, under error
  !> control its levels up to the cell budget (kcreep_solve_memory).
  subroutine kcreep_wheel_rail_memory_need(problem, setup, bytes, method, status)
    type(problem_t), intent(in) :: problem
    type(wheel_rail_setup_t), intent(in) :: setup
    integer(int64), intent(out) :: bytes
    character(len=:), allocatable, intent(out) :: method
    type(status_t), intent(inout) :: status
    type(problem_t) :: patch_problem
    integer(int64) :: budget
    real(real64), allocatable :: shift_bytes(:), shift_cells(:)
    integer :: at_once, shifts, k
    shifts = size(setup%shifts)
    at_once = most_shifts_at_once(problem%solve%threads, shifts)
    if (problem%target_error > 0 .and. region_level_cap(problem) < huge(1) .and. &
        problem%solve%method /= 'dense') then
      call wheel_rail_needs(setup, problem, shift_bytes, shift_cells, status)
      if (status%failed()) return
      bytes = process_bytes + int(wheel_rail_row_cell_bytes * sum(shift_cells), int64)
      do k = 1, at_once
        bytes = bytes + int(maxval(shift_bytes), int64)
        shift_bytes(maxloc(shift_bytes, 1)) = -1
      end do
      method = 'iterative'
      return
    end if
    patch_problem = problem
    patch_problem%normal%active = .true.
    patch_problem%normal%force_given = .true.
    call gap_from_array(spread(spread(0.0_real64, 1, wheel_rail_base_cells), 2, wheel_rail_base_cells), &
                        1.0_real64, 1.0_real64, 0.0_real64, 0.0_real64, 'wheel/rail patch', patch_problem%normal%gap, &
                        status)
    if (status%failed()) return
    call kcreep_memory_need(patch_problem, bytes, method, status)
    if (status%failed()) return
    if (problem%target_error > 0 .and. problem%refine_grid) then
      ! the levels up to the cell budget, as measured (kcreep_solve_memory)
      budget = int(cell_budget_or(problem, level_cell_budget(problem%target_error)), int64)
      bytes = process_bytes + at_once * (wheel_rail_shift_bytes + wheel_rail_cell_bytes * budget) + &
              (shifts - 1) * wheel_rail_row_cell_bytes * budget
    else
      bytes = process_bytes + at_once * (bytes - process_bytes)
    end if
  end subroutine kcreep_wheel_rail_memory_need

  !> f13, f23, f31, f32, f33 refer to the spin centre: when it lies outside
  !> the patch's bounding box (a mask in profile coordinates, spun about a
  !> far origin) they are dominated by the lever arm, so say so.
  subroutine warn_spin_centre_outside(patch, centre, warnings)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: centre(2)
    character(len=message_length), allocatable, intent(inout) :: warnings(:)
    real(real64) :: xmin, xmax, ymin, ymax
    character(len=message_length) :: line
    if (patch%n < 1) return
    xmin = patch%x0 + (minval(patch%ix) - 1.5_real64) * patch%dx
    xmax = patch%x0 + (maxval(patch%ix) - 0.5_real64) * patch%dx
    ymin = patch%y0 + (minval(patch%iy) - 1.5_real64) * patch%dy
    ymax = patch%y0 + (maxval(patch%iy) - 0.5_real64) * patch%dy
    if (centre(1) >= xmin .and. centre(1) <= xmax .and. centre(2) >= ymin .and. centre(2) <= ymax) return
    if (all(centre == 0)) then
      line = 'the spin centre, the coordinate origin, lies outside the patch''s bounding box ['// &
             rtoa(xmin)//', '//rtoa(xmax)//'] x ['//rtoa(ymin)//', '//rtoa(ymax)//']: f13, f23, f31, f32, f33 '// &
             'are about that far point (&solver spin_centre = ''centroid'' takes the patch''s centroid)'
    else
      line = 'the spin centre ('//rtoa(centre(1))//', '//rtoa(centre(2))//') lies outside the patch''s '// &
             'bounding box ['//rtoa(xmin)//', '//rtoa(xmax)//'] x ['//rtoa(ymin)//', '//rtoa(ymax)//']'
    end if
    if (.not. allocated(warnings)) allocate (warnings(0))
    warnings = [warnings, line]
  end subroutine warn_spin_centre_outside

end module kcreep
