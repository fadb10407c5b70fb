!> The input fingerprint of a case: one SHA-256 over everything its result
!> depends on, the one rule of kcreep --batch's resume, scripts/run_cases.sh
!> and the SLURM route (kcreep --fingerprint prints it for them).
!>
!> What it covers, in this order: the program ('kcreep <version>' and the
!> SHA-256 of the running executable, /proc/self/exe, as sha256sum prints
!> it: a rebuild counts as a change), then the namelist and every file it names for reading, each as
!> its path, a zero byte, its contents and '\0ok\0' (or '\0missing\0' when it
!> cannot be read): mask_file, contact_file and the .mat of its contact_case
!> beside it, gap_file, contact_inp, pressure_input_file, and &wheel_rail's
!> wheel_file and rail_file (and left_wheel_file, left_rail_file). A namelist that cannot be read is fingerprinted
!> by its contents and the reading's error message. Contents decide, not
!> modification times: a file rewritten with an old time still counts as
!> changed.
module kcreep_app_fingerprint
  use, intrinsic :: iso_fortran_env, only: int64
  use kcreep_status, only: status_t
  use kcreep, only: kcreep_version
  use kcreep_namelist, only: config_t, read_config
  implicit none
  private
  public :: program_digest, case_fingerprint, case_inputs, sha256_of

  integer(int64), parameter :: mask32 = 4294967295_int64

  !> A SHA-256 in progress (FIPS 180-4), 32-bit words held in int64.
  type :: sha256_t
    integer(int64) :: h(8) = [1779033703_int64, 3144134277_int64, 1013904242_int64, 2773480762_int64, &
                              1359893119_int64, 2600822924_int64, 528734635_int64, 1541459225_int64]
    character(len=64) :: block = ''
    integer :: fill = 0
    integer(int64) :: total = 0
  end type sha256_t

  integer(int64), parameter :: round_k(64) = [ &
    1116352408_int64, 1899447441_int64, 3049323471_int64, 3921009573_int64, 961987163_int64, 1508970993_int64, &
    2453635748_int64, 2870763221_int64, 3624381080_int64, 310598401_int64, 607225278_int64, 1426881987_int64, &
    1925078388_int64, 2162078206_int64, 2614888103_int64, 3248222580_int64, 3835390401_int64, 4022224774_int64, &
    264347078_int64, 604807628_int64, 770255983_int64, 1249150122_int64, 1555081692_int64, 1996064986_int64, &
    2554220882_int64, 2821834349_int64, 2952996808_int64, 3210313671_int64, 3336571891_int64, 3584528711_int64, &
    113926993_int64, 338241895_int64, 666307205_int64, 773529912_int64, 1294757372_int64, 1396182291_int64, &
    1695183700_int64, 1986661051_int64, 2177026350_int64, 2456956037_int64, 2730485921_int64, 2820302411_int64, &
    3259730800_int64, 3345764771_int64, 3516065817_int64, 3600352804_int64, 4094571909_int64, 275423344_int64, &
    430227734_int64, 506948616_int64, 659060556_int64, 883997877_int64, 958139571_int64, 1322822218_int64, &
    1537002063_int64, 1747873779_int64, 1955562222_int64, 2024104815_int64, 2227730452_int64, 2361852424_int64, &
    2428436474_int64, 2756734187_int64, 3204031479_int64, 3329325298_int64]

contains

  !> 'kcreep <version> <SHA-256 of the executable>': the program part of
  !> every fingerprint (computed once per run, handed to case_fingerprint).
  function program_digest() result(text)
    character(len=:), allocatable :: text
    type(sha256_t) :: sha
    call add_file(sha, '/proc/self/exe', .false.)
    text = 'kcreep '//kcreep_version//' '//sha256_hex(sha)
  end function program_digest

  !> The fingerprint of the case in namelist path (64 hex digits).
  function case_fingerprint(program, path) result(hex)
    character(len=*), intent(in) :: program, path
    character(len=:), allocatable :: hex
    type(sha256_t) :: sha
    type(config_t) :: cfg
    type(status_t) :: status
    character(len=:), allocatable :: inputs(:)
    integer :: k
    call update(sha, program//achar(0))
    call add_file(sha, path, .true.)
    call read_config(path, cfg, status)
    if (status%failed()) then
      call update(sha, 'unreadable: '//status%message//achar(0))
    else
      inputs = case_inputs(cfg)
      do k = 1, size(inputs)
        call add_file(sha, trim(inputs(k)), .true.)
      end do
    end if
    hex = sha256_hex(sha)
  end function case_fingerprint

  !> The files a case reads besides its namelist, in a fixed order.
  function case_inputs(cfg) result(files)
    type(config_t), intent(in) :: cfg
    character(len=:), allocatable :: files(:)
    character(len=4096) :: found(8)
    integer :: n
    n = 0
    if (allocated(cfg%mask_file)) call add(cfg%mask_file)
    if (allocated(cfg%contact_file)) then
      call add(cfg%contact_file)
      if (allocated(cfg%contact%mat_path)) call add(cfg%contact%mat_path)   ! the case's .mat, read or not
    end if
    if (allocated(cfg%gap_file)) call add(cfg%gap_file)
    if (allocated(cfg%contact_inp)) call add(cfg%contact_inp)
    if (allocated(cfg%pressure_input_file)) call add(cfg%pressure_input_file)
    if (cfg%wheel_rail_on) then
      call add(quoted(cfg%wheel_rail%wheel_name))
      call add(quoted(cfg%wheel_rail%rail_name))
      if (allocated(cfg%wheel_rail%left_wheel_name)) call add(quoted(cfg%wheel_rail%left_wheel_name))
      if (allocated(cfg%wheel_rail%left_rail_name)) call add(quoted(cfg%wheel_rail%left_rail_name))
    end if
    allocate (character(len=max(1, maxval([1, len_trim(found(1:n))]))) :: files(n))
    files = found(1:n)
  contains
    subroutine add(name)
      character(len=*), intent(in) :: name
      if (len_trim(name) == 0) return
      n = n + 1
      found(n) = name
    end subroutine add
  end function case_inputs

  !> The path inside "variable 'path'" (the profiles' names as the setup keeps them).
  function quoted(name) result(path)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: path
    integer :: first, last
    first = index(name, '''')
    last = index(name, '''', back=.true.)
    path = ''
    if (last > first + 1) path = name(first + 1:last - 1)
  end function quoted

  !> SHA-256 of text, 64 hex digits.
  function sha256_of(text) result(hex)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: hex
    type(sha256_t) :: sha
    call update(sha, text)
    hex = sha256_hex(sha)
  end function sha256_of

  !> Into sha: named, the path, a zero byte, the contents and an end mark
  !> ('\0ok\0' or '\0missing\0'); else the contents alone (the executable:
  !> its digest is what sha256sum prints).
  subroutine add_file(sha, path, named)
    type(sha256_t), intent(inout) :: sha
    character(len=*), intent(in) :: path
    logical, intent(in) :: named
    character(len=:), allocatable :: buffer
    integer :: unit, ios
    integer(int64) :: bytes
    if (named) call update(sha, path//achar(0))
    open (newunit=unit, file=path, access='stream', form='unformatted', status='old', action='read', iostat=ios)
    if (ios == 0) then
      inquire (unit=unit, size=bytes)
      if (bytes < 0) ios = 1
    end if
    if (ios == 0) then
      allocate (character(len=bytes) :: buffer)
      if (bytes > 0) read (unit, iostat=ios) buffer
      close (unit)
    end if
    if (ios == 0) call update(sha, buffer)
    if (.not. named) return
    if (ios == 0) then
      call update(sha, achar(0)//'ok'//achar(0))
    else
      call update(sha, achar(0)//'missing'//achar(0))
    end if
  end subroutine add_file

  !> Feed bytes to the hash.
  subroutine update(sha, bytes)
    type(sha256_t), intent(inout) :: sha
    character(len=*), intent(in) :: bytes
    integer :: i, take
    i = 1
    sha%total = sha%total + len(bytes)
    do while (i <= len(bytes))
      if (sha%fill == 0 .and. len(bytes) - i + 1 >= 64) then
        call compress(sha%h, bytes(i:i + 63))
        i = i + 64
        cycle
      end if
      take = min(64 - sha%fill, len(bytes) - i + 1)
      sha%block(sha%fill + 1:sha%fill + take) = bytes(i:i + take - 1)
      sha%fill = sha%fill + take
      i = i + take
      if (sha%fill == 64) then
        call compress(sha%h, sha%block)
        sha%fill = 0
      end if
    end do
  end subroutine update

  !> The digest as 64 lower-case hex digits (sha itself is left as it was).
  function sha256_hex(state) result(hex)
    type(sha256_t), intent(in) :: state
    character(len=:), allocatable :: hex
    type(sha256_t) :: sha
    character(len=8) :: tail
    integer(int64) :: bits
    integer :: k
    character(len=64) :: buf
    sha = state
    bits = sha%total * 8
    do k = 8, 1, -1
      tail(k:k) = achar(int(iand(bits, 255_int64)))
      bits = ishft(bits, -8)
    end do
    call update(sha, char(128))
    do while (sha%fill /= 56)
      call update(sha, achar(0))
    end do
    call update(sha, tail)
    write (buf, '(8z8.8)') sha%h
    do k = 1, 64
      if (buf(k:k) >= 'A' .and. buf(k:k) <= 'F') buf(k:k) = achar(iachar(buf(k:k)) + 32)
    end do
    hex = buf
  end function sha256_hex

  !> One 64-byte block into the hash state h.
  pure subroutine compress(h, block)
    integer(int64), intent(inout) :: h(8)
    character(len=64), intent(in) :: block
    integer(int64) :: w(64), a, b, c, d, e, f, g, hh, s0, s1, t1, t2
    integer :: t
    do t = 1, 16
      w(t) = ior(ior(ishft(int(iachar(block(4 * t - 3:4 * t - 3)), int64), 24), &
                     ishft(int(iachar(block(4 * t - 2:4 * t - 2)), int64), 16)), &
                 ior(ishft(int(iachar(block(4 * t - 1:4 * t - 1)), int64), 8), &
                     int(iachar(block(4 * t:4 * t)), int64)))
    end do
    do t = 17, 64
      s0 = ieor(ieor(rotr(w(t - 15), 7), rotr(w(t - 15), 18)), ishft(w(t - 15), -3))
      s1 = ieor(ieor(rotr(w(t - 2), 17), rotr(w(t - 2), 19)), ishft(w(t - 2), -10))
      w(t) = iand(w(t - 16) + s0 + w(t - 7) + s1, mask32)
    end do
    a = h(1); b = h(2); c = h(3); d = h(4); e = h(5); f = h(6); g = h(7); hh = h(8)
    do t = 1, 64
      s1 = ieor(ieor(rotr(e, 6), rotr(e, 11)), rotr(e, 25))
      t1 = iand(hh + s1 + ieor(iand(e, f), iand(ieor(e, mask32), g)) + round_k(t) + w(t), mask32)
      s0 = ieor(ieor(rotr(a, 2), rotr(a, 13)), rotr(a, 22))
      t2 = iand(s0 + ieor(ieor(iand(a, b), iand(a, c)), iand(b, c)), mask32)
      hh = g; g = f; f = e
      e = iand(d + t1, mask32)
      d = c; c = b; b = a
      a = iand(t1 + t2, mask32)
    end do
    h = iand(h + [a, b, c, d, e, f, g, hh], mask32)
  end subroutine compress

  pure integer(int64) function rotr(x, n)
    integer(int64), intent(in) :: x
    integer, intent(in) :: n
    rotr = iand(ior(ishft(x, -n), ishft(x, 32 - n)), mask32)
  end function rotr

end module kcreep_app_fingerprint
