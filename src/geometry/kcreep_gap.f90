!> The undeformed distance (gap) between the two surfaces on a grid.
!>
!> Grid convention as patch_t: mx x my cells of size dx x dy, (x0, y0) the
!> centre of cell (1, 1); h(ix, iy) is the distance at the cell centre
!> (x0 + (ix-1) dx, y0 + (iy-1) dy). Values >= 1e29 mark cells outside the
!> potential contact.
module kcreep_gap
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  implicit none
  private
  public :: gap_t, polynomial_gap_t, gap_from_array, gap_from_polynomial, auto_grid, polynomial_value
  public :: max_gap_cells, gap_resampled, outside_gap

  !> Gap values at or above this mark cells outside the potential contact.
  real(real64), parameter :: outside_gap = 1e29_real64

  !> Larger grids are refused (memory of the normal solve ~ 21 doubles per cell).
  integer, parameter :: max_gap_cells = 4000 * 4000

  type :: gap_t
    integer :: mx = 0, my = 0
    real(real64) :: dx = 0, dy = 0, x0 = 0, y0 = 0
    real(real64), allocatable :: h(:, :)
  contains
    procedure :: cell_x, cell_y
  end type gap_t

  !> h = x^2/(2 rx) + y^2/(2 ry) + lx x + ly y + cx x^3 + cy y^3 + h0
  !> (rx, ry <= 0 or huge: no curvature in that direction).
  type :: polynomial_gap_t
    real(real64) :: rx = 0, ry = 0
    real(real64) :: lx = 0, ly = 0, cx = 0, cy = 0, h0 = 0
  end type polynomial_gap_t

contains

  elemental real(real64) function cell_x(self, ix) result(x)
    class(gap_t), intent(in) :: self
    integer, intent(in) :: ix
    x = self%x0 + (ix - 1) * self%dx
  end function cell_x

  elemental real(real64) function cell_y(self, iy) result(y)
    class(gap_t), intent(in) :: self
    integer, intent(in) :: iy
    y = self%y0 + (iy - 1) * self%dy
  end function cell_y

  elemental real(real64) function polynomial_value(poly, x, y) result(h)
    type(polynomial_gap_t), intent(in) :: poly
    real(real64), intent(in) :: x, y
    h = poly%h0 + poly%lx * x + poly%ly * y + poly%cx * x**3 + poly%cy * y**3
    if (poly%rx > 0) h = h + x**2 / (2 * poly%rx)
    if (poly%ry > 0) h = h + y**2 / (2 * poly%ry)
  end function polynomial_value

  !> Check a grid description; source names the input in messages.
  subroutine check_grid(mx, my, dx, dy, source, status)
    integer, intent(in) :: mx, my
    real(real64), intent(in) :: dx, dy
    character(len=*), intent(in) :: source
    type(status_t), intent(inout) :: status
    if (mx < 1 .or. my < 1) then
      call fail(status, exit_bad_input, source//': mx, my = '//itoa(mx)//', '//itoa(my)//' (both must be >= 1)')
    else if (real(mx, real64) * my > max_gap_cells) then
      call fail(status, exit_bad_input, source//': mx * my = '//itoa(mx)//' * '//itoa(my)// &
                ' cells (at most '//itoa(max_gap_cells)//')')
    else if (.not. (dx > 0 .and. dy > 0 .and. dx < huge(dx) .and. dy < huge(dy))) then
      call fail(status, exit_bad_input, source//': dx, dy = '//rtoa(dx)//', '//rtoa(dy)//' (cell sizes must be > 0)')
    end if
  end subroutine check_grid

  !> A gap from values on a grid (e.g. read from a file); NaN/Inf refused.
  subroutine gap_from_array(h, dx, dy, x0, y0, source, gap, status)
    real(real64), intent(in) :: h(:, :)
    real(real64), intent(in) :: dx, dy, x0, y0
    character(len=*), intent(in) :: source
    type(gap_t), intent(out) :: gap
    type(status_t), intent(inout) :: status
    integer :: ix, iy
    call check_grid(size(h, 1), size(h, 2), dx, dy, source, status)
    if (status%failed()) return
    do iy = 1, size(h, 2)
      do ix = 1, size(h, 1)
        if (h(ix, iy) /= h(ix, iy) .or. abs(h(ix, iy)) > huge(1.0_real64)) then
          call fail(status, exit_bad_input, source//': gap value at cell ('//itoa(ix)//', '//itoa(iy)// &
                    ') is '//rtoa(h(ix, iy))//' (finite numbers only)')
          return
        end if
      end do
    end do
    gap%mx = size(h, 1)
    gap%my = size(h, 2)
    gap%dx = dx
    gap%dy = dy
    gap%x0 = x0
    gap%y0 = y0
    gap%h = h
  end subroutine gap_from_array

  !> A polynomial gap evaluated at the cell centres of the given grid.
  subroutine gap_from_polynomial(poly, mx, my, dx, dy, x0, y0, gap, status)
    type(polynomial_gap_t), intent(in) :: poly
    integer, intent(in) :: mx, my
    real(real64), intent(in) :: dx, dy, x0, y0
    type(gap_t), intent(out) :: gap
    type(status_t), intent(inout) :: status
    integer :: ix, iy
    call check_grid(mx, my, dx, dy, 'gap grid', status)
    if (status%failed()) return
    gap%mx = mx
    gap%my = my
    gap%dx = dx
    gap%dy = dy
    gap%x0 = x0
    gap%y0 = y0
    allocate (gap%h(mx, my))
    do iy = 1, my
      do ix = 1, mx
        gap%h(ix, iy) = polynomial_value(poly, gap%cell_x(ix), gap%cell_y(iy))
      end do
    end do
  end subroutine gap_from_polynomial

  !> A grid chosen from the interpenetration area {h < level} of a polynomial
  !> gap: the bounding box of that area (found on a fine sampling of the
  !> search box [-extent, extent]^2), widened by the relative margin on every
  !> side, with cells_across cells across its larger side (square cells).
  subroutine auto_grid(poly, level, extent, cells_across, margin, mx, my, dx, dy, x0, y0, status)
    type(polynomial_gap_t), intent(in) :: poly
    real(real64), intent(in) :: level, extent, margin
    integer, intent(in) :: cells_across
    integer, intent(out) :: mx, my
    real(real64), intent(out) :: dx, dy, x0, y0
    type(status_t), intent(inout) :: status
    integer, parameter :: ns = 2001
    real(real64) :: xs, ys, xlo, xhi, ylo, yhi, s, wx, wy
    integer :: i, j
    logical :: found

    mx = 0
    my = 0
    dx = 0
    dy = 0
    x0 = 0
    y0 = 0
    if (cells_across < 2) then
      call fail(status, exit_bad_input, 'cells_across = '//itoa(cells_across)//' (must be >= 2)')
      return
    end if
    if (.not. (margin >= 0 .and. margin <= 10)) then
      call fail(status, exit_bad_input, 'margin = '//rtoa(margin)//' (allowed 0 to 10, a fraction of the patch size)')
      return
    end if
    found = .false.
    xlo = huge(1.0_real64)
    xhi = -huge(1.0_real64)
    ylo = xlo
    yhi = xhi
    s = 2 * extent / (ns - 1)
    ! samples symmetric about 0 to the last bit (an integer times s/2), so that
    ! a gap even in x or y gives a box centred on 0 whatever the rounding
    do j = 1, ns
      ys = (2 * j - ns - 1) * (s / 2)
      do i = 1, ns
        xs = (2 * i - ns - 1) * (s / 2)
        if (polynomial_value(poly, xs, ys) < level) then
          found = .true.
          xlo = min(xlo, xs)
          xhi = max(xhi, xs)
          ylo = min(ylo, ys)
          yhi = max(yhi, ys)
        end if
      end do
    end do
    if (.not. found) then
      call fail(status, exit_bad_input, 'the surfaces do not interpenetrate at approach '//rtoa(level)// &
                ' (the undeformed distance is larger everywhere)')
      return
    end if
    ! the sampled box is exact to one sampling step: widen by it
    xlo = xlo - s
    xhi = xhi + s
    ylo = ylo - s
    yhi = yhi + s
    wx = xhi - xlo
    wy = yhi - ylo
    xlo = xlo - margin * wx
    xhi = xhi + margin * wx
    ylo = ylo - margin * wy
    yhi = yhi + margin * wy
    dx = max(xhi - xlo, yhi - ylo) / cells_across
    dy = dx
    mx = max(1, ceiling((xhi - xlo) / dx - 1e-9_real64))
    my = max(1, ceiling((yhi - ylo) / dy - 1e-9_real64))
    x0 = (xlo + xhi) / 2 - (mx - 1) * dx / 2
    y0 = (ylo + yhi) / 2 - (my - 1) * dy / 2
  end subroutine auto_grid

  !> The gap resampled at the cell centres of another grid (mx x my cells of
  !> dx x dy, (x0, y0) the centre of cell (1, 1)): bicubic Catmull-Rom
  !> interpolation of the given values (exact for quadratics, so a Hertzian
  !> gap comes out exact), beyond the outermost cell centres continued by
  !> quadratic extrapolation of the edge values (at most half a cell of the
  !> given grid, which the new grid should stay within). Where the stencil
  !> holds a cell outside the potential contact (>= outside_gap) the value of
  !> the nearest given cell is taken.
  pure function gap_resampled(gap, mx, my, dx, dy, x0, y0) result(fine)
    type(gap_t), intent(in) :: gap
    integer, intent(in) :: mx, my
    real(real64), intent(in) :: dx, dy, x0, y0
    type(gap_t) :: fine
    real(real64) :: sx, sy, wx(4), wy(4), v(4, 4)
    integer :: ix, iy, i0, j0, k, l
    logical :: outside

    fine%mx = mx
    fine%my = my
    fine%dx = dx
    fine%dy = dy
    fine%x0 = x0
    fine%y0 = y0
    allocate (fine%h(mx, my))
    do iy = 1, my
      sy = (fine%cell_y(iy) - gap%y0) / gap%dy + 1
      call stencil(sy, gap%my, j0, wy)
      do ix = 1, mx
        sx = (fine%cell_x(ix) - gap%x0) / gap%dx + 1
        call stencil(sx, gap%mx, i0, wx)
        outside = gap%mx < 3 .or. gap%my < 3
        if (.not. outside) then
          do l = 1, 4
            do k = 1, 4
              v(k, l) = value_at(i0 + k - 2, j0 + l - 2)
              outside = outside .or. v(k, l) >= outside_gap
            end do
          end do
        end if
        if (outside) then
          fine%h(ix, iy) = gap%h(min(max(nint(sx), 1), gap%mx), min(max(nint(sy), 1), gap%my))
        else
          fine%h(ix, iy) = dot_product(wy, matmul(transpose(v), wx))
        end if
      end do
    end do

  contains

    !> Index of the cell left of s (0 <= i0 <= n: the continued cells 0 and
    !> n + 1 take part beyond the outermost centres) and the four weights of
    !> cells i0 - 1 .. i0 + 2 (Keys' kernel, a = -1/2).
    pure subroutine stencil(s, n, i0, w)
      real(real64), intent(in) :: s
      integer, intent(in) :: n
      integer, intent(out) :: i0
      real(real64), intent(out) :: w(4)
      real(real64) :: t
      i0 = min(max(floor(s), 0), n)
      t = min(max(s - i0, 0.0_real64), 1.0_real64)
      w(1) = ((-t + 2) * t - 1) * t / 2
      w(2) = ((3 * t - 5) * t * t + 2) / 2
      w(3) = ((-3 * t + 4) * t + 1) * t / 2
      w(4) = (t - 1) * t * t / 2
    end subroutine stencil

    !> The given value, continued quadratically beyond the first and last cells.
    pure real(real64) function value_at(i, j) result(h)
      integer, intent(in) :: i, j
      real(real64) :: row(3)
      integer :: jj, k
      if (j < 1 .or. j > gap%my) then
        ! continue in y from three inner rows (each continued in x first)
        do k = 1, 3
          jj = merge(k, gap%my + 1 - k, j < 1)
          row(k) = in_x(i, jj)
        end do
        h = quadratic_beyond(row, merge(1 - j, j - gap%my, j < 1))
      else
        h = in_x(i, j)
      end if
    end function value_at

    !> Row j's value at column i, continued quadratically beyond its ends.
    pure real(real64) function in_x(i, j) result(h)
      integer, intent(in) :: i, j
      real(real64) :: col(3)
      integer :: k
      if (i < 1) then
        col = [(gap%h(k, j), k=1, 3)]
        h = quadratic_beyond(col, 1 - i)
      else if (i > gap%mx) then
        col = [(gap%h(gap%mx + 1 - k, j), k=1, 3)]
        h = quadratic_beyond(col, i - gap%mx)
      else
        h = gap%h(i, j)
      end if
    end function in_x

  end function gap_resampled

  !> The quadratic through v(1), v(2), v(3) at 0, 1, 2 cells inwards, at d cells
  !> outwards (d >= 1); any value >= outside_gap stays outside.
  pure real(real64) function quadratic_beyond(v, d) result(h)
    real(real64), intent(in) :: v(3)
    integer, intent(in) :: d
    if (any(v >= outside_gap)) then
      h = v(1)
    else
      ! Lagrange through x = 0, 1, 2 evaluated at x = -d
      h = v(1) * (d + 1) * (d + 2) / 2 - v(2) * d * (d + 2) + v(3) * d * (d + 1) / 2
    end if
  end function quadratic_beyond

end module kcreep_gap
