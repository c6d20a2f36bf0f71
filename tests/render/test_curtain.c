/* The moving part of the set on real pixels: the front curtain closed
 * over the stage at the show's start and open on the puppet in the
 * middle of it; the follow spot's pool where the puppet is; and a frame
 * drawn over the kept scenery (the curtain kept in it, the follow spot
 * lit again only where its cone falls) the same as one drawn whole.
 * Through OSMesa and EGL. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fixture.h"

static const mr_render_backend backends[] = { MR_RENDER_OSMESA, MR_RENDER_EGL };

/* The curtain's red velvet, lit or in a fold's shade. */
static int is_velvet(const uint8_t *p) {
  return p[0] > 40 && p[0] > 2 * p[1] && 2 * p[0] > 3 * p[2];
}

static int is_blue(const uint8_t *p) {
  return p[2] > 60 && p[0] * 2 < p[2] && p[1] * 2 < p[2];
}

/* The fixture's stage with the curtain and the follow spot, and its item
 * a blue sphere on point 0 of a stage (mr_stage), so that the draw list
 * is the stage's own: its curtain and its follow spot. */
typedef struct staged {
  fx_scene s;
  mr_stage *stage;
  const mr_draw_list *list;
} staged;

static void staged_init(staged *g, double x) {
  fx_scene_init(&g->s);
  g->s.stage.curtain.show = true;
  g->s.stage.follow_spot.show = true;
  g->s.stage.lights.shadows = false; /* no shadow moves with the sphere */
  mr_model_def *m = &g->s.models[0];
  const float blue[3] = { 0.05f, 0.1f, 0.9f };
  memcpy(m->materials[0].base_color, blue, sizeof blue);
  m->scale[0] = m->scale[1] = m->scale[2] = 0.4;
  m->particles[0] = 0;
  const double rest[3] = { x, 0.6, 0 };
  char msg[256];
  if (mr_stage_create(&g->s.stage, rest, 1, &g->stage, msg, sizeof msg) != MR_STAGE_OK)
    fail_msg("%s", msg);
  assert_int_equal(mr_stage_update(g->stage, rest, 1, &g->list), MR_STAGE_OK);
}

/* The sphere moved to x, at show time t of a show of `end` seconds; the
 * frame drawn (free it). */
static uint8_t *draw_at(mr_render *r, staged *g, double x, double t, double end) {
  const double xyz[3] = { x, 0.6, 0 };
  assert_int_equal(mr_stage_set_time(g->stage, t, end), MR_STAGE_OK);
  assert_int_equal(mr_stage_update(g->stage, xyz, 1, &g->list), MR_STAGE_OK);
  g->s.list = *g->list;
  return fx_draw(r, &g->s);
}

static void curtain_closed_then_open(mr_render_backend b) {
  staged g;
  staged_init(&g, 0);
  mr_render *r = fx_render(b, &g.s);
  uint8_t *start = draw_at(r, &g, 0, 0, 10);
  uint8_t *mid = draw_at(r, &g, 0, 5, 10);
  uint8_t *end = draw_at(r, &g, 0, 10, 10);
  fx_save("curtain_start", start);
  fx_save("curtain_mid", mid);
  double c[2];
  /* t = 0: red velvet over the whole middle of the stage, no puppet. */
  size_t red = fx_count(start, is_velvet, FX_W / 4, FX_H / 4, 3 * FX_W / 4, 3 * FX_H / 4, NULL);
  assert_int_equal(red, (size_t)(FX_W / 2) * (FX_H / 2));
  assert_int_equal(fx_count(start, is_blue, 0, 0, FX_W, FX_H, NULL), 0);
  /* Mid-show: the puppet in the middle, the curtain gathered to the
   * picture's sides only. */
  size_t blue = fx_count(mid, is_blue, 0, 0, FX_W, FX_H, c);
  assert_true(blue > 100);
  assert_true(fabs(c[0] - FX_W / 2.0) < 10 && fabs(c[1] - FX_H / 2.0) < 10);
  assert_int_equal(fx_count(mid, is_velvet, FX_W * 3 / 20, 0, FX_W - FX_W * 3 / 20, FX_H, NULL), 0);
  assert_true(fx_count(mid, is_velvet, 0, 0, FX_W / 10, FX_H, NULL) > 0);
  /* The end: closed again. */
  assert_int_equal(fx_count(end, is_blue, 0, 0, FX_W, FX_H, NULL), 0);
  free(start);
  free(mid);
  free(end);
  mr_render_destroy(r);
  mr_stage_destroy(g.stage);
}

static void
test_the_curtain_covers_the_stage_at_the_start_and_shows_the_puppet_mid_show(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) curtain_closed_then_open(backends[i]);
}

/* A floor point 0.5 m in front of where the puppet stands, in pixels. */
static double floor_luma(const fx_scene *s, const uint8_t *rgb, double x) {
  const double p[3] = { x, 0, 0.5 };
  double px[2];
  fx_project(&s->view, p, px);
  return fx_mean_luma(rgb, (int)px[0], (int)px[1], 2);
}

static void pool_follows(mr_render_backend b) {
  staged g;
  staged_init(&g, -1);
  g.s.stage.lights.sun_intensity = 0.3; /* an evening sun: the pool shows */
  g.s.stage.follow_spot.angle_deg = 12; /* wider than the default 8 */
  mr_render *r = fx_render(b, &g.s);
  uint8_t *left = draw_at(r, &g, -1, 5, 10);
  uint8_t *right = draw_at(r, &g, 1, 5, 10);
  fx_save("follow_spot_right", right);
  double ll = floor_luma(&g.s, left, -1), lr = floor_luma(&g.s, left, 1);
  double rl = floor_luma(&g.s, right, -1), rr = floor_luma(&g.s, right, 1);
  print_message("%s: puppet left: %.0f | %.0f, right: %.0f | %.0f\n", mr_render_backend_name(b), ll,
                lr, rl, rr);
  /* Brighter where the puppet is, by a clear margin, on either side. */
  assert_true(ll > lr + 20 && rr > rl + 20);
  assert_true(ll > rl + 20 && rr > lr + 20);
  free(left);
  free(right);
  mr_render_destroy(r);
  mr_stage_destroy(g.stage);
}

static void test_the_follow_spots_pool_is_where_the_puppet_is_and_moves_with_it(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) pool_follows(backends[i]);
}

/* The largest difference of one channel between two frames. */
static int max_apart(const uint8_t *a, const uint8_t *b) {
  int m = 0;
  for (size_t i = 0; i < (size_t)FX_W * FX_H * 3; i++) {
    int d = abs((int)a[i] - (int)b[i]);
    m = d > m ? d : m;
  }
  return m;
}

/* In software (by default one sample, edges smoothed) the scenery is
 * kept from the third frame that stays (still.c). A moved puppet moves
 * the follow spot: over the kept picture its pool is lit again where it
 * falls now, and nowhere is the pool it left behind; the set it sweeps
 * over stays as it was kept. */
static void test_a_frame_over_the_kept_scenery_is_the_frame_drawn_whole(void **state) {
  (void)state;
  staged g;
  staged_init(&g, -0.8);
  /* The set too, under a spot wide enough to reach the arch: the set is
   * kept still, so the spot must never light it, kept or whole. */
  mr_stage_destroy(g.stage);
  g.s.stage.proscenium = g.s.stage.wings = g.s.stage.footlights = true;
  g.s.stage.follow_spot.angle_deg = 25;
  g.s.stage.orbit_distance = 5; /* back in the seats, where the arch is seen */
  g.s.view = mr_default_render_view(&g.s.stage);
  const double rest[3] = { -0.8, 0.6, 0 };
  char msg[256];
  if (mr_stage_create(&g.s.stage, rest, 1, &g.stage, msg, sizeof msg) != MR_STAGE_OK)
    fail_msg("%s", msg);
  mr_render *kept = fx_render(MR_RENDER_OSMESA, &g.s);
  uint8_t *first = draw_at(kept, &g, -0.8, 5, 10);
  for (int k = 0; k < 3; k++) free(draw_at(kept, &g, -0.8, 5, 10));
  uint8_t *later = draw_at(kept, &g, -0.8, 5, 10);
  assert_true(max_apart(first, later) <= 1);
  uint8_t *moved = draw_at(kept, &g, 0.9, 5, 10);
  mr_render *whole = fx_render(MR_RENDER_OSMESA, &g.s);
  uint8_t *fresh = draw_at(whole, &g, 0.9, 5, 10);
  fx_save("follow_spot_kept", moved);
  int apart = max_apart(moved, fresh);
  if (apart > 1) fail_msg("the frame over the kept scenery is %d apart from the whole", apart);
  /* The curtain half open, drawn over a kept picture without it. */
  for (int k = 0; k < 3; k++) free(draw_at(kept, &g, 0.9, 0.75, 10));
  uint8_t *half = draw_at(kept, &g, 0.9, 0.75, 10);
  mr_render *whole2 = fx_render(MR_RENDER_OSMESA, &g.s);
  uint8_t *half_whole = draw_at(whole2, &g, 0.9, 0.75, 10);
  apart = max_apart(half, half_whole);
  if (apart > 1) fail_msg("the moving curtain over the kept scenery is %d apart", apart);
  free(half);
  free(half_whole);
  mr_render_destroy(whole2);
  free(first);
  free(later);
  free(moved);
  free(fresh);
  mr_render_destroy(kept);
  mr_render_destroy(whole);
  mr_stage_destroy(g.stage);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_the_curtain_covers_the_stage_at_the_start_and_shows_the_puppet_mid_show),
    cmocka_unit_test(test_the_follow_spots_pool_is_where_the_puppet_is_and_moves_with_it),
    cmocka_unit_test(test_a_frame_over_the_kept_scenery_is_the_frame_drawn_whole),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
