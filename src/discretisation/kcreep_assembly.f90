!> Assembly of the steady-rolling, full-adhesion system on the patch cells.
!>
!> Row i of the x-equation says: the x-derivative of u_x at cell i equals the
!> rigid creepage xi - phi*y; the y-equation: du_y/dx = eta + phi*x. Positive
!> x is the leading edge (material enters the contact there). The two
!> schemes differ only in the row operator:
!>   collocation: d/dx of the cell influence, in closed form, at the point
!>                (x_i + alpha*a, y_i), a = dx/2 (the paper's scheme);
!>   backward:    (u(x_i + dx) - u(x_i)) / dx from cell-centre displacements,
!>                the upwind difference of Kalker's CONTACT.
!> On a uniform grid the coefficient between two cells depends only on their
!> index offset, so each distinct offset is computed once (operator_table_t)
!> and the matrix is filled from that table.
!>
!> A blended patch (kcreep_patch blended_patch, the levels of a shape)
!> has cells partly inside the shape. Cell k's row, x and y alike, is
!>     phi (A t - rhs) + (1 - phi) kappa d t = 0,
!> phi its fraction inside, d the row's own-cell coefficient: slip
!> vanishes in a cell wholly inside, traction in one wholly outside, and
!> a level's f moves continuously as the edge crosses its cells (a
!> staircase of the cells whose centres are inside jumps whenever the
!> edge crosses a centre). Divided by phi + (1 - phi) kappa, so that the
!> diagonal stays d: w (A t - rhs) + (1 - w) d t = 0 with w =
!> slip_weight(phi).
module kcreep_assembly
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep_influence, only: influence_t, cell_displacement_x_derivative, displacement_offset_table
  implicit none
  private
  public :: scheme_t, operator_table_t, build_operator_table, assemble_dense, apply_operator, &
            rigid_creepage, load_case_names, n_load_cases, slip_weight, blended_row

  !> The blended edge's weight of a partly outside cell's own traction.
  !> Measured on the circle in a dense model (lab/boundary_blend_study.py,
  !> levels 24 to 64 cells across): kappa = 2 leaves the levels' C11 with
  !> no first-order term and a scatter of 0.0035 % about their line; kappa
  !> = 1 and 4 scatter 10 times more (docs/wheel_rail_checks.md, "The blended edge").
  real(real64), parameter :: blend_kappa = 2

  integer, parameter :: n_load_cases = 3
  character(len=3), parameter :: load_case_names(n_load_cases) = ['xi ', 'eta', 'phi']

  !> How a row of the system is discretised.
  type :: scheme_t
    character(len=:), allocatable :: name   !< 'collocation' or 'backward'
    real(real64) :: alpha = 0.5_real64      !< collocation point, in half cells, (-1, 1)
    !> Backward scheme: spin creepage evaluated at x_i + spin_shift*dx
    !> (CONTACT uses 1/6); collocation evaluates it at the collocation point.
    real(real64) :: spin_shift = 0
  end type scheme_t

  !> Row-operator coefficients by cell index offset (di, dj) = (row - column).
  type :: operator_table_t
    integer :: mx = 0, my = 0
    real(real64), allocatable :: xx(:, :), xy(:, :), yy(:, :)   !< (-(mx-1):mx-1, -(my-1):my-1)
    real(real64) :: g = 1   !< the shear modulus (the coefficients are in units of 1/g)
  end type operator_table_t

contains

  !> The weight w of a blended cell's slip in its row (module header):
  !> phi / (phi + (1 - phi) blend_kappa); 1 wholly inside, 0 outside.
  pure elemental real(real64) function slip_weight(fraction) result(w)
    real(real64), intent(in) :: fraction
    w = fraction / (fraction + (1 - fraction) * blend_kappa)
  end function slip_weight

  !> A blended cell's row value from the plain operator's: w (A t)_k + (1 -
  !> w) d t_k (module header); w its slip_weight, d the row's own-cell
  !> coefficient, t_k its own traction.
  pure elemental real(real64) function blended_row(plain, weight, own, traction)
    real(real64), intent(in) :: plain, weight, own, traction
    blended_row = weight * plain + (1 - weight) * own * traction
  end function blended_row

  subroutine build_operator_table(patch, scheme, nu, g, table)
    type(patch_t), intent(in) :: patch
    type(scheme_t), intent(in) :: scheme
    real(real64), intent(in) :: nu, g
    type(operator_table_t), intent(out) :: table
    type(influence_t), allocatable :: u(:, :), d(:, :), quadrant(:, :)
    real(real64) :: a, b
    integer :: di, dj, mx, my

    mx = patch%mx
    my = patch%my
    a = patch%dx / 2
    b = patch%dy / 2
    table%mx = mx
    table%my = my
    table%g = g
    allocate (d(-(mx - 1):mx - 1, -(my - 1):my - 1))
    select case (scheme%name)
    case ('collocation')
      do dj = -(my - 1), my - 1
        do di = -(mx - 1), mx - 1
          d(di, dj) = cell_displacement_x_derivative(di * patch%dx + scheme%alpha * a, dj * patch%dy, a, b, nu, g)
        end do
      end do
    case ('backward')
      ! displacements at every centre offset, one more column on the upwind side;
      ! u_xx and u_yy are even in each offset and u_xy odd, so one quadrant is
      ! evaluated and mirrored
      allocate (quadrant(0:mx, 0:my - 1))
      call displacement_offset_table(mx, my - 1, patch%dx, patch%dy, nu, g, quadrant)
      allocate (u(-(mx - 1):mx, -(my - 1):my - 1))
      do dj = -(my - 1), my - 1
        do di = -(mx - 1), mx
          u(di, dj) = quadrant(abs(di), abs(dj))
          if (di * dj < 0) u(di, dj)%xy = -u(di, dj)%xy
        end do
      end do
      do dj = -(my - 1), my - 1
        do di = -(mx - 1), mx - 1
          d(di, dj)%xx = (u(di + 1, dj)%xx - u(di, dj)%xx) / patch%dx
          d(di, dj)%xy = (u(di + 1, dj)%xy - u(di, dj)%xy) / patch%dx
          d(di, dj)%yy = (u(di + 1, dj)%yy - u(di, dj)%yy) / patch%dx
        end do
      end do
    case default
      error stop 'build_operator_table: unknown scheme (input validation missed it)'
    end select
    allocate (table%xx(-(mx - 1):mx - 1, -(my - 1):my - 1), table%xy(-(mx - 1):mx - 1, -(my - 1):my - 1), &
              table%yy(-(mx - 1):mx - 1, -(my - 1):my - 1))
    table%xx = d%xx
    table%xy = d%xy
    table%yy = d%yy
  end subroutine build_operator_table

  !> The dense 2n x 2n matrix [Axx Axy; Ayx Ayy], unknowns (px(1:n), py(1:n)).
  !> The kernel is symmetric in its components, so Ayx uses the xy table.
  subroutine assemble_dense(patch, table, a)
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    real(real64), intent(out) :: a(:, :)
    integer :: i, k, n, di, dj
    real(real64) :: w

    n = patch%n
    !$omp parallel do private(i, di, dj) schedule(static)
    do k = 1, n
      do i = 1, n
        di = patch%ix(i) - patch%ix(k)
        dj = patch%iy(i) - patch%iy(k)
        a(i, k) = table%xx(di, dj)
        a(n + i, k) = table%xy(di, dj)
        a(i, n + k) = table%xy(di, dj)
        a(n + i, n + k) = table%yy(di, dj)
      end do
    end do
    if (.not. allocated(patch%fraction)) return
    do i = 1, n
      w = slip_weight(patch%fraction(i))
      a(i, :) = w * a(i, :)
      a(n + i, :) = w * a(n + i, :)
      a(i, i) = a(i, i) + (1 - w) * table%xx(0, 0)
      a(n + i, n + i) = a(n + i, n + i) + (1 - w) * table%yy(0, 0)
    end do
  end subroutine assemble_dense

  !> y = A x without forming A (for residuals and refinement).
  subroutine apply_operator(patch, table, x, y)
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    real(real64), intent(in) :: x(:)     !< (2n)
    real(real64), intent(out) :: y(:)    !< (2n)
    integer :: i, k, n, di, dj
    real(real64) :: sx, sy, w

    n = patch%n
    do i = 1, n
      sx = 0
      sy = 0
      do k = 1, n
        di = patch%ix(i) - patch%ix(k)
        dj = patch%iy(i) - patch%iy(k)
        sx = sx + table%xx(di, dj) * x(k) + table%xy(di, dj) * x(n + k)
        sy = sy + table%xy(di, dj) * x(k) + table%yy(di, dj) * x(n + k)
      end do
      y(i) = sx
      y(n + i) = sy
      if (allocated(patch%fraction)) then
        w = slip_weight(patch%fraction(i))
        y(i) = blended_row(sx, w, table%xx(0, 0), x(i))
        y(n + i) = blended_row(sy, w, table%yy(0, 0), x(n + i))
      end if
    end do
  end subroutine apply_operator

  !> Right-hand sides for unit creepages: column j is load case j
  !> (1: xi, 2: eta, 3: phi about the origin).
  pure subroutine rigid_creepage(patch, scheme, case_id, rhs)
    type(patch_t), intent(in) :: patch
    type(scheme_t), intent(in) :: scheme
    integer, intent(in) :: case_id
    real(real64), intent(out) :: rhs(:)   !< (2n)
    integer :: n
    real(real64) :: shift

    n = patch%n
    select case (case_id)
    case (1)
      rhs(1:n) = 1
      rhs(n + 1:2 * n) = 0
    case (2)
      rhs(1:n) = 0
      rhs(n + 1:2 * n) = 1
    case (3)
      if (scheme%name == 'collocation') then
        shift = scheme%alpha * patch%dx / 2
      else
        shift = scheme%spin_shift * patch%dx
      end if
      rhs(1:n) = -patch%cell_y(patch%iy)
      rhs(n + 1:2 * n) = patch%cell_x(patch%ix) + shift
    end select
  end subroutine rigid_creepage

end module kcreep_assembly
