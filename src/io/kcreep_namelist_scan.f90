!> A lexical pass over a namelist file before Fortran's namelist read sees
!> it. The namelist read skips, in silence, anything outside a group it is
!> asked for: a misspelt group name, a group given twice (only the first is
!> read), a stray 'mx = 10' without a group, a binary file. This pass turns
!> each of those into an error with its line number, and tells which of the
!> known groups are present.
module kcreep_namelist_scan
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, lower, printable
  implicit none
  private
  public :: scan_namelist_text

contains

  !> label: how the file is named in messages, e.g. "input 'a.nml'".
  !> closed: the group's closing / (or &end) was seen.
  pure subroutine scan_namelist_text(text, label, group_names, present, closed, status)
    character(len=*), intent(in) :: text, label
    character(len=*), intent(in) :: group_names(:)
    logical, intent(out) :: present(size(group_names))
    type(status_t), intent(inout) :: status
    logical, intent(out) :: closed(size(group_names))
    integer :: i, line, col, k, first, code, first_line(size(group_names)), current
    logical :: ended(size(group_names))
    logical :: inside
    character :: quote, c
    character(len=:), allocatable :: word

    present = .false.
    ended = .false.
    current = 0
    first_line = 0
    inside = .false.
    quote = ' '
    line = 1
    col = 0
    i = 0
    do while (i < len(text))
      i = i + 1
      c = text(i:i)
      col = col + 1
      code = iachar(c)
      if (c == achar(10)) then
        line = line + 1
        col = 0
        cycle
      end if
      if (code < 32 .and. code /= 9 .and. code /= 13 .or. code == 127) then
        call fail(status, exit_bad_input, label//', line '//itoa(line)//', column '//itoa(col)// &
                  ': control character '//printable(c)//' (a namelist is plain text)')
        return
      end if
      if (quote /= ' ') then                      ! inside a string
        if (c == quote) quote = ' '
        cycle
      end if
      if (c == ' ' .or. code == 9 .or. code == 13) cycle
      if (c == '!') then                          ! comment: skip to the end of the line
        call skip_line(text, i)
        cycle
      end if
      if (inside) then
        if (c == '''' .or. c == '"') then
          quote = c
        else if (c == '/') then                   ! end of the group; the rest of the line is a comment
          inside = .false.
          ended(current) = .true.
          call skip_line(text, i)
        else if (c == '&') then
          if (lower(name_at(i + 1)) == 'end') then
            inside = .false.
            ended(current) = .true.
            call skip_line(text, i)
          end if
        end if
        cycle
      end if
      ! outside any group: only '&name' may start here
      if (c /= '&') then
        first = i
        call skip_line(text, i)
        call fail(status, exit_bad_input, label//', line '//itoa(line)//': text outside any namelist group ('''// &
                  shorten(text(first:i))//'''); groups start with &patch, &material, &solver or &output, '// &
                  'comments with !')
        return
      end if
      word = lower(name_at(i + 1))
      i = i + len(word)
      col = col + len(word)
      if (word == 'end') cycle
      k = 0
      do first = 1, size(group_names)   ! (findloc on strings of unequal length is unreliable in gfortran)
        if (len(word) > 0 .and. trim(group_names(first)) == word) k = first
      end do
      if (k == 0) then
        call fail(status, exit_bad_input, label//', line '//itoa(line)//': unknown namelist group &'// &
                  shorten(word)//' (known: &patch, &material, &solver, &output)')
        return
      end if
      if (present(k)) then
        call fail(status, exit_bad_input, label//', line '//itoa(line)//': namelist group &'//word// &
                  ' given twice (first on line '//itoa(first_line(k))//'); only one is allowed')
        return
      end if
      present(k) = .true.
      first_line(k) = line
      current = k
      inside = .true.
    end do
    closed = ended

  contains

    !> The name (letters, digits, '_') that starts at position pos.
    pure function name_at(pos) result(name)
      integer, intent(in) :: pos
      character(len=:), allocatable :: name
      integer :: j
      j = pos
      do while (j <= len(text))
        if (verify(text(j:j), 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') /= 0) exit
        j = j + 1
      end do
      name = text(pos:j - 1)
    end function name_at

  end subroutine scan_namelist_text

  !> Move pos to the last character before the next line end.
  pure subroutine skip_line(text, pos)
    character(len=*), intent(in) :: text
    integer, intent(inout) :: pos
    do while (pos < len(text))
      if (text(pos + 1:pos + 1) == achar(10)) exit
      pos = pos + 1
    end do
  end subroutine skip_line

  !> At most 40 characters of a piece of input, for a message.
  pure function shorten(s) result(t)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: t
    if (len_trim(s) > 40) then
      t = s(1:37)//'...'
    else
      t = trim(s)
    end if
  end function shorten

end module kcreep_namelist_scan
