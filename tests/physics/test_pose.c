/* mr_pose, the one pose type of physics, control and render: the Euler
 * conversion keeps the scene files' meaning (x, then y, then z), and
 * rotate, compose, interpolate and turn agree with each other. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "mr_pose.h"

static const double pi = 3.14159265358979323846;

static void assert_vec(const double a[3], double x, double y, double z, double tol) {
  if (fabs(a[0] - x) > tol || fabs(a[1] - y) > tol || fabs(a[2] - z) > tol)
    fail_msg("(%.12g, %.12g, %.12g) != (%.12g, %.12g, %.12g)", a[0], a[1], a[2], x, y, z);
}

/* v' = Rz Ry Rx v written as matrices, the way scene files always meant
 * their rotation: [rx, ry, rz] degrees, x turned first. */
static void euler_by_matrices(const double deg[3], const double v[3], double out[3]) {
  double ax = deg[0] * pi / 180, ay = deg[1] * pi / 180, az = deg[2] * pi / 180;
  double x = v[0], y = v[1], z = v[2];
  double y1 = y * cos(ax) - z * sin(ax), z1 = y * sin(ax) + z * cos(ax);
  double x2 = x * cos(ay) + z1 * sin(ay), z2 = -x * sin(ay) + z1 * cos(ay);
  out[0] = x2 * cos(az) - y1 * sin(az);
  out[1] = x2 * sin(az) + y1 * cos(az);
  out[2] = z2;
}

static void euler_degrees_turn_x_first_then_y_then_z(void **state) {
  (void)state;
  const double angles[][3] = {
    { 30, -50, 70 }, { 90, 0, 0 }, { 0, 90, 0 }, { 0, 0, 90 }, { -120, 45, 200 }
  };
  const double v[3] = { 0.3, -0.7, 1.1 }, pos[3] = { 1, 2, 3 };
  for (size_t i = 0; i < sizeof angles / sizeof angles[0]; i++) {
    mr_pose p = mr_pose_from_euler_deg(pos, angles[i]);
    double want[3], got[3];
    euler_by_matrices(angles[i], v, want);
    mr_pose_apply(&p, v, got);
    assert_vec(got, want[0] + 1, want[1] + 2, want[2] + 3, 1e-12);
  }
  /* A quarter turn about z takes x to y. */
  const double z90[3] = { 0, 0, 90 }, origin[3] = { 0, 0, 0 }, x[3] = { 1, 0, 0 };
  mr_pose q = mr_pose_from_euler_deg(origin, z90);
  double r[3];
  mr_pose_rotate(q.orientation, x, r);
  assert_vec(r, 0, 1, 0, 1e-15);
}

static void unrotate_undoes_rotate_and_identity_moves_nothing(void **state) {
  (void)state;
  const double deg[3] = { 10, 20, 30 }, pos[3] = { 0, 0, 0 }, v[3] = { 1, -2, 0.5 };
  mr_pose p = mr_pose_from_euler_deg(pos, deg);
  double r[3], back[3];
  mr_pose_rotate(p.orientation, v, r);
  mr_pose_unrotate(p.orientation, r, back);
  assert_vec(back, v[0], v[1], v[2], 1e-14);
  mr_pose id = mr_pose_identity();
  mr_pose_apply(&id, v, r);
  assert_vec(r, v[0], v[1], v[2], 0);
}

static void compose_applies_the_second_pose_first(void **state) {
  (void)state;
  const double da[3] = { 0, 0, 90 }, pa[3] = { 1, 0, 0 }, db[3] = { 90, 0, 0 }, pb[3] = { 0, 2, 0 };
  mr_pose a = mr_pose_from_euler_deg(pa, da), b = mr_pose_from_euler_deg(pb, db);
  mr_pose ab = mr_pose_compose(&a, &b);
  const double v[3] = { 0.1, 0.2, 0.3 };
  double once[3], twice[3], both[3];
  mr_pose_apply(&b, v, once);
  mr_pose_apply(&a, once, twice);
  mr_pose_apply(&ab, v, both);
  assert_vec(both, twice[0], twice[1], twice[2], 1e-14);
}

static void interpolate_slerps_the_short_way_at_a_constant_rate(void **state) {
  (void)state;
  const double o[3] = { 0, 0, 0 }, end[3] = { 2, 0, 0 }, z90[3] = { 0, 0, 90 };
  mr_pose a = mr_pose_from_euler_deg(o, o), b = mr_pose_from_euler_deg(end, z90);
  mr_pose half = mr_pose_interpolate(&a, &b, 0.5);
  assert_vec(half.position, 1, 0, 0, 0);
  const double x[3] = { 1, 0, 0 };
  double r[3];
  mr_pose_rotate(half.orientation, x, r);
  assert_vec(r, cos(pi / 4), sin(pi / 4), 0, 1e-15);
  /* −q is the same orientation: the path must not go the long way. */
  mr_pose nb = b;
  for (int k = 0; k < 4; k++) nb.orientation[k] = -nb.orientation[k];
  mr_pose nhalf = mr_pose_interpolate(&a, &nb, 0.5);
  mr_pose_rotate(nhalf.orientation, x, r);
  assert_vec(r, cos(pi / 4), sin(pi / 4), 0, 1e-15);
  double axis[3];
  double angle = mr_pose_turn(a.orientation, nb.orientation, axis);
  assert_true(fabs(angle - pi / 2) < 1e-15);
  assert_vec(axis, 0, 0, 1, 1e-15);
  assert_true(mr_pose_turn(a.orientation, a.orientation, axis) == 0.0);
  assert_vec(axis, 0, 0, 0, 0);
}

/* A jump in the input reaches the follower at most max_move and max_turn
 * at a time, along the straight line and the short slerp; within them the
 * goal itself comes out, to the bit; a goal that is not finite is held. */
static void approach_limits_a_jump_and_passes_a_small_move(void **state) {
  (void)state;
  mr_pose a = mr_pose_identity();
  const double far[3] = { 2.0, 0.0, 0.0 }, deg[3] = { 0, 0, 90 };
  mr_pose b = mr_pose_from_euler_deg(far, deg);
  mr_pose o = mr_pose_approach(&a, &b, 0.5, pi / 8);
  assert_vec(o.position, 0.5, 0, 0, 1e-15);
  double axis[3];
  assert_true(fabs(mr_pose_turn(a.orientation, o.orientation, axis) - pi / 8) < 1e-12);
  assert_vec(axis, 0, 0, 1, 1e-12);
  /* Five more of the same reach it, and stay. */
  for (int i = 0; i < 5; i++) o = mr_pose_approach(&o, &b, 0.5, pi / 8);
  assert_true(memcmp(&o, &b, sizeof o) == 0);
  const double near[3] = { 0.1, 0.0, 0.0 }, tilt[3] = { 5, 0, 0 };
  mr_pose c = mr_pose_from_euler_deg(near, tilt);
  o = mr_pose_approach(&a, &c, 0.5, pi / 8);
  assert_true(memcmp(&o, &c, sizeof o) == 0);
  /* The two limits are separate: a pure turn is not slowed by the move. */
  const double zero[3] = { 0, 0, 0 };
  mr_pose d = mr_pose_from_euler_deg(zero, deg);
  o = mr_pose_approach(&a, &d, 0.0, pi);
  assert_true(memcmp(o.orientation, d.orientation, sizeof o.orientation) == 0);
  mr_pose bad = b;
  bad.position[1] = NAN;
  o = mr_pose_approach(&a, &bad, 1.0, 1.0);
  assert_true(memcmp(&o, &a, sizeof o) == 0);
}

static void normalize_refuses_zero_and_non_finite_quaternions(void **state) {
  (void)state;
  mr_pose p = mr_pose_identity();
  p.orientation[0] = 2;
  assert_int_equal(mr_pose_normalize(&p), 0);
  assert_true(p.orientation[0] == 1.0);
  p.orientation[0] = 0;
  assert_int_equal(mr_pose_normalize(&p), -1);
  p.orientation[0] = NAN;
  assert_int_equal(mr_pose_normalize(&p), -1);
  p = mr_pose_identity();
  p.position[1] = INFINITY;
  assert_int_equal(mr_pose_normalize(&p), -1);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(euler_degrees_turn_x_first_then_y_then_z),
    cmocka_unit_test(unrotate_undoes_rotate_and_identity_moves_nothing),
    cmocka_unit_test(compose_applies_the_second_pose_first),
    cmocka_unit_test(interpolate_slerps_the_short_way_at_a_constant_rate),
    cmocka_unit_test(approach_limits_a_jump_and_passes_a_small_move),
    cmocka_unit_test(normalize_refuses_zero_and_non_finite_quaternions),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
