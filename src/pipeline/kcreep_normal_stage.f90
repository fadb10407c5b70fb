!> From the normal contact problem to the patch: solve for the pressure on
!> the gap's grid, take the cells with positive pressure (cropped to their
!> bounding box; the influence coefficients depend on cell offsets only, so
!> cropping changes nothing) as the patch, and keep the pressure per patch
!> cell for the result.
module kcreep_normal_stage
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_patch, only: patch_t, mask_patch
  use kcreep_normal_influence, only: compliance_from_g_nu
  use kcreep_normal_solve, only: normal_result_t, normal_options_t, solve_normal
  use kcreep_problem, only: problem_t, result_t
  use kcreep_verdict, only: message_length
  implicit none
  private
  public :: normal_patch, store_normal

contains

  !> Solve problem%normal and return the contact patch; nres holds the
  !> pressure on the patch's bounding box. start: a pressure on the gap's
  !> grid to start the solver from.
  subroutine normal_patch(problem, patch, nres, status, start)
    type(problem_t), intent(in) :: problem
    type(patch_t), intent(out) :: patch
    type(normal_result_t), intent(out) :: nres
    type(status_t), intent(inout) :: status
    real(real64), intent(in), optional :: start(:, :)
    real(real64) :: compliance
    type(normal_options_t) :: options
    integer :: ilo, ihi, jlo, jhi
    logical, allocatable :: contact(:, :)

    associate (np => problem%normal, gap => problem%normal%gap)
      if (.not. allocated(gap%h)) then
        call fail(status, exit_bad_input, 'normal problem: no undeformed distance given')
        return
      end if
      if (problem%extrapolate) then
        call fail(status, exit_bad_input, 'normal problem: mesh extrapolation is not available for a patch '// &
                  'found from the gap (refine the gap''s grid instead)')
        return
      end if
      compliance = np%compliance
      if (compliance <= 0) compliance = compliance_from_g_nu(problem%g, problem%nu)
      options = np%options
      options%threads = problem%solve%threads   ! one thread knob for every stage
      if (np%force_given) then
        call solve_normal(gap%h, gap%dx, gap%dy, compliance, options, nres, status, normal_force=np%normal_force, &
                          start=start)
      else
        call solve_normal(gap%h, gap%dx, gap%dy, compliance, options, nres, status, approach=np%approach, start=start)
      end if
      if (status%failed()) return
      contact = nres%pressure > 0
      if (.not. any(contact)) then
        call fail(status, exit_bad_input, 'normal problem: no cell in contact')
        return
      end if
      ilo = findloc(any(contact, dim=2), .true., dim=1)
      ihi = findloc(any(contact, dim=2), .true., dim=1, back=.true.)
      jlo = findloc(any(contact, dim=1), .true., dim=1)
      jhi = findloc(any(contact, dim=1), .true., dim=1, back=.true.)
      call mask_patch(contact(ilo:ihi, jlo:jhi), gap%dx, gap%dy, gap%cell_x(ilo), gap%cell_y(jlo), &
                      'normal problem', patch, status)
      if (status%failed()) return
      patch%kind = 'gap'
      ! keep only the bounding box of the pressure, aligned with the patch grid
      nres%pressure = nres%pressure(ilo:ihi, jlo:jhi)
    end associate
  end subroutine normal_patch

  !> The normal results into result (after the tangential solve on patch).
  subroutine store_normal(nres, patch, result)
    type(normal_result_t), intent(in) :: nres
    type(patch_t), intent(in) :: patch
    type(result_t), intent(inout) :: result
    integer :: k
    character(len=message_length), allocatable :: more(:)
    result%normal_solved = .true.
    result%fn = nres%fn
    result%approach = nres%approach
    result%pmax = nres%pmax
    result%normal_residual = nres%residual
    result%normal_iterations = nres%iterations
    allocate (result%pressure(patch%n))
    do k = 1, patch%n
      result%pressure(k) = nres%pressure(patch%ix(k), patch%iy(k))
    end do
    result%bbox = patch%grid_box()
    if (nres%touches_edge) then
      allocate (more(1))
      more(1) = 'the contact area reaches the edge of the gap''s grid: the potential contact area is too small, '// &
                'enlarge the grid (margin) or the gap file'
      if (allocated(result%warnings)) then
        result%warnings = [result%warnings, more]
      else
        result%warnings = more
      end if
    end if
  end subroutine store_normal

end module kcreep_normal_stage
