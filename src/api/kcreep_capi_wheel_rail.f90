!> The C API's wheel-rail calls: kcreep_set_profiles, kcreep_set_track,
!> kcreep_wheel_rail and kcreep_get_wheel_rail; the wheelset's
!> kcreep_set_left_profiles, kcreep_wheelset and kcreep_get_wheelset;
!> kcreep_take_wheel_rail_row (a row's patch as a handle's solved patch)
!> (include/kcreep.h).
module kcreep_capi_wheel_rail
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_f_pointer, c_associated
  use kcreep_kinds, only: wp
  use kcreep_status, only: fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use kcreep, only: problem_t, kcreep_wheel_rail, wheel_rail_setup_t, check_wheel_rail_setup, max_wheel_rail_shifts, &
                    default_target_error, kcreep_wheelset, wheel_rail_row_t, fast_forces_t
  use kcreep_profile_file, only: read_profile_file
  use kcreep_capi_handle, only: handle_t, status_ok, status_no_result, begin, finish, from_c, output_array
  implicit none
  private
  public :: row_values, wheel_rail_column_count, column_shift, column_patch, column_fn, column_verdict

  !> The wheel-rail table's columns (KCREEP_WHEEL_RAIL_COLUMNS in kcreep.h).
  integer, parameter :: wheel_rail_column_count = 25
  !> Where row_values puts the columns kcreep_wheel_rail_at sets itself.
  integer, parameter :: column_shift = 1, column_patch = 3, column_fn = 4, column_verdict = 19
  !> The wheelset table's columns (KCREEP_WHEELSET_COLUMNS in kcreep.h).
  integer, parameter :: wheelset_column_count = 9

contains

  !> The handle behind a C pointer, with its last error cleared.
  !> Wheel and rail profiles for kcreep_wheel_rail, read now (as &wheel_rail
  !> wheel_file, rail_file: SIMPACK .prw/.prr, MiniProf .whl/.ban, else two
  !> columns y z in mm); mirror flags 0 or 1; smoothing 0 to 1e12 (mm^4), negative: automatic.
  integer(c_int) function c_set_profiles(handle, wheel_file, rail_file, wheel_mirror, rail_mirror, smoothing) &
    bind(c, name='kcreep_set_profiles')
    type(c_ptr), value :: handle, wheel_file, rail_file
    integer(c_int), value :: wheel_mirror, rail_mirror
    real(c_double), value :: smoothing
    type(handle_t), pointer :: h
    character(len=:), allocatable :: wheel_path, rail_path
    c_set_profiles = begin(handle, h)
    if (c_set_profiles /= status_ok) return
    if (.not. (c_associated(wheel_file) .and. c_associated(rail_file))) then
      call fail(h%last, exit_bad_input, 'kcreep_set_profiles: wheel_file or rail_file is NULL')
    else if (.not. (smoothing <= 1e12_wp)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_profiles: smoothing = '//rtoa(real(smoothing, wp))// &
                ' (allowed: 0 to 1e12 mm^4, or negative: automatic)')
    else if (any([wheel_mirror, rail_mirror] /= 0 .and. [wheel_mirror, rail_mirror] /= 1)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_profiles: wheel_mirror, rail_mirror = '//itoa(int(wheel_mirror))// &
                ', '//itoa(int(rail_mirror))//' (allowed: 0 or 1)')
    else
      wheel_path = from_c(wheel_file, 4096)
      rail_path = from_c(rail_file, 4096)
      associate (s => h%wheel_rail)
        if (allocated(s%wheel_y)) deallocate (s%wheel_y, s%wheel_z)
        if (allocated(s%rail_y)) deallocate (s%rail_y, s%rail_z)
        call read_profile_file(wheel_path, 'wheel_file', .true., s%wheel_y, s%wheel_z, h%last)
        if (.not. h%last%failed()) call read_profile_file(rail_path, 'rail_file', .false., s%rail_y, s%rail_z, h%last)
        if (h%last%failed()) then
          if (allocated(s%wheel_y)) deallocate (s%wheel_y, s%wheel_z)
          if (allocated(s%rail_y)) deallocate (s%rail_y, s%rail_z)
          h%last%message = 'kcreep_set_profiles: '//h%last%message
        else
          s%wheel_name = 'wheel_file '''//wheel_path//''''
          s%rail_name = 'rail_file '''//rail_path//''''
          s%wheel_mirror = wheel_mirror == 1
          s%rail_mirror = rail_mirror == 1
          s%smoothing = smoothing
        end if
      end associate
    end if
    c_set_profiles = finish(h)
  end function c_set_profiles

  !> Track and wheelset placement of kcreep_wheel_rail (as &wheel_rail): side
  !> "right" or "left", gauge_width at gauge_height below the track plane,
  !> rail_cant (rad, added to the rail file's), flange_back_distance,
  !> flange_back_position, nominal_radius (mm). Until called: 'right', 1435,
  !> 14, 0, 1360, -70, 460.
  integer(c_int) function c_set_track(handle, side, gauge_width, gauge_height, rail_cant, flange_back_distance, &
                                      flange_back_position, nominal_radius) bind(c, name='kcreep_set_track')
    type(c_ptr), value :: handle, side
    real(c_double), value :: gauge_width, gauge_height, rail_cant, flange_back_distance, flange_back_position, &
                             nominal_radius
    type(handle_t), pointer :: h
    type(wheel_rail_setup_t) :: trial
    c_set_track = begin(handle, h)
    if (c_set_track /= status_ok) return
    if (.not. c_associated(side)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_track: side is NULL (allowed: "right", "left")')
    else
      trial%side = from_c(side, 16)
      trial%gauge_width = gauge_width
      trial%gauge_height = gauge_height
      trial%rail_cant = rail_cant
      trial%flange_back_distance = flange_back_distance
      trial%flange_back_position = flange_back_position
      trial%nominal_radius = nominal_radius
      trial%shifts = [0.0_wp]
      trial%vertical_force = 1
      call check_wheel_rail_setup(trial, 'kcreep_set_track: ', h%last)
      if (.not. h%last%failed()) then
        h%wheel_rail%side = trial%side
        h%wheel_rail%gauge_width = gauge_width
        h%wheel_rail%gauge_height = gauge_height
        h%wheel_rail%rail_cant = rail_cant
        h%wheel_rail%flange_back_distance = flange_back_distance
        h%wheel_rail%flange_back_position = flange_back_position
        h%wheel_rail%nominal_radius = nominal_radius
      end if
    end if
    c_set_track = finish(h)
  end function c_set_track

  !> The contact table of the handle's profiles and track for n_shifts lateral
  !> shifts (mm) at yaw (rad): exactly one of vertical_force (N) and approach
  !> (mm) > 0. The handle's material, solver settings and target error are
  !> used (target 0: the program's default, 1e-3). rows: the table's rows
  !> (one per shift and patch), read with kcreep_get_wheel_rail.
  integer(c_int) function c_wheel_rail(handle, n_shifts, shifts, yaw, vertical_force, approach, rows) &
    bind(c, name='kcreep_wheel_rail')
    type(c_ptr), value :: handle, shifts, rows
    integer(c_int), value :: n_shifts
    real(c_double), value :: yaw, vertical_force, approach
    type(handle_t), pointer :: h
    real(c_double), pointer :: values(:)
    integer(c_int), pointer :: n_rows
    type(problem_t) :: base
    c_wheel_rail = begin(handle, h)
    if (c_wheel_rail /= status_ok) return
    h%wheel_rail_done = .false.
    call check_table_call(h, 'kcreep_wheel_rail', shifts, rows, n_shifts)
    if (.not. h%last%failed() .and. ((vertical_force > 0) .eqv. (approach > 0))) &
      call fail(h%last, exit_bad_input, 'kcreep_wheel_rail: vertical_force = '//rtoa(real(vertical_force, wp))// &
                ', approach = '//rtoa(real(approach, wp))//' (allowed: exactly one > 0)')
    if (.not. h%last%failed()) then
      call c_f_pointer(shifts, values, [n_shifts])
      call c_f_pointer(rows, n_rows)
      n_rows = 0
      h%wheel_rail%shifts = values
      h%wheel_rail%yaw = yaw
      h%wheel_rail%force_given = vertical_force > 0
      h%wheel_rail%vertical_force = max(vertical_force, 0.0_c_double)
      h%wheel_rail%approach = max(approach, 0.0_c_double)
      call check_wheel_rail_setup(h%wheel_rail, 'kcreep_wheel_rail: ', h%last)
      if (.not. h%last%failed()) then
        base = h%problem
        if (.not. (base%target_error > 0)) base%target_error = default_target_error
        call kcreep_wheel_rail(h%wheel_rail, base, h%wheel_rail_rows, h%last)
        h%wheel_rail_done = .not. h%last%failed()
        if (h%wheel_rail_done) n_rows = size(h%wheel_rail_rows)
      end if
    end if
    c_wheel_rail = finish(h)
  end function c_wheel_rail

  !> The last kcreep_wheel_rail's table, row by row: table[r * KCREEP_WHEEL_RAIL_COLUMNS + k]
  !> (length >= rows * KCREEP_WHEEL_RAIL_COLUMNS), the columns of
  !> KCREEP_WHEEL_RAIL_COLUMN_NAMES, the verdict as its bits, kind 0 tread, 1 flange.
  integer(c_int) function c_get_wheel_rail(handle, length, table) bind(c, name='kcreep_get_wheel_rail')
    type(c_ptr), value :: handle, table
    integer(c_int), value :: length
    type(handle_t), pointer :: h
    real(c_double), pointer :: values(:)
    integer :: r, n
    c_get_wheel_rail = begin(handle, h)
    if (c_get_wheel_rail /= status_ok) return
    n = 0
    if (h%wheel_rail_done) n = size(h%wheel_rail_rows) * wheel_rail_column_count
    c_get_wheel_rail = table_output(h, h%wheel_rail_done, n, length, table, 'kcreep_get_wheel_rail', &
                                    'kcreep_wheel_rail', values)
    if (c_get_wheel_rail /= status_ok) return
    do r = 1, size(h%wheel_rail_rows)
      values((r - 1) * wheel_rail_column_count + 1:r * wheel_rail_column_count) = row_values(h%wheel_rail_rows(r))
    end do
  end function c_get_wheel_rail

  !> The checks and the output array of a kcreep_get_* table call (getter):
  !> a table made by maker (done), length holding its n values.
  integer(c_int) function table_output(h, done, n, length, table, getter, maker, values) result(code)
    type(handle_t), intent(inout) :: h
    logical, intent(in) :: done
    integer, intent(in) :: n
    integer(c_int), intent(in) :: length
    type(c_ptr), intent(in) :: table
    character(len=*), intent(in) :: getter, maker
    real(c_double), pointer, intent(out) :: values(:)
    nullify (values)
    if (.not. done) then
      call fail(h%last, int(status_no_result), getter//': no table: call '//maker//' (successfully) first')
    else if (length < n) then
      call fail(h%last, exit_bad_input, getter//': length = '//itoa(int(length))//' (the table has '// &
                itoa(n)//' values)')
    else
      code = output_array(h, table, n, getter//': table', values)
      return
    end if
    code = finish(h)
  end function table_output

  !> A row as the C table's columns (KCREEP_WHEEL_RAIL_COLUMN_NAMES), the verdict as its bits.
  pure function row_values(w) result(values)
    type(wheel_rail_row_t), intent(in) :: w
    real(wp) :: values(wheel_rail_column_count)
    values = [w%shift, w%yaw, real(w%patch, wp), w%fn, w%delta, w%y_rail, w%y_wheel, w%r_wheel, w%area, w%length, &
              w%width, w%c, w%err, real(w%result%verdict_flags, wp), w%l, w%spin, &
              merge(1.0_wp, 0.0_wp, w%kind == 'flange'), w%turn]
  end function row_values

  !> The wheelset's left profiles (as kcreep_set_profiles, its mirror flags
  !> and smoothing): NULL or "" for either keeps the right one mirrored.
  integer(c_int) function c_set_left_profiles(handle, wheel_file, rail_file) bind(c, name='kcreep_set_left_profiles')
    type(c_ptr), value :: handle, wheel_file, rail_file
    type(handle_t), pointer :: h
    character(len=:), allocatable :: path
    real(wp), allocatable :: wy(:), wz(:), ry(:), rz(:)
    character(len=:), allocatable :: wheel_name, rail_name
    c_set_left_profiles = begin(handle, h)
    if (c_set_left_profiles /= status_ok) return
    path = ''
    if (c_associated(wheel_file)) path = from_c(wheel_file, 4096)
    if (len(path) > 0) then
      wheel_name = 'left_wheel_file '''//path//''''
      call read_profile_file(path, 'left_wheel_file', .true., wy, wz, h%last)
    end if
    path = ''
    if (c_associated(rail_file)) path = from_c(rail_file, 4096)
    if (len(path) > 0 .and. .not. h%last%failed()) then
      rail_name = 'left_rail_file '''//path//''''
      call read_profile_file(path, 'left_rail_file', .false., ry, rz, h%last)
    end if
    if (h%last%failed()) then
      h%last%message = 'kcreep_set_left_profiles: '//h%last%message
    else
      associate (s => h%wheel_rail)
        if (allocated(s%left_wheel_y)) deallocate (s%left_wheel_y, s%left_wheel_z, s%left_wheel_name)
        if (allocated(s%left_rail_y)) deallocate (s%left_rail_y, s%left_rail_z, s%left_rail_name)
        if (allocated(wy)) then
          call move_alloc(wy, s%left_wheel_y)
          call move_alloc(wz, s%left_wheel_z)
          s%left_wheel_name = wheel_name
        end if
        if (allocated(ry)) then
          call move_alloc(ry, s%left_rail_y)
          call move_alloc(rz, s%left_rail_z)
          s%left_rail_name = rail_name
        end if
      end associate
    end if
    c_set_left_profiles = finish(h)
  end function c_set_left_profiles

  !> The checks kcreep_wheel_rail and kcreep_wheelset (who) share: shifts and rows given,
  !> 1 <= n_shifts <= max_wheel_rail_shifts, the handle's profiles set.
  subroutine check_table_call(h, who, shifts, rows, n_shifts)
    type(handle_t), intent(inout) :: h
    character(len=*), intent(in) :: who
    type(c_ptr), intent(in) :: shifts, rows
    integer(c_int), intent(in) :: n_shifts
    if (.not. (c_associated(shifts) .and. c_associated(rows))) then
      call fail(h%last, exit_bad_input, who//': shifts or rows is NULL')
    else if (n_shifts < 1 .or. n_shifts > max_wheel_rail_shifts) then
      call fail(h%last, exit_bad_input, who//': n_shifts = '//itoa(int(n_shifts))//' (allowed: 1 to '// &
                itoa(max_wheel_rail_shifts)//')')
    else if (.not. (allocated(h%wheel_rail%wheel_y) .and. allocated(h%wheel_rail%rail_y))) then
      call fail(h%last, exit_bad_input, who//': no profiles (call kcreep_set_profiles first)')
    end if
  end subroutine check_table_call

  !> The wheelset table of the handle's profiles and track (docs/wheel_rail.md,
  !> Wheelset) for n_shifts lateral shifts (mm) at yaw (rad), each wheel
  !> carrying vertical_force (N) > 0; rows: one per shift, read with
  !> kcreep_get_wheelset.
  integer(c_int) function c_wheelset(handle, n_shifts, shifts, yaw, vertical_force, rows) &
    bind(c, name='kcreep_wheelset')
    type(c_ptr), value :: handle, shifts, rows
    integer(c_int), value :: n_shifts
    real(c_double), value :: yaw, vertical_force
    type(handle_t), pointer :: h
    real(c_double), pointer :: values(:)
    integer(c_int), pointer :: n_rows
    type(problem_t) :: base
    c_wheelset = begin(handle, h)
    if (c_wheelset /= status_ok) return
    h%wheelset_done = .false.
    call check_table_call(h, 'kcreep_wheelset', shifts, rows, n_shifts)
    if (.not. h%last%failed()) then
      call c_f_pointer(shifts, values, [n_shifts])
      call c_f_pointer(rows, n_rows)
      n_rows = 0
      h%wheel_rail%shifts = values
      h%wheel_rail%yaw = yaw
      h%wheel_rail%force_given = .true.
      h%wheel_rail%vertical_force = vertical_force
      h%wheel_rail%approach = 0
      base = h%problem
      if (.not. (base%target_error > 0)) base%target_error = default_target_error
      call kcreep_wheelset(h%wheel_rail, base, h%wheelset_rows, h%last)
      h%wheelset_done = .not. h%last%failed()
      if (h%wheelset_done) n_rows = size(h%wheelset_rows)
      if (h%last%failed()) h%last%message = 'kcreep_wheelset: '//h%last%message
    end if
    c_wheelset = finish(h)
  end function c_wheelset

  !> The last kcreep_wheelset's table, row by row: table[r * KCREEP_WHEELSET_COLUMNS + k]
  !> (length >= rows * KCREEP_WHEELSET_COLUMNS), the columns of KCREEP_WHEELSET_COLUMN_NAMES.
  integer(c_int) function c_get_wheelset(handle, length, table) bind(c, name='kcreep_get_wheelset')
    type(c_ptr), value :: handle, table
    integer(c_int), value :: length
    type(handle_t), pointer :: h
    real(c_double), pointer :: values(:)
    integer :: r, n
    c_get_wheelset = begin(handle, h)
    if (c_get_wheelset /= status_ok) return
    n = 0
    if (h%wheelset_done) n = size(h%wheelset_rows) * wheelset_column_count
    c_get_wheelset = table_output(h, h%wheelset_done, n, length, table, 'kcreep_get_wheelset', 'kcreep_wheelset', &
                                  values)
    if (c_get_wheelset /= status_ok) return
    do r = 1, size(h%wheelset_rows)
      associate (w => h%wheelset_rows(r))
        values((r - 1) * wheelset_column_count + 1:r * wheelset_column_count) = &
          [w%shift, w%r_right, w%r_left, w%delta_r, w%delta_right, w%delta_left, w%roll, w%z, w%lambda_eq]
      end associate
    end do
  end function c_get_wheelset

  !> Row `row` (0-based) of source's last kcreep_wheel_rail table becomes
  !> handle's solved patch: its grid, pressure, coefficients and material, as
  !> if handle had just solved it, so kcreep_fastsim, kcreep_rolling and
  !> kcreep_get_results act on it (handle and source may be the same; the
  !> solver settings stay handle's own).
  integer(c_int) function c_take_wheel_rail_row(handle, source, row) bind(c, name='kcreep_take_wheel_rail_row')
    type(c_ptr), value :: handle, source
    integer(c_int), value :: row
    type(handle_t), pointer :: h, s
    nullify (s)
    c_take_wheel_rail_row = begin(handle, h)
    if (c_take_wheel_rail_row /= status_ok) return
    if (c_associated(source)) call c_f_pointer(source, s)   ! source's own last error kept
    if (.not. c_associated(source)) then
      call fail(h%last, int(status_no_result), 'kcreep_take_wheel_rail_row: source is a null handle')
    else if (.not. s%wheel_rail_done) then
      call fail(h%last, int(status_no_result), 'kcreep_take_wheel_rail_row: source has no table: call '// &
                'kcreep_wheel_rail (successfully) on it first')
    else if (row < 0 .or. row >= size(s%wheel_rail_rows)) then
      call fail(h%last, exit_bad_input, 'kcreep_take_wheel_rail_row: row = '//itoa(int(row))//' (allowed: 0 to '// &
                itoa(size(s%wheel_rail_rows) - 1)//')')
    else
      h%result = s%wheel_rail_rows(row + 1)%result
      h%solved = .true.
      ! the fast model belongs to the last solved patch (the rolling state checks its own patch)
      h%fast = fast_forces_t()
    end if
    c_take_wheel_rail_row = finish(h)
  end function c_take_wheel_rail_row

end module kcreep_capi_wheel_rail
