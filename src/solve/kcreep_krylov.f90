!> Restarted GMRES with right preconditioning, for several right-hand sides
!> in lockstep: each column has its own Krylov space, but the operator and
!> the preconditioner are applied to all active columns at once (one pass
!> over the preconditioner's factors and the FFT kernels per step).
!>
!> Right preconditioning: GMRES runs on A M^-1 and a cycle ends with
!> x = x0 + M^-1 (V y), one more apply of the preconditioner instead of
!> keeping every M^-1 v_j (half the basis memory). M^-1 must therefore be a
!> fixed linear map: the circulant one is, the strip one up to its single
!> precision rounding (about 1e-7 relative). The tolerance is on the true
!> ||b - A x|| / ||b||: after every cycle the residual is recomputed from x,
!> not updated (unless the caller ends columns on GMRES's estimate,
!> estimate_ends), so that rounding cannot pass unseen.
module kcreep_krylov
  use, intrinsic :: iso_fortran_env, only: real64, int64
  implicit none
  private
  public :: block_operator_t, gmres_result_t, gmres

  !> Gram-Schmidt runs on OpenMP loops of its own, not BLAS's dgemv: a
  !> threaded BLAS's sums may depend on its thread count, and its thread
  !> pool competed with OpenMP's (FFT operator, preconditioner) for the
  !> cores (measured: the solve 1.45 s instead of 1.1 s, 296 x 296 circle,
  !> 2 threads). Rows per partial sum of a dot product: fixed, so that the
  !> sums (and with them GMRES's iterates) do not depend on the threads.
  integer, parameter :: row_block = 4096

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
  !> estimate_ends: a column ends when GMRES's own residual estimate meets tol, without the
  !> product that checks it (an inexact Newton step's caller, which measures its own
  !> residual next, needs no more); restarts still begin from the true residual.
  !> second_pass_below: Gram-Schmidt's second pass runs when the first left less than this
  !> fraction of the vector's norm (default 1/sqrt(2), Kahan's "twice is enough"; a pass
  !> that keeps a fraction r loses about eps / r of orthogonality).
  subroutine gmres(a, precond, b, x, tol, restart, max_iterations, result, estimate_ends, second_pass_below)
    class(block_operator_t), intent(inout) :: a, precond
    real(real64), intent(in) :: b(:, :)
    real(real64), intent(inout) :: x(:, :)
    real(real64), intent(in) :: tol
    integer, intent(in) :: restart, max_iterations
    type(gmres_result_t), intent(out) :: result
    logical, intent(in), optional :: estimate_ends
    real(real64), intent(in), optional :: second_pass_below
    real(real64), allocatable :: v(:, :, :), h(:, :, :), g(:, :), cs(:, :), sn(:, :), y(:)
    real(real64), allocatable :: r(:, :), bnorm(:), work(:, :), z(:, :)
    integer, allocatable :: cols(:), jend(:)
    logical, allocatable :: active(:), in_cycle(:)
    logical :: trust
    integer :: nn, nv, m, j, i, c, col, na
    real(real64) :: beta, hnew, t, wnorm, second_pass
    integer(int64) :: c0, c1, c2, c3, rate

    nn = size(b, 1)
    nv = size(b, 2)
    m = restart
    allocate (v(nn, m + 1, nv), h(m + 1, m, nv), g(m + 1, nv), cs(m, nv), sn(m, nv), y(m))
    allocate (r(nn, nv), bnorm(nv), jend(nv), active(nv), in_cycle(nv))
    allocate (work(nn, nv), z(nn, nv))   ! once, for the widest block
    allocate (result%iterations(nv), result%relative_residual(nv), result%converged(nv))
    result%iterations = 0
    result%converged = .false.
    do c = 1, nv
      bnorm(c) = norm2(b(:, c))
    end do
    where (bnorm == 0) bnorm = 1
    active = .true.
    trust = .false.
    if (present(estimate_ends)) trust = estimate_ends
    second_pass = 0.7_real64
    if (present(second_pass_below)) second_pass = second_pass_below
    ! a zero start's residual is b itself (A 0 = 0 exactly): no product for it
    do c = 1, nv
      if (all(x(:, c) == 0)) then
        r(:, c) = b(:, c)
        result%relative_residual(c) = norm2(r(:, c)) / bnorm(c)
      end if
    end do
    call residual(pack([(c, c=1, nv)], [(any(x(:, c) /= 0), c=1, nv)]))

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
        do i = 1, na
          work(:, i) = v(:, j, cols(i))
        end do
        call system_clock(c0, rate)
        call precond%apply(work(:, 1:na), z(:, 1:na), cols)
        call system_clock(c1)
        call a%apply(z(:, 1:na), work(:, 1:na), cols)
        call system_clock(c2)
        do i = 1, na
          c = cols(i)
          ! classical Gram-Schmidt: one pass over the basis each way;
          ! a second pass only when the first cancelled much of the vector
          ! (Kahan's "twice is enough" test), where one pass loses orthogonality
          wnorm = norm(work(:, i))
          call project(v(:, 1:j, c), work(:, i), h(1:j, j, c))
          call add_combination(v(:, 1:j, c), -h(1:j, j, c), work(:, i))
          hnew = norm(work(:, i))
          if (hnew < second_pass * wnorm) then
            call project(v(:, 1:j, c), work(:, i), y(1:j))
            call add_combination(v(:, 1:j, c), -y(1:j), work(:, i))
            h(1:j, j, c) = h(1:j, j, c) + y(1:j)
            hnew = norm(work(:, i))
          end if
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
      end do

      ! x += M^-1 (V y) for each column that took steps: the preconditioner is
      ! a fixed linear map, so one more apply per cycle replaces keeping every
      ! preconditioned vector (half the basis memory)
      cols = pack([(c, c=1, nv)], jend > 0)
      na = size(cols)
      do i = 1, na
        c = cols(i)
        j = jend(c)
        do col = j, 1, -1
          y(col) = (g(col, c) - dot_product(h(col, col + 1:j, c), y(col + 1:j))) / h(col, col, c)
        end do
        work(:, i) = 0
        call add_combination(v(:, 1:j, c), y(1:j), work(:, i))
      end do
      if (na > 0) then
        call system_clock(c0, rate)
        call precond%apply(work(:, 1:na), z(:, 1:na), cols)
        call system_clock(c1)
        result%t_preconditioner = result%t_preconditioner + real(c1 - c0, real64) / rate
        do i = 1, na
          x(:, cols(i)) = x(:, cols(i)) + z(:, i)
        end do
      end if
      if (trust) then
        ! columns whose estimate met tol end on it; the others restart from the true residual
        do i = 1, na
          c = cols(i)
          if (abs(g(jend(c) + 1, c)) <= tol * bnorm(c)) then
            result%relative_residual(c) = abs(g(jend(c) + 1, c)) / bnorm(c)
            jend(c) = 0
          end if
        end do
        cols = pack(cols, jend(cols) > 0)
      end if
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

  !> h = V^T w: each thread sums whole blocks of rows, the blocks' sums are
  !> added in block order.
  subroutine project(v, w, h)
    real(real64), intent(in), contiguous :: v(:, :), w(:)
    real(real64), intent(out) :: h(:)
    real(real64) :: partial(size(v, 2), (size(w) + row_block - 1) / row_block)
    integer :: b, k, nb

    nb = size(partial, 2)
    if (nb == 1) then
      ! one block (short vectors: the rolling solver's): no parallel region to enter (an
      ! OpenMP region with if(.false.) still sets up a team, a microsecond per call)
      call block_products(v, w, 1, partial(:, 1))
    else
      !$omp parallel do schedule(static)
      do b = 1, nb
        call block_products(v, w, b, partial(:, b))
      end do
      !$omp end parallel do
    end if
    do k = 1, size(v, 2)
      h(k) = sum(partial(k, :))
    end do
  end subroutine project

  !> s(k) = the dot product of v(:, k) and w over block b of the rows, four
  !> columns at a time (four independent sums keep the adder busy).
  pure subroutine block_products(v, w, b, s)
    real(real64), intent(in), contiguous :: v(:, :), w(:)
    integer, intent(in) :: b
    real(real64), intent(out) :: s(:)
    real(real64) :: s1, s2, s3, s4
    integer :: i, k, lo, hi
    lo = (b - 1) * row_block + 1
    hi = min(b * row_block, size(w))
    do k = 1, size(v, 2) - 3, 4
      s1 = 0
      s2 = 0
      s3 = 0
      s4 = 0
      !$omp simd reduction(+:s1, s2, s3, s4)
      do i = lo, hi
        s1 = s1 + v(i, k) * w(i)
        s2 = s2 + v(i, k + 1) * w(i)
        s3 = s3 + v(i, k + 2) * w(i)
        s4 = s4 + v(i, k + 3) * w(i)
      end do
      s(k:k + 3) = [s1, s2, s3, s4]
    end do
    do k = size(v, 2) - mod(size(v, 2), 4) + 1, size(v, 2)
      s(k) = block_dot(v(:, k), w, b)
    end do
  end subroutine block_products

  !> ||w||_2 summed like project's products (the vectors are O(1) here:
  !> no scaling against overflow needed).
  real(real64) function norm(w)
    real(real64), intent(in), contiguous :: w(:)
    real(real64) :: partial((size(w) + row_block - 1) / row_block)
    integer :: b, nb
    nb = size(partial)
    if (nb == 1) then
      partial(1) = block_dot(w, w, 1)
    else
      !$omp parallel do schedule(static)
      do b = 1, nb
        partial(b) = block_dot(w, w, b)
      end do
      !$omp end parallel do
    end if
    norm = sqrt(sum(partial))
  end function norm

  !> Block b (rows row_block (b - 1) + 1 ...) of the dot product of a and b.
  pure real(real64) function block_dot(a, c, b) result(s)
    real(real64), intent(in), contiguous :: a(:), c(:)
    integer, intent(in) :: b
    integer :: i
    s = 0
    !$omp simd reduction(+:s)
    do i = (b - 1) * row_block + 1, min(b * row_block, size(a))
      s = s + a(i) * c(i)
    end do
  end function block_dot

  !> w = w + V a, row blocks in parallel (each row's sum in column order),
  !> four columns per pass over w (a pass per column cost twice the time:
  !> w loaded and stored for every column).
  subroutine add_combination(v, a, w)
    real(real64), intent(in), contiguous :: v(:, :), a(:)
    real(real64), intent(inout), contiguous :: w(:)
    integer :: b, lo, hi, nk
    nk = size(a)
    if (size(w) <= row_block) then
      call add_block(1, size(w))
      return
    end if
    !$omp parallel do private(lo, hi) schedule(static)
    do b = 1, (size(w) + row_block - 1) / row_block
      lo = (b - 1) * row_block + 1
      hi = min(b * row_block, size(w))
      call add_block(lo, hi)
    end do
    !$omp end parallel do

  contains

    subroutine add_block(lo, hi)
      integer, intent(in) :: lo, hi
      integer :: k, i
      real(real64) :: a1, a2, a3, a4
      do k = 1, nk - 3, 4
        a1 = a(k)
        a2 = a(k + 1)
        a3 = a(k + 2)
        a4 = a(k + 3)
        do i = lo, hi
          w(i) = w(i) + a1 * v(i, k) + a2 * v(i, k + 1) + a3 * v(i, k + 2) + a4 * v(i, k + 3)
        end do
      end do
      do k = nk - mod(nk, 4) + 1, nk
        w(lo:hi) = w(lo:hi) + a(k) * v(lo:hi, k)
      end do
    end subroutine add_block

  end subroutine add_combination

end module kcreep_krylov
