/* The swept gap of a contact over one step (collide.c, §4.4), checked
 * against the path it claims to bound: each particle on the cubic Hermite
 * curve through its step ends, sampled finely. For a plane the least gap
 * on that path is exact; for two spheres it is a lower bound, below the
 * chord's least gap by no more than the documented bulge. A bound that is
 * not one lets a body pass through within a step; one far too low cuts
 * steps for nothing. The sweeps are internal, so the test reads the
 * library's own header. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "internal.h"

#define SAMPLES 20000

/* A fixed sequence of numbers in [lo, hi): the same sweeps on every run. */
static double uniform(uint64_t *seed, double lo, double hi) {
  *seed = *seed * 6364136223846793005ULL + 1442695040888963407ULL;
  return lo + (hi - lo) * (double)(*seed >> 11) / 9007199254740992.0;
}

/* The Hermite curve through (x0, v0) and (x1, v1) over a step h, at s. */
static void hermite(const double x0[3], const double v0[3], const double x1[3], const double v1[3],
                    double h, double s, double out[3]) {
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2,
               h11 = s3 - s2;
  for (int k = 0; k < 3; k++)
    out[k] = h00 * x0[k] + h10 * h * v0[k] + h01 * x1[k] + h11 * h * v1[k];
}

static double norm3(const double a[3]) {
  return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

/* A step of one particle: random ends and rates, the end near where the
 * rates would take it, so that the path may bend either way. */
static void random_step(uint64_t *seed, double x0[3], double v0[3], double x1[3], double v1[3],
                        double *h) {
  *h = uniform(seed, 0.002, 0.05);
  for (int k = 0; k < 3; k++) {
    x0[k] = uniform(seed, -0.05, 0.05);
    v0[k] = uniform(seed, -8, 8);
    v1[k] = uniform(seed, -8, 8);
    x1[k] = x0[k] + 0.5 * *h * (v0[k] + v1[k]) + uniform(seed, -0.01, 0.01);
  }
}

/* An empty world with the planes' effect. */
static mr_world *planes_world(void) {
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_PLANES;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  return w;
}

/* A particle of radius r against a tilted plane: the swept gap is the least
 * gap on the particle's path, and without the bulge the lesser gap at the
 * step's ends (its straight path's least). */
static void plane_swept_gap_is_the_least_on_the_path(void **state) {
  (void)state;
  mr_world *w = planes_world();
  mr_plane_def pl = mr_default_plane_def();
  pl.normal[0] = 0.3;
  pl.normal[1] = 1.0;
  pl.normal[2] = -0.2;
  pl.offset = 0.01;
  int plane;
  assert_int_equal(mr_world_add_plane(w, &pl, &plane), MR_OK);
  mr_particle_def p = mr_default_particle_def();
  p.radius = 0.02;
  int id;
  assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
  assert_int_equal(mr_world_ensure_ready(w), 0);
  const double *n = MR_AT(w->planes, mr_plane, plane).n;
  const mr_contact c = { MR_CONTACT_PLANE, id, plane, 0.5, 0.3 };
  uint64_t seed = 7;
  double worst = 0.0;
  int dips = 0;
  for (int trial = 0; trial < 400; trial++) {
    double x0[3], v0[3], x1[3], v1[3], h;
    random_step(&seed, x0, v0, x1, v1, &h);
    const mr_sweep sw = { x0, v0, x1, v1, h };
    double least = INFINITY, q[3];
    for (int i = 0; i <= SAMPLES; i++) {
      hermite(x0, v0, x1, v1, h, (double)i / SAMPLES, q);
      least = fmin(least, n[0] * q[0] + n[1] * q[1] + n[2] * q[2] - pl.offset - p.radius);
    }
    const double g0 = mr_contact_gap(w, &c, x0), g1 = mr_contact_gap(w, &c, x1);
    if (least < fmin(g0, g1) - 1e-6) dips++;
    const double g = mr_contact_swept_gap(w, &c, &sw, 1);
    worst = fmax(worst, fabs(g - least));
    assert_true(fabs(g - least) < 1e-9);
    assert_true(mr_contact_swept_gap(w, &c, &sw, 0) == fmin(g0, g1));
  }
  print_message("plane: %d of 400 paths dip below both ends; swept gap off by %.3g m at most\n",
                dips, worst);
  assert_true(dips > 50); /* the interior minimum is what is tested */
  /* A dip symmetric about the step's middle on a level floor: the cubic's
   * s³ term vanishes, and its least is that of a parabola, at s = ½. */
  int floor_id;
  assert_int_equal(
      mr_world_add_plane(
          w, &(mr_plane_def){ .cookie = pl.cookie, .normal = { 0, 1, 0 }, .restitution = 0.5 },
          &floor_id),
      MR_OK);
  assert_int_equal(mr_world_ensure_ready(w), 0);
  const mr_contact on_floor = { MR_CONTACT_PLANE, id, floor_id, 0.5, 0.0 };
  const double x0[3] = { 0, 0.03, 0 }, v0[3] = { 1, -2, 0 }, x1[3] = { 0.02, 0.03, 0 },
               v1[3] = { 1, 2, 0 };
  const mr_sweep sym = { x0, v0, x1, v1, 0.02 };
  /* y(½) = 0.03 + 0.02 (⅛ (−2) − ⅛ 2) = 0.02, less the radius. */
  const double want = 0.02 - p.radius;
  print_message("symmetric dip: swept gap %.17g, path %.17g\n",
                mr_contact_swept_gap(w, &on_floor, &sym, 1), want);
  assert_true(fabs(mr_contact_swept_gap(w, &on_floor, &sym, 1) - want) < 1e-15);
  mr_world_destroy(w);
}

/* A particle whose position or speed is NaN at a step's end is listed
 * against the floor, not read as clear of it. */
static void a_nan_particle_is_listed_against_the_floor(void **state) {
  (void)state;
  mr_world *w = planes_world();
  mr_plane_def pl = mr_default_plane_def();
  assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
  mr_particle_def p = mr_default_particle_def();
  p.position[1] = 1.0;
  assert_int_equal(mr_world_add_particle(w, &p, NULL), MR_OK);
  assert_int_equal(mr_world_ensure_ready(w), 0);
  double x0[3] = { 0, 1, 0 }, v0[3] = { 0, 0, 0 }, x1[3] = { 0, NAN, 0 }, v1[3] = { 0, 0, 0 };
  mr_contact_list l = { 0 };
  assert_int_equal(mr_contacts_detect(w, x0, w->def.contact_slop, &l), 0);
  assert_int_equal(l.n, 0);
  assert_int_equal(mr_contacts_detect(w, x1, w->def.contact_slop, &l), 0);
  assert_int_equal(l.n, 1);
  const mr_sweep sw = { x0, v0, x1, v1, 0.01 };
  assert_int_equal(mr_contacts_sweep(w, &sw, -w->def.contact_slop, &l), 0);
  assert_int_equal(l.n, 1);
  assert_int_equal(l.c[0].kind, MR_CONTACT_PLANE);
  const mr_contact c = { MR_CONTACT_PLANE, 0, 0, 0.5, 0.3 };
  assert_true(isnan(mr_contact_swept_gap(w, &c, &sw, 0)));
  /* Ends in place, and a NaN speed at one of them: the path between is
   * unknown. */
  x1[1] = 1.0;
  v1[1] = NAN;
  assert_int_equal(mr_contacts_sweep(w, &sw, -w->def.contact_slop, &l), 0);
  assert_int_equal(l.n, 1);
  mr_contact_list_free(&l);
  mr_world_destroy(w);
}

/* Two single spheres, each on its own path: the swept gap is at most the
 * least gap on the paths, and at least the least gap on the chord of their
 * difference less the bulge h/4 max(|u0 − v̄|, |u1 − v̄|) of its path. */
static void sphere_swept_gap_bounds_the_path_within_the_bulge(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_PUPPET_COLLISION;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  const double r[2] = { 0.015, 0.007 };
  int id[2];
  for (int k = 0; k < 2; k++) {
    mr_particle_def p = mr_default_particle_def();
    p.position[0] = k;
    p.radius = r[k];
    p.puppet = k;
    assert_int_equal(mr_world_add_particle(w, &p, &id[k]), MR_OK);
    mr_part_def d = mr_default_part_def();
    d.particles = &id[k];
    d.count = 1;
    d.radius = r[k];
    assert_int_equal(mr_world_add_part(w, &d, NULL), MR_OK);
  }
  assert_int_equal(mr_world_ensure_ready(w), 0);
  assert_int_equal(w->leaves.n, 2);
  const mr_leaf *la = &MR_AT(w->leaves, mr_leaf, 0), *lb = &MR_AT(w->leaves, mr_leaf, 1);
  assert_int_equal(la->p0, id[0]);
  assert_int_equal(lb->p0, id[1]);
  const double rr = la->r + lb->r;
  uint64_t seed = 11;
  int tight = 0;
  for (int trial = 0; trial < 400; trial++) {
    double x0[6], v0[6], x1[6], v1[6], h, h2;
    random_step(&seed, x0, v0, x1, v1, &h);
    random_step(&seed, x0 + 3, v0 + 3, x1 + 3, v1 + 3, &h2);
    /* The second sphere's ends are moved off the first's by 3 cm or so,
     * so that some chords pass the first sphere and some stop short. */
    for (int k = 0; k < 3; k++) {
      const double off = uniform(&seed, -0.03, 0.03);
      x0[3 + k] += off;
      x1[3 + k] = x0[3 + k] + 0.5 * h * (v0[3 + k] + v1[3 + k]) + uniform(&seed, -0.01, 0.01);
    }
    const mr_sweep sw = { x0, v0, x1, v1, h };
    double d0[3], d1[3], u0[3], u1[3], e0 = 0.0, e1 = 0.0;
    for (int k = 0; k < 3; k++) {
      d0[k] = x0[3 + k] - x0[k];
      d1[k] = x1[3 + k] - x1[k];
      u0[k] = v0[3 + k] - v0[k];
      u1[k] = v1[3 + k] - v1[k];
      const double bar = (d1[k] - d0[k]) / h;
      e0 += (u0[k] - bar) * (u0[k] - bar);
      e1 += (u1[k] - bar) * (u1[k] - bar);
    }
    const double bulge = 0.25 * h * sqrt(fmax(e0, e1));
    /* The chord's least gap exactly (a chord through the other centre has
     * a kink there that sampling would miss by up to a sample's length). */
    double dd[3], c[3], q[3], on_path = INFINITY;
    for (int k = 0; k < 3; k++) dd[k] = d1[k] - d0[k];
    const double s_near = fmin(
        fmax(-(d0[0] * dd[0] + d0[1] * dd[1] + d0[2] * dd[2]) / (norm3(dd) * norm3(dd)), 0.0), 1.0);
    for (int k = 0; k < 3; k++) c[k] = d0[k] + s_near * dd[k];
    const double on_chord = norm3(c) - rr;
    for (int i = 0; i <= SAMPLES; i++) {
      hermite(d0, u0, d1, u1, h, (double)i / SAMPLES, q);
      on_path = fmin(on_path, norm3(q) - rr);
    }
    const double g = mr_sphere_pair_swept_gap(w, 0, 1, &sw);
    assert_true(g <= on_path + 1e-12);
    assert_true(g >= on_chord - bulge - 1e-9);
    if (on_path - g < 0.5 * bulge) tight++;
  }
  print_message("spheres: the bound within half the bulge of the path's least gap in %d of 400\n",
                tight);
  /* A step of no length has no path between its ends: its gap is theirs. */
  const double xa[6] = { 0, 0, 0, 0.03, 0, 0 }, va[6] = { 5, 0, 0, -5, 1, 0 };
  const mr_sweep still = { xa, va, xa, va, 0.0 };
  assert_true(mr_sphere_pair_swept_gap(w, 0, 1, &still) == 0.03 - rr);
  /* A NaN end, in place or in speed, makes the gap NaN, never clear. */
  const double xn[6] = { 0, 0, 0, NAN, 0, 0 }, vn[6] = { 5, 0, 0, -5, NAN, 0 };
  const mr_sweep to_nan = { xa, va, xn, va, 0.01 }, nan_speed = { xa, va, xa, vn, 0.01 };
  assert_true(isnan(mr_sphere_pair_swept_gap(w, 0, 1, &to_nan)));
  assert_true(isnan(mr_sphere_pair_swept_gap(w, 0, 1, &nan_speed)));
  const mr_contact pair = { MR_CONTACT_SPHERES, 0, 1, 0.0, 0.0 };
  assert_true(isnan(mr_contact_swept_gap(w, &pair, &to_nan, 0)));
  mr_world_destroy(w);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(plane_swept_gap_is_the_least_on_the_path),
    cmocka_unit_test(sphere_swept_gap_bounds_the_path_within_the_bulge),
    cmocka_unit_test(a_nan_particle_is_listed_against_the_floor),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
