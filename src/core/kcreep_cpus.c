/* What the operating system says about the CPUs this process may use and
 * how busy the machine is right now, for kcreep_threads (the automatic
 * thread count). Each function answers from a read of /proc or /sys and
 * returns 0 (or -1) when the file is not there, so that callers fall back
 * on what OpenMP knows. The one piece of state is the count of kcreep
 * solves running in this process (callers on several threads). */
#define _GNU_SOURCE
#include <dirent.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* CPUs in this process's affinity mask (taskset, SLURM's binding), 0 if unknown. */
int kcreep_affinity_cpus(void) {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 0;
  return CPU_COUNT(&set);
}

/* Online CPUs of the machine (the denominator of the run-queue count). */
int kcreep_online_cpus(void) {
  long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? (int)n : 0;
}

/* ceil(quota / period) of a cgroup CPU limit (containers, SLURM's cgroup
 * plugin), 0 when there is none. cgroup v2: cpu.max of this process's
 * group ("max 100000" means none); v1: cpu.cfs_quota_us / cpu.cfs_period_us. */
static int quota_from(double quota, double period) {
  if (quota <= 0 || period <= 0) return 0;
  int n = (int)(quota / period);
  return n + (quota > n * period ? 1 : 0);
}

int kcreep_cgroup_cpus(void) {
  char group[4096] = "", path[4200], word[64];
  FILE *f = fopen("/proc/self/cgroup", "r");
  if (f) {
    char line[4200];
    while (fgets(line, sizeof line, f))
      if (strncmp(line, "0::", 3) == 0) {
        line[strcspn(line, "\n")] = 0;
        snprintf(group, sizeof group, "%s", line + 3);
      }
    fclose(f);
  }
  for (int pass = 0; pass < 2; pass++) {   /* the process's own group, then the root one */
    snprintf(path, sizeof path, "/sys/fs/cgroup%s/cpu.max", pass == 0 ? group : "");
    double quota, period;
    f = fopen(path, "r");
    if (!f) continue;
    int got = fscanf(f, "%63s %lf", word, &period);
    fclose(f);
    if (got != 2 || strcmp(word, "max") == 0) return 0;
    if (sscanf(word, "%lf", &quota) != 1) return 0;
    return quota_from(quota, period);
  }
  double quota = -1, period = -1;
  f = fopen("/sys/fs/cgroup/cpu/cpu.cfs_quota_us", "r");
  if (f) { if (fscanf(f, "%lf", &quota) != 1) quota = -1; fclose(f); }
  f = fopen("/sys/fs/cgroup/cpu/cpu.cfs_period_us", "r");
  if (f) { if (fscanf(f, "%lf", &period) != 1) period = -1; fclose(f); }
  return quota_from(quota, period);
}

/* Runnable threads of this process now (state R in /proc/self/task). */
static int own_runnable(void) {
  DIR *d = opendir("/proc/self/task");
  if (!d) return 0;
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d))) {
    if (e->d_name[0] < '0' || e->d_name[0] > '9') continue;
    char path[64], line[512];
    snprintf(path, sizeof path, "/proc/self/task/%s/stat", e->d_name);
    FILE *f = fopen(path, "r");
    if (!f) continue;
    size_t got = fread(line, 1, sizeof line - 1, f);
    fclose(f);
    line[got] = 0;
    char *close = strrchr(line, ')');   /* the name may hold spaces: the state follows the last ')' */
    if (close && close[1] == ' ' && close[2] == 'R') n++;
  }
  closedir(d);
  return n;
}

/* Threads of other processes runnable on the machine at this moment: the
 * first number of /proc/loadavg's fourth field less this process's own
 * (its pool threads may still be spinning after the last parallel region,
 * which says nothing about the machine). -1 if unknown. */
int kcreep_runnable_elsewhere(void) {
  double one, five, fifteen;
  int running, total;
  FILE *f = fopen("/proc/loadavg", "r");
  if (!f) return -1;
  int got = fscanf(f, "%lf %lf %lf %d/%d", &one, &five, &fifteen, &running, &total);
  fclose(f);
  if (got != 5) return -1;
  int others = running - own_runnable();
  return others > 0 ? others : 0;
}

/* kcreep solves running in this process: callers on several threads, each
 * with its own handle, count each other as busy CPUs. */
static atomic_int solves_running;
int kcreep_solve_started(void) { return atomic_fetch_add(&solves_running, 1) + 1; }
void kcreep_solve_ended(void) { atomic_fetch_sub(&solves_running, 1); }
int kcreep_solves_running(void) { return atomic_load(&solves_running); }

/* OpenBLAS on one thread: kcreep's dense LU is for small systems, where
 * OpenBLAS's threads cost more than they give (docs/performance.md,
 * "Threads"), its pool spins while other processes hold the cores (and for
 * about 0.1 s after the library loads, doubling a short run's CPU time),
 * and its threaded LU rounds differently from its serial one, so that
 * handles solving at once on several threads would not repeat each other's
 * numbers. The count is process-wide and left at one (restoring it would
 * race with another handle's LU); the pool's threads are stopped the first
 * time. With another BLAS the symbols are absent (weak): nothing happens. */
extern void openblas_set_num_threads(int) __attribute__((weak));
extern int openblas_get_num_threads(void) __attribute__((weak));
extern int blas_thread_shutdown_(void) __attribute__((weak));
void kcreep_serial_blas(void) {
  if (!openblas_set_num_threads || !openblas_get_num_threads || openblas_get_num_threads() == 1) return;
  openblas_set_num_threads(1);
  if (blas_thread_shutdown_) blas_thread_shutdown_();
}
