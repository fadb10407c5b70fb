!> kcreep: Kalker's creep coefficients of any contact patch.
!>
!>   kcreep INPUT.nml
!>
!> Reads the namelist, solves the full-adhesion steady-rolling problem on the
!> patch cells, writes the coefficient table (and optionally the tractions)
!> and prints a short summary. Every error ends here: one line on standard
!> error and a non-zero exit status (2 input, 3 numerical, 4 output).
program kcreep
  use, intrinsic :: iso_fortran_env, only: real64, error_unit, output_unit
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa
  use patch_grid, only: patch_t
  use namelist_input, only: config_t, read_config, build_patch
  use creep_run, only: run_case
  use table_output, only: run_record_t, table_lines, write_text_file, &
                          check_output_path, traction_lines
  implicit none

  character(len=*), parameter :: version = '0.1.0'
  type(config_t) :: cfg
  type(patch_t) :: patch
  type(run_record_t) :: record
  type(status_t) :: status
  real(real64), allocatable :: traction(:, :)
  character(len=400), allocatable :: warnings(:)
  character(len=:), allocatable :: input_path

  call parse_arguments(input_path, status)
  if (.not. status%failed()) call read_config(input_path, cfg, status)
  if (.not. status%failed()) call build_patch(cfg, patch, status)
  if (.not. status%failed()) call check_output_path(cfg%table_file, 'table_file', status)
  if (.not. status%failed() .and. len(cfg%traction_file) > 0) &
    call check_output_path(cfg%traction_file, 'traction_file', status)
  if (.not. status%failed()) call run_case(cfg, patch, record, traction, warnings, status)
  if (status%failed()) call stop_with(status)

  call write_text_file(cfg%table_file, table_lines([record], warnings), 'table_file', status)
  if (.not. status%failed() .and. len(cfg%traction_file) > 0) &
    call write_text_file(cfg%traction_file, traction_lines(patch, traction, cfg%requested), 'traction_file', status)
  if (status%failed()) call stop_with(status)

  call print_summary()

contains

  subroutine parse_arguments(path, status)
    character(len=:), allocatable, intent(out) :: path
    type(status_t), intent(inout) :: status
    integer :: length
    character(len=:), allocatable :: arg

    path = ''
    if (command_argument_count() /= 1) then
      call fail(status, exit_bad_input, 'usage: kcreep INPUT.nml  (kcreep --help for more)')
      return
    end if
    call get_command_argument(1, length=length)
    allocate (character(len=length) :: arg)
    call get_command_argument(1, arg)
    select case (arg)
    case ('-h', '--help')
      write (output_unit, '(a)') 'kcreep '//version//': creep coefficients of any contact patch', &
        'usage: kcreep INPUT.nml', &
        'The namelist groups &patch, &material, &solver and &output are described in README.md.'
      stop
    case ('-V', '--version')
      write (output_unit, '(a)') 'kcreep '//version
      stop
    end select
    path = arg
  end subroutine parse_arguments

  !> The one place where errors are reported: one line, then exit with the code.
  subroutine stop_with(status)
    use, intrinsic :: iso_c_binding, only: c_int
    type(status_t), intent(in) :: status
    interface
      subroutine c_exit(code) bind(c, name='exit')
        import :: c_int
        integer(c_int), value :: code
      end subroutine c_exit
    end interface
    write (error_unit, '(a)') 'kcreep: error: '//status%message
    flush (output_unit)
    flush (error_unit)
    call c_exit(int(status%code, c_int))   ! STOP n would add a second line
  end subroutine stop_with

  subroutine print_summary()
    character(len=*), parameter :: fmt_c = '(2x, a, es12.5, a, f8.4, a, f8.3, a)'
    character(len=3), parameter :: names(3) = ['C11', 'C22', 'C23']
    integer :: i

    write (output_unit, '(a)') 'kcreep '//version//': '//input_path
    write (output_unit, '(2x, a, i0, a, i0, a, i0, a, es10.3)') 'patch: '//patch%kind//', grid ', &
      patch%mx, ' x ', patch%my, ', ', patch%n, ' cells, c = ', record%c
    if (cfg%scheme%name == 'collocation') then
      write (output_unit, '(2x, a, f6.3, a, g0.4, a, es10.3)') 'scheme: collocation, alpha = ', &
        cfg%scheme%alpha, ', nu = ', cfg%nu, ', G = ', cfg%g
    else
      write (output_unit, '(2x, a, g0.4, a, es10.3)') 'scheme: backward, nu = ', cfg%nu, ', G = ', cfg%g
    end if
    write (output_unit, '(2x, a, 3es14.6)') 'f11 f22 f23:', record%f(1, 1), record%f(2, 2), record%f(2, 3)
    do i = 1, 3
      if (record%klt(i) == record%klt(i)) then
        write (output_unit, fmt_c) names(i)//' = ', record%cn(i), '   Kalker ', record%klt(i), &
          '   (', 100 * (record%cn(i) / record%klt(i) - 1), ' %)'
      else
        write (output_unit, '(2x, a, es12.5)') names(i)//' = ', record%cn(i)
      end if
    end do
    write (output_unit, '(2x, a, es9.2, a, es9.2)') 'rcond ', record%rcond, ', backward error ', record%backward_error
    write (output_unit, '(2x, a, i0)') 'method: '//record%method//', GMRES iterations ', record%iterations
    write (output_unit, '(2x, a, 4f9.3)') 'time assemble factor solve total [s]:', record%t_assemble, &
      record%t_factor, record%t_solve, record%t_total
    write (output_unit, '(2x, a)') 'verdict: '//record%verdict//'   table: '//cfg%table_file
    do i = 1, size(warnings)
      write (output_unit, '(2x, a)') 'WARNING: '//trim(warnings(i))
      write (error_unit, '(a)') 'kcreep: warning: '//trim(warnings(i))
    end do
  end subroutine print_summary

end program kcreep
