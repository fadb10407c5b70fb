!> Writing outputs without ever leaving a half-written file: each file is
!> written to a temporary name in the target folder and renamed into place
!> only when complete, so an existing file is replaced whole or left as it was.
module kcreep_app_files
  use, intrinsic :: iso_fortran_env, only: int64
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
  use kcreep_status, only: status_t, fail, exit_io
  use kcreep_strings, only: itoa
  implicit none
  private
  public :: write_text_file, check_output_path, write_temporary, commit_temporary, discard_temporary

  interface
    integer(c_int) function c_rename(old, new) bind(c, name='rename')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: old(*), new(*)
    end function c_rename
    integer(c_int) function c_getpid() bind(c, name='getpid')
      import :: c_int
    end function c_getpid
  end interface

contains

  !> Fail unless a file can be created at path (its folder exists and is writable).
  subroutine check_output_path(path, variable, status)
    character(len=*), intent(in) :: path, variable
    type(status_t), intent(inout) :: status
    integer :: unit, ios
    character(len=512) :: msg
    character(len=:), allocatable :: probe
    probe = temporary_name(path)
    open (newunit=unit, file=probe, status='new', action='write', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_io, variable//' '''//path//''': cannot create a file there ('// &
                trim(msg)//'); does the folder exist and is it writable?')
      return
    end if
    close (unit, status='delete')
  end subroutine check_output_path

  !> Write lines to path atomically (temporary file in the same folder, then rename).
  subroutine write_text_file(path, lines, variable, status)
    character(len=*), intent(in) :: path, variable
    character(len=*), intent(in) :: lines(:)
    type(status_t), intent(inout) :: status
    call write_temporary(path, lines, variable, status)
    if (.not. status%failed()) call commit_temporary(path, variable, status)
  end subroutine write_text_file

  !> First half of write_text_file: the complete temporary file beside path.
  !> On any error (a full disk among them) the temporary file is removed.
  subroutine write_temporary(path, lines, variable, status)
    character(len=*), intent(in) :: path, variable
    character(len=*), intent(in) :: lines(:)
    type(status_t), intent(inout) :: status
    integer :: unit, ios, k
    integer(int64) :: expected, written
    character(len=512) :: msg
    character(len=:), allocatable :: tmp

    tmp = temporary_name(path)
    open (newunit=unit, file=tmp, status='replace', action='write', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_io, variable//' '''//path//''': cannot create ('//trim(msg)//')')
      return
    end if
    do k = 1, size(lines)
      write (unit, '(a)', iostat=ios, iomsg=msg) trim(lines(k))
      if (ios /= 0) exit
    end do
    if (ios == 0) flush (unit, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      close (unit, status='delete', iostat=k)
      call fail(status, exit_io, variable//' '''//path//''': write failed ('//trim(msg)// &
                '); the previous file, if any, is unchanged')
      return
    end if
    close (unit, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call discard_temporary(path)
      call fail(status, exit_io, variable//' '''//path//''': write failed ('//trim(msg)// &
                '); the previous file, if any, is unchanged')
      return
    end if
    ! libgfortran (12.2) drops ENOSPC from formatted writes without setting
    ! iostat: a full disk shows only as a short file, so check the size
    expected = 0
    do k = 1, size(lines)
      expected = expected + len_trim(lines(k)) + 1
    end do
    inquire (file=tmp, size=written)
    if (written /= expected) then
      call discard_temporary(path)
      call fail(status, exit_io, variable//' '''//path//''': write failed (only '//itoa(int(written))//' of '// &
                itoa(int(expected))//' bytes reached the disk; is it full?); the previous file, if any, is unchanged')
    end if
  end subroutine write_temporary

  !> Second half: rename the finished temporary file onto path.
  subroutine commit_temporary(path, variable, status)
    character(len=*), intent(in) :: path, variable
    type(status_t), intent(inout) :: status
    if (c_rename(temporary_name(path)//c_null_char, path//c_null_char) /= 0) then
      call discard_temporary(path)
      call fail(status, exit_io, variable//' '''//path//''': cannot rename the finished temporary file into place')
    end if
  end subroutine commit_temporary

  !> Remove the temporary file of path, if there is one.
  subroutine discard_temporary(path)
    character(len=*), intent(in) :: path
    integer :: unit, ios
    open (newunit=unit, file=temporary_name(path), status='old', iostat=ios)
    if (ios == 0) close (unit, status='delete', iostat=ios)
  end subroutine discard_temporary

  function temporary_name(path) result(tmp)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: tmp
    tmp = path//'.kcreep-tmp-'//itoa(int(c_getpid()))
  end function temporary_name

end module kcreep_app_files
