/* stage.curtain and stage.follow_spot in a scene file: every key read
 * back, false and true as switches, the defaults without them, and
 * mistakes refused at their place. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "mr_scene.h"

/* One particle: a scene the stage sections can be read with. */
#define PHYS "physics: {effects: [gravity], particles: [{name: a, position: [0, 1, 0], mass: 1}]}\n"

static void load(const char *text, mr_scene *s) {
  mr_scene_error e;
  if (mr_scene_load_text("t.yaml", text, strlen(text), s, &e) != MR_SCENE_OK)
    fail_msg("%s", e.text);
}

static void expect_error(const char *text, const char *expected) {
  mr_scene s;
  mr_scene_error e;
  if (mr_scene_load_text("t.yaml", text, strlen(text), &s, &e) == MR_SCENE_OK) {
    mr_scene_free(&s);
    fail_msg("loaded, expected: %s", expected);
  }
  if (strcmp(e.text, expected) != 0) fail_msg("got      %s\nexpected %s", e.text, expected);
}

static void the_curtain_and_the_follow_spot_keys_are_read_back(void **state) {
  (void)state;
  mr_scene s;
  load(PHYS "stage:\n"
            "  curtain: {color: [0.1, 0.2, 0.3], open: 2.5, close: 0.5, distance: 1.2,\n"
            "            width: 3, height: 2.2}\n"
            "  follow_spot: {position: [1, 4, 5], angle: 10, color: [0.9, 0.8, 0.7],\n"
            "                intensity: 2}\n",
       &s);
  const mr_curtain_def *c = &s.stage.curtain;
  assert_true(c->show);
  assert_true(c->color[0] == 0.1f && c->color[1] == 0.2f && c->color[2] == 0.3f);
  assert_true(c->open_s == 2.5 && c->close_s == 0.5 && c->distance == 1.2);
  assert_true(c->width == 3 && c->height == 2.2);
  const mr_follow_spot_def *f = &s.stage.follow_spot;
  assert_true(f->show);
  assert_true(f->position[0] == 1 && f->position[1] == 4 && f->position[2] == 5);
  assert_true(f->angle_deg == 10 && f->intensity == 2);
  assert_true(f->color[0] == 0.9f && f->color[2] == 0.7f);
  mr_scene_free(&s);
}

static void without_them_the_curtain_is_on_and_the_follow_spot_off(void **state) {
  (void)state;
  mr_scene s;
  load(PHYS, &s);
  assert_true(s.stage.curtain.show);
  assert_true(s.stage.curtain.open_s == 1.5 && s.stage.curtain.close_s == 1.5);
  assert_false(s.stage.follow_spot.show);
  mr_scene_free(&s);
  load(PHYS "stage: {curtain: false, follow_spot: true}\n", &s);
  assert_false(s.stage.curtain.show);
  assert_true(s.stage.follow_spot.show);
  mr_scene_free(&s);
  load(PHYS "stage: {curtain: {show: false, open: 3}, follow_spot: {show: false}}\n", &s);
  assert_false(s.stage.curtain.show);
  assert_true(s.stage.curtain.open_s == 3);
  assert_false(s.stage.follow_spot.show);
  mr_scene_free(&s);
}

static void curtain_and_follow_spot_mistakes_are_refused_at_their_place(void **state) {
  (void)state;
  expect_error(PHYS "stage: {curtain: {open: -1}}\n",
               "t.yaml:2:25: expected a number >= 0 for open, got -1");
  expect_error(PHYS "stage: {curtain: {open: 2e6}}\n",
               "t.yaml:2:25: expected open between 0 and 1e+06 s, got 2e+06");
  expect_error(PHYS "stage: {curtain: {width: 0}}\n",
               "t.yaml:2:26: expected a positive number for width, got 0");
  expect_error(PHYS "stage: {curtain: {colour: [1, 0, 0]}}\n",
               "t.yaml:2:19: unknown key 'colour' in stage.curtain; expected one of: show, "
               "color, open, close, distance, width, height");
  expect_error(PHYS "stage: {curtain: maybe}\n",
               "t.yaml:2:18: expected true or false for stage.curtain, got 'maybe'");
  expect_error(PHYS "stage: {follow_spot: {angle: 95}}\n",
               "t.yaml:2:30: expected angle between 0.1 and 89 °, got 95");
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(the_curtain_and_the_follow_spot_keys_are_read_back),
    cmocka_unit_test(without_them_the_curtain_is_on_and_the_follow_spot_off),
    cmocka_unit_test(curtain_and_follow_spot_mistakes_are_refused_at_their_place),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
