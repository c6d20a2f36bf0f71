/* Puppets as units (physics.puppets): qualified names, placement, each
 * puppet's own mass for the §6.2 forces, and collision between puppets
 * as an effect a scene lists. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mr_scene.h"
#include "mr_scene_world.h"

static void load(const char *text, mr_scene *s) {
  mr_scene_error e;
  mr_scene_status st = mr_scene_load_text("t.yaml", text, strlen(text), s, &e);
  if (st != MR_SCENE_OK) fail_msg("%s", e.text);
}

static void expect_error(const char *text, const char *expected) {
  mr_scene s;
  mr_scene_error e;
  mr_scene_status st = mr_scene_load_text("t.yaml", text, strlen(text), &s, &e);
  if (st == MR_SCENE_OK) mr_scene_free(&s);
  assert_int_not_equal(st, MR_SCENE_OK);
  assert_string_equal(e.text, expected);
}

/* One puppet's design: a head carried by antigravity on a string, a body
 * hanging from it. %s: its name, %g: its x, then the bar it hangs from. */
#define DESIGN                                                 \
  "    - name: %s\n"                                           \
  "      offset: [%g, 0, 0]\n"                                 \
  "      particles:\n"                                         \
  "        - {name: head, position: [0, 1.5, 0], mass: 0.5}\n" \
  "        - {name: body, position: [0, 1.1, 0], mass: 1.0}\n" \
  "      constraints: [{between: [head, body]}]\n"             \
  "      strings: [{from: %s, to: head}]\n"                    \
  "      antigravity: [{acted: head, trigger: %s, fraction: %g}]\n"

#define HEAD                                                                                \
  "physics:\n"                                                                              \
  "  effects: [gravity, constraints, strings, antigravity, control]\n"                      \
  "  control:\n"                                                                            \
  "    pose: {position: [0, 2, 0]}\n"                                                       \
  "    points: [{name: bar_a, offset: [-0.5, 0, 0]}, {name: bar_b, offset: [0.5, 0, 0]}]\n" \
  "  puppets:\n"

static void names_are_qualified_and_puppets_placed(void **state) {
  (void)state;
  char text[2048];
  snprintf(text, sizeof text, HEAD DESIGN DESIGN, "alice", -0.5, "bar_a", "bar_a", 1.0, "bob", 0.5,
           "bar_b", "bar_b", 1.0);
  mr_scene s;
  load(text, &s);
  assert_int_equal(s.n_puppets, 2);
  assert_int_equal(s.n_particles, 4);
  assert_string_equal(s.particles[0].name, "alice.head");
  assert_string_equal(s.particles[3].name, "bob.body");
  assert_true(s.particles[0].def.position[0] == -0.5);
  assert_true(s.particles[3].def.position[0] == 0.5);
  /* No particles of the scene's own: the puppets are 0 and 1. */
  assert_int_equal(s.particles[1].def.puppet, 0);
  assert_int_equal(s.particles[2].def.puppet, 1);
  assert_int_equal((int)s.puppets[1].first, 2);
  assert_int_equal((int)s.puppets[1].count, 2);
  /* "head" inside bob is bob's head. */
  assert_int_equal(s.n_distances, 2);
  assert_int_equal(s.distances[1].def.a, 2);
  assert_int_equal(s.distances[1].def.b, 3);
  assert_int_equal(s.n_forces, 4);
  mr_scene_free(&s);
}

/* The height of particle `name` after `t` seconds. */
static double height_after(const char *text, const char *name, double t) {
  mr_scene s;
  load(text, &s);
  mr_scene_world sw;
  mr_scene_error e;
  assert_int_equal(mr_scene_build(&s, &sw, &e), MR_SCENE_OK);
  mr_status st = mr_world_step_to(sw.world, t, NULL);
  assert_true(st == MR_OK || st == MR_DEPENDENT);
  size_t i = mr_scene_find_particle(&s, name);
  assert_true(i != (size_t)-1);
  double x[3];
  assert_int_equal(mr_world_particle_state(sw.world, sw.particle_ids[i], x, NULL), MR_OK);
  mr_scene_world_free(&sw);
  mr_scene_free(&s);
  return x[1];
}

/* §6.2: "the mass of the entire puppet" is the puppet's, so a second
 * puppet in the scene changes nothing about the first. Carried at 1.2
 * times its weight, a puppet alone and the same puppet beside another rise
 * alike; with the scene's whole mass it rose ten times as far. */
static void each_puppet_carries_its_own_mass(void **state) {
  (void)state;
  char one[2048], two[2048];
  snprintf(one, sizeof one, HEAD DESIGN, "alice", -0.5, "bar_a", "bar_a", 1.2);
  snprintf(two, sizeof two, HEAD DESIGN DESIGN, "alice", -0.5, "bar_a", "bar_a", 1.2, "bob", 0.5,
           "bar_b", "bar_b", 1.2);
  double alone = height_after(one, "alice.head", 3.0);
  double beside = height_after(two, "alice.head", 3.0);
  assert_true(alone > 1.5 + 0.01); /* it does rise */
  assert_true(fabs(alone - beside) < 1e-9);
}

/* Two puppets thrown at each other at 5 m/s each: with puppet_collision
 * listed their sphere trees meet and they bounce apart; without it they
 * pass through each other. */
static void puppet_collision_is_an_effect_a_scene_lists(void **state) {
  (void)state;
  static const char *const fmt =
      "physics:\n"
      "  effects: [constraints%s]\n"
      "  puppets:\n"
      "    - name: a\n"
      "      particles:\n"
      "        - {name: p, position: [-0.3, 1, 0], velocity: [5, 0, 0], mass: 1}\n"
      "        - {name: q, position: [-0.3, 1.3, 0], velocity: [5, 0, 0], mass: 1}\n"
      "      constraints: [{between: [p, q]}]\n"
      "      parts: [{particles: [p, q], radius: 0.05, segment_spheres: 3}]\n"
      "    - name: b\n"
      "      particles:\n"
      "        - {name: p, position: [0.3, 1.05, 0], velocity: [-5, 0, 0], mass: 1}\n"
      "        - {name: q, position: [0.3, 1.35, 0], velocity: [-5, 0, 0], mass: 1}\n"
      "      constraints: [{between: [p, q]}]\n"
      "      parts: [{particles: [p, q], radius: 0.05, segment_spheres: 3}]\n";
  char text[2048];
  for (int with = 0; with < 2; with++) {
    snprintf(text, sizeof text, fmt,
             with ? ", self_collision, puppet_collision" : ", self_collision");
    mr_scene s;
    load(text, &s);
    mr_scene_world sw;
    mr_scene_error e;
    assert_int_equal(mr_scene_build(&s, &sw, &e), MR_SCENE_OK);
    assert_true(mr_world_step_to(sw.world, 0.2, NULL) >= 0);
    double a[3], b[3];
    mr_world_particle_state(sw.world, 0, a, NULL);
    mr_world_particle_state(sw.world, 2, b, NULL);
    if (with)
      assert_true(a[0] < b[0] - 0.1); /* bounced: each on its own side */
    else
      assert_true(a[0] > b[0] + 0.5); /* passed through */
    assert_int_equal(mr_world_pass_calls(sw.world, MR_PASS_PUPPET_COLLISION) > 0, with);
    mr_scene_world_free(&sw);
    mr_scene_free(&s);
  }
}

static void puppet_errors_name_the_place(void **state) {
  (void)state;
  static const char *const base = "physics:\n"
                                  "  effects: [gravity]\n"
                                  "  puppets:\n"
                                  "    - name: a\n"
                                  "      particles: [{name: p, position: [0, 1, 0], mass: 1}]\n";
  char text[1024];
  snprintf(text, sizeof text, "%s%s", base,
           "    - name: a\n      particles: [{name: p, position: [1, 1, 0], mass: 1}]\n");
  expect_error(text, "t.yaml:6:13: expected a unique puppet name, 'a' is already declared");
  expect_error("physics:\n  effects: [gravity]\n  puppets:\n    - name: a.b\n"
               "      particles: [{name: p, position: [0, 1, 0], mass: 1}]\n",
               "t.yaml:4:13: expected a puppet name without '.', got 'a.b': '.' joins a puppet's "
               "name to its parts'");
  snprintf(text, sizeof text, "%s%s", base, "      legs: 2\n");
  expect_error(text, "t.yaml:6:7: unknown key 'legs' in a puppet; expected one of: name, offset, "
                     "particles, constraints, groups, parts, control, springs, strings, "
                     "sine_springs, "
                     "antigravity, triggered");
  expect_error("physics:\n  effects: [gravity]\n  puppets: []\n",
               "t.yaml:3:12: expected at least one puppet");
  /* A name resolves inside its own puppet first, then as written: a bare
   * name of another puppet's particle is unknown. */
  static const char *const cross = "physics:\n"
                                   "  effects: [springs]\n"
                                   "  puppets:\n"
                                   "    - name: a\n"
                                   "      particles: [{name: p, position: [0, 1, 0], mass: 1}]\n"
                                   "    - name: b\n"
                                   "      particles: [{name: q, position: [1, 1, 0], mass: 1}]\n"
                                   "      springs: [{between: [q, %s]}]\n";
  snprintf(text, sizeof text, cross, "p");
  expect_error(text, "t.yaml:8:31: expected the name of a particle or control point, got 'p'");
  snprintf(text, sizeof text, cross, "a.p");
  mr_scene s;
  load(text, &s);
  assert_int_equal(s.forces[0].def.spring.b, 0);
  mr_scene_free(&s);
  /* Places are compared across puppets, after the offset. */
  expect_error("physics:\n  effects: [gravity]\n  puppets:\n"
               "    - {name: a, particles: [{name: p, position: [0, 1, 0], mass: 1}]}\n"
               "    - {name: b, offset: [-1, 0, 0], particles: [{name: p, position: [1, 1, 0], "
               "mass: 1}]}\n",
               "t.yaml:5:49: particle 'b.p' coincides with particle 'a.p' (line 4); expected "
               "distinct positions");
}

/* A puppet's own control frame: its points named with it and placed with
 * its offset, its binding to a glove read, and built as a frame of its own
 * that moves its points alone. */
#define OWN_FRAME                                                       \
  "physics:\n"                                                          \
  "  effects: [gravity, constraints, strings, control]\n"               \
  "  puppets:\n"                                                        \
  "    - name: alice\n"                                                 \
  "      offset: [-1, 0, 0]\n"                                          \
  "      particles: [{name: head, position: [0, 1, 0], mass: 1}]\n"     \
  "      control:\n"                                                    \
  "        glove: %s\n"                                                 \
  "        pose: {position: [0, 2, 0]}\n"                               \
  "        points: [{name: bar, offset: [0, 0, 0]}]\n"                  \
  "        track: {keyframes: [{t: 0}, {t: 1, position: [0, 2, 1]}]}\n" \
  "      strings: [{from: bar, to: head}]\n"                            \
  "    - name: bob\n"                                                   \
  "      offset: [1, 0, 0]\n"                                           \
  "      particles: [{name: head, position: [0, 1, 0], mass: 1}]\n"     \
  "      control:\n"                                                    \
  "        points: [{name: bar, offset: [0, 0.5, 0]}]\n"                \
  "      strings: [{from: bar, to: head}]\n"

static void each_puppet_has_its_own_control_frame(void **state) {
  (void)state;
  char text[2048];
  snprintf(text, sizeof text, OWN_FRAME, "{hand: left}");
  mr_scene s;
  load(text, &s);
  assert_int_equal(s.n_frames, 2);
  assert_int_equal(s.n_control_points, 2);
  assert_string_equal(s.control_points[0].name, "alice.bar");
  assert_string_equal(s.control_points[1].name, "bob.bar");
  assert_int_equal((int)s.control_points[1].frame, 1);
  assert_string_equal(s.frames[0].puppet, "alice");
  assert_true(s.frames[0].pose.position[0] == -1 && s.frames[0].pose.position[1] == 2);
  assert_true(s.frames[1].pose.position[0] == 1 && s.frames[1].pose.position[1] == 0);
  assert_int_equal(s.frames[0].glove.by, MR_SCENE_BIND_HAND);
  assert_int_equal(s.frames[0].glove.hand, 0);
  /* Unbound: the second frame takes the second glove. */
  assert_int_equal(s.frames[1].glove.by, MR_SCENE_BIND_ORDER);
  assert_int_equal(s.frames[1].glove.order, 1);
  /* Strings name their own puppet's bar: control ids 2 and 3. */
  assert_int_equal(s.forces[0].def.string.frame_particle, 2);
  assert_int_equal(s.forces[1].def.string.frame_particle, 3);
  mr_pose p;
  mr_scene_frame_pose_at(&s, 0, 1.0, &p); /* the track moves with the puppet */
  assert_true(p.position[0] == -1 && p.position[2] == 1);
  mr_scene_world sw;
  mr_scene_error e;
  assert_int_equal(mr_scene_build(&s, &sw, &e), MR_SCENE_OK);
  assert_int_equal(sw.n_frames, 2);
  mr_pose to = mr_pose_identity();
  to.position[1] = 3;
  assert_int_equal(mr_world_set_frame_target(sw.world, sw.frames[1], &to, 0.5), MR_OK);
  mr_status st = mr_world_step_to(sw.world, 0.5, NULL);
  assert_true(st == MR_OK || st == MR_DEPENDENT);
  double a[3], b[3];
  mr_world_particle_state(sw.world, sw.control_ids[0], a, NULL);
  mr_world_particle_state(sw.world, sw.control_ids[1], b, NULL);
  assert_true(fabs(b[1] - 3.5) < 1e-9); /* bob's bar went with bob's frame */
  assert_true(fabs(a[1] - 2.0) < 1e-9); /* alice's stayed with hers */
  mr_scene_world_free(&sw);
  mr_scene_free(&s);

  snprintf(text, sizeof text, OWN_FRAME, "{uid: 0x1234abcd}");
  load(text, &s);
  assert_int_equal(s.frames[0].glove.by, MR_SCENE_BIND_UID);
  assert_int_equal(s.frames[0].glove.uid_words, 1);
  assert_true(s.frames[0].glove.uid[0] == 0x1234abcdu);
  mr_scene_free(&s);
  snprintf(text, sizeof text, OWN_FRAME, "{order: 2}");
  load(text, &s);
  assert_int_equal(s.frames[0].glove.order, 1);
  mr_scene_free(&s);
}

static void glove_bindings_refuse_what_they_cannot_mean(void **state) {
  (void)state;
  char text[2048];
  snprintf(text, sizeof text, OWN_FRAME, "{uid: 12ab}");
  expect_error(text, "t.yaml:8:22: expected a glove uid of 8 or 24 hex digits (as marionette "
                     "list-ports prints it), got '12ab'");
  snprintf(text, sizeof text, OWN_FRAME, "{hand: left, order: 1}");
  expect_error(text, "t.yaml:8:16: expected one of order, uid or hand in control.glove, got 2 "
                     "keys");
  snprintf(text, sizeof text, OWN_FRAME, "{order: 0}");
  expect_error(text, "t.yaml:8:24: expected order between 1 and 64 (the first glove is 1), got 0");
  snprintf(text, sizeof text, OWN_FRAME, "{hand: middle}");
  expect_error(text, "t.yaml:8:23: expected hand left or right");
  snprintf(text, sizeof text, OWN_FRAME, "{foot: left}");
  expect_error(text, "t.yaml:8:17: unknown key 'foot' in control.glove; expected one of: order, "
                     "uid, hand");
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(names_are_qualified_and_puppets_placed),
    cmocka_unit_test(each_puppet_carries_its_own_mass),
    cmocka_unit_test(puppet_collision_is_an_effect_a_scene_lists),
    cmocka_unit_test(puppet_errors_name_the_place),
    cmocka_unit_test(each_puppet_has_its_own_control_frame),
    cmocka_unit_test(glove_bindings_refuse_what_they_cannot_mean),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
