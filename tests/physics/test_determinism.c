/* Determinism (host/physics/README.md): the same world and the same inputs
 * give bit-identical states after N steps (the library reads no clock),
 * shown by the state hash; a perturbation of one input by one part in 10¹²
 * changes it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>

#include "mr_physics.h"

/* A marionette in miniature with every kind of work in it: a frame driven
 * through a pose sequence, strings, a rigid torso, a swinging limb, floor
 * contact, self- and puppet collision, the §6.2 forces. */
static mr_world *build(double kick) {
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_GRAVITY | MR_EFFECT_DRAG | MR_EFFECT_SPRINGS | MR_EFFECT_STRINGS |
                MR_EFFECT_ANTIGRAVITY | MR_EFFECT_TRIGGERED | MR_EFFECT_SINE_SPRINGS |
                MR_EFFECT_CONSTRAINTS | MR_EFFECT_PLANES | MR_EFFECT_SELF_COLLISION |
                MR_EFFECT_PUPPET_COLLISION | MR_EFFECT_FRAMES | MR_EFFECT_STRING_CORRECTION;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  mr_frame_def fd = mr_default_frame_def();
  fd.pose.position[1] = 2.0;
  int frame;
  assert_int_equal(mr_world_add_frame(w, &fd, &frame), MR_OK);
  mr_particle_def p = mr_default_particle_def();
  p.frame = frame;
  const double fx[3][3] = { { -0.3, 2.0, 0 }, { 0.3, 2.0, 0 }, { 0, 2.0, 0.3 } };
  int f[3];
  for (int i = 0; i < 3; i++) {
    for (int k = 0; k < 3; k++) p.position[k] = fx[i][k];
    assert_int_equal(mr_world_add_particle(w, &p, &f[i]), MR_OK);
  }
  const double bx[6][3] = { { -0.2, 1.2, 0 }, { 0.2, 1.2, 0 },  { 0, 1.2, 0.2 },
                            { 0, 0.9, 0.05 }, { -0.2, 0.6, 0 }, { 0.2, 0.6, 0 } };
  int b[6];
  p = mr_default_particle_def();
  p.radius = 0.06;
  for (int i = 0; i < 6; i++) {
    for (int k = 0; k < 3; k++) p.position[k] = bx[i][k];
    p.velocity[0] = i == 4 ? kick : 0.0;
    assert_int_equal(mr_world_add_particle(w, &p, &b[i]), MR_OK);
  }
  mr_rigid_group_def g = mr_default_rigid_group_def();
  g.particles = b;
  g.count = 4;
  assert_int_equal(mr_world_add_rigid_group(w, &g, NULL), MR_OK);
  mr_distance_def d = mr_default_distance_def();
  d.a = b[3];
  d.b = b[4];
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  mr_spring_def s = mr_default_spring_def();
  s.a = b[3];
  s.b = b[5];
  assert_int_equal(mr_world_add_spring(w, &s, NULL), MR_OK);
  for (int i = 0; i < 3; i++) {
    mr_string_def str = mr_default_string_def();
    str.frame_particle = f[i];
    str.puppet_particle = b[i];
    assert_int_equal(mr_world_add_string(w, &str, NULL), MR_OK);
  }
  mr_antigravity_def ag = mr_default_antigravity_def();
  ag.acted = b[0];
  ag.trigger = b[3];
  ag.fraction = 0.2;
  assert_int_equal(mr_world_add_antigravity(w, &ag, NULL), MR_OK);
  mr_triggered_def tr = mr_default_triggered_def();
  tr.acted = b[1];
  tr.control = f[1];
  tr.trigger = b[1];
  tr.gain = 1.0;
  assert_int_equal(mr_world_add_triggered(w, &tr, NULL), MR_OK);
  mr_sine_spring_def ss = mr_default_sine_spring_def();
  ss.a = b[2];
  ss.b = b[5];
  assert_int_equal(mr_world_add_sine_spring(w, &ss, NULL), MR_OK);
  mr_plane_def pl = mr_default_plane_def();
  assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
  mr_part_def part = mr_default_part_def();
  part.particles = b;
  part.count = 4;
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  part.particles = &b[4];
  part.count = 1;
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  part.particles = &b[5];
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  return w;
}

/* The puppeteer's hand: 240 frames at 60 fps of a swaying, dipping pose. */
static uint64_t run(mr_world *w) {
  int frame = 0;
  for (int i = 1; i <= 240; i++) {
    double t = i / 60.0;
    mr_pose pose = mr_pose_identity();
    pose.position[0] = 0.4 * sin(3.0 * t);
    pose.position[1] = 2.0 + 0.3 * sin(5.0 * t);
    double a = 0.3 * sin(2.0 * t);
    pose.orientation[0] = cos(a / 2);
    pose.orientation[2] = sin(a / 2);
    assert_int_equal(mr_world_set_frame_target(w, frame, &pose, t), MR_OK);
    assert_true(mr_world_step_to(w, t, NULL) >= MR_OK);
  }
  return mr_world_state_hash(w);
}

static void same_inputs_give_identical_hash(void **state) {
  (void)state;
  mr_world *a = build(0.5), *b = build(0.5), *c = build(0.5 * (1 + 1e-12));
  uint64_t h0 = mr_world_state_hash(a);
  uint64_t ha = run(a), hb = run(b), hc = run(c);
  mr_stats st;
  mr_world_stats(a, &st);
  printf("hash after %llu steps: %016llx (twin %016llx, perturbed %016llx), collisions %llu\n",
         (unsigned long long)st.steps, (unsigned long long)ha, (unsigned long long)hb,
         (unsigned long long)hc, (unsigned long long)st.collisions);
  assert_true(ha == hb);
  assert_true(ha != hc);
  assert_true(ha != h0);
  double xa[18], xb[18];
  assert_int_equal(mr_world_positions(a, xa, 6), 6);
  assert_int_equal(mr_world_positions(b, xb, 6), 6);
  assert_memory_equal(xa, xb, sizeof xa);
  mr_world_destroy(a);
  mr_world_destroy(b);
  mr_world_destroy(c);
}

/* The hash covers time, positions and velocities: changing any one byte of
 * them changes it. */
static void hash_sees_time_position_and_velocity(void **state) {
  (void)state;
  mr_world *w = build(0.0);
  uint64_t h0 = mr_world_state_hash(w);
  double x[3], v[3];
  mr_world_particle_state(w, 5, x, v);
  v[2] = 1e-300;
  assert_int_equal(mr_world_set_particle_state(w, 5, x, v), MR_OK);
  uint64_t h1 = mr_world_state_hash(w);
  assert_true(h1 != h0);
  x[0] = nextafter(x[0], 1.0);
  assert_int_equal(mr_world_set_particle_state(w, 5, x, v), MR_OK);
  uint64_t h2 = mr_world_state_hash(w);
  assert_true(h2 != h1);
  assert_int_equal(mr_world_step_to(w, 0.0, NULL), MR_OK); /* no time passes: same state */
  assert_true(mr_world_state_hash(w) == h2);
  mr_world_destroy(w);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(same_inputs_give_identical_hash),
    cmocka_unit_test(hash_sees_time_position_and_velocity),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
