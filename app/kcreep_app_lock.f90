!> File-system calls of the command line through C: an exclusive lock on a
!> file (flock(2)), so that two programs do not write the same table, and
!> realpath(3). The lock lives as long as its file descriptor: it is released
!> when the process ends, however it ends (a kill, a crash).
module kcreep_app_lock
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_long, c_ptr, c_size_t, c_null_ptr, &
                                         c_associated, c_f_pointer
  implicit none
  private
  public :: lock_exclusive, truncate_locked, real_path

  ! <fcntl.h> and <sys/file.h> on Linux (every architecture kcreep builds on)
  integer(c_int), parameter :: o_rdwr = 2, o_creat = 64, lock_ex = 2, lock_nb = 4
  integer(c_int), parameter :: mode_rw_r_r = int(o'644', c_int)

  interface
    function c_open(path, flags, mode) bind(c, name='open') result(fd)
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: flags, mode
      integer(c_int) :: fd
    end function c_open
    function c_flock(fd, operation) bind(c, name='flock') result(rc)
      import :: c_int
      integer(c_int), value :: fd, operation
      integer(c_int) :: rc
    end function c_flock
    function c_realpath(path, resolved) bind(c, name='realpath') result(p)
      import :: c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      type(c_ptr), value :: resolved
      type(c_ptr) :: p
    end function c_realpath
    subroutine c_free(p) bind(c, name='free')
      import :: c_ptr
      type(c_ptr), value :: p
    end subroutine c_free
    function c_strlen(p) bind(c, name='strlen') result(n)
      import :: c_ptr, c_size_t
      type(c_ptr), value :: p
      integer(c_size_t) :: n
    end function c_strlen
    function c_ftruncate(fd, length) bind(c, name='ftruncate') result(rc)
      import :: c_int, c_long
      integer(c_int), value :: fd
      integer(c_long), value :: length
      integer(c_int) :: rc
    end function c_ftruncate
  end interface

contains

  !> Open (creating it if need be) path and take an exclusive lock on it
  !> without waiting. fd: the descriptor holding the lock (kept open until the
  !> process ends), or -1. held: another process holds the lock.
  subroutine lock_exclusive(path, fd, held)
    character(len=*), intent(in) :: path
    integer(c_int), intent(out) :: fd
    logical, intent(out) :: held
    held = .false.
    fd = c_open(path//c_null_char, ior(o_rdwr, o_creat), mode_rw_r_r)
    if (fd < 0) return
    if (c_flock(fd, ior(lock_ex, lock_nb)) /= 0) then
      held = .true.
      fd = -1            ! (left open: closing it is not needed for a refusal that ends the run)
    end if
  end subroutine lock_exclusive

  !> The canonical absolute path of an existing file or folder (realpath(3):
  !> symbolic links, '.' and '..' resolved), or '' when it cannot be resolved.
  function real_path(path) result(resolved)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: resolved
    type(c_ptr) :: p
    character(kind=c_char), pointer :: chars(:)
    integer :: i, n
    p = c_realpath(path//c_null_char, c_null_ptr)
    if (.not. c_associated(p)) then
      resolved = ''
      return
    end if
    n = int(c_strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate (character(len=n) :: resolved)
    do i = 1, n
      resolved(i:i) = chars(i)
    end do
    call c_free(p)
  end function real_path

  !> Empty the locked file in place (the same file: a new one would not be locked).
  logical function truncate_locked(fd) result(ok)
    integer(c_int), intent(in) :: fd
    ok = c_ftruncate(fd, 0_c_long) == 0
  end function truncate_locked

end module kcreep_app_lock
