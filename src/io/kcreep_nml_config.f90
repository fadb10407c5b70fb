!> What a namelist file asks for, once read and checked: the configuration
!> the group modules (kcreep_nml_patch, _material, _solver, _output, _normal,
!> _fastsim, _wheel_rail) fill in and kcreep_namelist turns into the library's problem.
module kcreep_nml_config
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, lower
  use kcreep, only: rolling_request_t, &
                    scheme_t, n_load_cases, solver_options_t, creep_request_t, normal_problem_t, polynomial_gap_t, &
                    wheel_rail_setup_t
  use kcreep_contact_reader, only: contact_case_t
  implicit none
  private
  public :: config_t, rolling_config_t, input_where, default_output_name, creepage_points, pressure_source, &
            check_pressure_use

  integer, parameter, public :: max_inline_rows = 2048, max_row_length = 2048
  integer, parameter, public :: max_creepages = 100000   !< creepage points of &fastsim (list and sweep together)
  integer, parameter, public :: max_rolling_points = 100000   !< &rolling's points (list and sweep together)
  !> "not given": a value the user wrote is either used or refused, never
  !> replaced, and some defaults depend on other groups
  real(real64), parameter, public :: unset = -huge(1.0_real64)
  integer, parameter, public :: unset_int = -huge(1)

  !> &rolling (kcreep_nml_rolling): exact steady rolling with friction
  type :: rolling_config_t
    logical :: on = .false.                        !< the group was given
    type(rolling_request_t) :: request
    character(len=:), allocatable :: pressure      !< 'hertz', 'contact', 'normal', 'file', 'parabolic'
    character(len=:), allocatable :: pressure_input_file
    real(real64) :: fn = 1                         !< load of the 'hertz' and 'parabolic' pressures
    character(len=:), allocatable :: rolling_file, rolling_map_file   !< &output
  end type rolling_config_t

  type :: config_t
    character(len=:), allocatable :: input_path
    ! &patch
    character(len=:), allocatable :: shape
    real(real64) :: semi_a = 1, semi_b = 1
    integer :: mx = 0, my = 0                   !< 0: not given (an ellipse: its default)
    logical :: mx_my_given = .false.            !< mx or my written in the namelist
    character(len=:), allocatable :: mask_file
    character(len=max_row_length), allocatable :: mask_rows(:)   !< inline rows given
    real(real64) :: dx = 0, dy = 0, x0 = 0, y0 = 0
    logical :: x0_given = .false., y0_given = .false.   !< x0, y0 written in the namelist
    character(len=:), allocatable :: contact_file   !< shape 'contact': CONTACT .out file
    integer :: contact_case = 0
    type(contact_case_t) :: contact                 !< what was read from it
    ! &material
    real(real64) :: g = 1, nu = 0.25_real64
    logical :: material_given = .false.         !< g or nu written in &material
    ! &solver
    type(scheme_t) :: scheme
    logical :: requested(n_load_cases) = .true.
    logical :: extrapolate = .false.            !< Richardson in the mesh size (mesh_extrapolation)
    real(real64) :: target_error = 0            !< &solver target_error (kcreep_refine_estimate)
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
    type(rolling_config_t) :: rolling               !< &rolling; rolling%on: given
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
    integer :: cells_across = 60
    real(real64) :: margin = 0.2_real64
    real(real64) :: e(2) = 0, poisson(2) = 0    !< per body, when given (e(1) > 0)
    type(normal_problem_t) :: normal            !< built by read_config
    ! &wheel_rail (group absent: wheel_rail_on false): a contact table over lateral shifts
    logical :: wheel_rail_on = .false.
    type(wheel_rail_setup_t) :: wheel_rail
    character(len=:), allocatable :: wheel_rail_file   !< &output wheel_rail_file [<input name>.wr]
    character(len=:), allocatable :: wheelset_file     !< &output wheelset_file [<input name>.ws]
  end type config_t

contains

  !> The start of every message about the input: "input 'path': ".
  pure function input_where(cfg) result(where)
    type(config_t), intent(in) :: cfg
    character(len=:), allocatable :: where
    where = 'input '''//cfg%input_path//''': '
  end function input_where

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

  !> The creepage points of &fastsim and &rolling: the list `values` (xi,
  !> eta, phi triples, unset after the last one given) then the sweep
  !> (sweep_points values of sweep_from to sweep_to, 'linear' or 'log',
  !> along sweep_direction); checked against their ranges, errors prefixed
  !> with where.
  subroutine creepage_points(values, sweep_direction, sweep_from, sweep_to, sweep_points, sweep_spacing, &
                             max_points, where, points, status)
    real(real64), intent(in) :: values(:), sweep_direction(3), sweep_from, sweep_to
    integer, intent(in) :: sweep_points, max_points
    character(len=*), intent(in) :: sweep_spacing, where
    real(real64), allocatable, intent(out) :: points(:, :)
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: spacing
    integer :: n_values, n_list, k
    real(real64) :: t
    ! the list: numbers up to the last one given, three per point
    n_values = size(values)
    do while (n_values > 0)
      if (values(n_values) /= unset) exit
      n_values = n_values - 1
    end do
    if (mod(n_values, 3) /= 0) then
      call fail(status, exit_bad_input, where//'creepages: '//itoa(n_values)//' numbers given (allowed: '// &
                '(xi, eta, phi) triples, a multiple of 3)')
      return
    end if
    if (any(values(1:n_values) == unset) .or. .not. all(abs(values(1:n_values)) <= 1e6_real64)) then
      call fail(status, exit_bad_input, where//'creepages: a value is missing or not finite (allowed: '// &
                'finite numbers, |value| <= 1e6)')
      return
    end if
    n_list = n_values / 3
    spacing = lower(trim(adjustl(sweep_spacing)))
    if (sweep_points /= 0) then
      if (sweep_points < 2 .or. sweep_points > max_points - n_list) then
        call fail(status, exit_bad_input, where//'sweep_points = '//itoa(sweep_points)//' (allowed: 0 for '// &
                  'no sweep, or 2 to '//itoa(max_points - n_list)//')')
        return
      end if
      if (.not. any(sweep_direction /= 0) .or. .not. all(abs(sweep_direction) <= 1e6_real64)) then
        call fail(status, exit_bad_input, where//'sweep_direction = '//rtoa(sweep_direction(1))//', '// &
                  rtoa(sweep_direction(2))//', '//rtoa(sweep_direction(3))//' (a finite (xi, eta, phi), not all 0)')
        return
      end if
      select case (spacing)
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
    allocate (points(3, n_list + sweep_points))
    points(:, 1:n_list) = reshape(values(1:n_values), [3, n_list])
    do k = 1, sweep_points
      t = real(k - 1, real64) / (sweep_points - 1)
      if (spacing == 'log') then
        t = sweep_from * (sweep_to / sweep_from)**t
      else
        t = sweep_from + (sweep_to - sweep_from) * t
      end if
      points(:, n_list + k) = t * sweep_direction
    end do
  end subroutine creepage_points

  !> The pressure &fastsim or &rolling runs on: `given` ('auto', 'hertz',
  !> 'contact', 'normal', 'file', 'parabolic'; any case) resolved for the
  !> patch's shape and checked against it. With &wheel_rail every patch is a
  !> normal problem: only 'auto' or 'normal', and no maps (`table`: the
  !> table that has each patch's forces, for the message).
  subroutine pressure_source(given, shape, wheel_rail, maps, table, pressure_input_file, where, pressure, status)
    character(len=*), intent(in) :: given, shape, table, pressure_input_file, where
    logical, intent(in) :: wheel_rail, maps
    character(len=:), allocatable, intent(out) :: pressure
    type(status_t), intent(inout) :: status
    pressure = lower(trim(adjustl(given)))
    if (wheel_rail) then
      ! each patch of &wheel_rail is a normal problem: its pressure, its own geometric spin
      if (pressure /= 'auto' .and. pressure /= 'normal') call fail(status, exit_bad_input, where// &
          'pressure = '''//trim(adjustl(given))//''' with &wheel_rail (allowed: ''auto'' or ''normal'', each '// &
          'patch''s normal pressure)')
      if (maps) call fail(status, exit_bad_input, where//'maps with &wheel_rail: not available (the '//table// &
          ' table has each patch''s forces)')
      if (status%failed()) return
      pressure = 'normal'
    end if
    if (pressure == 'auto') then
      select case (shape)
      case ('ellipse')
        pressure = 'hertz'
      case ('contact')
        pressure = 'contact'
      case ('gap')
        pressure = 'normal'
      case default
        pressure = trim(merge('file     ', 'parabolic', len(pressure_input_file) > 0))
      end select
    end if
    select case (pressure)
    case ('hertz')
      if (shape /= 'ellipse') call fail(status, exit_bad_input, where//'pressure = ''hertz'' needs '// &
          '&patch shape = ''ellipse'' (for other patches: ''file'', ''contact'' or ''parabolic'')')
    case ('contact')
      if (shape /= 'contact') call fail(status, exit_bad_input, where//'pressure = ''contact'' needs '// &
          '&patch shape = ''contact''')
    case ('normal')
      if (shape /= 'gap' .and. .not. wheel_rail) call fail(status, exit_bad_input, where// &
          'pressure = ''normal'' needs &patch shape = ''gap'' (the normal problem gives the pressure)')
    case ('file')
      if (len(pressure_input_file) == 0) call fail(status, exit_bad_input, where//'pressure = ''file'' '// &
          'needs pressure_input_file (the pressure per cell on the patch''s grid)')
    case ('parabolic')
    case default
      call fail(status, exit_bad_input, where//'pressure = '''//pressure//''' (allowed: ''auto'', '// &
                '''hertz'', ''contact'', ''normal'', ''file'', ''parabolic'')')
    end select
    if (status%failed()) return
    if (len(pressure_input_file) > 0 .and. pressure /= 'file') call fail(status, exit_bad_input, where// &
        'pressure_input_file is read with pressure = ''file'' only (pressure = '''//pressure//''')')
  end subroutine pressure_source

  !> What the resolved pressure allows (&fastsim and &rolling alike): fn (unset:
  !> not given) only scales the model pressures 'hertz' and 'parabolic', within
  !> 0 < fn <= 1e30; a pressure on the patch's own grid ('file', 'contact') is
  !> not for extrapolation (`solver`, named in the message, runs on the finest level).
  subroutine check_pressure_use(pressure, fn, extrapolate, solver, where, status)
    character(len=*), intent(in) :: pressure, solver, where
    real(real64), intent(in) :: fn
    logical, intent(in) :: extrapolate
    type(status_t), intent(inout) :: status
    if (fn /= unset) then
      if (pressure /= 'hertz' .and. pressure /= 'parabolic') then  ! contact, normal, file: their own load
        call fail(status, exit_bad_input, where//'fn applies to pressure = ''hertz'' or ''parabolic'' only '// &
                  '(the pressure '''//pressure//''' carries its own load)')
        return
      end if
      if (.not. (fn > 0 .and. fn <= 1e30_real64)) then
        call fail(status, exit_bad_input, where//'fn = '//rtoa(fn)//' (allowed: 0 < fn <= 1e30)')
        return
      end if
    end if
    if (extrapolate .and. (pressure == 'file' .or. pressure == 'contact')) &
      call fail(status, exit_bad_input, where//'pressure = '''//pressure//''' is given on the patch''s '// &
                'own grid: not with &solver extrapolate = .true. ('//solver//' runs on the finest level)')
  end subroutine check_pressure_use

end module kcreep_nml_config
