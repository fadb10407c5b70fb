!> The command line: arguments to a mode, each mode run to its outputs, and
!> the one place where errors are reported (one line, then the exit code).
!>
!>   kcreep INPUT.nml
!>   kcreep --batch LIST [OUT_TABLE]      (many cases, one table)
!>   kcreep --estimate-memory INPUT.nml...
!>   kcreep --fingerprint INPUT.nml...     (the input fingerprint of each case)
!>
!> Exit status: 0 done, 2 bad input, 3 numerical failure, 4 output could not
!> be written, 5 some cases of a batch failed.
module kcreep_app_cli
  use, intrinsic :: iso_fortran_env, only: int64, output_unit, error_unit
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa
  use kcreep, only: kcreep_version, run_team, enter_team, leave_team
  use kcreep_namelist, only: config_t, group_list
  use kcreep_table, only: run_record_t, table_lines, traction_lines, pressure_lines, contact_mask_lines
  use kcreep_app_case, only: solve_input
  use kcreep_app_batch, only: run_batch, estimate_memory, default_batch_table, text_t, exit_cases_failed
  use kcreep_app_files, only: write_temporary, commit_temporary, discard_temporary
  use kcreep_app_summary, only: print_summary
  !$ use omp_lib, only: omp_set_num_threads
  use kcreep_app_fastsim, only: run_fastsim
  use kcreep_app_wheel_rail, only: wheel_rail_mode
  use kcreep_namelist, only: read_config
  use kcreep_app_fingerprint, only: program_digest, case_fingerprint
  use kcreep_app_rolling, only: run_rolling
  implicit none
  private
  public :: command_t, parse_command, run_command, stop_with, follow_slurm_cpus

  type :: command_t
    character(len=:), allocatable :: mode     !< 'single', 'batch', 'estimate', 'fingerprint', 'help' or 'version'
    type(text_t), allocatable :: args(:)      !< the arguments after the mode's flag
  end type command_t

contains

  subroutine parse_command(command, status)
    type(command_t), intent(out) :: command
    type(status_t), intent(inout) :: status
    integer :: k, n
    character(len=:), allocatable :: first, arg

    n = command_argument_count()
    allocate (command%args(0))
    command%mode = 'single'
    first = ''
    if (n >= 1) first = argument(1)
    select case (first)
    case ('-h', '--help')
      command%mode = 'help'
    case ('-V', '--version')
      command%mode = 'version'
    case ('--batch')
      command%mode = 'batch'
      if (n < 2 .or. n > 3) call fail(status, exit_bad_input, 'usage: kcreep --batch LIST [OUT_TABLE]')
    case ('--estimate-memory')
      command%mode = 'estimate'
      if (n < 2) call fail(status, exit_bad_input, 'usage: kcreep --estimate-memory INPUT.nml...')
    case ('--fingerprint')
      command%mode = 'fingerprint'
      if (n < 2) call fail(status, exit_bad_input, 'usage: kcreep --fingerprint INPUT.nml...')
    case default
      if (n /= 1) call fail(status, exit_bad_input, 'usage: kcreep INPUT.nml  (kcreep --help for more)')
    end select
    if (status%failed()) return
    do k = merge(1, 2, command%mode == 'single'), n
      arg = argument(k)   ! (a temporary: gfortran 12 fails on the function result in the constructor)
      command%args = [command%args, text_t(arg)]
    end do
  end subroutine parse_command

  subroutine run_command(command, status)
    type(command_t), intent(in) :: command
    type(status_t), intent(inout) :: status
    integer :: previous_team
    ! memory is estimated for the CPUs the process may use, whatever the load now
    if (command%mode == 'estimate') then
      call estimate_mode(command%args, status)
      return
    end if
    ! the one place that opens the team of the whole run: every stage, also
    ! one that chooses none, runs on at most the CPUs free now (kcreep_threads)
    call enter_team(run_team(), previous_team)
    select case (command%mode)
    case ('help')
      write (output_unit, '(a)') 'kcreep '//kcreep_version//': creep coefficients of any contact patch', &
        'usage: kcreep INPUT.nml', &
        '       kcreep --batch LIST [OUT_TABLE]   (one namelist path per line; table <LIST name>.tab)', &
        '       kcreep --estimate-memory INPUT.nml...   (per file: FILE BYTES dense|iterative)', &
        '       kcreep --fingerprint INPUT.nml...   (per file: SHA-256 FILE, of the program, the namelist '// &
        'and the files it reads)', &
        'The namelist groups '//group_list()//' are described in docs/input.md.'
    case ('version')
      write (output_unit, '(a)') 'kcreep '//kcreep_version
    case ('batch')
      call batch_mode(command%args, status)
    case ('fingerprint')
      call fingerprint_mode(command%args)
    case default
      call single_mode(command%args(1)%s, status)
    end select
    call leave_team(previous_team)
  end subroutine run_command

  !> kcreep --fingerprint: one line 'FINGERPRINT FILE' per namelist (64 hex
  !> digits; see kcreep_app_fingerprint), for scripts/run_cases.sh and the
  !> SLURM route. A namelist that cannot be read still has one.
  subroutine fingerprint_mode(args)
    type(text_t), intent(in) :: args(:)
    character(len=:), allocatable :: program
    integer :: k
    program = program_digest()
    do k = 1, size(args)
      write (output_unit, '(a)') case_fingerprint(program, args(k)%s)//' '//args(k)%s
    end do
    flush (output_unit)
  end subroutine fingerprint_mode

  !> kcreep INPUT.nml: solve, write the table (and tractions), print the summary.
  subroutine single_mode(input_path, status)
    character(len=*), intent(in) :: input_path
    type(status_t), intent(inout) :: status
    type(config_t) :: cfg
    type(run_record_t) :: record
    character(len=400), allocatable :: creep(:)
    character(len=200), allocatable :: maps(:), fastsim_summary(:), fastsim_warnings(:)
    character(len=400), allocatable :: rolling(:)
    character(len=200), allocatable :: rolling_maps(:), rolling_summary(:), rolling_warnings(:)
    character(len=4096) :: paths(8)
    character(len=24) :: variables(8)
    logical :: with_maps
    integer :: i, k, np

    call read_config(input_path, cfg, status)
    if (status%failed()) return
    if (cfg%wheel_rail_on) then
      call wheel_rail_mode(input_path, cfg, status)    ! a contact table over the shifts
      return
    end if
    call solve_input(input_path, .true., cfg, record, status)
    if (status%failed()) return
    with_maps = .false.
    if (cfg%fastsim_on) then
      call run_fastsim(cfg, record, creep, maps, fastsim_summary, fastsim_warnings, status)
      if (status%failed()) return
      with_maps = cfg%fastsim%maps
    end if
    if (cfg%rolling%on) then
      call run_rolling(cfg, record, rolling, rolling_maps, rolling_summary, rolling_warnings, status)
      if (status%failed()) return
    end if
    ! every output complete in its temporary file before any is renamed into
    ! place: a failure (a full disk) leaves all the previous files as they were
    np = 0
    call stage(cfg%table_file, 'table_file', table_lines([record], record%warnings))
    if (len(cfg%traction_file) > 0) &
      call stage(cfg%traction_file, 'traction_file', traction_lines(record%patch, record%traction, cfg%requested))
    if (len(cfg%pressure_file) > 0 .and. record%normal_solved) &
      call stage(cfg%pressure_file, 'pressure_file', &
                 pressure_lines(record%patch, record%pressure, record%fn, record%approach))
    if (len(cfg%contact_mask_file) > 0 .and. record%normal_solved) &
      call stage(cfg%contact_mask_file, 'contact_mask_file', contact_mask_lines(record%patch))
    if (cfg%fastsim_on) call stage(cfg%creep_file, 'creep_file', creep)
    if (with_maps) call stage(cfg%creep_map_file, 'creep_map_file', maps)
    if (cfg%rolling%on) call stage(cfg%rolling%rolling_file, 'rolling_file', rolling)
    if (cfg%rolling%on .and. cfg%rolling%request%maps) &
      call stage(cfg%rolling%rolling_map_file, 'rolling_map_file', rolling_maps)
    do k = 1, np
      if (.not. status%failed()) call commit_temporary(trim(paths(k)), trim(variables(k)), status)
    end do
    if (status%failed()) then
      do k = 1, np
        call discard_temporary(trim(paths(k)))
      end do
      return
    end if
    call print_summary(input_path, cfg, record)
    if (cfg%fastsim_on) then
      do i = 1, size(fastsim_summary)
        write (output_unit, '(2x, a)') trim(fastsim_summary(i))
      end do
      if (with_maps) write (output_unit, '(2x, a)') 'FASTSIM maps: '//cfg%creep_map_file
      do i = 1, size(fastsim_warnings)
        write (output_unit, '(2x, a)') 'WARNING: '//trim(fastsim_warnings(i))
        write (error_unit, '(a)') 'kcreep: warning: '//trim(fastsim_warnings(i))
      end do
    end if
    if (cfg%rolling%on) then
      do i = 1, size(rolling_summary)
        write (output_unit, '(2x, a)') trim(rolling_summary(i))
      end do
      do i = 1, size(rolling_warnings)
        write (output_unit, '(2x, a)') 'WARNING: '//trim(rolling_warnings(i))
        write (error_unit, '(a)') 'kcreep: warning: '//trim(rolling_warnings(i))
      end do
    end if
    if (profile_requested() .and. record%method == 'iterative') write (error_unit, '(a, 3f9.3)') &
      'kcreep: GMRES seconds in operator, preconditioner, orthogonalisation:', &
      record%t_operator, record%t_preconditioner, record%t_orthogonalise

  contains

    !> Write one output to its temporary file and remember it for the commit.
    subroutine stage(path, variable, lines)
      character(len=*), intent(in) :: path, variable
      character(len=*), intent(in) :: lines(:)
      if (status%failed()) return
      np = np + 1
      paths(np) = path
      variables(np) = variable
      call write_temporary(path, lines, variable, status)
    end subroutine stage

  end subroutine single_mode

  !> kcreep --batch LIST [OUT_TABLE]
  subroutine batch_mode(args, status)
    type(text_t), intent(in) :: args(:)
    type(status_t), intent(inout) :: status
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
    if (status%failed()) return
    write (output_unit, '(a)') 'kcreep: batch table '//out_path
  end subroutine batch_mode

  !> kcreep --estimate-memory INPUT.nml...: one line 'FILE BYTES PATH' per
  !> input, an error line for each one that cannot be estimated (the others
  !> still are); exit status 2 when any could not.
  subroutine estimate_mode(args, status)
    type(text_t), intent(in) :: args(:)
    type(status_t), intent(inout) :: status
    integer :: n_failed
    call estimate_memory(args, n_failed)
    if (n_failed > 0) call fail(status, exit_bad_input, '')   ! the errors are printed already
  end subroutine estimate_mode

  !> The one place where errors are reported: one line, then exit with the code.
  !> Inside a SLURM job step the CPUs per task bound the automatic thread
  !> count (unless OMP_NUM_THREADS says otherwise): the library's automatic
  !> count follows OpenMP's limit, set here for this process.
  subroutine follow_slurm_cpus()
    character(len=32) :: value
    integer :: stat, cpus
    call get_environment_variable('OMP_NUM_THREADS', status=stat)
    if (stat == 0) return
    call get_environment_variable('SLURM_CPUS_PER_TASK', value, status=stat)
    if (stat /= 0) return
    read (value, *, iostat=stat) cpus
    !$ if (stat == 0 .and. cpus >= 1) call omp_set_num_threads(cpus)
  end subroutine follow_slurm_cpus

  subroutine stop_with(status)
    use, intrinsic :: iso_c_binding, only: c_int
    type(status_t), intent(in) :: status
    interface
      subroutine c_exit(code) bind(c, name='exit')
        import :: c_int
        integer(c_int), value :: code
      end subroutine c_exit
    end interface
    if (len(status%message) > 0) write (error_unit, '(a)') 'kcreep: error: '//status%message
    flush (output_unit)
    flush (error_unit)
    call c_exit(int(status%code, c_int))   ! STOP n would add a second line
  end subroutine stop_with

  !> Command-line argument i, whole.
  function argument(i) result(arg)
    integer, intent(in) :: i
    character(len=:), allocatable :: arg
    integer :: length
    call get_command_argument(i, length=length)
    allocate (character(len=length) :: arg)
    call get_command_argument(i, arg)
  end function argument

  !> KCREEP_PROFILE set (to anything): print where the GMRES time went (benchmark aid).
  logical function profile_requested()
    integer :: stat
    call get_environment_variable('KCREEP_PROFILE', status=stat)
    profile_requested = stat == 0
  end function profile_requested

end module kcreep_app_cli
