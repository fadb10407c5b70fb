!> How much memory this process may use: the program measures it here and
!> hands it to the library as a solver option (the library reads nothing
!> of the machine itself).
module kcreep_app_memory
  use, intrinsic :: iso_fortran_env, only: int64
  implicit none
  private
  public :: memory_limit_bytes

contains

  !> MemAvailable from /proc/meminfo in bytes, or -1 when it cannot be read.
  function memory_limit_bytes() result(bytes)
    integer(int64) :: bytes
    integer :: unit, ios
    character(len=256) :: line
    integer(int64) :: kib
    bytes = -1
    open (newunit=unit, file='/proc/meminfo', status='old', action='read', iostat=ios)
    if (ios /= 0) return
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (line(1:13) == 'MemAvailable:') then
        read (line(14:), *, iostat=ios) kib
        if (ios == 0) bytes = 1024 * kib
        exit
      end if
    end do
    close (unit)
  end function memory_limit_bytes

end module kcreep_app_memory
