!> A fast force model of one patch, held to the exact steady-rolling theory:
!> a table of exact solutions (kcreep_rolling_curve, which builds it) over
!> normalised creepages with a smooth interpolant.
!>
!> Scaling: for a given patch and pressure the exact forces obey
!>   F(mu, xi, eta, phi) = mu F(1, xi/mu, eta/mu, phi/mu)
!> (tractions p = mu p1 solve the problem with bound mu pn), so one function
!> of three normalised creepages, F1(c), c = (xi, eta, phi)/mu, holds the
!> whole force surface. It is also odd: F1(-c) = -F1(c).
!>
!> Coordinates: z = K T c, T the creepage about the patch's centre (xc, yc)
!> (xi - phi yc, eta + phi xc, phi), K = diag(f11, f22, f22 r)/Fn
!> (r = sqrt(area/pi); f the linear coefficients of the exact solver, Fn the
!> normal force): |z| about 3 saturates a pure creepage on an ellipse.
!> Magnitude s = |z|/(1 + |z|) in [0, 1), s = 1 the full-slip limit (no
!> elastic slip). Direction: polar angle theta of z from the spin axis
!> (theta = pi/2 the pure creepages), azimuth lambda in the (xi, eta) plane.
!>
!> Nodes: theta on nt intervals from the pole to the equator, lambda on np
!> points, s on ns intervals, the last two spaced to follow the forces near
!> full slip. In s: uniform in sigma, s = sigma + (sigma^3 - sigma^5)/2
!> (magnitude_of_node), so 1 - s ~ (1 - sigma)^2: with spin, forces on long
!> patches approach the full-slip force as sqrt(1 - s), which is smooth in
!> sigma. In lambda: uniform in u, lambda = u - w/2 sin 2(u - lambda_dense)
!> (warped_azimuth), w = (a - b)/(a + b) from the pressure's principal
!> extents a >= b: dense where the spin pole (-eta, xi)/phi runs along the
!> patch's long axis, where the full-slip force turns within a degree or two
!> (near its ends, the pole moves by the patch's length times the azimuth's
!> step). The rays of theta <= pi/2 are solved (the
!> others by oddness; on the short rings near the pole every second or
!> fourth, the rest interpolated, fast_model_ring_stride), s = 1 is the
!> full-slip force. Interpolant: tensor
!> cubic B-splines interpolating the nodes: periodic in theta over the
!> doubled circle [0, 2 pi) (a point (theta, lambda) with theta > pi is
!> (2 pi - theta, lambda + pi), so each meridian pair is one periodic great
!> circle), periodic in lambda, and in s odd through s = 0 (F = 0 there)
!> with a natural end at s = 1.
module kcreep_fast_model
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_lapack, only: dgetrf, dgetrs
  implicit none
  private
  public :: fast_model_t, fast_model_grid, fast_model_ray, fast_model_fit, fast_model_forces
  public :: fast_model_theta_intervals, fast_model_lambda_points, fast_model_s_intervals
  public :: fast_model_ring_stride, fast_model_fill_ring

  real(real64), parameter :: pi = acos(-1.0_real64)

  !> The table's resolution. Measured against kcreep_rolling at 1000 random creepages
  !> (|z| log-uniform 1e-5 to 30, directions uniform; |F - F_exact| / (mu Fn), F = (Fx, Fy)),
  !> Hertzian ellipses a/b = 0.2, 1, 5 and an L-shaped mask, 260-432 cells: theta 7.5 deg,
  !> lambda 11.25 deg, s 1/16 (uniform): worst 0.54-1.16 %, 95th percentile 0.07-0.11 %;
  !> lambda 22.5 deg: worst 2.4 % (a/b = 5) and 4.2 % (a/b = 0.2), where the spin pole
  !> crosses the patch's narrow side near full slip; s 1/12: worst 1.8 %; theta 15 deg:
  !> 1.7 % on the circle alone (a table twice as fine held out). The spacing near full slip
  !> (header) on S1002's flange strip at 8 mm (15:1, 2254 cells, 300 points, built
  !> directly): worst 3.95 -> 1.23 %; 20 intervals in sigma, not 16, keep the spacing at
  !> s = 0.6-0.75 (saturation of pure creepage, sigma's steepest part) that of 16 in s
  !> (16 gave the circle 0.62 % instead of 0.26 %). lab/notes/rolling_speed.md.
  integer, parameter :: fast_model_theta_intervals = 12

  !> Patches longer than this many times their width (the pressure's principal extents)
  !> take twice the polar intervals: where the spin pole crosses a long patch's ends (tan
  !> theta = a / r, 76 deg on S1002's 15:1 flange strips) one polar step moved the pole by
  !> half the strip's length, and a lateral creepage with a little spin was up to 5 % of
  !> mu Fn off near full slip (8 mm, 2254 cells: largest 3.97 -> 0.95 % at 300 random
  !> creepages, builds 3.7 -> 7.4 s). Patches up to 8:1 keep 12 (issue 48 asks for builds of 2 s).
  real(real64), parameter :: long_patch_ratio = 8
  integer, parameter :: fast_model_lambda_points = 32
  integer, parameter :: fast_model_s_intervals = 20

  type :: fast_model_t
    logical :: ready = .false.
    integer :: nt = 0, np = 0, ns = 0
    real(real64) :: m(3, 3) = 0                  !< z = m creep / mu (K T)
    real(real64) :: m_inverse(3, 3) = 0
    !> the azimuth's nodes: lambda = u - warp/2 sin(2 (u - lambda_dense)), u uniform
    real(real64) :: warp = 0, lambda_dense = 0
    !> B-spline coefficients (3, 0:4 nt - 1, 0:np - 1, -1:ns + 1): (Fx, Fy, Mz) at mu = 1
    real(real64), allocatable :: coef(:, :, :, :)
  end type fast_model_t

contains

  !> Every how many azimuths ring i (polar angle theta_i = i pi / (2 nt)) is solved: rings
  !> near the spin pole are short (circumference sin theta_i), so they are sampled in
  !> proportion, np / stride >= np sin theta_i with stride a power of 2 (a subset of the
  !> ring's nodes), at least 8 a ring; the other nodes by trigonometric interpolation
  !> (fast_model_fill_ring). The arc between solved rays then stays at most the equator's.
  pure integer function fast_model_ring_stride(model, i) result(stride)
    type(fast_model_t), intent(in) :: model
    integer, intent(in) :: i
    real(real64) :: needed
    stride = 1
    if (i <= 0 .or. i >= model%nt) return
    needed = model%np * sin(0.5_real64 * pi * i / model%nt)
    do while (mod(model%np, 2 * stride) == 0 .and. model%np / (2 * stride) >= max(8.0_real64, needed))
      stride = 2 * stride
    end do
  end function fast_model_ring_stride

  !> Ring values v(3, 0:np - 1, ns) given at every stride-th azimuth: the others by the
  !> trigonometric interpolant of those (k = np / stride even: sum_j v_j sin(k x / 2)
  !> cot(x / 2) / k, x the angle from node j).
  pure subroutine fast_model_fill_ring(model, stride, v)
    type(fast_model_t), intent(in) :: model
    integer, intent(in) :: stride
    real(real64), intent(inout) :: v(:, 0:, :)
    real(real64) :: x, weight
    integer :: j, l, k
    if (stride <= 1) return
    k = model%np / stride
    do j = 0, model%np - 1
      if (mod(j, stride) == 0) cycle
      v(:, j, :) = 0
      do l = 0, model%np - 1, stride
        x = 2 * pi * (j - l) / model%np
        weight = sin(0.5_real64 * k * x) / (k * tan(0.5_real64 * x))
        v(:, j, :) = v(:, j, :) + weight * v(:, l, :)
      end do
    end do
  end subroutine fast_model_fill_ring

  !> An empty model with the grid's sizes: scales k (> 0), the patch's centre (about the
  !> spin centre) and its pressure's covariance about that centre (mm^2; the azimuth's
  !> spacing); sizes: (nt, np, ns) other than the table's resolution above (np even).
  pure subroutine fast_model_grid(k, centre, covariance, model, sizes)
    real(real64), intent(in) :: k(3), centre(2), covariance(2, 2)
    type(fast_model_t), intent(out) :: model
    integer, intent(in), optional :: sizes(3)
    real(real64) :: t(3, 3), half_trace, deviation, major, minor, axis
    model%nt = fast_model_theta_intervals
    model%np = fast_model_lambda_points
    model%ns = fast_model_s_intervals
    if (present(sizes)) then
      model%nt = sizes(1)
      model%np = sizes(2)
      model%ns = sizes(3)
    end if
    t = reshape([1.0_real64, 0.0_real64, 0.0_real64, 0.0_real64, 1.0_real64, 0.0_real64, &
                 -centre(2), centre(1), 1.0_real64], [3, 3])
    model%m = spread(k, 2, 3) * t
    ! T^-1 K^-1: the creepage back from z
    t(1, 3) = centre(2)
    t(2, 3) = -centre(1)
    model%m_inverse = t * spread(1 / k, 1, 3)
    ! the pressure's principal axes: the long axis at angle axis, extents major >= minor
    half_trace = 0.5_real64 * (covariance(1, 1) + covariance(2, 2))
    deviation = hypot(0.5_real64 * (covariance(1, 1) - covariance(2, 2)), covariance(1, 2))
    major = sqrt(max(half_trace + deviation, 0.0_real64))
    minor = sqrt(max(half_trace - deviation, 0.0_real64))
    axis = 0.5_real64 * atan2(2 * covariance(1, 2), covariance(1, 1) - covariance(2, 2))
    ! the pole (-eta, xi)/phi along the long axis: (xi, eta) along (sin axis, -cos axis)
    model%lambda_dense = atan2(-k(2) * cos(axis), k(1) * sin(axis))
    model%warp = 0
    if (major > 0) model%warp = min(0.9_real64, (major - minor) / (major + minor))
    if (major > long_patch_ratio * minor) model%nt = 2 * model%nt
    allocate (model%coef(3, 0:4 * model%nt - 1, 0:model%np - 1, -1:model%ns + 1))
    model%coef = 0
  end subroutine fast_model_grid

  !> The normalised creepages (mu = 1) of ray (i, j) at the nodes s = 1 .. ns - 1
  !> (s = 1 itself is the full-slip limit along dir), and the direction dir in creepage
  !> space (|z| = 1). i = 0 .. nt (pole to equator), j = 0 .. np - 1.
  pure subroutine fast_model_ray(model, i, j, creep, dir)
    type(fast_model_t), intent(in) :: model
    integer, intent(in) :: i, j
    real(real64), intent(out) :: creep(3, model%ns - 1), dir(3)
    real(real64) :: theta, lambda, z(3), s, t
    integer :: m
    theta = 0.5_real64 * pi * i / model%nt
    lambda = warped_azimuth(model, 2 * pi * j / model%np)
    z = [sin(theta) * cos(lambda), sin(theta) * sin(lambda), cos(theta)]
    dir = matmul(model%m_inverse, z)
    do m = 1, model%ns - 1
      s = magnitude_of_node(real(m, real64) / model%ns)
      t = s / (1 - s)
      creep(:, m) = t * dir
    end do
  end subroutine fast_model_ray

  !> The spline coefficients from the node values v(3, 0:nt, 0:np - 1, 1:ns) (forces at
  !> mu = 1; s = 1 in v(:, :, :, ns)); every (i, j) filled (i = 0: one value, i = nt,
  !> j >= np/2: -v(:, nt, j - np/2, :)). info /= 0: a factorisation failed.
  subroutine fast_model_fit(model, v, info)
    type(fast_model_t), intent(inout) :: model
    real(real64), intent(in) :: v(:, 0:, 0:, :)
    integer, intent(out) :: info
    real(real64), allocatable :: g(:, :, :, :), a(:, :), b(:, :)
    integer, allocatable :: piv(:)
    integer :: nth, np, ns, nt, i, j, a_i, jj, m, c
    nt = model%nt
    np = model%np
    ns = model%ns
    nth = 4 * nt
    allocate (g(3, 0:nth - 1, 0:np - 1, 1:ns))
    ! the doubled circle in theta: theta_i, i = 0 .. 4 nt - 1
    do i = 0, nth - 1
      do j = 0, np - 1
        a_i = i
        jj = j
        if (i > 2 * nt) then
          a_i = 4 * nt - i
          jj = modulo(j + np / 2, np)
        end if
        if (a_i <= nt) then
          g(:, i, j, :) = v(:, a_i, jj, :)
        else
          g(:, i, j, :) = -v(:, 2 * nt - a_i, modulo(jj + np / 2, np), :)
        end if
      end do
    end do
    ! theta: periodic
    call cyclic_matrix(nth, a, piv, info)
    if (info /= 0) return
    allocate (b(nth, 3 * np * ns))
    do c = 1, 3
      do m = 1, ns
        do j = 0, np - 1
          b(:, c + 3 * (j + np * (m - 1))) = g(c, :, j, m)
        end do
      end do
    end do
    call dgetrs('N', nth, size(b, 2), a, nth, piv, b, nth, info)
    do c = 1, 3
      do m = 1, ns
        do j = 0, np - 1
          g(c, :, j, m) = b(:, c + 3 * (j + np * (m - 1)))
        end do
      end do
    end do
    deallocate (b)
    ! lambda: periodic
    call cyclic_matrix(np, a, piv, info)
    if (info /= 0) return
    allocate (b(np, 3 * nth * ns))
    do c = 1, 3
      do m = 1, ns
        do i = 0, nth - 1
          b(:, c + 3 * (i + nth * (m - 1))) = g(c, i, :, m)
        end do
      end do
    end do
    call dgetrs('N', np, size(b, 2), a, np, piv, b, np, info)
    do c = 1, 3
      do m = 1, ns
        do i = 0, nth - 1
          g(c, i, :, m) = b(:, c + 3 * (i + nth * (m - 1)))
        end do
      end do
    end do
    deallocate (b)
    ! s: c_0 = 0 (odd), c_{ns+1} = 2 c_ns - c_{ns-1} (natural end): rows m = 1 .. ns
    deallocate (a, piv)
    allocate (a(ns, ns), piv(ns))
    a = 0
    do m = 1, ns
      a(m, m) = 4.0_real64 / 6
      if (m > 1) a(m, m - 1) = 1.0_real64 / 6
      if (m < ns) then
        a(m, m + 1) = 1.0_real64 / 6
      else
        a(m, m) = a(m, m) + 2.0_real64 / 6
        a(m, m - 1) = a(m, m - 1) - 1.0_real64 / 6
      end if
    end do
    call dgetrf(ns, ns, a, ns, piv, info)
    if (info /= 0) return
    allocate (b(ns, 3 * nth * np))
    do c = 1, 3
      do j = 0, np - 1
        do i = 0, nth - 1
          b(:, c + 3 * (i + nth * j)) = g(c, i, j, :)
        end do
      end do
    end do
    call dgetrs('N', ns, size(b, 2), a, ns, piv, b, ns, info)
    do c = 1, 3
      do j = 0, np - 1
        do i = 0, nth - 1
          model%coef(c, i, j, 1:ns) = b(:, c + 3 * (i + nth * j))
        end do
      end do
    end do
    model%coef(:, :, :, 0) = 0
    model%coef(:, :, :, -1) = -model%coef(:, :, :, 1)
    model%coef(:, :, :, ns + 1) = 2 * model%coef(:, :, :, ns) - model%coef(:, :, :, ns - 1)
    model%ready = info == 0

  contains

    !> LU of the periodic interpolation matrix (1, 4, 1)/6 of n nodes.
    subroutine cyclic_matrix(n, mat, pivots, status)
      integer, intent(in) :: n
      real(real64), allocatable, intent(out) :: mat(:, :)
      integer, allocatable, intent(out) :: pivots(:)
      integer, intent(out) :: status
      integer :: r
      allocate (mat(n, n), pivots(n))
      mat = 0
      do r = 1, n
        mat(r, r) = 4.0_real64 / 6
        mat(r, modulo(r - 2, n) + 1) = mat(r, modulo(r - 2, n) + 1) + 1.0_real64 / 6
        mat(r, modulo(r, n) + 1) = mat(r, modulo(r, n) + 1) + 1.0_real64 / 6
      end do
      call dgetrf(n, n, mat, n, pivots, status)
    end subroutine cyclic_matrix

  end subroutine fast_model_fit

  !> Forces (Fx, Fy, Mz) of the creepages creep(3, n) at friction mu > 0 on the model's
  !> patch and pressure: mu F1(creep / mu).
  pure subroutine fast_model_forces(model, mu, creep, force)
    type(fast_model_t), intent(in) :: model
    real(real64), intent(in) :: mu, creep(:, :)
    real(real64), intent(out) :: force(:, :)
    real(real64) :: z(3), t, s, theta, lambda, x, y, w, wt(4), wl(4), ws(4), acc(3), row(3)
    integer :: p, i0, j0, k0, a, b, ia, jb, nth
    nth = 4 * model%nt
    do p = 1, size(creep, 2)
      z = matmul(model%m, creep(:, p)) / mu
      t = norm2(z)
      if (.not. (t > 0)) then
        force(:, p) = 0
        cycle
      end if
      if (t > huge(t) / 4) then
        s = 1
      else
        s = t / (1 + t)
      end if
      theta = atan2(hypot(z(1), z(2)), z(3))
      lambda = atan2(z(2), z(1))
      x = theta / (0.5_real64 * pi) * model%nt
      y = modulo(azimuth_node(model, lambda) / (2 * pi) * model%np, real(model%np, real64))
      w = node_of_magnitude(s) * model%ns
      i0 = min(int(x), nth - 1)
      j0 = min(int(y), model%np - 1)
      k0 = min(int(w), model%ns - 1)
      wt = bspline_weights(x - i0)
      wl = bspline_weights(y - j0)
      ws = bspline_weights(w - k0)
      acc = 0
      do a = 1, 4
        ia = modulo(i0 - 2 + a, nth)
        row = 0
        do b = 1, 4
          jb = modulo(j0 - 2 + b, model%np)
          row = row + wl(b) * matmul(model%coef(:, ia, jb, k0 - 1:k0 + 2), ws)
        end do
        acc = acc + wt(a) * row
      end do
      force(:, p) = mu * acc
    end do
  end subroutine fast_model_forces

  !> The azimuth lambda of node coordinate u: nodes dense (d lambda / du = 1 - warp) at
  !> lambda_dense and its opposite, where the spin pole runs along a long patch: there the
  !> full-slip forces turn within a few degrees.
  pure real(real64) function warped_azimuth(model, u) result(lambda)
    type(fast_model_t), intent(in) :: model
    real(real64), intent(in) :: u
    lambda = u - 0.5_real64 * model%warp * sin(2 * (u - model%lambda_dense))
  end function warped_azimuth

  !> The node coordinate u of azimuth lambda (warped_azimuth's inverse by Newton: its slope
  !> is at least 1 - warp >= 0.1).
  pure real(real64) function azimuth_node(model, lambda) result(u)
    type(fast_model_t), intent(in) :: model
    real(real64), intent(in) :: lambda
    real(real64) :: residual
    integer :: step
    u = lambda
    if (model%warp == 0) return
    do step = 1, 30
      residual = warped_azimuth(model, u) - lambda
      u = u - residual / (1 - model%warp * cos(2 * (u - model%lambda_dense)))
      if (abs(residual) < 1e-13_real64) exit
    end do
  end function azimuth_node

  !> The magnitude s of node coordinate sigma in [0, 1]: s = sigma + (sigma^3 - sigma^5) / 2,
  !> odd, increasing, s(1) = 1 with slope 0 there (1 - s ~ 3.5 (1 - sigma)^2).
  pure real(real64) function magnitude_of_node(sigma) result(s)
    real(real64), intent(in) :: sigma
    s = sigma + 0.5_real64 * (sigma**3 - sigma**5)
  end function magnitude_of_node

  !> The node coordinate sigma of magnitude s in [0, 1], magnitude_of_node's inverse:
  !> Newton on sqrt(1 - s(sigma)) = sqrt(1 - s), nearly linear in sigma up to 1, kept
  !> inside a bracket that each step narrows.
  pure real(real64) function node_of_magnitude(s) result(sigma)
    real(real64), intent(in) :: s
    real(real64) :: target, low, high, gap, residual, slope
    integer :: step
    sigma = 1
    if (s >= 1) return
    target = sqrt(1 - s)
    low = 0
    high = 1
    sigma = s
    do step = 1, 60
      gap = sqrt(max(0.0_real64, 1 - magnitude_of_node(sigma)))
      residual = gap - target
      if (abs(residual) <= 1e-15_real64) exit
      if (residual > 0) then
        low = sigma
      else
        high = sigma
      end if
      slope = -(1 + 1.5_real64 * sigma**2 - 2.5_real64 * sigma**4) / (2 * max(gap, tiny(1.0_real64)))
      sigma = sigma - residual / slope
      if (.not. (sigma > low .and. sigma < high)) sigma = 0.5_real64 * (low + high)
      if (high - low < 1e-15_real64) exit
    end do
  end function node_of_magnitude

  !> Cubic B-spline weights of the nodes -1, 0, 1, 2 at u in [0, 1].
  pure function bspline_weights(u) result(wgt)
    real(real64), intent(in) :: u
    real(real64) :: wgt(4)
    wgt = [(1 - u)**3, (3 * u - 6) * u * u + 4, ((-3 * u + 3) * u + 3) * u + 1, u**3] / 6
  end function bspline_weights

end module kcreep_fast_model
