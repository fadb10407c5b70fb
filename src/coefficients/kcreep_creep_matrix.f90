!> From the cell tractions of the unit load cases to the creep-force matrix.
!>
!>   (Fx, Fy, Mz) = -[f_ij] (xi, eta, phi),
!>   Fx = sum px dA,  Fy = sum py dA,  Mz = sum (x py - y px) dA,
!> with x, y the cell centres and the spin centre at the origin.
!> Normalised (Kalker): C11 = f11/(G c^2), C22 = f22/(G c^2), C23 = f23/(G c^3).
module kcreep_creep_matrix
  use, intrinsic :: iso_fortran_env, only: real64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use kcreep_patch, only: patch_t
  implicit none
  private
  public :: creep_matrix, normalised, normalised_about, traction_coherence, centre_transfer

contains

  !> T of f = T' f0 T, f0 the creep matrix about the point centre = (xc, yc)
  !> and f the one about the origin: the spin about the origin is a spin
  !> about the centre plus the creepages (xi, eta) = phi (-yc, xc), and Mz
  !> about the origin adds xc Fy - yc Fx. T of -centre is its inverse.
  pure function centre_transfer(centre) result(t)
    real(real64), intent(in) :: centre(2)
    real(real64) :: t(3, 3)
    t = reshape([1.0_real64, 0.0_real64, 0.0_real64, 0.0_real64, 1.0_real64, 0.0_real64, &
                 -centre(2), centre(1), 1.0_real64], [3, 3])
  end function centre_transfer

  !> f(:, j) = -(Fx, Fy, Mz) of load case j; NaN for the cases not solved.
  pure function creep_matrix(patch, traction, solved) result(f)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: traction(:, :)   !< (2n, 3): px then py, unit creepage
    logical, intent(in) :: solved(3)
    real(real64) :: f(3, 3)
    real(real64) :: cell_area, x(patch%n), y(patch%n)
    integer :: j, n

    n = patch%n
    cell_area = patch%dx * patch%dy
    x = patch%cell_x(patch%ix)
    y = patch%cell_y(patch%iy)
    f = ieee_value(1.0_real64, ieee_quiet_nan)
    do j = 1, 3
      if (.not. solved(j)) cycle
      associate (px => traction(1:n, j), py => traction(n + 1:2 * n, j))
        f(1, j) = -sum(px) * cell_area
        f(2, j) = -sum(py) * cell_area
        f(3, j) = -sum(x * py - y * px) * cell_area
      end associate
    end do
  end function creep_matrix

  !> (C11, C22, C23) from f, G and the length scale c.
  pure function normalised(f, g, c) result(cn)
    real(real64), intent(in) :: f(3, 3), g, c
    real(real64) :: cn(3)
    cn = [f(1, 1) / (g * c**2), f(2, 2) / (g * c**2), f(2, 3) / (g * c**3)]
  end function normalised

  !> (C11, C22, C23) about the point d from the spin centre f refers to
  !> (centre_transfer): Kalker's ellipses spin about their centre, so a
  !> patch is compared with its equivalent ellipse about its centroid.
  pure function normalised_about(f, g, c, d) result(cn)
    real(real64), intent(in) :: f(3, 3), g, c, d(2)
    real(real64) :: cn(3), t(3, 3)
    t = centre_transfer(-d)
    cn = normalised(matmul(transpose(t), matmul(f, t)), g, c)
  end function normalised_about

  !> |sum p| / sum |p| of one traction component: 1 when the traction has one
  !> sign everywhere (the physical solution for a pure xi or eta load), near 0
  !> when it oscillates or is antisymmetric (a degenerate discretisation).
  pure real(real64) function traction_coherence(p) result(q)
    real(real64), intent(in) :: p(:)
    real(real64) :: total
    total = sum(abs(p))
    if (total > 0) then
      q = abs(sum(p)) / total
    else
      q = 0
    end if
  end function traction_coherence

end module kcreep_creep_matrix
