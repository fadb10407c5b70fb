!> Exact creep-force curves: steady rolling with Coulomb friction on the
!> solved patch (kcreep_rolling_solve), for a list of creepages, with the
!> discretisation of kcreep's full adhesion (the backward scheme, the spin
!> slip at x + spin_shift dx), so that at small creepage the forces are
!> -f (xi, eta, phi) with kcreep's coefficients of the same grid.
!>
!> Points are solved in the order given, each started from the best (the
!> smallest ||F||) of the previous point's tractions, the secant through the
!> previous two, and the full-adhesion tractions of its creepage (when the
!> unit tractions are known, and they lie within the bounds or no other start
!> is close) projected onto the traction bound (solve_point). A caller's
!> rolling_state_t carries the set-up (FFT plans, the preconditioner's
!> factors) and the previous points with their operator products across
!> calls (a time integration calling once per step).
module kcreep_rolling_curve
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t, fail, exit_bad_input, exit_numerical
  use kcreep_strings, only: itoa, rtoa
  use kcreep_threads, only: team_size, enter_team, leave_team, solve_started, solve_ended, &
                            cells_per_thread_iterative
  use kcreep_patch, only: patch_t
  use kcreep_assembly, only: scheme_t, operator_table_t, build_operator_table, rigid_creepage
  use kcreep_fastsim_forces, only: fastsim_result_t
  use kcreep_creep_curve, only: creep_map_t
  use kcreep_rolling_solve, only: rolling_solver_t, rolling_options_t, rolling_info_t, create_rolling_solver, &
                                  destroy_rolling_solver, solve_rolling, rolling_residual, residual_of_product, &
                                  project_to_bounds, cell_stick, cell_slip, default_rolling_tolerance
  implicit none
  private
  public :: rolling_request_t, rolling_point_t, rolling_curve, default_rolling_tolerance, cell_stick, cell_slip
  public :: rolling_residual_of, rolling_state_t, prepare_rolling_state, release_rolling_state, solve_point, &
            check_rolling_input

  !> A start whose max |F_i| is within this fraction of max(mu pn) is good enough that the
  !> full adhesion (one more operator product) is not tried. Measured (the 20 x 20 circle's
  !> warm loop): the secant's start 1e-3 to 7e-3, the last solution's about 1e-2, the full
  !> adhesion's 1e-2 to 1e-1 there.
  real(real64), parameter :: accept_start = 1e-2_real64

  !> Newton steps after which a point counts as stalled and is solved along the creepage
  !> path instead (follow_path). Converging solves took at most 19 steps in 50,000 solves of
  !> the tests fast_forces, contact_table, rolling_contact, wheel_rail_rolling,
  !> rolling_input, unit_rolling_warm and fastsim_exact (95 % within 4).
  integer, parameter :: stall_newton = 30

  type :: rolling_request_t
    real(real64) :: mu = 0                        !< friction coefficient
    real(real64), allocatable :: creepages(:, :)  !< (3, n): (xi, eta, phi) of each point
    real(real64) :: tolerance = default_rolling_tolerance   !< max |F| / max(mu pn) to stop at
    logical :: maps = .false.                     !< keep the traction and stick/slip map of every point
    integer :: threads = 0                        !< &solver threads: 0 automatic (kcreep_threads), else as given
  end type rolling_request_t

  type :: rolling_point_t
    real(real64) :: creep(3) = 0
    type(fastsim_result_t) :: force               !< fx fy mz fn adhesion, as FASTSIM's
    type(rolling_info_t) :: info                  !< Newton steps, products, residual
    real(real64) :: seconds = 0
    integer :: threads = 1                        !< the team the point was solved on
  end type rolling_point_t

  !> What successive solves on one patch reuse (the caller keeps it, e.g. the C API's
  !> handle): the operator set-up (FFT plans, the row blocks) and the last two solutions
  !> per unit mu with their creepages per unit mu, the starts of the next point.
  type :: rolling_state_t
    logical :: ready = .false.
    integer :: mx = 0, my = 0, n = 0
    real(real64) :: key(9) = 0                    !< dx dy x0 y0 nu g spin_centre spin_shift
    logical, allocatable :: inside(:, :)
    type(patch_t) :: centred                      !< the patch with the spin centre at the origin
    real(real64), allocatable :: x(:), y(:)       !< its cell centres (the moment's arms)
    type(rolling_solver_t) :: solver
    real(real64), allocatable :: unit_w(:, :)     !< (2n, 3) rigid slip per unit xi, eta, phi
    integer :: kept = 0                           !< solutions kept (0 to 2, 1 the newest)
    real(real64) :: creep1(3, 2) = 0              !< their creepages / mu
    real(real64), allocatable :: p1(:, :)         !< (2n, 2) their tractions / mu
    real(real64), allocatable :: ap1(:, :)        !< (2n, 2) A p1: their residuals at a new creepage cost no product
  end type rolling_state_t

contains

  !> The exact rolling forces on patch (cells' spin about spin_centre) with
  !> pressure pn (mx, my) for every creepage of request.
  !> unit_traction: (2n, 3) full-adhesion tractions per unit xi, eta, phi
  !> (result%traction), used to start; absent or NaN: not used.
  !> state: what successive calls on the same patch reuse (the operator set-up
  !> and the last two solutions, the start of the next call); absent: a local one.
  subroutine rolling_curve(patch, scheme, nu, g, spin_centre, pn, request, points, maps, status, unit_traction, state)
    type(patch_t), intent(in) :: patch
    type(scheme_t), intent(in) :: scheme
    real(real64), intent(in) :: nu, g, spin_centre(2)
    real(real64), intent(in) :: pn(:, :)
    type(rolling_request_t), intent(in) :: request
    type(rolling_point_t), allocatable, intent(out) :: points(:)
    type(creep_map_t), allocatable, intent(out) :: maps(:)
    type(status_t), intent(inout) :: status
    real(real64), intent(in), optional :: unit_traction(:, :)
    type(rolling_state_t), intent(inout), optional, target :: state
    type(rolling_state_t), target :: local
    type(rolling_state_t), pointer :: st
    real(real64), allocatable :: bound(:), p(:)
    integer, allocatable :: cells(:)
    real(real64) :: da
    logical :: have_unit
    integer :: n, k, c, team, previous_team
    integer(int64) :: t0, t1, rate

    allocate (points(0), maps(0))
    call check_rolling_input(patch, scheme, pn, status)
    if (status%failed()) return
    if (present(state)) then
      st => state
    else
      st => local
    end if
    n = patch%n
    ! the curve runs on the team kcreep_threads chooses for its n cells
    ! (request%threads when positive), as every stage does; points%threads says
    team = team_size(request%threads, int(n, int64), cells_per_thread_iterative)
    call solve_started()
    call enter_team(team, previous_team)
    call prepare_rolling_state(patch, scheme, nu, g, spin_centre, st)
    allocate (bound(n), p(2 * n), cells(n))
    do k = 1, n
      bound(k) = request%mu * pn(patch%ix(k), patch%iy(k))
    end do
    have_unit = .false.
    if (present(unit_traction)) then
      if (size(unit_traction, 1) == 2 * n .and. size(unit_traction, 2) == 3) &
        have_unit = all(unit_traction == unit_traction)
    end if
    deallocate (points, maps)
    allocate (points(size(request%creepages, 2)))
    if (request%maps) then
      allocate (maps(size(points)))
    else
      allocate (maps(0))
    end if
    da = patch%dx * patch%dy
    do k = 1, size(points)
      call system_clock(t0, rate)
      points(k)%creep = request%creepages(:, k)
      points(k)%threads = team
      if (have_unit) then
        call solve_point(st, request%creepages(:, k), request%mu, bound, request%tolerance, p, cells, &
                         points(k)%info, unit_traction)
      else
        call solve_point(st, request%creepages(:, k), request%mu, bound, request%tolerance, p, cells, points(k)%info)
      end if
      if (.not. points(k)%info%converged) then
        call fail(status, exit_numerical, '&rolling: Newton did not converge at (xi, eta, phi) = ('// &
                  rtoa(points(k)%creep(1))//', '//rtoa(points(k)%creep(2))//', '//rtoa(points(k)%creep(3))// &
                  '): residual '//rtoa(points(k)%info%residual)//' after '//itoa(points(k)%info%newton)// &
                  ' steps (tolerance '//rtoa(request%tolerance)//')')
        exit
      end if
      associate (r => points(k)%force)
        r%fx = sum(p(1:n)) * da
        r%fy = sum(p(n + 1:2 * n)) * da
        r%mz = sum(st%x * p(n + 1:2 * n) - st%y * p(1:n)) * da
        r%fn = sum(pn, mask=patch%inside) * da
        r%adhesion = real(count(cells == cell_stick), real64) / max(n, 1)
      end associate
      if (request%maps) then
        allocate (maps(k)%px(patch%mx, patch%my), maps(k)%py(patch%mx, patch%my), maps(k)%state(patch%mx, patch%my))
        maps(k)%px = 0
        maps(k)%py = 0
        maps(k)%state = 0
        do c = 1, n
          maps(k)%px(patch%ix(c), patch%iy(c)) = p(c)
          maps(k)%py(patch%ix(c), patch%iy(c)) = p(n + c)
          maps(k)%state(patch%ix(c), patch%iy(c)) = cells(c)
        end do
      end if
      call system_clock(t1)
      points(k)%seconds = real(t1 - t0, real64) / rate
    end do
    if (.not. present(state)) call release_rolling_state(local)
    call leave_team(previous_team)
    call solve_ended()
  end subroutine rolling_curve

  !> The checks of rolling_curve's input (scheme, pressure grid and values).
  subroutine check_rolling_input(patch, scheme, pn, status)
    type(patch_t), intent(in) :: patch
    type(scheme_t), intent(in) :: scheme
    real(real64), intent(in) :: pn(:, :)
    type(status_t), intent(inout) :: status
    if (scheme%name /= 'backward') then
      call fail(status, exit_bad_input, '&rolling needs &solver scheme = ''backward'' (scheme = '''// &
                scheme%name//''')')
    else if (size(pn, 1) /= patch%mx .or. size(pn, 2) /= patch%my) then
      call fail(status, exit_bad_input, '&rolling: pressure of '//itoa(size(pn, 1))//' x '//itoa(size(pn, 2))// &
                ' cells on a grid of '//itoa(patch%mx)//' x '//itoa(patch%my))
    else if (any(pn(:, :) < 0 .or. pn /= pn)) then
      call fail(status, exit_bad_input, '&rolling: the pressure is negative or not a number at some cell')
    end if
  end subroutine check_rolling_input

  !> The state ready for (patch, scheme, nu, g, spin_centre): kept when it was set up for
  !> them (the solutions it holds stay as starts), else set up anew.
  subroutine prepare_rolling_state(patch, scheme, nu, g, spin_centre, state)
    type(patch_t), intent(in) :: patch
    type(scheme_t), intent(in) :: scheme
    real(real64), intent(in) :: nu, g, spin_centre(2)
    type(rolling_state_t), intent(inout) :: state
    type(operator_table_t) :: table
    real(real64) :: key(9)
    integer :: j
    key = [patch%dx, patch%dy, patch%x0, patch%y0, nu, g, spin_centre, scheme%spin_shift]
    if (state%ready) then
      if (state%mx == patch%mx .and. state%my == patch%my .and. state%n == patch%n .and. all(state%key == key)) then
        if (all(state%inside .eqv. patch%inside)) return
      end if
    end if
    call release_rolling_state(state)
    state%mx = patch%mx
    state%my = patch%my
    state%n = patch%n
    state%key = key
    state%inside = patch%inside
    ! the spin about spin_centre: the patch moved so that it is the origin
    state%centred = patch
    state%centred%x0 = patch%x0 - spin_centre(1)
    state%centred%y0 = patch%y0 - spin_centre(2)
    state%x = state%centred%cell_x(state%centred%ix)
    state%y = state%centred%cell_y(state%centred%iy)
    allocate (state%unit_w(2 * patch%n, 3), state%p1(2 * patch%n, 2), state%ap1(2 * patch%n, 2))
    do j = 1, 3
      call rigid_creepage(state%centred, scheme, j, state%unit_w(:, j))
    end do
    call build_operator_table(state%centred, scheme, nu, g, table)
    call create_rolling_solver(state%centred, table, state%solver)
    state%kept = 0
    state%ready = .true.
  end subroutine prepare_rolling_state

  !> Frees what the state holds (FFT plans); the state is empty after.
  subroutine release_rolling_state(state)
    type(rolling_state_t), intent(inout) :: state
    if (state%ready) call destroy_rolling_solver(state%solver)
    state = rolling_state_t()
  end subroutine release_rolling_state

  !> One point: creepage cr at friction mu, bounds mu pn (bound), solved from the caller's
  !> start when given, else from the best (smallest ||F||) of: the state's last solution,
  !> the secant through its last two (both scaled to mu: p(mu, c) = mu p(1, c/mu)), the
  !> projected full adhesion of cr (unit_traction) when it lies within the bounds or neither
  !> other start is within accept_start of max(mu pn), and zero when there is no other.
  !> The last solution's residual costs no operator product (the state keeps its A p,
  !> linear in p); the winner's product is handed to the solver. p, cells: the solution
  !> and its stick/slip cells; the state keeps it (per unit mu) for the next point.
  subroutine solve_point(state, cr, mu, bound, tolerance, p, cells, info, unit_traction, start)
    type(rolling_state_t), intent(inout) :: state
    real(real64), intent(in) :: cr(3), mu, bound(:), tolerance
    real(real64), intent(out) :: p(:)
    integer, intent(out) :: cells(:)
    type(rolling_info_t), intent(out) :: info
    real(real64), intent(in), optional :: unit_traction(:, :)
    real(real64), intent(in), optional :: start(:)   !< the start (tractions at mu)
    type(rolling_options_t) :: options
    real(real64), allocatable :: w(:), guess(:), f(:), q(:), ap(:), best_ap(:)
    real(real64) :: best, fnorm, fmax, fbest, c1(3), d(3), alpha, gscale
    integer :: n, starts
    n = state%n
    allocate (w(2 * n), guess(2 * n), f(2 * n), q(2 * n), ap(2 * n), best_ap(2 * n))
    w = cr(1) * state%unit_w(:, 1) + cr(2) * state%unit_w(:, 2) + cr(3) * state%unit_w(:, 3)
    c1 = cr / mu
    gscale = max(maxval(bound), tiny(1.0_real64))
    best = huge(1.0_real64)
    fbest = huge(1.0_real64)
    starts = 0
    p = 0
    best_ap = 0   ! A 0 = 0: the zero start's product
    options%tolerance = tolerance
    options%max_newton = stall_newton
    if (present(start)) then
      ! the caller's start is the start (the fast model's build: its neighbours' solutions
      ! extrapolated, the best start at 88 % of its points): no residual spent on others
      p = start
      call solve_rolling(state%solver, w, bound, options, p, cells, info, ap=ap)
    else
      if (state%kept >= 1) then
        guess = mu * state%p1(:, 1)
        if (all(guess(1:n)**2 + guess(n + 1:)**2 <= (bound + tolerance * gscale)**2)) then
          ! Newton's answer lies on or within the bounds to the stop test (its slip cells
          ! outside by about 1e-9 of max(mu pn)): taken as it is, with its A p
          ap = mu * state%ap1(:, 1)
          call residual_of_product(state%solver, w, bound, guess, ap, f, q, fnorm, fmax)
          call keep(guess)
        else
          ! the bounds moved (another pressure): projected, its product anew
          call project_to_bounds(bound, guess)
          call try(guess)
        end if
      end if
      if (state%kept >= 2) then
        d = state%creep1(:, 1) - state%creep1(:, 2)
        if (dot_product(d, d) > 0) then
          alpha = dot_product(c1 - state%creep1(:, 1), d) / dot_product(d, d)
          guess = mu * (state%p1(:, 1) + alpha * (state%p1(:, 1) - state%p1(:, 2)))
          call project_to_bounds(bound, guess)
          call try(guess)
        end if
      end if
      if (present(unit_traction)) then
        ! within the bounds everywhere, the full adhesion is the solution (the forces -f c
        ! exactly, which no other start reaches closer than the stop test)
        guess = cr(1) * unit_traction(:, 1) + cr(2) * unit_traction(:, 2) + cr(3) * unit_traction(:, 3)
        if (fbest > accept_start * gscale .or. all(guess(1:n)**2 + guess(n + 1:)**2 <= bound**2)) then
          call project_to_bounds(bound, guess)
          call try(guess)
        end if
      end if
      call solve_rolling(state%solver, w, bound, options, p, cells, info, start_ap=best_ap, ap=ap)
    end if
    info%products = info%products + starts
    if (.not. info%converged) call follow_path()
    if (info%converged) then
      state%p1(:, 2) = state%p1(:, 1)
      state%ap1(:, 2) = state%ap1(:, 1)
      state%creep1(:, 2) = state%creep1(:, 1)
      state%p1(:, 1) = p / mu
      state%ap1(:, 1) = ap / mu
      state%creep1(:, 1) = c1
      state%kept = min(state%kept + 1, 2)
    end if

  contains

    !> Newton stalls where the stick/slip set moves far between the start and the answer
    !> (damped steps of about a quarter: on an S1002 flange row of 3929 cells, where the
    !> spin moment changes sign, still 2e-5 after 60 steps). Then the creepage path from
    !> the state's last solution (or from zero creepage, whose answer is zero) in steps,
    !> each started from the one before: 4, 16, then 64 steps.
    subroutine follow_path()
      real(real64), allocatable :: path_p(:)
      real(real64) :: c0(3), ck(3)
      type(rolling_info_t) :: step_info
      type(rolling_options_t) :: defaults
      integer :: steps, k
      options%max_newton = defaults%max_newton
      c0 = 0
      if (state%kept >= 1) c0 = mu * state%creep1(:, 1)
      steps = 4
      do while (steps <= 64)
        path_p = 0 * p
        if (state%kept >= 1) path_p = mu * state%p1(:, 1)
        do k = 1, steps
          ck = c0 + (cr - c0) * real(k, real64) / steps
          w = ck(1) * state%unit_w(:, 1) + ck(2) * state%unit_w(:, 2) + ck(3) * state%unit_w(:, 3)
          call solve_rolling(state%solver, w, bound, options, path_p, cells, step_info, ap=ap)
          info%newton = info%newton + step_info%newton
          info%gmres = info%gmres + step_info%gmres
          info%products = info%products + step_info%products
          info%residual = step_info%residual
          if (.not. step_info%converged) exit
        end do
        if (step_info%converged) then
          p = path_p
          info%converged = .true.
          return
        end if
        steps = 4 * steps
      end do
    end subroutine follow_path

    !> The residual of a start (one product) and kept when the best so far.
    subroutine try(start)
      real(real64), intent(in) :: start(:)
      call rolling_residual(state%solver, w, bound, start, f, q, fnorm, fmax, ap)
      starts = starts + 1
      call keep(start)
    end subroutine try

    !> start (its A p in ap, its residual in fnorm, fmax) kept when the best so far.
    subroutine keep(start)
      real(real64), intent(in) :: start(:)
      if (fnorm < best) then
        best = fnorm
        fbest = fmax
        p = start
        best_ap = ap
      end if
    end subroutine keep

  end subroutine solve_point

  !> The residual max|F_i| / max(mu pn) of given tractions (2n: px, py per
  !> patch cell) in the discrete rolling problem of (patch, creep, mu, pn):
  !> how far another solver's answer (CONTACT's element file) is from
  !> satisfying the Coulomb conditions of this discretisation.
  function rolling_residual_of(patch, scheme, nu, g, spin_centre, pn, mu, creep, traction) result(residual)
    type(patch_t), intent(in) :: patch
    type(scheme_t), intent(in) :: scheme
    real(real64), intent(in) :: nu, g, spin_centre(2), pn(:, :), mu, creep(3), traction(:)
    real(real64) :: residual
    type(patch_t) :: centred
    type(operator_table_t) :: table
    type(rolling_solver_t) :: solver
    real(real64), allocatable :: unit_w(:), w(:), bound(:), f(:), q(:)
    real(real64) :: fnorm, fmax
    integer :: j, k, n, previous_team
    n = patch%n
    centred = patch
    centred%x0 = patch%x0 - spin_centre(1)
    centred%y0 = patch%y0 - spin_centre(2)
    allocate (unit_w(2 * n), w(2 * n), bound(n), f(2 * n), q(2 * n))
    w = 0
    do j = 1, 3
      call rigid_creepage(centred, scheme, j, unit_w)
      w = w + creep(j) * unit_w
    end do
    do k = 1, n
      bound(k) = mu * pn(patch%ix(k), patch%iy(k))
    end do
    call solve_started()
    call enter_team(team_size(0, int(n, int64), cells_per_thread_iterative), previous_team)
    call build_operator_table(centred, scheme, nu, g, table)
    call create_rolling_solver(centred, table, solver)
    call rolling_residual(solver, w, bound, traction, f, q, fnorm, fmax)
    residual = fmax / max(maxval(bound), tiny(1.0_real64))
    call destroy_rolling_solver(solver)
    call leave_team(previous_team)
    call solve_ended()
  end function rolling_residual_of

end module kcreep_rolling_curve
