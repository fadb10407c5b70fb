!> Unit tests of FASTSIM with friction (kcreep_fastsim_forces), the pressure
!> models and the equivalent ellipses.
!>  1. Small creepage: with L = I/f the forces are -f11 xi, -f22 eta, -f23 phi
!>     (separate flexibilities also for combined creepage) to round-off, on a
!>     patch whose strips have two segments; all cells adhere.
!>  2. Large creepage: |F| = mu Fn, every cell slips, F along the creepage
!>     (weighted, aligned) or along (xi/L1, eta/L2) (separate).
!>  2b. The aligned rule: pure creepages as the separate rule (to round-off; with L3 < 0
!>     as the separate rule with |L3|), |p| <= mu pn in every cell, combined partial slip
!>     between the others.
!>  3. Pure spin on a Hertzian circle: |Fy| rises to a maximum and falls back
!>     toward 0; Mz tends to the full-slip moment -mu Int pn r dA.
!>  4. Grid convergence of partial-slip points on a rectangle (first order, measured).
!>  5. Paraboloidal pressure on an ellipse with Kalker's L1: FASTSIM's
!>     classical curve, strip by strip F = mu Fn_s (1 - (1 - u)^3).
!>  6. Equivalent ellipses: an elliptic mask gives back its own a, b and
!>     Kalker's coefficients; a rectangle's box ratio is its side ratio.
!> Tolerances: from the measured behaviour (numbers printed by the test).
program test_fastsim_forces
  use, intrinsic :: iso_fortran_env, only: real64, output_unit
  use kcreep_fastsim_forces
  use kcreep_pressure_models, only: hertz_pressure, paraboloid_pressure, strip_parabolic_pressure
  use kcreep_equivalent_ellipse, only: equivalent_ellipse_t, equivalent_ellipses, patch_moments, &
                                       ellipse_flexibilities, ellipse_box, ellipse_moments
  use kcreep_kalker_table, only: kalker_coefficients
  use unit_checks, only: checker_t
  implicit none
  type(checker_t) :: t
  real(real64), parameter :: pi = acos(-1.0_real64), mu = 0.3_real64

  call small_creepage()
  call large_creepage()
  call aligned_rule()
  call pure_spin()
  call convergence()
  call classical_curve()
  call ellipses()
  call t%finish()

contains

  !> Cells of an n x n grid over [-a, a] x [-b, b] whose centres are in the ellipse.
  subroutine ellipse_grid(a, b, n, inside, dx, dy, x0, y0)
    real(real64), intent(in) :: a, b
    integer, intent(in) :: n
    logical, allocatable, intent(out) :: inside(:, :)
    real(real64), intent(out) :: dx, dy, x0, y0
    integer :: ix, iy
    dx = 2 * a / n; dy = 2 * b / n
    x0 = -a + dx / 2; y0 = -b + dy / 2
    allocate (inside(n, n))
    do iy = 1, n
      do ix = 1, n
        inside(ix, iy) = ((x0 + (ix - 1) * dx) / a)**2 + ((y0 + (iy - 1) * dy) / b)**2 <= 1
      end do
    end do
  end subroutine ellipse_grid

  subroutine small_creepage()
    logical, allocatable :: inside(:, :)
    real(real64), allocatable :: pn(:, :)
    integer, allocatable :: state(:, :)
    real(real64) :: dx, dy, x0, y0, moments(2), f(3), flex(3), c_len, creep(3), expect(2)
    type(fastsim_result_t) :: r
    integer :: rule

    call ellipse_grid(2.0_real64, 1.0_real64, 40, inside, dx, dy, x0, y0)
    inside(18:22, :) = .false.          ! a gap across x: every strip has two segments
    pn = strip_parabolic_pressure(inside, dx, dy, 10.0_real64)
    allocate (state(40, 40))
    moments = mask_strip_integrals(inside, dx, dy, x0)
    f = [7.0_real64, 6.0_real64, 3.0_real64]      ! any positive coefficients
    flex = [moments(1) / f(1), moments(1) / f(2), moments(2) / f(3)]
    c_len = sqrt(count(inside) * dx * dy / pi)
    do rule = flexibility_weighted, flexibility_aligned
      call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, [1e-9_real64, 0.0_real64, 0.0_real64], &
                          c_len, rule, r, state=state)
      call t%check(abs(r%fx + f(1) * 1e-9_real64) <= 1e-12_real64 * f(1) * 1e-9_real64, 'slope f11')
      call t%check(r%adhesion == 1 .and. all(state(:, :) == merge(cell_adhesion, cell_outside, inside)), &
                   'all cells adhere at small creepage')
      call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, [0.0_real64, 1e-9_real64, 0.0_real64], &
                          c_len, rule, r)
      call t%check(abs(r%fy + f(2) * 1e-9_real64) <= 1e-12_real64 * f(2) * 1e-9_real64, 'slope f22')
      call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, [0.0_real64, 0.0_real64, 1e-9_real64], &
                          c_len, rule, r)
      call t%check(abs(r%fy + f(3) * 1e-9_real64) <= 1e-12_real64 * f(3) * 1e-9_real64, 'slope f23')
      call t%check(abs(r%fx) <= 1e-12_real64 * f(3) * 1e-9_real64, 'no Fx from spin on a y-symmetric patch')
      call t%check(abs(r%fn - 10) < 1e-12_real64, 'Fn is the load of the pressure model')
    end do
    ! combined: the separate flexibilities keep the linear theory, the weighted L does not
    creep = [0.0_real64, 2e-9_real64, -1e-9_real64 / c_len]
    expect = [-f(2) * creep(2) - f(3) * creep(3), 0.0_real64]
    call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, creep, c_len, flexibility_separate, r)
    call t%check(abs(r%fy - expect(1)) <= 1e-11_real64 * f(2) * 2e-9_real64, 'separate: linear combined Fy')
    call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, creep, c_len, flexibility_aligned, r, state=state)
    call t%check(abs(r%fy - expect(1)) <= 1e-11_real64 * f(2) * 2e-9_real64 .and. r%adhesion == 1, &
                 'aligned: linear combined Fy, all cells adhere')
    call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, creep, c_len, flexibility_weighted, r)
    write (output_unit, '(a, es11.3)') 'weighted L, combined small creepage: Fy / linear - 1 =', r%fy / expect(1) - 1
    call t%check(abs(r%fy / expect(1) - 1) > 1e-3_real64, 'weighted: combined Fy differs from the linear theory')
  end subroutine small_creepage

  subroutine large_creepage()
    logical, allocatable :: inside(:, :)
    real(real64), allocatable :: pn(:, :)
    real(real64) :: dx, dy, x0, y0, flex(3), c_len
    type(fastsim_result_t) :: r
    integer :: rule

    call ellipse_grid(1.5_real64, 1.0_real64, 30, inside, dx, dy, x0, y0)
    pn = hertz_pressure(inside, dx, dy, x0, y0, 1.5_real64, 1.0_real64, 5.0_real64)
    flex = [0.8_real64, 0.9_real64, 0.7_real64]
    c_len = sqrt(1.5_real64)
    do rule = flexibility_weighted, flexibility_aligned
      call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, [1e3_real64, 0.0_real64, 0.0_real64], &
                          c_len, rule, r)
      call t%check(abs(r%fx + mu * r%fn) <= 1e-12_real64 * mu * r%fn, 'full slip: Fx = -mu Fn')
      call t%check(r%adhesion == 0, 'full slip: no adhesion')
      call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, [1e3_real64, 1e3_real64, 0.0_real64], &
                          c_len, rule, r)
      ! (aligned: the slip directions of the cells differ by the elastic part, ~1e-6 rad: |F| short by ~1e-12)
      call t%check(abs(hypot(r%fx, r%fy) - mu * r%fn) <= merge(1e-10_real64, 1e-12_real64, &
                   rule == flexibility_aligned) * mu * r%fn, 'full slip: |F| = mu Fn')
      ! separate flexibilities turn the slip direction by L1/L2 (0.8/0.9); the weighted rule keeps it,
      ! the aligned rule's slip step restores it (up to the elastic part of the slip, about L / 1e3 here)
      if (rule == flexibility_weighted) then
        call t%check(abs(r%fx - r%fy) <= 1e-12_real64 * mu * r%fn, 'weighted: F along the creepage')
      else if (rule == flexibility_aligned) then
        write (output_unit, '(a, es10.2)') 'aligned, full slip (1e3, 1e3, 0): |Fx - Fy| / (mu Fn) =', &
          abs(r%fx - r%fy) / (mu * r%fn)
        call t%check(abs(r%fx - r%fy) <= 1e-3_real64 * mu * r%fn, 'aligned: F along the creepage')
        call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, [1e9_real64, 1e9_real64, 0.0_real64], &
                            c_len, rule, r)
        call t%check(abs(r%fx - r%fy) <= 1e-9_real64 * mu * r%fn, 'aligned: F along the creepage at 1e9')
        call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, [1e9_real64, -2e9_real64, 1e9_real64], &
                            c_len, rule, r)
        call t%check(hypot(r%fx, r%fy) <= mu * r%fn .and. r%adhesion == 0, &
                     'aligned: full slip with spin: |F| <= mu Fn, no adhesion')
      else
        call t%check(abs(r%fy / r%fx - flex(1) / flex(2)) <= 1e-12_real64, 'separate: F along (xi/L1, eta/L2)')
      end if
    end do
  end subroutine large_creepage

  !> The aligned rule against the separate one on a Hertzian ellipse in partial slip: pure
  !> creepages the same (to round-off: its slip step reduces to the scaling for one component
  !> or for spin alone); combined ones different; |p| <= mu pn in every cell (to round-off).
  subroutine aligned_rule()
    logical, allocatable :: inside(:, :)
    real(real64), allocatable :: pn(:, :), px(:, :), py(:, :)
    real(real64) :: dx, dy, x0, y0, flex(3), c_len, creep(3), excess
    type(fastsim_result_t) :: ra, rs
    integer :: k
    real(real64), parameter :: creeps(3, 6) = reshape([2e-3_real64, 0.0_real64, 0.0_real64, &
      0.0_real64, 2e-3_real64, 0.0_real64, 0.0_real64, 0.0_real64, 2e-3_real64, &
      4e-4_real64, 4e-4_real64, 0.0_real64, 0.0_real64, 4e-4_real64, -4e-4_real64, &
      -2e-4_real64, 6e-4_real64, 4e-4_real64], [3, 6])

    call ellipse_grid(1.5_real64, 1.0_real64, 40, inside, dx, dy, x0, y0)
    pn = hertz_pressure(inside, dx, dy, x0, y0, 1.5_real64, 1.0_real64, 1.0_real64)
    allocate (px(40, 40), py(40, 40))
    flex = [2e-3_real64, 2.6e-3_real64, 1.5e-3_real64]     ! L1 < L2, L3 below both: slip steps differ
    c_len = sqrt(1.5_real64)
    excess = 0
    do k = 1, 6
      creep = creeps(:, k)
      call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, creep, c_len, flexibility_aligned, ra, px, py)
      call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, creep, c_len, flexibility_separate, rs)
      excess = max(excess, maxval(hypot(px, py) - mu * pn, mask=inside) / (mu * maxval(pn)))
      write (output_unit, '(a, 3es10.2, a, 2f9.5, a, 2f9.5, a, f6.3)') 'aligned / separate at', creep, &
        ': F/(mu Fn) =', ra%fx / (mu * ra%fn), ra%fy / (mu * ra%fn), ' /', rs%fx / (mu * rs%fn), &
        rs%fy / (mu * rs%fn), ', adhesion', ra%adhesion
      if (k <= 3) then
        call t%check(abs(ra%fx - rs%fx) + abs(ra%fy - rs%fy) <= 1e-13_real64 * mu * ra%fn .and. &
                     ra%adhesion == rs%adhesion, 'aligned: a pure creepage as the separate rule')
      else
        call t%check(hypot(ra%fx - rs%fx, ra%fy - rs%fy) > 1e-3_real64 * mu * ra%fn .and. &
                     ra%adhesion > 0 .and. ra%adhesion < 1, 'aligned: combined partial slip differs from separate')
      end if
    end do
    call t%check(excess <= 1e-14_real64, 'aligned: |p| <= mu pn in every cell')
    ! L3 < 0 (f23 and the strip integral I3 of opposite sign): pure spin as plain FASTSIM with
    ! |L3| on both spin terms (a negative L3 on one term and |L3| on the other worked against
    ! each other: 13.8-19.4 % of mu Fn worse than plain FASTSIM on an L shape, fastsim_plain)
    do k = 1, 2
      creep = [0.0_real64, 0.0_real64, (3 - 2 * k) * 2e-3_real64]
      call fastsim_forces(inside, pn, dx, dy, x0, y0, [flex(1:2), -flex(3)], mu, creep, c_len, &
                          flexibility_aligned, ra)
      call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, creep, c_len, flexibility_separate, rs)
      call t%check(abs(ra%fx - rs%fx) + abs(ra%fy - rs%fy) <= 1e-13_real64 * mu * ra%fn .and. &
                   ra%adhesion == rs%adhesion, 'aligned, L3 < 0: pure spin as plain FASTSIM with |L3|')
    end do
  end subroutine aligned_rule

  subroutine pure_spin()
    logical, allocatable :: inside(:, :)
    real(real64), allocatable :: pn(:, :)
    real(real64) :: dx, dy, x0, y0, flex(3), c(3), phi, fy_max, m_slip, x, y
    type(fastsim_result_t) :: r
    integer :: k, ix, iy, k_max
    logical :: opposed

    call ellipse_grid(1.0_real64, 1.0_real64, 80, inside, dx, dy, x0, y0)
    pn = hertz_pressure(inside, dx, dy, x0, y0, 1.0_real64, 1.0_real64, 1.0_real64)
    c = kalker_coefficients(1.0_real64, 0.25_real64)
    flex = ellipse_flexibilities(1.0_real64, 1.0_real64, c, 1.0_real64)
    m_slip = 0
    do iy = 1, 80
      do ix = 1, 80
        x = x0 + (ix - 1) * dx; y = y0 + (iy - 1) * dy
        if (inside(ix, iy)) m_slip = m_slip + mu * pn(ix, iy) * hypot(x, y) * dx * dy
      end do
    end do
    fy_max = 0; k_max = 0
    opposed = .true.
    do k = 0, 40
      phi = 1e-3_real64 * 10**(k / 8.0_real64)      ! 1e-3 .. 1e2 (phi c / (mu L3 Fn) spans 4e-4 .. 40)
      call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, [0.0_real64, 0.0_real64, phi], &
                          1.0_real64, flexibility_weighted, r)
      opposed = opposed .and. r%fy < 0 .and. r%mz < 0
      if (-r%fy > fy_max) then
        fy_max = -r%fy
        k_max = k
      end if
    end do
    write (output_unit, '(a, f8.4, a, es10.2, a, f8.4, a, f8.4)') 'pure spin: max |Fy|/(mu Fn) =', &
      fy_max / (mu * r%fn), ' at phi =', 1e-3_real64 * 10**(k_max / 8.0_real64), &
      '; at phi = 100: Fy/(mu Fn) =', r%fy / (mu * r%fn), ', Mz / full-slip moment =', -r%mz / m_slip
    call t%check(opposed, 'spin: Fy and Mz oppose the spin at every phi')
    call t%check(k_max > 0 .and. k_max < 40, 'spin: |Fy| has an interior maximum')
    ! measured: |Fy|/(mu Fn) 0.035 at phi = 100 (80 x 80 grid), Mz 0.996 of the full-slip moment
    call t%check(-r%fy < 0.1_real64 * fy_max, 'spin: Fy falls back toward 0 at large spin')
    call t%check(abs(-r%mz / m_slip - 1) < 0.01_real64, 'spin: Mz tends to -mu Int pn r dA')
  end subroutine pure_spin

  !> Partial-slip points on a 2 x 1 rectangle (no staircase edge, so that only the
  !> marching is refined) with the parabolic strip pressure, grids 16 x 8 .. 256 x 128.
  subroutine convergence()
    logical, allocatable :: inside(:, :)
    real(real64), allocatable :: pn(:, :)
    real(real64) :: dx, dy, x0, y0, flex(3), f(5, 3), fa(5, 3), order(3), c_len
    real(real64), parameter :: creeps(3, 3) = reshape([0.1_real64, 0.0_real64, 0.0_real64, &
      0.0_real64, 0.3_real64, 0.3_real64, 0.2_real64, -0.3_real64, 0.4_real64], [3, 3])
    type(fastsim_result_t) :: r
    integer :: k, n, j

    flex = [0.9_real64, 1.0_real64, 0.7_real64]
    c_len = sqrt(2 / pi)
    do k = 1, 5
      n = 16 * 2**(k - 1)
      if (allocated(inside)) deallocate (inside)
      allocate (inside(n, n / 2))
      inside = .true.
      dx = 2.0_real64 / n; dy = dx
      x0 = -1 + dx / 2; y0 = -0.5_real64 + dy / 2
      pn = strip_parabolic_pressure(inside, dx, dy, 1.0_real64)
      do j = 1, 3
        call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, creeps(:, j), c_len, &
                            flexibility_separate, r)
        f(k, j) = hypot(r%fx, r%fy) / (mu * r%fn)
        call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, creeps(:, j), c_len, &
                            flexibility_aligned, r)
        fa(k, j) = hypot(r%fx, r%fy) / (mu * r%fn)
      end do
    end do
    do j = 1, 3
      order(j) = log(abs(f(4, j) - f(3, j)) / abs(f(5, j) - f(4, j))) / log(2.0_real64)
      write (output_unit, '(a, i1, a, 5f10.6, a, f6.2)') 'convergence point ', j, ': |F|/(mu Fn) =', f(:, j), &
        '  order (64-128-256) =', order(j)
      ! measured: pure xi is grid-independent to 2e-5 (cell averages of a linear adhesion traction and a
      ! parabolic bound are exact; only the cell where slip starts is approximate); the combined points
      ! converge at first order (0.93, 1.02), 128 -> 256 changes |F| by 5e-4 of mu Fn or less
      call t%check(abs(f(5, j) - f(4, j)) < 2e-3_real64, 'convergence: 128 -> 256 changes |F| by < 0.2 % of mu Fn')
      if (j == 1) then
        call t%check(maxval(abs(f(:, j) - f(5, j))) < 1e-4_real64, 'convergence: pure xi grid-independent')
      else
        call t%check(order(j) > 0.8_real64 .and. order(j) < 1.3_real64, 'convergence: first order')
      end if
      ! the aligned rule's slip step starts from the separate predictor's cell: one more O(dx) term
      order(j) = log(abs(fa(4, j) - fa(3, j)) / abs(fa(5, j) - fa(4, j))) / log(2.0_real64)
      write (output_unit, '(a, i1, a, 5f10.6, a, f6.2)') 'aligned, point ', j, ':       |F|/(mu Fn) =', fa(:, j), &
        '  order (64-128-256) =', order(j)
      call t%check(abs(fa(5, j) - fa(4, j)) < 2e-3_real64, 'aligned convergence: 128 -> 256 < 0.2 % of mu Fn')
      if (j > 1) call t%check(order(j) > 0.8_real64 .and. order(j) < 1.3_real64, 'aligned convergence: first order')
    end do
  end subroutine convergence

  !> Kalker's FASTSIM with the paraboloidal bound: per strip of half length s,
  !> F_s = mu Fn_s (1 - (1 - u)^3), u = min(1, xi / (2 s L mu p0 / a^2)).
  subroutine classical_curve()
    logical, allocatable :: inside(:, :)
    real(real64), allocatable :: pn(:, :)
    real(real64), parameter :: a = 1.0_real64, b = 1.6_real64, fn = 2.0_real64
    real(real64) :: dx, dy, x0, y0, flex(3), c(3), xi, p0, q, s, u, y, exact, worst
    type(fastsim_result_t) :: r
    integer :: k, j, nq

    call ellipse_grid(a, b, 200, inside, dx, dy, x0, y0)
    pn = paraboloid_pressure(inside, dx, dy, x0, y0, a, b, fn)
    c = kalker_coefficients(a / b, 0.25_real64)
    flex = ellipse_flexibilities(a, b, c, 1.0_real64)
    p0 = 2 * fn / (pi * a * b)
    q = mu * p0 / a**2
    worst = 0
    do k = 1, 8
      xi = 0.05_real64 * k**2 * mu * fn / (8 * a**2 * b / 3 / flex(1))   ! 0.05 .. 3.2 x mu Fn / f11
      nq = 20000
      exact = 0
      do j = 1, nq                                  ! midpoint rule over y
        y = -b + (j - 0.5_real64) * 2 * b / nq
        s = a * sqrt(1 - (y / b)**2)
        u = min(1.0_real64, xi / (flex(1) * q) / (2 * s))
        exact = exact + q * 4 * s**3 / 3 * (1 - (1 - u)**3) * 2 * b / nq
      end do
      call fastsim_forces(inside, pn, dx, dy, x0, y0, flex, mu, [xi, 0.0_real64, 0.0_real64], &
                          sqrt(a * b), flexibility_weighted, r)
      worst = max(worst, abs(-r%fx - exact) / (mu * fn))
    end do
    write (output_unit, '(a, es10.2)') 'classical FASTSIM curve (200 x 200): largest |F - F_exact|/(mu Fn) =', worst
    ! measured 1.0e-3 on 200 x 200 (staircase edge cells)
    call t%check(worst < 3e-3_real64, 'paraboloid + Kalker L1: the classical FASTSIM curve')
  end subroutine classical_curve

  subroutine ellipses()
    logical, allocatable :: inside(:, :)
    real(real64) :: dx, dy, x0, y0, m(7), c(3)
    type(equivalent_ellipse_t) :: e(2)

    call ellipse_grid(3.0_real64, 1.5_real64, 200, inside, dx, dy, x0, y0)
    e = equivalent_ellipses(inside, dx, dy, x0, y0, 0.25_real64, 1.0_real64)
    c = kalker_coefficients(2.0_real64, 0.25_real64)
    write (output_unit, '(a, 2(2f9.5, 2x))') 'ellipse 3 x 1.5, 200 x 200: box (a, b), moments (a, b) =', &
      e(1)%semi_a, e(1)%semi_b, e(2)%semi_a, e(2)%semi_b
    ! staircase of 200 x 200 cells: area and moments within 0.1 % (measured 2e-4)
    call t%check(abs(e(ellipse_box)%semi_a / 3 - 1) < 1e-3_real64 .and. abs(e(ellipse_box)%semi_b / 1.5_real64 - 1) &
                 < 1e-3_real64, 'box ellipse of an ellipse is itself')
    call t%check(abs(e(ellipse_moments)%semi_a / 3 - 1) < 1e-3_real64 .and. &
                 abs(e(ellipse_moments)%semi_b / 1.5_real64 - 1) < 1e-3_real64, 'moment ellipse of an ellipse is itself')
    call t%check(all(abs(e(ellipse_moments)%c / c - 1) < 2e-3_real64), 'ellipse: Kalker coefficients at a/b = 2')
    ! a 4 x 1 rectangle of cells
    deallocate (inside)
    allocate (inside(40, 10))
    inside = .true.
    m = patch_moments(inside, 0.1_real64, 0.1_real64, 0.0_real64, 0.0_real64)
    call t%check(abs(m(1) - 4) < 1e-12_real64 .and. abs(m(6) - 4) < 1e-12_real64 .and. abs(m(7) - 1) < 1e-12_real64, &
                 'rectangle: area and bounding box')
    call t%check(abs(m(4) - 4 * 4**2 / 12.0_real64) < 1e-12_real64 .and. abs(m(5) - 4 / 12.0_real64) < 1e-12_real64, &
                 'rectangle: second moments exact over the cells')
    e = equivalent_ellipses(inside, 0.1_real64, 0.1_real64, 0.0_real64, 0.0_real64, 0.25_real64, 1.0_real64)
    call t%check(abs(e(ellipse_box)%semi_a / e(ellipse_box)%semi_b - 4) < 1e-12_real64 .and. &
                 abs(pi * e(ellipse_box)%semi_a * e(ellipse_box)%semi_b - 4) < 1e-12_real64, &
                 'rectangle: box ellipse a/b = 4, same area')
    call t%check(abs(e(ellipse_moments)%semi_a / e(ellipse_moments)%semi_b - 4) < 1e-12_real64, &
                 'rectangle: moment ellipse a/b = 4 too')
  end subroutine ellipses

end program test_fastsim_forces
