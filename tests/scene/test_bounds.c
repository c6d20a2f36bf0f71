/* The edges of the glove sections a scene may hold: a mapping's dead zone
 * at load, the most mappings a scene may list, puppets numbered beside
 * the scene's own particles, and a glove uid of 24 hex digits read
 * whole. Each bound is tried on both sides. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "mr_scene.h"

static void load(const char *text, mr_scene *s) {
  mr_scene_error e;
  if (mr_scene_load_text("t.yaml", text, strlen(text), s, &e) != MR_SCENE_OK)
    fail_msg("%s", e.text);
}

static void expect_error(const char *text, mr_scene_status want, const char *message) {
  mr_scene s;
  mr_scene_error e;
  mr_scene_status st = mr_scene_load_text("t.yaml", text, strlen(text), &s, &e);
  if (st == MR_SCENE_OK) mr_scene_free(&s);
  assert_int_equal(st, want);
  assert_string_equal(e.text, message);
}

#define FRAME                                                \
  "physics:\n"                                               \
  "  effects: [control]\n"                                   \
  "  particles: [{name: a, position: [0, 0, 0], mass: 1}]\n" \
  "  control:\n"                                             \
  "    pose: {position: [0, 1.25, 0]}\n"                     \
  "    points: [{name: bar, offset: [0, 0, 0]}]\n"

/* A dead zone of 0.5 (half the input either side of neutral) is read; one
 * of 0.6 is refused at its place, naming the bound, before the control
 * side ever sees it. */
static void a_dead_zone_above_half_is_refused_at_load(void **state) {
  (void)state;
  char text[1024];
  const char *axis = "mapping:\n"
                     "  - name: m\n"
                     "    axes:\n"
                     "      move_y: {channel: 3, neutral: 0.3, dead_zone: %s}\n";
  char fmt[512];
  snprintf(fmt, sizeof fmt, "%s%s", FRAME, axis);
  snprintf(text, sizeof text, fmt, "0.5");
  mr_scene s;
  load(text, &s);
  assert_true(s.mappings[0].def.axes[MR_DOF_MOVE_Y].dead_zone == 0.5);
  assert_true(s.mappings[0].def.axes[MR_DOF_MOVE_Y].neutral == 0.3);
  mr_scene_free(&s);
  snprintf(text, sizeof text, fmt, "0.6");
  expect_error(text, MR_SCENE_ERR_VALUE,
               "t.yaml:10:53: expected dead_zone between 0 and 0.5, got 0.6");
  snprintf(text, sizeof text, fmt, "1.0");
  expect_error(text, MR_SCENE_ERR_VALUE,
               "t.yaml:10:53: expected dead_zone between 0 and 0.5, got 1");
}

/* n mappings named m1..mn after FRAME. */
static void mappings(char *text, size_t size, int n) {
  size_t at = (size_t)snprintf(text, size, "%smapping:\n", FRAME);
  for (int i = 1; i <= n && at < size; i++)
    at += (size_t)snprintf(text + at, size - at, "  - {name: m%d, stuck_after: %d}\n", i, i);
}

/* A scene may list as many mappings as the control side takes
 * (MR_CONTROL_MAX_MAPPINGS, 8), the last read like the first; one more is
 * refused at the list's place, saying how many are allowed. */
static void exactly_the_most_mappings_are_read_and_one_more_is_refused(void **state) {
  (void)state;
  char text[2048];
  mappings(text, sizeof text, MR_CONTROL_MAX_MAPPINGS);
  mr_scene s;
  load(text, &s);
  assert_int_equal(s.n_mappings, MR_CONTROL_MAX_MAPPINGS);
  assert_string_equal(s.mappings[MR_CONTROL_MAX_MAPPINGS - 1].def.name, "m8");
  assert_true(s.mappings[MR_CONTROL_MAX_MAPPINGS - 1].def.stuck_after == 8);
  mr_mapping_def defs[MR_CONTROL_MAX_MAPPINGS];
  for (int i = 0; i < MR_CONTROL_MAX_MAPPINGS; i++) defs[i] = s.mappings[i].def;
  mr_control *c = NULL;
  assert_int_equal(mr_control_create(defs, MR_CONTROL_MAX_MAPPINGS, &c, NULL, 0), MR_CONTROL_OK);
  mr_control_destroy(c);
  mr_scene_free(&s);
  mappings(text, sizeof text, MR_CONTROL_MAX_MAPPINGS + 1);
  expect_error(text, MR_SCENE_ERR_VALUE, "t.yaml:8:3: expected at most 8 mappings, got 9");
}

#define PUPPET(name, x)                                        \
  "    - name: " name "\n"                                     \
  "      offset: [" x ", 0, 0]\n"                              \
  "      particles:\n"                                         \
  "        - {name: head, position: [0, 1.5, 0], mass: 0.5}\n" \
  "        - {name: body, position: [0, 1.1, 0], mass: 1.0}\n"

/* The scene's own particles are puppet 0, so the puppets beside them are
 * 1 and 2; without particles of its own the puppets are 0 and 1. */
static void puppets_beside_the_scenes_own_particles_are_numbered_after_them(void **state) {
  (void)state;
  static const char with_own[] = "physics:\n"
                                 "  effects: [gravity]\n"
                                 "  particles: [{name: lamp, position: [0, 3, 0], mass: 2}]\n"
                                 "  puppets:\n" PUPPET("alice", "-1") PUPPET("bob", "1");
  mr_scene s;
  load(with_own, &s);
  assert_int_equal(s.n_particles, 5);
  assert_int_equal(s.puppets[0].id, 1);
  assert_int_equal(s.puppets[1].id, 2);
  static const int own[5] = { 0, 1, 1, 2, 2 };
  for (int i = 0; i < 5; i++) {
    if (s.particles[i].def.puppet != own[i])
      fail_msg("%s is in puppet %d, expected %d", s.particles[i].name, s.particles[i].def.puppet,
               own[i]);
  }
  mr_scene_free(&s);
  static const char alone[] = "physics:\n"
                              "  effects: [gravity]\n"
                              "  puppets:\n" PUPPET("alice", "-1") PUPPET("bob", "1");
  load(alone, &s);
  assert_int_equal(s.puppets[0].id, 0);
  assert_int_equal(s.puppets[1].id, 1);
  assert_int_equal(s.particles[3].def.puppet, 1);
  mr_scene_free(&s);
}

/* A uid of 24 hex digits is the glove's whole uid, three words, first
 * word first: two that differ only in the last digit bind different
 * gloves. One of 8 digits is the first word alone. */
static void a_24_digit_glove_uid_is_read_whole(void **state) {
  (void)state;
  char text[1024];
  const char *glove = "    glove: {uid: %s}\n";
  char fmt[512];
  snprintf(fmt, sizeof fmt, "%s%s", FRAME, glove);
  mr_scene a, b;
  snprintf(text, sizeof text, fmt, "0x00c0ffee12345678abcdef01");
  load(text, &a);
  snprintf(text, sizeof text, fmt, "00C0FFEE12345678ABCDEF02");
  load(text, &b);
  const mr_scene_glove_bind *ga = &a.frames[0].glove, *gb = &b.frames[0].glove;
  assert_int_equal(ga->by, MR_SCENE_BIND_UID);
  assert_int_equal(ga->uid_words, 3);
  assert_int_equal(gb->uid_words, 3);
  assert_true(ga->uid[0] == 0x00c0ffeeu && ga->uid[1] == 0x12345678u && ga->uid[2] == 0xabcdef01u);
  assert_true(gb->uid[0] == 0x00c0ffeeu && gb->uid[1] == 0x12345678u && gb->uid[2] == 0xabcdef02u);
  mr_scene_free(&a);
  mr_scene_free(&b);
  snprintf(text, sizeof text, fmt, "abcdef01");
  load(text, &a);
  assert_int_equal(a.frames[0].glove.uid_words, 1);
  assert_true(a.frames[0].glove.uid[0] == 0xabcdef01u);
  mr_scene_free(&a);
  snprintf(text, sizeof text, fmt, "00c0ffee12345678abcdef0");
  expect_error(text, MR_SCENE_ERR_VALUE,
               "t.yaml:7:18: expected a glove uid of 8 or 24 hex digits (as marionette "
               "list-ports prints it), got '00c0ffee12345678abcdef0'");
}

/* A scene may bind up to 64 gloves by order: the 64th is read (0-based
 * 63) and a 65th is refused at its place. */
static void glove_order_64_is_read_and_65_is_refused(void **state) {
  (void)state;
  char text[1024];
  const char *glove = "    glove: {order: %s}\n";
  char fmt[512];
  snprintf(fmt, sizeof fmt, "%s%s", FRAME, glove);
  mr_scene s;
  snprintf(text, sizeof text, fmt, "64");
  load(text, &s);
  assert_int_equal(s.frames[0].glove.by, MR_SCENE_BIND_ORDER);
  assert_int_equal(s.frames[0].glove.order, 63);
  mr_scene_free(&s);
  snprintf(text, sizeof text, fmt, "65");
  expect_error(text, MR_SCENE_ERR_VALUE,
               "t.yaml:7:20: expected order between 1 and 64 (the first glove is 1), got 65");
}

/* A glove is told which mapping to use by name, so a name may be given
 * once: the second of two mappings that share one is refused at its
 * name, whether or not another mapping lies between them. */
static void a_mapping_name_given_twice_is_refused(void **state) {
  (void)state;
  expect_error(FRAME "mapping: [{name: m}, {name: m}]\n", MR_SCENE_ERR_VALUE,
               "t.yaml:7:29: expected a unique mapping name, 'm' is already declared");
  expect_error(FRAME "mapping: [{name: m}, {name: n}, {name: m}]\n", MR_SCENE_ERR_VALUE,
               "t.yaml:7:40: expected a unique mapping name, 'm' is already declared");
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_dead_zone_above_half_is_refused_at_load),
    cmocka_unit_test(exactly_the_most_mappings_are_read_and_one_more_is_refused),
    cmocka_unit_test(puppets_beside_the_scenes_own_particles_are_numbered_after_them),
    cmocka_unit_test(a_24_digit_glove_uid_is_read_whole),
    cmocka_unit_test(glove_order_64_is_read_and_65_is_refused),
    cmocka_unit_test(a_mapping_name_given_twice_is_refused),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
