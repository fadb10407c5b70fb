!> A wheel or rail profile: a lateral section (y, z), mm, z positive downwards.
!>
!> The points are joined by a natural cubic spline in their arc length (a
!> parametric curve, so flanks and undercuts are kept), or by a smoothing
!> spline of the same kind for measured profiles: each coordinate f minimises
!>   sum_i w_i (f_i - g(s_i))^2 + lambda int g''(s)^2 ds,   w_i = (s_(i+1) - s_(i-1)) / 2,
!> (Reinsch's algorithm; CONTACT's weighted spline, Vollebregt 2020), lambda the
!> `smoothing` of &wheel_rail in mm^3 (0: the interpolating spline).
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
!> C11's estimate is 0.007 % instead of 0.083 % (docs/wheel_rail.md, "Speed").
module kcreep_profile
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  implicit none
  private
  public :: profile_t, envelope_t, make_profile, sample_profile, make_envelope, envelope_at, envelope_slope
  public :: no_surface, sample_step, envelope_step, min_profile_length, max_profile_length

  !> Envelope value where the profile does not cover y.
  real(real64), parameter :: no_surface = huge(1.0_real64)
  real(real64), parameter :: sample_step = 0.001_real64, envelope_step = 0.001_real64
  !> A profile's summed chord length must lie in this range (mm): outside it the
  !> units are wrong (CONTACT refuses the same range).
  real(real64), parameter :: min_profile_length = 5, max_profile_length = 500

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
    logical, allocatable :: keep(:)

    allocate (keep(size(y)))
    keep = .true.
    do i = 2, size(y)
      keep(i) = hypot(y(i) - y(i - 1), z(i) - z(i - 1)) > 1e-9_real64
    end do
    yk = pack(y, keep)
    zk = pack(z, keep)
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
    if (.not. (smoothing >= 0 .and. smoothing < 1e12_real64)) then
      call fail(status, exit_bad_input, source//': smoothing = '//rtoa(smoothing)//' (allowed 0 to 1e12 mm^3)')
      return
    end if
    prof%s = s
    call smoothing_spline(s, yk, smoothing, prof%y, prof%ypp)
    call smoothing_spline(s, zk, smoothing, prof%z, prof%zpp)
  end subroutine make_profile

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
    real(real64) :: t
    integer :: k
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
  end function envelope_at

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
