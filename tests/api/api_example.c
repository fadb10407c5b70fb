/* The C API in use, as a multibody code would call it: one handle, an
 * ellipse, then a mask solved repeatedly; every status checked, and the
 * error paths (NULL handle, NULL arrays, bad values) exercised.
 *
 *   api_example [ellipse|mask|errors|bench N [ellipse|mask|moving [auto|dense|iterative [estimate|steps]]]]
 * prints "key value..." lines that tests/api/test_install.py compares with the
 * command line and Python; bench ... steps also prints each step's C11 C22
 * C23 and GMRES iterations (to compare the solver paths step by step). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "kcreep.h"

static int failures = 0;

static void expect(int condition, const char *what) {
  if (!condition) {
    printf("FAIL %s\n", what);
    failures++;
  }
}

static void must(kcreep_handle h, int status, const char *call) {
  if (status != KCREEP_OK) {
    char message[512];
    kcreep_get_message(h, message, sizeof message);
    fprintf(stderr, "api_example: %s failed (%d): %s\n", call, status, message);
    exit(1);
  }
}

/* the circle of radius 1 as a 40 x 40 mask, cell centres from -0.975 */
static int *circle_mask(int m) {
  int *inside = malloc(sizeof(int) * m * m);
  for (int iy = 0; iy < m; iy++)
    for (int ix = 0; ix < m; ix++) {
      double x = -1 + (ix + 0.5) * 2.0 / m, y = -1 + (iy + 0.5) * 2.0 / m;
      inside[iy * m + ix] = x * x + y * y <= 1;
    }
  return inside;
}

static void print_result(kcreep_handle h, const char *label) {
  double f[9], c[3], l[3];
  int flags, n, mx, my;
  char verdict[2048];
  must(h, kcreep_get_matrix(h, f), "kcreep_get_matrix");
  must(h, kcreep_get_normalised(h, c), "kcreep_get_normalised");
  must(h, kcreep_get_fastsim(h, l), "kcreep_get_fastsim");
  must(h, kcreep_get_verdict(h, &flags, verdict, sizeof verdict), "kcreep_get_verdict");
  must(h, kcreep_get_cells(h, &n, &mx, &my), "kcreep_get_cells");
  printf("%s n %d\n", label, n);
  printf("%s f", label);
  for (int k = 0; k < 9; k++) printf(" %.15e", f[k]);
  printf("\n%s c %.15e %.15e %.15e\n", label, c[0], c[1], c[2]);
  printf("%s L %.15e %.15e %.15e\n", label, l[0], l[1], l[2]);
  printf("%s verdict %d %s\n", label, flags, verdict);
}

static double seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int compare_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int main(int argc, char **argv) {
  const char *mode = argc > 1 ? argv[1] : "ellipse";
  printf("version %d\n", kcreep_version());
  kcreep_handle h = kcreep_new();
  expect(h != NULL, "kcreep_new");
  must(h, kcreep_set_material(h, 82000.0, 0.25), "kcreep_set_material");

  if (strcmp(mode, "ellipse") == 0) {
    must(h, kcreep_set_ellipse(h, 2.0, 1.0, 40, 40), "kcreep_set_ellipse");
    must(h, kcreep_solve(h), "kcreep_solve");
    print_result(h, "ellipse");
  } else if (strcmp(mode, "mask") == 0) {
    int *inside = circle_mask(40);
    must(h, kcreep_solve_mask(h, 40, 40, inside, 0.05, 0.05, -0.975, -0.975), "kcreep_solve_mask");
    print_result(h, "mask");   /* the defaults: target 1e-3, the cells split */
    /* the in-loop case: grids solved as given and not judged (error control off);
       same grid, new mask -> the operator table is reused */
    must(h, kcreep_set_error_control(h, 0.0, 0, 0), "kcreep_set_error_control");
    must(h, kcreep_solve_mask(h, 40, 40, inside, 0.05, 0.05, -0.975, -0.975), "kcreep_solve_mask as given");
    inside[0 * 40 + 20] = 0;
    must(h, kcreep_solve_mask(h, 40, 40, inside, 0.05, 0.05, -0.975, -0.975), "kcreep_solve_mask again");
    int reused = -1;
    must(h, kcreep_get_reuse_count(h, &reused), "kcreep_get_reuse_count");
    printf("mask reused %d\n", reused);
    int n, mx, my;
    must(h, kcreep_get_cells(h, &n, &mx, &my), "kcreep_get_cells");
    double *t = malloc(sizeof(double) * 6 * n);
    int *ix = malloc(sizeof(int) * n), *iy = malloc(sizeof(int) * n);
    must(h, kcreep_get_tractions(h, 6 * n, t, ix, iy), "kcreep_get_tractions");
    double sum_px = 0;
    for (int k = 0; k < n; k++) sum_px += t[k];
    printf("mask sum_px_xi %.15e first_cell %d %d\n", sum_px, ix[0], iy[0]);
    expect(kcreep_get_tractions(h, 6 * n - 1, t, ix, iy) == KCREEP_BAD_INPUT, "short traction buffer refused");
    free(t); free(ix); free(iy); free(inside);
  } else if (strcmp(mode, "errors") == 0) {
    char message[512];
    double f[9];
    expect(kcreep_solve(NULL) == KCREEP_NO_RESULT, "NULL handle: solve");
    expect(kcreep_get_matrix(NULL, f) == KCREEP_NO_RESULT, "NULL handle: get_matrix");
    expect(kcreep_get_message(NULL, message, sizeof message) == KCREEP_NO_RESULT, "NULL handle: message");
    expect(kcreep_get_matrix(h, f) == KCREEP_NO_RESULT, "no result before a solve");
    expect(kcreep_solve(h) == KCREEP_BAD_INPUT, "solve without a patch");
    kcreep_get_message(h, message, sizeof message);
    printf("errors no_patch %s\n", message);
    expect(kcreep_set_mask(h, 4, 4, NULL, 1, 1, 0, 0) == KCREEP_BAD_INPUT, "NULL mask refused");
    int empty[4] = {0, 0, 0, 0};
    expect(kcreep_set_mask(h, 2, 2, empty, 1, 1, 0, 0) == KCREEP_BAD_INPUT, "empty mask refused");
    kcreep_get_message(h, message, sizeof message);
    printf("errors empty %s\n", message);
    expect(kcreep_set_mask(h, 2, 2, empty, -1, 1, 0, 0) == KCREEP_BAD_INPUT, "negative dx refused");
    expect(kcreep_set_ellipse(h, 1, 1, 0, 10) == KCREEP_BAD_INPUT, "mx = 0 refused");
    expect(kcreep_set_ellipse(h, NAN, 1, 10, 10) == KCREEP_BAD_INPUT, "NaN semi-axis refused");
    must(h, kcreep_set_ellipse(h, 1, 1, 20, 20), "kcreep_set_ellipse");
    /* the setters check their values and say so in C terms; the handle keeps its last good values */
    expect(kcreep_set_material(h, 1.0, 0.7) == KCREEP_BAD_INPUT, "nu = 0.7 refused by kcreep_set_material");
    kcreep_get_message(h, message, sizeof message);
    printf("errors nu %s\n", message);
    expect(strstr(message, "kcreep_set_material") != NULL && strstr(message, "&") == NULL,
           "the message names the C function, not a namelist group");
    expect(kcreep_set_material(h, -1.0, 0.25) == KCREEP_BAD_INPUT, "g = -1 refused by kcreep_set_material");
    expect(kcreep_set_material(h, NAN, 0.25) == KCREEP_BAD_INPUT, "g = NaN refused by kcreep_set_material");
    expect(kcreep_set_scheme(h, NULL, 0.5, 0) == KCREEP_BAD_INPUT, "NULL scheme name refused");
    expect(kcreep_set_scheme(h, "upwind", 0.5, 0) == KCREEP_BAD_INPUT, "unknown scheme refused by kcreep_set_scheme");
    kcreep_get_message(h, message, sizeof message);
    printf("errors scheme %s\n", message);
    expect(strstr(message, "kcreep_set_scheme") != NULL && strstr(message, "upwind") != NULL,
           "the scheme message names the function and the value");
    expect(kcreep_set_scheme(h, "collocation", 1.5, 0) == KCREEP_BAD_INPUT, "alpha = 1.5 refused by kcreep_set_scheme");
    expect(kcreep_set_scheme(h, "backward", 0, 2) == KCREEP_BAD_INPUT, "spin_shift = 2 refused by kcreep_set_scheme");
    expect(kcreep_set_solver(h, "fast", 0) == KCREEP_BAD_INPUT, "unknown method refused by kcreep_set_solver");
    expect(kcreep_set_solver(h, "iterative", -1) == KCREEP_BAD_INPUT, "negative tolerance refused by kcreep_set_solver");
    expect(kcreep_set_solver(h, "iterative", 1e-300) == KCREEP_BAD_INPUT, "tolerance 1e-300 refused by kcreep_set_solver");
    must(h, kcreep_set_solver(h, "auto", 0), "kcreep_set_solver");
    must(h, kcreep_set_material(h, 1.0, 0.25), "kcreep_set_material");
    must(h, kcreep_set_scheme(h, "backward", 0, 0), "kcreep_set_scheme");
    must(h, kcreep_solve(h), "kcreep_solve after errors");
    expect(kcreep_get_matrix(h, NULL) == KCREEP_BAD_INPUT, "NULL output array refused");
    /* the normal problem and FASTSIM: bad calls refused, a good one checked */
    double fn, approach, pmax, creep[6] = {1e-7, 0, 0, 1, 0, 0}, force[6], adhesion[2];
    int cells, iterations;
    expect(kcreep_get_normal(h, &fn, &approach, &pmax, &cells, &iterations) == KCREEP_NO_RESULT,
           "no normal problem solved yet");
    expect(kcreep_fastsim(h, 0.3, 2, creep, NULL, "separate", force, adhesion) == KCREEP_BAD_INPUT,
           "FASTSIM without a pressure refused");
    double gap[40 * 40];
    for (int iy = 0; iy < 40; iy++)
      for (int ix = 0; ix < 40; ix++) {
        double x = -1 + (ix + 0.5) / 20, y = -1 + (iy + 0.5) / 20;
        gap[iy * 40 + ix] = (x * x + y * y) / (2 * 10.0);
      }
    expect(kcreep_set_gap(h, 40, 40, NULL, 0.05, 0.05, -0.975, -0.975, 0, 1000) == KCREEP_BAD_INPUT, "NULL gap refused");
    expect(kcreep_set_gap(h, 40, 40, gap, 0.05, 0.05, -0.975, -0.975, 0.01, 1000) == KCREEP_BAD_INPUT,
           "approach and normal_force together refused");
    must(h, kcreep_set_material(h, 82000.0, 0.28), "kcreep_set_material");
    /* the gap on its own 40 x 40 grid (no refinement): the conventions are under test, not the accuracy */
    must(h, kcreep_set_error_control(h, 0, 0, 1), "kcreep_set_error_control");
    must(h, kcreep_set_gap(h, 40, 40, gap, 0.05, 0.05, -0.975, -0.975, 0, 1000.0), "kcreep_set_gap");
    must(h, kcreep_solve(h), "kcreep_solve (gap)");
    must(h, kcreep_get_normal(h, &fn, &approach, &pmax, &cells, &iterations), "kcreep_get_normal");
    expect(fabs(fn - 1000.0) < 1e-8 * 1000.0 && approach > 0 && pmax > 0 && cells > 100, "normal problem solved");
    expect(kcreep_fastsim(h, 0.3, 2, creep, NULL, "sideways", force, adhesion) == KCREEP_BAD_INPUT,
           "unknown FASTSIM rule refused");
    must(h, kcreep_fastsim(h, 0.3, 2, creep, NULL, "separate", force, adhesion), "kcreep_fastsim");
    expect(fabs(-force[3] - 0.3 * fn) < 1e-3 * 0.3 * fn && adhesion[0] > 0.99, "FASTSIM saturates at mu Fn");
    printf("errors gap fn %.6e cells %d fx_full_slip %.6e\n", fn, cells, force[3]);
    /* the aligned rule (the program's default): pure xi as the separate rule, to round-off */
    double aligned[6];
    must(h, kcreep_fastsim(h, 0.3, 2, creep, NULL, "aligned", aligned, NULL), "kcreep_fastsim (aligned)");
    expect(fabs(aligned[0] - force[0]) <= 1e-12 * fabs(force[0]) && fabs(aligned[3] - force[3]) <= 1e-12 * fabs(force[3]),
           "FASTSIM aligned: pure xi as separate");
    /* exact rolling: the same conventions; small creepage near FASTSIM's slope (f11), full slip mu Fn
       (the elastic slip bends the directions a little at xi = 1: within 1e-4) */
    double fastsim_fx = force[0];
    expect(kcreep_rolling(h, -0.3, 2, creep, NULL, force, adhesion) == KCREEP_BAD_INPUT, "rolling: mu < 0 refused");
    must(h, kcreep_rolling(h, 0.3, 2, creep, NULL, force, adhesion), "kcreep_rolling");
    expect(fabs(force[0] / fastsim_fx - 1) < 1e-3 && fabs(-force[3] - 0.3 * fn) < 1e-4 * 0.3 * fn &&
           adhesion[0] > 0.95 && adhesion[1] == 0, "rolling: slope f11, saturation at mu Fn");
    printf("errors rolling fx %.6e %.10e fastsim %.6e adhesion %.4f %.4f\n", force[0], force[3], fastsim_fx, adhesion[0], adhesion[1]);
    /* the fast force model (kcreep_fast_forces): bad calls refused; on this gap patch's pressure
       within 2 % of mu Fn of kcreep_rolling at partial-slip points of every kind (measured on this
       208-cell patch: 0.15 % at mu = 0.3, 0.32 % at mu = 0.17; the bound is 2 %) and at another mu (the exact scaling F(mu, c) = mu F(1, c/mu)) */
    double mixed[15] = {2e-4, 0, 0, 0, -5e-4, 0, 0, 0, 0.02, -5e-4, 2e-3, -0.01, 3e-3, 1e-3, 0.05};
    double fast[15], exact[15];
    expect(kcreep_fast_forces(h, 0, 5, mixed, NULL, fast) == KCREEP_BAD_INPUT, "fast forces: mu = 0 refused");
    expect(kcreep_fast_forces(h, 0.3, 5, NULL, NULL, fast) == KCREEP_BAD_INPUT, "fast forces: NULL creep refused");
    for (int m = 0; m < 2; m++) {
      double mu = m == 0 ? 0.3 : 0.17, worst = 0;
      must(h, kcreep_fast_forces(h, mu, 5, mixed, NULL, fast), "kcreep_fast_forces");
      must(h, kcreep_rolling(h, mu, 5, mixed, NULL, exact, NULL), "kcreep_rolling (fast forces' check)");
      for (int k = 0; k < 5; k++) {
        double e = hypot(fast[3 * k] - exact[3 * k], fast[3 * k + 1] - exact[3 * k + 1]) / (mu * fn);
        worst = e > worst ? e : worst;
      }
      expect(worst < 0.02, "fast forces within 2 % of mu Fn of the exact rolling forces");
      printf("errors fast forces mu %.2f: largest distance from rolling %.2e of mu Fn\n", mu, worst);
    }
    int flags;
    expect(kcreep_get_verdict(h, &flags, NULL, 10) == KCREEP_BAD_INPUT, "NULL verdict buffer refused");
    char warning[512];
    expect(kcreep_get_warning(h, 1000, warning, sizeof warning) == KCREEP_BAD_INPUT, "warning index out of range refused");
    expect(kcreep_get_warning(h, -1, warning, sizeof warning) == KCREEP_BAD_INPUT, "negative warning index refused");
    kcreep_handle gone = h;
    kcreep_delete(&gone);
    expect(gone == NULL, "delete sets the handle to NULL");
    kcreep_delete(&gone); /* deleting NULL is harmless */
    h = NULL;
    printf("errors failures %d\n", failures);
  } else if (strcmp(mode, "bench") == 0) {
    /* repeated solves of one 40 x 40 patch on one handle: first call, then the median */
    int repeats = argc > 2 ? atoi(argv[2]) : 50;
    const char *shape = argc > 3 ? argv[3] : "ellipse";
    if (argc > 4) must(h, kcreep_set_solver(h, argv[4], 0), "kcreep_set_solver");
    /* the grid is judged once outside the loop; argv[5] = "estimate" keeps the per-call estimate */
    int print_steps = argc > 5 && strcmp(argv[5], "steps") == 0;
    must(h, kcreep_set_error_control(h, 0, 0, argc > 5 && strcmp(argv[5], "estimate") == 0),
         "kcreep_set_error_control");
    int *inside = circle_mask(40);
    double *times = malloc(sizeof(double) * repeats);
    long total_iterations = 0;
    for (int r = 0; r < repeats; r++) {
      double t0 = seconds();
      if (strcmp(shape, "ellipse") == 0) {
        must(h, kcreep_set_ellipse(h, 1.0, 1.0, 40, 40), "kcreep_set_ellipse");
        must(h, kcreep_solve(h), "kcreep_solve");
      } else if (strcmp(shape, "moving") == 0) {
        /* a time-stepping loop: the patch changes every call (semi-axes
         * breathing by up to 5 %, centre drifting), the grid stays */
        double a = 0.9 + 0.05 * sin(0.7 * r), b = 0.9 + 0.05 * cos(0.5 * r), xc = 0.03 * sin(0.3 * r);
        for (int iy = 0; iy < 40; iy++)
          for (int ix = 0; ix < 40; ix++) {
            double x = -1 + (ix + 0.5) / 20 - xc, y = -1 + (iy + 0.5) / 20;
            inside[iy * 40 + ix] = (x / a) * (x / a) + (y / b) * (y / b) <= 1;
          }
        must(h, kcreep_solve_mask(h, 40, 40, inside, 0.05, 0.05, -0.975, -0.975), "kcreep_solve_mask");
      } else {
        must(h, kcreep_solve_mask(h, 40, 40, inside, 0.05, 0.05, -0.975, -0.975), "kcreep_solve_mask");
      }
      double c[3];
      must(h, kcreep_get_normalised(h, c), "kcreep_get_normalised");
      times[r] = seconds() - t0;
      int iterations;
      double residual, rcond, solve_seconds;
      must(h, kcreep_get_diagnostics(h, &iterations, &residual, &rcond, &solve_seconds), "kcreep_get_diagnostics");
      total_iterations += iterations;
      if (print_steps) printf("step %d c %.15e %.15e %.15e iterations %d\n", r, c[0], c[1], c[2], iterations);
    }
    double first = times[0];
    qsort(times + 1, repeats - 1, sizeof(double), compare_double);
    printf("bench %s first_ms %.3f repeated_median_ms %.3f mean_iterations %.1f\n", shape, 1e3 * first,
           1e3 * times[repeats / 2], (double)total_iterations / repeats);
    free(times); free(inside);
  }
  kcreep_delete(&h);
  return failures ? 1 : 0;
}
