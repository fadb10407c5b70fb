!> The Hertz convergence table of docs/normal.md: principal-radius ratios
!> Rx/Ry = 1, 2, 5, 10 and their inverses, force prescribed, n cells across
!> each axis of Hertz's ellipse (grid 1.25 times the ellipse, a cell centre
!> at the origin). Relative errors of the contact area, the semi-axes (from
!> the second moments of the contact cells: a = sqrt(4 Ixx / area)), the
!> approach and the maximum pressure against Hertz's closed forms, and the
!> observed orders between successive n.
!>   kcreep_hertz_convergence [n_max]      (default 320)
program hertz_convergence
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t
  use kcreep_hertz, only: hertz_t, hertz_from_force
  use kcreep_gap, only: gap_t, polynomial_gap_t, gap_from_polynomial
  use kcreep_normal_solve, only: normal_options_t, normal_result_t, solve_normal
  implicit none
  real(real64), parameter :: pi = acos(-1.0_real64)
  real(real64), parameter :: ratios(7) = [1.0_real64, 2.0_real64, 5.0_real64, 10.0_real64, 0.5_real64, 0.2_real64, &
                                          0.1_real64]
  integer, parameter :: ns(6) = [10, 20, 40, 80, 160, 320]
  type(hertz_t) :: hz
  type(polynomial_gap_t) :: poly
  type(gap_t) :: gap
  type(status_t) :: st
  type(normal_options_t) :: opt
  type(normal_result_t) :: res
  integer :: ir, k, mx, ix, iy, n_max
  real(real64) :: dx, dy, area, ix2, iy2, e(5), e_prev(5)
  character(len=16) :: arg

  n_max = 320
  if (command_argument_count() >= 1) then
    call get_command_argument(1, arg)
    read (arg, *) n_max
  end if
  print '(a)', '| Rx/Ry | n | iterations | area | a | b | approach | pmax | order approach | order pmax |'
  print '(a)', '|---|---|---|---|---|---|---|---|---|---|'
  do ir = 1, size(ratios)
    poly%rx = ratios(ir)
    poly%ry = 1
    hz = hertz_from_force(1 / (2 * poly%rx), 1 / (2 * poly%ry), 1.0_real64, 1.0_real64)
    do k = 1, size(ns)
      if (ns(k) > n_max) exit
      dx = 2 * hz%a / ns(k)
      dy = 2 * hz%b / ns(k)
      mx = 2 * ceiling(1.25_real64 * ns(k) / 2) + 1
      call gap_from_polynomial(poly, mx, mx, dx, dy, -(mx - 1) * dx / 2, -(mx - 1) * dy / 2, gap, st)
      call solve_normal(gap%h, dx, dy, 1.0_real64, opt, res, st, normal_force=1.0_real64)
      if (st%failed()) then
        print '(a)', st%message
        error stop 1
      end if
      area = res%n_contact * dx * dy
      ix2 = 0
      iy2 = 0
      do iy = 1, mx
        do ix = 1, mx
          if (res%pressure(ix, iy) > 0) then
            ix2 = ix2 + (gap%cell_x(ix)**2 + dx**2 / 12) * dx * dy
            iy2 = iy2 + (gap%cell_y(iy)**2 + dy**2 / 12) * dx * dy
          end if
        end do
      end do
      e = [area / (pi * hz%a * hz%b) - 1, sqrt(4 * ix2 / area) / hz%a - 1, sqrt(4 * iy2 / area) / hz%b - 1, &
           res%approach / hz%approach - 1, res%pmax / hz%p0 - 1]
      if (k == 1) then
        print '(a, g0.3, a, i0, a, i0, 5(a, es9.2), a)', '| ', ratios(ir), ' | ', ns(k), ' | ', res%iterations, &
          (' | ', e(ix), ix=1, 5), ' | | |'
      else
        print '(a, g0.3, a, i0, a, i0, 5(a, es9.2), 2(a, f5.2), a)', '| ', ratios(ir), ' | ', ns(k), ' | ', &
          res%iterations, (' | ', e(ix), ix=1, 5), ' | ', log(abs(e_prev(4) / e(4))) / log(2.0_real64), ' | ', &
          log(abs(e_prev(5) / e(5))) / log(2.0_real64), ' |'
      end if
      e_prev = e
    end do
  end do
end program hertz_convergence
