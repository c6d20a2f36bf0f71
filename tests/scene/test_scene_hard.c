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
#include "scene_proc.h"

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

static void sim_check_passes(void **state) {
  (void)state;
  char *argv[] = {marionette, "sim", "--check", "--quiet", scene_path, NULL};
  scene_proc p;
  assert_int_equal(scene_proc_run(argv, &p), 0);
  if (p.status != 0)
    fprintf(stderr, "%s", p.err);
  assert_int_equal(p.status, 0);
  assert_string_equal(p.err, "");
  assert_non_null(strstr(p.out, "check: passed"));
  scene_proc_free(&p);
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
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
