!> kcreep_rolling_residual: how well CONTACT's tractions of a case satisfy
!> kcreep's discrete rolling problem (the same grid, scheme and pressure):
!> the residual max|F_i| / max(mu pn) of the Coulomb conditions
!> (kcreep_rolling_curve, rolling_residual_of) at the tractions PX, PY of
!> the case's element file, beside the forces summed from it.
!>
!>   kcreep_rolling_residual FILE.out CASE MU
!>
!> Writes one line: case fx_mat fy_mat residual. Used by docs/rolling.md
!> to tell which of CONTACT's two solvers converged where they differ.
program rolling_residual
  use, intrinsic :: iso_fortran_env, only: real64, output_unit, error_unit
  use kcreep_status, only: status_t
  use kcreep_patch, only: patch_t, mask_patch
  use kcreep_assembly, only: scheme_t
  use kcreep_contact_reader, only: contact_case_t, read_contact_case, combined_material
  use kcreep_contact_compare, only: contact_spin_shift
  use kcreep, only: rolling_residual_of
  implicit none
  character(len=4096) :: out_path, arg
  type(contact_case_t) :: c
  type(status_t) :: status
  type(patch_t) :: patch
  type(scheme_t) :: scheme
  real(real64) :: mu, g, nu, v(11), residual
  real(real64), allocatable :: px(:, :), py(:, :), traction(:)
  integer :: case_number, unit, ios, i, ix, iy, k
  character(len=512) :: line

  if (command_argument_count() /= 3) then
    write (error_unit, '(a)') 'usage: kcreep_rolling_residual FILE.out CASE MU'
    error stop 2
  end if
  call get_command_argument(1, out_path)
  call get_command_argument(2, arg); read (arg, *) case_number
  call get_command_argument(3, arg); read (arg, *) mu
  call read_contact_case(trim(out_path), case_number, c, status)
  if (status%failed()) then
    write (error_unit, '(a)') 'kcreep_rolling_residual: '//status%message
    error stop 2
  end if
  call combined_material(c%gg, c%poiss, g, nu)
  call mask_patch(c%inside, c%dx, c%dy, c%xl + c%dx / 2, c%yl + c%dy / 2, 'contact', patch, status)
  scheme%name = 'backward'
  scheme%spin_shift = contact_spin_shift
  ! PX, PY of the element file: rows 'I IGS H MU PN PX PY UN UX UY SREL'
  allocate (px(c%mx, c%my), py(c%mx, c%my))
  px = 0
  py = 0
  open (newunit=unit, file=c%mat_path, status='old', action='read', iostat=ios)
  if (ios /= 0) error stop 'kcreep_rolling_residual: cannot open the element file'
  do
    read (unit, '(a)', iostat=ios) line
    if (ios /= 0) exit
    if (line(1:1) == '%') cycle
    read (line, *, iostat=ios) v
    if (ios /= 0) cycle
    i = nint(v(1))
    if (abs(v(1) - i) > 0 .or. v(2) < 1 .or. v(2) > 2 .or. abs(v(2) - nint(v(2))) > 0) cycle
    ix = mod(i - 1, c%mx) + 1
    iy = (i - 1) / c%mx + 1
    px(ix, iy) = v(6)
    py(ix, iy) = v(7)
  end do
  close (unit)
  allocate (traction(2 * patch%n))
  do k = 1, patch%n
    traction(k) = px(patch%ix(k), patch%iy(k))
    traction(patch%n + k) = py(patch%ix(k), patch%iy(k))
  end do
  residual = rolling_residual_of(patch, scheme, nu, g, [0.0_real64, 0.0_real64], c%pn, mu, &
                                 [c%cksi, c%ceta, c%cphi], traction)
  write (output_unit, '(i0, 2(1x, es16.8), 1x, es10.3)') case_number, sum(px) * c%dx * c%dy, &
    sum(py) * c%dx * c%dy, residual
end program rolling_residual
