!> FASTSIM's flexibilities L1, L2, L3 for the patch, from the exact
!> full-adhesion coefficients (the purpose the paper computes them for).
!>
!> FASTSIM (Kalker 1982) takes u = L p. In full adhesion each strip y of the
!> patch starts traction-free at the leading edge x_l of each of its
!> segments, so for unit creepages
!>   px = -(x_l - x)/L1 (xi),  py = -(x_l - x)/L2 (eta),  py = -(x_l^2 - x^2)/(2 L3) (phi).
!> Equating the forces with f11, f22, f23 gives
!>   L1 = I1/f11, L2 = I1/f22, L3 = I3/f23,
!>   I1 = Int (x_l - x) dA,  I3 = Int (x_l^2 - x^2)/2 dA,
!> integrated exactly over the cells (the integrands are polynomials in x).
!> For an ellipse these are Kalker's L1 = 8a/(3 C11 G), L2 = 8a/(3 C22 G),
!> L3 = pi a sqrt(a/b)/(4 C23 G).
module kcreep_fastsim
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep_fastsim_forces, only: mask_strip_integrals
  implicit none
  private
  public :: fastsim_flexibilities, strip_integrals

contains

  !> (L1, L2, L3) from f11, f22, f23 (NaN propagates from coefficients not computed).
  pure function fastsim_flexibilities(patch, f11, f22, f23) result(flex)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: f11, f22, f23
    real(real64) :: flex(3), moments(2)
    moments = strip_integrals(patch)
    flex = [moments(1) / f11, moments(1) / f22, moments(2) / f23]
  end function fastsim_flexibilities

  !> (I1, I3) of the patch's cells (kcreep_fastsim_forces mask_strip_integrals, which
  !> gives the per-cell integrals).
  pure function strip_integrals(patch) result(moments)
    type(patch_t), intent(in) :: patch
    real(real64) :: moments(2)
    moments = mask_strip_integrals(patch%inside, patch%dx, patch%dy, patch%x0)
  end function strip_integrals

end module kcreep_fastsim
