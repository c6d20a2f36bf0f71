/* The laws at a contact, each against numbers worked out by hand (§4.4,
 * §5.3, §6.2): an oblique bounce with restitution and Coulomb friction
 * capped at stopping the slide, a head-on bounce of two parts of
 * different restitution (the mean of the two), a string that is shortening
 * fast but still long (it pulls, or goes slack; it never pushes), and
 * sphere trees whose parents enclose children of different radii. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>

#include "mr_physics.h"

#include "failing_realloc.h"

static mr_world *world(uint32_t effects) {
  mr_world_def def = mr_default_world_def();
  def.effects = effects;
  def.drag = 0.0;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  return w;
}

static int particle(mr_world *w, const double x[3], const double v[3], double mass, double r,
                    int puppet) {
  mr_particle_def p = mr_default_particle_def();
  for (int k = 0; k < 3; k++) {
    p.position[k] = x[k];
    p.velocity[k] = v[k];
  }
  p.mass = mass;
  p.radius = r;
  p.puppet = puppet;
  int id = -1;
  assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
  return id;
}

static void velocity(const mr_world *w, int p, double v[3]) {
  assert_int_equal(mr_world_particle_state(w, p, NULL, v), MR_OK);
}

/* A particle meets the floor at (3, −4) m/s, no gravity. Restitution 0.5
 * sends it up at 2 m/s. Friction takes μ·(1 + e)·4 = 1.2·μ/0.2 m/s off the
 * slide, but never more than stops it: μ = 0.2 leaves 1.8 m/s, μ = 2 leaves
 * 0 (not −9). */
static void oblique_bounce_with_friction(void **state) {
  (void)state;
  const double mus[2] = { 0.2, 2.0 }, slide[2] = { 1.8, 0.0 };
  for (int c = 0; c < 2; c++) {
    mr_world *w = world(MR_EFFECT_PLANES);
    const double x[3] = { 0, 0.05, 0 }, v[3] = { 3, -4, 0 };
    int p = particle(w, x, v, 1.0, 0.0, 0);
    mr_plane_def f = mr_default_plane_def();
    f.restitution = 0.5;
    f.friction = mus[c];
    assert_int_equal(mr_world_add_plane(w, &f, NULL), MR_OK);
    mr_step_report rep;
    assert_true(mr_world_step_to(w, 0.05, &rep) >= 0);
    double after[3];
    velocity(w, p, after);
    printf("bounce, mu %.1f: v = (%.6f, %.6f, %.6f), expected (%.1f, 2, 0)\n", mus[c], after[0],
           after[1], after[2], slide[c]);
    assert_true(rep.collisions >= 1);
    /* To 1e-5: the impact is located in time to within the contact slop. */
    assert_true(fabs(after[1] - 2.0) < 1e-5);
    assert_true(fabs(after[0] - slide[c]) < 1e-5);
    assert_true(fabs(after[2]) < 1e-12);
    mr_world_destroy(w);
  }
}

/* Two spheres of two puppets, 1 kg and 3 kg, meet head-on at 2 m/s each;
 * their parts' restitutions 0.2 and 0.8 make e = 0.5. Momentum is kept and
 * the closing speed of 4 m/s comes back as 2 m/s apart:
 *   v1' = ((m1 − e m2) v1 + (1 + e) m2 v2) / (m1 + m2) = −2.5 m/s,
 *   v2' = ((m2 − e m1) v2 + (1 + e) m1 v1) / (m1 + m2) = −0.5 m/s. */
static void head_on_bounce_under_mixed_restitution(void **state) {
  (void)state;
  mr_world *w = world(MR_EFFECT_PUPPET_COLLISION);
  const double xa[3] = { -0.15, 1, 0 }, va[3] = { 2, 0, 0 };
  const double xb[3] = { 0.15, 1, 0 }, vb[3] = { -2, 0, 0 };
  int a = particle(w, xa, va, 1.0, 0.0, 0), b = particle(w, xb, vb, 3.0, 0.0, 1);
  const double e[2] = { 0.2, 0.8 };
  const int ids[2] = { a, b };
  for (int i = 0; i < 2; i++) {
    mr_part_def d = mr_default_part_def();
    d.particles = &ids[i];
    d.count = 1;
    d.radius = 0.1;
    d.restitution = e[i];
    d.friction = 0.0;
    assert_int_equal(mr_world_add_part(w, &d, NULL), MR_OK);
  }
  assert_true(mr_world_step_to(w, 0.1, NULL) >= 0);
  double v1[3], v2[3];
  velocity(w, a, v1);
  velocity(w, b, v2);
  printf("mixed restitution: v1 = %.6f, v2 = %.6f (expected -2.5, -0.5)\n", v1[0], v2[0]);
  assert_true(fabs(v1[0] + 2.5) < 1e-5);
  assert_true(fabs(v2[0] + 0.5) < 1e-5);
  assert_true(fabs(1.0 * v1[0] + 3.0 * v2[0] - (2.0 - 6.0)) < 1e-9); /* momentum */
  mr_world_destroy(w);
}

/* The force on a string's particle, from the change of its velocity over a
 * step too short for the state to move (no gravity, no drag). */
static double string_force_along(double rate) {
  mr_world *w = world(MR_EFFECT_STRINGS | MR_EFFECT_FRAMES);
  mr_frame_def fd = mr_default_frame_def();
  int frame;
  assert_int_equal(mr_world_add_frame(w, &fd, &frame), MR_OK);
  mr_particle_def top = mr_default_particle_def();
  top.frame = frame;
  int t = -1;
  assert_int_equal(mr_world_add_particle(w, &top, &t), MR_OK);
  /* 1.5 m below the frame, rest 1 m: still long. rate < 0: shortening. */
  const double x[3] = { 0, -1.5, 0 }, v[3] = { 0, -rate, 0 };
  int p = particle(w, x, v, 1.0, 0.0, 0);
  mr_string_def s = mr_default_string_def();
  s.frame_particle = t;
  s.puppet_particle = p;
  s.rest_length = 1.0;
  s.mode = MR_STRING_SPRING;
  s.stiffness = 10.0;
  s.damping = 5.0;
  assert_int_equal(mr_world_add_string(w, &s, NULL), MR_OK);
  const double h = 1e-7;
  assert_true(mr_world_step_to(w, h, NULL) >= 0);
  double after[3];
  velocity(w, p, after);
  mr_world_destroy(w);
  return (after[1] - v[1]) / h; /* up, towards the frame: pulling */
}

/* Tension = k (L − rest) + c L̇ = 10·0.5 + 5·L̇. Shortening at 0.5 m/s:
 * 2.5 N, a pull. At 10 m/s: −45 N, which a string cannot give: 0. */
static void shortening_string_pulls_or_goes_slack_never_pushes(void **state) {
  (void)state;
  double slow = string_force_along(-0.5), fast = string_force_along(-10.0);
  printf("string 1.5 m long, rest 1 m: %.4f N shortening at 0.5 m/s, %.4f N at 10 m/s\n", slow,
         fast);
  assert_true(fabs(slow - 2.5) < 1e-4);
  assert_true(fabs(fast) < 1e-9);
  assert_true(string_force_along(0.0) > 4.99); /* at rest: k·0.5 */
}

/* Parts of radii 0.01 to 0.3 m (a big sphere next to small ones, so one
 * child may hold the other), their particles flung about: after every
 * frame, every parent of both trees encloses both its children. */
static void sphere_tree_parents_enclose_children(void **state) {
  (void)state;
  mr_world *w = world(MR_EFFECT_SELF_COLLISION | MR_EFFECT_PUPPET_COLLISION);
  const double radii[7] = { 0.3, 0.01, 0.05, 0.02, 0.15, 0.01, 0.08 };
  int ids[14];
  for (int i = 0; i < 14; i++) {
    const double x[3] = { 0.7 * (i % 7), 0.4 * (i / 7), 0.1 * (i % 3) };
    const double v[3] = { (i % 5) - 2.0, (i % 3) - 1.0, (i % 4) - 1.5 };
    ids[i] = particle(w, x, v, 1.0 + i % 3, 0.0, i / 7);
    mr_part_def d = mr_default_part_def();
    d.particles = &ids[i];
    d.count = 1;
    d.radius = radii[i % 7];
    assert_int_equal(mr_world_add_part(w, &d, NULL), MR_OK);
  }
  double worst = mr_world_tree_slack(w);
  for (int f = 1; f <= 60; f++) {
    assert_true(mr_world_step_to(w, f / 60.0, NULL) >= 0);
    worst = fmin(worst, mr_world_tree_slack(w));
  }
  printf("sphere trees: parents enclose children with at least %.3g m to spare\n", worst);
  assert_true(isfinite(worst));
  assert_true(worst >= -1e-12);
  mr_world_destroy(w);
}

/* A chain of 80 particles of 0.1 kg, 5 cm apart, lying on a floor of
 * μ = 0.5 under gravity and sliding along itself at 1 m/s: every link's
 * resting contact takes friction at every evaluation, all in one island,
 * more contacts than the world makes room for before its first step. */
enum { CHAIN = 80 };
static mr_world *chain_sliding_on_a_floor(void *user) {
  (void)user;
  mr_world *w = world(MR_EFFECT_GRAVITY | MR_EFFECT_PLANES | MR_EFFECT_CONSTRAINTS);
  for (int i = 0; i < CHAIN; i++) {
    const double x[3] = { 0.05 * i, 0, 0 }, v[3] = { 1, 0, 0 };
    particle(w, x, v, 0.1, 0.0, 0);
    mr_distance_def d = mr_default_distance_def();
    d.a = i - 1;
    d.b = i;
    if (i > 0) assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  }
  mr_plane_def f = mr_default_plane_def();
  f.friction = 0.5;
  assert_int_equal(mr_world_add_plane(w, &f, NULL), MR_OK);
  return w;
}

/* Whichever reallocation of a step with friction fails (the friction's
 * own work arrays among them, grown for the contacts of its largest
 * island), the step says so, or did without at no cost to its answer. A
 * friction solve that ran out of memory was taken as done, and the step
 * went on with the contacts' forces left out. The slide itself is checked
 * too: μ g = 4.9 m/s² slows it to 0.755 m/s in 0.05 s. */
static void out_of_memory_in_friction_reaches_the_caller(void **state) {
  (void)state;
  mr_world *w = chain_sliding_on_a_floor(NULL);
  assert_int_equal(mr_world_step_to(w, 0.05, NULL), MR_OK);
  for (int i = 0; i < CHAIN; i++) {
    double v[3];
    velocity(w, i, v);
    assert_true(fabs(v[0] - (1.0 - 0.5 * 9.81 * 0.05)) < 1e-3);
  }
  mr_world_destroy(w);
  if (!failing_realloc_works()) skip();
  assert_true(failing_realloc_each(chain_sliding_on_a_floor, NULL, 0.05) >= 2);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(oblique_bounce_with_friction),
    cmocka_unit_test(head_on_bounce_under_mixed_restitution),
    cmocka_unit_test(shortening_string_pulls_or_goes_slack_never_pushes),
    cmocka_unit_test(sphere_tree_parents_enclose_children),
    cmocka_unit_test(out_of_memory_in_friction_reaches_the_caller),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
