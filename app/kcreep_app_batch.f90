!> Batch mode: many cases in one process, one table.
!>
!>   kcreep --batch LIST [OUT_TABLE]
!>
!> LIST holds one namelist path per line (relative to LIST's folder; blank
!> lines and lines starting with # are skipped). The cases run in LIST
!> order through the same path as a single run (solve_input, or
!> run_wheel_rail_case for contact tables); one table holds one kind: either
!> every case is a single patch (a row each) or every case has &wheel_rail
!> (its .wr file written as a single run writes it, and its rows, each led by
!> the case's name, in the batch table); a list mixing them is refused
!> before any work. Each finished case's rows are appended and flushed to
!> OUT_TABLE.partial, so a batch that is
!> killed keeps every row it had finished, and running the same command
!> again resumes: a row is kept when the input fingerprint of its case
!> (kcreep_app_fingerprint: the program, the namelist and every file it
!> reads), written beside it as '# fingerprint K HEX', is still the case's;
!> a case whose inputs changed since is named and run again, as is every
!> case without a row. At the end the table is
!> written whole to OUT_TABLE, rows in list order (temporary file and rename) and the partial
!> file is removed. A case that fails gets a row all the same: NaN numbers
!> and the verdict error:bad-input, error:numerical or error:io; its
!> message goes to standard error and into the table's comments, and the
!> batch goes on. The partial table is locked (flock) while the batch runs:
!> a second batch on the same table is refused at once. The lock goes with
!> the process however it ends (a kill, a crash), so a partial table without
!> a running batch is resumed by its own list; another list run on the same
!> table keeps it (when it holds rows) as OUT_TABLE.partial.SIGNATURE (its
!> list's signature) and starts afresh, and the first list, run again on the
!> table, resumes from that file.
module kcreep_app_batch
  use, intrinsic :: iso_fortran_env, only: real64, int64, output_unit, error_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use kcreep_status, only: status_t, fail, exit_bad_input, exit_numerical, exit_io
  use kcreep_strings, only: itoa, rtoa
  use kcreep, only: patch_t
  use kcreep_namelist, only: config_t
  use kcreep_app_case, only: solve_input, load_input, case_memory_bytes
  use kcreep_strings, only: folder_of, resolve_path
  use kcreep_table, only: run_record_t, table_lines, table_row, traction_lines, case_name, pressure_lines, &
                          contact_mask_lines, line_length
  use kcreep_app_files, only: write_text_file, check_output_path
  use kcreep_app_fastsim, only: run_fastsim
  use kcreep_app_rolling, only: run_rolling
  use kcreep_app_lock, only: lock_exclusive, truncate_locked, real_path
  use kcreep_namelist, only: read_config
  use kcreep_app_fingerprint, only: program_digest, case_fingerprint
  use kcreep_app_partial, only: text_t, fingerprint_mark, keep_unchanged, block_numbers, case_order, is_row, &
                                count_rows, count_error_rows, read_text_file, joined
  use kcreep, only: wheel_rail_row_t
  use kcreep_wheel_rail_table, only: wheel_rail_batch_head, wheel_rail_batch_columns, wheel_rail_row, &
                                     wheel_rail_header_lines
  use kcreep_table, only: table_columns
  use kcreep_app_wheel_rail, only: wheel_rail_case_t, run_wheel_rail_case, write_wheel_rail_case
  use, intrinsic :: iso_c_binding, only: c_int
  implicit none
  private
  public :: run_batch, read_case_list, estimate_memory, default_batch_table, text_t, count_error_rows

  !> Exit status of a batch that finished but in which some cases failed.
  integer, parameter, public :: exit_cases_failed = 5

contains

  !> Run every case of list_path; n_failed counts the error rows (of this
  !> run and of a resumed partial table). status fails only when the batch
  !> itself cannot go on (list unreadable, table not writable).
  subroutine run_batch(list_path, out_path, n_failed, status)
    character(len=*), intent(in) :: list_path, out_path
    integer, intent(out) :: n_failed
    type(status_t), intent(inout) :: status
    type(text_t), allocatable :: cases(:), partial(:), names(:), prints(:)
    character(len=:), allocatable :: partial_path, signature, program, columns
    logical, allocatable :: done(:)
    integer :: n_done, k, unit, ios
    integer(c_int) :: lock_fd
    logical :: held, tables
    character(len=512) :: msg

    n_failed = 0
    call read_case_list(list_path, cases, names, status)
    if (status%failed()) return
    call check_cases(list_path, cases, tables, status)
    if (status%failed()) return
    call check_output_path(out_path, 'batch table', status)
    if (status%failed()) return
    partial_path = out_path//'.partial'
    signature = '# kcreep batch in progress: '//itoa(size(cases))//' cases, list signature '// &
                list_signature(cases)

    ! one batch per table: the lock is held on the partial table until the end
    call lock_exclusive(partial_path, lock_fd, held)
    if (held) then
      call fail(status, exit_io, 'batch table '''//partial_path//''' is locked: another kcreep --batch is '// &
                'writing '''//out_path//''' now (wait for it to finish, or give another OUT_TABLE)')
      return
    else if (lock_fd < 0) then
      call fail(status, exit_io, 'batch table '''//partial_path//''': cannot create it')
      return
    end if
    call resume_partial(partial_path, lock_fd, signature, list_signature(cases), partial, status)
    if (status%failed()) return
    ! the rows whose cases are unchanged since they were written, the others dropped
    program = program_digest()
    allocate (prints(size(cases)))
    do k = 1, size(cases)
      prints(k)%s = case_fingerprint(program, cases(k)%s)
    end do
    call keep_unchanged(partial, cases, prints, done, k)
    if (k > 0) call rewrite_locked(partial_path, lock_fd, partial, status)
    if (status%failed()) return
    n_done = count(done)
    columns = table_columns
    if (tables) columns = wheel_rail_batch_columns
    n_failed = count_error_rows(partial, columns)
    if (n_done > 0) write (output_unit, '(a)') 'kcreep: resuming '''//partial_path//''': '// &
      itoa(n_done)//' of '//itoa(size(cases))//' cases already done'

    open (newunit=unit, file=partial_path, status='old', position='append', action='write', &
          iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_io, 'batch table '''//partial_path//''': cannot append ('//trim(msg)//')')
      return
    end if
    do k = 1, size(cases)
      if (done(k)) cycle
      if (tables) then
        call run_table_case(k, size(cases), cases(k)%s, names(k)%s, prints(k)%s, unit, n_failed, status)
      else
        call run_one(k, size(cases), cases(k)%s, names(k)%s, prints(k)%s, unit, n_failed, status)
      end if
      if (status%failed()) then
        close (unit)
        return
      end if
    end do
    close (unit)

    call finish_table(partial_path, out_path, list_path, size(cases), n_failed, tables, status)
  end subroutine run_batch

  !> The case k with &wheel_rail: its files as a single run writes them
  !> (run_wheel_rail_case), then its description, warnings, fingerprint and
  !> rows (one per shift and patch, each led by the case's name) appended to
  !> the partial table; a case that fails gets one row of NaN and its error.
  subroutine run_table_case(k, n, input_path, name, fingerprint, unit, n_failed, status)
    integer, intent(in) :: k, n, unit
    character(len=*), intent(in) :: input_path, name, fingerprint
    integer, intent(inout) :: n_failed
    type(status_t), intent(inout) :: status
    type(config_t) :: cfg
    type(wheel_rail_case_t) :: wr
    type(wheel_rail_row_t) :: nan_row
    type(status_t) :: case_status
    type(text_t), allocatable :: block(:)
    character(len=:), allocatable :: label, verdict
    integer :: i, j, n_rows, ios
    character(len=512) :: msg

    label = 'case '//itoa(k)//' '''//input_path//''''
    call read_config(input_path, cfg, case_status)
    if (.not. case_status%failed() .and. .not. cfg%wheel_rail_on) call fail(case_status, exit_bad_input, &
        'input '''//input_path//''': no &wheel_rail, while this list''s batch table holds contact tables '// &
        '(one kind per table)')
    if (.not. case_status%failed()) call run_wheel_rail_case(cfg, wr, case_status)
    if (.not. case_status%failed()) call write_wheel_rail_case(cfg, wr, case_status)
    allocate (block(0))
    if (case_status%failed()) then
      n_failed = n_failed + 1
      write (error_unit, '(a)') 'kcreep: '//label//': error: '//case_status%message
      block = [text_t('# '//label//': error: '//case_status%message)]
      verdict = error_word(case_status%code)
      nan_row = nan_wheel_rail_row(verdict)
      n_rows = 1
      block = [block, text_t(fingerprint_mark//itoa(k)//' '//fingerprint//' 1'), &
               text_t(name//' '//trim(wheel_rail_row(nan_row)))]
    else
      do i = 1, wheel_rail_header_lines - 3     ! the case's side, profiles, placement, load, material
        block = [block, text_t('# '//label//': '//trim(wr%table(i)(3:)))]
      end do
      do i = 1, size(wr%warnings)
        write (error_unit, '(a)') 'kcreep: '//label//': warning: '//trim(wr%warnings(i))
        block = [block, text_t('# '//label//': warning: '//trim(wr%warnings(i)))]
      end do
      n_rows = size(wr%table) - wheel_rail_header_lines
      block = [block, text_t(fingerprint_mark//itoa(k)//' '//fingerprint//' '//itoa(n_rows))]
      do i = wheel_rail_header_lines + 1, size(wr%table)
        block = [block, text_t(name//' '//trim(wr%table(i)))]
      end do
      i = 0
      do j = 1, size(wr%rows)
        if (wr%rows(j)%verdict /= 'ok') i = i + 1
      end do
      verdict = itoa(n_rows)//' rows, '//merge('all ok', itoa(i)//' not ok', i == 0)//' ('//seconds(wr%wall)//' s)'
    end if
    ios = 0
    do i = 1, size(block)
      if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=msg) block(i)%s
    end do
    if (ios == 0) flush (unit, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_io, 'batch table: cannot append the rows of '//label//' ('//trim(msg)//')')
      return
    end if
    write (output_unit, '(a)') 'kcreep: '//itoa(k)//'/'//itoa(n)//' '//name//': '//verdict
    flush (output_unit)
  end subroutine run_table_case

  !> The row of a contact table that could not be made: NaN numbers, patch 0, the error word.
  function nan_wheel_rail_row(verdict) result(row)
    character(len=*), intent(in) :: verdict
    type(wheel_rail_row_t) :: row
    real(real64) :: nan
    nan = ieee_value(1.0_real64, ieee_quiet_nan)
    row%shift = nan
    row%yaw = nan
    row%patch = 0
    row%fn = nan
    row%delta = nan
    row%y_rail = nan
    row%y_wheel = nan
    row%r_wheel = nan
    row%area = nan
    row%length = nan
    row%width = nan
    row%c = nan
    row%err = nan
    row%l = nan
    row%spin = nan
    row%verdict = verdict
  end function nan_wheel_rail_row

  !> Solve case k and append its row (after its comments and its input
  !> fingerprint) to the partial table.
  subroutine run_one(k, n, input_path, name, fingerprint, unit, n_failed, status)
    integer, intent(in) :: k, n, unit
    character(len=*), intent(in) :: input_path, name, fingerprint
    integer, intent(inout) :: n_failed
    type(status_t), intent(inout) :: status
    type(config_t) :: cfg
    type(run_record_t) :: record
    type(status_t) :: case_status
    character(len=:), allocatable :: label
    character(len=400), allocatable :: creep(:)
    character(len=200), allocatable :: maps(:), fastsim_summary(:), fastsim_warnings(:), rolling_warnings(:)
    integer :: i, ios
    character(len=512) :: msg

    label = 'case '//itoa(k)//' '''//input_path//''''
    allocate (fastsim_warnings(0))
    call solve_input(input_path, .false., cfg, record, case_status)
    if (.not. case_status%failed() .and. len(cfg%traction_file) > 0) &
      call write_text_file(cfg%traction_file, traction_lines(record%patch, record%traction, cfg%requested), &
                           'traction_file', case_status)
    if (.not. case_status%failed() .and. len(cfg%pressure_file) > 0 .and. record%normal_solved) &
      call write_text_file(cfg%pressure_file, pressure_lines(record%patch, record%pressure, record%fn, &
                           record%approach), 'pressure_file', case_status)
    if (.not. case_status%failed() .and. len(cfg%contact_mask_file) > 0 .and. record%normal_solved) &
      call write_text_file(cfg%contact_mask_file, contact_mask_lines(record%patch), 'contact_mask_file', case_status)
    ! &fastsim: the case's creep-force table (and maps) as in a single run
    if (.not. case_status%failed() .and. cfg%fastsim_on) then
      call run_fastsim(cfg, record, creep, maps, fastsim_summary, fastsim_warnings, case_status)
      if (.not. case_status%failed()) call write_text_file(cfg%creep_file, creep, 'creep_file', case_status)
      if (.not. case_status%failed() .and. cfg%fastsim%maps) &
        call write_text_file(cfg%creep_map_file, maps, 'creep_map_file', case_status)
    end if
    ! &rolling: the case's exact rolling table (and maps)
    if (.not. case_status%failed() .and. cfg%rolling%on) then
      call run_rolling(cfg, record, creep, maps, fastsim_summary, rolling_warnings, case_status)
      if (.not. case_status%failed()) &
        call write_text_file(cfg%rolling%rolling_file, creep, 'rolling_file', case_status)
      if (.not. case_status%failed() .and. cfg%rolling%request%maps) &
        call write_text_file(cfg%rolling%rolling_map_file, maps, 'rolling_map_file', case_status)
      if (.not. case_status%failed()) fastsim_warnings = [character(len=200) :: fastsim_warnings, rolling_warnings]
    end if

    if (case_status%failed()) then
      n_failed = n_failed + 1
      record = failed_record(name, case_status%code)
      write (error_unit, '(a)') 'kcreep: '//label//': error: '//case_status%message
      write (unit, '(a)', iostat=ios, iomsg=msg) '# '//label//': error: '//case_status%message
    else
      ios = 0
      do i = 1, size(record%warnings)
        write (error_unit, '(a)') 'kcreep: '//label//': warning: '//trim(record%warnings(i))
        if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=msg) '# '//label//': warning: '//trim(record%warnings(i))
      end do
      do i = 1, size(fastsim_warnings)
        write (error_unit, '(a)') 'kcreep: '//label//': warning: '//trim(fastsim_warnings(i))
        if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=msg) '# '//label//': warning: '//trim(fastsim_warnings(i))
      end do
    end if
    record%case_name = name
    if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=msg) fingerprint_mark//itoa(k)//' '//fingerprint//' 1'
    if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=msg) table_row(record)
    if (ios == 0) flush (unit, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_io, 'batch table: cannot append the row of '//label//' ('//trim(msg)//')')
      return
    end if
    if (case_status%failed()) then
      write (output_unit, '(a)') 'kcreep: '//itoa(k)//'/'//itoa(n)//' '//record%case_name//': '//record%verdict
    else
      write (output_unit, '(a)') 'kcreep: '//itoa(k)//'/'//itoa(n)//' '//record%case_name//': '// &
        record%verdict//' ('//seconds(record%t_total)//' s)'
    end if
    flush (output_unit)
  end subroutine run_one

  !> The row of a case that could not be solved: its name, NaN numbers, the error word.
  function failed_record(name, code) result(record)
    character(len=*), intent(in) :: name
    integer, intent(in) :: code
    type(run_record_t) :: record
    real(real64) :: nan
    nan = ieee_value(1.0_real64, ieee_quiet_nan)
    record%case_name = name
    record%scheme = '-'
    record%alpha = nan
    record%nu = nan
    record%g = nan
    record%c = nan
    record%f = nan
    record%cn = nan
    record%klt = nan
    record%fastsim = nan
    record%centroid = nan
    record%t_assemble = nan
    record%t_factor = nan
    record%t_solve = nan
    record%t_total = nan
    record%rcond = nan
    record%backward_error = nan
    record%verdict = error_word(code)
  end function failed_record

  !> The verdict of a case that failed with exit code code.
  pure function error_word(code) result(word)
    integer, intent(in) :: code
    character(len=:), allocatable :: word
    select case (code)
    case (exit_bad_input)
      word = 'error:bad-input'
    case (exit_numerical)
      word = 'error:numerical'
    case (exit_io)
      word = 'error:io'
    case default
      word = 'error:failed'
    end select
  end function error_word

  !> Open (or start) the partial table. One of this list (the same first
  !> line) is resumed; a torn last line, left by a kill in the middle of a
  !> write, is dropped so the case is simply run again. One left by a batch of
  !> another list (not running: this process holds the lock) is kept, when it
  !> has rows, as '<partial>.<its list signature>' and this batch starts
  !> afresh, or resumes from '<partial>.<this list's signature>' kept so before.
  subroutine resume_partial(partial_path, lock_fd, signature, hex, lines, status)
    character(len=*), intent(in) :: partial_path, signature, hex
    integer(c_int), intent(in) :: lock_fd
    type(text_t), allocatable, intent(out) :: lines(:)
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: tail, kept, other
    logical :: exists, from_kept
    integer :: unit, ios

    call read_text_file(partial_path, 'batch table', lines, tail, status)
    if (status%failed()) return
    kept = partial_path//'.'//hex
    from_kept = .false.
    inquire (file=kept, exist=exists)
    if (size(lines) == 0 .and. len(tail) == 0 .and. exists) then   ! new here: this list's, kept before?
      call read_text_file(kept, 'batch table', lines, tail, status)
      if (status%failed()) return
      from_kept = .true.
      write (output_unit, '(a)') 'kcreep: resuming from '''//kept//''' (kept there when another list ran on '// &
        'this table)'
    end if
    if (size(lines) > 0) then
      if (lines(1)%s /= signature .and. count_rows(lines) > 0) then
        other = partial_path//'.'//lines(1)%s(max(1, len(lines(1)%s) - 7):)   ! its list's signature
        inquire (file=other, exist=exists)
        if (exists .or. other == kept) then
          call fail(status, exit_bad_input, 'batch table '''//partial_path//''' is left from a batch of '// &
                    'another list, and '''//other//''', where it would be kept, exists too; remove one of them')
          return
        end if
        call write_text_file(other, joined(lines), 'batch table', status)
        if (status%failed()) return
        write (output_unit, '(a)') 'kcreep: '''//partial_path//''' held the unfinished batch of another list ('// &
          itoa(count_rows(lines))//' rows): kept as '''//other//''' (that list resumes from it); starting afresh'
      end if
      if (lines(1)%s /= signature) then
        deallocate (lines)
        allocate (lines(0))
      else if (len(tail) == 0 .and. .not. from_kept) then
        return                          ! clean: append to it as it is
      end if
    end if
    if (size(lines) == 0) lines = [text_t(signature)]
    call rewrite_locked(partial_path, lock_fd, lines, status)
    if (from_kept .and. .not. status%failed()) then
      open (newunit=unit, file=kept, status='old', iostat=ios)
      if (ios == 0) close (unit, status='delete')
    end if
  end subroutine resume_partial

  !> Replace the contents of the locked partial table in place (a new file
  !> renamed over it would not carry the lock).
  subroutine rewrite_locked(path, lock_fd, lines, status)
    character(len=*), intent(in) :: path
    integer(c_int), intent(in) :: lock_fd
    type(text_t), intent(in) :: lines(:)
    type(status_t), intent(inout) :: status
    integer :: unit, ios, k
    character(len=512) :: msg
    if (.not. truncate_locked(lock_fd)) then
      call fail(status, exit_io, 'batch table '''//path//''': cannot empty it to start over')
      return
    end if
    open (newunit=unit, file=path, status='old', action='write', position='rewind', iostat=ios, iomsg=msg)
    do k = 1, size(lines)
      if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=msg) lines(k)%s
    end do
    if (ios == 0) flush (unit, iostat=ios, iomsg=msg)
    if (ios == 0) close (unit, iostat=ios, iomsg=msg)
    if (ios /= 0) call fail(status, exit_io, 'batch table '''//path//''': cannot write ('//trim(msg)//')')
  end subroutine rewrite_locked

  !> Write the finished table from the partial one, then remove the partial one.
  !> tables: the cases are contact tables (&wheel_rail), else single patches.
  subroutine finish_table(partial_path, out_path, list_path, n_cases, n_failed, tables, status)
    character(len=*), intent(in) :: partial_path, out_path, list_path
    integer, intent(in) :: n_cases, n_failed
    logical, intent(in) :: tables
    type(status_t), intent(inout) :: status
    type(text_t), allocatable :: partial(:), lines(:), print_of(:), head(:)
    character(len=:), allocatable :: tail
    character(len=line_length), allocatable :: point_head(:)
    character(len=600), allocatable :: table_head(:)
    character(len=0) :: no_warnings(0)
    integer, allocatable :: case_of(:), order(:)
    integer :: j, k, nh, unit, ios

    call read_text_file(partial_path, 'batch table', partial, tail, status)
    if (status%failed()) return
    if (len(tail) > 0) then
      call fail(status, exit_io, 'batch table '''//partial_path//''': last line incomplete')
      return
    end if
    ! fixed comments, then the column names
    allocate (head(0), lines(0))
    if (tables) then
      table_head = wheel_rail_batch_head()
      do k = 1, size(table_head)
        head = [head, text_t(trim(table_head(k)))]
      end do
    else
      point_head = table_lines([run_record_t ::], no_warnings)
      do k = 1, size(point_head)
        head = [head, text_t(trim(point_head(k)))]
      end do
    end if
    nh = size(head)
    lines = head(1:nh - 1)
    lines = [lines, text_t('# batch '''//list_path//''': '//itoa(n_cases)//' cases, '// &
                           itoa(n_failed)//' failed (verdict error:...)')]
    ! per-case comments first, then the rows, both in list order (a resume may
    ! have run a changed case after later ones); line 1 is the signature
    call block_numbers(partial, case_of, print_of)
    order = case_order(case_of, n_cases)
    do j = 1, size(order)
      k = order(j)
      if (partial(k)%s(1:min(1, len(partial(k)%s))) /= '#') cycle
      if (index(partial(k)%s, fingerprint_mark) == 1) cycle
      lines = [lines, partial(k)]
    end do
    lines = [lines, head(nh)]
    do j = 1, size(order)
      if (is_row(partial(order(j))%s)) lines = [lines, partial(order(j))]
    end do
    call write_text_file(out_path, joined(lines), 'batch table', status)
    if (status%failed()) return
    open (newunit=unit, file=partial_path, status='old', iostat=ios)
    if (ios == 0) close (unit, status='delete')
  end subroutine finish_table

  !> The cases of a list file: one path per line, relative to the list's
  !> folder; names: each case's name in the table, its path relative to the
  !> list's folder without the extension (listed_case_name).
  subroutine read_case_list(list_path, cases, names, status)
    character(len=*), intent(in) :: list_path
    type(text_t), allocatable, intent(out) :: cases(:), names(:)
    type(status_t), intent(inout) :: status
    type(text_t), allocatable :: lines(:)
    character(len=:), allocatable :: tail, entry, list_folder, name
    integer :: k

    allocate (cases(0), names(0))
    list_folder = folder_of(list_path)
    if (len(list_folder) == 0) list_folder = '.'
    list_folder = real_path(list_folder)
    call read_text_file(list_path, 'batch list', lines, tail, status)
    if (status%failed()) return
    if (len(tail) > 0) lines = [lines, text_t(tail)]
    do k = 1, size(lines)
      entry = trim(adjustl(lines(k)%s))
      if (len(entry) == 0) cycle
      if (entry(1:1) == '#') cycle
      cases = [cases, text_t(resolve_path(entry, folder_of(list_path)))]
      name = listed_case_name(entry, list_folder)   ! (a temporary: gfortran 12 fails on the function result in the constructor)
      names = [names, text_t(name)]
    end do
    if (size(cases) == 0) call fail(status, exit_bad_input, 'batch list '''//list_path// &
        ''': no cases (expected one namelist path per line)')
  end subroutine read_case_list

  !> kcreep --estimate-memory: for each namelist one line 'FILE BYTES PATH' on
  !> standard output (the file as given, the bytes the case needs at its peak,
  !> the solve path it takes there: dense or iterative; the last two fields
  !> are single words, so a file name with blanks is read from the right), or
  !> one error line on standard error; every file is tried. n_failed: the
  !> files that could not be estimated.
  subroutine estimate_memory(paths, n_failed)
    type(text_t), intent(in) :: paths(:)
    integer, intent(out) :: n_failed
    type(config_t) :: cfg
    type(patch_t) :: patch
    type(status_t) :: status
    integer(int64) :: bytes
    character(len=:), allocatable :: method
    integer :: k
    n_failed = 0
    do k = 1, size(paths)
      status = status_t()
      call load_input(paths(k)%s, cfg, patch, status)
      if (.not. status%failed()) call case_memory_bytes(cfg, patch, bytes, method, status)
      if (status%failed()) then
        n_failed = n_failed + 1
        write (error_unit, '(a)') 'kcreep: error: '//status%message
      else
        write (output_unit, '(a, 1x, i0, 1x, a)') paths(k)%s, bytes, method
      end if
    end do
    flush (output_unit)
  end subroutine estimate_memory

  !> A case's name in a batch table: its path as the list gives it, relative
  !> to the list's folder (an absolute path inside that folder made relative;
  !> leading './' dropped), without the extension, blanks replaced. So
  !> a/case.nml and b/case.nml stay apart as a/case and b/case.
  !> list_folder: the list's folder as an absolute canonical path, or ''.
  function listed_case_name(entry, list_folder) result(name)
    character(len=*), intent(in) :: entry, list_folder
    character(len=:), allocatable :: name
    integer :: slash, dot, i
    name = entry
    if (len(list_folder) > 0 .and. len(name) > len(list_folder) + 1) then
      if (name(1:len(list_folder) + 1) == list_folder//'/') name = name(len(list_folder) + 2:)
    end if
    do while (len(name) > 2)
      if (name(1:2) /= './') exit
      name = name(3:)
    end do
    slash = index(name, '/', back=.true.)
    dot = index(name, '.', back=.true.)
    if (dot > slash + 1) name = name(1:dot - 1)
    do i = 1, len(name)
      if (name(i:i) == ' ' .or. iachar(name(i:i)) < 33) name(i:i) = '_'
    end do
    if (len(name) == 0) name = '-'
  end function listed_case_name

  !> One kind per batch table: tables is true when the cases (those that can
  !> be read; the others get their error rows) all have &wheel_rail, false
  !> when none has; a list mixing them is refused before any work. Two cases
  !> that write the same traction file, or the same wheel_rail_file, would
  !> overwrite each other: refused too.
  subroutine check_cases(list_path, cases, tables, status)
    character(len=*), intent(in) :: list_path
    type(text_t), intent(in) :: cases(:)
    logical, intent(out) :: tables
    type(status_t), intent(inout) :: status
    type(text_t), allocatable :: output(:)
    type(config_t) :: cfg
    type(status_t) :: case_status
    integer :: k, j, first_table, first_patch
    allocate (output(size(cases)))
    first_table = 0
    first_patch = 0
    do k = 1, size(cases)
      output(k)%s = ''
      case_status = status_t()
      call read_config(cases(k)%s, cfg, case_status)
      if (case_status%failed()) cycle
      if (cfg%wheel_rail_on) then
        if (first_table == 0) first_table = k
        output(k)%s = canonical_output(cfg%wheel_rail_file)
      else
        if (first_patch == 0) first_patch = k
        if (len(cfg%traction_file) > 0) output(k)%s = canonical_output(cfg%traction_file)
      end if
      if (first_table > 0 .and. first_patch > 0) then
        call fail(status, exit_bad_input, 'batch list '''//list_path//''': case '//itoa(first_table)//' '''// &
                  cases(first_table)%s//''' is a contact table (&wheel_rail) and case '//itoa(first_patch)// &
                  ' '''//cases(first_patch)%s//''' a single patch: one batch table holds one kind (give each '// &
                  'kind its own list)')
        return
      end if
      if (len(output(k)%s) == 0) cycle
      do j = 1, k - 1
        if (output(j)%s == output(k)%s) then
          call fail(status, exit_bad_input, 'batch list '''//list_path//''': cases '//itoa(j)//' '''// &
                    cases(j)%s//''' and '//itoa(k)//' '''//cases(k)%s//''' both write '// &
                    trim(merge('wheel_rail_file', 'traction_file  ', cfg%wheel_rail_on))//' '''//output(k)%s// &
                    ''' (the second would overwrite the first; give each case its own)')
          return
        end if
      end do
    end do
    tables = first_table > 0
  end subroutine check_cases

  !> An output path made comparable: its folder resolved (the file itself may not exist yet).
  function canonical_output(path) result(canonical)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: canonical, folder
    integer :: slash
    slash = index(path, '/', back=.true.)
    folder = folder_of(path)
    if (len(folder) == 0) folder = '.'
    folder = real_path(folder)
    if (len(folder) == 0) then
      canonical = path
    else
      canonical = folder//'/'//path(slash + 1:)
    end if
  end function canonical_output

  !> '<list name without folder and extension>.tab' in the working folder.
  pure function default_batch_table(list_path) result(name)
    character(len=*), intent(in) :: list_path
    character(len=:), allocatable :: name
    name = case_name(list_path)//'.tab'
  end function default_batch_table

  pure function seconds(t) result(text)
    real(real64), intent(in) :: t
    character(len=:), allocatable :: text
    character(len=24) :: buf
    write (buf, '(f12.3)') t
    text = trim(adjustl(buf))
  end function seconds

  !> A short checksum of the case paths, so that a partial table is only
  !> resumed by the list it was started from.
  pure function list_signature(cases) result(text)
    type(text_t), intent(in) :: cases(:)
    character(len=:), allocatable :: text
    integer(int64), parameter :: modulus = 2147483647_int64   ! 2^31 - 1, so h * 257 cannot overflow
    integer(int64) :: h
    integer :: k, i
    character(len=16) :: buf
    h = 1
    do k = 1, size(cases)
      do i = 1, len(cases(k)%s)
        h = mod(h * 257 + iachar(cases(k)%s(i:i)), modulus)
      end do
      h = mod(h * 257 + 10, modulus)
    end do
    write (buf, '(z8.8)') h
    text = trim(buf)
  end function list_signature

end module kcreep_app_batch
