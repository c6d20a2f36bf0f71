/* The example puppets load with what the stage draws: each scene has its
 * own models: section (not the loader's default capsules and balls), its
 * model files exist, and across the set every display mode of §3.3 is
 * used at least once; one scene is at night with stars, one has spot
 * lights. puppet.yaml, the README's first run, is one of them. */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "mr_scene.h"
#include "proc.h"

static const char *const examples[] = { "puppet", "stick", "humanoid", "dragon",
                                        "bird",   "clash", "ghost" };
enum { N_EXAMPLES = sizeof examples / sizeof examples[0] };

static const char *scene_path(const char *name) {
  static char path[512];
  snprintf(path, sizeof path, "%s/host/scenes/%s.yaml", MR_SOURCE_DIR, name);
  return path;
}

/* The file declares models: at the top level (the loader draws defaults
 * without one, which would hide a scene that forgot its own). */
static bool has_models_section(const char *path) {
  char *text = tt_read_file(path, NULL);
  assert_non_null(text);
  bool found = strncmp(text, "models:", 7) == 0 || strstr(text, "\nmodels:") != NULL;
  free(text);
  return found;
}

static void load(const char *name, mr_scene *s) {
  mr_scene_error e;
  if (mr_scene_load(scene_path(name), s, &e) != MR_SCENE_OK) fail_msg("%s: %s", name, e.text);
}

static void every_example_has_its_own_models(void **state) {
  (void)state;
  for (size_t i = 0; i < N_EXAMPLES; i++) {
    assert_true(has_models_section(scene_path(examples[i])));
    mr_scene s;
    load(examples[i], &s);
    assert_true(s.stage.n_models >= 1);
    for (size_t m = 0; m < s.stage.n_models; m++) {
      const mr_model_def *d = &s.stage.models[m];
      if (d->shape == MR_SHAPE_FILE) {
        char *data = tt_read_file(d->path, NULL);
        if (data == NULL)
          fail_msg("%s: model '%s' names a missing file %s", examples[i], d->name, d->path);
        free(data);
      }
      if (d->display == MR_DISPLAY_FREEFORM) assert_true(d->n_bones >= 3);
    }
    mr_scene_free(&s);
  }
}

static void the_set_uses_every_display_mode(void **state) {
  (void)state;
  int used[MR_DISPLAY_FREEFORM + 1] = { 0 };
  for (size_t i = 0; i < N_EXAMPLES; i++) {
    mr_scene s;
    load(examples[i], &s);
    for (size_t m = 0; m < s.stage.n_models; m++) used[s.stage.models[m].display]++;
    mr_scene_free(&s);
  }
  for (int mode = MR_DISPLAY_PARTICLE; mode <= MR_DISPLAY_FREEFORM; mode++) {
    if (used[mode] == 0)
      fail_msg("no example draws in display mode %s", mr_display_mode_name(mode));
  }
}

/* The ghost's cloth is skinned to every particle of its puppet. */
static void ghost_sheet_is_skinned_to_the_whole_sheet(void **state) {
  (void)state;
  mr_scene s;
  load("ghost", &s);
  bool found = false;
  for (size_t m = 0; m < s.stage.n_models; m++) {
    const mr_model_def *d = &s.stage.models[m];
    if (d->display != MR_DISPLAY_FREEFORM) continue;
    found = true;
    assert_int_equal(d->n_bones, 30); /* the 5 x 6 sheet */
  }
  assert_true(found);
  mr_scene_free(&s);
}

/* The stage's knobs across the set: a night with stars, spot lights. */
static void the_set_has_a_night_with_stars_and_spot_lights(void **state) {
  (void)state;
  bool night = false, spots = false;
  for (size_t i = 0; i < N_EXAMPLES; i++) {
    mr_scene s;
    load(examples[i], &s);
    if (s.stage.time_of_day >= 0.85 && s.stage.stars) night = true;
    if (s.stage.lights.n_spots > 0) spots = true;
    mr_scene_free(&s);
  }
  assert_true(night);
  assert_true(spots);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(every_example_has_its_own_models),
    cmocka_unit_test(the_set_uses_every_display_mode),
    cmocka_unit_test(ghost_sheet_is_skinned_to_the_whole_sheet),
    cmocka_unit_test(the_set_has_a_night_with_stars_and_spot_lights),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
