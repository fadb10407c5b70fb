!> Grid files: the mask file's header line "mx my dx dy x0 y0" (x0, y0: the
!> centre of the first cell), then my rows, in increasing y, of mx numbers
!> each, in increasing x, separated by blanks, tabs or commas. Blank lines
!> and lines starting with '!', '%' or '#' are skipped. The gap file and the
!> pressure file of FASTSIM are such files.
module kcreep_grid_file
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  implicit none
  private
  public :: parse_grid_text

  character(len=*), parameter :: separators = ' ,'//achar(9)//achar(13)

contains

  !> Parse the text of a grid file; source names it in messages, max_cells
  !> bounds mx * my. values(mx, my): rows in increasing y.
  subroutine parse_grid_text(text, source, max_cells, mx, my, dx, dy, x0, y0, h, status)
    character(len=*), intent(in) :: text, source
    real(real64), intent(in) :: max_cells
    integer, intent(out) :: mx, my
    real(real64), intent(out) :: dx, dy, x0, y0
    real(real64), allocatable, intent(out) :: h(:, :)
    type(status_t), intent(inout) :: status
    integer :: pos, lb, le, line_no, row, ncol, first, last, ios
    real(real64) :: v
    logical :: header_done
    character(len=64) :: word

    pos = 1
    line_no = 0
    header_done = .false.
    row = 0
    mx = 0
    my = 0
    do while (pos <= len(text))
      lb = pos
      le = index(text(pos:), achar(10))
      if (le == 0) then
        le = len(text)
        pos = len(text) + 1
      else
        le = pos + le - 2
        pos = le + 2
      end if
      line_no = line_no + 1
      if (le < lb) cycle
      first = verify(text(lb:le), separators)
      if (first == 0) cycle
      if (index('!%#', text(lb + first - 1:lb + first - 1)) > 0) cycle
      if (.not. header_done) then
        read (text(lb:le), *, iostat=ios) mx, my, dx, dy, x0, y0
        if (ios /= 0) then
          call fail(status, exit_bad_input, source//': line '//itoa(line_no)// &
                    ' must be the header "mx my dx dy x0 y0" (two integers, four reals)')
          return
        end if
        if (mx < 1 .or. my < 1 .or. real(mx, real64) * my > max_cells) then
          call fail(status, exit_bad_input, source//': header mx, my = '//itoa(mx)//', '//itoa(my)// &
                    ' (both >= 1, mx * my <= '//itoa(int(max_cells))//')')
          return
        end if
        if (.not. (dx > 0 .and. dy > 0 .and. dx < 1e30_real64 .and. dy < 1e30_real64)) then
          call fail(status, exit_bad_input, source//': header dx, dy = '//rtoa(dx)//', '//rtoa(dy)// &
                    ' (cell sizes must be > 0 and < 1e30)')
          return
        end if
        if (.not. (abs(x0) < 1e30_real64 .and. abs(y0) < 1e30_real64)) then
          call fail(status, exit_bad_input, source//': header x0, y0 = '//rtoa(x0)//', '//rtoa(y0)// &
                    ' (|x0|, |y0| < 1e30)')
          return
        end if
        allocate (h(mx, my))
        header_done = .true.
        cycle
      end if
      row = row + 1
      if (row > my) then
        call fail(status, exit_bad_input, source//': line '//itoa(line_no)//': more than my = '//itoa(my)// &
                  ' rows of values (the header says my = '//itoa(my)//')')
        return
      end if
      ncol = 0
      last = lb - 1
      do
        first = verify(text(last + 1:le), separators)
        if (first == 0) exit
        first = first + last
        last = scan(text(first:le), separators)
        last = merge(le, first + last - 2, last == 0)
        ncol = ncol + 1
        if (ncol > mx) exit
        if (last - first + 1 > len(word)) then
          ios = 1
        else
          word = text(first:last)
          read (word, *, iostat=ios) v
        end if
        if (ios /= 0) then
          call fail(status, exit_bad_input, source//': line '//itoa(line_no)//', value '//itoa(ncol)//' '''// &
                    text(first:min(last, first + 31))//''' is not a number')
          return
        end if
        if (v /= v .or. abs(v) > huge(v)) then
          call fail(status, exit_bad_input, source//': line '//itoa(line_no)//', value '//itoa(ncol)//' is '// &
                    trim(word)//' (finite numbers only)')
          return
        end if
        h(ncol, row) = v
      end do
      if (ncol > mx) then
        call fail(status, exit_bad_input, source//': line '//itoa(line_no)//' (row '//itoa(row)// &
                  ') has more than '//itoa(mx)//' values, the header says mx = '//itoa(mx))
        return
      else if (ncol /= mx) then
        call fail(status, exit_bad_input, source//': line '//itoa(line_no)//' (row '//itoa(row)//') has '// &
                  itoa(ncol)//' values, the header says mx = '//itoa(mx))
        return
      end if
    end do
    if (.not. header_done) then
      call fail(status, exit_bad_input, source//': empty (the header "mx my dx dy x0 y0" is missing)')
      return
    end if
    if (row /= my) then
      call fail(status, exit_bad_input, source//': '//itoa(row)//' rows of values, the header says my = '//itoa(my))
      return
    end if
  end subroutine parse_grid_text

end module kcreep_grid_file
