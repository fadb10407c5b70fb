!> What a namelist file asks for, once read and checked: the configuration
!> the group modules (kcreep_nml_patch, _material, _solver, _output, _normal,
!> _fastsim, _wheel_rail) fill in and kcreep_namelist turns into the library's problem.
module kcreep_nml_config
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep, only: rolling_request_t, &
                    scheme_t, n_load_cases, solver_options_t, creep_request_t, normal_problem_t, polynomial_gap_t, &
                    wheel_rail_setup_t
  use kcreep_contact_reader, only: contact_case_t
  implicit none
  private
  public :: config_t, rolling_config_t, input_where, default_output_name

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

end module kcreep_nml_config
