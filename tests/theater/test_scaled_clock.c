/* The show's clock that pause, single step and slow motion act on
 * (mr_scaled_clock), on a virtual clock: every time below is exact. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>

#include "mr_theater.h"

/* sc, the scaled clock on the virtual clock vc; returns it as a clock. */
static mr_clock scaled_on(mr_virtual_clock *vc, mr_scaled_clock *sc) {
  mr_clock base = mr_clock_virtual(vc);
  mr_scaled_clock_init(sc, &base);
  return mr_clock_scaled(sc);
}

/* At rate 1 over a base that starts at 0 (a replay's virtual clock) show
 * time is the base's, bit for bit; at a quarter, a second of show takes
 * four. */
static void slow_motion_stretches_show_time_without_a_jump(void **state) {
  (void)state;
  mr_virtual_clock vc = { 0.0 };
  mr_scaled_clock sc;
  mr_clock c = scaled_on(&vc, &sc);
  assert_true(c.now(c.self) == 0.0);
  for (int j = 1; j <= 60; j++) {
    c.wait_until(c.self, j / 60.0);
    assert_true(c.now(c.self) == j / 60.0);
  }
  vc.t += 10.0;
  sc.base_base += 10.0; /* the same clock, its base ten seconds on */
  c.wait_until(c.self, 1.0);
  mr_scaled_clock_set_rate(&sc, 0.25);
  assert_true(fabs(c.now(c.self) - 1.0) < 1e-12); /* no jump at the change */
  c.wait_until(c.self, 2.0);
  assert_true(fabs(vc.t - 15.0) < 1e-9); /* 1 s of show in 4 s */
  assert_true(sc.rate == 0.25);
  assert_true(c.now(c.self) >= 2.0 - 1e-12);
  mr_scaled_clock_set_rate(&sc, 1.0);
  c.wait_until(c.self, 3.0);
  assert_true(fabs(vc.t - 16.0) < 1e-9);
  mr_scaled_clock_set_rate(&sc, 0); /* refused */
  assert_true(sc.rate == 1.0);
}

/* Paused, show time stands still however long the base runs, a wait
 * without a step does not reach its time, and each step moves show time
 * to the time waited for, one at a time. */
static void paused_time_stands_still_and_steps_move_it_a_frame(void **state) {
  (void)state;
  mr_virtual_clock vc = { 0.0 };
  mr_scaled_clock sc;
  mr_clock c = scaled_on(&vc, &sc);
  c.wait_until(c.self, 0.5);
  mr_scaled_clock_pause(&sc, true);
  mr_virtual_clock_spend(&vc, 100.0);
  assert_true(c.now(c.self) == 0.5);
  c.wait_until(c.self, 0.6);
  assert_true(c.now(c.self) == 0.5);
  mr_scaled_clock_step(&sc);
  mr_scaled_clock_step(&sc);
  c.wait_until(c.self, 0.6);
  assert_true(c.now(c.self) == 0.6);
  c.wait_until(c.self, 0.7);
  assert_true(c.now(c.self) == 0.7);
  c.wait_until(c.self, 0.8); /* the steps are spent */
  assert_true(c.now(c.self) == 0.7);
  assert_true(sc.paused);
  mr_scaled_clock_pause(&sc, false);
  double v0 = vc.t;
  c.wait_until(c.self, 0.8);
  assert_true(fabs(c.now(c.self) - 0.8) < 1e-12);
  assert_true(fabs(vc.t - v0 - 0.1) < 1e-9); /* on from where it stood */
}

typedef struct script {
  mr_scaled_clock *sc;
  mr_virtual_clock *vc;
  int calls;
  double deadlines[8];
} script;

/* The idle hook: told when the wait would end (never, while paused),
 * spends a second, and the third time lets go of the pause. */
static int idle(void *user, double deadline) {
  script *s = user;
  if (s->calls < 8) s->deadlines[s->calls] = deadline;
  s->calls++;
  if (!isfinite(deadline)) {
    mr_virtual_clock_spend(s->vc, 1.0);
    if (s->calls == 3) mr_scaled_clock_pause(s->sc, false);
    return 0;
  }
  s->vc->t = deadline;
  return 0;
}

/* A paused wait goes to the idle hook (the physics thread waits there for
 * its commands) until a command lets it go on; then it ends at its time. */
static void a_paused_wait_idles_until_a_command_lets_it_go(void **state) {
  (void)state;
  mr_virtual_clock vc = { 0.0 };
  mr_scaled_clock sc;
  scaled_on(&vc, &sc);
  script s = { &sc, &vc, 0, { 0 } };
  sc.idle = idle;
  sc.user = &s;
  mr_clock c = mr_clock_scaled(&sc);
  mr_scaled_clock_pause(&sc, true);
  c.wait_until(c.self, 0.25);
  assert_int_equal(s.calls, 4);
  for (int i = 0; i < 3; i++) assert_true(isinf(s.deadlines[i]));
  assert_true(s.deadlines[3] == 3.25); /* paused for 3 s of base time */
  assert_true(c.now(c.self) == 0.25);
}

/* The pace (show time plus the base seconds slow motion held back) runs
 * on without a jump across changes of rate, and stands still while
 * paused; a rate that is not a finite positive number is refused. */
static void the_pace_holds_across_rates_and_stands_while_paused(void **state) {
  (void)state;
  mr_virtual_clock vc = { 2.0 };
  mr_scaled_clock sc;
  scaled_on(&vc, &sc);
  mr_scaled_clock_set_rate(&sc, 0.25);
  mr_virtual_clock_spend(&vc, 4.0);
  assert_true(fabs(mr_scaled_clock_now(&sc) - 1.0) < 1e-12);
  assert_true(fabs(mr_scaled_clock_pace_now(&sc) - 4.0) < 1e-12); /* the base's 4 s */
  mr_scaled_clock_set_rate(&sc, 0.5);
  mr_scaled_clock_set_rate(&sc, INFINITY); /* refused */
  assert_true(sc.rate == 0.5);
  assert_true(fabs(mr_scaled_clock_pace_now(&sc) - 4.0) < 1e-12);
  mr_virtual_clock_spend(&vc, 2.0);
  assert_true(fabs(mr_scaled_clock_pace_now(&sc) - 6.0) < 1e-12);
  mr_scaled_clock_pause(&sc, true);
  mr_virtual_clock_spend(&vc, 3.0);
  assert_true(fabs(mr_scaled_clock_pace_now(&sc) - 6.0) < 1e-12);
  mr_virtual_clock_spend(&vc, -1.0); /* a virtual clock never goes back */
  assert_true(vc.t == 11.0);
}

/* A step is spent only on a time past the paused show's: waiting for an
 * earlier one, or for the very time shown, returns at once, and show time
 * never goes back. */
static void a_step_is_not_spent_on_a_time_already_shown(void **state) {
  (void)state;
  mr_virtual_clock vc = { 0.0 };
  mr_scaled_clock sc;
  mr_clock c = scaled_on(&vc, &sc);
  c.wait_until(c.self, 0.5);
  mr_scaled_clock_step(&sc);
  c.wait_until(c.self, 0.4);
  assert_true(c.now(c.self) == 0.5);
  assert_int_equal(sc.steps, 1);
  c.wait_until(c.self, 0.5);
  assert_true(c.now(c.self) == 0.5);
  assert_int_equal(sc.steps, 1);
  c.wait_until(c.self, 0.6);
  assert_true(c.now(c.self) == 0.6);
  assert_int_equal(sc.steps, 0);
}

/* The wall clock waits until the time it is given, to the nanosecond's
 * order, never returning early; a clock is the wall only with both of the
 * wall's functions. */
static void the_wall_clock_waits_until_its_time(void **state) {
  (void)state;
  mr_clock w = mr_clock_wall();
  const double target = w.now(w.self) + 0.0123;
  w.wait_until(w.self, target);
  const double woke = w.now(w.self);
  print_message("woke %.3g ms after the target\n", 1e3 * (woke - target));
  assert_true(woke >= target);
  assert_true(mr_clock_is_wall(&w));
  mr_virtual_clock vc = { 0.0 };
  mr_clock mixed = mr_clock_virtual(&vc);
  mixed.now = w.now;
  assert_false(mr_clock_is_wall(&mixed));
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(slow_motion_stretches_show_time_without_a_jump),
    cmocka_unit_test(paused_time_stands_still_and_steps_move_it_a_frame),
    cmocka_unit_test(a_paused_wait_idles_until_a_command_lets_it_go),
    cmocka_unit_test(the_pace_holds_across_rates_and_stands_while_paused),
    cmocka_unit_test(a_step_is_not_spent_on_a_time_already_shown),
    cmocka_unit_test(the_wall_clock_waits_until_its_time),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
