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

/* Where a ball leaves the rod point it struck: velocity of the ball less
 * the point's, (1 − s) v_a + s v_b at s = 1/4, and the normal n from the
 * point's sphere to the ball. */
static void off_the_point(const mr_world *w, int ball_id, const int rod[2], double rel[3],
                          double n[3]) {
  double xb[3], vb[3], xa[3], va[3], xc[3], vc[3];
  mr_world_particle_state(w, ball_id, xb, vb);
  mr_world_particle_state(w, rod[0], xa, va);
  mr_world_particle_state(w, rod[1], xc, vc);
  double len = 0.0;
  for (int k = 0; k < 3; k++) {
    rel[k] = vb[k] - (0.75 * va[k] + 0.25 * vc[k]);
    n[k] = xb[k] - (0.75 * xa[k] + 0.25 * xc[k]);
    len += n[k] * n[k];
  }
  for (int k = 0; k < 3; k++) n[k] /= sqrt(len);
}

/* A ball falls at 2 m/s onto a rod's sphere a quarter of the way along it,
 * sliding across it at 1 m/s, while the rod's lighter end (1 kg; the other
 * 3 kg) rises at 1 m/s: no gravity, restitution 0.5 and friction 1 on both
 * parts. The point struck moves as (1 − s) v_a + s v_b with s = 1/4, so
 * the ball must leave that point along the normal at half the speed it
 * met it with, and friction enough to stop the slide leaves no slip
 * across the rod there: the impulse had to take the point's velocity with each end's
 * share, and each end's inverse mass with the square of it. Momentum is
 * kept. */
static void a_ball_striking_a_rod_off_its_middle_leaves_the_point_it_strikes(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_PUPPET_COLLISION | MR_EFFECT_CONSTRAINTS;
  def.drag = 0.0;
  def.contact_slop = SLOP;
  /* Short steps: the velocities are read a step after the impulse. */
  def.dt_initial = def.dt_min = def.dt_max = 1e-3;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  mr_particle_def p = mr_default_particle_def();
  int rod[2], b = ball(w, -0.1, 0.1, -0.02, 0, -2.0, 1.0, 0.02, 0);
  for (int i = 0; i < 2; i++) {
    p.position[0] = i ? 0.2 : -0.2;
    p.velocity[1] = i ? 0.0 : 1.0;
    p.mass = i ? 3.0 : 1.0;
    p.puppet = 1;
    assert_int_equal(mr_world_add_particle(w, &p, &rod[i]), MR_OK);
  }
  mr_distance_def d = mr_default_distance_def();
  d.a = rod[0];
  d.b = rod[1];
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  mr_part_def pd = mr_default_part_def();
  pd.particles = rod;
  pd.count = 2;
  pd.radius = 0.02;
  pd.segment_spheres = 3; /* at s = 1/4, 1/2, 3/4 */
  pd.friction = 1.0;
  assert_int_equal(mr_world_add_part(w, &pd, NULL), MR_OK);
  pd.particles = &b;
  pd.count = 1;
  pd.segment_spheres = 0;
  assert_int_equal(mr_world_add_part(w, &pd, NULL), MR_OK);
  mr_step_report rep;
  double before[3], after[3], n[3], unused[3];
  int hits = 0;
  while (hits == 0 && mr_world_time(w) < 0.2) {
    off_the_point(w, b, rod, before, n); /* the step before the impulse ends at the contact */
    assert_int_equal(mr_world_step(w, &rep), MR_OK);
    hits += rep.collisions;
  }
  assert_int_equal(hits, 1);
  off_the_point(w, b, rod, after, unused);
  const double in = before[0] * n[0] + before[1] * n[1] + before[2] * n[2];
  const double out = after[0] * n[0] + after[1] * n[1] + after[2] * n[2];
  /* Across the rod (z): along it, the rod's own constraint takes part of
   * friction's impulse, which friction's mass, that of free particles,
   * does not see. */
  const double slip = after[2] - out * n[2];
  printf("ball off a rod: met the point at %.6f m/s, left it at %.6f, slip %.2g m/s\n", in, out,
         slip);
  assert_true(in < -2.5); /* the rod's end rising: faster than the ball's 2 m/s */
  assert_true(fabs(out + 0.5 * in) < 1e-3);
  assert_true(fabs(slip) < 1e-3);
  double vb[3], va[3], vc[3];
  mr_world_particle_state(w, b, NULL, vb);
  mr_world_particle_state(w, rod[0], NULL, va);
  mr_world_particle_state(w, rod[1], NULL, vc);
  assert_true(fabs(vb[1] + va[1] + 3.0 * vc[1] + 1.0) < 1e-9);
  assert_true(fabs(vb[2] + va[2] + 3.0 * vc[2] - 1.0) < 1e-9);
  mr_world_destroy(w);
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
    cmocka_unit_test(a_ball_striking_a_rod_off_its_middle_leaves_the_point_it_strikes),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
