!> The system operator applied with FFTs.
!>
!> On the bounding grid the coefficient between two cells depends only on
!> their index offset: the operator is block-Toeplitz with Toeplitz blocks,
!> a 2-D convolution with the offset table. Embedded in a periodic grid of
!> at least (2 mx - 1) x (2 my - 1) cells (zero-padded), the circular
!> convolution equals the linear one on the grid, so y = A x costs four real
!> 2-D FFTs (two forward, two back) instead of (2n)^2 multiply-adds. Only the
!> patch cells carry unknowns: x is scattered onto the grid with zeros
!> outside and y is gathered back from the patch cells. A blended patch's
!> rows are then blended (kcreep_assembly slip_weight).
module kcreep_fft_operator
  use, intrinsic :: iso_c_binding
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep_assembly, only: operator_table_t, slip_weight, blended_row
  use kcreep_influence, only: influence_t, displacement_offset_table
  !$ use omp_lib, only: omp_get_max_threads
  implicit none
  private
  public :: fft_operator_t, create_fft_operator, create_inverse_displacement, set_fft_cells, destroy_fft_operator, &
            inverse_span, apply_fft_operator

  include 'fftw3.f03'

  !> The circulant preconditioner's periodic grid spans at least 5/4 of the
  !> patch's bounding grid each way (the operator's spans 2, which its exact
  !> convolution needs; an approximate inverse does not): 39 % of the cells
  !> for the same GMRES iterations nearly. Measured on the unit circle,
  !> tolerance 1e-7, span 5/4 (2): 21 (21) iterations at 148 cells across,
  !> 25 (24) at 296, 28 (28) at 600; span 1, no gap between the periodic
  !> images: 22, 26, 39.
  real(real64), parameter :: inverse_span = 1.25_real64

  !> A real grid and its half spectrum, FFTW-allocated (so SIMD-aligned alike).
  !> The spectrum is held twice: row by row as the x transforms leave it
  !> (spec), and column by column (cols) for the y transforms, which FFTW
  !> runs faster on contiguous columns: out of place from the strided rows,
  !> 20 us instead of 29 us for a pruned 80 x 80 forward and backward pass
  !> with FFTW_ESTIMATE (FFTW_MEASURE's in-place plan: 18 us, but its plan
  !> and so the rounding would vary from run to run). cols shares the grid's
  !> memory: the grid is read before cols is written and written after it
  !> is read.
  type :: fft_slot_t
    type(c_ptr) :: p_real = c_null_ptr, p_spec = c_null_ptr
    real(c_double), pointer, contiguous :: grid(:, :) => null()               !< (nx, ny)
    complex(c_double_complex), pointer, contiguous :: cols(:, :) => null()    !< (ny, nx/2 + 1), on p_real
    complex(c_double_complex), pointer, contiguous :: spec(:, :) => null()    !< (nx/2 + 1, ny)
  end type fft_slot_t

  type :: fft_operator_t
    integer :: n = 0                   !< patch cells
    integer :: nx = 0, ny = 0          !< padded periodic grid
    integer :: mx = 0, my = 0          !< the patch's bounding grid, the corner x and y live in
    integer, allocatable :: at(:)      !< each patch cell's place in the grid, in array element order
    !> Kernel spectra by column (ny, nx/2 + 1), scaled by 1/(nx ny) (the unnormalised inverse FFT).
    complex(c_double_complex), allocatable :: kxx(:, :), kxy(:, :), kyy(:, :)
    type(fft_slot_t), allocatable :: slots(:)   !< 2 per vector of a block
    !> Whole-grid 2-D transforms (the kernels; apply when not pruned).
    type(c_ptr) :: forward = c_null_ptr, backward = c_null_ptr
    !> The pruned pair (apply_fft_operator): r2c / c2r of the my grid rows
    !> that hold the patch, and the complex transforms of the nx/2 + 1
    !> spectrum columns between them (spec to cols and back).
    type(c_ptr) :: rows_forward = c_null_ptr, rows_backward = c_null_ptr
    type(c_ptr) :: columns_forward = c_null_ptr, columns_backward = c_null_ptr
    logical :: pruned = .true.
    !> A blended patch: each cell's slip_weight (unallocated otherwise), and
    !> the own-cell coefficients (xx, yy) its rows blend with.
    real(real64), allocatable :: slip_weight(:)
    real(real64) :: own(2) = 0
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

  !> Plan the FFTs and transform the kernel. max_vectors: largest block applied at once;
  !> pruned (default true): apply with the pruned transforms, else the whole-grid ones
  !> (the reference the pruned ones are tested against). Serves any patch on
  !> the same grid and operator table: set_fft_cells moves it to another.
  subroutine create_fft_operator(patch, table, max_vectors, op, pruned)
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    integer, intent(in) :: max_vectors
    type(fft_operator_t), intent(out) :: op
    logical, intent(in), optional :: pruned

    ! (2 mx - 1) x (2 my - 1) at least: the circular convolution is the linear one on the patch
    call plan_fft_grid(patch, max_vectors, 2 * patch%mx - 1, 2 * patch%my - 1, op)
    if (present(pruned)) op%pruned = pruned
    call kernel_spectrum(table%xx, op%kxx)
    call kernel_spectrum(table%xy, op%kxy)
    call kernel_spectrum(table%yy, op%kyy)
    op%own = [table%xx(0, 0), table%yy(0, 0)]
    call set_fft_cells(op, patch)

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
        spectrum = transpose(w%spec) / (real(op%nx, real64) * op%ny)
      end associate
    end subroutine kernel_spectrum

  end subroutine create_fft_operator

  !> The patch's cells: the operator (planned for the patch's bounding grid)
  !> now applies to this patch, which must lie on the same grid.
  subroutine set_fft_cells(op, patch)
    type(fft_operator_t), intent(inout) :: op
    type(patch_t), intent(in) :: patch
    if (patch%mx /= op%mx .or. patch%my /= op%my) error stop 'set_fft_cells: the patch is on another grid'
    op%n = patch%n
    op%at = patch%ix + (patch%iy - 1) * op%nx
    if (allocated(op%slip_weight)) deallocate (op%slip_weight)
    if (allocated(patch%fraction)) op%slip_weight = slip_weight(patch%fraction)
  end subroutine set_fft_cells

  !> The padded periodic grid of the patch's bounding grid, its FFT plans and
  !> work slots; the kernel spectra and the cells are left to the caller.
  !>
  !> Threads: apply_fft_operator runs its slots (independent transforms of
  !> the same size) on OpenMP threads, each with a single-threaded plan
  !> through FFTW's new-array execute, so every slot is transformed the same
  !> way whatever the number of threads and the results do not depend on it.
  !> FFTW's planner is not thread-safe (several handles may plan at once on
  !> their own threads): planning and destroying plans happen in the named
  !> critical section kcreep_fftw_planner, everywhere in kcreep.
  subroutine plan_fft_grid(patch, max_vectors, nx_min, ny_min, op)
    type(patch_t), intent(in) :: patch
    integer, intent(in) :: max_vectors
    integer, intent(in) :: nx_min, ny_min   !< the periodic grid's least size
    type(fft_operator_t), intent(out) :: op
    integer :: s, nh

    op%mx = patch%mx
    op%my = patch%my
    op%nx = fast_size(max(nx_min, patch%mx))
    if (mod(op%nx, 2) /= 0) op%nx = fast_size(op%nx + 1)   ! even: a simple half spectrum
    op%ny = fast_size(max(ny_min, patch%my))
    nh = op%nx / 2 + 1
    allocate (op%slots(2 * max_vectors))
    do s = 1, size(op%slots)
      ! the grid's buffer holds cols too: ny nh complex = (nx + 2) ny reals
      op%slots(s)%p_real = fftw_alloc_real(int(2 * nh, c_size_t) * op%ny)
      op%slots(s)%p_spec = fftw_alloc_complex(int(nh, c_size_t) * op%ny)
      call c_f_pointer(op%slots(s)%p_real, op%slots(s)%grid, [op%nx, op%ny])
      call c_f_pointer(op%slots(s)%p_real, op%slots(s)%cols, [op%ny, nh])
      call c_f_pointer(op%slots(s)%p_spec, op%slots(s)%spec, [nh, op%ny])
    end do
    ! FFTW's dimensions are row-major: (ny, nx) is our (nx, ny) in Fortran order.
    ! FFTW_ESTIMATE: measured planning (seconds at 800 x 800) did not pay back
    ! for one solve, and its plans (so the rounding) are the same in every run.
    associate (w => op%slots(1))
      !$omp critical (kcreep_fftw_planner)
      ! single-threaded plans, even if an earlier caller asked FFTW for threads
      if (fftw_init_threads() /= 0) call fftw_plan_with_nthreads(1_c_int)
      op%forward = fftw_plan_dft_r2c_2d(op%ny, op%nx, w%grid, w%spec, FFTW_ESTIMATE)
      op%backward = fftw_plan_dft_c2r_2d(op%ny, op%nx, w%spec, w%grid, FFTW_ESTIMATE)
      ! grid rows 1..my: one real transform of length nx each (row stride nx, nh in the spectrum)
      op%rows_forward = fftw_plan_many_dft_r2c(1_c_int, [int(op%nx, c_int)], int(op%my, c_int), &
                                               w%grid, [int(op%nx, c_int)], 1_c_int, int(op%nx, c_int), &
                                               w%spec, [int(nh, c_int)], 1_c_int, int(nh, c_int), FFTW_ESTIMATE)
      op%rows_backward = fftw_plan_many_dft_c2r(1_c_int, [int(op%nx, c_int)], int(op%my, c_int), &
                                                w%spec, [int(nh, c_int)], 1_c_int, int(nh, c_int), &
                                                w%grid, [int(op%nx, c_int)], 1_c_int, int(op%nx, c_int), &
                                                FFTW_ESTIMATE)
      ! spectrum columns 1..nh: complex transforms of length ny, from spec
      ! (stride nh, next column 1 along) to cols (contiguous) and back
      op%columns_forward = fftw_plan_many_dft(1_c_int, [int(op%ny, c_int)], int(nh, c_int), &
                                              w%spec, [int(op%ny, c_int)], int(nh, c_int), 1_c_int, &
                                              w%cols, [int(op%ny, c_int)], 1_c_int, int(op%ny, c_int), &
                                              FFTW_FORWARD, FFTW_ESTIMATE)
      op%columns_backward = fftw_plan_many_dft(1_c_int, [int(op%ny, c_int)], int(nh, c_int), &
                                               w%cols, [int(op%ny, c_int)], 1_c_int, int(op%ny, c_int), &
                                               w%spec, [int(op%ny, c_int)], int(nh, c_int), 1_c_int, &
                                               FFTW_BACKWARD, FFTW_ESTIMATE)
      !$omp end critical (kcreep_fftw_planner)
    end associate
  end subroutine plan_fft_grid

  !> The circulant approximation of the inverse of the displacement operator
  !> (cell-centre displacement from uniform cell tractions) on a periodic
  !> grid inverse_span times the patch's bounding grid: the kernel wrapped to its nearest periodic image, Fourier
  !> transformed (real and even, so a real symmetric 2 x 2 symbol per
  !> frequency) and inverted frequency by frequency. Applied with
  !> apply_fft_operator like the system operator itself. Depends on the
  !> grid and nu only: set_fft_cells moves it to another patch on the grid.
  subroutine create_inverse_displacement(patch, nu, max_vectors, op)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: nu
    integer, intent(in) :: max_vectors
    type(fft_operator_t), intent(out) :: op
    real(real64), allocatable :: kxx(:, :), kxy(:, :), kyy(:, :)
    type(influence_t), allocatable :: u(:, :)
    real(real64) :: det, scale
    integer :: i, j, hx, hy

    call plan_fft_grid(patch, max_vectors, ceiling(inverse_span * patch%mx), ceiling(inverse_span * patch%my), op)
    ! the kernel at offsets 0..nx/2, 0..ny/2; the other quadrants by symmetry
    ! (xx, yy even in both offsets, xy odd in each)
    hx = op%nx / 2
    hy = op%ny / 2
    allocate (u(0:hx, 0:hy))
    call displacement_offset_table(hx, hy, patch%dx, patch%dy, nu, 1.0_real64, u)
    allocate (kxx(op%ny, hx + 1), kxy(op%ny, hx + 1), kyy(op%ny, hx + 1))
    call wrapped_spectrum(u%xx, 1.0_real64, kxx)
    call wrapped_spectrum(u%xy, -1.0_real64, kxy)
    call wrapped_spectrum(u%yy, 1.0_real64, kyy)
    scale = 1 / (real(op%nx, real64) * op%ny)
    allocate (op%kxx, op%kxy, op%kyy, mold=op%slots(1)%cols)
    do i = 1, hx + 1
      do j = 1, op%ny
        det = kxx(j, i) * kyy(j, i) - kxy(j, i)**2
        if (kxx(j, i) > 0 .and. det > 0) then
          op%kxx(j, i) = scale * kyy(j, i) / det
          op%kxy(j, i) = -scale * kxy(j, i) / det
          op%kyy(j, i) = scale * kxx(j, i) / det
        else
          ! not positive definite here (never seen; a guard): leave the frequency out
          op%kxx(j, i) = 0
          op%kxy(j, i) = 0
          op%kyy(j, i) = 0
        end if
      end do
    end do
    call set_fft_cells(op, patch)

  contains

    !> Real part of the spectrum of one kernel component wrapped to its
    !> nearest periodic image; mirror_sign: the component's sign under a
    !> reflection of one offset.
    subroutine wrapped_spectrum(values, mirror_sign, symbol)
      real(real64), intent(in) :: values(0:, 0:)
      real(real64), intent(in) :: mirror_sign
      real(real64), intent(out) :: symbol(:, :)   !< (ny, nx/2 + 1), by column like the kernels
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
            ! an odd component at the Nyquist offset of an even grid is its own
            ! mirror image: zero, so that the wrapped kernel is exactly odd and
            ! the preconditioner keeps the parities of a y-symmetric patch
            ! (kcreep_linear_solve pairs load cases on that)
            if (mirror_sign < 0 .and. (2 * (i - 1) == op%nx .or. 2 * (j - 1) == op%ny)) w%grid(i, j) = 0
          end do
        end do
        call fftw_execute_dft_r2c(op%forward, w%grid, w%spec)
        symbol = transpose(real(w%spec, real64))
      end associate
    end subroutine wrapped_spectrum

  end subroutine create_inverse_displacement

  !> Free the slots and plans (an operator never created, or destroyed, is left as it is).
  subroutine destroy_fft_operator(op)
    type(fft_operator_t), intent(inout) :: op
    integer :: s
    if (.not. allocated(op%slots)) return
    do s = 1, size(op%slots)
      call fftw_free(op%slots(s)%p_real)
      call fftw_free(op%slots(s)%p_spec)
    end do
    !$omp critical (kcreep_fftw_planner)
    call fftw_destroy_plan(op%forward)
    call fftw_destroy_plan(op%backward)
    call fftw_destroy_plan(op%rows_forward)
    call fftw_destroy_plan(op%rows_backward)
    call fftw_destroy_plan(op%columns_forward)
    call fftw_destroy_plan(op%columns_backward)
    !$omp end critical (kcreep_fftw_planner)
    deallocate (op%slots)
    op%forward = c_null_ptr
    op%backward = c_null_ptr
    op%rows_forward = c_null_ptr
    op%rows_backward = c_null_ptr
    op%columns_forward = c_null_ptr
    op%columns_backward = c_null_ptr
  end subroutine destroy_fft_operator

  !> y(:, v) = A x(:, v) for each column: unknowns (px(1:n), py(1:n)) of the patch cells.
  !>
  !> Pruned (the default): x lives in the first mx x my corner of the
  !> nx x ny grid and y is read there only, so the forward transform runs
  !> the rows that hold the patch (my of ny) and then all spectrum columns,
  !> and the backward one all columns and then those rows: 3/4 of the work
  !> of the whole-grid transforms, the same result to rounding.
  subroutine apply_fft_operator(op, x, y)
    type(fft_operator_t), intent(inout) :: op
    real(real64), intent(in) :: x(:, :)    !< (2n, nv)
    real(real64), intent(out) :: y(:, :)   !< (2n, nv)
    integer :: nv, n, v, t, j
    logical :: serial

    n = op%n
    nv = size(x, 2)
    if (2 * nv > size(op%slots)) error stop 'apply_fft_operator: block wider than planned'
    serial = .true.
    !$ serial = omp_get_max_threads() == 1
    if (serial) then
      ! one thread: the same loops without a parallel region (setting up a team of one
      ! cost about a tenth of a product on the rolling solver's 20 x 20 patch)
      do t = 1, 2 * nv
        call forward_of(t)
      end do
      do j = 1, size(op%kxx, 2)
        call kernels_of(j)
      end do
      do t = 1, 2 * nv
        call backward_of(t)
      end do
    else
      !$omp parallel default(shared) private(t, j)
      !$omp do schedule(static)
      do t = 1, 2 * nv
        call forward_of(t)
      end do
      !$omp end do
      !$omp do schedule(static)
      do j = 1, size(op%kxx, 2)
        call kernels_of(j)
      end do
      !$omp end do
      !$omp do schedule(static)
      do t = 1, 2 * nv
        call backward_of(t)
      end do
      !$omp end do
      !$omp end parallel
    end if
    if (allocated(op%slip_weight)) then
      do v = 1, nv
        y(1:n, v) = blended_row(y(1:n, v), op%slip_weight, op%own(1), x(1:n, v))
        y(n + 1:2 * n, v) = blended_row(y(n + 1:2 * n, v), op%slip_weight, op%own(2), x(n + 1:2 * n, v))
      end do
    end if

  contains

    !> Slot t: vector (t + 1) / 2, component c = 0 (px) or 1 (py).
    subroutine forward_of(t)
      integer, intent(in) :: t
      integer :: vt, c
      vt = (t + 1) / 2
      c = t - 2 * vt + 1
      call forward_slot(op, op%slots(t), x(c * n + 1:c * n + n, vt))
    end subroutine forward_of

    subroutine kernels_of(j)
      integer, intent(in) :: j
      integer :: vt
      do vt = 1, nv
        call kernel_product(op%kxx(:, j), op%kxy(:, j), op%kyy(:, j), &
                            op%slots(2 * vt - 1)%cols(:, j), op%slots(2 * vt)%cols(:, j))
      end do
    end subroutine kernels_of

    subroutine backward_of(t)
      integer, intent(in) :: t
      integer :: vt, c
      vt = (t + 1) / 2
      c = t - 2 * vt + 1
      call backward_slot(op, op%slots(t), y(c * n + 1:c * n + n, vt))
    end subroutine backward_of

  end subroutine apply_fft_operator

  !> One component scattered onto the grid (zero elsewhere) and transformed into cols.
  subroutine forward_slot(op, w, values)
    type(fft_operator_t), intent(in) :: op
    type(fft_slot_t), intent(inout) :: w
    real(real64), intent(in) :: values(:)   !< (n)
    if (op%pruned) then
      call scatter(values, op%at, op%nx * op%my, w%grid)
      call fftw_execute_dft_r2c(op%rows_forward, w%grid, w%spec)
      call clear(w%spec(:, op%my + 1:))   ! the rows beyond the patch: zero input, zero spectrum
      call fftw_execute_dft(op%columns_forward, w%spec, w%cols)
    else
      call scatter(values, op%at, op%nx * op%ny, w%grid)
      call fftw_execute_dft_r2c(op%forward, w%grid, w%spec)
      w%cols = transpose(w%spec)
    end if
  end subroutine forward_slot

  !> One component transformed back from cols and gathered from the patch cells.
  subroutine backward_slot(op, w, values)
    type(fft_operator_t), intent(in) :: op
    type(fft_slot_t), intent(inout) :: w
    real(real64), intent(out) :: values(:)   !< (n)
    if (op%pruned) then
      call fftw_execute_dft(op%columns_backward, w%cols, w%spec)
      call fftw_execute_dft_c2r(op%rows_backward, w%spec, w%grid)
    else
      w%spec = transpose(w%cols)
      call fftw_execute_dft_c2r(op%backward, w%spec, w%grid)
    end if
    call gather(w%grid, op%at, values)
  end subroutine backward_slot

  !> The grid's first cells (whole rows) = 0, then the values at their
  !> places. scatter and gather are routines of their own so that the
  !> compiler sees plain arrays: through the slot's pointers it reloaded
  !> their descriptors at every element (a third of the operator's own time).
  pure subroutine scatter(values, at, cells, grid)
    real(real64), intent(in) :: values(:)
    integer, intent(in) :: at(:)
    integer, intent(in) :: cells
    real(real64), intent(out) :: grid(cells)
    grid = 0
    grid(at) = values
  end subroutine scatter

  pure subroutine gather(grid, at, values)
    real(real64), intent(in) :: grid(*)
    integer, intent(in) :: at(:)
    real(real64), intent(out) :: values(:)
    values = grid(at)
  end subroutine gather

  pure subroutine clear(spectrum)
    complex(c_double_complex), intent(out), contiguous :: spectrum(:, :)
    spectrum = 0
  end subroutine clear

  !> The 2 x 2 symbol times (sx, sy) along one spectrum column, in place.
  pure subroutine kernel_product(kxx, kxy, kyy, sx, sy)
    complex(c_double_complex), intent(in) :: kxx(:), kxy(:), kyy(:)
    complex(c_double_complex), intent(inout) :: sx(:), sy(:)
    complex(c_double_complex) :: a, b
    integer :: i
    do i = 1, size(sx)
      a = sx(i)
      b = sy(i)
      sx(i) = kxx(i) * a + kxy(i) * b
      sy(i) = kxy(i) * a + kyy(i) * b
    end do
  end subroutine kernel_product

end module kcreep_fft_operator
