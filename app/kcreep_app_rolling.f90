!> &rolling of a single case: the normal pressure from its source, the exact
!> rolling forces with friction on the solved patch (kcreep_rolling_curve),
!> the lines of the rolling table and maps, and the summary lines; with
!> &fastsim given too, FASTSIM's largest distance from the exact forces per
!> flexibility source, and the fast force model's (kcreep_fast_build), at the
!> rolling points.
module kcreep_app_rolling
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t
  use kcreep_namelist, only: config_t
  use kcreep_table, only: run_record_t
  use kcreep, only: creep_request_t, creep_point_t, creep_map_t, creep_curve, source_names, rolling_point_t, &
                    rolling_curve, flexibility_rule_name, rolling_state_t, release_rolling_state, fast_forces_t, &
                    build_fast_forces, fast_forces_of
  use kcreep_rolling_table, only: rolling_lines, rolling_map_lines
  use kcreep_app_fastsim, only: source_pressure
  use kcreep_threads, only: team_size, enter_team, leave_team, cells_per_thread_iterative
  implicit none
  private
  public :: run_rolling

  !> The largest patch whose fast force model the summary builds (one thread: 0.5-1.8 s up
  !> to 1300 cells, 2-3 s at 1600-1800, 7 s at 4000 on two levels; docs/rolling.md).
  integer, parameter :: fast_model_cells = 4000

contains

  pure function label_of(pressure, file) result(label)
    character(len=*), intent(in) :: pressure, file
    character(len=:), allocatable :: label
    select case (pressure)
    case ('hertz')
      label = 'hertz (semi-ellipsoid, Fn given)'
    case ('contact')
      label = 'contact (PN of the element file)'
    case ('file')
      label = 'file '''//file//''''
    case ('normal')
      label = 'normal (the pressure of the normal contact problem)'
    case default
      label = 'parabolic (MODEL: a parabola per strip segment scaled to Fn, not a normal solve)'
    end select
  end function label_of

  subroutine run_rolling(cfg, record, lines, map_lines, summary, warnings, status)
    type(config_t), intent(in) :: cfg
    type(run_record_t), intent(in) :: record
    character(len=400), allocatable, intent(out) :: lines(:)
    character(len=200), allocatable, intent(out) :: map_lines(:)
    character(len=200), allocatable, intent(out) :: summary(:)
    character(len=200), allocatable, intent(out) :: warnings(:)
    type(status_t), intent(inout) :: status
    integer :: previous_team
    real(real64), allocatable :: pn(:, :)
    type(rolling_point_t), allocatable :: points(:)
    type(creep_map_t), allocatable :: maps(:), fmaps(:)
    type(creep_point_t), allocatable :: fpoints(:)
    type(creep_request_t) :: frequest
    real(real64) :: worst(size(source_names)), mufn, seconds
    real(real64), allocatable :: fast_force(:, :)
    type(rolling_state_t) :: state
    type(fast_forces_t) :: fast
    character(len=200) :: buf
    integer :: k, s, q

    allocate (warnings(0))
    call source_pressure('rolling', cfg%rolling%pressure, cfg%rolling%pressure_input_file, cfg%rolling%fn, cfg, &
                         record, pn, warnings, status)
    if (status%failed()) return
    ! the team of the solves (automatic: one thread below cells_per_thread_iterative)
    call enter_team(team_size(cfg%solve%threads, int(record%patch%n, int64), cells_per_thread_iterative), previous_team)
    if (allocated(record%traction)) then
      call rolling_curve(record%patch, cfg%scheme, record%nu, record%g, record%spin_centre, pn, cfg%rolling%request, &
                         points, maps, status, record%traction)
    else
      call rolling_curve(record%patch, cfg%scheme, record%nu, record%g, record%spin_centre, pn, cfg%rolling%request, &
                         points, maps, status)
    end if
    call leave_team(previous_team)
    if (status%failed()) return
    lines = rolling_lines(record%case_name, cfg%rolling%request, label_of(cfg%rolling%pressure, &
                          cfg%rolling%pressure_input_file), points)
    if (cfg%rolling%request%maps) then
      map_lines = rolling_map_lines(record%patch, pn, points, maps)
    else
      allocate (map_lines(0))
    end if
    seconds = sum(points%seconds)
    allocate (summary(2))
    write (summary(1), '(a, i0, a, es10.3, a, f9.4, a, i0, a, f6.2, a, f7.1, a)') 'exact rolling: ', size(points), &
      ' creepage points, mu = ', cfg%rolling%request%mu, ', ', seconds, ' s on ', maxval([1, points%threads]), &
      ' thread(s); Newton steps per point ', &
      real(sum(points%info%newton), real64) / max(1, size(points)), ', operator products per point ', &
      real(sum(points%info%products), real64) / max(1, size(points)), ''
    write (summary(2), '(a, es9.2, a)') '  largest residual max|F|/max(mu pn) ', maxval(points%info%residual), &
      '; rolling table: '//cfg%rolling%rolling_file
    if (cfg%rolling%request%maps) summary = [character(len=200) :: summary, &
                                              '  rolling maps: '//cfg%rolling%rolling_map_file]
    ! FASTSIM at the rolling points, with rolling's mu and pressure: how far from exact
    if (cfg%fastsim_on) then
      frequest = cfg%fastsim
      frequest%mu = cfg%rolling%request%mu
      frequest%creepages = cfg%rolling%request%creepages
      frequest%maps = .false.
      call creep_curve(record%result_t, pn, frequest, fpoints, fmaps)
      worst = 0
      do q = 1, size(fpoints)
        k = (q - 1) / count(frequest%sources) + 1
        mufn = frequest%mu * points(k)%force%fn
        worst(fpoints(q)%source) = max(worst(fpoints(q)%source), hypot(fpoints(q)%force%fx - points(k)%force%fx, &
                                       fpoints(q)%force%fy - points(k)%force%fy) / mufn)
      end do
      do s = 1, size(source_names)
        if (.not. frequest%sources(s)) cycle
        write (buf, '(a, f8.3, a)') '  FASTSIM ('//flexibility_rule_name(frequest%rule)//', L of '// &
          trim(source_names(s))//') against exact: largest |F - F_exact| =', 100 * worst(s), &
          ' % of mu Fn over the rolling points'
        summary = [character(len=200) :: summary, buf]
      end do
      ! the fast force model of this patch and pressure at the same points
      if (record%patch%n > fast_model_cells) then
        write (buf, '(a, i0, a, i0, a)') '  fast model: not built (', record%patch%n, ' cells, more than ', &
          fast_model_cells, ')'
        summary = [character(len=200) :: summary, buf]
        return
      end if
      call enter_team(team_size(cfg%solve%threads, int(record%patch%n, int64), cells_per_thread_iterative), &
                      previous_team)
      call build_fast_forces(record%patch, cfg%scheme, record%nu, record%g, record%spin_centre, pn, state, fast, &
                             status)
      call leave_team(previous_team)
      call release_rolling_state(state)
      if (status%failed()) return
      allocate (fast_force(3, size(points)))
      call fast_forces_of(fast, cfg%rolling%request%mu, cfg%rolling%request%creepages, fast_force)
      mufn = 0
      do k = 1, size(points)
        mufn = max(mufn, hypot(fast_force(1, k) - points(k)%force%fx, fast_force(2, k) - points(k)%force%fy) / &
                   (cfg%rolling%request%mu * points(k)%force%fn))
      end do
      write (buf, '(a, f8.3, a, i0, a, f4.1, a, f6.2, a)') '  fast model against exact: largest |F - F_exact| =', &
        100 * mufn, ' % of mu Fn over the rolling points (', fast%solves, ' exact points, ', &
        real(fast%newton, real64) / max(fast%solves, 1), ' Newton steps each, built in ', fast%seconds, ' s)'
      summary = [character(len=200) :: summary, buf]
    end if
  end subroutine run_rolling

end module kcreep_app_rolling
