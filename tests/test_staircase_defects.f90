!> Unit test of the quiet grid of an ellipse's level (kcreep_staircase_defects).
!>  1. end_defect, whose row and column counts are a closed form, equals the
!>     same sums over the cells of kcreep_patch's own ellipse staircase
!>     (allowed 1e-12: rounding of sums of a few thousand terms of order 1e-3).
!>  2. quiet_ellipse_grid returns a grid with no more cells than the wanted
!>     one, from 92 % of its cells across, and columns within 0.5 % (at most
!>     4) of near-square.
!>  3. Over the wanted levels 56-256 of a/b = 5 and 10 the quiet grids' end
!>     defects lie closer to their smooth part than the wanted grids' do: the
!>     summed distance is checked to be at most half (measured: 0.13 at
!>     a/b = 5, 0.23 at a/b = 10, against this test's own trend lines).
program test_staircase_defects
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t
  use kcreep_patch, only: patch_t, ellipse_patch
  use kcreep_staircase_defects, only: end_defect, quiet_ellipse_grid
  use unit_checks, only: checker_t
  implicit none
  type(checker_t) :: t
  integer, parameter :: wanted(*) = [56, 64, 72, 84, 96, 112, 128, 148, 172, 196, 224, 256]

  call check_closed_form(5.0_real64, 280, 56)
  call check_closed_form(10.0_real64, 961, 96)
  call check_closed_form(1.0_real64, 57, 57)
  call check_choice(5.0_real64)
  call check_choice(10.0_real64)
  call t%finish()

contains

  subroutine check_closed_form(ratio, mx, my)
    real(real64), intent(in) :: ratio
    integer, intent(in) :: mx, my
    type(patch_t) :: patch
    type(status_t) :: st
    real(real64) :: by_cells, s
    integer :: i, j
    character(len=48) :: label
    write (label, '(a, i0, a, i0)') 'end defect from the patch, ', mx, ' x ', my
    call ellipse_patch(sqrt(ratio), 1 / sqrt(ratio), mx, my, patch, st)
    call t%check(.not. st%failed(), 'ellipse patch '//trim(label))
    by_cells = 0
    do j = 1, my
      s = sqrt(1 - centre(j, my)**2)
      by_cells = by_cells + s * (real(count(patch%inside(:, j)), real64) / mx - s) * 2 / my
    end do
    do i = 1, mx
      s = sqrt(1 - centre(i, mx)**2)
      by_cells = by_cells - 0.43_real64 * (real(count(patch%inside(i, :)), real64) / my - s) / sqrt(s) * 2 / mx
    end do
    call t%check(abs(end_defect(mx, my) - by_cells) <= 1e-12_real64, trim(label))
  end subroutine check_closed_form

  subroutine check_choice(ratio)
    real(real64), intent(in) :: ratio
    real(real64) :: plain, quiet, slope, offset
    integer :: k, cells, mx, wanted_mx
    character(len=48) :: label
    plain = 0
    quiet = 0
    do k = 1, size(wanted)
      write (label, '(a, f4.1, a, i0)') 'a/b ', ratio, ', wanted ', wanted(k)
      call quiet_ellipse_grid(sqrt(ratio), 1 / sqrt(ratio), wanted(k), cells, mx)
      wanted_mx = nint(wanted(k) * ratio)
      call t%check(cells <= wanted(k) .and. cells >= ceiling(0.92_real64 * wanted(k)), trim(label)//': cells in the window')
      call t%check(mx * cells <= wanted_mx * wanted(k), trim(label)//': no more grid cells')
      call t%check(abs(mx - nint(cells * ratio)) <= min(4, int(0.005_real64 * nint(cells * ratio))), &
                   trim(label)//': near-square')
      call local_trend(ratio, wanted(k), slope, offset)
      plain = plain + abs(end_defect(wanted_mx, wanted(k)) - (offset + slope / wanted(k)))
      quiet = quiet + abs(end_defect(mx, cells) - (offset + slope / cells))
    end do
    write (label, '(a, f4.1)') 'quiet grids nearer their trend, a/b ', ratio
    call t%check(quiet <= 0.5_real64 * plain, trim(label))
  end subroutine check_choice

  !> An independent smooth part: a straight line in 1/N through the
  !> near-square grids from 0.8 N to 1.25 N (no column changes).
  subroutine local_trend(ratio, n, slope, offset)
    real(real64), intent(in) :: ratio
    integer, intent(in) :: n
    real(real64), intent(out) :: slope, offset
    real(real64), allocatable :: h(:), d(:)
    integer :: m, lo, hi
    lo = floor(0.8_real64 * n)
    hi = ceiling(n / 0.8_real64)
    h = [(1.0_real64 / m, m = lo, hi)]
    d = [(end_defect(nint(m * ratio), m), m = lo, hi)]
    slope = (size(h) * sum(h * d) - sum(h) * sum(d)) / (size(h) * sum(h * h) - sum(h)**2)
    offset = (sum(d) - slope * sum(h)) / size(h)
  end subroutine local_trend

  pure real(real64) function centre(i, m)
    integer, intent(in) :: i, m
    centre = real(2 * i - 1 - m, real64) / m
  end function centre
end program test_staircase_defects
