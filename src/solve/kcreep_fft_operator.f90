!> The system operator applied with FFTs.
!>
!> On the bounding grid the coefficient between two cells depends only on
!> their index offset: the operator is block-Toeplitz with Toeplitz blocks,
!> a 2-D convolution with the offset table. Embedded in a periodic grid of
!> at least (2 mx - 1) x (2 my - 1) cells (zero-padded), the circular
!> convolution equals the linear one on the grid, so y = A x costs four real
!> 2-D FFTs (two forward, two back) instead of (2n)^2 multiply-adds. Only the
!> patch cells carry unknowns: x is scattered onto the grid with zeros
!> outside and y is gathered back from the patch cells.
module kcreep_fft_operator
  use, intrinsic :: iso_c_binding
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep_assembly, only: operator_table_t
  use kcreep_influence, only: influence_t, cell_displacement
  !$ use omp_lib, only: omp_get_max_threads
  implicit none
  private
  public :: fft_operator_t, create_fft_operator, create_inverse_displacement, destroy_fft_operator, &
            apply_fft_operator

  include 'fftw3.f03'

  !> A real grid and its half spectrum, FFTW-allocated (so SIMD-aligned alike).
  type :: fft_slot_t
    type(c_ptr) :: p_real = c_null_ptr, p_spec = c_null_ptr
    real(c_double), pointer :: grid(:, :) => null()               !< (nx, ny)
    complex(c_double_complex), pointer :: spec(:, :) => null()    !< (nx/2 + 1, ny)
  end type fft_slot_t

  type :: fft_operator_t
    integer :: n = 0                   !< patch cells
    integer :: nx = 0, ny = 0          !< padded periodic grid
    integer, allocatable :: ix(:), iy(:)
    !> Kernel spectra, scaled by 1/(nx ny) (the unnormalised inverse FFT).
    complex(c_double_complex), allocatable :: kxx(:, :), kxy(:, :), kyy(:, :)
    type(fft_slot_t), allocatable :: slots(:)   !< 2 per vector of a block
    type(c_ptr) :: forward = c_null_ptr, backward = c_null_ptr
  end type fft_operator_t

contains

  !> Smallest n' >= n whose prime factors are 2, 3, 5, 7 (fast FFT sizes).
  pure integer function fast_size(n) result(m)
    integer, intent(in) :: n
    integer :: r, p
    integer, parameter :: primes(4) = [2, 3, 5, 7]
    m = max(n, 1)
    do
      r = m
      do p = 1, 4
        do while (mod(r, primes(p)) == 0)
          r = r / primes(p)
        end do
      end do
      if (r == 1) return
      m = m + 1
    end do
  end function fast_size

  !> Plan the FFTs and transform the kernel. max_vectors: largest block applied at once.
  subroutine create_fft_operator(patch, table, max_vectors, op)
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    integer, intent(in) :: max_vectors
    type(fft_operator_t), intent(out) :: op

    call plan_fft_grid(patch, max_vectors, op)
    call kernel_spectrum(table%xx, op%kxx)
    call kernel_spectrum(table%xy, op%kxy)
    call kernel_spectrum(table%yy, op%kyy)

  contains

    subroutine kernel_spectrum(coefficients, spectrum)
      real(real64), intent(in) :: coefficients(-(table%mx - 1):, -(table%my - 1):)
      complex(c_double_complex), allocatable, intent(out) :: spectrum(:, :)
      integer :: di, dj
      associate (w => op%slots(1))
        w%grid = 0
        do dj = -(table%my - 1), table%my - 1
          do di = -(table%mx - 1), table%mx - 1
            w%grid(modulo(di, op%nx) + 1, modulo(dj, op%ny) + 1) = coefficients(di, dj)
          end do
        end do
        call fftw_execute_dft_r2c(op%forward, w%grid, w%spec)
        spectrum = w%spec / (real(op%nx, real64) * op%ny)
      end associate
    end subroutine kernel_spectrum

  end subroutine create_fft_operator

  !> The padded periodic grid of the patch's bounding grid, its FFT plans and
  !> work slots; the kernel spectra are left to the caller.
  subroutine plan_fft_grid(patch, max_vectors, op)
    type(patch_t), intent(in) :: patch
    integer, intent(in) :: max_vectors
    type(fft_operator_t), intent(out) :: op
    integer :: s, nh, threads

    op%n = patch%n
    op%ix = patch%ix
    op%iy = patch%iy
    op%nx = fast_size(2 * patch%mx - 1)
    if (mod(op%nx, 2) /= 0) op%nx = fast_size(op%nx + 1)   ! even: a simple half spectrum
    op%ny = fast_size(2 * patch%my - 1)
    nh = op%nx / 2 + 1
    ! FFTW's own (pthread) threads on big grids: they sleep when idle, unlike
    ! OpenMP workers, which spin between the many short parallel regions of
    ! a GMRES step and steal the cores from OpenBLAS and the main thread.
    threads = 1
    !$ threads = omp_get_max_threads()
    if (real(op%nx, real64) * op%ny < 6.5e4_real64) threads = 1
    if (threads > 1) then
      if (fftw_init_threads() == 0) threads = 1
    end if
    call fftw_plan_with_nthreads(int(threads, c_int))
    allocate (op%slots(2 * max_vectors))
    do s = 1, size(op%slots)
      op%slots(s)%p_real = fftw_alloc_real(int(op%nx, c_size_t) * op%ny)
      op%slots(s)%p_spec = fftw_alloc_complex(int(nh, c_size_t) * op%ny)
      call c_f_pointer(op%slots(s)%p_real, op%slots(s)%grid, [op%nx, op%ny])
      call c_f_pointer(op%slots(s)%p_spec, op%slots(s)%spec, [nh, op%ny])
    end do
    ! FFTW's dimensions are row-major: (ny, nx) is our (nx, ny) in Fortran order.
    ! FFTW_ESTIMATE: measured planning (seconds at 800 x 800) did not pay back here.
    associate (w => op%slots(1))
      op%forward = fftw_plan_dft_r2c_2d(op%ny, op%nx, w%grid, w%spec, FFTW_ESTIMATE)
      op%backward = fftw_plan_dft_c2r_2d(op%ny, op%nx, w%spec, w%grid, FFTW_ESTIMATE)
    end associate
  end subroutine plan_fft_grid

  !> The circulant approximation of the inverse of the displacement operator
  !> (cell-centre displacement from uniform cell tractions) on the padded
  !> periodic grid: the kernel wrapped to its nearest periodic image, Fourier
  !> transformed (real and even, so a real symmetric 2 x 2 symbol per
  !> frequency) and inverted frequency by frequency. Applied with
  !> apply_fft_operator like the system operator itself.
  subroutine create_inverse_displacement(patch, nu, max_vectors, op)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: nu
    integer, intent(in) :: max_vectors
    type(fft_operator_t), intent(out) :: op
    real(real64), allocatable :: kxx(:, :), kxy(:, :), kyy(:, :)
    real(real64), allocatable :: uxx(:, :), uxy(:, :), uyy(:, :)
    type(influence_t) :: u
    real(real64) :: det, scale
    integer :: i, j, hx, hy

    call plan_fft_grid(patch, max_vectors, op)
    ! the kernel at offsets 0..nx/2, 0..ny/2; the other quadrants by symmetry
    ! (xx, yy even in both offsets, xy odd in each)
    hx = op%nx / 2
    hy = op%ny / 2
    allocate (uxx(0:hx, 0:hy), uxy(0:hx, 0:hy), uyy(0:hx, 0:hy))
    do j = 0, hy
      do i = 0, hx
        u = cell_displacement(i * patch%dx, j * patch%dy, patch%dx / 2, patch%dy / 2, nu, 1.0_real64)
        uxx(i, j) = u%xx
        uxy(i, j) = u%xy
        uyy(i, j) = u%yy
      end do
    end do
    allocate (kxx(hx + 1, op%ny), kxy(hx + 1, op%ny), kyy(hx + 1, op%ny))
    call wrapped_spectrum(uxx, 1.0_real64, kxx)
    call wrapped_spectrum(uxy, -1.0_real64, kxy)
    call wrapped_spectrum(uyy, 1.0_real64, kyy)
    scale = 1 / (real(op%nx, real64) * op%ny)
    allocate (op%kxx, op%kxy, op%kyy, mold=op%slots(1)%spec)
    do j = 1, op%ny
      do i = 1, hx + 1
        det = kxx(i, j) * kyy(i, j) - kxy(i, j)**2
        if (kxx(i, j) > 0 .and. det > 0) then
          op%kxx(i, j) = scale * kyy(i, j) / det
          op%kxy(i, j) = -scale * kxy(i, j) / det
          op%kyy(i, j) = scale * kxx(i, j) / det
        else
          ! not positive definite here (never seen; a guard): leave the frequency out
          op%kxx(i, j) = 0
          op%kxy(i, j) = 0
          op%kyy(i, j) = 0
        end if
      end do
    end do

  contains

    !> Real part of the spectrum of one kernel component wrapped to its
    !> nearest periodic image; mirror_sign: the component's sign under a
    !> reflection of one offset.
    subroutine wrapped_spectrum(values, mirror_sign, symbol)
      real(real64), intent(in) :: values(0:, 0:)
      real(real64), intent(in) :: mirror_sign
      real(real64), intent(out) :: symbol(:, :)
      integer :: di, dj
      real(real64) :: sx, sy
      associate (w => op%slots(1))
        do j = 1, op%ny
          dj = j - 1
          sy = 1
          if (dj > hy) then
            dj = op%ny - dj
            sy = mirror_sign
          end if
          do i = 1, op%nx
            di = i - 1
            sx = 1
            if (di > hx) then
              di = op%nx - di
              sx = mirror_sign
            end if
            w%grid(i, j) = sx * sy * values(di, dj)
          end do
        end do
        call fftw_execute_dft_r2c(op%forward, w%grid, w%spec)
        symbol = real(w%spec, real64)
      end associate
    end subroutine wrapped_spectrum

  end subroutine create_inverse_displacement

  subroutine destroy_fft_operator(op)
    type(fft_operator_t), intent(inout) :: op
    integer :: s
    if (.not. allocated(op%slots)) return
    do s = 1, size(op%slots)
      call fftw_free(op%slots(s)%p_real)
      call fftw_free(op%slots(s)%p_spec)
      nullify (op%slots(s)%grid, op%slots(s)%spec)
    end do
    call fftw_destroy_plan(op%forward)
    call fftw_destroy_plan(op%backward)
    deallocate (op%slots)
  end subroutine destroy_fft_operator

  !> y(:, v) = A x(:, v) for each column: unknowns (px(1:n), py(1:n)) of the patch cells.
  subroutine apply_fft_operator(op, x, y)
    type(fft_operator_t), intent(inout) :: op
    real(real64), intent(in) :: x(:, :)    !< (2n, nv)
    real(real64), intent(out) :: y(:, :)   !< (2n, nv)
    integer :: nv, t, v, c, k, n, i, j
    complex(c_double_complex) :: sx, sy

    n = op%n
    nv = size(x, 2)
    if (2 * nv > size(op%slots)) error stop 'apply_fft_operator: block wider than planned'
    do t = 1, 2 * nv
      v = (t + 1) / 2
      c = t - 2 * (v - 1) - 1       ! 0: px, 1: py
      associate (w => op%slots(t))
        w%grid = 0
        do k = 1, n
          w%grid(op%ix(k), op%iy(k)) = x(c * n + k, v)
        end do
        call fftw_execute_dft_r2c(op%forward, w%grid, w%spec)
      end associate
    end do
    do v = 1, nv
      associate (wx => op%slots(2 * v - 1)%spec, wy => op%slots(2 * v)%spec)
        do j = 1, op%ny
          do i = 1, op%nx / 2 + 1
            sx = wx(i, j)
            sy = wy(i, j)
            wx(i, j) = op%kxx(i, j) * sx + op%kxy(i, j) * sy
            wy(i, j) = op%kxy(i, j) * sx + op%kyy(i, j) * sy
          end do
        end do
      end associate
    end do
    do t = 1, 2 * nv
      v = (t + 1) / 2
      c = t - 2 * (v - 1) - 1
      associate (w => op%slots(t))
        call fftw_execute_dft_c2r(op%backward, w%spec, w%grid)
        do k = 1, n
          y(c * n + k, v) = w%grid(op%ix(k), op%iy(k))
        end do
      end associate
    end do
  end subroutine apply_fft_operator

end module kcreep_fft_operator
