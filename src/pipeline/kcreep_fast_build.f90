!> The fast force model of a patch (kcreep_fast_model) built from exact
!> steady-rolling solutions (kcreep_rolling_curve's solver, mu = 1) on its
!> grid and pressure, and its forces at any friction and creepage.
!>
!> Build (build_table): the linear coefficients f11, f22 from two
!> full-adhesion points set the normalisation; then every ray of the model's
!> grid (theta <= pi/2) is solved outward in s to the stop test
!> build_tolerance, each point started from its neighbours: this ray's
!> previous point plus the step the neighbouring ray (the previous one of the
!> ring, or the previous ring's first) took between the same two s (second
!> order in both directions; the pole ray: the secant along it,
!> kcreep_rolling_curve solve_point); its s = 1 node is the full-slip force,
!> -sum mu pn w/|w| dA. The model is the interpolant of these values; it is
!> kept with the pressure it was built for, and rebuilt for another.
!>
!> Patches of more than direct_build_cells solved cells (two levels): the table is
!> built on the patch coarsened by whole blocks of cells (coarsened_patch), and a
!> correction table of the difference, exact forces on the patch itself less
!> the coarse model's, on a coarser creepage grid (correction_sizes) is added.
!> The difference is the coarse grid's discretisation error (1-3 % of mu Fn),
!> smooth in the creepage, so few exact solves on the fine grid hold it.
module kcreep_fast_build
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t, fail, exit_numerical
  use kcreep_strings, only: itoa, rtoa
  use kcreep_patch, only: patch_t
  use kcreep_grid_transfer, only: coarsened_patch
  use kcreep_assembly, only: scheme_t
  use kcreep_rolling_solve, only: rolling_info_t
  use kcreep_fast_model, only: fast_model_t, fast_model_grid, fast_model_ray, fast_model_fit, fast_model_forces, &
                               fast_model_ring_stride, fast_model_fill_ring
  use kcreep_rolling_curve, only: rolling_state_t, prepare_rolling_state, release_rolling_state, solve_point, &
                                 check_rolling_input, default_rolling_tolerance
  implicit none
  private
  public :: fast_forces_t, build_fast_forces, fast_forces_of

  !> Stop test of the table's exact solves, max|F| / max(mu pn). Measured on the six
  !> patches of tests/api/test_fast_forces.py (300 points each): 95th percentile and
  !> largest distance from the exact forces the same at 1e-4, 1e-3 and 3e-3 (largest
  !> 0.41-1.01 % of mu Fn), at 1e-2 up to 0.96 % and 2.6 %; the build at 3e-3 took
  !> 0.51 of its time at 1e-4 (L-shaped mask).
  real(real64), parameter :: build_tolerance = 2e-3_real64

  !> The most solved cells a table is built on directly (a patch that mirrors in y solves
  !> half its rays: half its cells count); larger patches take two levels, the coarse table
  !> on at most coarse_table_cells cells. A direct build costs about 5 ms per solved cell on
  !> one thread (0.54 s at 316 cells mirrored; 1.85 s at a 678-cell mirrored crescent, 339
  !> solved); two levels 0.5-1.5 s at 632-1276 cells (scripts/bench_loop.py --builds,
  !> lab/fast_model_levels.py). Two levels cost accuracy where a force has a kink (the spin
  !> pole crossing the patch's edge), which the coarse grid puts elsewhere: at 1500 points
  !> the a/b = 2 ellipse of 632 cells 1.39 % of mu Fn (0.88 % direct), the crescent 0.86 %
  !> (0.62 %); a coarse table on 300 cells instead of 350 took a/b = 5 (1276 cells) from
  !> 1.20 to 1.69 %. lab/notes/rolling_speed.md holds the measurements.
  integer, parameter :: direct_build_cells = 300
  integer, parameter :: coarse_table_cells = 350

  !> The correction table's (nt, np, ns): theta 22.5 deg, lambda 22.5 deg, s 1/16; 735
  !> exact solves on the patch. lab/fast_model_levels.py (1500 random points a patch):
  !> circle, a/b = 5 and 0.2, L-shaped masks of 675-1276 cells within 95th percentile
  !> 0.11-0.17 %, largest 0.88-1.27 % of mu Fn of the exact forces; with s 1/8 (343
  !> solves) 0.15-0.35 % and 0.79-1.51 %, and on S1002 flange rows of 3391-4069 cells
  !> (200 points) 0.85-1.34 % and 2.5-3.3 % against 0.75-1.18 % and 1.6-2.2 % (a direct
  !> build: 0.57 % and 1.44 %, 40 s); the coarse table alone 1.0-1.9 % and 1.9-2.8 %.
  integer, parameter :: correction_sizes(3) = [4, 16, 16]

  type :: fast_forces_t
    type(fast_model_t) :: model
    !> the two levels' correction (fine less coarse); not ready: none
    type(fast_model_t) :: correction
    real(real64), allocatable :: pn(:)     !< the pressure per patch cell it was built for
    integer :: solves = 0                  !< exact points solved to build it
    integer :: newton = 0                  !< their Newton steps
    real(real64) :: seconds = 0            !< its build time
  end type fast_forces_t

contains

  !> The model of (patch, scheme, nu, g, spin_centre) with pressure pn (mx, my) in fast,
  !> kept when fast already holds it (same pressure; the state set up for the patch).
  subroutine build_fast_forces(patch, scheme, nu, g, spin_centre, pn, state, fast, status)
    type(patch_t), intent(in) :: patch
    type(scheme_t), intent(in) :: scheme
    real(real64), intent(in) :: nu, g, spin_centre(2), pn(:, :)
    type(rolling_state_t), intent(inout) :: state
    type(fast_forces_t), intent(inout) :: fast
    type(status_t), intent(inout) :: status
    type(patch_t) :: coarse
    type(rolling_state_t) :: coarse_state
    real(real64), allocatable :: bound(:), coarse_pn(:, :)
    integer :: c
    integer(int64) :: t0, t1, rate

    call check_rolling_input(patch, scheme, pn, status)
    if (status%failed()) return
    call prepare_rolling_state(patch, scheme, nu, g, spin_centre, state)
    bound = [(pn(patch%ix(c), patch%iy(c)), c=1, patch%n)]
    if (fast%model%ready .and. allocated(fast%pn)) then
      if (size(fast%pn) == patch%n) then
        if (all(fast%pn == bound)) return
      end if
    end if
    call system_clock(t0, rate)
    fast = fast_forces_t()
    if (solved_cells(state%centred, pn) > direct_build_cells) &
      call coarsened_patch(patch, pn, coarse_table_cells, coarse, coarse_pn)
    ! a patch whose blocks are mostly empty (scattered cells) is built directly
    if (coarse%n < coarse_table_cells / 4) then
      call build_table(state, pn, g, fast%model, fast, status)
    else
      call prepare_rolling_state(coarse, scheme, nu, g, spin_centre, coarse_state)
      call build_table(coarse_state, coarse_pn, g, fast%model, fast, status)
      call release_rolling_state(coarse_state)
      if (status%failed()) return
      call build_table(state, pn, g, fast%correction, fast, status, base=fast%model, sizes=correction_sizes)
    end if
    if (status%failed()) return
    fast%pn = bound
    call system_clock(t1)
    fast%seconds = real(t1 - t0, real64) / rate
  end subroutine build_fast_forces

  !> The cells a direct build solves: half the patch's when it mirrors in y.
  pure integer function solved_cells(centred, pn) result(cells)
    type(patch_t), intent(in) :: centred
    real(real64), intent(in) :: pn(:, :)
    cells = centred%n
    if (mirror_symmetric(centred, pn)) cells = (cells + 1) / 2
  end function solved_cells

  !> The table of model (grid sizes: the default resolution, or sizes) on the state's patch
  !> with pressure pn (mx, my): the exact forces at its nodes, less base's forces there when
  !> base is given (the correction of the two levels). Counts solves in fast.
  subroutine build_table(state, pn, g, model, fast, status, base, sizes)
    type(rolling_state_t), intent(inout) :: state
    real(real64), intent(in) :: pn(:, :), g
    type(fast_model_t), intent(inout) :: model
    type(fast_forces_t), intent(inout) :: fast
    type(status_t), intent(inout) :: status
    type(fast_model_t), intent(in), optional :: base
    integer, intent(in), optional :: sizes(3)
    real(real64), allocatable :: bound(:), p(:), x(:), y(:), v(:, :, :, :), creep(:, :), w(:), base_f(:, :)
    real(real64), allocatable :: last_ray(:, :), row_first(:, :), here(:, :)
    integer, allocatable :: cells(:)
    type(rolling_info_t) :: info
    real(real64) :: da, fn, area, tiny_creep, f11, f22, dir(3), k(3), a, cr(3), centre(2), covariance(2, 2)
    integer :: n, i, j, m, c, nt, np, ns, info_fit, jm, stride
    logical :: mirrored

    n = state%centred%n
    allocate (p(2 * n), cells(n), w(2 * n))
    bound = [(pn(state%centred%ix(c), state%centred%iy(c)), c=1, n)]
    x = state%centred%cell_x(state%centred%ix)
    y = state%centred%cell_y(state%centred%iy)
    da = state%centred%dx * state%centred%dy
    fn = sum(bound) * da
    area = n * da
    ! the linear coefficients at a creepage far inside full adhesion (|F| ~ 4e-4 Fn),
    ! solved to the default tolerance (build_tolerance would accept zero tractions there)
    tiny_creep = 1e-4_real64 * fn / (g * area)
    call point([tiny_creep, 0.0_real64, 0.0_real64], tight=.true.)
    if (status%failed()) return
    f11 = -sum(p(1:n)) * da / tiny_creep
    call point([0.0_real64, tiny_creep, 0.0_real64], tight=.true.)
    if (status%failed()) return
    f22 = -sum(p(n + 1:2 * n)) * da / tiny_creep
    k = [abs(f11), abs(f22), abs(f22) * sqrt(area / acos(-1.0_real64))] / max(fn, tiny(1.0_real64))
    if (.not. all(k > 0 .and. k < huge(1.0_real64))) k = 1 / sqrt(area)
    ! the patch's centre: its pressure's centroid
    centre = [sum(bound * x), sum(bound * y)] / max(sum(bound), tiny(1.0_real64))
    if (.not. sum(bound) > 0) centre = [sum(x), sum(y)] / n
    ! and its spread about that centre (the pole's reach, kcreep_fast_model)
    covariance(1, 1) = sum(bound * (x - centre(1))**2)
    covariance(2, 2) = sum(bound * (y - centre(2))**2)
    covariance(1, 2) = sum(bound * (x - centre(1)) * (y - centre(2)))
    covariance(2, 1) = covariance(1, 2)
    covariance = covariance / max(sum(bound), tiny(1.0_real64))
    call fast_model_grid(k, centre, covariance, model, sizes)
    mirrored = mirror_symmetric(state%centred, pn)
    nt = model%nt
    np = model%np
    ns = model%ns
    allocate (v(3, 0:nt, 0:np - 1, 1:ns), creep(3, ns - 1), last_ray(2 * n, ns - 1), row_first(2 * n, ns - 1), &
              here(2 * n, ns - 1), base_f(3, ns))
    base_f = 0
    do i = 0, nt
      stride = fast_model_ring_stride(model, i)
      ! the neighbour of a ring's first ray: the previous ring's first
      if (i > 0) last_ray = row_first
      do j = 0, np - 1
        if ((i == 0 .and. j > 0) .or. (i == nt .and. j >= np / 2) .or. mod(j, stride) /= 0) cycle
        ! a patch symmetric about y = 0: F(-z1, z2, z3) = (-Fx, Fy, Mz)(z1, z2, z3), the mirror
        ! image y -> -y with the creepage's oddness; ray j is ray np/2 - j mirrored
        jm = modulo(np / 2 - j, np)
        if (mirrored .and. jm < j) then
          v(1, i, j, :) = -v(1, i, jm, :)
          v(2:3, i, j, :) = v(2:3, i, jm, :)
          cycle
        end if
        call fast_model_ray(model, i, j, creep, dir)
        if (present(base)) then
          ! the base at the same creepages; s = 1 as |z| = 1e12 (s within 1e-12 of 1)
          call fast_model_forces(base, 1.0_real64, creep, base_f(:, 1:ns - 1))
          call fast_model_forces(base, 1.0_real64, reshape(1e12_real64 * dir, [3, 1]), base_f(:, ns:ns))
        end if
        state%kept = 0
        do m = 1, ns - 1
          ! start: the neighbouring ray's (last_ray's) step from s(m - 1) to s(m) added to
          ! this ray's point at s(m - 1); at m = 1 the neighbour's point itself; the pole
          ! ray (i = 0) has no neighbour
          if (i == 0) then
            call point(creep(:, m))
          else if (m == 1) then
            call point(creep(:, m), last_ray(:, m))
          else
            call point(creep(:, m), here(:, m - 1) + last_ray(:, m) - last_ray(:, m - 1))
          end if
          if (status%failed()) return
          v(:, i, j, m) = forces(p) - base_f(:, m)
          here(:, m) = p
        end do
        last_ray = here
        if (j == 0) row_first = here
        ! s = 1: full slip, the traction opposing the rigid slip everywhere
        w = dir(1) * state%unit_w(:, 1) + dir(2) * state%unit_w(:, 2) + dir(3) * state%unit_w(:, 3)
        do c = 1, n
          a = hypot(w(c), w(n + c))
          if (a > 0) then
            p(c) = -bound(c) * w(c) / a
            p(n + c) = -bound(c) * w(n + c) / a
          else
            p(c) = 0
            p(n + c) = 0
          end if
        end do
        v(:, i, j, ns) = forces(p) - base_f(:, ns)
      end do
      call fast_model_fill_ring(model, stride, v(:, i, :, :))
    end do
    do j = 1, np - 1
      v(:, 0, j, :) = v(:, 0, 0, :)
    end do
    do j = np / 2, np - 1
      v(:, nt, j, :) = -v(:, nt, j - np / 2, :)
    end do
    call fast_model_fit(model, v, info_fit)
    if (info_fit /= 0) call fail(status, exit_numerical, 'fast force model: the interpolant could not be '// &
                                 'fitted (LAPACK info '//itoa(info_fit)//')')

  contains

    !> The exact solution p at creepage cr (mu = 1).
    subroutine point(cr_in, start, tight)
      real(real64), intent(in) :: cr_in(3)
      real(real64), intent(in), optional :: start(:)
      logical, intent(in), optional :: tight
      real(real64) :: tolerance
      cr = cr_in
      tolerance = build_tolerance
      if (present(tight)) tolerance = default_rolling_tolerance
      call solve_point(state, cr, 1.0_real64, bound, tolerance, p, cells, info, start=start)
      fast%solves = fast%solves + 1
      fast%newton = fast%newton + info%newton
      if (.not. info%converged) call fail(status, exit_numerical, 'fast force model: Newton did not converge at '// &
                                          '(xi, eta, phi)/mu = ('//rtoa(cr(1))//', '//rtoa(cr(2))//', '// &
                                          rtoa(cr(3))//'): residual '//rtoa(info%residual))
    end subroutine point

    function forces(t) result(f)
      real(real64), intent(in) :: t(:)
      real(real64) :: f(3)
      f = [sum(t(1:n)), sum(t(n + 1:2 * n)), sum(x * t(n + 1:2 * n) - y * t(1:n))] * da
    end function forces

  end subroutine build_table

  !> Whether the patch (spin centre at the origin) and its pressure pn (mx, my) are their own
  !> mirror images in y -> -y (Hertzian ellipses about their centre): the grid's rows
  !> symmetric about y = 0 within 1e-9 of a cell, the same cells and pressures (to 1e-12 of
  !> the largest) in rows iy and my + 1 - iy. The backward scheme's operator and the rigid
  !> slip (xi - phi y, eta + phi x) keep the mirror (x, the rolling direction, is unchanged).
  pure logical function mirror_symmetric(centred, pn) result(yes)
    type(patch_t), intent(in) :: centred
    real(real64), intent(in) :: pn(:, :)
    integer :: iy, my
    my = centred%my
    yes = abs(2 * centred%y0 + (my - 1) * centred%dy) <= 1e-9_real64 * centred%dy
    if (.not. yes) return
    do iy = 1, my / 2
      yes = all(centred%inside(:, iy) .eqv. centred%inside(:, my + 1 - iy))
      if (yes) yes = all(abs(pn(:, iy) - pn(:, my + 1 - iy)) <= 1e-12_real64 * maxval(abs(pn)))
      if (.not. yes) return
    end do
  end function mirror_symmetric

  !> Forces (3, n) (Fx, Fy, Mz) of the creepages creep(3, n) at friction mu on the model.
  pure subroutine fast_forces_of(fast, mu, creep, force)
    type(fast_forces_t), intent(in) :: fast
    real(real64), intent(in) :: mu, creep(:, :)
    real(real64), intent(out) :: force(:, :)
    real(real64), allocatable :: correction(:, :)
    call fast_model_forces(fast%model, mu, creep, force)
    if (fast%correction%ready) then
      allocate (correction(3, size(creep, 2)))
      call fast_model_forces(fast%correction, mu, creep, correction)
      force = force + correction
    end if
  end subroutine fast_forces_of

end module kcreep_fast_build
