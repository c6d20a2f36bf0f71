/* Hard cases: divergence (§7) resets to the start configuration and carries
 * on; dependent constraints are reported with bounded forces (§4.3, §5.1);
 * bad input is refused at build time with a message naming it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mr_physics.h"

static mr_world *make(uint32_t effects, mr_solve_method solver) {
  mr_world_def def = mr_default_world_def();
  def.effects = effects;
  def.solver = solver;
  mr_world *w = NULL;
  char msg[200];
  assert_int_equal(mr_world_create(&def, &w, msg, sizeof msg), MR_OK);
  return w;
}

static int add(mr_world *w, double x, double y, double z) {
  mr_particle_def p = mr_default_particle_def();
  p.position[0] = x;
  p.position[1] = y;
  p.position[2] = z;
  int id = -1;
  assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
  return id;
}

/* A hand-driven point that goes NaN for 30 ms (a broken input device). */
static void nan_curve(void *user, double t, double pos[3], double vel[3], double acc[3]) {
  (void)user;
  double bad = (t >= 0.5 && t < 0.53) ? NAN : 0.0;
  pos[0] = 0.2 * sin(4 * t) + bad;
  pos[1] = 1.0;
  pos[2] = 0.0;
  vel[0] = 0.8 * cos(4 * t);
  vel[1] = vel[2] = 0.0;
  acc[0] = -3.2 * sin(4 * t);
  acc[1] = acc[2] = 0.0;
}

static void nan_world_resets_to_start_counts_and_keeps_stepping(void **state) {
  (void)state;
  /* A floor too, so the NaN state also passes through contact detection. */
  mr_world *w = make(MR_EFFECT_GRAVITY | MR_EFFECT_CONSTRAINTS | MR_EFFECT_DRAG | MR_EFFECT_PLANES,
                     MR_SOLVE_LDLT);
  int hand = add(w, 0, 1, 0), bob = add(w, 0.3, 0.3, 0.1);
  mr_plane_def floor = mr_default_plane_def();
  floor.offset = -1.0;
  assert_int_equal(mr_world_add_plane(w, &floor, NULL), MR_OK);
  add(w, 2, -1, 0); /* resting on the floor: its contact row is in every solve */
  mr_curve_def c = mr_default_curve_def();
  c.particle = hand;
  c.fn = nan_curve;
  assert_int_equal(mr_world_add_curve(w, &c, NULL), MR_OK);
  mr_distance_def d = mr_default_distance_def();
  d.a = hand;
  d.b = bob;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  double start[9];
  mr_world_positions(w, start, 3);
  int resets = 0, moved = 0;
  while (mr_world_time(w) < 2.0) {
    mr_step_report rep;
    mr_status s = mr_world_step(w, &rep);
    if (s == MR_DIVERGED) {
      /* Right after the reset the state is the start state, bit for bit:
       * positions, and velocities (all started at rest). */
      double now[9];
      mr_world_positions(w, now, 3);
      assert_memory_equal(now, start, sizeof now);
      for (int i = 1; i < 3; i++) {
        double vel[3];
        mr_world_particle_state(w, i, NULL, vel);
        assert_true(vel[0] == 0.0 && vel[1] == 0.0 && vel[2] == 0.0);
      }
      assert_int_equal(rep.divergences, 1);
      assert_non_null(strstr(mr_world_last_error(w), "start configuration"));
      resets++;
    } else {
      assert_int_equal(s, MR_OK);
    }
    double x[3];
    mr_world_particle_state(w, bob, x, NULL);
    assert_true(isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]));
    if (mr_world_time(w) > 0.6 && fabs(x[0] - 0.3) > 1e-3) moved = 1;
  }
  mr_stats st;
  mr_world_stats(w, &st);
  printf("divergence: %d resets (stats %llu), deviation at 2 s %.3g\n", resets,
         (unsigned long long)st.divergences, mr_world_deviation(w));
  assert_true(resets >= 1 && resets <= 5);
  assert_int_equal((int)st.divergences, resets);
  assert_true(moved);
  assert_true(mr_world_deviation(w) < 1e-2);
  mr_world_destroy(w);
}

/* A rigid tetrahedron (six rows) with one of its edges held again by a
 * distance of its own, a dependent row, and a corner pinned. */
static void redundant_tetrahedron(mr_world *w, int ids[4]) {
  const double at[4][3] = { { 0, 0, 0 }, { 0.4, 0, 0 }, { 0.2, 0, 0.35 }, { 0.2, 0.3, 0.1 } };
  for (int k = 0; k < 4; k++) ids[k] = add(w, at[k][0], at[k][1], at[k][2]);
  mr_rigid_group_def g = mr_default_rigid_group_def();
  g.particles = ids;
  g.count = 4;
  assert_int_equal(mr_world_add_rigid_group(w, &g, NULL), MR_OK);
  assert_int_equal(mr_world_constraint_rows(w), 6);
  mr_distance_def d = mr_default_distance_def();
  d.a = ids[0];
  d.b = ids[1];
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = ids[3];
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
}

/* A rigid tetrahedron (6 links, §5.1) hung from a pin, plus a duplicate of
 * one link: J has a dependent row. Every solver reports it (LDLᵀ and Eigen
 * by their pivots, Gauss–Seidel and CG by their screen for parallel pairs)
 * and stays bounded; the multipliers (constraint forces per unit
 * length) stay under 100 N, the order of the tetrahedron's weight × a few. */
static void dependent_rows_reported_and_forces_bounded(void **state) {
  (void)state;
  const mr_solve_method methods[] = { MR_SOLVE_LDLT, MR_SOLVE_EIGEN, MR_SOLVE_GAUSS_SEIDEL,
                                      MR_SOLVE_CG };
  for (int m = 0; m < 4; m++) {
    mr_world *w = make(MR_EFFECT_GRAVITY | MR_EFFECT_CONSTRAINTS | MR_EFFECT_DRAG, methods[m]);
    int ids[4];
    redundant_tetrahedron(w, ids);
    double worst = 0;
    int reported = 0;
    for (int f = 1; f <= 120; f++) {
      mr_step_report rep;
      mr_status s = mr_world_step_to(w, f / 60.0, &rep);
      assert_true(s == MR_OK || s == MR_DEPENDENT);
      if (s == MR_DEPENDENT) {
        assert_true(rep.dependent >= 1);
        assert_non_null(strstr(mr_world_last_error(w), "dependent"));
        reported = 1;
      }
      mr_stats st;
      mr_world_stats(w, &st);
      worst = fmax(worst, st.max_multiplier);
      assert_true(isfinite(st.max_multiplier));
    }
    mr_stats st;
    mr_world_stats(w, &st);
    printf("%-12s dependent reported: %s, max |lambda| %.3g, deviation %.3g, divergences %llu\n",
           mr_solve_method_name(methods[m]), reported ? "yes" : "no", worst, mr_world_deviation(w),
           (unsigned long long)st.divergences);
    assert_true(reported);
    assert_true(worst < 100.0);
    assert_true(mr_world_deviation(w) < 1e-3);
    assert_int_equal((int)st.divergences, 0);
    mr_world_destroy(w);
  }
}

/* §4.3: every solver method, run through the world, moves a well-posed
 * system the same way. A chain of ten links pinned at one end falls from
 * horizontal for 1 s at a fixed 0.01 s step (so every method takes the same
 * steps); Gauss–Seidel, CG and Eigen end within 1e-6 m of the sparse LDLᵀ
 * default, none fails to converge, and the chain keeps its links. */
static void every_solver_moves_a_chain_alike(void **state) {
  (void)state;
  const mr_solve_method methods[] = { MR_SOLVE_LDLT, MR_SOLVE_EIGEN, MR_SOLVE_GAUSS_SEIDEL,
                                      MR_SOLVE_CG };
  enum { N = 11 };
  double ref[3 * N];
  for (int m = 0; m < 4; m++) {
    mr_world_def def = mr_default_world_def();
    def.effects = MR_EFFECT_GRAVITY | MR_EFFECT_CONSTRAINTS;
    def.solver = methods[m];
    def.dt_min = def.dt_max = def.dt_initial = 0.01;
    mr_world *w = NULL;
    assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
    int ids[N];
    for (int i = 0; i < N; i++) ids[i] = add(w, 0.1 * i, 1, 0.01 * (i % 2));
    mr_pin_def pin = mr_default_pin_def();
    pin.particle = ids[0];
    assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
    for (int i = 1; i < N; i++) {
      mr_distance_def d = mr_default_distance_def();
      d.a = ids[i - 1];
      d.b = ids[i];
      assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
    }
    assert_int_equal(mr_world_step_to(w, 1.0, NULL), MR_OK);
    double x[3 * N];
    assert_int_equal(mr_world_positions(w, x, N), N);
    mr_stats st;
    mr_world_stats(w, &st);
    double diff = 0;
    if (m == 0) memcpy(ref, x, sizeof ref);
    for (int i = 0; i < 3 * N; i++) diff = fmax(diff, fabs(x[i] - ref[i]));
    printf("%-12s %llu solves, %llu iterations, %llu failures, |x - x_ldlt| %.3g m, tip (%.4f, "
           "%.4f) m, "
           "deviation %.3g\n",
           mr_solve_method_name(methods[m]), (unsigned long long)st.solves,
           (unsigned long long)st.solver_iterations, (unsigned long long)st.solver_failures, diff,
           x[3 * (N - 1)], x[3 * (N - 1) + 1], mr_world_deviation(w));
    assert_int_equal((int)st.solver_failures, 0);
    assert_int_equal((int)st.steps, 100);
    assert_true(diff < 1e-6);
    assert_true(fabs(x[3 * (N - 1)] - 1.0) + fabs(x[3 * (N - 1) + 1] - 1.0) > 0.3); /* it swung */
    assert_true(mr_world_deviation(w) < 1e-2);
    mr_world_destroy(w);
  }
}

/* A step that diverges at a long Δt is first retried at dt_min, and only
 * a failure there resets the world (§7). A pendulum bob also held sideways
 * by a stiff spring (ω = 141/s) blows up in one 0.05 s RK4 step
 * (ω Δt = 7) and is fine at 0.01 s (ω Δt = 1.4): every divergence is
 * caught by the retry, none resets, and the run ends finite and within
 * the hard cases' 5 % (steps at dt_min are accepted over 1 %). */
static void divergence_is_retried_at_the_lower_bound_before_a_reset(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_GRAVITY | MR_EFFECT_CONSTRAINTS | MR_EFFECT_SPRINGS;
  def.dt_initial = 0.05;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  int pivot = add(w, 0, 1, 0), bob = add(w, 0.01, 0, 0), anchor = add(w, 1, 0, 0);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = pivot;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  pin.particle = anchor;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  mr_distance_def d = mr_default_distance_def();
  d.a = pivot;
  d.b = bob;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  mr_spring_def sp = mr_default_spring_def();
  sp.a = anchor;
  sp.b = bob;
  sp.rest_length = 1.0;
  sp.stiffness = 2e4;
  sp.damping = 0.0;
  assert_int_equal(mr_world_add_spring(w, &sp, NULL), MR_OK);
  mr_step_report rep;
  assert_int_equal(mr_world_step_to(w, 2.0, &rep), MR_OK);
  mr_stats st;
  mr_world_stats(w, &st);
  double x[3];
  mr_world_particle_state(w, bob, x, NULL);
  printf("stiff spring: %llu steps, %llu rejected, %llu resets, dt %.3f..%.3f s, deviation %.3g\n",
         (unsigned long long)st.steps, (unsigned long long)st.rejected,
         (unsigned long long)st.divergences, st.min_dt, st.max_dt, mr_world_deviation(w));
  assert_int_equal((int)st.divergences, 0);
  assert_true(st.rejected > 0);
  assert_true(isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]));
  assert_true(mr_world_deviation(w) < 0.05);
  mr_world_destroy(w);
}

static void bad_input_is_refused_with_a_message(void **state) {
  (void)state;
  mr_world *w = make(MR_EFFECT_GRAVITY | MR_EFFECT_CONSTRAINTS, MR_SOLVE_LDLT);
  int a = add(w, 0, 0, 0), b = add(w, 0, 0, 0), c = add(w, 1, 0, 0), e = add(w, 0, 1, 0);
  int rows = mr_world_constraint_rows(w);

  mr_distance_def d = mr_default_distance_def(); /* coincident particles */
  d.a = a;
  d.b = b;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_ERR_DEGENERATE);
  assert_non_null(strstr(mr_world_last_error(w), "coincide"));
  d.b = c; /* zero length */
  d.length = 0.0;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_ERR_DEGENERATE);
  assert_non_null(strstr(mr_world_last_error(w), "zero length"));
  d.length = NAN;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_ERR_NONFINITE);
  d.length = -1;
  d.b = 99;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_ERR_ID);
  assert_non_null(strstr(mr_world_last_error(w), "99"));

  mr_particle_def p = mr_default_particle_def();
  p.mass = -1.0;
  int n = mr_world_particle_count(w);
  assert_int_equal(mr_world_add_particle(w, &p, NULL), MR_ERR_ARG);
  assert_non_null(strstr(mr_world_last_error(w), "mass"));
  p.mass = 0.0;
  assert_int_equal(mr_world_add_particle(w, &p, NULL), MR_ERR_ARG);
  p.mass = 1.0;
  p.position[1] = NAN;
  assert_int_equal(mr_world_add_particle(w, &p, NULL), MR_ERR_NONFINITE);
  p.position[1] = 0;
  p.velocity[2] = INFINITY;
  assert_int_equal(mr_world_add_particle(w, &p, NULL), MR_ERR_NONFINITE);
  assert_int_equal(mr_world_particle_count(w), n);

  int flat[4] = { a, c, e, add(w, 1, 1, 0) }; /* all in z = 0 */
  mr_rigid_group_def g = mr_default_rigid_group_def();
  g.particles = flat;
  g.count = 4;
  assert_int_equal(mr_world_add_rigid_group(w, &g, NULL), MR_ERR_DEGENERATE);
  assert_non_null(strstr(mr_world_last_error(w), "coplanar"));
  int same[3] = { a, b, c };
  g.particles = same;
  g.count = 3;
  assert_int_equal(mr_world_add_rigid_group(w, &g, NULL), MR_ERR_DEGENERATE);
  assert_int_equal(mr_world_constraint_rows(w), rows); /* nothing half-added */

  double nan3[3] = { NAN, 0, 0 }, zero3[3] = { 0, 0, 0 };
  assert_int_equal(mr_world_set_particle_state(w, a, nan3, zero3), MR_ERR_NONFINITE);
  assert_int_equal(mr_world_step_to(w, 1.0, NULL), MR_OK);
  assert_int_equal(mr_world_step_to(w, 0.5, NULL), MR_ERR_TIME);
  assert_int_equal(mr_world_step_to(w, NAN, NULL), MR_ERR_NONFINITE);
  mr_world_destroy(w);

  mr_world_def def = mr_default_world_def();
  char msg[200] = "";
  def.dt_min = 0.1; /* above dt_max */
  assert_int_equal(mr_world_create(&def, &w, msg, sizeof msg), MR_ERR_ARG);
  assert_null(w);
  assert_non_null(strstr(msg, "dt_min"));
  def = mr_default_world_def();
  def.gravity[1] = NAN;
  assert_int_equal(mr_world_create(&def, &w, msg, sizeof msg), MR_ERR_NONFINITE);
  assert_non_null(strstr(msg, "gravity"));
}

/* The step guard: a world asked for far more steps than it may take in one
 * call stops with MR_ERR_LIMIT instead of running away. */
static void step_limit_stops_runaway_calls(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.max_steps_per_call = 50;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  add(w, 0, 0, 0);
  assert_int_equal(mr_world_step_to(w, 1e6, NULL), MR_ERR_LIMIT);
  assert_true(mr_world_time(w) > 0.4 && mr_world_time(w) < 3.0);
  mr_world_destroy(w);
}

/* The guard counts steps exactly: a call allowed 5 fixed steps of 10 ms
 * takes 5 and stops at 50 ms, not a sixth. */
static void step_limit_allows_exactly_its_steps(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.max_steps_per_call = 5;
  def.dt_floor = def.dt_min = def.dt_max = def.dt_initial = 0.01;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  add(w, 0, 0, 0);
  mr_step_report rep;
  assert_int_equal(mr_world_step_to(w, 1.0, &rep), MR_ERR_LIMIT);
  assert_int_equal(rep.steps, 5);
  assert_true(fabs(mr_world_time(w) - 0.05) < 1e-12);
  mr_world_destroy(w);
}

/* A call that diverged says so, even when its solves also met dependent
 * rows: the reset is what the caller must know of. A rigid tetrahedron
 * with a redundant distance and a pin (dependent rows) under a max_speed
 * every step passes. */
static void divergence_outranks_dependent_rows(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.max_speed = 1e-3;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  int ids[4];
  redundant_tetrahedron(w, ids);
  mr_step_report rep;
  assert_int_equal(mr_world_step_to(w, 0.1, &rep), MR_DIVERGED);
  printf("diverged with %d dependent rows: %s\n", rep.dependent, mr_world_last_error(w));
  assert_true(rep.dependent > 0);
  assert_true(rep.divergences > 0);
  assert_non_null(strstr(mr_world_last_error(w), "max_speed"));
  mr_world_destroy(w);
}

/* mr_rigid_group_shape names the points of a fault, and no point where
 * there is none: −1 for a sound group, a group of none or no positions
 * (a scene loader reads the indices it is given back to name them). */
static void group_shape_names_its_points_or_none(void **state) {
  (void)state;
  int i = 7, j = 7;
  assert_int_equal(mr_rigid_group_shape(NULL, 3, &i, &j), MR_SHAPE_OK);
  assert_true(i == -1 && j == -1);
  const double tetra[12] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  i = j = 7;
  assert_int_equal(mr_rigid_group_shape(tetra, 0, &i, &j), MR_SHAPE_OK);
  assert_true(i == -1 && j == -1);
  i = j = 7;
  assert_int_equal(mr_rigid_group_shape(tetra, 4, &i, &j), MR_SHAPE_OK);
  assert_true(i == -1 && j == -1);
  const double twice[9] = { 0, 0, 0, 1, 0, 0, 1, 0, 0 };
  assert_int_equal(mr_rigid_group_shape(twice, 3, &i, &j), MR_SHAPE_COINCIDENT);
  assert_true(i == 2 && j == 1);
  const double line[9] = { 0, 0, 0, 1, 0, 0, 2, 0, 0 };
  assert_int_equal(mr_rigid_group_shape(line, 3, &i, &j), MR_SHAPE_COLLINEAR);
  assert_true(i == 2 && j == -1);
}

/* A member far from a small group sees every three earlier members nearly
 * edge on, so it fixes no place (the scale-free measure falls under
 * MR_GROUP_MIN_SHAPE). It is the fifth, the first member past the starting
 * tetrahedron, that the shape test must reach: a loader that missed it
 * would accept a group the world's add call then refuses. */
static void a_fifth_member_far_off_is_flat_for_the_loader_and_the_world(void **state) {
  (void)state;
  const double five[15] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 100, 0 };
  int i = 7, j = 7;
  assert_int_equal(mr_rigid_group_shape(five, 5, &i, &j), MR_SHAPE_FLAT_MEMBER);
  assert_true(i == 4 && j == -1);
  mr_world *w = make(MR_EFFECT_CONSTRAINTS, MR_SOLVE_LDLT);
  int ids[5];
  for (int k = 0; k < 5; k++) ids[k] = add(w, five[3 * k], five[3 * k + 1], five[3 * k + 2]);
  mr_rigid_group_def g = mr_default_rigid_group_def();
  g.particles = ids;
  g.count = 5;
  assert_int_equal(mr_world_add_rigid_group(w, &g, NULL), MR_ERR_DEGENERATE);
  assert_int_equal(mr_world_constraint_rows(w), 0);
  mr_world_destroy(w);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(group_shape_names_its_points_or_none),
    cmocka_unit_test(nan_world_resets_to_start_counts_and_keeps_stepping),
    cmocka_unit_test(dependent_rows_reported_and_forces_bounded),
    cmocka_unit_test(every_solver_moves_a_chain_alike),
    cmocka_unit_test(divergence_is_retried_at_the_lower_bound_before_a_reset),
    cmocka_unit_test(bad_input_is_refused_with_a_message),
    cmocka_unit_test(step_limit_stops_runaway_calls),
    cmocka_unit_test(step_limit_allows_exactly_its_steps),
    cmocka_unit_test(divergence_outranks_dependent_rows),
    cmocka_unit_test(a_fifth_member_far_off_is_flat_for_the_loader_and_the_world),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
