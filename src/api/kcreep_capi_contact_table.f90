!> The C API's contact table for a time loop (include/kcreep.h, docs/mbs.md):
!> kcreep_wheel_rail_at (every patch at any shift of the handle's last
!> kcreep_wheel_rail table, interpolated between the neighbouring rows) and
!> kcreep_wheel_rail_forces (each patch's forces from its rows' patches and
!> pressures, interpolated likewise). One pairing of patches between rows
!> (table_terms), which kcreep.ContactTable uses too.
module kcreep_capi_contact_table
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_f_pointer, c_associated
  use kcreep_kinds, only: wp
  use kcreep_status, only: fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use kcreep, only: wheel_rail_row_t, creep_request_t, creep_point_t, creep_map_t, creep_curve, &
                    rolling_request_t, rolling_point_t, rolling_curve
  use kcreep_capi_handle, only: handle_t, status_ok, status_no_result, begin, finish
  use kcreep_capi_wheel_rail, only: row_values, wheel_rail_column_count, column_shift, column_patch, column_fn, &
                                    column_verdict
  implicit none
  private
  public :: table_terms

contains

  !> Every patch at shift (mm) of the handle's last kcreep_wheel_rail table.
  !> values[p * KCREEP_WHEEL_RAIL_COLUMNS + k]: patch p's columns, the linear
  !> interpolation of its two rows (the nearer row's patch and verdict; a
  !> patch in one row only keeps that row's values, fn times its weight);
  !> rows[2 p + 0..1] (0-based, -1: none) and weights[2 p + 0..1] its rows and
  !> their weights (rows, weights may be NULL). capacity: the patches the
  !> arrays hold; *n_patches: the patches at shift.
  integer(c_int) function c_wheel_rail_at(handle, shift, capacity, values, rows, weights, n_patches) &
    bind(c, name='kcreep_wheel_rail_at')
    type(c_ptr), value :: handle, values, rows, weights, n_patches
    real(c_double), value :: shift
    integer(c_int), value :: capacity
    type(handle_t), pointer :: h
    real(c_double), pointer :: v(:), w(:)
    integer(c_int), pointer :: r(:), count
    integer, allocatable :: term_rows(:, :)
    real(wp), allocatable :: term_weights(:, :)
    integer :: p, k, n, nearest
    real(wp) :: weight
    c_wheel_rail_at = begin(handle, h)
    if (c_wheel_rail_at /= status_ok) return
    if (.not. (c_associated(values) .and. c_associated(n_patches))) then
      call fail(h%last, exit_bad_input, 'kcreep_wheel_rail_at: values or n_patches is NULL')
    else
      call terms_of(h, shift, capacity, 'kcreep_wheel_rail_at', term_rows, term_weights)
    end if
    if (h%last%failed()) then
      c_wheel_rail_at = finish(h)
      return
    end if
    n = size(term_rows, 2)
    call c_f_pointer(n_patches, count)
    count = n
    call c_f_pointer(values, v, [n * wheel_rail_column_count])
    do p = 1, n
      associate (out => v((p - 1) * wheel_rail_column_count + 1:p * wheel_rail_column_count))
        weight = sum(term_weights(:, p))
        out = 0
        nearest = term_rows(maxloc(term_weights(:, p), 1), p)
        do k = 1, 2
          if (term_rows(k, p) > 0) out = out + term_weights(k, p) / weight * row_values(h%wheel_rail_rows(term_rows(k, p)))
        end do
        out(column_shift) = shift
        out(column_patch) = h%wheel_rail_rows(nearest)%patch
        out(column_fn) = out(column_fn) * weight
        out(column_verdict) = h%wheel_rail_rows(nearest)%result%verdict_flags
      end associate
    end do
    if (c_associated(rows)) then
      call c_f_pointer(rows, r, [2 * n])
      r = reshape(term_rows, [2 * n]) - 1
    end if
    if (c_associated(weights)) then
      call c_f_pointer(weights, w, [2 * n])
      w = reshape(term_weights, [2 * n])
    end if
  end function c_wheel_rail_at

  !> The forces of every patch at shift, in kcreep_wheel_rail_at's order, for
  !> n creepages of each: creep[(p n + k) 3 + 0..2] = (xi, eta, phi) of point
  !> k of patch p (n_patches of them, as kcreep_wheel_rail_at gives);
  !> force[(p n + k) 3 + 0..2] = (Fx, Fy, Mz): each row's forces on its own
  !> patch and pressure, weighted as kcreep_wheel_rail_at. exact = 0: FASTSIM
  !> (rule aligned; the place of a fast model), 1: exact rolling.
  integer(c_int) function c_wheel_rail_forces(handle, shift, mu, n, n_patches, creep, exact, force) &
    bind(c, name='kcreep_wheel_rail_forces')
    type(c_ptr), value :: handle, creep, force
    real(c_double), value :: shift, mu
    integer(c_int), value :: n, n_patches, exact
    type(handle_t), pointer :: h
    real(c_double), pointer :: creepages(:, :, :), forces(:, :, :)
    integer, allocatable :: term_rows(:, :)
    real(wp), allocatable :: term_weights(:, :), f(:, :)
    integer :: p, k
    c_wheel_rail_forces = begin(handle, h)
    if (c_wheel_rail_forces /= status_ok) return
    if (.not. (mu > 0 .and. mu < huge(1.0_wp)) .or. n < 1 .or. .not. (exact == 0 .or. exact == 1)) then
      call fail(h%last, exit_bad_input, 'kcreep_wheel_rail_forces: mu = '//rtoa(real(mu, wp))//', n = '// &
                itoa(int(n))//', exact = '//itoa(int(exact))//' (allowed: mu finite > 0, n >= 1, exact 0 or 1)')
    else if (.not. (c_associated(creep) .and. c_associated(force))) then
      call fail(h%last, exit_bad_input, 'kcreep_wheel_rail_forces: creep or force is NULL')
    else
      call terms_of(h, shift, n_patches, 'kcreep_wheel_rail_forces', term_rows, term_weights)
      if (.not. h%last%failed() .and. size(term_rows, 2) /= n_patches) &
        call fail(h%last, exit_bad_input, 'kcreep_wheel_rail_forces: n_patches = '//itoa(int(n_patches))// &
                  ' (the shift has '//itoa(size(term_rows, 2))//' patches, as kcreep_wheel_rail_at gives)')
    end if
    if (h%last%failed()) then
      c_wheel_rail_forces = finish(h)
      return
    end if
    call c_f_pointer(creep, creepages, [3, int(n), int(n_patches)])
    call c_f_pointer(force, forces, [3, int(n), int(n_patches)])
    do p = 1, n_patches
      forces(:, :, p) = 0
      do k = 1, 2
        if (term_rows(k, p) < 1) cycle
        call row_forces(h, h%wheel_rail_rows(term_rows(k, p)), mu, creepages(:, :, p), exact == 1, f)
        if (h%last%failed()) then
          c_wheel_rail_forces = finish(h)
          return
        end if
        forces(:, :, p) = forces(:, :, p) + term_weights(k, p) * f
      end do
    end do
    c_wheel_rail_forces = finish(h)
  end function c_wheel_rail_forces

  !> One row's forces (3, n) on its patch and the normal problem's pressure.
  subroutine row_forces(h, row, mu, creepages, exact, f)
    type(handle_t), intent(inout) :: h
    type(wheel_rail_row_t), intent(in) :: row
    real(wp), intent(in) :: mu, creepages(:, :)
    logical, intent(in) :: exact
    real(wp), allocatable, intent(out) :: f(:, :)
    real(wp), allocatable :: pn(:, :)
    type(creep_request_t) :: fastsim
    type(creep_point_t), allocatable :: fastsim_points(:)
    type(rolling_request_t) :: rolling
    type(rolling_point_t), allocatable :: rolling_points(:)
    type(creep_map_t), allocatable :: maps(:)
    integer :: k
    associate (res => row%result, p => row%result%patch)
      allocate (pn(p%mx, p%my))
      pn = 0
      do k = 1, p%n
        pn(p%ix(k), p%iy(k)) = res%pressure(k)
      end do
      allocate (f(3, size(creepages, 2)))
      if (exact) then
        rolling%mu = mu
        rolling%creepages = creepages
        rolling%threads = h%problem%solve%threads
        call rolling_curve(p, h%problem%scheme, res%nu, res%g, res%spin_centre, pn, rolling, rolling_points, maps, &
                           h%last)
        if (h%last%failed()) return
        f = reshape([(rolling_points(k)%force%fx, rolling_points(k)%force%fy, rolling_points(k)%force%mz, &
                      k=1, size(creepages, 2))], shape(f))
      else
        fastsim%mu = mu
        fastsim%creepages = creepages
        call creep_curve(res, pn, fastsim, fastsim_points, maps)
        f = reshape([(fastsim_points(k)%force%fx, fastsim_points(k)%force%fy, fastsim_points(k)%force%mz, &
                      k=1, size(creepages, 2))], shape(f))
      end if
    end associate
  end subroutine row_forces

  !> The terms of every patch at shift of the handle's last table, or the
  !> error in h%last: rows (2, patches) (row numbers, 0 none) and weights.
  subroutine terms_of(h, shift, capacity, who, rows, weights)
    type(handle_t), intent(inout) :: h
    real(wp), intent(in) :: shift
    integer, intent(in) :: capacity
    character(len=*), intent(in) :: who
    integer, allocatable, intent(out) :: rows(:, :)
    real(wp), allocatable, intent(out) :: weights(:, :)
    allocate (rows(2, 0), weights(2, 0))
    if (.not. h%wheel_rail_done) then
      call fail(h%last, int(status_no_result), who//': no table: call kcreep_wheel_rail (successfully) first')
      return
    end if
    associate (s => h%wheel_rail_rows%shift)
      if (.not. (shift >= minval(s) .and. shift <= maxval(s))) then
        call fail(h%last, exit_bad_input, who//': shift = '//rtoa(shift)//' (allowed: '//rtoa(minval(s))//' to '// &
                  rtoa(maxval(s))//' mm, the table''s range)')
        return
      end if
    end associate
    call table_terms(h%wheel_rail_rows, shift, rows, weights)
    if (size(rows, 2) > capacity) &
      call fail(h%last, exit_bad_input, who//': capacity = '//itoa(capacity)//' (the shift has '// &
                itoa(size(rows, 2))//' patches)')
  end subroutine terms_of

  !> The patches at shift (within the rows' range): the rows of the nearest
  !> table shifts below (a) and above (b), weights 1 - t and t (t the
  !> fraction of the way); a's and b's patches of the same kind (tread, flange)
  !> paired nearest y_rail first when within half their widths plus the step
  !> (a tread patch never continues as a flange patch), a patch without a partner
  !> alone with its own weight (it fades out or in). Zero weights dropped;
  !> patches in order of their weighted y_rail.
  pure subroutine table_terms(all_rows, shift, rows, weights)
    type(wheel_rail_row_t), intent(in) :: all_rows(:)
    real(wp), intent(in) :: shift
    integer, allocatable, intent(out) :: rows(:, :)
    real(wp), allocatable, intent(out) :: weights(:, :)
    real(wp) :: sa, sb, t, best, gate, dy
    integer, allocatable :: a(:), b(:), pair(:)
    logical, allocatable :: used_b(:)
    integer :: i, j, k, ia, ib, n
    real(wp), allocatable :: key(:)
    integer, allocatable :: order(:)
    integer :: m
    sa = maxval(all_rows%shift, mask=all_rows%shift <= shift)
    if (any(all_rows%shift > sa)) then
      sb = minval(all_rows%shift, mask=all_rows%shift > sa)
    else                                           ! shift is the last row's: the interval below it
      sb = sa
      sa = maxval(all_rows%shift, mask=all_rows%shift < sb)
    end if
    t = (shift - sa) / (sb - sa)
    a = pack([(i, i=1, size(all_rows))], all_rows%shift == sa)
    b = pack([(i, i=1, size(all_rows))], all_rows%shift == sb)
    allocate (pair(size(a)), used_b(size(b)))
    pair = 0
    used_b = .false.
    do                                             ! greedy: the closest remaining pair first
      best = huge(1.0_wp)
      ia = 0; ib = 0
      do i = 1, size(a)
        if (pair(i) /= 0) cycle
        do j = 1, size(b)
          if (used_b(j)) cycle
          if (all_rows(a(i))%kind /= all_rows(b(j))%kind) cycle
          dy = abs(all_rows(a(i))%y_rail - all_rows(b(j))%y_rail)
          gate = 0.5_wp * (all_rows(a(i))%width + all_rows(b(j))%width) + (sb - sa)
          if (dy <= gate .and. dy < best) then
            best = dy; ia = i; ib = j
          end if
        end do
      end do
      if (ia == 0) exit
      pair(ia) = ib
      used_b(ib) = .true.
    end do
    n = size(a) + count(.not. used_b)
    allocate (rows(2, n), weights(2, n))
    rows = 0
    weights = 0
    do i = 1, size(a)
      rows(1, i) = a(i)
      weights(1, i) = 1 - t
      if (pair(i) /= 0) then
        rows(2, i) = b(pair(i))
        weights(2, i) = t
      end if
    end do
    k = size(a)
    do j = 1, size(b)
      if (used_b(j)) cycle
      k = k + 1
      rows(2, k) = b(j)
      weights(2, k) = t
    end do
    where (.not. weights > 0) rows = 0          ! a zero weight: no term
    where (rows == 0) weights = 0
    m = count(sum(weights, 1) > 0)
    order = pack([(i, i=1, n)], sum(weights, 1) > 0)
    allocate (key(m))
    do i = 1, m
      key(i) = 0
      do k = 1, 2
        if (rows(k, order(i)) > 0) key(i) = key(i) + weights(k, order(i)) * all_rows(rows(k, order(i)))%y_rail
      end do
      key(i) = key(i) / sum(weights(:, order(i)))
    end do
    do i = 2, m                                    ! insertion sort by y_rail (a few patches)
      j = i
      do while (j > 1)
        if (key(j - 1) <= key(j)) exit
        key([j - 1, j]) = key([j, j - 1])
        order([j - 1, j]) = order([j, j - 1])
        j = j - 1
      end do
    end do
    rows = rows(:, order)
    weights = weights(:, order)
  end subroutine table_terms

end module kcreep_capi_contact_table
