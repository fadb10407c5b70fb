!> Reader for the normal-problem part of a CONTACT input file (.inp),
!> module 3 ("basic contact"): control digits, penetration or normal force,
!> material constants, the potential contact grid and the undeformed
!> distance (IBASE = 1 quadratic, IBASE = 9 tabulated per element; IPLAN = 1
!> unrestricted, 2 quadratic planform, 3 union of two rectangles).
!>
!> Lines starting with '%' or '!' are comments; on a data line the numbers
!> come first and anything after them (CONTACT's labels) is ignored. Values
!> not given again in a later case (digits D, Z, C = 0 or 1) keep those of
!> the previous case, as in CONTACT. Options outside this subset are
!> refused with a message naming the digit.
module kcreep_contact_input
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use kcreep_file_checks, only: read_input_file
  use kcreep_gap, only: gap_t, gap_from_array, max_gap_cells
  implicit none
  private
  public :: contact_input_t, read_contact_input

  integer, parameter :: max_values = 64

  type :: contact_input_t
    integer :: case_number = 0
    integer :: norm = 0                   !< digit N: 0 approach (PEN) given, 1 force (FN) given
    real(real64) :: pen = 0, fn = 0
    real(real64) :: cksi = 0, ceta = 0, cphi = 0
    real(real64) :: chi = 0, dq = 0, veloc = 0
    real(real64) :: poiss(2) = 0, gg(2) = 0
    integer :: mx = 0, my = 0
    real(real64) :: xl = 0, yl = 0, dx = 0, dy = 0   !< lower-left corner, cell sizes
    integer :: ibase = 0, iplan = 0
    type(gap_t) :: gap                    !< h per element (1e30 outside a planform)
  end type contact_input_t

  !> The lines of the file without comments, with their line numbers, and a cursor.
  type :: reader_t
    character(len=:), allocatable :: text
    integer :: pos = 1, line_no = 0
    character(len=:), allocatable :: source
  end type reader_t

contains

  !> Read case case_number (1 = first) of the CONTACT input file at path.
  subroutine read_contact_input(path, case_number, inp, status)
    character(len=*), intent(in) :: path
    integer, intent(in) :: case_number
    type(contact_input_t), intent(out) :: inp
    type(status_t), intent(inout) :: status
    type(reader_t) :: rd
    real(real64) :: v(max_values)
    real(real64), allocatable :: h(:), par(:), pln(:)
    integer :: n, icase, module_no, ipotcn, dig(8), ndig, p, b, t, nn, f, s, l, d, c, m, z, e, hh, gs, x, vv
    integer :: ix, iy
    real(real64) :: xc, yc

    rd%source = 'contact_inp '''//trim(path)//''''
    call read_input_file(path, rd%source, rd%text, status)
    if (status%failed()) return
    if (case_number < 1) then
      call fail(status, exit_bad_input, 'contact_case = '//itoa(case_number)//' (must be >= 1)')
      return
    end if
    ipotcn = 0
    do icase = 1, case_number
      call next_values(rd, v, n, status)
      if (status%failed()) return
      if (n < 1) then
        call fail(status, exit_bad_input, rd%source//': end of file before case '//itoa(case_number)// &
                  ' (the file has '//itoa(icase - 1)//' cases)')
        return
      end if
      module_no = nint(v(1))
      if (module_no == 0) then
        call fail(status, exit_bad_input, rd%source//': contact_case = '//itoa(case_number)//', the file has '// &
                  itoa(icase - 1)//' cases')
        return
      else if (module_no /= 3) then
        call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': module '//itoa(module_no)// &
                  ' (only module 3, basic contact, is read)')
        return
      end if
      ! P-B-T-N-F-S
      call digits_line(rd, 6, 6, dig, ndig, status)
      if (status%failed()) return
      p = dig(1); b = dig(2); t = dig(3); nn = dig(4); f = dig(5); s = dig(6)
      ! [V-]L-D-C-M-Z-E
      call digits_line(rd, 6, 7, dig, ndig, status)
      if (status%failed()) return
      vv = 0
      if (ndig == 7) then
        vv = dig(1)
        dig(1:6) = dig(2:7)
      end if
      l = dig(1); d = dig(2); c = dig(3); m = dig(4); z = dig(5); e = dig(6)
      ! [X-]H-G-I-A-O-W-R
      call digits_line(rd, 7, 8, dig, ndig, status)
      if (status%failed()) return
      x = 0
      if (ndig == 8) then
        x = dig(1)
        dig(1:7) = dig(2:8)
      end if
      hh = dig(1); gs = dig(2)
      if (p /= 2 .and. p /= 0) call unsupported('P', p)
      if (b /= 0) call unsupported('B', b)
      if (f /= 0) call unsupported('F', f)
      if (s /= 0) call unsupported('S', s)
      if (vv /= 0) call unsupported('V', vv)
      if (m /= 0) call unsupported('M', m)
      if (e /= 0) call unsupported('E', e)
      if (hh /= 0) call unsupported('H', hh)
      if (gs > 5) call unsupported('G', gs)
      if (l > 1) call unsupported('L', l)
      if (c == 4 .or. c == 9) call unsupported('C', c)
      if (status%failed()) return
      inp%norm = nn
      if (x >= 1) call skip_line(rd, 'debug output', status)
      if (gs /= 1) call required(rd, 5, 'iteration constants MAXGS MAXIN MAXNR MAXOUT EPS', v, status)
      if (gs == 2 .or. gs == 3) call required(rd, 4, 'relaxation parameters', v, status)
      if (gs == 4) call required(rd, 2, 'relaxation parameters', v, status)
      if (gs == 5) call required(rd, 8, 'GDsteady parameters', v, status)
      if (status%failed()) return
      call required(rd, 4, 'PEN (or FN), CKSI, CETA, CPHI', v, status)
      if (status%failed()) return
      if (nn == 0) then
        inp%pen = v(1)
      else
        inp%fn = v(1)
        if (.not. (inp%fn > 0)) then
          call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': FN = '//rtoa(inp%fn)// &
                    ' (must be > 0)')
          return
        end if
      end if
      inp%cksi = v(2)
      inp%ceta = v(3)
      inp%cphi = v(4)
      if (l == 0) then
        call required(rd, 2, 'FSTAT, FKIN', v, status)
        if (status%failed()) return
      end if
      if (c >= 2) then
        if (t == 2 .or. t == 3) then
          call required(rd, 3, 'CHI, DQ, VELOC', v, status)
          if (status%failed()) return
          inp%chi = v(1)
          inp%dq = v(2)
          inp%veloc = v(3)
        end if
        call required(rd, 4, 'POISS1, POISS2, GG1, GG2', v, status)
        if (status%failed()) return
        inp%poiss = v(1:2)
        inp%gg = v(3:4)
        if (any(.not. (inp%poiss >= 0 .and. inp%poiss <= 0.5_real64))) then
          call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': POISS = '// &
                    rtoa(inp%poiss(1))//', '//rtoa(inp%poiss(2))//' (allowed 0 to 0.5)')
          return
        end if
        if (any(.not. (inp%gg > 0 .and. inp%gg < 1e30_real64))) then
          call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': GG = '// &
                    rtoa(inp%gg(1))//', '//rtoa(inp%gg(2))//' (must be > 0)')
          return
        end if
      else if (icase == 1) then
        call fail(status, exit_bad_input, rd%source//': digit C = '//itoa(c)// &
                  ' in the first case: the material constants are missing')
        return
      end if
      if (d == 2) then
        call required(rd, 1, 'IPOTCN', v, status)
        if (status%failed()) return
        ipotcn = nint(v(1))
        if (ipotcn /= 1 .and. ipotcn /= 2) then
          call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': IPOTCN = '//itoa(ipotcn)// &
                    ' (only 1 and 2, a non-Hertzian rectangular grid, are read)')
          return
        end if
        call required(rd, 6, 'MX, MY, XL, YL, DX, DY (or XH, YH)', v, status)
        if (status%failed()) return
        inp%mx = nint(v(1))
        inp%my = nint(v(2))
        inp%xl = v(3)
        inp%yl = v(4)
        if (ipotcn == 1) then
          inp%dx = v(5)
          inp%dy = v(6)
        else
          inp%dx = (v(5) - v(3)) / max(inp%mx, 1)
          inp%dy = (v(6) - v(4)) / max(inp%my, 1)
        end if
        if (inp%mx < 1 .or. inp%my < 1 .or. real(inp%mx, real64) * inp%my > max_gap_cells) then
          call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': MX, MY = '// &
                    itoa(inp%mx)//', '//itoa(inp%my)//' (both >= 1, MX * MY <= '//itoa(max_gap_cells)//')')
          return
        end if
        if (.not. (inp%dx > 0 .and. inp%dy > 0)) then
          call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': DX, DY = '// &
                    rtoa(inp%dx)//', '//rtoa(inp%dy)//' (must be > 0)')
          return
        end if
      else if (d /= 0 .and. icase == 1) then
        call unsupported('D', d)
        return
      else if (icase == 1) then
        call fail(status, exit_bad_input, rd%source//': digit D = 0 in the first case: the grid is missing')
        return
      end if
      if (z == 2 .or. (z == 1 .and. icase == 1)) then
        call required(rd, 2, 'IBASE, IPLAN', v, status)
        if (status%failed()) return
        inp%ibase = nint(v(1))
        inp%iplan = nint(v(2))
        select case (inp%ibase)
        case (1)
          call read_array(rd, 6, 'IBASE = 1 coefficients B1..B6', par, status)
        case (9)
          call read_array(rd, inp%mx * inp%my, 'IBASE = 9 undeformed distance per element', h, status)
        case default
          call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': IBASE = '// &
                    itoa(inp%ibase)//' (only 1, quadratic, and 9, per element, are read)')
        end select
        if (status%failed()) return
        select case (inp%iplan)
        case (1)
        case (2)
          call read_array(rd, 6, 'IPLAN = 2 planform coefficients', pln, status)
        case (3)
          call read_array(rd, 8, 'IPLAN = 3 rectangles', pln, status)
        case default
          call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': IPLAN = '// &
                    itoa(inp%iplan)//' (allowed 1, 2, 3)')
        end select
        if (status%failed()) return
      else if (icase == 1) then
        call fail(status, exit_bad_input, rd%source//': digit Z = '//itoa(z)// &
                  ' in the first case: the undeformed distance is missing')
        return
      end if
    end do

    inp%case_number = case_number
    if (inp%ibase == 1) then
      if (allocated(h)) deallocate (h)
      allocate (h(inp%mx * inp%my))
      do iy = 1, inp%my
        do ix = 1, inp%mx
          xc = inp%xl + (ix - 0.5_real64) * inp%dx
          yc = inp%yl + (iy - 0.5_real64) * inp%dy
          h(ix + (iy - 1) * inp%mx) = par(1) * xc**2 + par(2) * xc * yc + par(3) * yc**2 + par(4) * xc + &
                                      par(5) * yc + par(6)
        end do
      end do
    end if
    if (size(h) /= inp%mx * inp%my) then
      call fail(status, exit_bad_input, rd%source//': the grid changed to '//itoa(inp%mx)//' x '//itoa(inp%my)// &
                ' without a new undeformed distance (digit Z)')
      return
    end if
    if (inp%iplan == 2 .or. inp%iplan == 3) then
      do iy = 1, inp%my
        do ix = 1, inp%mx
          xc = inp%xl + (ix - 0.5_real64) * inp%dx
          yc = inp%yl + (iy - 0.5_real64) * inp%dy
          if (.not. in_planform(xc, yc)) h(ix + (iy - 1) * inp%mx) = 1e30_real64
        end do
      end do
      if (all(h >= 1e29_real64)) then
        call fail(status, exit_bad_input, rd%source//': IPLAN = '//itoa(inp%iplan)//' excludes every element')
        return
      end if
    end if
    call gap_from_array(reshape(h, [inp%mx, inp%my]), inp%dx, inp%dy, inp%xl + inp%dx / 2, inp%yl + inp%dy / 2, &
                        rd%source, inp%gap, status)

  contains

    logical function in_planform(xp, yp)
      real(real64), intent(in) :: xp, yp
      if (inp%iplan == 2) then
        in_planform = pln(1) * xp**2 + pln(2) * xp * yp + pln(3) * yp**2 + pln(4) * xp + pln(5) * yp + pln(6) < 0
      else
        in_planform = (pln(1) <= xp .and. xp <= pln(2) .and. pln(3) <= yp .and. yp <= pln(4)) .or. &
                      (pln(5) <= xp .and. xp <= pln(6) .and. pln(7) <= yp .and. yp <= pln(8))
      end if
    end function in_planform

    subroutine unsupported(name, value)
      character(len=*), intent(in) :: name
      integer, intent(in) :: value
      call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': digit '//name//' = '// &
                itoa(value)//' is not supported by this reader (module 3, normal problem with B = 0, '// &
                'F = 0, S = 0, M = 0, E = 0, H = 0, C = 2 or 3, L = 0 or 1)')
    end subroutine unsupported

  end subroutine read_contact_input

  !> The next non-comment line: its leading numbers (up to the first word that is no number).
  subroutine next_values(rd, v, n, status)
    type(reader_t), intent(inout) :: rd
    real(real64), intent(out) :: v(:)
    integer, intent(out) :: n
    type(status_t), intent(inout) :: status
    integer :: lb, le, first, last, ios
    character(len=*), parameter :: separators = ' ,'//achar(9)//achar(13)
    character(len=64) :: word
    n = 0
    do while (rd%pos <= len(rd%text))
      lb = rd%pos
      le = index(rd%text(lb:), achar(10))
      if (le == 0) then
        le = len(rd%text)
      else
        le = lb + le - 2
      end if
      rd%pos = le + 2
      rd%line_no = rd%line_no + 1
      if (le < lb) cycle
      first = verify(rd%text(lb:le), separators)
      if (first == 0) cycle
      if (index('%!', rd%text(lb + first - 1:lb + first - 1)) > 0) cycle
      last = lb - 1
      do
        first = verify(rd%text(last + 1:le), separators)
        if (first == 0) exit
        first = first + last
        last = scan(rd%text(first:le), separators)
        last = merge(le, first + last - 2, last == 0)
        if (last - first + 1 > len(word)) exit
        word = rd%text(first:last)
        if (verify(word(1:1), '0123456789+-.') /= 0) exit
        if (n >= size(v)) then
          call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': more than '// &
                    itoa(size(v))//' numbers')
          return
        end if
        read (word, *, iostat=ios) v(n + 1)
        if (ios /= 0) exit
        if (v(n + 1) /= v(n + 1) .or. abs(v(n + 1)) > huge(1.0_real64)) then
          call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': value '//trim(word)// &
                    ' (finite numbers only)')
          return
        end if
        n = n + 1
      end do
      return
    end do
  end subroutine next_values

  subroutine required(rd, count, what, v, status)
    type(reader_t), intent(inout) :: rd
    integer, intent(in) :: count
    character(len=*), intent(in) :: what
    real(real64), intent(out) :: v(:)
    type(status_t), intent(inout) :: status
    integer :: n
    if (status%failed()) return
    call next_values(rd, v, n, status)
    if (status%failed()) return
    if (n < count) then
      call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': expected '//itoa(count)// &
                ' numbers ('//what//'), found '//itoa(n))
    end if
  end subroutine required

  subroutine skip_line(rd, what, status)
    type(reader_t), intent(inout) :: rd
    character(len=*), intent(in) :: what
    type(status_t), intent(inout) :: status
    real(real64) :: v(max_values)
    integer :: n
    call next_values(rd, v, n, status)
    if (n < 1 .and. .not. status%failed()) call fail(status, exit_bad_input, rd%source//': '//what//' missing')
  end subroutine skip_line

  !> count numbers over as many lines as needed.
  subroutine read_array(rd, count, what, a, status)
    type(reader_t), intent(inout) :: rd
    integer, intent(in) :: count
    character(len=*), intent(in) :: what
    real(real64), allocatable, intent(out) :: a(:)
    type(status_t), intent(inout) :: status
    real(real64) :: v(max_values)
    integer :: n, k
    allocate (a(count))
    k = 0
    do while (k < count)
      call next_values(rd, v, n, status)
      if (status%failed()) return
      if (n == 0) then
        call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': '//what//': '//itoa(k)// &
                  ' of '//itoa(count)//' numbers before this line')
        return
      end if
      if (k + n > count) then
        call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': '//what//': more than '// &
                  itoa(count)//' numbers')
        return
      end if
      a(k + 1:k + n) = v(1:n)
      k = k + n
    end do
  end subroutine read_array

  !> A line of control digits such as 203000 (leading zeros may be dropped).
  subroutine digits_line(rd, min_digits, max_digits, dig, ndig, status)
    type(reader_t), intent(inout) :: rd
    integer, intent(in) :: min_digits, max_digits
    integer, intent(out) :: dig(:), ndig
    type(status_t), intent(inout) :: status
    real(real64) :: v(max_values)
    integer :: n, k, value
    dig = 0
    ndig = min_digits
    call next_values(rd, v, n, status)
    if (status%failed()) return
    if (n < 1 .or. v(1) < 0 .or. v(1) >= 10.0_real64**max_digits .or. v(1) /= aint(v(1))) then
      call fail(status, exit_bad_input, rd%source//': line '//itoa(rd%line_no)//': expected a line of '// &
                itoa(min_digits)//' control digits')
      return
    end if
    value = nint(v(1))
    if (value >= 10**min_digits) ndig = max_digits
    do k = ndig, 1, -1
      dig(k) = mod(value, 10)
      value = value / 10
    end do
  end subroutine digits_line

end module kcreep_contact_input
