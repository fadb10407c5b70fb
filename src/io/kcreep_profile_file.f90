!> Wheel and rail profile files: the points (y, z) of one lateral section, in mm,
!> z positive downwards (CONTACT's convention for wheel and rail profiles).
!>
!> The format is chosen by the file's extension (case-insensitive):
!>  - SIMPACK `.prw` (wheel) / `.prr` (rail): `header.begin ... header.end` with
!>    `type` (0 rail, 1 wheel), `spline.begin ... spline.end` with processing keys
!>    applied in SIMPACK's order: `point.dist.min` (drop points closer than this
!>    to the last one kept), `shift.y`, `shift.z`, `rotate` (about x), `bound.y/z.min/max`
!>    (clip; min > max: no bound), `mirror.y`, `mirror.z`, `units.len.f` (user
!>    length units per metre: 1000 = mm), `units.ang.f`, `inversion` (reverse the
!>    order); then `point.begin ... point.end` with columns y z [weight]. `!` starts a comment.
!>  - MiniProf `.whl` (wheel) / `.ban` (rail): a header (new style `Key=Value`
!>    lines with `ColumnDef`, `XOffset`, `YOffset`; or old style free text),
!>    a blank line, then columns; X lateral and Y vertical, the offsets added;
!>    z = -Y or Y, whichever puts the profile's two ends (its side faces) below
!>    the mean for a rail and above it for a wheel (CONTACT's auto-detection).
!>  - anything else: two columns y z in mm, z positive downwards; lines starting
!>    with `!`, `%` or `#` are skipped.
!> Every error names the file, the line and what was expected.
module kcreep_profile_file
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, lower
  use kcreep_file_checks, only: read_input_file
  use kcreep_profile, only: median_of
  implicit none
  private
  public :: read_profile_file, profile_format

  !> At most this many points in a profile (measured profiles have a few hundred to a few thousand).
  integer, parameter :: max_points = 200000
  !> A point whose y goes back by at most this (mm) is dropped, a larger step
  !> back is refused: avg_HR.BAN (MiniProf, written to 0.01 mm) has one
  !> point 0.01 mm back (29.27 then 29.26 at z -2.55, line 136), a
  !> quantisation artefact that CONTACT drops too ("zig-zag").
  real(real64), parameter :: back_step_tolerance = 0.02_real64
  !> A vertical step: neighbouring points (not the first or last pair: side
  !> faces) at least step_slope times as far apart in z as in y and further
  !> than step_spacings median spacings and step_length mm. Measured: the
  !> steepest long pairs of the four profiles in ../shared/profiles are
  !> UIC60's gauge face (0.92 mm, 4 spacings, 40:1) and the MiniProf
  !> wheel's flange back (0.25 mm, one spacing).
  real(real64), parameter :: step_slope = 10, step_spacings = 10, step_length = 1
  !> The z-direction test decides only when the ends lie off the mean by more
  !> than this share of the profile's z range: a plain cone's ends sit on its
  !> mean (tests/scenario/test_wheelset.py's 1:20 cone, 1e-17 mm off). The
  !> ends lie off the mean by 5.8 % of the range on S1002, 59 % on UIC60, 19
  !> and 33 % on the MiniProf wheel and rail (../shared/profiles).
  real(real64), parameter :: z_direction_margin = 0.02_real64

contains

  !> The format the reader takes for a file name: 'simpack', 'miniprof' or 'table'.
  pure function profile_format(path) result(kind)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: kind
    character(len=:), allocatable :: ext
    integer :: dot, slash
    dot = index(path, '.', back=.true.)
    slash = index(path, '/', back=.true.)
    ext = ''
    if (dot > slash) ext = lower(path(dot + 1:))
    select case (ext)
    case ('prw', 'prr')
      kind = 'simpack'
    case ('whl', 'ban')
      kind = 'miniprof'
    case default
      kind = 'table'
    end select
  end function profile_format

  !> Read the profile at path; variable names it in messages ('wheel_file' or
  !> 'rail_file'); is_wheel: the profile is used as the wheel's (a SIMPACK file
  !> of the other type is refused). y, z: the points in the file's order after
  !> its own processing, in mm, z positive downwards.
  subroutine read_profile_file(path, variable, is_wheel, y, z, status)
    character(len=*), intent(in) :: path, variable
    logical, intent(in) :: is_wheel
    real(real64), allocatable, intent(out) :: y(:), z(:)
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: text, source, ext
    integer, allocatable :: lines(:)
    source = variable//' '''//path//''''
    call read_input_file(path, source, text, status)
    if (status%failed()) return
    select case (profile_format(path))
    case ('simpack')
      call parse_simpack(text, source, is_wheel, y, z, lines, status)
    case ('miniprof')
      ! a MiniProf file says by its extension which body it is
      ext = lower(path(index(path, '.', back=.true.) + 1:))
      if ((ext == 'ban') .eqv. is_wheel) then
        call fail(status, exit_bad_input, source//': a MiniProf '//trim(merge('rail ', 'wheel', ext == 'ban'))// &
                  ' profile (.'//ext//') given as the '//trim(merge('wheel', 'rail ', is_wheel))// &
                  ' (MiniProf wheels are .whl, rails .ban: wheel_file and rail_file swapped?)')
        return
      end if
      call parse_miniprof(text, source, is_wheel, y, z, lines, status)
    case default
      call parse_table(text, source, y, z, lines, status)
    end select
    if (status%failed()) return
    if (size(y) < 4) then
      call fail(status, exit_bad_input, source//': '//itoa(size(y))//' profile points (at least 4 needed)')
      return
    end if
    if (.not. all(abs(y) < 1e6_real64 .and. abs(z) < 1e6_real64)) then
      call fail(status, exit_bad_input, source//': a point is not finite or beyond 1e6 mm (allowed: |y|, |z| < 1e6 mm)')
      return
    end if
    call check_lateral_order(source, y, z, lines, status)
    if (status%failed()) return
    call check_vertical_steps(source, y, z, lines, status)
    if (status%failed()) return
    if (profile_format(path) == 'table') call check_z_downwards(source, is_wheel, z, status)
  end subroutine read_profile_file

  !> The lateral coordinate runs one way (up or down the file): a point that
  !> goes back by at most back_step_tolerance is dropped, further is refused.
  !> Vertical pairs (the same y) are kept.
  subroutine check_lateral_order(source, y, z, lines, status)
    character(len=*), intent(in) :: source
    real(real64), allocatable, intent(inout) :: y(:), z(:)
    integer, allocatable, intent(inout) :: lines(:)
    type(status_t), intent(inout) :: status
    logical :: keep(size(y))
    real(real64) :: sgn, back
    integer :: i, last
    sgn = sign(1.0_real64, y(size(y)) - y(1))
    keep = .true.
    last = 1
    do i = 2, size(y)
      back = sgn * (y(last) - y(i))
      if (back <= 0) then
        last = i
      else if (back <= back_step_tolerance) then
        keep(i) = .false.
      else
        call fail(status, exit_bad_input, source//' line '//itoa(lines(i))//': y = '//rtoa(y(i))// &
                  ' goes back from y = '//rtoa(y(last))//' on line '//itoa(lines(last))// &
                  ' (the lateral coordinate must run one way; a step back of at most '// &
                  rtoa(back_step_tolerance)//' mm, a measuring artefact, is dropped)')
        return
      end if
    end do
    y = pack(y, keep)
    z = pack(z, keep)
    lines = pack(lines, keep)
  end subroutine check_lateral_order

  !> No vertical step between neighbouring points inside the profile (a gap
  !> or a spike in a measurement; the first and last pair may be side faces).
  subroutine check_vertical_steps(source, y, z, lines, status)
    character(len=*), intent(in) :: source
    real(real64), intent(in) :: y(:), z(:)
    integer, intent(in) :: lines(:)
    type(status_t), intent(inout) :: status
    real(real64) :: h, dy, dz
    integer :: i, n
    n = size(y)
    h = median_of(hypot(y(2:n) - y(1:n - 1), z(2:n) - z(1:n - 1)))
    do i = 2, n - 2
      dy = abs(y(i + 1) - y(i))
      dz = abs(z(i + 1) - z(i))
      if (dz >= step_slope * dy .and. dz > max(step_length, step_spacings * h)) then
        call fail(status, exit_bad_input, source//' line '//itoa(lines(i + 1))//': z jumps by '//rtoa(dz)// &
                  ' mm from line '//itoa(lines(i))//' at y = '//rtoa(y(i))//' (a vertical step: more than '// &
                  rtoa(step_spacings)//' times the median point spacing of '//rtoa(h)// &
                  ' mm, steeper than 10:1; a gap or a spike in the measurement?)')
        return
      end if
    end do
  end subroutine check_vertical_steps

  !> A plain file's z points downwards: a rail's ends (its side faces) lie
  !> below its mean height (larger z), a wheel's above (CONTACT's test,
  !> which the MiniProf reader uses to choose the direction).
  subroutine check_z_downwards(source, is_wheel, z, status)
    character(len=*), intent(in) :: source
    logical, intent(in) :: is_wheel
    real(real64), intent(in) :: z(:)
    type(status_t), intent(inout) :: status
    real(real64) :: ends, mean
    integer :: n
    n = size(z)
    ends = (z(1) + z(n)) / 2
    mean = sum(z) / n
    if ((ends > mean) .neqv. is_wheel) return
    ! a profile whose ends lie level with its mean (a plain cone) tells no direction
    if (abs(ends - mean) <= z_direction_margin * (maxval(z) - minval(z))) return
    call fail(status, exit_bad_input, source//': z seems to point upwards: the ends (z = '//rtoa(z(1))//', '// &
              rtoa(z(n))//') lie '//trim(merge('below', 'above', is_wheel))//' the mean '//rtoa(mean)// &
              ' mm, a '//trim(merge('wheel''s rise', 'rail''s fall ', is_wheel))// &
              ' (two-column files need z positive downwards: negate the z column)')
  end subroutine check_z_downwards

  !> The next line of text from position pos (advanced past it); eof when none is left.
  subroutine next_line(text, pos, line, eof)
    character(len=*), intent(in) :: text
    integer, intent(inout) :: pos
    character(len=:), allocatable, intent(out) :: line
    logical, intent(out) :: eof
    integer :: cut
    eof = pos > len(text)
    if (eof) then
      line = ''
      return
    end if
    cut = index(text(pos:), achar(10))
    if (cut == 0) then
      line = text(pos:)
      pos = len(text) + 1
    else
      line = text(pos:pos + cut - 2)
      pos = pos + cut
    end if
    ! carriage returns and tabs are blanks
    line = translate_blanks(line)
  end subroutine next_line

  pure function translate_blanks(line) result(out)
    character(len=*), intent(in) :: line
    character(len=len(line)) :: out
    integer :: k
    out = line
    do k = 1, len(out)
      if (out(k:k) == achar(13) .or. out(k:k) == achar(9) .or. out(k:k) == ',' .or. out(k:k) == ';') out(k:k) = ' '
    end do
  end function translate_blanks

  !> Up to size(values) numbers from line; n: how many were read (stops at the first word).
  subroutine numbers_of(line, values, n)
    character(len=*), intent(in) :: line
    real(real64), intent(out) :: values(:)
    integer, intent(out) :: n
    character(len=len(line)) :: rest
    integer :: cut, ios
    real(real64) :: v
    n = 0
    values = 0
    rest = adjustl(line)
    do while (len_trim(rest) > 0 .and. n < size(values))
      cut = index(rest, ' ')
      if (cut == 0) cut = len(rest) + 1
      read (rest(1:cut - 1), *, iostat=ios) v
      if (ios /= 0) return
      if (scan(rest(1:cut - 1), '0123456789') == 0) return   ! 'nan', 'inf', words: not a number here
      n = n + 1
      values(n) = v
      rest = adjustl(rest(cut:))
    end do
  end subroutine numbers_of

  !> A point and its line number to the growing lists.
  subroutine push(ys, zs, ls, n, yv, zv, lv)
    real(real64), allocatable, intent(inout) :: ys(:), zs(:)
    integer, allocatable, intent(inout) :: ls(:)
    integer, intent(inout) :: n
    real(real64), intent(in) :: yv, zv
    integer, intent(in) :: lv
    real(real64), allocatable :: grown(:)
    integer, allocatable :: grown_l(:)
    if (.not. allocated(ls)) allocate (ls(size(ys)))
    if (n == size(ys)) then
      allocate (grown(2 * n + 16))
      grown(1:n) = ys(1:n)
      call move_alloc(grown, ys)
      allocate (grown(2 * n + 16))
      grown(1:n) = zs(1:n)
      call move_alloc(grown, zs)
    end if
    if (n >= size(ls)) then
      allocate (grown_l(size(ys)))
      grown_l(1:n) = ls(1:n)
      call move_alloc(grown_l, ls)
    end if
    n = n + 1
    ys(n) = yv
    zs(n) = zv
    ls(n) = lv
  end subroutine push

  !> Two columns y z per line.
  subroutine parse_table(text, source, y, z, lines, status)
    character(len=*), intent(in) :: text, source
    real(real64), allocatable, intent(out) :: y(:), z(:)
    integer, allocatable, intent(out) :: lines(:)
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: line
    real(real64) :: v(3)
    integer :: pos, n, lineno, k
    logical :: eof
    allocate (y(64), z(64), lines(64))
    n = 0
    pos = 1
    lineno = 0
    do
      call next_line(text, pos, line, eof)
      if (eof) exit
      lineno = lineno + 1
      line = adjustl(line)
      if (len_trim(line) == 0) cycle
      if (scan(line(1:1), '!%#') > 0) cycle
      call numbers_of(line, v, k)
      if (k < 2) then
        call fail(status, exit_bad_input, source//' line '//itoa(lineno)//': '''//trim(line(1:min(len(line), 40)))// &
                  ''' is not two numbers y z (a plain profile: columns y z in mm; SIMPACK needs .prw/.prr, '// &
                  'MiniProf .whl/.ban)')
        return
      end if
      if (n >= max_points) then
        call fail(status, exit_bad_input, source//': more than '//itoa(max_points)//' points')
        return
      end if
      call push(y, z, lines, n, v(1), v(2), lineno)
    end do
    y = y(1:n)
    z = z(1:n)
    lines = lines(1:n)
  end subroutine parse_table

  !> MiniProf: header up to the first blank line (its ColumnDef, XOffset, YOffset
  !> when given), then numeric rows; z = -(Y + YOffset), y = X + XOffset.
  subroutine parse_miniprof(text, source, is_wheel, y, z, lines, status)
    character(len=*), intent(in) :: text, source
    logical, intent(in) :: is_wheel
    real(real64), allocatable, intent(out) :: y(:), z(:)
    integer, allocatable, intent(out) :: lines(:)
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: line, key, value
    real(real64) :: v(16), xoff, yoff
    integer :: pos, n, lineno, k, eq, ix, iy, col, ios
    logical :: eof, in_header
    character(len=:), allocatable :: rest
    allocate (y(64), z(64), lines(64))
    n = 0
    pos = 1
    lineno = 0
    xoff = 0
    yoff = 0
    ix = 1
    iy = 2
    in_header = .true.
    do
      call next_line(text, pos, line, eof)
      if (eof) exit
      lineno = lineno + 1
      if (in_header) then
        if (len_trim(line) == 0) then
          in_header = .false.
          cycle
        end if
        ! a file without a header: the first line is already numbers
        call numbers_of(line, v, k)
        if (lineno == 1 .and. k >= 2) then
          in_header = .false.
        else
          eq = index(line, '=')
          if (eq > 0) then
            key = lower(trim(adjustl(line(1:eq - 1))))
            value = trim(adjustl(line(eq + 1:)))
            if (len(key) > 0) then
              if (key(1:1) == '"') key = key(2:)
            end if
            if (len(value) > 0) then
              if (value(len(value):len(value)) == '"') value = value(1:len(value) - 1)
            end if
            select case (key)
            case ('xoffset')
              if (len_trim(value) > 0) read (value, *, iostat=ios) xoff
              if (len_trim(value) > 0 .and. ios /= 0) goto 900
            case ('yoffset')
              if (len_trim(value) > 0) read (value, *, iostat=ios) yoff
              if (len_trim(value) > 0 .and. ios /= 0) goto 900
            case ('columndef')
              ! e.g. X,Y,A (the separators became blanks)
              rest = lower(value)
              col = 0
              ix = 0
              iy = 0
              do while (len_trim(rest) > 0)
                rest = adjustl(rest)
                col = col + 1
                if (rest(1:1) == 'x') ix = col
                if (rest(1:1) == 'y') iy = col
                k = index(rest, ' ')
                if (k == 0) exit
                rest = rest(k:)
              end do
              if (ix == 0 .or. iy == 0) then
                call fail(status, exit_bad_input, source//' line '//itoa(lineno)//': ColumnDef = '''//value// &
                          ''' names no X and Y column')
                return
              end if
            end select
          end if
          cycle
        end if
      end if
      line = adjustl(line)
      if (len_trim(line) == 0) cycle
      call numbers_of(line, v, k)
      if (k < max(ix, iy)) then
        call fail(status, exit_bad_input, source//' line '//itoa(lineno)//': '''//trim(line(1:min(len(line), 40)))// &
                  ''' is not a row of '//itoa(max(ix, iy))//' numbers (MiniProf data: X Y [A ...] after the header '// &
                  'and its blank line)')
        return
      end if
      if (n >= max_points) then
        call fail(status, exit_bad_input, source//': more than '//itoa(max_points)//' points')
        return
      end if
      call push(y, z, lines, n, v(ix) + xoff, -(v(iy) + yoff), lineno)
    end do
    y = y(1:n)
    z = z(1:n)
    lines = lines(1:n)
    ! MiniProf's vertical axis points up on most files (hence z = -Y), but not on
    ! all (avg_wheel.whl): as CONTACT, decide by the side faces, which run from
    ! the running surface into the body: down (larger z) at a rail's ends, up
    ! (smaller z) at a wheel's
    if (n >= 4) then
      if ((z(1) + z(n) > 2 * sum(z) / n) .eqv. is_wheel) z = -z
    end if
    return
900 call fail(status, exit_bad_input, source//' line '//itoa(lineno)//': '''//trim(line)//''' (a number expected)')
  end subroutine parse_miniprof

  !> SIMPACK .prw/.prr: header type, processing keys, points.
  subroutine parse_simpack(text, source, is_wheel, y, z, lines, status)
    character(len=*), intent(in) :: text, source
    logical, intent(in) :: is_wheel
    real(real64), allocatable, intent(out) :: y(:), z(:)
    integer, allocatable, intent(out) :: lines(:)
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: line, key, value
    real(real64) :: v(3), dist_min, shift(2), rotate, bound(4), len_f, ang_f, c, s, t
    integer :: pos, n, lineno, k, eq, ios, ptype, mirror(2), inversion
    logical :: eof, in_points, seen_begin, seen_end
    logical, allocatable :: inside(:)
    real(real64), allocatable :: yk(:), zk(:)
    integer, allocatable :: lk(:)
    allocate (y(64), z(64), lines(64))
    n = 0
    pos = 1
    lineno = 0
    ptype = -1
    dist_min = 0
    shift = 0
    rotate = 0
    bound = [1, 0, 1, 0]
    mirror = 0
    inversion = 0
    len_f = 1000
    ang_f = 1
    in_points = .false.
    seen_begin = .false.
    seen_end = .false.
    do
      call next_line(text, pos, line, eof)
      if (eof) exit
      lineno = lineno + 1
      k = index(line, '!')
      if (k > 0) line = line(1:k - 1)
      line = trim(adjustl(line))
      if (len(line) == 0) cycle
      if (lower(line) == 'point.begin') then
        in_points = .true.
        seen_begin = .true.
        cycle
      end if
      if (lower(line) == 'point.end') then
        in_points = .false.
        seen_end = .true.
        cycle
      end if
      if (in_points) then
        call numbers_of(line, v, k)
        if (k < 2) then
          call fail(status, exit_bad_input, source//' line '//itoa(lineno)//': '''//line(1:min(len(line), 40))// &
                    ''' is not a point y z [weight] (between point.begin and point.end)')
          return
        end if
        if (n >= max_points) then
          call fail(status, exit_bad_input, source//': more than '//itoa(max_points)//' points')
          return
        end if
        call push(y, z, lines, n, v(1), v(2), lineno)
        cycle
      end if
      eq = index(line, '=')
      if (eq == 0) cycle                       ! header.begin, spline.begin, ...
      key = lower(trim(line(1:eq - 1)))
      value = trim(adjustl(line(eq + 1:)))
      select case (key)
      case ('type', 'point.dist.min', 'shift.y', 'shift.z', 'rotate', 'bound.y.min', 'bound.y.max', 'bound.z.min', &
            'bound.z.max', 'mirror.y', 'mirror.z', 'units.len.f', 'units.ang.f', 'inversion')
        read (value, *, iostat=ios) t
        if (ios /= 0 .or. .not. abs(t) < 1e30_real64) then
          call fail(status, exit_bad_input, source//' line '//itoa(lineno)//': '//key//' = '''//value// &
                    ''' (a number expected)')
          return
        end if
      case default
        cycle
      end select
      select case (key)
      case ('type')
        ! the first 'type' is the header's (0 rail, 1 wheel); the spline's is the data file's
        if (ptype < 0) ptype = nint(t)
      case ('point.dist.min')
        dist_min = t
      case ('shift.y')
        shift(1) = t
      case ('shift.z')
        shift(2) = t
      case ('rotate')
        rotate = t
      case ('bound.y.min')
        bound(1) = t
      case ('bound.y.max')
        bound(2) = t
      case ('bound.z.min')
        bound(3) = t
      case ('bound.z.max')
        bound(4) = t
      case ('mirror.y')
        mirror(1) = nint(t)
      case ('mirror.z')
        mirror(2) = nint(t)
      case ('units.len.f')
        len_f = t
      case ('units.ang.f')
        ang_f = t
      case ('inversion')
        inversion = nint(t)
      end select
    end do
    if (.not. seen_begin .or. .not. seen_end) then
      call fail(status, exit_bad_input, source//': no point.begin ... point.end block (not a SIMPACK profile)')
      return
    end if
    if (ptype == 1 .neqv. is_wheel) then
      call fail(status, exit_bad_input, source//': header type = '//itoa(ptype)//' is a '// &
                trim(merge('wheel', 'rail ', ptype == 1))//' profile (type 0 rail, 1 wheel; a '// &
                trim(merge('wheel', 'rail ', is_wheel))//' profile is needed here)')
      return
    end if
    if (.not. (len_f > 0 .and. ang_f > 0)) then
      call fail(status, exit_bad_input, source//': units.len.f, units.ang.f = '//rtoa(len_f)//', '//rtoa(ang_f)// &
                ' (must be > 0)')
      return
    end if
    y = y(1:n)
    z = z(1:n)
    lines = lines(1:n)
    ! 1: drop points closer than point.dist.min to the last one kept
    if (dist_min > 0 .and. n > 0) then
      allocate (yk(n), zk(n), lk(n))
      yk(1) = y(1)
      zk(1) = z(1)
      lk(1) = lines(1)
      k = 1
      do eq = 2, n
        if (hypot(y(eq) - yk(k), z(eq) - zk(k)) >= dist_min) then
          k = k + 1
          yk(k) = y(eq)
          zk(k) = z(eq)
          lk(k) = lines(eq)
        end if
      end do
      y = yk(1:k)
      z = zk(1:k)
      lines = lk(1:k)
    end if
    ! 2: shift, 3: rotate about x
    y = y + shift(1)
    z = z + shift(2)
    if (rotate /= 0) then
      c = cos(rotate / ang_f)
      s = sin(rotate / ang_f)
      yk = c * y - s * z
      zk = s * y + c * z
      y = yk
      z = zk
    end if
    ! 4: bounds (min > max: no bound)
    allocate (inside(size(y)))
    inside = .true.
    if (bound(1) <= bound(2)) inside = inside .and. y >= bound(1) .and. y <= bound(2)
    if (bound(3) <= bound(4)) inside = inside .and. z >= bound(3) .and. z <= bound(4)
    y = pack(y, inside)
    z = pack(z, inside)
    lines = pack(lines, inside)
    ! 5: mirroring, 7: units (to mm), 6: order
    if (mirror(1) == 1) y = -y
    if (mirror(2) == 1) z = -z
    y = y * (1000 / len_f)
    z = z * (1000 / len_f)
    if (inversion == 1) then
      y = y(size(y):1:-1)
      z = z(size(z):1:-1)
      lines = lines(size(lines):1:-1)
    end if
  end subroutine parse_simpack

end module kcreep_profile_file
