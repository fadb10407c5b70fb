!> How much memory this process may use: the program measures it here and
!> hands it to the library as a solver option (the library reads nothing
!> of the machine itself).
!>
!> The smallest of
!>   - MemAvailable of /proc/meminfo (the machine),
!>   - each memory cgroup limit above the process, minus what the cgroup
!>     already uses (v2: memory.max - memory.current; v1:
!>     memory.limit_in_bytes - memory.usage_in_bytes; every SLURM job has one),
!>   - RLIMIT_AS (ulimit -v) minus the address space already mapped (VmSize),
!>     less a reserve for OpenBLAS's own work buffers: under an address-space
!>     limit OpenBLAS retries a refused buffer mmap for ever instead of
!>     failing (measured: dgetrf maps 128 MiB at once), so the dense solver
!>     must leave it that room.
!> -1 when none of them can be read (no limit is checked then).
module kcreep_app_memory
  use, intrinsic :: iso_fortran_env, only: int64
  use, intrinsic :: iso_c_binding, only: c_int, c_long
  implicit none
  private
  public :: memory_limit_bytes, address_space_reserve

  !> Room left for OpenBLAS's buffers under RLIMIT_AS (two of its 128 MiB maps).
  integer(int64), parameter :: address_space_reserve = 256_int64 * 1024 * 1024
  integer(c_int), parameter :: rlimit_as = 9      ! <sys/resource.h>, Linux

  type, bind(c) :: rlimit_t
    integer(c_long) :: cur, max                   ! rlim_t; RLIM_INFINITY reads as -1
  end type rlimit_t

  interface
    function c_getrlimit(resource, limit) bind(c, name='getrlimit') result(rc)
      import :: c_int, rlimit_t
      integer(c_int), value :: resource
      type(rlimit_t), intent(out) :: limit
      integer(c_int) :: rc
    end function c_getrlimit
  end interface

contains

  function memory_limit_bytes() result(bytes)
    integer(int64) :: bytes
    bytes = -1
    call take(meminfo_bytes('MemAvailable:'))
    call take(cgroup_room())
    call take(address_space_room())
  contains
    subroutine take(candidate)
      integer(int64), intent(in) :: candidate
      if (candidate < 0) return
      if (bytes < 0 .or. candidate < bytes) bytes = candidate
    end subroutine take
  end function memory_limit_bytes

  !> RLIMIT_AS minus VmSize minus the reserve (at least 0), or -1 without a limit.
  function address_space_room() result(bytes)
    integer(int64) :: bytes
    type(rlimit_t) :: limit
    integer(int64) :: mapped
    bytes = -1
    if (c_getrlimit(rlimit_as, limit) /= 0) return
    if (limit%cur < 0) return                     ! RLIM_INFINITY
    mapped = status_bytes('VmSize:')
    bytes = max(0_int64, int(limit%cur, int64) - max(mapped, 0_int64) - address_space_reserve)
  end function address_space_room

  !> The least room left under any memory cgroup limit of this process, or -1.
  function cgroup_room() result(bytes)
    integer(int64) :: bytes
    integer :: unit, ios, colon2
    character(len=4096) :: line
    character(len=:), allocatable :: path
    bytes = -1
    open (newunit=unit, file='/proc/self/cgroup', status='old', action='read', iostat=ios)
    if (ios /= 0) return
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (line(1:3) == '0::') then                              ! v2 (unified)
        path = trim(line(4:))
        call walk('/sys/fs/cgroup', path, 'memory.max', 'memory.current')
        call walk('/sys/fs/cgroup/unified', path, 'memory.max', 'memory.current')
      else
        colon2 = index(line, ':memory:')
        if (colon2 > 0) then                                    ! v1
          path = trim(line(colon2 + 8:))
          call walk('/sys/fs/cgroup/memory', path, 'memory.limit_in_bytes', 'memory.usage_in_bytes')
        end if
      end if
    end do
    close (unit)
  contains
    !> Every level from the process's cgroup up to the mount's root.
    subroutine walk(mount, cgroup, limit_file, usage_file)
      character(len=*), intent(in) :: mount, cgroup, limit_file, usage_file
      character(len=:), allocatable :: p
      integer(int64) :: limit, usage
      integer :: slash
      p = cgroup
      do
        limit = number_file(mount//p//'/'//limit_file)
        ! v1 without a limit reads as about 2^63; v2 says 'max' (-1 here)
        if (limit > 0 .and. limit < 2_int64**62) then
          usage = max(0_int64, number_file(mount//p//'/'//usage_file))
          if (bytes < 0 .or. limit - usage < bytes) bytes = max(0_int64, limit - usage)
        end if
        if (len(p) <= 1) exit
        slash = index(p, '/', back=.true.)
        p = p(1:max(slash - 1, 0))
        if (len(p) == 0) p = '/'
      end do
    end subroutine walk
  end function cgroup_room

  !> The first number in a file, or -1 (missing, unreadable, 'max').
  function number_file(path) result(value)
    character(len=*), intent(in) :: path
    integer(int64) :: value
    integer :: unit, ios
    value = -1
    open (newunit=unit, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return
    read (unit, *, iostat=ios) value
    if (ios /= 0) value = -1
    close (unit)
  end function number_file

  !> A 'Key:  N kB' line of /proc/meminfo in bytes, or -1.
  function meminfo_bytes(key) result(bytes)
    character(len=*), intent(in) :: key
    integer(int64) :: bytes
    bytes = key_kib('/proc/meminfo', key)
  end function meminfo_bytes

  !> A 'Key:  N kB' line of /proc/self/status in bytes, or -1.
  function status_bytes(key) result(bytes)
    character(len=*), intent(in) :: key
    integer(int64) :: bytes
    bytes = key_kib('/proc/self/status', key)
  end function status_bytes

  function key_kib(path, key) result(bytes)
    character(len=*), intent(in) :: path, key
    integer(int64) :: bytes, kib
    integer :: unit, ios
    character(len=256) :: line
    bytes = -1
    open (newunit=unit, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (line(1:len(key)) == key) then
        read (line(len(key) + 1:), *, iostat=ios) kib
        if (ios == 0) bytes = 1024 * kib
        exit
      end if
    end do
    close (unit)
  end function key_kib

end module kcreep_app_memory
