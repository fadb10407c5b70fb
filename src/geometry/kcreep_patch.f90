!> The contact patch: a uniform grid of rectangular cells and the mask of the
!> cells that are in contact.
!>
!> Grid convention: cell (ix, iy), ix = 1..mx along x (rolling direction),
!> iy = 1..my along y, has its centre at (x0 + (ix-1)*dx, y0 + (iy-1)*dy).
!> Only the cells of the mask become unknowns; they are numbered in the
!> order of the grid (ix fastest).
!>
!> A level of a shape kcreep samples (an ellipse, a contact area) has a
!> blended edge (blended_patch): every cell the shape reaches is a patch
!> cell, with the part of it inside the shape (fraction). The solver blends
!> such a cell's equation between the slip condition and zero traction
!> (kcreep_assembly slip_weight).
!>
!> Geometry only: files with masks are read in io (kcreep_mask_file).
module kcreep_patch
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa
  use kcreep_limits, only: check_grid_size
  implicit none
  private
  public :: patch_t, ellipse_patch, mask_patch, place_like, near_square_cells, part_patch
  public :: shape_t, ellipse_shape_t, blended_patch, cell_sample_offsets

  type :: patch_t
    character(len=:), allocatable :: kind     !< 'ellipse', 'mask' or 'contact'
    integer :: mx = 0, my = 0                 !< grid cells along x and y
    real(real64) :: dx = 0, dy = 0            !< cell sizes
    real(real64) :: x0 = 0, y0 = 0            !< centre of cell (1, 1)
    real(real64) :: semi_a = 0, semi_b = 0    !< ellipse semi-axes (kind 'ellipse' only)
    logical, allocatable :: inside(:, :)      !< (mx, my): cell is in the patch
    integer :: n = 0                          !< number of patch cells
    integer, allocatable :: ix(:), iy(:)      !< grid indices of patch cell k
    !> (n) the part of patch cell k inside the sampled shape (blended_patch);
    !> unallocated: every patch cell is wholly in the patch
    real(real64), allocatable :: fraction(:)
  contains
    procedure :: cell_x, cell_y, area, equivalent_radius, centroid, grid_box, cells_box, ellipse_centre
    procedure :: second_moments
    procedure :: mirror_symmetric_in_x, mirror_symmetric_in_y, fraction_grid, staircase, in_staircase, cell_ahead
  end type patch_t

  !> A shape a level samples: whether a point lies in it.
  type, abstract :: shape_t
  contains
    procedure(point_test), deferred :: contains_point
  end type shape_t

  abstract interface
    pure logical function point_test(self, x, y)
      import :: shape_t, real64
      class(shape_t), intent(in) :: self
      real(real64), intent(in) :: x, y
    end function point_test
  end interface

  !> The ellipse (x/a)^2 + (y/b)^2 <= 1.
  type, extends(shape_t) :: ellipse_shape_t
    real(real64) :: semi_a = 1, semi_b = 1
  contains
    procedure :: contains_point => ellipse_contains_point
  end type ellipse_shape_t

  !> Sample points per cell side where a cell's fraction inside is counted
  !> (the fraction to 1/256 of the cell); a cell whose corners, edge
  !> midpoints and centre are all on one side is taken as wholly in or out.
  integer, parameter :: fraction_samples = 16

contains

  !> Cells of an mx x my grid over [-a, a] x [-b, b] whose centres lie in
  !> the ellipse; blended: every cell it reaches, with its fraction inside
  !> (a level of kcreep's ladder).
  subroutine ellipse_patch(semi_a, semi_b, mx, my, patch, status, blended)
    real(real64), intent(in) :: semi_a, semi_b
    integer, intent(in) :: mx, my
    type(patch_t), intent(out) :: patch
    type(status_t), intent(inout) :: status
    logical, intent(in), optional :: blended
    integer :: ix, iy
    real(real64) :: x, y

    if (present(blended)) then
      if (blended) then
        call blended_patch(ellipse_shape_t(semi_a, semi_b), mx, my, 2 * semi_a / mx, 2 * semi_b / my, &
                           -semi_a + semi_a / mx, -semi_b + semi_b / my, 'ellipse', patch, status)
        patch%semi_a = semi_a
        patch%semi_b = semi_b
        return
      end if
    end if
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

  !> Cells along an axis `ratio` times as long as the one with `cells` cells,
  !> for cells about as long as wide (never fewer than `cells`).
  pure integer function near_square_cells(cells, ratio) result(along)
    integer, intent(in) :: cells
    real(real64), intent(in) :: ratio
    along = max(cells, nint(cells * ratio))
  end function near_square_cells

  !> Move an ellipse patch regenerated on another grid so that its centre is
  !> where source's is (source may have been moved, e.g. to put a spin centre
  !> at the origin).
  pure subroutine place_like(patch, source)
    type(patch_t), intent(inout) :: patch
    type(patch_t), intent(in) :: source
    real(real64) :: shift(2)
    shift = source%ellipse_centre()
    patch%x0 = patch%x0 + shift(1)
    patch%y0 = patch%y0 + shift(2)
  end subroutine place_like

  pure logical function ellipse_contains_point(self, x, y)
    class(ellipse_shape_t), intent(in) :: self
    real(real64), intent(in) :: x, y
    ellipse_contains_point = (x / self%semi_a)**2 + (y / self%semi_b)**2 <= 1
  end function ellipse_contains_point

  !> The cells of an mx x my grid (cell (1, 1) centred at x0, y0) that any
  !> part of `shape` reaches, each with the fraction of it inside.
  subroutine blended_patch(shape, mx, my, dx, dy, x0, y0, kind, patch, status)
    class(shape_t), intent(in) :: shape
    integer, intent(in) :: mx, my
    real(real64), intent(in) :: dx, dy, x0, y0
    character(len=*), intent(in) :: kind
    type(patch_t), intent(out) :: patch
    type(status_t), intent(inout) :: status
    real(real64) :: fraction(mx, my)
    integer :: ix, iy, k
    do iy = 1, my
      do ix = 1, mx
        fraction(ix, iy) = cell_fraction(shape, x0 + (ix - 1) * dx, y0 + (iy - 1) * dy, dx, dy)
      end do
    end do
    call mask_patch(fraction > 0, dx, dy, x0, y0, kind, patch, status)
    if (status%failed()) return
    patch%kind = kind
    patch%fraction = [(fraction(patch%ix(k), patch%iy(k)), k=1, patch%n)]
  end subroutine blended_patch

  !> The part of the dx x dy cell centred at (xc, yc) that lies in shape.
  pure real(real64) function cell_fraction(shape, xc, yc, dx, dy) result(fraction)
    class(shape_t), intent(in) :: shape
    real(real64), intent(in) :: xc, yc, dx, dy
    real(real64) :: u(fraction_samples)
    integer :: i, j, hits
    hits = 0
    do j = -1, 1
      do i = -1, 1
        if (shape%contains_point(xc + i * dx / 2, yc + j * dy / 2)) hits = hits + 1
      end do
    end do
    if (hits == 0 .or. hits == 9) then
      fraction = merge(1, 0, hits == 9)
      return
    end if
    u = cell_sample_offsets()
    hits = 0
    do j = 1, fraction_samples
      do i = 1, fraction_samples
        if (shape%contains_point(xc + u(i) * dx, yc + u(j) * dy)) hits = hits + 1
      end do
    end do
    fraction = real(hits, real64) / fraction_samples**2
  end function cell_fraction

  !> The sample points' offsets from a cell's centre along one side, in units
  !> of the cell's size: fraction_samples of them, evenly inside (-1/2, 1/2).
  pure function cell_sample_offsets() result(u)
    real(real64) :: u(fraction_samples)
    integer :: i
    u = [((i - 0.5_real64) / fraction_samples - 0.5_real64, i=1, fraction_samples)]
  end function cell_sample_offsets

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

  !> The cells of patch where keep is true, on the same grid and in the same
  !> order (keep has one entry per patch cell).
  pure function part_patch(patch, keep) result(part)
    type(patch_t), intent(in) :: patch
    logical, intent(in) :: keep(:)
    type(patch_t) :: part
    integer :: k
    part = patch
    part%inside = .false.
    do k = 1, patch%n
      if (.not. keep(k)) cycle
      part%inside(patch%ix(k), patch%iy(k)) = .true.
    end do
    part%n = count(keep)
    part%ix = pack(patch%ix, keep)
    part%iy = pack(patch%iy, keep)
    if (allocated(patch%fraction)) part%fraction = pack(patch%fraction, keep)
  end function part_patch

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

  !> The patch's area (a blended patch's cells counted by their fraction inside).
  pure real(real64) function area(self)
    class(patch_t), intent(in) :: self
    if (allocated(self%fraction)) then
      area = sum(self%fraction) * self%dx * self%dy
    else
      area = self%n * self%dx * self%dy
    end if
  end function area

  !> The grid's outer cell edges: xmin, xmax, ymin, ymax.
  pure function grid_box(self) result(box)
    class(patch_t), intent(in) :: self
    real(real64) :: box(4)
    box = [self%x0 - self%dx / 2, self%x0 + (self%mx - 0.5_real64) * self%dx, &
           self%y0 - self%dy / 2, self%y0 + (self%my - 0.5_real64) * self%dy]
  end function grid_box

  !> xmin xmax ymin ymax of the patch cells (cell edges).
  pure function cells_box(self) result(box)
    class(patch_t), intent(in) :: self
    real(real64) :: box(4)
    box = [self%cell_x(minval(self%ix)) - self%dx / 2, self%cell_x(maxval(self%ix)) + self%dx / 2, &
           self%cell_y(minval(self%iy)) - self%dy / 2, self%cell_y(maxval(self%iy)) + self%dy / 2]
  end function cells_box

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

  !> Centre of an ellipse patch's ellipse, where the patch was placed (the
  !> grid of ellipse_patch spans [-a, a] x [-b, b] about it).
  pure function ellipse_centre(self) result(xy)
    class(patch_t), intent(in) :: self
    real(real64) :: xy(2)
    xy = [self%x0 - (-self%semi_a + self%dx / 2), self%y0 - (-self%semi_b + self%dy / 2)]
  end function ellipse_centre

  !> Second moments of area about centre in cell units (sum over the cells of
  !> (x - xc)^2 and (y - yc)^2, each cell counted with its own dx^2/12, dy^2/12):
  !> times dx dy they are Ixx, Iyy.
  pure function second_moments(self, centre) result(m)
    class(patch_t), intent(in) :: self
    real(real64), intent(in) :: centre(2)
    real(real64) :: m(2)
    m = [sum((self%cell_x(self%ix) - centre(1))**2) + self%n * self%dx**2 / 12, &
         sum((self%cell_y(self%iy) - centre(2))**2) + self%n * self%dy**2 / 12]
  end function second_moments

  !> Centre of area of the patch cells (a blended patch's weighted by their fraction inside).
  pure function centroid(self) result(xy)
    class(patch_t), intent(in) :: self
    real(real64) :: xy(2)
    if (allocated(self%fraction)) then
      xy = [sum(self%fraction * self%cell_x(self%ix)), sum(self%fraction * self%cell_y(self%iy))] / sum(self%fraction)
    else
      xy = [sum(self%cell_x(self%ix)), sum(self%cell_y(self%iy))] / max(1, self%n)
    end if
  end function centroid

  !> The patch is its own mirror image in x about x = 0 (cell positions and fractions included).
  pure logical function mirror_symmetric_in_x(self)
    class(patch_t), intent(in) :: self
    real(real64) :: grid(self%mx, self%my)
    mirror_symmetric_in_x = abs(self%x0 + (self%mx - 1) * self%dx / 2) <= 1e-12_real64 * self%dx * self%mx
    if (.not. mirror_symmetric_in_x) return
    grid = self%fraction_grid()
    mirror_symmetric_in_x = all(grid == grid(self%mx:1:-1, :))
  end function mirror_symmetric_in_x

  !> The patch is its own mirror image in y about y = 0 (cell positions and fractions included).
  pure logical function mirror_symmetric_in_y(self)
    class(patch_t), intent(in) :: self
    real(real64) :: grid(self%mx, self%my)
    mirror_symmetric_in_y = abs(self%y0 + (self%my - 1) * self%dy / 2) <= 1e-12_real64 * self%dy * self%my
    if (.not. mirror_symmetric_in_y) return
    grid = self%fraction_grid()
    mirror_symmetric_in_y = all(grid == grid(:, self%my:1:-1))
  end function mirror_symmetric_in_y

  !> The staircase a patch stands for: of a blended patch its cells at
  !> least half inside (about those whose centres are inside; FASTSIM's
  !> strips and the equivalent ellipses are taken from it), else the patch.
  pure function staircase(self) result(cells)
    class(patch_t), intent(in) :: self
    type(patch_t) :: cells
    cells = part_patch(self, self%in_staircase())
    if (allocated(cells%fraction)) deallocate (cells%fraction)
  end function staircase

  !> (n) whether each patch cell is in the staircase (staircase).
  pure function in_staircase(self) result(keep)
    class(patch_t), intent(in) :: self
    logical :: keep(self%n)
    keep = .true.
    if (allocated(self%fraction)) keep = self%fraction >= 0.5_real64
  end function in_staircase

  !> (n) the patch cell next in x (the leading edge's side) of each patch
  !> cell, 0 where its row of patch cells ends. Cells are numbered row by
  !> row, x increasing within a row, so it is k + 1 or none.
  pure function cell_ahead(self) result(ahead)
    class(patch_t), intent(in) :: self
    integer :: ahead(self%n)
    integer :: k
    ahead = 0
    do k = 1, self%n - 1
      if (self%iy(k + 1) == self%iy(k) .and. self%ix(k + 1) == self%ix(k) + 1) ahead(k) = k + 1
    end do
  end function cell_ahead

  !> Each grid cell's part in the patch: 0 outside, 1 or its fraction inside.
  pure function fraction_grid(self) result(grid)
    class(patch_t), intent(in) :: self
    real(real64) :: grid(self%mx, self%my)
    integer :: k
    grid = 0
    do k = 1, self%n
      grid(self%ix(k), self%iy(k)) = 1
      if (allocated(self%fraction)) grid(self%ix(k), self%iy(k)) = self%fraction(k)
    end do
  end function fraction_grid

end module kcreep_patch
