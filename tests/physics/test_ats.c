/* The adaptive time step (§4.5, §7): the fourth-root rule on a scripted
 * error sequence, its bounds, rejection in a real world, the same rule
 * followed step by step by a world, and Δt doubling back after an impact. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>

#include "rigs.h"

static const mr_ats_params paper = { 0.01, 0.05, 1e-4, 1e-2 }; /* §7 */

static void near(double a, double b) {
  assert_true(fabs(a - b) <= 1e-15 * fabs(b));
}

/* Each scripted error against Δt_new = Δt_old·(threshold/error)^¼, with the
 * dead band between the thresholds and the clamps of §7. */
static void ats_follows_fourth_root_rule_on_scripted_errors(void **state) {
  (void)state;
  double dt = 0.02;
  mr_ats_decision d;

  d = mr_ats_next(&paper, dt, 5e-5); /* below low: grow */
  assert_int_equal(d.accept, 1);
  near(d.dt_next, 0.02 * pow(1e-4 / 5e-5, 0.25));
  dt = d.dt_next;

  d = mr_ats_next(&paper, dt, 1e-3); /* inside the band: keep */
  assert_int_equal(d.accept, 1);
  near(d.dt_next, dt);

  d = mr_ats_next(&paper, dt, 2e-1); /* above high: reject, shrink towards high */
  assert_int_equal(d.accept, 0);
  near(d.dt_next, dt * pow(1e-2 / 2e-1, 0.25));
  dt = d.dt_next;

  d = mr_ats_next(&paper, 0.04, 1.1e-2); /* just above: retried at least halved */
  assert_int_equal(d.accept, 0);
  near(d.dt_next, 0.02);

  dt = 0.02;
  d = mr_ats_next(&paper, dt, 3e-5);
  assert_int_equal(d.accept, 1);
  near(d.dt_next, dt * pow(1e-4 / 3e-5, 0.25));
  dt = d.dt_next;

  d = mr_ats_next(&paper, dt, 1e-9); /* huge ratio: clamped to the upper bound */
  assert_int_equal(d.accept, 1);
  near(d.dt_next, 0.05);

  d = mr_ats_next(&paper, 0.05, 0.0); /* no constraints: upper bound */
  near(d.dt_next, 0.05);

  d = mr_ats_next(&paper, 0.012, 0.9); /* big error: reject, clamped to the lower bound */
  assert_int_equal(d.accept, 0);
  near(d.dt_next, 0.01);

  d = mr_ats_next(&paper, 0.01, 0.9); /* at the lower bound nothing shorter exists */
  assert_int_equal(d.accept, 1);
  near(d.dt_next, 0.01);

  /* Under it (a sliver cut to land on a frame): accepted, and the next
   * step goes back to the bound, not on at the sliver. */
  d = mr_ats_next(&paper, 0.004, 0.9);
  assert_int_equal(d.accept, 1);
  near(d.dt_next, 0.01);

  d = mr_ats_next(&paper, 0.03, NAN); /* NaN never passes as small */
  assert_int_equal(d.accept, 0);
  near(d.dt_next, 0.01);
}

/* 10⁴ pseudo-random errors over 1e-10..1: Δt never leaves [0.01, 0.05] and
 * a step is rejected exactly when its error passes 1 % above the lower
 * bound. */
static void ats_stays_within_bounds(void **state) {
  (void)state;
  uint64_t s = 12345;
  double dt = 0.02;
  int rejects = 0;
  for (int i = 0; i < 10000; i++) {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    double u = (double)(s >> 11) / 9007199254740992.0;
    double err = pow(10.0, -10.0 + 10.0 * u);
    mr_ats_decision d = mr_ats_next(&paper, dt, err);
    assert_true(d.dt_next >= 0.01 && d.dt_next <= 0.05);
    assert_int_equal(d.accept, !(err > 1e-2 && dt > 0.01));
    rejects += !d.accept;
    dt = d.dt_next;
  }
  assert_true(rejects > 0);
}

/* The estimate's own controller: steered to low from both sides (no dead
 * band), with the safety factor, the fivefold and twofold limits, and the
 * bounds. */
static void estimate_is_steered_to_low_from_both_sides(void **state) {
  (void)state;
  const double dt = 0.02;
  near(mr_ats_aim(&paper, dt, 1e-4), dt * 0.9);                  /* on the aim */
  near(mr_ats_aim(&paper, dt, 1e-3), dt * 0.9 * pow(0.1, 0.25)); /* in the band */
  near(mr_ats_aim(&paper, dt, 5e-5), dt * 0.9 * pow(2.0, 0.25)); /* below */
  near(mr_ats_aim(&paper, 0.02, 1e-2), 0.01);                    /* ×0.28: lower bound */
  near(mr_ats_aim(&paper, 0.04, 0.5), 0.01);                     /* ×0.2 at most */
  near(mr_ats_aim(&paper, 0.005, 1e-9), 0.025);                  /* ×5 at most */
  near(mr_ats_aim(&paper, 0.04, 0.0), 0.05);                     /* clamped above */
  const mr_ats_params wide = { 1e-4, 1.0, 1e-4, 1e-2 };
  near(mr_ats_aim(&wide, 0.04, 0.5), 0.008); /* ×0.2 */
  near(mr_ats_aim(&wide, 0.04, NAN), 0.008); /* NaN: cut hardest */
  near(mr_ats_aim(&wide, 0.04, 1e-12), 0.2); /* ×5 */
  assert_true(mr_ats_aim(NULL, 0.03, 1.0) == 0.03);
}

/* The pendulum released from horizontal, under the paper's rule alone. */
static mr_world *released(double high, double low, int *bob) {
  mr_world_def def = mr_default_world_def();
  def.deviation_high = high;
  def.deviation_low = low;
  def.dt_initial = 0.05;
  return pendulum(def, 0.0, bob);
}

/* A pendulum released from horizontal with tight thresholds: steps over the
 * upper threshold are rejected and retried, so every accepted step above the
 * lower bound has its deviation under the threshold, and each accepted step
 * sets the next Δt exactly as mr_ats_next says. */
static void world_rejects_and_follows_rule_step_by_step(void **state) {
  (void)state;
  const double high = 2e-6, low = 2e-8;
  int bob;
  mr_world *w = released(high, low, &bob);
  const mr_ats_params p = { 0.01, 0.05, low, high };
  mr_stats st;
  int checked = 0;
  uint64_t rejected_before = 0;
  for (int i = 0; i < 300; i++) {
    assert_int_equal(mr_world_step(w, NULL), MR_OK);
    mr_world_stats(w, &st);
    assert_true(st.last_dt >= 0.01 && st.last_dt <= 0.05);
    if (st.last_dt > 0.01) assert_true(st.last_error <= high);
    if (st.rejected == rejected_before) {
      /* No retry: the step was the planned one and the rule chose the next. */
      mr_ats_decision d = mr_ats_next(&p, st.last_dt, st.last_error);
      assert_true(fabs(mr_world_next_dt(w) - d.dt_next) <= 1e-15);
      checked++;
    }
    rejected_before = st.rejected;
  }
  printf("ats: %llu steps, %llu rejected, dt %.4f..%.4f s, %d steps checked against the rule\n",
         (unsigned long long)st.steps, (unsigned long long)st.rejected, st.min_dt, st.max_dt,
         checked);
  assert_true(st.rejected > 0);
  assert_true(checked > 100);
  assert_true(st.min_dt < st.max_dt);
  mr_world_destroy(w);
}

/* §4.5: a ball falls onto the floor; the step is cut to the contact time,
 * then Δt doubles each step (h, 2h, 4h, ...) until the rule's value (the
 * upper bound here: no constraints) takes over again. */
static void dt_doubles_back_after_floor_impact(void **state) {
  (void)state;
  /* Drop heights chosen so that the step cut at the contact is short in
   * some runs and over half the upper bound in others, where doubling it
   * would overshoot the bound. */
  const double heights[] = { 1.0, 1.3, 0.77, 2.2, 3.05 };
  for (size_t hi = 0; hi < sizeof heights / sizeof heights[0]; hi++) {
    mr_world_def def = mr_default_world_def();
    def.effects = MR_EFFECT_GRAVITY | MR_EFFECT_PLANES;
    mr_world *w = NULL;
    assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
    mr_particle_def p = mr_default_particle_def();
    p.position[1] = heights[hi];
    p.radius = 0.1;
    assert_int_equal(mr_world_add_particle(w, &p, NULL), MR_OK);
    mr_plane_def pl = mr_default_plane_def();
    assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
    double dts[400];
    int n = 0, impact = -1;
    mr_stats st;
    while (n < 400 && mr_world_time(w) < 2.0) {
      uint64_t c0;
      mr_world_stats(w, &st);
      c0 = st.collisions;
      assert_int_equal(mr_world_step(w, NULL), MR_OK);
      mr_world_stats(w, &st);
      dts[n] = st.last_dt;
      /* §7: the bounds hold for every step, the ones after a contact too. */
      assert_true(dts[n] <= def.dt_max);
      if (impact < 0 && st.collisions > c0)
        impact = n; /* the impulse is given at the start of this step */
      n++;
    }
    assert_true(impact > 0);
    int cut = impact - 1; /* the step that was stopped at the contact */
    printf("drop %.2f m, after impact: dt = %.5f", heights[hi], dts[cut]);
    assert_true(dts[cut] < def.dt_max);
    int k = cut + 1;
    for (; k < n && dts[k] < def.dt_max; k++) {
      printf(", %.5f", dts[k]);
      assert_true(fabs(dts[k] - 2 * dts[k - 1]) <= 1e-15 * dts[k]);
    }
    printf(", then %.5f\n", dts[k]);
    assert_true(k < n && dts[k] == def.dt_max);
    /* The step that reaches the bound is the doubling, capped. */
    assert_true(2 * dts[k - 1] >= def.dt_max);
    mr_world_destroy(w);
  }
}

/* The fourth root is two square roots, correctly rounded each under IEEE
 * 754, so the pinned hashes do not depend on a libm's pow. Errors are
 * chosen where pow(x, 0.25) and sqrt(sqrt(x)) differ in the last bit. */
static void ats_growth_is_two_square_roots_to_the_bit(void **state) {
  (void)state;
  const mr_ats_params p = { 0.01, 0.05, 1e-4, 1e-2 };
  int differing = 0;
  for (int i = 1; i <= 2000; i++) {
    double error = p.low / (1.0 + i * 1e-4);
    double ratio = p.low / error;
    volatile double by_pow = pow(ratio, 0.25), by_sqrt = sqrt(sqrt(ratio));
    if (by_pow == by_sqrt) continue;
    differing++;
    mr_ats_decision d = mr_ats_next(&p, 0.02, error);
    assert_true(d.accept);
    if (d.dt_next != 0.02 * by_sqrt)
      fail_msg("error %.17g: dt_next %a, want %a", error, d.dt_next, 0.02 * by_sqrt);
  }
  assert_true(differing > 10);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(ats_follows_fourth_root_rule_on_scripted_errors),
    cmocka_unit_test(ats_stays_within_bounds),
    cmocka_unit_test(estimate_is_steered_to_low_from_both_sides),
    cmocka_unit_test(world_rejects_and_follows_rule_step_by_step),
    cmocka_unit_test(dt_doubles_back_after_floor_impact),
    cmocka_unit_test(ats_growth_is_two_square_roots_to_the_bit),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
