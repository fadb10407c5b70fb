!> kcreep INPUT.nml with &wheel_rail: the contact table over the lateral
!> shifts, written to &output wheel_rail_file, and a summary on standard output.
module kcreep_app_wheel_rail
  use, intrinsic :: iso_fortran_env, only: real64, int64, output_unit, error_unit
  use kcreep_status, only: status_t
  use kcreep_strings, only: rtoa, itoa
  use kcreep, only: problem_t, patch_t, wheel_rail_row_t, kcreep_wheel_rail, creep_request_t, creep_point_t, &
                    creep_map_t, creep_curve, result_t, rolling_request_t, rolling_point_t, rolling_curve
  use kcreep_namelist, only: config_t, problem_of
  use kcreep_wheel_rail_table, only: wheel_rail_lines, line_length, wheel_rail_creep_header, wheel_rail_creep_rows, &
                                     wheel_rail_rolling_header, wheel_rail_rolling_rows
  use kcreep_app_files, only: check_output_path, write_text_file
  use kcreep_app_memory, only: memory_limit_bytes
  implicit none
  private
  public :: wheel_rail_mode

contains

  subroutine wheel_rail_mode(input_path, cfg, status)
    character(len=*), intent(in) :: input_path
    type(config_t), intent(in) :: cfg
    type(status_t), intent(inout) :: status
    type(problem_t) :: base
    type(patch_t) :: none
    type(wheel_rail_row_t), allocatable :: rows(:)
    type(rolling_point_t), allocatable :: rolled(:)
    character(len=line_length), allocatable :: creep(:), rolling(:)
    character(len=200) :: buf
    integer :: k, j
    real(real64) :: t0, t1
    integer(int64) :: clock0, clock1, clock_rate
    integer :: team

    call check_output_path(cfg%wheel_rail_file, 'wheel_rail_file', status)
    if (cfg%fastsim_on .and. .not. status%failed()) call check_output_path(cfg%creep_file, 'creep_file', status)
    if (cfg%rolling%on .and. .not. status%failed()) &
      call check_output_path(cfg%rolling%rolling_file, 'rolling_file', status)
    if (status%failed()) return
    base = problem_of(cfg, none)
    base%solve%memory_limit = memory_limit_bytes()
    call system_clock(clock0, clock_rate)
    call cpu_time(t0)
    call kcreep_wheel_rail(cfg%wheel_rail, base, rows, status, team)
    call cpu_time(t1)
    call system_clock(clock1)
    if (status%failed()) return
    ! the per-patch tables before any file is written: a failed rolling point leaves none
    if (cfg%fastsim_on) creep = creep_lines_of(rows)
    if (cfg%rolling%on) call rolling_lines_of(rows, rolling, rolled, status)
    if (status%failed()) return
    call write_text_file(cfg%wheel_rail_file, wheel_rail_lines(rows, cfg%wheel_rail, cfg%g, cfg%nu, cfg%target_error), &
                         'wheel_rail_file', status)
    if (cfg%fastsim_on .and. .not. status%failed()) call write_text_file(cfg%creep_file, creep, 'creep_file', status)
    if (cfg%rolling%on .and. .not. status%failed()) &
      call write_text_file(cfg%rolling%rolling_file, rolling, 'rolling_file', status)
    if (status%failed()) return
    write (output_unit, '(a)') 'kcreep: '//input_path
    write (output_unit, '(2x, a)') 'wheel/rail: '//itoa(size(cfg%wheel_rail%shifts))//' shifts, '//itoa(size(rows))// &
      ' patches, side '//cfg%wheel_rail%side//'; table: '//cfg%wheel_rail_file
    write (output_unit, '(2x, a)') '  shift patch   kind        fn     delta   y_rail  y_wheel  r_wheel    c11    c22'// &
      '    c23   err11   err22   err23 verdict'
    do k = 1, size(rows)
      associate (r => rows(k))
        write (output_unit, '(2x, f7.2, i6, a7, es10.3, f10.4, 3f9.3, 3f7.3, 3es8.1, 1x, a)') r%shift, r%patch, &
          trim(r%kind), r%fn, r%delta, r%y_rail, r%y_wheel, r%r_wheel, r%c(1:3), r%err, trim(r%verdict)
        if (allocated(r%result%warnings)) then
          do j = 1, size(r%result%warnings)
            write (error_unit, '(a)') 'kcreep: warning: shift '//rtoa(r%shift)//' patch '//itoa(r%patch)//': '// &
              trim(r%result%warnings(j))
          end do
        end if
      end associate
    end do
    if (cfg%fastsim_on) write (output_unit, '(2x, a)') 'FASTSIM on each patch (phi + its geometric spin): '// &
      itoa(size(cfg%fastsim%creepages, 2))//' creepage points per patch; creep table: '//cfg%creep_file
    if (cfg%rolling%on) then
      write (buf, '(a, es10.3, a, f9.4, a, f6.2, a, es9.2)') 'exact rolling on each patch (phi + its geometric '// &
        'spin): '//itoa(size(cfg%rolling%request%creepages, 2))//' creepage points per patch, mu =', &
        cfg%rolling%request%mu, ',', sum(rolled%seconds), ' s; Newton steps per point', &
        real(sum(rolled%info%newton), real64) / max(1, size(rolled)), ', largest residual', &
        maxval(rolled%info%residual)
      write (output_unit, '(2x, a)') trim(buf)//'; rolling table: '//cfg%rolling%rolling_file
    end if
    if (team > 1) then
      write (output_unit, '(2x, a)') 'threads: '//itoa(team)//' (one shift per thread)'
    else
      write (output_unit, '(2x, a)') 'threads: 1 (one shift at a time)'
    end if
    write (output_unit, '(2x, a, f8.2, a, f8.2)') 'time [s]: wall', real(clock1 - clock0, real64) / clock_rate, &
      ', CPU', t1 - t0

  contains

    !> FASTSIM on every patch with its normal pressure, each creepage's phi
    !> plus the patch's geometric spin.
    function creep_lines_of(table_rows) result(lines)
      type(wheel_rail_row_t), intent(in) :: table_rows(:)
      character(len=line_length), allocatable :: lines(:)
      type(creep_request_t) :: request
      type(creep_point_t), allocatable :: points(:)
      type(creep_map_t), allocatable :: maps(:)
      integer :: r
      lines = wheel_rail_creep_header(cfg%wheel_rail, cfg%fastsim)
      do r = 1, size(table_rows)
        request = cfg%fastsim
        request%maps = .false.
        request%creepages(3, :) = request%creepages(3, :) + table_rows(r)%spin
        call creep_curve(table_rows(r)%result, pressure_grid(table_rows(r)%result), request, points, maps)
        lines = [lines, wheel_rail_creep_rows(table_rows(r), request, points)]
      end do
    end function creep_lines_of

    !> Exact steady rolling on every patch with its normal pressure, on its
    !> finest grid, each creepage's phi plus the patch's geometric spin; all
    !> the points in done (for the summary). A point that fails names its patch.
    subroutine rolling_lines_of(table_rows, lines, done, status)
      type(wheel_rail_row_t), intent(in) :: table_rows(:)
      character(len=line_length), allocatable, intent(out) :: lines(:)
      type(rolling_point_t), allocatable, intent(out) :: done(:)
      type(status_t), intent(inout) :: status
      type(rolling_request_t) :: request
      type(rolling_point_t), allocatable :: points(:)
      type(creep_map_t), allocatable :: maps(:)
      integer :: r
      lines = wheel_rail_rolling_header(cfg%wheel_rail, cfg%rolling%request)
      allocate (done(0))
      do r = 1, size(table_rows)
        associate (res => table_rows(r)%result)
          request = cfg%rolling%request
          request%maps = .false.
          request%creepages(3, :) = request%creepages(3, :) + table_rows(r)%spin
          if (allocated(res%traction)) then
            call rolling_curve(res%patch, cfg%scheme, res%nu, res%g, res%spin_centre, pressure_grid(res), request, &
                               points, maps, status, res%traction)
          else
            call rolling_curve(res%patch, cfg%scheme, res%nu, res%g, res%spin_centre, pressure_grid(res), request, &
                               points, maps, status)
          end if
        end associate
        if (status%failed()) then
          status%message = 'shift '//rtoa(table_rows(r)%shift)//' patch '//itoa(table_rows(r)%patch)//': '// &
                           status%message
          return
        end if
        lines = [lines, wheel_rail_rolling_rows(table_rows(r), request, points)]
        done = [done, points]
      end do
    end subroutine rolling_lines_of

    !> The normal solve's pressure on the patch's grid (mx, my), zero outside the patch cells.
    function pressure_grid(res) result(pn)
      type(result_t), intent(in) :: res
      real(real64), allocatable :: pn(:, :)
      integer :: c
      allocate (pn(res%patch%mx, res%patch%my), source=0.0_real64)
      do c = 1, res%patch%n
        pn(res%patch%ix(c), res%patch%iy(c)) = res%pressure(c)
      end do
    end function pressure_grid

  end subroutine wheel_rail_mode

end module kcreep_app_wheel_rail
