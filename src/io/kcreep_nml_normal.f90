!> The &normal group: the normal contact problem of shape = 'gap' (the
!> undeformed distance, the load, the bodies' material).
module kcreep_nml_normal
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, resolve_path, folder_of
  use kcreep_limits, only: check_grid_size
  use kcreep, only: normal_options_t, polynomial_gap_t, gap_from_polynomial, auto_grid
  use kcreep_hertz, only: hertz_t, hertz_from_force
  use kcreep_normal_influence, only: compliance_from_g_nu, compliance_from_e_nu, combined_g_nu_from_e_nu
  use kcreep_contact_reader, only: combined_material
  use kcreep_contact_input, only: contact_input_t, read_contact_input
  use kcreep_gap_file, only: read_gap_file
  use kcreep_nml_config, only: config_t, input_where, unset
  implicit none
  private
  public :: normal_variables, normal_group_t, read_normal_group, apply_normal_group, load_gap

  !> The group as written (unset: not given).
  type :: normal_group_t
    character(len=4096) :: gap_file = '', contact_inp = ''
    integer :: contact_inp_case = 1, cells_across = 60, normal_max_iterations = 0
    real(real64) :: rx = 0, ry = 0, lx = 0, ly = 0, cx = 0, cy = 0, approach = unset, normal_force = unset, &
                    margin = 0.2_real64, e1 = unset, nu1 = unset, e2 = unset, nu2 = unset, normal_tolerance = unset
  end type normal_group_t

  !> The group's variables and their types, as in its namelist statement
  !> (kcreep_namelist_scan diagnose_group explains a failed read with them).
  character(len=*), parameter :: normal_variables(19) = [character(len=29) :: &
    'gap_file character', 'contact_inp character', 'contact_inp_case integer', 'rx real', 'ry real', &
    'lx real', 'ly real', 'cx real', 'cy real', 'approach real', 'normal_force real', &
    'cells_across integer', 'margin real', 'e1 real', 'nu1 real', 'e2 real', 'nu2 real', &
    'normal_tolerance real', 'normal_max_iterations integer']

contains

  subroutine read_normal_group(unit, grp, ios, msg)
    integer, intent(in) :: unit
    type(normal_group_t), intent(out) :: grp
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    character(len=4096) :: gap_file, contact_inp
    integer :: contact_inp_case, cells_across, normal_max_iterations
    real(real64) :: rx, ry, lx, ly, cx, cy, approach, normal_force, margin, e1, nu1, e2, nu2, normal_tolerance
    type(normal_options_t) :: defaults
    namelist /normal/ gap_file, contact_inp, contact_inp_case, rx, ry, lx, ly, cx, cy, approach, normal_force, &
                      cells_across, margin, e1, nu1, e2, nu2, normal_tolerance, normal_max_iterations

    grp%normal_tolerance = unset
    grp%normal_max_iterations = defaults%max_iterations
    gap_file = grp%gap_file
    contact_inp = grp%contact_inp
    contact_inp_case = grp%contact_inp_case
    cells_across = grp%cells_across
    normal_max_iterations = grp%normal_max_iterations
    rx = grp%rx
    ry = grp%ry
    lx = grp%lx
    ly = grp%ly
    cx = grp%cx
    cy = grp%cy
    approach = grp%approach
    normal_force = grp%normal_force
    margin = grp%margin
    e1 = grp%e1
    nu1 = grp%nu1
    e2 = grp%e2
    nu2 = grp%nu2
    normal_tolerance = grp%normal_tolerance
    read (unit, nml=normal, iostat=ios, iomsg=msg)
    grp%gap_file = gap_file
    grp%contact_inp = contact_inp
    grp%contact_inp_case = contact_inp_case
    grp%cells_across = cells_across
    grp%normal_max_iterations = normal_max_iterations
    grp%rx = rx
    grp%ry = ry
    grp%lx = lx
    grp%ly = ly
    grp%cx = cx
    grp%cy = cy
    grp%approach = approach
    grp%normal_force = normal_force
    grp%margin = margin
    grp%e1 = e1
    grp%nu1 = nu1
    grp%e2 = e2
    grp%nu2 = nu2
    grp%normal_tolerance = normal_tolerance
  end subroutine read_normal_group

  !> Store &normal in cfg and check it: only with shape = 'gap', one gap
  !> source, one of approach and normal_force, the material either in
  !> &material or per body (cfg's &patch and &material applied).
  subroutine apply_normal_group(grp, present, cfg, status)
    type(normal_group_t), intent(in) :: grp
    logical, intent(in) :: present            !< the group was written
    type(config_t), intent(inout) :: cfg
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: where
    real(real64) :: body(4)
    integer :: sources
    type(normal_options_t) :: defaults

    where = input_where(cfg)
    cfg%gap_file = resolve_path(trim(grp%gap_file), folder_of(cfg%input_path))
    cfg%contact_inp = resolve_path(trim(grp%contact_inp), folder_of(cfg%input_path))
    cfg%contact_inp_case = grp%contact_inp_case
    cfg%poly = polynomial_gap_t(rx=grp%rx, ry=grp%ry, lx=grp%lx, ly=grp%ly, cx=grp%cx, cy=grp%cy)
    cfg%approach_given = grp%approach /= unset
    cfg%force_given = grp%normal_force /= unset
    if (cfg%approach_given) cfg%approach = grp%approach
    if (cfg%force_given) cfg%normal_force = grp%normal_force
    cfg%cells_across = grp%cells_across
    cfg%margin = grp%margin
    cfg%normal%options%tolerance_given = grp%normal_tolerance /= unset
    cfg%normal%options%tolerance = merge(grp%normal_tolerance, defaults%tolerance, &
                                         cfg%normal%options%tolerance_given)
    cfg%normal%options%max_iterations = grp%normal_max_iterations
    body = [grp%e1, grp%nu1, grp%e2, grp%nu2]

    if (cfg%shape /= 'gap') then
      if (present) call fail(status, exit_bad_input, where//'&normal is only read with &patch shape = '// &
                             '''gap'' (shape = '''//cfg%shape//''')')
      return
    end if
    sources = count([len(cfg%gap_file) > 0, len(cfg%contact_inp) > 0, cfg%poly%rx /= 0 .or. cfg%poly%ry /= 0])
    if (sources /= 1) then
      call fail(status, exit_bad_input, where//'&normal: give exactly one undeformed distance: gap_file, '// &
                'contact_inp, or the principal radii rx and ry (given: '//itoa(sources)//')')
      return
    end if
    if (len(cfg%contact_inp) > 0) then
      if (cfg%approach_given .or. cfg%force_given) call fail(status, exit_bad_input, where// &
          '&normal: approach and normal_force come from contact_inp (PEN or FN; leave them out)')
      if (cfg%material_given .or. body(1) /= unset) call fail(status, exit_bad_input, where// &
          '&material g, nu and &normal e1, nu1, e2, nu2 are not allowed with contact_inp (its GG and POISS are used)')
      if (cfg%contact_inp_case < 1) call fail(status, exit_bad_input, where//'&normal contact_inp_case = '// &
          itoa(cfg%contact_inp_case)//' (must be >= 1)')
      return
    end if
    if (cfg%approach_given .eqv. cfg%force_given) then
      call fail(status, exit_bad_input, where//'&normal: give exactly one of approach and normal_force')
    else if (cfg%force_given .and. .not. (cfg%normal_force > 0 .and. cfg%normal_force < 1e300_real64)) then
      call fail(status, exit_bad_input, where//'&normal normal_force = '//rtoa(cfg%normal_force)// &
                ' (must be > 0)')
    else if (cfg%approach_given .and. .not. (abs(cfg%approach) < 1e30_real64)) then
      call fail(status, exit_bad_input, where//'&normal approach = '//rtoa(cfg%approach)//' (|approach| < 1e30)')
    end if
    if (len(cfg%gap_file) == 0) then
      if (.not. (cfg%poly%rx > 0 .and. cfg%poly%ry > 0 .and. cfg%poly%rx < 1e30_real64 .and. &
                 cfg%poly%ry < 1e30_real64)) call fail(status, exit_bad_input, where//'&normal rx, ry = '// &
          rtoa(cfg%poly%rx)//', '//rtoa(cfg%poly%ry)//' (principal relative radii: both > 0 and < 1e30)')
      if (any(abs([cfg%poly%lx, cfg%poly%ly, cfg%poly%cx, cfg%poly%cy]) >= 1e30_real64)) &
        call fail(status, exit_bad_input, where//'&normal lx, ly, cx, cy: each |value| < 1e30')
    else if (cfg%mx /= 0 .or. cfg%my /= 0 .or. cfg%dx /= 0 .or. cfg%dy /= 0 .or. cfg%x0 /= 0 .or. cfg%y0 /= 0) then
      call fail(status, exit_bad_input, where//'&patch mx, my, dx, dy, x0, y0: the grid comes from gap_file''s '// &
                'header (leave them out)')
    end if
    if (cfg%cells_across < 2 .or. cfg%cells_across > 2000) call fail(status, exit_bad_input, where// &
        '&normal cells_across = '//itoa(cfg%cells_across)//' (allowed: 2 to 2000)')
    if (.not. (cfg%margin >= 0 .and. cfg%margin <= 10)) call fail(status, exit_bad_input, where// &
        '&normal margin = '//rtoa(cfg%margin)//' (allowed: 0 to 10, a fraction of the interpenetration size)')
    if (.not. (cfg%normal%options%tolerance > 0 .and. cfg%normal%options%tolerance < 1)) &
      call fail(status, exit_bad_input, where//'&normal normal_tolerance = '//rtoa(cfg%normal%options%tolerance)// &
                ' (allowed: 0 < tolerance < 1)')
    if (cfg%normal%options%max_iterations < 1) call fail(status, exit_bad_input, where// &
        '&normal normal_max_iterations = '//itoa(cfg%normal%options%max_iterations)//' (must be >= 1)')
    if (any(body /= unset)) then
      if (cfg%material_given) then
        call fail(status, exit_bad_input, where//'give the material either in &material (g, nu) or per body '// &
                  'in &normal (e1, nu1, e2, nu2), not both')
      else if (any(body == unset)) then
        call fail(status, exit_bad_input, where//'&normal e1, nu1, e2, nu2: give all four')
      else if (.not. (body(1) > 0 .and. body(3) > 0 .and. body(1) < 1e100_real64 .and. body(3) < 1e100_real64)) then
        call fail(status, exit_bad_input, where//'&normal e1, e2 = '//rtoa(body(1))//', '//rtoa(body(3))// &
                  ' (Young''s moduli: > 0)')
      else if (.not. (body(2) >= 0 .and. body(2) <= 0.5_real64 .and. body(4) >= 0 .and. body(4) <= 0.5_real64)) then
        call fail(status, exit_bad_input, where//'&normal nu1, nu2 = '//rtoa(body(2))//', '//rtoa(body(4))// &
                  ' (allowed: 0 to 0.5)')
      else
        cfg%e = [body(1), body(3)]
        cfg%poisson = [body(2), body(4)]
        call combined_g_nu_from_e_nu(body(1), body(2), body(3), body(4), cfg%g, cfg%nu)
      end if
    end if
  end subroutine apply_normal_group

  !> shape = 'gap': the undeformed distance on its grid (gap_file, contact_inp,
  !> or the polynomial on the &patch grid or on an automatic one), the load and
  !> the combined compliance, into cfg%normal.
  subroutine load_gap(cfg, status)
    type(config_t), intent(inout) :: cfg
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: where
    type(contact_input_t) :: inp
    type(hertz_t) :: hz
    real(real64) :: level, extent, dx, dy, x0, y0, compliance
    integer :: mx, my

    where = input_where(cfg)
    associate (np => cfg%normal)
      np%active = .true.
      if (len(cfg%contact_inp) > 0) then
        call read_contact_input(cfg%contact_inp, cfg%contact_inp_case, inp, status)
        if (status%failed()) return
        np%gap = inp%gap
        call combined_material(inp%gg, inp%poiss, cfg%g, cfg%nu)
        cfg%force_given = inp%norm == 1
        cfg%approach_given = .not. cfg%force_given
        cfg%approach = inp%pen
        cfg%normal_force = inp%fn
      else if (len(cfg%gap_file) > 0) then
        call read_gap_file(cfg%gap_file, np%gap, status)
        if (status%failed()) return
      end if
      if (cfg%e(1) > 0) then
        compliance = compliance_from_e_nu(cfg%e(1), cfg%poisson(1), cfg%e(2), cfg%poisson(2))
      else
        compliance = compliance_from_g_nu(cfg%g, cfg%nu)
      end if
      np%compliance = compliance
      if (len(cfg%contact_inp) == 0 .and. len(cfg%gap_file) == 0) then
        if (cfg%mx > 0 .and. cfg%my > 0 .and. cfg%dx > 0 .and. cfg%dy > 0) then
          mx = cfg%mx
          my = cfg%my
          dx = cfg%dx
          dy = cfg%dy
          x0 = cfg%x0
          y0 = cfg%y0
        else if (cfg%mx /= 0 .or. cfg%my /= 0 .or. cfg%dx /= 0 .or. cfg%dy /= 0) then
          call fail(status, exit_bad_input, where//'&patch mx, my, dx, dy: give all four (a grid for the gap) '// &
                    'or none (an automatic grid from &normal cells_across and margin)')
          return
        else
          ! the interpenetration area at the approach (or at Hertz's approach for the force)
          if (cfg%force_given) then
            hz = hertz_from_force(1 / (2 * cfg%poly%rx), 1 / (2 * cfg%poly%ry), compliance, cfg%normal_force)
            level = hz%approach
          else
            level = cfg%approach
          end if
          extent = 4 * sqrt(2 * max(cfg%poly%rx, cfg%poly%ry) * max(abs(level), tiny(level))) + &
                   2 * (abs(cfg%poly%lx) * cfg%poly%rx + abs(cfg%poly%ly) * cfg%poly%ry)
          call auto_grid(cfg%poly, level, extent, cfg%cells_across, cfg%margin, mx, my, dx, dy, x0, y0, status)
          if (status%failed()) then
            if (cfg%force_given) then
              status%message = where//'&normal: '//status%message
            else
              status%message = where//'&normal approach = '//rtoa(cfg%approach)//': the surfaces do not '// &
                               'interpenetrate (the undeformed distance from rx, ry, lx, ly, cx, cy is larger everywhere)'
            end if
            return
          end if
        end if
        call check_grid_size(mx, my, where//'&normal: the gap grid: ', status)
        if (status%failed()) return
        call gap_from_polynomial(cfg%poly, mx, my, dx, dy, x0, y0, np%gap, status)
        if (status%failed()) return
        np%poly_given = .true.
        np%poly = cfg%poly
      end if
      call check_grid_size(np%gap%mx, np%gap%my, where//'&normal: the gap grid: ', status)
      if (status%failed()) return
      np%force_given = cfg%force_given
      np%approach = cfg%approach
      np%normal_force = cfg%normal_force
      if (.not. np%force_given .and. .not. any(np%gap%h < np%approach)) then
        call fail(status, exit_bad_input, where//'&normal approach = '//rtoa(np%approach)// &
                  ': the surfaces do not interpenetrate (the smallest undeformed distance is '// &
                  rtoa(minval(np%gap%h))//'; the approach must exceed it)')
        return
      end if
      if (np%force_given .and. .not. (np%normal_force > 0)) then
        call fail(status, exit_bad_input, where//'normal force = '//rtoa(np%normal_force)//' (must be > 0)')
        return
      end if
    end associate
  end subroutine load_gap

end module kcreep_nml_normal
