!> Peak memory of a solve, as the process's resident set (what a machine's
!> free memory, a cgroup or a SLURM job counts), by solve path.
!>
!> Evidence: peak RSS of build/kcreep under GNU time (/usr/bin/time -v),
!> Release build, the 2-core development machine, OMP_NUM_THREADS=1 and the
!> default team alike (equal to 0.1 MB), target_error as the program's default
!> for circles and 0 for masks (one grid). Iterative, 22 runs: unit circles
!> 60 to 1000 cells across (restart 10, 20 and the default 50), a full square
!> mask and a thin ring mask (n / grid cells = 1 and 0.1) at 400 and 1000
!> across (restart 10 and 20). A least-squares fit of
!>   RSS = B + a G + w (V + c)
!> (G grid cells mx my, w bytes of one GMRES basis vector over all columns:
!> 8 sum of the columns' unknowns, V basis vectors GMRES touches: min(restart,
!> iterations) + 1, as pages it never writes are not resident) gave B = 9.8
!> MB, a = 759 bytes (the operator table's 320 among them), c = 18.4 vectors
!> (residuals, work, rhs, tractions, initial guess), within 2 % on every
!> run of 100 cells across or more. The estimate takes B = 11 MB, a = 775,
!> c = 20 and V = min(restart, 34) + 1 for the circulant preconditioner
!> (circles at the default restart 50 converge in 21 to 31 iterations from
!> 60 to 1000 across): 1.009 to 1.165 times the measured peak on all 22 runs
!> (circle 160 x 160: 57.9 against 49.7 MB; 400 x 400: 310 against 272 MB;
!> 1000 x 1000: 1.86 against 1.70 GB). A case taking more than 34 GMRES
!> iterations in one cycle (a tolerance below the default 1e-11 is counted
!> with the whole basis) writes up to restart - 34 more basis vectors than
!> counted. Under error control the estimate is that of the finest level
!> the cell budget allows, where kcreep may stop earlier: the default unit
!> circle, iterative, 102 MB against a 28.5 MB peak; input/crescent.nml
!> 128 MB against 54.5 MB. The strip preconditioner (72 iterations at alpha <= 0) is counted
!> with its whole basis and its LU blocks (an upper bound).
!> Dense, unit circles 40 to 130 across (the largest system m = n
!> unknowns, a y-symmetric half): RSS - 8 m^2 - the table = 17.6, 21.7, 29.4,
!> 38.4, 56.1 MB at m = 1257, 2828, 5024, 7860, 13273 (3200 bytes per unknown
!> above 13.6 MB); the estimate, B + 8 m^2 + 3400 m + 3 MiB + the table, is
!> 1.001 to 1.02 times the peak.
module kcreep_solve_memory
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use kcreep_patch, only: patch_t
  use kcreep_split, only: subsystem_t
  use kcreep_assembly, only: n_load_cases
  use kcreep_solver_options, only: solver_options_t
  implicit none
  private
  public :: iterative_bytes, dense_bytes, table_bytes, process_bytes, counted_iterations
  public :: wheel_rail_shift_bytes, wheel_rail_cell_bytes, wheel_rail_row_cell_bytes, normal_cell_bytes, &
             normal_solve_bytes, region_patch_bytes

  !> The program's own resident set before any solve (code, libraries,
  !> OpenBLAS and FFTW state): B of the fit above (a 10 x 10 grid: 13.1 MB).
  integer(int64), parameter :: process_bytes = 11000000_int64

  !> A contact area under error control (kcreep_gap_levels) at its peak,
  !> the ladder's finest level, beside the program's own: a fixed part, per
  !> cell of the fine normal grid (its pressure and region are kept), per
  !> cell of the level's grid (its bounding box: operator table, FFT grids)
  !> and per cell inside (GMRES's basis over its unknowns). Evidence: peak
  !> RSS (/usr/bin/time -v, one thread) of S1002 on UIC60 at each of the 17
  !> shifts -6 to 10 mm alone, default target (finest levels 96 to 172
  !> cells across, grids of 9,801 to 68,112 cells, 7,147 to 52,284 inside,
  !> fine normal grids 13,221 to 58,380 cells; peaks 37.5 to 167.8 MB): a
  !> least-squares fit 14.65 MB + 246 B per normal cell + 490 B per grid
  !> cell + 2,115 B per cell inside is within 1 % of every peak. The
  !> constants are those plus about 10 %.
  integer(int64), parameter :: region_fixed_bytes = 4000000_int64
  real(real64), parameter :: region_normal_cell_bytes = 270, region_grid_cell_bytes = 540
  real(real64), parameter :: region_contact_cell_bytes = 2330
  !> A shift of a wheel/rail table under error control with a cell budget
  !> given or a target below the default (no region_level_cap), at its peak: the
  !> fixed part and the bytes per cell of the level cell budget B (the
  !> ladder's finest grid, the contact area's box, has at most B cells);
  !> each earlier shift's rows keep wheel_rail_row_cell_bytes per budget
  !> cell (their finest grid's tractions and pressure). Evidence: peak RSS
  !> (/usr/bin/time -v, one thread) of S1002 on UIC60 at shift 0, target
  !> 1e-5 so that the ladder runs to the budget: B = 10,000, 40,000 and
  !> 160,000 reached finest grids of 8,827, 35,308 and 139,370 cells
  !> (7,015 to 117,008 in contact) at peaks of 38.0, 107.5 and 356.6 MB,
  !> 23 MB + 2,392 bytes per finest-grid cell; 2,700 bytes per budget cell
  !> counts a box full of contact (0.80 to 0.84 of it was): the bound is
  !> 1.22 to 1.32 times those peaks. Two shifts at once (threads = 2, B =
  !> 40,000): 169 MB against 251 MB counted. The 17 shifts -6 to 10 mm at
  !> the default target: 181 MB at the peak, 168 MB for the largest shift
  !> (9 mm, 68,112 cells) alone: 13 MB kept for 15 earlier rows of 283,721
  !> finest-grid cells in all, 46 bytes per cell.
  integer(int64), parameter :: wheel_rail_shift_bytes = 12000000_int64
  integer(int64), parameter :: wheel_rail_cell_bytes = 2700
  !> Each earlier row of a wheel/rail table keeps this per grid cell of its
  !> finest level (its tractions and pressure). Evidence: the 17 shifts -6
  !> to 10 mm at the default target: 181 MB at the peak, 168 MB for the
  !> largest shift (9 mm, 68,112 cells) alone: 13 MB kept for 15 earlier
  !> rows of 283,721 finest-grid cells in all, 46 bytes per cell.
  integer(int64), parameter :: wheel_rail_row_cell_bytes = 60
  !> The normal solve's ~21 doubles per grid cell (measured: 166 MiB at
  !> 1000 x 1000, scripts/bench/bench_normal.sh).
  integer(int64), parameter :: normal_cell_bytes = 168
  !> Bytes per grid cell besides the basis: operator table (table_bytes) and
  !> the FFT operator's and circulant preconditioner's grids and spectra.
  real(real64), parameter :: grid_cell_bytes = 775
  !> The operator table's share of them.
  integer(int64), parameter :: table_cell_bytes = 320
  !> Vectors of the basis's size besides the basis itself.
  real(real64), parameter :: extra_vectors = 20
  !> GMRES iterations per cycle counted for the circulant preconditioner.
  integer, parameter :: counted_iterations = 34
  !> Below this GMRES tolerance (the default) the whole basis is counted.
  real(real64), parameter :: default_tolerance = 1e-11_real64

contains

  !> The normal solve on a grid of `cells` cells (beside the program's own).
  pure integer(int64) function normal_solve_bytes(cells)
    real(real64), intent(in) :: cells
    normal_solve_bytes = normal_cell_bytes * int(cells, int64)
  end function normal_solve_bytes

  !> A contact area's ladder at its finest level of grid_cells cells,
  !> contact_cells inside, beside its fine normal grid of normal_cells
  !> (beside the program's own).
  pure integer(int64) function region_patch_bytes(normal_cells, grid_cells, contact_cells)
    real(real64), intent(in) :: normal_cells, grid_cells, contact_cells
    region_patch_bytes = region_fixed_bytes + int(region_normal_cell_bytes * normal_cells + &
                         region_grid_cell_bytes * grid_cells + region_contact_cell_bytes * contact_cells, int64)
  end function region_patch_bytes

  !> The operator table: about 40 reals per grid cell.
  pure integer(int64) function table_bytes(patch)
    type(patch_t), intent(in) :: patch
    table_bytes = table_cell_bytes * int(patch%mx, int64) * patch%my
  end function table_bytes

  !> The dense path at its peak: the largest subsystem's matrix of m
  !> unknowns and its vectors (the table not included).
  pure integer(int64) function dense_bytes(m)
    integer, intent(in) :: m
    dense_bytes = 8 * int(m, int64)**2 + 3400 * int(m, int64) + 3 * 2_int64**20
  end function dense_bytes

  !> The iterative path at its peak (the table not included): subs are
  !> the systems GMRES solves (plan_subsystems with decouple = .false.), one
  !> column per system and requested load case it serves; preconditioner
  !> 'circulant' or 'strip'.
  pure real(real64) function iterative_bytes(opts, preconditioner, patch, subs, requested) result(bytes)
    type(solver_options_t), intent(in) :: opts
    character(len=*), intent(in) :: preconditioner
    type(patch_t), intent(in) :: patch
    type(subsystem_t), intent(in) :: subs(:)
    logical, intent(in) :: requested(n_load_cases)
    real(real64) :: vector, strip, grid
    integer :: i, j, columns, touched, iy
    columns = 0
    do j = 1, n_load_cases
      do i = 1, size(subs)
        if (requested(j) .and. subs(i)%serves(j)) columns = columns + 1
      end do
    end do
    vector = 8 * real(maxval(subs%m), real64) * columns
    grid = real(patch%mx, real64) * patch%my
    strip = 0
    if (trim(preconditioner) == 'strip') then
      touched = opts%restart + 1
      ! the LU of each grid row's block per component in single precision
      do iy = 1, patch%my
        strip = strip + 2 * 4 * real(count(patch%inside(:, iy)), real64)**2
      end do
    else if (opts%tolerance < default_tolerance) then
      touched = opts%restart + 1   ! 300 x 300 at 1e-15: 51 iterations
    else
      touched = min(opts%restart, counted_iterations) + 1
    end if
    bytes = (grid_cell_bytes - table_cell_bytes) * grid + vector * (touched + extra_vectors) + strip
  end function iterative_bytes

end module kcreep_solve_memory
