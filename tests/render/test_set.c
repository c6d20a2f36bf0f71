/* The theater's set on real pixels (OSMesa and EGL): the arch is drawn
 * where its def puts it and goes when turned off; the footlights glow and
 * light a puppet from below; the floor is boards, not a checkerboard;
 * the bridge stands behind the backdrop when asked. */
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

/* The fixture's stage with the set on: an opening 1.4 x 1.1 m, 0.8 m in
 * front of the origin, so that the default camera (2.5 m from the
 * sphere) sees the arch's posts and header. */
static void with_set(fx_scene *s) {
  fx_scene_init(s);
  s->stage.proscenium = s->stage.wings = s->stage.footlights = true;
  s->stage.set_width = 1.4;
  s->stage.set_height = 1.1;
  s->stage.set_front = 0.8;
}

static const uint8_t *at(const uint8_t *rgb, const mr_render_view *v, const double p[3]) {
  double px[2];
  fx_project(v, p, px);
  assert_true(px[0] >= 0 && px[0] < FX_W && px[1] >= 0 && px[1] < FX_H);
  return rgb + 3 * ((size_t)px[1] * FX_W + (size_t)px[0]);
}

/* The brightest pixel (by red) within 3 pixels of where p lands: a lamp
 * is a few pixels across. */
static const uint8_t *brightest(const uint8_t *rgb, const mr_render_view *v, const double p[3]) {
  double px[2];
  fx_project(v, p, px);
  const uint8_t *best = NULL;
  for (int dy = -3; dy <= 3; dy++)
    for (int dx = -3; dx <= 3; dx++) {
      int x = (int)px[0] + dx, y = (int)px[1] + dy;
      if (x < 0 || y < 0 || x >= FX_W || y >= FX_H) continue;
      const uint8_t *q = rgb + 3 * ((size_t)y * FX_W + (size_t)x);
      if (!best || q[0] > best[0]) best = q;
    }
  assert_non_null(best);
  return best;
}

static double luma_at(const uint8_t *rgb, const mr_render_view *v, const double p[3]) {
  double px[2];
  fx_project(v, p, px);
  return fx_mean_luma(rgb, (int)px[0], (int)px[1], 1);
}

/* The left post's face, half-way up: post 0.1 w + 0.12 = 0.26 m wide
 * outside the opening's edge at x = -0.7; the header, 0.14 h + 0.12 =
 * 0.274 m tall above the opening's top at 1.1 m. */
static void arch(mr_render_backend b) {
  fx_scene s;
  with_set(&s);
  mr_render *r = fx_render(b, &s);
  uint8_t *on = fx_draw(r, &s);
  mr_render_destroy(r);
  fx_save("set_arch", on);
  s.stage.proscenium = false;
  r = fx_render(b, &s);
  uint8_t *off = fx_draw(r, &s);
  mr_render_destroy(r);
  const double post[3] = { -0.83, 0.6, 0.8 }, header[3] = { 0, 1.26, 0.8 };
  const uint8_t *p = at(on, &s.view, post), *q = at(off, &s.view, post);
  /* Dark red: red well above green and blue, not bright. */
  if (!(p[0] > 40 && p[0] > 2 * p[1] && p[0] > 2 * p[2] && p[0] < 200))
    fail_msg("the post is (%d, %d, %d), not dark red", p[0], p[1], p[2]);
  if (q[0] > 2 * q[1] && q[0] > 2 * q[2] && q[0] > 40)
    fail_msg("with the arch off the post's place is still (%d, %d, %d)", q[0], q[1], q[2]);
  const uint8_t *h = at(on, &s.view, header);
  assert_true(h[0] > 2 * h[1] && h[0] > 2 * h[2]);
  /* The sphere, inside the opening, is seen with or without it. */
  const double middle[3] = { 0, 0.6, 0.2 };
  assert_true(fx_is_red(at(on, &s.view, middle)) && fx_is_red(at(off, &s.view, middle)));
  free(on);
  free(off);
}

static void test_the_arch_is_drawn_where_its_def_puts_it_and_goes_when_turned_off(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) arch(backends[i]);
}

/* At night, a white ball low on the stage behind the footlights: lit
 * from below by their warm light, which turning them off takes away;
 * the lamps themselves glow. */
static void footlights(mr_render_backend b) {
  fx_scene s;
  with_set(&s);
  const float white[3] = { 0.9f, 0.9f, 0.9f };
  s.stage.n_models = 0;
  s.list.n_items = 0;
  fx_add(&s, MR_SHAPE_SPHERE, white, 0, 0.3, 0.45, 0.3);
  s.view.time_of_day = 0.1;
  const double eye[3] = { 0, 0.9, 3.2 }, target[3] = { 0, 0.4, 0 };
  memcpy(s.view.eye, eye, sizeof eye);
  memcpy(s.view.target, target, sizeof target);
  mr_render *r = fx_render(b, &s);
  uint8_t *on = fx_draw(r, &s);
  mr_render_destroy(r);
  fx_save("set_footlights", on);
  s.stage.footlights = false;
  r = fx_render(b, &s);
  uint8_t *off = fx_draw(r, &s);
  mr_render_destroy(r);
  /* The ball's front, a little below its middle (facing the lamps). */
  const double low[3] = { 0, 0.25, 0.59 };
  const uint8_t *p = at(on, &s.view, low), *q = at(off, &s.view, low);
  double gain = luma_at(on, &s.view, low) - luma_at(off, &s.view, low);
  if (!(gain > 15 && p[0] - q[0] > p[2] - q[2]))
    fail_msg("the footlights add %.1f to the ball (red %d -> %d, blue %d -> %d); expected a "
             "warm gain above 15",
             gain, q[0], p[0], q[2], p[2]);
  /* A lamp by the middle (six lamps 0.24 m apart), on the stage's front
   * edge (0.35 m in front of the arch, lamps 0.09 m behind that edge,
   * their tops 0.076 m above the boards, over the trough's lip). */
  const double lamp[3] = { 0.12, 0.06, 0.8 + 0.35 - 0.09 };
  const uint8_t *l = brightest(on, &s.view, lamp), *d = brightest(off, &s.view, lamp);
  if (!(l[0] > 150 && l[0] > l[2] + 40 && l[0] > d[0] + 60))
    fail_msg("the lamp is (%d, %d, %d), with the footlights off (%d, %d, %d); expected a warm "
             "glow",
             l[0], l[1], l[2], d[0], d[1], d[2]);
  free(on);
  free(off);
}

static void test_the_footlights_glow_and_light_a_puppet_from_below(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) footlights(backends[i]);
}

/* Looking down at the floor, the set off: along a line across the boards
 * (x), each seam between two boards (every board_width, with the stage's
 * middle line in a board's middle) is darker than the boards either
 * side, and the boards differ in tone; along a board (z) there is no
 * seam for most of its length. A checkerboard has neither. */
static void boards(mr_render_backend b) {
  fx_scene s;
  fx_scene_init(&s);
  s.stage.n_models = 0;
  s.list.n_items = 0;
  s.stage.board_width = 0.2;
  const double eye[3] = { 0, 1.6, 0.9 }, target[3] = { 0, 0, 0.3 };
  memcpy(s.view.eye, eye, sizeof eye);
  memcpy(s.view.target, target, sizeof target);
  mr_render *r = fx_render(b, &s);
  uint8_t *rgb = fx_draw(r, &s);
  mr_render_destroy(r);
  fx_save("set_boards", rgb);
  double lo = 1e9, hi = -1e9;
  for (int k = -2; k <= 2; k++) {
    const double seam[3] = { 0.2 * k + 0.1, 0, 0.3 }, left[3] = { 0.2 * k + 0.05, 0, 0.3 },
                 right[3] = { 0.2 * k + 0.15, 0, 0.3 }, middle[3] = { 0.2 * k, 0, 0.3 };
    double px[2];
    fx_project(&s.view, seam, px);
    double darkest = 1e9;
    for (int dx = -2; dx <= 2; dx++)
      darkest = fmin(darkest, fx_mean_luma(rgb, (int)px[0] + dx, (int)px[1], 0));
    double l = luma_at(rgb, &s.view, left), rr = luma_at(rgb, &s.view, right);
    if (!(darkest < 0.75 * fmin(l, rr)))
      fail_msg("no seam at x = %.2f: %.1f there, boards %.1f and %.1f", seam[0], darkest, l, rr);
    double m = luma_at(rgb, &s.view, middle);
    lo = fmin(lo, m), hi = fmax(hi, m);
  }
  if (!(hi - lo > 3)) fail_msg("the boards are all one tone (%.1f to %.1f)", lo, hi);
  /* Along the middle board, from z = 0.1 to 0.5: at most one joint. */
  int dips = 0;
  for (int k = 0; k <= 40; k++) {
    const double p[3] = { 0, 0, 0.1 + 0.01 * k };
    dips += luma_at(rgb, &s.view, p) < 0.75 * hi;
  }
  if (dips > 3) fail_msg("%d dark places along one board", dips);
  free(rgb);
}

static void test_the_floor_is_boards_with_seams_and_tones_not_a_checkerboard(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) boards(backends[i]);
}

/* From the wings, above them: the bridge's deck (the opening 0.8 m in
 * front, the backdrop 3 m behind the origin, so the deck runs from 0.15
 * to 0.95 m behind it, its top 0.35 m above the backdrop's 1.6 m) is
 * there, in the floor's wood, only when asked. */
static void bridge(mr_render_backend b) {
  fx_scene s;
  with_set(&s);
  s.stage.n_models = 0;
  s.list.n_items = 0;
  const double eye[3] = { 2.5, 3.2, 0.3 }, target[3] = { 0, 1.9, -3.5 };
  memcpy(s.view.eye, eye, sizeof eye);
  memcpy(s.view.target, target, sizeof target);
  mr_render *r = fx_render(b, &s);
  uint8_t *off = fx_draw(r, &s);
  mr_render_destroy(r);
  s.stage.bridge = true;
  r = fx_render(b, &s);
  uint8_t *on = fx_draw(r, &s);
  mr_render_destroy(r);
  fx_save("set_bridge", on);
  const double deck[3] = { 0, 1.95, -3.55 };
  const uint8_t *p = at(on, &s.view, deck), *q = at(off, &s.view, deck);
  if (!(p[0] > p[2] + 20 && abs(p[0] - q[0]) + abs(p[1] - q[1]) + abs(p[2] - q[2]) > 60))
    fail_msg("the deck is (%d, %d, %d), without the bridge (%d, %d, %d)", p[0], p[1], p[2], q[0],
             q[1], q[2]);
  free(on);
  free(off);
}

static void test_the_bridge_stands_behind_the_backdrop_only_when_asked(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) bridge(backends[i]);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_the_arch_is_drawn_where_its_def_puts_it_and_goes_when_turned_off),
    cmocka_unit_test(test_the_footlights_glow_and_light_a_puppet_from_below),
    cmocka_unit_test(test_the_floor_is_boards_with_seams_and_tones_not_a_checkerboard),
    cmocka_unit_test(test_the_bridge_stands_behind_the_backdrop_only_when_asked),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
