!> The namelist input: reading, defaults and validation.
!>
!> Groups &patch, &material, &solver, &output, &normal, each optional
!> (&normal describes the normal contact problem of shape = 'gap'). Anything out of
!> range or inconsistent is reported through status with the file, group,
!> variable, value and what is allowed, before any computation or output.
module kcreep_namelist
  use, intrinsic :: iso_fortran_env, only: real64, iostat_end
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, lower, resolve_path, folder_of
  use kcreep_patch, only: patch_t, ellipse_patch, mask_patch
  use kcreep_mask_file, only: read_mask_file, parse_mask_rows
  use kcreep_assembly, only: scheme_t, load_case_names, n_load_cases
  use kcreep_contact_reader, only: contact_case_t, read_contact_case, combined_material
  use kcreep_contact_compare, only: contact_spin_shift
  use kcreep_file_checks, only: read_input_file
  use kcreep_namelist_scan, only: scan_namelist_text
  use kcreep_limits, only: check_grid_size, length_in_range, offset_in_range, modulus_in_range
  use kcreep_solver_options, only: solver_options_t, validate_solver_options
  use kcreep_table_interpolation, only: table_ratio_range
  use kcreep_dense, only: refine_modes
  use kcreep_problem, only: problem_t
  use kcreep_error_control, only: default_target_error, cell_budget_allowed, cell_budget_range
  use kcreep_check, only: collocation_aspect_limit
  use kcreep_problem, only: problem_t, normal_problem_t
  use kcreep_gap, only: gap_t, polynomial_gap_t, gap_from_polynomial, auto_grid
  use kcreep_gap_file, only: read_gap_file
  use kcreep_contact_input, only: contact_input_t, read_contact_input
  use kcreep_hertz, only: hertz_t, hertz_from_force
  use kcreep_normal_influence, only: compliance_from_g_nu, compliance_from_e_nu, combined_g_nu_from_e_nu
  use kcreep_creep_curve, only: creep_request_t, source_names
  use kcreep_fastsim_forces, only: flexibility_rule_of
  use kcreep_rolling_input, only: rolling_config_t, read_rolling_group
  implicit none
  private
  public :: config_t, read_config, build_patch, problem_of, max_inline_rows, max_row_length, max_creepages

  integer, parameter :: max_inline_rows = 2048, max_row_length = 2048
  integer, parameter :: default_cells = 60
  integer, parameter :: max_creepages = 100000   !< creepage points of &fastsim (list and sweep together)
  character(len=*), parameter :: group_names(7) = [character(len=8) :: 'patch', 'material', 'solver', 'output', &
                                                    'normal', 'fastsim', 'rolling']
  !> &normal: the number of cells across the automatic grid's larger side, its margin
  integer, parameter :: default_cells_across = 60
  real(real64), parameter :: default_margin = 0.2_real64

  type :: config_t
    character(len=:), allocatable :: input_path
    ! &patch
    character(len=:), allocatable :: shape
    real(real64) :: semi_a = 1, semi_b = 1
    integer :: mx = 0, my = 0                   !< 0: not given
    character(len=:), allocatable :: mask_file
    character(len=max_row_length), allocatable :: mask_rows(:)   !< inline rows given
    real(real64) :: dx = 0, dy = 0, x0 = 0, y0 = 0
    logical :: x0_given = .false., y0_given = .false.   !< x0, y0 written in the namelist
    character(len=:), allocatable :: contact_file   !< shape 'contact': CONTACT .out file
    integer :: contact_case = 0
    type(contact_case_t) :: contact                 !< what was read from it
    ! &material
    real(real64) :: g = 1, nu = 0.25_real64
    ! &solver
    type(scheme_t) :: scheme
    logical :: requested(n_load_cases) = .true.
    logical :: extrapolate = .false.            !< Richardson in the mesh size (mesh_extrapolation)
    real(real64) :: target_error = 0            !< &solver target_error (kcreep_error_control)
    real(real64) :: cell_budget = 0             !< &solver cell_budget (problem_t%cell_budget; 0: the defaults)
    logical :: refine_grid = .false.            !< kcreep chooses the grids (ellipse without mx, my; mask)
    integer :: extrapolate_levels = 3, refine_ratio = 2
    character(len=:), allocatable :: refine     !< see dense_solver refine_modes
    type(solver_options_t) :: solve           !< method, tolerance, splits
    character(len=:), allocatable :: spin_centre   !< 'origin', 'centroid' or 'point'
    real(real64) :: spin_centre_xy(2) = 0          !< the point of spin_centre = 'point'
    ! &fastsim (group absent: fastsim_on false, nothing of it runs)
    logical :: fastsim_on = .false.
    type(creep_request_t) :: fastsim
    type(rolling_config_t) :: rolling               !< &rolling (kcreep_rolling_input); rolling%on: given
    character(len=:), allocatable :: pressure       !< 'hertz', 'contact', 'file', 'parabolic' (after 'auto')
    character(len=:), allocatable :: pressure_input_file   !< pressure = 'file': the pressure per cell
    real(real64) :: fn = 1                          !< load of the 'hertz' and 'parabolic' pressures
    ! &output
    character(len=:), allocatable :: table_file, traction_file, creep_file, creep_map_file
    character(len=:), allocatable :: pressure_file, contact_mask_file   !< shape 'gap' only
    ! &normal (shape 'gap')
    character(len=:), allocatable :: gap_file, contact_inp
    integer :: contact_inp_case = 1
    type(polynomial_gap_t) :: poly              !< rx, ry (+ linear, cubic terms)
    logical :: approach_given = .false., force_given = .false.
    real(real64) :: approach = 0, normal_force = 0
    integer :: cells_across = default_cells_across
    real(real64) :: margin = default_margin
    real(real64) :: e(2) = 0, poisson(2) = 0    !< per body, when given (e(1) > 0)
    type(normal_problem_t) :: normal            !< built by read_config
  end type config_t

contains

  !> Read and validate the namelist at path. Relative file names inside it
  !> (mask_file, contact_file, table_file, traction_file) are taken relative
  !> to the namelist's own folder, whatever the working folder and the mode
  !> (single run, batch, memory estimate). Only the default table, which the
  !> namelist does not name, goes to the working folder.
  subroutine read_config(path, cfg, status)
    character(len=*), intent(in) :: path
    type(config_t), intent(out) :: cfg
    type(status_t), intent(inout) :: status

    ! namelist variables, with their defaults
    character(len=32) :: shape, scheme, method, refine, spin_centre, preconditioner
    real(real64) :: spin_centre_x, spin_centre_y
    real(real64) :: semi_a, semi_b, dx, dy, x0, y0, g, nu, alpha, spin_shift, tolerance, target_error, cell_budget
    integer :: mx, my, extrapolate_levels, refine_ratio, max_iterations, restart, threads
    logical :: extrapolate, split_systems
    character(len=4096) :: mask_file, table_file, traction_file
    character(len=64) :: load_cases
    character(len=max_row_length), allocatable :: mask_rows(:)
    character(len=4096) :: contact_file
    integer :: contact_case
    ! &normal
    character(len=4096) :: gap_file, contact_inp, pressure_file, contact_mask_file
    integer :: contact_inp_case, cells_across, normal_max_iterations
    real(real64) :: rx, ry, lx, ly, cx, cy, approach, normal_force, margin, e1, nu1, e2, nu2, normal_tolerance
    ! &fastsim
    real(real64) :: mu, fn, l1, l2, l3, sweep_direction(3), sweep_from, sweep_to
    real(real64), allocatable :: creepages(:)
    integer :: sweep_points
    character(len=16) :: sweep_spacing, rule, pressure
    character(len=128) :: flexibility
    character(len=4096) :: pressure_input_file, creep_file, creep_map_file, rolling_file, rolling_map_file
    logical :: maps
    !> "not given": g, nu and spin_shift default differently for shape = 'contact',
    !> and a value the user wrote is either used or refused, never replaced
    real(real64), parameter :: unset = -huge(1.0_real64)
    integer, parameter :: unset_int = -huge(1)
    character(len=:), allocatable :: where
    logical :: material_given, scheme_given
    namelist /patch/ shape, semi_a, semi_b, mx, my, mask_file, mask_rows, dx, dy, x0, y0, contact_file, contact_case
    namelist /material/ g, nu
    namelist /solver/ target_error, cell_budget, scheme, alpha, spin_shift, load_cases, extrapolate, extrapolate_levels, &
                      refine_ratio, refine, method, tolerance, max_iterations, restart, split_systems, spin_centre, &
                      spin_centre_x, spin_centre_y, preconditioner, threads
    namelist /output/ table_file, traction_file, pressure_file, contact_mask_file, creep_file, &
                      creep_map_file, rolling_file, rolling_map_file
    namelist /normal/ gap_file, contact_inp, contact_inp_case, rx, ry, lx, ly, cx, cy, approach, normal_force, &
                      cells_across, margin, e1, nu1, e2, nu2, normal_tolerance, normal_max_iterations
    namelist /fastsim/ mu, creepages, sweep_direction, sweep_from, sweep_to, sweep_points, sweep_spacing, &
                       pressure, pressure_input_file, fn, flexibility, l1, l2, l3, rule, maps

    integer :: unit, ios, nrows
    logical :: group_present(size(group_names)), group_closed(size(group_names)), last_line_open
    character(len=512) :: msg
    character(len=:), allocatable :: text

    shape = 'ellipse'
    semi_a = unset
    semi_b = unset
    mx = unset_int
    my = unset_int
    mask_file = ''
    allocate (mask_rows(max_inline_rows))
    mask_rows = ''
    dx = 0
    dy = 0
    x0 = unset
    y0 = unset
    contact_file = ''
    contact_case = 1
    g = unset
    nu = unset
    scheme = ''
    target_error = unset
    cell_budget = 0
    alpha = unset
    spin_shift = unset
    load_cases = 'xi eta phi'
    spin_centre = 'origin'
    spin_centre_x = unset
    spin_centre_y = unset
    extrapolate = .false.
    extrapolate_levels = unset_int   ! (unset: given values that would go unused are refused below)
    refine_ratio = unset_int
    refine = ''
    method = 'auto'
    preconditioner = ''
    tolerance = unset
    max_iterations = unset_int
    restart = unset_int
    threads = cfg%solve%threads
    split_systems = cfg%solve%split_systems
    table_file = ''
    traction_file = ''
    pressure_file = ''
    contact_mask_file = ''
    gap_file = ''
    contact_inp = ''
    contact_inp_case = 1
    rx = 0
    ry = 0
    lx = 0
    ly = 0
    cx = 0
    cy = 0
    approach = unset
    normal_force = unset
    cells_across = default_cells_across
    margin = default_margin
    e1 = unset
    nu1 = unset
    e2 = unset
    nu2 = unset
    normal_tolerance = cfg%normal%options%tolerance
    normal_max_iterations = cfg%normal%options%max_iterations
    creep_file = ''
    creep_map_file = ''
    rolling_file = ''
    rolling_map_file = ''
    mu = unset
    allocate (creepages(3 * max_creepages + 1))
    creepages = unset
    sweep_direction = 0
    sweep_from = 0
    sweep_to = 0
    sweep_points = 0
    sweep_spacing = 'linear'
    pressure = 'auto'
    pressure_input_file = ''
    fn = unset
    flexibility = 'exact'
    l1 = 0
    l2 = 0
    l3 = 0
    rule = 'aligned'
    maps = .false.

    cfg%input_path = path
    ! the whole file first: a folder, a binary file, text outside the groups,
    ! unknown or repeated groups are errors the namelist read would not report
    call read_input_file(path, 'input '''//path//'''', text, status)
    if (.not. status%failed()) call scan_namelist_text(text, 'input '''//path//'''', group_names, group_present, &
                                                       group_closed, status)
    if (status%failed()) return
    ! a last line without its newline: the namelist read assigns the group and
    ! then meets the end of the file looking for the next record
    last_line_open = .false.
    if (len(text) > 0) last_line_open = text(len(text):len(text)) /= achar(10)
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_bad_input, 'input '''//path//''': cannot open ('//trim(msg)//')')
      return
    end if

    rewind (unit)
    if (group_present(1)) read (unit, nml=patch, iostat=ios, iomsg=msg)
    call check_read('patch', 1)
    rewind (unit)
    if (group_present(2)) read (unit, nml=material, iostat=ios, iomsg=msg)
    call check_read('material', 2)
    rewind (unit)
    if (group_present(3)) read (unit, nml=solver, iostat=ios, iomsg=msg)
    call check_read('solver', 3)
    rewind (unit)
    if (group_present(4)) read (unit, nml=output, iostat=ios, iomsg=msg)
    call check_read('output', 4)
    rewind (unit)
    if (group_present(5)) read (unit, nml=normal, iostat=ios, iomsg=msg)
    call check_read('normal', 5)
    rewind (unit)
    if (group_present(6)) read (unit, nml=fastsim, iostat=ios, iomsg=msg)
    call check_read('fastsim', 6)
    call read_rolling_group(unit, path, group_present(7), group_closed(7) .and. last_line_open, &
                            lower(trim(adjustl(shape))), extrapolate, cfg%rolling, status)
    close (unit)
    if (status%failed()) return

    cfg%shape = lower(trim(adjustl(shape)))
    scheme_given = len_trim(scheme) > 0
    ! shape = 'contact' follows CONTACT's conventions unless &solver says otherwise
    if (len_trim(scheme) == 0) scheme = 'backward'
    ! values written that the case would not use: refused, not ignored
    where = 'input '''//path//''': '
    if (mx /= unset_int .and. mx < 1) call fail(status, exit_bad_input, where//'&patch mx = '//itoa(mx)// &
        ' (must be >= 1; leave mx out for the default)')
    if (my /= unset_int .and. my < 1) call fail(status, exit_bad_input, where//'&patch my = '//itoa(my)// &
        ' (must be >= 1; leave my out for the default)')
    if (lower(trim(adjustl(scheme))) == 'collocation' .and. spin_shift /= unset) call fail(status, exit_bad_input, &
        where//'&solver spin_shift = '//rtoa(spin_shift)//' is not used by scheme = ''collocation'' '// &
        '(it moves the spin creepage of the backward scheme; leave it out or set scheme = ''backward'')')
    if (lower(trim(adjustl(scheme))) == 'backward' .and. alpha /= unset) call fail(status, exit_bad_input, &
        where//'&solver alpha = '//rtoa(alpha)//' is not used by scheme = ''backward'' '// &
        '(it is the collocation point of scheme = ''collocation''; leave it out or change the scheme)')
    if (cfg%shape /= 'ellipse' .and. semi_a /= unset) call fail(status, exit_bad_input, where// &
        '&patch semi_a = '//rtoa(semi_a)//' is only used by shape = ''ellipse'' (shape = '''//cfg%shape// &
        '''; leave it out)')
    if (cfg%shape /= 'ellipse' .and. semi_b /= unset) call fail(status, exit_bad_input, where// &
        '&patch semi_b = '//rtoa(semi_b)//' is only used by shape = ''ellipse'' (shape = '''//cfg%shape// &
        '''; leave it out)')
    cfg%spin_centre = lower(trim(adjustl(spin_centre)))
    select case (cfg%spin_centre)
    case ('origin', 'centroid')
      if (cfg%spin_centre == 'centroid' .and. cfg%shape == 'gap') call fail(status, exit_bad_input, where// &
          '&solver spin_centre = ''centroid'' is not available with shape = ''gap'' (the patch is found by the '// &
          'normal problem; spin about the origin)')
      if (spin_centre_x /= unset .or. spin_centre_y /= unset) call fail(status, exit_bad_input, where// &
          '&solver spin_centre_x, spin_centre_y are only used by spin_centre = ''point'' (spin_centre = '''// &
          cfg%spin_centre//''')')
    case ('point')
      if (spin_centre_x == unset .or. spin_centre_y == unset) call fail(status, exit_bad_input, where// &
          '&solver spin_centre = ''point'' needs both spin_centre_x and spin_centre_y')
      if (.not. (offset_in_range(spin_centre_x) .and. offset_in_range(spin_centre_y))) &
        call fail(status, exit_bad_input, where//'&solver spin_centre_x, spin_centre_y = '// &
                  rtoa(spin_centre_x)//', '//rtoa(spin_centre_y)//' (allowed: 0 or 1e-30 <= |x|, |y| <= 1e30)')
      cfg%spin_centre_xy = [spin_centre_x, spin_centre_y]
      if (cfg%shape == 'gap') call fail(status, exit_bad_input, where//'&solver spin_centre = ''point'' '// &
          'is not available with shape = ''gap'' (the patch is found by the normal problem; spin about the origin)')
    case default
      call fail(status, exit_bad_input, where//'&solver spin_centre = '''//cfg%spin_centre// &
                ''' (allowed: ''origin'', ''centroid'', ''point'' with spin_centre_x, spin_centre_y)')
    end select
    ! solver settings of a path the case does not take
    if (.not. extrapolate .and. (extrapolate_levels /= unset_int .or. refine_ratio /= unset_int)) &
      call fail(status, exit_bad_input, where//'&solver extrapolate_levels and refine_ratio are only used with '// &
                'extrapolate = .true. (leave them out, or set extrapolate = .true.)')
    if (lower(trim(adjustl(method))) == 'dense' .and. &
        (tolerance /= unset .or. max_iterations /= unset_int .or. restart /= unset_int)) &
      call fail(status, exit_bad_input, where//'&solver tolerance, max_iterations and restart are the '// &
                'iterative solver''s; method = ''dense'' does not use them (leave them out, or use method = '// &
                '''iterative'' or ''auto'')')
    if (lower(trim(adjustl(method))) == 'dense' .and. len_trim(preconditioner) > 0) &
      call fail(status, exit_bad_input, where//'&solver preconditioner = '''//trim(preconditioner)// &
                ''' is the iterative solver''s; method = ''dense'' does not use it (leave it out, or use '// &
                'method = ''iterative'' or ''auto'')')
    if (lower(trim(adjustl(method))) == 'iterative' .and. len_trim(refine) > 0) &
      call fail(status, exit_bad_input, where//'&solver refine = '''//trim(refine)//''' is the dense LU''s '// &
                'refinement; method = ''iterative'' does not use it (leave it out, or use method = ''dense'')')
    ! method = 'table': interpolation in the refined table of ellipses, nothing solved
    if (lower(trim(adjustl(method))) == 'table') then
      if (cfg%shape /= 'ellipse') call fail(status, exit_bad_input, where//'&solver method = ''table'' only '// &
          'for &patch shape = ''ellipse'' (shape = '''//cfg%shape//'''): the refined table holds ellipses; '// &
          'leave method out to solve this patch')
      if (extrapolate) call fail(status, exit_bad_input, where//'&solver extrapolate = .true. with method = '// &
          '''table'' (nothing is solved to extrapolate; leave it out)')
      if (scheme_given .or. alpha /= unset .or. spin_shift /= unset .or. tolerance /= unset .or. &
          max_iterations /= unset_int .or. restart /= unset_int .or. len_trim(refine) > 0 .or. &
          len_trim(preconditioner) > 0) &
        call fail(status, exit_bad_input, where//'&solver scheme, alpha, spin_shift, tolerance, max_iterations, '// &
                  'restart, preconditioner and refine are the solvers''; method = ''table'' solves nothing '// &
                  '(leave them out)')
      if (len_trim(traction_file) > 0) call fail(status, exit_bad_input, where//'&output traction_file = '''// &
          trim(traction_file)//''': method = ''table'' computes no tractions (leave traction_file out, or '// &
          'leave method out to solve for them)')
    end if
    if (status%failed()) return
    if (extrapolate_levels == unset_int) extrapolate_levels = 3
    if (refine_ratio == unset_int) refine_ratio = 2
    if (len_trim(refine) == 0) refine = 'auto'
    cfg%solve%tolerance_given = tolerance /= unset
    if (tolerance == unset) tolerance = cfg%solve%tolerance
    if (max_iterations == unset_int) max_iterations = cfg%solve%max_iterations
    if (restart == unset_int) restart = cfg%solve%restart
    if (mx == unset_int) mx = 0        ! 0 from here on: not given
    if (my == unset_int) my = 0
    if (semi_a == unset) semi_a = 1
    if (semi_b == unset) semi_b = 1
    if (alpha == unset) alpha = 0.5_real64
    cfg%x0_given = x0 /= unset
    cfg%y0_given = y0 /= unset
    if (x0 == unset) x0 = 0
    if (y0 == unset) y0 = 0
    ! error control: CONTACT's grid is compared as given (no target unless asked),
    ! so is the normal problem read from CONTACT's input; an ellipse without a
    ! grid and a mask are refined by kcreep to meet the target, a gap (gap_file,
    ! or rx, ry without a grid) by sampling its geometry on finer grids
    if (target_error == unset) target_error = merge(0.0_real64, default_target_error, &
                                                     cfg%shape == 'contact' .or. &
                                                     (cfg%shape == 'gap' .and. len_trim(contact_inp) > 0))
    cfg%target_error = target_error
    ! a pressure file for FASTSIM is given on the mask's own grid: keep that grid
    cfg%refine_grid = (cfg%shape == 'ellipse' .and. mx == 0 .and. my == 0) .or. &
                      (cfg%shape == 'mask' .and. len_trim(pressure_input_file) == 0) .or. &
                      (cfg%shape == 'gap' .and. len_trim(contact_inp) == 0 .and. mx == 0 .and. my == 0)
    cfg%cell_budget = cell_budget
    if (cell_budget /= 0 .and. .not. (cfg%refine_grid .and. target_error > 0 .and. .not. extrapolate)) &
      call fail(status, exit_bad_input, where//'&solver cell_budget = '//rtoa(cell_budget)//' limits the grids '// &
                'kcreep chooses under error control; this case has none (a given grid, target_error = 0 or '// &
                'extrapolate): leave cell_budget out')
    if (spin_shift == unset) spin_shift = merge(contact_spin_shift, 0.0_real64, cfg%shape == 'contact')
    material_given = g /= unset .or. nu /= unset
    if (g == unset) g = 1
    if (nu == unset) nu = 0.25_real64
    cfg%contact_file = trim(contact_file)
    cfg%contact_case = contact_case
    cfg%semi_a = semi_a
    cfg%semi_b = semi_b
    cfg%mx = mx
    cfg%my = my
    cfg%mask_file = trim(mask_file)
    nrows = count_rows(mask_rows)
    cfg%mask_rows = mask_rows(1:nrows)
    cfg%dx = dx
    cfg%dy = dy
    cfg%x0 = x0
    cfg%y0 = y0
    cfg%g = g
    cfg%nu = nu
    cfg%scheme%name = lower(trim(adjustl(scheme)))
    cfg%scheme%alpha = alpha
    cfg%scheme%spin_shift = spin_shift
    cfg%extrapolate = extrapolate
    cfg%extrapolate_levels = extrapolate_levels
    cfg%refine_ratio = refine_ratio
    cfg%refine = lower(trim(adjustl(refine)))
    cfg%solve%method = lower(trim(adjustl(method)))
    cfg%solve%tolerance = tolerance
    cfg%solve%max_iterations = max_iterations
    cfg%solve%restart = restart
    cfg%solve%threads = threads
    if (len_trim(preconditioner) > 0) cfg%solve%preconditioner = lower(trim(adjustl(preconditioner)))
    cfg%solve%split_systems = split_systems
    cfg%table_file = resolve_path(trim(table_file), folder_of(path))
    if (len(cfg%table_file) == 0) cfg%table_file = default_output_name(path, '.tab')
    ! every file name written in the namelist is relative to the namelist's folder
    cfg%traction_file = resolve_path(trim(traction_file), folder_of(path))
    cfg%mask_file = resolve_path(cfg%mask_file, folder_of(path))
    cfg%contact_file = resolve_path(cfg%contact_file, folder_of(path))
    cfg%pressure_file = resolve_path(trim(pressure_file), folder_of(path))
    cfg%contact_mask_file = resolve_path(trim(contact_mask_file), folder_of(path))
    cfg%gap_file = resolve_path(trim(gap_file), folder_of(path))
    cfg%contact_inp = resolve_path(trim(contact_inp), folder_of(path))
    cfg%contact_inp_case = contact_inp_case
    cfg%poly = polynomial_gap_t(rx=rx, ry=ry, lx=lx, ly=ly, cx=cx, cy=cy)
    cfg%approach_given = approach /= unset
    cfg%force_given = normal_force /= unset
    if (cfg%approach_given) cfg%approach = approach
    if (cfg%force_given) cfg%normal_force = normal_force
    cfg%cells_across = cells_across
    cfg%margin = margin
    cfg%normal%options%tolerance = normal_tolerance
    cfg%normal%options%max_iterations = normal_max_iterations

    cfg%fastsim_on = group_present(6)
    ! (like the default table, the default outputs go to the working folder)
    cfg%creep_file = resolve_path(trim(creep_file), folder_of(path))
    if (len(cfg%creep_file) == 0) cfg%creep_file = default_output_name(path, '.creep')
    cfg%creep_map_file = resolve_path(trim(creep_map_file), folder_of(path))
    if (maps .and. len(cfg%creep_map_file) == 0) cfg%creep_map_file = default_output_name(path, '.creepmap')
    cfg%pressure_input_file = resolve_path(trim(pressure_input_file), folder_of(path))
    cfg%rolling%rolling_file = resolve_path(trim(rolling_file), folder_of(path))
    if (len(cfg%rolling%rolling_file) == 0) cfg%rolling%rolling_file = default_output_name(path, '.roll')
    cfg%rolling%rolling_map_file = resolve_path(trim(rolling_map_file), folder_of(path))
    if (cfg%rolling%request%maps .and. len(cfg%rolling%rolling_map_file) == 0) &
      cfg%rolling%rolling_map_file = default_output_name(path, '.rollmap')
    cfg%rolling%request%maps = cfg%rolling%request%maps .or. len(cfg%rolling%rolling_map_file) > 0
    if (cfg%rolling%on .and. cfg%scheme%name /= 'backward') call fail(status, exit_bad_input, 'input '''//path// &
        ''': &rolling needs &solver scheme = ''backward'' (scheme = '''//cfg%scheme%name//''')')
    if (cfg%rolling%on .and. len(cfg%rolling%pressure_input_file) > 0 .and. cfg%shape == 'mask') &
      cfg%refine_grid = .false.   ! a pressure file is given on the mask's own grid

    call validate(cfg, mask_rows, nrows, load_cases, status)
    if (cfg%fastsim_on .and. .not. status%failed()) call validate_fastsim(status)
    if (cfg%shape == 'contact' .and. .not. status%failed()) call load_contact_case(cfg, material_given, status)
    if (.not. status%failed()) call validate_normal(cfg, group_present(5), material_given, [e1, nu1, e2, nu2], &
                                                    unset, status)
    if (cfg%shape == 'gap' .and. .not. status%failed()) call load_gap(cfg, status)
    if (cfg%rolling%on .and. cfg%rolling%pressure == 'contact' .and. .not. status%failed()) then
      if (.not. allocated(cfg%contact%pn)) call fail(status, exit_bad_input, 'input '''//path// &
          ''': &rolling pressure = ''contact'' needs the element file (.mat) of the case with its PN column')
    end if
    if (cfg%fastsim_on .and. cfg%pressure == 'contact' .and. .not. status%failed()) then
      if (.not. allocated(cfg%contact%pn)) call fail(status, exit_bad_input, 'input '''//path// &
          ''': &fastsim pressure = ''contact'' needs the element file (.mat) of the case with its PN column')
    end if

  contains

    !> &fastsim: friction, creepages (list and sweep), pressure, flexibility sources, rule.
    subroutine validate_fastsim(status)
      type(status_t), intent(inout) :: status
      character(len=:), allocatable :: where, word
      character(len=len(flexibility)) :: rest
      integer :: n_values, n_list, k, cut, s
      real(real64) :: t

      where = 'input '''//path//''': &fastsim '
      if (mu == unset) then
        call fail(status, exit_bad_input, where//'mu is required (the friction coefficient, > 0)')
        return
      end if
      if (.not. (mu > 0 .and. mu <= 1e3_real64)) then
        call fail(status, exit_bad_input, where//'mu = '//rtoa(mu)//' (allowed: 0 < mu <= 1000)')
        return
      end if
      cfg%fastsim%mu = mu
      ! the list: numbers up to the last one given, three per point
      n_values = size(creepages)
      do while (n_values > 0)
        if (creepages(n_values) /= unset) exit
        n_values = n_values - 1
      end do
      if (n_values > 3 * max_creepages) then
        call fail(status, exit_bad_input, where//'creepages: more than '//itoa(max_creepages)//' points')
        return
      end if
      if (mod(n_values, 3) /= 0) then
        call fail(status, exit_bad_input, where//'creepages: '//itoa(n_values)//' numbers given (allowed: '// &
                  '(xi, eta, phi) triples, a multiple of 3)')
        return
      end if
      if (any(creepages(1:n_values) == unset) .or. .not. all(abs(creepages(1:n_values)) <= 1e6_real64)) then
        call fail(status, exit_bad_input, where//'creepages: a value is missing or not finite (allowed: '// &
                  'finite numbers, |value| <= 1e6)')
        return
      end if
      n_list = n_values / 3
      if (sweep_points /= 0) then
        if (sweep_points < 2 .or. sweep_points > max_creepages - n_list) then
          call fail(status, exit_bad_input, where//'sweep_points = '//itoa(sweep_points)//' (allowed: 0 for '// &
                    'no sweep, or 2 to '//itoa(max_creepages - n_list)//')')
          return
        end if
        if (.not. any(sweep_direction /= 0) .or. .not. all(abs(sweep_direction) <= 1e6_real64)) then
          call fail(status, exit_bad_input, where//'sweep_direction = '//rtoa(sweep_direction(1))//', '// &
                    rtoa(sweep_direction(2))//', '//rtoa(sweep_direction(3))//' (a finite (xi, eta, phi), not all 0)')
          return
        end if
        select case (lower(trim(adjustl(sweep_spacing))))
        case ('linear')
          if (.not. (abs(sweep_from) <= 1e6_real64 .and. abs(sweep_to) <= 1e6_real64)) call fail(status, &
              exit_bad_input, where//'sweep_from, sweep_to = '//rtoa(sweep_from)//', '//rtoa(sweep_to)// &
              ' (allowed: finite, |value| <= 1e6)')
        case ('log')
          if (.not. (sweep_from > 0 .and. sweep_to > 0 .and. sweep_from <= 1e6_real64 .and. &
                     sweep_to <= 1e6_real64)) call fail(status, exit_bad_input, where//'sweep_from, sweep_to = '// &
              rtoa(sweep_from)//', '//rtoa(sweep_to)//' (sweep_spacing = ''log'' needs 0 < value <= 1e6)')
        case default
          call fail(status, exit_bad_input, where//'sweep_spacing = '''//trim(sweep_spacing)// &
                    ''' (allowed: ''linear'', ''log'')')
        end select
        if (status%failed()) return
      end if
      if (n_list + sweep_points == 0) then
        call fail(status, exit_bad_input, where//'no creepage: give creepages (xi, eta, phi triples) or a sweep '// &
                  '(sweep_direction, sweep_from, sweep_to, sweep_points)')
        return
      end if
      allocate (cfg%fastsim%creepages(3, n_list + sweep_points))
      cfg%fastsim%creepages(:, 1:n_list) = reshape(creepages(1:n_values), [3, n_list])
      do k = 1, sweep_points
        t = real(k - 1, real64) / (sweep_points - 1)
        if (lower(trim(adjustl(sweep_spacing))) == 'log') then
          t = sweep_from * (sweep_to / sweep_from)**t
        else
          t = sweep_from + (sweep_to - sweep_from) * t
        end if
        cfg%fastsim%creepages(:, n_list + k) = t * sweep_direction
      end do

      cfg%fastsim%rule = flexibility_rule_of(lower(trim(adjustl(rule))))
      if (cfg%fastsim%rule == 0) then
        call fail(status, exit_bad_input, where//'rule = '''//trim(rule)// &
                  ''' (allowed: ''aligned'', ''separate'', ''weighted'')')
        return
      end if

      cfg%fastsim%sources = .false.
      rest = lower(flexibility)
      do
        rest = adjustl(rest)
        if (len_trim(rest) == 0) exit
        cut = scan(rest, ' ,')
        if (cut == 0) cut = len(rest) + 1
        word = trim(rest(1:cut - 1))
        rest = rest(min(cut + 1, len(rest) + 1):)
        if (len(word) == 0) cycle
        select case (word)
        case ('ellipse')
          cfg%fastsim%sources(2:3) = .true.
        case ('all')
          cfg%fastsim%sources(1:3) = .true.
        case default
          ! (a loop: gfortran 12's findloc can miss a deferred-length scalar)
          s = 0
          do k = 1, size(source_names)
            if (source_names(k) == word) s = k
          end do
          if (s == 0) then
            call fail(status, exit_bad_input, where//'flexibility: unknown source '''//word//''' (allowed: '// &
                      '''exact'', ''ellipse-box'', ''ellipse-moments'', ''ellipse'' (both), ''all'', ''user'')')
            return
          end if
          cfg%fastsim%sources(s) = .true.
        end select
      end do
      if (.not. any(cfg%fastsim%sources)) then
        call fail(status, exit_bad_input, where//'flexibility is empty (allowed: exact, ellipse-box, '// &
                  'ellipse-moments, ellipse, all, user)')
        return
      end if
      if (cfg%fastsim%sources(4)) then
        if (.not. (l1 > 0 .and. l2 > 0 .and. l3 > 0 .and. max(l1, l2, l3) <= huge(1.0_real64))) then
          call fail(status, exit_bad_input, where//'flexibility = ''user'' needs l1, l2, l3 > 0 (given '// &
                    rtoa(l1)//', '//rtoa(l2)//', '//rtoa(l3)//')')
          return
        end if
        cfg%fastsim%user_flex = [l1, l2, l3]
      else if (l1 /= 0 .or. l2 /= 0 .or. l3 /= 0) then
        call fail(status, exit_bad_input, where//'l1, l2, l3 are used by flexibility = ''user'' only')
        return
      end if
      cfg%fastsim%maps = maps .or. len(cfg%creep_map_file) > 0

      cfg%pressure = lower(trim(adjustl(pressure)))
      if (cfg%pressure == 'auto') then
        select case (cfg%shape)
        case ('ellipse')
          cfg%pressure = 'hertz'
        case ('contact')
          cfg%pressure = 'contact'
        case ('gap')
          cfg%pressure = 'normal'
        case default
          cfg%pressure = trim(merge('file     ', 'parabolic', len(cfg%pressure_input_file) > 0))
        end select
      end if
      select case (cfg%pressure)
      case ('hertz')
        if (cfg%shape /= 'ellipse') call fail(status, exit_bad_input, where//'pressure = ''hertz'' needs '// &
            '&patch shape = ''ellipse'' (for other patches: ''file'', ''contact'' or ''parabolic'')')
      case ('contact')
        if (cfg%shape /= 'contact') call fail(status, exit_bad_input, where//'pressure = ''contact'' needs '// &
            '&patch shape = ''contact''')
      case ('normal')
        if (cfg%shape /= 'gap') call fail(status, exit_bad_input, where//'pressure = ''normal'' needs '// &
            '&patch shape = ''gap'' (the normal problem gives the pressure)')
      case ('file')
        if (len(cfg%pressure_input_file) == 0) call fail(status, exit_bad_input, where//'pressure = ''file'' needs '// &
            'pressure_input_file')
      case ('parabolic')
      case default
        call fail(status, exit_bad_input, where//'pressure = '''//cfg%pressure//''' (allowed: ''auto'', '// &
                  '''hertz'', ''contact'', ''normal'', ''file'', ''parabolic'')')
      end select
      if (status%failed()) return
      if (len(cfg%pressure_input_file) > 0 .and. cfg%pressure /= 'file') then
        call fail(status, exit_bad_input, where//'pressure_input_file is read with pressure = ''file'' only (pressure = '''// &
                  cfg%pressure//''')')
        return
      end if
      if (fn /= unset) then
        if (cfg%pressure /= 'hertz' .and. cfg%pressure /= 'parabolic') then  ! contact, normal, file: their own load
          call fail(status, exit_bad_input, where//'fn applies to pressure = ''hertz'' or ''parabolic'' only '// &
                    '(the pressure '''//cfg%pressure//''' carries its own load)')
          return
        end if
        if (.not. (fn > 0 .and. fn <= 1e30_real64)) then
          call fail(status, exit_bad_input, where//'fn = '//rtoa(fn)//' (allowed: 0 < fn <= 1e30)')
          return
        end if
        cfg%fn = fn
      end if
      if (cfg%extrapolate .and. (cfg%pressure == 'file' .or. cfg%pressure == 'contact')) then
        call fail(status, exit_bad_input, where//'pressure = '''//cfg%pressure//''' is given on the patch''s '// &
                  'own grid: not with &solver extrapolate = .true. (FASTSIM runs on the finest level)')
        return
      end if
    end subroutine validate_fastsim

    subroutine check_read(group, k)
      character(len=*), intent(in) :: group
      integer, intent(in) :: k
      if (.not. group_present(k) .or. status%failed()) return
      if (ios == iostat_end .and. group_closed(k) .and. last_line_open) then
        ios = 0                           ! read whole: its / was there, the newline after it was not
      else if (ios == iostat_end) then
        call fail(status, exit_bad_input, 'input '''//path//''': namelist &'//group// &
                  ': end of file before the closing /')
      else if (ios /= 0) then
        call fail(status, exit_bad_input, 'input '''//path//''': namelist &'//group//': '//trim(msg))
      end if
    end subroutine check_read

  end subroutine read_config

  !> Number of inline mask rows given: up to the last non-blank one.
  pure integer function count_rows(rows) result(nrows)
    character(len=*), intent(in) :: rows(:)
    nrows = size(rows)
    do while (nrows > 0)
      if (len_trim(rows(nrows)) > 0) exit
      nrows = nrows - 1
    end do
  end function count_rows

  subroutine validate(cfg, mask_rows, nrows, load_cases, status)
    type(config_t), intent(inout) :: cfg
    character(len=*), intent(in) :: mask_rows(:)
    integer, intent(in) :: nrows
    character(len=*), intent(in) :: load_cases
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: where

    where = 'input '''//cfg%input_path//''': '
    select case (cfg%shape)
    case ('ellipse')
      if (.not. length_in_range(cfg%semi_a)) call fail(status, exit_bad_input, where// &
          '&patch semi_a = '//rtoa(cfg%semi_a)//' (must be > 0, between 1e-30 and 1e30)')
      if (.not. length_in_range(cfg%semi_b)) call fail(status, exit_bad_input, where// &
          '&patch semi_b = '//rtoa(cfg%semi_b)//' (must be > 0, between 1e-30 and 1e30)')
      if (cfg%mx == 0) cfg%mx = default_cells
      if (cfg%my == 0) cfg%my = default_cells
      if (cfg%mx < 1) call fail(status, exit_bad_input, where//'&patch mx = '//itoa(cfg%mx)//' (must be >= 1)')
      if (cfg%my < 1) call fail(status, exit_bad_input, where//'&patch my = '//itoa(cfg%my)//' (must be >= 1)')
      call check_grid_size(cfg%mx, cfg%my, where//'&patch mx, my: ', status)
      if (len(cfg%mask_file) > 0 .or. nrows > 0) call fail(status, exit_bad_input, where// &
          '&patch shape = ''ellipse'' takes no mask_file or mask_rows (use shape = ''mask'')')
    case ('mask')
      if (len(cfg%mask_file) > 0 .and. nrows > 0) then
        call fail(status, exit_bad_input, where//'&patch: give mask_file or mask_rows, not both')
      else if (len(cfg%mask_file) == 0 .and. nrows == 0) then
        call fail(status, exit_bad_input, where//'&patch shape = ''mask'' needs mask_file or mask_rows')
      end if
      if (nrows > 0) then
        if (any(len_trim(mask_rows(1:nrows)) == len(mask_rows))) call fail(status, exit_bad_input, where// &
            '&patch mask_rows: a row is longer than '//itoa(len(mask_rows) - 1)//' cells (use mask_file)')
        if (nrows == size(mask_rows)) call fail(status, exit_bad_input, where// &
            '&patch mask_rows: more than '//itoa(size(mask_rows) - 1)//' rows (use mask_file)')
        if (.not. length_in_range(cfg%dx)) call fail(status, exit_bad_input, where// &
            '&patch dx = '//rtoa(cfg%dx)//' (an inline mask needs a cell size > 0, between 1e-30 and 1e30)')
        if (.not. length_in_range(cfg%dy)) call fail(status, exit_bad_input, where// &
            '&patch dy = '//rtoa(cfg%dy)//' (an inline mask needs a cell size > 0, between 1e-30 and 1e30)')
        if (cfg%mx /= 0 .and. cfg%mx /= len_trim(mask_rows(1))) call fail(status, exit_bad_input, where// &
            '&patch mx = '//itoa(cfg%mx)//' but mask row 1 has '//itoa(len_trim(mask_rows(1)))//' cells')
        if (cfg%my /= 0 .and. cfg%my /= nrows) call fail(status, exit_bad_input, where// &
            '&patch my = '//itoa(cfg%my)//' but mask_rows has '//itoa(nrows)//' rows')
      else
        if (cfg%dx < 0 .or. cfg%dy < 0) call fail(status, exit_bad_input, where// &
            '&patch dx, dy = '//rtoa(cfg%dx)//', '//rtoa(cfg%dy)//' (cell sizes must be > 0; the mask file header gives them)')
      end if
      if (.not. (offset_in_range(cfg%x0) .and. offset_in_range(cfg%y0))) &
        call fail(status, exit_bad_input, where//'&patch x0, y0 = '//rtoa(cfg%x0)//', '//rtoa(cfg%y0)// &
                  ' (allowed: 0 or 1e-30 <= |x0|, |y0| <= 1e30)')
    case ('contact')
      if (len(cfg%contact_file) == 0) call fail(status, exit_bad_input, where// &
          '&patch shape = ''contact'' needs contact_file (a CONTACT .out file)')
      if (cfg%contact_case < 1) call fail(status, exit_bad_input, where//'&patch contact_case = '// &
          itoa(cfg%contact_case)//' (must be >= 1)')
      if (len(cfg%mask_file) > 0 .or. nrows > 0 .or. cfg%mx /= 0 .or. cfg%my /= 0 .or. cfg%dx /= 0 .or. &
          cfg%dy /= 0 .or. cfg%x0_given .or. cfg%y0_given) call fail(status, exit_bad_input, where// &
          '&patch shape = ''contact'' takes its grid and mask from contact_file (leave out mask_file, '// &
          'mask_rows, mx, my, dx, dy, x0, y0)')
    case ('gap')
      if (len(cfg%mask_file) > 0 .or. nrows > 0 .or. len(cfg%contact_file) > 0) call fail(status, exit_bad_input, &
          where//'&patch shape = ''gap'' takes no mask_file, mask_rows or contact_file (the patch is the '// &
          'contact area the &normal group finds)')
    case default
      call fail(status, exit_bad_input, where//'&patch shape = '''//cfg%shape// &
                ''' (allowed: ''ellipse'', ''mask'', ''contact'', ''gap'')')
    end select

    if (.not. modulus_in_range(cfg%g)) call fail(status, exit_bad_input, where// &
        '&material g = '//rtoa(cfg%g)//' (must be > 0, between 1e-100 and 1e100)')
    if (.not. (cfg%nu >= 0 .and. cfg%nu <= 0.5_real64)) call fail(status, exit_bad_input, where// &
        '&material nu = '//rtoa(cfg%nu)//' (allowed: 0 <= nu <= 0.5)')

    select case (cfg%scheme%name)
    case ('collocation', 'backward')
    case default
      call fail(status, exit_bad_input, where//'&solver scheme = '''//cfg%scheme%name// &
                ''' (allowed: ''collocation'', ''backward'')')
    end select
    if (.not. (abs(cfg%scheme%alpha) < 1)) call fail(status, exit_bad_input, where// &
        '&solver alpha = '//rtoa(cfg%scheme%alpha)//' (allowed: -1 < alpha < 1, the open interval)')
    if (.not. (abs(cfg%scheme%spin_shift) <= 1)) call fail(status, exit_bad_input, where// &
        '&solver spin_shift = '//rtoa(cfg%scheme%spin_shift)//' (allowed: -1 <= spin_shift <= 1 cell)')
    if (.not. (cfg%target_error >= 0 .and. cfg%target_error < 1)) call fail(status, exit_bad_input, where// &
        '&solver target_error = '//rtoa(cfg%target_error)//' (allowed: 0 <= target_error < 1; 0: the grid as given)')
    if (.not. cell_budget_allowed(cfg%cell_budget)) call fail(status, exit_bad_input, &
        where//'&solver cell_budget = '//rtoa(cfg%cell_budget)//' '//cell_budget_range())
    if (cfg%extrapolate .and. (cfg%extrapolate_levels < 2 .or. cfg%extrapolate_levels > 3)) &
      call fail(status, exit_bad_input, where//'&solver extrapolate_levels = '//itoa(cfg%extrapolate_levels)// &
                ' (allowed: 2 or 3)')
    if (cfg%extrapolate .and. (cfg%refine_ratio < 2 .or. cfg%refine_ratio > 4)) &
      call fail(status, exit_bad_input, where//'&solver refine_ratio = '//itoa(cfg%refine_ratio)// &
                ' (allowed: 2, 3 or 4; every level multiplies the cells per direction by it)')
    if (findloc(refine_modes, cfg%refine, dim=1) == 0) &
      call fail(status, exit_bad_input, where//'&solver refine = '''//cfg%refine// &
                ''' (allowed: ''auto'', ''always'', ''never'', ''lapack'')')
    call parse_load_cases(load_cases, cfg%requested, where, status)
    select case (cfg%solve%method)
    case ('table')
      if (cfg%shape == 'ellipse' .and. .not. status%failed()) then
        if (.not. (cfg%semi_a / cfg%semi_b >= table_ratio_range(1) .and. &
                   cfg%semi_a / cfg%semi_b <= table_ratio_range(2))) call fail(status, exit_bad_input, where// &
            '&patch semi_a/semi_b = '//rtoa(cfg%semi_a / cfg%semi_b)//' (allowed with &solver method = '// &
            '''table'': 0.1 <= a/b <= 10, the refined table''s range; leave method out to solve this ellipse)')
      end if
    case ('dense', 'iterative', 'auto')
      call validate_solver_options(cfg%solve, where, status)
    case default
      call fail(status, exit_bad_input, where//'&solver method = '''//cfg%solve%method// &
                ''' (allowed: ''auto'', ''dense'', ''iterative'', ''table'' for ellipses)')
    end select
  end subroutine validate

  !> load_cases: words from xi, eta, phi separated by blanks or commas.
  subroutine parse_load_cases(text, requested, where, status)
    character(len=*), intent(in) :: text, where
    logical, intent(out) :: requested(n_load_cases)
    type(status_t), intent(inout) :: status
    character(len=len(text)) :: rest, word
    integer :: cut, k

    requested = .false.
    rest = lower(text)
    do
      rest = adjustl(rest)
      if (len_trim(rest) == 0) exit
      cut = scan(rest, ' ,')
      if (cut == 0) cut = len(rest) + 1
      word = rest(1:cut - 1)
      rest = rest(min(cut + 1, len(rest) + 1):)
      if (len_trim(word) == 0) cycle
      k = findloc(load_case_names, trim(word), dim=1)
      if (k == 0) then
        call fail(status, exit_bad_input, where//'&solver load_cases: unknown case '''//trim(word)// &
                  ''' (allowed: xi, eta, phi)')
        return
      end if
      requested(k) = .true.
    end do
    if (.not. any(requested)) call fail(status, exit_bad_input, where// &
        '&solver load_cases is empty (allowed: any of xi, eta, phi)')
  end subroutine parse_load_cases

  !> The patch the configuration describes.
  subroutine build_patch(cfg, patch, status)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(out) :: patch
    type(status_t), intent(inout) :: status
    logical, allocatable :: inside(:, :)
    character(len=:), allocatable :: where

    where = 'input '''//cfg%input_path//''': &patch mask_rows'
    select case (cfg%shape)
    case ('ellipse')
      call ellipse_patch(cfg%semi_a, cfg%semi_b, cfg%mx, cfg%my, patch, status)
    case ('mask')
      if (len(cfg%mask_file) > 0) then
        call read_mask_file(cfg%mask_file, patch, status)
        if (status%failed()) return
        if (cfg%mx /= 0 .and. cfg%mx /= patch%mx) call fail(status, exit_bad_input, 'input '''// &
            cfg%input_path//''': &patch mx = '//itoa(cfg%mx)//' but mask_file '''//cfg%mask_file// &
            ''' has mx = '//itoa(patch%mx))
        if (cfg%my /= 0 .and. cfg%my /= patch%my) call fail(status, exit_bad_input, 'input '''// &
            cfg%input_path//''': &patch my = '//itoa(cfg%my)//' but mask_file '''//cfg%mask_file// &
            ''' has my = '//itoa(patch%my))
        if ((cfg%dx /= 0 .and. cfg%dx /= patch%dx) .or. (cfg%dy /= 0 .and. cfg%dy /= patch%dy)) &
          call fail(status, exit_bad_input, 'input '''//cfg%input_path//''': &patch dx, dy = '// &
                    rtoa(cfg%dx)//', '//rtoa(cfg%dy)//' disagree with the header of mask_file '''// &
                    cfg%mask_file//''' ('//rtoa(patch%dx)//', '//rtoa(patch%dy)//'; leave them out)')
        if ((cfg%x0_given .and. cfg%x0 /= patch%x0) .or. (cfg%y0_given .and. cfg%y0 /= patch%y0)) &
          call fail(status, exit_bad_input, 'input '''//cfg%input_path//''': &patch x0, y0 = '// &
                    rtoa(cfg%x0)//', '//rtoa(cfg%y0)//' disagree with the header of mask_file '''// &
                    cfg%mask_file//''' ('//rtoa(patch%x0)//', '//rtoa(patch%y0)//'; leave them out)')
      else
        call parse_mask_rows(cfg%mask_rows, where, inside, status)
        if (status%failed()) return
        call mask_patch(inside, cfg%dx, cfg%dy, cfg%x0, cfg%y0, where, patch, status)
      end if
    case ('gap')
      ! found by the normal solve (kcreep_solve): nothing to build here
      patch%kind = 'gap'
    case ('contact')
      ! CONTACT's grid: corner (XL, YL), so the first cell centre is half a cell in
      call mask_patch(cfg%contact%inside, cfg%contact%dx, cfg%contact%dy, cfg%contact%xl + cfg%contact%dx / 2, &
                      cfg%contact%yl + cfg%contact%dy / 2, 'contact_file '''//cfg%contact_file//'''', patch, status)
      patch%kind = 'contact'
    end select
    if (status%failed()) return
    ! the same refusal as kcreep_check, naming the input
    if (cfg%scheme%name == 'collocation' .and. cfg%target_error > 0 .and. &
        .not. (cfg%refine_grid .and. patch%kind == 'ellipse')) then
      if (patch%dx > collocation_aspect_limit * patch%dy) call fail(status, exit_bad_input, 'input '''// &
          cfg%input_path//''': &solver scheme = ''collocation'' on cells long in x (dx/dy = '// &
          rtoa(patch%dx / patch%dy)//', allowed <= '//rtoa(collocation_aspect_limit)// &
          ' with target_error > 0): use near-square cells, scheme = ''backward'', or target_error = 0 '// &
          'to run this grid as given')
    end if
  end subroutine build_patch

  !> shape = 'contact': grid, mask and material of case contact_case of contact_file.
  !> A material in &material is refused rather than silently overridden: the
  !> comparison with CONTACT is only meaningful with CONTACT's own material.
  subroutine load_contact_case(cfg, material_given, status)
    type(config_t), intent(inout) :: cfg
    logical, intent(in) :: material_given
    type(status_t), intent(inout) :: status
    if (material_given) then
      call fail(status, exit_bad_input, 'input '''//cfg%input_path//''': &material g, nu are not allowed '// &
                'with &patch shape = ''contact'' (the material comes from contact_file''s GG and POISS)')
      return
    end if
    call read_contact_case(cfg%contact_file, cfg%contact_case, cfg%contact, status)
    if (status%failed()) return
    call combined_material(cfg%contact%gg, cfg%contact%poiss, cfg%g, cfg%nu)
  end subroutine load_contact_case

  !> The library's problem: the patch built from cfg and the namelist's
  !> material, scheme and solver settings.
  function problem_of(cfg, patch) result(problem)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(in) :: patch
    type(problem_t) :: problem
    problem%patch = patch
    problem%g = cfg%g
    problem%nu = cfg%nu
    problem%scheme = cfg%scheme
    problem%solve = cfg%solve
    problem%requested = cfg%requested
    problem%refine = cfg%refine
    problem%extrapolate = cfg%extrapolate
    problem%target_error = cfg%target_error
    problem%cell_budget = cfg%cell_budget
    problem%refine_grid = cfg%refine_grid .and. .not. cfg%extrapolate
    problem%extrapolate_levels = cfg%extrapolate_levels
    problem%refine_ratio = cfg%refine_ratio
    problem%tractions_wanted = len(cfg%traction_file) > 0
    select case (cfg%spin_centre)
    case ('centroid')
      problem%spin_centre = patch%centroid()
    case ('point')
      problem%spin_centre = cfg%spin_centre_xy
    case default
      problem%spin_centre = 0
    end select
    if (cfg%shape == 'gap') problem%normal = cfg%normal
  end function problem_of

  !> The &normal group: only with shape = 'gap', one gap source, one of
  !> approach and normal_force, the material either in &material or per body.
  subroutine validate_normal(cfg, normal_present, material_given, body, unset, status)
    type(config_t), intent(inout) :: cfg
    logical, intent(in) :: normal_present, material_given
    real(real64), intent(in) :: body(4)      !< e1, nu1, e2, nu2 as read
    real(real64), intent(in) :: unset
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: where
    integer :: sources

    where = 'input '''//cfg%input_path//''': '
    if (cfg%shape /= 'gap') then
      if (normal_present) call fail(status, exit_bad_input, where//'&normal is only read with &patch shape = '// &
                                    '''gap'' (shape = '''//cfg%shape//''')')
      if (len(cfg%pressure_file) > 0 .or. len(cfg%contact_mask_file) > 0) call fail(status, exit_bad_input, &
          where//'&output pressure_file and contact_mask_file need &patch shape = ''gap''')
      return
    end if
    sources = count([len(cfg%gap_file) > 0, len(cfg%contact_inp) > 0, cfg%poly%rx /= 0 .or. cfg%poly%ry /= 0])
    if (sources /= 1) then
      call fail(status, exit_bad_input, where//'&normal: give exactly one undeformed distance: gap_file, '// &
                'contact_inp, or the principal radii rx and ry (given: '//itoa(sources)//')')
      return
    end if
    if (len(cfg%contact_inp) > 0) then
      if (cfg%approach_given .or. cfg%force_given) call fail(status, exit_bad_input, where// &
          '&normal: approach and normal_force come from contact_inp (PEN or FN; leave them out)')
      if (material_given .or. body(1) /= unset) call fail(status, exit_bad_input, where// &
          '&material g, nu and &normal e1, nu1, e2, nu2 are not allowed with contact_inp (its GG and POISS are used)')
      if (cfg%contact_inp_case < 1) call fail(status, exit_bad_input, where//'&normal contact_inp_case = '// &
          itoa(cfg%contact_inp_case)//' (must be >= 1)')
      return
    end if
    if (cfg%approach_given .eqv. cfg%force_given) then
      call fail(status, exit_bad_input, where//'&normal: give exactly one of approach and normal_force')
    else if (cfg%force_given .and. .not. (cfg%normal_force > 0 .and. cfg%normal_force < 1e300_real64)) then
      call fail(status, exit_bad_input, where//'&normal normal_force = '//rtoa(cfg%normal_force)// &
                ' (must be > 0)')
    else if (cfg%approach_given .and. .not. (abs(cfg%approach) < 1e30_real64)) then
      call fail(status, exit_bad_input, where//'&normal approach = '//rtoa(cfg%approach)//' (|approach| < 1e30)')
    end if
    if (len(cfg%gap_file) == 0) then
      if (.not. (cfg%poly%rx > 0 .and. cfg%poly%ry > 0 .and. cfg%poly%rx < 1e30_real64 .and. &
                 cfg%poly%ry < 1e30_real64)) call fail(status, exit_bad_input, where//'&normal rx, ry = '// &
          rtoa(cfg%poly%rx)//', '//rtoa(cfg%poly%ry)//' (principal relative radii: both > 0 and < 1e30)')
      if (any(abs([cfg%poly%lx, cfg%poly%ly, cfg%poly%cx, cfg%poly%cy]) >= 1e30_real64)) &
        call fail(status, exit_bad_input, where//'&normal lx, ly, cx, cy: each |value| < 1e30')
    else if (cfg%mx /= 0 .or. cfg%my /= 0 .or. cfg%dx /= 0 .or. cfg%dy /= 0 .or. cfg%x0 /= 0 .or. cfg%y0 /= 0) then
      call fail(status, exit_bad_input, where//'&patch mx, my, dx, dy, x0, y0: the grid comes from gap_file''s '// &
                'header (leave them out)')
    end if
    if (cfg%cells_across < 2 .or. cfg%cells_across > 2000) call fail(status, exit_bad_input, where// &
        '&normal cells_across = '//itoa(cfg%cells_across)//' (allowed: 2 to 2000)')
    if (.not. (cfg%margin >= 0 .and. cfg%margin <= 10)) call fail(status, exit_bad_input, where// &
        '&normal margin = '//rtoa(cfg%margin)//' (allowed: 0 to 10, a fraction of the interpenetration size)')
    if (.not. (cfg%normal%options%tolerance > 0 .and. cfg%normal%options%tolerance < 1)) &
      call fail(status, exit_bad_input, where//'&normal normal_tolerance = '//rtoa(cfg%normal%options%tolerance)// &
                ' (allowed: 0 < tolerance < 1)')
    if (cfg%normal%options%max_iterations < 1) call fail(status, exit_bad_input, where// &
        '&normal normal_max_iterations = '//itoa(cfg%normal%options%max_iterations)//' (must be >= 1)')
    if (any(body /= unset)) then
      if (material_given) then
        call fail(status, exit_bad_input, where//'give the material either in &material (g, nu) or per body '// &
                  'in &normal (e1, nu1, e2, nu2), not both')
      else if (any(body == unset)) then
        call fail(status, exit_bad_input, where//'&normal e1, nu1, e2, nu2: give all four')
      else if (.not. (body(1) > 0 .and. body(3) > 0 .and. body(1) < 1e100_real64 .and. body(3) < 1e100_real64)) then
        call fail(status, exit_bad_input, where//'&normal e1, e2 = '//rtoa(body(1))//', '//rtoa(body(3))// &
                  ' (Young''s moduli: > 0)')
      else if (.not. (body(2) >= 0 .and. body(2) <= 0.5_real64 .and. body(4) >= 0 .and. body(4) <= 0.5_real64)) then
        call fail(status, exit_bad_input, where//'&normal nu1, nu2 = '//rtoa(body(2))//', '//rtoa(body(4))// &
                  ' (allowed: 0 to 0.5)')
      else
        cfg%e = [body(1), body(3)]
        cfg%poisson = [body(2), body(4)]
        call combined_g_nu_from_e_nu(body(1), body(2), body(3), body(4), cfg%g, cfg%nu)
      end if
    end if
  end subroutine validate_normal

  !> shape = 'gap': the undeformed distance on its grid (gap_file, contact_inp,
  !> or the polynomial on the &patch grid or on an automatic one), the load and
  !> the combined compliance, into cfg%normal.
  subroutine load_gap(cfg, status)
    type(config_t), intent(inout) :: cfg
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: where
    type(contact_input_t) :: inp
    type(hertz_t) :: hz
    real(real64) :: level, extent, dx, dy, x0, y0, compliance
    integer :: mx, my

    where = 'input '''//cfg%input_path//''': '
    associate (np => cfg%normal)
      np%active = .true.
      if (len(cfg%contact_inp) > 0) then
        call read_contact_input(cfg%contact_inp, cfg%contact_inp_case, inp, status)
        if (status%failed()) return
        np%gap = inp%gap
        call combined_material(inp%gg, inp%poiss, cfg%g, cfg%nu)
        cfg%force_given = inp%norm == 1
        cfg%approach_given = .not. cfg%force_given
        cfg%approach = inp%pen
        cfg%normal_force = inp%fn
      else if (len(cfg%gap_file) > 0) then
        call read_gap_file(cfg%gap_file, np%gap, status)
        if (status%failed()) return
      end if
      if (cfg%e(1) > 0) then
        compliance = compliance_from_e_nu(cfg%e(1), cfg%poisson(1), cfg%e(2), cfg%poisson(2))
      else
        compliance = compliance_from_g_nu(cfg%g, cfg%nu)
      end if
      np%compliance = compliance
      if (len(cfg%contact_inp) == 0 .and. len(cfg%gap_file) == 0) then
        if (cfg%mx > 0 .and. cfg%my > 0 .and. cfg%dx > 0 .and. cfg%dy > 0) then
          mx = cfg%mx
          my = cfg%my
          dx = cfg%dx
          dy = cfg%dy
          x0 = cfg%x0
          y0 = cfg%y0
        else if (cfg%mx /= 0 .or. cfg%my /= 0 .or. cfg%dx /= 0 .or. cfg%dy /= 0) then
          call fail(status, exit_bad_input, where//'&patch mx, my, dx, dy: give all four (a grid for the gap) '// &
                    'or none (an automatic grid from &normal cells_across and margin)')
          return
        else
          ! the interpenetration area at the approach (or at Hertz's approach for the force)
          if (cfg%force_given) then
            hz = hertz_from_force(1 / (2 * cfg%poly%rx), 1 / (2 * cfg%poly%ry), compliance, cfg%normal_force)
            level = hz%approach
          else
            level = cfg%approach
          end if
          extent = 4 * sqrt(2 * max(cfg%poly%rx, cfg%poly%ry) * max(abs(level), tiny(level))) + &
                   2 * (abs(cfg%poly%lx) * cfg%poly%rx + abs(cfg%poly%ly) * cfg%poly%ry)
          call auto_grid(cfg%poly, level, extent, cfg%cells_across, cfg%margin, mx, my, dx, dy, x0, y0, status)
          if (status%failed()) then
            if (cfg%force_given) then
              status%message = where//'&normal: '//status%message
            else
              status%message = where//'&normal approach = '//rtoa(cfg%approach)//': the surfaces do not '// &
                               'interpenetrate (the undeformed distance from rx, ry, lx, ly, cx, cy is larger everywhere)'
            end if
            return
          end if
        end if
        call check_grid_size(mx, my, where//'&normal: the gap grid: ', status)
        if (status%failed()) return
        call gap_from_polynomial(cfg%poly, mx, my, dx, dy, x0, y0, np%gap, status)
        if (status%failed()) return
        np%poly_given = .true.
        np%poly = cfg%poly
      end if
      call check_grid_size(np%gap%mx, np%gap%my, where//'&normal: the gap grid: ', status)
      if (status%failed()) return
      np%force_given = cfg%force_given
      np%approach = cfg%approach
      np%normal_force = cfg%normal_force
      if (.not. np%force_given .and. .not. any(np%gap%h < np%approach)) then
        call fail(status, exit_bad_input, where//'&normal approach = '//rtoa(np%approach)// &
                  ': the surfaces do not interpenetrate (the smallest undeformed distance is '// &
                  rtoa(minval(np%gap%h))//'; the approach must exceed it)')
        return
      end if
      if (np%force_given .and. .not. (np%normal_force > 0)) then
        call fail(status, exit_bad_input, where//'normal force = '//rtoa(np%normal_force)//' (must be > 0)')
        return
      end if
    end associate
  end subroutine load_gap

  !> '<input name without folder and extension><extension>' in the working folder.
  pure function default_output_name(path, extension) result(name)
    character(len=*), intent(in) :: path, extension
    character(len=:), allocatable :: name
    integer :: slash, dot
    slash = index(path, '/', back=.true.)
    name = path(slash + 1:)
    dot = index(name, '.', back=.true.)
    if (dot > 1) name = name(1:dot - 1)
    name = name//extension
  end function default_output_name

end module kcreep_namelist
