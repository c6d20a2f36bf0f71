/* The backends: OSMesa and EGL each start and give a 3.3+ core context;
 * AUTO without a display falls back; a window without a display fails,
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
  /* Headless: nothing to poll, present does nothing, fullscreen is moot. */
  mr_event ev;
  assert_int_equal(mr_render_poll(r, &ev), 0);
  mr_render_present(r);
  assert_int_equal(mr_render_set_fullscreen(r, true), MR_RENDER_OK);
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

static void test_a_window_without_a_display_fails_saying_why(void **state) {
  (void)state;
  fx_scene s;
  fx_scene_init(&s);
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
  /* SDL alone would fall back to a driver of its own (offscreen): ask for
   * X11, which needs the display that is not there. */
  setenv("SDL_VIDEODRIVER", "x11", 1);
  mr_render_def def = mr_default_render_def();
  def.backend = MR_RENDER_WINDOW;
  mr_render *r = (mr_render *)&s; /* must be cleared */
  char msg[512] = "";
  assert_int_equal(mr_render_create(&def, &s.stage, NULL, &r, msg, sizeof msg),
                   MR_RENDER_ERR_BACKEND);
  assert_null(r);
  assert_non_null(strstr(msg, "window: "));
  /* AUTO, not headless, with no display: no window is tried. */
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
    cmocka_unit_test(test_a_window_without_a_display_fails_saying_why),
    cmocka_unit_test(test_backend_names_parse_both_ways),
    cmocka_unit_test(test_a_def_not_from_its_maker_is_refused),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
