/* The control mapping at its edges: each bound of a mapping's fields,
 * one past it refused naming the field and the bound itself taken; the
 * clamp at both ends of the input; the dead zone's and stuck_after's own
 * edges; moves in the axes of a turned neutral pose. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>

#include "control_rig.h"
#include "mr_control.h"

/* A value below 0 is clamped to 0 like one above 1 is to 1: the frame
 * stops at the low end of the range, not past it, and the smoothed value
 * reads 0. Held for less than stuck_after, it is trusted. */
static void a_value_below_zero_is_clamped_to_the_low_end(void **state) {
  (void)state;
  mr_mapping_def d = height_only(-0.25, 0.75, 0.5, 0);
  mr_control *c = make(&d, 1);
  double v[5] = { 0.5, 0.5, 0.5, -3.0, 0.5 }, t = 0, u[5];
  mr_channel_state st[5];
  mr_pose p = hold(c, v, &t, 1, st);
  assert_int_equal(st[3], MR_CHANNEL_OK);
  if (!(fabs(p.position[1] + 0.25) < 1e-12))
    fail_msg("height %.9f m, expected -0.25 (the low end)", p.position[1]);
  mr_control_values(c, u);
  assert_true(u[3] == 0.0);
  mr_control_destroy(c);
}

/* A string at an end for exactly stuck_after (0.5 s) is still trusted;
 * past it, by the next sample, it is flagged. Times are exact in binary. */
static void a_string_at_an_end_for_exactly_stuck_after_is_trusted(void **state) {
  (void)state;
  mr_mapping_def d = height_only(0, 1, 0.5, 0);
  d.stuck_after = 0.5;
  mr_control *c = make(&d, 1);
  double v[5] = { 0.5, 0.5, 0.5, 1.0, 0.5 };
  mr_channel_state st[5];
  mr_pose p;
  static const double times[3] = { 1.0, 1.25, 1.5 };
  for (int i = 0; i < 3; i++) {
    assert_int_equal(mr_control_update(c, v, times[i], &p, st), MR_CONTROL_OK);
    if (st[3] != MR_CHANNEL_OK)
      fail_msg("at the end for %.2f s: %s", times[i] - 1.0, mr_channel_state_name(st[3]));
  }
  assert_int_equal(mr_control_update(c, v, 1.515625, &p, st), MR_CONTROL_OK);
  assert_int_equal(st[3], MR_CHANNEL_STUCK);
  mr_control_destroy(c);
}

/* The dead zone includes its edge: 0.25 from neutral (0.5) with a dead
 * zone of 0.25 reads as neutral, a hair further does not. The first
 * sample comes out of the filter as it went in, so the input is exact. */
static void the_dead_zone_includes_its_edge(void **state) {
  (void)state;
  mr_mapping_def d = height_only(0, 1, 0.5, 0.25);
  static const struct {
    double in, height;
  } cases[] = { { 0.75, 0.5 }, { 0.25, 0.5 }, { 0.76, 0.76 }, { 0.24, 0.24 } };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    mr_control *c = make(&d, 1);
    double v[5] = { 0.5, 0.5, 0.5, cases[i].in, 0.5 };
    mr_pose p;
    assert_int_equal(mr_control_update(c, v, 0.0, &p, NULL), MR_CONTROL_OK);
    if (!(p.position[1] == cases[i].height))
      fail_msg("input %.2f: height %.17g m, expected %.2f", cases[i].in, p.position[1],
               cases[i].height);
    mr_control_destroy(c);
  }
}

/* The moves are in the frame's own axes, on top of the neutral pose: with
 * the neutral turned 90° about y, the little finger's forward move (its
 * own z) goes along the world's x, from the neutral's position. */
static void moves_are_in_the_axes_of_a_turned_neutral_pose(void **state) {
  (void)state;
  mr_mapping_def d = mr_default_mapping_def();
  const double at[3] = { 0, 1, 0 }, yaw[3] = { 0, 90, 0 };
  d.neutral = mr_pose_from_euler_deg(at, yaw);
  mr_control *c = make(&d, 1);
  double v[5] = { 0.5, 0.5, 0.5, 0.5, 0.999999 }, t = 0;
  mr_pose p = hold(c, v, &t, 1.5, NULL);
  const double want[3] = { 0.2, 1, 0 };
  assert_pose(&p, want, yaw, 1e-4);
  mr_control_destroy(c);
}

/* Each field's bounds, one past each refused naming it and the bound
 * itself taken: a channel of −2, an infinite end of a range, a cutoff
 * of 0, a neutral pose that is not finite, no mappings at all; beta 0 (a
 * filter that does not open with speed) is taken. */
static void each_field_is_refused_past_its_bound(void **state) {
  (void)state;
  mr_control *c = NULL;
  char msg[160];
  mr_mapping_def d = mr_default_mapping_def();
  d.axes[MR_DOF_TURN_X].channel = -2;
  assert_int_equal(mr_control_create(&d, 1, &c, msg, sizeof msg), MR_CONTROL_ERR_ARG);
  assert_null(c);
  assert_string_equal(msg, "mapping 'default', turn_x: expected channel 0..4 or -1, got -2");
  d = mr_default_mapping_def();
  d.axes[MR_DOF_MOVE_Y].high = INFINITY;
  assert_int_equal(mr_control_create(&d, 1, &c, msg, sizeof msg), MR_CONTROL_ERR_ARG);
  assert_string_equal(msg, "mapping 'default', move_y: expected a finite range, neutral in 0..1 "
                           "and dead zone in 0..0.5");
  d = mr_default_mapping_def();
  d.min_cutoff = 0;
  assert_int_equal(mr_control_create(&d, 1, &c, msg, sizeof msg), MR_CONTROL_ERR_ARG);
  assert_string_equal(msg, "mapping 'default': expected min_cutoff and d_cutoff > 0 and beta >= "
                           "0, got 0, 1, 0.7");
  d = mr_default_mapping_def();
  d.neutral.position[1] = NAN;
  assert_int_equal(mr_control_create(&d, 1, &c, msg, sizeof msg), MR_CONTROL_ERR_ARG);
  assert_string_equal(msg, "mapping 'default': the neutral pose is not finite");
  d = mr_default_mapping_def();
  assert_int_equal(mr_control_create(&d, 0, &c, msg, sizeof msg), MR_CONTROL_ERR_ARG);
  assert_null(c);
  assert_string_equal(msg, "expected 1 to 8 mappings and somewhere to put the controller");
  d.beta = 0;
  c = make(&d, 1);
  assert_int_equal(mr_control_select(c, -1), MR_CONTROL_ERR_ARG);
  assert_int_equal(mr_control_selected(c), 0);
  mr_control_destroy(c);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_value_below_zero_is_clamped_to_the_low_end),
    cmocka_unit_test(a_string_at_an_end_for_exactly_stuck_after_is_trusted),
    cmocka_unit_test(the_dead_zone_includes_its_edge),
    cmocka_unit_test(moves_are_in_the_axes_of_a_turned_neutral_pose),
    cmocka_unit_test(each_field_is_refused_past_its_bound),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
