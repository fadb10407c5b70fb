!> A wheel or rail profile: a lateral section (y, z), mm, z positive downwards.
!>
!> The points are joined by a natural cubic spline in their arc length (a
!> parametric curve), or by a smoothing spline of the same kind for measured
!> profiles: each coordinate f minimises
!>   sum_i w_i (f_i - g(s_i))^2 + lambda int g''(s)^2 ds,   w_i = (s_(i+1) - s_(i-1)) / 2,
!> (Reinsch's algorithm), lambda the `smoothing` of &wheel_rail in mm^4 (0:
!> the interpolating spline). With the weights w_i the sum is a length
!> integral and the spline a low-pass filter independent of the point
!> spacing: a wave of length L keeps the part 1 / (1 + lambda (2 pi / L)^4)
!> of its amplitude, half at L = 2 pi lambda^(1/4) (lambda = 1: 6.3 mm). This
!> is CONTACT's weighted spline (ISMOOTH = 1) with lambda = (L_FILT / 2 pi)^4;
!> CONTACT's default (ISMOOTH = 0) weighs every point by 1, so its lambda
!> (mm^3) is about kcreep's divided by the point spacing.
!>
!> Automatic smoothing (smoothing < 0, the default of &wheel_rail): the noise
!> of the points is measured (profile_noise); a profile with noise up to
!> noise_floor keeps the interpolating spline, a noisier one (a measured,
!> quantised profile) gets the lambda whose smoothed spline has a curvature
!> noise of curvature_noise (auto_smoothing).
!>
!> What the contact search needs of a profile is its envelope as seen from the
!> other body: the rail's top surface z_r(y) = min z over the section at y, the
!> wheel's outer surface z_w(y) = max z (the largest radius). The spline is
!> sampled densely (chords of at most sample_step), placed (rotated, shifted),
!> and the envelope is kept on a uniform y grid of envelope_step, read by
!> linear interpolation. Its error is z'' step^2 / 8 with z'' = kappa (1 +
!> z'^2)^(3/2) the envelope's second derivative in y, which is large on a
!> flange: at 70 degrees (z' = 2.7) on a 10 mm radius, 2.4 / mm. At a step of
!> 0.01 mm that was 3e-5 mm, a ripple with the period of the normal grid's
!> cells: the S1002 +8 mm flange patch moved by 0.1 % when its normal grid
!> was moved by half a cell, and the +7 mm row's C11 was 0.2 % apart between
!> normal grids; at 0.001 mm (3e-7 mm) the +8 mm patch's normal-grid part of
!> C11's estimate is 0.007 % instead of 0.083 % (docs/wheel_rail_checks.md, "Speed").
module kcreep_profile
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  implicit none
  private
  public :: profile_t, envelope_t, make_profile, sample_profile, make_envelope, envelope_at, envelope_at_slope, envelope_slope
  public :: no_surface, sample_step, envelope_step, min_profile_length, max_profile_length
  public :: profile_noise, profile_smoothing, auto_smoothing, noise_floor, curvature_noise, median_of
  public :: check_flange_side

  !> Envelope value where the profile does not cover y.
  real(real64), parameter :: no_surface = huge(1.0_real64)
  real(real64), parameter :: sample_step = 0.001_real64, envelope_step = 0.001_real64
  !> A profile's summed chord length must lie in this range (mm): outside it the
  !> units are wrong (CONTACT refuses the same range).
  real(real64), parameter :: min_profile_length = 5, max_profile_length = 500
  !> Automatic smoothing: a profile whose points scatter by at most this (mm,
  !> 1 sigma, profile_noise) about a smooth curve keeps the interpolating
  !> spline. Measured: the design profiles MBench_S1002_v3.prw and
  !> MBench_UIC60_v3.prr 5.6e-6 and 3.1e-6 mm, the measured MiniProf pair
  !> avg_wheel.whl and avg_HR.BAN 3.3e-3 mm each (written to 0.01 mm: a
  !> quantisation noise of 0.01 / sqrt(12) = 2.9e-3 mm); a file written to
  !> 4 decimals has 2.9e-5 mm.
  real(real64), parameter :: noise_floor = 1e-4_real64
  !> Automatic smoothing of a noisier profile: lambda such that the smoothed
  !> spline's curvature noise (1 sigma, 1/mm) is this. White noise sigma at
  !> spacing h through the filter above leaves a curvature noise
  !> sigma sqrt(h sqrt(2) / 16) lambda^(-5/8). Chosen on the measured worn
  !> pair (avg_wheel.whl on avg_HR.BAN, 70 kN, shifts -10 to 10 mm by 1 mm,
  !> docs/wheel_rail.md "Measured profiles"): with lambda 0 the tread rows'
  !> C11 is 7.4-8.2 (the spline follows the 0.01 mm steps); lambda from 0.1
  !> to 3 gives the same C11 within 0.3 % (4.880-4.901 on the tread), 0.01
  !> up to 0.7 % higher, 30 and 100 0.9 % and 2.6 % higher (the worn shape
  !> itself smoothed away). 5e-4 / mm puts this pair at lambda 1.0 (wheel,
  !> h 0.25 mm) and 1.7 (rail, h 0.50 mm), inside that plateau by a factor
  !> of 10 in lambda towards the noise and 2-3 towards the bias.
  real(real64), parameter :: curvature_noise = 5e-4_real64

  type :: profile_t
    real(real64), allocatable :: s(:)            !< arc length (chord sum) at the knots
    real(real64), allocatable :: y(:), z(:)      !< knot values (smoothed when smoothing > 0)
    real(real64), allocatable :: ypp(:), zpp(:)  !< second derivatives in s
  end type profile_t

  !> z of a surface on a uniform grid in y: v(k) at y_first + (k - 1) step.
  type :: envelope_t
    real(real64) :: y_first = 0, step = envelope_step
    real(real64), allocatable :: v(:)
    logical :: take_max = .false.                !< wheel: the largest z; rail: the smallest
  end type envelope_t

contains

  !> The spline of the points y, z (in their order; duplicates dropped).
  subroutine make_profile(y, z, smoothing, source, prof, status)
    real(real64), intent(in) :: y(:), z(:), smoothing
    character(len=*), intent(in) :: source
    type(profile_t), intent(out) :: prof
    type(status_t), intent(inout) :: status
    real(real64), allocatable :: yk(:), zk(:), s(:)
    integer :: i, n
    real(real64) :: lambda
    call distinct_points(y, z, yk, zk)
    n = size(yk)
    if (n < 4) then
      call fail(status, exit_bad_input, source//': '//itoa(n)//' distinct profile points (at least 4 needed)')
      return
    end if
    allocate (s(n))
    s(1) = 0
    do i = 2, n
      s(i) = s(i - 1) + hypot(yk(i) - yk(i - 1), zk(i) - zk(i - 1))
    end do
    if (.not. (s(n) >= min_profile_length .and. s(n) <= max_profile_length)) then
      call fail(status, exit_bad_input, source//': the profile is '//rtoa(s(n))//' mm long (summed chords; '// &
                'allowed '//rtoa(min_profile_length)//' to '//rtoa(max_profile_length)//' mm: lengths in mm?)')
      return
    end if
    if (.not. (smoothing <= 1e12_real64)) then
      call fail(status, exit_bad_input, source//': smoothing = '//rtoa(smoothing)// &
                ' (allowed 0 to 1e12 mm^4, or negative: automatic)')
      return
    end if
    lambda = profile_smoothing(yk, zk, smoothing)
    prof%s = s
    call smoothing_spline(s, yk, lambda, prof%y, prof%ypp)
    call smoothing_spline(s, zk, lambda, prof%z, prof%zpp)
  end subroutine make_profile

  !> A wheel profile (y after wheel_mirror, z down) has its flange on the
  !> gauge side, towards smaller y: refused when its lowest point (largest
  !> z) stands more than 5 mm below the median height (a flange, not a
  !> tread's curve) and lies in the field-side third of the profile's width
  !> (S1002 and the MiniProf avg_wheel.whl: within the gauge-side eighth).
  !> what: the wheel's name and its wheel_mirror, for the message.
  subroutine check_flange_side(y, z, what, status)
    real(real64), intent(in) :: y(:), z(:)
    character(len=*), intent(in) :: what
    type(status_t), intent(inout) :: status
    integer :: tip
    real(real64) :: lo, hi
    if (status%failed() .or. size(y) < 2) return
    tip = maxloc(z, 1)
    lo = minval(y)
    hi = maxval(y)
    if (z(tip) - median_of(z) > 5 .and. y(tip) > lo + 2 * (hi - lo) / 3) &
      call fail(status, exit_bad_input, what//': the flange (lowest point at y = '//rtoa(y(tip))// &
                ' mm) is on the field side of the profile ('//rtoa(lo)//' to '//rtoa(hi)// &
                ' mm); its y must grow away from the track centre: change wheel_mirror')
  end subroutine check_flange_side

  !> The points without repeats (a point closer than 1e-9 mm to the one before).
  pure subroutine distinct_points(y, z, yk, zk)
    real(real64), intent(in) :: y(:), z(:)
    real(real64), allocatable, intent(out) :: yk(:), zk(:)
    logical :: keep(size(y))
    integer :: i
    keep = .true.
    do i = 2, size(y)
      keep(i) = hypot(y(i) - y(i - 1), z(i) - z(i - 1)) > 1e-9_real64
    end do
    yk = pack(y, keep)
    zk = pack(z, keep)
  end subroutine distinct_points

  !> The lambda (mm^4) a profile is smoothed with: smoothing when >= 0, else
  !> automatic (auto_smoothing of its measured noise).
  pure real(real64) function profile_smoothing(y, z, smoothing) result(lambda)
    real(real64), intent(in) :: y(:), z(:), smoothing
    real(real64) :: sigma, h
    lambda = smoothing
    if (smoothing >= 0) return
    call profile_noise(y, z, sigma, h)
    lambda = auto_smoothing(sigma, h)
  end function profile_smoothing

  !> Automatic lambda for points with noise sigma at spacing h (both mm): 0 up
  !> to noise_floor, else the lambda of a curvature noise of curvature_noise.
  elemental real(real64) function auto_smoothing(sigma, h) result(lambda)
    real(real64), intent(in) :: sigma, h
    lambda = 0
    if (.not. sigma > noise_floor) return
    lambda = (sigma * sqrt(h * sqrt(2.0_real64) / 16) / curvature_noise)**1.6_real64
  end function auto_smoothing

  !> The noise of the points about a smooth curve (sigma, mm, 1 sigma) and
  !> their median spacing h (mm). Each interior point's distance from the
  !> chord of its neighbours, e_i, is the curve's kappa h^2 / 2 (slowly
  !> varying) plus n_i - (n_(i-1) + n_(i+1)) / 2 of the noise n normal to the
  !> curve; e_(i+1) - e_i removes the curve and leaves noise of variance
  !> 5 sigma^2. sigma from the median absolute deviation of those
  !> differences (1.4826 MAD: robust to kinks and a flange's few strongly
  !> curved points). 0 with fewer than 6 points.
  pure subroutine profile_noise(y, z, sigma, h)
    real(real64), intent(in) :: y(:), z(:)
    real(real64), intent(out) :: sigma, h
    real(real64), allocatable :: yk(:), zk(:), e(:), d(:)
    real(real64) :: cy, cz, c
    integer :: n, i
    call distinct_points(y, z, yk, zk)
    n = size(yk)
    sigma = 0
    h = 0
    if (n < 2) return
    h = median_of(hypot(yk(2:n) - yk(1:n - 1), zk(2:n) - zk(1:n - 1)))
    if (n < 6) return
    allocate (e(n - 2))
    do i = 2, n - 1
      cy = yk(i + 1) - yk(i - 1)
      cz = zk(i + 1) - zk(i - 1)
      c = max(hypot(cy, cz), tiny(1.0_real64))
      e(i - 1) = (cy * (zk(i) - zk(i - 1)) - cz * (yk(i) - yk(i - 1))) / c
    end do
    d = e(2:) - e(:size(e) - 1)
    sigma = 1.4826_real64 * median_of(abs(d - median_of(d))) / sqrt(5.0_real64)
  end subroutine profile_noise

  !> The median of v (the mean of the two middle values for an even count; 0 if empty).
  pure real(real64) function median_of(v) result(m)
    real(real64), intent(in) :: v(:)
    real(real64), allocatable :: w(:)
    integer :: n
    n = size(v)
    m = 0
    if (n == 0) return
    w = v
    call kth_smallest(w, (n + 1) / 2, m)
    if (mod(n, 2) == 0) m = (m + minval(w((n + 1) / 2 + 1:))) / 2
  end function median_of

  !> v: the k-th smallest of w (Hoare's selection; w is reordered so that
  !> w(1:k-1) <= w(k) <= w(k+1:)).
  pure subroutine kth_smallest(w, k, v)
    real(real64), intent(inout) :: w(:)
    integer, intent(in) :: k
    real(real64), intent(out) :: v
    integer :: lo, hi, i, j
    real(real64) :: pivot, t
    lo = 1
    hi = size(w)
    do while (lo < hi)
      pivot = w((lo + hi) / 2)
      i = lo
      j = hi
      do while (i <= j)
        do while (w(i) < pivot)
          i = i + 1
        end do
        do while (w(j) > pivot)
          j = j - 1
        end do
        if (i <= j) then
          t = w(i)
          w(i) = w(j)
          w(j) = t
          i = i + 1
          j = j - 1
        end if
      end do
      if (k <= j) then
        hi = j
      else if (k >= i) then
        lo = i
      else
        exit
      end if
    end do
    v = w(k)
  end subroutine kth_smallest

  !> Reinsch's smoothing spline (lambda = 0: the natural interpolating spline):
  !> values g at the knots and second derivatives gpp (natural ends).
  pure subroutine smoothing_spline(s, f, lambda, g, gpp)
    real(real64), intent(in) :: s(:), f(:), lambda
    real(real64), allocatable, intent(out) :: g(:), gpp(:)
    real(real64), allocatable :: h(:), w(:), band(:, :), rhs(:), qg(:)
    integer :: n, m, j, i
    n = size(s)
    m = n - 2
    h = s(2:n) - s(1:n - 1)
    allocate (w(n))
    w(1) = h(1) / 2
    w(n) = h(n - 1) / 2
    w(2:n - 1) = (h(1:n - 2) + h(2:n - 1)) / 2
    ! the symmetric pentadiagonal R + lambda Q^T W^-1 Q: band(0:2, j) = row j's diagonal and the two right of it
    allocate (band(0:2, m), rhs(m))
    band = 0
    do j = 1, m                         ! interior knot j + 1
      band(0, j) = (h(j) + h(j + 1)) / 3
      if (j < m) band(1, j) = h(j + 1) / 6
      rhs(j) = (f(j + 2) - f(j + 1)) / h(j + 1) - (f(j + 1) - f(j)) / h(j)
    end do
    if (lambda > 0) then
      ! Q's column j has q(j) = 1/h_j, q(j+1) = -1/h_j - 1/h_(j+1), q(j+2) = 1/h_(j+1) (knot indices)
      do j = 1, m
        do i = 0, 2
          if (j + i > m) cycle
          band(i, j) = band(i, j) + lambda * qwq(j, j + i)
        end do
      end do
    end if
    call solve_penta(band, rhs)
    allocate (gpp(n))
    gpp = 0
    gpp(2:n - 1) = rhs
    if (lambda > 0) then
      ! g = f - lambda W^-1 Q gamma
      allocate (qg(n))
      qg = 0
      do j = 1, m
        qg(j) = qg(j) + rhs(j) / h(j)
        qg(j + 1) = qg(j + 1) - rhs(j) * (1 / h(j) + 1 / h(j + 1))
        qg(j + 2) = qg(j + 2) + rhs(j) / h(j + 1)
      end do
      g = f - lambda * qg / w
    else
      g = f
    end if

  contains

    !> (Q^T W^-1 Q)(a, b) for interior columns a <= b <= a + 2.
    pure real(real64) function qwq(a, b) result(v)
      integer, intent(in) :: a, b
      integer :: k
      v = 0
      do k = b, a + 2                   ! knots where both columns are non-zero
        v = v + q(a, k) * q(b, k) / w(k)
      end do
    end function qwq

    pure real(real64) function q(col, k) result(v)
      integer, intent(in) :: col, k
      select case (k - col)
      case (0)
        v = 1 / h(col)
      case (1)
        v = -1 / h(col) - 1 / h(col + 1)
      case (2)
        v = 1 / h(col + 1)
      case default
        v = 0
      end select
    end function q

  end subroutine smoothing_spline

  !> Solve a symmetric positive definite pentadiagonal system in place (band
  !> Cholesky; band(0:2, j) row j's diagonal and upper entries; rhs becomes x).
  pure subroutine solve_penta(band, rhs)
    real(real64), intent(inout) :: band(0:, :), rhs(:)
    integer :: n, j, k, i
    real(real64), allocatable :: l(:, :)
    n = size(rhs)
    allocate (l(0:2, n))
    l = 0
    ! L L^T with L stored by columns: l(0, j) diagonal, l(1, j) = L(j+1, j), l(2, j) = L(j+2, j)
    do j = 1, n
      l(0, j) = band(0, j)
      do k = max(1, j - 2), j - 1
        l(0, j) = l(0, j) - l(j - k, k)**2
      end do
      l(0, j) = sqrt(max(l(0, j), tiny(1.0_real64)))
      do i = 1, 2
        if (j + i > n) cycle
        l(i, j) = band(i, j)
        do k = max(1, j + i - 2), j - 1
          l(i, j) = l(i, j) - l(j + i - k, k) * l(j - k, k)
        end do
        l(i, j) = l(i, j) / l(0, j)
      end do
    end do
    do j = 1, n                          ! L y = b
      do k = max(1, j - 2), j - 1
        rhs(j) = rhs(j) - l(j - k, k) * rhs(k)
      end do
      rhs(j) = rhs(j) / l(0, j)
    end do
    do j = n, 1, -1                      ! L^T x = y
      do k = j + 1, min(n, j + 2)
        rhs(j) = rhs(j) - l(k - j, j) * rhs(k)
      end do
      rhs(j) = rhs(j) / l(0, j)
    end do
  end subroutine solve_penta

  !> The spline sampled with chords of at most step (both ends included).
  pure subroutine sample_profile(prof, step, ys, zs)
    type(profile_t), intent(in) :: prof
    real(real64), intent(in) :: step
    real(real64), allocatable, intent(out) :: ys(:), zs(:)
    integer :: i, k, m, n, total
    real(real64) :: h, t, a, b
    n = size(prof%s)
    total = 1
    do i = 1, n - 1
      total = total + max(1, ceiling((prof%s(i + 1) - prof%s(i)) / step))
    end do
    allocate (ys(total), zs(total))
    ys(1) = prof%y(1)
    zs(1) = prof%z(1)
    m = 1
    do i = 1, n - 1
      h = prof%s(i + 1) - prof%s(i)
      k = max(1, ceiling(h / step))
      do total = 1, k
        t = real(total, real64) / k
        a = 1 - t
        b = t
        m = m + 1
        ys(m) = a * prof%y(i) + b * prof%y(i + 1) + ((a**3 - a) * prof%ypp(i) + (b**3 - b) * prof%ypp(i + 1)) * h**2 / 6
        zs(m) = a * prof%z(i) + b * prof%z(i + 1) + ((a**3 - a) * prof%zpp(i) + (b**3 - b) * prof%zpp(i + 1)) * h**2 / 6
      end do
    end do
  end subroutine sample_profile

  !> The envelope of the polyline ys, zs on a uniform y grid: at each grid y the
  !> smallest (take_max false) or largest z of the chords that cross it.
  pure subroutine make_envelope(ys, zs, take_max, env)
    real(real64), intent(in) :: ys(:), zs(:)
    logical, intent(in) :: take_max
    type(envelope_t), intent(out) :: env
    integer :: i, k, k1, k2, n
    real(real64) :: ya, yb, za, zb, yg, zg
    env%take_max = take_max
    env%step = envelope_step
    env%y_first = envelope_step * floor(minval(ys) / envelope_step)
    n = ceiling((maxval(ys) - env%y_first) / envelope_step) + 1
    allocate (env%v(n))
    env%v = merge(-no_surface, no_surface, take_max)
    do i = 1, size(ys) - 1
      ya = min(ys(i), ys(i + 1))
      yb = max(ys(i), ys(i + 1))
      za = merge(zs(i), zs(i + 1), ys(i) <= ys(i + 1))
      zb = merge(zs(i + 1), zs(i), ys(i) <= ys(i + 1))
      k1 = ceiling((ya - env%y_first) / envelope_step - 1e-9_real64) + 1
      k2 = floor((yb - env%y_first) / envelope_step + 1e-9_real64) + 1
      do k = max(k1, 1), min(k2, n)
        yg = env%y_first + (k - 1) * envelope_step
        if (yb - ya > 0) then
          zg = za + (zb - za) * min(max((yg - ya) / (yb - ya), 0.0_real64), 1.0_real64)
        else
          zg = merge(max(za, zb), min(za, zb), take_max)
        end if
        if (take_max) then
          env%v(k) = max(env%v(k), zg)
        else
          env%v(k) = min(env%v(k), zg)
        end if
      end do
    end do
  end subroutine make_envelope

  !> The envelope at y (linear between its samples); no_surface (rail) or
  !> -no_surface (wheel) where the profile does not reach.
  elemental real(real64) function envelope_at(env, y) result(z)
    type(envelope_t), intent(in) :: env
    real(real64), intent(in) :: y
    real(real64) :: dz
    call envelope_at_slope(env, y, z, dz)
  end function envelope_at

  !> envelope_at, and the slope dz/dy of the sample interval y lies in
  !> (0 where the profile does not reach).
  elemental subroutine envelope_at_slope(env, y, z, dz)
    type(envelope_t), intent(in) :: env
    real(real64), intent(in) :: y
    real(real64), intent(out) :: z, dz
    real(real64) :: t
    integer :: k
    dz = 0
    t = (y - env%y_first) / env%step
    k = floor(t) + 1
    if (k < 1 .or. k >= size(env%v) .or. t /= t) then
      z = merge(-no_surface, no_surface, env%take_max)
      return
    end if
    if (abs(env%v(k)) >= no_surface .or. abs(env%v(k + 1)) >= no_surface) then
      z = merge(-no_surface, no_surface, env%take_max)
      return
    end if
    t = t - (k - 1)
    z = (1 - t) * env%v(k) + t * env%v(k + 1)
    dz = (env%v(k + 1) - env%v(k)) / env%step
  end subroutine envelope_at_slope

  !> dz/dy of the envelope at y by a central difference over +-half (mm).
  elemental real(real64) function envelope_slope(env, y, half) result(dz)
    type(envelope_t), intent(in) :: env
    real(real64), intent(in) :: y, half
    real(real64) :: a, b
    a = envelope_at(env, y - half)
    b = envelope_at(env, y + half)
    if (abs(a) >= no_surface .or. abs(b) >= no_surface) then
      dz = 0
    else
      dz = (b - a) / (2 * half)
    end if
  end function envelope_slope

end module kcreep_profile
