!> Unit tests of the rolling solver's warm starts across calls (kcreep_rolling_curve's
!> rolling_state_t), on the Hertzian circle of 20 x 20 cells (316), mu = 0.3:
!>  1. The same creepage again: the kept solution is the answer, found without a Newton
!>     step or an operator product (its residual from the kept A p).
!>  2. The same point per unit mu at another mu (creepage and mu both x 1.5): the kept
!>     solution scaled (p(mu, c) = mu p(1, c/mu), A p with it), no step, no product; the
!>     forces scale with mu to round-off.
!>  3. A slowly varying 20-step history, one call per step: every point equals a cold
!>     solve (a new state) within 1e-6 of mu Fn, with fewer operator products in all.
!>  4. A smaller pressure (the bounds move inside the kept solution): projected and
!>     solved, equal to the cold solve.
!> Tolerances: the stop test (max |F| <= 1e-7 max mu pn) leaves the forces within about
!> 4e-9 of mu Fn of the converged ones (docs/rolling.md); measured here: printed.
program test_rolling_warm
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t
  use kcreep_patch, only: patch_t, ellipse_patch
  use kcreep_assembly, only: scheme_t
  use kcreep_creep_curve, only: creep_map_t
  use kcreep_rolling_curve, only: rolling_request_t, rolling_point_t, rolling_curve, rolling_state_t, &
                                  release_rolling_state
  use unit_checks, only: checker_t
  implicit none
  type(checker_t) :: t
  type(patch_t) :: patch
  type(scheme_t) :: scheme
  type(status_t) :: status
  type(rolling_state_t) :: warm
  real(real64), allocatable :: pn(:, :)
  real(real64), parameter :: mu = 0.3_real64, c0(3) = [1e-3_real64, 5e-4_real64, 0.1_real64]
  real(real64) :: f1(3), f2(3), fc(3), gap, c(3)
  integer :: k, ix, iy, products_warm, products_cold
  type(rolling_point_t) :: point, cold_point

  call ellipse_patch(1.0_real64, 1.0_real64, 20, 20, patch, status)
  scheme%name = 'backward'
  allocate (pn(patch%mx, patch%my))
  pn = 0
  do iy = 1, patch%my
    do ix = 1, patch%mx
      if (patch%inside(ix, iy)) pn(ix, iy) = sqrt(max(0.0_real64, 1 - patch%cell_x(ix)**2 - patch%cell_y(iy)**2))
    end do
  end do
  pn = pn / (sum(pn) * patch%dx * patch%dy)
  call t%check(patch%n == 316, 'the circle has 316 cells')

  ! 1. the same creepage again
  point = solve(warm, mu, c0, pn)
  f1 = forces(point)
  point = solve(warm, mu, c0, pn)
  print '(a, i0, a, i0, a)', 'same creepage again: ', point%info%newton, ' Newton steps, ', &
    point%info%products, ' operator products'
  call t%check(point%info%converged .and. point%info%newton == 0 .and. point%info%products == 0, &
               'the same creepage again: the kept solution, no Newton step, no product')
  call t%check(maxval(abs(forces(point) - f1)) <= 1e-14_real64, 'the same creepage again: the same forces')

  ! 2. the same point per unit mu at 1.5 mu
  point = solve(warm, 1.5_real64 * mu, 1.5_real64 * c0, pn)
  f2 = forces(point)
  gap = maxval(abs(f2 / 1.5_real64 - f1)) / mu
  print '(a, i0, a, i0, a, es9.2, a)', 'same point per unit mu at 1.5 mu: ', point%info%newton, ' Newton steps, ', &
    point%info%products, ' products, forces / 1.5 off by ', gap, ' of mu Fn'
  call t%check(point%info%converged .and. point%info%newton == 0 .and. point%info%products == 0, &
               'mu and creepage x 1.5: the kept solution scaled, no Newton step, no product')
  call t%check(gap <= 1e-12_real64, 'mu and creepage x 1.5: the forces scale with mu')

  ! 3. a slowly varying history against cold solves
  call release_rolling_state(warm)
  products_warm = 0
  products_cold = 0
  gap = 0
  do k = 1, 20
    c = c0 * [cos(0.1_real64 * k), 1 + 0.05_real64 * k, sin(0.05_real64 * k) + 1]
    point = solve(warm, mu, c, pn)
    cold_point = cold(mu, c, pn)
    products_warm = products_warm + point%info%products
    products_cold = products_cold + cold_point%info%products
    gap = max(gap, maxval(abs(forces(point) - forces(cold_point))) / mu)
  end do
  print '(a, es9.2, a, i0, a, i0)', 'history of 20 steps: warm against cold ', gap, ' of mu Fn; products ', &
    products_warm, ' against ', products_cold
  call t%check(gap <= 1e-6_real64, 'a slowly varying history: warm equals cold within 1e-6 of mu Fn')
  call t%check(products_warm < products_cold, 'a slowly varying history: fewer products warm than cold')

  ! 4. the pressure smaller by 0.7: the kept solution lies outside the new bounds
  point = solve(warm, mu, c, 0.7_real64 * pn)
  cold_point = cold(mu, c, 0.7_real64 * pn)
  gap = maxval(abs(forces(point) - forces(cold_point))) / (0.7_real64 * mu)
  fc = forces(cold_point)
  print '(a, es9.2, a)', 'pressure x 0.7: warm against cold ', gap, ' of mu Fn'
  call t%check(point%info%converged .and. gap <= 1e-6_real64 .and. abs(fc(1)) > 0, &
               'a smaller pressure: projected, solved, equal to the cold solve')
  call release_rolling_state(warm)
  call t%finish()

contains

  !> One point on state (warm when state holds earlier solutions).
  function solve(state, mu_, creep, pressure) result(p)
    type(rolling_state_t), intent(inout) :: state
    real(real64), intent(in) :: mu_, creep(3), pressure(:, :)
    type(rolling_point_t) :: p
    type(rolling_request_t) :: request
    type(rolling_point_t), allocatable :: points(:)
    type(creep_map_t), allocatable :: maps(:)
    type(status_t) :: st
    request%mu = mu_
    request%creepages = reshape(creep, [3, 1])
    request%threads = 1
    call rolling_curve(patch, scheme, 0.25_real64, 1.0_real64, [0.0_real64, 0.0_real64], pressure, request, points, &
                       maps, st, state=state)
    if (st%failed()) then
      call t%check(.false., 'rolling_curve: '//st%message)
      error stop
    end if
    p = points(1)
  end function solve

  !> One point on a new state (a cold solve).
  function cold(mu_, creep, pressure) result(p)
    real(real64), intent(in) :: mu_, creep(3), pressure(:, :)
    type(rolling_point_t) :: p
    type(rolling_state_t) :: fresh
    p = solve(fresh, mu_, creep, pressure)
    call release_rolling_state(fresh)
  end function cold

  pure function forces(p) result(f)
    type(rolling_point_t), intent(in) :: p
    real(real64) :: f(3)
    f = [p%force%fx, p%force%fy, p%force%mz]
  end function forces

end program test_rolling_warm
