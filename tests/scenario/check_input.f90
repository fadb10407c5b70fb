!> Reader-only harness for fuzzing: the first half of kcreep (read the
!> namelist, validate it, build the patch, probe the output folders) and
!> nothing else, so that each input costs milliseconds.
!>
!>   check_input INPUT.nml
!>
!> Exit 0 and one line 'ok mx my n' when kcreep would go on to solve, or the
!> same single 'kcreep: error: ...' line and exit status kcreep would give.
program check_input
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use, intrinsic :: iso_c_binding, only: c_int
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_patch, only: patch_t
  use kcreep_namelist, only: config_t, read_config, build_patch
  use kcreep_app_files, only: check_output_path
  implicit none
  interface
    subroutine c_exit(code) bind(c, name='exit')
      import :: c_int
      integer(c_int), value :: code
    end subroutine c_exit
  end interface
  type(config_t) :: cfg
  type(patch_t) :: patch
  type(status_t) :: status
  character(len=:), allocatable :: path
  integer :: length

  if (command_argument_count() /= 1) then
    call fail(status, exit_bad_input, 'usage: check_input INPUT.nml')
  else
    call get_command_argument(1, length=length)
    allocate (character(len=length) :: path)
    call get_command_argument(1, path)
    call read_config(path, cfg, status)
  end if
  if (.not. status%failed()) call build_patch(cfg, patch, status)
  if (.not. status%failed()) call check_output_path(cfg%table_file, 'table_file', status)
  if (.not. status%failed() .and. len(cfg%traction_file) > 0) &
    call check_output_path(cfg%traction_file, 'traction_file', status)
  if (status%failed()) then
    write (error_unit, '(a)') 'kcreep: error: '//status%message
    flush (error_unit)
    call c_exit(int(status%code, c_int))
  end if
  write (output_unit, '(a, 3(1x, i0))') 'ok', patch%mx, patch%my, patch%n
end program check_input
