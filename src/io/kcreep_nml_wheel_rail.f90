!> The &wheel_rail group: wheel and rail profiles, track and wheelset
!> placement, lateral shifts, yaw and load (docs/wheel_rail.md).
!>
!>   &wheel_rail wheel_file = 'S1002.prw', rail_file = 'UIC60.prr',
!>               shift_from = -6, shift_to = 10, shift_step = 1, vertical_force = 80000 /
!>
!> Names and defaults are CONTACT's module-1 quantities: gauge_width [1435]
!> measured gauge_height [14] below the track plane, rail_cant [0 rad, added to
!> the rail file's], flange_back_distance [1360], flange_back_position [-70, in
!> the wheel profile's coordinates], nominal_radius [460, at the wheel profile's
!> origin]. The group's own checks (a list of shifts or from/to/step, one load)
!> are here, the ranges in the library's check_wheel_rail_setup (shared with
!> the C API); the profile files are read here (kcreep_profile_file), relative
!> to the namelist's folder.
module kcreep_nml_wheel_rail
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, lower, resolve_path, folder_of
  use kcreep, only: wheel_rail_setup_t, check_wheel_rail_setup, max_wheel_rail_shifts
  use kcreep_profile_file, only: read_profile_file
  use kcreep_nml_config, only: config_t, input_where, unset
  implicit none
  private
  public :: wheel_rail_variables, wheel_rail_group_t, read_wheel_rail_group, apply_wheel_rail_group

  !> The group as written (unset: not given).
  type :: wheel_rail_group_t
    character(len=1024) :: wheel_file = '', rail_file = '', left_wheel_file = '', left_rail_file = ''
    character(len=16) :: side = 'right'
    logical :: wheel_mirror = .false., rail_mirror = .false., wheelset = .false.
    real(real64) :: smoothing = -1, gauge_width = 1435, gauge_height = 14, rail_cant = 0, &
                    flange_back_distance = 1360, flange_back_position = -70, nominal_radius = 460, &
                    shift_from = unset, shift_to = unset, shift_step = unset, yaw = 0, &
                    vertical_force = unset, approach = unset, min_patch_share = 0
    real(real64), allocatable :: shifts(:)
  end type wheel_rail_group_t

  !> The group's variables and their types, as in its namelist statement
  !> (kcreep_namelist_scan diagnose_group explains a failed read with them).
  character(len=*), parameter :: wheel_rail_variables(23) = [character(len=30) :: &
    'wheel_file character', 'rail_file character', 'wheel_mirror logical', 'rail_mirror logical', &
    'wheelset logical', 'left_wheel_file character', 'left_rail_file character', &
    'smoothing real', 'side character', 'gauge_width real', 'gauge_height real', 'rail_cant real', &
    'flange_back_distance real', 'flange_back_position real', 'nominal_radius real', 'shifts real list', &
    'shift_from real', 'shift_to real', 'shift_step real', 'yaw real', 'vertical_force real', 'approach real', &
    'min_patch_share real']

contains

  subroutine read_wheel_rail_group(unit, grp, ios, msg)
    integer, intent(in) :: unit
    type(wheel_rail_group_t), intent(out) :: grp
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    character(len=1024) :: wheel_file, rail_file, left_wheel_file, left_rail_file
    character(len=16) :: side
    logical :: wheel_mirror, rail_mirror, wheelset
    real(real64) :: smoothing, gauge_width, gauge_height, rail_cant, flange_back_distance, flange_back_position, &
                    nominal_radius, shift_from, shift_to, shift_step, yaw, vertical_force, approach, min_patch_share
    real(real64), allocatable :: shifts(:)
    namelist /wheel_rail/ wheel_file, rail_file, wheel_mirror, rail_mirror, smoothing, side, gauge_width, &
                          gauge_height, rail_cant, flange_back_distance, flange_back_position, nominal_radius, &
                          shifts, shift_from, shift_to, shift_step, yaw, vertical_force, approach, &
                          wheelset, left_wheel_file, left_rail_file, min_patch_share

    allocate (shifts(max_wheel_rail_shifts))   ! more values: the read fails, diagnose_group counts them
    shifts = unset
    wheel_file = grp%wheel_file
    rail_file = grp%rail_file
    side = grp%side
    wheel_mirror = grp%wheel_mirror
    rail_mirror = grp%rail_mirror
    smoothing = grp%smoothing
    gauge_width = grp%gauge_width
    gauge_height = grp%gauge_height
    rail_cant = grp%rail_cant
    flange_back_distance = grp%flange_back_distance
    flange_back_position = grp%flange_back_position
    nominal_radius = grp%nominal_radius
    shift_from = grp%shift_from
    shift_to = grp%shift_to
    shift_step = grp%shift_step
    yaw = grp%yaw
    vertical_force = grp%vertical_force
    approach = grp%approach
    wheelset = grp%wheelset
    left_wheel_file = grp%left_wheel_file
    left_rail_file = grp%left_rail_file
    min_patch_share = grp%min_patch_share
    read (unit, nml=wheel_rail, iostat=ios, iomsg=msg)
    grp%wheel_file = wheel_file
    grp%rail_file = rail_file
    grp%side = side
    grp%wheel_mirror = wheel_mirror
    grp%rail_mirror = rail_mirror
    grp%smoothing = smoothing
    grp%gauge_width = gauge_width
    grp%gauge_height = gauge_height
    grp%rail_cant = rail_cant
    grp%flange_back_distance = flange_back_distance
    grp%flange_back_position = flange_back_position
    grp%nominal_radius = nominal_radius
    grp%shift_from = shift_from
    grp%shift_to = shift_to
    grp%shift_step = shift_step
    grp%yaw = yaw
    grp%vertical_force = vertical_force
    grp%approach = approach
    grp%wheelset = wheelset
    grp%left_wheel_file = left_wheel_file
    grp%left_rail_file = left_rail_file
    grp%min_patch_share = min_patch_share
    call move_alloc(shifts, grp%shifts)
  end subroutine read_wheel_rail_group

  !> Store &wheel_rail in cfg%wheel_rail, check it and read its two profile
  !> files. Without the group nothing of it runs.
  subroutine apply_wheel_rail_group(grp, present, cfg, status)
    type(wheel_rail_group_t), intent(in) :: grp
    logical, intent(in) :: present
    type(config_t), intent(inout) :: cfg
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: where, wheel_path, rail_path
    integer :: n, k

    cfg%wheel_rail_on = present
    if (.not. present) return
    where = input_where(cfg)//'&wheel_rail '
    associate (setup => cfg%wheel_rail)
      if (len_trim(grp%wheel_file) == 0 .or. len_trim(grp%rail_file) == 0) then
        call fail(status, exit_bad_input, where//'needs wheel_file and rail_file (SIMPACK .prw/.prr, MiniProf '// &
                  '.whl/.ban, or two columns y z in mm)')
        return
      end if
      ! the shifts: a list, or from / to / step
      n = 0
      if (allocated(grp%shifts)) n = count(grp%shifts /= unset)
      if (n > 0) then
        if (any(grp%shifts(1:n) == unset)) then
          call fail(status, exit_bad_input, where//'shifts: a value is missing in the list')
          return
        end if
      end if
      if (n > 0 .and. any([grp%shift_from, grp%shift_to, grp%shift_step] /= unset)) then
        call fail(status, exit_bad_input, where//'give shifts (a list) or shift_from, shift_to, shift_step, not both')
        return
      end if
      if (n > 0) then
        setup%shifts = grp%shifts(1:n)
      else if (all([grp%shift_from, grp%shift_to, grp%shift_step] /= unset)) then
        if (.not. (grp%shift_step > 0 .and. abs(grp%shift_from) <= 200 .and. abs(grp%shift_to) <= 200 .and. &
                   grp%shift_to >= grp%shift_from)) then
          call fail(status, exit_bad_input, where//'shift_from, shift_to, shift_step = '//rtoa(grp%shift_from)// &
                    ', '//rtoa(grp%shift_to)//', '//rtoa(grp%shift_step)// &
                    ' (allowed: -200 <= from <= to <= 200 mm, step > 0)')
          return
        end if
        n = floor((grp%shift_to - grp%shift_from) / grp%shift_step + 1e-9_real64) + 1
        if (n > max_wheel_rail_shifts) then
          call fail(status, exit_bad_input, where//'shift_from to shift_to by shift_step: '//itoa(n)// &
                    ' shifts (at most '//itoa(max_wheel_rail_shifts)//')')
          return
        end if
        setup%shifts = [(grp%shift_from + (k - 1) * grp%shift_step, k=1, n)]
      else
        call fail(status, exit_bad_input, where//'needs the wheelset''s lateral shifts: shifts = a list (mm), or '// &
                  'all three of shift_from, shift_to, shift_step')
        return
      end if
      ! the load: exactly one
      if ((grp%vertical_force == unset) .eqv. (grp%approach == unset)) then
        call fail(status, exit_bad_input, where//'give exactly one of vertical_force (N) and approach (mm)')
        return
      end if
      setup%force_given = grp%vertical_force /= unset
      if (setup%force_given) then
        setup%vertical_force = grp%vertical_force
      else
        setup%approach = grp%approach
      end if
      setup%side = lower(trim(adjustl(grp%side)))
      setup%wheel_mirror = grp%wheel_mirror
      setup%rail_mirror = grp%rail_mirror
      setup%smoothing = grp%smoothing
      setup%gauge_width = grp%gauge_width
      setup%gauge_height = grp%gauge_height
      setup%rail_cant = grp%rail_cant
      setup%flange_back_distance = grp%flange_back_distance
      setup%flange_back_position = grp%flange_back_position
      setup%nominal_radius = grp%nominal_radius
      setup%yaw = grp%yaw
      setup%wheelset = grp%wheelset
      if (.not. grp%wheelset .and. len_trim(grp%left_wheel_file) + len_trim(grp%left_rail_file) > 0) then
        call fail(status, exit_bad_input, where//'left_wheel_file and left_rail_file need wheelset = .true.')
        return
      end if
      setup%min_patch_share = grp%min_patch_share
      call check_wheel_rail_setup(setup, where, status)
      if (status%failed()) return

      wheel_path = resolve_path(trim(grp%wheel_file), folder_of(cfg%input_path))
      rail_path = resolve_path(trim(grp%rail_file), folder_of(cfg%input_path))
      setup%wheel_name = 'wheel_file '''//wheel_path//''''
      setup%rail_name = 'rail_file '''//rail_path//''''
      call read_profile_file(wheel_path, 'wheel_file', .true., setup%wheel_y, setup%wheel_z, status)
      if (status%failed()) return
      call read_profile_file(rail_path, 'rail_file', .false., setup%rail_y, setup%rail_z, status)
      if (status%failed()) return
      ! the wheelset's left side: its own profiles where given (as the right ones: mirror flags alike)
      if (len_trim(grp%left_wheel_file) > 0) then
        wheel_path = resolve_path(trim(grp%left_wheel_file), folder_of(cfg%input_path))
        setup%left_wheel_name = 'left_wheel_file '''//wheel_path//''''
        call read_profile_file(wheel_path, 'left_wheel_file', .true., setup%left_wheel_y, setup%left_wheel_z, status)
        if (status%failed()) return
      end if
      if (len_trim(grp%left_rail_file) > 0) then
        rail_path = resolve_path(trim(grp%left_rail_file), folder_of(cfg%input_path))
        setup%left_rail_name = 'left_rail_file '''//rail_path//''''
        call read_profile_file(rail_path, 'left_rail_file', .false., setup%left_rail_y, setup%left_rail_z, status)
      end if
    end associate
  end subroutine apply_wheel_rail_group

end module kcreep_nml_wheel_rail
