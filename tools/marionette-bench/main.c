/* marionette-bench: what accuracy costs in time (README: tools/README.md,
 * "Benchmark"). Runs the sections in order, prints every figure with the
 * machine it was measured on, and writes CSV files and plots into --out. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "bench.h"

static void usage(FILE *f) {
  fprintf(f, "usage: marionette-bench [--quick] [--out DIR] [--only LIST] [--root DIR]\n"
             "       marionette-bench --count puppet|fig10|crowd|decode|sweep|render\n"
             "\n"
             "Measures what accuracy costs in time and prints the figures, each run stamped\n"
             "with the machine (kernel, CPU model, cores). Sections, in order:\n"
             "  sweep     accuracy against cost: every setting (thresholds, bounds, solver,\n"
             "            integrator, Ks/Kd, error estimate, spring strings) on each puppet's\n"
             "            track; end-effector error against a converged RK4 reference; CSV,\n"
             "            and a gnuplot plot (SVG, PNG) with the Pareto front and the default\n"
             "  sec7      the paper's sec. 7 run: mean dt and the share at the upper bound\n"
             "  capacity  1, 10, 100, 1000 stick puppets, physics only, one core\n"
             "  load      loading scenes of up to 100 000 particles (scene-bench)\n"
             "  latency   glove sample to frame, headless, p50 and p99\n"
             "  peer      the stick marionette in MuJoCo and ours, at matched accuracy (built\n"
             "            only where libmujoco-dev is)\n"
             "  render    milliseconds a frame at 1280x720, headless, for each example scene,\n"
             "            the share of renders a 60 fps show skips, and the theater's set's\n"
             "            share of the cost (not with --quick)\n"
             "  window    the humanoid in a window at 1280x720 driven by glove-gen, idle and\n"
             "            beside a busy process a core: real-time factor, time given up,\n"
             "            drawn fps, glove-to-frame latency (xvfb-run without a display)\n"
             "  net       a show's state through a mosquitto of its own on loopback: bytes a\n"
             "            frame and a second for the humanoid at 60 fps, glove -> watcher\n"
             "            latency p50 and p99, the broker's CPU with 1 and 200 watchers\n"
             "\n"
             "  --quick       a run of about a minute (fewer settings, shorter tracks)\n"
             "  --out DIR     where sweep.csv, capacity.csv, the plots and summary.txt go\n"
             "                (default bench-out; created)\n"
             "  --only LIST   the sections to run, comma separated (default all)\n"
             "  --root DIR    the source tree holding host/scenes (default the one built)\n"
             "  --count RUN   one fixed run for `make bench-count` to count under callgrind\n"
             "                (--instr-atstart=no): puppet (puppet.yaml for 10 s), fig10 (the\n"
             "                stick figure on the Fig. 10 track for 10 s), crowd (the\n"
             "                capacity section's 100 stick puppets for 1 s), decode\n"
             "                (10 000 SAMPLE frames), sweep (the quick sweep's settings on\n"
             "                every puppet, 3 s each, one dump per run, a CSV line per run),\n"
             "                or render (one humanoid frame at 640x360, then at 1280x720, on\n"
             "                one llvmpipe thread, a dump each)\n"
             "  --help        this text\n"
             "\n"
             "Progress goes to stderr, figures to stdout and DIR/summary.txt. The CSV\n"
             "schemas are in tools/README.md.\n");
}

static int wanted(const char *only, const char *section) {
  if (only == NULL) return 1;
  size_t n = strlen(section);
  for (const char *p = only; (p = strstr(p, section)) != NULL; p += n)
    if ((p == only || p[-1] == ',') && (p[n] == '\0' || p[n] == ',')) return 1;
  return 0;
}

static int make_dir(const char *path) {
  if (mkdir(path, 0777) == 0 || errno == EEXIST) return 0;
  fprintf(stderr, "marionette-bench: cannot make %s: %s\n", path, strerror(errno));
  return -1;
}

static const struct {
  const char *name;
  int (*run)(bench *b);
} sections[] = {
  { "sweep", bench_sweep },    { "sec7", bench_paper_run },  { "capacity", bench_capacity },
  { "load", bench_load_time }, { "latency", bench_latency }, { "peer", bench_peer },
  { "render", bench_render },  { "window", bench_window },   { "net", bench_net }
};
#define N_SECTIONS (sizeof sections / sizeof sections[0])

/* Every comma-separated name in --only must be a section: a misspelt name
 * would otherwise run nothing and exit 0, as if it had measured. */
static int only_is_valid(const char *only) {
  for (const char *p = only;; p++) {
    size_t n = strcspn(p, ",");
    bool known = false;
    for (size_t i = 0; i < N_SECTIONS && !known; i++)
      known = strlen(sections[i].name) == n && strncmp(p, sections[i].name, n) == 0;
    if (!known) {
      fprintf(stderr, "marionette-bench: --only: unknown section '%.*s' in '%s' (see --help)\n",
              (int)n, p, only);
      return 0;
    }
    p += n;
    if (*p == '\0') return 1;
  }
}

static int run_sections(bench *b, const char *only) {
  int rc = 0;
  for (size_t i = 0; i < N_SECTIONS; i++) {
    if (!wanted(only, sections[i].name)) continue;
    double t0 = bench_cpu_seconds();
    if (sections[i].run(b) != 0) {
      fprintf(stderr, "marionette-bench: section %s failed\n", sections[i].name);
      rc = 1;
    }
    bench_progress(sections[i].name, "done in %.1f s of CPU", bench_cpu_seconds() - t0);
  }
  return rc;
}

int main(int argc, char **argv) {
  bench b = { .out = "bench-out", .root = SOURCE_ROOT };
  const char *only = NULL, *count = NULL;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(a, "--quick")) {
      b.quick = true;
    } else if (!strcmp(a, "--out") && v != NULL) {
      b.out = argv[++i];
    } else if (!strcmp(a, "--only") && v != NULL) {
      only = argv[++i];
    } else if (!strcmp(a, "--root") && v != NULL) {
      b.root = argv[++i];
    } else if (!strcmp(a, "--count") && v != NULL) {
      count = argv[++i];
    } else {
      fprintf(stderr, "marionette-bench: unknown or incomplete option '%s' (see --help)\n", a);
      return 2;
    }
  }
  /* Bad values are bad usage, like bad options: exit 2 before any work. */
  if (count != NULL && strcmp(count, "puppet") != 0 && strcmp(count, "decode") != 0 &&
      strcmp(count, "crowd") != 0 && strcmp(count, "fig10") != 0 && strcmp(count, "sweep") != 0 &&
      strcmp(count, "render") != 0) {
    fprintf(stderr,
            "marionette-bench: --count expects puppet, fig10, crowd, decode, sweep or render, got "
            "'%s'\n",
            count);
    return 2;
  }
  if (only != NULL && !only_is_valid(only)) return 2;
  bench_machine(b.machine, sizeof b.machine);
  if (count != NULL && strcmp(count, "sweep") == 0) return bench_sweep_count(&b) == 0 ? 0 : 1;
  if (count != NULL && strcmp(count, "render") == 0) return bench_count_render(&b) == 0 ? 0 : 1;
  if (count != NULL) return bench_count_run(&b, count) == 0 ? 0 : 1;
  if (make_dir(b.out) != 0) return 1;
  b.summary = bench_open(&b, "summary.txt");
  time_t now = time(NULL);
  char when[64];
  strftime(when, sizeof when, "%Y-%m-%d %H:%M UTC", gmtime(&now));
  bench_say(&b, "marionette-bench%s, %s\nmachine: %s\n", b.quick ? " --quick" : "", when,
            b.machine);
  int rc = run_sections(&b, only);
  if (b.summary) fclose(b.summary);
  return rc;
}
