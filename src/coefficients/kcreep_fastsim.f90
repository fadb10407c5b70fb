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

  !> (I1, I3): per cell of half length h centred at x_k in a segment with leading edge x_l,
  !> Int (x_l - x) dx = 2h (x_l - x_k) and Int (x_l^2 - x^2)/2 dx = h (x_l^2 - x_k^2) - h^3/3.
  pure function strip_integrals(patch) result(moments)
    type(patch_t), intent(in) :: patch
    real(real64) :: moments(2)
    real(real64) :: h, x_lead, x
    integer :: ix, iy

    h = patch%dx / 2
    moments = 0
    do iy = 1, patch%my
      x_lead = 0
      do ix = patch%mx, 1, -1          ! walk upstream from +x, where each segment starts
        if (.not. patch%inside(ix, iy)) cycle
        if (ix == patch%mx) then
          x_lead = patch%cell_x(ix) + h
        else if (.not. patch%inside(ix + 1, iy)) then
          x_lead = patch%cell_x(ix) + h
        end if
        x = patch%cell_x(ix)
        moments(1) = moments(1) + 2 * h * (x_lead - x)
        moments(2) = moments(2) + h * (x_lead**2 - x**2) - h**3 / 3
      end do
    end do
    moments = moments * patch%dy
  end function strip_integrals

end module kcreep_fastsim
