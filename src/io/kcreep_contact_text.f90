!> The text of a CONTACT output as lines, and reading it: the line holding
!> a key, the values under named header columns, tokens as numbers (errors
!> naming what was read and the token). Used by kcreep_contact_reader.
module kcreep_contact_text
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa
  implicit none
  private
  public :: text_t, max_tokens, find_line, read_columns, column, has, to_reals, to_integers, split, read_text, &
            token_bounds, integer_of

  integer, parameter :: max_tokens = 64

  !> One line of the file, as long as it is (no padding: a CONTACT .mat has
  !> a line per element, and lines padded to a fixed 8192 characters made
  !> reading a file cost more than solving its case, issue 45).
  type :: line_t
    character(len=:), allocatable :: s
  end type line_t

  type :: text_t
    type(line_t), allocatable :: lines(:)
    integer :: n = 0
  end type text_t

contains

  integer function find_line(text, first, last, key) result(line_no)
    type(text_t), intent(in) :: text
    integer, intent(in) :: first, last
    character(len=*), intent(in) :: key
    integer :: i
    line_no = 0
    do i = first, last
      if (index(text%lines(i)%s, key) > 0) then
        line_no = i
        return
      end if
    end do
  end function find_line

  !> Value tokens under the named header columns: the header is the line
  !> `offset` lines after the first one containing `anchor`, the values the line after it.
  subroutine read_columns(text, first, last, anchor, offset, names, what, tok, status)
    type(text_t), intent(in) :: text
    integer, intent(in) :: first, last, offset
    character(len=*), intent(in) :: anchor, names(:), what
    character(len=32), intent(out) :: tok(:)
    type(status_t), intent(inout) :: status
    character(len=32) :: head(max_tokens), vals(max_tokens)
    integer :: line_no, nh, nv, k, pos

    tok = ''
    if (status%failed()) return
    line_no = find_line(text, first, last, anchor)
    if (line_no == 0 .or. line_no + offset + 1 > last) then
      call fail(status, exit_bad_input, what//': block missing or cut short (truncated file?)')
      return
    end if
    call split(text%lines(line_no + offset)%s, head, nh)
    call split(text%lines(line_no + offset + 1)%s, vals, nv)
    do k = 1, size(names)
      pos = findloc(head(1:nh), names(k), dim=1)
      if (pos == 0 .or. pos > nv) then
        call fail(status, exit_bad_input, what//', line '//itoa(line_no + offset + 1)//': no value for '// &
                  trim(names(k))//' (truncated or malformed file?)')
        return
      end if
      tok(k) = vals(pos)
    end do
  end subroutine read_columns

  !> Token under header column `name` ('%' counts as a header token, not a value column).
  function column(head, nh, vals, nv, name) result(tok)
    character(len=*), intent(in) :: head(:), vals(:), name
    integer, intent(in) :: nh, nv
    character(len=32) :: tok
    integer :: pos
    tok = ''
    pos = findloc(head(1:nh), name, dim=1)
    if (head(1) == '%') pos = pos - 1
    if (pos >= 1 .and. pos <= nv) tok = vals(pos)
  end function column

  logical function has(words, name)
    character(len=*), intent(in) :: words(:), name
    has = findloc(words, name, dim=1) > 0
  end function has

  subroutine to_reals(tok, what, v, status)
    character(len=*), intent(in) :: tok(:), what
    real(real64), intent(out) :: v(:)
    type(status_t), intent(inout) :: status
    integer :: k, ios
    v = 0
    if (status%failed()) return
    do k = 1, size(tok)
      ios = 1
      if (len_trim(tok(k)) > 0 .and. verify(trim(tok(k)), '0123456789+-.EeDd') == 0) &
        read (tok(k), *, iostat=ios) v(k)
      if (ios /= 0) then
        call fail(status, exit_bad_input, what//': cannot read a number from '''//trim(tok(k))//'''')
        return
      end if
    end do
  end subroutine to_reals

  subroutine to_integers(tok, what, v, status)
    character(len=*), intent(in) :: tok(:), what
    integer, intent(out) :: v(:)
    type(status_t), intent(inout) :: status
    integer :: k, ios
    v = 0
    if (status%failed()) return
    do k = 1, size(tok)
      ios = 1
      if (len_trim(tok(k)) > 0 .and. verify(trim(tok(k)), '0123456789+-') == 0) &
        read (tok(k), *, iostat=ios) v(k)
      if (ios /= 0) then
        call fail(status, exit_bad_input, what//': cannot read an integer from '''//trim(tok(k))//'''')
        return
      end if
    end do
  end subroutine to_integers

  !> Blank-separated tokens of a line.
  pure subroutine split(line, tok, n)
    character(len=*), intent(in) :: line
    character(len=*), intent(out) :: tok(:)
    integer, intent(out) :: n
    integer :: i, start
    n = 0
    tok = ''
    i = 1
    do while (i <= len_trim(line))
      if (line(i:i) == ' ' .or. line(i:i) == achar(9)) then
        i = i + 1
        cycle
      end if
      start = i
      do while (i <= len(line))
        if (line(i:i) == ' ' .or. line(i:i) == achar(9)) exit
        i = i + 1
      end do
      if (n == size(tok)) return
      n = n + 1
      tok(n) = line(start:i - 1)
    end do
  end subroutine split

  !> Where the k-th blank-separated token of line is: line(first:last);
  !> first = 0 when the line has fewer tokens. Nothing is copied (a .mat
  !> has a line per element).
  pure subroutine token_bounds(line, k, first, last)
    character(len=*), intent(in) :: line
    integer, intent(in) :: k
    integer, intent(out) :: first, last
    integer :: i, n
    first = 0
    last = 0
    n = 0
    i = 1
    do while (i <= len(line))
      if (line(i:i) == ' ' .or. line(i:i) == achar(9)) then
        i = i + 1
        cycle
      end if
      n = n + 1
      if (n == k) first = i
      do while (i <= len(line))
        if (line(i:i) == ' ' .or. line(i:i) == achar(9)) exit
        i = i + 1
      end do
      if (n == k) then
        last = i - 1
        return
      end if
    end do
  end subroutine token_bounds

  !> The integer written in s (an optional sign, then digits only); ok false
  !> for anything else or a value beyond the default integer's range.
  pure subroutine integer_of(s, v, ok)
    character(len=*), intent(in) :: s
    integer, intent(out) :: v
    logical, intent(out) :: ok
    integer :: i, start, digit
    integer(int64) :: acc
    v = 0
    acc = 0
    start = 1
    if (len(s) > 0) then
      if (s(1:1) == '+' .or. s(1:1) == '-') start = 2
    end if
    ok = len(s) >= start
    do i = start, len(s)
      digit = iachar(s(i:i)) - iachar('0')
      if (digit < 0 .or. digit > 9 .or. acc > huge(v)) then
        ok = .false.
        return
      end if
      acc = 10 * acc + digit
    end do
    if (s(1:min(1, len(s))) == '-') acc = -acc
    ok = ok .and. abs(acc) <= huge(v)
    if (ok) v = int(acc)
  end subroutine integer_of

  !> All lines of a text file (read at once; a line ends LF or CR LF, a
  !> last line without one counts).
  subroutine read_text(path, what, text, status)
    character(len=*), intent(in) :: path, what
    type(text_t), intent(out) :: text
    type(status_t), intent(inout) :: status
    integer :: unit, ios, n, start, i, last
    integer, allocatable :: ends(:)
    integer(int64) :: bytes
    character(len=512) :: msg
    character(len=:), allocatable :: buffer

    open (newunit=unit, file=path, status='old', action='read', access='stream', form='unformatted', &
          iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_bad_input, what//' '''//path//''': cannot open ('//trim(msg)//')')
      return
    end if
    inquire (unit=unit, size=bytes)
    ios = merge(0, 1, bytes >= 0 .and. bytes < huge(1))
    if (ios == 0) then
      allocate (character(len=int(bytes)) :: buffer)
      if (bytes > 0) read (unit, iostat=ios) buffer
    end if
    close (unit)
    if (ios /= 0) then
      call fail(status, exit_bad_input, what//' '''//path//''': cannot be read as text')
      return
    end if
    ! the line ends (a last line without one ends at the end of the buffer)
    n = 0
    do i = 1, len(buffer)
      if (buffer(i:i) == achar(10)) n = n + 1
    end do
    if (len(buffer) > 0) then
      if (buffer(len(buffer):) /= achar(10)) n = n + 1
    end if
    allocate (ends(n), text%lines(n))
    text%n = n
    n = 0
    do i = 1, len(buffer)
      if (buffer(i:i) /= achar(10)) cycle
      n = n + 1
      ends(n) = i
    end do
    if (n < text%n) ends(text%n) = len(buffer) + 1
    start = 1
    do i = 1, text%n
      last = ends(i) - 1
      if (last >= start) then
        if (buffer(last:last) == achar(13)) last = last - 1
      end if
      text%lines(i)%s = buffer(start:last)
      start = ends(i) + 1
    end do
  end subroutine read_text

end module kcreep_contact_text
