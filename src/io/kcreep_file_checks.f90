!> Whole-file reading and the checks every input file gets before it is
!> parsed: it opens, it is a file (not a folder), it can be read, it is not
!> absurdly large.
module kcreep_file_checks
  use, intrinsic :: iso_fortran_env, only: int64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa
  implicit none
  private
  public :: read_input_file, max_input_bytes

  !> Larger input files are refused: the largest legal mask (2000 x 2000
  !> cells, one byte each plus line ends) is about 4 MB.
  integer(int64), parameter :: max_input_bytes = 64_int64 * 1024 * 1024

contains

  !> The bytes of the file at path; label names it in messages (e.g. "input 'a.nml'").
  subroutine read_input_file(path, label, text, status)
    character(len=*), intent(in) :: path, label
    character(len=:), allocatable, intent(out) :: text
    type(status_t), intent(inout) :: status
    integer :: unit, ios
    integer(int64) :: bytes
    character(len=512) :: msg

    text = ''
    open (newunit=unit, file=path, access='stream', form='unformatted', status='old', action='read', &
          iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call fail(status, exit_bad_input, label//': cannot open ('//trim(msg)//')')
      return
    end if
    inquire (unit=unit, size=bytes)
    if (bytes > max_input_bytes) then
      call fail(status, exit_bad_input, label//': '//itoa(int(bytes / 1048576))// &
                ' MiB is too large for an input file (at most 64 MiB)')
      close (unit)
      return
    end if
    if (bytes > 0) then
      deallocate (text)
      allocate (character(len=bytes) :: text)
      read (unit, iostat=ios, iomsg=msg) text
      ! a folder opens on Linux but cannot be read ('Is a directory')
      if (ios /= 0) call fail(status, exit_bad_input, label//': cannot be read ('//trim(msg)// &
                              '); a text file is expected')
    else if (bytes < 0) then
      call fail(status, exit_bad_input, label//': cannot be read (size unknown); a text file is expected')
    end if
    close (unit)
    if (status%failed()) text = ''
  end subroutine read_input_file

end module kcreep_file_checks
