!> Pressure files (&fastsim pressure_input_file): the normal pressure on the grid of the patch, for FASTSIM.
!> Format: a grid file (kcreep_grid_file: the mask file's header line
!> 'mx my dx dy x0 y0', then my rows of mx numbers, row iy the cells of
!> y = y0 + (iy-1) dy in order of increasing x). The header must describe the
!> patch's grid; pressures must be finite and >= 0; values on cells outside
!> the patch are ignored.
module kcreep_pressure_file
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use kcreep_patch, only: patch_t
  use kcreep_file_checks, only: read_input_file
  use kcreep_grid_file, only: parse_grid_text
  use kcreep_gap, only: max_gap_cells
  implicit none
  private
  public :: read_pressure_file

contains

  subroutine read_pressure_file(path, patch, pn, status)
    character(len=*), intent(in) :: path
    type(patch_t), intent(in) :: patch
    real(real64), allocatable, intent(out) :: pn(:, :)
    type(status_t), intent(inout) :: status
    integer :: mx, my
    real(real64) :: dx, dy, x0, y0, tol
    character(len=:), allocatable :: text, label

    label = 'pressure_input_file '''//trim(path)//''''
    call read_input_file(path, label, text, status)
    if (status%failed()) return
    call parse_grid_text(text, label, real(max_gap_cells, real64), mx, my, dx, dy, x0, y0, pn, status)
    if (status%failed()) return
    ! the grid of the patch, to the printed precision of a header (1e-6 of a cell)
    tol = 1e-6_real64 * min(patch%dx, patch%dy)
    if (mx /= patch%mx .or. my /= patch%my .or. abs(dx - patch%dx) > tol .or. abs(dy - patch%dy) > tol .or. &
        abs(x0 - patch%x0) > tol .or. abs(y0 - patch%y0) > tol) then
      call fail(status, exit_bad_input, label//': header '//itoa(mx)//' '//itoa(my)//' '//rtoa(dx)//' '// &
                rtoa(dy)//' '//rtoa(x0)//' '//rtoa(y0)//' is not the patch''s grid (allowed: '//itoa(patch%mx)// &
                ' '//itoa(patch%my)//' '//rtoa(patch%dx)//' '//rtoa(patch%dy)//' '//rtoa(patch%x0)//' '// &
                rtoa(patch%y0)//')')
      return
    end if
    if (.not. all(pn >= 0)) then   ! (NaN and infinities are refused by the grid reader)
      call fail(status, exit_bad_input, label//': a pressure is negative (allowed: finite values >= 0)')
      return
    end if
    where (.not. patch%inside) pn = 0
    if (.not. any(pn > 0)) call fail(status, exit_bad_input, label// &
        ': no positive pressure on the patch''s cells (FASTSIM needs a normal load)')
  end subroutine read_pressure_file

end module kcreep_pressure_file
