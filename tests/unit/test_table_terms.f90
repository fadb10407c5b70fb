!> The pairing of patches between two rows of a contact table (table_terms,
!> kcreep_capi_contact_table), which kcreep_wheel_rail_at, kcreep_wheel_rail_forces
!> and kcreep.ContactTable interpolate with:
!>  - the same patch in both rows (same kind, y_rail moved by less than its width):
!>    one term, weights 1 - t and t;
!>  - a tread patch that vanishes while a flange patch appears 2 mm beside it (closer
!>    than the gate, half their widths plus the step): not paired (each alone, with
!>    its own row's weight, fading out and in); pairing by y_rail alone joined them;
!>  - two patches in each row: paired by kind and nearness, the terms in order of y_rail.
program test_table_terms
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep, only: wheel_rail_row_t
  use kcreep_capi_contact_table, only: table_terms
  use unit_checks, only: checker_t
  implicit none
  type(checker_t) :: t
  type(wheel_rail_row_t) :: rows(4)
  integer, allocatable :: terms(:, :)
  real(real64), allocatable :: weights(:, :)

  ! one tread patch at shifts 1 and 2 mm
  rows(1) = row(1.0_real64, -10.0_real64, 12.0_real64, 'tread')
  rows(2) = row(2.0_real64, -9.0_real64, 12.0_real64, 'tread')
  call table_terms(rows(1:2), 1.25_real64, terms, weights)
  call t%check(size(terms, 2) == 1, 'one patch: one term')
  call t%check(all(terms(:, 1) == [1, 2]) .and. all(abs(weights(:, 1) - [0.75_real64, 0.25_real64]) < 1e-15_real64), &
               'one patch: its two rows, weights 0.75 and 0.25')

  ! a tread patch at -10 mm (shift 1) and a flange patch at -8 mm (shift 2): two terms
  rows(2) = row(2.0_real64, -8.0_real64, 6.0_real64, 'flange')
  call table_terms(rows(1:2), 1.5_real64, terms, weights)
  call t%check(size(terms, 2) == 2, 'tread then flange: two terms (not paired)')
  if (size(terms, 2) == 2) then
    call t%check(count(terms == 1) == 1 .and. count(terms == 2) == 1 .and. all(count(terms > 0, 1) == 1), &
                 'tread then flange: each row alone in its own term')
  end if

  ! two patches a row: tread and flange in each, the flange's y_rail nearer the other
  ! row's tread than its own flange's; paired by kind
  rows(1) = row(1.0_real64, -20.0_real64, 14.0_real64, 'tread')
  rows(2) = row(1.0_real64, -28.0_real64, 4.0_real64, 'flange')
  rows(3) = row(2.0_real64, -25.0_real64, 14.0_real64, 'tread')
  rows(4) = row(2.0_real64, -31.0_real64, 4.0_real64, 'flange')
  call table_terms(rows, 1.5_real64, terms, weights)
  call t%check(size(terms, 2) == 2, 'two patches a row: two terms')
  if (size(terms, 2) == 2) then
    call t%check(all(terms(:, 1) == [2, 4]) .and. all(terms(:, 2) == [1, 3]), &
                 'two patches a row: flange with flange, tread with tread, in order of y_rail')
  end if
  call t%finish()

contains

  function row(shift, y_rail, width, kind) result(r)
    real(real64), intent(in) :: shift, y_rail, width
    character(len=*), intent(in) :: kind
    type(wheel_rail_row_t) :: r
    r%shift = shift
    r%y_rail = y_rail
    r%width = width
    r%kind = kind
    r%fn = 1
  end function row

end program test_table_terms
