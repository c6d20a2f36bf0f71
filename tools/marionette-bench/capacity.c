/* Item 3, capacity: how many stick puppets, each on its own control frame,
 * one core keeps at 60 fps, physics only and with a headless render, and
 * how the cost grows with the count; then puppets lying on a floor with
 * friction, whose cost grows with their contacts. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "mr_render.h"
#include "mr_scene_world.h"

/* The rigid head and torso and the limbs' links of the puppet of Fig. 10
 * (hard cases 01 and 06b), for either pose below: a unit's `groups` and
 * `constraints`. */
#define PUPPET_JOINTS                                                                 \
  "    groups:\n"                                                                     \
  "      - {name: head, particles: [neck, head_top, nose, ear_l]}\n"                  \
  "      - {name: torso, particles: [shoulder_l, shoulder_r, chest, hip_l, hip_r]}\n" \
  "    constraints:\n"                                                                \
  "      - {between: [neck, shoulder_l]}\n      - {between: [neck, shoulder_r]}\n"    \
  "      - {between: [shoulder_l, elbow_l]}\n      - {between: [elbow_l, hand_l]}\n"  \
  "      - {between: [shoulder_r, elbow_r]}\n      - {between: [elbow_r, hand_r]}\n"  \
  "      - {between: [hip_l, knee_l]}\n      - {between: [knee_l, foot_l]}\n"         \
  "      - {between: [hip_r, knee_r]}\n      - {between: [knee_r, foot_r]}\n"

/* One stick puppet of Fig. 10 (hard case 01) as a unit of a `puppets:`
 * list, at (x, 0, z), with its own control frame swaying at 0.5 Hz. */
static const char stick_puppet[] =
    "  - name: p%d\n    offset: [%.2f, 0, %.2f]\n    particles:\n"
    "      - {name: neck, position: [0.00, 0.62, 0.00], mass: 0.08}\n"
    "      - {name: head_top, position: [0.00, 0.80, 0.00], mass: 0.10}\n"
    "      - {name: nose, position: [0.00, 0.71, 0.07], mass: 0.06}\n"
    "      - {name: ear_l, position: [-0.06, 0.71, 0.00], mass: 0.06}\n"
    "      - {name: shoulder_l, position: [-0.12, 0.56, 0.00], mass: 0.15}\n"
    "      - {name: shoulder_r, position: [0.12, 0.56, 0.00], mass: 0.15}\n"
    "      - {name: chest, position: [0.00, 0.46, 0.06], mass: 0.15}\n"
    "      - {name: hip_l, position: [-0.08, 0.32, 0.00], mass: 0.12}\n"
    "      - {name: hip_r, position: [0.08, 0.32, 0.00], mass: 0.12}\n"
    "      - {name: elbow_l, position: [-0.15, 0.42, 0.00], mass: 0.06}\n"
    "      - {name: hand_l, position: [-0.16, 0.28, 0.02], mass: 0.08}\n"
    "      - {name: elbow_r, position: [0.15, 0.42, 0.00], mass: 0.06}\n"
    "      - {name: hand_r, position: [0.16, 0.28, 0.02], mass: 0.08}\n"
    "      - {name: knee_l, position: [-0.08, 0.18, 0.01], mass: 0.08}\n"
    "      - {name: foot_l, position: [-0.08, 0.04, 0.00], mass: 0.08}\n"
    "      - {name: knee_r, position: [0.08, 0.18, 0.01], mass: 0.08}\n"
    "      - {name: foot_r, position: [0.08, 0.04, 0.00], mass: 0.08}\n" PUPPET_JOINTS
    "    control:\n      pose: {position: [0, 1.25, 0]}\n      points:\n"
    "        - {name: bar_head, offset: [0.00, 0, 0.00]}\n"
    "        - {name: bar_shoulder_l, offset: [-0.12, 0, 0.00]}\n"
    "        - {name: bar_shoulder_r, offset: [0.12, 0, 0.00]}\n"
    "        - {name: bar_hand_l, offset: [-0.25, 0, 0.06]}\n"
    "        - {name: bar_hand_r, offset: [0.25, 0, 0.06]}\n"
    "        - {name: bar_knee_l, offset: [-0.08, 0, 0.15]}\n"
    "        - {name: bar_knee_r, offset: [0.08, 0, 0.15]}\n"
    "      track: {oscillate: {amplitude: [0.05, 0.03, 0], rotation: [0, 0, 10], "
    "frequency: 0.5, ramp: 1}}\n"
    "    strings:\n"
    "      - {from: bar_head, to: head_top, stiffness: 60, damping: 1.0}\n"
    "      - {from: bar_shoulder_l, to: shoulder_l, stiffness: 60, damping: 1.0}\n"
    "      - {from: bar_shoulder_r, to: shoulder_r, stiffness: 60, damping: 1.0}\n"
    "      - {from: bar_hand_l, to: hand_l, stiffness: 30, damping: 0.5}\n"
    "      - {from: bar_hand_r, to: hand_r, stiffness: 30, damping: 0.5}\n"
    "      - {from: bar_knee_l, to: knee_l, stiffness: 30, damping: 0.5}\n"
    "      - {from: bar_knee_r, to: knee_r, stiffness: 30, damping: 0.5}\n"
    "    antigravity:\n"
    "      - {acted: shoulder_l, trigger: bar_shoulder_l, fraction: 0.35}\n"
    "      - {acted: shoulder_r, trigger: bar_shoulder_r, fraction: 0.35}\n"
    "      - {acted: head_top, trigger: bar_head, fraction: 0.15}\n";

/* What the stage draws of each puppet for the render rows: rods between
 * the joints its constraints join, and across shoulders and hips (link
 * mode), and a ball for the head (particle mode), as stick.yaml draws its
 * figure (§3.3); strings and frames are drawn by the stage's rigging. */
static const char *const rods[][2] = {
  { "neck", "shoulder_l" }, { "neck", "shoulder_r" },       { "shoulder_l", "elbow_l" },
  { "elbow_l", "hand_l" },  { "shoulder_r", "elbow_r" },    { "elbow_r", "hand_r" },
  { "hip_l", "knee_l" },    { "knee_l", "foot_l" },         { "hip_r", "knee_r" },
  { "knee_r", "foot_r" },   { "shoulder_l", "shoulder_r" }, { "hip_l", "hip_r" },
  { "neck", "chest" },
};
enum { N_RODS = sizeof rods / sizeof rods[0], MODEL_LINE = 160 };

static size_t crowd_models(char *t, size_t cap, int n, int side) {
  size_t used = (size_t)snprintf(t, cap, "models:\n");
  for (int i = 0; i < n; i++) {
    used += (size_t)snprintf(t + used, cap - used,
                             "  - {name: h%d, shape: sphere, scale: 0.12, display: particle, "
                             "particle: p%d.head_top}\n",
                             i, i);
    for (int k = 0; k < N_RODS; k++)
      used += (size_t)snprintf(t + used, cap - used,
                               "  - {name: r%d_%d, shape: cylinder, scale: [0.025, 1, 0.025], "
                               "display: link, between: [p%d.%s, p%d.%s]}\n",
                               i, k, i, rods[k][0], i, rods[k][1]);
  }
  /* A floor under the whole grid; the camera is the default one, which
   * looks at the middle of the scene's points from far enough to see all. */
  used += (size_t)snprintf(t + used, cap - used, "stage:\n  floor: {size: %d}\n", 2 * side + 2);
  return used;
}

/* A scene of n stick puppets on a grid 1 m apart, with their models when
 * `models` is set. */
static char *stick_crowd(int n, int models, size_t *len) {
  size_t cap = (size_t)n * (sizeof stick_puppet + 64) + 512, used = 0;
  if (models) cap += (size_t)n * (N_RODS + 1) * MODEL_LINE + 512;
  char *t = malloc(cap);
  if (t == NULL) return NULL;
  used += (size_t)snprintf(t, cap,
                           "format: 1\nname: crowd\nphysics:\n"
                           "  effects: [gravity, drag, constraints, strings, antigravity, "
                           "control]\n  drag: 0.2\n  puppets:\n");
  int side = (int)ceil(sqrt((double)n));
  for (int i = 0; i < n; i++)
    used += (size_t)snprintf(t + used, cap - used, stick_puppet, i, (double)(i % side),
                             (double)(i / side));
  if (models) used += crowd_models(t + used, cap - used, n, side);
  *len = used;
  return t;
}

static int crowd_load(int n, int models, mr_scene *sc) {
  size_t len;
  char *text = stick_crowd(n, models, &len);
  mr_scene_error err;
  int ok = text != NULL && mr_scene_load_text("crowd", text, len, sc, &err) == MR_SCENE_OK;
  if (!ok) fprintf(stderr, "marionette-bench: crowd of %d: %s\n", n, text ? err.text : "no memory");
  free(text);
  return ok ? 0 : -1;
}

int bench_crowd_load(int n, mr_scene *sc) {
  return crowd_load(n, 0, sc);
}

/* Hard case 06b's puppet as a unit of a `puppets:` list, lying face up
 * 5 cm above a floor with friction, at (x, 0, z), with no strings. */
static const char lying_puppet[] =
    "  - name: p%d\n    offset: [%.2f, 0, %.2f]\n    particles:\n"
    "      - {name: neck, position: [0.00, 0.08, 0.62], mass: 0.08, radius: 0.03}\n"
    "      - {name: head_top, position: [0.00, 0.08, 0.80], mass: 0.10, radius: 0.03}\n"
    "      - {name: nose, position: [0.00, 0.15, 0.71], mass: 0.06, radius: 0.03}\n"
    "      - {name: ear_l, position: [-0.06, 0.08, 0.71], mass: 0.06, radius: 0.03}\n"
    "      - {name: shoulder_l, position: [-0.12, 0.08, 0.56], mass: 0.15, radius: 0.03}\n"
    "      - {name: shoulder_r, position: [0.12, 0.08, 0.56], mass: 0.15, radius: 0.03}\n"
    "      - {name: chest, position: [0.00, 0.14, 0.46], mass: 0.15, radius: 0.03}\n"
    "      - {name: hip_l, position: [-0.08, 0.08, 0.32], mass: 0.12, radius: 0.03}\n"
    "      - {name: hip_r, position: [0.08, 0.08, 0.32], mass: 0.12, radius: 0.03}\n"
    "      - {name: elbow_l, position: [-0.15, 0.08, 0.42], mass: 0.06, radius: 0.03}\n"
    "      - {name: hand_l, position: [-0.16, 0.10, 0.28], mass: 0.08, radius: 0.03}\n"
    "      - {name: elbow_r, position: [0.15, 0.08, 0.42], mass: 0.06, radius: 0.03}\n"
    "      - {name: hand_r, position: [0.16, 0.10, 0.28], mass: 0.08, radius: 0.03}\n"
    "      - {name: knee_l, position: [-0.08, 0.09, 0.18], mass: 0.08, radius: 0.03}\n"
    "      - {name: foot_l, position: [-0.08, 0.08, 0.04], mass: 0.08, radius: 0.03}\n"
    "      - {name: knee_r, position: [0.08, 0.09, 0.18], mass: 0.08, radius: 0.03}\n"
    "      - {name: foot_r, position: [0.08, 0.08, 0.04], mass: 0.08, radius: "
    "0.03}\n" PUPPET_JOINTS;

/* n of those puppets dropped side by side onto a floor with friction 0.8,
 * 0.6 m apart across and 1 m deep (hard case 28 is sixteen of them). */
static int floor_crowd_load(int n, mr_scene *sc) {
  size_t cap = (size_t)n * (sizeof lying_puppet + 64) + 512, used = 0;
  char *t = malloc(cap);
  if (t != NULL) {
    used += (size_t)snprintf(t, cap,
                             "format: 1\nname: floor crowd\nphysics:\n"
                             "  effects: [gravity, drag, constraints, floor]\n  drag: 0.05\n"
                             "  floor: {height: 0, restitution: 0.0, friction: 0.8}\n"
                             "  puppets:\n");
    for (int i = 0; i < n; i++)
      used += (size_t)snprintf(t + used, cap - used, lying_puppet, i, 0.6 * (i % 8), 1.0 * (i / 8));
  }
  mr_scene_error err;
  int ok = t != NULL && mr_scene_load_text("floor crowd", t, used, sc, &err) == MR_SCENE_OK;
  if (!ok)
    fprintf(stderr, "marionette-bench: floor crowd of %d: %s\n", n, t ? err.text : "no memory");
  free(t);
  return ok ? 0 : -1;
}

/* A crowd's run, frame by frame on the CPU clock (the process's, so the
 * threads llvmpipe draws on are counted too): the world is built before
 * the first frame, so the build (a load cost) and the stepping (the cost
 * of real time) are told apart. With a renderer, each frame is also drawn
 * headless and read back, and what that costs is summed apart. */
typedef struct crowd_clock {
  double t0, first, mark; /* CPU s: start, first frame, end of the last frame's work */
  double physics, render; /* CPU s after the first frame */
  double render_wall;     /* wall s of the drawing after the first frame */
  int frames;
  bench_drawing draw; /* draw.render NULL: physics only */
  int failed;
} crowd_clock;

static void on_crowd_frame(void *user, double t, const double *xyz, int n) {
  (void)t;
  crowd_clock *c = user;
  double now = bench_cpu_seconds();
  if (c->frames == 0)
    c->first = now;
  else
    c->physics += now - c->mark;
  c->mark = now;
  c->frames++;
  if (c->draw.render == NULL || c->failed) return;
  double w0 = bench_wall_seconds();
  c->failed = bench_drawing_draw(&c->draw, xyz, n) != 0;
  c->mark = bench_cpu_seconds();
  if (c->frames > 1) c->render += c->mark - now, c->render_wall += bench_wall_seconds() - w0;
}

/* Runs sc for `seconds` at 60 frames a second presented by interpolation
 * (as bench_run_scene does), timing it frame by frame into c. */
static int crowd_run(const mr_scene *sc, double seconds, crowd_clock *c, mr_sim_result *r) {
  mr_sim_def o = mr_default_sim_def();
  o.duration = seconds;
  o.fps = 60;
  o.present = MR_PRESENT_INTERPOLATE;
  o.on_frame = on_crowd_frame;
  o.user = c;
  mr_scene_error err;
  c->t0 = bench_cpu_seconds();
  if (mr_sim_run(sc, &o, r, &err) != MR_SCENE_OK) {
    fprintf(stderr, "marionette-bench: crowd: %s\n", err.text);
    return -1;
  }
  if (r->resets > 0 || !r->finite)
    fprintf(stderr, "marionette-bench: crowd reset %llu times\n", (unsigned long long)r->resets);
  return c->frames >= 2 && !c->failed ? 0 : -1;
}

/* Physics only: the world's build (to the first frame, a load cost), then
 * the CPU per simulated second of the frames after it, and the ATS's steps
 * and rejections per simulated second (one world, one Δt for the whole
 * crowd, §4.2), so that a cost that grows faster than the count can be
 * told apart from a crowd that steps more often. */
static int physics_table(bench *b, FILE *csv, double *ms_per_frame) {
  static const int counts[] = { 1, 10, 100, 1000 };
  bench_say(b, "%8s %9s %11s %15s %7s %8s %10s %14s %10s\n", "puppets", "build s", "CPU s/sim s",
            "ms per puppet-s", "growth", "steps/s", "rejected/s", "us/puppet-step", "real-time");
  double last = 0;
  int n_counts = b->quick ? 3 : 4; /* 1 000 puppets take a minute under the sanitizers */
  for (int i = 0; i < n_counts; i++) {
    int n = counts[i];
    double seconds = b->quick ? (n >= 100 ? 0.2 : 1.0) : (n >= 1000 ? 3.0 : 10.0);
    bench_progress("capacity", "%d puppets for %g s, physics only", n, seconds);
    mr_scene sc;
    crowd_clock c = { 0 };
    mr_sim_result r;
    if (crowd_load(n, 0, &sc) != 0) return -1;
    int rc = crowd_run(&sc, seconds, &c, &r);
    mr_scene_free(&sc);
    if (rc != 0) return -1;
    double sim = (c.frames - 1) / 60.0, cost = c.physics / sim, per = 1000.0 * cost / n;
    double steps = (double)r.steps / r.sim_time, rejected = (double)r.rejected / r.sim_time;
    double per_step = 1e6 * cost / (steps * n), build = c.first - c.t0;
    ms_per_frame[i] = 1000.0 * cost / 60.0;
    char growth[32] = "-";
    if (last > 0) snprintf(growth, sizeof growth, "%.2fx", cost / last);
    bench_say(b, "%8d %9.3f %11.4f %15.4f %7s %8.1f %10.1f %14.3f %10.0f\n", n, build, cost, per,
              growth, steps, rejected, per_step, n / cost);
    fprintf(csv, "%d,%g,%.6g,%.6g,%.0f,%.6g,%.6g,%.6g,%.6g\n", n, sim, cost, per, n / cost, steps,
            rejected, per_step, build);
    last = cost;
  }
  bench_say(
      b, "build s: scene to world, before the first frame (not in the rest); CPU s/sim s "
         "and after: the frames after the first; real-time puppets: n / (CPU s per sim s); linear "
         "cost shows as growth 10x per row; steps/s, rejected/s: the one adaptive step the "
         "whole crowd shares\n");
  return 0;
}

/* Puppets lying on a floor with friction, physics only: each rests on
 * about seventeen contacts, and friction is found through the solve
 * (host/physics/README.md), so a crowd's cost shows whether it is worked
 * puppet by puppet (growth 4x per row) or all at once (it was the cube). */
static int floor_table(bench *b, FILE *csv) {
  static const int counts[] = { 1, 4, 16, 64 };
  bench_say(b, "\nlying on a floor with friction 0.8 (hard case 06b's puppet, dropped 5 cm), "
               "physics only, one core:\n");
  bench_say(b, "%8s %11s %15s %7s %8s %10s\n", "puppets", "CPU s/sim s", "ms per puppet-s",
            "growth", "steps/s", "real-time");
  double last = 0;
  for (int i = 0; i < (b->quick ? 3 : 4); i++) {
    const int n = counts[i];
    const double seconds = b->quick ? 1.0 : 3.0;
    bench_progress("capacity", "%d puppets lying on a floor for %g s", n, seconds);
    mr_scene sc;
    crowd_clock c = { 0 };
    mr_sim_result r;
    if (floor_crowd_load(n, &sc) != 0) return -1;
    int rc = crowd_run(&sc, seconds, &c, &r);
    mr_scene_free(&sc);
    if (rc != 0) return -1;
    const double sim = (c.frames - 1) / 60.0, cost = c.physics / sim;
    char growth[32] = "-";
    if (last > 0) snprintf(growth, sizeof growth, "%.2fx", cost / last);
    bench_say(b, "%8d %11.4f %15.4f %7s %8.1f %10.0f\n", n, cost, 1000.0 * cost / n, growth,
              (double)r.steps / r.sim_time, n / cost);
    fprintf(csv, "%d,%g,%.6g,%.6g,%.0f,%.6g\n", n, sim, cost, 1000.0 * cost / n, n / cost,
            (double)r.steps / r.sim_time);
    last = cost;
  }
  bench_say(b, "linear cost shows as growth 4x per row\n");
  return 0;
}

/* One row of the render table: n puppets drawn at w x h for `frames`
 * frames after the first (whose drawing compiles shaders and is not
 * counted). Fills ms[0] physics, ms[1] render (CPU), ms[2] render (wall)
 * per frame. */
static int render_row(int n, int w, int h, int frames, double ms[3], char *msg, size_t size) {
  mr_scene sc;
  if (crowd_load(n, 1, &sc) != 0) {
    snprintf(msg, size, "the crowd did not load");
    return -1;
  }
  crowd_clock c = { 0 };
  mr_sim_result r;
  int rc = bench_drawing_open(&sc, w, h, &c.draw, msg, size);
  if (rc == 0) rc = crowd_run(&sc, (frames + 0.5) / 60.0, &c, &r);
  if (rc == 0) {
    int k = c.frames - 1;
    ms[0] = 1e3 * c.physics / k, ms[1] = 1e3 * c.render / k, ms[2] = 1e3 * c.render_wall / k;
  } else if (msg[0] == '\0') {
    snprintf(msg, size, "the renderer failed");
  }
  if (rc == 0)
    snprintf(msg, size, "%s", mr_render_backend_name(mr_render_backend_of(c.draw.render)));
  bench_drawing_close(&c.draw);
  mr_scene_free(&sc);
  return rc;
}

/* Puppets whose physics and drawing fit a 60 fps frame on one core, from
 * a frame's cost a + b n fitted through the first and last rows: 0 when
 * the fixed cost a alone is over the period. */
static double fit_count(const int *n, const double *cost, int rows, double *a, double *b) {
  *b = rows > 1 ? (cost[rows - 1] - cost[0]) / (n[rows - 1] - n[0]) : cost[0] / n[0];
  *a = cost[0] - *b * n[0];
  if (*a < 0) *a = 0;
  double room = 1e3 / 60.0 - *a;
  return room > 0 && *b > 0 ? floor(room / *b) : 0;
}

/* With headless rendering: each frame's physics (the physics-only rows'
 * mean, over a longer run than the few frames drawn here) plus drawing
 * the crowd and reading it back, at 1280x720 (item 5's size) and 320x180,
 * on the process's CPU clock (llvmpipe's threads included: one core's
 * budget is 16.7 ms of CPU a frame). */
static void render_table(bench *b, FILE *csv, const double *physics_ms) {
  static const int counts[] = { 1, 10, 100, 1000 },
                   sizes[][3] = { { 1280, 720, 3 }, { 320, 180, 6 } };
  bench_say(b, "\nwith a headless render a frame (stick.yaml's rods and balls, strings, frames, "
               "4x multisampling, shadows), one core:\n");
  if (b->quick) { /* software GL takes a second a frame at 1 000 puppets */
    bench_say(b, "not measured with --quick\n");
    return;
  }
  bench_say(b, "%8s %9s %-7s %13s %14s %12s %13s %9s\n", "puppets", "size", "backend", "physics ms",
            "render CPU ms", "render wall", "frame CPU ms", "fps");
  for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
    int w = sizes[s][0], h = sizes[s][1], rows = 0, done[4];
    double frame_ms[4], a, per;
    for (int i = 0; i < 4; i++) {
      double ms[3] = { 0 };
      char msg[1100] = "";
      bench_progress("capacity", "%d puppets drawn at %dx%d, %d frames", counts[i], w, h,
                     sizes[s][2]);
      if (render_row(counts[i], w, h, sizes[s][2], ms, msg, sizeof msg) != 0) {
        bench_say(b, "%8d %4dx%-4d not drawn: %s\n", counts[i], w, h, msg);
        break;
      }
      double total = physics_ms[i] + ms[1];
      bench_say(b, "%8d %4dx%-4d %-7s %13.3f %14.1f %12.1f %13.1f %9.1f\n", counts[i], w, h, msg,
                physics_ms[i], ms[1], ms[2], total, 1e3 / total);
      fprintf(csv, "%d,%d,%d,%s,%d,%.6g,%.6g,%.6g,%.6g,%.6g\n", w, h, counts[i], msg, sizes[s][2],
              physics_ms[i], ms[1], ms[2], total, ms[0]);
      done[rows] = counts[i], frame_ms[rows++] = total;
    }
    if (rows == 0) continue;
    double fit = fit_count(done, frame_ms, rows, &a, &per);
    bench_say(b,
              "%dx%d: a frame costs %.1f ms + %.3f ms per puppet of CPU; puppets in a 16.7 ms "
              "frame: %.0f\n",
              w, h, a, per, fit);
  }
}

int bench_capacity(bench *b) {
  FILE *csv = bench_open(b, "capacity.csv"), *rcsv = bench_open(b, "capacity_render.csv");
  int rc = csv && rcsv ? 0 : -1;
  double physics_ms[4] = { 0 };
  if (rc == 0) {
    fprintf(csv,
            "# %s\npuppets,sim_s,cpu_s_per_sim_s,cpu_ms_per_puppet_s,realtime_puppets,"
            "steps_per_sim_s,rejected_per_sim_s,cpu_us_per_puppet_step,build_s\n",
            b->machine);
    fprintf(rcsv,
            "# %s\nwidth,height,puppets,backend,frames,physics_ms_per_frame,"
            "render_cpu_ms_per_frame,render_wall_ms_per_frame,frame_cpu_ms,"
            "drawn_physics_ms_per_frame\n",
            b->machine);
    bench_say(b, "\n== capacity (item 3): stick puppets of Fig. 10, each on its own frame, "
                 "one core ==\n");
    rc = physics_table(b, csv, physics_ms);
  }
  if (rc == 0) render_table(b, rcsv, physics_ms);
  FILE *fcsv = rc == 0 ? bench_open(b, "capacity_floor.csv") : NULL;
  if (fcsv) {
    fprintf(fcsv,
            "# %s\npuppets,sim_s,cpu_s_per_sim_s,cpu_ms_per_puppet_s,realtime_puppets,"
            "steps_per_sim_s\n",
            b->machine);
    rc = floor_table(b, fcsv);
    fclose(fcsv);
  } else if (rc == 0) {
    rc = -1;
  }
  if (csv) fclose(csv);
  if (rcsv) fclose(rcsv);
  return rc;
}
