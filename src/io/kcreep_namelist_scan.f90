!> A lexical pass over a namelist file before Fortran's namelist read sees
!> it. The namelist read skips, in silence, anything outside a group it is
!> asked for: a misspelt group name, a group given twice (only the first is
!> read), a stray 'mx = 10' without a group, a binary file. This pass turns
!> each of those into an error with its line number, and tells which of the
!> known groups are present. A group may follow another on the same line
!> (the namelist read finds it there); anything else after a group's closing
!> / other than a comment is text outside the groups.
module kcreep_namelist_scan
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, lower, printable
  implicit none
  private
  public :: scan_namelist_text, diagnose_group

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
        else if (c == '/') then                   ! end of the group; what follows is read as outside any
          inside = .false.
          ended(current) = .true.
        else if (c == '&') then
          word = name_at(i + 1)
          if (lower(word) /= 'end') then
            call fail(status, exit_bad_input, label//', line '//itoa(line)//': namelist group &'// &
                      trim(group_names(current))//' (line '//itoa(first_line(current))// &
                      ') is not closed with / before &'//shorten(word))
            return
          end if
          inside = .false.
          ended(current) = .true.
          i = i + len(word)
          col = col + len(word)
        end if
        cycle
      end if
      ! outside any group: only '&name' may start here
      if (c /= '&') then
        first = i
        call skip_line(text, i)
        call fail(status, exit_bad_input, label//', line '//itoa(line)//': text outside any namelist group ('''// &
                  shorten(text(first:i))//'''); groups start with '//known()//', comments with !')
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
                  shorten(word)//' (known: '//known()//')')
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

    !> '&patch, &material, ...': the groups asked for.
    pure function known() result(list)
      character(len=:), allocatable :: list
      integer :: j
      list = '&'//trim(group_names(1))
      do j = 2, size(group_names)
        list = list//', &'//trim(group_names(j))
      end do
    end function known

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

  !> Why the namelist read of group failed, in the input's terms: a name that
  !> is not one of the group's variables (listing them), a value of the
  !> wrong type (naming the variable and its type), or more values than the
  !> variable takes. variables: 'name kind [size]', kind integer, real,
  !> logical or character; size the number of values an array takes, or
  !> 'list' for the group's long list, which takes list_most (a scalar
  !> takes one). Empty when nothing is found (the caller keeps the
  !> compiler's message then).
  pure function diagnose_group(text, group, variables, list_most) result(message)
    character(len=*), intent(in) :: text, group
    character(len=*), intent(in) :: variables(:)
    integer, intent(in), optional :: list_most
    character(len=:), allocatable :: message
    character(len=:), allocatable :: body, name, kind, allowed, size_word
    integer, allocatable :: first(:), last(:)
    integer :: n, k, j, v, end_values, most, given, star

    message = ''
    body = group_body(text, group)
    call split_tokens(body, first, last, n)
    do k = 2, n
      if (body(first(k):last(k)) /= '=') cycle
      name = lower(body(first(k - 1):last(k - 1)))
      if (index(name, '(') > 1) name = name(1:index(name, '(') - 1)
      v = 0
      do j = 1, size(variables)
        if (word(variables(j), 1) == name) v = j
      end do
      if (v == 0) then
        allowed = word(variables(1), 1)
        do j = 2, size(variables)
          allowed = allowed//', '//word(variables(j), 1)
        end do
        message = '&'//group//': '''//shorten(name)//''' is not a variable of &'//group//' (allowed: '//allowed//')'
        return
      end if
      kind = word(variables(v), 2)
      ! the values run up to the name before the next '='
      end_values = n
      do j = k + 1, n
        if (body(first(j):last(j)) == '=') then
          end_values = j - 2
          exit
        end if
      end do
      do j = k + 1, end_values
        if (.not. fits(body(first(j):last(j)), kind)) then
          message = '&'//group//' '//name//' = '//shorten(body(first(j):last(j)))//': '//name//' is '// &
                    described(kind)
          return
        end if
      end do
      ! how many values: r*value counts r
      size_word = word(variables(v), 3)
      most = 1
      if (size_word == 'list') then
        most = huge(1)
        if (present(list_most)) most = list_most
      else if (len(size_word) > 0) then
        most = value_of(size_word)
      end if
      given = element_offset(body(first(k - 1):last(k - 1)))   ! name(i) = ...: values from element i on
      do j = k + 1, end_values
        given = given + 1
        star = index(body(first(j):last(j)), '*')
        if (star > 1) then
          if (verify(body(first(j):first(j) + star - 2), '0123456789') == 0 .and. star <= 10) &
            given = given - 1 + value_of(body(first(j):first(j) + star - 2))
        end if
      end do
      if (given > most) then
        message = '&'//group//' '//name//': '//itoa(given)//' values given (allowed: at most '//itoa(most)//')'
        return
      end if
    end do

  contains

    !> i - 1 for 'name(i)' or 'name(i:j)', else 0.
    pure integer function element_offset(token)
      character(len=*), intent(in) :: token
      integer :: open, stop
      element_offset = 0
      open = index(token, '(')
      if (open == 0) return
      stop = open
      do while (stop < len(token))
        if (index('0123456789', token(stop + 1:stop + 1)) == 0) exit
        stop = stop + 1
      end do
      if (stop > open .and. stop - open <= 9) element_offset = value_of(token(open + 1:stop)) - 1
    end function element_offset

    !> The value of up to 9 decimal digits.
    pure integer function value_of(digits)
      character(len=*), intent(in) :: digits
      integer :: i
      value_of = 0
      do i = 1, len(digits)
        value_of = 10 * value_of + (iachar(digits(i:i)) - iachar('0'))
      end do
    end function value_of

  end function diagnose_group

  !> The text of group (after '&group', up to its closing '/' or '&end'),
  !> comments blanked; empty when the group is not there. One pass, then one
  !> copy: a group of a million values takes milliseconds.
  pure function group_body(text, group) result(body)
    character(len=*), intent(in) :: text, group
    character(len=*), parameter :: separators = ' ,'//achar(9)//achar(10)//achar(13)
    character(len=:), allocatable :: body
    integer :: i, start, stop
    character :: quote
    logical :: inside, comment

    inside = .false.
    comment = .false.
    quote = ' '
    start = 1
    stop = len(text)
    i = 0
    do while (i < len(text))
      i = i + 1
      if (text(i:i) == achar(10)) comment = .false.
      if (comment) cycle
      if (quote /= ' ') then
        if (text(i:i) == quote) quote = ' '
        cycle
      end if
      if (text(i:i) == '!') then
        comment = .true.
        cycle
      end if
      if (inside) then
        if (text(i:i) == '/' .or. text(i:i) == '&') then
          stop = i - 1
          exit
        end if
        if (text(i:i) == '''' .or. text(i:i) == '"') quote = text(i:i)
      else if (text(i:i) == '&' .and. i + len(group) < len(text)) then
        if (lower(text(i + 1:i + len(group))) == group .and. &
            index(separators, text(i + len(group) + 1:i + len(group) + 1)) > 0) then
          inside = .true.
          start = i + len(group) + 1
          i = start - 1
        end if
      end if
    end do
    if (.not. inside) then
      body = ''
      return
    end if
    body = text(start:stop)
    ! blank the comments (strings as above)
    comment = .false.
    quote = ' '
    do i = 1, len(body)
      if (body(i:i) == achar(10)) comment = .false.
      if (comment) then
        body(i:i) = ' '
      else if (quote /= ' ') then
        if (body(i:i) == quote) quote = ' '
      else if (body(i:i) == '!') then
        comment = .true.
        body(i:i) = ' '
      else if (body(i:i) == '''' .or. body(i:i) == '"') then
        quote = body(i:i)
      end if
    end do
  end function group_body

  !> Tokens of a group's text: quoted strings, '=', and runs of other
  !> characters between blanks and commas (first(k):last(k) in text).
  pure subroutine split_tokens(text, first, last, n)
    character(len=*), intent(in) :: text
    integer, allocatable, intent(out) :: first(:), last(:)
    integer, intent(out) :: n
    integer :: i, j
    character(len=*), parameter :: separators = ' ,'//achar(9)//achar(10)//achar(13)

    allocate (first(len(text) + 1), last(len(text) + 1))
    n = 0
    i = 1
    do while (i <= len(text))
      if (index(separators, text(i:i)) > 0) then
        i = i + 1
        cycle
      end if
      n = n + 1
      first(n) = i
      if (text(i:i) == '=') then
        j = i
      else if (text(i:i) == '''' .or. text(i:i) == '"') then
        j = i + 1
        do while (j <= len(text))
          if (text(j:j) == text(i:i)) then
            if (j < len(text)) then
              if (text(j + 1:j + 1) == text(i:i)) then   ! a doubled quote inside
                j = j + 2
                cycle
              end if
            end if
            exit
          end if
          j = j + 1
        end do
        j = min(j, len(text))
      else
        j = i
        do while (j < len(text))
          if (index(separators//'=', text(j + 1:j + 1)) > 0) exit
          j = j + 1
        end do
      end if
      last(n) = j
      i = j + 1
    end do
  end subroutine split_tokens

  !> A namelist value (r*value repeats allowed) can be read as kind.
  pure logical function fits(token, kind)
    character(len=*), intent(in) :: token, kind
    character(len=:), allocatable :: v
    integer :: star, i, digits, k
    character(len=*), parameter :: numeral = '0123456789'

    v = token
    star = index(v, '*')
    if (star > 1) then
      if (verify(v(1:star - 1), numeral) == 0) v = v(star + 1:)
    end if
    fits = .true.
    if (len(v) == 0) return                 ! a null value
    select case (kind)
    case ('character')
      fits = v(1:1) == '''' .or. v(1:1) == '"'
    case ('logical')
      k = 1
      if (v(1:1) == '.') k = 2
      fits = .false.
      if (k <= len(v)) fits = index('tTfF', v(k:k)) > 0
    case ('integer')
      k = 1
      if (index('+-', v(1:1)) > 0) k = 2
      fits = k <= len(v)
      if (fits) fits = verify(v(k:), numeral) == 0
    case ('real')
      select case (lower(v))
      case ('nan', 'inf', '+inf', '-inf', 'infinity', '+infinity', '-infinity')
        return
      end select
      i = 1
      if (index('+-', v(1:1)) > 0) i = 2
      digits = 0
      do while (i <= len(v))
        if (index(numeral, v(i:i)) == 0) exit
        digits = digits + 1
        i = i + 1
      end do
      if (i <= len(v)) then
        if (v(i:i) == '.') then
          i = i + 1
          do while (i <= len(v))
            if (index(numeral, v(i:i)) == 0) exit
            digits = digits + 1
            i = i + 1
          end do
        end if
      end if
      fits = digits > 0
      if (fits .and. i <= len(v)) then
        fits = index('eEdD', v(i:i)) > 0
        i = i + 1
        if (fits .and. i <= len(v)) then
          if (index('+-', v(i:i)) > 0) i = i + 1
        end if
        fits = fits .and. i <= len(v)
        if (fits) fits = verify(v(i:), numeral) == 0
      end if
    end select
  end function fits

  !> What a variable of kind is and how to write one.
  pure function described(kind) result(text)
    character(len=*), intent(in) :: kind
    character(len=:), allocatable :: text
    select case (kind)
    case ('integer')
      text = 'an integer (a whole number, e.g. 60)'
    case ('real')
      text = 'a real number (e.g. 2, 0.25 or 1e-3)'
    case ('logical')
      text = 'a logical (.true. or .false.)'
    case default
      text = 'a text (in quotes, e.g. ''ellipse'')'
    end select
  end function described

  !> Word k (1, 2 or 3) of 'name kind size'; empty when there is none.
  pure function word(entry, k) result(w)
    character(len=*), intent(in) :: entry
    integer, intent(in) :: k
    character(len=:), allocatable :: w
    integer :: blank, j
    w = trim(adjustl(entry))
    do j = 1, k - 1
      blank = index(w, ' ')
      if (blank == 0) then
        w = ''
        return
      end if
      w = trim(adjustl(w(blank + 1:)))
    end do
    blank = index(w, ' ')
    if (blank > 0) w = w(1:blank - 1)
  end function word

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
