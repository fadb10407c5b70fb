!> Pressure files (&fastsim pressure_input_file): the normal pressure on the grid of the patch, for FASTSIM.
!> Format: the mask file's header line 'mx my dx dy x0 y0', then my rows of
!> mx numbers (row iy: cells of y = y0 + (iy-1) dy in order of increasing x).
!> Blank lines and lines starting with '!' or '%' after the header are
!> skipped. The header must describe the patch's grid; pressures must be
!> finite and >= 0; values on cells outside the patch are ignored.
module kcreep_pressure_file
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use kcreep_patch, only: patch_t
  use kcreep_file_checks, only: read_input_file
  use kcreep_mask_file, only: parse_header, read_line
  implicit none
  private
  public :: read_pressure_file

contains

  subroutine read_pressure_file(path, patch, pn, status)
    character(len=*), intent(in) :: path
    type(patch_t), intent(in) :: patch
    real(real64), allocatable, intent(out) :: pn(:, :)
    type(status_t), intent(inout) :: status
    integer :: unit, ios, mx, my, nrows
    real(real64) :: dx, dy, x0, y0, tol
    character(len=:), allocatable :: line, text, label
    character(len=512) :: msg

    label = 'pressure_input_file '''//trim(path)//''': '
    call read_input_file(path, 'pressure_input_file '''//trim(path)//'''', text, status)
    if (status%failed()) return
    deallocate (text)
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_bad_input, label//'cannot open ('//trim(msg)//')')
      return
    end if
    call read_line(unit, line, ios)
    if (ios == 0) call parse_header(line, mx, my, dx, dy, x0, y0, ios)
    if (ios /= 0) then
      call fail(status, exit_bad_input, label//'line 1 must be the header "mx my dx dy x0 y0" (two integers, four reals)')
      close (unit)
      return
    end if
    ! the grid of the patch, to the printed precision of a header (1e-6 of a cell)
    tol = 1e-6_real64 * min(patch%dx, patch%dy)
    if (mx /= patch%mx .or. my /= patch%my .or. abs(dx - patch%dx) > tol .or. abs(dy - patch%dy) > tol .or. &
        abs(x0 - patch%x0) > tol .or. abs(y0 - patch%y0) > tol) then
      call fail(status, exit_bad_input, label//'header '//itoa(mx)//' '//itoa(my)//' '//rtoa(dx)//' '//rtoa(dy)// &
                ' '//rtoa(x0)//' '//rtoa(y0)//' is not the patch''s grid (allowed: '//itoa(patch%mx)//' '// &
                itoa(patch%my)//' '//rtoa(patch%dx)//' '//rtoa(patch%dy)//' '//rtoa(patch%x0)//' '// &
                rtoa(patch%y0)//')')
      close (unit)
      return
    end if
    allocate (pn(mx, my))
    nrows = 0
    do
      call read_line(unit, line, ios)
      if (ios /= 0) exit
      if (len_trim(line) == 0) cycle
      if (line(1:1) == '!' .or. line(1:1) == '%') cycle
      nrows = nrows + 1
      if (nrows > my) exit
      if (scan(line, '/*') > 0) then
        ios = 1
      else
        read (line, *, iostat=ios) pn(:, nrows)
      end if
      if (ios /= 0) then
        call fail(status, exit_bad_input, label//'row '//itoa(nrows)//': cannot read '//itoa(mx)// &
                  ' pressures (the header says mx = '//itoa(mx)//')')
        close (unit)
        return
      end if
      if (.not. all(pn(:, nrows) >= 0 .and. pn(:, nrows) <= huge(1.0_real64))) then
        call fail(status, exit_bad_input, label//'row '//itoa(nrows)//': a pressure is negative, NaN or '// &
                  'infinite (allowed: finite values >= 0)')
        close (unit)
        return
      end if
    end do
    close (unit)
    if (nrows /= my) then
      call fail(status, exit_bad_input, label//merge('more than', 'only     ', nrows > my)//' '// &
                itoa(min(nrows, my))//' rows of pressures, the header says my = '//itoa(my))
      return
    end if
    where (.not. patch%inside) pn = 0
    if (.not. any(pn > 0)) call fail(status, exit_bad_input, label// &
        'no positive pressure on the patch''s cells (FASTSIM needs a normal load)')
  end subroutine read_pressure_file

end module kcreep_pressure_file
