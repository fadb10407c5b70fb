!> The namelist input: the file read group by group into the configuration,
!> the checks between groups, the patch and the library's problem.
!>
!> Groups &patch, &material, &solver, &output, &normal, &fastsim, &wheel_rail, each
!> optional and each in its own module (kcreep_nml_<group>: its variables,
!> defaults and checks). Anything out of range or inconsistent is reported
!> through status with the file, group, variable, value and what is
!> allowed, before any computation or output.
module kcreep_namelist
  use, intrinsic :: iso_fortran_env, only: real64, iostat_end
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: rtoa, itoa, resolve_path, folder_of, lower
  use kcreep, only: patch_t, ellipse_patch, mask_patch, problem_t, collocation_aspect_limit, max_wheel_rail_shifts
  use kcreep_refine_estimate, only: default_target_error
  use kcreep_mask_file, only: read_mask_file, parse_mask_rows
  use kcreep_contact_reader, only: read_contact_case, combined_material
  use kcreep_file_checks, only: read_input_file
  use kcreep_namelist_scan, only: scan_namelist_text, diagnose_group
  use kcreep_nml_config, only: config_t, input_where, unset, max_inline_rows, max_row_length, max_creepages, &
                               default_output_name
  use kcreep_nml_patch, only: patch_variables, patch_group_t, read_patch_group, apply_patch_group
  use kcreep_nml_material, only: material_variables, material_group_t, read_material_group, apply_material_group
  use kcreep_nml_solver, only: solver_variables, solver_group_t, read_solver_group, apply_solver_group
  use kcreep_nml_output, only: output_variables, output_group_t, read_output_group, apply_output_group
  use kcreep_nml_normal, only: normal_variables, normal_group_t, read_normal_group, apply_normal_group, load_gap
  use kcreep_nml_fastsim, only: fastsim_variables, fastsim_group_t, read_fastsim_group, apply_fastsim_group
  use kcreep_nml_wheel_rail, only: wheel_rail_variables, wheel_rail_group_t, read_wheel_rail_group, &
                                   apply_wheel_rail_group
  use kcreep_nml_rolling, only: read_rolling_group
  implicit none
  private
  public :: config_t, read_config, build_patch, problem_of, max_inline_rows, max_row_length, max_creepages
  public :: group_names, group_list

  character(len=*), parameter :: group_names(8) = [character(len=10) :: 'patch', 'material', 'solver', 'output', &
                                                     'normal', 'fastsim', 'wheel_rail', 'rolling']

contains

  !> '&patch, &material, ... and &fastsim': the groups an input may hold.
  pure function group_list() result(list)
    character(len=:), allocatable :: list
    integer :: k
    list = '&'//trim(group_names(1))
    do k = 2, size(group_names)
      if (k == size(group_names)) then
        list = list//' and &'//trim(group_names(k))
      else
        list = list//', &'//trim(group_names(k))
      end if
    end do
  end function group_list

  !> Read and validate the namelist at path. Relative file names inside it
  !> (mask_file, contact_file, table_file, traction_file) are taken relative
  !> to the namelist's own folder, whatever the working folder and the mode
  !> (single run, batch, memory estimate). Only the default table, which the
  !> namelist does not name, goes to the working folder.
  subroutine read_config(path, cfg, status)
    character(len=*), intent(in) :: path
    type(config_t), intent(out) :: cfg
    type(status_t), intent(inout) :: status
    type(patch_group_t) :: patch
    type(material_group_t) :: material
    type(solver_group_t) :: solver
    type(output_group_t) :: output
    type(normal_group_t) :: normal
    type(fastsim_group_t) :: fastsim
    type(wheel_rail_group_t) :: wheel_rail
    integer :: unit, ios
    logical :: present(size(group_names)), closed(size(group_names)), last_line_open
    character(len=512) :: msg
    character(len=:), allocatable :: text

    cfg%input_path = path
    ! the whole file first: a folder, a binary file, text outside the groups,
    ! unknown or repeated groups are errors the namelist read would not report
    call read_input_file(path, 'input '''//path//'''', text, status)
    if (.not. status%failed()) call scan_namelist_text(text, 'input '''//path//'''', group_names, present, &
                                                       closed, status)
    if (status%failed()) return
    ! a last line without its newline: the namelist read assigns the group and
    ! then meets the end of the file looking for the next record
    last_line_open = .false.
    if (len(text) > 0) last_line_open = text(len(text):len(text)) /= achar(10)
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_bad_input, 'input '''//path//''': cannot open ('//trim(msg)//')')
      return
    end if
    if (present(1)) then
      rewind (unit)
      call read_patch_group(unit, index(lower(text), 'mask_rows') > 0, patch, ios, msg)
      call check_read(1)
    end if
    if (present(2)) then
      rewind (unit)
      call read_material_group(unit, material, ios, msg)
      call check_read(2)
    end if
    if (present(3)) then
      rewind (unit)
      call read_solver_group(unit, solver, ios, msg)
      call check_read(3)
    end if
    if (present(4)) then
      rewind (unit)
      call read_output_group(unit, output, ios, msg)
      call check_read(4)
    end if
    if (present(5)) then
      rewind (unit)
      call read_normal_group(unit, normal, ios, msg)
      call check_read(5)
    end if
    if (present(6)) then
      rewind (unit)
      call read_fastsim_group(unit, fastsim, ios, msg)
      call check_read(6)
    end if
    if (present(7)) then
      rewind (unit)
      call read_wheel_rail_group(unit, wheel_rail, ios, msg)
      call check_read(7)
    end if
    if (status%failed()) then
      close (unit)
      return
    end if

    ! each group on its own, in the order their checks need
    if (.not. allocated(patch%mask_rows)) allocate (patch%mask_rows(0))
    call apply_patch_group(patch, cfg, status)
    if (.not. status%failed()) call apply_material_group(material, cfg, status)
    if (.not. status%failed()) call apply_output_group(output, cfg, status)
    if (.not. status%failed()) call apply_solver_group(solver, cfg, status)
    ! &wheel_rail finds its patches from the profiles, each patch a normal problem
    if (present(7) .and. any(present([1, 5])) .and. .not. status%failed()) call fail(status, exit_bad_input, &
        input_where(cfg)//'&wheel_rail finds its patches from the profiles: &patch and &normal are not read with it')
    if (.not. status%failed()) call apply_wheel_rail_group(wheel_rail, present(7), cfg, status)
    if (.not. status%failed()) call apply_fastsim_group(fastsim, present(6), cfg, status)
    if (.not. status%failed()) call apply_normal_group(normal, present(5), cfg, status)
    ! &rolling reads and checks its group itself, for the patch's shape
    if (present(8) .and. .not. status%failed()) then
      call read_rolling_group(unit, path, text, .true., closed(8) .and. last_line_open, cfg%shape, cfg%extrapolate, &
                              cfg%wheel_rail_on, cfg%rolling, status)
      if (.not. status%failed()) call apply_rolling_output(cfg, output%rolling_file, output%rolling_map_file, status)
      cfg%rolling%request%threads = cfg%solve%threads    ! &solver threads, for the rolling stage too
    end if
    close (unit)
    if (status%failed()) return
    call apply_error_control(cfg, status)
    ! a pressure file for &rolling is given on the mask's own grid: keep that grid
    if (cfg%rolling%on .and. cfg%shape == 'mask') then
      if (len(cfg%rolling%pressure_input_file) > 0) cfg%refine_grid = .false.
    end if
    if (status%failed()) return
    ! then what they name: CONTACT's case, the gap
    if (cfg%shape == 'contact') call load_contact_case(cfg, status)
    if (cfg%shape == 'gap' .and. .not. status%failed()) call load_gap(cfg, status)
    if (cfg%rolling%on .and. .not. status%failed()) then
      if (cfg%rolling%pressure == 'contact' .and. .not. allocated(cfg%contact%pn)) call fail(status, exit_bad_input, &
          input_where(cfg)//'&rolling pressure = ''contact'' needs the element file (.mat) of the case with its PN column')
    end if
    if (cfg%fastsim_on .and. cfg%pressure == 'contact' .and. .not. status%failed()) then
      if (.not. allocated(cfg%contact%pn)) call fail(status, exit_bad_input, input_where(cfg)// &
          '&fastsim pressure = ''contact'' needs the element file (.mat) of the case with its PN column')
    end if

  contains

    subroutine check_read(k)
      integer, intent(in) :: k
      character(len=:), allocatable :: why
      if (status%failed()) return
      if (ios == iostat_end .and. closed(k) .and. last_line_open) then
        ios = 0                           ! read whole: its / was there, the newline after it was not
      else if (ios == iostat_end) then
        call fail(status, exit_bad_input, 'input '''//path//''': namelist &'//trim(group_names(k))// &
                  ': end of file before the closing /')
      else if (ios /= 0) then
        ! the compiler's words ("Cannot match namelist object name '.5'") in the input's
        select case (k)
        case (1)
          why = diagnose_group(text, 'patch', patch_variables, max_inline_rows - 1)
        case (2)
          why = diagnose_group(text, 'material', material_variables)
        case (3)
          why = diagnose_group(text, 'solver', solver_variables)
        case (4)
          why = diagnose_group(text, 'output', output_variables)
        case (5)
          why = diagnose_group(text, 'normal', normal_variables)
        case (6)
          why = diagnose_group(text, 'fastsim', fastsim_variables, 3 * max_creepages)
        case default
          why = diagnose_group(text, 'wheel_rail', wheel_rail_variables, max_wheel_rail_shifts)
        end select
        if (len(why) == 0) why = '&'//trim(group_names(k))//': '//trim(msg)
        call fail(status, exit_bad_input, 'input '''//path//''': namelist '//why)
      end if
    end subroutine check_read

  end subroutine read_config

  !> &output's rolling_file [<input name>.roll] and rolling_map_file
  !> [<input name>.rollmap with maps; not with &wheel_rail] for &rolling, which
  !> needs the backward scheme.
  subroutine apply_rolling_output(cfg, rolling_file, rolling_map_file, status)
    type(config_t), intent(inout) :: cfg
    character(len=*), intent(in) :: rolling_file, rolling_map_file
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: folder
    folder = folder_of(cfg%input_path)
    cfg%rolling%rolling_file = resolve_path(trim(rolling_file), folder)
    if (len(cfg%rolling%rolling_file) == 0) cfg%rolling%rolling_file = default_output_name(cfg%input_path, '.roll')
    cfg%rolling%rolling_map_file = resolve_path(trim(rolling_map_file), folder)
    if (cfg%wheel_rail_on .and. len(cfg%rolling%rolling_map_file) > 0) call fail(status, exit_bad_input, &
        input_where(cfg)//'&output rolling_map_file with &wheel_rail: not available (the rolling table has each '// &
        'patch''s forces)')
    if (cfg%rolling%request%maps .and. len(cfg%rolling%rolling_map_file) == 0) &
      cfg%rolling%rolling_map_file = default_output_name(cfg%input_path, '.rollmap')
    cfg%rolling%request%maps = cfg%rolling%request%maps .or. len(cfg%rolling%rolling_map_file) > 0
    if (cfg%scheme%name /= 'backward') call fail(status, exit_bad_input, input_where(cfg)// &
        '&rolling needs &solver scheme = ''backward'' (scheme = '''//cfg%scheme%name//''')')
  end subroutine apply_rolling_output

  !> Error control, from &patch, &solver, &normal and &fastsim together: the
  !> default target, whether kcreep chooses the grids, the cell budget.
  subroutine apply_error_control(cfg, status)
    type(config_t), intent(inout) :: cfg
    type(status_t), intent(inout) :: status
    ! CONTACT's grid is compared as given (no target unless asked), so is the
    ! normal problem read from CONTACT's input; an ellipse without a grid and
    ! a mask are refined by kcreep to meet the target, a gap (gap_file, or
    ! rx, ry without a grid) by sampling its geometry on finer grids
    if (cfg%target_error == unset) cfg%target_error = merge(0.0_real64, default_target_error, &
        cfg%shape == 'contact' .or. (cfg%shape == 'gap' .and. len(cfg%contact_inp) > 0))
    ! a pressure file for FASTSIM is given on the mask's own grid: keep that grid
    cfg%refine_grid = (cfg%shape == 'ellipse' .and. .not. cfg%mx_my_given) .or. &
                      (cfg%shape == 'mask' .and. len(cfg%pressure_input_file) == 0) .or. &
                      (cfg%shape == 'gap' .and. len(cfg%contact_inp) == 0 .and. .not. cfg%mx_my_given)
    if (cfg%cell_budget /= 0 .and. .not. (cfg%refine_grid .and. cfg%target_error > 0 .and. .not. cfg%extrapolate)) &
      call fail(status, exit_bad_input, input_where(cfg)//'&solver cell_budget = '//rtoa(cfg%cell_budget)// &
                ' limits the grids kcreep chooses under error control; this case has none (a given grid, '// &
                'target_error = 0 or extrapolate): leave cell_budget out')
  end subroutine apply_error_control

  !> The patch the configuration describes.
  subroutine build_patch(cfg, patch, status)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(out) :: patch
    type(status_t), intent(inout) :: status
    logical, allocatable :: inside(:, :)
    character(len=:), allocatable :: where

    where = input_where(cfg)//'&patch mask_rows'
    select case (cfg%shape)
    case ('ellipse')
      call ellipse_patch(cfg%semi_a, cfg%semi_b, cfg%mx, cfg%my, patch, status)
    case ('mask')
      if (len(cfg%mask_file) > 0) then
        call read_mask_file(cfg%mask_file, patch, status)
        if (status%failed()) return
        if (cfg%mx /= 0 .and. cfg%mx /= patch%mx) call fail(status, exit_bad_input, input_where(cfg)// &
            '&patch mx = '//itoa(cfg%mx)//' but mask_file '''//cfg%mask_file//''' has mx = '//itoa(patch%mx))
        if (cfg%my /= 0 .and. cfg%my /= patch%my) call fail(status, exit_bad_input, input_where(cfg)// &
            '&patch my = '//itoa(cfg%my)//' but mask_file '''//cfg%mask_file//''' has my = '//itoa(patch%my))
        if ((cfg%dx /= 0 .and. cfg%dx /= patch%dx) .or. (cfg%dy /= 0 .and. cfg%dy /= patch%dy)) &
          call fail(status, exit_bad_input, input_where(cfg)//'&patch dx, dy = '// &
                    rtoa(cfg%dx)//', '//rtoa(cfg%dy)//' disagree with the header of mask_file '''// &
                    cfg%mask_file//''' ('//rtoa(patch%dx)//', '//rtoa(patch%dy)//'; leave them out)')
        if ((cfg%x0_given .and. cfg%x0 /= patch%x0) .or. (cfg%y0_given .and. cfg%y0 /= patch%y0)) &
          call fail(status, exit_bad_input, input_where(cfg)//'&patch x0, y0 = '// &
                    rtoa(cfg%x0)//', '//rtoa(cfg%y0)//' disagree with the header of mask_file '''// &
                    cfg%mask_file//''' ('//rtoa(patch%x0)//', '//rtoa(patch%y0)//'; leave them out)')
      else
        call parse_mask_rows(cfg%mask_rows, where, inside, status)
        if (status%failed()) return
        call mask_patch(inside, cfg%dx, cfg%dy, cfg%x0, cfg%y0, where, patch, status)
      end if
    case ('gap')
      ! found by the normal solve (kcreep_solve): nothing to build here
      patch%kind = 'gap'
    case ('contact')
      ! CONTACT's grid: corner (XL, YL), so the first cell centre is half a cell in
      call mask_patch(cfg%contact%inside, cfg%contact%dx, cfg%contact%dy, cfg%contact%xl + cfg%contact%dx / 2, &
                      cfg%contact%yl + cfg%contact%dy / 2, 'contact_file '''//cfg%contact_file//'''', patch, status)
      patch%kind = 'contact'
    end select
    if (status%failed()) return
    ! the same refusal as the library's check, naming the input
    if (cfg%scheme%name == 'collocation' .and. cfg%target_error > 0 .and. &
        .not. (cfg%refine_grid .and. patch%kind == 'ellipse')) then
      if (patch%dx > collocation_aspect_limit * patch%dy) call fail(status, exit_bad_input, input_where(cfg)// &
          '&solver scheme = ''collocation'' on cells long in x (dx/dy = '// &
          rtoa(patch%dx / patch%dy)//', allowed <= '//rtoa(collocation_aspect_limit)// &
          ' with target_error > 0): use near-square cells, scheme = ''backward'', or target_error = 0 '// &
          'to run this grid as given')
    end if
  end subroutine build_patch

  !> shape = 'contact': grid, mask and material of case contact_case of contact_file.
  !> A material in &material is refused rather than silently overridden: the
  !> comparison with CONTACT is only meaningful with CONTACT's own material.
  subroutine load_contact_case(cfg, status)
    type(config_t), intent(inout) :: cfg
    type(status_t), intent(inout) :: status
    if (cfg%material_given) then
      call fail(status, exit_bad_input, input_where(cfg)//'&material g, nu are not allowed '// &
                'with &patch shape = ''contact'' (the material comes from contact_file''s GG and POISS)')
      return
    end if
    call read_contact_case(cfg%contact_file, cfg%contact_case, cfg%contact, status)
    if (status%failed()) return
    call combined_material(cfg%contact%gg, cfg%contact%poiss, cfg%g, cfg%nu)
  end subroutine load_contact_case

  !> The library's problem: the patch built from cfg and the namelist's
  !> material, scheme and solver settings.
  function problem_of(cfg, patch) result(problem)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(in) :: patch
    type(problem_t) :: problem
    problem%patch = patch
    problem%g = cfg%g
    problem%nu = cfg%nu
    problem%scheme = cfg%scheme
    problem%solve = cfg%solve
    problem%requested = cfg%requested
    problem%refine = cfg%refine
    problem%extrapolate = cfg%extrapolate
    problem%target_error = cfg%target_error
    problem%cell_budget = cfg%cell_budget
    problem%refine_grid = cfg%refine_grid .and. .not. cfg%extrapolate
    problem%extrapolate_levels = cfg%extrapolate_levels
    problem%refine_ratio = cfg%refine_ratio
    problem%tractions_wanted = len(cfg%traction_file) > 0
    select case (cfg%spin_centre)
    case ('centroid')
      problem%spin_centre = patch%centroid()
    case ('point')
      problem%spin_centre = cfg%spin_centre_xy
    case default
      problem%spin_centre = 0
    end select
    if (cfg%shape == 'gap') problem%normal = cfg%normal
  end function problem_of

end module kcreep_namelist
