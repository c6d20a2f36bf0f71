/* The backends: OSMesa and EGL each start and give a 3.3+ core context;
 * EGL gives OpenGL ES 3 when asked, OSMesa says it has none; AUTO without
 * a window's context falls back; the window backend without one fails,
 * saying why; names parse both ways. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fixture.h"

static void starts(mr_render_backend b) {
  fx_scene s;
  fx_scene_init(&s);
  mr_render *r = fx_render(b, &s);
  assert_int_equal(mr_render_backend_of(r), b);
  int w = 0, h = 0;
  mr_render_size(r, &w, &h);
  assert_int_equal(w, FX_W);
  assert_int_equal(h, FX_H);
  const char *d = mr_render_gl_description(r);
  assert_non_null(strstr(d, "OpenGL"));
  /* "4.5 (Core Profile) Mesa ..." or at least 3.3 */
  const char *v = strstr(d, "OpenGL ");
  int major = 0, minor = 0;
  assert_int_equal(sscanf(v, "OpenGL %d.%d", &major, &minor), 2);
  assert_true(major * 10 + minor >= 33);
  /* Headless: present does nothing. */
  mr_render_present(r);
  uint8_t *rgb = fx_draw(r, &s);
  free(rgb);
  mr_render_destroy(r);
}

static void test_osmesa_starts_a_core_context_and_draws(void **state) {
  (void)state;
  starts(MR_RENDER_OSMESA);
}

static void test_egl_starts_a_surfaceless_core_context_and_draws(void **state) {
  (void)state;
  starts(MR_RENDER_EGL);
}

static void test_auto_headless_picks_egl(void **state) {
  (void)state;
  fx_scene s;
  fx_scene_init(&s);
  mr_render *r = fx_render(MR_RENDER_AUTO, &s);
  assert_int_equal(mr_render_backend_of(r), MR_RENDER_EGL);
  mr_render_destroy(r);
}

/* The renderer opens no window: the window backend draws only into a
 * context it is handed (mr_render_def.context). */
static void test_the_window_backend_without_a_window_context_fails_saying_why(void **state) {
  (void)state;
  fx_scene s;
  fx_scene_init(&s);
  mr_render_def def = mr_default_render_def();
  def.backend = MR_RENDER_WINDOW;
  mr_render *r = (mr_render *)&s; /* must be cleared */
  char msg[512] = "";
  assert_int_equal(mr_render_create(&def, &s.stage, NULL, &r, msg, sizeof msg),
                   MR_RENDER_ERR_BACKEND);
  assert_null(r);
  assert_non_null(strstr(msg, "window: no window's GL context given"));
  /* AUTO, not headless, with no context: no window is tried. */
  def.backend = MR_RENDER_AUTO;
  if (mr_render_create(&def, &s.stage, NULL, &r, msg, sizeof msg) != MR_RENDER_OK)
    fail_msg("%s", msg);
  assert_int_not_equal(mr_render_backend_of(r), MR_RENDER_WINDOW);
  mr_render_destroy(r);
}

static void test_backend_names_parse_both_ways(void **state) {
  (void)state;
  const char *names[] = { "auto", "window", "osmesa", "egl" };
  for (int i = 0; i < 4; i++) {
    mr_render_backend b;
    assert_int_equal(mr_render_backend_parse(names[i], &b), 0);
    assert_int_equal(b, i);
    assert_string_equal(mr_render_backend_name(b), names[i]);
  }
  mr_render_backend b = MR_RENDER_EGL;
  assert_int_equal(mr_render_backend_parse("vulkan", &b), -1);
  assert_int_equal(b, MR_RENDER_EGL);
}

/* --gl es3 through EGL: an ES context (GL_VERSION "OpenGL ES 3.x"), and
 * it draws the sphere as the desktop does; gl auto and core give the
 * desktop's core profile, which Mesa offers. */
static void test_egl_gives_opengl_es_3_when_asked_and_core_otherwise(void **state) {
  (void)state;
  fx_scene s;
  fx_scene_init(&s);
  const mr_render_gl asked[] = { MR_RENDER_GL_AUTO, MR_RENDER_GL_CORE, MR_RENDER_GL_ES3 };
  for (int i = 0; i < 3; i++) {
    mr_render *r = fx_render_gl(MR_RENDER_EGL, asked[i], &s);
    bool es = asked[i] == MR_RENDER_GL_ES3;
    assert_int_equal(mr_render_gl_of(r), es ? MR_RENDER_GL_ES3 : MR_RENDER_GL_CORE);
    int major = 0, minor = 0;
    const char *v = mr_render_gl_version(r);
    if (es)
      assert_int_equal(sscanf(v, "OpenGL ES %d.%d", &major, &minor), 2);
    else
      assert_int_equal(sscanf(v, "OpenGL %d.%d core", &major, &minor), 2);
    assert_true(major * 10 + minor >= (es ? 30 : 33));
    assert_true((strstr(mr_render_gl_description(r), "OpenGL ES") != NULL) == es);
    uint8_t *rgb = fx_draw(r, &s);
    double c[2];
    assert_true(fx_count(rgb, fx_is_red, 0, 0, FX_W, FX_H, c) > 500);
    free(rgb);
    mr_render_destroy(r);
  }
}

/* OSMesa makes desktop contexts only: ES asked of it fails by name. */
static void test_osmesa_refuses_opengl_es_saying_so(void **state) {
  (void)state;
  fx_scene s;
  fx_scene_init(&s);
  mr_render_def def = mr_default_render_def();
  def.backend = MR_RENDER_OSMESA;
  def.gl = MR_RENDER_GL_ES3;
  mr_render *r = NULL;
  char msg[512] = "";
  assert_int_equal(mr_render_create(&def, &s.stage, NULL, &r, msg, sizeof msg),
                   MR_RENDER_ERR_BACKEND);
  assert_null(r);
  assert_non_null(strstr(msg, "OSMesa has no OpenGL ES"));
}

static void test_gl_names_parse_both_ways(void **state) {
  (void)state;
  const char *names[] = { "auto", "core", "es3" };
  for (int i = 0; i < 3; i++) {
    mr_render_gl g;
    assert_int_equal(mr_render_gl_parse(names[i], &g), 0);
    assert_int_equal(g, i);
    assert_string_equal(mr_render_gl_name(g), names[i]);
  }
  mr_render_gl g = MR_RENDER_GL_ES3;
  assert_int_equal(mr_render_gl_parse("es2", &g), -1);
  assert_int_equal(g, MR_RENDER_GL_ES3);
}

static void test_a_def_not_from_its_maker_is_refused(void **state) {
  (void)state;
  fx_scene s;
  fx_scene_init(&s);
  mr_render_def def = mr_default_render_def();
  def.cookie = 0;
  mr_render *r = NULL;
  char msg[256] = "";
  assert_int_equal(mr_render_create(&def, &s.stage, NULL, &r, msg, sizeof msg), MR_RENDER_ERR_ARG);
  assert_null(r);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_osmesa_starts_a_core_context_and_draws),
    cmocka_unit_test(test_egl_starts_a_surfaceless_core_context_and_draws),
    cmocka_unit_test(test_auto_headless_picks_egl),
    cmocka_unit_test(test_egl_gives_opengl_es_3_when_asked_and_core_otherwise),
    cmocka_unit_test(test_osmesa_refuses_opengl_es_saying_so),
    cmocka_unit_test(test_gl_names_parse_both_ways),
    cmocka_unit_test(test_the_window_backend_without_a_window_context_fails_saying_why),
    cmocka_unit_test(test_backend_names_parse_both_ways),
    cmocka_unit_test(test_a_def_not_from_its_maker_is_refused),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
