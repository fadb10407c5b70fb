!> Masks as text: inline rows of a namelist and mask files (a header line
!> 'mx my dx dy x0 y0', then my rows of mx characters), turned into patches.
module kcreep_mask_file
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, printable
  use kcreep_limits, only: check_grid_size, length_in_range, offset_in_range
  use kcreep_patch, only: patch_t, mask_patch
  use kcreep_file_checks, only: read_input_file
  implicit none
  private
  public :: read_mask_file, parse_mask_rows

contains

  !> Turn mask rows (increasing y; characters in increasing x) into a logical grid.
  !> '1' or '#': in the patch; '0' or '.': outside. Trailing blanks are ignored.
  subroutine parse_mask_rows(rows, source, inside, status)
    character(len=*), intent(in) :: rows(:)
    character(len=*), intent(in) :: source
    logical, allocatable, intent(out) :: inside(:, :)
    type(status_t), intent(inout) :: status
    integer :: mx, my, ix, iy
    character(len=1) :: c

    my = size(rows)
    if (my == 0) then
      call fail(status, exit_bad_input, trim(source)//': mask has no rows')
      return
    end if
    mx = len_trim(rows(1))
    do iy = 1, my
      if (len_trim(rows(iy)) /= mx) then
        call fail(status, exit_bad_input, trim(source)//': mask row '//itoa(iy)// &
                  ' has '//itoa(len_trim(rows(iy)))//' cells, row 1 has '//itoa(mx)// &
                  ' (all rows must have the same length)')
        return
      end if
    end do
    if (mx == 0) then
      call fail(status, exit_bad_input, trim(source)//': mask rows are empty')
      return
    end if
    allocate (inside(mx, my))
    do iy = 1, my
      do ix = 1, mx
        c = rows(iy)(ix:ix)
        select case (c)
        case ('1', '#')
          inside(ix, iy) = .true.
        case ('0', '.')
          inside(ix, iy) = .false.
        case default
          call fail(status, exit_bad_input, trim(source)//': mask row '//itoa(iy)// &
                    ', column '//itoa(ix)//": character '"//printable(c)// &
                    "' (allowed: 1 or # inside, 0 or . outside)")
          return
        end select
      end do
    end do
  end subroutine parse_mask_rows

  !> Read a mask file: a header line 'mx my dx dy x0 y0', then my rows of mx cells.
  !> Blank lines and lines starting with '!' or '%' after the header are skipped.
  subroutine read_mask_file(path, patch, status)
    character(len=*), intent(in) :: path
    type(patch_t), intent(out) :: patch
    type(status_t), intent(inout) :: status
    integer :: unit, ios, mx, my, nrows
    real(real64) :: dx, dy, x0, y0
    character(len=:), allocatable :: line
    character(len=:), allocatable :: rows(:), text
    logical, allocatable :: inside(:, :)
    character(len=512) :: msg

    ! a folder, an unreadable or a huge file is refused before parsing
    call read_input_file(path, 'mask_file '''//trim(path)//'''', text, status)
    if (status%failed()) return
    deallocate (text)
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_bad_input, 'mask_file '''//trim(path)//''': cannot open ('//trim(msg)//')')
      return
    end if
    call read_line(unit, line, ios)
    if (ios == 0) call parse_header(line, mx, my, dx, dy, x0, y0, ios)
    if (ios /= 0) then
      call fail(status, exit_bad_input, 'mask_file '''//trim(path)// &
                ''': line 1 must be the header "mx my dx dy x0 y0" (two integers, four reals)')
      close (unit)
      return
    end if
    if (mx < 1 .or. my < 1) then
      call fail(status, exit_bad_input, 'mask_file '''//trim(path)//''': header mx = '//itoa(mx)// &
                ', my = '//itoa(my)//' (both must be >= 1)')
    else if (.not. (length_in_range(dx) .and. length_in_range(dy))) then
      call fail(status, exit_bad_input, 'mask_file '''//trim(path)//''': header dx, dy = '// &
                rtoa(dx)//', '//rtoa(dy)//' (cell sizes must be > 0, between 1e-30 and 1e30)')
    else if (.not. (offset_in_range(x0) .and. offset_in_range(y0))) then
      call fail(status, exit_bad_input, 'mask_file '''//trim(path)//''': header x0, y0 = '// &
                rtoa(x0)//', '//rtoa(y0)//' (allowed: 0 or 1e-30 <= |x0|, |y0| <= 1e30)')
    end if
    call check_grid_size(mx, my, 'mask_file '''//trim(path)//''': header: ', status)
    if (status%failed()) then
      close (unit)
      return
    end if
    allocate (character(len=mx) :: rows(my))
    nrows = 0
    do
      call read_line(unit, line, ios)
      if (ios /= 0) exit
      if (len_trim(line) == 0) cycle
      if (line(1:1) == '!' .or. line(1:1) == '%') cycle
      nrows = nrows + 1
      if (nrows > my) exit
      if (len_trim(line) /= mx) then
        call fail(status, exit_bad_input, 'mask_file '''//trim(path)//''': mask row '//itoa(nrows)// &
                  ' has '//itoa(len_trim(line))//' cells, the header says mx = '//itoa(mx))
        close (unit)
        return
      end if
      rows(nrows) = line
    end do
    close (unit)
    if (nrows /= my) then
      call fail(status, exit_bad_input, 'mask_file '''//trim(path)//''': '// &
                merge('more than', 'only     ', nrows > my)//' '//itoa(min(nrows, my))// &
                ' mask rows, the header says my = '//itoa(my))
      return
    end if
    call parse_mask_rows(rows, 'mask_file '''//trim(path)//'''', inside, status)
    if (status%failed()) return
    call mask_patch(inside, dx, dy, x0, y0, 'mask_file '''//trim(path)//'''', patch, status)
  end subroutine read_mask_file

  !> The six header fields, exactly: list-directed input alone would accept a
  !> '/' or a short line and leave the missing values undefined.
  subroutine parse_header(line, mx, my, dx, dy, x0, y0, ios)
    character(len=*), intent(in) :: line
    integer, intent(out) :: mx, my, ios
    real(real64), intent(out) :: dx, dy, x0, y0
    integer :: first, last, nwords
    character(len=64) :: words(7)
    character(len=*), parameter :: separators = ' ,'//achar(9)//achar(13)

    nwords = 0
    last = 0
    ios = 1
    mx = 0; my = 0; dx = 0; dy = 0; x0 = 0; y0 = 0
    do
      first = verify(line(last + 1:), separators)
      if (first == 0) exit
      first = first + last
      last = scan(line(first:), separators)
      last = merge(len(line), first + last - 2, last == 0)
      nwords = nwords + 1
      if (nwords > size(words) .or. last - first + 1 > len(words)) return
      words(nwords) = line(first:last)
      if (scan(words(nwords), '/*') > 0) return
    end do
    if (nwords /= 6) return
    read (words(1), *, iostat=ios) mx
    if (ios == 0) read (words(2), *, iostat=ios) my
    if (ios == 0) read (words(3:6), *, iostat=ios) dx, dy, x0, y0
  end subroutine parse_header

  !> Read one whole line of any length.
  subroutine read_line(unit, line, ios)
    integer, intent(in) :: unit
    character(len=:), allocatable, intent(out) :: line
    integer, intent(out) :: ios
    character(len=4096) :: chunk
    integer :: nread
    line = ''
    do
      read (unit, '(a)', advance='no', iostat=ios, size=nread) chunk
      line = line//chunk(1:nread)
      if (ios /= 0) exit
    end do
    if (is_iostat_eor(ios)) ios = 0
    ! a last line without newline is still a line
    if (is_iostat_end(ios) .and. len(line) > 0) ios = 0
  end subroutine read_line

end module kcreep_mask_file
