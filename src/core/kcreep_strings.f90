!> Small text helpers for messages and tables.
module kcreep_strings
  use, intrinsic :: iso_fortran_env, only: real64
  implicit none
  private
  public :: itoa, rtoa, printable, lower, one_line, folder_of, resolve_path

contains

  pure function itoa(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    character(len=24) :: buf
    write (buf, '(i0)') i
    s = trim(buf)
  end function itoa

  !> A number as messages show it, in the summary's notation: 0.1 <= |x| < 1e6
  !> in fixed point with 6 significant digits (0.25, 20.0, 80000.0), anything
  !> else in scientific notation with a two- or three-digit exponent (1.0E-03,
  !> 7.81111E-03, 1.0E+301); trailing zeros dropped, one decimal kept.
  pure function rtoa(x) result(s)
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    real(real64), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=40) :: buf
    character(len=16) :: fmt
    integer :: decimals, e
    if (ieee_is_nan(x)) then
      s = 'NaN'
      return
    else if (abs(x) > huge(x)) then
      s = merge('-Inf', ' Inf', x < 0)
      s = trim(adjustl(s))
      return
    else if (x == 0) then
      s = '0.0'
      return
    end if
    if (abs(x) >= 0.1_real64 .and. abs(x) < 1e6_real64) then
      decimals = max(1, 5 - floor(log10(abs(x))))
      write (fmt, '(a, i0, a)') '(f30.', decimals, ')'
      write (buf, fmt) x
      s = trim(adjustl(buf))
      s = strip_zeros(s)
    else
      if (abs(log10(abs(x))) < 99) then
        write (buf, '(es20.5e2)') x
      else
        write (buf, '(es20.5e3)') x
      end if
      buf = adjustl(buf)
      e = index(buf, 'E')
      s = strip_zeros(buf(1:e - 1))//trim(buf(e:))
    end if
  end function rtoa

  !> '2.50000' -> '2.5', '20.0000' -> '20.0': trailing zeros after the point, one digit kept.
  pure function strip_zeros(text) result(s)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: s
    integer :: last, point
    point = index(text, '.')
    last = len_trim(text)
    if (point > 0) then
      do while (last > point + 1 .and. text(last:last) == '0')
        last = last - 1
      end do
    end if
    s = text(1:last)
  end function strip_zeros

  !> A character as it can be shown in a one-line message (control bytes as \xNN).
  pure function printable(c) result(s)
    character(len=1), intent(in) :: c
    character(len=:), allocatable :: s
    character(len=16), parameter :: digits = '0123456789ABCDEF'
    integer :: code
    code = iachar(c)
    if (code < 32 .or. code > 126) then
      s = '\x'//digits(code / 16 + 1:code / 16 + 1)//digits(mod(code, 16) + 1:mod(code, 16) + 1)
    else
      s = c
    end if
  end function printable

  !> text with every control byte shown as \xNN, so that a message stays one
  !> line whatever bytes a bad input put into it.
  pure function one_line(text) result(s)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: s
    integer :: i, j, code, length
    ! sized first: appending byte by byte is quadratic on long bad input
    length = 0
    do i = 1, len(text)
      code = iachar(text(i:i))
      length = length + merge(4, 1, code < 32 .or. code == 127)
    end do
    allocate (character(len=length) :: s)
    j = 0
    do i = 1, len(text)
      code = iachar(text(i:i))
      if (code < 32 .or. code == 127) then
        s(j + 1:j + 4) = printable(text(i:i))
        j = j + 4
      else
        s(j + 1:j + 1) = text(i:i)
        j = j + 1
      end if
    end do
  end function one_line

  pure function lower(text) result(s)
    character(len=*), intent(in) :: text
    character(len=len(text)) :: s
    integer :: i, code
    s = text
    do i = 1, len(s)
      code = iachar(s(i:i))
      if (code >= iachar('A') .and. code <= iachar('Z')) s(i:i) = achar(code + 32)
    end do
  end function lower

  !> The folder part of a path, without the trailing slash ('' for a bare name).
  pure function folder_of(path) result(folder)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: folder
    integer :: slash
    slash = index(path, '/', back=.true.)
    if (slash == 1) then
      folder = '/'
    else if (slash > 1) then
      folder = path(1:slash - 1)
    else
      folder = ''
    end if
  end function folder_of

  !> path taken relative to folder unless it is absolute (or empty, or folder is empty).
  pure function resolve_path(path, folder) result(resolved)
    character(len=*), intent(in) :: path, folder
    character(len=:), allocatable :: resolved
    if (len(path) == 0 .or. len(folder) == 0) then
      resolved = path
    else if (path(1:1) == '/') then
      resolved = path
    else if (folder(len(folder):len(folder)) == '/') then
      resolved = folder//path
    else
      resolved = folder//'/'//path
    end if
  end function resolve_path

end module kcreep_strings
