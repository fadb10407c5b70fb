!> Hertz's closed forms for the elliptic contact of two bodies whose
!> undeformed distance is h = A x^2 + B y^2 (A = 1/(2 Rx), B = 1/(2 Ry)),
!> combined compliance c = 1/E* (Johnson, Contact Mechanics, sec. 4.2).
!>
!> With semi-axis a along x, b along y, k = (minor axis)/(major axis),
!> e^2 = 1 - k^2 and the complete elliptic integrals K(e), E(e):
!>   p = p0 sqrt(1 - x^2/a^2 - y^2/b^2),  Fn = 2/3 pi a b p0,
!>   delta = c p0 b K (b the minor semi-axis), and for the major axis a
!>   (along the smaller curvature A): A = c p0 b (K - E)/(a^2 e^2),
!>   B = c p0 b (E/k^2 - K)/(a^2 e^2) ... hence B/A fixes k.
!> K - E and E - k^2 K are written as K e^2 (1/2 +- q) with the AGM sum
!> q = sum_{n>=1} 2^(n-1) c_n^2 / e^2, free of cancellation down to the circle.
module kcreep_hertz
  use, intrinsic :: iso_fortran_env, only: real64
  implicit none
  private
  public :: hertz_t, hertz_from_force, hertz_from_approach

  real(real64), parameter :: pi = acos(-1.0_real64)

  type :: hertz_t
    real(real64) :: a = 0, b = 0        !< semi-axes along x and y
    real(real64) :: p0 = 0              !< maximum pressure
    real(real64) :: approach = 0        !< delta
    real(real64) :: fn = 0              !< total force
  end type hertz_t

contains

  !> K(k') for modulus k = sqrt(1 - e^2) given as the ratio k (0 < k <= 1),
  !> and q as defined above.
  pure subroutine agm(k, kk, q)
    real(real64), intent(in) :: k
    real(real64), intent(out) :: kk, q
    real(real64) :: an, bn, cn, e2, an1, w
    integer :: n
    e2 = (1 - k) * (1 + k)
    an = 1
    bn = k
    q = 0
    w = 1
    do n = 1, 60
      an1 = (an + bn) / 2
      if (n == 1) then
        cn = e2 / (4 * an1)            ! c_1 = (1 - k)/2 without cancellation
      else
        cn = cn**2 / (4 * an1)         ! c_{n} = c_{n-1}^2 / (4 a_n)
      end if
      bn = sqrt(an * bn)
      an = an1
      if (e2 > 0) q = q + w * cn**2 / e2
      w = 2 * w
      if (cn <= epsilon(1.0_real64) * an) exit
    end do
    kk = pi / (2 * an)
  end subroutine agm

  !> k = minor/major semi-axis ratio for curvature ratio rho = Bmax/Amin >= 1.
  pure real(real64) function axis_ratio(rho) result(k)
    real(real64), intent(in) :: rho
    real(real64) :: lo, hi, kk, q, f
    integer :: it
    if (rho <= 1) then
      k = 1
      return
    end if
    ! f(k) = (1/2 - q)/(k^2 (1/2 + q)) decreases from infinity (k -> 0) to 1 (k = 1)
    lo = 0
    hi = 1
    do it = 1, 200
      k = (lo + hi) / 2
      call agm(k, kk, q)
      f = (0.5_real64 - q) / (k**2 * (0.5_real64 + q))
      if (f > rho) then
        lo = k
      else
        hi = k
      end if
      if (hi - lo <= 4 * epsilon(1.0_real64) * hi) exit
    end do
    k = (lo + hi) / 2
  end function axis_ratio

  !> Hertz's solution for total force fn.
  pure type(hertz_t) function hertz_from_force(a_curv, b_curv, compliance, fn) result(hz)
    real(real64), intent(in) :: a_curv, b_curv, compliance, fn
    real(real64) :: amin, k, kk, q, major, minor
    amin = min(a_curv, b_curv)
    k = axis_ratio(max(a_curv, b_curv) / amin)
    call agm(k, kk, q)
    ! a^3 = 3 Fn c K (1/2 + q) / (2 pi A) (A the smaller curvature, a the major axis)
    major = (3 * fn * compliance * kk * (0.5_real64 + q) / (2 * pi * amin))**(1.0_real64 / 3)
    minor = k * major
    hz%fn = fn
    hz%p0 = 3 * fn / (2 * pi * major * minor)
    hz%approach = compliance * hz%p0 * minor * kk
    call orient(a_curv, b_curv, major, minor, hz)
  end function hertz_from_force

  !> Hertz's solution for approach delta.
  pure type(hertz_t) function hertz_from_approach(a_curv, b_curv, compliance, delta) result(hz)
    real(real64), intent(in) :: a_curv, b_curv, compliance, delta
    real(real64) :: amin, k, kk, q, major, minor
    amin = min(a_curv, b_curv)
    k = axis_ratio(max(a_curv, b_curv) / amin)
    call agm(k, kk, q)
    major = sqrt(delta * (0.5_real64 + q) / amin)
    minor = k * major
    hz%approach = delta
    hz%p0 = delta / (compliance * minor * kk)
    hz%fn = 2 * pi * major * minor * hz%p0 / 3
    call orient(a_curv, b_curv, major, minor, hz)
  end function hertz_from_approach

  !> The major axis lies along the direction of the smaller curvature.
  pure subroutine orient(a_curv, b_curv, major, minor, hz)
    real(real64), intent(in) :: a_curv, b_curv, major, minor
    type(hertz_t), intent(inout) :: hz
    if (a_curv <= b_curv) then
      hz%a = major
      hz%b = minor
    else
      hz%a = minor
      hz%b = major
    end if
  end subroutine orient

end module kcreep_hertz
