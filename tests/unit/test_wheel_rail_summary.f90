!> The wheel/rail summary's rows (issue 45, item 7): every number in a field
!> of its own, starting with a blank, so that no two run together and none
!> turns into asterisks, whatever its size ('241.425305.219*******' was C11,
!> C22 and C23 of a row in f7.3 fields); each field right-aligned under its
!> column's name.
program test_wheel_rail_summary
  use, intrinsic :: iso_fortran_env, only: real64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use kcreep, only: wheel_rail_row_t
  use kcreep_app_wheel_rail, only: summary_row, summary_columns
  use unit_checks, only: checker_t
  implicit none
  type(checker_t) :: checks
  type(wheel_rail_row_t) :: row
  character(len=:), allocatable :: line, head
  integer :: k

  head = summary_columns()
  ! an ordinary tread row, then one with every number too wide for a fixed format
  row%shift = 3
  row%patch = 1
  row%fn = 8.033e4_real64
  row%delta = 0.0908_real64
  row%y_rail = -20.44_real64
  row%y_wheel = -12.907_real64
  row%r_wheel = 460.763_real64
  row%c(1:3) = [4.995_real64, 4.754_real64, 2.255_real64]
  row%err = [4.9e-4_real64, 7.9e-4_real64, 2.1e-3_real64]
  row%verdict = 'ok'
  call check_row('tread row')
  row%shift = -12345.678_real64
  row%patch = 12
  row%fn = -2.34e15_real64
  row%delta = -12345.6_real64
  row%y_rail = -1241.425_real64
  row%y_wheel = 123456789.0_real64
  row%r_wheel = 1.0e7_real64
  row%c(1:3) = [241.425_real64, 305.219_real64, -12345.5_real64]
  row%err = ieee_value(1.0_real64, ieee_quiet_nan)
  row%verdict = 'uncertain'
  call check_row('row of huge numbers')
  call checks%check(index(line, '1.2E+04') > 0 .or. index(line, '1.23E+04') > 0, &
                    'a number too wide for its fixed field in ES notation: '//line)
  call checks%check(index(line, '241.425') > 0 .and. index(line, '305.219') > 0, &
                    'C11 and C22 still fixed where they fit: '//line)
  call checks%finish()

contains

  subroutine check_row(what)
    character(len=*), intent(in) :: what
    integer :: n_words, n_names
    line = summary_row(row)
    call checks%check(index(line, '*') == 0, what//': no asterisks: '//line)
    n_words = words(line)
    n_names = words(head)
    call checks%check(n_words == n_names, what//': as many fields as column names ('//itoa(n_words)//', '// &
                      itoa(n_names)//'): '//line)
    ! each field ends where its column's name ends (right-aligned), up to the verdict
    do k = 1, len(head) - len('verdict')
      if (head(k:k) /= ' ' .and. head(k + 1:k + 1) == ' ') &
        call checks%check(line(k:k) /= ' ' .and. line(k + 1:k + 1) == ' ', &
                          what//': a field ends under its name at column '//itoa(k)//': '//line)
    end do
  end subroutine check_row

  integer function words(text)
    character(len=*), intent(in) :: text
    integer :: i
    words = 0
    do i = 1, len(text)
      if (text(i:i) /= ' ' .and. (i == 1 .or. text(max(i - 1, 1):max(i - 1, 1)) == ' ')) words = words + 1
    end do
  end function words

  function itoa(i) result(text)
    integer, intent(in) :: i
    character(len=:), allocatable :: text
    character(len=16) :: buf
    write (buf, '(i0)') i
    text = trim(buf)
  end function itoa

end program test_wheel_rail_summary
