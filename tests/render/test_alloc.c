/* The stage and the renderer when memory runs out, on a scene of models
 * from files and the theater's whole set (host/scenes/dragon.yaml), drawn
 * by OSMesa. Every allocation of making the stage, and of starting the
 * renderer, fails in turn (tests/common/alloc.h): each start fails with a
 * message that says so and leaves nothing behind (the sanitizers' leak
 * check), or is one the code can do without, and then the frame is the
 * same picture, pixel for pixel. Once drawn, frames allocate nothing of
 * ours. (The model reader's and the GL driver's own allocations are in
 * their shared libraries, out of the counter's sight.) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "alloc.h"
#include "fixture.h"
#include "mr_render.h"
#include "mr_scene.h"
#include "mr_scene_world.h"
#include "mr_stage.h"

#define DRAGON MR_SOURCE_DIR "/host/scenes/dragon.yaml"

enum { W = 160, H = 90 };

typedef struct rig {
  mr_scene scene;
  double *rest;
  size_t n;
  mr_render_view view;
  uint64_t picture; /* of the frame at rest, made with nothing failing */
} rig;

static mr_render_def render_def(void) {
  mr_render_def d = mr_default_render_def();
  d.backend = MR_RENDER_OSMESA;
  d.headless = true;
  d.width = W;
  d.height = H;
  return d;
}

/* The frame at rest drawn by r from stage s: its hash. */
static uint64_t picture(mr_render *r, mr_stage *s, const rig *g) {
  const mr_draw_list *list = NULL;
  assert_int_equal(mr_stage_update(s, g->rest, g->n, &list), MR_STAGE_OK);
  assert_int_equal(mr_render_draw(r, list, &g->view), MR_RENDER_OK);
  static uint8_t rgb[3 * W * H];
  assert_int_equal(mr_render_read_rgb(r, rgb, sizeof rgb), MR_RENDER_OK);
  return fx_hash(rgb, sizeof rgb);
}

static mr_stage *stage_of(const rig *g) {
  mr_stage *s = NULL;
  char msg[400];
  if (mr_stage_create(&g->scene.stage, g->rest, g->n, &s, msg, sizeof msg) != MR_STAGE_OK)
    fail_msg("%s", msg);
  return s;
}

static mr_render *render_of(const rig *g) {
  mr_render_def d = render_def();
  mr_render *r = NULL;
  char msg[512];
  if (mr_render_create(&d, &g->scene.stage, DRAGON, &r, msg, sizeof msg) != MR_RENDER_OK)
    fail_msg("%s", msg);
  return r;
}

static void rig_make(rig *g) {
  memset(g, 0, sizeof *g);
  mr_scene_error err;
  if (mr_scene_load(DRAGON, &g->scene, &err) != MR_SCENE_OK) fail_msg("%s", err.text);
  g->rest = mr_scene_start_positions(&g->scene, &g->n, &err);
  if (g->rest == NULL) fail_msg("%s", err.text);
  g->view = mr_default_render_view(&g->scene.stage);
  mr_stage *s = stage_of(g);
  mr_render *r = render_of(g);
  g->picture = picture(r, s, g);
  mr_render_destroy(r);
  mr_stage_destroy(s);
}

static void rig_free(rig *g) {
  free(g->rest);
  mr_scene_free(&g->scene);
}

typedef struct tally {
  long made, refused, done_without;
} tally;

static void told(const char *what, long k, const char *msg, tally *t) {
  if (strstr(msg, "out of memory") == NULL)
    fail_msg("%s, allocation %ld failing: \"%s\", expected out of memory", what, k, msg);
  t->refused++;
}

static void every_allocation_of_making_the_stage_may_fail(void **state) {
  (void)state;
  rig g;
  rig_make(&g);
  mr_render *r = render_of(&g);
  tally t = { 0 };
  for (long k = 1;; k++) {
    mr_stage *s = NULL;
    char msg[400] = "";
    tt_alloc_count(k);
    mr_stage_status st = mr_stage_create(&g.scene.stage, g.rest, g.n, &s, msg, sizeof msg);
    const long n = tt_alloc_stop();
    if (st != MR_STAGE_OK) {
      assert_null(s);
      told("the stage", k, msg, &t);
      continue;
    }
    const uint64_t got = picture(r, s, &g);
    mr_stage_destroy(s);
    if (got != g.picture)
      fail_msg("the stage, allocation %ld failing: made, but drew %016llx, not %016llx", k,
               (unsigned long long)got, (unsigned long long)g.picture);
    if (n < k) {
      t.made = n;
      break;
    }
    t.done_without++;
  }
  print_message("the stage: %ld allocations; %ld refused it when they failed, %ld done without\n",
                t.made, t.refused, t.done_without);
  assert_true(t.refused > 10 && t.refused + t.done_without == t.made);
  mr_render_destroy(r);
  rig_free(&g);
}

static void every_allocation_of_starting_the_renderer_may_fail(void **state) {
  (void)state;
  rig g;
  rig_make(&g);
  mr_stage *s = stage_of(&g);
  tally t = { 0 };
  for (long k = 1;; k++) {
    mr_render_def d = render_def();
    mr_render *r = NULL;
    char msg[512] = "";
    tt_alloc_count(k);
    mr_render_status st = mr_render_create(&d, &g.scene.stage, DRAGON, &r, msg, sizeof msg);
    const long n = tt_alloc_stop();
    if (st != MR_RENDER_OK) {
      assert_null(r);
      told("the renderer", k, msg, &t);
      continue;
    }
    const uint64_t got = picture(r, s, &g);
    mr_render_destroy(r);
    if (got != g.picture)
      fail_msg("the renderer, allocation %ld failing: started, but drew %016llx, not %016llx", k,
               (unsigned long long)got, (unsigned long long)g.picture);
    if (n < k) {
      t.made = n;
      break;
    }
    t.done_without++;
  }
  print_message("the renderer: %ld allocations; %ld refused it when they failed, %ld done "
                "without\n",
                t.made, t.refused, t.done_without);
  assert_true(t.refused > 10 && t.refused + t.done_without == t.made);
  mr_stage_destroy(s);
  rig_free(&g);
}

/* After the first two frames (the still scenery is kept from the second
 * on, and with it the shadows' and the spot's outlines), ten more, the
 * dragon moving, allocate nothing of the stage's or the renderer's own. */
static void frames_after_the_first_allocate_nothing(void **state) {
  (void)state;
  rig g;
  rig_make(&g);
  mr_stage *s = stage_of(&g);
  mr_render *r = render_of(&g);
  (void)picture(r, s, &g);
  (void)picture(r, s, &g);
  double *xyz = malloc(3 * g.n * sizeof *xyz);
  assert_non_null(xyz);
  uint64_t first = 0, last = 0;
  tt_alloc_count(0);
  for (int f = 1; f <= 10; f++) {
    for (size_t i = 0; i < 3 * g.n; i++) xyz[i] = g.rest[i] + (i % 3 == 0 ? 0.02 * f : 0.0);
    const mr_draw_list *list = NULL;
    assert_int_equal(mr_stage_update(s, xyz, g.n, &list), MR_STAGE_OK);
    assert_int_equal(mr_render_draw(r, list, &g.view), MR_RENDER_OK);
    static uint8_t rgb[3 * W * H];
    assert_int_equal(mr_render_read_rgb(r, rgb, sizeof rgb), MR_RENDER_OK);
    last = fx_hash(rgb, sizeof rgb);
    if (f == 1) first = last;
  }
  const long n = tt_alloc_stop();
  print_message("ten frames: %ld allocations\n", n);
  assert_true(first != last); /* the dragon moved on the pictures */
  assert_int_equal(n, 0);
  free(xyz);
  mr_render_destroy(r);
  mr_stage_destroy(s);
  rig_free(&g);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(frames_after_the_first_allocate_nothing),
    cmocka_unit_test(every_allocation_of_making_the_stage_may_fail),
    cmocka_unit_test(every_allocation_of_starting_the_renderer_may_fail),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
