!> Creep-force curves: FASTSIM with friction (kcreep_fastsim_forces) on the
!> solved patch, for a list of creepages and one or more flexibility sources:
!>   'exact'            the patch's own L1 L2 L3 from kcreep's coefficients;
!>   'ellipse-box'      the equivalent ellipse of the bounding box (Kalker's table);
!>   'ellipse-moments'  the equivalent ellipse of the second moments;
!>   'user'             given L1 L2 L3.
!> The pressure comes in as an array on the patch's grid (its source is the
!> caller's: Hertz, CONTACT's PN, a file, a model or a normal solve).
module kcreep_creep_curve
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_patch, only: patch_t
  use kcreep_problem, only: result_t
  use kcreep_fastsim_forces, only: fastsim_forces, fastsim_result_t, flexibility_aligned
  use kcreep_equivalent_ellipse, only: ellipse_box, ellipse_moments
  implicit none
  private
  public :: creep_request_t, creep_point_t, creep_map_t, creep_curve, source_flexibilities, source_names

  character(len=16), parameter :: source_names(4) = [character(len=16) :: 'exact', 'ellipse-box', &
                                                     'ellipse-moments', 'user']

  type :: creep_request_t
    real(real64) :: mu = 0                       !< friction coefficient
    real(real64), allocatable :: creepages(:, :) !< (3, n): (xi, eta, phi) of each point
    integer :: rule = flexibility_aligned        !< kcreep_fastsim_forces: flexibility_aligned / _separate / _weighted
    logical :: sources(4) = [.true., .false., .false., .false.]   !< which of source_names
    real(real64) :: user_flex(3) = 0             !< L1 L2 L3 of the source 'user'
    logical :: maps = .false.                    !< keep the traction and stick/slip map of every point
  end type creep_request_t

  type :: creep_point_t
    real(real64) :: creep(3) = 0
    integer :: source = 1                        !< index into source_names
    type(fastsim_result_t) :: force
  end type creep_point_t

  type :: creep_map_t
    real(real64), allocatable :: px(:, :), py(:, :)
    integer, allocatable :: state(:, :)          !< 0 outside, 1 adhesion, 2 slip
  end type creep_map_t

contains

  !> L1 L2 L3 of every source (NaN-free only for the sources that exist).
  pure function source_flexibilities(result, request) result(flex)
    type(result_t), intent(in) :: result
    type(creep_request_t), intent(in) :: request
    real(real64) :: flex(3, size(source_names))
    flex(:, 1) = result%fastsim
    flex(:, 2) = result%ellipse(ellipse_box)%flex
    flex(:, 3) = result%ellipse(ellipse_moments)%flex
    flex(:, 4) = request%user_flex
  end function source_flexibilities

  !> FASTSIM on result%patch with pressure pn (mx, my) for every creepage and requested
  !> source, the spin about result%spin_centre; points ordered by creepage, then source.
  !> maps: allocated when request%maps. Mz is about the spin centre (as the exact solver's).
  pure subroutine creep_curve(result, pn, request, points, maps)
    type(result_t), intent(in) :: result
    real(real64), intent(in) :: pn(:, :)
    type(creep_request_t), intent(in) :: request
    type(creep_point_t), allocatable, intent(out) :: points(:)
    type(creep_map_t), allocatable, intent(out) :: maps(:)
    real(real64) :: flex(3, size(source_names)), x0, y0
    integer :: k, s, n
    associate (p => result%patch)
      flex = source_flexibilities(result, request)
      ! spin about the spin centre, as the coefficients and L were solved (and the exact
      ! rolling solver spins): the patch moved so that the spin centre is the origin
      x0 = p%x0 - result%spin_centre(1)
      y0 = p%y0 - result%spin_centre(2)
      allocate (points(size(request%creepages, 2) * count(request%sources)))
      if (request%maps) then
        allocate (maps(size(points)))
      else
        allocate (maps(0))
      end if
      n = 0
      do k = 1, size(request%creepages, 2)
        do s = 1, size(source_names)
          if (.not. request%sources(s)) cycle
          n = n + 1
          points(n)%creep = request%creepages(:, k)
          points(n)%source = s
          if (request%maps) then
            allocate (maps(n)%px(p%mx, p%my), maps(n)%py(p%mx, p%my), maps(n)%state(p%mx, p%my))
            call fastsim_forces(p%inside, pn, p%dx, p%dy, x0, y0, flex(:, s), request%mu, &
                                request%creepages(:, k), result%c, request%rule, points(n)%force, &
                                maps(n)%px, maps(n)%py, maps(n)%state)
          else
            call fastsim_forces(p%inside, pn, p%dx, p%dy, x0, y0, flex(:, s), request%mu, &
                                request%creepages(:, k), result%c, request%rule, points(n)%force)
          end if
        end do
      end do
    end associate
  end subroutine creep_curve

end module kcreep_creep_curve
