!> The &solver group: scheme, error control, solver path, load cases, spin centre.
module kcreep_nml_solver
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: itoa, rtoa, lower
  use kcreep_limits, only: offset_in_range
  use kcreep, only: solver_options_t, validate_solver_options, refine_modes, load_case_names, n_load_cases
  use kcreep_refine_estimate, only: cell_budget_allowed, cell_budget_range
  use kcreep_table_interpolation, only: table_ratio_range
  use kcreep_contact_compare, only: contact_spin_shift
  use kcreep_nml_config, only: config_t, input_where, unset, unset_int
  implicit none
  private
  public :: solver_variables, solver_group_t, read_solver_group, apply_solver_group

  !> The group as written (unset: not given; values the case would not use are refused).
  type :: solver_group_t
    character(len=32) :: scheme = '', method = 'auto', refine = '', spin_centre = 'origin', preconditioner = ''
    real(real64) :: spin_centre_x = unset, spin_centre_y = unset, alpha = unset, spin_shift = unset, &
                    tolerance = unset, target_error = unset, cell_budget = 0
    integer :: extrapolate_levels = unset_int, refine_ratio = unset_int, max_iterations = unset_int, &
               restart = unset_int, threads = 0
    logical :: extrapolate = .false., split_systems = .true.
    character(len=64) :: load_cases = 'xi eta phi'
  end type solver_group_t

  !> The group's variables and their types, as in its namelist statement
  !> (kcreep_namelist_scan diagnose_group explains a failed read with them).
  character(len=*), parameter :: solver_variables(20) = [character(len=26) :: &
    'target_error real', 'cell_budget real', 'scheme character', 'alpha real', 'spin_shift real', &
    'load_cases character', 'extrapolate logical', 'extrapolate_levels integer', 'refine_ratio integer', &
    'refine character', 'method character', 'tolerance real', 'max_iterations integer', 'restart integer', &
    'split_systems logical', 'spin_centre character', 'spin_centre_x real', 'spin_centre_y real', &
    'preconditioner character', 'threads integer']

contains

  subroutine read_solver_group(unit, grp, ios, msg)
    integer, intent(in) :: unit
    type(solver_group_t), intent(out) :: grp
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    character(len=32) :: scheme, method, refine, spin_centre, preconditioner
    real(real64) :: spin_centre_x, spin_centre_y, alpha, spin_shift, tolerance, target_error, cell_budget
    integer :: extrapolate_levels, refine_ratio, max_iterations, restart, threads
    logical :: extrapolate, split_systems
    character(len=64) :: load_cases
    type(solver_options_t) :: defaults
    namelist /solver/ target_error, cell_budget, scheme, alpha, spin_shift, load_cases, extrapolate, extrapolate_levels, &
                      refine_ratio, refine, method, tolerance, max_iterations, restart, split_systems, spin_centre, &
                      spin_centre_x, spin_centre_y, preconditioner, threads

    grp%threads = defaults%threads
    grp%split_systems = defaults%split_systems
    scheme = grp%scheme
    method = grp%method
    refine = grp%refine
    spin_centre = grp%spin_centre
    preconditioner = grp%preconditioner
    spin_centre_x = grp%spin_centre_x
    spin_centre_y = grp%spin_centre_y
    alpha = grp%alpha
    spin_shift = grp%spin_shift
    tolerance = grp%tolerance
    target_error = grp%target_error
    cell_budget = grp%cell_budget
    extrapolate_levels = grp%extrapolate_levels
    refine_ratio = grp%refine_ratio
    max_iterations = grp%max_iterations
    restart = grp%restart
    threads = grp%threads
    extrapolate = grp%extrapolate
    split_systems = grp%split_systems
    load_cases = grp%load_cases
    read (unit, nml=solver, iostat=ios, iomsg=msg)
    grp%scheme = scheme
    grp%method = method
    grp%refine = refine
    grp%spin_centre = spin_centre
    grp%preconditioner = preconditioner
    grp%spin_centre_x = spin_centre_x
    grp%spin_centre_y = spin_centre_y
    grp%alpha = alpha
    grp%spin_shift = spin_shift
    grp%tolerance = tolerance
    grp%target_error = target_error
    grp%cell_budget = cell_budget
    grp%extrapolate_levels = extrapolate_levels
    grp%refine_ratio = refine_ratio
    grp%max_iterations = max_iterations
    grp%restart = restart
    grp%threads = threads
    grp%extrapolate = extrapolate
    grp%split_systems = split_systems
    grp%load_cases = load_cases
  end subroutine read_solver_group

  !> Check &solver and store it in cfg (cfg%shape, semi_a, semi_b and
  !> traction_file set). target_error stays unset when not given: its
  !> default depends on the other groups (kcreep_namelist).
  subroutine apply_solver_group(grp, cfg, status)
    type(solver_group_t), intent(in) :: grp
    type(config_t), intent(inout) :: cfg
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: where, scheme, method
    logical :: scheme_given

    where = input_where(cfg)
    scheme_given = len_trim(grp%scheme) > 0
    scheme = lower(trim(adjustl(grp%scheme)))
    if (.not. scheme_given) scheme = 'backward'
    method = lower(trim(adjustl(grp%method)))
    ! values written that the case would not use: refused, not ignored
    if (scheme == 'collocation' .and. grp%spin_shift /= unset) call fail(status, exit_bad_input, &
        where//'&solver spin_shift = '//rtoa(grp%spin_shift)//' is not used by scheme = ''collocation'' '// &
        '(it moves the spin creepage of the backward scheme; leave it out or set scheme = ''backward'')')
    if (scheme == 'backward' .and. grp%alpha /= unset) call fail(status, exit_bad_input, &
        where//'&solver alpha = '//rtoa(grp%alpha)//' is not used by scheme = ''backward'' '// &
        '(it is the collocation point of scheme = ''collocation''; leave it out or change the scheme)')
    call apply_spin_centre(grp, cfg, where, status)
    ! solver settings of a path the case does not take
    if (.not. grp%extrapolate .and. (grp%extrapolate_levels /= unset_int .or. grp%refine_ratio /= unset_int)) &
      call fail(status, exit_bad_input, where//'&solver extrapolate_levels and refine_ratio are only used with '// &
                'extrapolate = .true. (leave them out, or set extrapolate = .true.)')
    if (method == 'dense' .and. &
        (grp%tolerance /= unset .or. grp%max_iterations /= unset_int .or. grp%restart /= unset_int)) &
      call fail(status, exit_bad_input, where//'&solver tolerance, max_iterations and restart are the '// &
                'iterative solver''s; method = ''dense'' does not use them (leave them out, or use method = '// &
                '''iterative'' or ''auto'')')
    if (method == 'dense' .and. len_trim(grp%preconditioner) > 0) &
      call fail(status, exit_bad_input, where//'&solver preconditioner = '''//trim(grp%preconditioner)// &
                ''' is the iterative solver''s; method = ''dense'' does not use it (leave it out, or use '// &
                'method = ''iterative'' or ''auto'')')
    if (method == 'iterative' .and. len_trim(grp%refine) > 0) &
      call fail(status, exit_bad_input, where//'&solver refine = '''//trim(grp%refine)//''' is the dense LU''s '// &
                'refinement; method = ''iterative'' does not use it (leave it out, or use method = ''dense'')')
    ! method = 'table': interpolation in the refined table of ellipses, nothing solved
    if (method == 'table') then
      if (cfg%shape /= 'ellipse') call fail(status, exit_bad_input, where//'&solver method = ''table'' only '// &
          'for &patch shape = ''ellipse'' (shape = '''//cfg%shape//'''): the refined table holds ellipses; '// &
          'leave method out to solve this patch')
      if (grp%extrapolate) call fail(status, exit_bad_input, where//'&solver extrapolate = .true. with method = '// &
          '''table'' (nothing is solved to extrapolate; leave it out)')
      if (scheme_given .or. grp%alpha /= unset .or. grp%spin_shift /= unset .or. grp%tolerance /= unset .or. &
          grp%max_iterations /= unset_int .or. grp%restart /= unset_int .or. len_trim(grp%refine) > 0 .or. &
          len_trim(grp%preconditioner) > 0) &
        call fail(status, exit_bad_input, where//'&solver scheme, alpha, spin_shift, tolerance, max_iterations, '// &
                  'restart, preconditioner and refine are the solvers''; method = ''table'' solves nothing '// &
                  '(leave them out)')
      if (len(cfg%traction_file) > 0) call fail(status, exit_bad_input, where//'&output traction_file = '''// &
          cfg%traction_file//''': method = ''table'' computes no tractions (leave traction_file out, or '// &
          'leave method out to solve for them)')
    end if
    if (status%failed()) return

    cfg%scheme%name = scheme
    cfg%scheme%alpha = merge(0.5_real64, grp%alpha, grp%alpha == unset)
    ! shape = 'contact' follows CONTACT's conventions unless &solver says otherwise
    cfg%scheme%spin_shift = merge(merge(contact_spin_shift, 0.0_real64, cfg%shape == 'contact'), grp%spin_shift, &
                                  grp%spin_shift == unset)
    cfg%extrapolate = grp%extrapolate
    cfg%extrapolate_levels = merge(3, grp%extrapolate_levels, grp%extrapolate_levels == unset_int)
    cfg%refine_ratio = merge(2, grp%refine_ratio, grp%refine_ratio == unset_int)
    cfg%refine = lower(trim(adjustl(grp%refine)))
    if (len(cfg%refine) == 0) cfg%refine = 'auto'
    cfg%target_error = grp%target_error
    cfg%cell_budget = grp%cell_budget
    cfg%solve%method = method
    cfg%solve%tolerance_given = grp%tolerance /= unset
    if (grp%tolerance /= unset) cfg%solve%tolerance = grp%tolerance
    if (grp%max_iterations /= unset_int) cfg%solve%max_iterations = grp%max_iterations
    if (grp%restart /= unset_int) cfg%solve%restart = grp%restart
    cfg%solve%threads = grp%threads
    if (len_trim(grp%preconditioner) > 0) cfg%solve%preconditioner = lower(trim(adjustl(grp%preconditioner)))
    cfg%solve%split_systems = grp%split_systems

    select case (cfg%scheme%name)
    case ('collocation', 'backward')
    case default
      call fail(status, exit_bad_input, where//'&solver scheme = '''//cfg%scheme%name// &
                ''' (allowed: ''collocation'', ''backward'')')
    end select
    if (.not. (abs(cfg%scheme%alpha) < 1)) call fail(status, exit_bad_input, where// &
        '&solver alpha = '//rtoa(cfg%scheme%alpha)//' (allowed: -1 < alpha < 1, the open interval)')
    if (.not. (abs(cfg%scheme%spin_shift) <= 1)) call fail(status, exit_bad_input, where// &
        '&solver spin_shift = '//rtoa(cfg%scheme%spin_shift)//' (allowed: -1 <= spin_shift <= 1 cell)')
    if (cfg%target_error /= unset .and. .not. (cfg%target_error >= 0 .and. cfg%target_error < 1)) &
      call fail(status, exit_bad_input, where//'&solver target_error = '//rtoa(cfg%target_error)// &
                ' (allowed: 0 <= target_error < 1; 0: the grid as given)')
    if (.not. cell_budget_allowed(cfg%cell_budget)) call fail(status, exit_bad_input, &
        where//'&solver cell_budget = '//rtoa(cfg%cell_budget)//' '//cell_budget_range())
    if (cfg%extrapolate .and. (cfg%extrapolate_levels < 2 .or. cfg%extrapolate_levels > 3)) &
      call fail(status, exit_bad_input, where//'&solver extrapolate_levels = '//itoa(cfg%extrapolate_levels)// &
                ' (allowed: 2 or 3)')
    if (cfg%extrapolate .and. (cfg%refine_ratio < 2 .or. cfg%refine_ratio > 4)) &
      call fail(status, exit_bad_input, where//'&solver refine_ratio = '//itoa(cfg%refine_ratio)// &
                ' (allowed: 2, 3 or 4; every level multiplies the cells per direction by it)')
    if (findloc(refine_modes, cfg%refine, dim=1) == 0) &
      call fail(status, exit_bad_input, where//'&solver refine = '''//cfg%refine// &
                ''' (allowed: ''auto'', ''always'', ''never'', ''lapack'')')
    call parse_load_cases(grp%load_cases, cfg%requested, where, status)
    select case (cfg%solve%method)
    case ('table')
      if (cfg%shape == 'ellipse' .and. .not. status%failed()) then
        if (.not. (cfg%semi_a / cfg%semi_b >= table_ratio_range(1) .and. &
                   cfg%semi_a / cfg%semi_b <= table_ratio_range(2))) call fail(status, exit_bad_input, where// &
            '&patch semi_a/semi_b = '//rtoa(cfg%semi_a / cfg%semi_b)//' (allowed with &solver method = '// &
            '''table'': 0.1 <= a/b <= 10, the refined table''s range; leave method out to solve this ellipse)')
      end if
    case ('dense', 'iterative', 'auto')
      call validate_solver_options(cfg%solve, where, status)
    case default
      call fail(status, exit_bad_input, where//'&solver method = '''//cfg%solve%method// &
                ''' (allowed: ''auto'', ''dense'', ''iterative'', ''table'' for ellipses)')
    end select
  end subroutine apply_solver_group

  !> spin_centre: 'origin', 'centroid' or 'point' (with spin_centre_x, _y).
  subroutine apply_spin_centre(grp, cfg, where, status)
    type(solver_group_t), intent(in) :: grp
    type(config_t), intent(inout) :: cfg
    character(len=*), intent(in) :: where
    type(status_t), intent(inout) :: status

    cfg%spin_centre = lower(trim(adjustl(grp%spin_centre)))
    select case (cfg%spin_centre)
    case ('origin', 'centroid')
      if (cfg%spin_centre == 'centroid' .and. cfg%shape == 'gap') call fail(status, exit_bad_input, where// &
          '&solver spin_centre = ''centroid'' is not available with shape = ''gap'' (the patch is found by the '// &
          'normal problem; spin about the origin)')
      if (grp%spin_centre_x /= unset .or. grp%spin_centre_y /= unset) call fail(status, exit_bad_input, where// &
          '&solver spin_centre_x, spin_centre_y are only used by spin_centre = ''point'' (spin_centre = '''// &
          cfg%spin_centre//''')')
    case ('point')
      if (grp%spin_centre_x == unset .or. grp%spin_centre_y == unset) call fail(status, exit_bad_input, where// &
          '&solver spin_centre = ''point'' needs both spin_centre_x and spin_centre_y')
      if (.not. (offset_in_range(grp%spin_centre_x) .and. offset_in_range(grp%spin_centre_y))) &
        call fail(status, exit_bad_input, where//'&solver spin_centre_x, spin_centre_y = '// &
                  rtoa(grp%spin_centre_x)//', '//rtoa(grp%spin_centre_y)// &
                  ' (allowed: 0 or 1e-30 <= |x|, |y| <= 1e30)')
      cfg%spin_centre_xy = [grp%spin_centre_x, grp%spin_centre_y]
      if (cfg%shape == 'gap') call fail(status, exit_bad_input, where//'&solver spin_centre = ''point'' '// &
          'is not available with shape = ''gap'' (the patch is found by the normal problem; spin about the origin)')
    case default
      call fail(status, exit_bad_input, where//'&solver spin_centre = '''//cfg%spin_centre// &
                ''' (allowed: ''origin'', ''centroid'', ''point'' with spin_centre_x, spin_centre_y)')
    end select
  end subroutine apply_spin_centre

  !> load_cases: words from xi, eta, phi separated by blanks or commas.
  subroutine parse_load_cases(text, requested, where, status)
    character(len=*), intent(in) :: text, where
    logical, intent(out) :: requested(n_load_cases)
    type(status_t), intent(inout) :: status
    character(len=len(text)) :: rest, word
    integer :: cut, k

    requested = .false.
    rest = lower(text)
    do
      rest = adjustl(rest)
      if (len_trim(rest) == 0) exit
      cut = scan(rest, ' ,')
      if (cut == 0) cut = len(rest) + 1
      word = rest(1:cut - 1)
      rest = rest(min(cut + 1, len(rest) + 1):)
      if (len_trim(word) == 0) cycle
      k = findloc(load_case_names, trim(word), dim=1)
      if (k == 0) then
        call fail(status, exit_bad_input, where//'&solver load_cases: unknown case '''//trim(word)// &
                  ''' (allowed: xi, eta, phi)')
        return
      end if
      requested(k) = .true.
    end do
    if (.not. any(requested)) call fail(status, exit_bad_input, where// &
        '&solver load_cases is empty (allowed: any of xi, eta, phi)')
  end subroutine parse_load_cases

end module kcreep_nml_solver
