/* The strings on real pixels: thin (about a pixel), anti-aliased (their
 * edge pixels blended, partly covered) and depth-tested (hidden behind a
 * model, shown in front of it), on OpenGL 3.3 core through OSMesa and
 * EGL, and on OpenGL ES 3 through EGL. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fixture.h"

/* Two black strings past the red sphere (0.4 m across at (0, 0.6, 0)),
 * slanting a little so that they cross pixels at every offset: one 0.3 m
 * in front of its centre, one 0.3 m behind. No floor, no backdrop: the
 * sky behind them is one colour. */
static const double front_a[3] = { 0.02, 0.1, 0.3 }, front_b[3] = { 0.14, 1.3, 0.3 };
static const double back_a[3] = { -0.14, 0.1, -0.3 }, back_b[3] = { -0.02, 1.3, -0.3 };

static void scene(fx_scene *s, mr_draw_line lines[2]) {
  fx_scene_init(s);
  s->stage.floor = false;
  s->stage.backdrop = false;
  memset(lines, 0, 2 * sizeof *lines);
  memcpy(lines[0].a, front_a, sizeof front_a);
  memcpy(lines[0].b, front_b, sizeof front_b);
  memcpy(lines[1].a, back_a, sizeof back_a);
  memcpy(lines[1].b, back_b, sizeof back_b);
}

/* The point of a -> b at height y. */
static void at_height(const double a[3], const double b[3], double y, double out[3]) {
  double t = (y - a[1]) / (b[1] - a[1]);
  for (int k = 0; k < 3; k++) out[k] = a[k] + t * (b[k] - a[k]);
}

/* How much of pixel (x, y) a black line covers: its darkening against the
 * frame drawn without lines, 0..1 (blending is linear in the stored
 * values, so this is the line's alpha there). */
static double cover(const uint8_t *with, const uint8_t *without, int x, int y) {
  const uint8_t *p = with + 3 * ((size_t)y * FX_W + (size_t)x);
  const uint8_t *q = without + 3 * ((size_t)y * FX_W + (size_t)x);
  double sp = p[0] + p[1] + p[2], sq = q[0] + q[1] + q[2];
  return sq > 0 ? 1.0 - sp / sq : 0;
}

typedef struct row_cover {
  double sum;  /* the line's coverage summed across the row: its width, px */
  int touched; /* pixels it darkens by more than 5 % */
  int partial; /* pixels it covers in part, 15 % to 85 % */
} row_cover;

/* The line a -> b where it is at height y, across its row (8 pixels
 * either side of it). */
static row_cover across(const uint8_t *with, const uint8_t *without, const mr_render_view *v,
                        const double a[3], const double b[3], double y) {
  double p[3], px[2];
  at_height(a, b, y, p);
  fx_project(v, p, px);
  row_cover rc = { 0, 0, 0 };
  int row = (int)px[1];
  for (int x = (int)px[0] - 8; x <= (int)px[0] + 8; x++) {
    double c = cover(with, without, x, row);
    rc.sum += c;
    rc.touched += c > 0.05;
    rc.partial += c > 0.15 && c < 0.85;
  }
  return rc;
}

static void strings_on(mr_render_backend b, mr_render_gl gl) {
  fx_scene s;
  mr_draw_line lines[2];
  scene(&s, lines);
  /* One sample and no smoothing pass: the line's own edges. */
  mr_render *r = fx_render_with(b, gl, &s, 1);
  uint8_t *without = fx_draw(r, &s);
  s.list.lines = lines;
  s.list.n_lines = 2;
  uint8_t *with = fx_draw(r, &s);
  fx_save("strings", with);
  /* Over the sphere: the front string is drawn, the back one hidden. */
  row_cover f = across(with, without, &s.view, front_a, front_b, 0.6);
  row_cover k = across(with, without, &s.view, back_a, back_b, 0.6);
  print_message("%s %s: over the sphere, front %.2f px, back %.2f px\n", mr_render_backend_name(b),
                mr_render_gl_name(gl), f.sum, k.sum);
  assert_true(f.sum > 0.6 && f.sum < 1.6);
  assert_true(k.sum < 0.05 && k.touched == 0);
  /* Against the sky, both show, about a pixel wide; along the front one,
   * rows by the dozen, some pixels are covered in part: its edges are
   * blended, not stepped. */
  int partial = 0;
  for (double y = 0.9; y < 1.25; y += 0.01) {
    row_cover sky_f = across(with, without, &s.view, front_a, front_b, y);
    row_cover sky_k = across(with, without, &s.view, back_a, back_b, y);
    assert_true(sky_f.sum > 0.6 && sky_f.sum < 1.6 && sky_f.touched <= 3);
    assert_true(sky_k.sum > 0.6 && sky_k.sum < 1.6 && sky_k.touched <= 3);
    partial += sky_f.partial;
  }
  print_message("%d pixels of the front string against the sky are covered in part\n", partial);
  assert_true(partial >= 8);
  free(with);
  free(without);
  mr_render_destroy(r);
}

static void strings_are_thin_blended_and_hidden_behind_a_model_through_osmesa(void **state) {
  (void)state;
  strings_on(MR_RENDER_OSMESA, MR_RENDER_GL_CORE);
}

static void strings_are_thin_blended_and_hidden_behind_a_model_through_egl(void **state) {
  (void)state;
  strings_on(MR_RENDER_EGL, MR_RENDER_GL_CORE);
}

static void strings_are_thin_blended_and_hidden_behind_a_model_on_opengl_es_3(void **state) {
  (void)state;
  strings_on(MR_RENDER_EGL, MR_RENDER_GL_ES3);
}

/* A string that reaches behind the eye is cut at the near plane, not
 * thrown across the picture: the part in front is drawn where it
 * projects, and nothing lands on the far side. */
static void a_string_reaching_behind_the_eye_is_cut_at_the_near_plane(void **state) {
  (void)state;
  fx_scene s;
  mr_draw_line lines[2];
  scene(&s, lines);
  mr_render *r = fx_render_with(MR_RENDER_OSMESA, MR_RENDER_GL_CORE, &s, 1);
  uint8_t *without = fx_draw(r, &s);
  /* From the sky above the sphere to a point a metre behind the eye,
   * passing it on the right: the part in front runs from the top point
   * out of the picture's right side. */
  double top[3] = { 0.3, 1.2, 0 }, off[3] = { 0.4, -0.3, 1.0 };
  mr_draw_line l;
  memset(&l, 0, sizeof l);
  memcpy(l.a, top, sizeof top);
  for (int k = 0; k < 3; k++) l.b[k] = s.view.eye[k] + off[k];
  s.list.lines = &l;
  s.list.n_lines = 1;
  uint8_t *with = fx_draw(r, &s);
  double px[2];
  fx_project(&s.view, top, px);
  int near_top = 0, far_side = 0; /* right of the top point, and left */
  for (int y = 0; y < FX_H; y++)
    for (int x = 0; x < FX_W; x++) {
      if (cover(with, without, x, y) < 0.05) continue;
      if (x >= (int)px[0] - 2)
        near_top++;
      else
        far_side++;
    }
  assert_true(near_top > 10);
  assert_int_equal(far_side, 0);
  free(with);
  free(without);
  mr_render_destroy(r);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(strings_are_thin_blended_and_hidden_behind_a_model_through_osmesa),
    cmocka_unit_test(strings_are_thin_blended_and_hidden_behind_a_model_through_egl),
    cmocka_unit_test(strings_are_thin_blended_and_hidden_behind_a_model_on_opengl_es_3),
    cmocka_unit_test(a_string_reaching_behind_the_eye_is_cut_at_the_near_plane),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
