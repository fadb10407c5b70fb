!> kcreep's forces for CONTACT's creepages, side by side with CONTACT's.
!>
!> Agreement rule: CONTACT prints FX, FY, MZ to four significant digits; kcreep
!> agrees when its value, rounded to the digits CONTACT printed, is CONTACT's
!> value, i.e. |kcreep - CONTACT| <= half a unit in CONTACT's last printed
!> digit. With slip in CONTACT's solution (NSLIP > 0) the linear
!> (full-adhesion) forces are only an upper bound and no difference is judged.
module kcreep_contact_compare
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_contact_reader, only: contact_case_t, printed_half_unit
  implicit none
  private
  public :: printed_half_unit, agrees_to_printed, contact_forces, comparison_lines, contact_spin_shift

  !> CONTACT evaluates the spin part of the rigid slip at x + DQ/6 ("facphi").
  real(real64), parameter :: contact_spin_shift = 1.0_real64 / 6

contains

  !> kcreep's value rounded to CONTACT's printed digits is CONTACT's printed value.
  pure logical function agrees_to_printed(value, printed_value, printed_text)
    real(real64), intent(in) :: value, printed_value
    character(len=*), intent(in) :: printed_text
    ! the slack only absorbs the binary representation of the printed decimal
    agrees_to_printed = abs(value - printed_value) <= printed_half_unit(printed_text) * (1 + 1e-9_real64)
  end function agrees_to_printed

  !> (FX, FY, MZ) = -[fij] (CKSI, CETA, CPHI); columns of zero creepage are skipped
  !> (they may be NaN when that load case was not solved).
  pure function contact_forces(f, creepage) result(force)
    real(real64), intent(in) :: f(3, 3), creepage(3)
    real(real64) :: force(3)
    integer :: j
    force = 0
    do j = 1, 3
      if (creepage(j) /= 0) force = force - f(:, j) * creepage(j)
    end do
  end function contact_forces

  !> The comparison block of kcreep's summary: one line per force, then the verdict.
  !> Lines start with 'CONTACT' so that scripts can pick them out.
  function comparison_lines(c, f, contact_like) result(lines)
    type(contact_case_t), intent(in) :: c
    real(real64), intent(in) :: f(3, 3)
    logical, intent(in) :: contact_like   !< backward scheme with spin_shift = 1/6
    character(len=300), allocatable :: lines(:)
    character(len=2), parameter :: names(3) = ['FX', 'FY', 'MZ']
    real(real64) :: mine(3), theirs(3)
    character(len=32) :: printed(3), rel
    logical :: ok(3)
    integer :: i
    character(len=:), allocatable :: bad

    mine = contact_forces(f, [c%cksi, c%ceta, c%cphi])
    theirs = [c%fx, c%fy, c%mz]
    printed = [c%fx_text, c%fy_text, c%mz_text]
    allocate (lines(6))
    write (lines(1), '(a, i0, a, es10.3, a, es10.3, a, es10.3, a, i0, a, i0, a)') 'CONTACT case ', c%case_number, &
      ': CKSI = ', c%cksi, ', CETA = ', c%ceta, ', CPHI = ', c%cphi, '; NCON = ', c%ncon, ', NSLIP = ', c%nslip, &
      '; mask from the '//c%mask_source
    lines(2) = 'CONTACT    force      CONTACT           kcreep    rel.diff  to the printed digits'
    bad = ''
    do i = 1, 3
      ok(i) = agrees_to_printed(mine(i), theirs(i), printed(i))
      if (theirs(i) /= 0) then
        write (rel, '(es10.2)') (mine(i) - theirs(i)) / abs(theirs(i))
      else
        rel = '         -'
      end if
      write (lines(2 + i), '(a, 6x, a2, 1x, a12, 1x, es16.8, 1x, a10, 2x, a)') 'CONTACT', names(i), &
        adjustr(printed(i)(1:12)), mine(i), rel(1:10), trim(judgement(ok(i), c%nslip > 0))
      if (.not. ok(i)) bad = bad//' '//names(i)
    end do
    if (c%nslip > 0) then
      lines(6) = 'CONTACT verdict: slip in CONTACT''s solution (NSLIP > 0): kcreep''s full-adhesion forces are an '// &
                 'upper bound, the linear comparison does not hold'
    else if (all(ok)) then
      lines(6) = 'CONTACT verdict: agrees with CONTACT to its printed digits (FX, FY, MZ)'
    else
      lines(6) = 'CONTACT verdict: DIFFERS from CONTACT beyond its printed digits in'//bad
    end if
    if (.not. contact_like) lines(6) = trim(lines(6))// &
      ' (note: CONTACT''s conventions were switched off in &solver)'
  end function comparison_lines

  pure function judgement(ok, slip) result(word)
    logical, intent(in) :: ok, slip
    character(len=12) :: word
    if (slip) then
      word = 'not judged'
    else if (ok) then
      word = 'agrees'
    else
      word = 'differs'
    end if
  end function judgement

end module kcreep_contact_compare
