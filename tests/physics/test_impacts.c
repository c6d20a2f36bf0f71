/* Collisions are never missed (§4.4, §4.5, §5.4): at impact speeds up to
 * 10 m/s, head-on and glancing, between puppets, within a puppet and with
 * the floor, no accepted step ends with two bodies deeper into each other
 * than the contact slop. The worst gap is taken after every accepted step. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>

#include "mr_physics.h"

#define SLOP 1e-4

static mr_world *world(uint32_t effects) {
  mr_world_def def = mr_default_world_def();
  def.effects = effects;
  def.drag = 0.0;
  def.contact_slop = SLOP;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  return w;
}

static int ball(mr_world *w, double x, double y, double z, double vx, double vy, double vz,
                double r, int puppet) {
  mr_particle_def p = mr_default_particle_def();
  p.position[0] = x;
  p.position[1] = y;
  p.position[2] = z;
  p.velocity[0] = vx;
  p.velocity[1] = vy;
  p.velocity[2] = vz;
  p.radius = r;
  p.puppet = puppet;
  int id = -1;
  assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
  return id;
}

static void part(mr_world *w, const int *ids, int n, double r) {
  mr_part_def d = mr_default_part_def();
  d.particles = ids;
  d.count = n;
  d.radius = r;
  assert_int_equal(mr_world_add_part(w, &d, NULL), MR_OK);
}

static double sphere_gap(const mr_world *w, int a, int b, double ra, double rb) {
  double xa[3], xb[3];
  mr_world_particle_state(w, a, xa, NULL);
  mr_world_particle_state(w, b, xb, NULL);
  double d[3] = { xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2] };
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - ra - rb;
}

/* Steps to t_end one accepted step at a time; the smallest gap seen. */
typedef double (*gap_fn)(const mr_world *w);
static const int *pair_ids;
static double pair_r;
static double pair_gap(const mr_world *w) {
  return sphere_gap(w, pair_ids[0], pair_ids[1], pair_r, pair_r);
}
static double floor_gap(const mr_world *w) {
  double x[3];
  mr_world_particle_state(w, pair_ids[0], x, NULL);
  return x[1] - pair_r;
}

static double worst_gap(mr_world *w, double t_end, gap_fn gap, int *collisions) {
  double worst = INFINITY;
  mr_step_report rep;
  *collisions = 0;
  while (mr_world_time(w) < t_end) {
    mr_status s = mr_world_step(w, &rep);
    assert_true(s == MR_OK || s == MR_DEPENDENT);
    *collisions += rep.collisions;
    worst = fmin(worst, gap(w));
  }
  return worst;
}

/* Two balls of two puppets, 2 cm radius, closing at 10 m/s each (20 m/s
 * relative) head-on, or offset by 3 cm (a glancing blow). */
static void sphere_sphere(double offset, uint32_t effect, int same_puppet) {
  mr_world *w = world(effect);
  const double r = 0.02;
  int ids[2];
  ids[0] = ball(w, -0.5, 0, 0, 10, 0, 0, r, 0);
  ids[1] = ball(w, 0.5, offset, 0, -10, 0, 0, r, same_puppet ? 0 : 1);
  part(w, &ids[0], 1, r);
  part(w, &ids[1], 1, r);
  pair_ids = ids;
  pair_r = r;
  int hits;
  double g = worst_gap(w, 0.2, pair_gap, &hits);
  printf("spheres, offset %.2f m, %s: worst gap %.3g m, %d impacts\n", offset,
         same_puppet ? "one puppet" : "two puppets", g, hits);
  assert_true(hits >= 1);
  assert_true(g >= -SLOP);
  mr_world_destroy(w);
}

static void spheres_of_two_puppets_head_on_at_10_m_s(void **state) {
  (void)state;
  sphere_sphere(0.0, MR_EFFECT_PUPPET_COLLISION, 0);
}
static void spheres_of_two_puppets_glancing_at_10_m_s(void **state) {
  (void)state;
  sphere_sphere(0.03, MR_EFFECT_PUPPET_COLLISION, 0);
}
static void spheres_of_one_puppet_head_on_at_10_m_s(void **state) {
  (void)state;
  sphere_sphere(0.0, MR_EFFECT_SELF_COLLISION, 1);
}
static void spheres_of_one_puppet_glancing_at_10_m_s(void **state) {
  (void)state;
  sphere_sphere(0.03, MR_EFFECT_SELF_COLLISION, 1);
}

/* A particle of 1 cm radius hits the floor at 10 m/s, straight down or at
 * 45° (10 m/s across, 10 m/s down). */
static void particle_plane(double across) {
  mr_world *w = world(MR_EFFECT_PLANES);
  mr_plane_def pl = mr_default_plane_def();
  assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
  const double r = 0.01;
  int ids[1] = { ball(w, 0, 0.5, 0, across, -10, 0, r, 0) };
  pair_ids = ids;
  pair_r = r;
  int hits;
  double g = worst_gap(w, 0.3, floor_gap, &hits);
  printf("floor, %.0f m/s across: worst gap %.3g m, %d impacts\n", across, g, hits);
  assert_true(hits >= 1);
  assert_true(g >= -SLOP);
  mr_world_destroy(w);
}

static void particle_hits_floor_head_on_at_10_m_s(void **state) {
  (void)state;
  particle_plane(0.0);
}
static void particle_hits_floor_glancing_at_10_m_s(void **state) {
  (void)state;
  particle_plane(10.0);
}

/* Two rigid stick puppets (a rod of two particles, 3 cm spheres along it)
 * thrown at each other at 5 m/s each, crossing: no sphere of one ends a
 * step inside a sphere of the other. */
static const int *rods;
static double rods_gap(const mr_world *w) {
  double worst = INFINITY;
  /* each rod: particles rods[0..1] and rods[2..3]; sample 9 points */
  for (int i = 0; i <= 8; i++)
    for (int j = 0; j <= 8; j++) {
      double a0[3], a1[3], b0[3], b1[3], pa[3], pb[3];
      mr_world_particle_state(w, rods[0], a0, NULL);
      mr_world_particle_state(w, rods[1], a1, NULL);
      mr_world_particle_state(w, rods[2], b0, NULL);
      mr_world_particle_state(w, rods[3], b1, NULL);
      for (int k = 0; k < 3; k++) {
        pa[k] = a0[k] + (a1[k] - a0[k]) * i / 8.0;
        pb[k] = b0[k] + (b1[k] - b0[k]) * j / 8.0;
      }
      double d = sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                      (pa[2] - pb[2]) * (pa[2] - pb[2]));
      worst = fmin(worst, d - 0.06);
    }
  return worst;
}

static void puppets_thrown_together_at_5_m_s(void **state) {
  (void)state;
  mr_world *w = world(MR_EFFECT_PUPPET_COLLISION | MR_EFFECT_CONSTRAINTS);
  int ids[4];
  ids[0] = ball(w, -0.5, -0.2, 0, 5, 0, 0, 0.03, 0);
  ids[1] = ball(w, -0.5, 0.2, 0, 5, 0, 0, 0.03, 0);
  ids[2] = ball(w, 0.5, 0, -0.2, -5, 0, 0, 0.03, 1);
  ids[3] = ball(w, 0.5, 0, 0.2, -5, 0, 0, 0.03, 1);
  for (int p = 0; p < 2; p++) {
    mr_distance_def d = mr_default_distance_def();
    d.a = ids[2 * p];
    d.b = ids[2 * p + 1];
    assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
    mr_part_def pd = mr_default_part_def();
    pd.particles = &ids[2 * p];
    pd.count = 2;
    pd.radius = 0.03;
    pd.segment_spheres = 7;
    assert_int_equal(mr_world_add_part(w, &pd, NULL), MR_OK);
  }
  rods = ids;
  int hits;
  double g = worst_gap(w, 0.3, rods_gap, &hits);
  printf("rods at 5 m/s: worst gap %.3g m (sampled), %d impacts\n", g, hits);
  assert_true(hits >= 1);
  /* The spheres along a rod are 5 cm apart, so between two of them the
   * rod's surface dips by up to 3 - sqrt(3² - 2.5²) ≈ 1.3 cm: the sampled
   * points must stay outside the spheres' hull, not the ideal capsule. */
  assert_true(g >= -0.014);
  mr_world_destroy(w);
}

/* A particle sliding at 2 m/s along the floor settles onto it from 5 cm up,
 * no gravity, friction 0.5, restitution 0.5. Settling at 3 cm/s, under the
 * rest speed (5 cm/s), it comes to rest on the floor with no impact: no
 * bounce and no friction impulse, so the slide keeps all of its 2 m/s
 * (with one it would lose 0.5 · 1.5 · 0.03 = 0.0225 m/s). At 8 cm/s it is
 * an impact: it bounces at 4 cm/s and friction takes 0.5 · 1.5 · 0.08 =
 * 0.06 m/s off the slide. */
static void only_impacts_faster_than_the_rest_speed_bounce_and_rub(void **state) {
  (void)state;
  const double down[2] = { 0.03, 0.08 }, up[2] = { 0.0, 0.04 }, slide[2] = { 2.0, 1.94 };
  for (int c = 0; c < 2; c++) {
    mr_world *w = world(MR_EFFECT_PLANES);
    mr_plane_def pl = mr_default_plane_def();
    pl.restitution = 0.5;
    pl.friction = 0.5;
    assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
    int id = ball(w, 0, 0.05, 0, 2.0, -down[c], 0, 0.0, 0);
    mr_step_report rep;
    assert_int_equal(mr_world_step_to(w, 0.05 / down[c] + 0.1, &rep), MR_OK);
    double v[3];
    mr_world_particle_state(w, id, NULL, v);
    printf("settling at %.2f m/s: v = (%.9f, %.9f), %d impacts\n", down[c], v[0], v[1],
           rep.collisions);
    assert_int_equal(rep.collisions, c);
    /* The resting contact's own correction moves the settled particle by
     * 1e-4 m/s at most: far below the 0.0225 m/s an impulse would take. */
    assert_true(fabs(v[0] - slide[c]) < 1e-3);
    assert_true(fabs(v[1] - up[c]) < 1e-3);
    mr_world_destroy(w);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(spheres_of_two_puppets_head_on_at_10_m_s),
    cmocka_unit_test(spheres_of_two_puppets_glancing_at_10_m_s),
    cmocka_unit_test(spheres_of_one_puppet_head_on_at_10_m_s),
    cmocka_unit_test(spheres_of_one_puppet_glancing_at_10_m_s),
    cmocka_unit_test(particle_hits_floor_head_on_at_10_m_s),
    cmocka_unit_test(particle_hits_floor_glancing_at_10_m_s),
    cmocka_unit_test(puppets_thrown_together_at_5_m_s),
    cmocka_unit_test(only_impacts_faster_than_the_rest_speed_bounce_and_rub),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
