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
!> origin]. Profile files are read here (kcreep_profile_file); file names are
!> relative to the namelist's folder. Errors name the file, variable, value and
!> what is allowed.
module kcreep_wheel_rail_input
  use, intrinsic :: iso_fortran_env, only: real64, iostat_end
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, lower, resolve_path, folder_of
  use kcreep_profile_file, only: read_profile_file
  use kcreep_wheel_rail_run, only: wheel_rail_setup_t
  implicit none
  private
  public :: read_wheel_rail, max_shifts

  !> At most this many shifts in one table.
  integer, parameter :: max_shifts = 10000

contains

  !> Read &wheel_rail from the namelist at path (the group is known to be
  !> there, once) and the two profile files it names.
  subroutine read_wheel_rail(path, setup, status)
    character(len=*), intent(in) :: path
    type(wheel_rail_setup_t), intent(out) :: setup
    type(status_t), intent(inout) :: status
    real(real64), parameter :: unset = -huge(1.0_real64)
    character(len=1024) :: wheel_file, rail_file
    character(len=16) :: side
    logical :: wheel_mirror, rail_mirror
    real(real64) :: smoothing, gauge_width, gauge_height, rail_cant, flange_back_distance, flange_back_position, &
                    nominal_radius, shift_from, shift_to, shift_step, yaw, vertical_force, approach
    real(real64), allocatable :: shifts(:)
    character(len=512) :: msg
    character(len=:), allocatable :: where
    integer :: unit, ios, n, k
    namelist /wheel_rail/ wheel_file, rail_file, wheel_mirror, rail_mirror, smoothing, side, gauge_width, &
                          gauge_height, rail_cant, flange_back_distance, flange_back_position, nominal_radius, &
                          shifts, shift_from, shift_to, shift_step, yaw, vertical_force, approach

    wheel_file = ''
    rail_file = ''
    wheel_mirror = .false.
    rail_mirror = .false.
    smoothing = 0
    side = 'right'
    gauge_width = 1435
    gauge_height = 14
    rail_cant = 0
    flange_back_distance = 1360
    flange_back_position = -70
    nominal_radius = 460
    allocate (shifts(max_shifts + 1))
    shifts = unset
    shift_from = unset
    shift_to = unset
    shift_step = unset
    yaw = 0
    vertical_force = unset
    approach = unset
    where = 'input '''//path//''': &wheel_rail '

    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_bad_input, 'input '''//path//''': cannot open ('//trim(msg)//')')
      return
    end if
    read (unit, nml=wheel_rail, iostat=ios, iomsg=msg)
    close (unit)
    if (ios == iostat_end) ios = 0      ! the group was read whole; the end came after its /
    if (ios /= 0) then
      call fail(status, exit_bad_input, 'input '''//path//''': namelist &wheel_rail: '//trim(msg))
      return
    end if

    if (len_trim(wheel_file) == 0 .or. len_trim(rail_file) == 0) then
      call fail(status, exit_bad_input, where//'needs wheel_file and rail_file (SIMPACK .prw/.prr, MiniProf '// &
                '.whl/.ban, or two columns y z in mm)')
      return
    end if
    setup%side = lower(trim(adjustl(side)))
    if (setup%side /= 'right' .and. setup%side /= 'left') &
      call fail(status, exit_bad_input, where//'side = '''//trim(side)//''' (allowed: ''right'', ''left'')')
    call check_range('gauge_width', gauge_width, 100.0_real64, 5000.0_real64)
    call check_range('gauge_height', gauge_height, 0.0_real64, 100.0_real64)
    call check_range('rail_cant', rail_cant, -0.5_real64, 0.5_real64)
    call check_range('flange_back_distance', flange_back_distance, 100.0_real64, 5000.0_real64)
    call check_range('flange_back_position', flange_back_position, -1000.0_real64, 1000.0_real64)
    call check_range('nominal_radius', nominal_radius, 10.0_real64, 10000.0_real64)
    call check_range('smoothing', smoothing, 0.0_real64, 1e12_real64)
    call check_range('yaw', yaw, -0.1_real64, 0.1_real64)
    if (status%failed()) return

    ! the shifts: a list, or from / to / step
    n = count(shifts /= unset)
    if (n > max_shifts) then
      call fail(status, exit_bad_input, where//'shifts: more than '//itoa(max_shifts)//' values')
      return
    end if
    if (n > 0 .and. any(shifts(1:n) == unset)) then
      call fail(status, exit_bad_input, where//'shifts: a value is missing in the list')
      return
    end if
    if (n > 0 .and. any([shift_from, shift_to, shift_step] /= unset)) then
      call fail(status, exit_bad_input, where//'give shifts (a list) or shift_from, shift_to, shift_step, not both')
      return
    end if
    if (n > 0) then
      setup%shifts = shifts(1:n)
    else if (all([shift_from, shift_to, shift_step] /= unset)) then
      if (.not. (shift_step > 0 .and. abs(shift_from) <= 200 .and. abs(shift_to) <= 200 .and. &
                 shift_to >= shift_from)) then
        call fail(status, exit_bad_input, where//'shift_from, shift_to, shift_step = '//rtoa(shift_from)//', '// &
                  rtoa(shift_to)//', '//rtoa(shift_step)//' (allowed: -200 <= from <= to <= 200 mm, step > 0)')
        return
      end if
      n = floor((shift_to - shift_from) / shift_step + 1e-9_real64) + 1
      if (n > max_shifts) then
        call fail(status, exit_bad_input, where//'shift_from to shift_to by shift_step: '//itoa(n)// &
                  ' shifts (at most '//itoa(max_shifts)//')')
        return
      end if
      setup%shifts = [(shift_from + (k - 1) * shift_step, k=1, n)]
    else
      call fail(status, exit_bad_input, where//'needs the wheelset''s lateral shifts: shifts = a list (mm), or '// &
                'all three of shift_from, shift_to, shift_step')
      return
    end if
    if (.not. all(abs(setup%shifts) <= 200)) then
      call fail(status, exit_bad_input, where//'shifts: a value beyond 200 mm in magnitude')
      return
    end if

    ! the load: exactly one
    if ((vertical_force == unset) .eqv. (approach == unset)) then
      call fail(status, exit_bad_input, where//'give exactly one of vertical_force (N) and approach (mm)')
      return
    end if
    setup%force_given = vertical_force /= unset
    if (setup%force_given) then
      call check_range('vertical_force', vertical_force, 1e-6_real64, 1e9_real64)
      setup%vertical_force = vertical_force
    else
      call check_range('approach', approach, 1e-9_real64, 10.0_real64)
      setup%approach = approach
    end if
    if (status%failed()) return

    setup%wheel_mirror = wheel_mirror
    setup%rail_mirror = rail_mirror
    setup%smoothing = smoothing
    setup%gauge_width = gauge_width
    setup%gauge_height = gauge_height
    setup%rail_cant = rail_cant
    setup%flange_back_distance = flange_back_distance
    setup%flange_back_position = flange_back_position
    setup%nominal_radius = nominal_radius
    setup%yaw = yaw
    setup%wheel_name = 'wheel_file '''//resolve_path(trim(wheel_file), folder_of(path))//''''
    setup%rail_name = 'rail_file '''//resolve_path(trim(rail_file), folder_of(path))//''''
    call read_profile_file(resolve_path(trim(wheel_file), folder_of(path)), 'wheel_file', .true., &
                           setup%wheel_y, setup%wheel_z, status)
    if (status%failed()) return
    call read_profile_file(resolve_path(trim(rail_file), folder_of(path)), 'rail_file', .false., &
                           setup%rail_y, setup%rail_z, status)

  contains

    subroutine check_range(name, value, lo, hi)
      character(len=*), intent(in) :: name
      real(real64), intent(in) :: value, lo, hi
      if (status%failed()) return
      if (.not. (value >= lo .and. value <= hi)) call fail(status, exit_bad_input, where//name//' = '// &
          rtoa(value)//' (allowed: '//rtoa(lo)//' to '//rtoa(hi)//')')
    end subroutine check_range

  end subroutine read_wheel_rail

end module kcreep_wheel_rail_input
