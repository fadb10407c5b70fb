!> The gap file: the undeformed distance on a grid, a grid file
!> (kcreep_grid_file: header "mx my dx dy x0 y0", then my rows of mx numbers).
module kcreep_gap_file
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t
  use kcreep_file_checks, only: read_input_file
  use kcreep_grid_file, only: parse_grid_text
  use kcreep_gap, only: gap_t, gap_from_array, max_gap_cells
  implicit none
  private
  public :: read_gap_file, parse_gap_text

contains

  subroutine read_gap_file(path, gap, status)
    character(len=*), intent(in) :: path
    type(gap_t), intent(out) :: gap
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: text
    call read_input_file(path, 'gap_file '''//trim(path)//'''', text, status)
    if (status%failed()) return
    call parse_gap_text(text, 'gap_file '''//trim(path)//'''', gap, status)
  end subroutine read_gap_file

  !> Parse the text of a gap file; source names it in messages.
  subroutine parse_gap_text(text, source, gap, status)
    character(len=*), intent(in) :: text, source
    type(gap_t), intent(out) :: gap
    type(status_t), intent(inout) :: status
    integer :: mx, my
    real(real64) :: dx, dy, x0, y0
    real(real64), allocatable :: h(:, :)
    call parse_grid_text(text, source, real(max_gap_cells, real64), mx, my, dx, dy, x0, y0, h, status)
    if (status%failed()) return
    call gap_from_array(h, dx, dy, x0, y0, source, gap, status)
  end subroutine parse_gap_text

end module kcreep_gap_file
