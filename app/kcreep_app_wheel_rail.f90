!> A case with &wheel_rail: the contact table over the lateral shifts (and,
!> with &fastsim or &rolling, the per-patch creep or rolling table), its
!> files and its summary. kcreep INPUT.nml (wheel_rail_mode) and kcreep
!> --batch (kcreep_app_batch) run it through the same run_wheel_rail_case.
module kcreep_app_wheel_rail
  use, intrinsic :: iso_fortran_env, only: real64, int64, output_unit, error_unit
  use kcreep_status, only: status_t
  use kcreep_strings, only: rtoa, itoa
  use kcreep, only: problem_t, patch_t, wheel_rail_row_t, kcreep_wheel_rail, kcreep_wheelset, wheelset_row_t, wheel_state_t, &
                    creep_request_t, creep_point_t, &
                    creep_map_t, creep_curve, result_t, rolling_request_t, rolling_point_t, rolling_curve
  use kcreep_namelist, only: config_t, problem_of
  use kcreep_wheel_rail_table, only: wheel_rail_lines, line_length, wheel_rail_creep_header, wheel_rail_creep_rows, &
                                     wheel_rail_rolling_header, wheel_rail_rolling_rows, wheelset_lines
  use kcreep_app_files, only: check_output_path, write_text_file
  use kcreep_app_memory, only: memory_limit_bytes
  implicit none
  private
  public :: wheel_rail_mode, wheel_rail_case_t, run_wheel_rail_case, write_wheel_rail_case, summary_row, &
            summary_columns

  !> What a case with &wheel_rail gives: its rows, the lines of its files,
  !> the lines of its summary and its warnings.
  type :: wheel_rail_case_t
    type(wheel_rail_row_t), allocatable :: rows(:)
    character(len=line_length), allocatable :: table(:)     !< wheel_rail_file
    character(len=line_length), allocatable :: creep(:)     !< creep_file (with &fastsim)
    character(len=line_length), allocatable :: rolling(:)   !< rolling_file (with &rolling)
    character(len=line_length), allocatable :: wheelset(:)  !< wheelset_file (with wheelset = .true.)
    character(len=line_length), allocatable :: summary(:)   !< for standard output
    character(len=line_length), allocatable :: warnings(:)  !< 'shift S patch P: ...'
    real(real64) :: wall = 0, cpu = 0                       !< seconds, all the stages
  end type wheel_rail_case_t

contains

  !> kcreep INPUT.nml with &wheel_rail: run, write the files, print the summary.
  subroutine wheel_rail_mode(input_path, cfg, status)
    character(len=*), intent(in) :: input_path
    type(config_t), intent(in) :: cfg
    type(status_t), intent(inout) :: status
    type(wheel_rail_case_t) :: wr
    integer :: k
    call run_wheel_rail_case(cfg, wr, status)
    if (status%failed()) return
    call write_wheel_rail_case(cfg, wr, status)
    if (status%failed()) return
    write (output_unit, '(a)') 'kcreep: '//input_path
    do k = 1, size(wr%summary)
      write (output_unit, '(2x, a)') trim(wr%summary(k))
    end do
    do k = 1, size(wr%warnings)
      write (error_unit, '(a)') 'kcreep: warning: '//trim(wr%warnings(k))
    end do
  end subroutine wheel_rail_mode

  !> Check that the case's files can be written, solve the contact table,
  !> run &fastsim and &rolling on its patches, and make every line. Nothing
  !> is written: a failure at any stage leaves the files as they were.
  subroutine run_wheel_rail_case(cfg, wr, status)
    type(config_t), intent(in) :: cfg
    type(wheel_rail_case_t), intent(out) :: wr
    type(status_t), intent(inout) :: status
    type(problem_t) :: base
    type(patch_t) :: none
    type(rolling_point_t), allocatable :: rolled(:)
    type(wheelset_row_t), allocatable :: wheelset(:)
    type(wheel_state_t), allocatable :: states(:)
    character(len=line_length) :: buf
    integer :: k, j, team
    real(real64) :: t0, t1
    integer(int64) :: clock0, clock1, clock_rate

    allocate (wr%summary(0), wr%warnings(0))
    call check_output_path(cfg%wheel_rail_file, 'wheel_rail_file', status)
    if (cfg%fastsim_on .and. .not. status%failed()) call check_output_path(cfg%creep_file, 'creep_file', status)
    if (cfg%rolling%on .and. .not. status%failed()) &
      call check_output_path(cfg%rolling%rolling_file, 'rolling_file', status)
    if (cfg%wheel_rail%wheelset .and. .not. status%failed()) &
      call check_output_path(cfg%wheelset_file, 'wheelset_file', status)
    if (status%failed()) return
    base = problem_of(cfg, none)
    base%solve%memory_limit = memory_limit_bytes()
    call system_clock(clock0, clock_rate)
    call cpu_time(t0)
    call kcreep_wheel_rail(cfg%wheel_rail, base, wr%rows, status, team, states)
    if (cfg%wheel_rail%wheelset .and. .not. status%failed()) then
      call kcreep_wheelset(cfg%wheel_rail, base, wheelset, status, states)
      if (.not. status%failed()) wr%wheelset = wheelset_lines(wheelset, cfg%wheel_rail)
    end if
    if (status%failed()) return
    ! the per-patch tables before any file is written: a failed rolling point leaves none
    if (cfg%fastsim_on) wr%creep = creep_lines_of(wr%rows)
    if (cfg%rolling%on) call rolling_lines_of(wr%rows, wr%rolling, rolled, status)
    if (status%failed()) return
    call cpu_time(t1)
    call system_clock(clock1)
    wr%wall = real(clock1 - clock0, real64) / clock_rate
    wr%cpu = t1 - t0
    wr%table = wheel_rail_lines(wr%rows, cfg%wheel_rail, cfg%g, cfg%nu, cfg%target_error)

    call add('wheel/rail: '//itoa(size(cfg%wheel_rail%shifts))//' shifts, '//itoa(size(wr%rows))// &
             ' patches, side '//cfg%wheel_rail%side//'; table: '//cfg%wheel_rail_file)
    call add(summary_columns())
    do k = 1, size(wr%rows)
      call add(summary_row(wr%rows(k)))
      associate (r => wr%rows(k))
        if (allocated(r%result%warnings)) then
          do j = 1, size(r%result%warnings)
            wr%warnings = [character(len=line_length) :: wr%warnings, 'shift '//rtoa(r%shift)//' patch '// &
                           itoa(r%patch)//': '//trim(r%result%warnings(j))]
          end do
        end if
      end associate
    end do
    if (cfg%fastsim_on) call add('FASTSIM on each patch (phi + its geometric spin): '// &
      itoa(size(cfg%fastsim%creepages, 2))//' creepage points per patch; creep table: '//cfg%creep_file)
    if (cfg%rolling%on) then
      write (buf, '(a, es10.3, a, f9.4, a, f6.2, a, es9.2)') 'exact rolling on each patch (phi + its geometric '// &
        'spin): '//itoa(size(cfg%rolling%request%creepages, 2))//' creepage points per patch, mu =', &
        cfg%rolling%request%mu, ',', sum(rolled%seconds), ' s on '//itoa(maxval([1, rolled%threads]))// &
        ' thread(s); Newton steps per point', &
        real(sum(rolled%info%newton), real64) / max(1, size(rolled)), ', largest residual', &
        maxval(rolled%info%residual)
      call add(trim(buf)//'; rolling table: '//cfg%rolling%rolling_file)
    end if
    if (cfg%wheel_rail%wheelset) call add('wheelset: '//itoa(size(wheelset))// &
                                          ' shifts, both wheels; wheelset table: '//cfg%wheelset_file)
    if (team > 1) then
      call add('threads: '//itoa(team)//' (one shift per thread)')
    else
      call add('threads: 1 (one shift at a time)')
    end if
    write (buf, '(a, f8.2, a, f8.2)') 'time [s]: wall', wr%wall, ', CPU', wr%cpu
    if (cfg%fastsim_on) buf = trim(buf)//'; with FASTSIM'
    if (cfg%rolling%on) buf = trim(buf)//'; with the rolling stage'
    call add(trim(buf))

  contains

    subroutine add(line)
      character(len=*), intent(in) :: line
      wr%summary = [character(len=line_length) :: wr%summary, line]
    end subroutine add

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

  end subroutine run_wheel_rail_case

  !> The case's files: wheel_rail_file, and creep_file or rolling_file.
  subroutine write_wheel_rail_case(cfg, wr, status)
    type(config_t), intent(in) :: cfg
    type(wheel_rail_case_t), intent(in) :: wr
    type(status_t), intent(inout) :: status
    call write_text_file(cfg%wheel_rail_file, wr%table, 'wheel_rail_file', status)
    if (cfg%fastsim_on .and. .not. status%failed()) call write_text_file(cfg%creep_file, wr%creep, 'creep_file', status)
    if (cfg%rolling%on .and. .not. status%failed()) &
      call write_text_file(cfg%rolling%rolling_file, wr%rolling, 'rolling_file', status)
    if (cfg%wheel_rail%wheelset .and. .not. status%failed()) &
      call write_text_file(cfg%wheelset_file, wr%wheelset, 'wheelset_file', status)
  end subroutine write_wheel_rail_case

  !> The summary's column names, each right-aligned over its column of summary_row.
  function summary_columns() result(line)
    character(len=:), allocatable :: line
    character(len=8), parameter :: names(15) = [character(len=8) :: 'shift', 'patch', 'kind', 'fn', 'delta', &
      'y_rail', 'y_wheel', 'r_wheel', 'c11', 'c22', 'c23', 'err11', 'err22', 'err23', 'verdict']
    integer, parameter :: widths(14) = [9, 6, 7, 11, 10, 10, 10, 10, 9, 9, 9, 9, 9, 9]
    integer :: k
    line = ''
    do k = 1, 14
      line = line//repeat(' ', widths(k) - len_trim(names(k)))//trim(names(k))
    end do
    line = line//' '//trim(names(15))
  end function summary_columns

  !> One row of the summary: every number in a field of its own that starts
  !> with a blank, in fixed notation where it fits and in ES notation where it
  !> does not, so no two numbers ever run together and none turns into '***'.
  function summary_row(r) result(line)
    type(wheel_rail_row_t), intent(in) :: r
    character(len=:), allocatable :: line
    character(len=16) :: buf
    integer :: k
    line = cell(r%shift, 9, 2)
    write (buf, '(i6)') r%patch
    line = line//buf(1:6)//repeat(' ', 7 - len_trim(r%kind))//trim(r%kind)
    write (buf, '(es11.3)') r%fn     ! (1x, es10.3: holds any sign and exponent up to 99)
    line = line//buf(1:11)//cell(r%delta, 10, 4)//cell(r%y_rail, 10, 3)//cell(r%y_wheel, 10, 3)// &
           cell(r%r_wheel, 10, 3)
    do k = 1, 3
      line = line//cell(r%c(k), 9, 3)
    end do
    do k = 1, 3
      write (buf, '(es9.1)') r%err(k)
      line = line//buf(1:9)
    end do
    line = line//' '//r%verdict
  end function summary_row

  !> x in exactly width characters, the first a blank: fixed with decimals
  !> digits where it fits, else ES with as many digits as fit (width >= 9:
  !> a sign, 'd.d' and a two-digit exponent: 8 characters and the blank).
  function cell(x, width, decimals) result(text)
    real(real64), intent(in) :: x
    integer, intent(in) :: width, decimals
    character(len=width) :: text
    character(len=40) :: form
    write (form, '(a, i0, a, i0, a)') '(1x, f', width - 1, '.', decimals, ')'
    write (text, form) x
    if (index(text, '*') > 0) then
      write (form, '(a, i0, a, i0, a)') '(1x, es', width - 1, '.', max(width - 8, 1), ')'
      write (text, form) x
    end if
  end function cell

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

end module kcreep_app_wheel_rail
