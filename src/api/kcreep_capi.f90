!> The C API (include/kcreep.h): the handle's life (kcreep_new, kcreep_delete,
!> kcreep_get_message), its setters and kcreep_solve. The handle type and
!> its helpers are in kcreep_capi_handle; results, FASTSIM and the wheel-rail
!> calls in kcreep_capi_results, kcreep_capi_fastsim, kcreep_capi_wheel_rail.
!>
!> Every function returns a status: 0 (KCREEP_OK), 2 (bad argument or
!> input), 3 (numerical failure) or 6 (no result yet, or a null handle).
!> After a failure kcreep_get_message gives the one-line reason. Null
!> handles and bad arrays are errors, never crashes.
module kcreep_capi
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_ptr, c_null_ptr, c_loc, c_f_pointer, c_associated
  use kcreep_kinds, only: wp
  use kcreep_status, only: fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use kcreep_limits, only: modulus_in_range
  use kcreep, only: kcreep_solve, kcreep_version_number, max_threads, default_problem, ellipse_patch, mask_patch, &
                    gap_from_array, compliance_from_e_nu, combined_g_nu_from_e_nu, nominal_ellipse_cells, &
                    release_rolling_state, fast_forces_t
  use kcreep_capi_handle, only: handle_t, status_ok, status_no_result, begin, solved, finish, from_c, to_c, output_array
  implicit none
  private

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
    h%wheel_rail%side = 'right'
    c_new = c_loc(h)
  end function c_new

  !> Free the handle and set the caller's pointer to NULL (NULL is accepted).
  subroutine c_delete(handle) bind(c, name='kcreep_delete')
    type(c_ptr), intent(inout) :: handle
    type(handle_t), pointer :: h
    if (.not. c_associated(handle)) return
    call c_f_pointer(handle, h)
    call release_rolling_state(h%rolling)
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
    if (.not. modulus_in_range(real(g, wp))) then
      call fail(h%last, exit_bad_input, 'kcreep_set_material: g = '//rtoa(real(g, wp))// &
                ' (allowed: 1e-100 <= g <= 1e100, the combined shear modulus)')
    else if (.not. (nu >= 0 .and. nu <= 0.5_wp)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_material: nu = '//rtoa(real(nu, wp))//' (allowed: 0 <= nu <= 0.5)')
    else
      h%problem%g = g
      h%problem%nu = nu
      h%problem%normal%compliance = 0   ! the normal problem's 1/E* from g, nu again
    end if
    c_set_material = finish(h)
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
    character(len=:), allocatable :: word
    c_set_scheme = begin(handle, h)
    if (c_set_scheme /= status_ok) return
    if (.not. c_associated(name)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_scheme: name is NULL')
      c_set_scheme = finish(h)
      return
    end if
    word = from_c(name, 32)
    if (word /= 'collocation' .and. word /= 'backward') then
      call fail(h%last, exit_bad_input, 'kcreep_set_scheme: name = "'//word//'" (allowed: "backward", "collocation")')
    else if (.not. (abs(alpha) < 1)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_scheme: alpha = '//rtoa(real(alpha, wp))// &
                ' (allowed: -1 < alpha < 1; used by "collocation")')
    else if (.not. (abs(spin_shift) <= 1)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_scheme: spin_shift = '//rtoa(real(spin_shift, wp))// &
                ' (allowed: -1 <= spin_shift <= 1 cell; used by "backward")')
    else
      h%problem%scheme%name = word
      h%problem%scheme%alpha = alpha
      h%problem%scheme%spin_shift = spin_shift
    end if
    c_set_scheme = finish(h)
  end function c_set_scheme

  !> method: "auto", "dense" or "iterative"; tolerance of the iterative solver (0: default).
  integer(c_int) function c_set_solver(handle, method, tolerance) bind(c, name='kcreep_set_solver')
    type(c_ptr), value :: handle, method
    real(c_double), value :: tolerance
    type(handle_t), pointer :: h
    character(len=:), allocatable :: word
    c_set_solver = begin(handle, h)
    if (c_set_solver /= status_ok) return
    if (.not. c_associated(method)) then
      call fail(h%last, exit_bad_input, 'kcreep_set_solver: method is NULL')
      c_set_solver = finish(h)
      return
    end if
    word = from_c(method, 32)
    if (word /= 'auto' .and. word /= 'dense' .and. word /= 'iterative' .and. word /= 'table') then
      call fail(h%last, exit_bad_input, 'kcreep_set_solver: method = "'//word// &
                '" (allowed: "auto", "dense", "iterative", "table")')
    else if (.not. (tolerance == 0 .or. (tolerance >= 1e-15_wp .and. tolerance < 1))) then
      call fail(h%last, exit_bad_input, 'kcreep_set_solver: tolerance = '//rtoa(real(tolerance, wp))// &
                ' (allowed: 0 for the default, or 1e-15 <= tolerance < 1)')
    else
      h%problem%solve%method = word
      if (tolerance > 0) then
        h%problem%solve%tolerance = tolerance
        h%problem%solve%tolerance_given = .true.
      end if
    end if
    c_set_solver = finish(h)
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
      h%refine_grid = refine_grid /= 0
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

  !> The ellipse of semi-axes a (along x, rolling) and b on an mx x my grid
  !> over [-a, a] x [-b, b], solved as given; mx = my = 0: kcreep chooses the
  !> grids (or answers from its refined table), as the program does for an
  !> ellipse without mx, my.
  integer(c_int) function c_set_ellipse(handle, semi_a, semi_b, mx, my) bind(c, name='kcreep_set_ellipse')
    type(c_ptr), value :: handle
    real(c_double), value :: semi_a, semi_b
    integer(c_int), value :: mx, my
    type(handle_t), pointer :: h
    c_set_ellipse = begin(handle, h)
    if (c_set_ellipse /= status_ok) return
    if (.not. (semi_a > 0 .and. semi_b > 0 .and. semi_a < huge(1.0_wp) .and. semi_b < huge(1.0_wp))) then
      call fail(h%last, exit_bad_input, 'kcreep_set_ellipse: semi_a, semi_b must be finite and > 0')
    else if (.not. ((mx >= 1 .and. my >= 1) .or. (mx == 0 .and. my == 0))) then
      call fail(h%last, exit_bad_input, 'kcreep_set_ellipse: mx, my must be >= 1 (the grid as given) '// &
                'or both 0 (kcreep chooses the grids)')
    else if (mx == 0) then
      call ellipse_patch(real(semi_a, wp), real(semi_b, wp), nominal_ellipse_cells, nominal_ellipse_cells, &
                         h%problem%patch, h%last)
      h%ellipse_grid_given = .false.
      h%problem%normal%active = .false.
    else
      call ellipse_patch(real(semi_a, wp), real(semi_b, wp), int(mx), int(my), h%problem%patch, h%last)
      h%ellipse_grid_given = .true.
      h%problem%normal%active = .false.
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
      h%ellipse_grid_given = .false.
      h%problem%normal%active = .false.   ! a gap set before is replaced by this patch
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
    ! the fast model belongs to the last solved patch (the rolling state checks its own patch)
    h%fast = fast_forces_t()
    ! kcreep chooses the grids unless turned off, or an ellipse's grid was given
    h%problem%refine_grid = h%refine_grid .and. (h%problem%normal%active .or. .not. h%ellipse_grid_given)
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

end module kcreep_capi
