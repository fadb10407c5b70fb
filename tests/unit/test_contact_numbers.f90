!> Unit test of the number handling behind the CONTACT comparison: half a unit
!> in the last printed digit, and the snapping of CONTACT's six-digit grid
!> values to the simple fractions they were computed from.
program test_contact_numbers
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_contact_reader, only: printed_half_unit, simplest_fraction, combined_material
  use kcreep_contact_compare, only: agrees_to_printed
  use unit_checks, only: checker_t
  implicit none
  type(checker_t) :: t
  real(real64) :: g, nu

  call t%check(printed_half_unit('-8418.') == 0.5_real64, 'half unit of -8418. is 0.5')
  call t%check(abs(printed_half_unit('1.439E+04') - 5) < 1e-12_real64, 'half unit of 1.439E+04 is 5')
  call t%check(abs(printed_half_unit('0.4064') - 5e-5_real64) < 1e-18_real64, 'half unit of 0.4064 is 5e-5')
  call t%check(abs(printed_half_unit('0.416667E-01') - 5e-8_real64) < 1e-20_real64, 'half unit of 0.416667E-01')
  call t%check(agrees_to_printed(-8417.555_real64, -8418.0_real64, '-8418.'), '-8417.555 rounds to -8418.')
  call t%check(.not. agrees_to_printed(-8417.45_real64, -8418.0_real64, '-8418.'), '-8417.45 does not')
  call t%check(.not. agrees_to_printed(-0.046_real64, 0.0_real64, '0.000'), '-0.046 is not 0.000')
  ! six-digit grid values of the samples and the fractions behind them
  call t%check(simplest_fraction(0.333333_real64, 5e-7_real64) == 1.0_real64 / 3, '0.333333 -> 1/3')
  call t%check(simplest_fraction(0.416667e-1_real64, 5e-8_real64) == 1.0_real64 / 24, '0.416667E-01 -> 1/24')
  call t%check(simplest_fraction(0.183333_real64, 5e-7_real64) == 11.0_real64 / 60, '0.183333 -> 11/60')
  call t%check(simplest_fraction(-1.58333_real64, 5e-6_real64) == -19.0_real64 / 12, '-1.58333 -> -19/12')
  call t%check(simplest_fraction(-5.5_real64, 5e-6_real64) == -5.5_real64, '-5.50000 stays -5.5')
  ! a value with no simple fraction nearby stays as printed (within its precision anyway)
  call t%check(abs(simplest_fraction(0.123457_real64, 5e-7_real64) - 0.123457_real64) <= 5e-7_real64, &
              '0.123457 stays within its printing precision')
  call combined_material([82000.0_real64, 82000.0_real64], [0.25_real64, 0.25_real64], g, nu)
  call t%check(g == 82000 .and. abs(nu - 0.25_real64) < 1e-15_real64, 'equal bodies: G and nu unchanged')
  call combined_material([100.0_real64, 300.0_real64], [0.2_real64, 0.3_real64], g, nu)
  ! 1/G = (1/100 + 1/300)/2 -> G = 150; nu = G (0.2/100 + 0.3/300)/2 = 0.225
  call t%check(abs(g - 150) < 1e-12_real64 .and. abs(nu - 0.225_real64) < 1e-15_real64, 'combined G = 150, nu = 0.225')

  call t%finish()

end program test_contact_numbers
