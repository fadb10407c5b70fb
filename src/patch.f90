!> The contact patch: a uniform grid of rectangular cells and the mask of the
!> cells that are in contact.
!>
!> Grid convention: cell (ix, iy), ix = 1..mx along x (rolling direction),
!> iy = 1..my along y, has its centre at (x0 + (ix-1)*dx, y0 + (iy-1)*dy).
!> Only the cells of the mask become unknowns; they are numbered in the
!> order of the grid (ix fastest).
module patch_grid
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, printable
  use file_checks, only: read_input_file
  use input_limits, only: check_grid_size, length_in_range, offset_in_range
  implicit none
  private
  public :: patch_t, ellipse_patch, mask_patch, read_mask_file, parse_mask_rows

  type :: patch_t
    character(len=:), allocatable :: kind     !< 'ellipse', 'mask' or 'contact'
    integer :: mx = 0, my = 0                 !< grid cells along x and y
    real(real64) :: dx = 0, dy = 0            !< cell sizes
    real(real64) :: x0 = 0, y0 = 0            !< centre of cell (1, 1)
    real(real64) :: semi_a = 0, semi_b = 0    !< ellipse semi-axes (kind 'ellipse' only)
    logical, allocatable :: inside(:, :)      !< (mx, my): cell is in the patch
    integer :: n = 0                          !< number of patch cells
    integer, allocatable :: ix(:), iy(:)      !< grid indices of patch cell k
  contains
    procedure :: cell_x, cell_y, area, equivalent_radius
    procedure :: mirror_symmetric_in_x, mirror_symmetric_in_y
  end type patch_t

contains

  !> Cells of an mx x my grid over [-a, a] x [-b, b] whose centres lie in the ellipse.
  subroutine ellipse_patch(semi_a, semi_b, mx, my, patch, status)
    real(real64), intent(in) :: semi_a, semi_b
    integer, intent(in) :: mx, my
    type(patch_t), intent(out) :: patch
    type(status_t), intent(inout) :: status
    integer :: ix, iy
    real(real64) :: x, y

    patch%kind = 'ellipse'
    patch%semi_a = semi_a
    patch%semi_b = semi_b
    patch%mx = mx
    patch%my = my
    patch%dx = 2 * semi_a / mx
    patch%dy = 2 * semi_b / my
    patch%x0 = -semi_a + patch%dx / 2
    patch%y0 = -semi_b + patch%dy / 2
    allocate (patch%inside(mx, my))
    do iy = 1, my
      do ix = 1, mx
        x = patch%cell_x(ix)
        y = patch%cell_y(iy)
        patch%inside(ix, iy) = (x / semi_a)**2 + (y / semi_b)**2 <= 1
      end do
    end do
    call index_cells(patch, 'ellipse', status)
  end subroutine ellipse_patch

  !> A patch from an explicit mask on a grid with given cell sizes and origin.
  subroutine mask_patch(inside, dx, dy, x0, y0, source, patch, status)
    logical, intent(in) :: inside(:, :)
    real(real64), intent(in) :: dx, dy, x0, y0
    character(len=*), intent(in) :: source   !< named in error messages
    type(patch_t), intent(out) :: patch
    type(status_t), intent(inout) :: status

    call check_grid_size(size(inside, 1), size(inside, 2), trim(source)//': ', status)
    if (status%failed()) return
    patch%kind = 'mask'
    patch%mx = size(inside, 1)
    patch%my = size(inside, 2)
    patch%dx = dx
    patch%dy = dy
    patch%x0 = x0
    patch%y0 = y0
    patch%inside = inside
    call index_cells(patch, source, status)
  end subroutine mask_patch

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

  !> Number the patch cells; an empty patch is an error.
  subroutine index_cells(patch, source, status)
    type(patch_t), intent(inout) :: patch
    character(len=*), intent(in) :: source
    type(status_t), intent(inout) :: status
    integer :: ix, iy, k

    patch%n = count(patch%inside)
    if (patch%n == 0) then
      call fail(status, exit_bad_input, trim(source)//': the patch is empty (no cell inside on the '// &
                itoa(patch%mx)//' x '//itoa(patch%my)//' grid)')
      return
    end if
    allocate (patch%ix(patch%n), patch%iy(patch%n))
    k = 0
    do iy = 1, patch%my
      do ix = 1, patch%mx
        if (.not. patch%inside(ix, iy)) cycle
        k = k + 1
        patch%ix(k) = ix
        patch%iy(k) = iy
      end do
    end do
  end subroutine index_cells

  elemental real(real64) function cell_x(self, ix)
    class(patch_t), intent(in) :: self
    integer, intent(in) :: ix
    cell_x = self%x0 + (ix - 1) * self%dx
  end function cell_x

  elemental real(real64) function cell_y(self, iy)
    class(patch_t), intent(in) :: self
    integer, intent(in) :: iy
    cell_y = self%y0 + (iy - 1) * self%dy
  end function cell_y

  pure real(real64) function area(self)
    class(patch_t), intent(in) :: self
    area = self%n * self%dx * self%dy
  end function area

  !> c of the normalisation: sqrt(a b) for an ellipse, sqrt(area/pi) otherwise.
  pure real(real64) function equivalent_radius(self)
    class(patch_t), intent(in) :: self
    real(real64), parameter :: pi = acos(-1.0_real64)
    if (self%kind == 'ellipse') then
      equivalent_radius = sqrt(self%semi_a * self%semi_b)
    else
      equivalent_radius = sqrt(self%area() / pi)
    end if
  end function equivalent_radius

  !> The mask is its own mirror image in x about x = 0 (cell positions included).
  pure logical function mirror_symmetric_in_x(self)
    class(patch_t), intent(in) :: self
    mirror_symmetric_in_x = abs(self%x0 + (self%mx - 1) * self%dx / 2) <= 1e-12_real64 * self%dx * self%mx
    if (mirror_symmetric_in_x) mirror_symmetric_in_x = all(self%inside .eqv. self%inside(self%mx:1:-1, :))
  end function mirror_symmetric_in_x

  !> The mask is its own mirror image in y about y = 0 (cell positions included).
  pure logical function mirror_symmetric_in_y(self)
    class(patch_t), intent(in) :: self
    mirror_symmetric_in_y = abs(self%y0 + (self%my - 1) * self%dy / 2) <= 1e-12_real64 * self%dy * self%my
    if (mirror_symmetric_in_y) mirror_symmetric_in_y = all(self%inside .eqv. self%inside(:, self%my:1:-1))
  end function mirror_symmetric_in_y

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

end module patch_grid
