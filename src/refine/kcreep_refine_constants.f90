!> Every constant of kcreep's refinement engine (error control), with the
!> measurement behind it: targets, budgets, level ladders, fit widths and
!> the estimator's margins. docs/accuracy.md gives the evidence;
!> `ctest -L calibration` (tests/calibration/) re-measures the ones marked
!> (calibration) through the library's own estimator.
module kcreep_refine_constants
  use, intrinsic :: iso_fortran_env, only: real64
  implicit none
  public

  ! ---- targets ----
  !> &solver target_error when not given: the relative error aimed at for C11 and C22.
  real(real64), parameter :: default_target_error = 1e-3_real64
  !> The grid an ellipse is set on when kcreep chooses its grids (the
  !> namelist's ellipse without mx, my; the C API's mx = my = 0): only its
  !> place and the ellipse matter, and a given-grid estimate would use it.
  integer, parameter :: nominal_ellipse_cells = 60
  !> C23 (and f23, f32) get this multiple of target_error: it is the slowest to
  !> converge (its discretisation error is 2-3 times that of C11 at the same grid).
  real(real64), parameter :: c23_target_factor = 3

  ! ---- ellipses (levels of cells across the shorter axis) ----
  !> Fewer cells than this across the shorter axis on the coarsest level used:
  !> the level is outside the first-order range (errors of 10-50 %, the sign of the
  !> error still changes); no estimate is made from it.
  integer, parameter :: min_estimate_cells = 12
  !> A sampled shape's levels: the fewest in a fit (shape_level_estimate, 2
  !> coefficients), and the finest this many in one fit (Student's factor 2.45).
  !> (calibration) With base_levels, next_level_growth and order_margin:
  !> ctest -R calibration_ellipse_levels (solved ellipses a/b 0.1 to 10
  !> against the refined table).
  integer, parameter :: ellipse_fit_min = 5, ellipse_fit_width = 8
  !> Cells long in y (ellipse_level_grid) are at most this many times as long
  !> as wide: the estimate was checked on a/b = 0.1 to 0.5 with cells up to
  !> 10 times as long (27 of 27 bounded, the staircase levels before the blended edge); at
  !> a/b = 0.02 on cells 50 times as long it missed C23 (0.025 % against an
  !> estimate of 0.017 %). A contact area's levels (kcreep_level_ladder)
  !> have the cell count of cells as much longer along its longer axis as
  !> the area is long, up to this (their cells are shorter:
  !> region_cell_aspect). Held to 5 instead (when the cells were that
  !> long), the S1002 table took 16.5 s instead of 18.2 s, but at a/b = 10
  !> the C11 estimate missed its error in 2 to 3 of 10 perturbed runs.
  real(real64), parameter :: max_cell_aspect = 10
  !> A contact area's level cells are at most this many times as long as
  !> wide (kcreep_level_ladder region_cell_shape), with as few cells across
  !> as keeps each level's cell count that of cells up to max_cell_aspect
  !> long (region_level_scale). On longer cells the levels bend: the S1002
  !> +6.3 mm row's C23 fit through 56-96 across lay 0.15 % below its limit
  !> with an estimate of 0.077 % (lab/notes/gap_placement.md, "The bend
  !> comes from the long level cells"). At 2, the same cell counts: the
  !> 161-shift table's seven flange references 21 of 21 C's bounded (19),
  !> 157 rows within their targets (154), 45.2 s (47.1); the off-centre
  !> Hertzian gaps 356 of 360 within their estimates (348), largest error /
  !> estimate 1.55 (1.78); the centred ones 45 of 45, median estimate /
  !> error 5.11 (4.4) (docs/accuracy.md, "Gaps"; "The short cells built
  !> into the ladder" in that note).
  real(real64), parameter :: region_cell_aspect = 2
  !> A contact area's normal grids (kcreep_gap_levels normal_cell_shape)
  !> have square cells up to this length / width of the area; a longer
  !> area's cells are as much longer along it, so that its length keeps
  !> this many cells per cell across its width (the width is what the C's
  !> depend on). On the S1002 flange patches (length / width 19 to 22:
  !> cells about 4 times as long) the table took 9.5 s instead of 11.0 s
  !> with a limit of 10 (13.4 s on square cells), every row `ok` and within
  !> its estimates of the 1e-4 references (docs/wheel_rail_checks.md, "Speed"). The
  !> Hertzian gaps a/b = 5, 7, 10 and 20 stayed bounded in 10 of 10
  !> perturbed runs each (docs/accuracy.md, "Gaps"). Longer cells on
  !> shorter areas were not honest: cells sqrt(a/b) times as long missed
  !> C11 of the gap a/b = 0.63 at nu = 0.25 and 0.5 in the calibration
  !> (0.021 % against 0.016 %); sqrt(a/b / 4) times as long (1.12 at a/b =
  !> 5) bounded a/b = 5's C11 in 6 of 10 perturbed runs.
  real(real64), parameter :: normal_cell_aspect_limit = 5
  !> The share of a sampled shape's extrapolation (f0 - f(finest level))
  !> counted as the uncertainty of its order (shape_level_estimate). On
  !> blended levels the error of 24 solved ellipses (a/b 0.1 to 10, nu 0
  !> to 0.5) against the refined table was at most 0.105 times their
  !> extrapolation, median 0.019 (docs/accuracy.md, "Ellipses").
  !> (calibration) calibration_ellipse_levels fails with it at 0.
  real(real64), parameter :: order_margin = 0.1_real64
  !> Patch cells of the finest level kcreep may choose at target_error = 1e-3
  !> (level_cell_budget). A run-time budget: a solved ellipse long in x
  !> needs it, its levels being near-square cells over the whole ellipse
  !> (a/b = 10 at 40,000 cells stopped `uncertain` at 71 cells across, estimates
  !> 0.08 / 0.13 / 0.23 %; at 160,000 it ends `ok` at 96 across in 2.6 s on one
  !> core; a/b = 5 `ok` in 0.7 s, docs/accuracy.md, "Ellipses"); ellipses, masks
  !> and gaps that meet the target on coarser levels stop there. Looser targets
  !> scale it by (1e-3 / target)**(1/4); tighter ones by 10 for each factor
  !> 10 (1.6 million cells at 1e-4): the Hertzian gaps a/b = 2, 5 and 0.5
  !> meet 1e-4 on levels of 550,000, 450,000 and 1.28 million grid cells
  !> (19-49 s on one core; at 320,000 all three stopped `uncertain`,
  !> docs/accuracy.md, "Gaps").
  real(real64), parameter :: cells_at_default_target = 160000
  real(real64), parameter :: tight_target_budget_growth = 10
  !> The range of a cell budget the caller gives (&solver cell_budget): below
  !> the minimum no ellipse reaches its base levels (32 cells across is 800
  !> cells); the maximum, 10 million patch cells, needs about 3 GB on the
  !> iterative path (the circle at 2048 cells across, 3.3 million cells, took
  !> 5 minutes on one core of the development machine).
  real(real64), parameter :: min_cell_budget = 1000, max_cell_budget = 1e7_real64


  ! ---- masks and CONTACT's grid: every cell split k x k (the same patch on every level) ----
  !> Levels of a split patch: k = 1, 2, 3, ... while the split patch keeps to
  !> the cell budget (level_cell_budget: 160,000 cells at 1e-3, 1.6 million
  !> at 1e-4), at least split_min_levels of them whatever the budget; the fit
  !> runs through the finest split_fit_width. (calibration) Measured on the
  !> seven shipped masks against references from splits up to 11-56
  !> (docs/data/mask_split_levels.dat, every window of splits coarser than
  !> the reference's): 4 levels bound 111 of 111 coefficient cases (median
  !> estimate / error 3.8), 5 levels 88 of 90 (90 allowing the reference's
  !> u; median 3.1): ctest -R calibration_split_levels
  !> (tests/calibration/test_split_levels.f90).
  integer, parameter :: split_min_levels = 4, split_fit_width = 5
  !> The finest split the ladder tries, whatever the budget: the shipped
  !> masks meet 1e-3 by k = 5 and 1e-4 within the budget's k; a mask that
  !> has not met its target by 32 x 32 subcells will not on the next level.
  !> Without it a tiny mask ran a level per k up to the budget: 5 cells
  !> 1e11 from the spin centre went on for minutes through 178 levels (a
  !> finding of scripts/fuzz.py).
  integer, parameter :: max_split = 32
  !> The staircase's re-entrant corners make the split levels converge as
  !> f0 + K h + L h^p with p between 4/3 and 3/2 (the slope grows as h
  !> falls): the fit uses split_order; the estimate adds the largest change
  !> of f0 when p is one of split_order_range instead (the model's
  !> uncertainty) to t95 x the standard error of f0. (calibration) The range
  !> [4/3, 2] bounded 90 of 90 at a median of 3.75; [4/3, 5/3] only 81.
  real(real64), parameter :: split_order = 1.5_real64
  !> GMRES's relative residual on split levels (caller gave none): at most
  !> split_tolerance_share x the target. A three-term fit through 4-5
  !> levels amplifies the levels' solver error: the superellipse at 1e-3
  !> (levels to GMRES 1e-5) estimated C23 at 0.0054 % with an error of
  !> 0.0085 %; at 1e-6 and below its estimate is 0.028 %, as with 1e-8.
  !> (calibration) The shipped masks at 1e-3 within their estimates, with
  !> max_split: ctest -R calibration_mask_examples.
  real(real64), parameter :: split_tolerance_share = 1e-3_real64
  real(real64), parameter :: split_order_range(2) = [1.25_real64, 1.75_real64]
  !> The error of a grid given as is, from one more grid: an ellipse's grid
  !> with twice the cell size, estimate single_grid_factor |f(h) - f(2h)| / f
  !> (first order gives 1; the factor 2 covers the noise and the h log h
  !> term of collocation: 185 of 189 bounded, docs/accuracy.md); a mask split
  !> in 2 x 2, split_grid_factor |f(h) - f(h/2)| / f (first order 2, times 2).
  real(real64), parameter :: single_grid_factor = 2, split_grid_factor = 4
  !> GMRES's relative residual on the levels when the caller gave no
  !> tolerance: level_tolerance_share x the target, at most
  !> max_level_tolerance. Measured on the unit circle (f11, f22, f23 against
  !> residual 1e-11): a residual r moves them by up to about r (1e-4: C23 by
  !> 9.5e-5; 1e-5: 3e-6; 1e-6: 7e-7 at 296 and 448 cells across), with 21-23
  !> iterations at 1e-6 instead of 37-41 at 1e-11. At the default target
  !> (1e-4, was 1e-5): the S1002 table took 17 % less time (10 instead of 13
  !> GMRES steps per level), its C's moved by at most 7e-5 (0.29 of their
  !> estimates), the +7 mm flange's levels by at most 6e-6 against residual
  !> 1e-9; the 15 Hertzian gaps stayed bounded, 45 of 45 (docs/accuracy.md,
  !> "Gaps").
  real(real64), parameter :: level_tolerance_share = 1e-1_real64, max_level_tolerance = 1e-4_real64

  ! ---- ellipses, solved (continued) ----
  !> Base levels on an ellipse (cells across the shorter axis); then one
  !> level next_level_growth finer at a time, a multiple of 4 cells across
  !> (112, 128, 148, 172, ...).
  real(real64), parameter :: next_level_growth = 1.15_real64
  integer, parameter :: base_levels(5) = [56, 64, 72, 84, 96]
  !> The finest level a contact area's ladder (kcreep_gap_levels) takes when
  !> the caller gave no cell budget and the target is the default or looser
  !> (kcreep_level_ladder region_level_cap): four levels past the base. A
  !> limit, so that --estimate-memory can count a patch's finest level from
  !> its contact area (kcreep_solve_memory) rather than the whole cell
  !> budget; a row stopped there ends `uncertain`. S1002 on UIC60, the 17
  !> shifts -6 to 10 mm at the default target: 11 rows stopped at 96 cells
  !> across, one each at 112, 128 and 148, two at 172.
  integer, parameter :: region_max_level = 172
  !> The base levels of a long ellipse are scaled down to its cell budget, to
  !> no fewer than this. Such a run ends `uncertain` (kcreep_level_ladder):
  !> below base_levels(1) the levels bend with L h^2, and on the S1002 flange
  !> strips (levels 49 to 92 across) the estimates moved by up to 10 times
  !> with small changes of the contact area (docs/wheel_rail.md).
  integer, parameter :: min_base_cells = 32
  !> Scaled-down levels are at least this many cells apart (32, 36, 40, 44,
  !> 48 at the least: h from 1/48 to 1/32; the finest 2.25 times the cells
  !> of the first).
  integer, parameter :: min_level_step = 4
  !> The share of an ellipse's bounding grid inside it (pi/4), for its patch cells.
  real(real64), parameter :: ellipse_fill = 0.79_real64
  !> Patch cells of a single grid's auxiliary grid (every cell split in 2 x 2):
  !> above it the given grid gets no estimate (a run-time bound).
  integer, parameter :: max_level_cells = 20000

  ! ---- patches from a gap function (the normal problem on a fine grid) ----
  !> Cells across the contact area's hydraulic diameter of the normal
  !> problem's fine grid at the default target and looser. The levels sample the zero level of the
  !> interpolated p^2 (kcreep_region), so the contact boundary lies inside
  !> the fine cells; the grid's error enters the estimate
  !> (normal_grid_estimate), so a coarser grid makes longer ladders. On
  !> blended levels (the S1002 table, one core, medians of three): 112
  !> across 18.2 s, 128 across 20.0 s, every row `ok` (at 96 across, in a
  !> run with cells at most 5 times as long, one row stayed `uncertain`);
  !> the 15 Hertzian gaps bounded 45 of 45 at 112 as at 128, their median
  !> estimate / error the same to 0.1, every run `ok`.
  real(real64), parameter :: gap_normal_cells_at_default = 112
  !> The same below the default target. At 1e-4 on the Hertzian gap a/b =
  !> 2 the normal grid's estimate was 0.0055 / 0.0071 / 0.019 % at 256
  !> across and 0.0020 / 0.0026 / 0.0076 % at 512 (C11, C22, C23; targets
  !> 0.01 / 0.01 / 0.03 %), the run `ok` at 512 in 19 s (docs/accuracy.md,
  !> "Gaps"). (calibration) ctest -R accurate_gap, with
  !> tight_target_budget_growth.
  real(real64), parameter :: gap_normal_cells_below_default = 512
  !> The fine normal grid has at most this share of the level cell budget
  !> (200,000 cells at the default target; coarser cells on a long thin
  !> contact area, whose bounding box is large for its width): a run-time
  !> bound; 200,000 cells take about 0.45 s on one core (the S1002 +8 mm
  !> flange, preconditioned CG). At 1e-4 the bound (2 million) holds the
  !> Hertzian gaps' 512 cells across (about 640,000 cells at a/b = 2).
  real(real64), parameter :: normal_grid_budget_share = 1.25_real64
  !> The complementarity residual the fine and coarse normal solves stop at
  !> when the caller gave none (&normal normal_tolerance; the given grid's
  !> solve keeps 1e-10): they only place the contact boundary. At 1e-7 C11,
  !> C22, C23 equal those at 1e-10 to six digits (Hertzian gaps a/b = 5, 10,
  !> 20 and input/wheel_rail.nml; at 1e-6 a boundary cell flips and C23 moves
  !> by 2e-4), with 40 % fewer CG steps; a decade below that for margin.
  real(real64), parameter :: gap_normal_tolerance = 1e-8_real64
  !> The normal grid's estimate (kcreep_gap_levels normal_grid_estimate) is
  !> the larger of two parts. The fine grid's placement noise: the change of
  !> the contact area when the fine grid is moved by half a cell (the edge's
  !> scatter of 0.02-0.03 cells, kcreep_region edge_blend, does not fall
  !> with the cell size as fast as the rest). And this share of the change
  !> from the coarse grid to the fine one, the part a finer grid still
  !> removes: it falls faster than first order (orders 1.2 to 3.7 observed
  !> on grids of 4, 2 and 1 times the cell size over Hertzian gaps).
  !> (calibration) 15 Hertzian gaps (ctest -R calibration_gap_levels;
  !> docs/accuracy.md, "Gaps", quotes the median estimate / error): 45 of
  !> 45 bounded (the whole coarse change alone: 44 of 45, one only within
  !> the reference's u: C11 at Rx/Ry = 5, nu = 0.5, error 0.027 % against
  !> 0.021 %, whose placement noise is 0.019 %). On the S1002 +5 and +6 mm
  !> tread patches the coarse grid (64 cells across) is far from the
  !> continuum: the whole change was 10-50 times their errors of 0.002-0.018 %
  !> (docs/wheel_rail.md).
  real(real64), parameter :: normal_systematic_share = 0.5_real64
  !> The coarse normal grid covers the contact area's bounding box on the
  !> given grid, the fine one that on the coarse grid, each widened by this
  !> fraction of its size on every side and by two cells of the grid it was
  !> found on: the contact area is within a cell of that grid's, and a
  !> larger grid only costs (a flange strip's box on the given grid is 2-4
  !> times its area; the fine grid over the coarse area's box took the S1002
  !> table from 38.3 to 34.7 s).
  real(real64), parameter :: gap_level_margin = 0.05_real64
  !> A gap's grid given as is: the geometry on cells gap_single_sizes times
  !> the size, estimate gap_single_factor max(|C(h) - C(2h)|, 2 |C(h) -
  !> C(1.5h)|) / C(h) (the contact boundary moves between the grids: 97 of
  !> 99 bounded on Hertzian gaps, where the ellipses' rule bounded 88).
  real(real64), parameter :: gap_single_sizes(2) = [1.5_real64, 2.0_real64], gap_single_factor = 3

end module kcreep_refine_constants
