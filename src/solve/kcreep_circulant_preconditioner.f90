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
!> one-sided; the circulant carries the smooth far coupling of 1/r. Neither
!> depends on the length of the rows, so the work per step is two FFT
!> passes whatever the patch's shape, and the iteration count stays nearly
!> the same as the grid is refined (measured in docs/performance.md).
module kcreep_circulant_preconditioner
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep_fft_operator, only: fft_operator_t, create_inverse_displacement, destroy_fft_operator, &
                                 apply_fft_operator
  implicit none
  private
  public :: circulant_preconditioner_t, build_circulant_preconditioner, apply_circulant_preconditioner, &
            destroy_circulant_preconditioner

  type :: circulant_preconditioner_t
    integer :: n = 0
    real(real64) :: dx = 0
    !> For each patch cell, the next cell ahead of it (x + dx) in its run, 0 at the leading edge.
    integer, allocatable :: ahead(:)
    type(fft_operator_t) :: inverse_displacement
    real(real64), allocatable :: u(:, :)   !< work: displacements, kept between steps
  end type circulant_preconditioner_t

contains

  subroutine build_circulant_preconditioner(patch, nu, max_vectors, prec)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: nu
    integer, intent(in) :: max_vectors
    type(circulant_preconditioner_t), intent(out) :: prec
    integer :: k

    prec%n = patch%n
    prec%dx = patch%dx
    ! cells are numbered row by row, x increasing within a row
    allocate (prec%ahead(patch%n))
    prec%ahead = 0
    do k = 1, patch%n - 1
      if (patch%iy(k + 1) == patch%iy(k) .and. patch%ix(k + 1) == patch%ix(k) + 1) prec%ahead(k) = k + 1
    end do
    call create_inverse_displacement(patch, nu, max_vectors, prec%inverse_displacement)
  end subroutine build_circulant_preconditioner

  !> z = A_circ^-1 D^-1 r for each column (px(1:n), py(1:n)).
  subroutine apply_circulant_preconditioner(prec, r, z)
    type(circulant_preconditioner_t), intent(inout) :: prec
    real(real64), intent(in) :: r(:, :)    !< (2n, nv)
    real(real64), intent(out) :: z(:, :)   !< (2n, nv)
    integer :: v, c, k, n

    n = prec%n
    if (allocated(prec%u)) then
      if (size(prec%u, 2) < size(r, 2)) deallocate (prec%u)
    end if
    if (.not. allocated(prec%u)) allocate (prec%u(2 * n, size(r, 2)))
    associate (u => prec%u(:, 1:size(r, 2)))
      ! (u(k+1) - u(k)) / dx = r(k)  =>  u(k) = u(k+1) - dx r(k), from the leading edge back;
      ! each (vector, component) is its own sequence
      !$omp parallel do collapse(2) private(k) schedule(static)
      do v = 1, size(r, 2)
        do c = 0, 1
          do k = n, 1, -1
            if (prec%ahead(k) > 0) then
              u(c * n + k, v) = u(c * n + prec%ahead(k), v) - prec%dx * r(c * n + k, v)
            else
              u(c * n + k, v) = -prec%dx * r(c * n + k, v)
            end if
          end do
        end do
      end do
      !$omp end parallel do
      call apply_fft_operator(prec%inverse_displacement, u, z)
    end associate
  end subroutine apply_circulant_preconditioner

  subroutine destroy_circulant_preconditioner(prec)
    type(circulant_preconditioner_t), intent(inout) :: prec
    call destroy_fft_operator(prec%inverse_displacement)
  end subroutine destroy_circulant_preconditioner

end module kcreep_circulant_preconditioner
