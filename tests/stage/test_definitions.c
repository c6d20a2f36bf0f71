/* The stage's definitions: defaults, names, the built-in sky, and defs
 * that name what is not there, refused with a message. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "mr_stage.h"

static void defaults_are_the_documented_ones(void **state) {
  (void)state;
  mr_stage_def d = mr_default_stage_def();
  assert_int_equal(d.cookie, MR_DEF_COOKIE);
  assert_int_equal(d.width, 1280);
  assert_int_equal(d.height, 720);
  assert_true(d.time_of_day == 0.5 && d.floor && d.backdrop && d.stars);
  /* 0: the renderer sizes the map to the frame and picks the filter. */
  assert_true(d.lights.shadows && d.lights.shadow_size == 0 && d.lights.shadow_filter == 0);
  mr_model_def m = mr_default_model_def();
  assert_int_equal(m.influences, 4);
  assert_true(m.cast_shadow && m.scale[1] == 1 && m.place.orientation[0] == 1);
  assert_int_equal(m.orient, MR_RIGID_INITIAL);
  mr_material_def k = mr_default_material_def();
  assert_true(k.base_color[3] == 1.0f && k.roughness == 0.6f);
  assert_true(mr_default_spot_def().angle_deg == 25);
  assert_true(mr_default_camera_def().fov_deg == 45);
}

static void names_parse_back_to_their_values(void **state) {
  (void)state;
  for (int i = MR_SHAPE_FILE; i <= MR_SHAPE_CONE; i++) {
    mr_shape s;
    assert_int_equal(mr_shape_parse(mr_shape_name((mr_shape)i), &s), 0);
    assert_int_equal(s, i);
  }
  for (int i = MR_DISPLAY_PARTICLE; i <= MR_DISPLAY_FREEFORM; i++) {
    mr_display_mode m;
    assert_int_equal(mr_display_mode_parse(mr_display_mode_name((mr_display_mode)i), &m), 0);
    assert_int_equal(m, i);
  }
  mr_shape s;
  assert_int_equal(mr_shape_parse("teapot", &s), -1);
  assert_string_equal(mr_shape_name((mr_shape)99), "unknown");
  assert_string_equal(mr_display_mode_name((mr_display_mode)4), "unknown");
  assert_string_equal(mr_display_mode_name(MR_DISPLAY_LINK), "link");
}

static void the_built_in_sky_is_fixed_unit_and_above_the_horizon(void **state) {
  (void)state;
  size_t n = 0;
  const mr_star *s = mr_stage_builtin_stars(&n);
  assert_true(n >= 100);
  assert_ptr_equal(s, mr_stage_builtin_stars(NULL));
  int bright = 0;
  for (size_t i = 0; i < n; i++) {
    double len =
        sqrt(s[i].dir[0] * s[i].dir[0] + s[i].dir[1] * s[i].dir[1] + s[i].dir[2] * s[i].dir[2]);
    assert_true(fabs(len - 1) < 1e-3);
    assert_true(s[i].dir[1] > 0);
    assert_true(s[i].brightness > 0 && s[i].brightness <= 1);
    bright += s[i].brightness >= 0.45f;
  }
  /* The constellations' stars stand out from the faint field. */
  assert_true(bright >= 15);
  mr_star up = mr_stage_star_at(0, 90, 2);
  assert_true(fabs(up.dir[1] - 1) < 1e-6 && up.brightness == 1);
  mr_star ahead = mr_stage_star_at(0, 0, 0.5), right = mr_stage_star_at(90, 0, 0.5);
  assert_true(fabs(ahead.dir[2] + 1) < 1e-6 && fabs(right.dir[0] - 1) < 1e-6);
}

/* Creates the stage and expects `status` with a message containing want. */
static void refused(const mr_stage_def *d, const double *rest, size_t n, mr_stage_status status,
                    const char *want) {
  mr_stage *s = (mr_stage *)1;
  char msg[256] = "";
  assert_int_equal(mr_stage_create(d, rest, n, &s, msg, sizeof msg), status);
  assert_null(s);
  if (strstr(msg, want) == NULL) fail_msg("'%s' does not say '%s'", msg, want);
}

static void defs_naming_missing_points_are_refused_with_a_message(void **state) {
  (void)state;
  double rest[9] = { 0, 0, 0, 1, 0, 0, 2, 0, 0 };
  mr_model_def m = mr_default_model_def();
  snprintf(m.name, sizeof m.name, "head");
  mr_stage_def d = mr_default_stage_def();
  d.models = &m;
  d.n_models = 1;
  refused(&d, rest, 3, MR_STAGE_ERR_ARG, "model 'head' (particle): point -1 is not one of");
  m.particles[0] = 3;
  refused(&d, rest, 3, MR_STAGE_ERR_ARG, "point 3 is not one of the stage's 3 points");
  m.display = MR_DISPLAY_LINK;
  m.particles[0] = 0;
  m.particles[1] = 7;
  refused(&d, rest, 3, MR_STAGE_ERR_ARG, "model 'head' (link): point 7");
  m.display = MR_DISPLAY_RIGID;
  m.particles[1] = 1;
  m.particles[2] = 2; /* three on a line */
  refused(&d, rest, 3, MR_STAGE_ERR_VALUE, "lie on one line at the start");
  int bones[2] = { 0, 9 };
  m.display = MR_DISPLAY_FREEFORM;
  m.bones = bones;
  m.n_bones = 2;
  refused(&d, rest, 3, MR_STAGE_ERR_ARG, "bone 1 is point 9");
  m.n_bones = 0;
  refused(&d, rest, 3, MR_STAGE_ERR_ARG, "no bones");
  d.n_models = 0;
  int strings[2] = { 0, 3 };
  d.strings = strings;
  d.n_strings = 1;
  refused(&d, rest, 3, MR_STAGE_ERR_ARG, "a string: point 3");
  d.n_strings = 0;
  d.lights.n_spots = 9;
  refused(&d, rest, 3, MR_STAGE_ERR_ARG, "9 spots");
  d.lights.n_spots = 0;
  d.cookie = 0;
  refused(&d, rest, 3, MR_STAGE_ERR_ARG, "mr_default_stage_def");
  d.cookie = MR_DEF_COOKIE;
  rest[4] = NAN;
  refused(&d, rest, 3, MR_STAGE_ERR_VALUE, "point 1 starts at NaN");
}

/* Every def in a stage def is made by its maker, down to the models'
 * materials, the spots and the cameras: one filled by hand (its cookie 0)
 * is refused by name, and the same def from the maker is taken. */
static void a_stage_def_holding_a_def_not_from_its_maker_is_refused(void **state) {
  (void)state;
  double rest[6] = { 0, 0, 0, 1, 0, 0 };
  mr_model_def m = mr_default_model_def();
  m.particles[0] = 1;
  m.n_materials = 2;
  mr_stage_def d = mr_default_stage_def();
  d.models = &m;
  d.n_models = 1;
  d.lights.n_spots = 2;
  d.n_cameras = 1;
  mr_stage *s = NULL;
  assert_int_equal(mr_stage_create(&d, rest, 2, &s, NULL, 0), MR_STAGE_OK);
  mr_stage_destroy(s);
  m.cookie = 0;
  refused(&d, rest, 2, MR_STAGE_ERR_ARG, "mr_default_model_def");
  m.cookie = MR_DEF_COOKIE;
  m.materials[1].cookie = 0;
  refused(&d, rest, 2, MR_STAGE_ERR_ARG, "material 1 was not made by mr_default_material_def");
  m.materials[1] = mr_default_material_def();
  d.lights.spots[1].cookie = 0;
  refused(&d, rest, 2, MR_STAGE_ERR_ARG, "spot 1 was not made by mr_default_spot_def");
  d.lights.spots[1] = mr_default_spot_def();
  memset(&d.cameras[0], 0, sizeof d.cameras[0]);
  refused(&d, rest, 2, MR_STAGE_ERR_ARG, "camera 0 was not made by mr_default_camera_def");
}

static void the_stage_keeps_its_own_copy_of_the_def(void **state) {
  (void)state;
  double rest[6] = { 0, 0, 0, 1, 0, 0 };
  mr_model_def m = mr_default_model_def();
  m.particles[0] = 1;
  int strings[2] = { 0, 1 };
  mr_stage_def d = mr_default_stage_def();
  d.models = &m;
  d.n_models = 1;
  d.strings = strings;
  d.n_strings = 1;
  mr_stage *s = NULL;
  assert_int_equal(mr_stage_create(&d, rest, 2, &s, NULL, 0), MR_STAGE_OK);
  m.particles[0] = 99;
  strings[1] = 99;
  const mr_stage_def *c = mr_stage_get_def(s);
  assert_ptr_not_equal(c->models, &m);
  assert_int_equal(c->models[0].particles[0], 1);
  assert_int_equal(c->strings[1], 1);
  const mr_draw_list *l;
  assert_int_equal(mr_stage_update(s, rest, 2, &l), MR_STAGE_OK);
  assert_int_equal(mr_stage_update(s, rest, 3, &l), MR_STAGE_ERR_ARG);
  mr_stage_destroy(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(defaults_are_the_documented_ones),
    cmocka_unit_test(names_parse_back_to_their_values),
    cmocka_unit_test(the_built_in_sky_is_fixed_unit_and_above_the_horizon),
    cmocka_unit_test(defs_naming_missing_points_are_refused_with_a_message),
    cmocka_unit_test(a_stage_def_holding_a_def_not_from_its_maker_is_refused),
    cmocka_unit_test(the_stage_keeps_its_own_copy_of_the_def),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
