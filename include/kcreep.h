/* kcreep: Kalker's creep coefficients of any contact patch -- C API.
 *
 * One opaque handle holds a problem (grid geometry, material, scheme, solver
 * settings), its last result and its last error. Every function returns a
 * status: KCREEP_OK (0) or an error code; kcreep_get_message() gives the
 * one-line reason. NULL handles and NULL arrays are errors, never crashes.
 * Repeated solves on one handle with the same grid, scheme and material
 * reuse the operator table (the in-loop case: a new mask each step).
 *
 * Units: any consistent set (mm and N/mm^2 give N and N mm). Sign
 * convention: (Fx, Fy, Mz) = -f (xi, eta, phi), x the rolling direction,
 * leading edge at +x.
 */
#ifndef KCREEP_H
#define KCREEP_H

#ifdef __cplusplus
extern "C" {
#endif

#define KCREEP_OK 0
#define KCREEP_BAD_INPUT 2   /* a value out of range, a NULL array, an empty patch */
#define KCREEP_NUMERICAL 3   /* the solver could not produce a result */
#define KCREEP_NO_RESULT 6   /* NULL handle, or no successful solve yet */

/* Verdict bits (kcreep_get_verdict); 0 is "ok". */
#define KCREEP_VERDICT_DEGENERATE 1
#define KCREEP_VERDICT_NONPHYSICAL 2
#define KCREEP_VERDICT_ALPHA_EDGE 4
#define KCREEP_VERDICT_COARSE 8
#define KCREEP_VERDICT_ILL_CONDITIONED 16
#define KCREEP_VERDICT_INACCURATE 32
#define KCREEP_VERDICT_UNCERTAIN 64

typedef void *kcreep_handle;

/* 10000 major + 100 minor + patch */
int kcreep_version(void);

kcreep_handle kcreep_new(void);                 /* default settings, no patch */
void kcreep_delete(kcreep_handle *handle);      /* frees and sets *handle = NULL */
int kcreep_get_message(kcreep_handle handle, char *buffer, int buffer_length);

/* Settings (defaults: g = 1, nu = 0.25, scheme "backward" spin_shift 0, method "auto",
 * the grid as given). Each setter checks its values (g 1e-100 to 1e100, nu 0 to 0.5;
 * scheme "backward" or "collocation", -1 < alpha < 1, -1 <= spin_shift <= 1;
 * method as below, tolerance 0 or 1e-15 to 1): a bad value returns
 * KCREEP_BAD_INPUT with the message, and the handle keeps what it had. */
int kcreep_set_material(kcreep_handle handle, double g, double nu);
int kcreep_set_scheme(kcreep_handle handle, const char *name, double alpha, double spin_shift);
/* Or the two bodies: Young's moduli and Poisson ratios, combined as CONTACT does. */
int kcreep_set_bodies(kcreep_handle handle, double e1, double nu1, double e2, double nu2);
/* The point the spin turns about and Mz is taken at (default the origin). */
int kcreep_set_spin_centre(kcreep_handle handle, double x, double y);
/* method: "auto", "dense", "iterative", or "table" (ellipses with 0.1 <= a/b <= 10:
 * interpolated in kcreep's refined table in microseconds, the stated relative
 * uncertainty as the error estimate, no tractions; the grid is only FASTSIM's). */
int kcreep_set_solver(kcreep_handle handle, const char *method, double tolerance);
int kcreep_set_extrapolation(kcreep_handle handle, int levels, int ratio);   /* levels 0: off */
/* Threads of each solve: 0 automatic (default: the CPUs this process may use
 * that are free when a stage starts, where the work pays for them; one on a
 * busy machine), else exactly this many (1 to 1024). Handles are
 * independent: several threads, each with its own handle, may solve at
 * once. Results do not depend on the count. */
int kcreep_set_threads(kcreep_handle handle, int threads);
/* Error control: relative target for C11, C22 (C23: 3 times it; 0: none;
 * default 1e-3, as the program's); refine_grid != 0 (the default) lets kcreep
 * choose the grids (an ellipse set with mx = my = 0), split the cells (mask)
 * or resample the gap; an ellipse set with its grid is solved as given and
 * judged. estimate 0 (with target 0) skips the estimate of a given grid,
 * which costs one more solve (default 1): for loops whose grid was judged
 * once, with kcreep_set_error_control(h, 0, 0, 0); the verdict is then
 * 'uncertain' (no estimate), as for any grid without one. */
int kcreep_set_error_control(kcreep_handle handle, double target_error, int refine_grid, int estimate);
/* The most patch cells of a level kcreep chooses under error control (0: the
 * defaults, a run-time budget; 1e3 to 1e7, checked when solving): raised for
 * reference work, e.g. target_error 1e-4 to reach "ok". */
int kcreep_set_cell_budget(kcreep_handle handle, double cells);

/* Geometry: an ellipse on an mx x my grid over [-a, a] x [-b, b] (mx = my = 0:
 * kcreep chooses the grids or answers from its refined table), or a mask
 * inside[iy * mx + ix] != 0 (rows in increasing y) with cell sizes dx, dy and
 * the centre (x0, y0) of cell (0, 0). */
int kcreep_set_ellipse(kcreep_handle handle, double semi_a, double semi_b, int mx, int my);
int kcreep_set_mask(kcreep_handle handle, int mx, int my, const int *inside,
                    double dx, double dy, double x0, double y0);

/* The normal problem: the undeformed distance h[iy * mx + ix] of the two
 * surfaces on a grid, and exactly one of approach and normal_force > 0. The
 * next solve finds the contact area and pressure, then the coefficients of
 * that area (the handle's g, nu are the material). */
int kcreep_set_gap(kcreep_handle handle, int mx, int my, const double *gap, double dx, double dy,
                   double x0, double y0, double approach, double normal_force);

int kcreep_solve(kcreep_handle handle);
/* kcreep_set_mask + kcreep_solve in one call */
int kcreep_solve_mask(kcreep_handle handle, int mx, int my, const int *inside,
                      double dx, double dy, double x0, double y0);

/* Results of the last successful solve. */
int kcreep_get_matrix(kcreep_handle handle, double f[9]);          /* f[3 i + j] = f_(i+1)(j+1) */
int kcreep_get_normalised(kcreep_handle handle, double c[3]);      /* C11, C22, C23 */
int kcreep_get_error_estimate(kcreep_handle handle, double limit[3], double error[3]); /* NaN if none */
int kcreep_get_fastsim(kcreep_handle handle, double l[3]);         /* L1, L2, L3 */
int kcreep_get_relative_error(kcreep_handle handle, double error[3]); /* estimated, of C11 C22 C23; NaN: none */
int kcreep_get_verdict(kcreep_handle handle, int *flags, char *buffer, int buffer_length);
/* Warning number index (0 to count - 1, count from kcreep_get_results [32]), whole. */
int kcreep_get_warning(kcreep_handle handle, int index, char *buffer, int buffer_length);
int kcreep_get_cells(kcreep_handle handle, int *n, int *mx, int *my);
/* (none after method "table": an error) t: length >= 6 n; px of case j (0 xi, 1 eta, 2 phi) at t[j*2n + k], py at
 * t[j*2n + n + k]; ix, iy (1-based grid indices, n each) may be NULL. */
int kcreep_get_tractions(kcreep_handle handle, int length, double *t, int *ix, int *iy);
/* GMRES iterations (0: dense LU), relative residual or backward error,
 * rcond (NaN on the iterative path), seconds of the solve */
int kcreep_get_diagnostics(kcreep_handle handle, int *iterations, double *residual, double *rcond,
                           double *seconds);
int kcreep_get_reuse_count(kcreep_handle handle, int *count);
/* The threads the last solve's linear solve ran on. */
int kcreep_get_threads(kcreep_handle handle, int *threads);
/* All numbers of the last solve in one call (length >= 33): [0..8] f row by
 * row, [9..11] C11 C22 C23, [12..14] L1 L2 L3, [15..17] relative error
 * estimates, [18..20] extrapolated C, [21..23] their errors, [24] iterations,
 * [25] residual, [26] rcond, [27] seconds, [28] cells, [29] mx, [30] my,
 * [31] verdict bits, [32] number of warnings. */
int kcreep_get_results(kcreep_handle handle, int length, double *values);
/* After a solve with kcreep_set_gap: total force, approach, maximum pressure,
 * cells in contact, iterations of the normal solve. */
int kcreep_get_normal(kcreep_handle handle, double *fn, double *approach, double *pmax, int *cells,
                      int *iterations);

/* FASTSIM with friction mu on the solved patch, for n creepages
 * creep[3 k + 0..2] = (xi, eta, phi), with the patch's exact L1 L2 L3.
 * pressure: mx * my values on the patch's grid (rows in increasing y), or
 * NULL for the normal problem's pressure. rule: "aligned" (the program's
 * default), "separate" or "weighted" (docs/fastsim.md).
 * force[3 k + 0..2] = (Fx, Fy, Mz); adhesion[k] (may be NULL): the fraction
 * of the area in adhesion. */
int kcreep_fastsim(kcreep_handle handle, double mu, int n, const double *creep, const double *pressure,
                   const char *rule, double *force, double *adhesion);
/* Exact steady rolling with Coulomb friction mu on the solved patch
 * (docs/rolling.md: kcreep's backward scheme, semi-smooth Newton), for n
 * creepages creep[3 k + 0..2] = (xi, eta, phi); pressure as kcreep_fastsim
 * (NULL: the normal problem's). force[3 k + 0..2] = (Fx, Fy, Mz); adhesion[k]
 * (may be NULL): the fraction of the patch cells in adhesion. Needs the
 * backward scheme. */
int kcreep_rolling(kcreep_handle handle, double mu, int n, const double *creep, const double *pressure,
                   double *force, double *adhesion);
/* Calls of kcreep_rolling on one solved patch start from the previous call's
 * solutions (and keep the solver's set-up): a time integration calling once
 * per step with a slowly varying creepage pays a warm solve only. */
/* The fast force model of the solved patch (docs/rolling.md): kcreep_rolling's
 * forces interpolated in a table of exact solutions over normalised creepages
 * (F(mu, c) = mu F(1, c/mu)), built on the first call for a pressure (one to a
 * few seconds on one thread) and kept on the handle until the next solve;
 * then microseconds per point. Arguments as kcreep_rolling. */
int kcreep_fast_forces(kcreep_handle handle, double mu, int n, const double *creep, const double *pressure,
                       double *force);
/* The solved patch and the normal problem's pressure coarsened by square
 * blocks of cells to at most max_cells (>= 16) cells, for kcreep_fastsim,
 * kcreep_rolling and kcreep_fast_forces where the normal grid is finer than
 * their forces need (a contact table's rows: 1,600-4,000 cells); the solved
 * coefficients stay. The forces are then those of the coarser grid
 * (docs/mbs.md says how far they move). Needs a normal problem. */
int kcreep_coarsen_patch(kcreep_handle handle, int max_cells);

/* Wheel and rail profiles to a contact table (docs/wheel_rail.md; the same
 * table as the program's &wheel_rail). Profiles are read by
 * kcreep_set_profiles (SIMPACK .prw/.prr, MiniProf .whl/.ban, else two
 * columns y z in mm; mirror flags 0 or 1; smoothing 0 to 1e12 mm^4, negative:
 * automatic, docs/wheel_rail.md). The track
 * (side "right" or "left", then mm and rad as &wheel_rail) defaults to
 * "right", 1435, 14, 0, 1360, -70, 460 until kcreep_set_track. kcreep_wheel_rail
 * runs n_shifts lateral shifts (mm) at yaw (rad) with exactly one of
 * vertical_force (N) and approach (mm) > 0, the handle's material, solver
 * and target error (0: the program's default 1e-3); *rows: the table's rows. */
int kcreep_set_profiles(kcreep_handle handle, const char *wheel_file, const char *rail_file, int wheel_mirror,
                        int rail_mirror, double smoothing);
int kcreep_set_track(kcreep_handle handle, const char *side, double gauge_width, double gauge_height,
                     double rail_cant, double flange_back_distance, double flange_back_position,
                     double nominal_radius);
int kcreep_wheel_rail(kcreep_handle handle, int n_shifts, const double *shifts, double yaw, double vertical_force,
                      double approach, int *rows);
/* The table row by row: table[r * KCREEP_WHEEL_RAIL_COLUMNS + k] (length >= rows * columns),
 * columns named as below, the verdict as its bits (0: ok), kind 0 tread, 1 flange. */
#define KCREEP_WHEEL_RAIL_COLUMNS 25
#define KCREEP_WHEEL_RAIL_COLUMN_NAMES "shift yaw patch fn delta y_rail y_wheel r_wheel area length width " \
  "c11 c22 c23 c33 err11 err22 err23 verdict l1 l2 l3 spin kind turn"
int kcreep_get_wheel_rail(kcreep_handle handle, int length, double *table);
/* Row `row` (0-based) of source's last kcreep_wheel_rail table becomes
 * handle's solved patch (grid, pressure, coefficients, material), so
 * kcreep_fastsim, kcreep_rolling and kcreep_get_results act on that row's
 * patch and pressure; handle and source may be the same. */
int kcreep_take_wheel_rail_row(kcreep_handle handle, kcreep_handle source, int row);
/* The last table held for a time loop (docs/mbs.md): every patch at any
 * shift (mm) in its range, interpolated between the neighbouring rows, its
 * patches paired nearest y_rail first (within half their widths plus the
 * step; a patch without a partner fades with its weight), in order of y_rail.
 * kcreep_wheel_rail_at: values[p * KCREEP_WHEEL_RAIL_COLUMNS + k] (the
 * nearer row's patch and verdict), rows[2 p + 0..1] (0-based, -1: none) and
 * weights[2 p + 0..1] (rows, weights may be NULL), capacity the patches the
 * arrays hold, *n_patches the patches at shift. kcreep_wheel_rail_forces: n
 * creepages of each of the n_patches patches, creep[(p n + k) 3 + 0..2] =
 * (xi, eta, phi), force[(p n + k) 3 + 0..2] = (Fx, Fy, Mz), each row's forces
 * on its own patch and pressure weighted likewise; exact 0: FASTSIM (rule
 * aligned), 1: exact rolling. */
int kcreep_wheel_rail_at(kcreep_handle handle, double shift, int capacity, double *values, int *rows,
                         double *weights, int *n_patches);
int kcreep_wheel_rail_forces(kcreep_handle handle, double shift, double mu, int n, int n_patches,
                             const double *creep, int exact, double *force);

/* The wheelset (docs/wheel_rail.md, Wheelset; the program's &wheel_rail
 * wheelset = .true.): both wheels of a rigid wheelset on the handle's profiles
 * and track, each carrying vertical_force (N) > 0, the left wheel the right
 * one mirrored, or on its own profiles from kcreep_set_left_profiles (read as
 * kcreep_set_profiles with its mirror flags and smoothing; NULL or "" keeps
 * the right one). kcreep_wheelset runs n_shifts lateral shifts (mm) at yaw
 * (rad); *rows: one per shift, read with kcreep_get_wheelset:
 * table[r * KCREEP_WHEELSET_COLUMNS + k], lengths mm, angles rad. */
int kcreep_set_left_profiles(kcreep_handle handle, const char *left_wheel_file, const char *left_rail_file);
int kcreep_wheelset(kcreep_handle handle, int n_shifts, const double *shifts, double yaw, double vertical_force,
                    int *rows);
#define KCREEP_WHEELSET_COLUMNS 9
#define KCREEP_WHEELSET_COLUMN_NAMES "shift r_right r_left delta_r delta_right delta_left roll z lambda_eq"
int kcreep_get_wheelset(kcreep_handle handle, int length, double *table);

#ifdef __cplusplus
}
#endif
#endif /* KCREEP_H */
