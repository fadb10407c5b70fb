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
module kcreep_assembly
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep_influence, only: influence_t, cell_displacement, cell_displacement_x_derivative
  implicit none
  private
  public :: scheme_t, operator_table_t, build_operator_table, assemble_dense, apply_operator, &
            rigid_creepage, load_case_names, n_load_cases

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
  end type operator_table_t

contains

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
      ! evaluated (a quarter of the kernel calls, the costly part) and mirrored
      allocate (quadrant(0:mx, 0:my - 1))
      !$omp parallel do private(di) schedule(static)
      do dj = 0, my - 1
        do di = 0, mx
          quadrant(di, dj) = cell_displacement(di * patch%dx, dj * patch%dy, a, b, nu, g)
        end do
      end do
      !$omp end parallel do
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
  end subroutine assemble_dense

  !> y = A x without forming A (for residuals and refinement).
  subroutine apply_operator(patch, table, x, y)
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    real(real64), intent(in) :: x(:)     !< (2n)
    real(real64), intent(out) :: y(:)    !< (2n)
    integer :: i, k, n, di, dj
    real(real64) :: sx, sy

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
