/* Small worlds the physics' step tests share: particles, a weight hanging
 * on a spring string from a frame, and a pendulum on a pin. Each
 * test program includes cmocka before this header. */
#ifndef MR_TEST_PHYSICS_RIGS_H
#define MR_TEST_PHYSICS_RIGS_H

#include <math.h>

#include "mr_physics.h"

static inline int particle(mr_world *w, double x, double y, double z, double mass, int frame) {
  mr_particle_def p = mr_default_particle_def();
  p.position[0] = x;
  p.position[1] = y;
  p.position[2] = z;
  p.mass = mass;
  p.frame = frame;
  int id = -1;
  assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
  return id;
}

/* A control frame at (0, 2, 0) with one point, and a particle hanging from
 * it on a string of rest length `rest` (k, c given). */
static inline mr_world *hanging(mr_world_def def, double mass, double rest, double k, double c,
                                double start[3], int *bob) {
  def.effects |= MR_EFFECT_FRAMES | MR_EFFECT_STRINGS;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  mr_frame_def f = mr_default_frame_def();
  f.pose.position[1] = 2.0;
  int frame;
  assert_int_equal(mr_world_add_frame(w, &f, &frame), MR_OK);
  int bar = particle(w, 0, 2, 0, 1, frame);
  *bob = particle(w, start[0], start[1], start[2], mass, -1);
  mr_string_def s = mr_default_string_def();
  s.frame_particle = bar;
  s.puppet_particle = *bob;
  s.rest_length = rest;
  s.mode = MR_STRING_SPRING;
  s.stiffness = k;
  s.damping = c;
  assert_int_equal(mr_world_add_string(w, &s, NULL), MR_OK);
  return w;
}

static inline double speed_of(const mr_world *w, int id, double x[3]) {
  double v[3];
  assert_int_equal(mr_world_particle_state(w, id, x, v), MR_OK);
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* A pin at the origin and a 1 m distance to a bob at (1, 0, 0) moving at
 * `speed` m/s along z (0: released from rest), with the estimate off: the
 * deviation alone steers the step (§4.5, the paper's rule). */
static inline mr_world *pendulum(mr_world_def def, double speed, int *bob) {
  def.error_length = def.error_speed = 0.0;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  int pivot = particle(w, 0, 0, 0, 1, -1);
  *bob = particle(w, 1, 0, 0, 1, -1);
  if (speed != 0.0)
    assert_int_equal(
        mr_world_set_particle_state(w, *bob, (double[3]){ 1, 0, 0 }, (double[3]){ 0, 0, speed }),
        MR_OK);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = pivot;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  mr_distance_def d = mr_default_distance_def();
  d.a = pivot;
  d.b = *bob;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  return w;
}

#endif
