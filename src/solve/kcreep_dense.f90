!> What the dense path needs besides the LU itself (which linear_solve does
!> on the split systems): the diagnostics record, memory checks, the
!> normwise backward error and relative residual, and the whole-system solve
!> with LAPACK's expert driver (&solver refine = 'lapack') for comparison.
module kcreep_dense
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t, fail, exit_numerical, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use kcreep_lapack, only: dlange, dgesvx
  use kcreep_patch, only: patch_t
  use kcreep_assembly, only: operator_table_t, assemble_dense, apply_operator
  implicit none
  private
  public :: dense_diagnostics_t, solve_lapack_expert, check_dense_memory, refine_modes
  public :: backward_error, relative_residual, refine_threshold

  !> Backward errors above this are refined once (about 100 unit round-offs).
  real(real64), parameter :: refine_threshold = 100 * epsilon(1.0_real64)
  !> &solver refine: 'auto' one step of refinement when the backward error is
  !> above refine_threshold; 'always' one step whatever it is; 'never' none;
  !> 'lapack' LAPACK's expert driver dgesvx with equilibration (FACT = 'E'),
  !> whose dgerfs refines until the componentwise backward error stalls
  !> (twice the memory: the matrix and its factors).
  character(len=*), parameter :: refine_modes(4) = [character(len=6) :: 'auto', 'always', 'never', 'lapack']

  type :: dense_diagnostics_t
    real(real64) :: rcond = 0                !< LAPACK dgecon, 1-norm
    real(real64) :: backward_error = 0       !< max over load cases, after refinement
    real(real64) :: backward_error_initial = 0
    real(real64) :: relative_residual = 0     !< max_j |b_j - A x_j| / |b_j| before refinement, inf-norms
    logical :: refined = .false.
    real(real64) :: t_assemble = 0, t_factor = 0, t_solve = 0
    character(len=:), allocatable :: method   !< 'dense' or 'iterative' (set by linear_solve)
    integer :: iterations = 0                 !< GMRES iterations (largest over load cases), 0 for dense
    integer :: threads = 1                    !< the solve's team (kcreep_threads)
    real(real64) :: t_operator = 0, t_preconditioner = 0, t_orthogonalise = 0   !< where GMRES spent its time
  end type dense_diagnostics_t

contains

  pure integer(int64) function dense_matrix_bytes(n_unknowns)
    integer, intent(in) :: n_unknowns
    dense_matrix_bytes = 8_int64 * n_unknowns * n_unknowns
  end function dense_matrix_bytes

  !> Fail before allocating when the dense matrix cannot fit in the memory available.
  !> memory_limit: bytes the caller allows (solver_options_t), negative for no limit.
  subroutine check_dense_memory(n_cells, memory_limit, status)
    integer, intent(in) :: n_cells
    integer(int64), intent(in) :: memory_limit
    type(status_t), intent(inout) :: status
    integer(int64) :: need, have
    need = dense_matrix_bytes(2 * n_cells)
    have = memory_limit
    if (have > 0 .and. need > have) then
      call fail(status, exit_bad_input, 'the dense matrix of '//itoa(2 * n_cells)//' unknowns needs '// &
                rtoa(real(need, real64) / 2.0_real64**30)//' GiB, only '// &
                rtoa(real(have, real64) / 2.0_real64**30)//' GiB are available (use a coarser grid)')
    end if
  end subroutine check_dense_memory

  !> refine = 'lapack': the whole unsplit 2n x 2n system through LAPACK's expert
  !> driver: equilibration, LU, condition estimate and iterative refinement
  !> (dgerfs) in one call, to compare with kcreep's own refinement. rcond is that of the
  !> equilibrated matrix; the backward errors are recomputed here, normwise,
  !> so that they compare with the other modes.
  subroutine solve_lapack_expert(patch, table, memory_limit, rhs, diag, status)
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    integer(int64), intent(in) :: memory_limit   !< bytes, negative: no limit
    real(real64), intent(inout) :: rhs(:, :)
    type(dense_diagnostics_t), intent(out) :: diag
    type(status_t), intent(inout) :: status
    real(real64), allocatable :: a(:, :), af(:, :), b(:, :), x(:, :), r(:, :), rs(:), cs(:), &
                                 ferr(:), berr(:), work(:)
    integer, allocatable :: ipiv(:), iwork(:)
    integer :: m, nrhs, info
    integer(int64) :: t0, t1, rate
    character(len=1) :: equed
    real(real64) :: anorm_inf, rcond

    m = 2 * patch%n
    nrhs = size(rhs, 2)
    call check_dense_memory(ceiling(sqrt(2.0_real64) * patch%n), memory_limit, status)   ! two matrices: 2 (2n)^2 doubles
    if (status%failed()) return
    call system_clock(t0, rate)
    allocate (a(m, m), af(m, m), ipiv(m), rs(m), cs(m), ferr(nrhs), berr(nrhs), work(4 * m), iwork(m), &
              x(m, nrhs), r(m, nrhs), stat=info)
    if (info /= 0) then
      call fail(status, exit_numerical, 'out of memory: the two dense matrices of '//itoa(m)//' unknowns ('// &
                rtoa(16 * real(m, real64)**2 / 2.0_real64**30)//' GiB) could not be allocated '// &
                '(use a coarser grid, another refine mode or method = ''iterative'')')
      return
    end if
    call assemble_dense(patch, table, a)
    call system_clock(t1)
    diag%t_assemble = real(t1 - t0, real64) / rate
    t0 = t1
    anorm_inf = dlange('I', m, m, a, m, work)
    b = rhs
    call dgesvx('E', 'N', m, nrhs, a, m, af, m, ipiv, equed, rs, cs, rhs, m, x, m, rcond, ferr, berr, &
                work, iwork, info)
    if (info > 0 .and. info <= m) then
      call fail(status, exit_numerical, 'the influence matrix is exactly singular (LU pivot '// &
                itoa(info)//' is zero); the collocation point or the patch is degenerate')
      return
    end if
    call system_clock(t1)
    diag%t_factor = real(t1 - t0, real64) / rate
    diag%rcond = rcond
    diag%refined = .true.
    rhs = x
    call residual(patch, table, b, rhs, r)
    diag%backward_error = backward_error(r, b, rhs, anorm_inf)
    diag%backward_error_initial = diag%backward_error
    diag%relative_residual = relative_residual(r, b)
  end subroutine solve_lapack_expert

  !> max_j |r_j| / |b_j|, infinity norms.
  pure real(real64) function relative_residual(r, b) result(rho)
    real(real64), intent(in) :: r(:, :), b(:, :)
    integer :: j
    rho = 0
    do j = 1, size(r, 2)
      if (maxval(abs(b(:, j))) > 0) rho = max(rho, maxval(abs(r(:, j))) / maxval(abs(b(:, j))))
    end do
  end function relative_residual

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
    real(real64) :: scale
    eta = 0
    do j = 1, size(r, 2)
      scale = anorm * maxval(abs(x(:, j))) + maxval(abs(b(:, j)))
      ! b = 0 (e.g. spin about the only cell's centre) gives x = 0 and r = 0: no error
      if (scale > 0) then
        eta = max(eta, maxval(abs(r(:, j))) / scale)
      else if (maxval(abs(r(:, j))) > 0) then
        eta = huge(eta)
      end if
    end do
  end function backward_error

end module kcreep_dense
