!> Unit tests of the surfaces' slopes, which plane_root's Newton steps take
!> (kcreep_wheel_rail_geometry: the gap in a contact plane, cell by cell).
!> A wrong slope would not show in the results, only slow the roots down or
!> lose them: so the slopes are checked against central differences.
!>  1. envelope_at_slope: the slope of the sample interval, equal to the
!>     difference quotient of envelope_at inside the interval (h a tenth of
!>     the interval: the same linear piece; measured 6e-13, allowed 1e-9).
!>  2. wheel_surface_slope (the envelope as a tread on a wheel of radius
!>     460 mm, yawed by 0 and 0.02 rad, at x = 0 and 35 mm): z equals
!>     wheel_surface's, and dz/dy the central difference with h a tenth of
!>     the envelope's interval, at points mid-interval of the tread (the
!>     circle's curvature over h and rounding: measured 1e-11, allowed
!>     1e-8; a slope without the yaw's cosine would be off by 3e-5).
program test_wheel_surface
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_profile, only: envelope_t, envelope_at, envelope_at_slope
  use kcreep_wheel_rail_geometry, only: wheel_surface_slope, wheel_surface
  use unit_checks, only: checker_t
  implicit none
  type(checker_t) :: t
  type(envelope_t) :: env
  real(real64), parameter :: r_nom = 460, origin = 12.5_real64, shift = 1.3_real64, w = 0.2_real64
  real(real64) :: y, z, dz, zp, zm, h, worst(3), yaw, x
  integer :: k, i, j

  ! a tread with a flange-like rise: z = 0.002 y^2 + 3 exp(-(y - 30)^2 / 20), every 0.05 mm
  env%y_first = -40
  env%step = 0.05_real64
  env%take_max = .true.
  env%v = [(0.002_real64 * (env%y_first + k * env%step)**2 + &
            3 * exp(-(env%y_first + k * env%step - 30)**2 / 20), k=0, 1600)]
  h = env%step / 10

  worst = 0
  do k = 1, 150
    y = env%y_first + (10 * k + 0.5_real64) * env%step   ! mid-interval
    call envelope_at_slope(env, y, z, dz)
    worst(1) = max(worst(1), abs(z - envelope_at(env, y)))
    worst(2) = max(worst(2), abs(dz - (envelope_at(env, y + h) - envelope_at(env, y - h)) / (2 * h)))
  end do
  print '(a, 2es10.2)', 'envelope: largest |z - envelope_at|, |slope - difference quotient|: ', worst(1:2)
  call t%check(worst(1) == 0, 'envelope_at_slope: z is envelope_at''s')
  call t%check(worst(2) <= 1e-9_real64, 'envelope_at_slope: the slope is the difference quotient''s')

  worst = 0
  do i = 0, 1
    yaw = 0.02_real64 * i
    do j = 0, 1
      x = 35.0_real64 * j
      do k = 1, 100
        ! the tread's coordinate mid-interval, so that y +- h stays on its linear piece
        y = shift + (origin + env%y_first + (10 * k + 0.5_real64) * env%step + x * sin(yaw)) / cos(yaw)
        call wheel_surface_slope(env, r_nom, origin, shift, sin(yaw), cos(yaw), w, x, y, z, dz)
        zp = wheel_surface(env, r_nom, origin, shift, yaw, w, x, y + h)
        zm = wheel_surface(env, r_nom, origin, shift, yaw, w, x, y - h)
        worst(1) = max(worst(1), abs(z - wheel_surface(env, r_nom, origin, shift, yaw, w, x, y)))
        worst(2) = max(worst(2), abs(dz - (zp - zm) / (2 * h)))
        worst(3) = max(worst(3), abs(dz))
      end do
    end do
  end do
  print '(a, 3es10.2)', 'wheel: largest |z - wheel_surface|, |slope - difference quotient|, |slope|: ', worst
  call t%check(worst(1) == 0, 'wheel_surface_slope: z is wheel_surface''s')
  call t%check(worst(2) <= 1e-8_real64, 'wheel_surface_slope: the slope is the difference quotient''s')
  call t%check(worst(3) > 0.1_real64, 'the points cover slopes of the flange-like rise')
  call t%finish()
end program test_wheel_surface
