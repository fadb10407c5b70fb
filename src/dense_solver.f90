!> Dense LU solution of the full-adhesion system with LAPACK, with the
!> checks that say whether the answer can be trusted: LAPACK's reciprocal
!> condition estimate, the normwise backward error of each solution
!> (residual computed without the matrix, from the offset table), and one
!> step of iterative refinement when that backward error is not at round-off.
module dense_solver
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t, fail, exit_numerical, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use lapack_interfaces, only: dgetrf, dgetrs, dgecon, dlange
  use patch_grid, only: patch_t
  use tang_assembly, only: operator_table_t, assemble_dense, apply_operator
  implicit none
  private
  public :: dense_diagnostics_t, solve_dense, check_dense_memory
  public :: available_memory_bytes, backward_error, refine_threshold

  !> Backward errors above this are refined once (about 100 unit round-offs).
  real(real64), parameter :: refine_threshold = 100 * epsilon(1.0_real64)

  type :: dense_diagnostics_t
    real(real64) :: rcond = 0                !< LAPACK dgecon, 1-norm
    real(real64) :: backward_error = 0       !< max over load cases, after refinement
    real(real64) :: backward_error_initial = 0
    logical :: refined = .false.
    real(real64) :: t_assemble = 0, t_factor = 0, t_solve = 0
    character(len=:), allocatable :: method   !< 'dense' or 'iterative' (set by linear_solve)
    integer :: iterations = 0                 !< GMRES iterations (largest over load cases), 0 for dense
  end type dense_diagnostics_t

contains

  pure integer(int64) function dense_matrix_bytes(n_unknowns)
    integer, intent(in) :: n_unknowns
    dense_matrix_bytes = 8_int64 * n_unknowns * n_unknowns
  end function dense_matrix_bytes

  !> MemAvailable from /proc/meminfo in bytes, or -1 when it cannot be read.
  function available_memory_bytes() result(bytes)
    integer(int64) :: bytes
    integer :: unit, ios
    character(len=256) :: line
    integer(int64) :: kib
    bytes = -1
    open (newunit=unit, file='/proc/meminfo', status='old', action='read', iostat=ios)
    if (ios /= 0) return
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (line(1:13) == 'MemAvailable:') then
        read (line(14:), *, iostat=ios) kib
        if (ios == 0) bytes = 1024 * kib
        exit
      end if
    end do
    close (unit)
  end function available_memory_bytes

  !> Fail before allocating when the dense matrix cannot fit in the memory available.
  subroutine check_dense_memory(n_cells, status)
    integer, intent(in) :: n_cells
    type(status_t), intent(inout) :: status
    integer(int64) :: need, have
    need = dense_matrix_bytes(2 * n_cells)
    have = available_memory_bytes()
    if (have > 0 .and. need > have) then
      call fail(status, exit_bad_input, 'the dense matrix of '//itoa(2 * n_cells)//' unknowns needs '// &
                rtoa(real(need, real64) / 2.0_real64**30)//' GiB, only '// &
                rtoa(real(have, real64) / 2.0_real64**30)//' GiB are available (use a coarser grid)')
    end if
  end subroutine check_dense_memory

  !> Solve A x = b for the columns of rhs (x overwrites rhs).
  subroutine solve_dense(patch, table, rhs, diag, status)
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    real(real64), intent(inout) :: rhs(:, :)      !< (2n, ncases): in b, out x
    type(dense_diagnostics_t), intent(out) :: diag
    type(status_t), intent(inout) :: status
    real(real64), allocatable :: a(:, :), b(:, :), r(:, :), work(:)
    integer, allocatable :: ipiv(:), iwork(:)
    integer :: m, info, nrhs
    integer(int64) :: t0, t1, rate
    real(real64) :: anorm_1, anorm_inf

    m = 2 * patch%n
    nrhs = size(rhs, 2)
    call check_dense_memory(patch%n, status)
    if (status%failed()) return

    call system_clock(t0, rate)
    allocate (a(m, m), ipiv(m), work(4 * m), iwork(m))
    call assemble_dense(patch, table, a)
    call system_clock(t1)
    diag%t_assemble = real(t1 - t0, real64) / rate

    t0 = t1
    anorm_1 = dlange('1', m, m, a, m, work)
    anorm_inf = dlange('I', m, m, a, m, work)
    call dgetrf(m, m, a, m, ipiv, info)
    if (info > 0) then
      call fail(status, exit_numerical, 'the influence matrix is exactly singular (LU pivot '// &
                itoa(info)//' is zero); the collocation point or the patch is degenerate')
      return
    end if
    call dgecon('1', m, a, m, anorm_1, diag%rcond, work, iwork, info)
    call system_clock(t1)
    diag%t_factor = real(t1 - t0, real64) / rate

    t0 = t1
    b = rhs
    call dgetrs('N', m, nrhs, a, m, ipiv, rhs, m, info)
    allocate (r(m, nrhs))
    call residual(patch, table, b, rhs, r)
    diag%backward_error_initial = backward_error(r, b, rhs, anorm_inf)
    diag%backward_error = diag%backward_error_initial
    if (diag%backward_error > refine_threshold) then
      call dgetrs('N', m, nrhs, a, m, ipiv, r, m, info)
      rhs = rhs + r
      call residual(patch, table, b, rhs, r)
      diag%backward_error = backward_error(r, b, rhs, anorm_inf)
      diag%refined = .true.
    end if
    call system_clock(t1)
    diag%t_solve = real(t1 - t0, real64) / rate
  end subroutine solve_dense

  !> r = b - A x, column by column, with A applied from the offset table.
  subroutine residual(patch, table, b, x, r)
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    real(real64), intent(in) :: b(:, :), x(:, :)
    real(real64), intent(out) :: r(:, :)
    integer :: j
    do j = 1, size(b, 2)
      call apply_operator(patch, table, x(:, j), r(:, j))
      r(:, j) = b(:, j) - r(:, j)
    end do
  end subroutine residual

  !> Normwise backward error max_j |r_j| / (|A| |x_j| + |b_j|), infinity norms.
  pure real(real64) function backward_error(r, b, x, anorm) result(eta)
    real(real64), intent(in) :: r(:, :), b(:, :), x(:, :), anorm
    integer :: j
    eta = 0
    do j = 1, size(r, 2)
      eta = max(eta, maxval(abs(r(:, j))) / (anorm * maxval(abs(x(:, j))) + maxval(abs(b(:, j)))))
    end do
  end function backward_error

end module dense_solver
