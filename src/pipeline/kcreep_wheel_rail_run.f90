!> From wheel and rail profiles to a contact table: for each lateral shift of
!> the wheelset, every contact patch with its contact plane, the normal problem
!> in that plane and the error-controlled creep coefficients of its patch.
!>
!> Per shift (kcreep_wheel_rail_geometry for the geometry):
!>  1. the vertical clearance d(y) of wheel and rail, the wheel lowered to touch;
!>  2. the vertical approach dz: given (approach), or found for vertical_force
!>     from normal solves on coarse grids of every patch (the sum of Fn cos(delta)
!>     over the patches equal to the force; a patch's normal approach is
!>     dz cos(delta), its gap holding its own clearance). The patches are the
!>     intervals of d < dz, so a second contact enters when dz reaches it;
!>  3. per patch: the normal problem with its force (the force split of step 2,
!>     scaled to the vertical force exactly) or its approach, under kcreep's error
!>     control of gap patches, the gap evaluated exactly in the contact plane on
!>     every level (kcreep_gap_levels); then C11 C22 C23 with their estimates,
!>     C33, FASTSIM's L1 L2 L3 and the geometric spin sin(delta) / r.
!> Patches are independent (no elastic interaction between separate patches,
!> which lie in different planes), as CONTACT treats them.
!> Shifts are independent too: a team of threads runs one shift per thread
!> (run_wheel_rail), and the table is the same on any team.
module kcreep_wheel_rail_run
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_status, only: status_t, fail, exit_bad_input, exit_numerical
  use kcreep_strings, only: itoa, rtoa
  use kcreep_profile, only: profile_t, make_profile, no_surface, check_flange_side, envelope_at
  use kcreep_wheel_rail_geometry, only: track_t, contact_t, plane_gap_t, place_track, clearance, find_contacts, &
                                        plane_of, plane_gap_value, plane_gap_grid, search_step, refine_minimum, &
                                        check_profile_ends
  use kcreep_gap, only: gap_t, outside_gap
  use kcreep_problem, only: problem_t, result_t, add_warning
  use kcreep_normal_solve, only: normal_result_t, solve_normal
  use kcreep_normal_influence, only: compliance_from_g_nu
  use kcreep_error_run, only: run_controlled
  use kcreep_gap_levels, only: gap_levels_need
  use kcreep_threads, only: team_size, enter_team, leave_team, solve_started, solve_ended, cpus_allowed, &
                            cells_per_thread_iterative
  implicit none
  private
  public :: base_cells
  public :: wheel_rail_setup_t, wheel_rail_row_t, prepare_track, run_wheel_rail, wheel_rail_columns, &
            check_wheel_rail_setup, max_wheel_rail_shifts, most_shifts_at_once, wheel_rail_needs
  public :: wheel_state_t, rows_at_shift

  real(real64), parameter :: pi = acos(-1.0_real64)
  !> The table's columns, in order (verdict and kind words).
  character(len=*), parameter :: wheel_rail_columns = 'shift yaw patch fn delta y_rail y_wheel r_wheel area '// &
                                 'length width c11 c22 c23 c33 err11 err22 err23 verdict l1 l2 l3 spin kind turn'
  !> A patch is 'flange' where its contact angle |delta| is at least this
  !> (rad, 45 degrees), else 'tread': the row's kind.
  real(real64), parameter :: flange_angle = pi / 4
  !> Warn where the rail's surface angle across a patch departs from its
  !> contact angle by more than this (rad): acos(1 / 1.03), where the gap
  !> along the plane's normal is 3 % off the gap along the surface's, the
  !> threshold of CONTACT's warning "large angle variation within contact
  !> patch" (its m_wr_undefdist).
  real(real64), parameter :: turn_warning = 0.24153_real64
  !> At most this many shifts in one table.
  integer, parameter :: max_wheel_rail_shifts = 10000
  !> Cells across the larger side of a patch's potential contact area on the
  !> coarse grids of the force iteration and the first solve of error control.
  integer, parameter :: base_cells = 64
  !> The vertical approach (mm) every shift's force iteration starts from. The
  !> same start for every shift, not the previous shift's approach: the coarse
  !> grids are made on the way, and a row must not depend on the shifts before
  !> it (from the previous approach, S1002's +5 mm row on its given grid had a
  !> C23 1.5 % off the same shift run alone).
  real(real64), parameter :: first_approach = 0.05_real64
  !> The force iteration makes a patch's plane and grid anew when its
  !> reference at the approach tried has moved by more than this (mm of the
  !> point, rad of the angle) from the plane's.
  real(real64), parameter :: ref_moved = 1e-4_real64

  !> What &wheel_rail describes (the profiles already read).
  type :: wheel_rail_setup_t
    real(real64), allocatable :: wheel_y(:), wheel_z(:), rail_y(:), rail_z(:)   !< points as read (mm, z down)
    character(len=:), allocatable :: wheel_name, rail_name                      !< for messages
    logical :: wheel_mirror = .false., rail_mirror = .false.
    real(real64) :: smoothing = -1                                              !< mm^4; < 0: automatic (kcreep_profile)
    character(len=:), allocatable :: side                                       !< 'right' or 'left'
    real(real64) :: gauge_width = 1435, gauge_height = 14, rail_cant = 0
    real(real64) :: flange_back_distance = 1360, flange_back_position = -70, nominal_radius = 460
    real(real64), allocatable :: shifts(:)
    real(real64) :: yaw = 0
    logical :: force_given = .true.
    real(real64) :: vertical_force = 0, approach = 0
    logical :: wheelset = .false.                                               !< also the wheelset table (kcreep_wheelset)
    real(real64), allocatable :: left_wheel_y(:), left_wheel_z(:), left_rail_y(:), left_rail_z(:)  !< the left side's own, if given
    character(len=:), allocatable :: left_wheel_name, left_rail_name
    !> with vertical_force: a patch whose share fn cos(delta) / vertical_force
    !> is below this is dropped and the others carry the load (0: none dropped)
    real(real64) :: min_patch_share = 0
  end type wheel_rail_setup_t

  !> One wheel at one shift without the patches' solves (rows_at_shift with
  !> wheel): the wheel's vertical position and each loaded patch's force
  !> split, angle, rolling radius and lateral position (the side's own
  !> right-side configuration, as the table's rows before the side's sign).
  type :: wheel_state_t
    real(real64) :: height = 0                   !< w0 + dz: the wheel's vertical position (mm, z down)
    real(real64), allocatable :: fn(:), delta(:), r_wheel(:), y(:)
  end type wheel_state_t

  !> One row of the table: one patch at one shift.
  type :: wheel_rail_row_t
    real(real64) :: shift = 0, yaw = 0
    integer :: patch = 0
    real(real64) :: fn = 0, delta = 0, y_rail = 0, y_wheel = 0, r_wheel = 0, area = 0, length = 0, width = 0
    real(real64) :: c(4) = 0                 !< C11 C22 C23 C33
    real(real64) :: err(3) = 0
    real(real64) :: l(3) = 0, spin = 0
    character(len=6) :: kind = 'tread'       !< 'tread' or 'flange' (flange_angle)
    real(real64) :: turn = 0                 !< largest |surface angle - delta| across the patch (rad)
    real(real64) :: approach = 0             !< the vertical approach of the shift
    real(real64) :: y_track = 0, z_track = 0 !< contact point in track coordinates (the side's own)
    character(len=:), allocatable :: verdict
    type(result_t) :: result                 !< everything kcreep_solve gives for the patch
  end type wheel_rail_row_t

  !> What one shift gives the table (run_wheel_rail's team fills one per shift).
  type :: shift_rows_t
    type(wheel_rail_row_t), allocatable :: rows(:)
    type(status_t) :: status
    logical :: skipped = .false.   !< not run: an earlier shift failed
    type(wheel_state_t) :: wheel   !< the wheel's state (run_wheel_rail's states)
  end type shift_rows_t

contains

  !> The setup's values in their ranges (the namelist group and the C API both
  !> check with this): where starts each message ("input 'a.nml': &wheel_rail "
  !> or "kcreep_wheel_rail: "), which names the variable, value and range.
  subroutine check_wheel_rail_setup(setup, where, status)
    type(wheel_rail_setup_t), intent(in) :: setup
    character(len=*), intent(in) :: where
    type(status_t), intent(inout) :: status
    if (status%failed()) return
    if (.not. allocated(setup%side)) then
      call fail(status, exit_bad_input, where//'side is not set (allowed: ''right'', ''left'')')
    else if (setup%side /= 'right' .and. setup%side /= 'left') then
      call fail(status, exit_bad_input, where//'side = '''//setup%side//''' (allowed: ''right'', ''left'')')
    end if
    call check_range('gauge_width', setup%gauge_width, 100.0_real64, 5000.0_real64)
    call check_range('gauge_height', setup%gauge_height, 0.0_real64, 100.0_real64)
    call check_range('rail_cant', setup%rail_cant, -0.5_real64, 0.5_real64)
    call check_range('flange_back_distance', setup%flange_back_distance, 100.0_real64, 5000.0_real64)
    call check_range('flange_back_position', setup%flange_back_position, -1000.0_real64, 1000.0_real64)
    call check_range('nominal_radius', setup%nominal_radius, 10.0_real64, 10000.0_real64)
    if (.not. status%failed() .and. .not. (setup%smoothing <= 1e12_real64)) call fail(status, exit_bad_input, &
        where//'smoothing = '//rtoa(setup%smoothing)//' (allowed: 0 to 1e12 mm^4, or negative: automatic)')
    call check_range('yaw', setup%yaw, -0.1_real64, 0.1_real64)
    if (setup%force_given) then
      call check_range('vertical_force', setup%vertical_force, 1e-6_real64, 1e9_real64)
    else
      call check_range('approach', setup%approach, 1e-9_real64, 10.0_real64)
      if (setup%min_patch_share /= 0 .and. .not. status%failed()) call fail(status, exit_bad_input, where// &
          'min_patch_share = '//rtoa(setup%min_patch_share)//' needs vertical_force (the shares of a given '// &
          'approach are not known before the patches are solved)')
    end if
    call check_range('min_patch_share', setup%min_patch_share, 0.0_real64, 0.5_real64)
    if (status%failed()) return
    if (setup%wheelset .and. .not. setup%force_given) then
      call fail(status, exit_bad_input, where//'wheelset = .true. needs vertical_force (each wheel carries it), '// &
                'not approach')
      return
    end if
    if (.not. allocated(setup%shifts)) then
      call fail(status, exit_bad_input, where//'shifts: none given')
    else if (size(setup%shifts) < 1 .or. size(setup%shifts) > max_wheel_rail_shifts) then
      call fail(status, exit_bad_input, where//'shifts: '//itoa(size(setup%shifts))//' values (allowed: 1 to '// &
                itoa(max_wheel_rail_shifts)//')')
    else if (.not. all(abs(setup%shifts) <= 200)) then
      call fail(status, exit_bad_input, where//'shifts: a value beyond 200 mm in magnitude (or not a number)')
    end if

  contains

    subroutine check_range(name, value, lo, hi)
      character(len=*), intent(in) :: name
      real(real64), intent(in) :: value, lo, hi
      if (status%failed()) return
      if (.not. (value >= lo .and. value <= hi)) call fail(status, exit_bad_input, where//name//' = '// &
          rtoa(value)//' (allowed: '//rtoa(lo)//' to '//rtoa(hi)//')')
    end subroutine check_range

  end subroutine check_wheel_rail_setup

  !> The profiles' splines and their placement in the track (right-side configuration).
  subroutine prepare_track(setup, track, status)
    type(wheel_rail_setup_t), intent(in) :: setup
    type(track_t), intent(out) :: track
    type(status_t), intent(inout) :: status
    type(profile_t) :: wheel, rail
    call check_flange_side(merge(-setup%wheel_y, setup%wheel_y, setup%wheel_mirror), setup%wheel_z, &
                           setup%wheel_name//' with wheel_mirror = '//trim(merge('.true. ', '.false.', &
                           setup%wheel_mirror)), status)
    if (status%failed()) return
    call make_profile(merge(-setup%wheel_y, setup%wheel_y, setup%wheel_mirror), setup%wheel_z, setup%smoothing, &
                      setup%wheel_name, wheel, status)
    if (status%failed()) return
    call make_profile(merge(-setup%rail_y, setup%rail_y, setup%rail_mirror), setup%rail_z, setup%smoothing, &
                      setup%rail_name, rail, status)
    if (status%failed()) return
    call place_track(rail, wheel, setup%rail_cant, setup%gauge_width, setup%gauge_height, &
                     setup%flange_back_distance, setup%flange_back_position, setup%nominal_radius, track, status)
  end subroutine prepare_track

  !> The table: base carries the material, the solver settings and the target.
  !> states: each shift's wheel state (rows_at_shift's wheel), as the
  !> wheelset of the same setup and base takes it (kcreep_wheelset).
  subroutine run_wheel_rail(setup, base, rows, status, shifts_at_once, states)
    type(wheel_rail_setup_t), intent(in) :: setup
    type(problem_t), intent(in) :: base
    type(wheel_rail_row_t), allocatable, intent(out) :: rows(:)
    type(status_t), intent(inout) :: status
    integer, intent(out), optional :: shifts_at_once   !< the team: shifts run at once, one per thread
    type(wheel_state_t), allocatable, intent(out), optional :: states(:)   !< per shift of setup
    type(track_t) :: track
    type(shift_rows_t), allocatable :: at_shift(:)
    type(problem_t) :: row_base
    real(real64) :: sgn
    integer :: i, n, team, stage_team, previous_team, last
    logical :: failed

    allocate (rows(0))
    call prepare_track(setup, track, status)
    if (status%failed()) return
    sgn = merge(-1.0_real64, 1.0_real64, setup%side == 'left')
    n = size(setup%shifts)
    allocate (at_shift(n))
    ! The shifts are independent: a team runs one shift per thread, each on
    ! one thread inside (a whole shift per thread wastes nothing at the
    ! levels' barriers). Rows do not depend on the team: every stage gives
    ! the same numbers on any count (kcreep_threads).
    team = min(team_size(base%solve%threads, int(n, int64), 1), n)    ! work: one thread per shift
    if (present(shifts_at_once)) shifts_at_once = team
    row_base = base
    if (team > 1) then
      row_base%solve%threads = 1
      row_base%normal%options%threads = 1
    end if
    failed = .false.
    call solve_started()
    ! the stages' own parallel regions: one thread each inside a team, else
    ! as for a single patch
    stage_team = 1
    if (team == 1) stage_team = team_size(base%solve%threads, 10000_int64, cells_per_thread_iterative)
    call enter_team(stage_team, previous_team)
    !$omp parallel do num_threads(team) schedule(dynamic, 1) default(shared) private(i)
    do i = 1, n
      ! shifts are handed out in order: after a failure only later ones are skipped
      !$omp atomic read
      at_shift(i)%skipped = failed
      if (at_shift(i)%skipped) cycle
      call rows_at_shift(setup, row_base, track, sgn, i, at_shift(i)%rows, at_shift(i)%status, &
                         wheel=at_shift(i)%wheel, and_rows=.true.)
      if (at_shift(i)%status%failed()) then
        !$omp atomic write
        failed = .true.
      end if
    end do
    !$omp end parallel do
    call leave_team(previous_team)
    call solve_ended()
    ! the rows up to the first failed shift, which gives the status
    last = 0
    do i = 1, n
      if (at_shift(i)%skipped) exit
      last = i
      if (at_shift(i)%status%failed()) then
        status = at_shift(i)%status
        exit
      end if
    end do
    rows = [(at_shift(i)%rows, i=1, last)]
    if (present(states)) states = at_shift(1:last)%wheel
  end subroutine run_wheel_rail

  !> What each shift of the table needs at its peak under error control
  !> (bytes beside the program's own: kcreep_gap_levels gap_levels_need of
  !> its patches, solved one after another, the largest) and the grid cells
  !> of its patches' finest levels (what its rows keep): the geometry and
  !> the normal problems run as the table runs them, the levels not.
  subroutine wheel_rail_needs(setup, base, bytes, cells, status)
    type(wheel_rail_setup_t), intent(in) :: setup
    type(problem_t), intent(in) :: base
    real(real64), allocatable, intent(out) :: bytes(:), cells(:)
    type(status_t), intent(inout) :: status
    type(track_t) :: track
    type(wheel_rail_row_t), allocatable :: rows(:)
    real(real64) :: sgn, need(2)
    integer :: i
    allocate (bytes(size(setup%shifts)), cells(size(setup%shifts)), source=0.0_real64)
    call prepare_track(setup, track, status)
    if (status%failed()) return
    sgn = merge(-1.0_real64, 1.0_real64, setup%side == 'left')
    do i = 1, size(setup%shifts)
      call rows_at_shift(setup, base, track, sgn, i, rows, status, need=need)
      if (status%failed()) return
      bytes(i) = need(1)
      cells(i) = need(2)
    end do
  end subroutine wheel_rail_needs

  !> The most shifts a table of `shifts` runs at once (each needs a patch's
  !> memory): `threads` when given (&solver threads), else the CPUs this
  !> process may use; run_wheel_rail takes fewer on a busy machine.
  integer function most_shifts_at_once(threads, shifts) result(n)
    integer, intent(in) :: threads, shifts
    n = threads
    if (n <= 0) n = cpus_allowed()
    n = max(1, min(n, shifts))
  end function most_shifts_at_once

  !> The rows of shift i: its contacts, the approach (given, or found for the
  !> vertical force), then each patch under error control.
  !> With wheel: the wheel's state after the approach; the rows too only with
  !> and_rows = .true. (else no solves, no rows).
  !> With need: no rows, only what the patches' solves under error control
  !> need (gap_levels_need: the most bytes, the sum of the finest grids' cells).
  subroutine rows_at_shift(setup, base, track, sgn, i, rows, status, wheel, need, and_rows)
    type(wheel_rail_setup_t), intent(in) :: setup
    type(problem_t), intent(in) :: base
    type(track_t), intent(in) :: track
    real(real64), intent(in) :: sgn      !< -1 on the left side (the mirrored right side)
    integer, intent(in) :: i
    type(wheel_rail_row_t), allocatable, intent(out) :: rows(:)
    type(status_t), intent(inout) :: status
    type(wheel_state_t), intent(out), optional :: wheel
    real(real64), intent(out), optional :: need(2)
    logical, intent(in), optional :: and_rows
    real(real64), allocatable :: ys(:), d(:), xs(:)
    type(contact_t), allocatable :: contacts(:), refs(:)
    type(gap_t), allocatable :: grids(:)
    type(plane_gap_t), allocatable :: planes(:)
    real(real64), allocatable :: forces(:), hmins(:)
    real(real64) :: shift, yaw, dz, w0, area_dz
    integer :: k, j
    character(len=200), allocatable :: notes(:)   !< the shift's dropped patches (min_patch_share)
    type(wheel_rail_row_t) :: row
    type(problem_t) :: problem
    character(len=:), allocatable :: where
    integer(int64) :: bytes
    real(real64) :: cells

    allocate (rows(0), notes(0))
    if (present(need)) need = 0
    shift = sgn * setup%shifts(i)
    yaw = sgn * setup%yaw
    where = '&wheel_rail shift = '//rtoa(setup%shifts(i))//' mm: '
    call clearance(track, shift, yaw, ys, d, xs)
    if (.not. any(d < no_surface)) then
      call fail(status, exit_bad_input, where//'the wheel profile never meets the rail profile (no lateral '// &
                'overlap: check flange_back_distance, flange_back_position, gauge_width and the mirror flags)')
      return
    end if
    w0 = minval(d)
    if (setup%force_given) then
      call approach_for_force(first_approach, dz)
      if (status%failed()) return
      call drop_small_patches()
    else
      dz = setup%approach
      call patches_at(dz, dz)
      if (status%failed()) return
      allocate (forces(size(refs)), source=0.0_real64)
    end if
    call check_profile_ends(setup%wheel_name, setup%rail_name, track, ys, d, refs, where, status)
    if (status%failed()) return
    if (present(wheel)) then
      wheel%height = w0 + dz
      wheel%fn = pack(forces, forces > 0)
      wheel%delta = pack(refs%delta, forces > 0)
      wheel%r_wheel = pack([(rolling_radius(refs(k), hmins(k)), k = 1, size(refs))], forces > 0)
      wheel%y = pack(refs%y, forces > 0)
      if (.not. present(and_rows)) return
      if (.not. and_rows) return
    end if
    do k = 1, size(refs)
      problem = base
      problem%normal%active = .true.
      problem%normal%gap = grids(k)
      problem%normal%plane = planes(k)
      problem%normal%poly_given = .false.
      problem%normal%force_given = setup%force_given
      problem%normal%normal_force = forces(k)
      problem%normal%approach = dz * cos(refs(k)%delta)
      problem%refine_grid = .true.
      if (setup%force_given .and. .not. forces(k) > 0) cycle    ! touches, carries nothing
      if (present(need)) then
        call gap_levels_need(problem, bytes, cells, status)
        if (status%failed()) then
          status%message = where//'patch '//itoa(k)//': '//status%message
          return
        end if
        need = [max(need(1), real(bytes, real64)), need(2) + cells]
        cycle
      end if
      call run_controlled(problem, row%result, status)
      if (status%failed()) then
        status%message = where//'patch '//itoa(size(rows) + 1)//': '//status%message
        return
      end if
      call fill_row(refs(k), hmins(k), size(rows) + 1)
      do j = 1, size(notes)
        call add_warning(row%result, trim(notes(j)))
      end do
      rows = [rows, row]
    end do

  contains

    !> The contacts at vertical approach dz_now (refs, the planes' references),
    !> their gap objects, coarse grids over the potential area of approach
    !> dz_area >= dz_now, and smallest gaps.
    subroutine patches_at(dz_now, dz_area)
      real(real64), intent(in) :: dz_now, dz_area
      integer :: j
      call find_contacts(track, shift, yaw, ys, d, xs, dz_now, refs)
      area_dz = dz_area
      if (size(refs) == 0) then
        call fail(status, exit_bad_input, where//'approach = '//rtoa(dz_now)//' mm: no interpenetration (the '// &
                  'approach must be > 0)')
        return
      end if
      if (allocated(grids)) deallocate (grids, planes, hmins)
      allocate (grids(size(refs)), planes(size(refs)), hmins(size(refs)))
      do j = 1, size(refs)
        call potential_area(refs(j), dz_now, dz_area, planes(j), grids(j), hmins(j))
      end do
    end subroutine patches_at

    !> The plane of a contact with the limits of its potential contact area in
    !> s (twice its interpenetration depth, not into a neighbour's interval), a
    !> grid over that area in the plane (x: rolling, y: s), and the smallest
    !> gap of the touching wheel in the plane (hmin; the patch's interpenetration
    !> at approach dz is dz cos(delta) - hmin).
    subroutine potential_area(c, dz_now, dz_area, plane, grid, hmin)
      type(contact_t), intent(in) :: c
      real(real64), intent(in) :: dz_now, dz_area
      type(plane_gap_t), intent(out) :: plane
      type(gap_t), intent(out) :: grid
      real(real64), intent(out) :: hmin
      real(real64), parameter :: ds = 0.05_real64     ! steps along the plane's lines (mm)
      integer :: klo, khi, mx, my, line, step, k, ridge, n_in
      real(real64) :: level, a, s_lo, s_hi, x_lo, x_hi, cell, s, cd, s_in_lo, s_in_hi, h, s_min
      plane = plane_of(track, shift, yaw, w0, c)
      cd = cos(c%delta)
      klo = nint((c%y_lo - ys(1)) / search_step) + 1
      khi = nint((c%y_hi - ys(1)) / search_step) + 1
      ! in s: not beyond the ridge of d towards a neighbouring patch's interval
      s_lo = -huge(1.0_real64)
      s_hi = huge(1.0_real64)
      ridge = 0
      do k = klo - 1, 1, -1
        if (d(k) - w0 < dz_now) then
          s_lo = (ys(ridge) - c%y) / cd
          exit
        end if
        if (ridge == 0) ridge = k
        if (d(k) > d(ridge)) ridge = k
      end do
      ridge = 0
      do k = khi + 1, size(d)
        if (d(k) - w0 < dz_now) then
          s_hi = (ys(ridge) - c%y) / cd
          exit
        end if
        if (ridge == 0) ridge = k
        if (d(k) > d(ridge)) ridge = k
      end do
      plane%s_lo = s_lo
      plane%s_hi = s_hi
      ! the smallest gap on the line xi = 0 across the interpenetration interval
      ! (its image in the plane), refined by a parabola and, with yaw, along xi
      s_in_lo = max((c%y_lo - search_step - c%y) / cd, plane%s_lo)
      s_in_hi = min((c%y_hi + search_step - c%y) / cd, plane%s_hi)
      n_in = max(4, ceiling((s_in_hi - s_in_lo) / ds))
      hmin = huge(1.0_real64)
      s_min = 0
      do k = 0, n_in
        s = s_in_lo + (s_in_hi - s_in_lo) * k / n_in
        h = plane_gap_value(plane, 0.0_real64, s)
        if (h < hmin) then
          hmin = h
          s_min = s
        end if
      end do
      call refine_minimum(plane, 0.0_real64, s_min, (s_in_hi - s_in_lo) / n_in, .false., hmin)
      if (yaw /= 0) call refine_minimum(plane, 0.0_real64, s_min, 0.5_real64, .true., hmin)
      ! in s: where the gap on the line xi = 0 stays below twice the interpenetration,
      ! from the reference outward, at least to the interval's ends
      a = dz_area * cd
      level = hmin + 2 * max(a - hmin, 0.0_real64)
      do step = 1, 4000
        s = -step * ds
        if (s < s_in_lo .and. plane_gap_value(plane, 0.0_real64, s) >= level) exit
      end do
      s_lo = max(plane%s_lo, -step * ds)
      do step = 1, 4000
        s = step * ds
        if (s > s_in_hi .and. plane_gap_value(plane, 0.0_real64, s) >= level) exit
      end do
      s_hi = min(plane%s_hi, step * ds)
      s_lo = s_lo - 0.1_real64 * (s_hi - s_lo) - 0.05_real64
      s_hi = s_hi + 0.1_real64 * (s_hi - s_lo) + 0.05_real64
      plane%s_lo = max(plane%s_lo, s_lo)
      plane%s_hi = min(plane%s_hi, s_hi)
      ! along x: where the gap stays below twice the interpenetration, on 9 lines across s
      x_lo = 0
      x_hi = 0
      do line = 0, 8
        s = s_lo + (s_hi - s_lo) * (line + 0.5_real64) / 9
        ! the largest |xi| each way with the gap below level (steps of 0.05 mm, up to 100 mm)
        do step = 1, 2000
          if (plane_gap_value(plane, step * ds, s) >= level) exit
          x_hi = max(x_hi, step * ds)
        end do
        do step = 1, 2000
          if (plane_gap_value(plane, -step * ds, s) >= level) exit
          x_lo = min(x_lo, -step * ds)
        end do
      end do
      x_lo = x_lo - 0.1_real64 * (x_hi - x_lo) - 0.05_real64
      x_hi = x_hi + 0.1_real64 * (x_hi - x_lo) + 0.05_real64
      cell = min(max(x_hi - x_lo, s_hi - s_lo) / base_cells, min(x_hi - x_lo, s_hi - s_lo) / 16)
      mx = ceiling((x_hi - x_lo) / cell)
      my = ceiling((s_hi - s_lo) / cell)
      call plane_gap_grid(plane, mx, my, cell, cell, (x_lo + x_hi) / 2 - (mx - 1) * cell / 2, &
                          (s_lo + s_hi) / 2 - (my - 1) * cell / 2, grid)
    end subroutine potential_area

    !> The vertical approach at which sum(Fn cos(delta)) is the vertical force
    !> (coarse normal solves), and each patch's Fn. Every evaluation takes the
    !> patches' references and planes at its own approach (CONTACT's contact
    !> search at each wheelset height): those made before are kept while the
    !> references at this approach are within ref_moved of theirs and the
    !> grids cover it. Fn ~ dz^(3/2) updates inside a bracket of the force,
    !> halved (geometrically) when an update leaves it: where the weighted
    !> angle turns fast with the approach (a flange root) the force need not
    !> follow the power law.
    subroutine approach_for_force(dz_first, dz_out)
      real(real64), intent(in) :: dz_first
      real(real64), intent(out) :: dz_out
      real(real64) :: total, compliance, dz_lo, dz_hi, dz_next
      type(normal_result_t) :: nres
      integer :: it, j
      compliance = base%normal%compliance
      if (compliance <= 0) compliance = compliance_from_g_nu(base%g, base%nu)
      dz_out = dz_first
      dz_lo = 0
      dz_hi = huge(1.0_real64)
      area_dz = -1
      do it = 1, 100
        call find_contacts(track, shift, yaw, ys, d, xs, dz_out, contacts)
        if (dz_out > area_dz .or. .not. same_references(contacts)) then
          call patches_at(dz_out, 1.3_real64 * dz_out)
          if (status%failed()) return
        end if
        if (allocated(forces)) deallocate (forces)
        allocate (forces(size(refs)))
        total = 0
        do j = 1, size(refs)
          forces(j) = 0
          if (.not. any(grids(j)%h < dz_out * cos(refs(j)%delta))) cycle
          call solve_normal(grids(j)%h, grids(j)%dx, grids(j)%dy, compliance, base%normal%options, nres, status, &
                            approach=dz_out * cos(refs(j)%delta))
          if (status%failed()) then
            status%message = where//'finding the approach: '//status%message
            return
          end if
          forces(j) = nres%fn
          total = total + nres%fn * cos(refs(j)%delta)
        end do
        if (abs(total / setup%vertical_force - 1) < 1e-6_real64) exit
        if (total < setup%vertical_force) then
          dz_lo = max(dz_lo, dz_out)
        else
          dz_hi = min(dz_hi, dz_out)
        end if
        if (dz_hi < huge(1.0_real64) .and. dz_hi - dz_lo <= 1e-9_real64 * dz_hi .and. total > 0) exit  ! a step of the force
        if (total > 0) then
          dz_next = dz_out * (setup%vertical_force / total)**(2.0_real64 / 3)
        else
          dz_next = 2 * dz_out
        end if
        if (dz_next <= dz_lo .or. dz_next >= dz_hi) then
          if (dz_hi < huge(1.0_real64) .and. dz_lo > 0) then
            dz_next = sqrt(dz_lo * dz_hi)
          else if (dz_hi < huge(1.0_real64)) then
            dz_next = dz_hi / 2
          else
            dz_next = 2 * dz_lo
          end if
        end if
        dz_out = dz_next
      end do
      if (.not. (total > 0)) then
        call fail(status, exit_numerical, where//'no approach found for vertical_force = '//rtoa(setup%vertical_force))
        return
      end if
      ! the forces scaled to the vertical force
      forces = forces * setup%vertical_force / total
    end subroutine approach_for_force

    !> The planes' references are those of now (the same patches, each point
    !> and angle within ref_moved).
    pure logical function same_references(now) result(same)
      type(contact_t), intent(in) :: now(:)
      same = .false.
      if (.not. allocated(refs)) return
      if (size(now) /= size(refs)) return
      same = all(abs(now%y - refs%y) <= ref_moved .and. abs(now%x - refs%x) <= ref_moved .and. &
                 abs(now%delta - refs%delta) <= ref_moved)
    end function same_references

    !> Patches whose share of the vertical force is below min_patch_share
    !> carry nothing (skipped); the others' forces are scaled to carry the
    !> load, and every row of the shift notes each dropped patch.
    subroutine drop_small_patches()
      real(real64) :: shares(size(forces)), kept
      integer :: j
      shares = forces * cos(refs%delta) / setup%vertical_force
      if (.not. any(shares < setup%min_patch_share) .or. all(shares < setup%min_patch_share)) return
      do j = 1, size(forces)
        if (shares(j) < setup%min_patch_share .and. forces(j) > 0) notes = [notes, &
            [character(len=200) :: 'a patch of '//rtoa(1e2_real64 * shares(j))//' % of the vertical '// &
             'force at y_rail = '//rtoa(rail_y(refs(j)))//' mm dropped (min_patch_share); the other patches '// &
             'carry its share']]
      end do
      where (shares < setup%min_patch_share) forces = 0
      kept = sum(forces * cos(refs%delta))
      forces = forces * setup%vertical_force / kept
    end subroutine drop_small_patches

    !> The row of a patch: CONTACT's reference point, angle and rolling
    !> radius: the distance from the wheel's axis of the reference point moved
    !> along the plane's normal by the patch's interpenetration pen (CONTACT's
    !> point Q, m_wr_rigslip), pen = dz cos(delta) - hmin.
    subroutine fill_row(c, hmin, patch)
      type(contact_t), intent(in) :: c
      real(real64), intent(in) :: hmin
      integer, intent(in) :: patch
      associate (r => row%result)
        row%shift = setup%shifts(i)
        row%yaw = setup%yaw
        row%patch = patch
        row%fn = r%fn
        row%delta = sgn * c%delta
        row%y_rail = rail_y(c)
        row%y_wheel = merge(-c%y_wheel, c%y_wheel, setup%wheel_mirror)
        row%r_wheel = rolling_radius(c, hmin)
        row%area = pi * r%c**2
        row%length = r%bbox(2) - r%bbox(1)
        row%width = r%bbox(4) - r%bbox(3)
        row%c(1:3) = r%cn
        row%c(4) = r%f(3, 3) / (r%g * r%c**4)
        row%err = r%err
        row%verdict = r%verdict
        row%l = r%fastsim
        row%spin = sin(row%delta) / row%r_wheel
        row%turn = c%turn
        row%kind = merge('flange', 'tread ', abs(c%delta) >= flange_angle)
        row%approach = dz
        row%y_track = sgn * c%y
        row%z_track = c%z
      end associate
      if (c%turn > turn_warning) call add_warning(row%result, 'the rail''s surface angle varies by up '// &
          'to '//rtoa(c%turn)//' rad from the contact angle across the patch (more than '//rtoa(turn_warning)// &
          ': the planar gap along the normal is off by more than 3 % there; CONTACT warns too)')
    end subroutine fill_row

    !> The rolling radius at CONTACT's point Q: the reference point moved along
    !> the normal by the patch's interpenetration, from the wheel's axis.
    pure real(real64) function rolling_radius(c, hmin) result(r)
      type(contact_t), intent(in) :: c
      real(real64), intent(in) :: hmin
      real(real64) :: pen
      pen = dz * cos(c%delta) - hmin
      r = c%z + pen * cos(c%delta) - (w0 + dz - track%r_nom)
    end function rolling_radius

    !> The reference point's lateral coordinate in the rail profile's own coordinates.
    pure real(real64) function rail_y(c) result(y)
      type(contact_t), intent(in) :: c
      real(real64) :: yp, zp
      yp = c%y - track%rail_shift(1)
      zp = c%z - track%rail_shift(2)
      y = cos(track%cant) * yp + sin(track%cant) * zp
      if (setup%rail_mirror) y = -y
    end function rail_y

  end subroutine rows_at_shift

end module kcreep_wheel_rail_run
