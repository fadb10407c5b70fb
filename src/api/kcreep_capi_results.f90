!> The C API's results of a solved handle: creep matrix, normalised
!> coefficients, error estimate, FASTSIM flexibilities, verdict and
!> warnings, cells and tractions, diagnostics, the normal problem's result,
!> all results in one array, the reuse count (include/kcreep.h).
module kcreep_capi_results
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_ptr, c_f_pointer, c_associated
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use kcreep_kinds, only: wp
  use kcreep_status, only: fail, exit_bad_input
  use kcreep_strings, only: itoa
  use kcreep, only: n_load_cases
  use kcreep_capi_handle, only: handle_t, status_ok, status_no_result, begin, solved, finish, to_c, output_array
  implicit none
  private

contains

  !> f[3 i + j] = f_(i+1)(j+1): (Fx, Fy, Mz) = -f (xi, eta, phi).
  integer(c_int) function c_get_matrix(handle, f) bind(c, name='kcreep_get_matrix')
    type(c_ptr), value :: handle, f
    type(handle_t), pointer :: h
    real(c_double), pointer :: values(:)
    c_get_matrix = solved(handle, h)
    if (c_get_matrix == status_ok) c_get_matrix = output_array(h, f, 9, 'kcreep_get_matrix: f', values)
    if (c_get_matrix /= status_ok) return
    values = reshape(transpose(h%result%f), [9])   ! C reads row-major
  end function c_get_matrix

  !> c[0..2] = C11, C22, C23 (f11 / (G c^2), f22 / (G c^2), f23 / (G c^3)).
  integer(c_int) function c_get_normalised(handle, c) bind(c, name='kcreep_get_normalised')
    type(c_ptr), value :: handle, c
    type(handle_t), pointer :: h
    real(c_double), pointer :: values(:)
    c_get_normalised = solved(handle, h)
    if (c_get_normalised == status_ok) c_get_normalised = output_array(h, c, 3, 'kcreep_get_normalised: c', values)
    if (c_get_normalised /= status_ok) return
    values = h%result%cn
  end function c_get_normalised

  !> Estimated absolute error of C11, C22, C23 (Richardson extrapolation);
  !> NaN when no estimate was computed. value[0..2]: the extrapolated limits.
  integer(c_int) function c_get_error_estimate(handle, limit, error) bind(c, name='kcreep_get_error_estimate')
    type(c_ptr), value :: handle, limit, error
    type(handle_t), pointer :: h
    real(c_double), pointer :: limits(:), errors(:)
    c_get_error_estimate = solved(handle, h)
    if (c_get_error_estimate == status_ok) &
      c_get_error_estimate = output_array(h, limit, 3, 'kcreep_get_error_estimate: limit', limits)
    if (c_get_error_estimate == status_ok) &
      c_get_error_estimate = output_array(h, error, 3, 'kcreep_get_error_estimate: error', errors)
    if (c_get_error_estimate /= status_ok) return
    if (h%result%extrapolated) then
      limits = h%result%ext
      errors = h%result%ext_error
    else
      limits = ieee_value(1.0_wp, ieee_quiet_nan)
      errors = limits
    end if
  end function c_get_error_estimate

  !> FASTSIM flexibilities L1, L2, L3 from the exact coefficients.
  integer(c_int) function c_get_fastsim(handle, flexibility) bind(c, name='kcreep_get_fastsim')
    type(c_ptr), value :: handle, flexibility
    type(handle_t), pointer :: h
    real(c_double), pointer :: values(:)
    c_get_fastsim = solved(handle, h)
    if (c_get_fastsim == status_ok) c_get_fastsim = output_array(h, flexibility, 3, 'kcreep_get_fastsim: l', values)
    if (c_get_fastsim /= status_ok) return
    values = h%result%fastsim
  end function c_get_fastsim

  !> Verdict bits (0: ok) and the verdict words with the warnings, '; '-separated.
  integer(c_int) function c_get_verdict(handle, flags, buffer, buffer_length) bind(c, name='kcreep_get_verdict')
    type(c_ptr), value :: handle, flags, buffer
    integer(c_int), value :: buffer_length
    type(handle_t), pointer :: h
    character(len=:), allocatable :: text
    integer(c_int), pointer :: flag_value
    character(kind=c_char), pointer :: chars(:)
    integer :: i
    c_get_verdict = solved(handle, h)
    if (c_get_verdict /= status_ok) return
    if (.not. c_associated(flags) .or. .not. c_associated(buffer) .or. buffer_length < 1) then
      call fail(h%last, exit_bad_input, 'kcreep_get_verdict: flags and buffer must not be NULL, buffer_length >= 1')
      c_get_verdict = finish(h)
      return
    end if
    call c_f_pointer(flags, flag_value)
    call c_f_pointer(buffer, chars, [buffer_length])
    flag_value = int(h%result%verdict_flags, c_int)
    text = h%result%verdict
    do i = 1, size(h%result%warnings)
      text = text//'; '//trim(h%result%warnings(i))
    end do
    call to_c(text, chars, buffer_length)
  end function c_get_verdict

  !> Warning number index (0-based; kcreep_get_results gives their count), whole:
  !> a warning's text may contain any punctuation, so callers need not split
  !> kcreep_get_verdict's joined string.
  integer(c_int) function c_get_warning(handle, index, buffer, buffer_length) bind(c, name='kcreep_get_warning')
    type(c_ptr), value :: handle, buffer
    integer(c_int), value :: index, buffer_length
    type(handle_t), pointer :: h
    character(kind=c_char), pointer :: chars(:)
    integer :: count
    c_get_warning = solved(handle, h)
    if (c_get_warning /= status_ok) return
    count = 0
    if (allocated(h%result%warnings)) count = size(h%result%warnings)
    if (.not. c_associated(buffer) .or. buffer_length < 1 .or. index < 0 .or. index >= count) then
      call fail(h%last, exit_bad_input, 'kcreep_get_warning: index = '//itoa(int(index))//' (allowed: 0 to '// &
                itoa(count - 1)//'), buffer not NULL, buffer_length >= 1')
      c_get_warning = finish(h)
      return
    end if
    call c_f_pointer(buffer, chars, [buffer_length])
    call to_c(trim(h%result%warnings(index + 1)), chars, buffer_length)
  end function c_get_warning

  !> Cells in the patch solved (the finest level when extrapolated) and its grid.
  integer(c_int) function c_get_cells(handle, n, mx, my) bind(c, name='kcreep_get_cells')
    type(c_ptr), value :: handle
    integer(c_int), intent(out) :: n, mx, my   ! (by reference: NULL is not allowed, see kcreep.h)
    type(handle_t), pointer :: h
    c_get_cells = solved(handle, h)
    if (c_get_cells /= status_ok) return
    n = int(h%result%n, c_int)
    mx = int(h%result%mx, c_int)
    my = int(h%result%my, c_int)
  end function c_get_cells

  !> Tractions per unit creepage: for cell k (patch order, x fastest) and load
  !> case j (0 xi, 1 eta, 2 phi), px = t[j * 2n + k], py = t[j * 2n + n + k];
  !> ix[k], iy[k] (1-based grid indices) when the pointers are not NULL.
  !> length: the room in t, at least 6 n.
  integer(c_int) function c_get_tractions(handle, length, t, ix, iy) bind(c, name='kcreep_get_tractions')
    type(c_ptr), value :: handle
    integer(c_int), value :: length
    type(c_ptr), value :: t, ix, iy
    type(handle_t), pointer :: h
    integer(c_int), pointer :: cells(:)
    real(c_double), pointer :: values(:)
    integer :: n
    c_get_tractions = solved(handle, h)
    if (c_get_tractions /= status_ok) return
    if (.not. allocated(h%result%traction)) then
      call fail(h%last, exit_bad_input, 'kcreep_get_tractions: the last solve computed no tractions '// &
                '(method "table" interpolates the coefficients; set another method to solve for them)')
      c_get_tractions = finish(h)
      return
    end if
    n = h%result%n
    if (length < 2 * n * n_load_cases) then
      call fail(h%last, exit_bad_input, 'kcreep_get_tractions: length must be at least 6 n = '// &
                itoa(6 * n))
      c_get_tractions = finish(h)
      return
    end if
    c_get_tractions = output_array(h, t, 2 * n * n_load_cases, 'kcreep_get_tractions: t', values)
    if (c_get_tractions /= status_ok) return
    values = reshape(h%result%traction, [2 * n * n_load_cases])
    if (c_associated(ix)) then
      call c_f_pointer(ix, cells, [n])
      cells = int(h%result%patch%ix, c_int)
    end if
    if (c_associated(iy)) then
      call c_f_pointer(iy, cells, [n])
      cells = int(h%result%patch%iy, c_int)
    end if
  end function c_get_tractions

  !> How the last solve went: GMRES iterations (0 for dense LU), the final
  !> relative residual (iterative) or backward error (dense), LAPACK's rcond
  !> (NaN for the iterative path) and the seconds it took.
  integer(c_int) function c_get_diagnostics(handle, iterations, residual, rcond, seconds) &
    bind(c, name='kcreep_get_diagnostics')
    type(c_ptr), value :: handle
    integer(c_int), intent(out) :: iterations
    real(c_double), intent(out) :: residual, rcond, seconds
    type(handle_t), pointer :: h
    c_get_diagnostics = solved(handle, h)
    if (c_get_diagnostics /= status_ok) return
    iterations = int(h%result%iterations, c_int)
    residual = h%result%backward_error
    rcond = h%result%rcond
    seconds = h%result%t_total
  end function c_get_diagnostics

  !> The normal problem of the last solve: total force, approach, maximum
  !> pressure, cells in contact and CG iterations (status 6 when the last
  !> solve had no normal problem).
  integer(c_int) function c_get_normal(handle, fn, approach, pmax, cells, iterations) bind(c, name='kcreep_get_normal')
    type(c_ptr), value :: handle
    real(c_double), intent(out) :: fn, approach, pmax
    integer(c_int), intent(out) :: cells, iterations
    type(handle_t), pointer :: h
    c_get_normal = solved(handle, h)
    if (c_get_normal /= status_ok) return
    if (.not. h%result%normal_solved) then
      call fail(h%last, int(status_no_result), 'kcreep_get_normal: the last solve had no normal problem '// &
                '(kcreep_set_gap)')
      c_get_normal = finish(h)
      return
    end if
    fn = h%result%fn
    approach = h%result%approach
    pmax = h%result%pmax
    cells = int(h%result%n, c_int)
    iterations = int(h%result%normal_iterations, c_int)
  end function c_get_normal

  !> Everything numeric of the last solve in one call (for bindings, where
  !> each call costs): values(1:9) f row by row, (10:12) C11 C22 C23,
  !> (13:15) L1 L2 L3, (16:18) relative error estimates, (19:21) extrapolated
  !> C, (22:24) their errors, (25) GMRES iterations, (26) residual or backward
  !> error, (27) rcond, (28) seconds, (29) cells, (30) mx, (31) my, (32)
  !> verdict bits, (33) number of warnings. length: at least 33.
  integer(c_int) function c_get_results(handle, length, values) bind(c, name='kcreep_get_results')
    type(c_ptr), value :: handle, values
    integer(c_int), value :: length
    type(handle_t), pointer :: h
    real(c_double), pointer :: v(:)
    real(wp) :: nan
    c_get_results = solved(handle, h)
    if (c_get_results /= status_ok) return
    if (length < 33) then
      call fail(h%last, exit_bad_input, 'kcreep_get_results: length must be at least 33')
      c_get_results = finish(h)
      return
    end if
    c_get_results = output_array(h, values, 33, 'kcreep_get_results: values', v)
    if (c_get_results /= status_ok) return
    nan = ieee_value(1.0_wp, ieee_quiet_nan)
    associate (r => h%result)
      v(1:9) = reshape(transpose(r%f), [9])
      v(10:12) = r%cn
      v(13:15) = r%fastsim
      v(16:18) = r%err
      v(19:21) = merge(r%ext, [nan, nan, nan], r%extrapolated)
      v(22:24) = merge(r%ext_error, [nan, nan, nan], r%extrapolated)
      v(25:31) = [real(r%iterations, wp), r%backward_error, r%rcond, r%t_total, real(r%n, wp), real(r%mx, wp), &
                  real(r%my, wp)]
      v(32) = r%verdict_flags
      v(33) = size(r%warnings)
    end associate
  end function c_get_results

  !> Solves on this handle that reused the operator table of an earlier one.
  integer(c_int) function c_get_reuse_count(handle, count) bind(c, name='kcreep_get_reuse_count')
    type(c_ptr), value :: handle
    integer(c_int), intent(out) :: count
    type(handle_t), pointer :: h
    c_get_reuse_count = begin(handle, h)
    if (c_get_reuse_count /= status_ok) return
    count = int(h%cache%reused, c_int)
  end function c_get_reuse_count

  ! --- helpers -------------------------------------------------------------

end module kcreep_capi_results
