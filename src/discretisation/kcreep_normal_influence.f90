!> Normal influence coefficients of the two-body half-space problem on a
!> uniform grid: piecewise-constant pressure per rectangular cell, normal
!> displacement difference collocated at the cell centres.
!>
!> A uniform pressure p on the rectangle |x'| <= a, |y'| <= b of one
!> half-space displaces its surface normally by (Love 1929; Johnson,
!> Contact Mechanics, sec. 3.4)
!>   u(x, y) = (1 - nu^2) / (pi E) p Int Int dx' dy' / r,
!> and the double integral has the closed form (corner sum of the
!> antiderivative F(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|)). For two bodies
!> the displacement differences add: the factor becomes c / pi with the
!> combined compliance
!>   c = 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 = (1 - nu1)/(2 G1) + (1 - nu2)/(2 G2),
!> which is (1 - nu)/G for quasi-identical bodies with the combined G and nu
!> of the tangential problem (1/G = (1/G1 + 1/G2)/2, nu/G = (nu1/G1 + nu2/G2)/2).
!> This is the piecewise-constant family of Kalker's CONTACT (digit C = 2).
module kcreep_normal_influence
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_influence, only: rectangle_integral, rectangle_offset_table   ! the same 1/r integral as the tangential kernel's
  implicit none
  private
  public :: normal_cell_coefficient, normal_offset_table, compliance_from_g_nu, compliance_from_e_nu
  public :: combined_g_nu_from_e_nu, rectangle_integral

  real(real64), parameter :: pi = acos(-1.0_real64)

contains

  !> Combined compliance 1/E* of two quasi-identical bodies from the combined G and nu.
  elemental real(real64) function compliance_from_g_nu(g, nu) result(c)
    real(real64), intent(in) :: g, nu
    c = (1 - nu) / g
  end function compliance_from_g_nu

  !> Combined compliance 1/E* of two bodies with Young's moduli e1, e2 and Poisson ratios nu1, nu2.
  elemental real(real64) function compliance_from_e_nu(e1, nu1, e2, nu2) result(c)
    real(real64), intent(in) :: e1, nu1, e2, nu2
    c = (1 - nu1**2) / e1 + (1 - nu2**2) / e2
  end function compliance_from_e_nu

  !> The combined shear modulus and Poisson ratio of the tangential problem
  !> (CONTACT's convention) from Young's moduli and Poisson ratios per body.
  pure subroutine combined_g_nu_from_e_nu(e1, nu1, e2, nu2, g, nu)
    real(real64), intent(in) :: e1, nu1, e2, nu2
    real(real64), intent(out) :: g, nu
    real(real64) :: g1, g2
    g1 = e1 / (2 * (1 + nu1))
    g2 = e2 / (2 * (1 + nu2))
    g = 2 / (1 / g1 + 1 / g2)
    nu = g * (nu1 / g1 + nu2 / g2) / 2
  end subroutine combined_g_nu_from_e_nu

  !> Normal displacement difference at (xr, yr) (relative to the cell centre)
  !> from a unit pressure on a cell of sizes dx x dy; compliance = 1/E*.
  elemental real(real64) function normal_cell_coefficient(xr, yr, dx, dy, compliance) result(c)
    real(real64), intent(in) :: xr, yr, dx, dy, compliance
    c = compliance / pi * rectangle_integral(xr, yr, dx / 2, dy / 2)
  end function normal_cell_coefficient

  !> The coefficient for every index offset of an mx x my grid,
  !> table(i, j) for offsets i = 0..mx-1, j = 0..my-1 (the kernel is even
  !> in both offsets, so negative offsets use the absolute values).
  pure subroutine normal_offset_table(mx, my, dx, dy, compliance, table)
    integer, intent(in) :: mx, my
    real(real64), intent(in) :: dx, dy, compliance
    real(real64), allocatable, intent(out) :: table(:, :)
    allocate (table(0:mx - 1, 0:my - 1))
    call rectangle_offset_table(mx - 1, my - 1, dx, dy, table)
    table = compliance / pi * table
  end subroutine normal_offset_table

end module kcreep_normal_influence
