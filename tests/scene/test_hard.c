/* One hard case: `marionette sim --check` on a scene of host/scenes/hard/
 * meets the outcome the file declares. Arguments: the marionette program,
 * the scene file. CMake registers one test per scene. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "mr_scene.h"
#include "proc.h"

static char *marionette, *scene_path;

/* A scene without expectations would pass whatever happened. */
static void scene_declares_an_outcome(void **state) {
  (void)state;
  mr_scene s;
  mr_scene_error e;
  if (mr_scene_load(scene_path, &s, &e) != MR_SCENE_OK) {
    char expected[256];
    assert_int_equal(mr_scene_expected_load_error(scene_path, expected, sizeof expected), 0);
    assert_non_null(strstr(e.text, expected));
    return;
  }
  assert_true(s.expect.present);
  assert_true(s.expect.finite);
  assert_true(s.expect.resets_min >= 0 || s.expect.resets_max >= 0);
  /* Zero resets unless the scene is the reset case, which needs one. */
  assert_true(s.expect.resets_max == 0 || s.expect.resets_min >= 1);
  /* Determinism pinned: every case that runs names the state it ends on. */
  assert_true(s.expect.has_state_hash);
  mr_scene_free(&s);
}

/* One run of `marionette sim --check SCENE`, shared by the tests below. */
static tt_output run;

static int run_once(void **state) {
  (void)state;
  char *argv[] = { marionette, "sim", "--check", scene_path, NULL };
  return tt_capture(argv, &run);
}

static int run_free(void **state) {
  (void)state;
  tt_output_free(&run);
  return 0;
}

static void sim_check_passes(void **state) {
  (void)state;
  if (run.status != 0) fprintf(stderr, "%s", run.err);
  assert_int_equal(run.status, 0);
  assert_string_equal(run.err, "");
  assert_non_null(strstr(run.out, "check: passed"));
}

/* hard/README.md shows each case's run; the row must be what this run
 * printed (host/scenes/pin-hashes.sh writes the rows). */
static void readme_row_is_this_run(void **state) {
  (void)state;
  static const char *const keys[] = { "simulated",      "steps",         "rejected", "dt mean",
                                      "at upper bound", "deviation max", "resets" };
  if (strstr(run.out, "state hash: ") == NULL)
    return; /* a case refused at load has no run to show */
  const char *base = strrchr(scene_path, '/');
  char row[512], v[64], stem[128];
  snprintf(stem, sizeof stem, "%s", base ? base + 1 : scene_path);
  char *dot = strrchr(stem, '.');
  if (dot != NULL) *dot = '\0';
  size_t n = (size_t)snprintf(row, sizeof row, "| `%s` |", stem);
  for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) {
    assert_int_equal(tt_field(run.out, keys[i], v, sizeof v), 0);
    n += (size_t)snprintf(row + n, sizeof row - n, " %s |", v);
  }
  FILE *f = fopen(MR_SOURCE_DIR "/host/scenes/hard/README.md", "rb");
  assert_non_null(f);
  static char doc[1 << 16];
  size_t len = fread(doc, 1, sizeof doc - 1, f);
  fclose(f);
  doc[len] = '\0';
  if (strstr(doc, row) == NULL)
    fprintf(stderr,
            "hard/README.md lacks the row of this run:\n%s\n(host/scenes/pin-hashes.sh "
            "rewrites the table)\n",
            row);
  assert_non_null(strstr(doc, row));
}

int main(int argc, char **argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: %s PATH-TO-marionette SCENE\n", argv[0]);
    return 2;
  }
  marionette = argv[1];
  scene_path = argv[2];
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(scene_declares_an_outcome),
    cmocka_unit_test(sim_check_passes),
    cmocka_unit_test(readme_row_is_this_run),
  };
  return cmocka_run_group_tests(tests, run_once, run_free);
}
