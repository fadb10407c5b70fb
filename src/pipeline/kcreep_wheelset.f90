!> The wheelset over the lateral shift (&wheel_rail wheelset = .true.): both
!> wheels of a rigid wheelset, each carrying vertical_force, their rolling
!> radii, contact angles, the wheelset's roll and vertical position, and the
!> equivalent conicity (docs/wheel_rail.md, Wheelset).
!>
!> The right wheel is the table's right side; the left wheel is the right
!> side's computation mirrored (kcreep_wheel_rail_run's side 'left'): at the
!> wheelset's shift y it sits at -y in its own right-side configuration, on
!> the left profiles if given (left_wheel_file, left_rail_file), else on the
!> right ones. Each wheel's state is the table's approach for the vertical
!> force (rows_at_shift with wheel, no patch solves): the same force split,
!> angle and rolling radius as the table's rows.
!>
!> Per wheel, with two or more patches, the patches' values weighted by their
!> normal forces Fn (CONTACT defines a rolling radius per patch only):
!> r = sum(Fn r_k) / sum(Fn), delta likewise, and the lateral position of the
!> contact y_c likewise. Roll and vertical position by the small-angle rigid
!> wheelset: each wheel's vertical position z_w (mm, z down: where its nominal
!> rolling circle's lowest point lies, the approach included) is z + roll y_c,
!> so roll = (z_right - z_left) / (y_c,right - y_c,left) (rad, positive right
!> side down: about the track's x, which points along the track with y to the
!> right and z down), z = z_right - roll y_c,right at the track centre. The
!> roll's own tilt of the contact is not fed back (of order 1e-3 rad).
!>
!> Equivalent conicity at amplitude A (the harmonic linearisation):
!> lambda_eq = b1 / (2 A), b1 the first harmonic of Delta r(A sin t),
!> b1 = (1/pi) int_0^2pi Delta r(A sin t) sin t dt = (2 / (pi A)) int_-A^A
!> Delta r(y) y / sqrt(A^2 - y^2) dy, evaluated exactly for Delta r linear
!> between the computed shifts (the shifts of the table and their negatives);
!> at A = 0 its limit, the slope of Delta r at 0 over 2.
module kcreep_wheelset
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: rtoa
  use kcreep_problem, only: problem_t
  use kcreep_wheel_rail_geometry, only: track_t
  use kcreep_wheel_rail_run, only: wheel_rail_setup_t, wheel_rail_row_t, wheel_state_t, prepare_track, rows_at_shift
  use kcreep_threads, only: team_size, enter_team, leave_team, solve_started, solve_ended
  implicit none
  private
  public :: wheelset_row_t, wheelset_columns, run_wheelset, harmonic_conicity

  !> The wheelset table's columns, in order.
  character(len=*), parameter :: wheelset_columns = 'shift r_right r_left delta_r delta_right delta_left roll z '// &
                                                    'lambda_eq'
  real(real64), parameter :: pi = acos(-1.0_real64)

  !> One row per shift of the table.
  type :: wheelset_row_t
    real(real64) :: shift = 0
    real(real64) :: r_right = 0, r_left = 0, delta_r = 0   !< rolling radii (mm), delta_r = r_right - r_left
    real(real64) :: delta_right = 0, delta_left = 0        !< contact angles (rad), each positive towards its own flange
    real(real64) :: roll = 0, z = 0                        !< wheelset roll (rad), vertical position (mm, z down)
    real(real64) :: lambda_eq = 0                          !< equivalent conicity at amplitude |shift|
  end type wheelset_row_t

  !> One wheel's load-weighted values at one shift.
  type :: wheel_point_t
    real(real64) :: r = 0, delta = 0, y = 0, height = 0
  end type wheel_point_t

contains

  !> The wheelset table of setup (checked, profiles read) for the shifts of setup.
  !> states: the wheel states of setup's own table (run_wheel_rail of setup
  !> and base), which are not computed again.
  subroutine run_wheelset(setup, base, table, status, states)
    type(wheel_rail_setup_t), intent(in) :: setup
    type(problem_t), intent(in) :: base
    type(wheelset_row_t), allocatable, intent(out) :: table(:)
    type(status_t), intent(inout) :: status
    type(wheel_state_t), intent(in), optional :: states(:)   !< per shift of setup
    type(wheel_rail_setup_t) :: both, left
    type(track_t) :: right_track, left_track
    type(wheel_point_t), allocatable :: right_at(:), left_at(:), points(:)
    real(real64), allocatable :: ys(:), dr(:), ones(:)
    logical :: own_left
    integer :: i, k, n

    allocate (table(0))
    ! the shifts and their negatives, ascending: Delta r over [-A, A] for every A = |shift|
    ys = sorted_unique([setup%shifts, -setup%shifts])
    n = size(ys)
    allocate (ones(n), source=1.0_real64)
    both = setup
    both%shifts = ys
    left = both
    if (allocated(setup%left_wheel_y)) then
      left%wheel_y = setup%left_wheel_y
      left%wheel_z = setup%left_wheel_z
      left%wheel_name = setup%left_wheel_name
    end if
    if (allocated(setup%left_rail_y)) then
      left%rail_y = setup%left_rail_y
      left%rail_z = setup%left_rail_z
      left%rail_name = setup%left_rail_name
    end if
    own_left = allocated(setup%left_wheel_y) .or. allocated(setup%left_rail_y)
    call prepare_track(both, right_track, status)
    if (status%failed()) return
    ! Each wheel state is one rows_at_shift of a track at the shift sgn y and
    ! yaw sgn yaw (sgn -1: the left wheel, mirrored). On the right profiles
    ! the left wheel's state at y is the same computation as the right
    ! wheel's at -y when the yaw is zero, and the table's own states are
    ! those of its side: each computation is made once.
    if (own_left) then
      call wheel_points(both, right_track, ys, ones, right_at)
    else
      call wheel_points(both, right_track, [ys, ys], [ones, -ones], points)
      if (status%failed()) return
      right_at = points(1:n)
      left_at = points(n + 1:2 * n)
    end if
    if (status%failed()) return
    if (own_left) then
      call prepare_track(left, left_track, status)
      if (status%failed()) return
      call wheel_points(left, left_track, ys, -ones, left_at, own=.true.)
      if (status%failed()) return
    end if
    dr = right_at%r - left_at%r
    deallocate (table)
    allocate (table(size(setup%shifts)))
    do i = 1, size(setup%shifts)
      k = minloc(abs(ys - setup%shifts(i)), 1)
      associate (t => table(i), r => right_at(k), l => left_at(k))
        t%shift = setup%shifts(i)
        t%r_right = r%r
        t%r_left = l%r
        t%delta_r = dr(k)
        t%delta_right = r%delta
        t%delta_left = l%delta
        ! the left contact at track y = -(its own configuration's y)
        t%roll = (r%height - l%height) / (r%y + l%y)
        t%z = r%height - t%roll * r%y
        t%lambda_eq = harmonic_conicity(ys, dr, abs(setup%shifts(i)))
      end associate
    end do

  contains

    !> The load-weighted wheel values of one track at the wheelset's shifts
    !> y(j) on the side sgns(j) (-1: the left wheel, its own right-side
    !> configuration at shift -y(j), yaw -yaw). Equal computations (the same
    !> shift sgn y and, unless the yaw is zero, the same side) are made once,
    !> and the table's states taken where they are the same computation (not
    !> on the left wheel's own profiles: own).
    subroutine wheel_points(side_setup, track, y, sgns, points, own)
      type(wheel_rail_setup_t), intent(in) :: side_setup
      type(track_t), intent(in) :: track
      real(real64), intent(in) :: y(:), sgns(:)
      type(wheel_point_t), allocatable, intent(out) :: points(:)
      logical, intent(in), optional :: own
      type(wheel_rail_setup_t) :: run_setup
      type(wheel_state_t), allocatable :: state(:), computed(:)
      type(wheel_rail_row_t), allocatable :: none(:)
      type(status_t), allocatable :: at(:)
      type(problem_t) :: row_base
      real(real64), allocatable :: run_sgn(:), table_sgn(:)
      integer, allocatable :: from_table(:), run_of(:)
      integer :: j, m, runs, team, stage_team, previous_team
      m = size(y)
      allocate (points(m), state(m), from_table(m), run_of(m), run_sgn(m))
      run_setup = side_setup
      run_setup%shifts = y
      if (present(states) .and. .not. present(own)) then
        allocate (table_sgn(size(states)), source=merge(-1.0_real64, 1.0_real64, setup%side == 'left'))
      else
        allocate (table_sgn(0))
      end if
      runs = 0
      do j = 1, m
        from_table(j) = same_as(setup%shifts(1:size(table_sgn)), table_sgn, y(j), sgns(j), setup%yaw == 0)
        run_of(j) = 0
        if (from_table(j) > 0) cycle
        run_of(j) = same_as(run_setup%shifts(1:runs), run_sgn(1:runs), y(j), sgns(j), setup%yaw == 0)
        if (run_of(j) > 0) cycle
        runs = runs + 1
        run_of(j) = runs
        run_sgn(runs) = sgns(j)
        run_setup%shifts(runs) = y(j)   ! rows_at_shift: shift sgn * shifts(i)
      end do
      allocate (computed(runs), at(runs))
      team = min(team_size(base%solve%threads, int(runs, int64), 1), max(runs, 1))
      row_base = base
      if (team > 1) then
        row_base%solve%threads = 1
        row_base%normal%options%threads = 1
      end if
      stage_team = 1
      call solve_started()
      call enter_team(stage_team, previous_team)
      !$omp parallel do num_threads(team) schedule(dynamic, 1) default(shared) private(j, none)
      do j = 1, runs
        call rows_at_shift(run_setup, row_base, track, run_sgn(j), j, none, at(j), computed(j))
      end do
      !$omp end parallel do
      call leave_team(previous_team)
      call solve_ended()
      do j = 1, m
        if (run_of(j) > 0) then
          if (at(run_of(j))%failed()) then
            status = at(run_of(j))
            if (sgns(j) < 0) status%message = 'left wheel: '//status%message
            return
          end if
          state(j) = computed(run_of(j))
        else
          state(j) = states(from_table(j))
        end if
        if (size(state(j)%fn) == 0) then
          call fail(status, exit_bad_input, '&wheel_rail wheelset: shift = '//rtoa(y(j))//' mm: no loaded contact')
          if (sgns(j) < 0) status%message = 'left wheel: '//status%message
          return
        end if
        points(j)%r = sum(state(j)%fn * state(j)%r_wheel) / sum(state(j)%fn)
        points(j)%delta = sum(state(j)%fn * state(j)%delta) / sum(state(j)%fn)
        points(j)%y = sum(state(j)%fn * state(j)%y) / sum(state(j)%fn)
        points(j)%height = state(j)%height
      end do


    end subroutine wheel_points

  end subroutine run_wheelset

  !> The first k whose computation (rows_at_shift at shift sgns(k) shifts(k),
  !> yaw sgns(k) yaw) is that of shift y on side sgn: the same shift (within
  !> 1e-9 mm, as sorted_unique takes the shifts: the table's 0.3 and the
  !> negated -0.30000000000000004 are one) and the same side, either side at
  !> zero yaw; else 0.
  pure integer function same_as(shifts, sgns, y, sgn, zero_yaw) result(k)
    real(real64), intent(in) :: shifts(:), sgns(:), y, sgn
    logical, intent(in) :: zero_yaw
    do k = 1, size(shifts)
      if (abs(sgns(k) * shifts(k) - sgn * y) <= 1e-9_real64 .and. (sgns(k) == sgn .or. zero_yaw)) return
    end do
    k = 0
  end function same_as

  !> Ascending values without repeats (within 1e-9 mm).
  pure function sorted_unique(values) result(out)
    real(real64), intent(in) :: values(:)
    real(real64), allocatable :: out(:)
    real(real64) :: v(size(values)), t
    integer :: i, j, m
    v = values
    do i = 2, size(v)
      t = v(i)
      j = i - 1
      do while (j >= 1)
        if (v(j) <= t) exit
        v(j + 1) = v(j)
        j = j - 1
      end do
      v(j + 1) = t
    end do
    allocate (out(size(v)))
    m = 0
    do i = 1, size(v)
      if (m > 0) then
        if (v(i) - out(m) <= 1e-9_real64) cycle
      end if
      m = m + 1
      out(m) = v(i)
    end do
    out = out(1:m)
  end function sorted_unique

  !> Equivalent conicity at amplitude a of Delta r given at ascending ys,
  !> linear in between: b1 / (2 a), b1 = (2 / (pi a)) int_-a^a dr(y) y /
  !> sqrt(a^2 - y^2) dy, exactly per piece (dr = p + q y: the antiderivatives
  !> -p sqrt(a^2 - y^2) and q (a^2 asin(y/a) - y sqrt(a^2 - y^2)) / 2); at a = 0
  !> the mean of the slopes either side of 0, over 2. NaN where ys do not
  !> cover [-a, a].
  pure real(real64) function harmonic_conicity(ys, dr, a) result(lambda)
    real(real64), intent(in) :: ys(:), dr(:), a
    real(real64) :: lo, hi, p, q, integral
    integer :: k, n
    n = size(ys)
    lambda = ieee_value(1.0_real64, ieee_quiet_nan)
    if (n < 2) return
    if (a <= 0) then
      k = count(ys <= 0)          ! the piece left of 0 ends at ys(k)
      if (k < 1 .or. k >= n) return
      if (ys(k) == 0 .and. k > 1) then
        lambda = ((dr(k) - dr(k - 1)) / (ys(k) - ys(k - 1)) + (dr(k + 1) - dr(k)) / (ys(k + 1) - ys(k))) / 4
      else
        lambda = (dr(k + 1) - dr(k)) / (ys(k + 1) - ys(k)) / 2
      end if
      return
    end if
    if (ys(1) > -a * (1 - 1e-12_real64) .or. ys(n) < a * (1 - 1e-12_real64)) return
    integral = 0
    do k = 1, n - 1
      lo = max(ys(k), -a)
      hi = min(ys(k + 1), a)
      if (hi <= lo) cycle
      q = (dr(k + 1) - dr(k)) / (ys(k + 1) - ys(k))
      p = dr(k) - q * ys(k)
      integral = integral + p * (root(lo) - root(hi)) + q * (arc(hi) - arc(lo)) / 2
    end do
    lambda = 2 * integral / (pi * a) / (2 * a)

  contains

    pure real(real64) function root(y)
      real(real64), intent(in) :: y
      root = sqrt(max(a * a - y * y, 0.0_real64))
    end function root

    pure real(real64) function arc(y)
      real(real64), intent(in) :: y
      arc = a * a * asin(max(-1.0_real64, min(1.0_real64, y / a))) - y * root(y)
    end function arc

  end function harmonic_conicity

end module kcreep_wheelset
