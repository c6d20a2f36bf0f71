/* Item 4, live: glove-gen writes SAMPLEs at 250 Hz into a pty on the wall
 * clock; the glove library reads them, and a 60 fps loop steps
 * puppet.yaml's world one frame at each tick. A sample is shown by the
 * first frame finished after it was read. Its latency is that frame's end
 * minus the sample's device time put on the host clock with the offset
 * the glove library estimates (the smallest host − device time seen, so
 * the path's fixed delay is inside the offset, not in the figure). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "mr_glove.h"
#include "mr_scene_world.h"

extern char **environ;

enum { MAX_SAMPLES = 20000 };

typedef struct live {
  double now;                 /* the poll under way's time */
  double device[MAX_SAMPLES]; /* s */
  double read[MAX_SAMPLES];   /* host time it was read */
  double shown[MAX_SAMPLES];  /* host time of the frame showing it */
  int n, pending;             /* samples, and the first not yet shown */
} live;

static void on_frame(void *user, gp_event ev, const gp_msg *m, uint64_t byte) {
  (void)byte;
  live *l = user;
  if (ev != GP_EV_FRAME || m == NULL || m->type != GP_SAMPLE || l->n >= MAX_SAMPLES) return;
  l->device[l->n] = m->u.sample.t_us * 1e-6;
  l->read[l->n++] = l->now;
}

pid_t bench_glove_gen_start(const bench *b, const char *name, double seconds, char *path,
                            size_t size) {
  char file[1024], dur[32];
  snprintf(file, sizeof file, "%s/%s-pty.txt", b->out, name);
  snprintf(dur, sizeof dur, "%g", seconds);
  remove(file);
  char *argv[] = { GLOVE_GEN_PATH, "-o", "pty", "--path-file", file, "--wait", "10", "-r",
                   "250",          "-d", dur,   "--linger",    "1",  "-q",     NULL };
  pid_t pid;
  if (posix_spawn(&pid, argv[0], NULL, NULL, argv, environ) != 0) return -1;
  for (int i = 0; i < 500; i++) {
    FILE *f = fopen(file, "r");
    if (f != NULL && fgets(path, (int)size, f) != NULL && strchr(path, '\n')) {
      path[strcspn(path, "\n")] = '\0';
      fclose(f);
      return pid;
    }
    if (f) fclose(f);
    nanosleep(&(struct timespec){ 0, 10000000 }, NULL);
  }
  kill(pid, SIGTERM);
  waitpid(pid, NULL, 0);
  return -1;
}

/* The 60 fps loop for `seconds` of wall time: poll the glove until each
 * tick, step the world to the tick, and mark the samples read before it
 * as shown when the step is done. */
static void run_loop(mr_glove *g, live *l, mr_scene *sc, mr_scene_world *sw, double seconds) {
  const double period = 1.0 / 60.0, t0 = bench_wall_seconds();
  for (int frame = 1; frame <= (int)(seconds * 60); frame++) {
    double tick = t0 + frame * period;
    for (double now = bench_wall_seconds(); now < tick; now = bench_wall_seconds()) {
      l->now = now;
      mr_glove_poll(g, now, (int)ceil((tick - now) * 1e3));
    }
    mr_pose goal;
    mr_scene_frame_pose_at(sc, 0, frame * period, &goal);
    mr_world_set_frame_target(sw->world, sw->frames[0], &goal, frame * period);
    mr_world_step_to(sw->world, frame * period, NULL);
    double done = bench_wall_seconds();
    for (; l->pending < l->n; l->pending++) l->shown[l->pending] = done;
  }
}

static void report(bench *b, const live *l, double offset) {
  double *lat = malloc((size_t)(l->pending > 0 ? l->pending : 1) * sizeof *lat);
  int n = 0;
  for (int i = 0; lat && i < l->pending; i++) lat[n++] = l->shown[i] - (l->device[i] + offset);
  if (n == 0) {
    bench_say(b, "live: no sample arrived\n");
    free(lat);
    return;
  }
  bench_sort(lat, (int)n);
  double read_p99 = 0;
  for (int i = 0; i < n; i++) read_p99 = fmax(read_p99, l->read[i] - (l->device[i] + offset));
  bench_say(b,
            "live, glove-gen through a pty at 250 Hz, %d samples: sample to frame p50 %.2f ms, "
            "p99 %.2f ms (the slowest read %.2f ms after its device time)\n",
            n, 1e3 * lat[n / 2], 1e3 * lat[(n * 99) / 100], 1e3 * read_p99);
  free(lat);
}

int bench_latency_live(bench *b) {
  const double seconds = b->quick ? 2.0 : 10.0;
  char path[512];
  bench_progress("latency", "live: glove-gen on a pty for %g s", seconds);
  pid_t pid = bench_glove_gen_start(b, "latency", seconds + 2, path, sizeof path);
  if (pid < 0) {
    bench_say(b, "live: glove-gen did not start\n");
    return -1;
  }
  mr_glove_def def = mr_default_glove_def();
  snprintf(def.source, sizeof def.source, "pty:%.240s", path);
  mr_glove *g = NULL;
  mr_scene sc;
  mr_scene_world sw = { 0 };
  mr_scene_error err;
  live *l = calloc(1, sizeof *l);
  char msg[256];
  int rc = -1;
  if (l && mr_glove_create(&def, &g, msg, sizeof msg) == MR_GLOVE_OK &&
      bench_load(b, "host/scenes/puppet.yaml", &sc) == 0) {
    if (mr_scene_build(&sc, &sw, &err) == MR_SCENE_OK) {
      mr_glove_set_observer(g, on_frame, l);
      run_loop(g, l, &sc, &sw, seconds);
      report(b, l, mr_glove_clock_offset(g));
      mr_scene_world_free(&sw);
      rc = 0;
    }
    mr_scene_free(&sc);
  }
  if (g) mr_glove_destroy(g);
  free(l);
  kill(pid, SIGTERM);
  waitpid(pid, NULL, 0);
  return rc;
}
