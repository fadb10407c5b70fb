!> The kinds kcreep computes with: double precision reals throughout, and
!> 64-bit integers for byte counts and clocks.
module kcreep_kinds
  use, intrinsic :: iso_fortran_env, only: real64, int64
  implicit none
  private
  public :: wp, long

  integer, parameter :: wp = real64     !< every real in kcreep
  integer, parameter :: long = int64    !< byte counts, clock ticks
end module kcreep_kinds
