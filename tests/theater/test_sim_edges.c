/* A headless run (mr_sim_run) at its edges: a run that needs exactly
 * sim.max_steps steps, a run that ends a hair past a frame, the rest
 * checks anchored on a step that lands on `settle`, the step guard
 * counting rejected tries, a frame interpolated outside its step, the
 * account of the first of many resets, steps that add up a hair short of
 * the end, and the checks' bounds. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mr_scene.h"
#include "mr_scene_world.h"
#include "mr_sim.h"
#include "theater_internal.h"

/* A particle falling from 10 m, at fixed steps of 0.01 s. */
#define FALL                                                \
  "physics:\n"                                              \
  "  effects: [gravity]\n"                                  \
  "  ats: {dt_initial: 0.01, dt_min: 0.01, dt_max: 0.01}\n" \
  "  particles: [{name: p, position: [0, 10, 0], mass: 1}]\n"

static void load(const char *text, mr_scene *s) {
  mr_scene_error err;
  if (mr_scene_load_text("edge.yaml", text, strlen(text), s, &err) != MR_SCENE_OK)
    fail_msg("%s", err.text);
}

static void sim(const mr_scene *s, const mr_sim_def *o, mr_sim_result *r) {
  mr_scene_error err;
  if (mr_sim_run(s, o, r, &err) != MR_SCENE_OK) fail_msg("%s", err.text);
}

/* A run starts from the state it is given and leaves its end state: the
 * particle thrown from (1, 2, 3) at (4, 5, −6) m/s falls for 1 s under
 * g = 9.81 (RK4 is exact on a parabola), and a second run from that end
 * state ends where one run of 2 s would. A state that is not finite is
 * refused, naming the particle. */
static void a_run_starts_from_a_given_state_and_leaves_its_end_state(void **state) {
  (void)state;
  mr_scene s;
  load(FALL, &s);
  const double start[6] = { 1, 2, 3, 4, 5, -6 };
  double end[6], again[6];
  mr_sim_def o = mr_default_sim_def();
  o.duration = 1.0;
  o.start_state = start;
  o.end_state = end;
  mr_sim_result r;
  sim(&s, &o, &r);
  const double want[6] = { 5, 2 + 5 - 0.5 * 9.81, -3, 4, 5 - 9.81, -6 };
  for (int i = 0; i < 6; i++) assert_true(fabs(end[i] - want[i]) < 1e-9);
  o.start_state = end;
  o.end_state = again;
  sim(&s, &o, &r);
  print_message("after 1 s: y %.12f, vy %.12f; after 2: y %.12f\n", end[1], end[4], again[1]);
  assert_true(fabs(again[1] - (2 + 10 - 0.5 * 9.81 * 4)) < 1e-9);
  assert_true(fabs(again[4] - (5 - 9.81 * 2)) < 1e-9);
  const double bad[6] = { 0, NAN, 0, 0, 0, 0 };
  o.start_state = bad;
  mr_scene_error err;
  assert_int_equal(mr_sim_run(&s, &o, &r, &err), MR_SCENE_ERR_VALUE);
  assert_non_null(strstr(err.text, "the start state of particle p"));
  mr_scene_free(&s);
}

/* 1 s at steps of 0.01 s needs 100 steps: sim.max_steps 100 is enough,
 * and the run is not refused; every step is at dt_max, and counted so. */
static void a_run_that_needs_exactly_max_steps_is_taken(void **state) {
  (void)state;
  mr_scene s;
  load("sim: {duration: 1, max_steps: 100}\n" FALL, &s);
  mr_sim_result r;
  sim(&s, NULL, &r);
  assert_int_equal(r.steps, 100);
  assert_int_equal(r.rejected, 0);
  assert_true(r.at_upper_fraction == 1.0);
  mr_scene_free(&s);
}

/* A run 0.1 ns longer than ten frames at 10 fps ends with the frame at
 * 1 s (steps closer than 1 ns to a frame land on it): eleven frames, the
 * start included, not a twelfth for the sliver. */
static void a_run_a_hair_past_a_frame_ends_on_that_frame(void **state) {
  (void)state;
  mr_scene s;
  load("sim: {duration: 1}\n" FALL, &s);
  mr_sim_def o = mr_default_sim_def();
  o.fps = 10;
  o.duration = 1.0 + 1e-10;
  mr_sim_result r;
  sim(&s, &o, &r);
  assert_int_equal(r.frames, 11);
  assert_true(r.sim_time == 1.0);
  mr_scene_free(&s);
}

typedef struct heights {
  int n;
  double t[16], y[16];
} heights;

static void keep_height(void *user, double t, const double *xyz, int n) {
  heights *h = user;
  (void)n;
  if (h->n < 16) {
    h->t[h->n] = t;
    h->y[h->n] = xyz[1];
    h->n++;
  }
}

/* The rest checks measure from the state at `settle` itself when a step
 * lands there: frames at 10 fps land on 0.5 s, so the creep of a falling
 * particle over the run is exactly its fall from the frame at 0.5 s to the
 * frame at 1 s. */
static void creep_is_measured_from_the_step_that_lands_on_settle(void **state) {
  (void)state;
  mr_scene s;
  load("sim: {duration: 1, fps: 10}\n" FALL
       "expect: {rest: {particles: [p], settle: 0.5, creep: 100, jitter: 100}}\n",
       &s);
  heights h;
  memset(&h, 0, sizeof h);
  mr_sim_def o = mr_default_sim_def();
  o.on_frame = keep_height;
  o.user = &h;
  mr_sim_result r;
  sim(&s, &o, &r);
  assert_int_equal(h.n, 11);
  assert_true(h.t[5] == 0.5 && h.t[10] == 1.0);
  const double fall = h.y[5] - h.y[10];
  print_message("creep %.12f m, fall from 0.5 s to 1 s %.12f m\n", r.creep, fall);
  assert_true(fall > 3.0);
  assert_true(fabs(r.creep - fall) < 1e-12);
  mr_scene_free(&s);
}

/* The step guard counts tries, rejected ones too: the paper's puppet,
 * stepped at the ATS's own Δt, rejects some steps; with sim.max_steps at
 * the number it accepts, the run stops on the way, naming the tries. */
static void the_step_guard_counts_rejected_tries(void **state) {
  (void)state;
  mr_scene s;
  mr_scene_error err;
  if (mr_scene_load(MR_SOURCE_DIR "/host/scenes/puppet.yaml", &s, &err) != MR_SCENE_OK)
    fail_msg("%s", err.text);
  s.fps = 0;
  mr_sim_result r;
  sim(&s, NULL, &r);
  print_message("puppet: %llu steps, %llu rejected\n", (unsigned long long)r.steps,
                (unsigned long long)r.rejected);
  assert_true(r.rejected > 0);
  s.max_steps = (long)r.steps;
  assert_int_equal(mr_sim_run(&s, NULL, &r, &err), MR_SCENE_ERR_BUILD);
  char want[120];
  snprintf(want, sizeof want, "step tries, past sim.max_steps (%ld)", s.max_steps);
  if (strstr(err.message, "stopped after ") != err.message || strstr(err.message, want) == NULL)
    fail_msg("%s", err.message);
  mr_scene_free(&s);
}

/* A string of rest length 0 has no stretch ratio: it is left out of the
 * largest one, which stays 0 with no other string, and is 2 for a string
 * of rest 0.5 hanging 1 m from its point beside it. */
static void a_string_of_rest_zero_has_no_stretch(void **state) {
  (void)state;
  static const char *const strings[2] = {
    "  strings: [{from: bar, to: a, mode: spring, stiffness: 100, rest: 0}]\n",
    "  strings: [{from: bar, to: a, mode: spring, stiffness: 100, rest: 0},\n"
    "            {from: bar, to: b, mode: spring, stiffness: 100, rest: 0.5}]\n",
  };
  for (int i = 0; i < 2; i++) {
    char text[600];
    snprintf(text, sizeof text,
             "sim: {duration: 0.01}\n"
             "physics:\n"
             "  effects: [strings, control]\n"
             "  particles: [{name: a, position: [0, 1, 0], mass: 1},\n"
             "              {name: b, position: [1, 2, 0], mass: 1}]\n"
             "  control: {points: [{name: bar, offset: [0, 2, 0]}]}\n"
             "%s",
             strings[i]);
    mr_scene s;
    load(text, &s);
    mr_sim_result r;
    sim(&s, NULL, &r);
    print_message("largest stretch %.6f\n", r.string_stretch);
    if (i == 0)
      assert_true(r.string_stretch == 0.0);
    else
      assert_true(fabs(r.string_stretch - 2.0) < 0.01);
    mr_scene_free(&s);
  }
}

/* A frame asked for outside the step marked around it is the nearer end of
 * the step, never extrapolated along it: the falling particle's step from
 * 0 to 0.01 s gives its middle at 0.005 s, its end at 0.02 s (and says the
 * physics is 0.01 s behind that frame), its start at -0.01 s. */
static void an_interpolated_frame_outside_its_step_is_the_nearer_end(void **state) {
  (void)state;
  mr_scene s;
  load("sim: {duration: 1}\n" FALL, &s);
  mr_scene_world sw;
  mr_scene_error err;
  if (mr_scene_build(&s, &sw, &err) != MR_SCENE_OK) fail_msg("%s", err.text);
  mr_interp ip;
  assert_int_equal(mr_interp_open(&ip, 1), 0);
  double before[3], after[3];
  mr_world_positions(sw.world, before, 1);
  mr_interp_mark(&ip, sw.world);
  assert_true(mr_world_step_to(sw.world, 0.01, NULL) >= 0);
  mr_world_positions(sw.world, after, 1);
  assert_true(before[1] - after[1] > 1e-4);
  const double *y = mr_interp_at(&ip, sw.world, 0.005);
  assert_true(fabs(y[1] - 0.5 * (before[1] + after[1])) < 1e-12);
  y = mr_interp_at(&ip, sw.world, 0.02);
  if (!(y[1] == after[1])) fail_msg("at 0.02 s: %.12f, the step's end %.12f", y[1], after[1]);
  assert_true(fabs(ip.lead + 0.01) < 1e-12);
  y = mr_interp_at(&ip, sw.world, -0.01);
  assert_true(y[1] == before[1]);
  mr_interp_close(&ip);
  mr_scene_world_free(&sw);
  mr_scene_free(&s);
}

/* A run that resets many times keeps the account of its first reset, not
 * its latest: a speed bound no fall can meet resets every step, first at
 * 0.01 s, last near the end at 0.5 s. */
static void the_first_reset_is_the_one_kept(void **state) {
  (void)state;
  mr_scene s;
  load("sim: {duration: 0.5, fps: 10}\n"
       "physics:\n"
       "  effects: [gravity]\n"
       "  ats: {max_speed: 0.001, dt_min: 0.01, dt_max: 0.02}\n"
       "  particles: [{name: a, position: [0, 1, 0], mass: 1}]\n",
       &s);
  mr_sim_result r;
  sim(&s, NULL, &r);
  print_message("%llu resets, the first: %s\n", (unsigned long long)r.resets, r.first_reset);
  assert_true(r.resets >= 10);
  if (strncmp(r.first_reset, "t=0.010000 s: ", 14) != 0) fail_msg("first reset: %s", r.first_reset);
  mr_scene_free(&s);
}

/* Ten fixed steps of 0.1 s add up a hair short of 1 s (0.9999999999999999):
 * the last one lands on the run's end all the same, so the run ends at
 * 1 s exactly (where a pinned state hash is checked). */
static void steps_that_add_up_short_still_land_on_the_end(void **state) {
  (void)state;
  mr_scene s;
  load("sim: {duration: 1}\n"
       "physics:\n"
       "  effects: [gravity]\n"
       "  ats: {dt_initial: 0.1, dt_min: 0.1, dt_max: 0.1}\n"
       "  particles: [{name: p, position: [0, 10, 0], mass: 1}]\n",
       &s);
  mr_sim_result r;
  sim(&s, NULL, &r);
  assert_int_equal(r.steps, 10);
  if (!(r.sim_time == 1.0)) fail_msg("the run ended at %.17g s", r.sim_time);
  mr_scene_free(&s);
}

/* Each expectation is a bound the result may reach: the paper's puppet,
 * run for 1 s and checked against its own figures, each set as the
 * bound, passes. */
static void a_result_exactly_on_each_bound_passes_the_check(void **state) {
  (void)state;
  mr_scene s;
  mr_scene_error err;
  if (mr_scene_load(MR_SOURCE_DIR "/host/scenes/puppet.yaml", &s, &err) != MR_SCENE_OK)
    fail_msg("%s", err.text);
  mr_sim_def o = mr_default_sim_def();
  o.duration = 1;
  mr_sim_result r;
  sim(&s, &o, &r);
  assert_true(r.max_deviation > 0 && r.max_speed > 0 && r.dt_mean > 0 && r.string_stretch > 1);
  s.expect.max_deviation = r.max_deviation;
  s.expect.max_speed = r.max_speed;
  s.expect.min_mean_dt = r.dt_mean;
  s.expect.max_penetration = r.max_penetration;
  s.expect.min_string_stretch = r.string_stretch;
  s.expect.max_string_stretch = r.string_stretch;
  s.expect.resets_min = s.expect.resets_max = (long)r.resets;
  char msg[200];
  if (mr_sim_check(&s, &r, msg, sizeof msg) != 0) fail_msg("%s", msg);
  mr_scene_free(&s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_run_starts_from_a_given_state_and_leaves_its_end_state),
    cmocka_unit_test(a_run_that_needs_exactly_max_steps_is_taken),
    cmocka_unit_test(a_run_a_hair_past_a_frame_ends_on_that_frame),
    cmocka_unit_test(creep_is_measured_from_the_step_that_lands_on_settle),
    cmocka_unit_test(the_step_guard_counts_rejected_tries),
    cmocka_unit_test(a_string_of_rest_zero_has_no_stretch),
    cmocka_unit_test(an_interpolated_frame_outside_its_step_is_the_nearer_end),
    cmocka_unit_test(the_first_reset_is_the_one_kept),
    cmocka_unit_test(steps_that_add_up_short_still_land_on_the_end),
    cmocka_unit_test(a_result_exactly_on_each_bound_passes_the_check),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
