!> Unit tests of the normal contact problem on the grid.
!> Argument 1: the folder of the CONTACT samples (kidney_nu25, twin_nu25).
!>  1. Influence coefficients: the centre of a square cell (closed form
!>     8 a asinh 1), far field (point load, relative error O((a/R)^2)).
!>  2. The FFT product equals the direct double sum (to round-off).
!>  3. Hertz closed forms: the relations between a, b, p0, delta and the
!>     curvatures hold with K and E from an independent quadrature.
!>  4. Hertz on the grid, force prescribed: errors below bounds taken from the
!>     measured convergence table (docs/normal.md) with ~30 % headroom.
!>  5. Approach prescribed = force prescribed (same solution); a start
!>     pressure near the solution gives the same solution in fewer steps.
!>  6. CONTACT's kidney and twin samples: contact area cell for cell, FN and
!>     PMAX to the printed four digits.
!>  7. Gap file and CONTACT .inp readers: good input and each refusal.
!>  8. Resampling a gap on another grid (error control's finer geometry):
!>     quadratics exactly, also half a cell beyond the outermost centres;
!>     cells outside the potential contact stay outside.
program test_normal
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t
  use kcreep_normal_influence, only: rectangle_integral, normal_cell_coefficient, normal_offset_table, &
                                     compliance_from_g_nu, compliance_from_e_nu, combined_g_nu_from_e_nu
  use kcreep_normal_solve, only: normal_options_t, normal_result_t, solve_normal, normal_operator_t, &
                                 create_normal_operator, apply_normal_operator, destroy_normal_operator
  use kcreep_hertz, only: hertz_t, hertz_from_force, hertz_from_approach
  use kcreep_gap, only: gap_t, polynomial_gap_t, gap_from_polynomial, auto_grid, gap_resampled, outside_gap
  use kcreep_gap_file, only: parse_gap_text
  use kcreep_contact_input, only: contact_input_t, read_contact_input
  use kcreep_contact_reader, only: contact_case_t, read_contact_case
  use unit_checks, only: checker_t
  use kcreep_strings, only: itoa
  implicit none
  type(checker_t) :: t
  real(real64), parameter :: pi = acos(-1.0_real64)
  character(len=1024) :: samples

  call get_command_argument(1, samples)
  call test_influence()
  call test_fft_product()
  call test_hertz_formulas()
  call test_hertz_grid()
  call test_approach_equals_force()
  call test_rough_start()
  call test_gap_resampled()
  if (len_trim(samples) > 0) then
    call test_contact_sample('kidney_nu25')
    call test_contact_sample('twin_nu25')
  else
    call t%check(.false., 'CONTACT samples folder given as argument 1')
  end if
  call test_gap_file()
  call test_contact_inp_quadratic()
  call test_auto_grid()
  call t%finish()

contains

  subroutine test_influence()
    real(real64) :: a, s, r, x, y, g, nu
    a = 0.3_real64
    s = rectangle_integral(0.0_real64, 0.0_real64, a, a)
    call t%check(abs(s - 8 * a * asinh(1.0_real64)) <= 1e-14_real64 * s, 'square cell at its centre: 8 a asinh(1)')
    x = 150 * a
    y = -90 * a
    r = hypot(x, y)
    s = rectangle_integral(x, y, a, 0.5_real64 * a)
    call t%check(abs(s / (2 * a * a / r) - 1) < 1e-4_real64, 'far field: point load 4ab/r')
    call t%check(rectangle_integral(0.7_real64, -0.2_real64, a, 0.2_real64) == &
                 rectangle_integral(-0.7_real64, 0.2_real64, a, 0.2_real64), 'even in x and y')
    ! 1/E* of two identical bodies: (1 - nu)/G, also from E and nu
    g = 82000
    nu = 0.28_real64
    call t%check(abs(compliance_from_e_nu(2 * g * (1 + nu), nu, 2 * g * (1 + nu), nu) / compliance_from_g_nu(g, nu) - 1) &
                 < 1e-14_real64, 'combined compliance: E, nu per body = (1 - nu)/G for identical bodies')
    call combined_g_nu_from_e_nu(210e3_real64, 0.3_real64, 70e3_real64, 0.33_real64, g, nu)
    ! quasi-identity: (1 - nu)/G of the combined constants is the exact 1/E*
    call t%check(abs(compliance_from_g_nu(g, nu) / compliance_from_e_nu(210e3_real64, 0.3_real64, 70e3_real64, &
                 0.33_real64) - 1) < 1e-14_real64, 'combined G, nu give the exact 1/E* of dissimilar bodies')
    call t%check(abs(normal_cell_coefficient(0.0_real64, 0.0_real64, 2 * a, 2 * a, 2.0_real64) - &
                 2 / pi * 8 * a * asinh(1.0_real64)) < 1e-14_real64, 'cell coefficient = c/pi x integral')
  end subroutine test_influence

  subroutine test_fft_product()
    integer, parameter :: mx = 7, my = 5
    real(real64) :: p(mx, my), u(mx, my), d(mx, my)
    real(real64), allocatable :: table(:, :)
    type(normal_operator_t) :: op
    integer :: i, j, k, l
    call random_seed_fixed()
    call random_number(p)
    call normal_offset_table(mx, my, 0.3_real64, 0.2_real64, 1.5_real64, table)
    do j = 1, my
      do i = 1, mx
        d(i, j) = 0
        do l = 1, my
          do k = 1, mx
            d(i, j) = d(i, j) + table(abs(i - k), abs(j - l)) * p(k, l)
          end do
        end do
      end do
    end do
    call create_normal_operator(mx, my, 0.3_real64, 0.2_real64, 1.5_real64, 0, op)
    call apply_normal_operator(op, p, u)
    call destroy_normal_operator(op)
    ! round-off of a 14 x 10 FFT pair: ~1e-15 relative; 1e-13 is generous
    call t%check(maxval(abs(u - d)) <= 1e-13_real64 * maxval(abs(d)), 'FFT product = direct sum (7 x 5 grid)')
  end subroutine test_fft_product

  subroutine random_seed_fixed()
    integer :: n
    integer, allocatable :: seed(:)
    call random_seed(size=n)
    allocate (seed(n))
    seed = 20260
    call random_seed(put=seed)
  end subroutine random_seed_fixed

  !> K(e), E(e) by Gauss-Chebyshev-free midpoint quadrature on the angle (smooth periodic: exponential convergence).
  subroutine elliptic_quadrature(e2, kk, ee)
    real(real64), intent(in) :: e2
    real(real64), intent(out) :: kk, ee
    integer, parameter :: n = 4000
    integer :: i
    real(real64) :: th, s
    kk = 0
    ee = 0
    do i = 1, n
      th = (i - 0.5_real64) * (pi / 2) / n
      s = 1 - e2 * sin(th)**2
      kk = kk + 1 / sqrt(s)
      ee = ee + sqrt(s)
    end do
    kk = kk * (pi / 2) / n
    ee = ee * (pi / 2) / n
  end subroutine elliptic_quadrature

  subroutine test_hertz_formulas()
    real(real64) :: ratios(4) = [1.0_real64, 3.0_real64, 10.0_real64, 0.1_real64]
    type(hertz_t) :: hz, h2
    real(real64) :: acurv, bcurv, c, major, minor, e2, kk, ee, amin, bmax
    integer :: i
    logical :: ok
    c = 1.0_real64 / 170000
    ok = .true.
    do i = 1, size(ratios)
      acurv = 1 / (2 * 0.5_real64 * ratios(i))
      bcurv = 1 / (2 * 0.5_real64)
      hz = hertz_from_force(acurv, bcurv, c, 1000.0_real64)
      major = max(hz%a, hz%b)
      minor = min(hz%a, hz%b)
      amin = min(acurv, bcurv)
      bmax = max(acurv, bcurv)
      e2 = 1 - (minor / major)**2
      call elliptic_quadrature(e2, kk, ee)
      if (e2 > 1e-12_real64) then
        ok = ok .and. abs(c * hz%p0 * minor * (kk - ee) / (major**2 * e2) / amin - 1) < 1e-10_real64
        ok = ok .and. abs(c * hz%p0 * minor * (ee * major**2 / minor**2 - kk) / (major**2 * e2) / bmax - 1) < 1e-10_real64
      else
        ! sphere: a^3 = 3 F R / (4 E*)
        ok = ok .and. abs(hz%a**3 / (3 * 1000 * 0.5_real64 * c / 4) - 1) < 1e-12_real64
      end if
      ok = ok .and. abs(hz%approach / (c * hz%p0 * minor * kk) - 1) < 1e-10_real64
      ok = ok .and. abs(hz%fn / (2 * pi * hz%a * hz%b * hz%p0 / 3) - 1) < 1e-14_real64
      h2 = hertz_from_approach(acurv, bcurv, c, hz%approach)
      ok = ok .and. abs(h2%fn / hz%fn - 1) < 1e-12_real64 .and. abs(h2%a / hz%a - 1) < 1e-12_real64
    end do
    ! (tolerances: the bisection for b/a stops at 4 eps; quadrature error of K, E is ~1e-15)
    call t%check(ok, 'Hertz: curvatures, approach and force from K and E by quadrature (1e-10)')
    hz = hertz_from_force(0.1_real64, 1.0_real64, c, 1.0_real64)
    h2 = hertz_from_force(1.0_real64, 0.1_real64, c, 1.0_real64)
    call t%check(abs(hz%a - h2%b) < 1e-15_real64 * hz%a .and. abs(hz%b - h2%a) < 1e-15_real64 * hz%a, &
                 'Hertz: swapping the curvatures swaps the axes')
  end subroutine test_hertz_formulas

  !> Solve Hertz's problem with n cells across each axis of the contact ellipse.
  subroutine hertz_on_grid(ratio, n, hz, res, e_area, e_a, e_b)
    real(real64), intent(in) :: ratio
    integer, intent(in) :: n
    type(hertz_t), intent(out) :: hz
    type(normal_result_t), intent(out) :: res
    real(real64), intent(out) :: e_area, e_a, e_b
    type(polynomial_gap_t) :: poly
    type(gap_t) :: gap
    type(status_t) :: st
    type(normal_options_t) :: opt
    real(real64) :: dx, dy, area, ix2, iy2
    integer :: mx, my, ix, iy
    poly%rx = ratio
    poly%ry = 1
    hz = hertz_from_force(1 / (2 * poly%rx), 1 / (2 * poly%ry), 1.0_real64, 1.0_real64)
    dx = 2 * hz%a / n
    dy = 2 * hz%b / n
    mx = 2 * ceiling(1.25_real64 * n / 2) + 1
    my = mx
    call gap_from_polynomial(poly, mx, my, dx, dy, -(mx - 1) * dx / 2, -(my - 1) * dy / 2, gap, st)
    call solve_normal(gap%h, dx, dy, 1.0_real64, opt, res, st, normal_force=1.0_real64)
    area = res%n_contact * dx * dy
    ix2 = 0
    iy2 = 0
    do iy = 1, my
      do ix = 1, mx
        if (res%pressure(ix, iy) > 0) then
          ix2 = ix2 + (gap%cell_x(ix)**2 + dx**2 / 12) * dx * dy
          iy2 = iy2 + (gap%cell_y(iy)**2 + dy**2 / 12) * dx * dy
        end if
      end do
    end do
    e_area = abs(area / (pi * hz%a * hz%b) - 1)
    e_a = abs(sqrt(4 * ix2 / area) / hz%a - 1)
    e_b = abs(sqrt(4 * iy2 / area) / hz%b - 1)
  end subroutine hertz_on_grid

  subroutine test_hertz_grid()
    real(real64) :: ratios(3) = [1.0_real64, 10.0_real64, 0.1_real64]
    type(hertz_t) :: hz
    type(normal_result_t) :: res
    real(real64) :: e_area, e_a, e_b
    character(len=80) :: label
    integer :: i
    do i = 1, size(ratios)
      write (label, '(a, f5.2)') 'Rx/Ry = ', ratios(i)
      ! measured (docs/normal.md), n = 40: area <= 1.62e-2, axes <= 1.20e-2, approach <= 7.1e-5, pmax <= 1.72e-4
      call hertz_on_grid(ratios(i), 40, hz, res, e_area, e_a, e_b)
      call t%check(res%converged .and. res%residual <= 1e-10_real64, trim(label)//', n = 40: converged to 1e-10')
      call t%check(e_area < 2.1e-2_real64 .and. max(e_a, e_b) < 1.6e-2_real64, trim(label)//', n = 40: area and axes')
      call t%check(abs(res%approach / hz%approach - 1) < 9.5e-5_real64 .and. abs(res%pmax / hz%p0 - 1) < 2.3e-4_real64, &
                   trim(label)//', n = 40: approach and pmax')
      ! n = 80: area <= 6.1e-3, axes <= 3.6e-3, approach <= 2.4e-5, pmax <= 3.6e-5
      call hertz_on_grid(ratios(i), 80, hz, res, e_area, e_a, e_b)
      call t%check(e_area < 8e-3_real64 .and. max(e_a, e_b) < 4.7e-3_real64, trim(label)//', n = 80: area and axes')
      call t%check(abs(res%approach / hz%approach - 1) < 3.2e-5_real64 .and. abs(res%pmax / hz%p0 - 1) < 4.7e-5_real64, &
                   trim(label)//', n = 80: approach and pmax (second order: ~4x smaller than at n = 40)')
      call t%check(abs(res%fn - 1) < 1e-13_real64, trim(label)//': total force as prescribed')
      ! the preconditioned CG: 19-24 steps measured (53-86 without the preconditioner)
      call t%check(res%iterations <= 30, trim(label)//', n = 80: at most 30 CG steps to 1e-10 from the uniform '// &
                   'start ('//itoa(res%iterations)//')')
    end do
  end subroutine test_hertz_grid

  !> A rough sphere (many contact spots) with the force given, from the
  !> uniform pressure over the whole grid: the active set shrinks from 25,600
  !> cells to 80. The preconditioned directions shrink it slowly (47 steps
  !> measured when used from the start), the plain ones fast; the solver
  !> switches once the set has settled: 21 steps measured (plain CG 33).
  subroutine test_rough_start()
    integer, parameter :: n = 160
    real(real64), parameter :: d = 0.0125_real64
    real(real64), allocatable :: h(:, :)   ! heap: 25,600 cells
    real(real64) :: x, y
    type(normal_options_t) :: opt
    type(normal_result_t) :: by_force, by_approach
    type(status_t) :: st
    integer :: i, j
    allocate (h(n, n))
    do j = 1, n
      do i = 1, n
        x = (i - (n + 1) / 2.0_real64) * d
        y = (j - (n + 1) / 2.0_real64) * d
        h(i, j) = (x**2 + y**2) / 2 + 0.002_real64 * sin(25 * x) * sin(31 * y) + 0.001_real64 * cos(47 * x + 13 * y)
      end do
    end do
    call solve_normal(h, d, d, 0.7_real64, opt, by_force, st, normal_force=5e-4_real64)
    call t%check(.not. st%failed() .and. by_force%converged .and. by_force%iterations <= 30, &
                 'rough sphere, force given: converged in at most 30 steps ('//itoa(by_force%iterations)//', '// &
                 itoa(by_force%n_contact)//' contact cells)')
    ! the same problem with the approach found: the same pressure
    call solve_normal(h, d, d, 0.7_real64, opt, by_approach, st, approach=by_force%approach)
    call t%check(.not. st%failed() .and. maxval(abs(by_approach%pressure - by_force%pressure)) <= &
                 1e-7_real64 * by_force%pmax, 'rough sphere: the approach found gives back the pressure (1e-7 of pmax)')
  end subroutine test_rough_start

  subroutine test_approach_equals_force()
    type(polynomial_gap_t) :: poly
    type(gap_t) :: gap
    type(status_t) :: st
    type(normal_options_t) :: opt
    type(normal_result_t) :: r1, r2
    poly%rx = 2
    poly%ry = 0.7_real64
    poly%lx = 0.01_real64
    poly%cx = 0.02_real64
    call gap_from_polynomial(poly, 40, 30, 0.01_real64, 0.01_real64, -0.2_real64, -0.15_real64, gap, st)
    call solve_normal(gap%h, 0.01_real64, 0.01_real64, 1e-5_real64, opt, r1, st, normal_force=50.0_real64)
    call solve_normal(gap%h, 0.01_real64, 0.01_real64, 1e-5_real64, opt, r2, st, approach=r1%approach)
    call t%check(.not. st%failed(), 'force and approach prescribed: both solved')
    ! both stop at residual 1e-10 of max(u): pressures agree to ~1e-9 of pmax
    call t%check(maxval(abs(r1%pressure - r2%pressure)) < 1e-8_real64 * r1%pmax .and. &
                 abs(r2%fn / 50 - 1) < 1e-8_real64, 'approach prescribed reproduces the force-prescribed solution')
    ! a start 10 % off the solution and spread one cell wider (as a coarser
    ! grid's pressure interpolated is): the same solution; the solution
    ! itself as start: done at once
    call solve_normal(gap%h, 0.01_real64, 0.01_real64, 1e-5_real64, opt, r2, st, normal_force=50.0_real64, &
                      start=1.1_real64 * max(r1%pressure, eoshift(r1%pressure, 1, dim=1)))
    call t%check(.not. st%failed() .and. maxval(abs(r1%pressure - r2%pressure)) < 1e-8_real64 * r1%pmax, &
                 'a start pressure: the same solution')
    call solve_normal(gap%h, 0.01_real64, 0.01_real64, 1e-5_real64, opt, r2, st, normal_force=50.0_real64, &
                      start=r1%pressure)
    call t%check(r2%iterations <= 1, 'the solution as start: at most one step ('//itoa(r2%iterations)//' against '// &
                 itoa(r1%iterations)//' from the uniform start)')
    call solve_normal(gap%h, 0.01_real64, 0.01_real64, 1e-5_real64, opt, r2, st, approach=r1%approach, &
                      start=1.1_real64 * r1%pressure)
    call t%check(.not. st%failed() .and. maxval(abs(r1%pressure - r2%pressure)) < 1e-8_real64 * r1%pmax, &
                 'a start pressure, approach prescribed: the same solution')
  end subroutine test_approach_equals_force

  subroutine test_contact_sample(name)
    character(len=*), intent(in) :: name
    type(contact_input_t) :: inp
    type(contact_case_t) :: cc
    type(status_t) :: st
    type(normal_options_t) :: opt
    type(normal_result_t) :: res
    real(real64) :: g, pmax_printed
    call read_contact_input(trim(samples)//'/'//name//'.inp', 1, inp, st)
    call t%check(.not. st%failed(), name//': .inp read')
    if (st%failed()) then
      print '(a)', st%message
      return
    end if
    g = 2 / (1 / inp%gg(1) + 1 / inp%gg(2))
    call solve_normal(inp%gap%h, inp%dx, inp%dy, compliance_from_g_nu(g, g * sum(inp%poiss / inp%gg) / 2), opt, res, &
                      st, approach=inp%pen)
    call read_contact_case(trim(samples)//'/'//name//'.out', 1, cc, st)
    call t%check(.not. st%failed(), name//': CONTACT .out/.mat read')
    if (st%failed()) return
    call t%check(all((res%pressure > 0) .eqv. cc%inside), name//': contact area cell for cell ('// &
                 trim(itoa_(res%n_contact))//' cells)')
    call t%check(abs(res%fn - cc%fn) <= half_unit(cc%fn), name//': FN to the printed digits')
    pmax_printed = printed_pmax(trim(samples)//'/'//name//'.out')
    call t%check(abs(res%pmax - pmax_printed) <= half_unit(pmax_printed), name//': PMAX to the printed digits')
    print '(a, es16.9, a, es16.9, a, i0, a, es9.2)', '     '//name//': FN ', res%fn, '  PMAX ', res%pmax, &
      '  iterations ', res%iterations, '  residual ', res%residual
    ! the force-prescribed variant with CONTACT's force gives back PEN and the same area
    block
      type(normal_result_t) :: rf
      type(contact_input_t) :: inp3
      call solve_normal(inp%gap%h, inp%dx, inp%dy, compliance_from_g_nu(g, g * sum(inp%poiss / inp%gg) / 2), opt, &
                        rf, st, normal_force=res%fn)
      ! both solves stop at residual 1e-10 of max(u): the approach agrees to ~1e-10 of PEN
      call t%check(abs(rf%approach / inp%pen - 1) < 1e-8_real64 .and. all((rf%pressure > 0) .eqv. cc%inside), &
                   name//': force prescribed (FN) gives back PEN and the same area')
      call read_contact_input(trim(samples)//'/'//name//'.inp', 3, inp3, st)
      call t%check(.not. st%failed() .and. inp3%cphi == 0.001_real64 .and. all(inp3%gap%h == inp%gap%h), &
                   name//': case 3 of the .inp read (CPHI = 0.001, the same gap)')
    end block
  end subroutine test_contact_sample

  !> Half a unit in the 4th significant digit (CONTACT prints FN and PMAX as 1.964E+04).
  pure real(real64) function half_unit(x)
    real(real64), intent(in) :: x
    half_unit = 0.5_real64 * 10.0_real64**(floor(log10(abs(x))) - 3)
  end function half_unit

  function itoa_(i) result(s)
    integer, intent(in) :: i
    character(len=16) :: s
    write (s, '(i0)') i
  end function itoa_

  !> PMAX of the first case: the 5th number under 'APPROACH     PMAX'.
  real(real64) function printed_pmax(path)
    character(len=*), intent(in) :: path
    integer :: u, ios
    character(len=256) :: line
    real(real64) :: v(5)
    printed_pmax = -1
    open (newunit=u, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return
    do
      read (u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (index(line, 'APPROACH') > 0 .and. index(line, 'PMAX') > 0) then
        read (u, *, iostat=ios) v
        if (ios == 0) printed_pmax = v(5)
        exit
      end if
    end do
    close (u)
  end function printed_pmax

  subroutine test_gap_file()
    type(gap_t) :: gap
    type(status_t) :: st
    character(len=*), parameter :: nl = achar(10)
    call parse_gap_text('3 2 0.5 0.25 -1 2'//nl//'% comment'//nl//'1 2 3'//nl//'4,5,6.5'//nl, 'good', gap, st)
    call t%check(.not. st%failed() .and. gap%mx == 3 .and. gap%my == 2, 'gap file: read')
    call t%check(gap%h(3, 2) == 6.5_real64 .and. gap%h(1, 2) == 4 .and. gap%cell_x(3) == 0 .and. gap%cell_y(2) == 2.25_real64, &
                 'gap file: values in increasing x, rows in increasing y; x0, y0 the first cell centre')
    call expect_refusal('3 2 0.5 0.25 -1 2'//nl//'1 2 3'//nl, 'the header says my = 2', 'gap file: too few rows')
    call expect_refusal('3 2 0.5 0.25 -1 2'//nl//'1 2 3'//nl//'1 2'//nl, 'has 2 values, the header says mx = 3', &
                        'gap file: a short row')
    call expect_refusal('3 1 0.5 0.25 -1 2'//nl//'1 2 3 4'//nl, 'more than 3 values', 'gap file: a long row')
    call expect_refusal('3 2 0.5 0.25 -1 2'//nl//'1 2 3'//nl//'1 2 3'//nl//'1 2 3'//nl, 'more than my = 2', &
                        'gap file: too many rows')
    call expect_refusal('2 1 0.5 0.25 0 0'//nl//'1 NaN'//nl, 'finite numbers only', 'gap file: NaN')
    call expect_refusal('2 1 0.5 0.25 0 0'//nl//'1 abc'//nl, 'is not a number', 'gap file: a word')
    call expect_refusal('2 1 0 0.25 0 0'//nl//'1 2'//nl, 'cell sizes must be > 0', 'gap file: dx = 0')
    call expect_refusal('2 x 1 1 0 0'//nl, 'must be the header', 'gap file: bad header')
    call expect_refusal('', 'header "mx my dx dy x0 y0" is missing', 'gap file: empty')
  end subroutine test_gap_file

  subroutine expect_refusal(text, phrase, label)
    character(len=*), intent(in) :: text, phrase, label
    type(gap_t) :: gap
    type(status_t) :: st
    call parse_gap_text(text, 'f', gap, st)
    call t%check(st%failed(), label//': refused')
    if (st%failed()) then
      call t%check(index(st%message, phrase) > 0, label//': message "'//st%message//'"')
    end if
  end subroutine expect_refusal

  subroutine test_contact_inp_quadratic()
    type(contact_input_t) :: inp
    type(status_t) :: st
    type(normal_options_t) :: opt
    type(normal_result_t) :: res
    type(hertz_t) :: hz
    integer :: u
    character(len=*), parameter :: path = 'test_normal_ibase1.inp'
    real(real64) :: g, c
    open (newunit=u, file=path, status='replace', action='write')
    write (u, '(a)') '% quadratic undeformed distance: circle of Hertz', ' 3 MODULE', '  203000  P-B-T-N-F-S', &
      '  022020  L-D-C-M-Z-E', ' 0501331  H-G-I-A-O-W-R', ' 9999 100 30 1 1e-09', ' 1.0 0.1 1 1.0 1.0 1.0 1.0 0.9', &
      ' 0.01 0.001 0.0 0.0   PEN, CKSI, CETA, CPHI', ' 100.0 100.0', ' 0.0 0.05 1.0', ' 0.28 0.28 82000.0 82000.0', &
      ' 1', ' 41 41 -1.025 -1.025 0.05 0.05', ' 1 1', ' 0.05 0.0 0.05 0.0 0.0 0.0', ' 0 MODULE'
    close (u)
    call read_contact_input(path, 1, inp, st)
    call t%check(.not. st%failed(), 'CONTACT .inp, IBASE = 1: read')
    if (st%failed()) then
      print '(a)', st%message
      return
    end if
    call t%check(abs(inp%gap%h(21, 21)) < 1e-15_real64 .and. abs(inp%gap%h(1, 21) - 0.05_real64) < 1e-14_real64, &
                 'CONTACT .inp, IBASE = 1: h = B1 x^2 + B3 y^2 at the cell centres')
    g = 82000
    c = compliance_from_g_nu(g, 0.28_real64)
    call solve_normal(inp%gap%h, inp%dx, inp%dy, c, opt, res, st, approach=inp%pen)
    hz = hertz_from_approach(0.05_real64, 0.05_real64, c, 0.01_real64)
    ! n ~ 2a/dx = 18 cells across: measured force error about 1e-3 (first order in the area)
    call t%check(abs(res%fn / hz%fn - 1) < 5e-3_real64, 'CONTACT .inp, IBASE = 1: force near Hertz''s')
    ! IPLAN = 3: the potential contact restricted to a rectangle (x <= 0.01: the cells up to x = 0)
    open (newunit=u, file=path, status='replace', action='write')
    write (u, '(a)') ' 3 MODULE', '  203000', '  022020', ' 0501331', ' 9999 100 30 1 1e-09', &
      ' 1.0 0.1 1 1.0 1.0 1.0 1.0 0.9', ' 0.01 0.001 0.0 0.0', ' 100.0 100.0', ' 0.0 0.05 1.0', &
      ' 0.28 0.28 82000.0 82000.0', ' 1', ' 41 41 -1.025 -1.025 0.05 0.05', ' 1 3', ' 0.05 0.0 0.05 0.0 0.0 0.0', &
      ' -2 0.01 -2 2  -2 0.01 -2 2', ' 0 MODULE'
    close (u)
    call read_contact_input(path, 1, inp, st)
    call t%check(.not. st%failed() .and. all(inp%gap%h(22:, :) >= 1e29_real64) .and. all(inp%gap%h(:21, :) < 1), &
                 'CONTACT .inp, IPLAN = 3: cells outside the rectangles excluded (h = 1e30)')
    if (.not. st%failed()) then
      call solve_normal(inp%gap%h, inp%dx, inp%dy, c, opt, res, st, approach=inp%pen)
      call t%check(.not. st%failed() .and. all(res%pressure(22:, :) == 0) .and. res%n_contact > 0, &
                   'CONTACT .inp, IPLAN = 3: no pressure outside the planform')
    end if
    open (newunit=u, file=path, status='old')
    close (u, status='delete')
    call read_contact_input(trim(samples)//'/kidney_nu25.inp', 4, inp, st)
    call t%check(st%failed() .and. index(st%message, 'the file has 3 cases') > 0, 'CONTACT .inp: case beyond the last refused')
  end subroutine test_contact_inp_quadratic

  subroutine test_auto_grid()
    type(polynomial_gap_t) :: poly
    type(status_t) :: st
    integer :: mx, my
    real(real64) :: dx, dy, x0, y0
    poly%rx = 8
    poly%ry = 2
    ! interpenetration at level 0.01: semi-axes 0.4 (x) and 0.2 (y)
    call auto_grid(poly, 0.01_real64, 2.0_real64, 40, 0.1_real64, mx, my, dx, dy, x0, y0, st)
    call t%check(.not. st%failed() .and. mx == 40 .and. my >= 20 .and. my <= 22, 'auto grid: 40 cells across x, half in y')
    call t%check(x0 - dx / 2 < -0.4_real64 * 1.1_real64 + 0.01_real64 .and. abs(x0 + (mx - 1) * dx / 2) < 1e-12_real64, &
                 'auto grid: covers the interpenetration with the margin, centred')
    call auto_grid(poly, -0.01_real64, 2.0_real64, 40, 0.1_real64, mx, my, dx, dy, x0, y0, st)
    call t%check(st%failed() .and. index(st%message, 'do not interpenetrate') > 0, 'auto grid: no interpenetration refused')
  end subroutine test_auto_grid

  subroutine test_gap_resampled()
    type(polynomial_gap_t) :: poly
    type(gap_t) :: coarse, fine, exact
    type(status_t) :: st
    poly = polynomial_gap_t(rx=0.7_real64, ry=2.5_real64, lx=0.3_real64, ly=-0.1_real64, h0=0.02_real64)
    call gap_from_polynomial(poly, 21, 13, 0.1_real64, 0.15_real64, -1.0_real64, -0.9_real64, coarse, st)
    ! a finer grid reaching half a coarse cell beyond the outermost centres
    call gap_from_polynomial(poly, 67, 59, 0.0325_real64, 0.0325_real64, -1.05_real64, -0.975_real64, exact, st)
    fine = gap_resampled(coarse, exact%mx, exact%my, exact%dx, exact%dy, exact%x0, exact%y0)
    ! round-off of the cubic weights on values of order 1: measured 1e-15
    call t%check(maxval(abs(fine%h - exact%h)) < 1e-12_real64, 'resampled gap: a quadratic exactly, to the edges')
    fine = gap_resampled(coarse, coarse%mx, coarse%my, coarse%dx, coarse%dy, coarse%x0, coarse%y0)
    call t%check(maxval(abs(fine%h - coarse%h)) < 1e-14_real64, 'resampled gap: the same grid gives the same values')
    coarse%h(1:5, :) = 2 * outside_gap
    fine = gap_resampled(coarse, exact%mx, exact%my, exact%dx, exact%dy, exact%x0, exact%y0)
    call t%check(all(fine%h(1:10, :) >= outside_gap) .and. all(fine%h(20:, :) < outside_gap), &
                 'resampled gap: cells outside the potential contact stay outside, the others inside')
  end subroutine test_gap_resampled

end program test_normal
