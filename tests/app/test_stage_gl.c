/* Which OpenGL the stage gets, and a box with no screen: `marionette run
 * --fullscreen` with no X or Wayland display and no console screen
 * (KMS/DRM) ends at once with one line and a non-zero status; under Xvfb,
 * `--gl es3` opens the window on OpenGL ES and `--gl core` on the
 * desktop's, each named in the stage line; `render --gl es3` draws through
 * EGL on ES, OSMesa refuses it by name, and a bad --gl is bad usage.
 * Where desktop OpenGL stops short of 3.3 (Mesa held to 3.1, as a
 * Raspberry Pi's V3D offers), --gl auto falls back to ES, in the window
 * and headless, and --gl core fails in one line. */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app_test.h"
#include "proc.h"

static char *marionette;

#define STICK MR_SOURCE_DIR "/host/scenes/stick.yaml"

/* With DISPLAY, WAYLAND_DISPLAY and SDL_VIDEODRIVER unset the window has
 * only the console (SDL's KMS/DRM driver), which a machine without
 * /dev/dri cannot open: no frames drawn into nothing, no "exit 0". */
static void fullscreen_without_any_screen_exits_non_zero_with_one_line(void **state) {
  (void)state;
  if (access("/dev/dri", F_OK) == 0) {
    print_message("/dev/dri is here: the console might open, so no screen is not tried\n");
    skip();
  }
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
  unsetenv("SDL_VIDEODRIVER");
  char *argv[] = { marionette, "run", STICK, "--fullscreen", "--time", "2", NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  print_message("status %d, stderr: %s", o.status, o.err);
  assert_int_equal(o.status, 1);
  assert_int_equal(at_lines(o.err), 1);
  assert_non_null(strstr(o.err, "KMS/DRM"));
  assert_null(strstr(o.out, "frames drawn"));
  tt_output_free(&o);
}

/* Under Xvfb, a short windowed show on the OpenGL gl names; what the
 * stage line says it got, from "frames drawn (" to ")", into got. */
static void window_on(const char *gl, char *got, size_t size) {
  char xvfb[512];
  if (at_which("xvfb-run", xvfb, sizeof xvfb) != 0) {
    print_message("xvfb-run is not installed: the window is not tried\n");
    skip();
  }
  char *argv[] = { xvfb,       "-a",     "-s",  "-screen 0 640x480x24",
                   marionette, "run",    STICK, "--gl",
                   (char *)gl, "--keys", "1:q", "--size",
                   "160x96",   "--time", "10",  NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  const char *stage = strstr(o.out, "stage: in a window (SDL), 160x96, ");
  assert_non_null(stage);
  const char *from = strstr(stage, "frames drawn (");
  assert_non_null(from);
  from += strlen("frames drawn (");
  const char *to = strchr(from, ')');
  assert_true(to != NULL && to < strchr(stage, '\n') && (size_t)(to - from) < size);
  snprintf(got, size, "%.*s", (int)(to - from), from);
  print_message("--gl %s: the window's stage is on %s\n", gl, got);
  tt_output_free(&o);
}

static void the_window_opens_on_opengl_es_when_asked(void **state) {
  (void)state;
  char got[64];
  window_on("es3", got, sizeof got);
  assert_memory_equal(got, "OpenGL ES 3.", strlen("OpenGL ES 3."));
}

static void the_window_opens_on_desktop_core_when_asked(void **state) {
  (void)state;
  char got[64];
  window_on("core", got, sizeof got);
  int major = 0, minor = 0;
  assert_int_equal(sscanf(got, "OpenGL %d.%d core", &major, &minor), 2);
  assert_true(major * 10 + minor >= 33);
  assert_non_null(strstr(got, " core"));
}

/* One frame of render with --gl gl through backend: its status and what
 * it printed (free it). */
static tt_output render_on(const char *backend, const char *gl, const char *out) {
  char *argv[] = { marionette, "render",   STICK,       "--frame",       "2",  "--size",    "64x48",
                   "--gl",     (char *)gl, "--backend", (char *)backend, "-o", (char *)out, NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  return o;
}

static void render_draws_on_opengl_es_through_egl_and_osmesa_says_it_cannot(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  char png[600];
  snprintf(png, sizeof png, "%s", tt_path(dir, "es.png"));
  tt_output o = render_on("egl", "es3", png);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_non_null(strstr(o.out, "OpenGL ES 3."));
  int w = 0, h = 0;
  assert_int_equal(at_png_size(png, &w, &h), 0);
  assert_true(w == 64 && h == 48);
  tt_output_free(&o);
  o = render_on("osmesa", "es3", tt_path(dir, "no.png"));
  print_message("osmesa, es3: %s", o.err);
  assert_int_equal(o.status, 1);
  assert_int_equal(at_lines(o.err), 1);
  assert_non_null(strstr(o.err, "OSMesa has no OpenGL ES"));
  tt_output_free(&o);
  o = render_on("egl", "gles", tt_path(dir, "bad.png"));
  assert_int_equal(o.status, 2);
  assert_non_null(strstr(o.err, "expected --gl auto, core or es3, got 'gles'"));
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

/* Mesa's desktop OpenGL held to 3.1 for the children: no 3.3 core. */
static void render_and_the_window_fall_back_to_es_without_desktop_3_3(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  tt_output o = render_on("egl", "auto", tt_path(dir, "core.png"));
  assert_int_equal(o.status, 0);
  bool mesa = strstr(o.out, "Mesa") != NULL;
  tt_output_free(&o);
  if (!mesa) {
    print_message("not Mesa: its GL version cannot be held down here\n");
    tt_rmdir(dir);
    free(dir);
    skip();
  }
  setenv("MESA_GL_VERSION_OVERRIDE", "3.1", 1);
  o = render_on("egl", "auto", tt_path(dir, "auto.png"));
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_non_null(strstr(o.out, "OpenGL ES 3."));
  tt_output_free(&o);
  o = render_on("egl", "core", tt_path(dir, "core.png"));
  print_message("egl, core, Mesa at 3.1: %s", o.err);
  assert_int_equal(o.status, 1);
  assert_int_equal(at_lines(o.err), 1);
  assert_non_null(strstr(o.err, "no OpenGL 3.3 core context"));
  tt_output_free(&o);
  char got[64];
  window_on("auto", got, sizeof got);
  assert_memory_equal(got, "OpenGL ES 3.", strlen("OpenGL ES 3."));
  unsetenv("MESA_GL_VERSION_OVERRIDE");
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s MARIONETTE\n", argv[0]);
    return 2;
  }
  marionette = argv[1];
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(render_draws_on_opengl_es_through_egl_and_osmesa_says_it_cannot),
    cmocka_unit_test(the_window_opens_on_opengl_es_when_asked),
    cmocka_unit_test(the_window_opens_on_desktop_core_when_asked),
    cmocka_unit_test(render_and_the_window_fall_back_to_es_without_desktop_3_3),
    cmocka_unit_test(fullscreen_without_any_screen_exits_non_zero_with_one_line),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
