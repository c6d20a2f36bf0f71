/* The frame scheduler (§4.6) on a virtual clock: every frame lands on its
 * time and is shown one period later; under load renders are skipped and
 * simulated time stays within a frame of wall time without spiralling; the
 * slow policy skips nothing and reports how far it fell behind; a sample is
 * on screen within two frame periods. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mr_theater.h"

typedef struct show {
  mr_virtual_clock vc;
  double render_cost, advance_cost, period;
  uint64_t advances, presents;
  double last_advance_t;
  int bad_landing; /* an advance whose time was not j·period */
  int bad_delay;   /* a frame shown other than one period after its time */
  int advances_in_tick, most_in_tick;
  double origin;   /* the clock's time at simulated time 0 */
  double tick_lag; /* wall − simulated time of the newest frame this tick */
  double stalest;  /* the most a shown frame's time trailed the wall's */
} show;

static int advance(void *user, double t, mr_frame_work *w) {
  show *s = user;
  if (t != (double)s->advances / 60.0) s->bad_landing++;
  s->advances++;
  s->advances_in_tick++;
  s->last_advance_t = t;
  s->tick_lag = (s->vc.t - s->origin) - t;
  w->steps = 2;
  w->rejected = 0;
  w->resets = 0;
  mr_virtual_clock_spend(&s->vc, s->advance_cost);
  return 0;
}

static void present(void *user, double t) {
  show *s = user;
  s->presents++;
  s->stalest = fmax(s->stalest, s->vc.t - s->origin - t);
  if (fabs(s->vc.t - s->origin - (t + s->period)) > 1e-9) s->bad_delay++;
  mr_virtual_clock_spend(&s->vc, s->render_cost);
}

static mr_scheduler *start(show *s, mr_policy policy) {
  mr_scheduler_def d = mr_default_scheduler_def();
  d.policy = policy;
  s->period = 1.0 / d.fps;
  mr_clock c = mr_clock_virtual(&s->vc);
  mr_scheduler_hooks h = { advance, present, s };
  mr_scheduler *sch = NULL;
  char msg[160];
  if (mr_scheduler_create(&d, &c, &h, &sch, msg, sizeof msg) != MR_THEATER_OK) fail_msg("%s", msg);
  return sch;
}

/* Light load: nothing skipped, every frame computed for exactly j/60 s and
 * shown exactly one period after that time: the one frame of delay. */
static void light_load_lands_every_frame_on_time(void **state) {
  (void)state;
  show s;
  memset(&s, 0, sizeof s);
  s.vc.t = s.origin = 100.0;
  s.render_cost = 0.2 / 60;
  s.advance_cost = 0.3 / 60;
  mr_scheduler *sch = start(&s, MR_POLICY_SKIP);
  for (int i = 0; i < 1000; i++) assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  mr_scheduler_stats st;
  mr_scheduler_get_stats(sch, &st);
  assert_int_equal(st.frames_skipped, 0);
  assert_int_equal(st.frames_simulated, 1000);
  assert_int_equal(st.frames_presented, 999); /* the last waits for the next tick */
  assert_int_equal(s.bad_landing, 0);
  assert_int_equal(s.bad_delay, 0);
  assert_int_equal(st.steps, 2000);
  assert_true(fabs(st.last_present_wall - 100.0 - (st.last_present_sim + s.period)) < 1e-9);
  assert_true(st.dropped_time == 0.0);
  mr_scheduler_destroy(sch);
}

/* A render costing twice the frame period: renders are skipped, the
 * frames between are still simulated on their times, and over 10 000
 * frames simulated time never trails wall time by more than a frame. */
static void heavy_renders_are_skipped_without_a_spiral(void **state) {
  (void)state;
  show s;
  memset(&s, 0, sizeof s);
  s.render_cost = 2.0 / 60;
  s.advance_cost = 0.1 / 60;
  mr_scheduler *sch = start(&s, MR_POLICY_SKIP);
  double worst = 0;
  mr_scheduler_stats st;
  while (s.advances < 10000) {
    s.advances_in_tick = 0;
    assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
    if (s.advances_in_tick > s.most_in_tick) s.most_in_tick = s.advances_in_tick;
    mr_scheduler_get_stats(sch, &st);
    /* When the newest frame of the tick was simulated, how far its time
     * trailed the wall's. */
    worst = fmax(worst, s.tick_lag);
  }
  printf("render 2 periods: %llu of %llu frames shown, %llu skipped, sim trails wall by <= %.4f "
         "frames, shown frames at most %.2f periods old, at most %d frames simulated in a tick, "
         "%.3f s "
         "given up\n",
         (unsigned long long)st.frames_presented, (unsigned long long)st.frames_simulated,
         (unsigned long long)st.frames_skipped, worst / s.period, s.stalest / s.period,
         s.most_in_tick, st.dropped_time);
  assert_true(st.frames_skipped > 5000);
  assert_true(st.frames_presented > 2000);
  assert_int_equal(st.frames_presented + st.frames_skipped + 1, st.frames_simulated);
  assert_true(worst < s.period);
  assert_true(s.stalest < 2 * s.period); /* no stale frame is drawn */
  assert_int_equal(s.bad_landing, 0);
  assert_true(s.most_in_tick <= 3);
  assert_true(st.dropped_time == 0.0);
  mr_scheduler_destroy(sch);
}

/* Physics slower than real time (each frame costs two periods to
 * simulate): the catch-up cap gives the lag up instead of chasing it, so
 * every tick does a bounded amount of work and the show goes on. */
static void slow_physics_is_capped_not_chased(void **state) {
  (void)state;
  show s;
  memset(&s, 0, sizeof s);
  s.render_cost = 0.0;
  s.advance_cost = 2.0 / 60;
  mr_scheduler *sch = start(&s, MR_POLICY_SKIP);
  for (int i = 0; i < 2000; i++) {
    s.advances_in_tick = 0;
    assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
    if (s.advances_in_tick > s.most_in_tick) s.most_in_tick = s.advances_in_tick;
  }
  mr_scheduler_stats st;
  mr_scheduler_get_stats(sch, &st);
  printf("physics at half real time: at most %d frames a tick, %.2f s of %.2f given up, real-time "
         "factor %.3f\n",
         s.most_in_tick, st.dropped_time, st.wall_time, st.real_time_factor);
  assert_true(s.most_in_tick <= mr_default_scheduler_def().max_catch_up);
  /* A frame that waited past its slot is dropped, not drawn late. */
  assert_true(st.frames_skipped > 0);
  assert_true(s.stalest < 2 * s.period);
  assert_true(st.dropped_time > 0.4 * st.wall_time);
  mr_scheduler_destroy(sch);
}

/* The slow policy shows every frame and lets simulated time fall behind:
 * with renders of two periods every frame takes two, so it runs at half of
 * real time, and says so. */
static void slow_policy_skips_nothing_and_reports_the_factor(void **state) {
  (void)state;
  show s;
  memset(&s, 0, sizeof s);
  s.render_cost = 2.0 / 60;
  mr_scheduler *sch = start(&s, MR_POLICY_SLOW);
  for (int i = 0; i < 600; i++) assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  mr_scheduler_stats st;
  mr_scheduler_get_stats(sch, &st);
  printf("slow policy, render 2 periods: %llu shown, %llu skipped, real-time factor %.3f\n",
         (unsigned long long)st.frames_presented, (unsigned long long)st.frames_skipped,
         st.real_time_factor);
  assert_int_equal(st.frames_skipped, 0);
  assert_int_equal(st.frames_presented, 599);
  assert_true(fabs(st.real_time_factor - 0.5) < 0.01);
  mr_scheduler_destroy(sch);
}

/* A sample that arrives at wall time t is in the next frame simulated and
 * on screen by t plus two frame periods, wherever in a period it lands. */
static void a_sample_is_shown_within_two_frame_periods(void **state) {
  (void)state;
  show s;
  memset(&s, 0, sizeof s);
  s.render_cost = 0.1 / 60;
  mr_scheduler *sch = start(&s, MR_POLICY_SKIP);
  for (int i = 0; i < 500; i++) {
    /* Arrives somewhere inside the period before the tick. */
    mr_scheduler_note_input(sch, s.vc.t - s.period * ((i % 10) + 0.5) / 10.0);
    assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  }
  mr_scheduler_stats st;
  mr_scheduler_get_stats(sch, &st);
  printf("latency: p50 %.2f ms, p99 %.2f ms (two periods: %.2f ms)\n", st.latency_p50 * 1e3,
         st.latency_p99 * 1e3, 2e3 * s.period);
  assert_true(st.latency_p99 <= 2 * s.period + 1e-4);
  assert_true(st.latency_p50 > s.period);
  mr_scheduler_destroy(sch);
}

static void bad_definitions_are_refused(void **state) {
  (void)state;
  mr_virtual_clock vc = { 0 };
  mr_clock c = mr_clock_virtual(&vc);
  show s;
  mr_scheduler_hooks h = { advance, present, &s };
  mr_scheduler *sch = NULL;
  char msg[160];
  mr_scheduler_def d = mr_default_scheduler_def();
  d.fps = 0;
  assert_int_equal(mr_scheduler_create(&d, &c, &h, &sch, msg, sizeof msg), MR_THEATER_ERR_ARG);
  assert_null(sch);
  assert_string_equal(msg, "expected fps between 1 and 10000, max_catch_up >= 1 and policy skip "
                           "or slow, got 0, 5, 0");
  mr_scheduler_def z;
  memset(&z, 0, sizeof z);
  assert_int_equal(mr_scheduler_create(&z, &c, &h, &sch, msg, sizeof msg), MR_THEATER_ERR_ARG);
  mr_policy p;
  assert_int_equal(mr_policy_parse("slow", &p), 0);
  assert_int_equal(p, MR_POLICY_SLOW);
  assert_int_equal(mr_policy_parse("fast", &p), -1);
  assert_string_equal(mr_policy_name(MR_POLICY_SKIP), "skip");
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(light_load_lands_every_frame_on_time),
    cmocka_unit_test(heavy_renders_are_skipped_without_a_spiral),
    cmocka_unit_test(slow_physics_is_capped_not_chased),
    cmocka_unit_test(slow_policy_skips_nothing_and_reports_the_factor),
    cmocka_unit_test(a_sample_is_shown_within_two_frame_periods),
    cmocka_unit_test(bad_definitions_are_refused),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
