/* The pictures of test_pictures.c (pictures.h) drawn on OpenGL ES 3 by the
 * real `marionette render --frame T --backend egl --gl es3` (Mesa's
 * llvmpipe gives ES 3.2 through EGL), against the desktop's goldens in
 * tests/golden/ at the same tolerance (tests/render/golden.h: each channel
 * within 5/255 on 99.9 % of pixels). Each picture's agreement is printed;
 * every picture is tried before the test fails. The goldens are never
 * written from here: they are the desktop path's (MR_UPDATE_GOLDEN is for
 * test_pictures.c). Argument: the marionette program. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <stb_image.h>

#include "golden.h"
#include "pictures.h"
#include "proc.h"

enum { W = 320, H = 180 };

static char *marionette;
static char *scratch;

/* A W x H PNG as RGB (free it with stbi_image_free). */
static uint8_t *load_png(const char *path) {
  int w = 0, h = 0, n = 0;
  uint8_t *rgb = stbi_load(path, &w, &h, &n, 3);
  if (rgb == NULL) fail_msg("%s: cannot read (%s)", path, stbi_failure_reason());
  if (w != W || h != H) {
    stbi_image_free(rgb);
    fail_msg("%s: %dx%d, expected %dx%d", path, w, h, W, H);
  }
  return rgb;
}

/* The picture's frame drawn on OpenGL ES; asserts the program said it
 * drew on ES ("backend: egl (..., OpenGL ES 3.x ...)"). */
static uint8_t *draw_es(const picture *p) {
  char scene[1024], out[1024], size[32], name[128];
  snprintf(scene, sizeof scene, "%s/host/scenes/%s", MR_SOURCE_DIR, p->scene);
  snprintf(name, sizeof name, "%s-gles.png", p->name);
  snprintf(out, sizeof out, "%s", tt_path(scratch, name));
  snprintf(size, sizeof size, "%dx%d", W, H);
  char *argv[] = { marionette, "render", scene,       "--frame", (char *)p->frame,
                   "--size",   size,     "--backend", "egl",     "--gl",
                   "es3",      "-o",     out,         NULL };
  tt_output run;
  assert_int_equal(tt_capture(argv, &run), 0);
  if (run.status != 0) fail_msg("%s: exit %d: %s", p->scene, run.status, run.err);
  const char *backend = strstr(run.out, "backend: egl (");
  if (backend == NULL || strstr(backend, "OpenGL ES 3.") == NULL)
    fail_msg("%s: not drawn on OpenGL ES: %s", p->scene, run.out);
  tt_output_free(&run);
  return load_png(out);
}

/* How many of list's pictures fall short of their goldens. */
static int check(const picture *list, size_t n) {
  int failed = 0;
  for (size_t i = 0; i < n; i++) {
    const picture *p = &list[i];
    char golden[1024];
    snprintf(golden, sizeof golden, "%s/tests/golden/%s.png", MR_SOURCE_DIR, p->name);
    uint8_t *rgb = draw_es(p), *g = load_png(golden);
    int worst = 0;
    double a = mr_frames_agreement(rgb, g, W, H, MR_GOLDEN_TOLERANCE, &worst);
    printf("%-14s on OpenGL ES: %8.4f %% of pixels within %d/255 of the golden (worst %d)\n",
           p->name, 100 * a, MR_GOLDEN_TOLERANCE, worst);
    if (a < MR_GOLDEN_FRACTION) {
      char actual[1024];
      snprintf(actual, sizeof actual, "%s/tests/pictures/%s.gles.png", MR_BINARY_DIR, p->name);
      mr_png_write(actual, rgb, W, H);
      fprintf(stderr, "%s (t %s): below %.1f %% on OpenGL ES; the frame is in %s\n", p->name,
              p->frame, 100 * MR_GOLDEN_FRACTION, actual);
      failed++;
    }
    stbi_image_free(rgb);
    stbi_image_free(g);
  }
  return failed;
}

static void each_display_mode_on_opengl_es_matches_the_desktop_golden(void **state) {
  (void)state;
  int failed = check(modes, N_OF(modes));
  if (failed)
    fail_msg("%d of %zu pictures on OpenGL ES differ from the goldens", failed, N_OF(modes));
}

static void each_example_scene_on_opengl_es_matches_the_desktop_golden(void **state) {
  (void)state;
  int failed = check(examples, N_OF(examples));
  if (failed)
    fail_msg("%d of %zu pictures on OpenGL ES differ from the goldens", failed, N_OF(examples));
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s MARIONETTE\n", argv[0]);
    return 2;
  }
  marionette = argv[1];
  scratch = tt_tmpdir();
  if (scratch == NULL) return 1;
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(each_display_mode_on_opengl_es_matches_the_desktop_golden),
    cmocka_unit_test(each_example_scene_on_opengl_es_matches_the_desktop_golden),
  };
  int rc = cmocka_run_group_tests(tests, NULL, NULL);
  tt_rmdir(scratch);
  free(scratch);
  return rc;
}
