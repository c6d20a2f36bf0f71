/* The constraint rows (constraints.c): which particles each row names is
 * written once and kept between builds, and only the values are written
 * on each evaluation. What is kept must follow the constraints: one added
 * after the world has stepped takes part from its next step. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "mr_physics.h"

static int add_ball(mr_world *w, double x, double y) {
  mr_particle_def p = mr_default_particle_def();
  p.mass = 0.2;
  p.position[0] = x;
  p.position[1] = y;
  int id;
  assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
  return id;
}

static void pin(mr_world *w, int particle) {
  mr_pin_def d = mr_default_pin_def();
  d.particle = particle;
  assert_int_equal(mr_world_add_pin(w, &d, NULL), MR_OK);
}

/* A pendulum (a ball pinned at its pivot, a second on a link of 0.5 m)
 * swings for 0.2 s; then the swinging ball is pinned where it is, with a
 * third ball linked to it. For the next 0.5 s under gravity the second
 * ball stays where it was pinned (within 3 µm: it was moving there) and
 * the third hangs from it at its length. */
static void constraints_added_after_a_step_hold_from_the_next_one(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_CONSTRAINTS | MR_EFFECT_GRAVITY;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  int pivot = add_ball(w, 0.0, 1.0), bob = add_ball(w, 0.5, 1.0);
  pin(w, pivot);
  mr_distance_def link = mr_default_distance_def();
  link.a = pivot;
  link.b = bob;
  assert_int_equal(mr_world_add_distance(w, &link, NULL), MR_OK);
  assert_int_equal(mr_world_step_to(w, 0.2, NULL), MR_OK);
  double held[3], x[3], v[3];
  assert_int_equal(mr_world_particle_state(w, bob, held, v), MR_OK);
  assert_true(held[1] < 0.95); /* it swung */
  pin(w, bob);
  int tail = add_ball(w, held[0] + 0.3, held[1]);
  link.a = bob;
  link.b = tail;
  assert_int_equal(mr_world_add_distance(w, &link, NULL), MR_OK);
  /* the pivot's link is now redundant with the two pins: reported */
  mr_status s = mr_world_step_to(w, 0.7, NULL);
  assert_true(s == MR_OK || s == MR_DEPENDENT);
  assert_int_equal(mr_world_particle_state(w, bob, x, v), MR_OK);
  for (int k = 0; k < 3; k++) assert_true(fabs(x[k] - held[k]) < 1e-4);
  double t[3];
  assert_int_equal(mr_world_particle_state(w, tail, t, v), MR_OK);
  double len = sqrt((t[0] - x[0]) * (t[0] - x[0]) + (t[1] - x[1]) * (t[1] - x[1]) +
                    (t[2] - x[2]) * (t[2] - x[2]));
  assert_true(fabs(len - 0.3) < 1e-3);
  assert_true(t[1] < held[1] - 0.1); /* it fell, on its link */
  mr_world_destroy(w);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(constraints_added_after_a_step_hold_from_the_next_one),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
