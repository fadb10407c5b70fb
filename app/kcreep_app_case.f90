!> One case from namelist file to solved record: the path shared by the
!> single-case program and the batch driver, so both validate and solve a
!> namelist in exactly the same way.
module kcreep_app_case
  use, intrinsic :: iso_fortran_env, only: int64
  use kcreep_status, only: status_t
  use kcreep, only: problem_t, patch_t, kcreep_solve, kcreep_memory_need, kcreep_wheel_rail_memory_need
  use kcreep_namelist, only: config_t, read_config, build_patch, problem_of
  use kcreep_table, only: run_record_t, case_name
  use kcreep_app_files, only: check_output_path
  use kcreep_app_memory, only: memory_limit_bytes
  implicit none
  private
  public :: solve_input, load_input, case_memory_bytes

contains

  !> Read and check the namelist at input_path and build its patch (relative
  !> file names inside the namelist are taken from the namelist's folder).
  subroutine load_input(input_path, cfg, patch, status)
    character(len=*), intent(in) :: input_path
    type(config_t), intent(out) :: cfg
    type(patch_t), intent(out) :: patch
    type(status_t), intent(inout) :: status

    call read_config(input_path, cfg, status)
    if (status%failed()) return
    call build_patch(cfg, patch, status)
  end subroutine load_input

  !> load_input, check that the outputs can be created, then solve with the
  !> library. With check_table false the namelist's table_file is not checked
  !> (the batch writes its own table); the traction file, when asked for,
  !> always is. The record holds the finest grid solved and its tractions.
  subroutine solve_input(input_path, check_table, cfg, record, status)
    character(len=*), intent(in) :: input_path
    logical, intent(in) :: check_table
    type(config_t), intent(out) :: cfg
    type(run_record_t), intent(out) :: record
    type(status_t), intent(inout) :: status
    type(patch_t) :: patch
    type(problem_t) :: problem

    call load_input(input_path, cfg, patch, status)
    if (check_table .and. .not. status%failed()) call check_output_path(cfg%table_file, 'table_file', status)
    if (.not. status%failed() .and. len(cfg%traction_file) > 0) &
      call check_output_path(cfg%traction_file, 'traction_file', status)
    if (.not. status%failed() .and. len(cfg%pressure_file) > 0) &
      call check_output_path(cfg%pressure_file, 'pressure_file', status)
    if (.not. status%failed() .and. len(cfg%contact_mask_file) > 0) &
      call check_output_path(cfg%contact_mask_file, 'contact_mask_file', status)
    if (check_table .and. cfg%fastsim_on .and. .not. status%failed()) &
      call check_output_path(cfg%creep_file, 'creep_file', status)
    if (check_table .and. cfg%fastsim_on .and. len(cfg%creep_map_file) > 0 .and. .not. status%failed()) &
      call check_output_path(cfg%creep_map_file, 'creep_map_file', status)
    if (check_table .and. cfg%rolling%on .and. .not. status%failed()) &
      call check_output_path(cfg%rolling%rolling_file, 'rolling_file', status)
    if (check_table .and. cfg%rolling%on .and. cfg%rolling%request%maps .and. .not. status%failed()) &
      call check_output_path(cfg%rolling%rolling_map_file, 'rolling_map_file', status)
    if (status%failed()) return
    problem = problem_of(cfg, patch)
    problem%solve%memory_limit = memory_limit_bytes()
    call kcreep_solve(problem, record%result_t, status)
    record%case_name = case_name(cfg%input_path)
  end subroutine solve_input

  !> Bytes a case needs at its peak and the solve path it takes there
  !> (kcreep_memory_need), under the memory limit of this machine.
  subroutine case_memory_bytes(cfg, patch, bytes, method, status)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(in) :: patch
    integer(int64), intent(out) :: bytes
    character(len=:), allocatable, intent(out) :: method
    type(status_t), intent(inout) :: status
    type(problem_t) :: problem
    problem = problem_of(cfg, patch)
    problem%solve%memory_limit = memory_limit_bytes()
    if (cfg%wheel_rail_on) then
      call kcreep_wheel_rail_memory_need(problem, cfg%wheel_rail, bytes, method, status)
    else
      call kcreep_memory_need(problem, bytes, method, status)
    end if
  end subroutine case_memory_bytes

end module kcreep_app_case
