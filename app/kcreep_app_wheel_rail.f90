!> kcreep INPUT.nml with &wheel_rail: the contact table over the lateral
!> shifts, written to &output wheel_rail_file, and a summary on standard output.
module kcreep_app_wheel_rail
  use, intrinsic :: iso_fortran_env, only: real64, output_unit, error_unit
  use kcreep_status, only: status_t
  use kcreep_strings, only: rtoa, itoa
  use kcreep, only: problem_t, patch_t, wheel_rail_row_t, kcreep_wheel_rail
  use kcreep_namelist, only: config_t, problem_of
  use kcreep_wheel_rail_table, only: wheel_rail_lines
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
    integer :: k, j
    real(real64) :: t0, t1

    call check_output_path(cfg%wheel_rail_file, 'wheel_rail_file', status)
    if (status%failed()) return
    base = problem_of(cfg, none)
    base%solve%memory_limit = memory_limit_bytes()
    call cpu_time(t0)
    call kcreep_wheel_rail(cfg%wheel_rail, base, rows, status)
    call cpu_time(t1)
    if (status%failed()) return
    call write_text_file(cfg%wheel_rail_file, wheel_rail_lines(rows, cfg%wheel_rail, cfg%g, cfg%nu, cfg%target_error), &
                         'wheel_rail_file', status)
    if (status%failed()) return
    write (output_unit, '(a)') 'kcreep: '//input_path
    write (output_unit, '(2x, a)') 'wheel/rail: '//itoa(size(cfg%wheel_rail%shifts))//' shifts, '//itoa(size(rows))// &
      ' patches, side '//cfg%wheel_rail%side//'; table: '//cfg%wheel_rail_file
    write (output_unit, '(2x, a)') '  shift patch        fn     delta   y_rail  y_wheel  r_wheel    c11    c22    c23'// &
      '   err11   err22   err23 verdict'
    do k = 1, size(rows)
      associate (r => rows(k))
        write (output_unit, '(2x, f7.2, i6, es10.3, f10.4, 3f9.3, 3f7.3, 3es8.1, 1x, a)') r%shift, r%patch, r%fn, &
          r%delta, r%y_rail, r%y_wheel, r%r_wheel, r%c(1:3), r%err, trim(r%verdict)
        if (allocated(r%result%warnings)) then
          do j = 1, size(r%result%warnings)
            write (error_unit, '(a)') 'kcreep: warning: shift '//rtoa(r%shift)//' patch '//itoa(r%patch)//': '// &
              trim(r%result%warnings(j))
          end do
        end if
      end associate
    end do
    write (output_unit, '(2x, a, f8.2)') 'time [s, CPU]:', t1 - t0
  end subroutine wheel_rail_mode

end module kcreep_app_wheel_rail
