/* Only declared effects exist in a world (host/physics/README.md, "Only
 * declared effects exist"). The per-pass counters show that an undeclared
 * pass never runs (not even a test per particle: its counter stays 0), that
 * declared passes do, and that an element of an undeclared effect is
 * refused when added. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mr_physics.h"

static mr_world *make(uint32_t effects) {
  mr_world_def def = mr_default_world_def();
  def.effects = effects;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  return w;
}

static int add(mr_world *w, double x, double y, double z, int frame) {
  mr_particle_def p = mr_default_particle_def();
  p.position[0] = x;
  p.position[1] = y;
  p.position[2] = z;
  p.radius = 0.05;
  p.frame = frame;
  int id = -1;
  assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
  return id;
}

static void gravity_only_world_runs_no_other_pass(void **state) {
  (void)state;
  mr_world *w = make(MR_EFFECT_GRAVITY);
  add(w, 0, 1, 0, -1);
  add(w, 1, 1, 0, -1);
  assert_int_equal(mr_world_step_to(w, 1.0, NULL), MR_OK);
  assert_true(mr_world_pass_calls(w, MR_PASS_GRAVITY) > 0);
  for (int p = 0; p < MR_PASS_COUNT; p++)
    if (p != MR_PASS_GRAVITY) assert_int_equal(mr_world_pass_calls(w, (mr_pass)p), 0);
  mr_world_destroy(w);
}

/* Constraints but no colliders: zero collision work, however many steps. */
static void world_without_colliders_does_no_collision_work(void **state) {
  (void)state;
  mr_world *w = make(MR_EFFECT_GRAVITY | MR_EFFECT_CONSTRAINTS | MR_EFFECT_DRAG);
  int a = add(w, 0, 0, 0, -1), b = add(w, 1, 0, 0, -1);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = a;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  mr_distance_def d = mr_default_distance_def();
  d.a = a;
  d.b = b;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  assert_int_equal(mr_world_step_to(w, 2.0, NULL), MR_OK);
  assert_true(mr_world_pass_calls(w, MR_PASS_CONSTRAINTS) > 0);
  assert_true(mr_world_pass_calls(w, MR_PASS_SOLVE) > 0);
  assert_true(mr_world_pass_calls(w, MR_PASS_DRAG) > 0);
  assert_int_equal(mr_world_pass_calls(w, MR_PASS_PLANES), 0);
  assert_int_equal(mr_world_pass_calls(w, MR_PASS_SELF_COLLISION), 0);
  assert_int_equal(mr_world_pass_calls(w, MR_PASS_PUPPET_COLLISION), 0);
  assert_int_equal(mr_world_pass_calls(w, MR_PASS_SPRINGS), 0);
  assert_int_equal(mr_world_pass_calls(w, MR_PASS_FRAMES), 0);
  mr_world_destroy(w);
}

static void undeclared_elements_are_refused(void **state) {
  (void)state;
  mr_world *w = make(MR_EFFECT_GRAVITY);
  int a = add(w, 0, 0, 0, -1), b = add(w, 1, 0, 0, -1);
  mr_spring_def s = mr_default_spring_def();
  s.a = a;
  s.b = b;
  assert_int_equal(mr_world_add_spring(w, &s, NULL), MR_ERR_NOT_DECLARED);
  mr_distance_def d = mr_default_distance_def();
  d.a = a;
  d.b = b;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_ERR_NOT_DECLARED);
  mr_plane_def pl = mr_default_plane_def();
  assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_ERR_NOT_DECLARED);
  int ids[2] = { a, b };
  mr_part_def part = mr_default_part_def();
  part.particles = ids;
  part.count = 2;
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_ERR_NOT_DECLARED);
  mr_frame_def fd = mr_default_frame_def();
  assert_int_equal(mr_world_add_frame(w, &fd, NULL), MR_ERR_NOT_DECLARED);
  mr_sine_spring_def ss = mr_default_sine_spring_def();
  ss.a = a;
  ss.b = b;
  assert_int_equal(mr_world_add_sine_spring(w, &ss, NULL), MR_ERR_NOT_DECLARED);
  mr_antigravity_def ag = mr_default_antigravity_def();
  ag.acted = a;
  ag.trigger = b;
  assert_int_equal(mr_world_add_antigravity(w, &ag, NULL), MR_ERR_NOT_DECLARED);
  mr_triggered_def tr = mr_default_triggered_def();
  tr.acted = a;
  tr.control = b;
  tr.trigger = a;
  assert_int_equal(mr_world_add_triggered(w, &tr, NULL), MR_ERR_NOT_DECLARED);
  assert_non_null(strstr(mr_world_last_error(w), "declare"));
  mr_world_destroy(w);
}

static double apart(mr_world *w, int a, int b) {
  double x[3], y[3];
  assert_int_equal(mr_world_particle_state(w, a, x, NULL), MR_OK);
  assert_int_equal(mr_world_particle_state(w, b, y, NULL), MR_OK);
  return sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
              (x[2] - y[2]) * (x[2] - y[2]));
}

/* Taut strings need only STRINGS: they hold their length without the
 * string-length correction, whose counter stays 0 and which does not touch
 * the world's spring string (a soft one, left stretched far past the 10 %
 * the correction would bring it back to). */
static void taut_strings_run_no_string_correction(void **state) {
  (void)state;
  mr_world *w = make(MR_EFFECT_GRAVITY | MR_EFFECT_STRINGS | MR_EFFECT_FRAMES);
  mr_frame_def fd = mr_default_frame_def();
  int frame;
  assert_int_equal(mr_world_add_frame(w, &fd, &frame), MR_OK);
  int fa = add(w, 0, 0, 0, frame), fb = add(w, 1, 0, 0, frame);
  int taut = add(w, 0, -1, 0, -1), soft = add(w, 1, -1, 0, -1);
  mr_string_def str = mr_default_string_def();
  str.frame_particle = fa;
  str.puppet_particle = taut;
  str.rest_length = 1.0;
  str.mode = MR_STRING_TAUT;
  assert_int_equal(mr_world_add_string(w, &str, NULL), MR_OK);
  str = mr_default_string_def();
  str.frame_particle = fb;
  str.puppet_particle = soft;
  str.rest_length = 1.0;
  str.mode = MR_STRING_SPRING;
  str.stiffness = 20.0; /* 1 kg hangs 0.49 m further */
  assert_int_equal(mr_world_add_string(w, &str, NULL), MR_OK);
  for (int f = 1; f <= 180; f++) {
    assert_int_equal(mr_world_step_to(w, f / 60.0, NULL), MR_OK);
    assert_true(apart(w, fa, taut) < 1.01);
  }
  assert_true(apart(w, fb, soft) > 1.2);
  assert_true(mr_world_pass_calls(w, MR_PASS_STRINGS) > 0);
  assert_true(mr_world_pass_calls(w, MR_PASS_FRAMES) > 0);
  assert_int_equal(mr_world_pass_calls(w, MR_PASS_STRING_CORRECTION), 0);
  for (int p = 0; p < MR_PASS_COUNT; p++)
    if (p != MR_PASS_STRINGS && p != MR_PASS_FRAMES && p != MR_PASS_GRAVITY && p != MR_PASS_SOLVE)
      assert_int_equal(mr_world_pass_calls(w, (mr_pass)p), 0);
  mr_world_destroy(w);
}

/* Every effect declared and present: every pass runs. */
static void every_declared_pass_runs(void **state) {
  (void)state;
  mr_world *w = make(MR_EFFECT_GRAVITY | MR_EFFECT_DRAG | MR_EFFECT_SPRINGS | MR_EFFECT_STRINGS |
                     MR_EFFECT_ANTIGRAVITY | MR_EFFECT_TRIGGERED | MR_EFFECT_SINE_SPRINGS |
                     MR_EFFECT_CONSTRAINTS | MR_EFFECT_PLANES | MR_EFFECT_SELF_COLLISION |
                     MR_EFFECT_PUPPET_COLLISION | MR_EFFECT_STRING_CORRECTION | MR_EFFECT_FRAMES);
  mr_frame_def fd = mr_default_frame_def();
  fd.pose.position[1] = 3.0;
  int frame;
  assert_int_equal(mr_world_add_frame(w, &fd, &frame), MR_OK);
  int c = add(w, 0, 3, 0, frame);
  int a = add(w, 0, 2, 0, -1), b = add(w, 0.3, 2, 0, -1), e = add(w, 0, 1.5, 0.3, -1);
  int ids[2] = { a, b };
  mr_distance_def d = mr_default_distance_def();
  d.a = a;
  d.b = b;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  mr_spring_def s = mr_default_spring_def();
  s.a = b;
  s.b = e;
  assert_int_equal(mr_world_add_spring(w, &s, NULL), MR_OK);
  mr_string_def str = mr_default_string_def();
  str.frame_particle = c;
  str.puppet_particle = a;
  str.mode = MR_STRING_SPRING; /* a force pass, corrected by the string correction */
  assert_int_equal(mr_world_add_string(w, &str, NULL), MR_OK);
  mr_antigravity_def ag = mr_default_antigravity_def();
  ag.acted = a;
  ag.trigger = e;
  assert_int_equal(mr_world_add_antigravity(w, &ag, NULL), MR_OK);
  mr_triggered_def tr = mr_default_triggered_def();
  tr.acted = a;
  tr.control = c;
  tr.trigger = e;
  assert_int_equal(mr_world_add_triggered(w, &tr, NULL), MR_OK);
  mr_sine_spring_def ss = mr_default_sine_spring_def();
  ss.a = a;
  ss.b = e;
  assert_int_equal(mr_world_add_sine_spring(w, &ss, NULL), MR_OK);
  mr_plane_def pl = mr_default_plane_def();
  assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
  mr_part_def part = mr_default_part_def();
  part.particles = ids;
  part.count = 2;
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  part.particles = &e;
  part.count = 1;
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  assert_true(mr_world_step_to(w, 1.0, NULL) >= MR_OK);
  for (int p = 0; p < MR_PASS_COUNT; p++) {
    printf("%-18s %llu\n", mr_pass_name((mr_pass)p),
           (unsigned long long)mr_world_pass_calls(w, (mr_pass)p));
    assert_true(mr_world_pass_calls(w, (mr_pass)p) > 0);
  }
  mr_world_destroy(w);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(gravity_only_world_runs_no_other_pass),
    cmocka_unit_test(world_without_colliders_does_no_collision_work),
    cmocka_unit_test(undeclared_elements_are_refused),
    cmocka_unit_test(taut_strings_run_no_string_correction),
    cmocka_unit_test(every_declared_pass_runs),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
