!> The text of the outputs: the coefficient table (comment lines, column
!> names, one row per case) and the traction file. Writing them to disk is
!> the caller's (app/kcreep_app_files: atomic writes).
module kcreep_table
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep_assembly, only: load_case_names, n_load_cases
  use kcreep, only: result_t, normalised_about
  implicit none
  private
  public :: run_record_t, table_lines, table_row, traction_lines, table_columns, case_name, line_length
  public :: pressure_lines, contact_mask_lines

  !> One row of the coefficient table.
  type, extends(result_t) :: run_record_t
    character(len=:), allocatable :: case_name   !< the input's name, the row's first word
  end type run_record_t

  integer, parameter :: line_length = 2048
  character(len=*), parameter :: table_columns = &
    'case scheme mx my n alpha nu g c f11 f12 f13 f21 f22 f23 f31 f32 f33 c11 c22 c23 '// &
    'klt11 klt22 klt23 t_assemble t_factor t_solve t_total rcond berr verdict '// &
    'ext11 ext22 ext23 exterr11 exterr22 exterr23 extp11 extp22 extp23 iterations L1 L2 L3 '// &
    'fn approach pmax normal_iterations normal_residual '// &
    'ebox_a ebox_b ebox_c11 ebox_c22 ebox_c23 ebox_L1 ebox_L2 ebox_L3 '// &
    'ebox_err11 ebox_err22 ebox_err23 ebox_errL1 ebox_errL2 ebox_errL3 '// &
    'emom_a emom_b emom_c11 emom_c22 emom_c23 emom_L1 emom_L2 emom_L3 '// &
    'emom_err11 emom_err22 emom_err23 emom_errL1 emom_errL2 emom_errL3 '// &
    'err11 err22 err23 xc yc'


contains

  !> The whole table: comment lines (warnings among them), the column names
  !> as the last comment line, then one row per record.
  function table_lines(records, warnings) result(lines)
    type(run_record_t), intent(in) :: records(:)
    character(len=*), intent(in) :: warnings(:)
    character(len=line_length), allocatable :: lines(:)
    character(len=*), parameter :: fixed(8) = [character(len=160) :: &
      '# kcreep: creep coefficients of full-adhesion steady rolling', &
      '# (Fx, Fy, Mz) = -[fij] (xi, eta, phi); rigid slip (xi - phi*y, eta + phi*x), x, y from the spin centre', &
      '# c11 = f11/(g c^2), c22 = f22/(g c^2), c23 = f23/(g c^3); kltij: Kalker table E3 (ellipses)', &
      '# ebox_*, emom_*: equivalent ellipses (same area; a/b of the bounding box, of the second moments): '// &
      'Kalker''s C and L, err = ellipse / exact - 1', &
      '# leading edge at +x; xc, yc: centroid of the patch cells (coordinates of the input)', &
      '# times in s; rcond: LAPACK 1-norm estimate; berr: backward error (iterative: relative residual)', &
      '# shape gap: fn approach pmax of the normal problem (n = cells in contact), its iterations and residual', &
      '# units: the input''s (mm, N/mm^2: f11 f12 f21 f22 N, f13 f23 f31 f32 N mm, f33 N mm^2, l1 l2 l3 mm^3/N); '// &
      'cij, err* dimensionless']
    integer :: k, nw

    nw = size(warnings)
    allocate (lines(size(fixed) + nw + 1 + size(records)))
    lines(1:size(fixed)) = fixed
    do k = 1, nw
      lines(size(fixed) + k) = '# WARNING: '//trim(warnings(k))
    end do
    lines(size(fixed) + nw + 1) = '# '//table_columns
    do k = 1, size(records)
      lines(size(fixed) + nw + 1 + k) = table_row(records(k))
    end do
  end function table_lines

  function table_row(r) result(line)
    type(run_record_t), intent(in) :: r
    character(len=:), allocatable :: line
    character(len=1024) :: buf
    real(real64) :: ext(9)
    integer :: k
    write (buf, '(a, 1x, a, 3(1x, i0), 4(1x, es23.15e3), 9(1x, es23.15e3), 6(1x, es23.15e3), &
                & 4(1x, es10.3e2), 2(1x, es10.3e3), 1x, a)') &
      r%case_name, r%scheme, r%mx, r%my, r%n, r%alpha, r%nu, r%g, r%c, &
      transpose(r%f), r%cn, r%klt, r%t_assemble, r%t_factor, r%t_solve, r%t_total, &
      r%rcond, r%backward_error, r%verdict
    ext = ieee_nan()
    if (r%extrapolated) ext = [r%ext, r%ext_error, r%ext_order]
    line = trim(buf)
    write (buf, '(6(1x, es23.15e3), 3(1x, f6.3), 1x, i0, 3(1x, es23.15e3))') ext, r%iterations, r%fastsim
    line = line//trim(buf)
    if (r%normal_solved) then
      write (buf, '(3(1x, es23.15e3), 1x, i0, 1x, es10.3e3)') r%fn, r%approach, r%pmax, r%normal_iterations, &
        r%normal_residual
    else
      write (buf, '(3(1x, es23.15e3), 1x, i0, 1x, es10.3e3)') ieee_nan(), ieee_nan(), ieee_nan(), 0, ieee_nan()
    end if
    line = line//trim(buf)
    ! (the patch's C23 about its centroid, as Kalker's about the ellipse's centre)
    do k = 1, 2
      write (buf, '(14(1x, es23.15e3))') r%ellipse(k)%semi_a, r%ellipse(k)%semi_b, r%ellipse(k)%c, &
        r%ellipse(k)%flex, r%ellipse(k)%c / normalised_about(r%f, r%g, r%c, r%centroid - r%spin_centre) - 1, &
        r%ellipse(k)%flex / r%fastsim - 1
      line = line//trim(buf)
    end do
    ! error estimates of c11 c22 c23 (kcreep_refine_estimate), then the centroid
    write (buf, '(3(1x, es10.3e3))') r%err
    line = line//trim(buf)
    write (buf, '(2(1x, es23.15e3))') r%centroid
    line = line//trim(buf)
  end function table_row

  !> Lines of the traction file: per cell, px and py of each load case for a unit creepage.
  function traction_lines(patch, traction, solved) result(lines)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: traction(:, :)
    logical, intent(in) :: solved(n_load_cases)
    character(len=400), allocatable :: lines(:)
    character(len=400) :: head
    integer :: k, j, n
    n = patch%n
    head = '# ix iy x y'
    do j = 1, n_load_cases
      head = trim(head)//' px_'//trim(load_case_names(j))//' py_'//trim(load_case_names(j))
    end do
    allocate (lines(n + 3))
    lines(1) = '# kcreep tractions for unit creepage (xi = 1, eta = 1, phi = 1 per unit length);'
    lines(2) = '# NaN for a load case that was not requested; multiply by the creepage for any other'
    lines(3) = head
    do k = 1, n
      write (lines(k + 3), '(2(i0, 1x), 2(es23.15e3, 1x), 6(es23.15e3, :, 1x))') patch%ix(k), patch%iy(k), &
        patch%cell_x(patch%ix(k)), patch%cell_y(patch%iy(k)), &
        (merge(traction(k, j), ieee_nan(), solved(j)), merge(traction(n + k, j), ieee_nan(), solved(j)), &
         j=1, n_load_cases)
    end do
  end function traction_lines

  !> Lines of the pressure file: per contact cell, its indices on the patch
  !> grid, its centre and the pressure of the normal problem.
  function pressure_lines(patch, pressure, fn, approach) result(lines)
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: pressure(:), fn, approach
    character(len=200), allocatable :: lines(:)
    integer :: k
    allocate (lines(patch%n + 3))
    write (lines(1), '(a, es23.15e3, a, es23.15e3)') '# kcreep normal pressure: fn = ', fn, ', approach = ', approach
    write (lines(2), '(a, 2(i0, 1x), 4(es23.15e3, :, 1x))') '# grid mx my dx dy x0 y0: ', patch%mx, patch%my, &
      patch%dx, patch%dy, patch%x0, patch%y0
    lines(3) = '# ix iy x y p'
    do k = 1, patch%n
      write (lines(k + 3), '(2(i0, 1x), 2(es23.15e3, 1x), es23.15e3)') patch%ix(k), patch%iy(k), &
        patch%cell_x(patch%ix(k)), patch%cell_y(patch%iy(k)), pressure(k)
    end do
  end function pressure_lines

  !> The contact area as a mask file (header mx my dx dy x0 y0, rows in increasing y, '1' in contact).
  function contact_mask_lines(patch) result(lines)
    type(patch_t), intent(in) :: patch
    character(len=:), allocatable :: lines(:)
    integer :: iy, ix
    allocate (character(len=max(patch%mx, 120)) :: lines(patch%my + 1))
    write (lines(1), '(2(i0, 1x), 3(es23.15e3, 1x), es23.15e3)') patch%mx, patch%my, patch%dx, patch%dy, &
      patch%x0, patch%y0
    do iy = 1, patch%my
      lines(iy + 1) = ''
      do ix = 1, patch%mx
        lines(iy + 1)(ix:ix) = merge('1', '0', patch%inside(ix, iy))
      end do
    end do
  end function contact_mask_lines

  !> Input file name without folder and extension, blanks replaced (a table word).
  pure function case_name(path) result(name)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: name
    integer :: slash, dot, i
    slash = index(path, '/', back=.true.)
    name = path(slash + 1:)
    dot = index(name, '.', back=.true.)
    if (dot > 1) name = name(1:dot - 1)
    do i = 1, len(name)
      if (name(i:i) == ' ' .or. iachar(name(i:i)) < 33) name(i:i) = '_'
    end do
    if (len(name) == 0) name = '-'
  end function case_name

  real(real64) function ieee_nan()
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    ieee_nan = ieee_value(1.0_real64, ieee_quiet_nan)
  end function ieee_nan

end module kcreep_table
