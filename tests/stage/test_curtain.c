/* The moving part of the set as maths: the curtain's openness as a pure
 * function of show time and the show's end, and the follow spot's aim at
 * the middle of the puppets' points (not the control bars'). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "mr_stage.h"

#define NEAR(a, b, tol) assert_true(fabs((a) - (b)) <= (tol))

static void the_curtain_starts_closed_and_is_open_after_its_open_time(void **state) {
  (void)state;
  mr_curtain_def c = mr_default_stage_def().curtain;
  assert_true(c.show);
  NEAR(c.open_s, 1.5, 0);
  NEAR(mr_curtain_openness(&c, -1, 10), 0, 0);
  NEAR(mr_curtain_openness(&c, 0, 10), 0, 0);
  double mid = mr_curtain_openness(&c, 0.75, 10);
  NEAR(mid, 0.5, 1e-12); /* half the time, half open: the step is symmetric */
  double early = mr_curtain_openness(&c, 0.3, 10), late = mr_curtain_openness(&c, 1.2, 10);
  assert_true(early > 0 && early < mid && mid < late && late < 1);
  NEAR(mr_curtain_openness(&c, 1.5, 10), 1, 0);
  NEAR(mr_curtain_openness(&c, 5, 10), 1, 0);
}

static void the_curtain_closes_over_the_last_close_seconds_before_the_end(void **state) {
  (void)state;
  mr_curtain_def c = mr_default_stage_def().curtain;
  NEAR(mr_curtain_openness(&c, 8.5, 10), 1, 0);
  NEAR(mr_curtain_openness(&c, 9.25, 10), 0.5, 1e-12);
  double a = mr_curtain_openness(&c, 9.0, 10), b = mr_curtain_openness(&c, 9.6, 10);
  assert_true(1 > a && a > b && b > 0);
  NEAR(mr_curtain_openness(&c, 10, 10), 0, 0);
  NEAR(mr_curtain_openness(&c, 12, 10), 0, 0);
  /* An end not known (a live show still running): it stays open. */
  NEAR(mr_curtain_openness(&c, 1e5, -1), 1, 0);
  NEAR(mr_curtain_openness(&c, 1e5, NAN), 1, 0);
}

static void other_open_and_close_times_are_kept_and_a_short_show_never_opens_fully(void **state) {
  (void)state;
  mr_curtain_def c = mr_default_stage_def().curtain;
  c.open_s = 3;
  c.close_s = 0.5;
  NEAR(mr_curtain_openness(&c, 1.5, 20), 0.5, 1e-12);
  assert_true(mr_curtain_openness(&c, 2.9, 20) < 1);
  NEAR(mr_curtain_openness(&c, 3, 20), 1, 0);
  NEAR(mr_curtain_openness(&c, 19.75, 20), 0.5, 1e-12);
  NEAR(mr_curtain_openness(&c, 19.5, 20), 1, 0);
  /* A 2 s show: opening and closing overlap; the lesser wins. */
  c.open_s = c.close_s = 1.5;
  double top = 0;
  for (int k = 0; k <= 200; k++) top = fmax(top, mr_curtain_openness(&c, k * 0.01, 2));
  assert_true(top > 0.5 && top < 1);
  /* No time at all: open at once, closed at the end. */
  c.open_s = c.close_s = 0;
  NEAR(mr_curtain_openness(&c, 0, 5), 1, 0);
  NEAR(mr_curtain_openness(&c, 4.999, 5), 1, 0);
  NEAR(mr_curtain_openness(&c, 5, 5), 0, 0);
  /* No curtain: always open. */
  c.show = false;
  NEAR(mr_curtain_openness(&c, 0, 5), 1, 0);
}

/* Two puppet points with models (0 and 1), and a control bar's two
 * points (2 and 3) with a model of its own: the spot aims at the
 * middle of 0 and 1's box only. */
static mr_stage *two_points_and_a_bar(const double *rest) {
  static mr_model_def m[3];
  static const int bar[2] = { 2, 3 }, count[1] = { 2 };
  for (int k = 0; k < 3; k++) m[k] = mr_default_model_def();
  m[0].particles[0] = 0;
  m[1].particles[0] = 1;
  m[2].display = MR_DISPLAY_LINK;
  m[2].particles[0] = 2;
  m[2].particles[1] = 3;
  mr_stage_def d = mr_default_stage_def();
  assert_false(d.follow_spot.show); /* asked for only */
  d.follow_spot.show = true;
  d.models = m;
  d.n_models = 3;
  d.frame_points = bar;
  d.frame_point_count = count;
  d.n_frames = 1;
  mr_stage *s = NULL;
  char msg[256];
  if (mr_stage_create(&d, rest, 4, &s, msg, sizeof msg) != MR_STAGE_OK) fail_msg("%s", msg);
  return s;
}

static void the_stage_tells_the_draw_list_how_far_the_curtain_is_closed(void **state) {
  (void)state;
  const double rest[12] = { 0, 0.5, 0, 0, 1, 0, -0.3, 2, 0, 0.3, 2, 0 };
  mr_stage *s = two_points_and_a_bar(rest);
  const mr_draw_list *l;
  assert_int_equal(mr_stage_update(s, rest, 4, &l), MR_STAGE_OK);
  NEAR(l->curtain_closed, 0, 0); /* not told the time: open */
  assert_int_equal(mr_stage_set_time(s, 0, 10), MR_STAGE_OK);
  NEAR(l->curtain_closed, 1, 0);
  assert_int_equal(mr_stage_set_time(s, 0.75, 10), MR_STAGE_OK);
  assert_int_equal(mr_stage_update(s, rest, 4, &l), MR_STAGE_OK);
  NEAR(l->curtain_closed, 0.5, 1e-12);
  assert_int_equal(mr_stage_set_time(s, NAN, 10), MR_STAGE_ERR_ARG);
  assert_int_equal(mr_stage_set_time(NULL, 0, 10), MR_STAGE_ERR_ARG);
  mr_stage_destroy(s);
}

static void the_follow_spot_aims_at_the_puppets_middle_and_not_at_the_bar(void **state) {
  (void)state;
  double xyz[12] = { 0, 0.5, 0, 0, 1, 0, -0.3, 2, 0, 0.3, 2, 0 };
  mr_stage *s = two_points_and_a_bar(xyz);
  const mr_draw_list *l;
  assert_int_equal(mr_stage_update(s, xyz, 4, &l), MR_STAGE_OK);
  assert_true(l->follow_spot.on);
  NEAR(l->follow_spot.target[0], 0, 1e-12);
  NEAR(l->follow_spot.target[1], 0.75, 1e-12);
  /* The puppet walks 1 m to the right and 0.5 m forward, the bar
   * elsewhere: the spot follows the puppet. */
  const double walked[12] = { 1, 0.5, 0.5, 1, 1, 0.5, 3, 2, -2, 4, 2, -2 };
  memcpy(xyz, walked, sizeof xyz);
  assert_int_equal(mr_stage_update(s, xyz, 4, &l), MR_STAGE_OK);
  NEAR(l->follow_spot.target[0], 1, 1e-12);
  NEAR(l->follow_spot.target[1], 0.75, 1e-12);
  NEAR(l->follow_spot.target[2], 0.5, 1e-12);
  /* It hangs in front of and above the stage (the audience's side, +z). */
  double at[3];
  mr_follow_spot_position(mr_stage_get_def(s), at);
  for (int k = 0; k < 3; k++) NEAR(l->follow_spot.position[k], at[k], 1e-12);
  assert_true(at[1] > 2 && at[2] > 2);
  mr_stage_destroy(s);
}

static void the_follow_spot_and_the_curtain_turn_with_the_audience(void **state) {
  (void)state;
  mr_stage_def d = mr_default_stage_def();
  d.facing_deg = d.orbit_azimuth_deg = 90; /* the audience sits on +x */
  double at[3];
  mr_follow_spot_position(&d, at);
  NEAR(at[0], 4, 1e-9);
  NEAR(at[1], 3.2, 1e-9);
  NEAR(at[2], 0, 1e-9);
  mr_curtain_place p = mr_curtain_place_of(&d);
  NEAR(p.normal[0], 1, 1e-9);
  NEAR(p.right[2], -1, 1e-9);
  assert_true(p.origin[0] > 0 && fabs(p.origin[2]) < 1e-9);
  /* Given, its place and size are the scene's. */
  d.curtain.distance = 2.5;
  d.curtain.width = 3;
  d.curtain.height = 2;
  p = mr_curtain_place_of(&d);
  NEAR(p.origin[0], 2.5, 1e-9);
  NEAR(p.width, 3, 0);
  NEAR(p.height, 2, 0);
}

static void the_default_curtain_hangs_between_the_audience_and_the_show(void **state) {
  (void)state;
  mr_stage_def d = mr_default_stage_def();
  mr_curtain_place p = mr_curtain_place_of(&d);
  mr_orbit o = mr_orbit_of_stage(&d);
  double eye[3];
  mr_orbit_eye(&o, eye);
  assert_true(p.origin[2] > o.target[2] && p.origin[2] < eye[2]);
  assert_true(p.origin[2] <= d.floor_size / 2);
  assert_true(p.width > 0 && p.width <= d.floor_size);
  /* Its top is above what the audience sees where it hangs. */
  double top[3] = { 0, p.origin[1] + p.height, p.origin[2] }, ndc[2];
  mr_view_project(eye, o.target, o.fov_deg, 16.0 / 9, top, ndc);
  assert_true(ndc[1] > 1);
}

/* With an arch, the curtain hangs just behind its plane, on the opening's
 * middle, taller than the opening, and wide enough that open, each half
 * gathered to 18 % of its width (curtain.c) stands behind a post, clear
 * of the opening. Without one it hangs as above. */
static void
behind_an_arch_the_curtain_hangs_just_upstage_and_opens_clear_of_the_opening(void **state) {
  (void)state;
  mr_stage_def d = mr_default_stage_def();
  d.proscenium = true;
  d.set_width = 2.2, d.set_height = 1.7, d.set_front = 0.8, d.set_middle = 0.3;
  mr_curtain_place p = mr_curtain_place_of(&d);
  const double along = p.origin[0] * p.normal[0] + p.origin[2] * p.normal[2];
  const double across = p.origin[0] * p.right[0] + p.origin[2] * p.right[2];
  assert_true(along < d.set_front && along > d.set_front - 0.15);
  NEAR(across, d.set_middle, 1e-9);
  assert_true(p.height > d.set_height);
  assert_true(p.width / 2 * (1 - 0.18) >= d.set_width / 2);
  assert_true(p.width / 2 * (1 - 0.18) < d.set_width / 2 + 0.15);
  d.proscenium = false;
  p = mr_curtain_place_of(&d);
  NEAR(p.origin[0] * p.right[0] + p.origin[2] * p.right[2], 0, 1e-9);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(the_curtain_starts_closed_and_is_open_after_its_open_time),
    cmocka_unit_test(the_curtain_closes_over_the_last_close_seconds_before_the_end),
    cmocka_unit_test(other_open_and_close_times_are_kept_and_a_short_show_never_opens_fully),
    cmocka_unit_test(the_stage_tells_the_draw_list_how_far_the_curtain_is_closed),
    cmocka_unit_test(the_follow_spot_aims_at_the_puppets_middle_and_not_at_the_bar),
    cmocka_unit_test(the_follow_spot_and_the_curtain_turn_with_the_audience),
    cmocka_unit_test(the_default_curtain_hangs_between_the_audience_and_the_show),
    cmocka_unit_test(behind_an_arch_the_curtain_hangs_just_upstage_and_opens_clear_of_the_opening),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
