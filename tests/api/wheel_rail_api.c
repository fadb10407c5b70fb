/* The wheel-rail contact table through the C API: kcreep_set_profiles,
 * kcreep_set_track, kcreep_wheel_rail, kcreep_get_wheel_rail, the wheelset's
 * kcreep_wheelset, kcreep_get_wheelset, and their errors.
 *
 * usage: kcreep_wheel_rail_api WHEEL RAIL OUT G NU FORCE FLANGE_BACK_POSITION SHIFT...
 * Writes the table to OUT ('# ' and the column names, then one row per shift
 * and patch, 17 digits) and the wheelset table likewise to OUT.ws; prints FAIL
 * lines and exits 1 when a check fails. */
#include <kcreep.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;

static void expect_error(kcreep_handle h, int status, int code, const char *words, const char *what) {
  char message[512];
  kcreep_get_message(h, message, sizeof message);
  if (status != code || strstr(message, words) == NULL) {
    printf("FAIL %s: status %d (expected %d), message '%s' (expected to name '%s')\n", what, status, code, message,
           words);
    failures++;
  }
}

int main(int argc, char **argv) {
  if (argc < 9) {
    fprintf(stderr, "usage: %s WHEEL RAIL OUT G NU FORCE FLANGE_BACK_POSITION SHIFT...\n", argv[0]);
    return 2;
  }
  int n = argc - 8, rows = -1;
  double *shifts = malloc(n * sizeof *shifts);
  for (int k = 0; k < n; k++) shifts[k] = atof(argv[8 + k]);
  kcreep_handle h = kcreep_new();
  double t1[KCREEP_WHEEL_RAIL_COLUMNS];

  /* errors: each with status 2 (6: no table yet) and a message naming what is wrong */
  expect_error(h, kcreep_get_wheel_rail(h, KCREEP_WHEEL_RAIL_COLUMNS, t1), 6, "kcreep_wheel_rail", "table before a run");
  expect_error(h, kcreep_get_wheelset(h, KCREEP_WHEEL_RAIL_COLUMNS, t1), 6, "kcreep_wheelset", "wheelset before a run");
  expect_error(h, kcreep_wheelset(h, 1, shifts, 0, 80000, &rows), 2, "kcreep_set_profiles", "wheelset, no profiles");
  expect_error(h, kcreep_wheel_rail(h, 1, shifts, 0, 80000, 0, &rows), 2, "kcreep_set_profiles", "run without profiles");
  expect_error(h, kcreep_set_profiles(h, "no-such-wheel.prw", argv[2], 0, 0, 0), 2, "no-such-wheel.prw", "missing file");
  expect_error(h, kcreep_set_profiles(h, argv[1], NULL, 0, 0, 0), 2, "NULL", "NULL rail file");
  expect_error(h, kcreep_set_profiles(h, argv[1], argv[2], 2, 0, 0), 2, "wheel_mirror", "mirror flag 2");
  expect_error(h, kcreep_set_track(h, "middle", 1435, 14, 0, 1360, -70, 460), 2, "side", "side 'middle'");
  expect_error(h, kcreep_set_track(h, "right", 1435, 14, 0, 1360, -70, -460), 2, "nominal_radius", "radius < 0");
  if (kcreep_set_profiles(h, argv[1], argv[2], 0, 0, 0) != 0) {
    printf("FAIL profiles %s, %s not read\n", argv[1], argv[2]);
    return 1;
  }
  expect_error(h, kcreep_wheel_rail(h, n, shifts, 0, 80000, 0.1, &rows), 2, "exactly one", "force and approach");
  expect_error(h, kcreep_wheel_rail(h, n, shifts, 0.5, 80000, 0, &rows), 2, "yaw", "yaw 0.5");
  expect_error(h, kcreep_wheel_rail(h, 0, shifts, 0, 80000, 0, &rows), 2, "n_shifts", "no shifts");

  /* the table */
  if (kcreep_set_material(h, atof(argv[4]), atof(argv[5])) != 0 ||
      kcreep_set_track(h, "right", 1435, 14, 0, 1360, atof(argv[7]), 460) != 0 ||
      kcreep_wheel_rail(h, n, shifts, 0, atof(argv[6]), 0, &rows) != 0) {
    char message[512];
    kcreep_get_message(h, message, sizeof message);
    printf("FAIL the table: %s\n", message);
    return 1;
  }
  double *table = malloc((size_t)rows * KCREEP_WHEEL_RAIL_COLUMNS * sizeof *table);
  expect_error(h, kcreep_get_wheel_rail(h, rows * KCREEP_WHEEL_RAIL_COLUMNS - 1, table), 2, "length", "short array");
  if (kcreep_get_wheel_rail(h, rows * KCREEP_WHEEL_RAIL_COLUMNS, table) != 0) {
    printf("FAIL kcreep_get_wheel_rail\n");
    return 1;
  }
  FILE *out = fopen(argv[3], "w");
  fprintf(out, "# %s\n", KCREEP_WHEEL_RAIL_COLUMN_NAMES);
  for (int r = 0; r < rows; r++) {
    for (int k = 0; k < KCREEP_WHEEL_RAIL_COLUMNS; k++)
      fprintf(out, "%.17g%s", table[r * KCREEP_WHEEL_RAIL_COLUMNS + k], k + 1 < KCREEP_WHEEL_RAIL_COLUMNS ? " " : "\n");
  }
  fclose(out);

  /* the wheelset: its errors, then its table to OUT.ws */
  int ws_rows = -1;
  expect_error(h, kcreep_wheelset(h, n, shifts, 0, 0, &ws_rows), 2, "vertical_force", "wheelset without a load");
  expect_error(h, kcreep_set_left_profiles(h, "no-such-left.prw", NULL), 2, "no-such-left.prw", "missing left file");
  if (kcreep_set_left_profiles(h, NULL, "") != 0 || kcreep_wheelset(h, n, shifts, 0, atof(argv[6]), &ws_rows) != 0) {
    char message[512];
    kcreep_get_message(h, message, sizeof message);
    printf("FAIL the wheelset: %s\n", message);
    return 1;
  }
  double *ws = malloc((size_t)ws_rows * KCREEP_WHEELSET_COLUMNS * sizeof *ws);
  expect_error(h, kcreep_get_wheelset(h, ws_rows * KCREEP_WHEELSET_COLUMNS - 1, ws), 2, "length", "short wheelset array");
  if (ws_rows != n || kcreep_get_wheelset(h, ws_rows * KCREEP_WHEELSET_COLUMNS, ws) != 0) {
    printf("FAIL kcreep_get_wheelset (%d rows for %d shifts)\n", ws_rows, n);
    return 1;
  }
  char ws_path[4096];
  snprintf(ws_path, sizeof ws_path, "%s.ws", argv[3]);
  out = fopen(ws_path, "w");
  fprintf(out, "# %s\n", KCREEP_WHEELSET_COLUMN_NAMES);
  for (int r = 0; r < ws_rows; r++) {
    for (int k = 0; k < KCREEP_WHEELSET_COLUMNS; k++)
      fprintf(out, "%.17g%s", ws[r * KCREEP_WHEELSET_COLUMNS + k], k + 1 < KCREEP_WHEELSET_COLUMNS ? " " : "\n");
  }
  fclose(out);
  free(ws);
  kcreep_delete(&h);
  free(table);
  free(shifts);
  printf("%d rows, %d failed checks\n", rows, failures);
  return failures ? 1 : 0;
}
