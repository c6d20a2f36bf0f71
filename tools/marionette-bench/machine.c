/* The machine a figure was measured on, the clock, output, and one run. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"

void bench_machine(char *out, size_t size) {
  struct utsname u;
  char model[128] = "unknown CPU", line[256];
  FILE *f = fopen("/proc/cpuinfo", "r");
  while (f != NULL && fgets(line, sizeof line, f) != NULL) {
    char *colon = strchr(line, ':');
    if (strncmp(line, "model name", 10) != 0 || colon == NULL) continue;
    snprintf(model, sizeof model, "%s", colon + 2);
    model[strcspn(model, "\n")] = '\0';
    break;
  }
  if (f != NULL) fclose(f);
  if (uname(&u) != 0) memset(&u, 0, sizeof u);
  snprintf(out, size, "%s %s %s, %s, %ld cores", u.sysname, u.release, u.machine, model,
           sysconf(_SC_NPROCESSORS_ONLN));
}

double bench_cpu_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

double bench_wall_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

void bench_say(bench *b, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vprintf(fmt, ap);
  va_end(ap);
  fflush(stdout);
  if (b->summary == NULL) return;
  va_start(ap, fmt);
  vfprintf(b->summary, fmt, ap);
  va_end(ap);
}

void bench_progress(const char *section, const char *fmt, ...) {
  va_list ap;
  fprintf(stderr, "[%s] ", section);
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
}

FILE *bench_open(const bench *b, const char *name) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", b->out, name);
  FILE *f = fopen(path, "w");
  if (f == NULL) fprintf(stderr, "marionette-bench: cannot write %s\n", path);
  return f;
}

int bench_load(const bench *b, const char *rel, mr_scene *scene) {
  char path[1024];
  mr_scene_error err;
  snprintf(path, sizeof path, "%s/%s", b->root, rel);
  if (mr_scene_load(path, scene, &err) == MR_SCENE_OK) return 0;
  fprintf(stderr, "marionette-bench: %s\n", err.text);
  return -1;
}

static void on_frame(void *user, double t, const double *xyz, int n) {
  bench_run *r = user;
  if (t > r->horizon + 1e-9 || (int)r->ee_index >= n) return;
  if (r->ee_count == r->ee_cap) {
    int cap = r->ee_cap ? 2 * r->ee_cap : 1024;
    double *p = realloc(r->ee, (size_t)cap * 3 * sizeof *p);
    if (p == NULL) return;
    r->ee = p;
    r->ee_cap = cap;
  }
  memcpy(&r->ee[3 * r->ee_count++], &xyz[3 * r->ee_index], 3 * sizeof(double));
}

int bench_run_scene(const mr_scene *scene, double duration, size_t ee_index, double horizon,
                    bench_run *out) {
  return bench_run_scene_from(scene, duration, ee_index, horizon, NULL, NULL, out);
}

int bench_run_scene_from(const mr_scene *scene, double duration, size_t ee_index, double horizon,
                         const double *start, double *end, bench_run *out) {
  memset(out, 0, sizeof *out);
  out->ee_index = ee_index;
  out->horizon = horizon;
  mr_sim_def o = mr_default_sim_def();
  o.duration = duration;
  o.fps = 60;
  o.present = MR_PRESENT_INTERPOLATE;
  o.on_frame = on_frame;
  o.user = out;
  o.start_state = start;
  o.end_state = end;
  mr_scene_error err;
  double t0 = bench_cpu_seconds();
  mr_scene_status st = mr_sim_run(scene, &o, &out->r, &err);
  out->cpu = bench_cpu_seconds() - t0;
  if (st == MR_SCENE_OK) return 0;
  fprintf(stderr, "marionette-bench: %s\n", err.text);
  return -1;
}

static int ascending(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

void bench_sort(double *v, int n) {
  if (n > 1) qsort(v, (size_t)n, sizeof *v, ascending);
}

void bench_run_free(bench_run *r) {
  free(r->ee);
  r->ee = NULL;
  r->ee_count = r->ee_cap = 0;
}

void bench_ee_error(const bench_run *a, const bench_run *ref, double *max, double *rms) {
  int n = a->ee_count < ref->ee_count ? a->ee_count : ref->ee_count;
  double big = 0.0, sum = 0.0;
  for (int i = 0; i < n; i++) {
    const double *p = &a->ee[3 * i], *q = &ref->ee[3 * i];
    double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                (p[2] - q[2]) * (p[2] - q[2]);
    if (!(d2 <= big * big)) big = sqrt(d2);
    sum += d2;
  }
  *max = n > 0 ? big : NAN;
  *rms = n > 0 ? sqrt(sum / n) : NAN;
}
