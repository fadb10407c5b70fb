!> The C API's handle (include/kcreep.h): one problem (grid geometry,
!> material, scheme, solver settings), its last result, its last error and
!> what repeated solves on the same grid can reuse; and the helpers every
!> C function uses: begin (the handle of a call, its last error cleared),
!> solved (the handle of a solved problem, or why there is none), finish
!> (the call's status), from_c / to_c (strings), output_array (a C array).
!> Every function returns a status: 0 (KCREEP_OK), 2 (bad argument or
!> input), 3 (numerical failure) or 6 (no result yet, or a null handle).
module kcreep_capi_handle
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_ptr, c_null_char, c_f_pointer, c_associated
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep, only: problem_t, result_t, solve_cache_t, wheel_rail_setup_t, wheel_rail_row_t, wheelset_row_t, &
                    rolling_state_t, fast_forces_t
  implicit none
  private
  public :: handle_t, status_ok, status_no_result, begin, solved, finish, from_c, to_c, output_array

  integer(c_int), parameter :: status_ok = 0, status_no_result = 6

  type :: handle_t
    type(problem_t) :: problem
    type(result_t) :: result
    type(solve_cache_t) :: cache
    logical :: solved = .false.
    !> kcreep_set_error_control's refine_grid (default on, as the program's)
    logical :: refine_grid = .true.
    !> the ellipse was set with its grid (mx, my > 0): solved as given, as the
    !> namelist's ellipse with mx, my
    logical :: ellipse_grid_given = .false.
    type(status_t) :: last
    !> kcreep_rolling / kcreep_fast_forces on the solved patch: the exact solver's set-up and
    !> last solutions (warm starts across calls) and the fast force model; both emptied by a solve
    type(rolling_state_t) :: rolling
    type(fast_forces_t) :: fast
    ! kcreep_wheel_rail: profiles and track (kcreep_set_profiles, kcreep_set_track), the last table
    type(wheel_rail_setup_t) :: wheel_rail
    type(wheel_rail_row_t), allocatable :: wheel_rail_rows(:)
    logical :: wheel_rail_done = .false.
    ! kcreep_wheelset: the last wheelset table (the left profiles in wheel_rail, kcreep_set_left_profiles)
    type(wheelset_row_t), allocatable :: wheelset_rows(:)
    logical :: wheelset_done = .false.
  end type handle_t

contains

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

end module kcreep_capi_handle
