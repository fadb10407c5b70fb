!> kcreep: Kalker's creep coefficients of any contact patch.
!>
!>   kcreep INPUT.nml
!>   kcreep --batch LIST [OUT_TABLE]      (batch_driver: many cases, one table)
!>   kcreep --estimate-memory INPUT.nml...
!>
!> Reads the namelist, solves the full-adhesion steady-rolling problem on the
!> patch cells, writes the coefficient table (and optionally the tractions)
!> and prints a short summary. Every error ends here: one line on standard
!> error and a non-zero exit status (2 input, 3 numerical, 4 output, 5 some
!> cases of a batch failed).
program kcreep
  use, intrinsic :: iso_fortran_env, only: real64, int64, error_unit, output_unit
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa
  use patch_grid, only: patch_t
  use namelist_input, only: config_t
  use case_driver, only: solve_input
  use batch_driver, only: run_batch, estimate_memory, default_batch_table, text_t, exit_cases_failed
  use contact_compare, only: comparison_lines, contact_spin_shift
  use table_output, only: run_record_t, table_lines, write_temporary, commit_temporary, &
                          discard_temporary, traction_lines
  implicit none

  character(len=*), parameter :: version = '0.1.0'
  type(config_t) :: cfg
  type(patch_t) :: patch
  type(run_record_t) :: record
  type(status_t) :: status
  real(real64), allocatable :: traction(:, :)
  character(len=400), allocatable :: warnings(:)
  character(len=:), allocatable :: input_path, mode
  type(text_t), allocatable :: args(:)

  call parse_arguments(mode, args, status)
  if (.not. status%failed()) then
    select case (mode)
    case ('batch')
      call batch_mode()
    case ('estimate')
      call estimate_mode()
    end select
  end if
  if (.not. status%failed()) input_path = args(1)%s
  if (.not. status%failed()) call solve_input(input_path, '', .true., cfg, patch, record, traction, warnings, status)
  if (status%failed()) call stop_with(status)

  ! every output complete in its temporary file before any is renamed into
  ! place: a failure (a full disk) leaves all the previous files as they were
  call write_temporary(cfg%table_file, table_lines([record], warnings), 'table_file', status)
  if (.not. status%failed() .and. len(cfg%traction_file) > 0) &
    call write_temporary(cfg%traction_file, traction_lines(patch, traction, cfg%requested), 'traction_file', status)
  if (.not. status%failed()) call commit_temporary(cfg%table_file, 'table_file', status)
  if (.not. status%failed() .and. len(cfg%traction_file) > 0) &
    call commit_temporary(cfg%traction_file, 'traction_file', status)
  if (status%failed()) then
    call discard_temporary(cfg%table_file)
    if (len(cfg%traction_file) > 0) call discard_temporary(cfg%traction_file)
    call stop_with(status)
  end if

  call print_summary()

contains

  !> mode 'single' (args: the input), 'batch' (list [, table]) or 'estimate' (inputs).
  subroutine parse_arguments(mode, args, status)
    character(len=:), allocatable, intent(out) :: mode
    type(text_t), allocatable, intent(out) :: args(:)
    type(status_t), intent(inout) :: status
    integer :: k, n
    character(len=:), allocatable :: first, arg

    n = command_argument_count()
    allocate (args(0))
    mode = 'single'
    first = ''
    if (n >= 1) first = argument(1)
    select case (first)
    case ('-h', '--help')
      write (output_unit, '(a)') 'kcreep '//version//': creep coefficients of any contact patch', &
        'usage: kcreep INPUT.nml', &
        '       kcreep --batch LIST [OUT_TABLE]   (one namelist path per line; table <LIST name>.tab)', &
        '       kcreep --estimate-memory INPUT.nml...   (bytes each case needs)', &
        'The namelist groups &patch, &material, &solver and &output are described in README.md.'
      stop
    case ('-V', '--version')
      write (output_unit, '(a)') 'kcreep '//version
      stop
    case ('--batch')
      mode = 'batch'
      if (n < 2 .or. n > 3) call fail(status, exit_bad_input, 'usage: kcreep --batch LIST [OUT_TABLE]')
    case ('--estimate-memory')
      mode = 'estimate'
      if (n < 2) call fail(status, exit_bad_input, 'usage: kcreep --estimate-memory INPUT.nml...')
    case default
      if (n /= 1) call fail(status, exit_bad_input, 'usage: kcreep INPUT.nml  (kcreep --help for more)')
    end select
    if (status%failed()) return
    do k = merge(1, 2, mode == 'single'), n
      arg = argument(k)
      args = [args, text_t(arg)]
    end do
  end subroutine parse_arguments

  !> Command-line argument i, whole.
  function argument(i) result(arg)
    integer, intent(in) :: i
    character(len=:), allocatable :: arg
    integer :: length
    call get_command_argument(i, length=length)
    allocate (character(len=length) :: arg)
    call get_command_argument(i, arg)
  end function argument

  !> kcreep --batch LIST [OUT_TABLE]; exits here.
  subroutine batch_mode()
    character(len=:), allocatable :: out_path
    integer :: n_failed
    if (size(args) == 2) then
      out_path = args(2)%s
    else
      out_path = default_batch_table(args(1)%s)
    end if
    call run_batch(args(1)%s, out_path, n_failed, status)
    if (.not. status%failed() .and. n_failed > 0) call fail(status, exit_cases_failed, &
        itoa(n_failed)//' case(s) of '''//args(1)%s//''' failed: see the rows with verdict error:... in '''// &
        out_path//'''')
    if (status%failed()) call stop_with(status)
    write (output_unit, '(a)') 'kcreep: batch table '//out_path
    stop
  end subroutine batch_mode

  !> kcreep --estimate-memory INPUT.nml...: one number of bytes per input; exits here.
  subroutine estimate_mode()
    integer(int64), allocatable :: bytes(:)
    integer :: k
    allocate (bytes(size(args)))
    call estimate_memory(args, bytes, status)
    if (status%failed()) call stop_with(status)
    do k = 1, size(args)
      write (output_unit, '(i0)') bytes(k)
    end do
    stop
  end subroutine estimate_mode

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
    if (patch%kind == 'contact') call print_contact_comparison()
    if (record%extrapolated) then
      write (output_unit, '(2x, a, i0, a, i0, a)') 'extrapolated (', cfg%extrapolate_levels, &
        ' levels, ratio ', cfg%refine_ratio, '; the rows above are the finest level):'
      do i = 1, 3
        write (output_unit, '(4x, a, f9.5, a, es8.1, a, f5.2, a)') names(i)//' -> ', record%ext(i), &
          ' +- ', record%ext_error(i), '   (order ', record%ext_order(i), ')'
      end do
    end if
    write (output_unit, '(2x, a, 3es12.4)') 'FASTSIM L1 L2 L3:', record%fastsim
    if (record%method == 'dense') then
      write (output_unit, '(2x, a)') 'method: dense LU (LAPACK)'
      write (output_unit, '(2x, a, es9.2, a, es9.2)') 'rcond ', record%rcond, ', backward error ', record%backward_error
      write (output_unit, '(2x, a, es9.2, a, es9.2, a)') 'solve: relative residual ', record%relative_residual, &
        ', backward error before refinement ', record%backward_error_initial, ', refine = '//trim(record%refine)
    else
      write (output_unit, '(2x, a, i0, a, es9.2, a)') 'method: iterative (FFT operator, preconditioned GMRES), ', &
        record%iterations, ' iterations, relative residual ', record%backward_error, ' (no rcond estimate)'
    end if
    write (output_unit, '(2x, a, 4f9.3)') 'time assemble factor solve total [s]:', record%t_assemble, &
      record%t_factor, record%t_solve, record%t_total
    write (output_unit, '(2x, a)') 'verdict: '//record%verdict//'   table: '//cfg%table_file
    do i = 1, size(warnings)
      write (output_unit, '(2x, a)') 'WARNING: '//trim(warnings(i))
      write (error_unit, '(a)') 'kcreep: warning: '//trim(warnings(i))
    end do
  end subroutine print_summary

  !> shape = 'contact': kcreep's forces for CONTACT's creepages beside CONTACT's.
  subroutine print_contact_comparison()
    character(len=300), allocatable :: lines(:)
    integer :: i
    lines = comparison_lines(cfg%contact, record%f, cfg%scheme%name == 'backward' .and. &
                             cfg%scheme%spin_shift == contact_spin_shift)
    do i = 1, size(lines)
      write (output_unit, '(2x, a)') trim(lines(i))
    end do
  end subroutine print_contact_comparison

end program kcreep
