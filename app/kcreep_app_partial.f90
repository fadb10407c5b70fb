!> The partial table of kcreep --batch, read back: its lines (text files
!> read whole), the blocks of each case (comments, '# fingerprint K HEX N',
!> its N rows), which of them still hold for the inputs as they are now, and
!> the rows' verdicts.
module kcreep_app_partial
  use, intrinsic :: iso_fortran_env, only: output_unit
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa
  use kcreep_table, only: table_columns
  implicit none
  private
  public :: text_t, fingerprint_mark, keep_unchanged, block_numbers, case_order, is_row, count_rows, &
            count_error_rows, read_text_file, joined

  !> A line of text of any length.
  type :: text_t
    character(len=:), allocatable :: s
  end type text_t

  !> The line before each case's rows in a partial table: this, the case's
  !> number, its fingerprint, its number of rows.
  character(len=*), parameter :: fingerprint_mark = '# fingerprint '

contains

  !> Keep of a partial table (line 1, its signature, and then blocks: a case's
  !> comments, its '# fingerprint K HEX N' line, its N rows) the blocks whose
  !> fingerprint is the case's now; done(k): case k has its row. Blocks of a
  !> changed case are dropped and the case named on standard output, as are
  !> rows without a fingerprint and comments without a row. n_dropped:
  !> lines dropped.
  subroutine keep_unchanged(lines, cases, prints, done, n_dropped)
    type(text_t), allocatable, intent(inout) :: lines(:)
    type(text_t), intent(in) :: cases(:), prints(:)
    logical, allocatable, intent(out) :: done(:)
    integer, intent(out) :: n_dropped
    type(text_t), allocatable :: print_of(:)
    integer, allocatable :: case_of(:)
    logical, allocatable :: keep(:), named(:)
    integer :: i, k, n_stale
    allocate (done(size(cases)), named(size(cases)))
    done = .false.
    named = .false.
    call block_numbers(lines, case_of, print_of)
    allocate (keep(size(lines)))
    keep = .false.
    if (size(lines) > 0) keep(1) = .true.
    n_stale = 0
    do i = 2, size(lines)
      if (.not. is_row(lines(i)%s)) cycle
      k = case_of(i)
      if (k < 1 .or. k > size(cases)) then
        n_stale = n_stale + 1
      else if (done(k) .or. named(k)) then
        cycle
      else if (print_of(i)%s == prints(k)%s) then
        done(k) = .true.
        where (case_of == k) keep = .true.
      else
        named(k) = .true.
        write (output_unit, '(a)') 'kcreep: case '//itoa(k)//' '''//cases(k)%s//''': its inputs changed since '// &
          'its row was written (the namelist, a file it reads, or the program): running it again'
      end if
    end do
    if (n_stale > 0) write (output_unit, '(a)') 'kcreep: '//itoa(n_stale)//' rows without an input fingerprint '// &
      '(from an older kcreep): their cases run again'
    n_dropped = count(.not. keep)
    if (n_dropped > 0) lines = pack(lines, keep)
  end subroutine keep_unchanged

  !> For each line of a partial table, the case of its block (0 for line 1,
  !> and for lines of no complete block) and, on its rows, its fingerprint.
  !> A block: the case's comments, '# fingerprint K HEX N', then its N rows
  !> (N: 1 for a single patch, one per shift and patch of a contact table;
  !> 1 when the mark gives none). A block cut short (a kill while its rows
  !> were written) is no block: its case runs again.
  subroutine block_numbers(lines, case_of, print_of)
    type(text_t), intent(in) :: lines(:)
    integer, allocatable, intent(out) :: case_of(:)
    type(text_t), allocatable, intent(out) :: print_of(:)
    integer :: i, first, k, need
    character(len=:), allocatable :: hex
    allocate (case_of(size(lines)), print_of(size(lines)))
    case_of = 0
    do i = 1, size(lines)
      print_of(i)%s = ''
    end do
    first = 2
    k = 0
    need = 0
    hex = ''
    do i = 2, size(lines)
      if (index(lines(i)%s, fingerprint_mark) == 1) then
        if (k /= 0) first = i          ! a mark after a block cut short: that block is dropped
        call read_mark(lines(i)%s(len(fingerprint_mark) + 1:), k, hex, need)
      else if (is_row(lines(i)%s)) then
        print_of(i)%s = hex
        need = need - 1
        if (k == 0 .or. need <= 0) then   ! the block's last row (or a row of no block)
          case_of(first:i) = k
          first = i + 1
          k = 0
          hex = ''
        end if
      else if (k /= 0) then            ! a comment inside a block's rows: it was cut short
        first = i
        k = 0
        hex = ''
      end if
    end do

  contains

    !> 'K HEX [N]' of a mark; k = 0 when it cannot be read.
    subroutine read_mark(text, k, hex, n)
      character(len=*), intent(in) :: text
      integer, intent(out) :: k, n
      character(len=:), allocatable, intent(out) :: hex
      character(len=len(text)) :: word
      integer :: k_again, ios
      read (text, *, iostat=ios) k, word
      if (ios /= 0) k = 0
      hex = trim(word)
      if (ios /= 0) hex = ''
      read (text, *, iostat=ios) k_again, word, n
      if (ios /= 0) n = 1
    end subroutine read_mark

  end subroutine block_numbers

  !> Line numbers of a partial table's blocks by case, 1 to n_cases (each
  !> block's lines in file order), then lines of no case (a stable sort).
  pure function case_order(case_of, n_cases) result(order)
    integer, intent(in) :: case_of(:), n_cases
    integer, allocatable :: order(:)
    integer :: start(0:n_cases + 1), i, k, first, count_k
    start = 0
    do i = 2, size(case_of)
      k = merge(case_of(i), n_cases + 1, case_of(i) >= 1 .and. case_of(i) <= n_cases)
      start(k) = start(k) + 1
    end do
    allocate (order(sum(start)))
    ! running offsets: start(k) becomes the first slot of case k
    first = 1
    do i = 0, n_cases + 1
      count_k = start(i)
      start(i) = first
      first = first + count_k
    end do
    do i = 2, size(case_of)
      k = merge(case_of(i), n_cases + 1, case_of(i) >= 1 .and. case_of(i) <= n_cases)
      order(start(k)) = i
      start(k) = start(k) + 1
    end do
  end function case_order

  pure logical function is_row(line)
    character(len=*), intent(in) :: line
    is_row = len_trim(line) > 0
    if (is_row) is_row = line(1:1) /= '#'
  end function is_row

  pure integer function count_rows(lines) result(n)
    type(text_t), intent(in) :: lines(:)
    integer :: k
    n = 0
    do k = 1, size(lines)
      if (is_row(lines(k)%s)) n = n + 1
    end do
  end function count_rows

  !> Rows whose verdict (the table's verdict column, not the last word: more
  !> columns follow it) starts with 'error:'.
  !> columns: the table's column names [table_columns: a batch of single patches].
  pure integer function count_error_rows(lines, columns) result(n)
    type(text_t), intent(in) :: lines(:)
    character(len=*), intent(in), optional :: columns
    integer :: k, column
    n = 0
    if (present(columns)) then
      column = verdict_column(columns)
    else
      column = verdict_column(table_columns)
    end if
    do k = 1, size(lines)
      if (.not. is_row(lines(k)%s)) cycle
      if (index(word_of(lines(k)%s, column), 'error:') == 1) n = n + 1
    end do
  end function count_error_rows

  !> Position of 'verdict' among the table's columns.
  pure integer function verdict_column(columns)
    character(len=*), intent(in) :: columns
    verdict_column = 1
    do while (word_of(columns, verdict_column) /= 'verdict' .and. len(word_of(columns, verdict_column)) > 0)
      verdict_column = verdict_column + 1
    end do
  end function verdict_column

  !> Word k (blank-separated) of text, '' when there are fewer.
  pure function word_of(text, k) result(word)
    character(len=*), intent(in) :: text
    integer, intent(in) :: k
    character(len=:), allocatable :: word
    integer :: i, first, count
    count = 0
    i = 1
    word = ''
    do while (i <= len(text))
      if (text(i:i) == ' ') then
        i = i + 1
        cycle
      end if
      first = i
      do while (i <= len(text))
        if (text(i:i) == ' ') exit
        i = i + 1
      end do
      count = count + 1
      if (count == k) then
        word = text(first:i - 1)
        return
      end if
    end do
  end function word_of

  !> The whole file as lines; tail is what follows the last newline (a torn line).
  subroutine read_text_file(path, what, lines, tail, status)
    character(len=*), intent(in) :: path, what
    type(text_t), allocatable, intent(out) :: lines(:)
    character(len=:), allocatable, intent(out) :: tail
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: buffer
    integer :: unit, ios, size_bytes, first, k, n
    character(len=512) :: msg

    allocate (lines(0))
    tail = ''
    open (newunit=unit, file=path, access='stream', form='unformatted', status='old', action='read', &
          iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_bad_input, what//' '''//path//''': cannot open ('//trim(msg)//')')
      return
    end if
    inquire (unit=unit, size=size_bytes)
    allocate (character(len=max(size_bytes, 0)) :: buffer)
    if (size_bytes > 0) read (unit, iostat=ios, iomsg=msg) buffer
    close (unit)
    if (ios /= 0) then
      call fail(status, exit_bad_input, what//' '''//path//''': cannot read ('//trim(msg)//')')
      return
    end if
    n = 0
    do k = 1, len(buffer)
      if (buffer(k:k) == achar(10)) n = n + 1
    end do
    deallocate (lines)
    allocate (lines(n))
    first = 1
    n = 0
    do k = 1, len(buffer)
      if (buffer(k:k) /= achar(10)) cycle
      n = n + 1
      lines(n)%s = buffer(first:k - 1)
      first = k + 1
    end do
    tail = buffer(first:)
  end subroutine read_text_file

  !> Lines as one fixed-length array for write_text_file.
  function joined(lines) result(fixed)
    type(text_t), intent(in) :: lines(:)
    character(len=:), allocatable :: fixed(:)
    integer :: k, width
    width = 1
    do k = 1, size(lines)
      width = max(width, len(lines(k)%s))
    end do
    allocate (character(len=width) :: fixed(size(lines)))
    do k = 1, size(lines)
      fixed(k) = lines(k)%s
    end do
  end function joined

end module kcreep_app_partial
