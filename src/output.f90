!> Output files: the coefficient table and the traction file.
!>
!> Every file is written to a temporary name in the target folder and
!> renamed into place only when complete, so an existing file is either
!> replaced whole or left untouched.
module table_output
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
  use kcreep_status, only: status_t, fail, exit_io
  use kcreep_strings, only: itoa
  use patch_grid, only: patch_t
  use tang_assembly, only: load_case_names, n_load_cases
  implicit none
  private
  public :: run_record_t, table_lines, table_row, write_text_file, check_output_path, &
            traction_lines, table_columns, write_temporary, commit_temporary, discard_temporary

  !> One row of the coefficient table.
  type :: run_record_t
    character(len=:), allocatable :: case_name, scheme, verdict
    integer :: mx = 0, my = 0, n = 0
    real(real64) :: alpha = 0, nu = 0, g = 0, c = 0
    real(real64) :: f(3, 3) = 0              !< f(i, j) = f_ij
    real(real64) :: cn(3) = 0                !< C11, C22, C23
    real(real64) :: klt(3) = 0               !< Kalker's C11, C22, C23 (NaN unless ellipse)
    real(real64) :: t_assemble = 0, t_factor = 0, t_solve = 0, t_total = 0
    real(real64) :: rcond = 0, backward_error = 0
    ! &solver extrapolate: Richardson limits of C11, C22, C23, error estimates, orders used
    logical :: extrapolated = .false.
    real(real64) :: ext(3) = 0, ext_error(3) = 0, ext_order(3) = 0
    real(real64) :: backward_error_initial = 0, relative_residual = 0   !< before refinement
    character(len=:), allocatable :: refine                              !< mode and whether it refined
    character(len=:), allocatable :: method   !< 'dense' or 'iterative'
    integer :: iterations = 0                 !< GMRES iterations, 0 for dense
    real(real64) :: fastsim(3) = 0            !< FASTSIM flexibilities L1, L2, L3 (fastsim_flexibility)
  end type run_record_t

  integer, parameter :: line_length = 1024
  character(len=*), parameter :: table_columns = &
    'case scheme mx my n alpha nu g c f11 f12 f13 f21 f22 f23 f31 f32 f33 c11 c22 c23 '// &
    'klt11 klt22 klt23 t_assemble t_factor t_solve t_total rcond berr verdict '// &
    'ext11 ext22 ext23 exterr11 exterr22 exterr23 extp11 extp22 extp23 iterations L1 L2 L3'

  interface
    integer(c_int) function c_rename(old, new) bind(c, name='rename')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: old(*), new(*)
    end function c_rename
    integer(c_int) function c_getpid() bind(c, name='getpid')
      import :: c_int
    end function c_getpid
  end interface

contains

  !> The whole table: comment lines (warnings among them), the column names
  !> as the last comment line, then one row per record.
  function table_lines(records, warnings) result(lines)
    type(run_record_t), intent(in) :: records(:)
    character(len=*), intent(in) :: warnings(:)
    character(len=line_length), allocatable :: lines(:)
    character(len=*), parameter :: fixed(4) = [character(len=100) :: &
      '# kcreep: creep coefficients of full-adhesion steady rolling', &
      '# (Fx, Fy, Mz) = -[fij] (xi, eta, phi); rigid slip (xi - phi*y, eta + phi*x), leading edge at +x', &
      '# c11 = f11/(g c^2), c22 = f22/(g c^2), c23 = f23/(g c^3); kltij: Kalker table E3 (ellipses)', &
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
    write (buf, '(6(1x, es23.15e3), 3(1x, f6.3), 1x, i0, 3(1x, es23.15e3))') ext, r%iterations, r%fastsim
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

  !> Fail unless a file can be created at path (its folder exists and is writable).
  subroutine check_output_path(path, variable, status)
    character(len=*), intent(in) :: path, variable
    type(status_t), intent(inout) :: status
    integer :: unit, ios
    character(len=512) :: msg
    character(len=:), allocatable :: probe
    probe = temporary_name(path)
    open (newunit=unit, file=probe, status='new', action='write', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_io, variable//' '''//path//''': cannot create a file there ('// &
                trim(msg)//'); does the folder exist and is it writable?')
      return
    end if
    close (unit, status='delete')
  end subroutine check_output_path

  !> Write lines to path atomically (temporary file in the same folder, then rename).
  subroutine write_text_file(path, lines, variable, status)
    character(len=*), intent(in) :: path, variable
    character(len=*), intent(in) :: lines(:)
    type(status_t), intent(inout) :: status
    call write_temporary(path, lines, variable, status)
    if (.not. status%failed()) call commit_temporary(path, variable, status)
  end subroutine write_text_file

  !> First half of write_text_file: the complete temporary file beside path.
  !> On any error (a full disk among them) the temporary file is removed.
  subroutine write_temporary(path, lines, variable, status)
    character(len=*), intent(in) :: path, variable
    character(len=*), intent(in) :: lines(:)
    type(status_t), intent(inout) :: status
    integer :: unit, ios, k
    integer(int64) :: expected, written
    character(len=512) :: msg
    character(len=:), allocatable :: tmp

    tmp = temporary_name(path)
    open (newunit=unit, file=tmp, status='replace', action='write', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_io, variable//' '''//path//''': cannot create ('//trim(msg)//')')
      return
    end if
    do k = 1, size(lines)
      write (unit, '(a)', iostat=ios, iomsg=msg) trim(lines(k))
      if (ios /= 0) exit
    end do
    if (ios == 0) flush (unit, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      close (unit, status='delete', iostat=k)
      call fail(status, exit_io, variable//' '''//path//''': write failed ('//trim(msg)// &
                '); the previous file, if any, is unchanged')
      return
    end if
    close (unit, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call discard_temporary(path)
      call fail(status, exit_io, variable//' '''//path//''': write failed ('//trim(msg)// &
                '); the previous file, if any, is unchanged')
      return
    end if
    ! libgfortran (12.2) drops ENOSPC from formatted writes without setting
    ! iostat: a full disk shows only as a short file, so check the size
    expected = 0
    do k = 1, size(lines)
      expected = expected + len_trim(lines(k)) + 1
    end do
    inquire (file=tmp, size=written)
    if (written /= expected) then
      call discard_temporary(path)
      call fail(status, exit_io, variable//' '''//path//''': write failed (only '//itoa(int(written))//' of '// &
                itoa(int(expected))//' bytes reached the disk; is it full?); the previous file, if any, is unchanged')
    end if
  end subroutine write_temporary

  !> Second half: rename the finished temporary file onto path.
  subroutine commit_temporary(path, variable, status)
    character(len=*), intent(in) :: path, variable
    type(status_t), intent(inout) :: status
    if (c_rename(temporary_name(path)//c_null_char, path//c_null_char) /= 0) then
      call discard_temporary(path)
      call fail(status, exit_io, variable//' '''//path//''': cannot rename the finished temporary file into place')
    end if
  end subroutine commit_temporary

  !> Remove the temporary file of path, if there is one.
  subroutine discard_temporary(path)
    character(len=*), intent(in) :: path
    integer :: unit, ios
    open (newunit=unit, file=temporary_name(path), status='old', iostat=ios)
    if (ios == 0) close (unit, status='delete', iostat=ios)
  end subroutine discard_temporary

  function temporary_name(path) result(tmp)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: tmp
    tmp = path//'.kcreep-tmp-'//itoa(int(c_getpid()))
  end function temporary_name

  real(real64) function ieee_nan()
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    ieee_nan = ieee_value(1.0_real64, ieee_quiet_nan)
  end function ieee_nan

end module table_output
