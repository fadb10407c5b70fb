!> The text of the FASTSIM outputs: the creep-force table (one row per
!> creepage and flexibility source) and the traction / stick-slip maps.
module kcreep_creep_table
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep, only: result_t, creep_request_t, creep_point_t, creep_map_t, source_names, source_flexibilities, &
                    flexibility_rule_name
  implicit none
  private
  public :: creep_lines, creep_map_lines, creep_columns, traction_map_lines

  character(len=*), parameter :: creep_columns = 'xi eta phi fx fy mz fn adhesion source fx_mufn fy_mufn'

contains

  !> The creep-force table: comment lines, the column names, one row per point.
  function creep_lines(case_name, result, request, pressure, points) result(lines)
    character(len=*), intent(in) :: case_name, pressure
    type(result_t), intent(in) :: result
    type(creep_request_t), intent(in) :: request
    type(creep_point_t), intent(in) :: points(:)
    character(len=400), allocatable :: lines(:)
    real(real64) :: flex(3, size(source_names)), mufn
    integer :: k, s, nh
    character(len=400) :: buf

    flex = source_flexibilities(result, request)
    nh = 5 + count(request%sources)
    allocate (lines(nh + size(points)))
    lines(1) = '# kcreep FASTSIM creep forces, case '//case_name//' (Kalker 1982, friction, patch grid)'
    write (lines(2), '(a, es12.5, a)') '# mu = ', request%mu, ', flexibility rule '// &
      flexibility_rule_name(request%rule)//', pressure '//pressure
    lines(3) = '# (Fx, Fy, Mz) = -f (xi, eta, phi) at small creepage; adhesion: fraction of the patch area in adhesion'
    lines(4) = '# source: where L1 L2 L3 come from; fx_mufn = fx / (mu fn), fy_mufn = fy / (mu fn); units: '// &
               'the input''s (lengths in mm, g in N/mm^2: fx fy fn in N, mz in N mm, phi in 1/mm, L in mm^3/N)'
    k = 4
    do s = 1, size(source_names)
      if (.not. request%sources(s)) cycle
      k = k + 1
      write (lines(k), '(a, 3es14.6)') '# L1 L2 L3 '//source_names(s), flex(:, s)
    end do
    lines(nh) = '# '//creep_columns
    do k = 1, size(points)
      associate (p => points(k), f => points(k)%force)
        mufn = request%mu * f%fn
        write (buf, '(7(es23.15e3, 1x), f8.6, 1x, a, 2(1x, es23.15e3))') p%creep, f%fx, f%fy, f%mz, f%fn, &
          f%adhesion, trim(source_names(p%source)), f%fx / mufn, f%fy / mufn
        lines(nh + k) = buf
      end associate
    end do
  end function creep_lines

  !> The maps: per point a comment line naming it, then one row per patch cell:
  !> ix iy x y pn px py state (state 1 adhesion, 2 slip); blocks separated by two blank lines.
  function creep_map_lines(patch, pn, points, maps) result(lines)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: pn(:, :)
    type(creep_point_t), intent(in) :: points(:)
    type(creep_map_t), intent(in) :: maps(:)
    character(len=200), allocatable :: lines(:)
    character(len=200) :: titles(size(points))
    integer :: k
    do k = 1, size(points)
      write (titles(k), '(a, i0, a, 3es14.6, a)') '# point ', k, ': xi eta phi =', points(k)%creep, &
        ', source '//trim(source_names(points(k)%source))
    end do
    lines = traction_map_lines(patch, pn, maps, &
                               '# kcreep FASTSIM traction and stick/slip maps: one block per creepage point and source', &
                               titles)
  end function creep_map_lines

  !> Traction and stick/slip maps as text (FASTSIM's and exact rolling's):
  !> the header, the columns, then per map its title line and one row per
  !> patch cell: ix iy x y pn px py state (state 1 adhesion, 2 slip); blocks
  !> separated by two blank lines.
  function traction_map_lines(patch, pn, maps, header, titles) result(lines)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: pn(:, :)
    type(creep_map_t), intent(in) :: maps(:)
    character(len=*), intent(in) :: header, titles(:)
    character(len=200), allocatable :: lines(:)
    integer :: k, c, n, ix, iy

    allocate (lines(2 + size(titles) * (patch%n + 1) + 2 * max(0, size(titles) - 1)))
    lines(1) = header
    lines(2) = '# ix iy x y pn px py state   (state 1 adhesion, 2 slip; blocks separated by two blank lines)'
    n = 2
    do k = 1, size(titles)
      if (k > 1) then          ! two blank lines: gnuplot's 'index k-1' selects block k
        lines(n + 1:n + 2) = ''
        n = n + 2
      end if
      n = n + 1
      lines(n) = titles(k)
      do c = 1, patch%n
        ix = patch%ix(c)
        iy = patch%iy(c)
        n = n + 1
        write (lines(n), '(2(i0, 1x), 5(es16.8, 1x), i0)') ix, iy, patch%cell_x(ix), patch%cell_y(iy), &
          pn(ix, iy), maps(k)%px(ix, iy), maps(k)%py(ix, iy), maps(k)%state(ix, iy)
      end do
    end do
  end function traction_map_lines

end module kcreep_creep_table
