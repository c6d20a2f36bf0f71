/* What the renderer draws, checked on real pixels (OSMesa and EGL). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fixture.h"
#include "golden.h"

static const mr_render_backend backends[] = { MR_RENDER_OSMESA, MR_RENDER_EGL };

/* The red sphere shows where its centre projects, inside its projected
 * radius, and nowhere else. */
static void colour_where_it_should_be(mr_render_backend b) {
  fx_scene s;
  fx_scene_init(&s);
  s.items[0].pose.position[0] = -0.5;
  mr_render *r = fx_render(b, &s);
  uint8_t *rgb = fx_draw(r, &s);
  fx_save(b == MR_RENDER_EGL ? "draw_red_egl" : "draw_red_osmesa", rgb);
  double c[2], centre[2], edge[2];
  const double p[3] = { -0.5, 0.6, 0 }, q[3] = { -0.5 + 0.2, 0.6, 0 };
  fx_project(&s.view, p, centre);
  fx_project(&s.view, q, edge);
  double radius = edge[0] - centre[0];
  size_t all = fx_count(rgb, fx_is_red, 0, 0, FX_W, FX_H, c);
  int x0 = (int)(centre[0] - radius * 1.3), x1 = (int)(centre[0] + radius * 1.3) + 1;
  int y0 = (int)(centre[1] - radius * 1.3), y1 = (int)(centre[1] + radius * 1.3) + 1;
  size_t inside = fx_count(rgb, fx_is_red, x0, y0, x1, y1, NULL);
  /* A disc of that radius is pi r^2 pixels; the lit part is red. */
  assert_true((double)all > 0.6 * 3.14159 * radius * radius);
  assert_int_equal(all, inside);
  assert_true(fabs(c[0] - centre[0]) < radius * 0.25);
  assert_true(fabs(c[1] - centre[1]) < radius * 0.25);
  free(rgb);
  mr_render_destroy(r);
}

static void test_an_items_colour_appears_where_it_should_and_nowhere_else(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) colour_where_it_should_be(backends[i]);
}

/* Two poses differ in the item's region, and only near it; the same input
 * twice gives the same frame, bit for bit. */
static void test_poses_differ_and_the_same_input_gives_the_same_frame(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) {
    fx_scene s;
    fx_scene_init(&s);
    mr_render *r = fx_render(backends[i], &s);
    uint8_t *a = fx_draw(r, &s);
    uint8_t *a2 = fx_draw(r, &s);
    s.items[0].pose.position[0] = 0.3;
    uint8_t *b = fx_draw(r, &s);
    const size_t n = (size_t)FX_W * FX_H * 3;
    assert_true(fx_hash(a, n) == fx_hash(a2, n));
    assert_memory_equal(a, a2, n);
    assert_true(fx_hash(a, n) != fx_hash(b, n));
    /* The middle (where the sphere was) changed; the top left corner
     * (sky, far from both places) did not. */
    double m[2];
    const double p[3] = { 0, 0.6, 0 };
    fx_project(&s.view, p, m);
    size_t k = 3 * ((size_t)m[1] * FX_W + (size_t)m[0]);
    assert_true(fx_is_red(a + k));
    assert_false(fx_is_red(b + k));
    assert_memory_equal(a, b, 3 * 20);
    free(a);
    free(a2);
    free(b);
    mr_render_destroy(r);
  }
}

/* One draw list through OSMesa and EGL: the same picture within the
 * golden tolerance. */
static void test_osmesa_and_egl_frames_agree(void **state) {
  (void)state;
  fx_scene s;
  fx_scene_init(&s);
  mr_render *r = fx_render(MR_RENDER_OSMESA, &s);
  uint8_t *a = fx_draw(r, &s);
  mr_render_destroy(r);
  r = fx_render(MR_RENDER_EGL, &s);
  uint8_t *b = fx_draw(r, &s);
  mr_render_destroy(r);
  int worst = 0;
  double agree = mr_frames_agreement(a, b, FX_W, FX_H, MR_GOLDEN_TOLERANCE, &worst);
  if (agree < MR_GOLDEN_FRACTION) fail_msg("%.4f%% agree, worst %d", agree * 100, worst);
  free(a);
  free(b);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_an_items_colour_appears_where_it_should_and_nowhere_else),
    cmocka_unit_test(test_poses_differ_and_the_same_input_gives_the_same_frame),
    cmocka_unit_test(test_osmesa_and_egl_frames_agree),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
