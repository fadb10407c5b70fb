!> The text of the outputs: the coefficient table (comment lines, column
!> names, one row per case) and the traction file. Writing them to disk is
!> the caller's (app/kcreep_app_files: atomic writes).
module kcreep_table
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep_assembly, only: load_case_names, n_load_cases
  use kcreep_problem, only: result_t
  implicit none
  private
  public :: run_record_t, table_lines, table_row, traction_lines, table_columns, case_name, line_length

  !> One row of the coefficient table.
  type, extends(result_t) :: run_record_t
    character(len=:), allocatable :: case_name   !< the input's name, the row's first word
  end type run_record_t

  integer, parameter :: line_length = 1024
  character(len=*), parameter :: table_columns = &
    'case scheme mx my n alpha nu g c f11 f12 f13 f21 f22 f23 f31 f32 f33 c11 c22 c23 '// &
    'klt11 klt22 klt23 t_assemble t_factor t_solve t_total rcond berr verdict '// &
    'ext11 ext22 ext23 exterr11 exterr22 exterr23 extp11 extp22 extp23 iterations L1 L2 L3 xc yc'


contains

  !> The whole table: comment lines (warnings among them), the column names
  !> as the last comment line, then one row per record.
  function table_lines(records, warnings) result(lines)
    type(run_record_t), intent(in) :: records(:)
    character(len=*), intent(in) :: warnings(:)
    character(len=line_length), allocatable :: lines(:)
    character(len=*), parameter :: fixed(5) = [character(len=100) :: &
      '# kcreep: creep coefficients of full-adhesion steady rolling', &
      '# (Fx, Fy, Mz) = -[fij] (xi, eta, phi); rigid slip (xi - phi*y, eta + phi*x), x, y from the spin centre', &
      '# c11 = f11/(g c^2), c22 = f22/(g c^2), c23 = f23/(g c^3); kltij: Kalker table E3 (ellipses)', &
      '# leading edge at +x; xc, yc: centroid of the patch cells (coordinates of the input)', &
      '# times in s; rcond: LAPACK 1-norm estimate; berr: backward error (iterative: relative residual)']
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
    write (buf, '(a, 1x, a, 3(1x, i0), 4(1x, es23.15e3), 9(1x, es23.15e3), 6(1x, es23.15e3), &
                & 4(1x, es10.3e2), 2(1x, es10.3e3), 1x, a)') &
      r%case_name, r%scheme, r%mx, r%my, r%n, r%alpha, r%nu, r%g, r%c, &
      transpose(r%f), r%cn, r%klt, r%t_assemble, r%t_factor, r%t_solve, r%t_total, &
      r%rcond, r%backward_error, r%verdict
    ext = ieee_nan()
    if (r%extrapolated) ext = [r%ext, r%ext_error, r%ext_order]
    line = trim(buf)
    write (buf, '(6(1x, es23.15e3), 3(1x, f6.3), 1x, i0, 5(1x, es23.15e3))') ext, r%iterations, r%fastsim, &
      r%centroid
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
