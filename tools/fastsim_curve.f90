!> kcreep_fastsim_curve: FASTSIM creep forces of a patch given by its pressure
!> on a grid, for a list of creepages, with the flexibilities from the
!> patch's exact coefficients and from its two equivalent ellipses, under
!> both flexibility rules (the comparison with CONTACT uses it).
!>
!>   kcreep_fastsim_curve PRESSURE_FILE CREEP_FILE MU NU G F11 F22 F23 [F33]
!>
!> PRESSURE_FILE: header `mx my dx dy x0 y0`, then my rows of mx pressures
!> (row iy = cell centres y0 + (iy-1) dy, increasing x); the patch is the
!> cells with p > 0. CREEP_FILE: one `xi eta phi` per line. F11 F22 F23:
!> the patch's exact coefficients (kcreep's table); F33 (optional) gives the
!> variant 'separate-m' of the exact source (longitudinal spin term with
!> the flexibility that reproduces f33). Rules: weighted; separate (spin
!> terms with L3); separate-l1 (the -phi y term with L1); aligned (the
!> separate rule in adhesion, slipping tractions opposing the slip: the
!> program's default, docs/fastsim.md). Writes to standard
!> output one row per creepage, source and rule:
!>   source rule xi eta phi fx fy mz fn adhesion
!> and comment lines (#) with the flexibilities of each source.
program fastsim_curve
  use, intrinsic :: iso_fortran_env, only: real64, output_unit, error_unit
  use kcreep_fastsim_forces
  use kcreep_equivalent_ellipse, only: equivalent_ellipse_t, equivalent_ellipses
  implicit none
  character(len=1024) :: pressure_path, creep_path, arg
  real(real64) :: mu, nu, g, f(4), dx, l4, dy, x0, y0, c_len, moments(2), flex(3, 3), creep(3)
  real(real64), allocatable :: pn(:, :), creeps(:, :), tmp(:, :)
  logical, allocatable :: inside(:, :)
  type(equivalent_ellipse_t) :: e(2)
  type(fastsim_result_t) :: r
  character(len=8), parameter :: sources(3) = [character(len=8) :: 'exact', 'box', 'moments']
  character(len=12), parameter :: variants(5) = [character(len=12) :: 'weighted', 'separate', 'separate-l1', &
                                                   'separate-m', 'aligned']
  integer :: unit, ios, mx, my, iy, k, n, src, i, v

  if (command_argument_count() /= 8 .and. command_argument_count() /= 9) then
    write (error_unit, '(a)') 'usage: kcreep_fastsim_curve PRESSURE_FILE CREEP_FILE MU NU G F11 F22 F23 [F33]'
    error stop 2
  end if
  call get_command_argument(1, pressure_path)
  call get_command_argument(2, creep_path)
  call get_command_argument(3, arg); read (arg, *) mu
  call get_command_argument(4, arg); read (arg, *) nu
  call get_command_argument(5, arg); read (arg, *) g
  f(4) = -1
  do i = 1, command_argument_count() - 5
    call get_command_argument(5 + i, arg); read (arg, *) f(i)
  end do

  open (newunit=unit, file=trim(pressure_path), status='old', action='read', iostat=ios)
  if (ios /= 0) call stop_with(trim(pressure_path)//': cannot be opened')
  read (unit, *, iostat=ios) mx, my, dx, dy, x0, y0
  if (ios /= 0 .or. mx < 1 .or. my < 1 .or. dx <= 0 .or. dy <= 0) &
    call stop_with(trim(pressure_path)//': header `mx my dx dy x0 y0` expected with mx, my >= 1, dx, dy > 0')
  allocate (pn(mx, my))
  do iy = 1, my
    read (unit, *, iostat=ios) pn(:, iy)
    if (ios /= 0) call stop_with(trim(pressure_path)//': row of mx pressures expected')
  end do
  close (unit)
  inside = pn > 0

  open (newunit=unit, file=trim(creep_path), status='old', action='read', iostat=ios)
  if (ios /= 0) call stop_with(trim(creep_path)//': cannot be opened')
  allocate (creeps(3, 0))
  n = 0
  do
    read (unit, *, iostat=ios) creep
    if (ios /= 0) exit
    n = n + 1
    allocate (tmp(3, n))
    tmp(:, 1:n - 1) = creeps
    tmp(:, n) = creep
    call move_alloc(tmp, creeps)
  end do
  close (unit)

  moments = mask_strip_integrals(inside, dx, dy, x0)
  flex(:, 1) = [moments(1) / f(1), moments(1) / f(2), moments(2) / f(3)]
  e = equivalent_ellipses(inside, dx, dy, x0, y0, nu, g)
  flex(:, 2) = e(1)%flex
  flex(:, 3) = e(2)%flex
  c_len = sqrt(count(inside) * dx * dy / acos(-1.0_real64))

  write (output_unit, '(a, i0, a, es14.6)') '# cells ', count(inside), '  c = sqrt(area/pi) = ', c_len
  do src = 1, 3
    write (output_unit, '(a, a8, a, 3es14.6)') '# L1 L2 L3 ', sources(src), ' ', flex(:, src)
  end do
  do k = 1, 2
    write (output_unit, '(a, a8, a, 2es14.6, a, 3es14.6)') '# ellipse ', e(k)%kind, ' a b ', e(k)%semi_a, &
      e(k)%semi_b, ' C11 C22 C23 ', e(k)%c
  end do
  l4 = -1
  if (f(4) > 0) l4 = spin_x_flexibility(inside, dx, dy, x0, y0, flex(3, 1), f(4))
  write (output_unit, '(a, es14.6)') '# L of the -phi y term reproducing f33 ', l4
  write (output_unit, '(a)') '# source rule xi eta phi fx fy mz fn adhesion'
  do k = 1, n
    do src = 1, 3
      do v = 1, 5
        select case (v)
        case (1)
          call fastsim_forces(inside, pn, dx, dy, x0, y0, flex(:, src), mu, creeps(:, k), c_len, &
                              flexibility_weighted, r)
        case (2)
          call fastsim_forces(inside, pn, dx, dy, x0, y0, flex(:, src), mu, creeps(:, k), c_len, &
                              flexibility_separate, r)
        case (3)
          call fastsim_forces(inside, pn, dx, dy, x0, y0, flex(:, src), mu, creeps(:, k), c_len, &
                              flexibility_separate, r, flex_spin_x=flex(1, src))
        case (4)
          if (src /= 1 .or. .not. l4 > 0) cycle
          call fastsim_forces(inside, pn, dx, dy, x0, y0, flex(:, src), mu, creeps(:, k), c_len, &
                              flexibility_separate, r, flex_spin_x=l4)
        case (5)
          call fastsim_forces(inside, pn, dx, dy, x0, y0, flex(:, src), mu, creeps(:, k), c_len, &
                              flexibility_aligned, r)
        end select
        write (output_unit, '(a, 1x, a, 8es16.8)') trim(sources(src)), trim(variants(v)), creeps(:, k), &
          r%fx, r%fy, r%mz, r%fn, r%adhesion
      end do
    end do
  end do

contains

  subroutine stop_with(message)
    character(len=*), intent(in) :: message
    write (error_unit, '(a)') 'kcreep_fastsim_curve: error: '//message
    error stop 2
  end subroutine stop_with

end program fastsim_curve
