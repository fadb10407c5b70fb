!> Exact creep-force curves: steady rolling with Coulomb friction on the
!> solved patch (kcreep_rolling_solve), for a list of creepages, with the
!> discretisation of kcreep's full adhesion (the backward scheme, the spin
!> slip at x + spin_shift dx), so that at small creepage the forces are
!> -f (xi, eta, phi) with kcreep's coefficients of the same grid.
!>
!> Points are solved in the order given, each started from the better (the
!> smaller ||F||) of the previous point's tractions and the full-adhesion
!> tractions of its creepage (when the unit tractions are known) projected
!> onto the traction bound.
module kcreep_rolling_curve
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t, fail, exit_bad_input, exit_numerical
  use kcreep_strings, only: itoa, rtoa
  use kcreep_patch, only: patch_t
  use kcreep_assembly, only: scheme_t, operator_table_t, build_operator_table, rigid_creepage
  use kcreep_fastsim_forces, only: fastsim_result_t
  use kcreep_creep_curve, only: creep_map_t
  use kcreep_threads, only: team_size, enter_team, leave_team, solve_started, solve_ended, &
                            cells_per_thread_iterative
  use kcreep_rolling_solve, only: rolling_solver_t, rolling_options_t, rolling_info_t, create_rolling_solver, &
                                  destroy_rolling_solver, solve_rolling, rolling_residual, cell_stick, cell_slip, &
                                  default_rolling_tolerance
  implicit none
  private
  public :: rolling_request_t, rolling_point_t, rolling_curve, default_rolling_tolerance, cell_stick, cell_slip
  public :: rolling_residual_of

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

contains

  !> The exact rolling forces on patch (cells' spin about spin_centre) with
  !> pressure pn (mx, my) for every creepage of request.
  !> unit_traction: (2n, 3) full-adhesion tractions per unit xi, eta, phi
  !> (result%traction), used to start; absent or NaN: not used.
  !> The curve runs on the team kcreep_threads chooses for its n cells
  !> (request%threads when positive), as every stage does; points%threads says.
  subroutine rolling_curve(patch, scheme, nu, g, spin_centre, pn, request, points, maps, status, unit_traction)
    type(patch_t), intent(in) :: patch
    type(scheme_t), intent(in) :: scheme
    real(real64), intent(in) :: nu, g, spin_centre(2)
    real(real64), intent(in) :: pn(:, :)
    type(rolling_request_t), intent(in) :: request
    type(rolling_point_t), allocatable, intent(out) :: points(:)
    type(creep_map_t), allocatable, intent(out) :: maps(:)
    type(status_t), intent(inout) :: status
    real(real64), intent(in), optional :: unit_traction(:, :)
    type(patch_t) :: centred
    type(operator_table_t) :: table
    type(rolling_solver_t) :: solver
    type(rolling_options_t) :: options
    real(real64), allocatable :: unit_w(:, :), bound(:), p(:), w(:), guess(:), f(:), q(:), x(:), y(:)
    integer, allocatable :: state(:)
    real(real64) :: fnorm_warm, fnorm_adh, fmax, da
    logical :: have_unit, have_warm
    integer :: n, k, j, c, team, previous_team
    integer(int64) :: t0, t1, rate

    allocate (points(0), maps(0))
    if (scheme%name /= 'backward') then
      call fail(status, exit_bad_input, '&rolling needs &solver scheme = ''backward'' (scheme = '''// &
                scheme%name//''')')
      return
    end if
    if (size(pn, 1) /= patch%mx .or. size(pn, 2) /= patch%my) then
      call fail(status, exit_bad_input, '&rolling: pressure of '//itoa(size(pn, 1))//' x '//itoa(size(pn, 2))// &
                ' cells on a grid of '//itoa(patch%mx)//' x '//itoa(patch%my))
      return
    end if
    n = patch%n
    if (any(pn(:, :) < 0 .or. pn /= pn)) then
      call fail(status, exit_bad_input, '&rolling: the pressure is negative or not a number at some cell')
      return
    end if
    ! the spin about spin_centre: the patch moved so that it is the origin
    centred = patch
    centred%x0 = patch%x0 - spin_centre(1)
    centred%y0 = patch%y0 - spin_centre(2)
    allocate (unit_w(2 * n, 3), bound(n), p(2 * n), w(2 * n), guess(2 * n), f(2 * n), q(2 * n), state(n))
    do j = 1, 3
      call rigid_creepage(centred, scheme, j, unit_w(:, j))
    end do
    do k = 1, n
      bound(k) = request%mu * pn(patch%ix(k), patch%iy(k))
    end do
    have_unit = .false.
    if (present(unit_traction)) then
      if (size(unit_traction, 1) == 2 * n .and. size(unit_traction, 2) == 3) &
        have_unit = all(unit_traction == unit_traction)
    end if
    team = team_size(request%threads, int(n, int64), cells_per_thread_iterative)
    call solve_started()
    call enter_team(team, previous_team)
    call build_operator_table(centred, scheme, nu, g, table)
    call create_rolling_solver(centred, table, solver)
    options%tolerance = request%tolerance
    deallocate (points, maps)
    allocate (points(size(request%creepages, 2)))
    if (request%maps) then
      allocate (maps(size(points)))
    else
      allocate (maps(0))
    end if
    x = centred%cell_x(centred%ix)
    y = centred%cell_y(centred%iy)
    da = patch%dx * patch%dy
    have_warm = .false.
    p = 0
    do k = 1, size(points)
      call system_clock(t0, rate)
      points(k)%threads = team
      associate (cr => request%creepages(:, k))
        w = cr(1) * unit_w(:, 1) + cr(2) * unit_w(:, 2) + cr(3) * unit_w(:, 3)
        points(k)%creep = cr
        ! the start: the previous solution or the projected full adhesion, whichever is closer
        fnorm_warm = huge(1.0_real64)
        if (have_warm) call rolling_residual(solver, w, bound, p, f, q, fnorm_warm, fmax)
        if (have_unit) then
          guess = cr(1) * unit_traction(:, 1) + cr(2) * unit_traction(:, 2) + cr(3) * unit_traction(:, 3)
          call project(guess)
          call rolling_residual(solver, w, bound, guess, f, q, fnorm_adh, fmax)
          if (fnorm_adh < fnorm_warm) p = guess
        end if
      end associate
      call solve_rolling(solver, w, bound, options, p, state, points(k)%info)
      points(k)%info%products = points(k)%info%products + merge(1, 0, have_warm) + merge(1, 0, have_unit)
      have_warm = .true.
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
        r%mz = sum(x * p(n + 1:2 * n) - y * p(1:n)) * da
        r%fn = sum(pn, mask=patch%inside) * da
        r%adhesion = real(count(state == cell_stick), real64) / max(n, 1)
      end associate
      if (request%maps) then
        allocate (maps(k)%px(patch%mx, patch%my), maps(k)%py(patch%mx, patch%my), maps(k)%state(patch%mx, patch%my))
        maps(k)%px = 0
        maps(k)%py = 0
        maps(k)%state = 0
        do c = 1, n
          maps(k)%px(patch%ix(c), patch%iy(c)) = p(c)
          maps(k)%py(patch%ix(c), patch%iy(c)) = p(n + c)
          maps(k)%state(patch%ix(c), patch%iy(c)) = state(c)
        end do
      end if
      call system_clock(t1)
      points(k)%seconds = real(t1 - t0, real64) / rate
    end do
    call destroy_rolling_solver(solver)
    call leave_team(previous_team)
    call solve_ended()

  contains

    pure subroutine project(v)
      real(real64), intent(inout) :: v(:)
      real(real64) :: a
      integer :: i
      do i = 1, n
        a = hypot(v(i), v(n + i))
        if (a > bound(i) .and. a > 0) then
          v(i) = v(i) * bound(i) / a
          v(n + i) = v(n + i) * bound(i) / a
        end if
      end do
    end subroutine project

  end subroutine rolling_curve

  !> The residual max|F_i| / max(mu pn) of given tractions (2n: px, py per
  !> patch cell) in the discrete rolling problem of (patch, creep, mu, pn):
  !> how far another solver's answer (CONTACT's element file) is from
  !> satisfying the Coulomb conditions of this discretisation. On the
  !> automatic team of kcreep_threads.
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
