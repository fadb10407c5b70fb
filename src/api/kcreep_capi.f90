!> The C API (include/kcreep.h): an opaque handle holding one problem
!> (grid geometry, material, scheme, solver settings), its last result, its
!> last error and what repeated solves on the same grid can reuse.
!>
!> Every function returns a status: 0 (KCREEP_OK), 2 (bad argument or
!> input), 3 (numerical failure) or 6 (no result yet, or a null handle).
!> After a failure kcreep_get_message gives the one-line reason. Null
!> handles and bad arrays are errors, never crashes.
module kcreep_capi
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_ptr, c_null_ptr, c_null_char, &
                                         c_loc, c_f_pointer, c_associated
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use kcreep_kinds, only: wp
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa
  use kcreep, only: kcreep_solve, kcreep_version_number, max_threads, problem_t, result_t, default_problem, solve_cache_t, &
                    ellipse_patch, mask_patch, n_load_cases, gap_from_array
  use kcreep_creep_curve, only: creep_request_t, creep_point_t, creep_map_t, creep_curve
  use kcreep_fastsim_forces, only: flexibility_rule_of
  use kcreep_rolling_curve, only: rolling_request_t, rolling_point_t, rolling_curve
  use kcreep_normal_influence, only: compliance_from_e_nu, combined_g_nu_from_e_nu
  implicit none
  private

  integer(c_int), parameter :: status_ok = 0, status_no_result = 6

  type :: handle_t
    type(problem_t) :: problem
    type(result_t) :: result
    type(solve_cache_t) :: cache
    logical :: solved = .false.
    type(status_t) :: last
  end type handle_t

contains

  !> Version as an integer: 10000 major + 100 minor + patch.
  integer(c_int) function c_version() bind(c, name='kcreep_version')
    c_version = int(kcreep_version_number, c_int)
  end function c_version

  !> A new handle with kcreep's default settings and no patch.
  type(c_ptr) function c_new() bind(c, name='kcreep_new')
    type(handle_t), pointer :: h
    allocate (h)
    h%problem = default_problem()
    c_new = c_loc(h)
  end function c_new

  !> Free the handle and set the caller's pointer to NULL (NULL is accepted).
  subroutine c_delete(handle) bind(c, name='kcreep_delete')
    type(c_ptr), intent(inout) :: handle
    type(handle_t), pointer :: h
    if (.not. c_associated(handle)) return
    call c_f_pointer(handle, h)
    deallocate (h)
    handle = c_null_ptr
  end subroutine c_delete

  !> The last error's message (empty after success), cut to buffer_length - 1
  !> characters and NUL-terminated.
  integer(c_int) function c_get_message(handle, buffer, buffer_length) bind(c, name='kcreep_get_message')
    type(c_ptr), value :: handle, buffer
    integer(c_int), value :: buffer_length
    type(handle_t), pointer :: h
    character(kind=c_char), pointer :: chars(:)
    if (buffer_length < 1 .or. .not. c_associated(buffer)) then
      c_get_message = exit_bad_input
      return
    end if
    call c_f_pointer(buffer, chars, [buffer_length])
    if (.not. c_associated(handle)) then
      call to_c('null handle', chars, buffer_length)
      c_get_message = status_no_result
      return
    end if
    call c_f_pointer(handle, h)
    if (allocated(h%last%message)) then
      call to_c(h%last%message, chars, buffer_length)
    else
      call to_c('', chars, buffer_length)
    end if
    c_get_message = status_ok
  end function c_get_message

  !> Combined shear modulus g and Poisson's ratio nu of the two bodies.
  integer(c_int) function c_set_material(handle, g, nu) bind(c, name='kcreep_set_material')
    type(c_ptr), value :: handle
    real(c_double), value :: g, nu
    type(handle_t), pointer :: h
    c_set_material = begin(handle, h)
    if (c_set_material /= status_ok) return
    h%problem%g = g
    h%problem%nu = nu
    h%problem%normal%compliance = 0   ! the normal problem's 1/E* from g, nu again
  end function c_set_material

  !> Two bodies of Young's moduli e1, e2 and Poisson ratios nu1, nu2: the
  !> combined g, nu of the tangential problem and 1/E* of the normal problem
  !> (CONTACT's convention); replaces kcreep_set_material.
  integer(c_int) function c_set_bodies(handle, e1, nu1, e2, nu2) bind(c, name='kcreep_set_bodies')
    type(c_ptr), value :: handle
    real(c_double), value :: e1, nu1, e2, nu2
    type(handle_t), pointer :: h
    c_set_bodies = begin(handle, h)
    if (c_set_bodies /= status_ok) return
    if (.not. (e1 > 0 .and. e2 > 0 .and. e1 < huge(1.0_wp) .and. e2 < huge(1.0_wp))) then
      call fail(h%last, exit_bad_input, 'kcreep_set_bodies: e1, e2 must be finite and > 0')
    else if (.not. (nu1 >= 0 .and. nu1 <= 0.5_wp .and. nu2 >= 0 .and. nu2 <= 0.5_wp)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_bodies: nu1, nu2 must be in [0, 0.5]')
    else
      call combined_g_nu_from_e_nu(real(e1, wp), real(nu1, wp), real(e2, wp), real(nu2, wp), &
                                   h%problem%g, h%problem%nu)
      h%problem%normal%compliance = compliance_from_e_nu(real(e1, wp), real(nu1, wp), real(e2, wp), real(nu2, wp))
    end if
    c_set_bodies = finish(h)
  end function c_set_bodies

  !> The point (x, y) the spin turns about and Mz is taken at (default the origin).
  integer(c_int) function c_set_spin_centre(handle, x, y) bind(c, name='kcreep_set_spin_centre')
    type(c_ptr), value :: handle
    real(c_double), value :: x, y
    type(handle_t), pointer :: h
    c_set_spin_centre = begin(handle, h)
    if (c_set_spin_centre /= status_ok) return
    if (.not. (abs(x) < huge(1.0_wp) .and. abs(y) < huge(1.0_wp))) then
      call fail(h%last, exit_bad_input, 'kcreep_set_spin_centre: x, y must be finite')
    else
      h%problem%spin_centre = [x, y]
    end if
    c_set_spin_centre = finish(h)
  end function c_set_spin_centre

  !> scheme: "collocation" (with alpha) or "backward" (with spin_shift, in cells).
  integer(c_int) function c_set_scheme(handle, name, alpha, spin_shift) bind(c, name='kcreep_set_scheme')
    type(c_ptr), value :: handle, name
    real(c_double), value :: alpha, spin_shift
    type(handle_t), pointer :: h
    c_set_scheme = begin(handle, h)
    if (c_set_scheme /= status_ok) return
    if (.not. c_associated(name)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_scheme: name is NULL')
      c_set_scheme = finish(h)
      return
    end if
    h%problem%scheme%name = from_c(name, 32)
    h%problem%scheme%alpha = alpha
    h%problem%scheme%spin_shift = spin_shift
  end function c_set_scheme

  !> method: "auto", "dense" or "iterative"; tolerance of the iterative solver (0: default).
  integer(c_int) function c_set_solver(handle, method, tolerance) bind(c, name='kcreep_set_solver')
    type(c_ptr), value :: handle, method
    real(c_double), value :: tolerance
    type(handle_t), pointer :: h
    c_set_solver = begin(handle, h)
    if (c_set_solver /= status_ok) return
    if (.not. c_associated(method)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_solver: method is NULL')
      c_set_solver = finish(h)
      return
    end if
    h%problem%solve%method = from_c(method, 32)
    if (tolerance > 0) then
      h%problem%solve%tolerance = tolerance
      h%problem%solve%tolerance_given = .true.
    end if
  end function c_set_solver

  !> Threads of each solve on this handle: 0 automatic (the default: the CPUs
  !> this process may use that are free when a stage starts, where the work
  !> pays for them), else exactly this many (1 to 1024).
  integer(c_int) function c_set_threads(handle, threads) bind(c, name='kcreep_set_threads')
    type(c_ptr), value :: handle
    integer(c_int), value :: threads
    type(handle_t), pointer :: h
    c_set_threads = begin(handle, h)
    if (c_set_threads /= status_ok) return
    if (threads < 0 .or. threads > max_threads) then
      call fail(h%last, exit_bad_input, 'kcreep_set_threads: threads = '//itoa(int(threads))// &
                ' (allowed: 0 = automatic, or 1 to '//itoa(max_threads)//')')
    else
      h%problem%solve%threads = int(threads)
    end if
    c_set_threads = finish(h)
  end function c_set_threads

  !> The threads the last solve's linear solve ran on.
  integer(c_int) function c_get_threads(handle, threads) bind(c, name='kcreep_get_threads')
    type(c_ptr), value :: handle
    integer(c_int), intent(out) :: threads
    type(handle_t), pointer :: h
    c_get_threads = solved(handle, h)
    if (c_get_threads /= status_ok) return
    threads = int(h%result%threads, c_int)
  end function c_get_threads

  !> Richardson extrapolation over levels (2 or 3) refined by ratio; levels 0 turns it off.
  integer(c_int) function c_set_extrapolation(handle, levels, ratio) bind(c, name='kcreep_set_extrapolation')
    type(c_ptr), value :: handle
    integer(c_int), value :: levels, ratio
    type(handle_t), pointer :: h
    c_set_extrapolation = begin(handle, h)
    if (c_set_extrapolation /= status_ok) return
    h%problem%extrapolate = levels > 0
    if (levels > 0) then
      h%problem%extrapolate_levels = levels
      h%problem%refine_ratio = ratio
    end if
  end function c_set_extrapolation

  !> Error control: target_error (relative, for C11 and C22; C23 gets 3 times
  !> it; 0: none) and whether kcreep may choose the grids (ellipse: near-square
  !> cells) or split the cells (mask) to meet it (refine_grid != 0); with
  !> refine_grid 0 the grid is solved as given and only judged. estimate 0
  !> with target 0 skips the judging (one more solve on a coarser or split
  !> grid): for loops over similar patches whose grid was judged once.
  integer(c_int) function c_set_error_control(handle, target_error, refine_grid, estimate) &
    bind(c, name='kcreep_set_error_control')
    type(c_ptr), value :: handle
    real(c_double), value :: target_error
    integer(c_int), value :: refine_grid, estimate
    type(handle_t), pointer :: h
    c_set_error_control = begin(handle, h)
    if (c_set_error_control /= status_ok) return
    if (.not. (target_error >= 0 .and. target_error < 1)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_error_control: target_error must be in [0, 1)')
    else
      h%problem%target_error = target_error
      h%problem%refine_grid = refine_grid /= 0
      h%problem%estimate_error = estimate /= 0
    end if
    c_set_error_control = finish(h)
  end function c_set_error_control

  !> The most patch cells of a level kcreep chooses under error control
  !> (0: the defaults, a run-time budget; 1e3 to 1e7): raised for reference
  !> work, e.g. target_error 1e-4 to reach `ok`. Checked when solving.
  integer(c_int) function c_set_cell_budget(handle, cells) bind(c, name='kcreep_set_cell_budget')
    type(c_ptr), value :: handle
    real(c_double), value :: cells
    type(handle_t), pointer :: h
    c_set_cell_budget = begin(handle, h)
    if (c_set_cell_budget /= status_ok) return
    h%problem%cell_budget = cells
    c_set_cell_budget = finish(h)
  end function c_set_cell_budget

  !> The estimated relative errors of C11, C22, C23 of the last solve (every
  !> run makes one; NaN when the grid is too coarse to judge itself).
  integer(c_int) function c_get_relative_error(handle, error) bind(c, name='kcreep_get_relative_error')
    type(c_ptr), value :: handle, error
    type(handle_t), pointer :: h
    real(c_double), pointer :: values(:)
    c_get_relative_error = solved(handle, h)
    if (c_get_relative_error == status_ok) &
      c_get_relative_error = output_array(h, error, 3, 'kcreep_get_relative_error: error', values)
    if (c_get_relative_error /= status_ok) return
    values = h%result%err
  end function c_get_relative_error

  !> The ellipse of semi-axes a (along x, rolling) and b on an mx x my grid over [-a, a] x [-b, b].
  integer(c_int) function c_set_ellipse(handle, semi_a, semi_b, mx, my) bind(c, name='kcreep_set_ellipse')
    type(c_ptr), value :: handle
    real(c_double), value :: semi_a, semi_b
    integer(c_int), value :: mx, my
    type(handle_t), pointer :: h
    c_set_ellipse = begin(handle, h)
    if (c_set_ellipse /= status_ok) return
    if (.not. (semi_a > 0 .and. semi_b > 0 .and. semi_a < huge(1.0_wp) .and. semi_b < huge(1.0_wp))) then
      call fail(h%last, exit_bad_input, 'kcreep_set_ellipse: semi_a, semi_b must be finite and > 0')
    else if (mx < 1 .or. my < 1) then
      call fail(h%last, exit_bad_input, 'kcreep_set_ellipse: mx, my must be >= 1')
    else
      call ellipse_patch(real(semi_a, wp), real(semi_b, wp), int(mx), int(my), h%problem%patch, h%last)
    end if
    c_set_ellipse = finish(h)
  end function c_set_ellipse

  !> A mask of mx x my cells: inside[iy * mx + ix] != 0 for cells in the patch
  !> (rows in increasing y, cells in increasing x), cell sizes dx, dy, centre
  !> of the first cell (x0, y0).
  integer(c_int) function c_set_mask(handle, mx, my, inside, dx, dy, x0, y0) bind(c, name='kcreep_set_mask')
    type(c_ptr), value :: handle
    integer(c_int), value :: mx, my
    type(c_ptr), value :: inside
    real(c_double), value :: dx, dy, x0, y0
    type(handle_t), pointer :: h
    integer(c_int), pointer :: cells(:, :)
    c_set_mask = begin(handle, h)
    if (c_set_mask /= status_ok) return
    if (.not. c_associated(inside)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_mask: inside is NULL')
    else if (mx < 1 .or. my < 1) then
      call fail(h%last, exit_bad_input, 'kcreep_set_mask: mx, my must be >= 1')
    else if (.not. (dx > 0 .and. dy > 0 .and. dx < huge(1.0_wp) .and. dy < huge(1.0_wp))) then
      call fail(h%last, exit_bad_input, 'kcreep_set_mask: dx, dy must be finite and > 0')
    else if (.not. (abs(x0) < huge(1.0_wp) .and. abs(y0) < huge(1.0_wp))) then
      call fail(h%last, exit_bad_input, 'kcreep_set_mask: x0, y0 must be finite')
    else
      call c_f_pointer(inside, cells, [mx, my])
      call mask_patch(cells /= 0, real(dx, wp), real(dy, wp), real(x0, wp), real(y0, wp), 'kcreep_set_mask', &
                      h%problem%patch, h%last)
    end if
    c_set_mask = finish(h)
  end function c_set_mask

  !> Solve the handle's problem (reusing the operator table of the last solve
  !> when the grid, scheme and material are the same).
  integer(c_int) function c_solve(handle) bind(c, name='kcreep_solve')
    type(c_ptr), value :: handle
    type(handle_t), pointer :: h
    c_solve = begin(handle, h)
    if (c_solve /= status_ok) return
    h%solved = .false.
    call kcreep_solve(h%problem, h%result, h%last, h%cache)
    h%solved = .not. h%last%failed()
    c_solve = finish(h)
  end function c_solve

  !> kcreep_set_mask, then kcreep_solve: the in-loop call.
  integer(c_int) function c_solve_mask(handle, mx, my, inside, dx, dy, x0, y0) bind(c, name='kcreep_solve_mask')
    type(c_ptr), value :: handle
    integer(c_int), value :: mx, my
    type(c_ptr), value :: inside
    real(c_double), value :: dx, dy, x0, y0
    c_solve_mask = c_set_mask(handle, mx, my, inside, dx, dy, x0, y0)
    if (c_solve_mask == status_ok) c_solve_mask = c_solve(handle)
  end function c_solve_mask

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

  !> The undeformed distance h of the two surfaces on an mx x my grid
  !> (h[iy * mx + ix], rows in increasing y; cell sizes dx, dy; centre of the
  !> first cell x0, y0): the next solve finds the contact area and pressure
  !> (the normal problem) and then the coefficients of that area. Exactly one
  !> of approach and normal_force is > 0 (the other 0): what is prescribed.
  !> The material is the handle's (g, nu: 1/E* = (1 - nu)/g).
  integer(c_int) function c_set_gap(handle, mx, my, gap, dx, dy, x0, y0, approach, normal_force) &
    bind(c, name='kcreep_set_gap')
    type(c_ptr), value :: handle, gap
    integer(c_int), value :: mx, my
    real(c_double), value :: dx, dy, x0, y0, approach, normal_force
    type(handle_t), pointer :: h
    real(c_double), pointer :: values(:, :)
    c_set_gap = begin(handle, h)
    if (c_set_gap /= status_ok) return
    if (.not. c_associated(gap)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_gap: gap is NULL')
    else if (mx < 1 .or. my < 1) then
      call fail(h%last, exit_bad_input, 'kcreep_set_gap: mx, my must be >= 1')
    else if ((approach > 0) .eqv. (normal_force > 0)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_gap: exactly one of approach and normal_force must be > 0')
    else if (.not. (approach >= 0 .and. normal_force >= 0 .and. approach < huge(1.0_wp) &
                    .and. normal_force < huge(1.0_wp))) then
      call fail(h%last, exit_bad_input, 'kcreep_set_gap: approach, normal_force must be finite and >= 0')
    else
      call c_f_pointer(gap, values, [mx, my])
      call gap_from_array(values, real(dx, wp), real(dy, wp), real(x0, wp), real(y0, wp), 'kcreep_set_gap', &
                          h%problem%normal%gap, h%last)
      if (.not. h%last%failed()) then
        h%problem%normal%active = .true.
        h%problem%normal%force_given = normal_force > 0
        h%problem%normal%approach = approach
        h%problem%normal%normal_force = normal_force
      end if
    end if
    c_set_gap = finish(h)
  end function c_set_gap

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

  !> FASTSIM with friction mu on the solved patch for n creepages
  !> creep[3 k + 0..2] = (xi, eta, phi), with the patch's exact L1 L2 L3.
  !> pressure: mx * my values on the patch's grid (rows in increasing y), or
  !> NULL for the pressure of the normal problem (after kcreep_set_gap).
  !> rule: "aligned" (the program's default: each creepage term with its own
  !> L, slipping tractions opposing the slip; docs/fastsim.md), "separate"
  !> (each term with its own L, slipping tractions along the predictor) or
  !> "weighted" (Kalker's single weighted L). Out: force[3 k + 0..2] = (Fx, Fy, Mz),
  !> adhesion[k] = fraction of the area in adhesion (may be NULL).
  integer(c_int) function c_fastsim(handle, mu, n, creep, pressure, rule, force, adhesion) &
    bind(c, name='kcreep_fastsim')
    type(c_ptr), value :: handle, creep, pressure, rule, force, adhesion
    real(c_double), value :: mu
    integer(c_int), value :: n
    type(handle_t), pointer :: h
    real(c_double), pointer :: creepages(:, :), forces(:, :), adhered(:)
    real(wp), allocatable :: pn(:, :)
    type(creep_request_t) :: request
    type(creep_point_t), allocatable :: points(:)
    type(creep_map_t), allocatable :: maps(:)
    character(len=:), allocatable :: rule_name
    integer :: k
    c_fastsim = solved(handle, h)
    if (c_fastsim /= status_ok) return
    if (.not. (mu > 0 .and. mu < huge(1.0_wp)) .or. n < 1) then
      call fail(h%last, exit_bad_input, 'kcreep_fastsim: mu must be finite and > 0, n >= 1')
    else if (.not. c_associated(creep) .or. .not. c_associated(force) .or. .not. c_associated(rule)) then
      call fail(h%last, exit_bad_input, 'kcreep_fastsim: creep, rule and force must not be NULL')
    else if (.not. c_associated(pressure) .and. .not. h%result%normal_solved) then
      call fail(h%last, exit_bad_input, 'kcreep_fastsim: pressure is NULL and the last solve had no normal problem')
    end if
    if (h%last%failed()) then
      c_fastsim = finish(h)
      return
    end if
    rule_name = from_c(rule, 16)
    request%rule = flexibility_rule_of(rule_name)
    if (request%rule == 0) then
      call fail(h%last, exit_bad_input, 'kcreep_fastsim: rule = "'//rule_name//'" (allowed: aligned, separate, weighted)')
      c_fastsim = finish(h)
      return
    end if
    call pressure_of(h, pressure, 'kcreep_fastsim', pn)
    if (h%last%failed()) then
      c_fastsim = finish(h)
      return
    end if
    call c_f_pointer(creep, creepages, [3, int(n)])
    request%mu = mu
    request%creepages = creepages
    call creep_curve(h%result, pn, request, points, maps)
    call c_f_pointer(force, forces, [3, int(n)])
    do k = 1, n
      forces(:, k) = [points(k)%force%fx, points(k)%force%fy, points(k)%force%mz]
    end do
    if (c_associated(adhesion)) then
      call c_f_pointer(adhesion, adhered, [int(n)])
      adhered = [(points(k)%force%adhesion, k=1, n)]
    end if
  end function c_fastsim

  !> The pressure for kcreep_fastsim / kcreep_rolling: mx * my values, or the
  !> normal problem's (pressure NULL); an error in h%last when not usable.
  subroutine pressure_of(h, pressure, who, pn)
    type(handle_t), intent(inout) :: h
    type(c_ptr), intent(in) :: pressure
    character(len=*), intent(in) :: who
    real(wp), allocatable, intent(out) :: pn(:, :)
    real(c_double), pointer :: grid(:, :)
    integer :: k
    associate (p => h%result%patch)
      if (c_associated(pressure)) then
        call c_f_pointer(pressure, grid, [p%mx, p%my])
        pn = grid
        if (.not. all(pn >= 0 .and. pn < huge(1.0_wp))) &
          call fail(h%last, exit_bad_input, who//': pressure must be finite and >= 0 on the grid')
      else
        allocate (pn(p%mx, p%my))
        pn = 0
        do k = 1, p%n
          pn(p%ix(k), p%iy(k)) = h%result%pressure(k)
        end do
      end if
    end associate
  end subroutine pressure_of

  !> Exact steady rolling with friction mu on the solved patch (docs/rolling.md),
  !> the same conventions as kcreep_fastsim: creep[3 k + 0..2], pressure (or
  !> NULL), force[3 k + 0..2] = (Fx, Fy, Mz), adhesion[k] (may be NULL).
  integer(c_int) function c_rolling(handle, mu, n, creep, pressure, force, adhesion) bind(c, name='kcreep_rolling')
    type(c_ptr), value :: handle, creep, pressure, force, adhesion
    real(c_double), value :: mu
    integer(c_int), value :: n
    type(handle_t), pointer :: h
    real(c_double), pointer :: creepages(:, :), forces(:, :), adhered(:)
    real(wp), allocatable :: pn(:, :)
    type(rolling_request_t) :: request
    type(rolling_point_t), allocatable :: points(:)
    type(creep_map_t), allocatable :: maps(:)
    integer :: k
    c_rolling = solved(handle, h)
    if (c_rolling /= status_ok) return
    if (.not. (mu > 0 .and. mu < huge(1.0_wp)) .or. n < 1) then
      call fail(h%last, exit_bad_input, 'kcreep_rolling: mu must be finite and > 0, n >= 1')
    else if (.not. c_associated(creep) .or. .not. c_associated(force)) then
      call fail(h%last, exit_bad_input, 'kcreep_rolling: creep and force must not be NULL')
    else if (.not. c_associated(pressure) .and. .not. h%result%normal_solved) then
      call fail(h%last, exit_bad_input, 'kcreep_rolling: pressure is NULL and the last solve had no normal problem')
    end if
    if (.not. h%last%failed()) call pressure_of(h, pressure, 'kcreep_rolling', pn)
    if (.not. h%last%failed()) then
      call c_f_pointer(creep, creepages, [3, int(n)])
      request%mu = mu
      request%creepages = creepages
      if (allocated(h%result%traction)) then
        call rolling_curve(h%result%patch, h%problem%scheme, h%result%nu, h%result%g, h%result%spin_centre, pn, &
                           request, points, maps, h%last, h%result%traction)
      else
        call rolling_curve(h%result%patch, h%problem%scheme, h%result%nu, h%result%g, h%result%spin_centre, pn, &
                           request, points, maps, h%last)
      end if
    end if
    if (h%last%failed()) then
      c_rolling = finish(h)
      return
    end if
    call c_f_pointer(force, forces, [3, int(n)])
    forces = reshape([(points(k)%force%fx, points(k)%force%fy, points(k)%force%mz, k=1, n)], [3, int(n)])
    if (c_associated(adhesion)) then
      call c_f_pointer(adhesion, adhered, [int(n)])
      adhered = [(points(k)%force%adhesion, k=1, n)]
    end if
  end function c_rolling

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

  !> The handle behind a C pointer, with its last error cleared.
  integer(c_int) function begin(handle, h)
    type(c_ptr), intent(in) :: handle
    type(handle_t), pointer, intent(out) :: h
    nullify (h)
    if (.not. c_associated(handle)) then
      begin = status_no_result
      return
    end if
    call c_f_pointer(handle, h)
    h%last = status_t()
    begin = status_ok
  end function begin

  !> The handle of a solved problem, or the status saying why there is none.
  integer(c_int) function solved(handle, h)
    type(c_ptr), intent(in) :: handle
    type(handle_t), pointer, intent(out) :: h
    solved = begin(handle, h)
    if (solved /= status_ok) return
    if (.not. h%solved) then
      call fail(h%last, int(status_no_result), 'no result: call kcreep_solve (successfully) first')
      solved = status_no_result
    end if
  end function solved

  integer(c_int) function finish(h)
    type(handle_t), intent(in) :: h
    finish = int(h%last%code, c_int)
  end function finish

  !> A NUL-terminated C string (at most max_length characters read).
  function from_c(text_ptr, max_length) result(s)
    type(c_ptr), intent(in) :: text_ptr
    integer, intent(in) :: max_length
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: text(:)
    integer :: i
    call c_f_pointer(text_ptr, text, [max_length])
    s = ''
    do i = 1, max_length
      if (text(i) == c_null_char) exit
      s = s//text(i)
    end do
  end function from_c

  subroutine to_c(s, buffer, buffer_length)
    character(len=*), intent(in) :: s
    character(kind=c_char), intent(out) :: buffer(*)
    integer(c_int), intent(in) :: buffer_length
    integer :: i, n
    n = min(len(s), int(buffer_length) - 1)
    do i = 1, n
      buffer(i) = s(i:i)
    end do
    buffer(n + 1) = c_null_char
  end subroutine to_c

  !> out as a Fortran array of length n, or a bad-input status when it is NULL.
  integer(c_int) function output_array(h, out, n, what, values)
    type(handle_t), intent(inout) :: h
    type(c_ptr), intent(in) :: out
    integer, intent(in) :: n
    character(len=*), intent(in) :: what
    real(c_double), pointer, intent(out) :: values(:)
    nullify (values)
    if (.not. c_associated(out)) then
      call fail(h%last, exit_bad_input, what//' is NULL')
    else
      call c_f_pointer(out, values, [n])
    end if
    output_array = finish(h)
  end function output_array

end module kcreep_capi
