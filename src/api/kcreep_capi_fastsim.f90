!> The C API's calls with friction on a solved handle's patch
!> (include/kcreep.h): kcreep_fastsim (FASTSIM) and kcreep_rolling (exact
!> steady rolling), with the same conventions and the same pressure;
!> kcreep_coarsen_patch, a coarser grid for them.
module kcreep_capi_fastsim
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_f_pointer, c_associated, c_null_ptr
  use kcreep_kinds, only: wp
  use kcreep_status, only: fail, exit_bad_input
  use kcreep_strings, only: itoa
  use kcreep, only: creep_request_t, creep_point_t, creep_map_t, creep_curve, flexibility_rule_of, &
                    rolling_request_t, rolling_point_t, rolling_curve, build_fast_forces, fast_forces_of, &
                    fast_forces_t, coarsened_patch, patch_t
  use kcreep_capi_handle, only: handle_t, status_ok, solved, finish, from_c
  use kcreep_threads, only: team_size, enter_team, leave_team, cells_per_thread_iterative
  use, intrinsic :: iso_fortran_env, only: int64
  implicit none
  private

contains

  !> FASTSIM with friction mu on the solved patch for n creepages
  !> creep[3 k + 0..2] = (xi, eta, phi), with the patch's exact L1 L2 L3.
  !> pressure: mx * my values on the patch's grid (rows in increasing y), or
  !> NULL for the pressure of the normal problem (after kcreep_set_gap).
  !> rule: "aligned" (the program's default: each creepage term with its own
  !> L, slipping tractions opposing the slip; docs/fastsim.md), "separate"
  !> (each term with its own L, slipping tractions along the predictor) or
  !> "weighted" (Kalker's single weighted L). Out: force[3 k + 0..2] = (Fx, Fy, Mz),
  !> adhesion[k] = fraction of the area in adhesion (may be NULL).
  integer(c_int) function c_fastsim(handle, mu, n, creep, pressure, rule, force, adhesion) &
    bind(c, name='kcreep_fastsim')
    type(c_ptr), value :: handle, creep, pressure, rule, force, adhesion
    real(c_double), value :: mu
    integer(c_int), value :: n
    type(handle_t), pointer :: h
    real(c_double), pointer :: creepages(:, :), forces(:, :), adhered(:)
    real(wp), allocatable :: pn(:, :)
    type(creep_request_t) :: request
    type(creep_point_t), allocatable :: points(:)
    type(creep_map_t), allocatable :: maps(:)
    character(len=:), allocatable :: rule_name
    integer :: k
    c_fastsim = solved(handle, h)
    if (c_fastsim /= status_ok) return
    if (.not. (mu > 0 .and. mu < huge(1.0_wp)) .or. n < 1) then
      call fail(h%last, exit_bad_input, 'kcreep_fastsim: mu must be finite and > 0, n >= 1')
    else if (.not. c_associated(creep) .or. .not. c_associated(force) .or. .not. c_associated(rule)) then
      call fail(h%last, exit_bad_input, 'kcreep_fastsim: creep, rule and force must not be NULL')
    else if (.not. c_associated(pressure) .and. .not. h%result%normal_solved) then
      call fail(h%last, exit_bad_input, 'kcreep_fastsim: pressure is NULL and the last solve had no normal problem')
    end if
    if (h%last%failed()) then
      c_fastsim = finish(h)
      return
    end if
    rule_name = from_c(rule, 16)
    request%rule = flexibility_rule_of(rule_name)
    if (request%rule == 0) then
      call fail(h%last, exit_bad_input, 'kcreep_fastsim: rule = "'//rule_name//'" (allowed: aligned, separate, weighted)')
      c_fastsim = finish(h)
      return
    end if
    call pressure_of(h, pressure, 'kcreep_fastsim', pn)
    if (h%last%failed()) then
      c_fastsim = finish(h)
      return
    end if
    call c_f_pointer(creep, creepages, [3, int(n)])
    request%mu = mu
    request%creepages = creepages
    call creep_curve(h%result, pn, request, points, maps)
    call c_f_pointer(force, forces, [3, int(n)])
    do k = 1, n
      forces(:, k) = [points(k)%force%fx, points(k)%force%fy, points(k)%force%mz]
    end do
    if (c_associated(adhesion)) then
      call c_f_pointer(adhesion, adhered, [int(n)])
      adhered = [(points(k)%force%adhesion, k=1, n)]
    end if
  end function c_fastsim

  !> Exact steady rolling with friction mu on the solved patch (docs/rolling.md),
  !> the same conventions as kcreep_fastsim: creep[3 k + 0..2], pressure (or
  !> NULL), force[3 k + 0..2] = (Fx, Fy, Mz), adhesion[k] (may be NULL).
  integer(c_int) function c_rolling(handle, mu, n, creep, pressure, force, adhesion) bind(c, name='kcreep_rolling')
    type(c_ptr), value :: handle, creep, pressure, force, adhesion
    real(c_double), value :: mu
    integer(c_int), value :: n
    type(handle_t), pointer :: h
    real(c_double), pointer :: creepages(:, :), forces(:, :), adhered(:)
    real(wp), allocatable :: pn(:, :)
    type(rolling_request_t) :: request
    type(rolling_point_t), allocatable :: points(:)
    type(creep_map_t), allocatable :: maps(:)
    integer :: k
    c_rolling = solved(handle, h)
    if (c_rolling /= status_ok) return
    if (.not. (mu > 0 .and. mu < huge(1.0_wp)) .or. n < 1) then
      call fail(h%last, exit_bad_input, 'kcreep_rolling: mu must be finite and > 0, n >= 1')
    else if (.not. c_associated(creep) .or. .not. c_associated(force)) then
      call fail(h%last, exit_bad_input, 'kcreep_rolling: creep and force must not be NULL')
    else if (.not. c_associated(pressure) .and. .not. h%result%normal_solved) then
      call fail(h%last, exit_bad_input, 'kcreep_rolling: pressure is NULL and the last solve had no normal problem')
    end if
    if (.not. h%last%failed()) call pressure_of(h, pressure, 'kcreep_rolling', pn)
    if (.not. h%last%failed()) then
      call c_f_pointer(creep, creepages, [3, int(n)])
      request%mu = mu
      request%creepages = creepages
      request%threads = h%problem%solve%threads
      if (allocated(h%result%traction)) then
        call rolling_curve(h%result%patch, h%problem%scheme, h%result%nu, h%result%g, h%result%spin_centre, pn, &
                           request, points, maps, h%last, h%result%traction, state=h%rolling)
      else
        call rolling_curve(h%result%patch, h%problem%scheme, h%result%nu, h%result%g, h%result%spin_centre, pn, &
                           request, points, maps, h%last, state=h%rolling)
      end if
    end if
    if (h%last%failed()) then
      c_rolling = finish(h)
      return
    end if
    call c_f_pointer(force, forces, [3, int(n)])
    forces = reshape([(points(k)%force%fx, points(k)%force%fy, points(k)%force%mz, k=1, n)], [3, int(n)])
    if (c_associated(adhesion)) then
      call c_f_pointer(adhesion, adhered, [int(n)])
      adhered = [(points(k)%force%adhesion, k=1, n)]
    end if
  end function c_rolling

  !> The fast force model of the solved patch (docs/rolling.md, "7. In the time step: warm starts and the fast force model"): the
  !> exact rolling forces interpolated in a table of exact solutions over normalised
  !> creepages, built on the first call for a pressure (about a second) and kept on the
  !> handle. Arguments as kcreep_rolling: creep[3 k + 0..2], pressure (or NULL: the
  !> normal problem's), force[3 k + 0..2] = (Fx, Fy, Mz).
  integer(c_int) function c_fast_forces(handle, mu, n, creep, pressure, force) bind(c, name='kcreep_fast_forces')
    type(c_ptr), value :: handle, creep, pressure, force
    real(c_double), value :: mu
    integer(c_int), value :: n
    type(handle_t), pointer :: h
    real(c_double), pointer :: creepages(:, :), forces(:, :)
    real(wp), allocatable :: pn(:, :)
    integer :: previous_team
    c_fast_forces = solved(handle, h)
    if (c_fast_forces /= status_ok) return
    if (.not. (mu > 0 .and. mu < huge(1.0_wp)) .or. n < 1) then
      call fail(h%last, exit_bad_input, 'kcreep_fast_forces: mu must be finite and > 0, n >= 1')
    else if (.not. c_associated(creep) .or. .not. c_associated(force)) then
      call fail(h%last, exit_bad_input, 'kcreep_fast_forces: creep and force must not be NULL')
    else if (.not. c_associated(pressure) .and. .not. h%result%normal_solved) then
      call fail(h%last, exit_bad_input, 'kcreep_fast_forces: pressure is NULL and the last solve had no normal problem')
    end if
    if (.not. h%last%failed()) call pressure_of(h, pressure, 'kcreep_fast_forces', pn)
    if (.not. h%last%failed()) then
      call c_f_pointer(creep, creepages, [3, int(n)])
      if (.not. all(creepages == creepages .and. abs(creepages) < huge(1.0_wp))) &
        call fail(h%last, exit_bad_input, 'kcreep_fast_forces: the creepages must be finite')
    end if
    if (.not. h%last%failed()) then
      call enter_team(team_size(h%problem%solve%threads, int(h%result%patch%n, int64), cells_per_thread_iterative), &
                      previous_team)
      call build_fast_forces(h%result%patch, h%problem%scheme, h%result%nu, h%result%g, h%result%spin_centre, pn, &
                             h%rolling, h%fast, h%last)
      call leave_team(previous_team)
    end if
    if (h%last%failed()) then
      c_fast_forces = finish(h)
      return
    end if
    call c_f_pointer(force, forces, [3, int(n)])
    call fast_forces_of(h%fast, mu, creepages, forces)
    c_fast_forces = finish(h)
  end function c_fast_forces

  !> The solved patch and the normal problem's pressure coarsened by square blocks of cells
  !> to at most max_cells cells (kcreep_grid_transfer coarsened_patch), for the force models
  !> (kcreep_fastsim, kcreep_rolling, kcreep_fast_forces) where the normal grid is finer
  !> than their forces need; the coefficients and their errors stay the solved ones. A
  !> patch of at most max_cells cells is kept as it is.
  integer(c_int) function c_coarsen_patch(handle, max_cells) bind(c, name='kcreep_coarsen_patch')
    type(c_ptr), value :: handle
    integer(c_int), value :: max_cells
    type(handle_t), pointer :: h
    type(patch_t) :: coarse
    real(wp), allocatable :: pn(:, :), coarse_pn(:, :)
    integer :: k
    c_coarsen_patch = solved(handle, h)
    if (c_coarsen_patch /= status_ok) return
    if (max_cells < 16) then
      call fail(h%last, exit_bad_input, 'kcreep_coarsen_patch: max_cells = '//itoa(int(max_cells))// &
                ' (allowed: 16 or more)')
    else if (.not. h%result%normal_solved) then
      call fail(h%last, exit_bad_input, 'kcreep_coarsen_patch: the last solve had no normal problem (its '// &
                'pressure is what is coarsened)')
    else if (h%result%patch%n > max_cells) then
      call pressure_of(h, c_null_ptr, 'kcreep_coarsen_patch', pn)
      call coarsened_patch(h%result%patch, pn, int(max_cells), coarse, coarse_pn)
      if (coarse%n == 0) then
        call fail(h%last, exit_bad_input, 'kcreep_coarsen_patch: max_cells = '//itoa(int(max_cells))// &
                  ' leaves no cell of the patch (allowed: a larger value)')
      else
        h%result%patch = coarse
        h%result%n = coarse%n
        h%result%mx = coarse%mx
        h%result%my = coarse%my
        h%result%pressure = [(coarse_pn(coarse%ix(k), coarse%iy(k)), k=1, coarse%n)]
        if (allocated(h%result%traction)) deallocate (h%result%traction)
        h%fast = fast_forces_t()
      end if
    end if
    c_coarsen_patch = finish(h)
  end function c_coarsen_patch

  !> The pressure for kcreep_fastsim / kcreep_rolling: mx * my values, or the
  !> normal problem's (pressure NULL); an error in h%last when not usable.
  subroutine pressure_of(h, pressure, who, pn)
    type(handle_t), intent(inout) :: h
    type(c_ptr), intent(in) :: pressure
    character(len=*), intent(in) :: who
    real(wp), allocatable, intent(out) :: pn(:, :)
    real(c_double), pointer :: grid(:, :)
    integer :: k
    associate (p => h%result%patch)
      if (c_associated(pressure)) then
        call c_f_pointer(pressure, grid, [p%mx, p%my])
        pn = grid
        if (.not. all(pn >= 0 .and. pn < huge(1.0_wp))) &
          call fail(h%last, exit_bad_input, who//': pressure must be finite and >= 0 on the grid')
      else
        allocate (pn(p%mx, p%my))
        pn = 0
        do k = 1, p%n
          pn(p%ix(k), p%iy(k)) = h%result%pressure(k)
        end do
      end if
    end associate
  end subroutine pressure_of

end module kcreep_capi_fastsim
