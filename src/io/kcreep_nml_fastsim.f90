!> The &fastsim group: creep-force curves with friction (FASTSIM) on the patch.
module kcreep_nml_fastsim
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, lower, resolve_path, folder_of
  use kcreep, only: source_names, flexibility_rule_of
  use kcreep_nml_config, only: config_t, input_where, default_output_name, unset, max_creepages, creepage_points, &
                               pressure_source, check_pressure_use
  implicit none
  private
  public :: fastsim_variables, fastsim_group_t, read_fastsim_group, apply_fastsim_group

  !> The group as written (unset: not given).
  type :: fastsim_group_t
    real(real64) :: mu = unset, fn = unset, l1 = 0, l2 = 0, l3 = 0, sweep_direction(3) = 0, sweep_from = 0, &
                    sweep_to = 0
    real(real64), allocatable :: creepages(:)
    integer :: sweep_points = 0
    character(len=16) :: sweep_spacing = 'linear', rule = 'aligned', pressure = 'auto'
    character(len=128) :: flexibility = 'exact'
    character(len=4096) :: pressure_input_file = ''
    logical :: maps = .false.
  end type fastsim_group_t

  !> The group's variables and their types, as in its namelist statement
  !> (kcreep_namelist_scan diagnose_group explains a failed read with them).
  character(len=*), parameter :: fastsim_variables(16) = [character(len=29) :: &
    'mu real', 'creepages real list', 'sweep_direction real 3', 'sweep_from real', 'sweep_to real', &
    'sweep_points integer', 'sweep_spacing character', 'pressure character', &
    'pressure_input_file character', 'fn real', 'flexibility character', 'l1 real', 'l2 real', 'l3 real', &
    'rule character', 'maps logical']

contains

  subroutine read_fastsim_group(unit, grp, ios, msg)
    integer, intent(in) :: unit
    type(fastsim_group_t), intent(out) :: grp
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    real(real64) :: mu, fn, l1, l2, l3, sweep_direction(3), sweep_from, sweep_to
    real(real64), allocatable :: creepages(:)
    integer :: sweep_points
    character(len=16) :: sweep_spacing, rule, pressure
    character(len=128) :: flexibility
    character(len=4096) :: pressure_input_file
    logical :: maps
    namelist /fastsim/ mu, creepages, sweep_direction, sweep_from, sweep_to, sweep_points, sweep_spacing, &
                       pressure, pressure_input_file, fn, flexibility, l1, l2, l3, rule, maps

    allocate (creepages(3 * max_creepages))   ! more values: the read fails, diagnose_group counts them
    creepages = unset
    mu = grp%mu
    fn = grp%fn
    l1 = grp%l1
    l2 = grp%l2
    l3 = grp%l3
    sweep_direction = grp%sweep_direction
    sweep_from = grp%sweep_from
    sweep_to = grp%sweep_to
    sweep_points = grp%sweep_points
    sweep_spacing = grp%sweep_spacing
    rule = grp%rule
    pressure = grp%pressure
    flexibility = grp%flexibility
    pressure_input_file = grp%pressure_input_file
    maps = grp%maps
    read (unit, nml=fastsim, iostat=ios, iomsg=msg)
    grp%mu = mu
    grp%fn = fn
    grp%l1 = l1
    grp%l2 = l2
    grp%l3 = l3
    grp%sweep_direction = sweep_direction
    grp%sweep_from = sweep_from
    grp%sweep_to = sweep_to
    grp%sweep_points = sweep_points
    grp%sweep_spacing = sweep_spacing
    grp%rule = rule
    grp%pressure = pressure
    grp%flexibility = flexibility
    grp%pressure_input_file = pressure_input_file
    grp%maps = maps
    call move_alloc(creepages, grp%creepages)
  end subroutine read_fastsim_group

  !> Store &fastsim in cfg and check it (cfg's &patch, &solver and &output
  !> applied): friction, creepages (list and sweep), pressure, flexibility
  !> sources, rule. Without the group, nothing of FASTSIM runs.
  subroutine apply_fastsim_group(grp, present, cfg, status)
    type(fastsim_group_t), intent(in) :: grp
    logical, intent(in) :: present            !< the group was written
    type(config_t), intent(inout) :: cfg
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: where, word
    character(len=len(grp%flexibility)) :: rest
    integer :: k, cut, s

    cfg%fastsim_on = present
    cfg%pressure_input_file = resolve_path(trim(grp%pressure_input_file), folder_of(cfg%input_path))
    ! (like the default table, the default maps go to the working folder)
    if (grp%maps .and. len(cfg%creep_map_file) == 0) cfg%creep_map_file = default_output_name(cfg%input_path, &
                                                                                              '.creepmap')
    if (.not. present) return
    where = input_where(cfg)//'&fastsim '
    if (grp%mu == unset) then
      call fail(status, exit_bad_input, where//'mu is required (the friction coefficient, > 0)')
      return
    end if
    if (.not. (grp%mu > 0 .and. grp%mu <= 1e3_real64)) then
      call fail(status, exit_bad_input, where//'mu = '//rtoa(grp%mu)//' (allowed: 0 < mu <= 1000)')
      return
    end if
    cfg%fastsim%mu = grp%mu
    call creepage_points(grp%creepages, grp%sweep_direction, grp%sweep_from, grp%sweep_to, grp%sweep_points, &
                         grp%sweep_spacing, max_creepages, where, cfg%fastsim%creepages, status)
    if (status%failed()) return

    cfg%fastsim%rule = flexibility_rule_of(lower(trim(adjustl(grp%rule))))
    if (cfg%fastsim%rule == 0) then
      call fail(status, exit_bad_input, where//'rule = '''//trim(grp%rule)// &
                ''' (allowed: ''aligned'', ''separate'', ''weighted'')')
      return
    end if

    cfg%fastsim%sources = .false.
    rest = lower(grp%flexibility)
    do
      rest = adjustl(rest)
      if (len_trim(rest) == 0) exit
      cut = scan(rest, ' ,')
      if (cut == 0) cut = len(rest) + 1
      word = trim(rest(1:cut - 1))
      rest = rest(min(cut + 1, len(rest) + 1):)
      if (len(word) == 0) cycle
      select case (word)
      case ('ellipse')
        cfg%fastsim%sources(2:3) = .true.
      case ('all')
        cfg%fastsim%sources(1:3) = .true.
      case default
        ! (a loop: gfortran 12's findloc can miss a deferred-length scalar)
        s = 0
        do k = 1, size(source_names)
          if (source_names(k) == word) s = k
        end do
        if (s == 0) then
          call fail(status, exit_bad_input, where//'flexibility: unknown source '''//word//''' (allowed: '// &
                    '''exact'', ''ellipse-box'', ''ellipse-moments'', ''ellipse'' (both), ''all'', ''user'')')
          return
        end if
        cfg%fastsim%sources(s) = .true.
      end select
    end do
    if (.not. any(cfg%fastsim%sources)) then
      call fail(status, exit_bad_input, where//'flexibility is empty (allowed: exact, ellipse-box, '// &
                'ellipse-moments, ellipse, all, user)')
      return
    end if
    if (cfg%fastsim%sources(4)) then
      if (.not. (grp%l1 > 0 .and. grp%l2 > 0 .and. grp%l3 > 0 .and. max(grp%l1, grp%l2, grp%l3) <= huge(1.0_real64))) then
        call fail(status, exit_bad_input, where//'flexibility = ''user'' needs l1, l2, l3 > 0 (given '// &
                  rtoa(grp%l1)//', '//rtoa(grp%l2)//', '//rtoa(grp%l3)//')')
        return
      end if
      cfg%fastsim%user_flex = [grp%l1, grp%l2, grp%l3]
    else if (grp%l1 /= 0 .or. grp%l2 /= 0 .or. grp%l3 /= 0) then
      call fail(status, exit_bad_input, where//'l1, l2, l3 are used by flexibility = ''user'' only')
      return
    end if
    cfg%fastsim%maps = grp%maps .or. len(cfg%creep_map_file) > 0

    call pressure_source(grp%pressure, cfg%shape, cfg%wheel_rail_on, grp%maps .or. len(cfg%creep_map_file) > 0, &
                         'creep', cfg%pressure_input_file, where, cfg%pressure, status)
    if (status%failed()) return
    call check_pressure_use(cfg%pressure, grp%fn, cfg%extrapolate, 'FASTSIM', where, status)
    if (status%failed()) return
    if (grp%fn /= unset) cfg%fn = grp%fn
  end subroutine apply_fastsim_group
end module kcreep_nml_fastsim
