!> Circulant preconditioner for the iterative solver of the backward scheme.
!>
!> The backward system is slip = D u, u = A p: D the one-cell upwind
!> difference along x, A the displacement operator. Its approximate inverse
!> is built from the two factors:
!>   D^-1 exactly, a running sum along each run of patch cells in a grid row,
!>        from the leading edge (largest x), where the displacement just
!>        ahead of the run is taken as zero;
!>   A^-1 as a circulant: the displacement kernel on a periodic FFT grid
!>        5/4 of the patch's bounding grid each way, inverted frequency by
!>        frequency (kcreep_fft_operator, create_inverse_displacement).
!> The running sum carries the leading-edge condition that makes the system
!> one-sided; the circulant carries the smooth far coupling of 1/r; the
!> circulant is conjugated by the square root of the distance to the edge
!> (apply_circulant_preconditioner), which makes it follow the patch. Neither
!> depends on the length of the rows, so the work per step is two FFT
!> passes whatever the patch's shape, and the iteration count stays nearly
!> the same as the grid is refined (measured in docs/performance.md).
module kcreep_circulant_preconditioner
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep_fft_operator, only: fft_operator_t, create_inverse_displacement, set_fft_cells, destroy_fft_operator, &
                                 apply_fft_operator
  implicit none
  private
  public :: circulant_preconditioner_t, build_circulant_preconditioner, set_circulant_cells, &
            apply_circulant_preconditioner, destroy_circulant_preconditioner

  type :: circulant_preconditioner_t
    integer :: n = 0
    real(real64) :: dx = 0
    !> For each patch cell: it is the last of its run in its grid row (the leading edge).
    logical, allocatable :: leading(:)
    !> sqrt of each cell's distance to the nearest cell outside the patch (edge_weights)
    real(real64), allocatable :: weight(:)
    type(fft_operator_t) :: inverse_displacement
    real(real64), allocatable :: u(:, :)   !< work: displacements, kept between steps
  end type circulant_preconditioner_t

contains

  !> The preconditioner on patch's grid (plans and inverse spectra, which
  !> depend on the grid and nu only), for patch's cells.
  subroutine build_circulant_preconditioner(patch, nu, max_vectors, prec)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: nu
    integer, intent(in) :: max_vectors
    type(circulant_preconditioner_t), intent(out) :: prec
    call create_inverse_displacement(patch, nu, max_vectors, prec%inverse_displacement)
    call set_circulant_cells(prec, patch)
  end subroutine build_circulant_preconditioner

  !> The preconditioner for another patch on the grid it was built on: the
  !> runs along the rows and the edge weights follow the patch's cells.
  subroutine set_circulant_cells(prec, patch)
    type(circulant_preconditioner_t), intent(inout) :: prec
    type(patch_t), intent(in) :: patch

    call set_fft_cells(prec%inverse_displacement, patch)
    prec%n = patch%n
    prec%dx = patch%dx
    prec%leading = patch%cell_ahead() == 0
    call edge_weights(patch, prec%weight)
  end subroutine set_circulant_cells

  !> z = W A_circ^-1 W^-1 D^-1 r for each column (px(1:n), py(1:n)); W: the
  !> edge weights. The circulant inverse knows nothing of the patch's edge,
  !> where the true solution has its square-root behaviour: conjugated by W
  !> it follows the edge. Measured (GMRES iterations, tolerance 1e-11,
  !> unweighted -> weighted): unit circle 40 x 40: 22 -> 19, 100 x 100: 28 ->
  !> 23, 200 x 200: 34 -> 25; ellipse a/b = 5, 100 x 20: 22 -> 20, a/b = 0.2:
  !> 23 -> 20; collocation 60 x 60: 27 -> 24; the moving 40 x 40 mask of
  !> tests/api/api_example.c: 20.0 -> 17.9. W^-1 A_circ^-1 W (the weights
  !> the other way round) needs more iterations than none (24.3), and so do
  !> other powers of the distance (0.25: 18.4, 0.75: 20.5).
  subroutine apply_circulant_preconditioner(prec, r, z)
    type(circulant_preconditioner_t), intent(inout) :: prec
    real(real64), intent(in) :: r(:, :)    !< (2n, nv)
    real(real64), intent(out) :: z(:, :)   !< (2n, nv)
    integer :: v, c, k, n
    real(real64) :: run

    n = prec%n
    if (allocated(prec%u)) then
      if (size(prec%u, 1) /= 2 * n .or. size(prec%u, 2) < size(r, 2)) deallocate (prec%u)
    end if
    if (.not. allocated(prec%u)) allocate (prec%u(2 * n, size(r, 2)))
    associate (u => prec%u(:, 1:size(r, 2)))
      ! (u(k+1) - u(k)) / dx = r(k)  =>  u(k) = u(k+1) - dx r(k), from the leading edge back;
      ! each (vector, component) is its own sequence
      !$omp parallel do collapse(2) private(k, run) schedule(static)
      do v = 1, size(r, 2)
        do c = 0, 1
          run = 0
          do k = n, 1, -1
            if (prec%leading(k)) run = 0
            run = run - prec%dx * r(c * n + k, v)
            u(c * n + k, v) = run / prec%weight(k)
          end do
        end do
      end do
      !$omp end parallel do
      call apply_fft_operator(prec%inverse_displacement, u, z)
    end associate
    !$omp parallel do collapse(2) schedule(static)
    do v = 1, size(r, 2)
      do c = 0, 1
        z(c * n + 1:c * n + n, v) = z(c * n + 1:c * n + n, v) * prec%weight
      end do
    end do
    !$omp end parallel do
  end subroutine apply_circulant_preconditioner

  !> weight(k) = sqrt of the distance from cell k's centre to the nearest
  !> cell centre outside the patch (the grid's border counts as outside):
  !> the exact Euclidean distance transform by lower envelopes of parabolas
  !> (Felzenszwalb and Huttenlocher 2012), along x, then along y; O(mx my).
  subroutine edge_weights(patch, weight)
    type(patch_t), intent(in) :: patch
    real(real64), allocatable, intent(out) :: weight(:)
    real(real64), allocatable :: d2(:, :)   ! squared distances on the grid with its outside ring
    integer :: ix, iy, k

    allocate (d2(0:patch%mx + 1, 0:patch%my + 1))
    d2 = 0
    d2(1:patch%mx, 1:patch%my) = merge(huge(1.0_real64), 0.0_real64, patch%inside)
    do iy = 1, patch%my
      call envelope(d2(:, iy), patch%dx)
    end do
    do ix = 1, patch%mx
      call envelope(d2(ix, :), patch%dy)
    end do
    allocate (weight(patch%n))
    do k = 1, patch%n
      weight(k) = sqrt(sqrt(d2(patch%ix(k), patch%iy(k))))
    end do

  contains

    !> f(q) = min over p of f(p) + (h (q - p))^2, in place; f holds some 0 (the outside ring).
    pure subroutine envelope(f, h)
      real(real64), intent(inout) :: f(0:)
      real(real64), intent(in) :: h
      real(real64) :: g(0:size(f) - 1), z(0:size(f)), s
      integer :: v(0:size(f) - 1), j, q, e
      g = f
      j = -1
      do q = 0, size(f) - 1
        if (g(q) >= huge(1.0_real64)) cycle   ! no parabola: an inside cell before the second pass
        do
          if (j < 0) exit
          s = ((g(q) / h**2 + q**2) - (g(v(j)) / h**2 + v(j)**2)) / (2.0_real64 * (q - v(j)))
          if (s > z(j)) exit
          j = j - 1
        end do
        j = j + 1
        v(j) = q
        if (j == 0) then
          z(j) = -huge(1.0_real64)
        else
          z(j) = ((g(q) / h**2 + q**2) - (g(v(j - 1)) / h**2 + v(j - 1)**2)) / (2.0_real64 * (q - v(j - 1)))
        end if
        z(j + 1) = huge(1.0_real64)
      end do
      e = 0
      do q = 0, size(f) - 1
        do while (z(e + 1) < q)
          e = e + 1
        end do
        f(q) = g(v(e)) + (h * (q - v(e)))**2
      end do
    end subroutine envelope

  end subroutine edge_weights

  subroutine destroy_circulant_preconditioner(prec)
    type(circulant_preconditioner_t), intent(inout) :: prec
    call destroy_fft_operator(prec%inverse_displacement)
  end subroutine destroy_circulant_preconditioner

end module kcreep_circulant_preconditioner
