/* The benchmark's other sections: the paper's §7 run (item 7), scene load
 * time (item 3), latency (item 4), and the fixed runs `make bench-count`
 * counts (item 6). Capacity (item 3) is in capacity.c. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <valgrind/callgrind.h>

#include "bench.h"
#include "gg_stream.h"
#include "gp.h"
#include "mr_scene_world.h"

/* §7: bounds 0.01–0.05 s, thresholds 0.01 %–1 %, the walking tracks. */
int bench_paper_run(bench *b) {
  static const char *const scenes[] = { "host/scenes/puppet.yaml", "host/scenes/stick.yaml" };
  bench_say(b, "\n== the paper's sec. 7 run (item 7): bounds 0.01-0.05 s, thresholds "
               "0.01 %%-1 %% ==\n");
  bench_say(b, "%-26s %-22s %7s %9s %8s %9s %9s\n", "scene", "error control", "steps", "mean dt",
            "upper", "max dev", "ms/sim-s");
  for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
    mr_scene sc;
    if (bench_load(b, scenes[i], &sc) != 0) return -1;
    mr_world_def *d = &sc.world;
    d->dt_min = 0.01, d->dt_max = 0.05, d->deviation_low = 1e-4, d->deviation_high = 1e-2;
    for (int paper = 0; paper < 2; paper++) {
      if (paper) d->error_length = d->error_speed = 0.0;
      bench_progress("sec7", "%s%s", scenes[i], paper ? " (deviation only)" : "");
      bench_run run;
      if (bench_run_scene(&sc, 0, 0, 0, &run) != 0) break;
      const mr_sim_result *r = &run.r;
      bench_say(b, "%-26s %-22s %7llu %9.5f %7.1f%% %9.2e %9.3f\n", scenes[i] + 12,
                paper ? "deviation (paper)" : "deviation + estimate", (unsigned long long)r->steps,
                r->dt_mean, 100 * r->at_upper_fraction, r->max_deviation,
                1000 * run.cpu / r->sim_time);
      bench_run_free(&run);
    }
    mr_scene_free(&sc);
  }
  bench_say(b, "the paper: mean dt about 0.02 s, \"most of the movements\" at the upper bound\n");
  return 0;
}

int bench_load_time(bench *b) {
  bench_say(b, "\n== scene load time (item 3), by scene-bench ==\n");
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "'%s' --max %d", SCENE_BENCH_PATH, b->quick ? 10000 : 100000);
  FILE *p = popen(cmd, "r");
  if (p == NULL) return -1;
  char line[512];
  while (fgets(line, sizeof line, p) != NULL) bench_say(b, "%s", line);
  return pclose(p) == 0 ? 0 : -1;
}

/* Per-frame CPU time of a paced run: the time between frames presented. */
typedef struct frame_clock {
  double last, *cost;
  int n, cap;
} frame_clock;

static void on_frame_clock(void *user, double t, const double *xyz, int n) {
  (void)t, (void)xyz, (void)n;
  frame_clock *c = user;
  double now = bench_cpu_seconds();
  if (c->n < c->cap) c->cost[c->n++] = now - c->last;
  c->last = now;
}

/* Glove sample to the first frame that shows it, headless: the theater
 * reads the newest sample at each frame tick and the frame is shown when
 * its steps are done, so a sample waits for the next tick (arrivals spread
 * evenly over the frame period, 16 per frame) and then for that frame's
 * compute, measured frame by frame on puppet.yaml at 60 fps (landing, as
 * the theater presents). */
int bench_latency(bench *b) {
  mr_scene sc;
  if (bench_load(b, "host/scenes/puppet.yaml", &sc) != 0) return -1;
  const double period = 1.0 / 60.0;
  frame_clock c = { 0 };
  c.cap = 60 * 13;
  c.cost = calloc((size_t)c.cap, sizeof *c.cost);
  double *lat = calloc((size_t)c.cap * 16, sizeof *lat);
  mr_sim_def o = mr_default_sim_def();
  o.fps = 60;
  o.present = MR_PRESENT_LAND;
  o.on_frame = on_frame_clock;
  o.user = &c;
  mr_sim_result r;
  mr_scene_error err;
  bench_progress("latency", "puppet.yaml at 60 fps");
  c.last = bench_cpu_seconds();
  int rc = c.cost && lat && mr_sim_run(&sc, &o, &r, &err) == MR_SCENE_OK ? 0 : -1;
  int n = 0;
  for (int f = 0; rc == 0 && f < c.n; f++)
    for (int k = 0; k < 16; k++) lat[n++] = period * (k + 0.5) / 16.0 + c.cost[f];
  if (rc == 0 && n > 0) {
    bench_sort(lat, (int)n);
    bench_sort(c.cost, (int)c.n);
    double wire = (double)GP_MAX_WIRE * 10.0 / 115200.0;
    bench_say(b, "\n== latency (item 4), headless, puppet.yaml at 60 fps ==\n");
    bench_say(b, "frame compute: p50 %.3f ms, p99 %.3f ms, max %.3f ms (%d frames)\n",
              1e3 * c.cost[c.n / 2], 1e3 * c.cost[(c.n * 99) / 100], 1e3 * c.cost[c.n - 1], c.n);
    bench_say(b,
              "sample to frame: p50 %.2f ms, p99 %.2f ms; target p99 <= %.2f ms (one frame "
              "%.2f ms + a SAMPLE's wire time at 115200 8N1, at most %.2f ms)\n",
              1e3 * lat[n / 2], 1e3 * lat[(n * 99) / 100], 1e3 * (period + wire), 1e3 * period,
              1e3 * wire);
  }
  free(c.cost);
  free(lat);
  mr_scene_free(&sc);
  if (rc == 0 && bench_latency_live(b) != 0) rc = -1;
  return rc;
}

static int count_decode(void) {
  enum { FRAMES = 10000 };
  size_t len = 0;
  uint8_t *stream = gg_sample_burst(FRAMES, &len);
  if (stream == NULL) return -1;
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  CALLGRIND_START_INSTRUMENTATION;
  for (size_t off = 0; off < len;) {
    gp_msg out;
    gp_event ev;
    off += gp_decoder_feed(&d, stream + off, len - off, &out, &ev);
  }
  CALLGRIND_STOP_INSTRUMENTATION;
  free(stream);
  return d.c.frames == FRAMES ? 0 : -1;
}

int bench_count_run(bench *b, const char *which) {
  if (strcmp(which, "decode") == 0) return count_decode();
  /* The Fig. 10 track is where steps are shortest: the evaluation's cost
   * shows most there, the puppet's mix of forces on puppet.yaml. */
  const char *scene = strcmp(which, "puppet") == 0  ? "host/scenes/puppet.yaml"
                      : strcmp(which, "fig10") == 0 ? "host/scenes/hard/01_fig10_oscillate.yaml"
                                                    : NULL;
  /* The capacity benchmark's crowd: what a puppet costs among many. */
  const int crowd = strcmp(which, "crowd") == 0;
  if (scene == NULL && !crowd) {
    fprintf(stderr, "marionette-bench: --count expects puppet, fig10, crowd or decode, got '%s'\n",
            which);
    return -1;
  }
  mr_scene sc;
  if (crowd ? bench_crowd_load(100, &sc) != 0 : bench_load(b, scene, &sc) != 0) return -1;
  mr_sim_def o = mr_default_sim_def();
  o.duration = crowd ? 1.0 : 10.0;
  mr_sim_result r;
  mr_scene_error err;
  CALLGRIND_START_INSTRUMENTATION;
  mr_scene_status st = mr_sim_run(&sc, &o, &r, &err);
  CALLGRIND_STOP_INSTRUMENTATION;
  mr_scene_free(&sc);
  if (st != MR_SCENE_OK) fprintf(stderr, "marionette-bench: %s\n", err.text);
  return st == MR_SCENE_OK ? 0 : -1;
}
