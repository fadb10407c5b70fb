!> The text of the &rolling outputs: the exact creep-force table (one row per
!> creepage) and the traction / stick-slip maps.
module kcreep_rolling_table
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep, only: rolling_request_t, rolling_point_t
  use kcreep, only: creep_map_t
  use kcreep_creep_table, only: traction_map_lines
  implicit none
  private
  public :: rolling_lines, rolling_map_lines, rolling_columns, rolling_notes, rolling_row

  character(len=*), parameter :: rolling_columns = 'xi eta phi fx fy mz fn adhesion fx_mufn fy_mufn newton residual'

contains

  !> The table: comment lines, the column names, one row per point.
  function rolling_lines(case_name, request, pressure, points) result(lines)
    character(len=*), intent(in) :: case_name, pressure
    type(rolling_request_t), intent(in) :: request
    type(rolling_point_t), intent(in) :: points(:)
    character(len=400), allocatable :: lines(:)
    integer, parameter :: nh = 6
    integer :: k

    allocate (lines(nh + size(points)))
    lines(1) = '# kcreep exact steady rolling with Coulomb friction, case '//case_name// &
               ' (backward scheme on the patch grid, semi-smooth Newton)'
    write (lines(2), '(a, es12.5, a, es9.2)') '# mu = ', request%mu, ', pressure '//pressure// &
      ', tolerance', request%tolerance
    lines(3:5) = rolling_notes()
    lines(nh) = '# '//rolling_columns
    do k = 1, size(points)
      lines(nh + k) = rolling_row(request%mu, points(k))
    end do
  end function rolling_lines

  !> The comment lines that explain the table's columns (also &wheel_rail's rolling table).
  pure function rolling_notes() result(lines)
    character(len=160) :: lines(3)
    lines(1) = '# (Fx, Fy, Mz) = -f (xi, eta, phi) at small creepage; adhesion: fraction of the patch cells in adhesion'
    lines(2) = '# fx_mufn = fx / (mu fn), fy_mufn = fy / (mu fn); newton: Newton steps of the point'
    lines(3) = '# residual: max |F_i| / max(mu pn) of the Coulomb conditions F(p) = p - Proj(p - rho s(p)) = 0 '// &
               '(checked at the solution)'
  end function rolling_notes

  !> One point's row, the columns rolling_columns (friction coefficient mu).
  function rolling_row(mu, point) result(row)
    real(real64), intent(in) :: mu
    type(rolling_point_t), intent(in) :: point
    character(len=:), allocatable :: row
    character(len=400) :: buf
    real(real64) :: mufn
    associate (f => point%force)
      mufn = mu * f%fn
      write (buf, '(7(es23.15e3, 1x), f8.6, 2(1x, es23.15e3), 1x, i0, 1x, es10.3e3)') point%creep, f%fx, f%fy, &
        f%mz, f%fn, f%adhesion, f%fx / mufn, f%fy / mufn, point%info%newton, point%info%residual
    end associate
    row = trim(buf)
  end function rolling_row

  !> The maps: per point a comment line naming it, then one row per patch cell:
  !> ix iy x y pn px py state (state 1 adhesion, 2 slip); blocks separated by two blank lines.
  function rolling_map_lines(patch, pn, points, maps) result(lines)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: pn(:, :)
    type(rolling_point_t), intent(in) :: points(:)
    type(creep_map_t), intent(in) :: maps(:)
    character(len=200), allocatable :: lines(:)
    character(len=200) :: titles(size(maps))
    integer :: k
    do k = 1, size(maps)
      write (titles(k), '(a, i0, a, 3es14.6)') '# point ', k, ': xi eta phi =', points(k)%creep
    end do
    lines = traction_map_lines(patch, pn, maps, &
                               '# kcreep exact rolling: traction and stick/slip maps, one block per creepage point', titles)
  end function rolling_map_lines

end module kcreep_rolling_table
