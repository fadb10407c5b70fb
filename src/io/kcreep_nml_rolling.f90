!> The &rolling group: exact steady rolling with Coulomb friction
!> (kcreep_rolling_curve). It reads and validates its group in one call;
!> kcreep_namelist calls read_rolling_group when the group is present.
!>
!>   &rolling
!>     mu = 0.3                                  ! required, 0 < mu <= 1000
!>     creepages = 1e-3 0 0,  0 1e-3 0           ! (xi, eta, phi) triples
!>     sweep_direction = 1 0 0, sweep_from = 1e-5, sweep_to = 1e-2, sweep_points = 50,
!>     sweep_spacing = 'linear'                  ! or 'log'
!>     pressure = 'auto', pressure_input_file = '', fn = 1    ! as &fastsim
!>     maps = .false.                            ! traction and stick/slip map of every point
!>     tolerance = 1e-7                          ! Newton stops at max|F| <= tolerance * max(mu pn)
!>   /
module kcreep_nml_rolling
  use, intrinsic :: iso_fortran_env, only: real64, iostat_end
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, lower, resolve_path, folder_of
  use kcreep, only: default_rolling_tolerance
  use kcreep_namelist_scan, only: diagnose_group
  use kcreep_nml_config, only: rolling_config_t, max_rolling_points, creepage_points, pressure_source, &
                               check_pressure_use, unset
  implicit none
  private
  public :: rolling_variables, read_rolling_group

  !> The group's variables and their types, as in its namelist statement
  !> (kcreep_namelist_scan diagnose_group explains a failed read with them).
  character(len=*), parameter :: rolling_variables(12) = [character(len=29) :: &
    'mu real', 'creepages real list', 'sweep_direction real 3', 'sweep_from real', 'sweep_to real', &
    'sweep_points integer', 'sweep_spacing character', 'pressure character', &
    'pressure_input_file character', 'fn real', 'maps logical', 'tolerance real']

contains

  !> Read &rolling from unit (rewound here; text: the whole file, to explain a
  !> failed read) and validate it for a patch of the given shape. given: the group is in the file; closed_open: its /
  !> was read and only the last newline is missing (a complete group);
  !> wheel_rail: with &wheel_rail, each patch's normal pressure (no maps).
  subroutine read_rolling_group(unit, path, text, given, closed_open, shape, extrapolate, wheel_rail, config, status)
    integer, intent(in) :: unit
    character(len=*), intent(in) :: path, text, shape
    logical, intent(in) :: given, closed_open, extrapolate, wheel_rail
    type(rolling_config_t), intent(out) :: config
    type(status_t), intent(inout) :: status
    real(real64) :: mu, fn, sweep_direction(3), sweep_from, sweep_to, tolerance
    real(real64), allocatable :: creepages(:)
    integer :: sweep_points, ios
    character(len=16) :: sweep_spacing, pressure
    character(len=4096) :: pressure_input_file
    character(len=512) :: msg
    character(len=:), allocatable :: where, why
    logical :: maps
    namelist /rolling/ mu, creepages, sweep_direction, sweep_from, sweep_to, sweep_points, sweep_spacing, &
                       pressure, pressure_input_file, fn, maps, tolerance

    config%on = given
    if (.not. given .or. status%failed()) return
    mu = unset
    allocate (creepages(3 * max_rolling_points))   ! more values: the read fails, diagnose_group counts them
    creepages = unset
    sweep_direction = 0
    sweep_from = 0
    sweep_to = 0
    sweep_points = 0
    sweep_spacing = 'linear'
    pressure = 'auto'
    pressure_input_file = ''
    fn = unset
    maps = .false.
    tolerance = default_rolling_tolerance
    where = 'input '''//path//''': &rolling '
    rewind (unit)
    read (unit, nml=rolling, iostat=ios, iomsg=msg)
    if (ios == iostat_end .and. closed_open) ios = 0
    if (ios == iostat_end) then
      call fail(status, exit_bad_input, 'input '''//path//''': namelist &rolling: end of file before the closing /')
    else if (ios /= 0) then
      ! the compiler's words ("Bad data for namelist object") in the input's
      why = diagnose_group(text, 'rolling', rolling_variables, 3 * max_rolling_points)
      if (len(why) == 0) why = '&rolling: '//trim(msg)
      call fail(status, exit_bad_input, 'input '''//path//''': namelist '//why)
    end if
    if (status%failed()) return

    if (mu == unset) then
      call fail(status, exit_bad_input, where//'mu is required (the friction coefficient, > 0)')
      return
    end if
    if (.not. (mu > 0 .and. mu <= 1e3_real64)) then
      call fail(status, exit_bad_input, where//'mu = '//rtoa(mu)//' (allowed: 0 < mu <= 1000)')
      return
    end if
    config%request%mu = mu
    if (.not. (tolerance >= 1e-14_real64 .and. tolerance <= 1e-2_real64)) then
      call fail(status, exit_bad_input, where//'tolerance = '//rtoa(tolerance)//' (allowed: 1e-14 to 1e-2; '// &
                'Newton stops at max|F| <= tolerance * max(mu pn))')
      return
    end if
    config%request%tolerance = tolerance
    call creepage_points(creepages, sweep_direction, sweep_from, sweep_to, sweep_points, sweep_spacing, &
                         max_rolling_points, where, config%request%creepages, status)
    if (status%failed()) return
    config%request%maps = maps

    ! the pressure: &fastsim's sources and meanings
    config%pressure_input_file = resolve_path(trim(pressure_input_file), folder_of(path))
    call pressure_source(pressure, shape, wheel_rail, maps, 'rolling', config%pressure_input_file, where, &
                         config%pressure, status)
    if (status%failed()) return
    call check_pressure_use(config%pressure, fn, extrapolate, 'the rolling problem', where, status)
    if (status%failed()) return
    if (fn /= unset) config%fn = fn
  end subroutine read_rolling_group

end module kcreep_nml_rolling
