/* Steps cut or stretched to land on a requested time (step.c): they are
 * reported apart from the rule's own, they keep the plan the rule made, a
 * sliver short of the target is not left for a step of its own, and a
 * landing shorter than dt_min is retried at the floor the estimate may
 * use. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "rigs.h"

/* Steps cut to land on a requested time are not the rule's choice: they
 * are reported apart, and the rule's smallest step stays within its bounds. */
static void landing_steps_are_reported_apart(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  particle(w, 0, 0, 0, 1, -1);
  for (int k = 1; k <= 20; k++) assert_int_equal(mr_world_step_to(w, k * 0.13, NULL), MR_OK);
  mr_stats st;
  mr_world_stats(w, &st);
  printf("dt min %.4g s (rule), %.4g s (landing)\n", st.min_dt, st.min_dt_landing);
  assert_true(st.min_dt >= def.dt_min);
  assert_true(st.min_dt_landing < def.dt_min);
  mr_world_destroy(w);
}

/* A reset in a step that lands on the target leaves no sliver behind: the
 * world is at the target afterwards, exactly. */
static void reset_at_a_landing_leaves_no_sliver(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.max_speed = 1e-3; /* every step diverges */
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  particle(w, 0, 0, 0, 1, -1);
  for (int k = 1; k <= 30; k++) {
    double target = k * 0.1 / 3.0;
    mr_step_report rep;
    assert_int_equal(mr_world_step_to(w, target, &rep), MR_DIVERGED);
    assert_true(mr_world_time(w) == target);
  }
  mr_world_destroy(w);
}

/* A try rejected to dt_min that would then stop 5 µs short of the
 * requested time lands on it instead: one step, not a second 5 µs sliver
 * after it. */
static void a_retry_a_hair_short_of_the_target_lands_on_it(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.deviation_high = 1e-9; /* the first try, 10 ms long, is over it */
  def.deviation_low = 1e-11;
  int bob;
  mr_world *w = pendulum(def, 3.0, &bob);
  const double target = def.dt_min * (1.0 + 5e-4);
  mr_step_report rep;
  assert_int_equal(mr_world_step_to(w, target, &rep), MR_OK);
  printf("to %.9g s: %d steps, %d rejected\n", target, rep.steps, rep.rejected);
  assert_true(rep.rejected >= 1);
  assert_int_equal(rep.steps, 1);
  assert_true(mr_world_time(w) == target);
  mr_world_destroy(w);
}

/* Fixed steps of 20 ms landing on multiples of 20 ms: each is the step the
 * rule chose, to rounding, not one cut to land, so none is reported as a
 * landing. */
static void a_landing_as_long_as_the_plan_is_no_landing(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.dt_floor = def.dt_min = def.dt_max = def.dt_initial = 0.02;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  particle(w, 0, 0, 0, 1, -1);
  for (int k = 1; k <= 20; k++) assert_int_equal(mr_world_step_to(w, k * 0.02, NULL), MR_OK);
  mr_stats st;
  mr_world_stats(w, &st);
  printf("%llu steps: dt min %.17g s (rule), %.4g s (landing)\n", (unsigned long long)st.steps,
         st.min_dt, st.min_dt_landing);
  assert_int_equal((int)st.steps, 20);
  assert_true(fabs(st.min_dt - 0.02) < 1e-12);
  assert_true(isinf(st.min_dt_landing));
  mr_world_destroy(w);
}

/* A step cut short to land on the requested time says nothing about the
 * step the motion needs: the plan made before it stands for the next. */
static void a_step_cut_to_land_keeps_the_plan(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = 0;
  int bob;
  mr_world *w = hanging(def, 0.5, 0.0, 50.0, 0.0, (double[3]){ 0.3, 2.0, 0 }, &bob);
  assert_int_equal(
      mr_world_set_particle_state(w, bob, (double[3]){ 0.3, 2.0, 0 }, (double[3]){ 0, 0, 2.0 }),
      MR_OK);
  for (int i = 0; i < 20; i++) assert_int_equal(mr_world_step(w, NULL), MR_OK);
  const double plan = mr_world_next_dt(w);
  mr_step_report rep;
  assert_int_equal(mr_world_step_to(w, mr_world_time(w) + 0.05 * plan, &rep), MR_OK);
  printf("plan %.4g s, after a landing of %.4g s: %.4g s\n", plan, 0.05 * plan,
         mr_world_next_dt(w));
  assert_int_equal(rep.steps, 1);
  assert_int_equal(rep.rejected, 0);
  assert_true(mr_world_next_dt(w) == plan);
  mr_world_destroy(w);
}

/* A step stretched by a hair to land on the requested time is judged as
 * the step the rule planned: at the lower bound, with a deviation over the
 * threshold, it is accepted (and corrected) at once, not rejected for
 * being a hair longer than dt_min and then taken all the same. */
static void a_step_stretched_to_land_is_judged_as_planned(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.dt_initial = def.dt_min;
  def.deviation_high = 1e-9; /* a step of dt_min is over it */
  def.deviation_low = 1e-11;
  int bob;
  mr_world *w = pendulum(def, 3.0, &bob);
  const double target = def.dt_min * (1.0 + 5e-4);
  mr_step_report rep;
  assert_int_equal(mr_world_step_to(w, target, &rep), MR_OK);
  printf("stretched to %.9g s: %d steps, %d rejected, %d corrected\n", target, rep.steps,
         rep.rejected, rep.corrections);
  assert_int_equal(rep.steps, 1);
  assert_int_equal(rep.rejected, 0);
  assert_int_equal(rep.corrections, 1);
  assert_true(mr_world_time(w) == target);
  mr_world_destroy(w);
}

/* A step shorter than dt_min (here one landing 4 ms ahead) that passes the
 * divergence bound is retried down to the floor, as one of dt_min would
 * be, and the run goes on; it is no divergence while a shorter step stays
 * within the bound (0.1 ms here). */
static void a_short_landing_past_the_bound_is_retried_at_the_floor(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.divergence_bound = 1e-10; /* a 4 ms step of this swing passes it */
  def.deviation_high = 1e-11;
  def.deviation_low = 1e-13;
  int bob;
  mr_world *w = pendulum(def, 3.0, &bob);
  mr_step_report rep;
  assert_int_equal(mr_world_step_to(w, 0.004, &rep), MR_OK);
  mr_stats st;
  mr_world_stats(w, &st);
  printf("to 4 ms: %d steps, %d rejected, dt min %.3g s\n", rep.steps, rep.rejected, st.min_dt);
  assert_int_equal(rep.divergences, 0);
  assert_true(rep.rejected >= 1);
  assert_true(st.min_dt == 0.01 * def.dt_min); /* the default floor, dt_min/100 */
  assert_true(mr_world_time(w) == 0.004);
  mr_world_destroy(w);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(landing_steps_are_reported_apart),
    cmocka_unit_test(reset_at_a_landing_leaves_no_sliver),
    cmocka_unit_test(a_retry_a_hair_short_of_the_target_lands_on_it),
    cmocka_unit_test(a_landing_as_long_as_the_plan_is_no_landing),
    cmocka_unit_test(a_step_cut_to_land_keeps_the_plan),
    cmocka_unit_test(a_step_stretched_to_land_is_judged_as_planned),
    cmocka_unit_test(a_short_landing_past_the_bound_is_retried_at_the_floor),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
