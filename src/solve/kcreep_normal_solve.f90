!> The normal contact problem of two elastic half-spaces on a grid.
!>
!> Unknown: the pressure p >= 0 per cell (piecewise constant). With the
!> undeformed distance h, the approach delta and the normal displacement
!> difference u = A p (kcreep_normal_influence), the deformed distance
!>   g = h - delta + u
!> must satisfy g >= 0, p >= 0 and p g = 0 in every cell. Either delta is
!> prescribed, or the total force Fn = dx dy sum(p) (then delta is the
!> Lagrange multiplier of that constraint and comes out of the solve).
!>
!> Method: the constrained conjugate gradient of Polonsky and Keer (Wear 231,
!> 1999, 206-219): CG on the cells carrying pressure, negative pressures cut
!> to zero, cells that interpenetrate without pressure added to the active
!> set (and the conjugation restarted). Preconditioned with the inverse of
!> the influence kernel as a circulant, restricted to the active cells (the
!> FFT-based preconditioner of Vollebregt, J. Comput. Phys. 257, 2014,
!> 333-351) once the active set has settled (a step keeps settled_share of
!> it); before that, from the uniform start of a given force, the plain
!> residual cuts the far cells off faster. 12-23 steps instead of 33-86 on
!> Hertz, CONTACT's samples, rough gaps and the grids of error control (the
!> S1002 +8 mm flange's 200,000 cells: 15 instead of 75), each step with
!> one pass of the preconditioner besides the product (docs/normal.md).
!> A p is a 2-D linear convolution with
!> the offset table, done with zero-padded real FFTs (FFTW), so memory and
!> work per iteration are O(grid) and O(grid log grid). Each step needs
!> r = A t; u = A p is updated along the step (u - tau r) when the active set
!> did not change and recomputed otherwise, every 25 steps, and before
!> convergence is accepted.
!>
!> Start: a given pressure (the solution on a coarser grid of the same
!> area, interpolated: the contact area is then nearly right from the first
!> step), else the uniform pressure (force given) or the best multiple of
!> the interpenetration (approach given).
!>
!> Stopping: the complementarity residual
!>   max( max_{p>0} |g|, max_{p=0} max(-g, 0) ) / max(u)
!> (relative to the elastic displacement, i.e. to the size of the
!> deformation) below the tolerance.
module kcreep_normal_solve
  use, intrinsic :: iso_c_binding
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t, fail, exit_bad_input, exit_numerical
  use kcreep_strings, only: itoa, rtoa
  use kcreep_normal_influence, only: normal_offset_table
  use kcreep_threads, only: team_size, cells_per_thread_normal
  implicit none
  private
  public :: normal_options_t, normal_result_t, solve_normal
  public :: normal_operator_t, create_normal_operator, apply_normal_operator, destroy_normal_operator

  include 'fftw3.f03'

  type :: normal_options_t
    real(real64) :: tolerance = 1e-10_real64   !< on the complementarity residual
    !> tolerance set by the caller (else error control may choose its own)
    logical :: tolerance_given = .false.
    integer :: max_iterations = 5000
    !> FFTW threads: 0 automatic (kcreep_threads), else this many
    integer :: threads = 0
  end type normal_options_t

  type :: normal_result_t
    real(real64), allocatable :: pressure(:, :)   !< (mx, my)
    real(real64) :: approach = 0                  !< delta (prescribed or found)
    real(real64) :: fn = 0                        !< dx dy sum(pressure)
    real(real64) :: pmax = 0
    real(real64) :: residual = huge(1.0_real64)   !< final complementarity residual (relative)
    integer :: iterations = 0
    integer :: products = 0                       !< FFT products A x (about 1 per iteration)
    integer :: n_contact = 0                      !< cells with p > 0
    logical :: converged = .false.
    logical :: touches_edge = .false.             !< pressure on the grid's outer cells
  end type normal_result_t

  !> A periodic real grid, its half spectrum and FFTW's r2c / c2r plans:
  !> the convolutions of the operator and of the preconditioner. With
  !> rows > 0 also the pruned pair of a convolution whose input and output
  !> live in the grid's first `rows` columns (the zero-padded operator's:
  !> x transforms of those columns only, then the y transforms of every
  !> spectrum row; 3/4 of the whole grid's work, the same result
  !> to rounding, as kcreep_fft_operator's; the y transforms out of place
  !> into cols, contiguous, as there).
  type :: periodic_grid_t
    integer :: nx = 0, ny = 0, rows = 0
    type(c_ptr) :: p_real = c_null_ptr, p_spec = c_null_ptr, p_cols = c_null_ptr
    real(c_double), pointer :: grid(:, :) => null()
    complex(c_double_complex), pointer :: spec(:, :) => null()
    complex(c_double_complex), pointer :: cols(:, :) => null()   !< (ny, nx/2 + 1), with rows > 0
    type(c_ptr) :: forward = c_null_ptr, backward = c_null_ptr
    type(c_ptr) :: rows_forward = c_null_ptr, rows_backward = c_null_ptr
    type(c_ptr) :: columns_forward = c_null_ptr, columns_backward = c_null_ptr
  end type periodic_grid_t

  !> A p on an mx x my grid by FFT (the kernel is even: its spectrum is real).
  type :: normal_operator_t
    integer :: applications = 0                 !< products A p done
    integer :: threads = 1                      !< FFTW threads of its plans
    type(periodic_grid_t) :: fft                !< at least 2 mx x 2 my: the linear convolution
    real(real64), allocatable :: kernel(:, :)   !< real spectrum / (nx ny), (ny, nx/2 + 1)
  end type normal_operator_t

  !> The preconditioner z = M^-1 g: the operator's kernel wrapped onto a
  !> periodic grid the size of the contact grid (each offset its nearest
  !> periodic image), inverted frequency by frequency. A periodic grid 1.25,
  !> 1.5 or 2 times the size took as many steps (the Hertzian gap a/b = 2,
  !> 13 on its fine grid each; the S1002 +8 mm flange, 16 and 18), for more work.
  type :: normal_preconditioner_t
    type(periodic_grid_t) :: fft
    real(real64), allocatable :: inverse(:, :)   !< 1 / (spectrum nx ny)
  end type normal_preconditioner_t

contains

  !> Smallest n' >= n, even, whose prime factors are 2, 3, 5, 7.
  pure integer function fast_even_size(n) result(m)
    integer, intent(in) :: n
    integer :: r, k
    integer, parameter :: primes(4) = [2, 3, 5, 7]
    m = max(n, 2)
    if (mod(m, 2) /= 0) m = m + 1
    do
      r = m
      do k = 1, 4
        do while (mod(r, primes(k)) == 0)
          r = r / primes(k)
        end do
      end do
      if (r == 1) return
      m = m + 2
    end do
  end function fast_even_size

  !> An nx x ny periodic grid with its plans; threads: FFTW threads (1 if
  !> FFTW has no thread support); rows: the pruned pair's columns (0: none).
  subroutine create_periodic_grid(nx, ny, threads, pg, rows)
    integer, intent(in) :: nx, ny
    integer, intent(inout) :: threads
    type(periodic_grid_t), intent(out) :: pg
    integer, intent(in), optional :: rows
    integer :: nh
    pg%nx = nx
    pg%ny = ny
    if (present(rows)) pg%rows = rows
    nh = nx / 2 + 1
    pg%p_real = fftw_alloc_real(int(nx, c_size_t) * ny)
    pg%p_spec = fftw_alloc_complex(int(nh, c_size_t) * ny)
    call c_f_pointer(pg%p_real, pg%grid, [nx, ny])
    call c_f_pointer(pg%p_spec, pg%spec, [nh, ny])
    ! FFTW's dimensions are row-major: (ny, nx) is our (nx, ny). Its planner
    ! is not thread-safe: one planner at a time in the process.
    !$omp critical (kcreep_fftw_planner)
    if (fftw_init_threads() /= 0) then
      call fftw_plan_with_nthreads(int(threads, c_int))
    else
      threads = 1   ! FFTW without thread support
    end if
    pg%forward = fftw_plan_dft_r2c_2d(ny, nx, pg%grid, pg%spec, FFTW_ESTIMATE)
    pg%backward = fftw_plan_dft_c2r_2d(ny, nx, pg%spec, pg%grid, FFTW_ESTIMATE)
    if (pg%rows > 0) then
      pg%p_cols = fftw_alloc_complex(int(nh, c_size_t) * ny)
      call c_f_pointer(pg%p_cols, pg%cols, [ny, nh])
      ! grid columns 1..rows: real transforms of length nx (FFTW's rows)
      pg%rows_forward = fftw_plan_many_dft_r2c(1_c_int, [int(nx, c_int)], int(pg%rows, c_int), &
                                               pg%grid, [int(nx, c_int)], 1_c_int, int(nx, c_int), &
                                               pg%spec, [int(nh, c_int)], 1_c_int, int(nh, c_int), FFTW_ESTIMATE)
      pg%rows_backward = fftw_plan_many_dft_c2r(1_c_int, [int(nx, c_int)], int(pg%rows, c_int), &
                                                pg%spec, [int(nh, c_int)], 1_c_int, int(nh, c_int), &
                                                pg%grid, [int(nx, c_int)], 1_c_int, int(nx, c_int), FFTW_ESTIMATE)
      ! spectrum rows 1..nh: complex transforms of length ny, from spec
      ! (stride nh) to cols (contiguous) and back
      pg%columns_forward = fftw_plan_many_dft(1_c_int, [int(ny, c_int)], int(nh, c_int), &
                                              pg%spec, [int(ny, c_int)], int(nh, c_int), 1_c_int, &
                                              pg%cols, [int(ny, c_int)], 1_c_int, int(ny, c_int), &
                                              FFTW_FORWARD, FFTW_ESTIMATE)
      pg%columns_backward = fftw_plan_many_dft(1_c_int, [int(ny, c_int)], int(nh, c_int), &
                                               pg%cols, [int(ny, c_int)], 1_c_int, int(ny, c_int), &
                                               pg%spec, [int(ny, c_int)], int(nh, c_int), 1_c_int, &
                                               FFTW_BACKWARD, FFTW_ESTIMATE)
    end if
    !$omp end critical (kcreep_fftw_planner)
  end subroutine create_periodic_grid

  subroutine destroy_periodic_grid(pg)
    type(periodic_grid_t), intent(inout) :: pg
    if (.not. c_associated(pg%p_real)) return
    call fftw_free(pg%p_real)
    call fftw_free(pg%p_spec)
    !$omp critical (kcreep_fftw_planner)
    call fftw_destroy_plan(pg%forward)
    call fftw_destroy_plan(pg%backward)
    if (pg%rows > 0) then
      call fftw_free(pg%p_cols)
      pg%p_cols = c_null_ptr
      nullify (pg%cols)
      call fftw_destroy_plan(pg%rows_forward)
      call fftw_destroy_plan(pg%rows_backward)
      call fftw_destroy_plan(pg%columns_forward)
      call fftw_destroy_plan(pg%columns_backward)
    end if
    !$omp end critical (kcreep_fftw_planner)
    pg%p_real = c_null_ptr
    pg%p_spec = c_null_ptr
    nullify (pg%grid, pg%spec)
  end subroutine destroy_periodic_grid

  !> y = the periodic convolution of x (zero beyond its mx x my cells) with
  !> the kernel of (unnormalised) real spectrum `spectrum`, on those cells;
  !> the spectrum (nx/2 + 1, ny), or (ny, nx/2 + 1) on a pruned grid.
  subroutine convolve(pg, spectrum, x, y)
    type(periodic_grid_t), intent(inout) :: pg
    real(real64), intent(in) :: spectrum(:, :), x(:, :)
    real(real64), intent(out) :: y(:, :)
    integer :: j
    if (pg%rows > 0) then
      if (size(x, 2) > pg%rows .or. size(y, 2) > pg%rows) error stop 'convolve: beyond the pruned columns'
      pg%grid(:, 1:pg%rows) = 0
      do j = 1, size(x, 2)
        pg%grid(1:size(x, 1), j) = x(:, j)
      end do
      call fftw_execute_dft_r2c(pg%rows_forward, pg%grid, pg%spec)
      pg%spec(:, pg%rows + 1:) = 0   ! zero columns: zero spectrum
      call fftw_execute_dft(pg%columns_forward, pg%spec, pg%cols)
      pg%cols = pg%cols * spectrum
      call fftw_execute_dft(pg%columns_backward, pg%cols, pg%spec)
      call fftw_execute_dft_c2r(pg%rows_backward, pg%spec, pg%grid)
      do j = 1, size(y, 2)
        y(:, j) = pg%grid(1:size(y, 1), j)
      end do
      return
    end if
    pg%grid = 0
    do j = 1, size(x, 2)
      pg%grid(1:size(x, 1), j) = x(:, j)
    end do
    call fftw_execute_dft_r2c(pg%forward, pg%grid, pg%spec)
    pg%spec = pg%spec * spectrum
    call fftw_execute_dft_c2r(pg%backward, pg%spec, pg%grid)
    do j = 1, size(y, 2)
      y(:, j) = pg%grid(1:size(y, 1), j)
    end do
  end subroutine convolve

  !> threads: FFTW threads for the transforms, 0 automatic (kcreep_threads);
  !> offsets: normal_offset_table of at least mx x my (else made here).
  subroutine create_normal_operator(mx, my, dx, dy, compliance, threads, op, offsets)
    integer, intent(in) :: mx, my, threads
    real(real64), intent(in) :: dx, dy, compliance
    type(normal_operator_t), intent(out) :: op
    real(real64), intent(in), optional :: offsets(0:, 0:)
    real(real64), allocatable :: table(:, :)
    integer :: i, j, nx, ny

    nx = fast_even_size(2 * mx)
    ny = fast_even_size(2 * my)
    op%threads = team_size(threads, int(nx, int64) * ny, cells_per_thread_normal)
    call create_periodic_grid(nx, ny, op%threads, op%fft, rows=my)
    if (present(offsets)) then
      allocate (table(0:mx - 1, 0:my - 1))
      table(:, :) = offsets(0:mx - 1, 0:my - 1)
    else
      call normal_offset_table(mx, my, dx, dy, compliance, table)
    end if
    op%fft%grid = 0
    do j = -(my - 1), my - 1
      do i = -(mx - 1), mx - 1
        op%fft%grid(modulo(i, nx) + 1, modulo(j, ny) + 1) = table(abs(i), abs(j))
      end do
    end do
    call fftw_execute_dft_r2c(op%fft%forward, op%fft%grid, op%fft%spec)
    op%kernel = transpose(real(op%fft%spec, real64)) / (real(nx, real64) * ny)   ! by column: pruned
  end subroutine create_normal_operator

  subroutine destroy_normal_operator(op)
    type(normal_operator_t), intent(inout) :: op
    call destroy_periodic_grid(op%fft)
  end subroutine destroy_normal_operator

  !> u = A p on the grid.
  subroutine apply_normal_operator(op, p, u)
    type(normal_operator_t), intent(inout) :: op
    real(real64), intent(in) :: p(:, :)
    real(real64), intent(out) :: u(:, :)
    op%applications = op%applications + 1
    call convolve(op%fft, op%kernel, p, u)
  end subroutine apply_normal_operator

  !> The preconditioner of an mx x my grid (normal_preconditioner_t); table:
  !> normal_offset_table of preconditioner_offsets(mx, my) cells.
  subroutine create_normal_preconditioner(mx, my, threads, table, pre)
    integer, intent(in) :: mx, my, threads
    real(real64), intent(in) :: table(0:, 0:)
    type(normal_preconditioner_t), intent(out) :: pre
    real(real64) :: smallest
    integer :: i, j, nx, ny, fft_threads

    nx = fast_even_size(mx)
    ny = fast_even_size(my)
    fft_threads = threads
    call create_periodic_grid(nx, ny, fft_threads, pre%fft)
    ! the kernel at the offset of each periodic cell's nearest image
    do j = 0, ny - 1
      do i = 0, nx - 1
        pre%fft%grid(i + 1, j + 1) = table(min(i, nx - i), min(j, ny - j))
      end do
    end do
    call fftw_execute_dft_r2c(pre%fft%forward, pre%fft%grid, pre%fft%spec)
    ! the wrapped kernel's spectrum was positive on every grid tried (its
    ! smallest value 2e-3 to 1.4e-2 of the largest); the floor only guards
    pre%inverse = real(pre%fft%spec, real64)
    smallest = 1e-6_real64 * maxval(pre%inverse)
    pre%inverse = 1 / (max(pre%inverse, smallest) * (real(nx, real64) * ny))
  end subroutine create_normal_preconditioner

  !> The offsets the preconditioner of an mx x my grid needs, each way: the
  !> grid's own and its periodic grid's half (the operator's are a corner).
  pure function preconditioner_offsets(mx, my) result(n)
    integer, intent(in) :: mx, my
    integer :: n(2)
    n = [max(mx, fast_even_size(mx) / 2 + 1), max(my, fast_even_size(my) / 2 + 1)]
  end function preconditioner_offsets

  subroutine destroy_normal_preconditioner(pre)
    type(normal_preconditioner_t), intent(inout) :: pre
    call destroy_periodic_grid(pre%fft)
  end subroutine destroy_normal_preconditioner

  !> z = M^-1 g on the active cells, zero elsewhere (g taken on them only).
  subroutine apply_normal_preconditioner(pre, g, active, z)
    type(normal_preconditioner_t), intent(inout) :: pre
    real(real64), intent(in) :: g(:, :)
    logical, intent(in) :: active(:, :)
    real(real64), intent(out) :: z(:, :)
    call convolve(pre%fft, pre%inverse, merge(g, 0.0_real64, active), z)
    where (.not. active) z = 0
  end subroutine apply_normal_preconditioner

  !> Solve the normal problem on the grid of h (cell sizes dx, dy; compliance
  !> 1/E*). Exactly one of approach and normal_force must be present.
  !> Cells with h >= 1e29 are outside the potential contact (never loaded).
  !> start: a pressure (mx, my) to start from (scaled to normal_force).
  subroutine solve_normal(h, dx, dy, compliance, options, res, status, approach, normal_force, start)
    real(real64), intent(in) :: h(:, :)
    real(real64), intent(in) :: dx, dy, compliance
    type(normal_options_t), intent(in) :: options
    type(normal_result_t), intent(out) :: res
    type(status_t), intent(inout) :: status
    real(real64), intent(in), optional :: approach, normal_force
    real(real64), intent(in), optional :: start(:, :)

    type(normal_operator_t) :: op
    type(normal_preconditioner_t) :: pre
    real(real64), allocatable :: p(:, :), g(:, :), t(:, :), u(:, :), r(:, :), z(:, :), offsets(:, :)
    integer :: n_offsets(2)
    logical, allocatable :: active(:, :)
    logical :: force_given, restart, fresh, changed, started
    integer :: since_fresh
    real(real64) :: factor
    !> steps between recomputations of u = A p (round-off drift of the update)
    integer, parameter :: refresh_every = 25
    real(real64) :: delta, fn, gg, gg_old, tau, mean, scale, cell_area
    integer :: mx, my, it, nc, nc_before
    logical :: settled, preconditioned
    !> the preconditioner is used once a step keeps more than this share of
    !> the active cells: 0.8 to 0.95 took the same steps within 2 on eleven
    !> solves (Hertz, CONTACT's samples, rough gaps; 201-204 in all); at 0.5
    !> the rough gaps' force-given solves took 45-51 (plain CG: 33-40)
    real(real64), parameter :: settled_share = 0.9_real64

    mx = size(h, 1)
    my = size(h, 2)
    force_given = present(normal_force)
    if (force_given .eqv. present(approach)) then
      call fail(status, exit_bad_input, 'normal problem: give exactly one of approach and normal_force')
      return
    end if
    if (mx < 1 .or. my < 1) then
      call fail(status, exit_bad_input, 'normal problem: empty grid')
      return
    end if
    if (any(h /= h)) then
      call fail(status, exit_bad_input, 'normal problem: the undeformed distance contains NaN')
      return
    end if
    cell_area = dx * dy
    started = .false.
    if (present(start)) started = all(shape(start) == shape(h))   ! else the usual start
    allocate (p(mx, my), g(mx, my), t(mx, my), u(mx, my), r(mx, my), z(mx, my), active(mx, my))
    delta = 0
    fn = 0
    if (force_given) then
      fn = normal_force
      if (.not. (fn > 0)) then
        call fail(status, exit_bad_input, 'normal problem: normal_force = '//rtoa(fn)//' (must be > 0)')
        return
      end if
      where (h < 1e29_real64)
        p = fn / (cell_area * count(h < 1e29_real64))
      elsewhere
        p = 0
      end where
      if (count(h < 1e29_real64) == 0) then
        call fail(status, exit_bad_input, 'normal problem: no cell of the grid can come into contact')
        return
      end if
    else
      delta = approach
      g = max(delta - h, 0.0_real64)
      if (.not. any(g > 0)) then
        call fail(status, exit_bad_input, 'normal problem: approach = '//rtoa(delta)// &
                  ' gives no interpenetration (the smallest undeformed distance is '//rtoa(minval(h))// &
                  '; the approach must exceed it)')
        return
      end if
    end if

    if (started) started = any(start > 0 .and. h < 1e29_real64)
    if (started) then
      where (h < 1e29_real64)
        p = max(start, 0.0_real64)
      elsewhere
        p = 0
      end where
      if (force_given) p = p * (fn / (cell_area * sum(p)))
    end if

    ! one offset table for the operator and the preconditioner
    n_offsets = preconditioner_offsets(mx, my)
    call normal_offset_table(n_offsets(1), n_offsets(2), dx, dy, compliance, offsets)
    call create_normal_operator(mx, my, dx, dy, compliance, options%threads, op, offsets)
    call create_normal_preconditioner(mx, my, op%threads, offsets, pre)
    deallocate (offsets)
    if (.not. force_given .and. .not. started) then
      ! first estimate: the best multiple of the interpenetration
      call apply_normal_operator(op, g, u)
      p = g * (sum(g * g) / sum(g * u))
    end if

    gg_old = 1
    restart = .true.
    preconditioned = .false.
    nc_before = huge(nc_before)
    t = 0
    fresh = .false.
    since_fresh = 0
    do it = 0, options%max_iterations
      ! u = A p: updated along the CG step when the active set did not change,
      ! recomputed otherwise, every refresh_every steps, and before accepting convergence
      if (.not. fresh .or. since_fresh >= refresh_every) then
        call apply_normal_operator(op, p, u)
        since_fresh = 0
      end if
      do
        call gap_and_active(h, u, p, force_given, delta, g, active, nc)
        scale = max(maxval(u), tiny(1.0_real64))
        res%residual = complementarity(g, active) / scale
        if (res%residual > options%tolerance .or. since_fresh == 0) exit
        call apply_normal_operator(op, p, u)
        since_fresh = 0
      end do
      res%iterations = it
      if (res%residual <= options%tolerance) then
        res%converged = .true.
        exit
      end if
      if (it == options%max_iterations) exit
      if (nc == 0) then
        ! everything was cut off: restart from the interpenetration
        t = max(-g, 0.0_real64)
        call apply_normal_operator(op, t, u)
        p = t * (sum(t * t) / sum(t * u))
        restart = .true.
        fresh = .false.
        cycle
      end if
      ! while the active set still shrinks fast (from the uniform start of a
      ! given force), the plain residual: it cuts the far cells off sooner
      settled = nc > settled_share * nc_before
      nc_before = nc
      if (settled .neqv. preconditioned) restart = .true.   ! the directions are conjugate in one metric
      preconditioned = settled
      if (preconditioned) then
        ! the preconditioned residual, in the force constraint's subspace (zero sum)
        call apply_normal_preconditioner(pre, g, active, z)
        if (force_given) then
          mean = sum(z, mask=active) / nc
          where (active) z = z - mean
        end if
      else
        z = merge(g, 0.0_real64, active)
      end if
      gg = sum(g * z, mask=active)
      if (restart) then
        t = z   ! zero off the active cells, as z is
      else
        where (active)
          t = z + (gg / gg_old) * t
        elsewhere
          t = 0
        end where
      end if
      gg_old = gg
      call apply_normal_operator(op, t, r)
      call step_length(g, t, r, active, force_given, nc, tau)
      call take_step(tau, t, g, p, active, changed, restart)
      factor = 1
      if (force_given) factor = fn / (cell_area * sum(p))
      if (force_given) p = p * factor
      fresh = .not. changed
      if (fresh) then
        u = factor * (u - tau * r)
        since_fresh = since_fresh + 1
      end if
    end do
    res%products = op%applications
    call destroy_normal_operator(op)
    call destroy_normal_preconditioner(pre)

    if (.not. res%converged) then
      call fail(status, exit_numerical, 'normal problem: no convergence in '//itoa(options%max_iterations)// &
                ' iterations (complementarity residual '//rtoa(res%residual)//', tolerance '// &
                rtoa(options%tolerance)//')')
    end if
    res%approach = delta
    res%fn = cell_area * sum(p)
    res%pmax = maxval(p)
    res%n_contact = count(p > 0)
    res%touches_edge = any(p(1, :) > 0) .or. any(p(mx, :) > 0) .or. any(p(:, 1) > 0) .or. any(p(:, my) > 0)
    call move_alloc(p, res%pressure)

  contains

    ! The steps' cell loops, each in one pass over the grid (the solve's own
    ! time is memory traffic): the same operations in the same order as the
    ! whole-array statements they stand for, so the same rounding.

    !> g = h + u - approach; active: the cells with pressure (nc of them);
    !> with the force given, g less its mean over them, which is the approach.
    pure subroutine gap_and_active(h, u, p, force_given, delta, g, active, nc)
      real(real64), intent(in) :: h(:, :), u(:, :), p(:, :)
      logical, intent(in) :: force_given
      real(real64), intent(inout) :: delta
      real(real64), intent(out) :: g(:, :)
      logical, intent(out) :: active(:, :)
      integer, intent(out) :: nc
      real(real64) :: total
      integer :: i, j
      nc = 0
      total = 0
      do j = 1, size(h, 2)
        do i = 1, size(h, 1)
          g(i, j) = h(i, j) + u(i, j)
          if (.not. force_given) g(i, j) = g(i, j) - delta
          active(i, j) = p(i, j) > 0
          if (active(i, j)) then
            nc = nc + 1
            total = total + g(i, j)
          end if
        end do
      end do
      if (force_given .and. nc > 0) then
        delta = total / nc
        g = g - delta
      end if
    end subroutine gap_and_active

    !> The complementarity residual: the largest |g| on the active cells and
    !> -g (interpenetration) on the others.
    pure real(real64) function complementarity(g, active) result(worst)
      real(real64), intent(in) :: g(:, :)
      logical, intent(in) :: active(:, :)
      integer :: i, j
      worst = 0
      do j = 1, size(g, 2)
        do i = 1, size(g, 1)
          if (active(i, j)) then
            worst = max(worst, abs(g(i, j)))
          else
            worst = max(worst, -g(i, j))
          end if
        end do
      end do
    end function complementarity

    !> The CG step length along t (r = A t) over the active cells; with the
    !> force given, in the subspace of zero total pressure change.
    pure subroutine step_length(g, t, r, active, force_given, nc, tau)
      real(real64), intent(in) :: g(:, :), t(:, :), r(:, :)
      logical, intent(in) :: active(:, :), force_given
      integer, intent(in) :: nc
      real(real64), intent(out) :: tau
      real(real64) :: num, den, sum_r, sum_t
      integer :: i, j
      num = 0
      den = 0
      sum_r = 0
      sum_t = 0
      do j = 1, size(g, 2)
        do i = 1, size(g, 1)
          if (active(i, j)) then
            num = num + g(i, j) * t(i, j)
            den = den + r(i, j) * t(i, j)
            sum_r = sum_r + r(i, j)
            sum_t = sum_t + t(i, j)
          end if
        end do
      end do
      if (force_given) den = den - sum_r / nc * sum_t
      tau = 0
      if (den > 0) tau = num / den
    end subroutine step_length

    !> p less tau t on the active cells, cut at zero (changed: a cell was
    !> cut); cells without pressure that interpenetrate join the active set
    !> with p = -tau g (restart: one did; active is left marking them).
    pure subroutine take_step(tau, t, g, p, active, changed, restart)
      real(real64), intent(in) :: tau, t(:, :), g(:, :)
      real(real64), intent(inout) :: p(:, :)
      logical, intent(inout) :: active(:, :)
      logical, intent(out) :: changed, restart
      integer :: i, j
      changed = .false.
      restart = .false.
      do j = 1, size(p, 2)
        do i = 1, size(p, 1)
          if (active(i, j)) p(i, j) = p(i, j) - tau * t(i, j)
          if (p(i, j) < 0) changed = .true.
          p(i, j) = max(p(i, j), 0.0_real64)
          active(i, j) = p(i, j) <= 0 .and. g(i, j) < 0
          if (active(i, j)) then
            restart = .true.
            p(i, j) = p(i, j) - tau * g(i, j)
          end if
        end do
      end do
      changed = changed .or. restart
    end subroutine take_step

  end subroutine solve_normal

end module kcreep_normal_solve
