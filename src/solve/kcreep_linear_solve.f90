!> Solve the requested load cases by the chosen method.
!>
!> dense:     LU of each subsystem the scene needs (system_split): a
!>            y-symmetric patch gives two half-size systems, nu = 0 splits
!>            px from py, and a system no requested case needs is skipped.
!>            Residuals for the backward error come from the FFT operator
!>            (O(n log n) instead of O(n^2)).
!> iterative: GMRES on the full system with the FFT operator and the strip
!>            preconditioner; all requested cases in lockstep.
!> auto:      the one estimated faster, and iterative whenever the dense
!>            matrix does not fit in the memory available.
module kcreep_linear_solve
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use kcreep_status, only: status_t, fail, exit_numerical, exit_bad_input
  use kcreep_strings, only: itoa, rtoa
  use kcreep_lapack, only: dgetrf, dgetrs, dgecon
  use kcreep_patch, only: patch_t
  use kcreep_assembly, only: operator_table_t, scheme_t, rigid_creepage, n_load_cases, slip_weight
  use kcreep_dense, only: dense_diagnostics_t, backward_error, relative_residual, &
                          refine_threshold, solve_lapack_expert
  use kcreep_split, only: subsystem_t, plan_subsystems, assemble_subsystem, restrict_to, restrict_projected, &
                          expand_from, shares_transforms
  use kcreep_fft_operator, only: fft_operator_t, create_fft_operator, set_fft_cells, destroy_fft_operator, apply_fft_operator, &
                                 inverse_span
  use kcreep_preconditioner, only: strip_preconditioner_t, build_strip_preconditioner, apply_strip_preconditioner
  use kcreep_circulant_preconditioner, only: circulant_preconditioner_t, build_circulant_preconditioner, &
                                            set_circulant_cells, apply_circulant_preconditioner, &
                                            destroy_circulant_preconditioner
  use kcreep_krylov, only: block_operator_t, gmres_result_t, gmres
  use kcreep_block_operators, only: fft_block_t, circulant_block_t, strip_block_t
  use kcreep_solver_options, only: solver_options_t
  use kcreep_solve_memory, only: iterative_bytes, dense_bytes
  use kcreep_threads, only: team_size, enter_team, leave_team, serial_blas, cells_per_thread_dense, &
                            cells_per_thread_iterative
  implicit none
  private
  public :: solve_load_cases, choose_method, solve_memory_bytes, solve_memory_plan, solve_workspace_t, clear_workspace, &
            check_solve_memory

  !> The block operators (fft_block_t, circulant_block_t, strip_block_t)
  !> are kcreep_block_operators'.


  !> What the solvers build for a grid and not for a patch: the FFT operator
  !> (plans, work grids, kernel spectra) and the circulant preconditioner
  !> (plans, inverse spectra). A caller solving patch after patch on one grid
  !> (kcreep_run's solve_cache_t) keeps it, so that a new patch only moves
  !> their cells (measured, moving 40 x 40 mask: building them took 0.55 ms
  !> of the 5.4 ms a solve took). The kernel spectra are the operator
  !> table's: the keeper clears the workspace when the table changes. Never
  !> copied (it owns FFTW plans and memory); freed when it goes away.
  type :: solve_workspace_t
    private
    logical :: has_operator = .false., has_circulant = .false.
    integer :: mx = 0, my = 0, max_vectors = 0   !< the grid and block width planned for
    real(real64) :: dx = 0, dy = 0, nu = 0
    type(fft_block_t) :: a
    type(circulant_block_t) :: circulant
  contains
    final :: finalise_workspace
  end type solve_workspace_t

  !> Costs for the 'auto' choice, measured on one thread (OMP_NUM_THREADS=1,
  !> the 2-core development machine, shared, so good to about 30 %), on
  !> circles of n cells, whose y-symmetric halves are two systems of about n
  !> unknowns. Dense, the split LU end to end (assembly, dgetrf, dgecon,
  !> dgetrs, FFT residuals), per system of m unknowns 2/3 m^3 / dense_rate +
  !> dense_entry_cost m^2 (the second term: assembly and the O(m^2) LAPACK
  !> steps, and LU's low rate on small matrices): measured 0.55, 1.0, 2.2,
  !> 5.0, 16, 86, 636, 2932 ms at n = 152, 196, 306, 442, 688, 1264, 2828,
  !> 5024, modelled 0.74, 1.25, 3.1, 6.8, 18, 70, 740, 3590 ms (the LU
  !> alone runs at 5.8e10 flop/s at n = 5024). Iterative, one lockstep GMRES
  !> step of the three load cases (operator, circulant preconditioner,
  !> Gram-Schmidt) on the padded FFT grid of G cells: iterative_step_fixed +
  !> iterative_step_cost G log2(G); measured 55 us at 14 x 14 cells, 0.26 ms
  !> at 40 x 40, 35 ms at 296 x 296 (modelled 60 us, 0.35 ms, 26 ms). Its
  !> setup (FFTW plans, kernel and preconditioner spectra), when the solve
  !> workspace does not hold them for the grid yet: iterative_setup_fixed +
  !> iterative_setup_cost G log2(G) (measured 0.55 ms at 40 x 40, 25 ms at
  !> 296 x 296). The choice falls near n = 170 cells, where either takes
  !> about a millisecond (measured dense / iterative with the workspace
  !> kept: 0.55 / 0.83 ms at n = 152, 1.0 / 0.76 ms at n = 196; the moving
  !> 40 x 40 mask of tests/api/api_example.c: 43 / 4.6 ms).
  real(real64), parameter :: dense_rate = 6e10_real64
  real(real64), parameter :: dense_entry_cost = 1.5e-8_real64
  real(real64), parameter :: iterative_step_fixed = 3e-5_real64, iterative_step_cost = 4e-9_real64
  real(real64), parameter :: iterative_setup_fixed = 3e-4_real64, iterative_setup_cost = 4e-9_real64
  !> GMRES iterations assumed by the estimate (circulant preconditioner,
  !> tolerance 1e-11, circles: measured 15 to 17 near the choice (14 x 14 to
  !> 24 x 24), 19 at 40 x 40, 23 at 96 x 96, 26 at 296 x 296).
  integer, parameter :: assumed_iterations = 20

contains

  !> 'dense' or 'iterative' for these options and this patch. prepared: the
  !> iterative path's setup is done (the solve workspace holds the grid's
  !> FFT operator, as in a loop over patches on one grid); default false.
  function choose_method(opts, patch, subs, requested, prepared) result(method)
    type(solver_options_t), intent(in) :: opts
    type(patch_t), intent(in) :: patch
    type(subsystem_t), intent(in) :: subs(:)
    logical, intent(in) :: requested(n_load_cases)
    logical, intent(in), optional :: prepared
    character(len=:), allocatable :: method
    real(real64) :: t_dense, t_iterative, grid_log
    integer :: i
    logical :: setup_done
    if (opts%method /= 'auto') then
      method = opts%method
      return
    end if
    if (.not. dense_fits(subs, opts%memory_limit)) then
      method = 'iterative'
      return
    end if
    t_dense = 0
    do i = 1, size(subs)
      t_dense = t_dense + 2 * real(subs(i)%m, real64)**3 / 3 / dense_rate + dense_entry_cost * real(subs(i)%m, real64)**2
    end do
    grid_log = 4 * real(patch%mx, real64) * patch%my
    grid_log = grid_log * log(grid_log) / log(2.0_real64)
    t_iterative = assumed_iterations * (iterative_step_fixed + iterative_step_cost * grid_log) &
                  * max(1, count(requested)) / 3
    setup_done = .false.
    if (present(prepared)) setup_done = prepared
    if (.not. setup_done) t_iterative = t_iterative + iterative_setup_fixed + iterative_setup_cost * grid_log
    method = merge('dense    ', 'iterative', t_dense <= t_iterative)
    method = trim(method)
  end function choose_method

  !> opts with preconditioner 'auto' made concrete: the circulant one is
  !> built on the backward difference and serves collocation as long as its
  !> point lies ahead of the cell centre (alpha > 0: 25-45 GMRES steps at
  !> alpha 0.25-0.9); at alpha <= 0 it stalls (no convergence in 1000 steps
  !> at alpha = -0.5) and the strip preconditioner takes over (72 steps).
  pure function resolved_preconditioner(opts, scheme) result(out)
    type(solver_options_t), intent(in) :: opts
    type(scheme_t), intent(in) :: scheme
    type(solver_options_t) :: out
    out = opts
    if (trim(out%preconditioner) /= 'auto') return
    if (scheme%name == 'collocation' .and. scheme%alpha <= 0) then
      out%preconditioner = 'strip'
    else
      out%preconditioner = 'circulant'
    end if
  end function resolved_preconditioner

  !> The largest dense subsystem matrix (plus its copy-free solve) fits in available memory.
  logical function dense_fits(subs, memory_limit)
    type(subsystem_t), intent(in) :: subs(:)
    integer(int64), intent(in) :: memory_limit   !< bytes, negative: no limit
    integer(int64) :: have, need
    integer :: i
    need = 0
    do i = 1, size(subs)
      need = max(need, 8_int64 * subs(i)%m * subs(i)%m)
    end do
    have = memory_limit
    dense_fits = have < 0 .or. need <= have * 9 / 10
  end function dense_fits

  !> traction(:, j): (px, py) of load case j for unit creepage; NaN for cases not requested.
  !> refine: 'auto' refines once when the backward error is above round-off,
  !> 'always' / 'never' force it, 'lapack' solves the whole unsplit system with
  !> LAPACK's expert driver (dgesvx, equilibration and refinement) for comparison.
  !> initial: a guess of the tractions (2n, 3), e.g. the solution on the
  !> previous mask of a time-stepping loop; the iterative path starts from it
  !> (and stops at once when it already meets the tolerance), dense ignores it.
  !> workspace: kept by a caller that solves patches on the same grid with
  !> the same table (solve_workspace_t); without it one is built and freed.
  subroutine solve_load_cases(opts, scheme, nu, patch, table, requested, refine, traction, diag, status, initial, &
                              workspace)
    type(solver_options_t), intent(in) :: opts
    type(scheme_t), intent(in) :: scheme
    real(real64), intent(in) :: nu
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    logical, intent(in) :: requested(n_load_cases)
    character(len=*), intent(in) :: refine
    real(real64), allocatable, intent(out) :: traction(:, :)
    type(dense_diagnostics_t), intent(out) :: diag
    type(status_t), intent(inout) :: status
    real(real64), intent(in), optional :: initial(:, :)
    type(solve_workspace_t), intent(inout), optional, target :: workspace
    type(solve_workspace_t), target :: own
    integer :: team, previous_team

    ! the team for this solve, chosen now (kcreep_threads): a ladder of levels
    ! re-judges the machine's load at every level. 'auto' takes the dense LU
    ! only for patches far below a thread's worth of work.
    team = team_size(opts%threads, int(patch%n, int64), &
                     merge(cells_per_thread_dense, cells_per_thread_iterative, opts%method == 'dense'))
    call enter_team(team, previous_team)
    call serial_blas()
    if (present(workspace)) then
      call solve_in(workspace)
    else
      call solve_in(own)
      call clear_workspace(own)
    end if
    call leave_team(previous_team)
    diag%threads = team

  contains

    subroutine solve_in(ws)
      type(solve_workspace_t), intent(inout), target :: ws
      type(subsystem_t), allocatable :: subs(:)
      real(real64), allocatable :: rhs(:, :)
      integer :: j, n
      logical :: fallback

      n = patch%n
      allocate (rhs(2 * n, n_load_cases), traction(2 * n, n_load_cases))
      do j = 1, n_load_cases
        call rigid_creepage(patch, scheme, j, rhs(:, j))
        ! a blended patch's rows weigh the slip by slip_weight (kcreep_assembly)
        if (allocated(patch%fraction)) rhs(:, j) = [slip_weight(patch%fraction), slip_weight(patch%fraction)] * rhs(:, j)
      end do
      traction = ieee_value(1.0_real64, ieee_quiet_nan)
      subs = plan_subsystems(patch, nu, opts%split_systems, requested)
      diag%method = choose_method(opts, patch, subs, requested, operator_ready(ws, patch, nu, count(requested)))
      if (diag%method == 'dense') then
        if (.not. dense_fits(subs, opts%memory_limit)) then
          call fail(status, exit_bad_input, 'method = ''dense'': the largest dense matrix ('// &
                    itoa(maxval(subs%m))//' unknowns) needs '// &
                    rtoa(8 * real(maxval(subs%m), real64)**2 / 2.0_real64**30)//' GiB, only '// &
                    rtoa(real(opts%memory_limit, real64) / 2.0_real64**30)// &
                    ' GiB are available (use method = ''iterative'' or ''auto'')')
          return
        end if
        if (refine == 'lapack') then
          call solve_dense_expert(patch, table, requested, opts%memory_limit, rhs, traction, diag, status)
        else
          call solve_dense_split(ws, nu, patch, table, subs, requested, refine, rhs, traction, diag, status)
        end if
      else
        call check_iterative_memory(opts, nu, patch, requested, 0_int64, status)
        if (status%failed()) return
        call solve_iterative(ws, resolved_preconditioner(opts, scheme), nu, patch, table, requested, rhs, traction, &
                             diag, status, initial)
        fallback = status%code == exit_numerical .and. opts%method == 'auto'
        if (fallback) fallback = dense_fits(subs, opts%memory_limit)
        if (fallback) then
          ! auto promised an answer: GMRES stalls only on hard (near-degenerate)
          ! systems, which the dense LU still solves and the verdict then judges
          status = status_t()
          diag%method = 'dense'
          diag%iterations = 0
          call solve_dense_split(ws, nu, patch, table, subs, requested, refine, rhs, traction, diag, status)
        end if
      end if
    end subroutine solve_in

  end subroutine solve_load_cases

  !> The workspace holds the FFT operator of patch's grid for blocks of max_vectors.
  logical function operator_ready(ws, patch, nu, max_vectors)
    type(solve_workspace_t), intent(in) :: ws
    type(patch_t), intent(in) :: patch
    real(real64), intent(in) :: nu
    integer, intent(in) :: max_vectors
    operator_ready = ws%has_operator .and. ws%mx == patch%mx .and. ws%my == patch%my .and. ws%dx == patch%dx &
                     .and. ws%dy == patch%dy .and. ws%nu == nu .and. ws%max_vectors == max_vectors
  end function operator_ready

  !> The workspace's FFT operator on patch's cells, built when it holds none
  !> for this grid (and whatever it held freed).
  subroutine prepare_operator(ws, nu, patch, table, max_vectors)
    type(solve_workspace_t), intent(inout) :: ws
    real(real64), intent(in) :: nu
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    integer, intent(in) :: max_vectors
    if (operator_ready(ws, patch, nu, max_vectors)) then
      call set_fft_cells(ws%a%op, patch)
      return
    end if
    call clear_workspace(ws)
    call create_fft_operator(patch, table, max_vectors, ws%a%op)
    ws%has_operator = .true.
    ws%mx = patch%mx
    ws%my = patch%my
    ws%dx = patch%dx
    ws%dy = patch%dy
    ws%nu = nu
    ws%max_vectors = max_vectors
  end subroutine prepare_operator

  !> The workspace's circulant preconditioner on patch's cells (after
  !> prepare_operator, whose grid it shares), built on first use.
  subroutine prepare_circulant(ws, nu, patch)
    type(solve_workspace_t), intent(inout) :: ws
    real(real64), intent(in) :: nu
    type(patch_t), intent(in) :: patch
    if (ws%has_circulant) then
      call set_circulant_cells(ws%circulant%p, patch)
    else
      call build_circulant_preconditioner(patch, nu, ws%max_vectors, ws%circulant%p)
      ws%has_circulant = .true.
    end if
  end subroutine prepare_circulant

  !> Free what the workspace holds (the keeper calls this when the operator
  !> table changes); it is then empty, as new.
  subroutine clear_workspace(ws)
    type(solve_workspace_t), intent(inout) :: ws
    if (ws%has_operator) call destroy_fft_operator(ws%a%op)
    if (ws%has_circulant) call destroy_circulant_preconditioner(ws%circulant%p)
    ws%has_operator = .false.
    ws%has_circulant = .false.
  end subroutine clear_workspace

  subroutine finalise_workspace(ws)
    type(solve_workspace_t), intent(inout) :: ws
    call clear_workspace(ws)
  end subroutine finalise_workspace

  !> refine = 'lapack': the whole 2n x 2n system through dense_solver's dgesvx path.
  subroutine solve_dense_expert(patch, table, requested, memory_limit, rhs, traction, diag, status)
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    logical, intent(in) :: requested(n_load_cases)
    integer(int64), intent(in) :: memory_limit
    real(real64), intent(in) :: rhs(:, :)
    real(real64), intent(inout) :: traction(:, :)
    type(dense_diagnostics_t), intent(inout) :: diag
    type(status_t), intent(inout) :: status
    real(real64), allocatable :: x(:, :)
    integer, allocatable :: cases(:)
    integer :: j
    cases = pack([(j, j=1, n_load_cases)], requested)
    x = rhs(:, cases)
    call solve_lapack_expert(patch, table, memory_limit, x, diag, status)
    if (status%failed()) return
    diag%method = 'dense'
    diag%iterations = 0
    do j = 1, size(cases)
      traction(:, cases(j)) = x(:, j)
    end do
  end subroutine solve_dense_expert

  !> Fail before allocating when the iterative path's storage
  !> (kcreep_solve_memory) and extra bytes (the operator table when it is
  !> still to be built) cannot fit in opts%memory_limit.
  subroutine check_iterative_memory(opts, nu, patch, requested, extra, status)
    type(solver_options_t), intent(in) :: opts
    real(real64), intent(in) :: nu
    type(patch_t), intent(in) :: patch
    logical, intent(in) :: requested(n_load_cases)
    integer(int64), intent(in) :: extra
    type(status_t), intent(inout) :: status
    real(real64) :: need, have
    need = iterative_need(opts, nu, patch, requested) + extra
    have = real(opts%memory_limit, real64)
    if (have > 0 .and. need > have) then
      call fail(status, exit_bad_input, 'the iterative solver for '//itoa(patch%n)//' cells needs about '// &
                rtoa(need / 2.0_real64**30)//' GiB, only '//rtoa(have / 2.0_real64**30)// &
                ' GiB are available (use a coarser grid, fewer load_cases or a smaller restart)')
    end if
  end subroutine check_iterative_memory

  !> Before any large allocation (the operator table among them: extra, its
  !> bytes when still to be built): the path 'auto' would take fits, or
  !> status says why not, as solve_load_cases would after the table.
  subroutine check_solve_memory(opts, nu, patch, requested, extra, status)
    type(solver_options_t), intent(in) :: opts
    real(real64), intent(in) :: nu
    type(patch_t), intent(in) :: patch
    logical, intent(in) :: requested(n_load_cases)
    integer(int64), intent(in) :: extra
    type(status_t), intent(inout) :: status
    type(subsystem_t), allocatable :: subs(:)
    real(real64) :: have
    subs = plan_subsystems(patch, nu, opts%split_systems, requested, sizes_only=.true.)
    if (choose_method(opts, patch, subs, requested) == 'dense') then
      have = real(opts%memory_limit, real64)
      if (have > 0 .and. real(dense_bytes(maxval(subs%m)) + extra, real64) > have) then
        call fail(status, exit_bad_input, 'method = ''dense'': the largest dense matrix ('// &
                  itoa(maxval(subs%m))//' unknowns) needs '// &
                  rtoa(real(dense_bytes(maxval(subs%m)) + extra, real64) / 2.0_real64**30)//' GiB, only '// &
                  rtoa(have / 2.0_real64**30)//' GiB are available (use method = ''iterative'' or ''auto'')')
      end if
    else
      call check_iterative_memory(opts, nu, patch, requested, extra, status)
    end if
  end subroutine check_solve_memory

  !> iterative_bytes for the systems solve_iterative would solve.
  real(real64) function iterative_need(opts, nu, patch, requested)
    type(solver_options_t), intent(in) :: opts
    real(real64), intent(in) :: nu
    type(patch_t), intent(in) :: patch
    logical, intent(in) :: requested(n_load_cases)
    iterative_need = iterative_bytes(opts, opts%preconditioner, patch, &
                                     plan_subsystems(patch, nu, opts%split_systems, requested, decouple=.false., &
                                                     sizes_only=.true.), &
                                     requested)
  end function iterative_need

  !> Peak bytes of solve_load_cases for this case, for the method it will take
  !> ('auto' decided as it would be now): the largest dense subsystem matrix
  !> with about 20 vectors of its size, or the iterative solver's storage.
  function solve_memory_bytes(opts, nu, patch, requested) result(bytes)
    type(solver_options_t), intent(in) :: opts
    real(real64), intent(in) :: nu
    type(patch_t), intent(in) :: patch
    logical, intent(in) :: requested(n_load_cases)
    integer(int64) :: bytes
    character(len=:), allocatable :: method
    call solve_memory_plan(opts, nu, patch, requested, bytes, method)
  end function solve_memory_bytes

  !> solve_memory_bytes and the method it assumes ('dense' or 'iterative').
  subroutine solve_memory_plan(opts, nu, patch, requested, bytes, method)
    type(solver_options_t), intent(in) :: opts
    real(real64), intent(in) :: nu
    type(patch_t), intent(in) :: patch
    logical, intent(in) :: requested(n_load_cases)
    integer(int64), intent(out) :: bytes
    character(len=:), allocatable, intent(out) :: method
    type(subsystem_t), allocatable :: subs(:)
    subs = plan_subsystems(patch, nu, opts%split_systems, requested, sizes_only=.true.)
    method = choose_method(opts, patch, subs, requested)
    if (method == 'dense') then
      bytes = dense_bytes(maxval(subs%m))
    else
      bytes = int(iterative_need(opts, nu, patch, requested), int64)
    end if
  end subroutine solve_memory_plan

  subroutine solve_dense_split(ws, nu, patch, table, subs, requested, refine, rhs, traction, diag, status)
    type(solve_workspace_t), intent(inout), target :: ws   !< its FFT operator gives the residuals
    real(real64), intent(in) :: nu
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    type(subsystem_t), intent(in) :: subs(:)
    logical, intent(in) :: requested(n_load_cases)
    character(len=*), intent(in) :: refine   !< 'auto', 'always' or 'never'
    real(real64), intent(in) :: rhs(:, :)
    real(real64), intent(inout) :: traction(:, :)
    type(dense_diagnostics_t), intent(inout) :: diag
    type(status_t), intent(inout) :: status
    real(real64), allocatable :: a(:, :), b(:, :), x(:, :), r(:, :), work(:)
    integer, allocatable :: ipiv(:), iwork(:), cases(:)
    integer :: i, j, m, nrhs, info, n, lda
    integer(int64) :: t0, t1, rate
    real(real64) :: anorm_1, anorm_inf, rcond, berr

    n = patch%n
    call system_clock(t0, rate)
    call prepare_operator(ws, nu, patch, table, count(requested))
    call system_clock(t1)
    diag%t_solve = real(t1 - t0, real64) / rate
    diag%rcond = huge(1.0_real64)
    diag%backward_error = 0
    diag%backward_error_initial = 0
    diag%relative_residual = 0
    do j = 1, n_load_cases
      if (requested(j)) traction(:, j) = 0
    end do
    ! one matrix buffer for all the subsystems: its pages are faulted in once
    ! (first touch of hundreds of MB costs about a tenth of the LU)
    lda = maxval(subs%m)
    call system_clock(t0)
    allocate (a(lda, lda), ipiv(lda), work(4 * lda), iwork(lda), stat=info)
    if (info /= 0) then
      call fail(status, exit_numerical, 'out of memory: the dense matrix of '//itoa(lda)//' unknowns ('// &
                rtoa(8 * real(lda, real64)**2 / 2.0_real64**30)//' GiB) could not be allocated '// &
                '(use a coarser grid or method = ''iterative'')')
      return
    end if
    call system_clock(t1)
    diag%t_assemble = diag%t_assemble + real(t1 - t0, real64) / rate
    do i = 1, size(subs)
      associate (s => subs(i))
        m = s%m
        cases = pack([(j, j=1, n_load_cases)], s%serves .and. requested)
        nrhs = size(cases)
        call system_clock(t0)
        call assemble_subsystem(patch, table, s, a(1:m, 1:m))
        call system_clock(t1)
        diag%t_assemble = diag%t_assemble + real(t1 - t0, real64) / rate

        t0 = t1
        call norms_1_inf(a(1:m, 1:m), anorm_1, anorm_inf)
        call dgetrf(m, m, a, lda, ipiv, info)
        if (info > 0) then
          call fail(status, exit_numerical, 'the influence matrix ('//s%label//') is exactly singular (LU pivot '// &
                    itoa(info)//' is zero); the collocation point or the patch is degenerate')
          return
        end if
        call dgecon('1', m, a, lda, anorm_1, rcond, work, iwork, info)
        diag%rcond = min(diag%rcond, rcond)
        call system_clock(t1)
        diag%t_factor = diag%t_factor + real(t1 - t0, real64) / rate

        t0 = t1
        allocate (b(m, nrhs), r(m, nrhs))
        do j = 1, nrhs
          call restrict_to(s, n, rhs(:, cases(j)), b(:, j))
        end do
        x = b
        call dgetrs('N', m, nrhs, a, lda, ipiv, x, m, info)
        call residual(s, b, x, r)
        berr = backward_error(r, b, x, anorm_inf)
        diag%backward_error_initial = max(diag%backward_error_initial, berr)
        diag%relative_residual = max(diag%relative_residual, relative_residual(r, b))
        if ((refine == 'auto' .and. berr > refine_threshold) .or. refine == 'always') then
          call dgetrs('N', m, nrhs, a, lda, ipiv, r, m, info)
          x = x + r
          call residual(s, b, x, r)
          berr = backward_error(r, b, x, anorm_inf)
          diag%refined = .true.
        end if
        diag%backward_error = max(diag%backward_error, berr)
        do j = 1, nrhs
          call expand_from(s, n, x(:, j), traction(:, cases(j)))
        end do
        deallocate (b, r, x)
        call system_clock(t1)
        diag%t_solve = diag%t_solve + real(t1 - t0, real64) / rate
      end associate
    end do

  contains

    !> r = b - A_s x: the full traction x stands for, through the FFT operator, at the subsystem's rows.
    subroutine residual(s, b, x, r)
      type(subsystem_t), intent(in) :: s
      real(real64), intent(in) :: b(:, :), x(:, :)
      real(real64), intent(out) :: r(:, :)
      real(real64), allocatable :: full(:, :), ax(:, :)
      integer :: k
      allocate (full(2 * n, size(x, 2)), ax(2 * n, size(x, 2)))
      full = 0
      do k = 1, size(x, 2)
        call expand_from(s, n, x(:, k), full(:, k))
      end do
      call apply_fft_operator(ws%a%op, full, ax)
      do k = 1, size(x, 2)
        call restrict_to(s, n, ax(:, k), r(:, k))
        r(:, k) = b(:, k) - r(:, k)
      end do
    end subroutine residual

  end subroutine solve_dense_split

  !> 1-norm and infinity-norm of a in one pass over it (instead of two dlange calls).
  pure subroutine norms_1_inf(a, norm_1, norm_inf)
    real(real64), intent(in) :: a(:, :)
    real(real64), intent(out) :: norm_1, norm_inf
    real(real64) :: row_sums(size(a, 1))
    integer :: j
    row_sums = 0
    norm_1 = 0
    do j = 1, size(a, 2)
      row_sums = row_sums + abs(a(:, j))
      norm_1 = max(norm_1, sum(abs(a(:, j))))
    end do
    norm_inf = maxval(row_sums)
  end subroutine norms_1_inf

  subroutine solve_iterative(ws, opts, nu, patch, table, requested, rhs, traction, diag, status, initial)
    type(solve_workspace_t), intent(inout), target :: ws
    type(solver_options_t), intent(in) :: opts
    real(real64), intent(in) :: nu
    type(patch_t), intent(in) :: patch
    type(operator_table_t), intent(in) :: table
    logical, intent(in) :: requested(n_load_cases)
    real(real64), intent(in) :: rhs(:, :)
    real(real64), intent(inout) :: traction(:, :)
    type(dense_diagnostics_t), intent(inout) :: diag
    type(status_t), intent(inout) :: status
    real(real64), intent(in), optional :: initial(:, :)
    type(strip_block_t), target :: strip
    class(block_operator_t), pointer :: m_inv
    type(gmres_result_t) :: result
    type(subsystem_t), allocatable :: subs(:)
    real(real64), allocatable :: x(:, :), b(:, :)
    integer, allocatable :: case_of(:), sub_of(:)
    logical, allocatable :: rows_used(:)
    integer(int64) :: t0, t1, rate
    integer :: i, j, nc, n, mmax, worst

    n = patch%n
    ! px and py stay together at nu = 0 too: the parity classes then pair on
    ! the transforms (xi with eta, phi alone: two full vectors, apply_expanded),
    ! where the decoupled systems take three (measured: docs/performance.md)
    subs = plan_subsystems(patch, nu, opts%split_systems, requested, decouple=.false.)
    ! one GMRES column per (subsystem, requested load case it serves)
    allocate (case_of(0), sub_of(0))
    do j = 1, n_load_cases
      do i = 1, size(subs)
        if (requested(j) .and. subs(i)%serves(j)) then
          case_of = [case_of, j]
          sub_of = [sub_of, i]
        end if
      end do
    end do
    nc = size(case_of)
    mmax = maxval(subs%m)
    ! rows holding representative cells (all rows unless mirrored partners exist)
    allocate (rows_used(patch%my))
    rows_used = .false.
    do i = 1, size(subs)
      rows_used(patch%iy(subs(i)%cell)) = .true.
    end do

    call system_clock(t0, rate)
    call prepare_operator(ws, nu, patch, table, nc)
    ws%a%subs = subs
    ws%a%sub_of = sub_of
    ws%a%n = n
    call system_clock(t1)
    diag%t_assemble = real(t1 - t0, real64) / rate
    t0 = t1
    select case (trim(opts%preconditioner))
    case ('strip')
      call build_strip_preconditioner(patch, table, strip%p, status, rows_used)
      if (status%failed()) return
      strip%subs = subs
      strip%sub_of = sub_of
      strip%n = n
      m_inv => strip
    case default
      call ws%circulant%set_edge(patch, table)
      call prepare_circulant(ws, nu, ws%circulant%core_patch(patch))
      ws%circulant%subs = subs
      ws%circulant%sub_of = sub_of
      ws%circulant%n = n
      m_inv => ws%circulant
    end select
    call system_clock(t1)
    diag%t_factor = real(t1 - t0, real64) / rate
    t0 = t1
    allocate (x(mmax, nc), b(mmax, nc))
    x = 0
    b = 0
    do i = 1, nc
      if (present(initial)) call restrict_to(subs(sub_of(i)), n, initial(:, case_of(i)), x(1:subs(sub_of(i))%m, i))
      call restrict_to(subs(sub_of(i)), n, rhs(:, case_of(i)), b(1:subs(sub_of(i))%m, i))
    end do
    call gmres(ws%a, m_inv, b, x, opts%tolerance, opts%restart, opts%max_iterations, result)
    call system_clock(t1)
    diag%t_solve = real(t1 - t0, real64) / rate
    diag%rcond = ieee_value(1.0_real64, ieee_quiet_nan)   ! no factorisation to estimate it from
    diag%backward_error = maxval(result%relative_residual)
    diag%backward_error_initial = diag%backward_error
    diag%relative_residual = diag%backward_error
    diag%iterations = maxval(result%iterations)
    diag%t_operator = result%t_operator
    diag%t_preconditioner = result%t_preconditioner
    diag%t_orthogonalise = result%t_orthogonalise
    if (.not. all(result%converged)) then
      worst = maxloc(result%relative_residual, dim=1)
      call fail(status, exit_numerical, 'the iterative solver did not converge: load case '// &
                trim(case_word(case_of(worst)))//' has relative residual '// &
                rtoa(result%relative_residual(worst))//' after '//itoa(result%iterations(worst))// &
                ' GMRES iterations (tolerance '//rtoa(opts%tolerance)// &
                '; raise max_iterations or use method = ''dense'')')
      return
    end if
    do j = 1, n_load_cases
      if (requested(j)) traction(:, j) = 0
    end do
    do i = 1, nc
      call expand_from(subs(sub_of(i)), n, x(1:subs(sub_of(i))%m, i), traction(:, case_of(i)))
    end do

  contains

    pure function case_word(j) result(w)
      integer, intent(in) :: j
      character(len=3) :: w
      w = merge('xi ', merge('eta', 'phi', j == 2), j == 1)
    end function case_word

  end subroutine solve_iterative


end module kcreep_linear_solve
