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

/* A show whose clock starts at origin, simulated time 0 there. */
static show at_origin(double origin) {
  show s;
  memset(&s, 0, sizeof s);
  s.vc.t = s.origin = origin;
  return s;
}

static mr_scheduler *start_def(show *s, const mr_scheduler_def *def) {
  mr_scheduler_def d = *def;
  s->period = 1.0 / d.fps;
  mr_clock c = mr_clock_virtual(&s->vc);
  mr_scheduler_hooks h = { advance, present, s };
  mr_scheduler *sch = NULL;
  char msg[160];
  if (mr_scheduler_create(&d, &c, &h, &sch, msg, sizeof msg) != MR_THEATER_OK) fail_msg("%s", msg);
  return sch;
}

static mr_scheduler *start(show *s, mr_policy policy) {
  mr_scheduler_def d = mr_default_scheduler_def();
  d.policy = policy;
  return start_def(s, &d);
}

/* Light load: nothing skipped, every frame computed for exactly j/60 s and
 * shown exactly one period after that time: the one frame of delay. */
static void light_load_lands_every_frame_on_time(void **state) {
  (void)state;
  show s = at_origin(100.0);
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

/* One tick that costs ten periods (a render that stalled), with the
 * catch-up cap at 3 (not the default 5): that tick simulates three frames
 * and gives up the other eight periods for good, moving the wall origin,
 * so every tick after it simulates one frame again, and shows it one period
 * after its time (from the moved origin); nothing more is given up. */
static void a_stall_past_the_cap_gives_its_lag_up_for_good(void **state) {
  (void)state;
  show s = at_origin(50.0);
  mr_scheduler_def d = mr_default_scheduler_def();
  d.max_catch_up = 3;
  mr_scheduler *sch = start_def(&s, &d);
  for (int i = 0; i < 100; i++) assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  s.render_cost = 10 * s.period; /* the frame shown in the next tick */
  s.advances_in_tick = 0;
  assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  assert_int_equal(s.advances_in_tick, 3);
  s.render_cost = 0;
  mr_scheduler_stats st;
  mr_scheduler_get_stats(sch, &st);
  assert_true(fabs(st.dropped_time - 8 * s.period) < 1e-9);
  s.origin += st.dropped_time;
  s.bad_delay = 0;
  for (int i = 0; i < 100; i++) {
    s.advances_in_tick = 0;
    assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
    if (s.advances_in_tick != 1)
      fail_msg("tick %d after the stall simulated %d frames", i + 1, s.advances_in_tick);
  }
  mr_scheduler_get_stats(sch, &st);
  assert_true(fabs(st.dropped_time - 8 * s.period) < 1e-9);
  assert_int_equal(s.bad_delay, 0);
  assert_int_equal(s.bad_landing, 0);
  mr_scheduler_destroy(sch);
}

/* The slow policy after a single slow frame (a render of ten periods):
 * the nine periods it fell behind are kept as lag, and the frames after it
 * come one period apart, not in a burst to catch up. */
static void slow_policy_after_one_slow_frame_keeps_the_pace(void **state) {
  (void)state;
  show s = at_origin(7.0);
  mr_scheduler *sch = start(&s, MR_POLICY_SLOW);
  mr_scheduler_stats st;
  for (int i = 0; i < 100; i++) assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  mr_scheduler_get_stats(sch, &st);
  double lag_before = st.wall_time - st.sim_time;
  s.render_cost = 10 * s.period;
  assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  s.render_cost = 0;
  assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  mr_scheduler_get_stats(sch, &st);
  double shown = st.last_present_wall;
  for (int i = 0; i < 100; i++) {
    assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
    mr_scheduler_get_stats(sch, &st);
    if (fabs(st.last_present_wall - shown - s.period) > 1e-9)
      fail_msg("frame %d after the slow one came %.3f periods after the last", i + 1,
               (st.last_present_wall - shown) / s.period);
    shown = st.last_present_wall;
  }
  double lag = st.wall_time - st.sim_time - lag_before;
  print_message("one frame of ten periods: %.3f periods behind for good, real-time factor %.4f\n",
                lag / s.period, st.real_time_factor);
  assert_true(fabs(lag - 9 * s.period) < 1e-9);
  assert_int_equal(st.frames_skipped, 0);
  mr_scheduler_destroy(sch);
}

/* Latency counts from the first sample noted for a frame, whichever order
 * they are noted in: two samples 0.9 and 0.1 periods before the tick give
 * 1.9 periods to the frame's presentation, not 1.1. A frame that read no
 * sample adds no latency, however long the show runs on. */
static void latency_counts_from_the_first_sample_of_a_frame(void **state) {
  (void)state;
  show s;
  memset(&s, 0, sizeof s);
  mr_scheduler *sch = start(&s, MR_POLICY_SKIP);
  mr_scheduler_stats st;
  for (int i = 0; i < 100; i++) {
    double early = s.vc.t - 0.9 * s.period, late = s.vc.t - 0.1 * s.period;
    mr_scheduler_note_input(sch, i % 2 == 0 ? early : late);
    mr_scheduler_note_input(sch, i % 2 == 0 ? late : early);
    assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  }
  assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK); /* shows the last of them */
  mr_scheduler_get_stats(sch, &st);
  print_message("latency p50 %.4f, p99 %.4f periods\n", st.latency_p50 / s.period,
                st.latency_p99 / s.period);
  assert_true(st.latency_p50 >= 1.9 * s.period && st.latency_p50 <= 1.9 * s.period + 1.001e-4);
  assert_true(st.latency_p99 == st.latency_p50);
  for (int i = 0; i < 300; i++) assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  mr_scheduler_stats st2;
  mr_scheduler_get_stats(sch, &st2);
  assert_true(st2.latency_p50 == st.latency_p50 && st2.latency_p99 == st.latency_p99);
  mr_scheduler_destroy(sch);
}

/* The latency quantiles on three frames of known latency (5.05, 12.35 and
 * 40.05 ms, each in the middle of a 0.1 ms bin): the median is the second
 * sample's bin's upper edge, 12.4 ms, never below the sample, and the
 * 99th percentile the third's, 40.1 ms. */
static void latency_quantiles_are_the_upper_edge_of_the_samples_bin(void **state) {
  (void)state;
  show s = at_origin(3.0);
  mr_scheduler_def d = mr_default_scheduler_def();
  d.fps = 50;
  mr_scheduler *sch = start_def(&s, &d);
  static const double lat[3] = { 5.05e-3, 12.35e-3, 40.05e-3 };
  for (uint64_t k = 0; k < 4; k++) {
    /* Frame k is computed now and shown at the next tick, origin + (k+1)/fps. */
    if (k < 3) mr_scheduler_note_input(sch, s.origin + (double)(k + 1) / d.fps - lat[k]);
    assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  }
  mr_scheduler_stats st;
  mr_scheduler_get_stats(sch, &st);
  print_message("p50 %.6f s, p99 %.6f s\n", st.latency_p50, st.latency_p99);
  assert_int_equal(st.frames_presented, 3);
  assert_true(fabs(st.latency_p50 - 12.4e-3) < 1e-12);
  assert_true(fabs(st.latency_p99 - 40.1e-3) < 1e-12);
  mr_scheduler_destroy(sch);
}

static void bad_definitions_are_refused(void **state) {
  (void)state;
  mr_virtual_clock vc = { 0 };
  mr_clock c = mr_clock_virtual(&vc);
  show s;
  mr_scheduler_hooks h = { advance, present, &s };
  /* Whatever the pointer held, a refusal leaves it NULL. */
  mr_scheduler *sch = (mr_scheduler *)&s;
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
  assert_int_equal(mr_policy_parse("skip", NULL), -1);
  assert_string_equal(mr_policy_name(MR_POLICY_SKIP), "skip");
  assert_string_equal(mr_policy_name(MR_POLICY_SLOW), "slow");
  assert_string_equal(mr_policy_name((mr_policy)7), "unknown");
  /* The bounds themselves are allowed, a hair past them is not. */
  const double fps[4] = { 1.0, 10000.0, 0.999, 10000.5 };
  for (int i = 0; i < 4; i++) {
    d = mr_default_scheduler_def();
    d.fps = fps[i];
    assert_int_equal(mr_scheduler_create(&d, &c, &h, &sch, NULL, 0),
                     i < 2 ? MR_THEATER_OK : MR_THEATER_ERR_ARG);
    mr_scheduler_destroy(sch);
    sch = NULL;
  }
  for (int cap = 0; cap <= 1; cap++) {
    d = mr_default_scheduler_def();
    d.max_catch_up = cap;
    assert_int_equal(mr_scheduler_create(&d, &c, &h, &sch, NULL, 0),
                     cap ? MR_THEATER_OK : MR_THEATER_ERR_ARG);
    mr_scheduler_destroy(sch);
    sch = NULL;
  }
}

/* Twenty frames: eleven whose sample was noted after the latency clock
 * shows them (a clock behind; counted as no latency, in the first bin),
 * eight at 5.05 ms, and one 5 s late, past the histogram's 2 s and so in
 * its last bin. The median is the first bin's edge, 0.1 ms; the 99th
 * percentile is the late frame, 2 s, where the 90th would still be
 * 5.1 ms. */
static void latency_ends_of_the_histogram_and_its_tail(void **state) {
  (void)state;
  show s = at_origin(1.0);
  mr_scheduler_def d = mr_default_scheduler_def();
  d.fps = 50;
  mr_scheduler *sch = start_def(&s, &d);
  for (uint64_t k = 0; k < 21; k++) {
    const double shown = s.origin + (double)(k + 1) / d.fps;
    if (k < 20) mr_scheduler_note_input(sch, shown - (k < 11 ? -1e-3 : k < 19 ? 5.05e-3 : 5.0));
    assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  }
  mr_scheduler_stats st;
  mr_scheduler_get_stats(sch, &st);
  print_message("p50 %.6f s, p99 %.6f s\n", st.latency_p50, st.latency_p99);
  assert_int_equal(st.frames_presented, 20);
  assert_true(fabs(st.latency_p50 - 0.1e-3) < 1e-12);
  assert_true(fabs(st.latency_p99 - 2.0) < 1e-12);
  mr_scheduler_destroy(sch);
}

/* What the advance hook reports is summed over the frames, from zero;
 * before the first tick the show has taken no time and runs at 1x. */
static int busy_advance(void *user, double t, mr_frame_work *w) {
  (void)t;
  (void)user;
  w->steps = 3;
  w->rejected = 1;
  w->resets = 2;
  return 0;
}

/* A frame that needed no work: the hook leaves the figures as handed to
 * it, which the scheduler zeroes, so a hook may add to them. */
static int idle_advance(void *user, double t, mr_frame_work *w) {
  (void)t;
  (void)user;
  (void)w;
  return 0;
}

static void frame_work_is_summed_over_the_frames(void **state) {
  (void)state;
  show s = at_origin(0.0);
  mr_scheduler_def d = mr_default_scheduler_def();
  mr_clock c = mr_clock_virtual(&s.vc);
  mr_scheduler_hooks h = { busy_advance, present, &s };
  mr_scheduler *sch = NULL;
  assert_int_equal(mr_scheduler_create(&d, &c, &h, &sch, NULL, 0), MR_THEATER_OK);
  mr_scheduler_stats st;
  mr_scheduler_get_stats(sch, &st);
  assert_true(st.wall_time == 0.0 && st.real_time_factor == 1.0);
  for (int k = 0; k < 7; k++) assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  mr_scheduler_get_stats(sch, &st);
  assert_int_equal(st.frames_simulated, 7);
  assert_int_equal(st.steps, 21);
  assert_int_equal(st.rejected, 7);
  assert_int_equal(st.resets, 14);
  mr_scheduler_destroy(sch);
  h.advance = idle_advance;
  assert_int_equal(mr_scheduler_create(&d, &c, &h, &sch, NULL, 0), MR_THEATER_OK);
  for (int k = 0; k < 7; k++) assert_int_equal(mr_scheduler_tick(sch), MR_THEATER_OK);
  mr_scheduler_get_stats(sch, &st);
  assert_int_equal(st.frames_simulated, 7);
  assert_true(st.steps == 0 && st.rejected == 0 && st.resets == 0);
  mr_scheduler_destroy(sch);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(light_load_lands_every_frame_on_time),
    cmocka_unit_test(heavy_renders_are_skipped_without_a_spiral),
    cmocka_unit_test(slow_physics_is_capped_not_chased),
    cmocka_unit_test(slow_policy_skips_nothing_and_reports_the_factor),
    cmocka_unit_test(a_sample_is_shown_within_two_frame_periods),
    cmocka_unit_test(bad_definitions_are_refused),
    cmocka_unit_test(a_stall_past_the_cap_gives_its_lag_up_for_good),
    cmocka_unit_test(slow_policy_after_one_slow_frame_keeps_the_pace),
    cmocka_unit_test(latency_counts_from_the_first_sample_of_a_frame),
    cmocka_unit_test(latency_quantiles_are_the_upper_edge_of_the_samples_bin),
    cmocka_unit_test(latency_ends_of_the_histogram_and_its_tail),
    cmocka_unit_test(frame_work_is_summed_over_the_frames),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
