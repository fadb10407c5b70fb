!> Unit test of the tractions carried from one level to the next
!> (kcreep_grid_transfer), the iterative solver's starting guess there.
!>  1. A linear field is carried exactly (bilinear interpolation) to every
!>     target cell whose four surrounding source centres are in the source
!>     patch: allowed 1e-12 of the field's size (rounding).
!>  2. Every other target cell gets the value of a source cell within two
!>     cells of it, so no target cell is left at zero and the values stay
!>     within the field's range.
!>  3. A column of NaN (a load case not solved) gives zeros.
program test_grid_transfer
  use, intrinsic :: iso_fortran_env, only: real64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use kcreep_status, only: status_t
  use kcreep_patch, only: patch_t, ellipse_patch
  use kcreep_grid_transfer, only: transferred_traction
  use unit_checks, only: checker_t
  implicit none
  type(checker_t) :: t

  call check_levels(1.0_real64, 1.0_real64, 56, 56, 64, 64)
  call check_levels(2.0_real64, 0.5_real64, 112, 28, 128, 32)
  call check_levels(0.6_real64, 1.5_real64, 33, 81, 40, 100)
  call t%finish()

contains

  subroutine check_levels(a, b, mx1, my1, mx2, my2)
    real(real64), intent(in) :: a, b
    integer, intent(in) :: mx1, my1, mx2, my2
    type(status_t) :: st
    type(patch_t) :: coarse, fine
    real(real64), allocatable :: p(:, :), q(:, :)
    logical, allocatable :: interior(:)
    integer, allocatable :: cell_of(:, :)
    character(len=64) :: label
    integer :: k, i, j
    real(real64) :: fx, fy, err

    write (label, '(i0, a, i0, a, i0, a, i0)') mx1, ' x ', my1, ' -> ', mx2, ' x ', my2
    call ellipse_patch(a, b, mx1, my1, coarse, st)
    call ellipse_patch(a, b, mx2, my2, fine, st)
    allocate (p(2 * coarse%n, 3))
    p(1:coarse%n, 1) = 1 + 2 * coarse%cell_x(coarse%ix) - 3 * coarse%cell_y(coarse%iy)
    p(coarse%n + 1:, 1) = -0.5_real64 + coarse%cell_y(coarse%iy)
    p(:, 2) = 7
    p(:, 3) = ieee_value(1.0_real64, ieee_quiet_nan)
    q = transferred_traction(coarse, p, fine)

    ! which fine cells have all four surrounding coarse centres inside
    allocate (cell_of(0:mx1 + 1, 0:my1 + 1), interior(fine%n))
    cell_of = 0
    do k = 1, coarse%n
      cell_of(coarse%ix(k), coarse%iy(k)) = k
    end do
    err = 0
    do k = 1, fine%n
      fx = (fine%cell_x(fine%ix(k)) - coarse%x0) / coarse%dx + 1
      fy = (fine%cell_y(fine%iy(k)) - coarse%y0) / coarse%dy + 1
      i = floor(fx)
      j = floor(fy)
      interior(k) = i >= 1 .and. j >= 1 .and. i < mx1 .and. j < my1
      if (interior(k)) interior(k) = all(cell_of(i:i + 1, j:j + 1) > 0)
      if (interior(k)) err = max(err, &
        abs(q(k, 1) - (1 + 2 * fine%cell_x(fine%ix(k)) - 3 * fine%cell_y(fine%iy(k)))), &
        abs(q(fine%n + k, 1) - (-0.5_real64 + fine%cell_y(fine%iy(k)))))
    end do
    call t%check(count(interior) > fine%n / 2 .and. err <= 1e-12_real64 * maxval(abs(p(:, 1))), &
                 trim(label)//': a linear field carried exactly between inside centres')
    call t%check(all(abs(q(:, 2) - 7) <= 1e-12_real64), trim(label)//': a constant field everywhere, boundary included')
    call t%check(all(q(:, 1) >= minval(p(:, 1)) - 1e-12_real64 .and. q(:, 1) <= maxval(p(:, 1)) + 1e-12_real64), &
                 trim(label)//': values within the source range')
    call t%check(all(q(:, 3) == 0), trim(label)//': a case not solved (NaN) gives zeros')
  end subroutine check_levels

end program test_grid_transfer
