!> The text of a CONTACT output as lines, and reading it: the line holding
!> a key, the values under named header columns, tokens as numbers (errors
!> naming what was read and the token). Used by kcreep_contact_reader.
module kcreep_contact_text
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa
  implicit none
  private
  public :: text_t, max_line, max_tokens, find_line, read_columns, column, has, to_reals, to_integers, split, read_text

  integer, parameter :: max_line = 8192
  integer, parameter :: max_tokens = 64

  type :: text_t
    character(len=max_line), allocatable :: lines(:)
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
      if (index(text%lines(i), key) > 0) then
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
    call split(text%lines(line_no + offset), head, nh)
    call split(text%lines(line_no + offset + 1), vals, nv)
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

  !> All lines of a text file.
  subroutine read_text(path, what, text, status)
    character(len=*), intent(in) :: path, what
    type(text_t), intent(out) :: text
    type(status_t), intent(inout) :: status
    integer :: unit, ios, n
    character(len=512) :: msg
    character(len=max_line) :: line

    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_bad_input, what//' '''//path//''': cannot open ('//trim(msg)//')')
      return
    end if
    n = 0
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      n = n + 1
    end do
    if (.not. is_iostat_end(ios)) then
      close (unit)
      call fail(status, exit_bad_input, what//' '''//path//''': cannot be read as text')
      return
    end if
    allocate (text%lines(n))
    text%n = n
    rewind (unit)
    do n = 1, text%n
      read (unit, '(a)') text%lines(n)
    end do
    close (unit)
  end subroutine read_text

end module kcreep_contact_text
