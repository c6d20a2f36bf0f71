/* The orbit camera's maths (mr_orbit), which the window's mouse drives. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "mr_stage.h"

static double dist3(const double a[3], const double b[3]) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
              (a[2] - b[2]) * (a[2] - b[2]));
}

/* Leaving a scene camera for the orbit keeps the eye where that camera
 * stood and its target and field of view; a camera on its own target
 * gives no direction, and the orbit stays as it was. */
static void the_orbit_starts_where_the_camera_stood(void **state) {
  (void)state;
  mr_stage_def def = mr_default_stage_def();
  mr_orbit start = mr_orbit_of_stage(&def);
  mr_camera_def c = mr_default_camera_def();
  const double pos[3] = { 1.5, 2.0, -3.0 }, target[3] = { 0.2, 0.8, 0.1 };
  for (int i = 0; i < 3; i++) {
    c.position[i] = pos[i];
    c.target[i] = target[i];
  }
  c.fov_deg = 30;
  mr_orbit o = mr_orbit_of_camera(&c, &start);
  double eye[3];
  mr_orbit_eye(&o, eye);
  assert_true(dist3(eye, pos) < 1e-12);
  assert_true(dist3(o.target, target) < 1e-15);
  assert_true(o.fov_deg == 30);
  for (int i = 0; i < 3; i++) c.position[i] = c.target[i];
  mr_orbit same = mr_orbit_of_camera(&c, &start);
  assert_true(same.distance == start.distance && same.azimuth_deg == start.azimuth_deg);
}

/* Dragging keeps the distance and never flips the view over the top;
 * zooming steps 10 % and stops at 5 cm and 100 m. */
static void turns_and_zooms_keep_within_their_limits(void **state) {
  (void)state;
  mr_orbit o = { { 0, 1, 0 }, 2.0, 350, 10, 45 };
  mr_orbit_turn(&o, 20, 100);
  assert_true(fabs(o.azimuth_deg - 10) < 1e-12);
  assert_true(o.elevation_deg == 89);
  mr_orbit_turn(&o, 0, -500);
  assert_true(o.elevation_deg == -89);
  double eye[3];
  mr_orbit_eye(&o, eye);
  assert_true(fabs(dist3(eye, o.target) - 2.0) < 1e-12);
  mr_orbit_zoom(&o, 1);
  assert_true(fabs(o.distance - 1.8) < 1e-12);
  mr_orbit_zoom(&o, -1000);
  assert_true(o.distance == 100);
  mr_orbit_zoom(&o, 1000);
  assert_true(o.distance == 0.05);
}

/* The renderer's projection as maths: the target falls in the middle, a
 * point on the edge of the vertical field of view on the top edge, one as
 * far to the side as aspect allows on the right edge. */
static void a_point_projects_where_the_renderer_draws_it(void **state) {
  (void)state;
  const double eye[3] = { 0, 1, 3 }, target[3] = { 0, 1, 0 },
               t = tan(20 * 3.14159265358979323846 / 180);
  double ndc[2];
  assert_true(fabs(mr_view_project(eye, target, 40, 2, target, ndc) - 3) < 1e-12);
  assert_true(fabs(ndc[0]) < 1e-12 && fabs(ndc[1]) < 1e-12);
  const double top[3] = { 0, 1 + 3 * t, 0 }, right[3] = { 2 * 3 * t, 1, 0 };
  mr_view_project(eye, target, 40, 2, top, ndc);
  assert_true(fabs(ndc[0]) < 1e-12 && fabs(ndc[1] - 1) < 1e-12);
  mr_view_project(eye, target, 40, 2, right, ndc);
  assert_true(fabs(ndc[0] - 1) < 1e-12 && fabs(ndc[1]) < 1e-12);
}

/* `camera: follow`: a goal that jumps and stays is reached without ever
 * passing it, the same whether the frames come often or seldom, and the
 * follower's speed starts from 0 (no jolt at the jump); with a longer
 * time it is slower. */
static void the_follower_reaches_a_still_goal_smoothly_without_overshoot(void **state) {
  (void)state;
  const double start[3] = { 0, 0, 0 }, goal[3] = { 1, 0.5, -2 };
  mr_follow fine = mr_follow_start(0), coarse = mr_follow_start(0), slow = mr_follow_start(1.2);
  assert_true(fine.time == MR_FOLLOW_TIME);
  mr_follow_step(&fine, start, 0.01);
  mr_follow_step(&coarse, start, 0.01);
  mr_follow_step(&slow, start, 0.01);
  assert_true(dist3(fine.pos, start) == 0);
  double last = 0;
  for (int k = 1; k <= 300; k++) {
    mr_follow_step(&fine, goal, 0.01);
    double v =
        sqrt(fine.vel[0] * fine.vel[0] + fine.vel[1] * fine.vel[1] + fine.vel[2] * fine.vel[2]);
    if (k == 1) assert_true(v < 0.2 * dist3(goal, start) / MR_FOLLOW_TIME);
    double gone = fine.pos[0] / goal[0];
    assert_true(gone >= last && gone <= 1);
    last = gone;
  }
  for (int k = 0; k < 3; k++) mr_follow_step(&coarse, goal, 1.0);
  assert_true(dist3(fine.pos, coarse.pos) < 1e-9);
  assert_true(dist3(fine.pos, goal) < 1e-3 * dist3(goal, start));
  mr_follow_step(&slow, goal, 1.0);
  assert_true(dist3(slow.pos, goal) > 0.5 * dist3(goal, start));
}

/* The overlay's box sits in the bottom left corner, inside the picture,
 * and grows with its rows and columns and the picture's height. */
static void the_overlay_box_is_a_compact_bottom_left_corner(void **state) {
  (void)state;
  double a[4], b[4], c[4];
  mr_osd_rect(1280, 720, MR_OSD_ROWS, MR_OSD_COLUMNS, a);
  assert_true(a[0] > 0 && a[0] < 20 && a[1] > 0 && fabs(a[1] + a[3] + a[0] - 720) < 1e-9);
  assert_true(a[2] < 1280 * 0.3 && a[3] < 720 * 0.15);
  mr_osd_rect(1280, 720, 2, 10, b);
  assert_true(b[2] < a[2] && b[3] < a[3] && b[1] > a[1]);
  mr_osd_rect(1920, 1080, MR_OSD_ROWS, MR_OSD_COLUMNS, c);
  assert_true(c[3] > a[3] && c[3] < 1080 * 0.15);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_point_projects_where_the_renderer_draws_it),
    cmocka_unit_test(the_follower_reaches_a_still_goal_smoothly_without_overshoot),
    cmocka_unit_test(the_overlay_box_is_a_compact_bottom_left_corner),
    cmocka_unit_test(the_orbit_starts_where_the_camera_stood),
    cmocka_unit_test(turns_and_zooms_keep_within_their_limits),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
