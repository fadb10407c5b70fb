!> A contact area known on a fine grid, sampled by coarser level grids.
!>
!> A gap's contact area comes from the normal problem on a grid (cells with
!> positive pressure). Error control solves the normal problem once on a
!> fine grid and lets the tangential levels sample that one area, so every
!> level describes the same shape, as an ellipse's levels do, instead of a
!> new contact boundary per level.
!>
!> The area is not taken as the fine grid's staircase but as the zero level
!> of p^2 interpolated bilinearly between the fine cell centres: near the
!> edge of a contact area p^2 falls linearly to zero (Hertz: p^2 = p0^2 (1 -
!> r^2/a^2)), so the boundary is placed inside the cells rather than on
!> cell edges. The outermost contact cells (a neighbour outside) carry about
!> the mean pressure over the cell, which the edge cuts, not the value at
!> the centre (Hertz at 50 cells across: 0.90 of the centre value,
!> lab/edge_pressure.py), and
!> their p^2 alone puts the edge inside by 0.02-0.08 cells; the parabola
!> through the three cells behind them uses centre values 0.4-1 % high near
!> the edge and puts it outside by as much. Their level is the mean of the
!> two (edge_blend). Outside the contact cells p^2 is continued
!> from the contact cells behind it along each of the 8 grid directions:
!> by the parabola through three (exact for Hertz's p^2 along any line),
!> the line through two, or mirrored where only one is there. A level's
!> cells are those the region reaches, each with its part inside
!> (kcreep_patch blended_patch; region_level_patch).
!>
!> The region's own moments (area, centre, second moments) are integrals
!> over the zero level itself: its pieces in each
!> rectangle of four fine cell centres (marching squares, the crossings on the
!> rectangle's sides exact for the bilinear level), integrated by Green's
!> theorem. A staircase of the region, however fine, moves them by a
!> fraction of its cells from one placement to the next.
module kcreep_region
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t
  use kcreep_patch, only: patch_t, mask_patch, shape_t, blended_patch, cell_sample_offsets
  implicit none
  private
  public :: region_t, sampled_region, region_level_patch, region_pressure, contact_diameter, level_size
  public :: contour_area, contour_moments

  real(real64), parameter :: pi = acos(-1.0_real64)
  !> Cells of the fine grid around its contact cells, for the continued p^2.
  integer, parameter :: pad = 2
  !> The region's reference staircase (its size and box; the moments come
  !> from the zero level itself) is sampled on cells up to this many times
  !> smaller than the fine grid's, on at most max_reference_cells grid cells
  !> (memory and time: 1e6 cells are about 50 ms).
  integer, parameter :: reference_split = 4
  real(real64), parameter :: max_reference_cells = 1e6_real64
  !> The outermost contact cells' level: this share of their own p^2, the
  !> rest from the parabola through the three cells behind them. Measured on
  !> the normal problem of Hertzian gaps a/b = 0.5, 1, 2, 3, 5, 10, 20 at 48 to
  !> 128 cells across the hydraulic diameter (28 grids; docs/normal.md):
  !> own value alone (1) median |aspect error| 0.089 % (at most 0.33 %),
  !> area 0.17 %; extrapolation alone (0) 0.19 % (0.50 %), area 0.20 %, on
  !> the other side; the mean (0.5) 0.024 % (0.12 %), area 0.014 % (the
  !> grids set by a temporary override of the cell count; reproducible at
  !> the default 128 cells: lab/gap_error_calibration.py prints
  !> the default runs' area against pi a b, 0.016 % median, and
  !> tests/unit/test_region.f90 checks one solved grid).
  real(real64), parameter :: edge_blend = 0.5_real64

  type, extends(shape_t) :: region_t
    integer :: mx = 0, my = 0                    !< the fine grid, padded
    real(real64) :: x0 = 0, y0 = 0               !< centre of its cell (1, 1)
    real(real64) :: hx = 0, hy = 0               !< its cells' sizes
    real(real64), allocatable :: level(:, :)     !< (mx, my) p^2, continued below zero outside
    type(patch_t) :: reference                   !< the region on cells a quarter the fine size (max_reference_cells)
    real(real64) :: diameter = 0                 !< the size levels are counted across (level_size)
    real(real64), allocatable :: edge(:, :)      !< (4, pieces) x, y from and to: the zero level, inside on the left
  contains
    procedure :: contains_point => region_contains_point
  end type region_t

  !> Three-point Gauss-Legendre on [0, 1]: exact for the polynomials (degree
  !> up to 5) integrated along the edge's straight pieces.
  real(real64), parameter :: gauss_t(3) = [0.5_real64 - sqrt(0.15_real64), 0.5_real64, 0.5_real64 + sqrt(0.15_real64)]
  real(real64), parameter :: gauss_w(3) = [5.0_real64 / 18, 8.0_real64 / 18, 5.0_real64 / 18]

contains

  !> The region of the contact cells `fine` with the pressure
  !> on the same grid. moments_only: only its zero level and moments, no
  !> reference staircase (a region that is compared, not sampled).
  function sampled_region(fine, pressure, status, moments_only) result(region)
    type(patch_t), intent(in) :: fine
    real(real64), intent(in) :: pressure(:, :)
    type(status_t), intent(inout) :: status
    logical, intent(in), optional :: moments_only
    type(region_t) :: region
    integer :: split
    region%mx = fine%mx + 2 * pad
    region%my = fine%my + 2 * pad
    region%hx = fine%dx
    region%hy = fine%dy
    region%x0 = fine%x0 - pad * fine%dx
    region%y0 = fine%y0 - pad * fine%dy
    allocate (region%level(region%mx, region%my), source=0.0_real64)
    where (pressure > 0) region%level(pad + 1:pad + fine%mx, pad + 1:pad + fine%my) = pressure**2
    call continue_outside(region%level)
    call zero_level_pieces(region)
    if (present(moments_only)) then
      if (moments_only) return
    end if
    split = max(1, min(reference_split, floor(sqrt(max_reference_cells / (real(fine%mx, real64) * fine%my)))))
    call region_patch(region, region%hx / split, fine%grid_box(), region%reference, status, region%hy / split)
    if (status%failed()) return
    region%diameter = level_size(region%reference)
  end function sampled_region

  !> The zero level of the bilinear level as straight pieces, one or two per
  !> square of four cell centres it crosses, each with the inside (level >
  !> 0) on its left. Going round a square counter-clockwise, a piece runs
  !> from a crossing out of the region to the crossing into it before it
  !> (the corners cut off) or after it (a saddle whose centre is inside).
  pure subroutine zero_level_pieces(region)
    type(region_t), intent(inout) :: region
    integer, parameter :: di(5) = [0, 1, 1, 0, 0], dj(5) = [0, 0, 1, 1, 0]
    real(real64) :: v(5), corner(2, 5), cross(2, 4)
    logical :: leaves(4)
    integer :: i, j, k, n, m, pieces
    allocate (region%edge(4, 2 * (region%mx - 1) * (region%my - 1)))
    pieces = 0
    do j = 1, region%my - 1
      do i = 1, region%mx - 1
        ! corners counter-clockwise, the first repeated
        v = [(region%level(i + di(k), j + dj(k)), k=1, 5)]
        if (all(v(1:4) > 0) .or. all(v(1:4) <= 0)) cycle
        corner(1, :) = region%x0 + (i - 1 + di) * region%hx
        corner(2, :) = region%y0 + (j - 1 + dj) * region%hy
        n = 0
        do k = 1, 4
          if ((v(k) > 0) .eqv. (v(k + 1) > 0)) cycle
          n = n + 1
          cross(:, n) = corner(:, k) + v(k) / (v(k) - v(k + 1)) * (corner(:, k + 1) - corner(:, k))
          leaves(n) = v(k) > 0
        end do
        do k = 1, n
          if (.not. leaves(k)) cycle
          if (n == 4 .and. sum(v(1:4)) > 0) then
            m = modulo(k, n) + 1           ! the crossing into the region after it
          else
            m = modulo(k - 2, n) + 1       ! the one before it
          end if
          pieces = pieces + 1
          region%edge(:, pieces) = [cross(:, k), cross(:, m)]
        end do
      end do
    end do
    region%edge = region%edge(:, 1:pieces)
  end subroutine zero_level_pieces

  !> The region's area, centroid and second moments about it, over the zero
  !> level: [area, xc, yc, integral of (x - xc)^2, of (y - yc)^2].
  pure function contour_moments(region) result(m)
    type(region_t), intent(in) :: region
    real(real64) :: m(5), area, xc, yc
    ! Green: the integral of P over the region is that of Q dy round its
    ! edge, dQ/dx = P: P = 1, x, y with Q = x, x^2 / 2, x y
    area = along_edge(region, 0.0_real64, 0.0_real64, 1)
    xc = along_edge(region, 0.0_real64, 0.0_real64, 2) / area
    yc = along_edge(region, 0.0_real64, 0.0_real64, 3) / area
    m = [area, xc, yc, along_edge(region, xc, yc, 4), along_edge(region, xc, yc, 5)]
  end function contour_moments

  !> The region's area, over its zero level.
  pure real(real64) function contour_area(region)
    type(region_t), intent(in) :: region
    contour_area = along_edge(region, 0.0_real64, 0.0_real64, 1)
  end function contour_area

  !> The integral of Q dy round the region's edge about (xc, yc), Q one of
  !> u, u^2 / 2, u w, u^3 / 3, u w^2 (u = x - xc, w = y - yc).
  pure real(real64) function along_edge(region, xc, yc, which) result(total)
    type(region_t), intent(in) :: region
    real(real64), intent(in) :: xc, yc
    integer, intent(in) :: which
    real(real64) :: u(3), w(3), q(3)
    integer :: k
    total = 0
    do k = 1, size(region%edge, 2)
      u = region%edge(1, k) + gauss_t * (region%edge(3, k) - region%edge(1, k)) - xc
      w = region%edge(2, k) + gauss_t * (region%edge(4, k) - region%edge(2, k)) - yc
      select case (which)
      case (1)
        q = u
      case (2)
        q = u**2 / 2
      case (3)
        q = u * w
      case (4)
        q = u**3 / 3
      case default
        q = u * w**2
      end select
      total = total + (region%edge(4, k) - region%edge(2, k)) * sum(gauss_w * q)
    end do
  end function along_edge

  !> The outermost contact cells' level blended with the parabola through
  !> the cells behind them (edge_blend); outside the contact cells (level =
  !> 0): the level continued from the contact cells behind it along the 8
  !> grid directions (quadratically, linearly or mirrored; the mean over
  !> those directions), at most -tiny; farther cells get -max(level).
  pure subroutine continue_outside(level)
    real(real64), intent(inout) :: level(:, :)
    real(real64), allocatable :: inside(:, :)
    real(real64) :: total, far
    integer :: i, j, di, dj, n, mx, my
    mx = size(level, 1)
    my = size(level, 2)
    inside = level
    far = -maxval(inside)
    do j = 1, my
      do i = 1, mx
        if (inside(i, j) <= 0) cycle
        total = 0
        n = 0
        do dj = -1, 1
          do di = -1, 1
            if (di == 0 .and. dj == 0) cycle
            ! towards a neighbour outside the contact, with three contact cells behind
            if (in_contact(i + di, j + dj) .or. .not. on_grid(i + di, j + dj)) cycle
            if (.not. (in_contact(i - di, j - dj) .and. in_contact(i - 2 * di, j - 2 * dj) .and. &
                       in_contact(i - 3 * di, j - 3 * dj))) cycle
            n = n + 1
            total = total + 3 * inside(i - di, j - dj) - 3 * inside(i - 2 * di, j - 2 * dj) + &
                    inside(i - 3 * di, j - 3 * dj)
          end do
        end do
        if (n > 0) level(i, j) = max(edge_blend * inside(i, j) + (1 - edge_blend) * total / n, tiny(1.0_real64))
      end do
    end do
    where (inside > 0) inside = level
    do j = 1, my
      do i = 1, mx
        if (inside(i, j) > 0) cycle
        total = 0
        n = 0
        do dj = -1, 1
          do di = -1, 1
            if (di == 0 .and. dj == 0) cycle
            if (.not. in_contact(i + di, j + dj)) cycle
            n = n + 1
            if (in_contact(i + 3 * di, j + 3 * dj) .and. in_contact(i + 2 * di, j + 2 * dj)) then
              total = total + 3 * inside(i + di, j + dj) - 3 * inside(i + 2 * di, j + 2 * dj) + &
                      inside(i + 3 * di, j + 3 * dj)
            else if (in_contact(i + 2 * di, j + 2 * dj)) then
              total = total + 2 * inside(i + di, j + dj) - inside(i + 2 * di, j + 2 * dj)
            else
              total = total - inside(i + di, j + dj)
            end if
          end do
        end do
        if (n > 0) then
          level(i, j) = min(total / n, -tiny(1.0_real64))
        else
          level(i, j) = far
        end if
      end do
    end do
  contains
    pure logical function in_contact(i, j)
      integer, intent(in) :: i, j
      in_contact = .false.
      if (on_grid(i, j)) in_contact = inside(i, j) > 0
    end function in_contact
    pure logical function on_grid(i, j)
      integer, intent(in) :: i, j
      on_grid = i >= 1 .and. i <= mx .and. j >= 1 .and. j <= my
    end function on_grid
  end subroutine continue_outside

  !> The level interpolated bilinearly at (x, y).
  pure real(real64) function level_at(region, x, y) result(value)
    type(region_t), intent(in) :: region
    real(real64), intent(in) :: x, y
    real(real64) :: u, v, s, t
    integer :: i, j
    u = (x - region%x0) / region%hx + 1
    v = (y - region%y0) / region%hy + 1
    i = min(max(floor(u), 1), region%mx - 1)
    j = min(max(floor(v), 1), region%my - 1)
    s = min(max(u - i, 0.0_real64), 1.0_real64)
    t = min(max(v - j, 0.0_real64), 1.0_real64)
    value = (1 - s) * (1 - t) * region%level(i, j) + s * (1 - t) * region%level(i + 1, j) + &
            (1 - s) * t * region%level(i, j + 1) + s * t * region%level(i + 1, j + 1)
  end function level_at

  !> Whether (x, y) lies in the region: its level above zero.
  pure logical function region_contains_point(self, x, y)
    class(region_t), intent(in) :: self
    real(real64), intent(in) :: x, y
    region_contains_point = level_at(self, x, y) > 0
  end function region_contains_point

  !> The cells of size h x hy (hy = h unless given) over box (centred on
  !> it, one cell wider on every side) whose centres lie in the region;
  !> blended: every cell the region reaches, with its fraction inside.
  subroutine region_patch(region, h, box, patch, status, hy, blended)
    type(region_t), intent(in) :: region
    real(real64), intent(in) :: h, box(4)
    type(patch_t), intent(out) :: patch
    type(status_t), intent(inout) :: status
    real(real64), intent(in), optional :: hy
    logical, intent(in), optional :: blended
    real(real64) :: x0, y0, dy
    logical, allocatable :: inside(:, :)
    integer :: mx, my, ix, iy
    dy = h
    if (present(hy)) dy = hy
    mx = ceiling((box(2) - box(1)) / h) + 2
    my = ceiling((box(4) - box(3)) / dy) + 2
    x0 = (box(1) + box(2)) / 2 - (mx - 1) * h / 2
    y0 = (box(3) + box(4)) / 2 - (my - 1) * dy / 2
    if (present(blended)) then
      if (blended) then
        call blended_patch(region, mx, my, h, dy, x0, y0, 'gap', patch, status)
        return
      end if
    end if
    allocate (inside(mx, my))
    do iy = 1, my
      do ix = 1, mx
        inside(ix, iy) = level_at(region, x0 + (ix - 1) * h, y0 + (iy - 1) * dy) > 0
      end do
    end do
    call mask_patch(inside, h, dy, x0, y0, 'contact area level', patch, status)
    if (status%failed()) return
    patch%kind = 'gap'
  end subroutine region_patch

  !> A level of `cells` across the region's diameter with a blended edge,
  !> each cell cell_shape(1) times that size in x and cell_shape(2) in y.
  subroutine region_level_patch(region, cells, cell_shape, patch, status)
    type(region_t), intent(in) :: region
    integer, intent(in) :: cells
    real(real64), intent(in) :: cell_shape(2)
    type(patch_t), intent(out) :: patch
    type(status_t), intent(inout) :: status
    call region_patch(region, cell_shape(1) * region%diameter / cells, region%reference%grid_box(), patch, status, &
                      cell_shape(2) * region%diameter / cells, blended=.true.)
  end subroutine region_level_patch

  !> The pressure of patch's cells: sqrt of the interpolated p^2 at the
  !> centre, or, where the centre lies outside the region (an edge cell of a
  !> blended level, only part of it inside), its mean over the cell's sample
  !> points (those of its fraction inside, kcreep_patch cell_sample_offsets).
  !> So every cell of the patch has a positive traction bound, and FASTSIM's
  !> slopes at small creepage stay f11, f22, f23 (a cell at p = 0 slips at
  !> any creepage: 0.15 % of f11 lost on a centred Hertzian gap, test
  !> fastsim_namelist).
  pure function region_pressure(region, patch) result(p)
    type(region_t), intent(in) :: region
    type(patch_t), intent(in) :: patch
    real(real64) :: p(patch%n)
    real(real64) :: x, y, sum_p, u(size(cell_sample_offsets()))
    integer :: k, i, j
    u = cell_sample_offsets()
    do k = 1, patch%n
      x = patch%cell_x(patch%ix(k))
      y = patch%cell_y(patch%iy(k))
      p(k) = sqrt(max(level_at(region, x, y), 0.0_real64))
      if (p(k) > 0) cycle
      sum_p = 0
      do j = 1, size(u)
        do i = 1, size(u)
          sum_p = sum_p + sqrt(max(level_at(region, x + u(i) * patch%dx, y + u(j) * patch%dy), 0.0_real64))
        end do
      end do
      p(k) = sum_p / size(u)**2
    end do
  end function region_pressure

  !> The size a contact area's levels are counted across: its hydraulic
  !> diameter (contact_diameter), or the shorter axis of its second-moment
  !> ellipse where that is shorter (a long area: a/b = 2.9 has 1.45 times
  !> as many cells across its width on the hydraulic diameter's count).
  pure real(real64) function level_size(area)
    type(patch_t), intent(in) :: area
    real(real64) :: m(2)
    m = area%second_moments(area%centroid())
    level_size = min(contact_diameter(area), 4 * sqrt(minval(m) / area%n))
  end function level_size

  !> The size the levels are counted across: 4 area / perimeter of the contact
  !> area (its hydraulic diameter: a circle's diameter, 0.79 times the short axis
  !> of a long ellipse, each lobe's diameter for two equal round lobes), the
  !> perimeter from the staircase's, times pi/4 (the mean ratio of a curve's
  !> length to that of its staircase over all directions).
  pure real(real64) function contact_diameter(patch) result(d)
    type(patch_t), intent(in) :: patch
    logical, allocatable :: inside(:, :)
    integer :: k, edges_x, edges_y
    allocate (inside(0:patch%mx + 1, 0:patch%my + 1))
    inside = .false.
    do k = 1, patch%n
      inside(patch%ix(k), patch%iy(k)) = .true.
    end do
    edges_x = count(inside(0:patch%mx, :) .neqv. inside(1:patch%mx + 1, :))   ! edges of length dy
    edges_y = count(inside(:, 0:patch%my) .neqv. inside(:, 1:patch%my + 1))   ! edges of length dx
    d = 4 * patch%area() / (pi / 4 * (edges_x * patch%dy + edges_y * patch%dx))
  end function contact_diameter

end module kcreep_region
