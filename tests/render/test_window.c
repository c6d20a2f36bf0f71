/* The window path, run under Xvfb (ctest starts it through xvfb-run):
 * an SDL window opens (mr_window), the renderer is handed its context as
 * the program hands it (glue.c), 60 frames are drawn and shown, and the
 * window's own pixels (the frame blitted into its back buffer, read from
 * there) match the headless EGL frame of the same draw list; the same on
 * an OpenGL ES 3 window, against the desktop's headless frame. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fixture.h"
#include "glue.h"
#include "golden.h"
#include "render_internal.h"

/* A window on the OpenGL gl asks for (AUTO: the desktop's here). */
static void window_shows_the_headless_frame(mr_render_gl gl) {
  const char *display = getenv("DISPLAY");
  if (!display || !*display) fail_msg("no DISPLAY: run under xvfb-run -a");
  fx_scene s;
  fx_scene_init(&s);
  /* The headless frame first: EGL keeps Mesa's driver loaded for the
   * process, so the window's GL library, unloaded when SDL quits, does not
   * take it along (the sanitizer would then see allocations of code that
   * is gone). The item ends where the window's 60 frames leave it. */
  mr_render *egl = fx_render(MR_RENDER_EGL, &s);
  uint8_t *headless = fx_draw(egl, &s);
  mr_render_destroy(egl);
  mr_window_def wdef = mr_default_window_def();
  wdef.width = FX_W;
  wdef.height = FX_H;
  wdef.vsync = false;
  wdef.title = "marionette test";
  wdef.gl = mr_glue_gl(gl);
  mr_window *window = NULL;
  char msg[1024] = "";
  if (mr_window_create(&wdef, &window, msg, sizeof msg) != MR_WINDOW_OK) fail_msg("%s", msg);
  mr_render_context ctx = mr_glue_context(window);
  mr_render_def def = mr_default_render_def();
  def.width = FX_W;
  def.height = FX_H;
  def.gl = gl;
  def.context = &ctx;
  mr_render *win = NULL;
  /* AUTO with a window's context is the window. */
  if (mr_render_create(&def, &s.stage, NULL, &win, msg, sizeof msg) != MR_RENDER_OK)
    fail_msg("%s", msg);
  assert_int_equal(mr_render_backend_of(win), MR_RENDER_WINDOW);
  assert_int_equal(mr_render_gl_of(win),
                   gl == MR_RENDER_GL_ES3 ? MR_RENDER_GL_ES3 : MR_RENDER_GL_CORE);
  for (int i = 0; i < 60; i++) {
    s.items[0].pose.position[0] = 0.3 * (i - 59) / 59.0; /* ends at 0 */
    assert_int_equal(mr_render_draw(win, &s.list, &s.view), MR_RENDER_OK);
    mr_render_present(win);
    mr_window_event ev;
    while (mr_window_poll(window, &ev)) assert_int_not_equal(ev.kind, MR_WINDOW_EVENT_NONE);
  }
  int w = 0, h = 0;
  uint8_t *shown = malloc((size_t)4096 * 4096 * 3);
  assert_int_equal(mr_render_read_window_rgb(win, shown, (size_t)4096 * 4096 * 3, &w, &h), 0);
  assert_int_equal(w, FX_W);
  assert_int_equal(h, FX_H);
  uint8_t *fbo = malloc((size_t)FX_W * FX_H * 3);
  assert_int_equal(mr_render_read_rgb(win, fbo, (size_t)FX_W * FX_H * 3), MR_RENDER_OK);
  assert_memory_equal(shown, fbo, (size_t)FX_W * FX_H * 3);
  assert_int_equal(mr_window_set_fullscreen(window, false), MR_WINDOW_OK);
  mr_render_destroy(win);
  mr_window_destroy(window);

  int worst = 0;
  double agree = mr_frames_agreement(shown, headless, FX_W, FX_H, MR_GOLDEN_TOLERANCE, &worst);
  if (agree < MR_GOLDEN_FRACTION) {
    fx_save(gl == MR_RENDER_GL_ES3 ? "window_shown_gles" : "window_shown", shown);
    fail_msg("window (gl %s) and EGL: %.4f%% agree, worst %d", mr_render_gl_name(gl), agree * 100,
             worst);
  }
  free(shown);
  free(fbo);
  free(headless);
}

static void test_a_window_shows_the_frame_the_headless_backends_draw(void **state) {
  (void)state;
  window_shows_the_headless_frame(MR_RENDER_GL_AUTO);
}

static void test_an_opengl_es_window_shows_the_frame_the_desktop_draws(void **state) {
  (void)state;
  window_shows_the_headless_frame(MR_RENDER_GL_ES3);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_a_window_shows_the_frame_the_headless_backends_draw),
    cmocka_unit_test(test_an_opengl_es_window_shows_the_frame_the_desktop_draws),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
