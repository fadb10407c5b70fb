!> The contact table of &wheel_rail as text lines (&output wheel_rail_file):
!> comment lines starting with '#', the last naming the columns, then one row
!> per shift and patch (the facade's wheel_rail_columns). python/kcreep
!> table.read reads it. Also the per-patch tables of &fastsim (creep_file)
!> and &rolling (rolling_file) with &wheel_rail.
module kcreep_wheel_rail_table
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep, only: wheel_rail_row_t, wheel_rail_setup_t, wheel_rail_columns, creep_request_t, creep_point_t, &
                    source_names, flexibility_rule_name, rolling_request_t, rolling_point_t, wheelset_row_t, &
                    wheelset_columns
  use kcreep_strings, only: rtoa
  use kcreep_profile, only: profile_smoothing
  use kcreep_rolling_table, only: rolling_columns, rolling_notes, rolling_row
  implicit none
  private
  public :: wheel_rail_lines, line_length, wheel_rail_creep_header, wheel_rail_creep_rows, wheel_rail_creep_columns
  public :: wheel_rail_header_lines, wheel_rail_batch_head, wheel_rail_batch_columns, wheel_rail_row
  public :: wheel_rail_rolling_header, wheel_rail_rolling_rows, wheel_rail_rolling_columns
  public :: wheelset_lines

  !> The columns that lead each row of the per-patch tables: which shift and patch, its geometric spin.
  character(len=*), parameter :: patch_columns = 'shift yaw patch spin'
  !> The creep table of &fastsim with &wheel_rail: one block of rows per shift and patch.
  character(len=*), parameter :: wheel_rail_creep_columns = patch_columns//' xi eta phi fx fy mz fn adhesion '// &
                                                          'source fx_mufn fy_mufn'
  !> The rolling table of &rolling with &wheel_rail: one block of rows per shift and patch.
  character(len=*), parameter :: wheel_rail_rolling_columns = patch_columns//' '//rolling_columns

  integer, parameter :: line_length = 600

  !> The columns of a batch's merged table of contact tables (kcreep --batch,
  !> scripts/run_cases.sh): the case's name, then the columns of its table.
  character(len=*), parameter :: wheel_rail_batch_columns = 'case '//wheel_rail_columns

  !> Lines of a table before its rows: lines 1-5 describe the case (its side,
  !> profiles, placement, load, material), lines 6-8 the columns.
  integer, parameter :: wheel_rail_header_lines = 8

  !> The comment lines on the columns (a table's lines 6 and 7).
  character(len=*), parameter :: point_note = '# delta: contact angle (the patch''s weighted mean surface '// &
    'angle); y_rail, y_wheel: its reference point (interpenetration centre) in each profile''s own coordinates; '// &
    'r_wheel: rolling radius there; area = pi c^2, length x width: extent of the contact area; kind: tread or '// &
    'flange (|delta| >= pi/4); turn: largest |surface angle - delta| across the patch (rad; above 0.2415 the '// &
    'row is warned of)'
  character(len=*), parameter :: coefficient_note = '# c11 c22 c23 = f/(G c^2), f23/(G c^3), c33 = f33/(G c^4) '// &
    'about the contact point; err: estimated relative errors; l1 l2 l3: FASTSIM flexibilities; '// &
    'spin = sin(delta)/r_wheel'

contains

  function wheel_rail_lines(rows, setup, g, nu, target_error) result(lines)
    type(wheel_rail_row_t), intent(in) :: rows(:)
    type(wheel_rail_setup_t), intent(in) :: setup
    real(real64), intent(in) :: g, nu, target_error
    character(len=line_length), allocatable :: lines(:)
    integer :: k
    allocate (lines(size(rows) + 8))
    lines(1) = '# kcreep: contact table of a wheel on a rail over the lateral shift (side '//setup%side//')'
    lines(2) = '# '//setup%wheel_name//' on '//setup%rail_name
    lines(3) = '# gauge_width '//rtoa(setup%gauge_width)//' at gauge_height '//rtoa(setup%gauge_height)// &
               ', rail_cant '//rtoa(setup%rail_cant)//', flange_back_distance '//rtoa(setup%flange_back_distance)// &
               ', flange_back_position '//rtoa(setup%flange_back_position)//', nominal_radius '// &
               rtoa(setup%nominal_radius)//', smoothing '//smoothing_text()
    if (setup%force_given) then
      lines(4) = '# load: vertical_force '//rtoa(setup%vertical_force)//' N (sum of fn cos(delta) over the patches)'
    else
      lines(4) = '# load: vertical approach '//rtoa(setup%approach)//' mm'
    end if
    lines(5) = '# material g '//rtoa(g)//', nu '//rtoa(nu)//'; target_error '//rtoa(target_error)// &
               '; lengths mm, forces N, angles rad'
    lines(6) = point_note
    lines(7) = coefficient_note
    lines(8) = '# '//wheel_rail_columns
    do k = 1, size(rows)
      lines(k + 8) = wheel_rail_row(rows(k))
    end do

  contains

    !> The smoothing as given, or automatic with each profile's lambda (mm^4).
    function smoothing_text() result(text)
      character(len=:), allocatable :: text
      if (setup%smoothing >= 0) then
        text = rtoa(setup%smoothing)
      else
        text = 'automatic (wheel '//rtoa(profile_smoothing(setup%wheel_y, setup%wheel_z, setup%smoothing))// &
               ', rail '//rtoa(profile_smoothing(setup%rail_y, setup%rail_z, setup%smoothing))//' mm^4)'
      end if
    end function smoothing_text

  end function wheel_rail_lines

  !> One row of the table (the columns wheel_rail_columns).
  function wheel_rail_row(r) result(line)
    type(wheel_rail_row_t), intent(in) :: r
    character(len=line_length) :: line
    write (line, '(2(es15.7), i4, 5(es16.8), 3(es14.6), 4(es15.7), 3(es10.2), 1x, a, 4(es14.6), 1x, a, es12.4)') &
      r%shift, r%yaw, r%patch, r%fn, r%delta, r%y_rail, r%y_wheel, r%r_wheel, r%area, r%length, r%width, &
      r%c, r%err, trim(no_blanks(r%verdict)), r%l, r%spin, trim(r%kind), r%turn
  end function wheel_rail_row

  !> The fixed comment lines and the column names of a batch's merged table
  !> of contact tables: one block of rows per case, each row led by the case's
  !> name; each case's own description (wheel_rail_lines 1-5) comes with it.
  function wheel_rail_batch_head() result(lines)
    character(len=line_length), allocatable :: lines(:)
    allocate (lines(4))
    lines(1) = '# kcreep: contact tables of wheels on rails over the lateral shift, one block of rows per case '// &
               '(its &wheel_rail), each row led by the case''s name; each case''s profiles, load and material '// &
               'in the comments ''# case K ...'''
    lines(2) = point_note
    lines(3) = coefficient_note
    lines(4) = '# '//wheel_rail_batch_columns
  end function wheel_rail_batch_head
  !> The wheelset table (&output wheelset_file): one row per shift.
  function wheelset_lines(table, setup) result(lines)
    type(wheelset_row_t), intent(in) :: table(:)
    type(wheel_rail_setup_t), intent(in) :: setup
    character(len=line_length), allocatable :: lines(:)
    integer :: k
    allocate (lines(size(table) + 7))
    lines(1) = '# kcreep: wheelset over the lateral shift (a rigid wheelset, each wheel carrying vertical_force '// &
               rtoa(setup%vertical_force)//' N)'
    lines(2) = '# right: '//setup%wheel_name//' on '//setup%rail_name
    if (allocated(setup%left_wheel_name) .or. allocated(setup%left_rail_name)) then
      lines(3) = '# left: '//left_name(setup%left_wheel_name, setup%wheel_name)//' on '// &
                 left_name(setup%left_rail_name, setup%rail_name)
    else
      lines(3) = '# left: the right profiles mirrored (a symmetric wheelset)'
    end if
    lines(4) = '# r_right, r_left: rolling radii at the contact (load-weighted over two patches); '// &
               'delta_r = r_right - r_left; delta_right, delta_left: contact angles, each positive towards its flange'
    lines(5) = '# roll: wheelset roll (positive: right wheel down), z: its vertical position at the track centre '// &
               '(z down, 0: nominal rolling circles in the track plane), from each wheel''s approach for the load'
    lines(6) = '# lambda_eq: equivalent conicity at amplitude |shift| (first harmonic of delta_r(A sin t) over 2A); '// &
               'lengths mm, angles rad'
    lines(7) = '# '//wheelset_columns
    do k = 1, size(table)
      associate (t => table(k))
        write (lines(k + 7), '(es15.7, 3(es17.9), 2(es16.8), 2(es16.8), es16.8)') t%shift, t%r_right, t%r_left, &
          t%delta_r, t%delta_right, t%delta_left, t%roll, t%z, t%lambda_eq
      end associate
    end do

  contains

    function left_name(own, right) result(name)
      character(len=:), allocatable, intent(in) :: own
      character(len=*), intent(in) :: right
      character(len=:), allocatable :: name
      if (allocated(own)) then
        name = own
      else
        name = 'the right '//right//' mirrored'
      end if
    end function left_name

  end function wheelset_lines

  !> The creep table's comment lines and column names.
  function wheel_rail_creep_header(setup, request) result(lines)
    type(wheel_rail_setup_t), intent(in) :: setup
    type(creep_request_t), intent(in) :: request
    character(len=line_length), allocatable :: lines(:)
    allocate (lines(5))
    lines(1) = '# kcreep FASTSIM creep forces on each patch of a wheel on a rail ('//setup%wheel_name//' on '// &
               setup%rail_name//')'
    write (lines(2), '(a, es12.5, a)') '# mu = ', request%mu, ', flexibility rule '// &
      flexibility_rule_name(request%rule)//', pressure: each patch''s normal solve, L1 L2 L3 per patch'
    lines(3) = spin_note('FASTSIM')
    lines(4) = '# (Fx, Fy, Mz) = -f (xi, eta, phi) at small creepage; adhesion: fraction of the area in adhesion; '// &
               'fx_mufn = fx / (mu fn)'
    lines(5) = '# '//wheel_rail_creep_columns
  end function wheel_rail_creep_header

  !> The rows of one patch: its points (FASTSIM at phi + spin) prefixed by shift, yaw, patch, spin.
  function wheel_rail_creep_rows(row, request, points) result(lines)
    type(wheel_rail_row_t), intent(in) :: row
    type(creep_request_t), intent(in) :: request
    type(creep_point_t), intent(in) :: points(:)
    character(len=line_length), allocatable :: lines(:)
    character(len=line_length) :: buf
    real(real64) :: mufn
    integer :: k
    allocate (lines(size(points)))
    do k = 1, size(points)
      associate (p => points(k), f => points(k)%force)
        mufn = request%mu * f%fn
        write (buf, '(7(1x, es23.15e3), 1x, f8.6, 1x, a, 2(1x, es23.15e3))') p%creep, f%fx, f%fy, f%mz, f%fn, &
          f%adhesion, trim(source_names(p%source)), f%fx / mufn, f%fy / mufn
        lines(k) = patch_prefix(row)//trim(buf)
      end associate
    end do
  end function wheel_rail_creep_rows

  !> The rolling table's comment lines and column names.
  function wheel_rail_rolling_header(setup, request) result(lines)
    type(wheel_rail_setup_t), intent(in) :: setup
    type(rolling_request_t), intent(in) :: request
    character(len=line_length), allocatable :: lines(:)
    allocate (lines(7))
    lines(1) = '# kcreep exact steady rolling with Coulomb friction on each patch of a wheel on a rail ('// &
               setup%wheel_name//' on '//setup%rail_name//')'
    write (lines(2), '(a, es12.5, a, es9.2, a)') '# mu = ', request%mu, ', tolerance', request%tolerance, &
      '; pressure: each patch''s normal solve, on its finest grid (backward scheme, semi-smooth Newton)'
    lines(3) = spin_note('rolling')
    lines(4:6) = rolling_notes()
    lines(7) = '# '//wheel_rail_rolling_columns
  end function wheel_rail_rolling_header

  !> The rows of one patch: its rolling points (at phi + spin) prefixed by shift, yaw, patch, spin.
  function wheel_rail_rolling_rows(row, request, points) result(lines)
    type(wheel_rail_row_t), intent(in) :: row
    type(rolling_request_t), intent(in) :: request
    type(rolling_point_t), intent(in) :: points(:)
    character(len=line_length), allocatable :: lines(:)
    integer :: k
    allocate (lines(size(points)))
    do k = 1, size(points)
      lines(k) = patch_prefix(row)//' '//rolling_row(request%mu, points(k))
    end do
  end function wheel_rail_rolling_rows

  !> The columns patch_columns of a row: shift, yaw, patch, spin.
  function patch_prefix(row) result(text)
    type(wheel_rail_row_t), intent(in) :: row
    character(len=49) :: text
    write (text, '(2(es15.7), i4, es15.7)') row%shift, row%yaw, row%patch, row%spin
  end function patch_prefix

  !> The comment line on the spin column, for the engine that ran.
  pure function spin_note(engine) result(line)
    character(len=*), intent(in) :: engine
    character(len=:), allocatable :: line
    line = '# spin: the patch''s geometric spin sin(delta)/r_wheel (1/mm); phi = the given phi + spin '// &
           '(the creepage '//engine//' ran with)'
  end function spin_note

  !> A verdict of several words as one column ('ok' or 'uncertain,coarse').
  pure function no_blanks(text) result(out)
    character(len=*), intent(in) :: text
    character(len=len(text)) :: out
    integer :: k
    out = text
    do k = 1, len_trim(out)
      if (out(k:k) == ' ') out(k:k) = '_'
    end do
    if (len_trim(out) == 0) out = '-'
  end function no_blanks

end module kcreep_wheel_rail_table
