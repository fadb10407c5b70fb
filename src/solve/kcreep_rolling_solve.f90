!> Steady rolling with Coulomb friction on the patch's grid: the exact
!> (discrete) partial-slip problem of the backward scheme, by a semi-smooth
!> Newton method.
!>
!> Unknowns: the cell tractions p = (px(1:n), py(1:n)). With A the backward
!> scheme's operator (A p = w in full adhesion, kcreep_assembly) the slip of
!> cell i is s_i = w_i - (A p)_i, w the rigid slip of the creepage. Coulomb:
!>   |p_i| <= g_i = mu pn_i;  s_i = 0 where |p_i| < g_i;  p_i = -g_i s_i/|s_i| where s_i /= 0,
!> the traction opposing the slip. As a projection (the same for any rho > 0):
!>   F_i(p) = p_i - Proj_{|.| <= g_i}(q_i) = 0,  q_i = p_i - rho s_i(p),
!> so that F_i = rho s_i in adhesion (|q_i| <= g_i) and p_i - g_i q_i/|q_i| in slip.
!> Newton's step solves J dp = -F with the generalised Jacobian
!>   J = I - P' (I + rho A),  P'_i = I (adhesion),  (g_i/|q_i|)(I - n_i n_i^T) (slip), n_i = q_i/|q_i|,
!> inexactly by flexible GMRES (kcreep_krylov) with the FFT operator
!> (kcreep_fft_operator) and, as preconditioner, the exact LU of the
!> Jacobian restricted to each grid row (both components of the row's cells:
!> the row carries the one-sided upwind difference of rolling). Armijo
!> back-tracking on ||F||_2 globalises the step; the stop test is on the
!> residual itself, max_i |F_i| <= tolerance * max_i g_i (not on the size of
!> the update, which leaves CONTACT's GDsteady short of convergence at some points).
module kcreep_rolling_solve
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep_assembly, only: operator_table_t
  use kcreep_fft_operator, only: fft_operator_t, create_fft_operator, destroy_fft_operator, apply_fft_operator
  use kcreep_krylov, only: block_operator_t, gmres_result_t, gmres
  implicit none
  private
  public :: rolling_solver_t, rolling_options_t, rolling_info_t, create_rolling_solver, destroy_rolling_solver, &
            solve_rolling, rolling_residual, residual_of_product, project_to_bounds, cell_stick, cell_slip, &
            default_rolling_tolerance

  integer, parameter :: cell_stick = 1, cell_slip = 2   !< CONTACT's IGS: 1 adhesion, 2 slip

  !> max |F_i| / max g_i at which Newton stops. 1e-7: the forces then agree
  !> with a run to 1e-13 within 3.6e-9 of mu Fn (20 x 20 circle, a 200-step
  !> history and 200 random creepages; docs/rolling.md, "Stopping"), far below
  !> CONTACT's printed digits; 0.65 of the time of 1e-10 in the time step.
  real(real64), parameter :: default_rolling_tolerance = 1e-7_real64

  !> GMRES's relative tolerance in the first Newton step and its largest
  !> value later (Eisenstat-Walker forcing in between). Never below
  !> stop_forcing x (the stop test / max|F|): a step need not be solved more
  !> finely than what would bring a linear F to the stop test. Measured (fast
  !> model's build, 432-cell L-shaped mask; the 20 x 20 circle's warm loop):
  !> 0.1 and 0.1: 2.21 s, 0.55 ms; 0.5 and 0.5: 1.98 s, 0.50 ms; 0.9 and
  !> 0.5: 1.82 s, 0.48 ms (0.9 and 0.9 the same); the answers keep their stop test.
  real(real64), parameter :: first_forcing = 1e-2_real64, max_forcing = 0.5_real64, stop_forcing = 0.9_real64

  !> Cells of a grid row coupled in the preconditioner's row blocks, each side.
  !> Measured, one thread, CPU time, with the rows' substitutions side by side
  !> (rows_solve: their cost now grows with the band): band 4 / 3 / 2, the 20 x 20
  !> circle's warm loop 0.295 / 0.283 / 0.283 ms per call, the fast model's build
  !> 0.54 / 0.51 / 0.50 s (circle) and 1.43 / 1.32 / 1.24 s (432-cell L-shaped mask),
  !> one cold point xi = 2e-3 on a 200 x 200 circle 0.265 / - / 0.248 s. (With one row after
  !> another, before: whole rows 0.47 s, 0.37 s, 7.8 s on a 24-point curve, one point
  !> at 100 x 100 and at 200 x 200; band 8: 0.56, 0.22, 2.3 s; band 4: 0.41, 0.15,
  !> 1.3 s; band 2: 0.38, 0.25, 1.4 s.)
  integer, parameter :: band_cells = 2

  !> GMRES's second Gram-Schmidt pass only where the first kept less than a tenth of the
  !> vector (at most about 10 eps of orthogonality lost a step; a Newton step asks GMRES
  !> for 1e-2 to 1e-3). Measured (the 20 x 20 circle's warm loop, 3033 GMRES steps): the
  !> first pass kept 0.14 to 0.72 of the vector, median 0.38, so the default test (1/sqrt(2))
  !> ran the second pass at all but 4 steps; without it, the same iterations and the warm
  !> loop 0.307 -> 0.293 ms per call.
  real(real64), parameter :: second_pass_below = 0.1_real64

  !> A row block is factored again when P' of one of its cells moved by more than this
  !> (|d pxx| + |d pxy| + |d pyy|; a cell turning from adhesion to slip moves it by
  !> about 1 or more) since the row's last factorisation, kept across Newton steps and
  !> calls; the others keep their LU as the preconditioner. Measured, one thread, CPU
  !> time (the 20 x 20 circle's warm loop; the fast model's build of the circle and of
  !> the 432-cell L-shaped mask): every row every step 0.45 ms, 0.70 s, 1.84 s; only
  !> unchanged rows kept (0): 0.45 ms; 0.01: 0.43 ms; 0.1: 0.41 ms, 0.66 s, 1.71 s;
  !> 0.3: 0.40 ms, 0.63 s, 1.64 s; 0.5: 0.42 ms, 0.63 s, 1.64 s; 1: 0.41 ms.
  real(real64), parameter :: refactor_change = 0.3_real64

  type :: rolling_options_t
    real(real64) :: tolerance = default_rolling_tolerance
    integer :: max_newton = 60
    integer :: restart = 40          !< GMRES restart length
    integer :: max_gmres = 600       !< GMRES iterations per Newton step
  end type rolling_options_t

  type :: rolling_info_t
    integer :: newton = 0            !< Newton steps
    integer :: gmres = 0             !< GMRES iterations, all steps
    integer :: products = 0          !< operator products (A p), all uses
    real(real64) :: residual = 0     !< max |F_i| / max g_i at the end
    logical :: converged = .false.
  end type rolling_info_t

  !> The generalised Jacobian J v = v - P' (v + rho A v), P' per cell
  !> (symmetric 2 x 2: pxx, pxy, pyy).
  type, extends(block_operator_t) :: rolling_jacobian_t
    type(fft_operator_t) :: op
    integer :: n = 0
    real(real64) :: rho = 0
    real(real64), allocatable :: pxx(:), pxy(:), pyy(:)
    integer :: products = 0
  contains
    procedure :: apply => apply_jacobian
  end type rolling_jacobian_t

  !> Banded LU of the Jacobian restricted to one grid row: unknowns (px, py)
  !> of its m cells interleaved, couplings between cells at most band_cells
  !> apart in the row (A's row coupling falls off as 1/distance^2).
  type :: row_block_t
    integer :: first = 0, m = 0      !< cells first .. first + m - 1
    logical :: factored = .false.    !< ab holds the LU of P' as in row_preconditioner_t's fxx ...
    integer :: kl = 0                !< sub- and superdiagonals of the band (unknowns)
    integer :: ku = 0                !< U's superdiagonals that are not zero (kl to 2 kl, by the pivoting)
    real(real64), allocatable :: ab(:, :)      !< LAPACK band storage (2 kl + kl + 1, 2 m)
    integer, allocatable :: pivots(:)
  end type row_block_t

  !> The row blocks' LU factors side by side for the substitutions (rows_solve), the
  !> row index fastest: all rows' substitutions advance together, independent steps
  !> in one loop instead of one row's chain of dependent steps after another (that
  !> chain, not the flops, set the time: 6 us against 2 us per apply, 20 x 20 circle).
  !> Rows shorter than the longest and bands narrower than the widest are padded with
  !> the identity (zero multipliers, unit diagonal), which leaves every value as the
  !> row's own substitution computes it.
  type, extends(block_operator_t) :: row_preconditioner_t
    type(row_block_t), allocatable :: rows(:)
    integer :: n = 0
    integer :: kl = 0, width = 0                          !< the widest band; the longest row's unknowns (2 m)
    integer, allocatable :: ix(:)                         !< grid column of each cell
    real(real64), allocatable :: rxx(:), rxy(:), ryy(:)   !< A within a grid row, by offset
    real(real64), allocatable :: fxx(:), fxy(:), fyy(:)   !< P' per cell at the rows' last factorisation
    !> (row, i, j): L's multiplier of unknown j + i by unknown j; U(j - i, j); (row, j): 1 / U(j, j)
    !> (the back substitution multiplies: a division's latency was a sixth of its time);
    !> the row interchanged with j minus j
    real(real64), allocatable :: lower(:, :, :), upper(:, :, :), inverse_diagonal(:, :)
    integer, allocatable :: swap(:, :)
    logical, allocatable :: swapped(:)                    !< (width): some row interchanges unknown j
    integer, allocatable :: place(:)                      !< (2n): each unknown's element of b
    real(real64), allocatable :: b(:, :)                  !< (rows, width) work
  contains
    procedure :: apply => apply_rows
  end type row_preconditioner_t

  type :: rolling_solver_t
    type(rolling_jacobian_t) :: jac
    type(row_preconditioner_t) :: prec
    integer :: n = 0
  end type rolling_solver_t

contains

  !> Plan the FFT operator of the patch and the row blocks (once per patch and material).
  subroutine create_rolling_solver(patch, table, solver)
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    type(rolling_solver_t), intent(out) :: solver
    integer :: k, first, nrows, r, m

    solver%n = patch%n
    solver%jac%n = patch%n
    call create_fft_operator(patch, table, 1, solver%jac%op)
    ! rho: the inverse of the cell's own coefficient, so that q_i hardly depends on p_i itself
    solver%jac%rho = 2 / (abs(table%xx(0, 0)) + abs(table%yy(0, 0)))
    allocate (solver%jac%pxx(patch%n), solver%jac%pxy(patch%n), solver%jac%pyy(patch%n))
    ! grid rows: cells are numbered row by row, x increasing
    nrows = 0
    do k = 1, patch%n
      if (k == 1) then
        nrows = 1
      else if (patch%iy(k) /= patch%iy(k - 1)) then
        nrows = nrows + 1
      end if
    end do
    solver%prec%n = patch%n
    solver%prec%ix = patch%ix
    allocate (solver%prec%rxx(-(patch%mx - 1):patch%mx - 1), solver%prec%rxy(-(patch%mx - 1):patch%mx - 1), &
              solver%prec%ryy(-(patch%mx - 1):patch%mx - 1))
    solver%prec%rxx = table%xx(:, 0)
    solver%prec%rxy = table%xy(:, 0)
    solver%prec%ryy = table%yy(:, 0)
    allocate (solver%prec%rows(nrows), solver%prec%fxx(patch%n), solver%prec%fxy(patch%n), solver%prec%fyy(patch%n), &
              solver%prec%place(2 * patch%n))
    r = 0
    first = 1
    do k = 1, patch%n
      if (k == patch%n) then
        call add_row(first, k)
      else if (patch%iy(k + 1) /= patch%iy(k)) then
        call add_row(first, k)
        first = k + 1
      end if
    end do
    associate (pr => solver%prec)
      pr%kl = maxval(pr%rows%kl)
      pr%width = 2 * maxval(pr%rows%m)
      allocate (pr%lower(nrows, pr%kl, pr%width), pr%upper(nrows, 2 * pr%kl, pr%width), &
                pr%inverse_diagonal(nrows, pr%width), pr%swap(nrows, pr%width), pr%b(nrows, pr%width), &
                pr%swapped(pr%width))
      pr%lower = 0
      pr%upper = 0
      pr%inverse_diagonal = 1
      pr%swap = 0
      pr%swapped = .false.
      pr%b = 0
      ! unknown px of a row's i-th cell is its 2 i - 1-th, py the 2 i-th
      do r = 1, nrows
        do k = 1, pr%rows(r)%m
          pr%place(pr%rows(r)%first + k - 1) = r + (2 * k - 2) * nrows
          pr%place(patch%n + pr%rows(r)%first + k - 1) = r + (2 * k - 1) * nrows
        end do
      end do
    end associate

  contains

    subroutine add_row(lo, hi)
      integer, intent(in) :: lo, hi
      integer :: kl
      r = r + 1
      m = hi - lo + 1
      kl = 2 * min(m - 1, band_cells) + 1
      solver%prec%rows(r)%first = lo
      solver%prec%rows(r)%m = m
      solver%prec%rows(r)%kl = kl
      allocate (solver%prec%rows(r)%ab(3 * kl + 1, 2 * m), solver%prec%rows(r)%pivots(2 * m))
    end subroutine add_row

  end subroutine create_rolling_solver

  subroutine destroy_rolling_solver(solver)
    type(rolling_solver_t), intent(inout) :: solver
    call destroy_fft_operator(solver%jac%op)
  end subroutine destroy_rolling_solver

  !> F(p) and what Newton needs of it: q = p - rho s, ||F||_2, max |F_i|;
  !> ap: A p (one operator product), kept by callers that reuse it.
  subroutine rolling_residual(solver, w, bound, p, f, q, fnorm, fmax, ap)
    type(rolling_solver_t), intent(inout) :: solver
    real(real64), intent(in) :: w(:), bound(:), p(:)
    real(real64), intent(out) :: f(:), q(:)
    real(real64), intent(out) :: fnorm, fmax
    real(real64), intent(out), optional :: ap(:)
    real(real64) :: product(size(p), 1)
    call apply_fft_operator(solver%jac%op, reshape(p, [size(p), 1]), product)
    solver%jac%products = solver%jac%products + 1
    call residual_of_product(solver, w, bound, p, product(:, 1), f, q, fnorm, fmax)
    if (present(ap)) ap = product(:, 1)
  end subroutine rolling_residual

  !> rolling_residual with A p given (ap): no operator product.
  subroutine residual_of_product(solver, w, bound, p, ap, f, q, fnorm, fmax)
    type(rolling_solver_t), intent(in) :: solver
    real(real64), intent(in) :: w(:), bound(:), p(:), ap(:)
    real(real64), intent(out) :: f(:), q(:)
    real(real64), intent(out) :: fnorm, fmax
    real(real64) :: shrink
    integer :: i, n
    n = solver%n
    q = p + solver%jac%rho * (ap - w)
    ! the projection as one factor, min(1, g / |q|): no branch, so that the loop vectorises
    do i = 1, n
      shrink = min(1.0_real64, bound(i) / max(sqrt(q(i)**2 + q(n + i)**2), tiny(1.0_real64)))
      f(i) = p(i) - shrink * q(i)
      f(n + i) = p(n + i) - shrink * q(n + i)
    end do
    fmax = sqrt(maxval(f(1:n)**2 + f(n + 1:2 * n)**2))
    ! O(1) values: the plain sum of squares (norm2's scaling divides at every element)
    fnorm = sqrt(sum(f**2))
  end subroutine residual_of_product

  !> Solve the rolling problem for rigid slip w (2n) and traction bounds g (n);
  !> p: start in, solution out; state: cell_stick / cell_slip per cell.
  !> start_ap: A p of the start as given (a caller that has it saves the product; p is
  !> then taken as it is, else projected onto the bounds first); ap: A p of the solution.
  subroutine solve_rolling(solver, w, bound, options, p, state, info, start_ap, ap)
    type(rolling_solver_t), intent(inout) :: solver
    real(real64), intent(in) :: w(:), bound(:)
    type(rolling_options_t), intent(in) :: options
    real(real64), intent(inout) :: p(:)
    integer, intent(out) :: state(:)
    type(rolling_info_t), intent(out) :: info
    real(real64), intent(in), optional :: start_ap(:)
    real(real64), intent(out), optional :: ap(:)
    real(real64), allocatable :: f(:), q(:), ftrial(:), qtrial(:), ptrial(:), dp(:, :), rhs(:, :), pa(:), patrial(:)
    real(real64) :: fnorm, fmax, gscale, tnorm, tmax, t, eta, fnorm_previous
    type(gmres_result_t) :: gr
    integer :: n, i, halvings
    real(real64), parameter :: armijo = 1e-4_real64

    n = solver%n
    allocate (f(2 * n), q(2 * n), ftrial(2 * n), qtrial(2 * n), ptrial(2 * n), dp(2 * n, 1), rhs(2 * n, 1), &
              pa(2 * n), patrial(2 * n))
    solver%jac%products = 0
    gscale = max(maxval(bound), tiny(1.0_real64))
    if (present(start_ap)) then
      pa = start_ap
      call residual_of_product(solver, w, bound, p, pa, f, q, fnorm, fmax)
    else
      ! p must start inside the bounds for the residual to mean what it says
      call project_to_bounds(bound, p)
      call rolling_residual(solver, w, bound, p, f, q, fnorm, fmax, pa)
    end if
    do
      info%residual = fmax / gscale
      if (info%residual <= options%tolerance) then
        info%converged = .true.
        exit
      end if
      if (info%newton >= options%max_newton) exit
      info%newton = info%newton + 1
      call set_derivative(q)
      call factor_rows(solver)
      ! forcing term (Eisenstat and Walker's choice 2, safeguarded): loose while
      ! far, tighter as ||F|| falls; never far below what the stop test needs
      if (info%newton == 1) then
        eta = first_forcing
      else
        eta = max(0.9_real64 * (fnorm / fnorm_previous)**2, 0.9_real64 * eta**2)
      end if
      eta = min(max_forcing, max(eta, stop_forcing * options%tolerance * gscale / fmax))
      fnorm_previous = fnorm
      rhs(:, 1) = -f
      dp = 0
      call gmres(solver%jac, solver%prec, rhs, dp, eta, options%restart, options%max_gmres, gr, estimate_ends=.true., &
                 second_pass_below=second_pass_below)
      info%gmres = info%gmres + gr%iterations(1)
      ! Armijo back-tracking on ||F||_2
      t = 1
      halvings = 0
      do
        ptrial = p + t * dp(:, 1)
        call rolling_residual(solver, w, bound, ptrial, ftrial, qtrial, tnorm, tmax, patrial)
        if (tnorm <= (1 - armijo * t) * fnorm .or. halvings >= 30) exit
        t = t / 2
        halvings = halvings + 1
      end do
      p = ptrial
      f = ftrial
      q = qtrial
      pa = patrial
      fnorm = tnorm
      fmax = tmax
    end do
    info%products = solver%jac%products
    if (present(ap)) ap = pa
    ! the element division of the solution (q: of the final p)
    do i = 1, n
      if (q(i)**2 + q(n + i)**2 <= bound(i)**2) then
        state(i) = cell_stick
      else
        state(i) = cell_slip
      end if
    end do

  contains

    !> P' per cell at q.
    subroutine set_derivative(qq)
      real(real64), intent(in) :: qq(:)
      real(real64) :: a, c, nx, ny
      integer :: k
      do k = 1, n
        a = sqrt(qq(k)**2 + qq(n + k)**2)
        if (a <= bound(k)) then
          solver%jac%pxx(k) = 1
          solver%jac%pxy(k) = 0
          solver%jac%pyy(k) = 1
        else
          c = bound(k) / a
          nx = qq(k) / a
          ny = qq(n + k) / a
          solver%jac%pxx(k) = c * (1 - nx * nx)
          solver%jac%pxy(k) = -c * nx * ny
          solver%jac%pyy(k) = c * (1 - ny * ny)
        end if
      end do
    end subroutine set_derivative

  end subroutine solve_rolling

  !> Tractions v (2n: px, py) scaled back onto the disc |p_i| <= bound_i where they lie outside it.
  pure subroutine project_to_bounds(bound, v)
    real(real64), intent(in) :: bound(:)
    real(real64), intent(inout) :: v(:)
    real(real64) :: a
    integer :: k, n
    n = size(bound)
    do k = 1, n
      a = sqrt(v(k)**2 + v(n + k)**2)
      if (a > bound(k) .and. a > 0) then
        v(k) = v(k) * bound(k) / a
        v(n + k) = v(n + k) * bound(k) / a
      end if
    end do
  end subroutine project_to_bounds

  !> y = J x = x - P' (x + rho A x) for each column.
  subroutine apply_jacobian(self, x, y, columns)
    class(rolling_jacobian_t), intent(inout) :: self
    real(real64), intent(in) :: x(:, :)
    real(real64), intent(out) :: y(:, :)
    integer, intent(in) :: columns(:)
    real(real64) :: vx, vy
    integer :: k, v, n
    if (size(columns) < 0) return
    n = self%n
    call apply_fft_operator(self%op, x, y)
    self%products = self%products + size(x, 2)
    do v = 1, size(x, 2)
      do k = 1, n
        vx = x(k, v) + self%rho * y(k, v)
        vy = x(n + k, v) + self%rho * y(n + k, v)
        y(k, v) = x(k, v) - (self%pxx(k) * vx + self%pxy(k) * vy)
        y(n + k, v) = x(n + k, v) - (self%pxy(k) * vx + self%pyy(k) * vy)
      end do
    end do
  end subroutine apply_jacobian

  !> Banded LU of each row's block of J = I - P' (I + rho A_row), for the rows where P'
  !> moved by more than refactor_change (any entry of any cell) since their last one.
  subroutine factor_rows(solver)
    type(rolling_solver_t), intent(inout) :: solver
    integer :: r, i, j, m, k, l, kl, info, d, ci, cj, lo, hi
    real(real64) :: rho, pxx, pxy, pyy, bxx, bxy, byy
    rho = solver%jac%rho
    associate (pr => solver%prec)
      do r = 1, size(pr%rows)
        associate (row => pr%rows(r))
          m = row%m
          kl = row%kl
          lo = row%first
          hi = lo + m - 1
          if (row%factored) then
            if (maxval(abs(solver%jac%pxx(lo:hi) - pr%fxx(lo:hi)) + abs(solver%jac%pxy(lo:hi) - pr%fxy(lo:hi)) + &
                       abs(solver%jac%pyy(lo:hi) - pr%fyy(lo:hi))) <= refactor_change) cycle
          end if
          pr%fxx(lo:hi) = solver%jac%pxx(lo:hi)
          pr%fxy(lo:hi) = solver%jac%pxy(lo:hi)
          pr%fyy(lo:hi) = solver%jac%pyy(lo:hi)
          row%factored = .true.
          row%ku = 0
          row%ab = 0
          do i = 1, m
            k = row%first + i - 1
            pxx = solver%jac%pxx(k)
            pxy = solver%jac%pxy(k)
            pyy = solver%jac%pyy(k)
            do j = max(1, i - (kl - 1) / 2), min(m, i + (kl - 1) / 2)
              l = row%first + j - 1
              d = pr%ix(k) - pr%ix(l)
              bxx = rho * pr%rxx(d)
              bxy = rho * pr%rxy(d)
              byy = rho * pr%ryy(d)
              if (i == j) then
                bxx = bxx + 1
                byy = byy + 1
              end if
              ci = 2 * i - 1   ! px of cell i; py is ci + 1
              cj = 2 * j - 1
              call put(ci, cj, -(pxx * bxx + pxy * bxy))
              call put(ci, cj + 1, -(pxx * bxy + pxy * byy))
              call put(ci + 1, cj, -(pxy * bxx + pyy * bxy))
              call put(ci + 1, cj + 1, -(pxy * bxy + pyy * byy))
              if (i == j) then
                call put(ci, cj, 1.0_real64)
                call put(ci + 1, cj + 1, 1.0_real64)
              end if
            end do
          end do
          call band_factor(2 * m, kl, row%ab, row%pivots, info)
          if (info > 0) then
            ! a singular row block (not seen; a guard): the identity there
            row%ab = 0
            row%ab(2 * kl + 1, :) = 1
            row%pivots = [(i, i=1, 2 * m)]
          end if
          ! the factors side by side (kept zero or one beyond the row's own)
          do j = 1, 2 * m
            pr%swap(r, j) = row%pivots(j) - j
            pr%inverse_diagonal(r, j) = 1 / row%ab(2 * kl + 1, j)
            do i = 1, kl
              pr%lower(r, i, j) = 0
              if (i <= 2 * m - j) pr%lower(r, i, j) = row%ab(2 * kl + 1 + i, j)
            end do
            do i = 1, 2 * kl
              pr%upper(r, i, j) = 0
              if (i <= j - 1) pr%upper(r, i, j) = row%ab(2 * kl + 1 - i, j)
              if (pr%upper(r, i, j) /= 0) row%ku = max(row%ku, i)
            end do
          end do
        end associate
      end do
      pr%swapped = any(pr%swap /= 0, dim=1)
    end associate

  contains

    !> Add v to element (a, b) of the row's band matrix.
    subroutine put(a, b, v)
      integer, intent(in) :: a, b
      real(real64), intent(in) :: v
      associate (row => solver%prec%rows(r))
        row%ab(2 * row%kl + 1 + a - b, b) = row%ab(2 * row%kl + 1 + a - b, b) + v
      end associate
    end subroutine put

  end subroutine factor_rows

  !> z = (row-block J)^-1 r for each column.
  subroutine apply_rows(self, x, y, columns)
    class(row_preconditioner_t), intent(inout) :: self
    real(real64), intent(in) :: x(:, :)
    real(real64), intent(out) :: y(:, :)
    integer, intent(in) :: columns(:)
    integer :: v
    if (size(columns) < 0) return
    do v = 1, size(x, 2)
      call place_values(x(:, v), self%place, self%b)
      call rows_solve(size(self%rows), self%width, self%kl, maxval(self%rows%ku), self%lower, self%upper, &
                      self%inverse_diagonal, self%swap, self%swapped, self%b)
      call take_values(self%b, self%place, y(:, v))
    end do
  end subroutine apply_rows

  pure subroutine place_values(values, place, b)
    real(real64), intent(in) :: values(:)
    integer, intent(in) :: place(:)
    real(real64), intent(inout) :: b(*)
    b(place) = values
  end subroutine place_values

  pure subroutine take_values(b, place, values)
    real(real64), intent(in) :: b(*)
    integer, intent(in) :: place(:)
    real(real64), intent(out) :: values(:)
    values = b(place)
  end subroutine take_values

  !> All rows' banded LU solves at once (LAPACK's dgbtrs with band_factor's LU, one
  !> right-hand side each), b(row, unknown): in, the right-hand sides; out, the solutions.
  !> The padding's unknowns stay zero.
  pure subroutine rows_solve(nr, nu, kl, ku, lower, upper, inverse_diagonal, swap, swapped, b)
    integer, intent(in) :: nr, nu, kl, ku   !< ku: U's superdiagonals not zero in any row
    real(real64), intent(in) :: lower(nr, kl, nu), upper(nr, 2 * kl, nu), inverse_diagonal(nr, nu)
    integer, intent(in) :: swap(nr, nu)
    logical, intent(in) :: swapped(nu)
    real(real64), intent(inout) :: b(nr, nu)
    real(real64) :: t
    integer :: j, i, r, l
    do j = 1, nu - 1
      ! (the rolling Jacobian's row blocks seldom pivot: none on the 20 x 20 circle's loop)
      if (swapped(j)) then
        do r = 1, nr
          l = j + swap(r, j)
          t = b(r, l)
          b(r, l) = b(r, j)
          b(r, j) = t
        end do
      end if
      do i = 1, min(kl, nu - j)
        b(:, j + i) = b(:, j + i) - lower(:, i, j) * b(:, j)
      end do
    end do
    do j = nu, 1, -1
      b(:, j) = b(:, j) * inverse_diagonal(:, j)
      do i = 1, min(ku, j - 1)
        b(:, j - i) = b(:, j - i) - b(:, j) * upper(:, i, j)
      end do
    end do
  end subroutine rows_solve

  !> LU with partial pivoting of a band matrix with kl sub- and kl superdiagonals in
  !> LAPACK's storage (ab(2 kl + kl + 1, n), A(i, j) = ab(2 kl + 1 + i - j, j)): LAPACK's
  !> dgbtf2 written out, the same operations; at these sizes (kl <= 9) the BLAS calls
  !> of LAPACK's own cost more than the arithmetic (40 % of the fast model's build went
  !> to OpenBLAS's daxpy, dger and dtbsv on vectors of 1 to 19). info = j > 0: the
  !> first zero pivot.
  pure subroutine band_factor(n, kl, ab, pivots, info)
    integer, intent(in) :: n, kl
    real(real64), intent(inout) :: ab(3 * kl + 1, n)
    integer, intent(out) :: pivots(n), info
    integer :: kv, i, j, jp, ju, km, c, sft, r
    real(real64) :: big, t, ys
    info = 0
    kv = 2 * kl
    do j = kl + 2, min(kv, n)
      do i = kv - j + 2, kl
        ab(i, j) = 0
      end do
    end do
    ju = 1
    do j = 1, n
      if (j + kv <= n) ab(1:kl, j + kv) = 0
      km = min(kl, n - j)
      jp = 1
      big = abs(ab(kv + 1, j))
      do i = 2, km + 1
        if (abs(ab(kv + i, j)) > big) then
          big = abs(ab(kv + i, j))
          jp = i
        end if
      end do
      pivots(j) = jp + j - 1
      if (ab(kv + jp, j) /= 0) then
        ju = max(ju, min(j + kl + jp - 1, n))
        if (jp /= 1) then
          do sft = 0, ju - j
            t = ab(kv + jp - sft, j + sft)
            ab(kv + jp - sft, j + sft) = ab(kv + 1 - sft, j + sft)
            ab(kv + 1 - sft, j + sft) = t
          end do
        end if
        if (km > 0) then
          ab(kv + 2:kv + 1 + km, j) = ab(kv + 2:kv + 1 + km, j) / ab(kv + 1, j)
          do sft = 1, ju - j
            c = j + sft
            ys = ab(kv + 1 - sft, c)
            if (ys /= 0) then
              do r = 1, km
                ab(kv + 1 + r - sft, c) = ab(kv + 1 + r - sft, c) - ab(kv + 1 + r, j) * ys
              end do
            end if
          end do
        end if
      else if (info == 0) then
        info = j
      end if
    end do
  end subroutine band_factor


end module kcreep_rolling_solve
