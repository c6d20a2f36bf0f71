/* The control mapping (§3.2, §6.2): five values in 0..1 become the control
 * frame's pose. Expected poses are worked out by hand; the One Euro
 * filter's lag on a step and its jitter on held-still noise are measured
 * here and quoted in host/control/README.md. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "control_rig.h"
#include "mr_control.h"

static const double PI = 3.14159265358979323846;

/* The relaxed hand (every string at its neutral 0.5) holds the frame at
 * its neutral pose, exactly; each finger alone, fully pulled, gives its
 * own degree of freedom at the end of its range (§3.2's five). */
static void each_finger_drives_its_own_degree_of_freedom(void **state) {
  (void)state;
  const double zero[3] = { 0, 0, 0 };
  static const struct {
    int channel;
    double pos[3], deg[3];
  } cases[] = {
    { 0, { 0, 0, 0 }, { 0, 0, 30 } },   /* thumb: roll */
    { 1, { 0, 0, 0 }, { 30, 0, 0 } },   /* index: pitch */
    { 2, { 0, 0, 0 }, { 0, 45, 0 } },   /* middle: yaw */
    { 3, { 0, 0.15, 0 }, { 0, 0, 0 } }, /* ring: up */
    { 4, { 0, 0, 0.2 }, { 0, 0, 0 } },  /* little: forward */
  };
  mr_mapping_def d = mr_default_mapping_def();
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    mr_control *c = make(&d, 1);
    double v[5] = { 0.5, 0.5, 0.5, 0.5, 0.5 }, t = 0;
    mr_pose p = hold(c, v, &t, 0.5, NULL);
    assert_pose(&p, zero, zero, 1e-15);
    v[cases[i].channel] = 0.999999; /* below the end, so not "stuck" */
    p = hold(c, v, &t, 1.5, NULL);
    assert_pose(&p, cases[i].pos, cases[i].deg, 1e-4);
    mr_control_destroy(c);
  }
}

/* A scene's mapping: a channel on a move with its own range, inverted, a
 * dead zone, a neutral pose the offsets compose onto, and a second
 * mapping to switch to. */
static void scene_mappings_invert_dead_zone_and_switch(void **state) {
  (void)state;
  mr_mapping_def walk = mr_default_mapping_def(), head = mr_default_mapping_def();
  snprintf(head.name, sizeof head.name, "head-only");
  const double at[3] = { 0, 1.25, 0 }, none[3] = { 0, 0, 0 };
  walk.neutral = mr_pose_from_euler_deg(at, none);
  walk.axes[MR_DOF_MOVE_Z] = (mr_axis_def){ 4, -0.4, 0.4, true, 0.5, 0.1 };
  for (int a = 0; a < MR_DOF_COUNT; a++) head.axes[a].channel = -1;
  head.axes[MR_DOF_TURN_Y] = (mr_axis_def){ 4, -90, 90, false, 0.5, 0.0 };
  head.neutral = walk.neutral;
  const mr_mapping_def both[2] = { walk, head };
  mr_control *c = make(both, 2);
  double v[5] = { 0.5, 0.5, 0.5, 0.5, 0.58 }, t = 0; /* within the dead zone */
  mr_pose p = hold(c, v, &t, 3, NULL);
  assert_pose(&p, at, none, 1e-9);
  v[4] = 0.75; /* inverted: 1 − 0.75 = 0.25 of the way from −0.4 to 0.4 */
  p = hold(c, v, &t, 3, NULL);
  const double back[3] = { 0, 1.25, -0.2 };
  assert_pose(&p, back, none, 1e-4);
  assert_int_equal(mr_control_find(c, "head-only"), 1);
  assert_int_equal(mr_control_select(c, 1), MR_CONTROL_OK);
  assert_int_equal(mr_control_selected(c), 1);
  p = hold(c, v, &t, 0.01, NULL); /* same inputs, the other reading: a turn */
  const double turn[3] = { 0, 45, 0 };
  assert_pose(&p, at, turn, 1e-3);
  assert_int_equal(mr_control_select(c, 2), MR_CONTROL_ERR_ARG);
  mr_control_destroy(c);
}

/* A string that reads NaN is held at neutral at once; one stuck at full
 * scale is trusted for stuck_after (2 s), then held at neutral too; both
 * come back when the values do. */
static void broken_channels_are_flagged_and_held_at_neutral(void **state) {
  (void)state;
  mr_mapping_def d = mr_default_mapping_def();
  mr_control *c = make(&d, 1);
  double v[5] = { 0.5, 0.5, 0.5, 0.5, 0.5 }, t = 0;
  mr_channel_state st[5];
  hold(c, v, &t, 1, st);
  v[1] = NAN;
  mr_pose p = hold(c, v, &t, 0.5, st);
  assert_int_equal(st[1], MR_CHANNEL_NOT_FINITE);
  const double zero[3] = { 0, 0, 0 };
  assert_pose(&p, zero, zero, 1e-12);
  v[1] = 0.5;
  v[3] = 1.0;
  hold(c, v, &t, 1.9, st);
  assert_int_equal(st[1], MR_CHANNEL_OK);
  assert_int_equal(st[3], MR_CHANNEL_OK); /* at the end for 1.9 s: still trusted */
  p = hold(c, v, &t, 0.2, st);
  assert_int_equal(st[3], MR_CHANNEL_STUCK);
  p = hold(c, v, &t, 3, st);
  assert_pose(&p, zero, zero, 1e-6); /* back at neutral, smoothly */
  v[3] = 0.9;
  hold(c, v, &t, 0.01, st);
  assert_int_equal(st[3], MR_CHANNEL_OK);
  assert_string_equal(mr_channel_state_name(MR_CHANNEL_STUCK), "stuck at an end");
  /* Out of range values are clamped, not extrapolated. */
  v[3] = 7.0;
  p = hold(c, v, &t, 1.5, st);
  assert_true(p.position[1] <= 0.15 + 1e-12);
  mr_control_destroy(c);
}

static double gaussian(uint64_t *s) {
  double u[2];
  for (int k = 0; k < 2; k++) {
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    u[k] = ((double)(*s >> 11) + 0.5) / 9007199254740992.0;
  }
  return sqrt(-2 * log(u[0])) * cos(2 * PI * u[1]);
}

/* The filter's two promises, at the default settings sampled at 100 Hz:
 * held still under noise of σ = 0.01 its output wanders much less than the
 * input; on a step of 0.3 it gets within 5 % of the new value quickly.
 * Both figures are printed for the README. */
static void one_euro_is_steady_when_still_and_quick_on_a_step(void **state) {
  (void)state;
  mr_mapping_def d = mr_default_mapping_def();
  mr_one_euro f;
  mr_one_euro_init(&f, d.min_cutoff, d.beta, d.d_cutoff);
  uint64_t seed = 7;
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int i = 0; i < 2000; i++) {
    double y = mr_one_euro_filter(&f, 0.5 + 0.01 * gaussian(&seed), i * 0.01);
    if (i >= 500) {
      sum += y;
      sum2 += y * y;
      n++;
    }
  }
  double sd = sqrt(sum2 / n - (sum / n) * (sum / n));
  double lag = -1;
  for (int i = 2000; i < 2300; i++) {
    double y = mr_one_euro_filter(&f, 0.8, i * 0.01);
    if (lag < 0 && y > 0.8 - 0.05 * 0.3) lag = (i - 2000 + 1) * 0.01;
  }
  printf("one euro (min_cutoff %.1f Hz, beta %.1f, 100 Hz): jitter %.4f for input sigma 0.01; "
         "within 5 %% of a 0.3 step after %.2f s\n",
         d.min_cutoff, d.beta, sd, lag);
  assert_true(sd < 0.004);
  assert_true(lag > 0 && lag <= 0.15);
}

/* A string stuck at full scale for less than stuck_after (0.5 s here, not
 * the default 2 s) is trusted; leaving the end, even for one sample, or
 * reading NaN once, starts its timer afresh, so two stretches at the end
 * never add up; one stretch past 0.5 s is flagged. */
static void leaving_an_end_starts_the_stuck_timer_afresh(void **state) {
  (void)state;
  mr_mapping_def d = height_only(0, 1, 0.5, 0);
  d.stuck_after = 0.5;
  mr_control *c = make(&d, 1);
  double v[5] = { 0.5, 0.5, 0.5, 0.5, 0.5 }, t = 0;
  mr_channel_state st[5];
  hold(c, v, &t, 0.2, st);
  for (int round = 0; round < 4; round++) {
    v[3] = 1.0;
    hold(c, v, &t, 0.4, st);
    assert_int_equal(st[3], MR_CHANNEL_OK);
    v[3] = round % 2 == 0 ? 0.9 : NAN; /* off the end for one sample */
    hold(c, v, &t, 0.01, st);
    assert_int_equal(st[3], round % 2 == 0 ? MR_CHANNEL_OK : MR_CHANNEL_NOT_FINITE);
  }
  v[3] = 0.0; /* the other end counts the same */
  hold(c, v, &t, 0.45, st);
  assert_int_equal(st[3], MR_CHANNEL_OK);
  hold(c, v, &t, 0.1, st);
  assert_int_equal(st[3], MR_CHANNEL_STUCK);
  mr_control_destroy(c);
}

/* A broken channel is held at its own axis's neutral, here 0.3 (the
 * range puts 0 m there), not at the middle: the frame stays where the
 * relaxed hand held it, whether the string reads NaN or sticks at an end. */
static void a_broken_channel_is_held_at_its_axis_neutral(void **state) {
  (void)state;
  mr_mapping_def d = height_only(-0.3, 0.7, 0.3, 0);
  d.stuck_after = 0.25;
  mr_control *c = make(&d, 1);
  double v[5] = { 0.5, 0.5, 0.5, 0.3, 0.5 }, t = 0;
  mr_channel_state st[5];
  mr_pose p = hold(c, v, &t, 1, st);
  assert_true(fabs(p.position[1]) < 1e-12);
  v[3] = NAN;
  p = hold(c, v, &t, 1, st);
  assert_int_equal(st[3], MR_CHANNEL_NOT_FINITE);
  if (!(fabs(p.position[1]) < 1e-12)) fail_msg("NaN held at %.6f m, expected 0", p.position[1]);
  v[3] = 1.0;
  hold(c, v, &t, 0.2, st);
  assert_int_equal(st[3], MR_CHANNEL_OK);
  p = hold(c, v, &t, 4, st);
  assert_int_equal(st[3], MR_CHANNEL_STUCK);
  if (!(fabs(p.position[1]) < 1e-6)) fail_msg("stuck held at %.6f m, expected 0", p.position[1]);
  mr_control_destroy(c);
}

/* The dead zone lies about the axis's own neutral, 0.25 here: 0.33 and
 * 0.17 read as 0.25 (the frame holds still at 0 m), 0.4 does not; and
 * 0.45, near the middle but 0.2 from neutral, moves the frame. */
static void the_dead_zone_centres_on_a_neutral_other_than_the_middle(void **state) {
  (void)state;
  mr_mapping_def d = height_only(-0.25, 0.75, 0.25, 0.1);
  static const struct {
    double in, height;
  } cases[] = { { 0.33, 0.0 }, { 0.17, 0.0 }, { 0.25, 0.0 }, { 0.4, 0.15 }, { 0.45, 0.2 } };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    mr_control *c = make(&d, 1);
    double v[5] = { 0.5, 0.5, 0.5, cases[i].in, 0.5 }, t = 0;
    mr_pose p = hold(c, v, &t, 1, NULL);
    if (!(fabs(p.position[1] - cases[i].height) < 1e-9))
      fail_msg("input %.2f: height %.9f m, expected %.2f", cases[i].in, p.position[1],
               cases[i].height);
    mr_control_destroy(c);
  }
}

/* Two samples stamped with the same time (two readings in one frame, or
 * a repeat) are allowed; the second cannot be smoothed against the first
 * (no time passed), so the output stays, and never turns NaN. */
static void two_updates_at_one_time_keep_the_pose_finite(void **state) {
  (void)state;
  mr_mapping_def d = height_only(0, 1, 0.5, 0);
  mr_control *c = make(&d, 1);
  double v[5] = { 0.5, 0.5, 0.5, 0.4, 0.5 }, t = 0;
  mr_pose first, again;
  hold(c, v, &t, 0.5, NULL);
  assert_int_equal(mr_control_update(c, v, t + 0.01, &first, NULL), MR_CONTROL_OK);
  v[3] = 0.8;
  assert_int_equal(mr_control_update(c, v, t + 0.01, &again, NULL), MR_CONTROL_OK);
  t += 0.01;
  assert_true(again.position[1] == first.position[1]);
  mr_pose p = hold(c, v, &t, 2, NULL);
  if (!(fabs(p.position[1] - 0.8) < 1e-3)) fail_msg("height %.6f, expected 0.8", p.position[1]);
  mr_one_euro f;
  mr_one_euro_init(&f, 2.0, 0.5, 3.0);
  assert_true(mr_one_euro_filter(&f, 0.2, 1.0) == 0.2);
  assert_true(mr_one_euro_filter(&f, 0.9, 1.0) == 0.2);
  assert_true(isfinite(mr_one_euro_filter(&f, 0.9, 1.01)));
  mr_control_destroy(c);
}

/* Each mapping smooths with its own filter settings: after a switch the
 * filters run on the new mapping's min_cutoff, beta and d_cutoff (from
 * the state they had), and after switching back on the first's. Checked
 * against a lone One Euro filter given the same samples and settings. */
static void switching_mappings_switches_the_filter_settings(void **state) {
  (void)state;
  mr_mapping_def a = height_only(0, 1, 0.5, 0), b = a;
  snprintf(b.name, sizeof b.name, "quick");
  b.min_cutoff = 4.0;
  b.beta = 3.0;
  b.d_cutoff = 0.2;
  const mr_mapping_def both[2] = { a, b };
  mr_control *c = make(both, 2);
  mr_one_euro f;
  mr_one_euro_init(&f, a.min_cutoff, a.beta, a.d_cutoff);
  const mr_mapping_def *sel[3] = { &a, &b, &a };
  double worst = 0;
  for (int i = 1; i <= 300; i++) {
    int phase = (i - 1) / 100;
    if (i % 100 == 1 && phase > 0) {
      assert_int_equal(mr_control_select(c, phase % 2), MR_CONTROL_OK);
      f.min_cutoff = sel[phase]->min_cutoff; /* the state kept, the settings new */
      f.beta = sel[phase]->beta;
      f.d_cutoff = sel[phase]->d_cutoff;
    }
    double t = i * 0.01, v[5] = { 0.5, 0.5, 0.5, 0.5 + 0.4 * sin(2 * PI * 1.5 * t), 0.5 };
    mr_pose p;
    assert_int_equal(mr_control_update(c, v, t, &p, NULL), MR_CONTROL_OK);
    worst = fmax(worst, fabs(p.position[1] - mr_one_euro_filter(&f, v[3], t)));
  }
  print_message("the control's output differs from a lone filter's by %.3g at most\n", worst);
  assert_true(worst < 1e-12);
  mr_control_destroy(c);
}

/* A dead zone reaches at most half the input on either side of neutral:
 * 0.5 is taken (every input then reads neutral), 0.75 and 1.0 are
 * refused naming the axis; so is a neutral outside 0..1, while 0 and 1
 * themselves are taken. */
static void a_dead_zone_past_half_the_input_or_a_neutral_outside_it_is_refused(void **state) {
  (void)state;
  const char *want = "mapping 'default', move_y: expected a finite range, neutral in 0..1 and "
                     "dead zone in 0..0.5";
  char msg[160];
  mr_control *c = NULL;
  static const double refused[][2] = { { 0.5, 0.75 },  { 0.5, 1.0 },  { 0.5, 0.5000001 },
                                       { -0.01, 0.1 }, { 1.01, 0.1 }, { 0.5, -0.01 } };
  for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
    mr_mapping_def d = height_only(0, 1, refused[i][0], refused[i][1]);
    msg[0] = '\0';
    assert_int_equal(mr_control_create(&d, 1, &c, msg, sizeof msg), MR_CONTROL_ERR_ARG);
    assert_null(c);
    assert_string_equal(msg, want);
  }
  static const double taken[][2] = { { 0.0, 0.1 }, { 1.0, 0.1 } };
  for (size_t i = 0; i < sizeof taken / sizeof taken[0]; i++) {
    mr_mapping_def d = height_only(0, 1, taken[i][0], taken[i][1]);
    c = make(&d, 1);
    mr_control_destroy(c);
  }
  mr_mapping_def d = height_only(0, 1, 0.5, 0.5);
  c = make(&d, 1);
  double v[5] = { 0.5, 0.5, 0.5, 0.999, 0.5 }, t = 0;
  mr_pose p = hold(c, v, &t, 1, NULL);
  assert_true(p.position[1] == 0.5);
  mr_control_destroy(c);
}

/* Bad definitions are refused naming the field; time may not go back. */
static void bad_definitions_and_time_are_refused(void **state) {
  (void)state;
  mr_mapping_def d = mr_default_mapping_def();
  mr_control *c = NULL;
  char msg[160];
  d.axes[MR_DOF_TURN_X].channel = 5;
  assert_int_equal(mr_control_create(&d, 1, &c, msg, sizeof msg), MR_CONTROL_ERR_ARG);
  assert_null(c);
  assert_string_equal(msg, "mapping 'default', turn_x: expected channel 0..4 or -1, got 5");
  mr_mapping_def z;
  memset(&z, 0, sizeof z);
  assert_int_equal(mr_control_create(&z, 1, &c, msg, sizeof msg), MR_CONTROL_ERR_ARG);
  assert_string_equal(msg, "mapping 0 was not made by mr_default_mapping_def");
  d = mr_default_mapping_def();
  d.beta = NAN;
  assert_int_equal(mr_control_create(&d, 1, &c, NULL, 0), MR_CONTROL_ERR_ARG);
  d = mr_default_mapping_def();
  c = make(&d, 1);
  double v[5] = { 0.5, 0.5, 0.5, 0.5, 0.5 };
  mr_pose p;
  assert_int_equal(mr_control_update(c, v, 1.0, &p, NULL), MR_CONTROL_OK);
  assert_int_equal(mr_control_update(c, v, 0.5, &p, NULL), MR_CONTROL_ERR_TIME);
  assert_int_equal(mr_control_update(c, v, NAN, &p, NULL), MR_CONTROL_ERR_TIME);
  mr_dof dof;
  assert_int_equal(mr_dof_parse("move_y", &dof), 0);
  assert_int_equal(dof, MR_DOF_MOVE_Y);
  assert_int_equal(mr_dof_parse("fly", &dof), -1);
  for (int k = 0; k < MR_DOF_COUNT; k++) {
    assert_int_equal(mr_dof_parse(mr_dof_name((mr_dof)k), &dof), 0);
    assert_int_equal(dof, k);
  }
  assert_string_equal(mr_dof_name(MR_DOF_MOVE_Z), "move_z");
  assert_string_equal(mr_dof_name((mr_dof)MR_DOF_COUNT), "unknown");
  mr_control_destroy(c);
  c = NULL;
  d.stuck_after = 0.0; /* a channel would be broken the moment it reached an end */
  assert_int_equal(mr_control_create(&d, 1, &c, msg, sizeof msg), MR_CONTROL_ERR_ARG);
  assert_string_equal(msg, "mapping 'default': expected stuck_after > 0 s, got 0");
  mr_mapping_def many[MR_CONTROL_MAX_MAPPINGS + 1];
  for (int i = 0; i <= MR_CONTROL_MAX_MAPPINGS; i++) many[i] = mr_default_mapping_def();
  assert_int_equal(mr_control_create(many, MR_CONTROL_MAX_MAPPINGS + 1, &c, NULL, 0),
                   MR_CONTROL_ERR_ARG);
  assert_null(c);
  c = make(many, MR_CONTROL_MAX_MAPPINGS);
  assert_int_equal(mr_control_select(c, MR_CONTROL_MAX_MAPPINGS - 1), MR_CONTROL_OK);
  assert_int_equal(mr_control_selected(c), MR_CONTROL_MAX_MAPPINGS - 1);
  assert_int_equal(mr_control_selected(NULL), -1);
  mr_control_destroy(c);
}

/* The defaults host/scenes/FORMAT.md promises, and the values before the
 * first reading: every channel at the middle of its range. */
static void the_defaults_are_the_documented_ones(void **state) {
  (void)state;
  const mr_mapping_def d = mr_default_mapping_def();
  assert_true(d.min_cutoff == 1.0 && d.beta == 0.7 && d.d_cutoff == 1.0);
  assert_true(d.stuck_after == 2.0);
  mr_control *c = make(&d, 1);
  double v[MR_CONTROL_CHANNELS];
  mr_control_values(c, v);
  for (int k = 0; k < MR_CONTROL_CHANNELS; k++) assert_true(v[k] == 0.5);
  mr_control_destroy(c);
}

/* Two readings worked by hand, with the derivative's cutoff apart from
 * the signal's: 0 at t = 0, then 1 at t = 0.1 s. With α(f, T) =
 * 1/(1 + 1/(2π f T)), the speed is α(d_cutoff, T)·10 per second, and the
 * output α(min_cutoff + β·speed, T). */
static void one_euro_takes_the_speed_at_its_own_cutoff(void **state) {
  (void)state;
  const double T = 0.1, min_cutoff = 1.0, beta = 0.3, d_cutoff = 5.0;
  mr_one_euro f;
  mr_one_euro_init(&f, min_cutoff, beta, d_cutoff);
  assert_true(mr_one_euro_filter(&f, 0.0, 0.0) == 0.0);
  const double a_d = 1.0 / (1.0 + 1.0 / (2.0 * PI * d_cutoff * T));
  const double speed = a_d * 1.0 / T;
  const double a = 1.0 / (1.0 + 1.0 / (2.0 * PI * (min_cutoff + beta * speed) * T));
  const double y = mr_one_euro_filter(&f, 1.0, T);
  print_message("one euro: %.12f, by hand %.12f\n", y, a);
  assert_true(fabs(y - a) < 1e-12);
  assert_true(fabs(f.dx - speed) < 1e-12); /* the rate it keeps, rising */
}

/* The same two readings falling, 1 then 0: the speed is as fast the other
 * way, and the cutoff opens by its size as on the way up, so the output
 * falls as far as it rose, 1 − α, and the rate kept is negative. */
static void one_euro_opens_its_cutoff_on_a_fall_as_on_a_rise(void **state) {
  (void)state;
  const double T = 0.1, min_cutoff = 1.0, beta = 0.3, d_cutoff = 5.0;
  mr_one_euro f;
  mr_one_euro_init(&f, min_cutoff, beta, d_cutoff);
  assert_true(mr_one_euro_filter(&f, 1.0, 0.0) == 1.0);
  const double a_d = 1.0 / (1.0 + 1.0 / (2.0 * PI * d_cutoff * T));
  const double speed = a_d * 1.0 / T;
  const double a = 1.0 / (1.0 + 1.0 / (2.0 * PI * (min_cutoff + beta * speed) * T));
  const double y = mr_one_euro_filter(&f, 0.0, T);
  if (!(fabs(y - (1.0 - a)) < 1e-12)) fail_msg("one euro: %.12f, by hand %.12f", y, 1.0 - a);
  assert_true(fabs(f.dx + speed) < 1e-12);
}

/* Each degree of freedom in turn, driven alone by the middle finger with
 * its neutral at 0.3 (the range puts the neutral pose there): a NaN on that
 * string holds the frame at the neutral pose, whichever axis the string
 * drives, the first one too. A string that drives no axis (the thumb here)
 * reads the middle, 0.5, once broken, whatever it read before. */
static void a_broken_channel_is_held_at_the_neutral_of_whichever_axis_it_drives(void **state) {
  (void)state;
  const double zero[3] = { 0, 0, 0 };
  for (int a = 0; a < MR_DOF_COUNT; a++) {
    mr_mapping_def d = mr_default_mapping_def();
    for (int b = 0; b < MR_DOF_COUNT; b++) d.axes[b].channel = -1;
    const double unit = a < MR_DOF_MOVE_X ? 10.0 : 0.1; /* degrees or metres */
    d.axes[a] = (mr_axis_def){ 2, -3 * unit, 7 * unit, false, 0.3, 0 };
    mr_control *c = make(&d, 1);
    double v[5] = { 0.9, 0.5, 0.3, 0.5, 0.5 }, t = 0, u[5];
    mr_channel_state st[5];
    hold(c, v, &t, 1, st);
    mr_control_values(c, u);
    if (!(fabs(u[0] - 0.9) < 1e-3))
      fail_msg("%s: the thumb reads %.6f, expected 0.9", mr_dof_name(a), u[0]);
    v[0] = v[2] = NAN;
    mr_pose p = hold(c, v, &t, 2, st);
    assert_int_equal(st[0], MR_CHANNEL_NOT_FINITE);
    assert_int_equal(st[2], MR_CHANNEL_NOT_FINITE);
    assert_pose(&p, zero, zero, 1e-9);
    mr_control_values(c, u);
    if (!(fabs(u[0] - 0.5) < 1e-3))
      fail_msg("%s: the broken thumb reads %.6f, expected 0.5", mr_dof_name(a), u[0]);
    if (!(fabs(u[2] - 0.3) < 1e-12))
      fail_msg("%s: the broken middle finger reads %.6f, expected 0.3", mr_dof_name(a), u[2]);
    mr_control_destroy(c);
  }
}

/* A mapping is found by its own name only: not by a name no mapping has,
 * the empty one included (the controller's unused room holds empty names),
 * nor by NULL. */
static void a_mapping_is_found_by_its_own_name_only(void **state) {
  (void)state;
  mr_mapping_def two[2] = { mr_default_mapping_def(), mr_default_mapping_def() };
  snprintf(two[0].name, sizeof two[0].name, "walk");
  snprintf(two[1].name, sizeof two[1].name, "fly");
  mr_control *c = make(two, 2);
  assert_int_equal(mr_control_find(c, "walk"), 0);
  assert_int_equal(mr_control_find(c, "fly"), 1);
  assert_int_equal(mr_control_find(c, ""), -1);
  assert_int_equal(mr_control_find(c, "swim"), -1);
  assert_int_equal(mr_control_find(c, NULL), -1);
  assert_int_equal(mr_control_find(NULL, "walk"), -1);
  mr_control_destroy(c);
}

/* A filter just made has seen nothing: its state reads zero, whatever the
 * memory held before, and its first sample comes out as it went in. */
static void a_new_filter_has_seen_nothing(void **state) {
  (void)state;
  mr_one_euro f;
  memset(&f, 0xff, sizeof f);
  mr_one_euro_init(&f, 2.0, 0.5, 3.0);
  assert_true(f.min_cutoff == 2.0 && f.beta == 0.5 && f.d_cutoff == 3.0);
  assert_true(f.x == 0.0 && f.dx == 0.0 && f.t == 0.0);
  assert_false(f.started);
  assert_true(mr_one_euro_filter(&f, 0.75, 4.0) == 0.75);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(each_finger_drives_its_own_degree_of_freedom),
    cmocka_unit_test(scene_mappings_invert_dead_zone_and_switch),
    cmocka_unit_test(broken_channels_are_flagged_and_held_at_neutral),
    cmocka_unit_test(one_euro_is_steady_when_still_and_quick_on_a_step),
    cmocka_unit_test(bad_definitions_and_time_are_refused),
    cmocka_unit_test(the_defaults_are_the_documented_ones),
    cmocka_unit_test(one_euro_takes_the_speed_at_its_own_cutoff),
    cmocka_unit_test(one_euro_opens_its_cutoff_on_a_fall_as_on_a_rise),
    cmocka_unit_test(leaving_an_end_starts_the_stuck_timer_afresh),
    cmocka_unit_test(a_broken_channel_is_held_at_its_axis_neutral),
    cmocka_unit_test(a_broken_channel_is_held_at_the_neutral_of_whichever_axis_it_drives),
    cmocka_unit_test(a_mapping_is_found_by_its_own_name_only),
    cmocka_unit_test(a_new_filter_has_seen_nothing),
    cmocka_unit_test(the_dead_zone_centres_on_a_neutral_other_than_the_middle),
    cmocka_unit_test(two_updates_at_one_time_keep_the_pose_finite),
    cmocka_unit_test(switching_mappings_switches_the_filter_settings),
    cmocka_unit_test(a_dead_zone_past_half_the_input_or_a_neutral_outside_it_is_refused),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
