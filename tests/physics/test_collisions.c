/* Collisions (§4.4, §5.3, §5.4): a bounce to the height restitution
 * predicts, resting contact, Coulomb friction against μg, and sphere-tree
 * puppets that do not pass through each other. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mr_physics.h"

static mr_world *make_world(uint32_t effects, mr_world_def *override) {
  mr_world_def def = override ? *override : mr_default_world_def();
  def.effects = effects;
  mr_world *w = NULL;
  char msg[200];
  assert_int_equal(mr_world_create(&def, &w, msg, sizeof msg), MR_OK);
  return w;
}

static int add(mr_world *w, const double x[3], const double v[3], double r, int puppet) {
  mr_particle_def p = mr_default_particle_def();
  for (int k = 0; k < 3; k++) {
    p.position[k] = x[k];
    p.velocity[k] = v ? v[k] : 0.0;
  }
  p.radius = r;
  p.puppet = puppet;
  int id = -1;
  assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
  return id;
}

static int floor_plane(mr_world *w, double e, double mu) {
  mr_plane_def pl = mr_default_plane_def();
  pl.restitution = e;
  pl.friction = mu;
  int id = -1;
  assert_int_equal(mr_world_add_plane(w, &pl, &id), MR_OK);
  return id;
}

/* Dropped from h₀ = 1 m (bottom of the ball above the floor), restitution
 * e = 0.8: the ball leaves the floor at e·√(2 g h₀) and rises to e² h₀ =
 * 0.64 m. RK4 is exact for free flight, the contact time is located to
 * within the 1e-4 m contact slop and the apex is sampled every 1 ms
 * (height error g·dt²/8 ≈ 1e-6 m), so we allow 1 mm. */
static void ball_bounces_to_restitution_height(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.drag = 0;
  mr_world *w = make_world(MR_EFFECT_GRAVITY | MR_EFFECT_PLANES, &def);
  const double r = 0.1, h0 = 1.0, e = 0.8;
  int b = add(w, (double[3]){ 0, h0 + r, 0 }, NULL, r, 0);
  floor_plane(w, e, 0.0);
  double apex = 0, lowest = INFINITY;
  int bounced = 0;
  for (int i = 1; i <= 1100; i++) {
    assert_int_equal(mr_world_step_to(w, i * 0.001, NULL), MR_OK);
    double x[3], v[3];
    mr_world_particle_state(w, b, x, v);
    lowest = fmin(lowest, x[1] - r);
    if (v[1] > 0) bounced = 1;
    if (bounced) apex = fmax(apex, x[1] - r);
  }
  mr_stats st;
  mr_world_stats(w, &st);
  printf("bounce: apex %.6f m, predicted %.6f m, lowest %.3g m, collisions %llu\n", apex,
         e * e * h0, lowest, (unsigned long long)st.collisions);
  assert_true(bounced);
  assert_int_equal((int)st.collisions, 1);
  assert_true(fabs(apex - e * e * h0) < 1e-3);
  assert_true(lowest > -2e-4);
  mr_world_destroy(w);
}

/* A particle placed on the floor at rest stays there: no sinking, no
 * jitter, and a bouncing ball comes to rest on the floor instead of
 * chattering. Contact rows carry a compliance of 1e-6 of their diagonal
 * (eval.c), so a resting particle sags until K_s·χ makes up 1e-6 g:
 * χ = −1e-6·g/K_s ≈ −1e-7 m. We allow twice that, and 1e-6 m/s. */
static void resting_contact_holds_without_sinking_or_jitter(void **state) {
  (void)state;
  mr_world *w = make_world(MR_EFFECT_GRAVITY | MR_EFFECT_PLANES | MR_EFFECT_DRAG, NULL);
  const double r = 0.05;
  int still = add(w, (double[3]){ 0, r, 0 }, NULL, r, 0);
  int ball = add(w, (double[3]){ 1, 0.5 + r, 0 }, NULL, r, 1);
  floor_plane(w, 0.5, 0.3);
  double worst_y = 0, worst_v = 0;
  for (int f = 1; f <= 600; f++) {
    assert_int_equal(mr_world_step_to(w, f / 60.0, NULL), MR_OK);
    double x[3], v[3];
    mr_world_particle_state(w, still, x, v);
    worst_y = fmax(worst_y, fabs(x[1] - r));
    worst_v = fmax(worst_v, sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  }
  double xb[3], vb[3];
  mr_world_particle_state(w, ball, xb, vb);
  mr_stats st;
  mr_world_stats(w, &st);
  printf("resting: |y - r| <= %.3g m, |v| <= %.3g m/s; ball settles at %.3g m above rest, "
         "|v| = %.3g, %llu collisions\n",
         worst_y, worst_v, xb[1] - r, fabs(vb[1]), (unsigned long long)st.collisions);
  assert_true(worst_y < 2e-6 * 9.81 / 100.0);
  assert_true(worst_v < 1e-6);
  assert_true(fabs(xb[1] - r) < 1e-4);
  assert_true(fabs(vb[1]) < 1e-6);
  assert_true(st.collisions >= 3);
  mr_world_destroy(w);
}

/* Sliding at v₀ = 3 m/s with μ = 0.5 stops after v₀²/(2 μ g) = 0.9174 m.
 * Kinetic friction is exact under RK4 (constant deceleration); near rest the
 * force is limited to 2m|v|/Δt so it cannot reverse the motion. That tail
 * slides h·v/2 instead of v²/(2μg), at most μ g Δt²/8 = 1.5 mm at the
 * 0.05 s step, plus the step in which the limit takes over mid-way: we
 * assert twice the tail bound, μ g Δt²/4 = 3.1 mm (0.33 %). */
static void friction_stops_slide_at_mu_g_distance(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.drag = 0;
  mr_world *w = make_world(MR_EFFECT_GRAVITY | MR_EFFECT_PLANES, &def);
  const double r = 0.05, v0 = 3.0, mu = 0.5;
  int p = add(w, (double[3]){ 0, r, 0 }, (double[3]){ v0, 0, 0 }, r, 0);
  floor_plane(w, 0.0, mu);
  for (int f = 1; f <= 30; f++) assert_int_equal(mr_world_step_to(w, f * 0.1, NULL), MR_OK);
  double x[3], v[3];
  mr_world_particle_state(w, p, x, v);
  double expect = v0 * v0 / (2 * mu * 9.81);
  printf("friction: slid %.5f m, predicted %.5f m, error %.3g m, final speed %.3g m/s\n", x[0],
         expect, x[0] - expect, fabs(v[0]));
  assert_true(fabs(x[0] - expect) <= mu * 9.81 * 0.05 * 0.05 / 4);
  assert_true(fabs(v[0]) < 1e-6);
  assert_true(fabs(x[1] - r) < 2e-6 * 9.81 / 100.0); /* the contact's sag, see above */
  mr_world_destroy(w);
}

static void tetra(mr_world *w, const double c[3], const double v[3], double r, int puppet,
                  int ids[4]) {
  const double off[4][3] = { { 0.2, 0, 0 }, { -0.1, 0.17, 0 }, { -0.1, -0.17, 0 }, { 0, 0, 0.2 } };
  for (int i = 0; i < 4; i++) {
    double x[3] = { c[0] + off[i][0], c[1] + off[i][1], c[2] + off[i][2] };
    ids[i] = add(w, x, v, r, puppet);
  }
  mr_rigid_group_def g = mr_default_rigid_group_def();
  g.particles = ids;
  g.count = 4;
  assert_int_equal(mr_world_add_rigid_group(w, &g, NULL), MR_OK);
  mr_part_def part = mr_default_part_def();
  part.particles = ids;
  part.count = 4;
  part.restitution = 0.9;
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
}

/* Coulomb friction on a 20° slope (§4.4), for a particle and for a rigid
 * tetrahedron lying on three points, both starting at rest on it. With
 * μ = 0.5 > tan 20° = 0.364 friction holds them: static friction must
 * cancel the pull along the slope (applied only against a velocity and
 * limited by it, friction let this particle creep 0.28 m in 10 s). With μ
 * below tan 20° they slide 10 s with
 * s = ½ g (sinθ − μ cosθ) t².
 * mass[] gives the tetrahedron's four particles their masses (kg). */
static double slope_run(int body, double mu, const double mass[4]) {
  const double th = 20.0 * 3.14159265358979323846 / 180.0;
  const double n[3] = { -sin(th), cos(th), 0 }, along[3] = { cos(th), sin(th), 0 },
               side[3] = { 0, 0, 1 };
  mr_world *w = make_world(MR_EFFECT_GRAVITY | MR_EFFECT_PLANES | MR_EFFECT_CONSTRAINTS, NULL);
  mr_plane_def pl = mr_default_plane_def();
  pl.normal[0] = n[0];
  pl.normal[1] = n[1];
  pl.restitution = 0.0;
  pl.friction = mu;
  assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
  /* In slope coordinates (along, normal, side); radius 0.02 m. */
  const double pts[4][3] = {
    { 0, 0.02, 0 }, { 0.3, 0.02, 0 }, { 0.15, 0.02, 0.25 }, { 0.15, 0.25, 0.08 }
  };
  int count = body ? 4 : 1, ids[4];
  for (int i = 0; i < count; i++) {
    double x[3];
    for (int k = 0; k < 3; k++)
      x[k] = pts[i][0] * along[k] + pts[i][1] * n[k] + pts[i][2] * side[k];
    mr_particle_def p = mr_default_particle_def();
    memcpy(p.position, x, sizeof x);
    p.radius = 0.02;
    p.mass = mass[i];
    assert_int_equal(mr_world_add_particle(w, &p, &ids[i]), MR_OK);
  }
  if (body) {
    mr_rigid_group_def g = mr_default_rigid_group_def();
    g.particles = ids;
    g.count = 4;
    assert_int_equal(mr_world_add_rigid_group(w, &g, NULL), MR_OK);
  }
  double x0[3], x[3];
  mr_world_particle_state(w, ids[0], x0, NULL);
  for (int f = 1; f <= 600; f++) assert_int_equal(mr_world_step_to(w, f / 60.0, NULL), MR_OK);
  mr_world_particle_state(w, ids[0], x, NULL);
  double s = 0;
  for (int k = 0; k < 3; k++) s += (x0[k] - x[k]) * along[k]; /* downhill is −along */
  if (body) assert_true(mr_world_deviation(w) < 1e-6);
  mr_world_destroy(w);
  return s;
}

static void friction_holds_on_a_slope_and_slides_below_tan_theta(void **state) {
  (void)state;
  const double th = 20.0 * 3.14159265358979323846 / 180.0, g = 9.81;
  const double even[4] = { 1, 1, 1, 1 };
  for (int body = 0; body < 2; body++) {
    double held = slope_run(body, 0.5, even);
    double mu = body ? 0.3 : 0.2, slid = slope_run(body, mu, even);
    double expect = 0.5 * g * (sin(th) - mu * cos(th)) * 100.0;
    printf("slope, %s: mu 0.5 moved %.3g m in 10 s; mu %.1f slid %.6f m (expected %.6f)\n",
           body ? "tetrahedron" : "particle", held, mu, slid, expect);
    assert_true(fabs(held) < 1e-4);
    assert_true(fabs(slid - expect) < 1e-4 * expect);
  }
}

/* The same tetrahedron with its mass spread unevenly, the heaviest at the
 * apex or on the ground. Its three contacts then carry unequal loads, and
 * each one's friction moves the whole body, not its particle alone:
 * worked from the particle's own mass, the contacts disagreed for 32
 * rounds and it crept 1.2 cm in 10 s at μ = 0.5. It must hold at μ = 0.5
 * and at 0.38, just over tan 20° = 0.364 (friction in proportion to the
 * loads holds it, at 0.364 μN each), and slide at μ = 0.3 as a block
 * slides, whatever its masses. */
static void friction_holds_a_body_of_uneven_masses(void **state) {
  (void)state;
  const double th = 20.0 * 3.14159265358979323846 / 180.0, g = 9.81;
  const double masses[2][4] = { { 0.3, 0.5, 0.7, 2.0 }, { 2.0, 0.7, 0.5, 0.3 } };
  const double expect = 0.5 * g * (sin(th) - 0.3 * cos(th)) * 100.0;
  for (int k = 0; k < 2; k++) {
    const double held = slope_run(1, 0.5, masses[k]), barely = slope_run(1, 0.38, masses[k]);
    const double slid = slope_run(1, 0.3, masses[k]);
    printf("uneven tetrahedron %d: mu 0.5 moved %.3g m, mu 0.38 %.3g m, mu 0.3 slid %.6f m\n", k,
           held, barely, slid);
    assert_true(fabs(held) < 1e-4);
    assert_true(fabs(barely) < 1e-4);
    assert_true(fabs(slid - expect) < 1e-4 * expect);
  }
}

/* A bob lying on a 20° slope, tethered by a link in the slope's plane,
 * 30° below its level line, to a pinned anchor (r = 1 cm, clear of the
 * slope): it can move only across the link, about the anchor, so its
 * friction works along one direction of the plane, which neither of the
 * contact's tangents is; along the link no friction could move it. With
 * μ = 0.5 it stays; with μ = 0.1 it starts across the link as a block
 * slides on a slope of sinθ cos 30°, s = ½ g (sinθ cos 30° − μ cosθ) t²
 * (within 1 % over 0.1 s: the link turns 0.02 rad). */
static double tethered_run(double mu, double t_end) {
  const double th = 20.0 * 3.14159265358979323846 / 180.0,
               phi = 30.0 * 3.14159265358979323846 / 180.0;
  const double r = 0.02, len = 0.5;
  const double n[3] = { 0, cos(th), sin(th) }, down[3] = { 0, -sin(th), cos(th) };
  double along[3], across[3], a0[3], b0[3];
  for (int k = 0; k < 3; k++) {
    along[k] = cos(phi) * (k == 0) + sin(phi) * down[k];
    across[k] = -sin(phi) * (k == 0) + cos(phi) * down[k];
    a0[k] = r * n[k];
    b0[k] = a0[k] + len * along[k];
  }
  mr_world *w = make_world(MR_EFFECT_GRAVITY | MR_EFFECT_PLANES | MR_EFFECT_CONSTRAINTS, NULL);
  mr_plane_def pl = mr_default_plane_def();
  memcpy(pl.normal, n, sizeof n);
  pl.restitution = 0.0;
  pl.friction = mu;
  assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
  const int anchor = add(w, a0, NULL, 0.01, 0), bob = add(w, b0, NULL, r, 0);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = anchor;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  mr_distance_def link = mr_default_distance_def();
  link.a = anchor;
  link.b = bob;
  assert_int_equal(mr_world_add_distance(w, &link, NULL), MR_OK);
  double x[3];
  for (int f = 1; f <= (int)(t_end * 60.0 + 0.5); f++)
    assert_int_equal(mr_world_step_to(w, f / 60.0, NULL), MR_OK);
  mr_world_particle_state(w, bob, x, NULL);
  mr_world_destroy(w);
  double s = 0;
  for (int k = 0; k < 3; k++) s += (x[k] - b0[k]) * across[k];
  return s;
}

static void friction_works_along_the_one_direction_a_link_leaves_free(void **state) {
  (void)state;
  const double th = 20.0 * 3.14159265358979323846 / 180.0, g = 9.81, t = 0.1;
  const double held = tethered_run(0.5, 10.0), slid = tethered_run(0.1, t);
  const double expect =
      0.5 * g * (sin(th) * cos(30.0 * 3.14159265358979323846 / 180.0) - 0.1 * cos(th)) * t * t;
  printf("tethered bob: mu 0.5 moved %.3g m in 10 s; mu 0.1 slid %.6f m in %.2f s (block %.6f)\n",
         held, slid, t, expect);
  assert_true(fabs(held) < 1e-4);
  assert_true(fabs(slid - expect) < 0.01 * expect);
}

/* Coulomb friction between sphere-tree spheres (§4.4): a ball (r = 5 cm,
 * puppet 1) lies at rest on a pinned sphere of radius 100 m (puppet 0),
 * 20° off its top, which is locally a 20° slope. With μ = 0.5 it stays; with
 * μ = 0.2 and μ = 0 it slides 1 s down with s ≈ ½ g (sinθ − μ cosθ) t²
 * (within 2 %: the slope steepens by 0.4° over the slide). */
static double ball_on_sphere(double mu, double t_end) {
  const double th = 20.0 * 3.14159265358979323846 / 180.0, R = 100.0, r = 0.05;
  mr_world *w =
      make_world(MR_EFFECT_GRAVITY | MR_EFFECT_CONSTRAINTS | MR_EFFECT_PUPPET_COLLISION, NULL);
  int big = add(w, (double[3]){ 0, 0, 0 }, NULL, R, 0);
  int ball = add(w, (double[3]){ (R + r) * sin(th), (R + r) * cos(th), 0 }, NULL, r, 1);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = big;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  mr_part_def part = mr_default_part_def();
  part.count = 1;
  part.restitution = 0.0;
  part.friction = mu;
  part.particles = &big;
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  part.particles = &ball;
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  double x0[3], x[3];
  mr_world_particle_state(w, ball, x0, NULL);
  for (int f = 1; f <= (int)(t_end * 60.0 + 0.5); f++)
    assert_int_equal(mr_world_step_to(w, f / 60.0, NULL), MR_OK);
  mr_world_particle_state(w, ball, x, NULL);
  double gap = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - R - r;
  assert_true(fabs(gap) < 1e-3); /* it stays on the surface */
  mr_world_destroy(w);
  return sqrt((x[0] - x0[0]) * (x[0] - x0[0]) + (x[1] - x0[1]) * (x[1] - x0[1]) +
              (x[2] - x0[2]) * (x[2] - x0[2]));
}

static void friction_between_sphere_tree_spheres(void **state) {
  (void)state;
  const double th = 20.0 * 3.14159265358979323846 / 180.0, g = 9.81;
  double held = ball_on_sphere(0.5, 2.0);
  printf("ball on a sphere, mu 0.5: moved %.3g m in 2 s\n", held);
  assert_true(held < 1e-4);
  const double mus[2] = { 0.2, 0.0 };
  for (int i = 0; i < 2; i++) {
    double slid = ball_on_sphere(mus[i], 1.0), expect = 0.5 * g * (sin(th) - mus[i] * cos(th));
    printf("ball on a sphere, mu %.1f: slid %.4f m in 1 s (plane: %.4f m)\n", mus[i], slid, expect);
    assert_true(fabs(slid - expect) < 0.02 * expect);
  }
}

/* A resting sphere contact on a curved path needs its J̇q̇ (eq. 8): a ball
 * (r = 0.05 m, 1 kg) orbits a pinned sphere (R = 0.25 m) at 3 m/s, pulled
 * to its centre by a spring (200 N/m, rest 0: 60 N inwards) of which the
 * orbit needs m v²/d = 30 N, so the contact pushes with 30 N. Without the
 * centripetal term v²/d = 30 m/s² the contact would hold the wrong
 * acceleration and the gap would settle near −30/K_s = −0.3 m. No gravity,
 * no friction: the ball keeps its speed and stays on the surface. */
static void ball_orbits_a_sphere_on_a_resting_contact(void **state) {
  (void)state;
  const double R = 0.25, r = 0.05, d = R + r, speed = 3.0;
  mr_world_def def = mr_default_world_def();
  def.gravity[1] = 0.0;
  mr_world *w =
      make_world(MR_EFFECT_CONSTRAINTS | MR_EFFECT_SPRINGS | MR_EFFECT_PUPPET_COLLISION, &def);
  int centre = add(w, (double[3]){ 0, 0, 0 }, NULL, R, 0);
  int ball = add(w, (double[3]){ d, 0, 0 }, (double[3]){ 0, 0, speed }, r, 1);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = centre;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  mr_spring_def sp = mr_default_spring_def();
  sp.a = centre;
  sp.b = ball;
  sp.rest_length = 0.0;
  sp.stiffness = 200.0;
  sp.damping = 0.0;
  assert_int_equal(mr_world_add_spring(w, &sp, NULL), MR_OK);
  mr_part_def part = mr_default_part_def();
  part.count = 1;
  part.friction = 0.0;
  part.particles = &centre;
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  part.particles = &ball;
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  double worst_gap = 0, worst_speed = 0;
  for (int f = 1; f <= 120; f++) {
    assert_int_equal(mr_world_step_to(w, f / 60.0, NULL), MR_OK);
    double x[3], v[3];
    mr_world_particle_state(w, ball, x, v);
    worst_gap = fmax(worst_gap, fabs(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - d));
    worst_speed = fmax(worst_speed, fabs(sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - speed));
  }
  printf("orbit on a sphere contact: |gap| <= %.3g m, |speed - 3| <= %.3g m/s over 2 s\n",
         worst_gap, worst_speed);
  assert_true(worst_gap < 1e-3);
  assert_true(worst_speed < 0.03);
  mr_world_destroy(w);
}

/* Planes other than the floor: a wall x ≤ 1 (normal (−1, 0, 0), offset −1)
 * with restitution 1 sends a particle sliding at 2 m/s back at 2 m/s, its
 * surface stopping at the wall. The normal is normalised on entry. */
static void wall_plane_reflects_particle(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.drag = 0;
  mr_world *w = make_world(MR_EFFECT_PLANES, &def);
  int p = add(w, (double[3]){ 0, 0, 0 }, (double[3]){ 2, 0, 0 }, 0.1, 0);
  mr_plane_def wall = mr_default_plane_def();
  wall.normal[0] = -3.0; /* not unit on purpose */
  wall.normal[1] = 0.0;
  wall.offset = -1.0;
  wall.restitution = 1.0;
  wall.friction = 0.0;
  assert_int_equal(mr_world_add_plane(w, &wall, NULL), MR_OK);
  double far = -INFINITY;
  for (int f = 1; f <= 60; f++) {
    assert_int_equal(mr_world_step_to(w, f / 60.0, NULL), MR_OK);
    double x[3];
    mr_world_particle_state(w, p, x, NULL);
    far = fmax(far, x[0] + 0.1);
  }
  double x[3], v[3];
  mr_world_particle_state(w, p, x, v);
  printf("wall: farthest surface point %.6f m (wall at 1), v = %.6f m/s after\n", far, v[0]);
  assert_true(far < 1.0 + 2e-4);
  assert_true(fabs(v[0] + 2.0) <
              1e-5); /* the contact's 1e-6 compliance costs 2e-6 of the rebound */
  assert_true(fabs(x[0] - (0.9 - 2.0 * (1.0 - 0.45))) < 1e-3);
  mr_world_destroy(w);
}

/* Two rigid tetrahedra (one part each, sphere radius 0.12 m per particle)
 * thrown at each other at 2 m/s each: sampled every 2 ms, no leaf sphere of
 * one ever overlaps one of the other by more than twice the contact slop,
 * and they leave the impact moving apart. */
static void sphere_tree_puppets_do_not_interpenetrate(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.drag = 0;
  mr_world *w = make_world(MR_EFFECT_CONSTRAINTS | MR_EFFECT_PUPPET_COLLISION, &def);
  const double r = 0.12;
  int a[4], b[4];
  tetra(w, (double[3]){ -1, 0, 0 }, (double[3]){ 2, 0, 0 }, r, 0, a);
  tetra(w, (double[3]){ 1, 0.05, 0.03 }, (double[3]){ -2, 0, 0 }, r, 1, b);
  double worst = INFINITY;
  for (int f = 1; f <= 500; f++) {
    assert_int_equal(mr_world_step_to(w, f * 0.002, NULL), MR_OK);
    for (int i = 0; i < 4; i++)
      for (int j = 0; j < 4; j++) {
        double xa[3], xb[3];
        mr_world_particle_state(w, a[i], xa, NULL);
        mr_world_particle_state(w, b[j], xb, NULL);
        double d = sqrt((xa[0] - xb[0]) * (xa[0] - xb[0]) + (xa[1] - xb[1]) * (xa[1] - xb[1]) +
                        (xa[2] - xb[2]) * (xa[2] - xb[2]));
        worst = fmin(worst, d - 2 * r);
      }
  }
  double va[3], vb[3];
  mr_world_particle_state(w, a[0], NULL, va);
  mr_world_particle_state(w, b[0], NULL, vb);
  mr_stats st;
  mr_world_stats(w, &st);
  printf("sphere trees: smallest gap %.3g m, collisions %llu, vx %.3f / %.3f, deviation %.3g\n",
         worst, (unsigned long long)st.collisions, va[0], vb[0], mr_world_deviation(w));
  assert_true(st.collisions >= 1);
  assert_true(worst > -2e-4);
  assert_true(va[0] < 0 && vb[0] > 0);
  assert_true(mr_world_pass_calls(w, MR_PASS_PUPPET_COLLISION) > 0);
  mr_world_destroy(w);
}

/* A rigid tetrahedron dropped tilted onto the floor lands on several
 * points at once: its contact rows are redundant with each other and with
 * the group's links. It must come to rest (speed under 1 mm/s over the last
 * 2 s of 6 s, no particle below the floor by more than the slop) instead of
 * chattering on its contacts. */
static void rigid_body_settles_on_floor_without_chatter(void **state) {
  (void)state;
  mr_world *w = make_world(
      MR_EFFECT_GRAVITY | MR_EFFECT_DRAG | MR_EFFECT_CONSTRAINTS | MR_EFFECT_PLANES, NULL);
  const double r = 0.04;
  const double pts[4][3] = {
    { 0, 0.5, 0 }, { 0.3, 0.55, 0 }, { 0.1, 0.45, 0.3 }, { 0.12, 0.75, 0.1 }
  };
  int ids[4];
  for (int i = 0; i < 4; i++) ids[i] = add(w, pts[i], (double[3]){ 0.3, 0, 0 }, r, 0);
  mr_rigid_group_def g = mr_default_rigid_group_def();
  g.particles = ids;
  g.count = 4;
  assert_int_equal(mr_world_add_rigid_group(w, &g, NULL), MR_OK);
  floor_plane(w, 0.3, 0.5);
  double late_speed = 0, lowest = INFINITY;
  for (int f = 1; f <= 360; f++) {
    assert_int_equal(mr_world_step_to(w, f / 60.0, NULL), MR_OK);
    for (int i = 0; i < 4; i++) {
      double x[3], v[3];
      mr_world_particle_state(w, ids[i], x, v);
      lowest = fmin(lowest, x[1] - r);
      if (f > 240) late_speed = fmax(late_speed, sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    }
  }
  mr_stats st;
  mr_world_stats(w, &st);
  printf("tetrahedron on the floor: speed over the last 2 s <= %.3g m/s, lowest %.3g m, %llu "
         "collisions, %d resting contacts, deviation %.3g\n",
         late_speed, lowest, (unsigned long long)st.collisions, st.resting_contacts,
         mr_world_deviation(w));
  assert_true(late_speed < 1e-3);
  assert_true(lowest > -2e-4);
  assert_true(st.resting_contacts >= 3);
  assert_true(st.collisions < 40);
  assert_true(mr_world_deviation(w) < 1e-4);
  mr_world_destroy(w);
}

/* Self-collision (§4.4): two arms of one puppet, hinged at a pinned
 * shoulder, swing towards each other. Their hand spheres (parts {A} and
 * {C}) collide and bounce; the shoulder's big sphere (part {B}) overlaps
 * both hands from the start but is adjacent to them (joined by the arms'
 * distance constraints) and so is never tested. */
static void non_adjacent_parts_of_one_puppet_collide(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.drag = 0;
  mr_world *w = make_world(MR_EFFECT_CONSTRAINTS | MR_EFFECT_SELF_COLLISION, &def);
  const double r = 0.1;
  int b = add(w, (double[3]){ 0, 0, 0 }, NULL, 0.0, 0);
  int a = add(w, (double[3]){ 1, 0, 0 }, (double[3]){ 0, 1, 0 }, r, 0);
  int c = add(w, (double[3]){ 0, 1, 0 }, (double[3]){ 1, 0, 0 }, r, 0);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = b;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  mr_distance_def d = mr_default_distance_def();
  d.a = b;
  d.b = a;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  d.b = c;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  mr_part_def part = mr_default_part_def();
  part.count = 1;
  part.restitution = 1.0;
  part.particles = &a;
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  part.particles = &c;
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  part.particles = &b;
  part.radius = 0.95;
  assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  double worst = INFINITY;
  for (int f = 1; f <= 600; f++) { /* they meet at t = π/4 s */
    assert_int_equal(mr_world_step_to(w, f * 0.002, NULL), MR_OK);
    double xa[3], xc[3];
    mr_world_particle_state(w, a, xa, NULL);
    mr_world_particle_state(w, c, xc, NULL);
    double dist = sqrt((xa[0] - xc[0]) * (xa[0] - xc[0]) + (xa[1] - xc[1]) * (xa[1] - xc[1]) +
                       (xa[2] - xc[2]) * (xa[2] - xc[2]));
    worst = fmin(worst, dist - 2 * r);
  }
  double va[3];
  mr_world_particle_state(w, a, NULL, va);
  mr_stats st;
  mr_world_stats(w, &st);
  printf("self-collision: smallest gap %.3g m, collisions %llu, hand A now moving (%.3f, %.3f)\n",
         worst, (unsigned long long)st.collisions, va[0], va[1]);
  assert_int_equal((int)st.collisions, 1);
  /* B overlaps A and C all along; as adjacent parts they never make a
   * contact, so once the hands are apart no contact is left. */
  assert_int_equal(st.resting_contacts, 0);
  assert_true(worst > -2e-4);
  assert_true(va[1] < 0); /* A swung back down */
  assert_int_equal((int)mr_world_pass_calls(w, MR_PASS_PUPPET_COLLISION), 0);
  mr_world_destroy(w);
}

/* The depth reading is the deepest overlap in the current state, in m:
 * balls 5 mm and 3 mm into the floor read 5 mm; the deeper one lifted out,
 * 3 mm; both, 0. */
static void penetration_reads_the_deepest_overlap(void **state) {
  (void)state;
  mr_world *w = make_world(MR_EFFECT_PLANES, NULL);
  floor_plane(w, 0.5, 0.3);
  int deep = add(w, (double[3]){ 0, 0.015, 0 }, NULL, 0.02, 0);
  int shallow = add(w, (double[3]){ 1, 0.027, 0 }, NULL, 0.03, 1);
  const double still[3] = { 0, 0, 0 };
  assert_true(fabs(mr_world_penetration(w) - 0.005) < 1e-12);
  assert_int_equal(mr_world_set_particle_state(w, deep, (double[3]){ 0, 0.5, 0 }, still), MR_OK);
  assert_true(fabs(mr_world_penetration(w) - 0.003) < 1e-12);
  assert_int_equal(mr_world_set_particle_state(w, shallow, (double[3]){ 1, 0.5, 0 }, still), MR_OK);
  assert_true(mr_world_penetration(w) == 0.0);
  mr_world_destroy(w);
}

/* A frame's particle is the hand's: the floor does not push it, so one
 * held 10 cm under the floor makes no contact and no depth, and the puppet
 * particle resting on the floor beside it is the only contact. */
static void a_frame_particle_under_the_floor_makes_no_contact(void **state) {
  (void)state;
  mr_world *w = make_world(MR_EFFECT_GRAVITY | MR_EFFECT_PLANES | MR_EFFECT_FRAMES, NULL);
  floor_plane(w, 0.5, 0.3);
  mr_frame_def f = mr_default_frame_def();
  int frame;
  assert_int_equal(mr_world_add_frame(w, &f, &frame), MR_OK);
  mr_particle_def p = mr_default_particle_def();
  p.position[1] = -0.1;
  p.radius = 0.02;
  p.frame = frame;
  assert_int_equal(mr_world_add_particle(w, &p, NULL), MR_OK);
  add(w, (double[3]){ 1, 0.02, 0 }, NULL, 0.02, 0);
  assert_true(mr_world_penetration(w) == 0.0);
  mr_step_report rep;
  assert_int_equal(mr_world_step_to(w, 0.2, &rep), MR_OK);
  mr_stats st;
  mr_world_stats(w, &st);
  printf("frame particle under the floor: %d collisions, %d resting contacts\n", rep.collisions,
         st.resting_contacts);
  assert_int_equal(rep.collisions, 0);
  assert_int_equal(st.resting_contacts, 1);
  mr_world_destroy(w);
}

/* A taut string past its length is an over-length, not a depth: a bob
 * 10 cm beyond its 0.5 m string, far above the floor, reads no depth. */
static void a_string_past_its_length_is_no_depth(void **state) {
  (void)state;
  mr_world *w = make_world(MR_EFFECT_PLANES | MR_EFFECT_FRAMES | MR_EFFECT_STRINGS, NULL);
  floor_plane(w, 0.5, 0.3);
  mr_frame_def f = mr_default_frame_def();
  f.pose.position[1] = 2.0;
  int frame;
  assert_int_equal(mr_world_add_frame(w, &f, &frame), MR_OK);
  mr_particle_def p = mr_default_particle_def();
  p.frame = frame;
  p.position[1] = 2.0;
  int bar;
  assert_int_equal(mr_world_add_particle(w, &p, &bar), MR_OK);
  int bob = add(w, (double[3]){ 0, 1.4, 0 }, NULL, 0.02, 0);
  mr_string_def sd = mr_default_string_def();
  sd.frame_particle = bar;
  sd.puppet_particle = bob;
  sd.rest_length = 0.5;
  assert_int_equal(mr_world_add_string(w, &sd, NULL), MR_OK);
  assert_true(mr_world_string_stretch(w) > 0.19); /* it is 20 % over */
  assert_true(mr_world_penetration(w) == 0.0);
  mr_world_destroy(w);
}

/* Friction between two free spheres is a pair of opposite forces: a ball
 * slid across the top of another, on a floor without friction, leaves the
 * pair's momentum along the slide as it was, while it slows the one and
 * drags the other. */
static void friction_between_two_free_spheres_keeps_their_momentum(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.drag = 0.0;
  mr_world *w = make_world(MR_EFFECT_GRAVITY | MR_EFFECT_PLANES | MR_EFFECT_PUPPET_COLLISION, &def);
  floor_plane(w, 0.0, 0.0);
  const double r = 0.05;
  int low = add(w, (double[3]){ 0, r, 0 }, NULL, r, 0);
  int top = add(w, (double[3]){ 0, 3 * r, 0 }, (double[3]){ 0.5, 0, 0 }, r, 1);
  const int ids[2] = { low, top };
  for (int i = 0; i < 2; i++) {
    mr_part_def d = mr_default_part_def();
    d.particles = &ids[i];
    d.count = 1;
    d.radius = r;
    d.restitution = 0.0;
    d.friction = 0.5;
    assert_int_equal(mr_world_add_part(w, &d, NULL), MR_OK);
  }
  assert_int_equal(mr_world_step_to(w, 0.05, NULL), MR_OK);
  double vl[3], vt[3];
  mr_world_particle_state(w, low, NULL, vl);
  mr_world_particle_state(w, top, NULL, vt);
  printf("after 50 ms: top %.4g m/s, bottom %.4g m/s, momentum %.6g of 0.5\n", vt[0], vl[0],
         vt[0] + vl[0]);
  assert_true(vt[0] < 0.45); /* slowed */
  assert_true(vl[0] > 0.05); /* dragged along */
  assert_true(fabs(vt[0] + vl[0] - 0.5) < 1e-6);
  mr_world_destroy(w);
}

/* Restitution is a fraction of the closing speed: above 1 a plane would
 * make energy, and is refused. */
static void a_plane_with_restitution_over_1_is_refused(void **state) {
  (void)state;
  mr_world *w = make_world(MR_EFFECT_PLANES, NULL);
  mr_plane_def pl = mr_default_plane_def();
  pl.restitution = 1.5;
  assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_ERR_ARG);
  pl.restitution = 1.0;
  assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
  mr_world_destroy(w);
}

/* Two rigid tetrahedra of uneven masses sliding on a floor with μ = 0.5,
 * 5 m apart, and a ball lying still: their rows are blocks of eq. 8 of
 * their own, and what one body's
 * friction comes to must not hear the other. Body A slides the same way
 * in both runs, body B slides in one and lies still in the other; with
 * fixed steps, A's state after 0.5 s must be the same to the bit. Worked
 * over both bodies at once, B's sliding set the rounds' tolerance, their
 * count and the skip of the probes for A as well (and a crowd of puppets
 * lying on a floor cost the cube of its contacts). */
static void friction_on_one_body_does_not_hear_another(void **state) {
  (void)state;
  double got[2][4][6];
  for (int run = 0; run < 2; run++) {
    mr_world_def def = mr_default_world_def();
    def.dt_initial = def.dt_min = def.dt_max = def.dt_floor = 0.005;
    mr_world *w = make_world(MR_EFFECT_GRAVITY | MR_EFFECT_PLANES | MR_EFFECT_CONSTRAINTS, &def);
    floor_plane(w, 0.0, 0.5);
    const double r = 0.02, mass[4] = { 0.3, 0.5, 0.7, 2.0 };
    const double pts[4][3] = {
      { 0, r, 0 }, { 0.3, r, 0 }, { 0.15, r, 0.25 }, { 0.15, 0.25, 0.08 }
    };
    const double vel[2][3] = { { 0.0, 0.0, 0.6 }, { run == 0 ? 0.8 : 0.0, 0.0, 0.0 } };
    int ids[2][4];
    for (int b = 0; b < 2; b++) {
      for (int i = 0; i < 4; i++) {
        mr_particle_def p = mr_default_particle_def();
        for (int k = 0; k < 3; k++) {
          p.position[k] = pts[i][k] + (k == 0 ? 5.0 * b : 0.0);
          p.velocity[k] = vel[b][k];
        }
        p.radius = r;
        p.mass = mass[i];
        assert_int_equal(mr_world_add_particle(w, &p, &ids[b][i]), MR_OK);
      }
      mr_rigid_group_def g = mr_default_rigid_group_def();
      g.particles = ids[b];
      g.count = 4;
      assert_int_equal(mr_world_add_rigid_group(w, &g, NULL), MR_OK);
    }
    /* Last, a ball lying still 5 m the other way: a block with nothing to
     * stop, which asks for no friction, after two that do. */
    const int ball = add(w, (double[3]){ -5.0, r, 0.0 }, NULL, r, 0);
    for (int f = 1; f <= 50; f++) assert_int_equal(mr_world_step_to(w, f / 100.0, NULL), MR_OK);
    for (int i = 0; i < 4; i++) mr_world_particle_state(w, ids[0][i], got[run][i], got[run][i] + 3);
    double xc[3];
    mr_world_particle_state(w, ball, xc, NULL);
    assert_true(xc[0] == -5.0 && xc[2] == 0.0);
    double xb[3];
    mr_world_particle_state(w, ids[1][0], xb, NULL);
    /* B slid in the first run (0.8²/(2 μ g) = 6.5 cm) and lay still in the
     * second; A slid 0.6²/(2 μ g) = 3.7 cm along z in both. */
    printf("island friction, run %d: A slid %.5f m along z, B %.5f m along x\n", run,
           got[run][0][2], xb[0] - 5.0);
    assert_true(run == 0 ? fabs(xb[0] - 5.0 - 0.8 * 0.8 / 9.81) < 5e-4 : fabs(xb[0] - 5.0) < 1e-6);
    assert_true(fabs(got[run][0][2] - 0.6 * 0.6 / 9.81) < 5e-4);
    mr_world_destroy(w);
  }
  assert_memory_equal(got[0], got[1], sizeof got[0]);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(ball_bounces_to_restitution_height),
    cmocka_unit_test(resting_contact_holds_without_sinking_or_jitter),
    cmocka_unit_test(friction_stops_slide_at_mu_g_distance),
    cmocka_unit_test(friction_holds_on_a_slope_and_slides_below_tan_theta),
    cmocka_unit_test(friction_holds_a_body_of_uneven_masses),
    cmocka_unit_test(friction_works_along_the_one_direction_a_link_leaves_free),
    cmocka_unit_test(friction_on_one_body_does_not_hear_another),
    cmocka_unit_test(friction_between_sphere_tree_spheres),
    cmocka_unit_test(ball_orbits_a_sphere_on_a_resting_contact),
    cmocka_unit_test(rigid_body_settles_on_floor_without_chatter),
    cmocka_unit_test(wall_plane_reflects_particle),
    cmocka_unit_test(sphere_tree_puppets_do_not_interpenetrate),
    cmocka_unit_test(non_adjacent_parts_of_one_puppet_collide),
    cmocka_unit_test(penetration_reads_the_deepest_overlap),
    cmocka_unit_test(a_frame_particle_under_the_floor_makes_no_contact),
    cmocka_unit_test(a_string_past_its_length_is_no_depth),
    cmocka_unit_test(friction_between_two_free_spheres_keeps_their_momentum),
    cmocka_unit_test(a_plane_with_restitution_over_1_is_refused),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
