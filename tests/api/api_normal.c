/* The normal contact problem through the C API: Hertz's sphere from a gap
 * array with the force prescribed; the pressure against Hertz, the contact
 * cells against kcreep_get_cells, errors for bad arguments. Exit 0 when all
 * checks pass. Tolerances: on this grid (20 cells across the contact
 * circle, a cell centre at the origin) the measured errors are 6.4e-4
 * (pmax) and 2.3e-4 (approach): docs/normal.md, Hertz table at n = 20. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "kcreep.h"

static int failures = 0;
static void check(int ok, const char *what) {
    printf("%s %s\n", ok ? "ok  " : "FAIL", what);
    if (!ok) failures++;
}

int main(void) {
    const double pi = acos(-1.0), g = 1.0, nu = 0.25, force = 1.0;
    const double c = (1 - nu) / g;                       /* 1/E* of identical bodies */
    const double a = cbrt(3 * force * 1.0 * c / 4);      /* Hertz, relative radius 1 */
    const double p0 = 3 * force / (2 * pi * a * a);
    const int n = 20, m = 27;                            /* 20 cells across 2a, grid 27 x 27 */
    const double d = 2 * a / n, x0 = -(m - 1) * d / 2;
    double *gap = malloc(sizeof(double) * m * m);
    for (int iy = 0; iy < m; iy++)
        for (int ix = 0; ix < m; ix++) {
            double x = x0 + ix * d, y = x0 + iy * d;
            gap[iy * m + ix] = (x * x + y * y) / 2;
        }
    kcreep_handle h = kcreep_new();
    check(kcreep_set_material(h, g, nu) == KCREEP_OK, "set material");
    check(kcreep_set_gap(h, m, m, gap, d, d, x0, x0) == KCREEP_OK, "set gap");
    check(kcreep_set_normal_load(h, 1, force) == KCREEP_OK, "set normal force");
    check(kcreep_solve(h) == KCREEP_OK, "solve (normal, then tangential on the contact cells)");
    double fn, approach, pmax, residual;
    int iterations, cells, mx, my;
    check(kcreep_get_normal(h, &fn, &approach, &pmax, &iterations, &residual) == KCREEP_OK, "get normal");
    check(fabs(fn / force - 1) < 1e-12, "fn as prescribed");
    check(fabs(pmax / p0 - 1) < 1.5e-3, "pmax against Hertz");
    check(fabs(approach / (a * a) - 1) < 1e-3, "approach against Hertz (a^2 / R)");
    check(residual <= 1e-10 && iterations > 0, "converged to 1e-10");
    kcreep_get_cells(h, &cells, &mx, &my);
    double *p = malloc(sizeof(double) * cells);
    check(kcreep_get_pressure(h, cells, p) == KCREEP_OK, "get pressure");
    double sum = 0, big = 0;
    for (int k = 0; k < cells; k++) { sum += p[k]; if (p[k] > big) big = p[k]; }
    check(fabs(sum * d * d / fn - 1) < 1e-12 && big == pmax, "pressure per cell sums to fn, maximum pmax");
    check(fabs(cells * d * d / (pi * a * a) - 1) < 0.05, "contact area near pi a^2 (first order in the cell)");
    /* errors */
    check(kcreep_set_normal_load(h, 1, -1.0) == KCREEP_BAD_INPUT, "negative force refused");
    check(kcreep_set_gap(h, m, m, NULL, d, d, x0, x0) == KCREEP_BAD_INPUT, "NULL gap refused");
    gap[5] = NAN;
    check(kcreep_set_gap(h, m, m, gap, d, d, x0, x0) == KCREEP_BAD_INPUT, "NaN in the gap refused");
    gap[5] = 1.0;
    check(kcreep_set_gap(h, m, m, gap, d, d, x0, x0) == KCREEP_OK, "gap set again");
    check(kcreep_set_normal_load(h, 0, -1.0) == KCREEP_OK && kcreep_solve(h) == KCREEP_BAD_INPUT,
          "an approach without interpenetration: solve refused");
    char message[300];
    kcreep_get_message(h, message, sizeof message);
    printf("     message: %s\n", message);
    /* back to an ellipse: no normal problem in the result */
    check(kcreep_set_ellipse(h, 1.0, 1.0, 20, 20) == KCREEP_OK && kcreep_solve(h) == KCREEP_OK, "ellipse after gap");
    check(kcreep_get_normal(h, &fn, &approach, &pmax, &iterations, &residual) == KCREEP_NO_RESULT,
          "no normal result for an ellipse");
    kcreep_delete(&h);
    free(p);
    free(gap);
    printf("%d failed\n", failures);
    return failures ? 1 : 0;
}
