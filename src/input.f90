!> The namelist input: reading, defaults and validation.
!>
!> Groups &patch, &material, &solver, &output, each optional. Anything out of
!> range or inconsistent is reported through status with the file, group,
!> variable, value and what is allowed, before any computation or output.
module namelist_input
  use, intrinsic :: iso_fortran_env, only: real64, iostat_end
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, lower
  use patch_grid, only: patch_t, ellipse_patch, mask_patch, read_mask_file, parse_mask_rows
  use tang_assembly, only: scheme_t, load_case_names, n_load_cases
  use solver_options, only: solver_options_t, validate_solver_options
  implicit none
  private
  public :: config_t, read_config, build_patch, max_inline_rows, max_row_length

  integer, parameter :: max_inline_rows = 2048, max_row_length = 2048
  integer, parameter :: default_cells = 60
  character(len=*), parameter :: group_names(4) = [character(len=8) :: 'patch', 'material', 'solver', 'output']

  type :: config_t
    character(len=:), allocatable :: input_path
    ! &patch
    character(len=:), allocatable :: shape
    real(real64) :: semi_a = 1, semi_b = 1
    integer :: mx = 0, my = 0                   !< 0: not given
    character(len=:), allocatable :: mask_file
    character(len=max_row_length), allocatable :: mask_rows(:)   !< inline rows given
    real(real64) :: dx = 0, dy = 0, x0 = 0, y0 = 0
    ! &material
    real(real64) :: g = 1, nu = 0.25_real64
    ! &solver
    type(scheme_t) :: scheme
    logical :: requested(n_load_cases) = .true.
    type(solver_options_t) :: solve           !< method, tolerance, splits
    ! &output
    character(len=:), allocatable :: table_file, traction_file
  end type config_t

contains

  subroutine read_config(path, cfg, status)
    character(len=*), intent(in) :: path
    type(config_t), intent(out) :: cfg
    type(status_t), intent(inout) :: status

    ! namelist variables, with their defaults
    character(len=32) :: shape, scheme, method
    real(real64) :: semi_a, semi_b, dx, dy, x0, y0, g, nu, alpha, spin_shift, tolerance
    integer :: mx, my, max_iterations, restart
    logical :: split_systems
    character(len=4096) :: mask_file, table_file, traction_file
    character(len=64) :: load_cases
    character(len=max_row_length), allocatable :: mask_rows(:)
    namelist /patch/ shape, semi_a, semi_b, mx, my, mask_file, mask_rows, dx, dy, x0, y0
    namelist /material/ g, nu
    namelist /solver/ scheme, alpha, spin_shift, load_cases, method, tolerance, max_iterations, restart, &
                      split_systems
    namelist /output/ table_file, traction_file

    integer :: unit, ios, nrows
    logical :: present(size(group_names))
    character(len=512) :: msg

    shape = 'ellipse'
    semi_a = 1
    semi_b = 1
    mx = 0
    my = 0
    mask_file = ''
    allocate (mask_rows(max_inline_rows))
    mask_rows = ''
    dx = 0
    dy = 0
    x0 = 0
    y0 = 0
    g = 1
    nu = 0.25_real64
    scheme = 'collocation'
    alpha = 0.5_real64
    spin_shift = 0
    load_cases = 'xi eta phi'
    method = 'auto'
    tolerance = cfg%solve%tolerance
    max_iterations = cfg%solve%max_iterations
    restart = cfg%solve%restart
    split_systems = cfg%solve%split_systems
    table_file = ''
    traction_file = ''

    cfg%input_path = path
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_bad_input, 'input '''//path//''': cannot open ('//trim(msg)//')')
      return
    end if
    call scan_groups(unit, path, present, status)
    if (status%failed()) then
      close (unit)
      return
    end if

    rewind (unit)
    if (present(1)) read (unit, nml=patch, iostat=ios, iomsg=msg)
    call check_read('patch', present(1))
    rewind (unit)
    if (present(2)) read (unit, nml=material, iostat=ios, iomsg=msg)
    call check_read('material', present(2))
    rewind (unit)
    if (present(3)) read (unit, nml=solver, iostat=ios, iomsg=msg)
    call check_read('solver', present(3))
    rewind (unit)
    if (present(4)) read (unit, nml=output, iostat=ios, iomsg=msg)
    call check_read('output', present(4))
    close (unit)
    if (status%failed()) return

    cfg%shape = lower(trim(adjustl(shape)))
    cfg%semi_a = semi_a
    cfg%semi_b = semi_b
    cfg%mx = mx
    cfg%my = my
    cfg%mask_file = trim(mask_file)
    nrows = count_rows(mask_rows)
    cfg%mask_rows = mask_rows(1:nrows)
    cfg%dx = dx
    cfg%dy = dy
    cfg%x0 = x0
    cfg%y0 = y0
    cfg%g = g
    cfg%nu = nu
    cfg%scheme%name = lower(trim(adjustl(scheme)))
    cfg%scheme%alpha = alpha
    cfg%scheme%spin_shift = spin_shift
    cfg%solve%method = lower(trim(adjustl(method)))
    cfg%solve%tolerance = tolerance
    cfg%solve%max_iterations = max_iterations
    cfg%solve%restart = restart
    cfg%solve%split_systems = split_systems
    cfg%table_file = trim(table_file)
    if (len(cfg%table_file) == 0) cfg%table_file = default_table_name(path)
    cfg%traction_file = trim(traction_file)

    call validate(cfg, mask_rows, nrows, load_cases, status)

  contains

    subroutine check_read(group, was_present)
      character(len=*), intent(in) :: group
      logical, intent(in) :: was_present
      if (.not. was_present .or. status%failed()) return
      if (ios == iostat_end) then
        call fail(status, exit_bad_input, 'input '''//path//''': namelist &'//group// &
                  ': end of file before the closing /')
      else if (ios /= 0) then
        call fail(status, exit_bad_input, 'input '''//path//''': namelist &'//group//': '//trim(msg))
      end if
    end subroutine check_read

  end subroutine read_config

  !> Which known groups the file holds; any other '&name' is an error (a
  !> misspelt group would otherwise be skipped in silence).
  subroutine scan_groups(unit, path, present, status)
    integer, intent(in) :: unit
    character(len=*), intent(in) :: path
    logical, intent(out) :: present(:)
    type(status_t), intent(inout) :: status
    character(len=256) :: line, word
    integer :: ios, k, line_no, first, last

    present = .false.
    line_no = 0
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      line_no = line_no + 1
      line = adjustl(line)
      if (line(1:1) /= '&') cycle
      first = 2
      last = scan(line(first:), ' /,'//achar(9)) + first - 2
      if (last < first) last = len_trim(line)
      word = lower(line(first:last))
      if (trim(word) == 'end') cycle
      k = findloc(group_names, trim(word), dim=1)
      if (k == 0) then
        call fail(status, exit_bad_input, 'input '''//path//''', line '//itoa(line_no)// &
                  ': unknown namelist group &'//trim(word)//' (known: &patch, &material, &solver, &output)')
        return
      end if
      present(k) = .true.
    end do
    if (.not. is_iostat_end(ios)) then
      call fail(status, exit_bad_input, 'input '''//path//''': cannot be read as text')
    end if
  end subroutine scan_groups

  !> Number of inline mask rows given: up to the last non-blank one.
  pure integer function count_rows(rows) result(nrows)
    character(len=*), intent(in) :: rows(:)
    nrows = size(rows)
    do while (nrows > 0)
      if (len_trim(rows(nrows)) > 0) exit
      nrows = nrows - 1
    end do
  end function count_rows

  subroutine validate(cfg, mask_rows, nrows, load_cases, status)
    type(config_t), intent(inout) :: cfg
    character(len=*), intent(in) :: mask_rows(:)
    integer, intent(in) :: nrows
    character(len=*), intent(in) :: load_cases
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: where

    where = 'input '''//cfg%input_path//''': '
    select case (cfg%shape)
    case ('ellipse')
      if (.not. positive_finite(cfg%semi_a)) call fail(status, exit_bad_input, where// &
          '&patch semi_a = '//rtoa(cfg%semi_a)//' (must be > 0 and finite)')
      if (.not. positive_finite(cfg%semi_b)) call fail(status, exit_bad_input, where// &
          '&patch semi_b = '//rtoa(cfg%semi_b)//' (must be > 0 and finite)')
      if (cfg%mx == 0) cfg%mx = default_cells
      if (cfg%my == 0) cfg%my = default_cells
      if (cfg%mx < 1) call fail(status, exit_bad_input, where//'&patch mx = '//itoa(cfg%mx)//' (must be >= 1)')
      if (cfg%my < 1) call fail(status, exit_bad_input, where//'&patch my = '//itoa(cfg%my)//' (must be >= 1)')
      if (len(cfg%mask_file) > 0 .or. nrows > 0) call fail(status, exit_bad_input, where// &
          '&patch shape = ''ellipse'' takes no mask_file or mask_rows (use shape = ''mask'')')
    case ('mask')
      if (len(cfg%mask_file) > 0 .and. nrows > 0) then
        call fail(status, exit_bad_input, where//'&patch: give mask_file or mask_rows, not both')
      else if (len(cfg%mask_file) == 0 .and. nrows == 0) then
        call fail(status, exit_bad_input, where//'&patch shape = ''mask'' needs mask_file or mask_rows')
      end if
      if (nrows > 0) then
        if (any(len_trim(mask_rows(1:nrows)) == len(mask_rows))) call fail(status, exit_bad_input, where// &
            '&patch mask_rows: a row is longer than '//itoa(len(mask_rows) - 1)//' cells (use mask_file)')
        if (nrows == size(mask_rows)) call fail(status, exit_bad_input, where// &
            '&patch mask_rows: more than '//itoa(size(mask_rows) - 1)//' rows (use mask_file)')
        if (.not. positive_finite(cfg%dx)) call fail(status, exit_bad_input, where// &
            '&patch dx = '//rtoa(cfg%dx)//' (an inline mask needs a cell size > 0)')
        if (.not. positive_finite(cfg%dy)) call fail(status, exit_bad_input, where// &
            '&patch dy = '//rtoa(cfg%dy)//' (an inline mask needs a cell size > 0)')
        if (cfg%mx /= 0 .and. cfg%mx /= len_trim(mask_rows(1))) call fail(status, exit_bad_input, where// &
            '&patch mx = '//itoa(cfg%mx)//' but mask row 1 has '//itoa(len_trim(mask_rows(1)))//' cells')
        if (cfg%my /= 0 .and. cfg%my /= nrows) call fail(status, exit_bad_input, where// &
            '&patch my = '//itoa(cfg%my)//' but mask_rows has '//itoa(nrows)//' rows')
      else
        if (cfg%dx < 0 .or. cfg%dy < 0) call fail(status, exit_bad_input, where// &
            '&patch dx, dy = '//rtoa(cfg%dx)//', '//rtoa(cfg%dy)//' (cell sizes must be > 0; the mask file header gives them)')
      end if
      if (.not. (abs(cfg%x0) <= huge(1.0_real64) .and. abs(cfg%y0) <= huge(1.0_real64))) &
        call fail(status, exit_bad_input, where//'&patch x0, y0 must be finite')
    case default
      call fail(status, exit_bad_input, where//'&patch shape = '''//cfg%shape// &
                ''' (allowed: ''ellipse'', ''mask'')')
    end select

    if (.not. positive_finite(cfg%g)) call fail(status, exit_bad_input, where// &
        '&material g = '//rtoa(cfg%g)//' (must be > 0 and finite)')
    if (.not. (cfg%nu >= 0 .and. cfg%nu <= 0.5_real64)) call fail(status, exit_bad_input, where// &
        '&material nu = '//rtoa(cfg%nu)//' (allowed: 0 <= nu <= 0.5)')

    select case (cfg%scheme%name)
    case ('collocation', 'backward')
    case default
      call fail(status, exit_bad_input, where//'&solver scheme = '''//cfg%scheme%name// &
                ''' (allowed: ''collocation'', ''backward'')')
    end select
    if (.not. (abs(cfg%scheme%alpha) < 1)) call fail(status, exit_bad_input, where// &
        '&solver alpha = '//rtoa(cfg%scheme%alpha)//' (allowed: -1 < alpha < 1, the open interval)')
    if (.not. (abs(cfg%scheme%spin_shift) <= 1)) call fail(status, exit_bad_input, where// &
        '&solver spin_shift = '//rtoa(cfg%scheme%spin_shift)//' (allowed: -1 <= spin_shift <= 1 cell)')
    call parse_load_cases(load_cases, cfg%requested, where, status)
    call validate_solver_options(cfg%solve, where, status)
  end subroutine validate

  !> load_cases: words from xi, eta, phi separated by blanks or commas.
  subroutine parse_load_cases(text, requested, where, status)
    character(len=*), intent(in) :: text, where
    logical, intent(out) :: requested(n_load_cases)
    type(status_t), intent(inout) :: status
    character(len=len(text)) :: rest, word
    integer :: cut, k

    requested = .false.
    rest = lower(text)
    do
      rest = adjustl(rest)
      if (len_trim(rest) == 0) exit
      cut = scan(rest, ' ,')
      if (cut == 0) cut = len(rest) + 1
      word = rest(1:cut - 1)
      rest = rest(min(cut + 1, len(rest) + 1):)
      if (len_trim(word) == 0) cycle
      k = findloc(load_case_names, trim(word), dim=1)
      if (k == 0) then
        call fail(status, exit_bad_input, where//'&solver load_cases: unknown case '''//trim(word)// &
                  ''' (allowed: xi, eta, phi)')
        return
      end if
      requested(k) = .true.
    end do
    if (.not. any(requested)) call fail(status, exit_bad_input, where// &
        '&solver load_cases is empty (allowed: any of xi, eta, phi)')
  end subroutine parse_load_cases

  !> The patch the configuration describes.
  subroutine build_patch(cfg, patch, status)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(out) :: patch
    type(status_t), intent(inout) :: status
    logical, allocatable :: inside(:, :)
    character(len=:), allocatable :: where

    where = 'input '''//cfg%input_path//''': &patch mask_rows'
    select case (cfg%shape)
    case ('ellipse')
      call ellipse_patch(cfg%semi_a, cfg%semi_b, cfg%mx, cfg%my, patch, status)
    case ('mask')
      if (len(cfg%mask_file) > 0) then
        call read_mask_file(cfg%mask_file, patch, status)
        if (status%failed()) return
        if (cfg%mx /= 0 .and. cfg%mx /= patch%mx) call fail(status, exit_bad_input, 'input '''// &
            cfg%input_path//''': &patch mx = '//itoa(cfg%mx)//' but mask_file '''//cfg%mask_file// &
            ''' has mx = '//itoa(patch%mx))
        if (cfg%my /= 0 .and. cfg%my /= patch%my) call fail(status, exit_bad_input, 'input '''// &
            cfg%input_path//''': &patch my = '//itoa(cfg%my)//' but mask_file '''//cfg%mask_file// &
            ''' has my = '//itoa(patch%my))
        if ((cfg%dx /= 0 .and. cfg%dx /= patch%dx) .or. (cfg%dy /= 0 .and. cfg%dy /= patch%dy)) &
          call fail(status, exit_bad_input, 'input '''//cfg%input_path//''': &patch dx, dy = '// &
                    rtoa(cfg%dx)//', '//rtoa(cfg%dy)//' disagree with the header of mask_file '''// &
                    cfg%mask_file//''' ('//rtoa(patch%dx)//', '//rtoa(patch%dy)//'; leave them out)')
      else
        call parse_mask_rows(cfg%mask_rows, where, inside, status)
        if (status%failed()) return
        call mask_patch(inside, cfg%dx, cfg%dy, cfg%x0, cfg%y0, where, patch, status)
      end if
    end select
  end subroutine build_patch

  pure logical function positive_finite(x)
    real(real64), intent(in) :: x
    positive_finite = x > 0 .and. x <= huge(x)
  end function positive_finite

  !> '<input name without folder and extension>.tab' in the working folder.
  pure function default_table_name(path) result(name)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: name
    integer :: slash, dot
    slash = index(path, '/', back=.true.)
    name = path(slash + 1:)
    dot = index(name, '.', back=.true.)
    if (dot > 1) name = name(1:dot - 1)
    name = name//'.tab'
  end function default_table_name

end module namelist_input
