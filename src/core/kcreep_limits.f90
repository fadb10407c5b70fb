!> Limits on input values beyond the obvious signs and ranges: sizes the
!> dense solver can never handle and magnitudes at which the influence
!> coefficients (squares, logarithms and 1/G of lengths) would overflow or
!> underflow in double precision. Checked before anything is allocated.
module kcreep_limits
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  implicit none
  private
  public :: check_grid_size, length_in_range, modulus_in_range, offset_in_range, &
            max_grid_cells, min_length, max_length, min_modulus, max_modulus

  !> mx*my: the offset tables take about 100 bytes per grid cell (0.4 GB at
  !> this size), whatever the number of patch cells.
  integer(int64), parameter :: max_grid_cells = 4000000_int64
  !> Lengths (semi-axes, cell sizes, cell positions) in [min_length, max_length]:
  !> their squares and products stay far from overflow and underflow.
  real(real64), parameter :: min_length = 1e-30_real64, max_length = 1e30_real64
  !> G in [min_modulus, max_modulus]: 1/(pi G) and f ~ G c^2 stay finite.
  real(real64), parameter :: min_modulus = 1e-100_real64, max_modulus = 1e100_real64

contains

  pure logical function length_in_range(x)
    real(real64), intent(in) :: x
    length_in_range = x >= min_length .and. x <= max_length
  end function length_in_range

  !> A coordinate: 0 or a length in range, either sign.
  pure logical function offset_in_range(x)
    real(real64), intent(in) :: x
    offset_in_range = x == 0 .or. length_in_range(abs(x))
  end function offset_in_range

  pure logical function modulus_in_range(x)
    real(real64), intent(in) :: x
    modulus_in_range = x >= min_modulus .and. x <= max_modulus
  end function modulus_in_range

  !> Fail when an mx x my grid is beyond what kcreep can tabulate.
  pure subroutine check_grid_size(mx, my, where, status)
    integer, intent(in) :: mx, my
    character(len=*), intent(in) :: where
    type(status_t), intent(inout) :: status
    if (mx < 1 .or. my < 1) return   ! reported by the caller with its own wording
    if (int(mx, int64) * my > max_grid_cells) call fail(status, exit_bad_input, where// &
        'grid of '//itoa(mx)//' x '//itoa(my)//' cells is too large (at most '// &
        rtoa(real(max_grid_cells, real64))//' grid cells, e.g. 2000 x 2000)')
  end subroutine check_grid_size

end module kcreep_limits
