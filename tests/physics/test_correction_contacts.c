/* The string-length correction after a step (string_correction.c) moves
 * a puppet towards its frames by a projection that knows the constraints
 * and the strings, not the contacts. Where that projection would take a
 * contact past the slop, and deeper than it was, the contact is held in
 * it: the part may go as deep as the slop, or stay as deep as it already
 * is, and the string is still brought back to its length. A contact the
 * step itself left deeper than the slop and half a millimetre is taken
 * back out to that depth. The correction is called here as the step calls
 * it, through the internal header. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "internal.h"

#define RADIUS 0.05
#define REST   0.9

/* A ball of radius RADIUS whose lowest point is `gap` above the floor
 * (y = 0), at x = 0, on a taut string of rest length REST from a frame
 * point at (1, anchor_y, 0): the string is about 0.1 m too long. */
/* One ball on its string, at z, of the world being built. */
static void add_ball(mr_world *w, double gap, double anchor_y, double z) {
  mr_frame_def fd = mr_default_frame_def();
  int frame, anchor, ball;
  assert_int_equal(mr_world_add_frame(w, &fd, &frame), MR_OK);
  mr_particle_def p = mr_default_particle_def();
  p.frame = frame;
  p.position[0] = 1.0;
  p.position[1] = anchor_y;
  p.position[2] = z;
  assert_int_equal(mr_world_add_particle(w, &p, &anchor), MR_OK);
  p = mr_default_particle_def();
  p.position[1] = RADIUS + gap;
  p.position[2] = z;
  p.radius = RADIUS;
  assert_int_equal(mr_world_add_particle(w, &p, &ball), MR_OK);
  mr_string_def s = mr_default_string_def();
  s.frame_particle = anchor;
  s.puppet_particle = ball;
  s.rest_length = REST;
  s.mode = MR_STRING_TAUT;
  assert_int_equal(mr_world_add_string(w, &s, NULL), MR_OK);
}

/* A ball of radius RADIUS whose lowest point is `gap` above the floor
 * (y = 0), at x = 0, on a taut string of rest length REST from a frame
 * point at (1, anchor_y, 0): the string is about 0.1 m too long. `floors`
 * floors in the same place, and `balls` such balls side by side, 1 m
 * apart along z (each its own block of the solve, islands.c). */
static mr_world *ball_on_floors(double gap, double anchor_y, int floors, int balls) {
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_STRINGS | MR_EFFECT_FRAMES | MR_EFFECT_PLANES;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  for (int b = 0; b < balls; b++) add_ball(w, gap, anchor_y, (double)b);
  for (int i = 0; i < floors; i++) {
    mr_plane_def floor = mr_default_plane_def();
    assert_int_equal(mr_world_add_plane(w, &floor, NULL), MR_OK);
  }
  assert_int_equal(mr_world_ensure_ready(w), 0);
  return w;
}

static mr_world *ball_on_floor(double gap, double anchor_y) {
  return ball_on_floors(gap, anchor_y, 1, 1);
}

static double string_length(const mr_world *w) {
  const double *a = &w->x[0], *b = &w->x[3];
  return sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
              (b[2] - a[2]) * (b[2] - a[2]));
}

static double floor_gap(const mr_world *w) {
  return w->x[3 + 1] - RADIUS;
}

/* The frame point is 5 cm below the ball's centre: pulled straight along
 * its string, the ball would end 4.5 mm under the floor. It slides along
 * the floor instead, down to the slop and no further, and the string is
 * at its length. */
static void a_string_pulling_into_the_floor_leaves_the_ball_on_it(void **state) {
  (void)state;
  mr_world *w = ball_on_floor(0.0, 0.0);
  assert_int_equal(mr_strings_correct(w, NAN), 0);
  const double slop = w->def.contact_slop;
  print_message("gap %.9g m, string %.9f m, ball at x = %.4f m\n", floor_gap(w), string_length(w),
                w->x[3]);
  /* to the slop, less what the contact rows' compliance of 1e-6 gives */
  assert_true(fabs(floor_gap(w) + slop) < 1e-8);
  assert_true(fabs(string_length(w) - REST) < 1e-6 * REST);
  assert_true(w->x[3] > 0.09); /* it moved along the floor, to the frame */
  mr_world_destroy(w);
}

/* A ball already 0.5 mm into the floor (the step may leave a contact as
 * deep as the slop and 0.5 mm) is held where it is: not deeper, and not
 * pushed out either, which is the next step's work. */
static void a_ball_already_deep_stays_as_deep(void **state) {
  (void)state;
  mr_world *w = ball_on_floor(-5e-4, -5e-4);
  assert_int_equal(mr_strings_correct(w, NAN), 0);
  print_message("gap %.9g m\n", floor_gap(w));
  assert_true(fabs(floor_gap(w) + 5e-4) < 1e-8);
  assert_true(fabs(string_length(w) - REST) < 1e-6 * REST);
  mr_world_destroy(w);
}

/* A ball 1.5 mm into the floor after a step that went that deep (a
 * contact creeping deeper at every floor step, inside a pile) is taken back
 * out to the slop and half a millimetre, its string at its length; after a
 * step that stayed shallower, nothing is looked for and it stays. */
static void a_ball_left_too_deep_is_taken_back_out(void **state) {
  (void)state;
  const double depth = 1.5e-3;
  for (int deep_step = 0; deep_step < 2; deep_step++) {
    mr_world *w = ball_on_floor(-depth, -depth);
    w->step_deepest = deep_step ? depth : 4e-4;
    assert_int_equal(mr_strings_correct(w, NAN), 0);
    print_message("step %s: gap %.9g m\n", deep_step ? "that deep" : "shallower", floor_gap(w));
    const double want = deep_step ? -(w->def.contact_slop + MR_SINK_MAX) : -depth;
    assert_true(fabs(floor_gap(w) - want) < 1e-8);
    assert_true(fabs(string_length(w) - REST) < 1e-6 * REST);
    mr_world_destroy(w);
  }
}

/* The frame point above the ball: the string lifts it off the floor, no
 * contact goes deeper and the correction is the plain projection, the
 * ball on the string's line at its length. */
static void a_string_lifting_the_ball_is_not_held_back(void **state) {
  (void)state;
  mr_world *w = ball_on_floor(0.0, 0.5);
  const double x0[3] = { w->x[3], w->x[4], w->x[5] };
  assert_int_equal(mr_strings_correct(w, NAN), 0);
  const double d[3] = { w->x[3] - x0[0], w->x[4] - x0[1], w->x[5] - x0[2] };
  const double u[3] = { 1.0 - x0[0], 0.5 - x0[1], -x0[2] };
  /* Δx parallel to the string at the start: the cross product vanishes */
  const double cross = fabs(d[1] * u[0] - d[0] * u[1]);
  print_message("gap %.6f m, off the string's line by %.3g\n", floor_gap(w), cross);
  assert_true(floor_gap(w) > 0.01);
  assert_true(cross < 1e-6);
  assert_true(fabs(string_length(w) - REST) < 1e-6 * REST);
  mr_world_destroy(w);
}

/* The frame point 0.5 mm below the ball's centre: the plain projection
 * sinks the ball 0.05 mm, within the slop, and that is left as it is, the
 * ball on the string's line (a contact is held only past the slop). */
static void a_sink_within_the_slop_is_left_alone(void **state) {
  (void)state;
  mr_world *w = ball_on_floor(0.0, RADIUS - 5e-4);
  const double x0[3] = { w->x[3], w->x[4], w->x[5] };
  assert_int_equal(mr_strings_correct(w, NAN), 0);
  const double d[3] = { w->x[3] - x0[0], w->x[4] - x0[1], w->x[5] - x0[2] };
  const double u[3] = { 1.0 - x0[0], RADIUS - 5e-4 - x0[1], -x0[2] };
  const double cross = fabs(d[1] * u[0] - d[0] * u[1]);
  print_message("gap %.9g m, off the string's line by %.3g\n", floor_gap(w), cross);
  assert_true(floor_gap(w) < -1e-6 && floor_gap(w) > -w->def.contact_slop);
  assert_true(cross < 1e-9);
  mr_world_destroy(w);
}

/* What one correction held is not held by the next: the frame point then
 * above the ball, the ball lifts off the floor it was held on. */
static void a_contact_held_once_is_not_held_again(void **state) {
  (void)state;
  mr_world *w = ball_on_floor(0.0, 0.0);
  assert_int_equal(mr_strings_correct(w, NAN), 0);
  assert_true(fabs(floor_gap(w) + w->def.contact_slop) < 1e-8);
  w->x[1] = 0.5; /* the frame point, raised */
  assert_int_equal(mr_strings_correct(w, NAN), 0);
  print_message("gap after the lift %.6f m\n", floor_gap(w));
  assert_true(floor_gap(w) > 0.01);
  assert_true(fabs(string_length(w) - REST) < 1e-6 * REST);
  mr_world_destroy(w);
}

/* Two floors in one place hold the ball twice: two rows of the same
 * contact, dependent on each other. The contact rows' compliance keeps
 * them independent, as it does in eq. 8 (eval.c), so they share the
 * load and no row is dropped; so too when two such balls are solved
 * block by block. */
static void a_contact_held_twice_shares_the_load(void **state) {
  (void)state;
  for (int balls = 1; balls <= 2; balls++) {
    mr_world *w = ball_on_floors(0.0, 0.0, 2, balls);
    assert_int_equal(mr_strings_correct(w, NAN), 0);
    print_message("%d ball(s): gap %.9g m, dependent rows %d, blocks %d\n", balls, floor_gap(w),
                  w->last_dependent, w->stats.blocks);
    assert_int_equal(w->last_dependent, 0);
    assert_int_equal(w->stats.blocks, balls);
    assert_true(fabs(floor_gap(w) + w->def.contact_slop) < 1e-8);
    assert_true(fabs(string_length(w) - REST) < 1e-6 * REST);
    mr_world_destroy(w);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_string_pulling_into_the_floor_leaves_the_ball_on_it),
    cmocka_unit_test(a_ball_already_deep_stays_as_deep),
    cmocka_unit_test(a_ball_left_too_deep_is_taken_back_out),
    cmocka_unit_test(a_string_lifting_the_ball_is_not_held_back),
    cmocka_unit_test(a_sink_within_the_slop_is_left_alone),
    cmocka_unit_test(a_contact_held_once_is_not_held_again),
    cmocka_unit_test(a_contact_held_twice_shares_the_load),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
