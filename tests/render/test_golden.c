/* Whole pictures against committed goldens (tests/render/golden, PNG,
 * 320 x 180): a day scene, a night sky with stars, and a low sun's
 * shadows with a spot; drawn through EGL and OSMesa, both held to the
 * same golden. MR_UPDATE_GOLDEN=1 rewrites them.
 *
 * Built a second time with MR_TEST_GLES (render_golden_on_gles3): the same
 * pictures drawn through EGL on an OpenGL ES 3 context, held to the same
 * goldens at the same tolerance, each one's agreement printed. That build
 * never writes a golden: they are the desktop path's. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fixture.h"
#include "golden.h"

#ifdef MR_TEST_GLES
#include <stb_image.h>
#endif

/* A small show: a sphere head, a box body, a cylinder arm, and the
 * rigging as lines. */
static void show_init(fx_scene *s, mr_draw_line lines[3]) {
  fx_scene_init(s);
  const float skin[3] = { 0.85f, 0.6f, 0.45f }, coat[3] = { 0.2f, 0.3f, 0.7f },
              arm[3] = { 0.8f, 0.7f, 0.2f };
  memcpy(s->models[0].materials[0].base_color, skin, sizeof skin);
  s->items[0].pose.position[1] = 0.95;
  s->items[0].scale[0] = s->items[0].scale[1] = s->items[0].scale[2] = 0.25;
  fx_add(s, MR_SHAPE_BOX, coat, 0, 0.6, 0, 0.4);
  s->items[1].scale[0] = 0.3;
  s->items[1].scale[2] = 0.2;
  int k = fx_add(s, MR_SHAPE_CYLINDER, arm, 0.25, 0.35, 0, 0.08);
  s->items[k].scale[1] = 0.45;
  s->models[k].materials[0].roughness = 0.2f;
  s->models[k].materials[0].metallic = 0.8f;
  const double top[3] = { 0, 1.8, 0 };
  const double ends[3][3] = { { 0, 1.08, 0 }, { 0.15, 0.8, 0 }, { 0.25, 0.8, 0 } };
  for (int i = 0; i < 3; i++) {
    memcpy(lines[i].a, top, sizeof top);
    memcpy(lines[i].b, ends[i], sizeof ends[i]);
    lines[i].rgb[0] = lines[i].rgb[1] = lines[i].rgb[2] = 0.9f;
  }
  s->list.lines = lines;
  s->list.n_lines = 3;
}

#ifndef MR_TEST_GLES
static void check(const fx_scene *s, const char *name) {
  char path[512], msg[1024] = "";
  snprintf(path, sizeof path, "%s/tests/render/golden/%s.png", MR_SOURCE_DIR, name);
  const mr_render_backend order[] = { MR_RENDER_EGL, MR_RENDER_OSMESA };
  for (int i = 0; i < 2; i++) {
    mr_render *r = fx_render(order[i], s);
    uint8_t *rgb = fx_draw(r, s);
    mr_render_destroy(r);
    int rc = mr_golden_compare(path, rgb, FX_W, FX_H, msg, sizeof msg);
    free(rgb);
    if (rc != 0) fail_msg("%s: %s", mr_render_backend_name(order[i]), msg);
  }
}
#else
/* Drawn on OpenGL ES (the renderer says so, and so does GL_VERSION),
 * compared with the desktop golden; a frame that fails is written to the
 * build folder as NAME.gles.png. */
static void check(const fx_scene *s, const char *name) {
  char path[512];
  snprintf(path, sizeof path, "%s/tests/render/golden/%s.png", MR_SOURCE_DIR, name);
  mr_render *r = fx_render_gl(MR_RENDER_EGL, MR_RENDER_GL_ES3, s);
  assert_int_equal(mr_render_gl_of(r), MR_RENDER_GL_ES3);
  assert_non_null(strstr(mr_render_gl_description(r), "OpenGL ES 3."));
  uint8_t *rgb = fx_draw(r, s);
  mr_render_destroy(r);
  int w = 0, h = 0, n = 0;
  uint8_t *golden = stbi_load(path, &w, &h, &n, 3);
  if (!golden || w != FX_W || h != FX_H) fail_msg("%s: cannot read a %dx%d PNG", path, FX_W, FX_H);
  int worst = 0;
  double a = mr_frames_agreement(rgb, golden, FX_W, FX_H, MR_GOLDEN_TOLERANCE, &worst);
  printf("%s on OpenGL ES: %.4f %% of pixels within %d/255 of the golden (worst %d)\n", name,
         100 * a, MR_GOLDEN_TOLERANCE, worst);
  stbi_image_free(golden);
  if (a < MR_GOLDEN_FRACTION) {
    char actual[512];
    snprintf(actual, sizeof actual, "%s/tests/render/%s.gles.png", MR_BINARY_DIR, name);
    mr_png_write(actual, rgb, FX_W, FX_H);
    free(rgb);
    fail_msg("%s on OpenGL ES: only %.4f %% of pixels agree with %s; the frame is in %s", name,
             100 * a, path, actual);
  }
  free(rgb);
}
#endif

static void test_a_day_scene_matches_its_golden(void **state) {
  (void)state;
  fx_scene s;
  mr_draw_line lines[3];
  show_init(&s, lines);
  check(&s, "day");
}

static void test_a_night_sky_with_stars_matches_its_golden(void **state) {
  (void)state;
  fx_scene s;
  mr_draw_line lines[3];
  show_init(&s, lines);
  const double eye[3] = { 0, 0.4, 2.8 }, target[3] = { 0, 1.4, 0 };
  memcpy(s.view.eye, eye, sizeof eye);
  memcpy(s.view.target, target, sizeof target);
  s.view.time_of_day = 0.02;
  check(&s, "night_stars");
}

static void test_a_low_sun_and_a_spot_match_their_golden(void **state) {
  (void)state;
  fx_scene s;
  mr_draw_line lines[3];
  show_init(&s, lines);
  s.view.time_of_day = 0.33;
  mr_spot_def sp = mr_default_spot_def();
  const double pos[3] = { 1.2, 2.2, 1.2 }, target[3] = { 0, 0.4, 0 };
  memcpy(sp.position, pos, sizeof pos);
  memcpy(sp.target, target, sizeof target);
  const float warm[3] = { 1, 0.8, 0.5 };
  memcpy(sp.color, warm, sizeof warm);
  sp.intensity = 1.5;
  s.stage.lights.spots[0] = sp;
  s.stage.lights.n_spots = 1;
  check(&s, "shadows_spot");
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_a_day_scene_matches_its_golden),
    cmocka_unit_test(test_a_night_sky_with_stars_matches_its_golden),
    cmocka_unit_test(test_a_low_sun_and_a_spot_match_their_golden),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
