!> Reader for the outputs of Kalker's program CONTACT (module 3, "basic
!> contact"): the text output `.out` and, when CONTACT wrote it (flag A = 1),
!> the element file `<base>.<case, 4 digits>.mat` beside it.
!>
!> From case k of the `.out`: creepages (CKSI, CETA, CPHI), total forces (FN,
!> FX, FY, MZ, also kept as printed so that a comparison can respect CONTACT's
!> digits), material (POISS(1:2), GG(1:2)), statistics (NPOT, NCON, NADH,
!> NSLIP) and, for Hertzian cases only, the grid (MX, MY, DX, DY and the
!> potential-contact corner). From the `.mat`: the grid at six digits
!> (non-Hertzian `.out` files do not print it) and the status IGS of every
!> element, which gives the contact area without the cropping of the printed
!> map. Without a `.mat` the printed map is used when it covers the whole grid.
!> What is read twice is cross-checked (grid, material, cell counts against
!> NCON and NSLIP); any inconsistency is a one-line error naming file and case.
module kcreep_contact_reader
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use kcreep_contact_text, only: text_t, max_tokens, find_line, read_columns, column, has, to_reals, &
                                 to_integers, split, read_text, token_bounds, integer_of
  implicit none
  private
  public :: contact_case_t, read_contact_case, combined_material, contact_mat_path, count_contact_cases
  public :: printed_half_unit, simplest_fraction

  !> The .out prints 4 significant digits, the .mat 6: two readings of one
  !> quantity must agree to the coarser one.
  real(real64), parameter :: printed_tolerance = 1e-3_real64

  type :: contact_case_t
    character(len=:), allocatable :: out_path, mat_path
    character(len=:), allocatable :: mask_source     !< 'mat' or 'out map'
    integer :: case_number = 0
    integer :: mx = 0, my = 0
    real(real64) :: dx = 0, dy = 0
    real(real64) :: xl = 0, yl = 0                   !< lower-left corner of the potential contact
    real(real64) :: poiss(2) = 0, gg(2) = 0
    real(real64) :: cksi = 0, ceta = 0, cphi = 0
    real(real64) :: fn = 0, fx = 0, fy = 0, mz = 0
    character(len=32) :: fx_text = '', fy_text = '', mz_text = ''   !< as printed
    integer :: npot = 0, ncon = 0, nadh = 0, nslip = 0
    logical, allocatable :: inside(:, :)             !< (mx, my): cell in contact (IGS >= 1)
    real(real64), allocatable :: pn(:, :)            !< (mx, my): normal pressure PN of the .mat (0 elsewhere;
                                                     !< not allocated when the mask came from the .out map)
  end type contact_case_t


contains

  !> Combined material of two bodies: 1/G = (1/G1 + 1/G2)/2, nu/G = (nu1/G1 + nu2/G2)/2.
  pure subroutine combined_material(gg, poiss, g, nu)
    real(real64), intent(in) :: gg(2), poiss(2)
    real(real64), intent(out) :: g, nu
    g = 2 / (1 / gg(1) + 1 / gg(2))
    nu = g * (poiss(1) / gg(1) + poiss(2) / gg(2)) / 2
  end subroutine combined_material

  !> '<out path without .out>.<case as 4 digits>.mat', where CONTACT writes it.
  pure function contact_mat_path(out_path, case_number) result(path)
    character(len=*), intent(in) :: out_path
    integer, intent(in) :: case_number
    character(len=:), allocatable :: path
    character(len=16) :: digits
    integer :: n
    n = len_trim(out_path)
    path = out_path(1:n)
    if (n > 4) then
      if (out_path(n - 3:n) == '.out') path = out_path(1:n - 4)
    end if
    write (digits, '(i4.4)') case_number
    path = path//'.'//trim(digits)//'.mat'
  end function contact_mat_path

  !> Number of cases ('Case k' headers) in a CONTACT .out file.
  subroutine count_contact_cases(out_path, n_cases, status)
    character(len=*), intent(in) :: out_path
    integer, intent(out) :: n_cases
    type(status_t), intent(inout) :: status
    type(text_t) :: text
    integer :: i, k
    n_cases = 0
    call read_text(out_path, 'contact_file', text, status)
    if (status%failed()) return
    do i = 1, text%n
      if (case_header(text%lines(i)%s, k)) n_cases = n_cases + 1
    end do
  end subroutine count_contact_cases

  !> Everything kcreep needs of case k of a CONTACT .out (and its .mat).
  subroutine read_contact_case(out_path, case_number, c, status)
    character(len=*), intent(in) :: out_path
    integer, intent(in) :: case_number
    type(contact_case_t), intent(out) :: c
    type(status_t), intent(inout) :: status
    type(text_t) :: text
    integer :: first, last, n_cases, i, k
    character(len=:), allocatable :: where
    logical :: have_mat, grid_printed

    c%out_path = trim(out_path)
    c%case_number = case_number
    where = 'contact_file '''//c%out_path//''', case '//itoa(case_number)//': '
    call read_text(c%out_path, 'contact_file', text, status)
    if (status%failed()) return

    ! the case's block: from its header to the next header (or the end)
    first = 0
    last = text%n
    n_cases = 0
    do i = 1, text%n
      if (.not. case_header(text%lines(i)%s, k)) cycle
      n_cases = n_cases + 1
      if (first > 0 .and. last == text%n) last = i - 1
      if (k == case_number .and. first == 0) first = i
    end do
    if (n_cases == 0) then
      call fail(status, exit_bad_input, 'contact_file '''//c%out_path// &
                ''': no "Case" header found (not a CONTACT output file?)')
      return
    end if
    if (first == 0) then
      call fail(status, exit_bad_input, 'contact_file '''//c%out_path//''': no case '//itoa(case_number)// &
                ' (the file has '//itoa(n_cases)//' case(s))')
      return
    end if

    call read_out_block(text, first, last, where, c, grid_printed, status)
    if (status%failed()) return

    c%mat_path = contact_mat_path(c%out_path, case_number)
    inquire (file=c%mat_path, exist=have_mat)
    if (have_mat) then
      call read_mat(c%mat_path, grid_printed, c, status)
      c%mask_source = 'mat'
    else if (.not. grid_printed) then
      call fail(status, exit_bad_input, where//'the .out does not print the grid (non-Hertzian case) and '// &
                'the element file '''//c%mat_path//''' does not exist (run CONTACT with A = 1)')
    else
      call read_map(text, first, last, where, c, status)
      c%mask_source = 'out map'
    end if
    if (status%failed()) return

    if (count(c%inside) == 0) call fail(status, exit_bad_input, where//'no element is in contact (NCON = 0)')
    if (count(c%inside) /= c%ncon) call fail(status, exit_bad_input, where//itoa(count(c%inside))// &
        ' elements in contact in the '//c%mask_source//' but NCON = '//itoa(c%ncon)//' in the .out')
  end subroutine read_contact_case

  !> Parse the numbers of one case block of the .out.
  subroutine read_out_block(text, first, last, where, c, grid_printed, status)
    type(text_t), intent(in) :: text
    integer, intent(in) :: first, last
    character(len=*), intent(in) :: where
    type(contact_case_t), intent(inout) :: c
    logical, intent(out) :: grid_printed
    type(status_t), intent(inout) :: status
    character(len=32) :: tok(6)
    real(real64) :: v(6)
    integer :: iv(4), line_no, ios, nt
    real(real64) :: xl, yl

    call read_columns(text, first, last, 'POISS(1)', 0, [character(len=8) :: 'POISS(1)', 'POISS(2)', 'GG(1)', &
                      'GG(2)'], where//'MATERIAL CONSTANTS', tok, status)
    call to_reals(tok(1:4), where//'POISS(1), POISS(2), GG(1), GG(2)', v(1:4), status)
    c%poiss = v(1:2)
    c%gg = v(3:4)
    call read_columns(text, first, last, 'KINEMATIC CONSTANTS', 1, [character(len=8) :: 'CKSI', 'CETA', 'CPHI'], &
                      where//'KINEMATIC CONSTANTS', tok, status)
    call to_reals(tok(1:3), where//'CKSI, CETA, CPHI', v(1:3), status)
    c%cksi = v(1)
    c%ceta = v(2)
    c%cphi = v(3)
    call read_columns(text, first, last, 'TOTAL FORCES', 1, [character(len=8) :: 'FN', 'FX', 'FY', 'MZ'], &
                      where//'TOTAL FORCES', tok, status)
    call to_reals(tok(1:4), where//'FN, FX, FY, MZ', v(1:4), status)
    c%fn = v(1)
    c%fx = v(2)
    c%fy = v(3)
    c%mz = v(4)
    c%fx_text = tok(2)
    c%fy_text = tok(3)
    c%mz_text = tok(4)
    call read_columns(text, first, last, 'NPOT', 0, [character(len=8) :: 'NPOT', 'NCON', 'NADH', 'NSLIP'], &
                      where//'CONTACT STATISTICS', tok, status)
    call to_integers(tok(1:4), where//'NPOT, NCON, NADH, NSLIP', iv, status)
    if (status%failed()) return
    c%npot = iv(1)
    c%ncon = iv(2)
    c%nadh = iv(3)
    c%nslip = iv(4)
    if (any(iv < 0) .or. iv(2) /= iv(3) + iv(4) .or. iv(2) > iv(1)) then
      call fail(status, exit_bad_input, where//'CONTACT STATISTICS NPOT, NCON, NADH, NSLIP = '//itoa(iv(1))// &
                ', '//itoa(iv(2))//', '//itoa(iv(3))//', '//itoa(iv(4))//' are inconsistent (need NCON = NADH + NSLIP <= NPOT)')
      return
    end if
    if (.not. (all(c%gg > 0) .and. all(c%gg <= huge(1.0_real64)))) then
      call fail(status, exit_bad_input, where//'GG(1), GG(2) = '//rtoa(c%gg(1))//', '//rtoa(c%gg(2))//' (must be > 0)')
      return
    end if
    if (.not. all(c%poiss >= 0 .and. c%poiss <= 0.5_real64)) then
      call fail(status, exit_bad_input, where//'POISS(1), POISS(2) = '//rtoa(c%poiss(1))//', '// &
                rtoa(c%poiss(2))//' (allowed: 0 to 0.5)')
      return
    end if

    ! Hertzian cases print the grid; non-Hertzian ones do not
    grid_printed = .false.
    line_no = find_line(text, first, last, 'DISCRETISATION MX,MY, DX,DY:')
    if (line_no > 0) then
      call split(text%lines(line_no)%s(index(text%lines(line_no)%s, ':') + 1:), tok, nt)
      ios = merge(0, 1, nt == 4)
      if (ios == 0) read (tok(1), *, iostat=ios) c%mx
      if (ios == 0) read (tok(2), *, iostat=ios) c%my
      if (ios == 0) call to_reals(tok(3:4), where//'DISCRETISATION DX, DY', v(1:2), status)
      if (status%failed()) return
      ! four printed digits: 0.3333 stands for 1/3 (see simplest_fraction)
      c%dx = simplest_fraction(v(1), printed_half_unit(tok(3)))
      c%dy = simplest_fraction(v(2), printed_half_unit(tok(4)))
      if (ios /= 0) then
        call fail(status, exit_bad_input, where//'line '//itoa(line_no)//': cannot read MX, MY, DX, DY from "'// &
                  trim(adjustl(text%lines(line_no)%s))//'"')
        return
      end if
      line_no = find_line(text, first, last, 'POTENTIAL CONTACT, SCALE:')
      if (line_no == 0) then
        call fail(status, exit_bad_input, where//'DISCRETISATION printed without the POTENTIAL CONTACT line')
        return
      end if
      call split(text%lines(line_no)%s(index(text%lines(line_no)%s, ':') + 1:), tok, nt)
      ios = merge(0, 1, nt == 3)
      if (ios == 0) call to_reals(tok(1:3), where//'POTENTIAL CONTACT XL, YL, SCALE', v(1:3), status)
      if (status%failed()) return
      xl = simplest_fraction(v(1), printed_half_unit(tok(1)))
      yl = simplest_fraction(v(2), printed_half_unit(tok(2)))
      if (ios /= 0) then
        call fail(status, exit_bad_input, where//'line '//itoa(line_no)//': cannot read XL, YL from "'// &
                  trim(adjustl(text%lines(line_no)%s))//'"')
        return
      end if
      c%xl = xl
      c%yl = yl
      if (c%mx < 1 .or. c%my < 1 .or. .not. (c%dx > 0 .and. c%dy > 0)) then
        call fail(status, exit_bad_input, where//'DISCRETISATION MX, MY, DX, DY = '//itoa(c%mx)//', '// &
                  itoa(c%my)//', '//rtoa(c%dx)//', '//rtoa(c%dy)//' (need MX, MY >= 1, DX, DY > 0)')
        return
      end if
      grid_printed = .true.
    end if
  end subroutine read_out_block

  !> The grid, material and element status of the .mat file of one case.
  subroutine read_mat(path, grid_printed, c, status)
    character(len=*), intent(in) :: path
    logical, intent(in) :: grid_printed     !< the .out printed a grid: cross-check it
    type(contact_case_t), intent(inout) :: c
    type(status_t), intent(inout) :: status
    type(text_t) :: text
    character(len=32) :: head(max_tokens), vals(max_tokens)
    integer :: nh, nv, i, ios, mx, my, element, igs, ix, iy, n_slip, first_element, pn_column
    real(real64) :: xl, yl, dx, dy, gg(2), poiss(2), material(4), grid(4)
    real(real64) :: pn
    integer :: f1, l1, f2, l2, fp, lp
    logical :: ok1, ok2
    integer :: grid_size(2), k
    logical :: have_grid, have_material
    logical, allocatable :: seen(:, :)
    character(len=:), allocatable :: where

    where = 'contact_file '''//c%out_path//''', case '//itoa(c%case_number)//', element file '''//path//''': '
    call read_text(path, 'element file', text, status)
    if (status%failed()) return
    have_grid = .false.
    have_material = .false.
    first_element = 0
    do i = 1, text%n - 1
      if (adjustl(text%lines(i)%s) /= '%' .and. index(adjustl(text%lines(i)%s), '%') /= 1) cycle
      call split(text%lines(i)%s, head, nh)
      if (has(head(1:nh), 'MX') .and. has(head(1:nh), 'XL')) then
        call split(text%lines(i + 1)%s, vals, nv)
        call to_integers(vals(1:2), where//'line '//itoa(i + 1)//': MX, MY', grid_size, status)
        call to_reals(vals(3:6), where//'line '//itoa(i + 1)//': XL, YL, DX, DY', grid, status)
        if (status%failed()) return
        mx = grid_size(1)
        my = grid_size(2)
        ! six printed digits are not enough for the position of the grid
        ! (a symmetric grid would come out lopsided): take the simplest
        ! fraction within the printing precision, e.g. 0.333333 -> 1/3
        do k = 1, 4
          grid(k) = simplest_fraction(grid(k), printed_half_unit(vals(2 + k)))
        end do
        xl = grid(1)
        yl = grid(2)
        dx = grid(3)
        dy = grid(4)
        have_grid = .true.
      else if (has(head(1:nh), 'GG1')) then
        call split(text%lines(i + 1)%s, vals, nv)
        call to_reals([column(head, nh, vals, nv, 'GG1'), column(head, nh, vals, nv, 'GG2'), &
                       column(head, nh, vals, nv, 'POISS1'), column(head, nh, vals, nv, 'POISS2')], &
                      where//'line '//itoa(i + 1)//': GG1, GG2, POISS1, POISS2', material, status)
        if (status%failed()) return
        gg = material(1:2)
        poiss = material(3:4)
        have_material = .true.
      else if (has(head(1:nh), 'IGS')) then
        first_element = i + 1
        pn_column = findloc(head(1:nh), 'PN', dim=1)
        if (head(1) == '%') pn_column = pn_column - 1
        exit
      end if
    end do
    if (.not. have_grid) then
      call fail(status, exit_bad_input, where//'no grid block "MX MY XL YL DX DY" (truncated or not a CONTACT .mat?)')
      return
    end if
    if (first_element == 0) then
      call fail(status, exit_bad_input, where//'no element block "I IGS ..." (truncated or not a CONTACT .mat?)')
      return
    end if
    if (mx < 1 .or. my < 1 .or. .not. (dx > 0 .and. dy > 0 .and. dx <= huge(dx) .and. dy <= huge(dy)) &
        .or. .not. (abs(xl) <= huge(xl) .and. abs(yl) <= huge(yl))) then
      call fail(status, exit_bad_input, where//'grid MX, MY, DX, DY = '//itoa(mx)//', '//itoa(my)//', '// &
                rtoa(dx)//', '//rtoa(dy)//' (need MX, MY >= 1, DX, DY > 0, finite XL, YL)')
      return
    end if
    if (grid_printed) then
      if (mx /= c%mx .or. my /= c%my .or. .not. same_printed(dx, c%dx) .or. .not. same_printed(dy, c%dy)) then
        call fail(status, exit_bad_input, where//'grid '//itoa(mx)//' x '//itoa(my)//', DX, DY = '//rtoa(dx)// &
                  ', '//rtoa(dy)//' differs from the .out''s '//itoa(c%mx)//' x '//itoa(c%my)//', '// &
                  rtoa(c%dx)//', '//rtoa(c%dy)//' (element file of another run?)')
        return
      end if
    end if
    if (have_material) then
      if (.not. (all(same_printed(gg, c%gg)) .and. all(same_printed(poiss, c%poiss)))) then
        call fail(status, exit_bad_input, where//'GG, POISS = '//rtoa(gg(1))//', '//rtoa(gg(2))//', '// &
                  rtoa(poiss(1))//', '//rtoa(poiss(2))//' differ from the .out''s (element file of another run?)')
        return
      end if
      c%gg = gg
      c%poiss = poiss
    end if
    c%mx = mx
    c%my = my
    c%dx = dx
    c%dy = dy
    c%xl = xl
    c%yl = yl

    allocate (c%inside(mx, my), seen(mx, my), c%pn(mx, my))
    c%inside = .false.
    c%pn = 0
    seen = .false.
    n_slip = 0
    do i = first_element, text%n
      ! I and IGS, and PN below, found in place: a formatted read per line
      ! cost more than the solve on large grids (issue 45)
      associate (line => text%lines(i)%s)
        call token_bounds(line, 1, f1, l1)
        if (f1 == 0) cycle                    ! a blank line
        if (line(f1:f1) == '%') exit          ! the next comment block
        call token_bounds(line, 2, f2, l2)
        ok1 = f2 > 0
        ok2 = .false.
        if (ok1) call integer_of(line(f1:l1), element, ok1)
        if (ok1) call integer_of(line(f2:l2), igs, ok2)
      end associate
      if (.not. (ok1 .and. ok2)) then
        call fail(status, exit_bad_input, where//'line '//itoa(i)//': cannot read I, IGS from "'// &
                  trim(text%lines(i)%s(1:min(60, len_trim(text%lines(i)%s))))//'"')
        return
      end if
      if (element < 1 .or. element > mx * my) then
        call fail(status, exit_bad_input, where//'line '//itoa(i)//': element I = '//itoa(element)// &
                  ' (allowed: 1 to MX*MY = '//itoa(mx * my)//')')
        return
      end if
      if (igs < 0 .or. igs > 2) then
        call fail(status, exit_bad_input, where//'line '//itoa(i)//': IGS = '//itoa(igs)// &
                  ' (allowed: 0 exterior, 1 adhesion, 2 slip)')
        return
      end if
      ! row-major element numbering: ix fastest
      ix = mod(element - 1, mx) + 1
      iy = (element - 1) / mx + 1
      if (seen(ix, iy)) then
        call fail(status, exit_bad_input, where//'line '//itoa(i)//': element '//itoa(element)//' listed twice')
        return
      end if
      seen(ix, iy) = .true.
      c%inside(ix, iy) = igs >= 1
      if (pn_column >= 3 .and. igs >= 1) then
        call token_bounds(text%lines(i)%s, pn_column, fp, lp)
        ios = 1
        if (fp > 0) read (text%lines(i)%s(fp:lp), *, iostat=ios) pn
        if (ios /= 0) then
          call fail(status, exit_bad_input, where//'line '//itoa(i)//': cannot read PN (column '// &
                    itoa(pn_column)//') from "'//trim(text%lines(i)%s(1:min(60, len_trim(text%lines(i)%s))))//'"')
          return
        end if
        if (.not. (pn >= 0 .and. pn <= huge(1.0_real64))) then
          call fail(status, exit_bad_input, where//'line '//itoa(i)//': PN = '//rtoa(pn)// &
                    ' (a normal pressure must be finite and >= 0)')
          return
        end if
        c%pn(ix, iy) = pn
      end if
      if (igs == 2) n_slip = n_slip + 1
    end do
    if (pn_column < 3) deallocate (c%pn)      ! no PN column: no pressure from this file
    if (n_slip /= c%nslip) then
      call fail(status, exit_bad_input, where//itoa(n_slip)//' elements in slip (IGS = 2) but NSLIP = '// &
                itoa(c%nslip)//' in the .out (truncated, or the element file of another case?)')
    end if
  end subroutine read_mat

  !> The mask from the printed map, accepted only when it covers the whole grid.
  subroutine read_map(text, first, last, where, c, status)
    type(text_t), intent(in) :: text
    integer, intent(in) :: first, last
    character(len=*), intent(in) :: where
    type(contact_case_t), intent(inout) :: c
    type(status_t), intent(inout) :: status
    character(len=32) :: tok(max_tokens)
    integer :: start, i, nt, row, ios, rows_read, k, top, bottom, first_symbol
    character(len=:), allocatable :: units_line, tens_line

    start = find_line(text, first, last, 'FORM OF THE CONTACT')
    if (start == 0) then
      call fail(status, exit_bad_input, where//'no element file and no printed contact map '// &
                '("FORM OF THE CONTACT ..."; CONTACT output level O >= 3 prints it)')
      return
    end if
    allocate (c%inside(c%mx, c%my))
    c%inside = .false.
    rows_read = 0
    top = 0
    bottom = 0
    first_symbol = 0
    do i = start + 1, last
      call split(text%lines(i)%s, tok, nt)
      if (nt < 2) exit
      read (tok(1), *, iostat=ios) row
      ! a map row: its number, then one non-digit symbol per column (the
      ! column-number lines below the map have digits instead)
      if (ios /= 0 .or. any(len_trim(tok(2:nt)) /= 1) .or. any(scan(tok(2:nt), '0123456789') > 0)) exit
      if (rows_read == 0) then
        top = row
        first_symbol = index(text%lines(i)%s, trim(tok(2)))
        ! the first symbol follows the row number: look past it
        first_symbol = index(text%lines(i)%s(index(text%lines(i)%s, trim(tok(1))) + len_trim(tok(1)):), trim(tok(2))) &
                       + index(text%lines(i)%s, trim(tok(1))) + len_trim(tok(1)) - 1
      end if
      rows_read = rows_read + 1
      bottom = row
      if (row /= top - rows_read + 1 .or. nt - 1 /= c%mx .or. row < 1 .or. row > c%my) then
        call fail(status, exit_bad_input, where//'the printed map is cropped (row '//itoa(row)//' has '// &
                  itoa(nt - 1)//' of '//itoa(c%mx)//' columns) and the element file '''//c%mat_path// &
                  ''' does not exist (run CONTACT with A = 1)')
        return
      end if
      do k = 1, c%mx
        select case (tok(k + 1)(1:1))
        case ('*', 'S')
          c%inside(k, row) = .true.
        case ('.', 'o')
          c%inside(k, row) = .false.
        case default
          call fail(status, exit_bad_input, where//'line '//itoa(i)//': map symbol '''//tok(k + 1)(1:1)// &
                    ''' (known: * adhesion, S slip, . and o exterior)')
          return
        end select
      end do
    end do
    ! the two lines after the rows number the columns (tens, then units)
    tens_line = ''
    units_line = ''
    if (start + rows_read + 2 <= last) then
      tens_line = text%lines(start + rows_read + 1)%s
      units_line = text%lines(start + rows_read + 2)%s
    end if
    if (top /= c%my .or. bottom /= 1 .or. rows_read /= c%my .or. first_symbol < 1 .or. &
        first_symbol > len(units_line)) then
      call fail(status, exit_bad_input, where//'the printed map is cropped or incomplete (rows '//itoa(top)// &
                ' to '//itoa(bottom)//' of 1 to '//itoa(c%my)//') and the element file '''//c%mat_path// &
                ''' does not exist (run CONTACT with A = 1)')
      return
    end if
    if (units_line(first_symbol:first_symbol) /= '1' .or. &
        len_trim(tens_line(1:min(first_symbol, len(tens_line)))) /= 0) then
      call fail(status, exit_bad_input, where//'the printed map does not start at column 1 and the element file '''// &
                c%mat_path//''' does not exist (run CONTACT with A = 1)')
    end if
  end subroutine read_map

  ! ---------------------------------------------------------------- helpers

  !> Half a unit in the last digit of a number as printed ('-8418.', '1.439E+04', '0.000').
  pure real(real64) function printed_half_unit(text) result(half)
    character(len=*), intent(in) :: text
    integer :: e_at, dot, decimals, exponent, ios, last
    character(len=len(text)) :: s
    s = adjustl(text)
    last = len_trim(s)
    e_at = scan(s(1:last), 'EeDd')
    exponent = 0
    if (e_at > 0) then
      read (s(e_at + 1:last), *, iostat=ios) exponent
      if (ios /= 0) exponent = 0
      last = e_at - 1
    end if
    dot = index(s(1:last), '.')
    decimals = 0
    if (dot > 0) decimals = last - dot
    half = 0.5_real64 * 10.0_real64**(exponent - decimals)
  end function printed_half_unit

  !> The first continued-fraction convergent p/q (q <= 10^4) of x within tol
  !> of x, or x itself if there is none: the value a printed number most
  !> likely stood for when it was computed as a simple ratio (L/M cells).
  !> Never further than tol from x, so never outside the printing precision.
  pure real(real64) function simplest_fraction(x, tol) result(r)
    real(real64), intent(in) :: x, tol
    real(real64), parameter :: max_denominator = 1e4_real64
    real(real64) :: rest, a, p0, q0, p1, q1, p2, q2
    integer :: iteration
    r = x
    if (x == 0 .or. .not. abs(x) <= huge(x)) return
    p0 = 0
    q0 = 1
    p1 = 1
    q1 = 0
    rest = abs(x)
    do iteration = 1, 40
      a = aint(rest)
      p2 = a * p1 + p0
      q2 = a * q1 + q0
      if (q2 > max_denominator) return
      if (abs(p2 / q2 - abs(x)) <= tol) then
        r = sign(p2 / q2, x)
        return
      end if
      if (rest - a <= 0) return
      rest = 1 / (rest - a)
      p0 = p1
      q0 = q1
      p1 = p2
      q1 = q2
    end do
  end function simplest_fraction

  !> 'Case k' header line of the .out.
  logical function case_header(line, k)
    character(len=*), intent(in) :: line
    integer, intent(out) :: k
    character(len=max(len(line), 5)) :: s
    integer :: ios
    case_header = .false.
    k = 0
    s = adjustl(line)
    if (s(1:5) /= 'Case ') return
    read (s(6:), *, iostat=ios) k
    case_header = ios == 0 .and. len_trim(s(6:)) <= 10
  end function case_header

  !> Equal to the .out's 4 printed digits.
  elemental logical function same_printed(precise, printed)
    real(real64), intent(in) :: precise, printed
    same_printed = abs(precise - printed) <= printed_tolerance * max(abs(precise), abs(printed))
  end function same_printed

end module kcreep_contact_reader
