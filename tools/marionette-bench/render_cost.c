/* Item 5: what a frame costs to draw. Each example scene runs its track
 * and its first frames are drawn headless at 1280x720, then at 640x360,
 * with the renderer's defaults (EGL, else OSMesa;
 * on a machine without a GPU both are Mesa's llvmpipe), each drawn and read
 * back, on the wall clock (llvmpipe draws on threads of its own). A frame
 * dearer than the 60 fps period cannot be shown on time: the theater's
 * scheduler then skips renders to keep the physics on time, and the share
 * it must skip is 1 − period/cost. At 1280x720 each scene is drawn again
 * without the theater's set, and the set's share of the cost is printed. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <string.h>

#include <valgrind/callgrind.h>

#include "bench.h"
#include "mr_render.h"
#include "mr_scene_world.h"

/* The stage and the renderer for a scene, from its world's start. */
int bench_drawing_open(const mr_scene *sc, int w, int h, bench_drawing *d, char *msg, size_t size) {
  memset(d, 0, sizeof *d);
  mr_scene_error err;
  double *xyz = mr_scene_start_positions(sc, &d->n, &err);
  if (xyz == NULL) {
    snprintf(msg, size, "%.500s", err.text);
    return -1;
  }
  int rc = mr_stage_create(&sc->stage, xyz, d->n, &d->stage, msg, size) == MR_STAGE_OK ? 0 : -1;
  free(xyz);
  if (rc != 0) return -1;
  mr_render_def def = mr_default_render_def();
  def.headless = true;
  def.width = w;
  def.height = h;
  if (mr_render_create(&def, &sc->stage, sc->path, &d->render, msg, size) != MR_RENDER_OK)
    return -1;
  d->view = mr_default_render_view(&sc->stage);
  d->rgb_size = (size_t)w * (size_t)h * 3;
  d->rgb = malloc(d->rgb_size);
  return d->rgb ? 0 : -1;
}

int bench_drawing_draw(bench_drawing *d, const double *xyz, int n) {
  const mr_draw_list *list;
  if (d->render == NULL || (size_t)n != d->n) return -1;
  return mr_stage_update(d->stage, xyz, d->n, &list) == MR_STAGE_OK &&
                 mr_render_draw(d->render, list, &d->view) == MR_RENDER_OK &&
                 mr_render_read_rgb(d->render, d->rgb, d->rgb_size) == MR_RENDER_OK
             ? 0
             : -1;
}

void bench_drawing_close(bench_drawing *d) {
  if (d->render) mr_render_destroy(d->render);
  if (d->stage) mr_stage_destroy(d->stage);
  free(d->rgb);
  memset(d, 0, sizeof *d);
}

typedef struct drawing {
  bench_drawing draw;
  int frames, max_frames, failed;
  double cost[64];
} drawing;

static void draw_frame(void *user, double t, const double *xyz, int n) {
  (void)t;
  drawing *d = user;
  if (d->frames >= d->max_frames || d->failed) return;
  double t0 = bench_wall_seconds();
  d->failed = bench_drawing_draw(&d->draw, xyz, n) != 0;
  d->cost[d->frames++] = bench_wall_seconds() - t0;
}

/* A scene's frames drawn at w x h, with the theater's set or without it
 * (its proscenium, wings, footlights and bridge off; the boards stay):
 * the p50 and the dearest frame's seconds into cost[0] and cost[1], and
 * the backend's name; -1 with msg when it was not drawn. */
static int scene_cost(bench *b, const char *rel, int frames, int w, int h, bool set, double cost[2],
                      const char **backend, char *msg, size_t size) {
  mr_scene sc;
  if (bench_load(b, rel, &sc) != 0) {
    snprintf(msg, size, "not loaded");
    return -1;
  }
  if (!set) sc.stage.proscenium = sc.stage.wings = sc.stage.footlights = sc.stage.bridge = false;
  drawing d = { .max_frames = frames };
  bench_progress("render", "%s: %d frames at %dx%d%s", rel, frames, w, h, set ? "" : ", no set");
  if (bench_drawing_open(&sc, w, h, &d.draw, msg, size) == 0) {
    mr_sim_def o = mr_default_sim_def();
    o.fps = 30;
    o.duration = (frames + 0.5) / 30.0;
    o.on_frame = draw_frame;
    o.user = &d;
    mr_sim_result r;
    mr_scene_error err;
    if (mr_sim_run(&sc, &o, &r, &err) != MR_SCENE_OK) snprintf(msg, size, "%s", err.text);
  }
  int rc = -1;
  if (d.frames > 0 && !d.failed) {
    bench_sort(d.cost, (int)d.frames);
    cost[0] = d.cost[d.frames / 2], cost[1] = d.cost[d.frames - 1];
    *backend = mr_render_backend_name(mr_render_backend_of(d.draw.render));
    rc = 0;
  } else if (!msg[0]) {
    snprintf(msg, size, "the renderer failed");
  }
  bench_drawing_close(&d.draw);
  mr_scene_free(&sc);
  return rc;
}

/* One row: the scene with its set, and (share) the set's part of the
 * p50, from the same frames drawn without it. */
static void one_scene(bench *b, const char *rel, int frames, int w, int h, bool share) {
  char msg[1100] = "";
  double with[2], without[2];
  const char *backend = "";
  if (scene_cost(b, rel, frames, w, h, true, with, &backend, msg, sizeof msg) != 0) {
    bench_say(b, "%-16s %4dx%-4d not drawn: %s\n", rel + 12, w, h, msg);
    return;
  }
  const double period = 1.0 / 60.0, p50 = with[0];
  char set[32] = "";
  if (share && scene_cost(b, rel, frames, w, h, false, without, &backend, msg, sizeof msg) == 0)
    snprintf(set, sizeof set, "%9.1f %6.0f %%", 1e3 * without[0], 100.0 * (1.0 - without[0] / p50));
  bench_say(b, "%-16s %4dx%-4d %-7s %9.1f %9.1f %9.0f %% %s\n", rel + 12, w, h, backend, 1e3 * p50,
            1e3 * with[1], p50 > period ? 100.0 * (1.0 - period / p50) : 0.0, set);
}

/* One humanoid frame at w x h for callgrind (`--count render`; a third
 * dump at 1280x720 without the theater's set): two frames first (the shaders are compiled at their first draw), then one
 * counted, with a particle nudged each frame so the shadow map is drawn
 * again, as in a show; one dump named for the size. */
static int count_frame(const mr_scene *sc, int w, int h) {
  bench_drawing d;
  char msg[1100] = "";
  if (bench_drawing_open(sc, w, h, &d, msg, sizeof msg) != 0) {
    fprintf(stderr, "marionette-bench: %s\n", msg[0] ? msg : "the renderer failed");
    bench_drawing_close(&d);
    return -1;
  }
  mr_scene_error err;
  size_t n = 0;
  double *xyz = mr_scene_start_positions(sc, &n, &err);
  int rc = xyz ? 0 : -1;
  for (int f = 0; rc == 0 && f < 3; f++) {
    xyz[0] += f % 2 ? 1e-3 : -1e-3;
    if (f == 2) CALLGRIND_START_INSTRUMENTATION;
    rc = bench_drawing_draw(&d, xyz, (int)n);
    if (f == 2) CALLGRIND_STOP_INSTRUMENTATION;
  }
  char name[64];
  snprintf(name, sizeof name, "render %dx%d%s", w, h,
           sc->stage.proscenium ? "" : " without the theater's set");
  CALLGRIND_DUMP_STATS_AT(name);
  free(xyz);
  bench_drawing_close(&d);
  return rc;
}

int bench_count_render(bench *b) {
  /* llvmpipe's own threads would run outside the count's order. */
  setenv("LP_NUM_THREADS", "0", 1);
  mr_scene sc;
  if (bench_load(b, "host/scenes/humanoid.yaml", &sc) != 0) return -1;
  int rc = count_frame(&sc, 640, 360) == 0 && count_frame(&sc, 1280, 720) == 0 ? 0 : -1;
  /* The set's part of a frame: the same frame without it. */
  sc.stage.proscenium = sc.stage.wings = sc.stage.footlights = sc.stage.bridge = false;
  if (rc == 0) rc = count_frame(&sc, 1280, 720);
  mr_scene_free(&sc);
  return rc;
}

int bench_render(bench *b) {
  static const char *const scenes[] = {
    "host/scenes/stick.yaml",  "host/scenes/humanoid.yaml", "host/scenes/dragon.yaml",
    "host/scenes/bird.yaml",   "host/scenes/clash.yaml",    "host/scenes/ghost.yaml",
    "host/scenes/puppet.yaml", "host/scenes/duet.yaml",
  };
  bench_say(b, "\n== render cost (item 5): 1280x720 and 640x360, the renderer's defaults, "
               "headless ==\n");
  if (b->quick) { /* software GL takes seconds a frame: not a minute's run */
    bench_say(b, "not measured with --quick\n");
    return 0;
  }
  size_t count = sizeof scenes / sizeof scenes[0];
  bench_say(b, "%-16s %-9s %-7s %9s %9s %10s %9s %8s\n", "scene", "size", "backend", "p50 ms",
            "max ms", "skipped at 60 fps", "no set ms", "set");
  for (size_t i = 0; i < count; i++) one_scene(b, scenes[i], 8, 1280, 720, true);
  for (size_t i = 0; i < count; i++) one_scene(b, scenes[i], 8, 640, 360, false);
  bench_say(b, "skipped: the share of renders a 60 fps show must skip to keep the physics on "
               "time, 1 - period / p50\n");
  bench_say(b, "set: the theater's set's share of the p50 (proscenium, wings, footlights; the "
               "boards stay), 1 - no set / p50, the same frames drawn without it\n");
  return 0;
}
