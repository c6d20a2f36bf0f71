/* Property test: 60 random worlds (fixed seed) with every kind of element,
 * random effects declared, frames jerked about. Whatever the mix, each call
 * returns a status of the API (never crashes: ASan/UBSan watch), the state
 * stays finite, time lands exactly on each target, and a rerun of the same
 * world gives the same hash. Random stiff mixes (a triggered force of 100 N
 * on a 50 g particle) do diverge; the property is that they are reset and
 * carry on (§7), never that they don't. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>

#include "mr_physics.h"

static uint64_t rng;
static double uni(void) {
  rng = rng * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(rng >> 11) / 9007199254740992.0;
}
static int pick(int n) {
  return (int)(uni() * n) % n;
}

static mr_world *random_world(uint64_t seed, int *frame_out) {
  rng = seed;
  mr_world_def def = mr_default_world_def();
  def.effects = (uint32_t)(uni() * 8192.0) & 0x1fffu;
  def.effects |= MR_EFFECT_FRAMES | MR_EFFECT_CONSTRAINTS;
  def.integrator = (mr_integrator)pick(4);
  def.solver = (mr_solve_method)pick(4);
  def.drag = uni() * 0.5;
  /* At the paper's lower bound: the steps under it that the local error
   * estimate may take (dt_floor) are tested in test_error_control.c, and
   * random worlds full of nearly degenerate geometry would spend minutes
   * there under the sanitizers. */
  def.dt_floor = def.dt_min;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  mr_frame_def fd = mr_default_frame_def();
  fd.pose.position[1] = 2.0;
  assert_int_equal(mr_world_add_frame(w, &fd, frame_out), MR_OK);
  int n = 3 + pick(10), nf = 1 + pick(3);
  for (int i = 0; i < nf; i++) {
    mr_particle_def p = mr_default_particle_def();
    p.frame = *frame_out;
    p.position[0] = uni() - 0.5;
    p.position[1] = 2.0;
    p.position[2] = uni() - 0.5;
    assert_int_equal(mr_world_add_particle(w, &p, NULL), MR_OK);
  }
  for (int i = 0; i < n; i++) {
    mr_particle_def p = mr_default_particle_def();
    p.mass = 0.05 + uni();
    p.radius = 0.02 + 0.05 * uni();
    p.puppet = pick(2);
    for (int k = 0; k < 3; k++) {
      p.position[k] = (k == 1 ? 1.0 : 0.0) + (uni() - 0.5);
      p.velocity[k] = uni() - 0.5;
    }
    assert_int_equal(mr_world_add_particle(w, &p, NULL), MR_OK);
  }
  int total = nf + n;
  /* Elements: each call may be refused (undeclared effect, degenerate
   * geometry); it must then say so with an error status. */
  for (int e = 0; e < 3 * n; e++) {
    int a = nf + pick(n), b = pick(total), kind = pick(9);
    mr_status s = MR_OK;
    switch (kind) {
    case 0: {
      mr_distance_def d = mr_default_distance_def();
      d.a = a;
      d.b = b;
      s = mr_world_add_distance(w, &d, NULL);
      break;
    }
    case 1: {
      mr_spring_def d = mr_default_spring_def();
      d.a = a;
      d.b = b;
      s = mr_world_add_spring(w, &d, NULL);
      break;
    }
    case 2: {
      mr_string_def d = mr_default_string_def();
      d.frame_particle = pick(nf);
      d.puppet_particle = a;
      s = mr_world_add_string(w, &d, NULL);
      break;
    }
    case 3: {
      mr_sine_spring_def d = mr_default_sine_spring_def();
      d.a = a;
      d.b = b;
      s = mr_world_add_sine_spring(w, &d, NULL);
      break;
    }
    case 4: {
      mr_antigravity_def d = mr_default_antigravity_def();
      d.acted = a;
      d.trigger = b;
      s = mr_world_add_antigravity(w, &d, NULL);
      break;
    }
    case 5: {
      mr_triggered_def d = mr_default_triggered_def();
      d.acted = a;
      d.control = pick(nf);
      d.trigger = b;
      s = mr_world_add_triggered(w, &d, NULL);
      break;
    }
    case 6: {
      int ids[5];
      int cnt = 2 + pick(4);
      for (int i = 0; i < cnt; i++) ids[i] = nf + pick(n);
      mr_rigid_group_def d = mr_default_rigid_group_def();
      d.particles = ids;
      d.count = cnt;
      s = mr_world_add_rigid_group(w, &d, NULL);
      break;
    }
    case 7: {
      int ids[2] = { a, nf + pick(n) };
      mr_part_def d = mr_default_part_def();
      d.particles = ids;
      d.count = 1 + pick(2);
      d.segment_spheres = d.count == 2 ? pick(3) : 0;
      s = mr_world_add_part(w, &d, NULL);
      break;
    }
    default: {
      mr_plane_def d = mr_default_plane_def();
      d.normal[0] = 0.3 * (uni() - 0.5);
      d.offset = -0.5 * uni();
      s = mr_world_add_plane(w, &d, NULL);
      break;
    }
    }
    assert_true(s == MR_OK || s < 0);
    if (s < 0) assert_true(mr_world_last_error(w)[0] != '\0');
  }
  return w;
}

static uint64_t run(mr_world *w, int frame, uint64_t seed, int *resets) {
  rng = seed ^ 0x9e3779b97f4a7c15ull;
  for (int f = 1; f <= 60; f++) {
    double t = f / 30.0;
    mr_pose pose = mr_pose_identity();
    pose.position[0] = 0.5 * (uni() - 0.5);
    pose.position[1] = 2.0 + 0.5 * (uni() - 0.5);
    double a = uni() - 0.5;
    pose.orientation[0] = cos(a);
    pose.orientation[1] = sin(a);
    assert_int_equal(mr_world_set_frame_target(w, frame, &pose, t), MR_OK);
    mr_step_report rep;
    mr_status s = mr_world_step_to(w, t, &rep);
    assert_true(s == MR_OK || s == MR_DIVERGED || s == MR_DEPENDENT);
    *resets += rep.divergences;
    assert_true(mr_world_time(w) == t);
    int n = mr_world_particle_count(w);
    for (int i = 0; i < n; i++) {
      double x[3], v[3];
      mr_world_particle_state(w, i, x, v);
      for (int k = 0; k < 3; k++) assert_true(isfinite(x[k]) && isfinite(v[k]));
    }
  }
  return mr_world_state_hash(w);
}

static void random_worlds_stay_finite_and_reproducible(void **state) {
  (void)state;
  int resets = 0, worlds = 60;
  uint64_t steps = 0;
  for (int i = 0; i < worlds; i++) {
    uint64_t seed = 1000003ull * (uint64_t)(i + 1);
    int fa, fb;
    mr_world *a = random_world(seed, &fa);
    uint64_t ha = run(a, fa, seed, &resets);
    mr_world *b = random_world(seed, &fb);
    uint64_t hb = run(b, fb, seed, &resets);
    assert_true(ha == hb);
    mr_stats st;
    mr_world_stats(a, &st);
    steps += st.steps;
    mr_world_destroy(a);
    mr_world_destroy(b);
  }
  printf("random worlds: %d worlds, %llu steps, %d resets, all finite and reproducible\n", worlds,
         (unsigned long long)steps, resets);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(random_worlds_stay_finite_and_reproducible),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
