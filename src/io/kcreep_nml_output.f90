!> The &output group: the files a run writes.
module kcreep_nml_output
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: resolve_path, folder_of
  use kcreep_nml_config, only: config_t, input_where, default_output_name
  implicit none
  private
  public :: output_variables, output_group_t, read_output_group, apply_output_group

  type :: output_group_t
    character(len=4096) :: table_file = '', traction_file = '', pressure_file = '', contact_mask_file = '', &
                           creep_file = '', creep_map_file = '', wheel_rail_file = '', wheelset_file = '', &
                           rolling_file = '', rolling_map_file = ''
  end type output_group_t

  !> The group's variables and their types, as in its namelist statement
  !> (kcreep_namelist_scan diagnose_group explains a failed read with them).
  character(len=*), parameter :: output_variables(10) = [character(len=27) :: &
    'table_file character', 'traction_file character', 'pressure_file character', &
    'contact_mask_file character', 'creep_file character', 'creep_map_file character', &
    'wheel_rail_file character', 'wheelset_file character', 'rolling_file character', &
    'rolling_map_file character']

contains

  subroutine read_output_group(unit, grp, ios, msg)
    integer, intent(in) :: unit
    type(output_group_t), intent(out) :: grp
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    character(len=4096) :: table_file, traction_file, pressure_file, contact_mask_file, creep_file, creep_map_file, &
                           wheel_rail_file, wheelset_file, rolling_file, rolling_map_file
    namelist /output/ table_file, traction_file, pressure_file, contact_mask_file, creep_file, creep_map_file, &
                      wheel_rail_file, wheelset_file, rolling_file, rolling_map_file

    table_file = grp%table_file
    traction_file = grp%traction_file
    pressure_file = grp%pressure_file
    contact_mask_file = grp%contact_mask_file
    creep_file = grp%creep_file
    creep_map_file = grp%creep_map_file
    wheel_rail_file = grp%wheel_rail_file
    wheelset_file = grp%wheelset_file
    rolling_file = grp%rolling_file
    rolling_map_file = grp%rolling_map_file
    read (unit, nml=output, iostat=ios, iomsg=msg)
    grp%table_file = table_file
    grp%traction_file = traction_file
    grp%pressure_file = pressure_file
    grp%contact_mask_file = contact_mask_file
    grp%creep_file = creep_file
    grp%creep_map_file = creep_map_file
    grp%wheel_rail_file = wheel_rail_file
    grp%wheelset_file = wheelset_file
    grp%rolling_file = rolling_file
    grp%rolling_map_file = rolling_map_file
  end subroutine read_output_group

  !> The file names relative to the namelist's folder; the default table and
  !> creep table, which the namelist does not name, go to the working folder.
  !> (cfg%shape set.)
  subroutine apply_output_group(grp, cfg, status)
    type(output_group_t), intent(in) :: grp
    type(config_t), intent(inout) :: cfg
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: folder

    folder = folder_of(cfg%input_path)
    cfg%table_file = resolve_path(trim(grp%table_file), folder)
    if (len(cfg%table_file) == 0) cfg%table_file = default_output_name(cfg%input_path, '.tab')
    cfg%traction_file = resolve_path(trim(grp%traction_file), folder)
    cfg%pressure_file = resolve_path(trim(grp%pressure_file), folder)
    cfg%contact_mask_file = resolve_path(trim(grp%contact_mask_file), folder)
    cfg%creep_file = resolve_path(trim(grp%creep_file), folder)
    if (len(cfg%creep_file) == 0) cfg%creep_file = default_output_name(cfg%input_path, '.creep')
    cfg%creep_map_file = resolve_path(trim(grp%creep_map_file), folder)
    cfg%wheel_rail_file = resolve_path(trim(grp%wheel_rail_file), folder)
    if (len(cfg%wheel_rail_file) == 0) cfg%wheel_rail_file = default_output_name(cfg%input_path, '.wr')
    cfg%wheelset_file = resolve_path(trim(grp%wheelset_file), folder)
    if (len(cfg%wheelset_file) == 0) cfg%wheelset_file = default_output_name(cfg%input_path, '.ws')
    if (cfg%shape /= 'gap' .and. (len(cfg%pressure_file) > 0 .or. len(cfg%contact_mask_file) > 0)) &
      call fail(status, exit_bad_input, input_where(cfg)//'&output pressure_file and contact_mask_file need '// &
                '&patch shape = ''gap''')
  end subroutine apply_output_group

end module kcreep_nml_output
