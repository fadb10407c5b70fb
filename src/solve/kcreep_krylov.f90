!> Restarted GMRES with right preconditioning, for several right-hand sides
!> in lockstep: each column has its own Krylov space, but the operator and
!> the preconditioner are applied to all active columns at once (one pass
!> over the preconditioner's factors and the FFT kernels per step).
!>
!> Flexible right preconditioning (FGMRES, Saad 1993): the preconditioned
!> vectors z_j = M^-1 v_j are kept and x = x0 + Z y. The preconditioner may
!> then be inexact (it runs in single precision, so M^-1 is not exactly
!> linear), and the residual GMRES minimises is still the true one: the
!> tolerance is on ||b - A x|| / ||b||, and at every restart the residual is
!> recomputed from x, not updated.
module kcreep_krylov
  use, intrinsic :: iso_fortran_env, only: real64, int64
  implicit none
  private
  public :: block_operator_t, gmres_result_t, gmres

  interface
    subroutine dgemv(trans, m, n, alpha, a, lda, x, incx, beta, y, incy)
      import :: real64
      character(len=1), intent(in) :: trans
      integer, intent(in) :: m, n, lda, incx, incy
      real(real64), intent(in) :: alpha, beta, a(lda, *), x(*)
      real(real64), intent(inout) :: y(*)
    end subroutine dgemv
  end interface

  !> Something that maps a block of vectors x(N, nv) to y(N, nv); columns(k)
  !> says which right-hand side column k of the block belongs to (an
  !> operator may differ between right-hand sides).
  type, abstract :: block_operator_t
  contains
    procedure(block_apply), deferred :: apply
  end type block_operator_t

  abstract interface
    subroutine block_apply(self, x, y, columns)
      import :: block_operator_t, real64
      class(block_operator_t), intent(inout) :: self
      real(real64), intent(in) :: x(:, :)
      real(real64), intent(out) :: y(:, :)
      integer, intent(in) :: columns(:)
    end subroutine block_apply
  end interface

  type :: gmres_result_t
    integer, allocatable :: iterations(:)          !< per column
    real(real64), allocatable :: relative_residual(:)   !< true ||b - A x|| / ||b|| at the end
    logical, allocatable :: converged(:)
    real(real64) :: t_operator = 0, t_preconditioner = 0, t_orthogonalise = 0   !< seconds
  end type gmres_result_t

contains

  !> Solve A x = b column by column to ||b - A x||_2 <= tol ||b||_2; x in: start, out: solution.
  subroutine gmres(a, precond, b, x, tol, restart, max_iterations, result)
    class(block_operator_t), intent(inout) :: a, precond
    real(real64), intent(in) :: b(:, :)
    real(real64), intent(inout) :: x(:, :)
    real(real64), intent(in) :: tol
    integer, intent(in) :: restart, max_iterations
    type(gmres_result_t), intent(out) :: result
    real(real64), allocatable :: v(:, :, :), zs(:, :, :), h(:, :, :), g(:, :), cs(:, :), sn(:, :), y(:)
    real(real64), allocatable :: r(:, :), bnorm(:), work(:, :), z(:, :)
    integer, allocatable :: cols(:), jend(:)
    logical, allocatable :: active(:), in_cycle(:)
    integer :: nn, nv, m, j, i, c, col, na
    real(real64) :: beta, hnew, t, wnorm
    integer(int64) :: c0, c1, c2, c3, rate

    nn = size(b, 1)
    nv = size(b, 2)
    m = restart
    allocate (v(nn, m + 1, nv), zs(nn, m, nv), h(m + 1, m, nv), g(m + 1, nv), cs(m, nv), sn(m, nv), y(m))
    allocate (r(nn, nv), bnorm(nv), jend(nv), active(nv), in_cycle(nv))
    allocate (result%iterations(nv), result%relative_residual(nv), result%converged(nv))
    result%iterations = 0
    result%converged = .false.
    do c = 1, nv
      bnorm(c) = norm2(b(:, c))
    end do
    where (bnorm == 0) bnorm = 1
    active = .true.
    call residual([(c, c=1, nv)])

    do
      ! columns done: converged, or out of iterations
      do c = 1, nv
        if (.not. active(c)) cycle
        if (result%relative_residual(c) <= tol) then
          result%converged(c) = .true.
          active(c) = .false.
        else if (result%iterations(c) >= max_iterations) then
          active(c) = .false.
        end if
      end do
      if (.not. any(active)) exit

      ! one cycle of GMRES(m) for the active columns
      in_cycle = active
      jend = 0
      do c = 1, nv
        if (.not. in_cycle(c)) cycle
        beta = norm2(r(:, c))
        v(:, 1, c) = r(:, c) / beta
        g(:, c) = 0
        g(1, c) = beta
      end do
      do j = 1, m
        cols = pack([(c, c=1, nv)], in_cycle)
        na = size(cols)
        if (na == 0) exit
        allocate (work(nn, na), z(nn, na))
        do i = 1, na
          work(:, i) = v(:, j, cols(i))
        end do
        call system_clock(c0, rate)
        call precond%apply(work, z, cols)
        call system_clock(c1)
        call a%apply(z, work, cols)
        call system_clock(c2)
        do i = 1, na
          c = cols(i)
          zs(:, j, c) = z(:, i)
          ! classical Gram-Schmidt: one BLAS-2 pass over the basis each way;
          ! a second pass only when the first cancelled much of the vector
          ! (Kahan's "twice is enough" test), where one pass loses orthogonality
          wnorm = norm2(work(:, i))
          call dgemv('T', nn, j, 1.0_real64, v(:, :, c), nn, work(:, i), 1, 0.0_real64, h(:, j, c), 1)
          call dgemv('N', nn, j, -1.0_real64, v(:, :, c), nn, h(:, j, c), 1, 1.0_real64, work(:, i), 1)
          if (norm2(work(:, i)) < 0.7_real64 * wnorm) then
            call dgemv('T', nn, j, 1.0_real64, v(:, :, c), nn, work(:, i), 1, 0.0_real64, y, 1)
            call dgemv('N', nn, j, -1.0_real64, v(:, :, c), nn, y, 1, 1.0_real64, work(:, i), 1)
            h(1:j, j, c) = h(1:j, j, c) + y(1:j)
          end if
          hnew = norm2(work(:, i))
          h(j + 1, j, c) = hnew
          if (hnew > 0) v(:, j + 1, c) = work(:, i) / hnew
          ! earlier rotations, then a new one to zero h(j+1, j)
          do col = 1, j - 1
            t = cs(col, c) * h(col, j, c) + sn(col, c) * h(col + 1, j, c)
            h(col + 1, j, c) = -sn(col, c) * h(col, j, c) + cs(col, c) * h(col + 1, j, c)
            h(col, j, c) = t
          end do
          t = hypot(h(j, j, c), h(j + 1, j, c))
          cs(j, c) = h(j, j, c) / t
          sn(j, c) = h(j + 1, j, c) / t
          h(j, j, c) = t
          h(j + 1, j, c) = 0
          g(j + 1, c) = -sn(j, c) * g(j, c)
          g(j, c) = cs(j, c) * g(j, c)
          jend(c) = j
          result%iterations(c) = result%iterations(c) + 1
          ! estimated residual small enough, exact (breakdown), or out of iterations
          if (abs(g(j + 1, c)) <= tol * bnorm(c) .or. hnew == 0 .or. &
              result%iterations(c) >= max_iterations) in_cycle(c) = .false.
        end do
        call system_clock(c3)
        result%t_preconditioner = result%t_preconditioner + real(c1 - c0, real64) / rate
        result%t_operator = result%t_operator + real(c2 - c1, real64) / rate
        result%t_orthogonalise = result%t_orthogonalise + real(c3 - c2, real64) / rate
        deallocate (work, z)
      end do

      ! x += Z y for each column that took steps
      cols = pack([(c, c=1, nv)], jend > 0)
      do i = 1, size(cols)
        c = cols(i)
        j = jend(c)
        do col = j, 1, -1
          y(col) = (g(col, c) - dot_product(h(col, col + 1:j, c), y(col + 1:j))) / h(col, col, c)
        end do
        call dgemv('N', nn, j, 1.0_real64, zs(:, :, c), nn, y, 1, 1.0_real64, x(:, c), 1)
      end do
      call residual(cols)
    end do

  contains

    !> r = b - A x and the relative residual, for the given columns.
    subroutine residual(which)
      integer, intent(in) :: which(:)
      real(real64), allocatable :: ax(:, :), xs(:, :)
      integer :: k
      if (size(which) == 0) return
      xs = x(:, which)
      allocate (ax(nn, size(which)))
      call a%apply(xs, ax, which)
      do k = 1, size(which)
        r(:, which(k)) = b(:, which(k)) - ax(:, k)
        result%relative_residual(which(k)) = norm2(r(:, which(k))) / bnorm(which(k))
      end do
    end subroutine residual

  end subroutine gmres

end module kcreep_krylov
