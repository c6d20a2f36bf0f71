/* The theater's set in a scene file (stage.proscenium, .wings,
 * .footlights, .bridge, floor.board): on by default and sized from the
 * show, every key read back, every mistake refused at its
 * file:line:column. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "mr_scene.h"
#include "mr_stage.h"

/* A puppet of two particles under a bar of two points, 0.6 m across. */
#define SHOW                                                                        \
  "physics:\n"                                                                      \
  "  effects: [gravity, constraints, strings, control]\n"                           \
  "  particles:\n"                                                                  \
  "    - {name: head, position: [0, 1.0, 0], mass: 0.2}\n"                          \
  "    - {name: feet, position: [0, 0.3, 0], mass: 0.2}\n"                          \
  "  constraints: [{between: [head, feet]}]\n"                                      \
  "  control:\n"                                                                    \
  "    pose: {position: [0, 1.6, 0]}\n"                                             \
  "    points: [{name: l, offset: [-0.3, 0, 0]}, {name: r, offset: [0.3, 0, 0]}]\n" \
  "  strings: [{from: l, to: head}, {from: r, to: head}]\n"

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

/* A scene that says nothing of the set has all of it but the bridge,
 * with the opening sized about the show: wider than the bar with room,
 * taller than the bar, in front of the puppet, centred on it. */
static void a_scene_has_the_set_by_default_sized_to_hold_its_show(void **state) {
  (void)state;
  mr_scene s;
  load(SHOW, &s);
  const mr_stage_def *d = &s.stage;
  assert_true(d->proscenium && d->wings && d->footlights && !d->bridge);
  assert_true(d->board_width == 0.16 && d->footlight_intensity == 1);
  /* Dark red, gold, near black, warm. */
  assert_true(d->proscenium_color[0] > 4 * d->proscenium_color[1]);
  assert_true(d->trim_color[0] > d->trim_color[1] && d->trim_color[1] > d->trim_color[2]);
  assert_true(d->wing_color[0] < 0.05f && d->footlight_color[0] > d->footlight_color[2]);
  /* The bar reaches 0.3 m each side and 1.6 m up. */
  assert_true(d->set_width >= 0.6 + 2 * 0.25 && d->set_height >= 1.6 + 0.25);
  assert_true(d->set_width >= 1.25 * d->set_height - 1e-9);
  assert_true(fabs(d->set_middle) < 1e-9 && d->set_front >= 0.3);
  mr_scene_free(&s);
  /* Turned: the audience sits on +x; the opening is in front of the
   * show along +x. */
  load(SHOW "camera: {facing: 90}\n", &s);
  assert_true(s.stage.set_front >= 0.3 && s.stage.set_width >= 1.1);
  mr_scene_free(&s);
}

static void every_set_key_is_read_back(void **state) {
  (void)state;
  mr_scene s;
  load(SHOW "stage:\n"
            "  floor: {board: 0.25, color: [0.5, 0.3, 0.2]}\n"
            "  proscenium: {width: 2.5, height: 1.8, distance: 0.7, middle: 0.2,\n"
            "               color: [0.2, 0, 0], trim: [0.9, 0.8, 0.1]}\n"
            "  wings: {color: [0.1, 0.1, 0.2]}\n"
            "  footlights: {color: [1, 0.5, 0.25], intensity: 2.5}\n"
            "  bridge: true\n",
       &s);
  const mr_stage_def *d = &s.stage;
  assert_true(d->floor && d->board_width == 0.25 && d->floor_color[0] == 0.5f);
  assert_true(d->proscenium && d->set_width == 2.5 && d->set_height == 1.8);
  assert_true(d->set_front == 0.7 && d->set_middle == 0.2);
  assert_true(d->proscenium_color[0] == 0.2f && d->trim_color[1] == 0.8f);
  assert_true(d->wings && d->wing_color[2] == 0.2f);
  assert_true(d->footlights && d->footlight_color[1] == 0.5f && d->footlight_intensity == 2.5);
  assert_true(d->bridge);
  mr_scene_free(&s);
  load(SHOW "stage: {proscenium: false, wings: false, footlights: false, bridge: false}\n", &s);
  assert_true(!s.stage.proscenium && !s.stage.wings && !s.stage.footlights && !s.stage.bridge);
  mr_scene_free(&s);
  /* A mapping turns a part on. */
  load(SHOW "stage: {proscenium: {color: [0.3, 0, 0]}, footlights: {intensity: 0}}\n", &s);
  assert_true(s.stage.proscenium && s.stage.footlights && s.stage.footlight_intensity == 0);
  assert_true(s.stage.set_width > 0);
  mr_scene_free(&s);
}

static void set_mistakes_are_refused_at_their_place(void **state) {
  (void)state;
  static const struct {
    const char *text, *error;
  } cases[] = {
    { SHOW "stage: {proscenium: {width: -1}}\n",
      "t.yaml:11:29: expected a positive number for width, got -1" },
    { SHOW "stage: {proscenium: {colour: [1, 0, 0]}}\n",
      "t.yaml:11:22: unknown key 'colour' in stage.proscenium; expected one of: width, height, "
      "distance, middle, color, trim" },
    { SHOW "stage: {proscenium: maybe}\n",
      "t.yaml:11:21: expected true or false for stage.proscenium, got 'maybe'" },
    { SHOW "stage: {wings: {color: [1, 0]}}\n",
      "t.yaml:11:24: expected [x, y, z] (three numbers) for color, got a sequence of 2 items" },
    { SHOW "stage: {footlights: {intensity: -2}}\n",
      "t.yaml:11:33: expected a number >= 0 for intensity, got -2" },
    { SHOW "stage: {bridge: {on: true}}\n",
      "t.yaml:11:17: expected true or false for bridge, got a mapping" },
    { SHOW "stage: {floor: {board: 0}}\n",
      "t.yaml:11:24: expected a positive number for board, got 0" },
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    expect_error(cases[i].text, cases[i].error);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_scene_has_the_set_by_default_sized_to_hold_its_show),
    cmocka_unit_test(every_set_key_is_read_back),
    cmocka_unit_test(set_mistakes_are_refused_at_their_place),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
