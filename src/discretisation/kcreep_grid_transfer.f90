!> A patch's grids: a patch and its pressure coarsened by blocks of cells
!> (coarsened_patch), and tractions carried from one grid of a patch to
!> another (transferred_traction): the starting guess
!> of the iterative solver on the next level of error control, which solves
!> the same patch on finer cells. A guess only has to be close: GMRES still
!> solves to its tolerance on the new grid, so the result does not depend on
!> the guess beyond that tolerance.
module kcreep_grid_transfer
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t
  use kcreep_patch, only: patch_t, mask_patch
  implicit none
  private
  public :: transferred_traction, coarsened_patch

  !> How far (in source cells, each way) a target cell outside the source's
  !> cells looks for the nearest source cell: the levels differ by about 15 %,
  !> so the boundary moves by a cell or two.
  integer, parameter :: search_cells = 2

contains

  !> The tractions (2 n_to, columns) on the cells of `to`, from tractions
  !> (2 n_from, columns) on the cells of `from`: bilinear between the four
  !> source cell centres around each target centre, over those of the four
  !> that are in the source patch (weights renormalised); where none is, the
  !> nearest source cell within search_cells; else zero. Columns holding NaN
  !> (a load case not solved) give zeros.
  pure function transferred_traction(from, traction, to) result(guess)
    type(patch_t), intent(in) :: from, to
    real(real64), intent(in) :: traction(:, :)
    real(real64), allocatable :: guess(:, :)
    integer, allocatable :: cell_of(:, :)      ! heap, not stack: grids reach millions of cells
    integer :: k, i, j, di, dj, c, best
    real(real64) :: fx, fy, wx, wy, w, weights, d2, best_d2
    real(real64) :: sums(2, size(traction, 2))

    allocate (guess(2 * to%n, size(traction, 2)), cell_of(from%mx, from%my))
    cell_of = 0
    do k = 1, from%n
      cell_of(from%ix(k), from%iy(k)) = k
    end do
    do k = 1, to%n
      ! the target centre in source index units (1 = the first centre)
      fx = (to%cell_x(to%ix(k)) - from%x0) / from%dx + 1
      fy = (to%cell_y(to%iy(k)) - from%y0) / from%dy + 1
      i = floor(fx)
      j = floor(fy)
      sums = 0
      weights = 0
      do dj = 0, 1
        do di = 0, 1
          c = cell_at(i + di, j + dj)
          if (c == 0) cycle
          wx = merge(fx - i, 1 - (fx - i), di == 1)
          wy = merge(fy - j, 1 - (fy - j), dj == 1)
          w = wx * wy
          sums(1, :) = sums(1, :) + w * traction(c, :)
          sums(2, :) = sums(2, :) + w * traction(from%n + c, :)
          weights = weights + w
        end do
      end do
      if (weights > 0) then
        guess(k, :) = sums(1, :) / weights
        guess(to%n + k, :) = sums(2, :) / weights
        cycle
      end if
      best = 0
      best_d2 = huge(1.0_real64)
      do dj = -search_cells, search_cells + 1
        do di = -search_cells, search_cells + 1
          c = cell_at(i + di, j + dj)
          if (c == 0) cycle
          d2 = (fx - (i + di))**2 + (fy - (j + dj))**2
          if (d2 < best_d2) then
            best_d2 = d2
            best = c
          end if
        end do
      end do
      if (best > 0) then
        guess(k, :) = traction(best, :)
        guess(to%n + k, :) = traction(from%n + best, :)
      else
        guess(k, :) = 0
        guess(to%n + k, :) = 0
      end if
    end do
    where (guess /= guess) guess = 0

  contains

    !> The source cell at grid index (ix, iy), 0 outside the grid or the patch.
    pure integer function cell_at(ix, iy)
      integer, intent(in) :: ix, iy
      cell_at = 0
      if (ix >= 1 .and. ix <= from%mx .and. iy >= 1 .and. iy <= from%my) cell_at = cell_of(ix, iy)
    end function cell_at

  end function transferred_traction

  !> The patch coarsened by blocks of kx x ky cells, the smallest blocks (their sides within
  !> a factor 1.5 of each other) that leave at most max_cells cells: a block is a coarse
  !> cell when at least half its cells carry pressure pn (mx, my); its pressure the block's
  !> mean, all scaled to keep the normal force; its centre the block's. An empty coarse
  !> patch (n = 0) when none is left. The fast force model's coarse level and a contact
  !> table's force grid (kcreep_coarsen_patch).
  subroutine coarsened_patch(patch, pn, max_cells, coarse, coarse_pn)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: pn(:, :)
    integer, intent(in) :: max_cells
    type(patch_t), intent(out) :: coarse
    real(real64), allocatable, intent(out) :: coarse_pn(:, :)
    type(status_t) :: status
    integer, allocatable :: loaded(:, :)
    logical, allocatable :: inside(:, :)
    real(real64) :: total, fine_total
    integer :: kx, ky, mx, my, c, bx, by
    kx = 1
    ky = 1
    do while (patch%n > max(max_cells, 1) * kx * ky .or. (kx * ky > 1 .and. &
              max(kx * patch%dx, ky * patch%dy) > 1.5_real64 * min(kx * patch%dx, ky * patch%dy)))
      if (kx * patch%dx <= ky * patch%dy) then
        kx = kx + 1
      else
        ky = ky + 1
      end if
    end do
    mx = (patch%mx + kx - 1) / kx
    my = (patch%my + ky - 1) / ky
    allocate (loaded(mx, my), coarse_pn(mx, my))
    loaded = 0
    coarse_pn = 0
    do c = 1, patch%n
      bx = (patch%ix(c) - 1) / kx + 1
      by = (patch%iy(c) - 1) / ky + 1
      if (pn(patch%ix(c), patch%iy(c)) > 0) loaded(bx, by) = loaded(bx, by) + 1
      coarse_pn(bx, by) = coarse_pn(bx, by) + pn(patch%ix(c), patch%iy(c)) / (kx * ky)
    end do
    inside = 2 * loaded >= kx * ky .and. loaded > 0
    fine_total = sum(coarse_pn)   ! every cell's share, before the sparse blocks are dropped
    where (.not. inside) coarse_pn = 0
    total = sum(coarse_pn)
    if (total > 0) coarse_pn = coarse_pn * (fine_total / total)
    call mask_patch(inside, kx * patch%dx, ky * patch%dy, patch%x0 + 0.5_real64 * (kx - 1) * patch%dx, &
                    patch%y0 + 0.5_real64 * (ky - 1) * patch%dy, 'coarsened patch', coarse, status)
    if (status%failed()) coarse%n = 0
  end subroutine coarsened_patch

end module kcreep_grid_transfer
