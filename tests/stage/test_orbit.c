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

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(the_orbit_starts_where_the_camera_stood),
    cmocka_unit_test(turns_and_zooms_keep_within_their_limits),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
