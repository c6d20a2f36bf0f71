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

/* A buffer one byte short of 3 w h is refused before anything is read
 * into it: not a byte of it changes. */
static void test_a_read_into_a_buffer_too_small_is_refused_and_leaves_it_alone(void **state) {
  (void)state;
  fx_scene s;
  fx_scene_init(&s);
  mr_render *r = fx_render(MR_RENDER_OSMESA, &s);
  uint8_t *first = fx_draw(r, &s);
  const size_t n = (size_t)FX_W * FX_H * 3;
  uint8_t *rgb = malloc(n);
  assert_non_null(rgb);
  memset(rgb, 0xab, n);
  assert_int_equal(mr_render_read_rgb(r, rgb, n - 1), MR_RENDER_ERR_ARG);
  assert_int_equal(mr_render_read_rgb(r, NULL, n), MR_RENDER_ERR_ARG);
  for (size_t i = 0; i < n; i++) assert_int_equal(rgb[i], 0xab);
  assert_int_equal(mr_render_read_rgb(r, rgb, n), MR_RENDER_OK);
  assert_memory_equal(rgb, first, n);
  free(rgb);
  free(first);
  mr_render_destroy(r);
}

/* A view with no direction (eye on its target) or one looking along its
 * up vector has no camera basis: the draw is refused and the last frame
 * stays as it was, not replaced by a picture of only sky. Looking down
 * from 89 degrees still draws the sphere under the camera. */
/* v from the orbit camera at 2.5 m from (0, 0.6, 0), its field of view
 * kept. */
static void orbit_view(mr_render_view *v, double azimuth_deg, double elevation_deg) {
  const mr_orbit o = { .target = { 0, 0.6, 0 },
                       .distance = 2.5,
                       .azimuth_deg = azimuth_deg,
                       .elevation_deg = elevation_deg,
                       .fov_deg = v->fov_deg };
  mr_render_view_orbit(v, &o);
}

static void test_a_view_without_a_camera_basis_is_refused(void **state) {
  (void)state;
  fx_scene s;
  fx_scene_init(&s);
  mr_render *r = fx_render(MR_RENDER_OSMESA, &s);
  uint8_t *before = fx_draw(r, &s);
  const size_t n = (size_t)FX_W * FX_H * 3;
  mr_render_view v = s.view;
  for (int k = 0; k < 3; k++) v.eye[k] = v.target[k];
  assert_int_equal(mr_render_draw(r, &s.list, &v), MR_RENDER_ERR_ARG);
  v = s.view;
  orbit_view(&v, 30, 90);
  assert_int_equal(mr_render_draw(r, &s.list, &v), MR_RENDER_ERR_ARG);
  orbit_view(&v, 0, -90);
  assert_int_equal(mr_render_draw(r, &s.list, &v), MR_RENDER_ERR_ARG);
  v = s.view;
  v.up[0] = v.up[1] = v.up[2] = 0;
  assert_int_equal(mr_render_draw(r, &s.list, &v), MR_RENDER_ERR_ARG);
  uint8_t *after = malloc(n);
  assert_non_null(after);
  assert_int_equal(mr_render_read_rgb(r, after, n), MR_RENDER_OK);
  assert_memory_equal(before, after, n);

  v = s.view;
  orbit_view(&v, 30, 89);
  assert_int_equal(mr_render_draw(r, &s.list, &v), MR_RENDER_OK);
  assert_int_equal(mr_render_read_rgb(r, after, n), MR_RENDER_OK);
  double c[2];
  size_t red = fx_count(after, fx_is_red, 0, 0, FX_W, FX_H, c);
  assert_true(red > 200);
  assert_true(fabs(c[0] - FX_W / 2.0) < 10 && fabs(c[1] - FX_H / 2.0) < 10);
  free(before);
  free(after);
  mr_render_destroy(r);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_an_items_colour_appears_where_it_should_and_nowhere_else),
    cmocka_unit_test(test_poses_differ_and_the_same_input_gives_the_same_frame),
    cmocka_unit_test(test_osmesa_and_egl_frames_agree),
    cmocka_unit_test(test_a_read_into_a_buffer_too_small_is_refused_and_leaves_it_alone),
    cmocka_unit_test(test_a_view_without_a_camera_basis_is_refused),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
