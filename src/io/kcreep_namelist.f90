!> The namelist input: reading, defaults and validation.
!>
!> Groups &patch, &material, &solver, &output, each optional. Anything out of
!> range or inconsistent is reported through status with the file, group,
!> variable, value and what is allowed, before any computation or output.
module kcreep_namelist
  use, intrinsic :: iso_fortran_env, only: real64, iostat_end
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, lower, resolve_path, folder_of
  use kcreep_patch, only: patch_t, ellipse_patch, mask_patch
  use kcreep_mask_file, only: read_mask_file, parse_mask_rows
  use kcreep_assembly, only: scheme_t, load_case_names, n_load_cases
  use kcreep_contact_reader, only: contact_case_t, read_contact_case, combined_material
  use kcreep_contact_compare, only: contact_spin_shift
  use kcreep_file_checks, only: read_input_file
  use kcreep_namelist_scan, only: scan_namelist_text
  use kcreep_limits, only: check_grid_size, length_in_range, offset_in_range, modulus_in_range
  use kcreep_solver_options, only: solver_options_t, validate_solver_options
  use kcreep_dense, only: refine_modes
  use kcreep_problem, only: problem_t
  implicit none
  private
  public :: config_t, read_config, build_patch, problem_of, max_inline_rows, max_row_length

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
    logical :: x0_given = .false., y0_given = .false.   !< x0, y0 written in the namelist
    character(len=:), allocatable :: contact_file   !< shape 'contact': CONTACT .out file
    integer :: contact_case = 0
    type(contact_case_t) :: contact                 !< what was read from it
    ! &material
    real(real64) :: g = 1, nu = 0.25_real64
    ! &solver
    type(scheme_t) :: scheme
    logical :: requested(n_load_cases) = .true.
    logical :: extrapolate = .false.            !< Richardson in the mesh size (mesh_extrapolation)
    integer :: extrapolate_levels = 3, refine_ratio = 2
    character(len=:), allocatable :: refine     !< see dense_solver refine_modes
    type(solver_options_t) :: solve           !< method, tolerance, splits
    character(len=:), allocatable :: spin_centre   !< 'origin', 'centroid' or 'point'
    real(real64) :: spin_centre_xy(2) = 0          !< the point of spin_centre = 'point'
    ! &output
    character(len=:), allocatable :: table_file, traction_file
  end type config_t

contains

  !> Read and validate the namelist at path. Relative file names inside it
  !> (mask_file, contact_file, table_file, traction_file) are taken relative
  !> to the namelist's own folder, whatever the working folder and the mode
  !> (single run, batch, memory estimate). Only the default table, which the
  !> namelist does not name, goes to the working folder.
  subroutine read_config(path, cfg, status)
    character(len=*), intent(in) :: path
    type(config_t), intent(out) :: cfg
    type(status_t), intent(inout) :: status

    ! namelist variables, with their defaults
    character(len=32) :: shape, scheme, method, refine, spin_centre
    real(real64) :: spin_centre_x, spin_centre_y
    real(real64) :: semi_a, semi_b, dx, dy, x0, y0, g, nu, alpha, spin_shift, tolerance
    integer :: mx, my, extrapolate_levels, refine_ratio, max_iterations, restart
    logical :: extrapolate, split_systems
    character(len=4096) :: mask_file, table_file, traction_file
    character(len=64) :: load_cases
    character(len=max_row_length), allocatable :: mask_rows(:)
    character(len=4096) :: contact_file
    integer :: contact_case
    !> "not given": g, nu and spin_shift default differently for shape = 'contact',
    !> and a value the user wrote is either used or refused, never replaced
    real(real64), parameter :: unset = -huge(1.0_real64)
    integer, parameter :: unset_int = -huge(1)
    character(len=:), allocatable :: where
    logical :: material_given
    namelist /patch/ shape, semi_a, semi_b, mx, my, mask_file, mask_rows, dx, dy, x0, y0, contact_file, contact_case
    namelist /material/ g, nu
    namelist /solver/ scheme, alpha, spin_shift, load_cases, extrapolate, extrapolate_levels, refine_ratio, refine, &
                      method, tolerance, max_iterations, restart, split_systems, spin_centre, spin_centre_x, &
                      spin_centre_y
    namelist /output/ table_file, traction_file

    integer :: unit, ios, nrows
    logical :: group_present(size(group_names)), group_closed(size(group_names)), last_line_open
    character(len=512) :: msg
    character(len=:), allocatable :: text

    shape = 'ellipse'
    semi_a = unset
    semi_b = unset
    mx = unset_int
    my = unset_int
    mask_file = ''
    allocate (mask_rows(max_inline_rows))
    mask_rows = ''
    dx = 0
    dy = 0
    x0 = unset
    y0 = unset
    contact_file = ''
    contact_case = 1
    g = unset
    nu = unset
    scheme = ''
    alpha = unset
    spin_shift = unset
    load_cases = 'xi eta phi'
    spin_centre = 'origin'
    spin_centre_x = unset
    spin_centre_y = unset
    extrapolate = .false.
    extrapolate_levels = 3
    refine_ratio = 2
    refine = 'auto'
    method = 'auto'
    tolerance = cfg%solve%tolerance
    max_iterations = cfg%solve%max_iterations
    restart = cfg%solve%restart
    split_systems = cfg%solve%split_systems
    table_file = ''
    traction_file = ''

    cfg%input_path = path
    ! the whole file first: a folder, a binary file, text outside the groups,
    ! unknown or repeated groups are errors the namelist read would not report
    call read_input_file(path, 'input '''//path//'''', text, status)
    if (.not. status%failed()) call scan_namelist_text(text, 'input '''//path//'''', group_names, group_present, &
                                                       group_closed, status)
    if (status%failed()) return
    ! a last line without its newline: the namelist read assigns the group and
    ! then meets the end of the file looking for the next record
    last_line_open = .false.
    if (len(text) > 0) last_line_open = text(len(text):len(text)) /= achar(10)
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_bad_input, 'input '''//path//''': cannot open ('//trim(msg)//')')
      return
    end if

    rewind (unit)
    if (group_present(1)) read (unit, nml=patch, iostat=ios, iomsg=msg)
    call check_read('patch', 1)
    rewind (unit)
    if (group_present(2)) read (unit, nml=material, iostat=ios, iomsg=msg)
    call check_read('material', 2)
    rewind (unit)
    if (group_present(3)) read (unit, nml=solver, iostat=ios, iomsg=msg)
    call check_read('solver', 3)
    rewind (unit)
    if (group_present(4)) read (unit, nml=output, iostat=ios, iomsg=msg)
    call check_read('output', 4)
    close (unit)
    if (status%failed()) return

    cfg%shape = lower(trim(adjustl(shape)))
    ! shape = 'contact' follows CONTACT's conventions unless &solver says otherwise
    if (len_trim(scheme) == 0) scheme = merge('backward   ', 'collocation', cfg%shape == 'contact')
    ! values written that the case would not use: refused, not ignored
    where = 'input '''//path//''': '
    if (mx /= unset_int .and. mx < 1) call fail(status, exit_bad_input, where//'&patch mx = '//itoa(mx)// &
        ' (must be >= 1; leave mx out for the default)')
    if (my /= unset_int .and. my < 1) call fail(status, exit_bad_input, where//'&patch my = '//itoa(my)// &
        ' (must be >= 1; leave my out for the default)')
    if (lower(trim(adjustl(scheme))) == 'collocation' .and. spin_shift /= unset) call fail(status, exit_bad_input, &
        where//'&solver spin_shift = '//rtoa(spin_shift)//' is not used by scheme = ''collocation'' '// &
        '(it moves the spin creepage of the backward scheme; leave it out or set scheme = ''backward'')')
    if (lower(trim(adjustl(scheme))) == 'backward' .and. alpha /= unset) call fail(status, exit_bad_input, &
        where//'&solver alpha = '//rtoa(alpha)//' is not used by scheme = ''backward'' '// &
        '(it is the collocation point of scheme = ''collocation''; leave it out or change the scheme)')
    if (cfg%shape /= 'ellipse' .and. semi_a /= unset) call fail(status, exit_bad_input, where// &
        '&patch semi_a = '//rtoa(semi_a)//' is only used by shape = ''ellipse'' (shape = '''//cfg%shape// &
        '''; leave it out)')
    if (cfg%shape /= 'ellipse' .and. semi_b /= unset) call fail(status, exit_bad_input, where// &
        '&patch semi_b = '//rtoa(semi_b)//' is only used by shape = ''ellipse'' (shape = '''//cfg%shape// &
        '''; leave it out)')
    cfg%spin_centre = lower(trim(adjustl(spin_centre)))
    select case (cfg%spin_centre)
    case ('origin', 'centroid')
      if (spin_centre_x /= unset .or. spin_centre_y /= unset) call fail(status, exit_bad_input, where// &
          '&solver spin_centre_x, spin_centre_y are only used by spin_centre = ''point'' (spin_centre = '''// &
          cfg%spin_centre//''')')
    case ('point')
      if (spin_centre_x == unset .or. spin_centre_y == unset) call fail(status, exit_bad_input, where// &
          '&solver spin_centre = ''point'' needs both spin_centre_x and spin_centre_y')
      if (.not. (offset_in_range(spin_centre_x) .and. offset_in_range(spin_centre_y))) &
        call fail(status, exit_bad_input, where//'&solver spin_centre_x, spin_centre_y = '// &
                  rtoa(spin_centre_x)//', '//rtoa(spin_centre_y)//' (allowed: 0 or 1e-30 <= |x|, |y| <= 1e30)')
      cfg%spin_centre_xy = [spin_centre_x, spin_centre_y]
    case default
      call fail(status, exit_bad_input, where//'&solver spin_centre = '''//cfg%spin_centre// &
                ''' (allowed: ''origin'', ''centroid'', ''point'' with spin_centre_x, spin_centre_y)')
    end select
    if (status%failed()) return
    if (mx == unset_int) mx = 0        ! 0 from here on: not given
    if (my == unset_int) my = 0
    if (semi_a == unset) semi_a = 1
    if (semi_b == unset) semi_b = 1
    if (alpha == unset) alpha = 0.5_real64
    cfg%x0_given = x0 /= unset
    cfg%y0_given = y0 /= unset
    if (x0 == unset) x0 = 0
    if (y0 == unset) y0 = 0
    if (spin_shift == unset) spin_shift = merge(contact_spin_shift, 0.0_real64, cfg%shape == 'contact')
    material_given = g /= unset .or. nu /= unset
    if (g == unset) g = 1
    if (nu == unset) nu = 0.25_real64
    cfg%contact_file = trim(contact_file)
    cfg%contact_case = contact_case
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
    cfg%extrapolate = extrapolate
    cfg%extrapolate_levels = extrapolate_levels
    cfg%refine_ratio = refine_ratio
    cfg%refine = lower(trim(adjustl(refine)))
    cfg%solve%method = lower(trim(adjustl(method)))
    cfg%solve%tolerance = tolerance
    cfg%solve%max_iterations = max_iterations
    cfg%solve%restart = restart
    cfg%solve%split_systems = split_systems
    cfg%table_file = resolve_path(trim(table_file), folder_of(path))
    if (len(cfg%table_file) == 0) cfg%table_file = default_table_name(path)
    cfg%traction_file = resolve_path(trim(traction_file), folder_of(path))
    cfg%mask_file = resolve_path(cfg%mask_file, folder_of(path))
    cfg%contact_file = resolve_path(cfg%contact_file, folder_of(path))

    call validate(cfg, mask_rows, nrows, load_cases, status)
    if (cfg%shape == 'contact' .and. .not. status%failed()) call load_contact_case(cfg, material_given, status)

  contains

    subroutine check_read(group, k)
      character(len=*), intent(in) :: group
      integer, intent(in) :: k
      if (.not. group_present(k) .or. status%failed()) return
      if (ios == iostat_end .and. group_closed(k) .and. last_line_open) then
        ios = 0                           ! read whole: its / was there, the newline after it was not
      else if (ios == iostat_end) then
        call fail(status, exit_bad_input, 'input '''//path//''': namelist &'//group// &
                  ': end of file before the closing /')
      else if (ios /= 0) then
        call fail(status, exit_bad_input, 'input '''//path//''': namelist &'//group//': '//trim(msg))
      end if
    end subroutine check_read

  end subroutine read_config

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
      if (.not. length_in_range(cfg%semi_a)) call fail(status, exit_bad_input, where// &
          '&patch semi_a = '//rtoa(cfg%semi_a)//' (must be > 0, between 1e-30 and 1e30)')
      if (.not. length_in_range(cfg%semi_b)) call fail(status, exit_bad_input, where// &
          '&patch semi_b = '//rtoa(cfg%semi_b)//' (must be > 0, between 1e-30 and 1e30)')
      if (cfg%mx == 0) cfg%mx = default_cells
      if (cfg%my == 0) cfg%my = default_cells
      if (cfg%mx < 1) call fail(status, exit_bad_input, where//'&patch mx = '//itoa(cfg%mx)//' (must be >= 1)')
      if (cfg%my < 1) call fail(status, exit_bad_input, where//'&patch my = '//itoa(cfg%my)//' (must be >= 1)')
      call check_grid_size(cfg%mx, cfg%my, where//'&patch mx, my: ', status)
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
        if (.not. length_in_range(cfg%dx)) call fail(status, exit_bad_input, where// &
            '&patch dx = '//rtoa(cfg%dx)//' (an inline mask needs a cell size > 0, between 1e-30 and 1e30)')
        if (.not. length_in_range(cfg%dy)) call fail(status, exit_bad_input, where// &
            '&patch dy = '//rtoa(cfg%dy)//' (an inline mask needs a cell size > 0, between 1e-30 and 1e30)')
        if (cfg%mx /= 0 .and. cfg%mx /= len_trim(mask_rows(1))) call fail(status, exit_bad_input, where// &
            '&patch mx = '//itoa(cfg%mx)//' but mask row 1 has '//itoa(len_trim(mask_rows(1)))//' cells')
        if (cfg%my /= 0 .and. cfg%my /= nrows) call fail(status, exit_bad_input, where// &
            '&patch my = '//itoa(cfg%my)//' but mask_rows has '//itoa(nrows)//' rows')
      else
        if (cfg%dx < 0 .or. cfg%dy < 0) call fail(status, exit_bad_input, where// &
            '&patch dx, dy = '//rtoa(cfg%dx)//', '//rtoa(cfg%dy)//' (cell sizes must be > 0; the mask file header gives them)')
      end if
      if (.not. (offset_in_range(cfg%x0) .and. offset_in_range(cfg%y0))) &
        call fail(status, exit_bad_input, where//'&patch x0, y0 = '//rtoa(cfg%x0)//', '//rtoa(cfg%y0)// &
                  ' (allowed: 0 or 1e-30 <= |x0|, |y0| <= 1e30)')
    case ('contact')
      if (len(cfg%contact_file) == 0) call fail(status, exit_bad_input, where// &
          '&patch shape = ''contact'' needs contact_file (a CONTACT .out file)')
      if (cfg%contact_case < 1) call fail(status, exit_bad_input, where//'&patch contact_case = '// &
          itoa(cfg%contact_case)//' (must be >= 1)')
      if (len(cfg%mask_file) > 0 .or. nrows > 0 .or. cfg%mx /= 0 .or. cfg%my /= 0 .or. cfg%dx /= 0 .or. &
          cfg%dy /= 0 .or. cfg%x0_given .or. cfg%y0_given) call fail(status, exit_bad_input, where// &
          '&patch shape = ''contact'' takes its grid and mask from contact_file (leave out mask_file, '// &
          'mask_rows, mx, my, dx, dy, x0, y0)')
    case default
      call fail(status, exit_bad_input, where//'&patch shape = '''//cfg%shape// &
                ''' (allowed: ''ellipse'', ''mask'', ''contact'')')
    end select

    if (.not. modulus_in_range(cfg%g)) call fail(status, exit_bad_input, where// &
        '&material g = '//rtoa(cfg%g)//' (must be > 0, between 1e-100 and 1e100)')
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
    if (cfg%extrapolate .and. (cfg%extrapolate_levels < 2 .or. cfg%extrapolate_levels > 3)) &
      call fail(status, exit_bad_input, where//'&solver extrapolate_levels = '//itoa(cfg%extrapolate_levels)// &
                ' (allowed: 2 or 3)')
    if (cfg%extrapolate .and. (cfg%refine_ratio < 2 .or. cfg%refine_ratio > 4)) &
      call fail(status, exit_bad_input, where//'&solver refine_ratio = '//itoa(cfg%refine_ratio)// &
                ' (allowed: 2, 3 or 4; every level multiplies the cells per direction by it)')
    if (findloc(refine_modes, cfg%refine, dim=1) == 0) &
      call fail(status, exit_bad_input, where//'&solver refine = '''//cfg%refine// &
                ''' (allowed: ''auto'', ''always'', ''never'', ''lapack'')')
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
        if ((cfg%x0_given .and. cfg%x0 /= patch%x0) .or. (cfg%y0_given .and. cfg%y0 /= patch%y0)) &
          call fail(status, exit_bad_input, 'input '''//cfg%input_path//''': &patch x0, y0 = '// &
                    rtoa(cfg%x0)//', '//rtoa(cfg%y0)//' disagree with the header of mask_file '''// &
                    cfg%mask_file//''' ('//rtoa(patch%x0)//', '//rtoa(patch%y0)//'; leave them out)')
      else
        call parse_mask_rows(cfg%mask_rows, where, inside, status)
        if (status%failed()) return
        call mask_patch(inside, cfg%dx, cfg%dy, cfg%x0, cfg%y0, where, patch, status)
      end if
    case ('contact')
      ! CONTACT's grid: corner (XL, YL), so the first cell centre is half a cell in
      call mask_patch(cfg%contact%inside, cfg%contact%dx, cfg%contact%dy, cfg%contact%xl + cfg%contact%dx / 2, &
                      cfg%contact%yl + cfg%contact%dy / 2, 'contact_file '''//cfg%contact_file//'''', patch, status)
      patch%kind = 'contact'
    end select
  end subroutine build_patch

  !> shape = 'contact': grid, mask and material of case contact_case of contact_file.
  !> A material in &material is refused rather than silently overridden: the
  !> comparison with CONTACT is only meaningful with CONTACT's own material.
  subroutine load_contact_case(cfg, material_given, status)
    type(config_t), intent(inout) :: cfg
    logical, intent(in) :: material_given
    type(status_t), intent(inout) :: status
    if (material_given) then
      call fail(status, exit_bad_input, 'input '''//cfg%input_path//''': &material g, nu are not allowed '// &
                'with &patch shape = ''contact'' (the material comes from contact_file''s GG and POISS)')
      return
    end if
    call read_contact_case(cfg%contact_file, cfg%contact_case, cfg%contact, status)
    if (status%failed()) return
    call combined_material(cfg%contact%gg, cfg%contact%poiss, cfg%g, cfg%nu)
  end subroutine load_contact_case

  !> The library's problem: the patch built from cfg and the namelist's
  !> material, scheme and solver settings.
  function problem_of(cfg, patch) result(problem)
    type(config_t), intent(in) :: cfg
    type(patch_t), intent(in) :: patch
    type(problem_t) :: problem
    problem%patch = patch
    problem%g = cfg%g
    problem%nu = cfg%nu
    problem%scheme = cfg%scheme
    problem%solve = cfg%solve
    problem%requested = cfg%requested
    problem%refine = cfg%refine
    problem%extrapolate = cfg%extrapolate
    problem%extrapolate_levels = cfg%extrapolate_levels
    problem%refine_ratio = cfg%refine_ratio
    select case (cfg%spin_centre)
    case ('centroid')
      problem%spin_centre = patch%centroid()
    case ('point')
      problem%spin_centre = cfg%spin_centre_xy
    case default
      problem%spin_centre = 0
    end select
  end function problem_of

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

end module kcreep_namelist
