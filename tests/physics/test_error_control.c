/* Error control beyond the paper's constraint measure: the embedded local
 * error estimate, which either scale switches on and which may take the
 * step below dt_min, the correction of a step the rule had to accept over
 * its threshold, the stability limit of stiff springs, and the memo of
 * evaluations a step's tries share. Steps cut to land are in
 * test_landing.c, divergence and resets in test_divergence.c. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "rigs.h"

/* A weight on a string and nothing else: no constraint, so the paper's
 * measure reads 0 and would take Δt to the upper bound of 100 s. */
static void weight_on_a_string_stays_under_it_at_any_upper_bound(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_GRAVITY;
  def.dt_max = 100.0;
  def.dt_initial = 1.0;
  int bob;
  mr_world *w = hanging(def, 1.0, 0.9, 500.0, 5.0, (double[3]){ 0, 1.0, 0 }, &bob);
  assert_int_equal(mr_world_step_to(w, 10.0, NULL), MR_OK);
  double x[3];
  double v = speed_of(w, bob, x);
  mr_stats st;
  mr_world_stats(w, &st);
  printf("after 10 s: y = %.6f m, speed %.3g m/s, %llu steps, max dt %.4f s\n", x[1], v,
         (unsigned long long)st.steps, st.max_dt);
  /* At rest it hangs 0.9 + g/k below the bar. */
  assert_true(fabs(x[1] - (2.0 - 0.9 - 9.81 / 500.0)) < 1e-3);
  assert_true(v < 1e-2);
  assert_true(st.max_dt <= st.stable_dt);
  /* and so does the step it says it will try next */
  assert_true(mr_world_next_dt(w) <= st.stable_dt);
  mr_world_destroy(w);
}

/* A zero-rest-length string without damping is a harmonic oscillator in
 * 3D (the weight circles the bar): its energy must stay. Without the local
 * error estimate the steps run at the stability limit and RK4 bleeds the
 * energy away. */
static void undamped_string_keeps_its_energy(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = 0;
  def.dt_max = 1.0;
  int bob;
  const double k = 50.0, m = 0.5;
  mr_world *w = hanging(def, m, 0.0, k, 0.0, (double[3]){ 0.5, 2.0, 0 }, &bob);
  assert_int_equal(
      mr_world_set_particle_state(w, bob, (double[3]){ 0.5, 2.0, 0 }, (double[3]){ 0, 0, 5.0 }),
      MR_OK);
  const double e0 = 0.5 * m * 25.0 + 0.5 * k * 0.25;
  assert_int_equal(mr_world_step_to(w, 5.0, NULL), MR_OK);
  double x[3];
  double v = speed_of(w, bob, x);
  double r2 = x[0] * x[0] + (x[1] - 2) * (x[1] - 2) + x[2] * x[2];
  double e = 0.5 * m * v * v + 0.5 * k * r2;
  mr_stats st;
  mr_world_stats(w, &st);
  printf("energy after 5 s: %.6f of %.6f (%llu steps, largest error estimate %.3g)\n", e, e0,
         (unsigned long long)st.steps, st.max_integration_error);
  assert_true(fabs(e - e0) / e0 < 1e-3);
  assert_true(st.max_integration_error > 0);
  mr_world_destroy(w);
}

/* The estimate of one RK4 step is the embedded third-order solution's
 * error: O(h⁴). Halving h must divide it by 16. */
static double one_step_estimate(double h) {
  mr_world_def def = mr_default_world_def();
  def.effects = 0;
  def.dt_floor = def.dt_min = def.dt_max = def.dt_initial = h;
  int bob;
  mr_world *w = hanging(def, 0.5, 0.0, 50.0, 0.0, (double[3]){ 0.5, 2.0, 0 }, &bob);
  assert_int_equal(mr_world_step(w, NULL), MR_OK);
  mr_stats st;
  mr_world_stats(w, &st);
  mr_world_destroy(w);
  return st.max_integration_error;
}

static void rk4_estimate_is_fourth_order(void **state) {
  (void)state;
  double a = one_step_estimate(0.02), b = one_step_estimate(0.01), c = one_step_estimate(0.005);
  printf("estimates %.4g %.4g %.4g: ratios %.3f %.3f\n", a, b, c, a / b, b / c);
  assert_true(fabs(a / b - 16.0) < 1.0);
  assert_true(fabs(b / c - 16.0) < 0.5);
}

/* With thresholds no step at the lower bound can meet, every step would be
 * accepted over the threshold; each is projected back instead and counted. */
static void over_threshold_at_lower_bound_is_corrected(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.dt_floor = def.dt_min = def.dt_max = def.dt_initial = 0.05;
  def.deviation_high = 1e-9;
  def.deviation_low = 1e-11;
  def.divergence_bound = 0.5;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  int pivot = particle(w, 0, 0, 0, 1, -1), bob = particle(w, 1, 0, 0, 1, -1);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = pivot;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  mr_distance_def d = mr_default_distance_def();
  d.a = pivot;
  d.b = bob;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  double worst = 0;
  int corrected = 0;
  for (int i = 0; i < 40; i++) {
    mr_step_report rep;
    assert_int_equal(mr_world_step(w, &rep), MR_OK);
    corrected += rep.corrections;
    worst = fmax(worst, mr_world_deviation(w));
  }
  mr_stats st;
  mr_world_stats(w, &st);
  printf("%llu corrections in %llu steps, worst deviation after a step %.3g\n",
         (unsigned long long)st.corrections, (unsigned long long)st.steps, worst);
  assert_true(st.corrections > 0);
  assert_int_equal((int)st.corrections, corrected);
  assert_true(worst <= 1e-9);
  mr_world_destroy(w);
}

/* A 1 mg particle on a default string: k/m and c/m ask for Δt far below
 * the lower bound. The stability limit lets the step go there (softening
 * the string's damping to a step of dt_min/100), and the run stays finite
 * and under the bar. */
static void light_particle_on_a_string_is_stable(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_GRAVITY | MR_EFFECT_DRAG;
  int bob;
  mr_world *w = hanging(def, 1e-6, 1.0, 500.0, 5.0, (double[3]){ 0, 1.0, 0 }, &bob);
  assert_int_equal(mr_world_step_to(w, 1.0, NULL), MR_OK);
  double x[3];
  double v = speed_of(w, bob, x);
  mr_stats st;
  mr_world_stats(w, &st);
  printf("1 mg: y = %.6f, speed %.3g, stable dt %.3g s, softened %llu, %llu steps\n", x[1], v,
         st.stable_dt, (unsigned long long)st.softened_forces, (unsigned long long)st.steps);
  assert_true(isfinite(v) && v < 1e-3);
  assert_true(fabs(x[1] - 1.0) < 1e-3);
  /* The string's damping and the drag each at the floor's rate: twice it. */
  assert_true(st.stable_dt < def.dt_min && st.stable_dt >= 0.005 * def.dt_min * 0.999);
  assert_int_equal((int)st.softened_forces, 1);
  assert_int_equal((int)st.divergences, 0);
  mr_world_destroy(w);
}

/* A weight on a zero-length string (no gravity) is a linear oscillator,
 * x(t) = x₀ cos ωt + (v₀/ω) sin ωt about the bar, ω = √(k/m). Started at
 * the upper bound, its first step's estimate lies inside the §4.5 dead
 * band, which alone would keep that 50 ms step for good and end 14 mm off
 * after 20 periods. The estimate's own rule steers it to the aim (`low`):
 * within 0.5 mm. */
static void oscillator_keeps_its_phase(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = 0;
  def.dt_initial = def.dt_max; /* a step the band would keep */
  const double k = 50.0, m = 0.5, w0 = 10.0, t_end = 4.0 * 3.14159265358979323846;
  int bob;
  mr_world *w = hanging(def, m, 0.0, k, 0.0, (double[3]){ 0.3, 2.0, 0 }, &bob);
  assert_int_equal(
      mr_world_set_particle_state(w, bob, (double[3]){ 0.3, 2.0, 0 }, (double[3]){ 0, 0, 2.0 }),
      MR_OK);
  assert_int_equal(mr_world_step_to(w, t_end, NULL), MR_OK);
  double x[3];
  speed_of(w, bob, x);
  const double want[3] = { 0.3 * cos(w0 * t_end), 2.0, 0.2 * sin(w0 * t_end) };
  double off = sqrt(pow(x[0] - want[0], 2) + pow(x[1] - want[1], 2) + pow(x[2] - want[2], 2));
  mr_stats st;
  mr_world_stats(w, &st);
  printf("oscillator after 20 periods: %.3g m from x(t), %llu steps, largest estimate %.3g\n", off,
         (unsigned long long)st.steps, st.max_integration_error);
  assert_true(off < 5e-4);
  mr_world_destroy(w);
}

/* once, a world built as w was but for its first step's length, which is
 * the length w's step was accepted at after rejected tries: taken, that
 * step is accepted at once, costs four evaluations of RK4 and the end
 * (five of gravity's passes), and leaves particle b in the same state,
 * bit for bit, as particle a of w. Both worlds are destroyed. */
static void expect_as_one_step(mr_world *w, int a, mr_world *once, int b) {
  assert_int_equal(mr_world_step(once, NULL), MR_OK);
  mr_stats st;
  mr_world_stats(once, &st);
  assert_int_equal(st.rejected, 0);
  assert_int_equal(mr_world_pass_calls(once, MR_PASS_GRAVITY), 5);
  double x[3], v[3], x1[3], v1[3];
  assert_int_equal(mr_world_particle_state(w, a, x, v), MR_OK);
  assert_int_equal(mr_world_particle_state(once, b, x1, v1), MR_OK);
  print_message("after a retried step: v (%.17g, %.17g, %.17g), at once (%.17g, %.17g, %.17g)\n",
                v[0], v[1], v[2], v1[0], v1[1], v1[2]);
  assert_memory_equal(x, x1, sizeof x);
  assert_memory_equal(v, v1, sizeof v);
  mr_world_destroy(once);
  mr_world_destroy(w);
}

/* The end evaluation of a step, which the local error estimate needs
 * (integrate.c), is the next step's first: a step costs four evaluations
 * of RK4, not five, and the answer is the same bits. A velocity set
 * between steps changes the point, and the next step evaluates afresh. */
static void end_evaluation_is_the_next_steps_first_unless_the_state_changed(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_GRAVITY;
  def.dt_initial = def.dt_max = def.dt_min = 0.01; /* no rejection, no change of h */
  int bob;
  mr_world *w = hanging(def, 0.2, 0.5, 40.0, 0.5, (double[3]){ 0.2, 1.6, 0 }, &bob);
  mr_step_report rep;
  assert_int_equal(mr_world_step(w, &rep), MR_OK);
  const uint64_t first = mr_world_pass_calls(w, MR_PASS_GRAVITY);
  assert_int_equal(first, 5); /* four stages and the end */
  for (int i = 0; i < 10; i++) assert_int_equal(mr_world_step(w, &rep), MR_OK);
  mr_stats st;
  mr_world_stats(w, &st);
  assert_int_equal(st.rejected, 0);
  assert_int_equal(mr_world_pass_calls(w, MR_PASS_GRAVITY) - first, 10 * 4);
  double x[3], v[3];
  assert_int_equal(mr_world_particle_state(w, bob, x, v), MR_OK);
  v[2] += 0.25;
  assert_int_equal(mr_world_set_particle_state(w, bob, x, v), MR_OK);
  const uint64_t before = mr_world_pass_calls(w, MR_PASS_GRAVITY);
  assert_int_equal(mr_world_step(w, &rep), MR_OK);
  assert_int_equal(mr_world_pass_calls(w, MR_PASS_GRAVITY) - before, 5);
  mr_world_destroy(w);
}

/* A rejected try is retried from the same start with a shorter step:
 * the start's evaluation is kept apart from the last one (the rejected
 * try's end), so each retry costs three evaluations of RK4 and the end,
 * not four and the end; and the state is the same bits as one step of
 * the accepted length taken at once, whose start is evaluated afresh. */
static void a_retried_step_does_not_evaluate_its_start_again(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_GRAVITY;
  def.dt_initial = def.dt_max = 0.4; /* a stiff string: the first tries fail */
  def.dt_min = 0.001;
  int bob;
  mr_world *w = hanging(def, 0.2, 0.5, 400.0, 0.5, (double[3]){ 0.3, 1.4, 0 }, &bob);
  mr_step_report rep;
  assert_int_equal(mr_world_step(w, &rep), MR_OK);
  mr_stats st;
  mr_world_stats(w, &st);
  assert_true(st.rejected >= 2);
  assert_int_equal(mr_world_pass_calls(w, MR_PASS_GRAVITY), 5 + 4 * st.rejected);
  def.dt_initial = def.dt_max = st.last_dt;
  int bob1;
  mr_world *once = hanging(def, 0.2, 0.5, 400.0, 0.5, (double[3]){ 0.3, 1.4, 0 }, &bob1);
  expect_as_one_step(w, bob, once, bob1);
}

/* A mode whose local error at dt_min is over the threshold (an oscillator
 * held to 10 µm a step) takes steps below dt_min, down to the floor, until
 * the estimate is within it; the deviation's lower bound does not hold it. */
static void the_estimate_takes_the_step_below_dt_min(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = 0;
  def.error_length = 1e-5;
  def.error_speed = 1e-4;
  int bob;
  mr_world *w = hanging(def, 0.5, 0.0, 50.0, 0.0, (double[3]){ 0.3, 2.0, 0 }, &bob);
  assert_int_equal(mr_world_step_to(w, 1.0, NULL), MR_OK);
  mr_stats st;
  mr_world_stats(w, &st);
  printf("dt min %.4g s, largest estimate %.4g, %llu steps\n", st.min_dt, st.max_integration_error,
         (unsigned long long)st.steps);
  assert_true(st.min_dt < 0.5 * def.dt_min);
  assert_true(st.max_integration_error <= def.deviation_high * (1.0 + 1e-6));
  assert_int_equal((int)st.divergences, 0);
  mr_world_destroy(w);
}

/* A 0.5 kg bob on a 50 N/m string (damping c) from 0.3 m aside, its
 * estimate on the speed scale alone (error_speed, no length scale); the
 * world's definition into *def. */
static mr_world *speed_held_oscillator(double error_speed, double c, mr_world_def *def) {
  *def = mr_default_world_def();
  def->effects = 0;
  def->error_length = 0.0;
  def->error_speed = error_speed;
  int bob;
  return hanging(*def, 0.5, 0.0, 50.0, c, (double[3]){ 0.3, 2.0, 0 }, &bob);
}

/* A step the estimate cut below dt_min climbs back as a step at dt_min is
 * held (step.c, climb()). A damped oscillator held to 1 mm/s a step starts
 * with an estimate over the threshold at dt_min and decays out of it: 18
 * of its 272 steps in 3 s run below dt_min, and 47 tries are rejected;
 * 57 of 284, and 49, when the deviation's dead band held the step there
 * and the estimate aimed at `low`. */
static void a_step_below_dt_min_climbs_back_to_it(void **state) {
  (void)state;
  mr_world_def def;
  mr_world *w = speed_held_oscillator(1e-3, 2.0, &def);
  int below = 0, steps = 0;
  for (; mr_world_time(w) < 3.0; steps++) {
    assert_int_equal(mr_world_step(w, NULL), MR_OK);
    mr_stats st;
    mr_world_stats(w, &st);
    below += st.last_dt < def.dt_min * (1 - 1e-9);
  }
  mr_stats st;
  mr_world_stats(w, &st);
  printf("climbing back: %d of %d steps below dt_min, %llu tries rejected, largest estimate %.3g\n",
         below, steps, (unsigned long long)st.rejected, st.max_integration_error);
  assert_true(below > 0);
  assert_true(below <= 25);
  assert_true(st.rejected < 49);
  assert_true(st.max_integration_error <= def.deviation_high * (1.0 + 1e-6));
  mr_world_destroy(w);
}

/* Either scale alone switches the estimate on: an oscillator held to
 * 0.1 mm/s a step in speed, with no length scale, has each step's estimate
 * measured and kept to the threshold, as with both. */
static void the_speed_scale_alone_steers_the_step(void **state) {
  (void)state;
  mr_world_def def;
  mr_world *w = speed_held_oscillator(1e-4, 0.0, &def);
  assert_int_equal(mr_world_step_to(w, 1.0, NULL), MR_OK);
  mr_stats st;
  mr_world_stats(w, &st);
  printf("speed scale alone: largest estimate %.4g, dt min %.4g s, %llu steps\n",
         st.max_integration_error, st.min_dt, (unsigned long long)st.steps);
  assert_true(st.max_integration_error > def.deviation_low);
  assert_true(st.max_integration_error <= def.deviation_high * (1.0 + 1e-6));
  assert_true(st.min_dt < def.dt_min);
  mr_world_destroy(w);
}

/* The estimate's own rule, which steers the step to the aim from inside
 * the dead band, applies with either scale alone too: the oscillator of
 * oscillator_keeps_its_phase, held to the speed scale only, stays within
 * 0.5 mm of x(t) after 20 periods (14 mm off without that rule). */
static void the_speed_scale_alone_keeps_an_oscillator_in_phase(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = 0;
  def.dt_initial = def.dt_max;
  def.error_length = 0.0;
  const double k = 50.0, m = 0.5, w0 = 10.0, t_end = 4.0 * 3.14159265358979323846;
  int bob;
  mr_world *w = hanging(def, m, 0.0, k, 0.0, (double[3]){ 0.3, 2.0, 0 }, &bob);
  assert_int_equal(
      mr_world_set_particle_state(w, bob, (double[3]){ 0.3, 2.0, 0 }, (double[3]){ 0, 0, 2.0 }),
      MR_OK);
  assert_int_equal(mr_world_step_to(w, t_end, NULL), MR_OK);
  double x[3];
  speed_of(w, bob, x);
  const double want[3] = { 0.3 * cos(w0 * t_end), 2.0, 0.2 * sin(w0 * t_end) };
  double off = sqrt(pow(x[0] - want[0], 2) + pow(x[1] - want[1], 2) + pow(x[2] - want[2], 2));
  printf("speed scale alone, after 20 periods: %.3g m from x(t)\n", off);
  assert_true(off < 5e-4);
  mr_world_destroy(w);
}

/* What the stats report for a step the rule had to accept over its
 * threshold, and projected back (§6.2), is the deviation after the
 * projection, the state's own, not the one the projection removed. Fixed
 * 50 ms steps of a 3 m/s swing deviate by 6e-5, over a threshold of 1e-5. */
static void a_corrected_step_reports_the_corrected_deviation(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.dt_floor = def.dt_min = def.dt_max = def.dt_initial = 0.05;
  def.deviation_high = 1e-5;
  def.deviation_low = 1e-8;
  int bob;
  mr_world *w = pendulum(def, 3.0, &bob);
  for (int i = 0; i < 10; i++) {
    mr_step_report rep;
    assert_int_equal(mr_world_step(w, &rep), MR_OK);
    mr_stats st;
    mr_world_stats(w, &st);
    if (i == 0)
      printf("corrected: deviation %.3g, reported %.3g\n", mr_world_deviation(w), st.last_error);
    assert_int_equal(rep.corrections, 1);
    assert_true(mr_world_deviation(w) <= def.deviation_low);
    assert_true(st.last_error == mr_world_deviation(w));
    assert_true(st.max_error <= def.deviation_low);
  }
  mr_world_destroy(w);
}

/* A world of a stiff string whose first tries are rejected, and beside it
 * a block sliding to rest on the floor. */
static mr_world *retried_beside_friction(double dt, int *block) {
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_GRAVITY | MR_EFFECT_PLANES;
  def.dt_initial = def.dt_max = dt;
  def.dt_min = 0.001;
  int bob;
  mr_world *w = hanging(def, 0.2, 0.5, 400.0, 0.5, (double[3]){ 0.3, 1.4, 0 }, &bob);
  mr_plane_def pl = mr_default_plane_def();
  pl.friction = 0.8;
  assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
  mr_particle_def p = mr_default_particle_def();
  p.position[0] = 3.0;
  p.position[1] = p.radius = 0.05;
  p.velocity[0] = 0.02; /* slow enough for static friction to stop within a step */
  assert_int_equal(mr_world_add_particle(w, &p, block), MR_OK);
  return w;
}

/* Static friction aims to stop a slide within half the step (eval.c), so
 * an evaluation with a friction contact depends on h: a retry of another
 * length does not reuse the start's evaluation from the rejected try, and
 * the block ends the same bits as in one step of the accepted length. */
static void a_retry_with_friction_evaluates_its_start_for_its_own_step(void **state) {
  (void)state;
  int block, block1;
  mr_world *w = retried_beside_friction(0.4, &block);
  assert_int_equal(mr_world_step(w, NULL), MR_OK);
  mr_stats st;
  mr_world_stats(w, &st);
  assert_true(st.rejected >= 2);
  assert_int_equal(st.resting_contacts, 1);
  mr_world *once = retried_beside_friction(st.last_dt, &block1);
  expect_as_one_step(w, block, once, block1);
}

/* The first- and second-order integrators estimate their local error by
 * the trapezoid rule, δx = h/2 (v1 − v0): for a fall under gravity from
 * rest that is g h²/2, exactly what one explicit Euler step (x1 = x0 + h
 * v0) falls short by. */
static void euler_estimate_is_its_own_error_in_free_fall(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_GRAVITY;
  def.integrator = MR_INTEGRATOR_EULER;
  def.drag = 0.0;
  const double h = 0.01;
  def.dt_floor = def.dt_min = def.dt_max = def.dt_initial = h;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  int p = particle(w, 0, 1, 0, 1, -1);
  assert_int_equal(mr_world_step(w, NULL), MR_OK);
  double x[3];
  speed_of(w, p, x);
  const double fall = 0.5 * 9.81 * h * h, short_by = x[1] - (1.0 - fall);
  mr_stats st;
  mr_world_stats(w, &st);
  printf("Euler in free fall: estimate %.6g m, short by %.6g m, g h^2/2 = %.6g m\n",
         st.max_integration_error, short_by, fall);
  assert_true(fabs(short_by - fall) < 1e-12);
  assert_true(fabs(st.max_integration_error - fall) < 1e-12);
  mr_world_destroy(w);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(weight_on_a_string_stays_under_it_at_any_upper_bound),
    cmocka_unit_test(undamped_string_keeps_its_energy),
    cmocka_unit_test(rk4_estimate_is_fourth_order),
    cmocka_unit_test(over_threshold_at_lower_bound_is_corrected),
    cmocka_unit_test(light_particle_on_a_string_is_stable),
    cmocka_unit_test(oscillator_keeps_its_phase),
    cmocka_unit_test(end_evaluation_is_the_next_steps_first_unless_the_state_changed),
    cmocka_unit_test(a_retried_step_does_not_evaluate_its_start_again),
    cmocka_unit_test(the_estimate_takes_the_step_below_dt_min),
    cmocka_unit_test(a_step_below_dt_min_climbs_back_to_it),
    cmocka_unit_test(the_speed_scale_alone_steers_the_step),
    cmocka_unit_test(the_speed_scale_alone_keeps_an_oscillator_in_phase),
    cmocka_unit_test(a_corrected_step_reports_the_corrected_deviation),
    cmocka_unit_test(a_retry_with_friction_evaluates_its_start_for_its_own_step),
    cmocka_unit_test(euler_estimate_is_its_own_error_in_free_fall),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
