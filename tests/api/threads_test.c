/* Handles are independent: eight threads, each with its own handle, solve a
 * mixed list of problems (ellipses on the dense and the iterative path,
 * masks, gaps through the normal problem, with and without the error
 * estimate, automatic and explicit thread counts) at the same time, and
 * every number must equal, bit for bit, what the same handles give when the
 * same calls run one after another. The one exception is LAPACK's condition
 * estimate rcond (a diagnostic, not a result): OpenBLAS's dgecon was seen to
 * differ in its last two bits between such runs (relative 1e-15, with the LU
 * factors and every coefficient identical), so it is held to 1e-12.
 *
 *   threads_test [rounds]     (exit 0: identical; 1: a difference or a failed call)
 */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "kcreep.h"

#define WORKERS 8
#define JOBS_PER_WORKER 3
#define VALUES 33     /* kcreep_get_results */
#define NORMAL 5      /* fn, approach, pmax, cells, iterations */
#define RCOND 26      /* kcreep_get_results: rcond */

typedef struct {
  int kind;           /* 0 ellipse, 1 mask, 2 gap */
  int m;              /* grid cells across */
  double a, b;        /* semi-axes (ellipse, mask) or curvatures (gap) */
  const char *method; /* "auto", "dense", "iterative" */
  int estimate;       /* the error estimate of the grid (one more solve) */
  int threads;        /* 0 automatic */
} job_t;

typedef struct {
  int worker;
  double values[JOBS_PER_WORKER][VALUES + NORMAL];
  int failed;
  char message[512];
} work_t;

static job_t job_of(int worker, int k) {
  /* a different mix per worker: kinds, sizes, methods and thread counts turn */
  int i = worker * JOBS_PER_WORKER + k;
  job_t j;
  j.kind = i % 3;
  j.m = 24 + 4 * (i % 5);
  j.a = 1.0 + 0.15 * (i % 4);
  j.b = 1.0 - 0.1 * (i % 3);
  j.method = (i % 4 == 0) ? "dense" : (i % 4 == 1 ? "iterative" : "auto");
  j.estimate = i % 2;
  j.threads = (i % 5 == 0) ? 2 : 0;
  return j;
}

static int run_job(kcreep_handle h, job_t j, double *out, char *message, size_t length) {
  int status = kcreep_set_solver(h, j.method, 0);
  if (status == KCREEP_OK) status = kcreep_set_error_control(h, 0, 0, j.estimate);
  if (status == KCREEP_OK) status = kcreep_set_threads(h, j.threads);
  int m = j.m;
  if (status == KCREEP_OK && j.kind == 0) {
    status = kcreep_set_ellipse(h, j.a, j.b, m, m);
    if (status == KCREEP_OK) status = kcreep_solve(h);
  } else if (status == KCREEP_OK && j.kind == 1) {
    /* a non-convex patch: an ellipse with a bite out of one side */
    int *inside = malloc(sizeof(int) * m * m);
    for (int iy = 0; iy < m; iy++)
      for (int ix = 0; ix < m; ix++) {
        double x = -1 + (ix + 0.5) * 2.0 / m, y = -1 + (iy + 0.5) * 2.0 / m;
        inside[iy * m + ix] = (x / j.a) * (x / j.a) + (y / j.b) * (y / j.b) <= 1 &&
                              (x - 0.9) * (x - 0.9) + y * y > 0.16;
      }
    status = kcreep_solve_mask(h, m, m, inside, 2.0 / m, 2.0 / m, -1 + 1.0 / m, -1 + 1.0 / m);
    free(inside);
  } else if (status == KCREEP_OK) {
    /* two curved bodies: the normal problem finds the contact area */
    double *gap = malloc(sizeof(double) * m * m), d = 2.4 / m;
    for (int iy = 0; iy < m; iy++)
      for (int ix = 0; ix < m; ix++) {
        double x = -1.2 + (ix + 0.5) * d, y = -1.2 + (iy + 0.5) * d;
        gap[iy * m + ix] = 0.5 * (j.a * x * x + j.b * y * y) + 0.05 * x * x * x;
      }
    status = kcreep_set_gap(h, m, m, gap, d, d, -1.2 + d / 2, -1.2 + d / 2, 0.3, 0);
    if (status == KCREEP_OK) status = kcreep_solve(h);
    free(gap);
  }
  memset(out, 0, sizeof(double) * (VALUES + NORMAL));
  if (status == KCREEP_OK) status = kcreep_get_results(h, VALUES, out);
  out[27] = 0;   /* seconds: the one number that may differ */
  if (status == KCREEP_OK && j.kind == 2) {
    int cells, iterations;
    status = kcreep_get_normal(h, &out[VALUES], &out[VALUES + 1], &out[VALUES + 2], &cells, &iterations);
    out[VALUES + 3] = cells;
    out[VALUES + 4] = iterations;
  }
  if (status != KCREEP_OK) kcreep_get_message(h, message, (int)length);
  return status;
}

static void *worker_main(void *argument) {
  work_t *w = argument;
  kcreep_handle h = kcreep_new();
  for (int k = 0; k < JOBS_PER_WORKER && !w->failed; k++)
    if (run_job(h, job_of(w->worker, k), w->values[k], w->message, sizeof w->message) != KCREEP_OK)
      w->failed = 1;
  kcreep_delete(&h);
  return NULL;
}

int main(int argc, char **argv) {
  int rounds = argc > 1 ? atoi(argv[1]) : 2;
  static work_t alone[WORKERS], together[WORKERS];
  for (int t = 0; t < WORKERS; t++) {   /* one after another */
    alone[t].worker = t;
    worker_main(&alone[t]);
    if (alone[t].failed) {
      printf("FAIL worker %d alone: %s\n", t, alone[t].message);
      return 1;
    }
  }
  int differences = 0;
  for (int r = 0; r < rounds; r++) {   /* all at once, several times */
    pthread_t threads[WORKERS];
    memset(together, 0, sizeof together);
    for (int t = 0; t < WORKERS; t++) {
      together[t].worker = t;
      if (pthread_create(&threads[t], NULL, worker_main, &together[t]) != 0) {
        printf("FAIL pthread_create\n");
        return 1;
      }
    }
    for (int t = 0; t < WORKERS; t++) pthread_join(threads[t], NULL);
    for (int t = 0; t < WORKERS; t++) {
      if (together[t].failed) {
        printf("FAIL worker %d together: %s\n", t, together[t].message);
        return 1;
      }
      for (int k = 0; k < JOBS_PER_WORKER; k++)
        for (int v = 0; v < VALUES + NORMAL; v++)
          if (v == RCOND ? fabs(alone[t].values[k][v] - together[t].values[k][v]) >
                               1e-12 * fabs(alone[t].values[k][v])
                         : memcmp(&alone[t].values[k][v], &together[t].values[k][v], sizeof(double)) != 0) {
            if (differences++ < 20)
              printf("FAIL round %d worker %d job %d value %d: %.17g alone, %.17g together\n", r, t, k, v,
                     alone[t].values[k][v], together[t].values[k][v]);
          }
    }
  }
  int kinds[3] = {0, 0, 0};
  for (int t = 0; t < WORKERS; t++)
    for (int k = 0; k < JOBS_PER_WORKER; k++) kinds[job_of(t, k).kind]++;
  printf("threads_test: %d workers x %d jobs (%d ellipses, %d masks, %d gaps), %d rounds: %d values differ\n",
         WORKERS, JOBS_PER_WORKER, kinds[0], kinds[1], kinds[2], rounds, differences);
  return differences ? 1 : 0;
}
