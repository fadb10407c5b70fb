!> A wheel on a rail: placement in the track, contact search, contact planes and
!> the undeformed distance in each contact plane.
!>
!> Coordinates are CONTACT's (module 1) for the right side: track frame x along
!> the track, y lateral positive towards the field side, z downwards, origin in
!> the track plane (the plane resting on the rails) at the track centre. The
!> left side is computed as the mirrored right side by the caller.
!>
!> Rail: its profile is rotated by the cant (positive: the head leans towards
!> the track centre, as a 1:40 inclination), shifted down to touch the track
!> plane (smallest z = 0) and sideways so that its gauge point, the innermost
!> point (smallest y) at most gauge_height below the track plane, lies at
!> y = gauge_width / 2.
!> Wheel: a body of revolution; its profile (y_w towards the field side, z_w
!> downwards) has its origin at y = shift + (flange_back_distance / 2 -
!> flange_back_position) from the track centre, at radius nominal_radius, so
!> the radius at y_w is R(y_w) = nominal_radius + z_w(y_w). With yaw psi about
!> the vertical axis through the wheelset centre, a track point (x, y) has the
!> axial coordinate t = -x sin psi + (y - shift) cos psi and the horizontal
!> distance u = x cos psi + (y - shift) sin psi from the axis, and the wheel's
!> surface lies at z = w - nominal_radius + sqrt(R(t - origin)^2 - u^2), w the
!> wheel's height (exact for any yaw).
!>
!> Contact search: d(y) = z_rail(y) - max_x z_wheel(x, y) on a fine y grid (the
!> vertical clearance over the contact locus); the wheel is lowered until
!> min d = 0 (touching) and then by the vertical approach dz; every interval of
!> y where d < dz is one contact patch (two dips joined by a ridge lower than
!> dz make one non-elliptic patch, separate intervals separate patches), its
!> reference point and contact angle CONTACT's weighted interpenetration
!> centre and weighted mean surface angle (find_contacts).
!> Contact plane: through the reference point on the rail (the rail is
!> straight along x), tilted about x by the contact angle delta (positive
!> towards the flange on the right side). Gap: for a point (xi, s) of the
!> plane (xi along x, s along the tilted lateral axis), the distance between
!> the two surfaces along the plane's normal (0, sin delta, cos delta), each found
!> by Newton's method on the surface functions.
module kcreep_wheel_rail_geometry
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: rtoa
  use kcreep_profile, only: profile_t, envelope_t, sample_profile, make_envelope, envelope_at, envelope_at_slope, &
                            envelope_slope, no_surface, sample_step
  use kcreep_gap, only: gap_t, outside_gap
  implicit none
  private
  public :: track_t, contact_t, plane_gap_t, place_track, clearance, find_contacts, plane_of, plane_gap_value, &
            plane_gap_grid, wheel_surface, wheel_surface_slope, search_step, refine_minimum, check_profile_ends

  !> Lateral step of the contact search (mm).
  real(real64), parameter :: search_step = 0.02_real64

  !> The placed profiles of one side (right-side configuration).
  type :: track_t
    type(envelope_t) :: rail                 !< z_r(y) in track coordinates
    type(envelope_t) :: wheel                !< z_w(y_w) in the wheel profile's coordinates
    real(real64) :: cant = 0                 !< rotation of the rail profile (file's + rail_cant)
    real(real64) :: rail_shift(2) = 0        !< track (y, z) = rotated profile point + rail_shift
    real(real64) :: wheel_origin = 0         !< flange_back_distance / 2 - flange_back_position
    real(real64) :: r_nom = 460
  end type track_t

  !> One contact patch found at a shift (find_contacts: CONTACT's reference).
  type :: contact_t
    real(real64) :: x = 0, y = 0, z = 0      !< the contact reference point on the rail, track coordinates
    real(real64) :: delta = 0                !< contact angle (rad), the weighted mean surface angle
    real(real64) :: turn = 0                 !< largest |surface angle - delta| where pen >= max pen / 2 (rad)
    real(real64) :: weight = 0               !< integral of pen^(5/2) dy (mm^(7/2))
    real(real64) :: y_lo = 0, y_hi = 0       !< the interval of y where d < dz (its interpenetration)
    real(real64) :: y_wheel = 0              !< the reference point in the wheel profile's coordinates
  end type contact_t

  !> The undeformed distance in a contact plane.
  type :: plane_gap_t
    type(envelope_t) :: rail, wheel
    real(real64) :: r_nom = 0, wheel_origin = 0, shift = 0, yaw = 0
    real(real64) :: wheel_height = 0         !< w of the touching position
    real(real64) :: p0(3) = 0, delta = 0     !< plane origin (contact point) and tilt
    real(real64) :: s_lo = -huge(1.0_real64), s_hi = huge(1.0_real64)   !< beyond: outside the potential contact
  end type plane_gap_t

contains

  !> Place the rail and the wheel (profiles already mirrored as asked).
  subroutine place_track(rail, wheel, cant, gauge_width, gauge_height, fb_distance, fb_position, r_nom, track, status)
    type(profile_t), intent(in) :: rail, wheel
    real(real64), intent(in) :: cant, gauge_width, gauge_height, fb_distance, fb_position, r_nom
    type(track_t), intent(out) :: track
    type(status_t), intent(inout) :: status
    real(real64), allocatable :: ys(:), zs(:), yr(:), zr(:)
    logical, allocatable :: gauge_band(:)

    call sample_profile(rail, sample_step, ys, zs)
    yr = cos(cant) * ys - sin(cant) * zs
    zr = sin(cant) * ys + cos(cant) * zs
    track%cant = cant
    track%rail_shift(2) = -minval(zr)
    zr = zr + track%rail_shift(2)
    gauge_band = zr <= gauge_height
    track%rail_shift(1) = gauge_width / 2 - minval(yr, mask=gauge_band)
    yr = yr + track%rail_shift(1)
    call make_envelope(yr, zr, .false., track%rail)
    call sample_profile(wheel, sample_step, ys, zs)
    if (.not. all(r_nom + zs > 0)) then
      call fail(status, exit_bad_input, 'wheel profile: nominal_radius = '//rtoa(r_nom)//' makes a radius <= 0 '// &
                '(the profile reaches z = '//rtoa(minval(zs))//' mm above its origin)')
      return
    end if
    call make_envelope(ys, zs, .true., track%wheel)
    track%wheel_origin = fb_distance / 2 - fb_position
    track%r_nom = r_nom
  end subroutine place_track

  !> The wheel's surface z at track point (x, y) for wheel height w
  !> (-no_surface where the wheel does not reach).
  elemental real(real64) function wheel_surface(track_wheel, r_nom, origin, shift, yaw, w, x, y) result(z)
    type(envelope_t), intent(in) :: track_wheel
    real(real64), intent(in) :: r_nom, origin, shift, yaw, w, x, y
    z = wheel_surface_yawed(track_wheel, r_nom, origin, shift, sin(yaw), cos(yaw), w, x, y)
  end function wheel_surface

  !> wheel_surface with the yaw's sine and cosine given.
  elemental real(real64) function wheel_surface_yawed(track_wheel, r_nom, origin, shift, sin_yaw, cos_yaw, w, x, y) &
    result(z)
    type(envelope_t), intent(in) :: track_wheel
    real(real64), intent(in) :: r_nom, origin, shift, sin_yaw, cos_yaw, w, x, y
    real(real64) :: dz
    call wheel_surface_slope(track_wheel, r_nom, origin, shift, sin_yaw, cos_yaw, w, x, y, z, dz)
  end function wheel_surface_yawed

  !> wheel_surface_yawed and its slope dz/dy at (x, y) (0 where the wheel
  !> does not reach). The tread's radius r = r_nom + zw(t) at the profile
  !> coordinate t and the distance u from the axis' plane along the rail:
  !> z = w - r_nom + sqrt(r^2 - u^2).
  elemental subroutine wheel_surface_slope(track_wheel, r_nom, origin, shift, sin_yaw, cos_yaw, w, x, y, z, dz)
    type(envelope_t), intent(in) :: track_wheel
    real(real64), intent(in) :: r_nom, origin, shift, sin_yaw, cos_yaw, w, x, y
    real(real64), intent(out) :: z, dz
    real(real64) :: t, u, zw, dzw, r, root
    dz = 0
    t = -x * sin_yaw + (y - shift) * cos_yaw
    u = x * cos_yaw + (y - shift) * sin_yaw
    call envelope_at_slope(track_wheel, t - origin, zw, dzw)
    if (zw <= -no_surface) then
      z = -no_surface
      return
    end if
    r = r_nom + zw
    if (abs(u) >= r) then
      z = -no_surface
      return
    end if
    root = sqrt((r - u) * (r + u))
    z = w - r_nom + root
    dz = (r * dzw * cos_yaw - u * sin_yaw) / root
  end subroutine wheel_surface_slope

  !> The vertical clearance d(y) = z_rail - lowest wheel point at wheel height 0,
  !> on the grid y(k) = y_first + (k - 1) search_step over the rail; xs: where
  !> along x the wheel is lowest (0 without yaw); no_surface where either misses.
  subroutine clearance(track, shift, yaw, ys, d, xs)
    type(track_t), intent(in) :: track
    real(real64), intent(in) :: shift, yaw
    real(real64), allocatable, intent(out) :: ys(:), d(:), xs(:)
    integer :: n, k
    real(real64) :: zr, zl, xl
    n = floor((size(track%rail%v) - 1) * track%rail%step / search_step)
    allocate (ys(n), d(n), xs(n))
    do k = 1, n
      ys(k) = track%rail%y_first + (k - 1) * search_step
      zr = envelope_at(track%rail, ys(k))
      call lowest_wheel_point(ys(k), zl, xl)
      xs(k) = xl
      if (zr >= no_surface .or. zl <= -no_surface) then
        d(k) = no_surface
      else
        d(k) = zr - zl
      end if
    end do

  contains

    !> max over x of the wheel's z at lateral track position y (golden section with yaw).
    subroutine lowest_wheel_point(y, z, x)
      real(real64), intent(in) :: y
      real(real64), intent(out) :: z, x
      real(real64), parameter :: g = (sqrt(5.0_real64) - 1) / 2
      real(real64) :: a, b, c1, c2, f1, f2
      integer :: it
      x = 0
      z = wheel_surface(track%wheel, track%r_nom, track%wheel_origin, shift, yaw, 0.0_real64, 0.0_real64, y)
      if (yaw == 0) return
      ! the lowest point lies within r |tan(flank)| |sin yaw| of x = 0: search +-3.5 r |sin yaw| + 1 mm
      b = 3.5_real64 * track%r_nom * abs(sin(yaw)) + 1
      a = -b
      c1 = b - g * (b - a)
      c2 = a + g * (b - a)
      f1 = wheel_surface(track%wheel, track%r_nom, track%wheel_origin, shift, yaw, 0.0_real64, c1, y)
      f2 = wheel_surface(track%wheel, track%r_nom, track%wheel_origin, shift, yaw, 0.0_real64, c2, y)
      do it = 1, 60
        if (f1 >= f2) then
          b = c2
          c2 = c1
          f2 = f1
          c1 = b - g * (b - a)
          f1 = wheel_surface(track%wheel, track%r_nom, track%wheel_origin, shift, yaw, 0.0_real64, c1, y)
        else
          a = c1
          c1 = c2
          f1 = f2
          c2 = a + g * (b - a)
          f2 = wheel_surface(track%wheel, track%r_nom, track%wheel_origin, shift, yaw, 0.0_real64, c2, y)
        end if
        if (b - a < 1e-7_real64) exit
      end do
      x = (a + b) / 2
      z = wheel_surface(track%wheel, track%r_nom, track%wheel_origin, shift, yaw, 0.0_real64, x, y)
      if (z < max(f1, f2)) then
        z = max(f1, f2)
        x = merge(c1, c2, f1 >= f2)
      end if
    end subroutine lowest_wheel_point

  end subroutine clearance

  !> The contacts at vertical approach dz (beyond touching): one per interval
  !> of y where the interpenetration pen(y) = dz - (d(y) - min d) is positive,
  !> ordered from the field side (largest y) to the track centre as CONTACT
  !> orders them. Each contact's reference is CONTACT's module 1 "weighted
  !> centre" (its m_wr_locatecp, default gap weighting): with the wheel's
  !> surface along x taken as a parabola of curvature 1 / nominal_radius about
  !> the lowest point xs(y), the squared interpenetration integrated along x is
  !> (16/15) pen^(5/2) sqrt(2 nominal_radius), so each sample y_k weighs
  !> w_k = pen(y_k)^(5/2), and
  !>   y = sum w y_k / sum w,   x = sum w xs_k / sum w,
  !>   delta = sum w alpha_k / sum w,  alpha = atan(-dz_r/dy) the rail's surface angle,
  !> z the rail's surface at y. turn is the largest |alpha_k - delta| where
  !> pen >= max pen / 2 (for a Hertzian gap, the contact area): the planar
  !> patch's misfit, its gap along the plane's normal is off by about
  !> 1 / cos(turn) - 1 there. ys, d, xs from clearance.
  pure subroutine find_contacts(track, shift, yaw, ys, d, xs, dz, contacts)
    type(track_t), intent(in) :: track
    real(real64), intent(in) :: shift, yaw, ys(:), d(:), xs(:), dz
    type(contact_t), allocatable, intent(out) :: contacts(:)
    real(real64) :: d0, w, sw, swy, swx, swa, alpha, pen_max
    integer :: k, k1, n, j
    type(contact_t) :: one
    allocate (contacts(0))
    d0 = minval(d)
    n = size(d)
    k = 1
    do while (k <= n)
      if (d(k) - d0 >= dz) then
        k = k + 1
        cycle
      end if
      k1 = k
      sw = 0
      swy = 0
      swx = 0
      swa = 0
      pen_max = 0
      do while (k <= n)
        if (d(k) - d0 >= dz) exit
        w = (dz - (d(k) - d0))**2.5_real64
        alpha = atan(-envelope_slope(track%rail, ys(k), 0.05_real64))
        sw = sw + w
        swy = swy + w * ys(k)
        swx = swx + w * xs(k)
        swa = swa + w * alpha
        pen_max = max(pen_max, dz - (d(k) - d0))
        k = k + 1
      end do
      one%y_lo = ys(k1)
      one%y_hi = ys(k - 1)
      one%weight = sw * search_step
      one%y = swy / sw
      one%x = swx / sw
      one%delta = swa / sw
      one%turn = 0
      do j = k1, k - 1
        if (dz - (d(j) - d0) < pen_max / 2) cycle
        one%turn = max(one%turn, abs(atan(-envelope_slope(track%rail, ys(j), 0.05_real64)) - one%delta))
      end do
      one%z = envelope_at(track%rail, one%y)
      one%y_wheel = -one%x * sin(yaw) + (one%y - shift) * cos(yaw) - track%wheel_origin
      contacts = [one, contacts]
    end do
  end subroutine find_contacts

  !> The gap object of a contact: plane through the contact point, wheel at its
  !> touching height w0 (= min d).
  pure function plane_of(track, shift, yaw, w0, contact) result(plane)
    type(track_t), intent(in) :: track
    real(real64), intent(in) :: shift, yaw, w0
    type(contact_t), intent(in) :: contact
    type(plane_gap_t) :: plane
    plane%rail = track%rail
    plane%wheel = track%wheel
    plane%r_nom = track%r_nom
    plane%wheel_origin = track%wheel_origin
    plane%shift = shift
    plane%yaw = yaw
    plane%wheel_height = w0
    plane%p0 = [contact%x, contact%y, contact%z]
    plane%delta = contact%delta
  end function plane_of

  !> The undeformed distance at (xi, s) of the plane (outside_gap where a surface misses).
  elemental real(real64) function plane_gap_value(plane, xi, s) result(h)
    type(plane_gap_t), intent(in) :: plane
    real(real64), intent(in) :: xi, s
    real(real64) :: trig(4), lr
    logical :: ok_r
    h = outside_gap
    if (s < plane%s_lo .or. s > plane%s_hi) return
    trig = plane_trig(plane)
    call plane_root(plane, trig, .true., xi, s, lr, ok_r)
    if (ok_r) h = wheel_gap(plane, trig, xi, s, lr)
  end function plane_gap_value

  !> sin and cos of the plane's tilt and of the yaw.
  pure function plane_trig(plane) result(trig)
    type(plane_gap_t), intent(in) :: plane
    real(real64) :: trig(4)
    trig = [sin(plane%delta), cos(plane%delta), sin(plane%yaw), cos(plane%yaw)]
  end function plane_trig

  !> The gap at (xi, s) given the rail's lambda there, lr (outside_gap where the wheel misses).
  pure real(real64) function wheel_gap(plane, trig, xi, s, lr) result(h)
    type(plane_gap_t), intent(in) :: plane
    real(real64), intent(in) :: trig(4), xi, s, lr
    real(real64) :: lw
    logical :: ok_w
    call plane_root(plane, trig, .false., xi, s, lw, ok_w)
    if (ok_w) then
      h = lr - lw
    else
      h = outside_gap
    end if
  end function wheel_gap

  !> lambda where the point (xi, s) of the plane moved by lambda along its
  !> normal meets the rail (rail; straight along x: xi does not matter) or
  !> the wheel: Newton from the plane (lambda = 0) with the surface's own
  !> slope (of its sample interval: the envelopes are piecewise linear).
  !> trig: plane_trig.
  pure subroutine plane_root(plane, trig, rail, xi, s, lambda, ok)
    type(plane_gap_t), intent(in) :: plane
    real(real64), intent(in) :: trig(4), xi, s
    logical, intent(in) :: rail
    real(real64), intent(out) :: lambda
    logical, intent(out) :: ok
    real(real64) :: p(3), f, df, step
    integer :: it
    associate (sd => trig(1), cd => trig(2))
      p = plane%p0 + [xi, s * cd, -s * sd]
      lambda = 0
      ok = .false.
      do it = 1, 30
        call residual(lambda, f, df)
        if (abs(f) >= 1e20_real64 .or. df == 0) return
        step = -f / df
        step = max(min(step, 5.0_real64), -5.0_real64)
        lambda = lambda + step
        if (abs(step) < 1e-12_real64) exit
      end do
      call residual(lambda, f, df)
      ok = abs(f) < 1e-9_real64
    end associate

  contains

    !> surface z minus the line's z at lambda, and its derivative in lambda
    pure subroutine residual(lambda, f, df)
      real(real64), intent(in) :: lambda
      real(real64), intent(out) :: f, df
      real(real64) :: y, z, zs, dzs
      y = p(2) + lambda * trig(1)
      z = p(3) + lambda * trig(2)
      if (rail) then
        call envelope_at_slope(plane%rail, y, zs, dzs)
      else
        call wheel_surface_slope(plane%wheel, plane%r_nom, plane%wheel_origin, plane%shift, trig(3), trig(4), &
                                 plane%wheel_height, p(1), y, zs, dzs)
      end if
      if (abs(zs) >= no_surface) then
        f = 1e30_real64
        df = 0
      else
        f = zs - z
        df = dzs * trig(1) - trig(2)
      end if
    end subroutine residual

  end subroutine plane_root

  !> The gap at the cell centres of a grid in the plane (x = xi, y = s):
  !> plane_gap_value at each, the rail's root once per line of s.
  pure subroutine plane_gap_grid(plane, mx, my, dx, dy, x0, y0, gap)
    type(plane_gap_t), intent(in) :: plane
    integer, intent(in) :: mx, my
    real(real64), intent(in) :: dx, dy, x0, y0
    type(gap_t), intent(out) :: gap
    integer :: ix, iy
    real(real64) :: trig(4), s, lr
    logical :: ok_r
    gap%mx = mx
    gap%my = my
    gap%dx = dx
    gap%dy = dy
    gap%x0 = x0
    gap%y0 = y0
    allocate (gap%h(mx, my))
    trig = plane_trig(plane)
    do iy = 1, my
      s = y0 + (iy - 1) * dy
      gap%h(:, iy) = outside_gap
      if (s < plane%s_lo .or. s > plane%s_hi) cycle
      call plane_root(plane, trig, .true., x0, s, lr, ok_r)
      if (.not. ok_r) cycle
      do ix = 1, mx
        gap%h(ix, iy) = wheel_gap(plane, trig, x0 + (ix - 1) * dx, s, lr)
      end do
    end do
  end subroutine plane_gap_grid

  !> hmin lowered to the smallest gap near (xi, s) along s (along_xi false)
  !> or xi: parabolas through three points, steps quartered three times.
  pure subroutine refine_minimum(plane, xi, s, step0, along_xi, hmin)
    type(plane_gap_t), intent(in) :: plane
    real(real64), intent(in) :: xi, step0
    real(real64), intent(inout) :: s, hmin
    logical, intent(in) :: along_xi
    real(real64) :: t0, h0, hm, hp, step, t, h
    integer :: pass
    t0 = merge(xi, s, along_xi)
    step = step0
    h0 = value_at(t0)
    do pass = 1, 3
      hm = value_at(t0 - step)
      hp = value_at(t0 + step)
      if (hm < h0 .and. hm <= hp) then
        t0 = t0 - step
        h0 = hm
      else if (hp < h0) then
        t0 = t0 + step
        h0 = hp
      else if (hm + hp - 2 * h0 > 0) then
        t = t0 + step * (hm - hp) / (2 * (hm + hp - 2 * h0))
        h = value_at(t)
        if (h < h0) then
          t0 = t
          h0 = h
        end if
      end if
      step = step / 4
    end do
    hmin = min(hmin, h0)
    if (.not. along_xi) s = t0

  contains

    pure real(real64) function value_at(tt) result(v)
      real(real64), intent(in) :: tt
      if (along_xi) then
        v = plane_gap_value(plane, tt, s)
      else
        v = plane_gap_value(plane, xi, tt)
      end if
    end function value_at

  end subroutine refine_minimum

  !> A contact whose interpenetration reaches the end of a profile (the last
  !> point the file gives) is refused: the surface beyond is unknown.
  subroutine check_profile_ends(wheel_name, rail_name, track, ys, d, contacts, where, status)
    character(len=*), intent(in) :: wheel_name, rail_name   !< the files, for the message
    type(track_t), intent(in) :: track
    real(real64), intent(in) :: ys(:), d(:)
    type(contact_t), intent(in) :: contacts(:)
    character(len=*), intent(in) :: where
    type(status_t), intent(inout) :: status
    integer :: j, k, side
    real(real64) :: y_end
    character(len=:), allocatable :: name
    do j = 1, size(contacts)
      do side = -1, 1, 2
        if (side < 0) then
          k = nint((contacts(j)%y_lo - ys(1)) / search_step)
        else
          k = nint((contacts(j)%y_hi - ys(1)) / search_step) + 2
        end if
        if (k >= 1 .and. k <= size(d)) then
          if (d(k) < no_surface) cycle
        end if
        y_end = merge(contacts(j)%y_lo, contacts(j)%y_hi, side < 0)
        name = wheel_name
        if (abs(envelope_at(track%rail, y_end + side * search_step)) >= no_surface) name = rail_name
        call fail(status, exit_bad_input, where//'the contact at y = '//rtoa(contacts(j)%y)// &
                  ' mm (track) reaches the end of '//name//' at y = '//rtoa(y_end)// &
                  ' mm (track): the surface beyond its last point is '// &
                  'unknown (a profile measured too short, or a wrong rail_mirror, wheel_mirror or placement)')
        return
      end do
    end do
  end subroutine check_profile_ends

end module kcreep_wheel_rail_geometry
