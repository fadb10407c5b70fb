!> The &patch group: the shape of the contact patch and its grid.
module kcreep_nml_patch
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, lower, resolve_path, folder_of
  use kcreep_limits, only: check_grid_size, length_in_range, offset_in_range
  use kcreep_nml_config, only: config_t, input_where, unset, unset_int, max_inline_rows, max_row_length
  use kcreep, only: nominal_ellipse_cells
  implicit none
  private
  public :: patch_variables, patch_group_t, read_patch_group, apply_patch_group

  integer, parameter :: default_cells = nominal_ellipse_cells   !< an ellipse's cells across when mx, my are left out

  !> The group as written (unset: not given).
  type :: patch_group_t
    character(len=32) :: shape = 'ellipse'
    real(real64) :: semi_a = unset, semi_b = unset, dx = 0, dy = 0, x0 = unset, y0 = unset
    integer :: mx = unset_int, my = unset_int, contact_case = 1
    character(len=4096) :: mask_file = '', contact_file = ''
    character(len=max_row_length), allocatable :: mask_rows(:)
  end type patch_group_t

  !> The group's variables and their types, as in its namelist statement
  !> (kcreep_namelist_scan diagnose_group explains a failed read with them).
  character(len=*), parameter :: patch_variables(13) = [character(len=24) :: &
    'shape character', 'semi_a real', 'semi_b real', 'mx integer', 'my integer', 'mask_file character', &
    'mask_rows character list', 'dx real', 'dy real', 'x0 real', 'y0 real', 'contact_file character', &
    'contact_case integer']

contains

  !> Read &patch from unit (positioned before it); ios, msg as from the read.
  !> rows_given: the input's text names mask_rows; only then is the space for
  !> max_inline_rows rows (4 MB) taken, not for every namelist.
  subroutine read_patch_group(unit, rows_given, grp, ios, msg)
    integer, intent(in) :: unit
    logical, intent(in) :: rows_given
    type(patch_group_t), intent(out) :: grp
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    character(len=32) :: shape
    real(real64) :: semi_a, semi_b, dx, dy, x0, y0
    integer :: mx, my, contact_case
    character(len=4096) :: mask_file, contact_file
    character(len=max_row_length), allocatable :: mask_rows(:)
    namelist /patch/ shape, semi_a, semi_b, mx, my, mask_file, mask_rows, dx, dy, x0, y0, contact_file, contact_case

    allocate (mask_rows(merge(max_inline_rows, 1, rows_given)))
    mask_rows = ''
    shape = grp%shape
    semi_a = grp%semi_a
    semi_b = grp%semi_b
    dx = grp%dx
    dy = grp%dy
    x0 = grp%x0
    y0 = grp%y0
    mx = grp%mx
    my = grp%my
    contact_case = grp%contact_case
    mask_file = grp%mask_file
    contact_file = grp%contact_file
    read (unit, nml=patch, iostat=ios, iomsg=msg)
    grp%shape = shape
    grp%semi_a = semi_a
    grp%semi_b = semi_b
    grp%dx = dx
    grp%dy = dy
    grp%x0 = x0
    grp%y0 = y0
    grp%mx = mx
    grp%my = my
    grp%contact_case = contact_case
    grp%mask_file = mask_file
    grp%contact_file = contact_file
    call move_alloc(mask_rows, grp%mask_rows)
  end subroutine read_patch_group

  !> Check &patch on its own and store it in cfg (file names relative to the
  !> namelist's folder).
  subroutine apply_patch_group(grp, cfg, status)
    type(patch_group_t), intent(in) :: grp
    type(config_t), intent(inout) :: cfg
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: where
    integer :: nrows

    where = input_where(cfg)
    cfg%shape = lower(trim(adjustl(grp%shape)))
    if (grp%mx /= unset_int .and. grp%mx < 1) call fail(status, exit_bad_input, where//'&patch mx = '// &
        itoa(grp%mx)//' (must be >= 1; leave mx out for the default)')
    if (grp%my /= unset_int .and. grp%my < 1) call fail(status, exit_bad_input, where//'&patch my = '// &
        itoa(grp%my)//' (must be >= 1; leave my out for the default)')
    if (cfg%shape /= 'ellipse' .and. grp%semi_a /= unset) call fail(status, exit_bad_input, where// &
        '&patch semi_a = '//rtoa(grp%semi_a)//' is only used by shape = ''ellipse'' (shape = '''//cfg%shape// &
        '''; leave it out)')
    if (cfg%shape /= 'ellipse' .and. grp%semi_b /= unset) call fail(status, exit_bad_input, where// &
        '&patch semi_b = '//rtoa(grp%semi_b)//' is only used by shape = ''ellipse'' (shape = '''//cfg%shape// &
        '''; leave it out)')
    if (status%failed()) return
    cfg%mx_my_given = grp%mx /= unset_int .or. grp%my /= unset_int
    cfg%mx = merge(0, grp%mx, grp%mx == unset_int)        ! 0 from here on: not given
    cfg%my = merge(0, grp%my, grp%my == unset_int)
    cfg%semi_a = merge(1.0_real64, grp%semi_a, grp%semi_a == unset)
    cfg%semi_b = merge(1.0_real64, grp%semi_b, grp%semi_b == unset)
    cfg%x0_given = grp%x0 /= unset
    cfg%y0_given = grp%y0 /= unset
    cfg%x0 = merge(0.0_real64, grp%x0, grp%x0 == unset)
    cfg%y0 = merge(0.0_real64, grp%y0, grp%y0 == unset)
    cfg%dx = grp%dx
    cfg%dy = grp%dy
    cfg%contact_case = grp%contact_case
    nrows = count_rows(grp%mask_rows)
    cfg%mask_rows = grp%mask_rows(1:nrows)
    ! every file name written in the namelist is relative to the namelist's folder
    cfg%mask_file = resolve_path(trim(grp%mask_file), folder_of(cfg%input_path))
    cfg%contact_file = resolve_path(trim(grp%contact_file), folder_of(cfg%input_path))

    select case (cfg%shape)
    case ('ellipse')
      if (.not. length_in_range(cfg%semi_a)) call fail(status, exit_bad_input, where// &
          '&patch semi_a = '//rtoa(cfg%semi_a)//' (must be > 0, between 1e-30 and 1e30)')
      if (.not. length_in_range(cfg%semi_b)) call fail(status, exit_bad_input, where// &
          '&patch semi_b = '//rtoa(cfg%semi_b)//' (must be > 0, between 1e-30 and 1e30)')
      if (cfg%mx == 0) cfg%mx = default_cells
      if (cfg%my == 0) cfg%my = default_cells
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
        associate (rows => grp%mask_rows)
          if (any(len_trim(rows(1:nrows)) == len(rows))) call fail(status, exit_bad_input, where// &
              '&patch mask_rows: a row is longer than '//itoa(len(rows) - 1)//' cells (use mask_file)')
          if (nrows == size(rows)) call fail(status, exit_bad_input, where// &
              '&patch mask_rows: more than '//itoa(size(rows) - 1)//' rows (use mask_file)')
          if (.not. length_in_range(cfg%dx)) call fail(status, exit_bad_input, where// &
              '&patch dx = '//rtoa(cfg%dx)//' (an inline mask needs a cell size > 0, between 1e-30 and 1e30)')
          if (.not. length_in_range(cfg%dy)) call fail(status, exit_bad_input, where// &
              '&patch dy = '//rtoa(cfg%dy)//' (an inline mask needs a cell size > 0, between 1e-30 and 1e30)')
          if (cfg%mx /= 0 .and. cfg%mx /= len_trim(rows(1))) call fail(status, exit_bad_input, where// &
              '&patch mx = '//itoa(cfg%mx)//' but mask row 1 has '//itoa(len_trim(rows(1)))//' cells')
          if (cfg%my /= 0 .and. cfg%my /= nrows) call fail(status, exit_bad_input, where// &
              '&patch my = '//itoa(cfg%my)//' but mask_rows has '//itoa(nrows)//' rows')
        end associate
      else
        if (cfg%dx < 0 .or. cfg%dy < 0) call fail(status, exit_bad_input, where//'&patch dx, dy = '// &
            rtoa(cfg%dx)//', '//rtoa(cfg%dy)//' (cell sizes must be > 0; the mask file header gives them)')
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
    case ('gap')
      if (len(cfg%mask_file) > 0 .or. nrows > 0 .or. len(cfg%contact_file) > 0) call fail(status, exit_bad_input, &
          where//'&patch shape = ''gap'' takes no mask_file, mask_rows or contact_file (the patch is the '// &
          'contact area the &normal group finds)')
    case default
      call fail(status, exit_bad_input, where//'&patch shape = '''//cfg%shape// &
                ''' (allowed: ''ellipse'', ''mask'', ''contact'', ''gap'')')
    end select
  end subroutine apply_patch_group

  !> Number of inline mask rows given: up to the last non-blank one.
  pure integer function count_rows(rows) result(nrows)
    character(len=*), intent(in) :: rows(:)
    nrows = size(rows)
    do while (nrows > 0)
      if (len_trim(rows(nrows)) > 0) exit
      nrows = nrows - 1
    end do
  end function count_rows

end module kcreep_nml_patch
