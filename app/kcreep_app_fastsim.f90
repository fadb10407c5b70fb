!> &fastsim of a single case: the normal pressure from its source, FASTSIM's
!> creep-force curve on the solved patch, the lines of the creep table and
!> of the maps, and the summary lines.
module kcreep_app_fastsim
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_namelist, only: config_t
  use kcreep_table, only: run_record_t
  use kcreep, only: hertz_pressure, strip_parabolic_pressure, creep_point_t, creep_map_t, creep_curve, source_names, &
                    flexibility_rule_name
  use kcreep_pressure_file, only: read_pressure_file
  use kcreep_creep_table, only: creep_lines, creep_map_lines
  implicit none
  private
  public :: run_fastsim, pressure_label, source_pressure

contains

  !> A word for the pressure source, as the creep table and the summary name it.
  pure function pressure_label(cfg) result(label)
    type(config_t), intent(in) :: cfg
    character(len=:), allocatable :: label
    select case (cfg%pressure)
    case ('hertz')
      label = 'hertz (semi-ellipsoid, Fn given)'
    case ('contact')
      label = 'contact (PN of the element file)'
    case ('file')
      label = 'file '''//cfg%pressure_input_file//''''
    case ('normal')
      label = 'normal (the pressure of the normal contact problem)'
    case default
      label = 'parabolic (MODEL: a parabola per strip segment scaled to Fn, not a normal solve)'
    end select
  end function pressure_label

  !> The normal pressure (mx, my) on record's patch from its source ('hertz',
  !> 'contact', 'file', 'normal', 'parabolic'); &fastsim and &rolling share it
  !> (who: the group's name in the warning).
  subroutine source_pressure(who, pressure, pressure_file, fn, cfg, record, pn, warnings, status)
    character(len=*), intent(in) :: who, pressure, pressure_file
    real(real64), intent(in) :: fn
    type(config_t), intent(in) :: cfg
    type(run_record_t), intent(in) :: record
    real(real64), allocatable, intent(out) :: pn(:, :)
    character(len=200), allocatable, intent(inout) :: warnings(:)
    type(status_t), intent(inout) :: status
    integer :: k
    associate (p => record%patch)
      select case (pressure)
      case ('hertz')
        pn = hertz_pressure(p%inside, p%dx, p%dy, p%x0, p%y0, p%semi_a, p%semi_b, fn)
      case ('contact')
        pn = cfg%contact%pn
      case ('file')
        call read_pressure_file(pressure_file, p, pn, status)
        if (status%failed()) return
      case ('normal')
        ! the normal solve's pressure, per patch cell, onto the patch's grid
        if (.not. (record%normal_solved .and. allocated(record%pressure))) then
          call fail(status, exit_bad_input, who//' pressure = ''normal'': this case solved no normal problem')
          return
        end if
        allocate (pn(p%mx, p%my))
        pn = 0
        do k = 1, p%n
          pn(p%ix(k), p%iy(k)) = record%pressure(k)
        end do
      case default
        pn = strip_parabolic_pressure(p%inside, p%dx, p%dy, fn)
        warnings = [character(len=200) :: warnings, who//' pressure: the parabolic strip MODEL (no normal solve, '// &
                    'no pressure given): forces beyond the linear range depend on it']
      end select
    end associate
  end subroutine source_pressure

  !> FASTSIM for every creepage and source of cfg%fastsim on record's patch.
  !> lines: the creep table; map_lines: the maps (empty unless requested);
  !> summary: lines for the case's summary; warnings: to standard error too.
  subroutine run_fastsim(cfg, record, lines, map_lines, summary, warnings, status)
    type(config_t), intent(in) :: cfg
    type(run_record_t), intent(in) :: record
    character(len=400), allocatable, intent(out) :: lines(:)
    character(len=200), allocatable, intent(out) :: map_lines(:)
    character(len=200), allocatable, intent(out) :: summary(:)
    character(len=200), allocatable, intent(out) :: warnings(:)
    type(status_t), intent(inout) :: status
    real(real64), allocatable :: pn(:, :)
    type(creep_point_t), allocatable :: points(:)
    type(creep_map_t), allocatable :: maps(:)
    integer :: ns, k, s, ref
    real(real64) :: worst(size(source_names)), mufn
    character(len=200) :: buf
    integer(int64) :: t0, t1, rate

    allocate (warnings(0))
    call source_pressure('FASTSIM', cfg%pressure, cfg%pressure_input_file, cfg%fn, cfg, record, pn, warnings, status)
    if (status%failed()) return
    call system_clock(t0, rate)
    call creep_curve(record%result_t, pn, cfg%fastsim, points, maps)
    call system_clock(t1)
    lines = creep_lines(record%case_name, record%result_t, cfg%fastsim, pressure_label(cfg), points)
    if (cfg%fastsim%maps) then
      map_lines = creep_map_lines(record%patch, pn, points, maps)
    else
      allocate (map_lines(0))
    end if

    ! summary: the points, and for each other source its largest force difference to the exact L
    ns = count(cfg%fastsim%sources)
    allocate (summary(2))
    write (summary(1), '(a, i0, a, i0, a, es10.3, a, f8.4, a)') 'FASTSIM: ', size(cfg%fastsim%creepages, 2), &
      ' creepage points x ', ns, ' flexibility source(s), mu = ', cfg%fastsim%mu, &
      ', rule '//flexibility_rule_name(cfg%fastsim%rule)//', ', real(t1 - t0, real64) / rate, ' s'
    summary(2) = '  pressure '//pressure_label(cfg)//'; creep table: '//cfg%creep_file
    if (cfg%fastsim%sources(1) .and. ns > 1) then
      worst = 0
      do k = 1, size(points)
        if (points(k)%source /= 1) cycle
        ref = k
        do s = k + 1, min(k + ns - 1, size(points))
          mufn = cfg%fastsim%mu * points(ref)%force%fn
          worst(points(s)%source) = max(worst(points(s)%source), hypot(points(s)%force%fx - points(ref)%force%fx, &
            points(s)%force%fy - points(ref)%force%fy) / mufn)
        end do
      end do
      do s = 2, size(source_names)
        if (.not. cfg%fastsim%sources(s)) cycle
        write (buf, '(a, f8.3, a)') '  FASTSIM with L of '//trim(source_names(s))//': largest |F - F(exact L)| =', &
          100 * worst(s), ' % of mu Fn over the points'
        summary = [summary, buf]
      end do
    end if
  end subroutine run_fastsim

end module kcreep_app_fastsim
