/* The control frames' path (frame.c): a cubic Hermite curve from target to
 * target whose velocity does not jump where one target follows another,
 * whose rates are the derivatives of its pose, and whose speed stays
 * within the bound a rate limiter reads (mr_world_frame_target_peak); and
 * the motion of a point the frame carries as the taut strings' rows read
 * it (mr_frame_point_motion, through the library's internal header: no
 * public call reports a frame point's acceleration). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "internal.h"

#define FPS 60.0

typedef struct rig {
  mr_world *w;
  int frame, point;
} rig;

/* A smooth track: the frame swings and bobs, and turns to and fro about a
 * tilted axis. */
static mr_pose track(double t) {
  mr_pose p = mr_pose_identity();
  p.position[0] = 0.2 * sin(6.283185307179586 * t);
  p.position[1] = 1.0 + 0.1 * cos(3.0 * t);
  p.position[2] = 0.05 * t;
  const double axis[3] = { 0.28734788556634544, 0.9578262852211514, 0.0 };
  double half = 0.5 * 0.8 * sin(2.0 * t);
  p.orientation[0] = cos(half);
  for (int k = 0; k < 3; k++) p.orientation[k + 1] = axis[k] * sin(half);
  return p;
}

/* A frame at the track's start with one point 0.3 m off its origin (so
 * turns move it). */
/* A world of frames alone, with one frame on the given path at start. */
static mr_world *frame_world(mr_frame_path path, const mr_pose *start, int *frame) {
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_FRAMES;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  mr_frame_def fd = mr_default_frame_def();
  fd.path = path;
  fd.pose = *start;
  assert_int_equal(mr_world_add_frame(w, &fd, frame), MR_OK);
  return w;
}

static void make_rig(rig *r, mr_frame_path path) {
  const mr_pose start = track(0.0);
  r->w = frame_world(path, &start, &r->frame);
  mr_particle_def p = mr_default_particle_def();
  p.frame = r->frame;
  p.position[0] = 0.3;
  assert_int_equal(mr_world_add_particle(r->w, &p, &r->point), MR_OK);
}

static double norm3(const double v[3]) {
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* The largest change of velocity and angular velocity where a target is
 * set, over 1 s of the track at 60 targets a second. */
static double largest_jump(mr_frame_path path) {
  rig r;
  make_rig(&r, path);
  double worst = 0.0;
  for (int f = 1; f <= (int)FPS; f++) {
    double v0[3], w0[3], v1[3], w1[3];
    assert_int_equal(mr_world_frame_rates(r.w, r.frame, v0, w0), MR_OK);
    mr_pose goal = track(f / FPS);
    assert_int_equal(mr_world_set_frame_target(r.w, r.frame, &goal, f / FPS), MR_OK);
    assert_int_equal(mr_world_frame_rates(r.w, r.frame, v1, w1), MR_OK);
    if (f > 1) {
      double dv[3] = { v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2] };
      double dw[3] = { w1[0] - w0[0], w1[1] - w0[1], w1[2] - w0[2] };
      worst = fmax(worst, fmax(norm3(dv), norm3(dw)));
    }
    assert_int_equal(mr_world_step_to(r.w, f / FPS, NULL), MR_OK);
    /* and the target is reached when it is due */
    mr_pose at;
    assert_int_equal(mr_world_frame_pose(r.w, r.frame, &at), MR_OK);
    for (int k = 0; k < 3; k++) assert_true(fabs(at.position[k] - goal.position[k]) < 1e-12);
  }
  mr_world_destroy(r.w);
  return worst;
}

/* Where one target follows the next, the frame's velocity and angular
 * velocity carry on unchanged (to rounding); on the straight path
 * (MR_FRAME_LINEAR) they jump by the change of chord, 0.07 m/s and more. */
static void velocity_is_continuous_where_targets_follow(void **state) {
  (void)state;
  double smooth = largest_jump(MR_FRAME_SMOOTH), linear = largest_jump(MR_FRAME_LINEAR);
  print_message("largest jump: smooth %.3g, linear %.3g\n", smooth, linear);
  assert_true(smooth < 1e-12);
  assert_true(linear > 0.05);
}

/* Quaternion product a b. */
static void qmul(const double a[4], const double b[4], double o[4]) {
  o[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  o[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  o[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  o[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
}

/* Inside each segment, the rates the frame reports at t are the central
 * differences of its pose at t ± δ (δ = 10 µs, so the differences are
 * exact to about 1e-7 of these rates): the velocity of its position, the
 * angular velocity of its orientation (q(t+δ) q(t−δ)* turns by 2δ ω), and
 * its point's velocity v + ω × r of the point's positions. */
static void rates_are_the_derivatives_of_the_pose(void **state) {
  (void)state;
  rig r;
  make_rig(&r, MR_FRAME_SMOOTH);
  const double d = 1e-5;
  double worst = 0.0, scale = 0.0;
  for (int f = 1; f <= 30; f++) {
    mr_pose goal = track(f / FPS);
    assert_int_equal(mr_world_set_frame_target(r.w, r.frame, &goal, f / FPS), MR_OK);
    for (int i = 1; i <= 3; i++) {
      double tm = (f - 1 + 0.25 * i) / FPS;
      mr_pose a, b;
      double v[3], om[3], xa[3], xb[3], xv[3];
      assert_int_equal(mr_world_step_to(r.w, tm - d, NULL), MR_OK);
      mr_world_frame_pose(r.w, r.frame, &a);
      mr_world_particle_state(r.w, r.point, xa, NULL);
      assert_int_equal(mr_world_step_to(r.w, tm, NULL), MR_OK);
      mr_world_frame_rates(r.w, r.frame, v, om);
      mr_world_particle_state(r.w, r.point, NULL, xv);
      assert_int_equal(mr_world_step_to(r.w, tm + d, NULL), MR_OK);
      mr_world_frame_pose(r.w, r.frame, &b);
      mr_world_particle_state(r.w, r.point, xb, NULL);
      const double ac[4] = { a.orientation[0], -a.orientation[1], -a.orientation[2],
                             -a.orientation[3] };
      double rel[4];
      qmul(b.orientation, ac, rel);
      double sgn = rel[0] < 0 ? -1.0 : 1.0;
      for (int k = 0; k < 3; k++) {
        worst = fmax(worst, fabs((b.position[k] - a.position[k]) / (2 * d) - v[k]));
        worst = fmax(worst, fabs(sgn * rel[k + 1] / d - om[k]));
        worst = fmax(worst, fabs((xb[k] - xa[k]) / (2 * d) - xv[k]));
      }
      scale = fmax(scale, fmax(norm3(v), norm3(om)));
    }
    assert_int_equal(mr_world_step_to(r.w, f / FPS, NULL), MR_OK);
  }
  print_message("rates against differences: %.3g (rates up to %.3g)\n", worst, scale);
  assert_true(scale > 0.5);
  assert_true(worst < 1e-6 * scale);
  mr_world_destroy(r.w);
}

/* mr_world_frame_target_peak bounds the path's speed and turn rate. The
 * frame moves and turns at 3, then 1, then 1 m/s (rad/s) of chord: on the
 * third segment it leaves at rest (the parabola's slope after slowing
 * down) and arrives at 1, and its speed bulges to 4/3 inside the segment,
 * above both ends. Sampled every 1/200 of the segment, it never passes the
 * bound (2: the Bézier control points of its velocity), and the bound is
 * not loose by more than a factor 1.6 (measured 1.5). */
static void peak_bounds_the_path(void **state) {
  (void)state;
  rig r;
  make_rig(&r, MR_FRAME_SMOOTH);
  const double at[4] = { 0.0, 3.0, 4.0, 5.0 }; /* 60ths of a metre, of a radian */
  mr_pose start = track(0.0), goal = start;
  double speed = 0.0, turn = 0.0, top = 0.0, top_turn = 0.0;
  for (int f = 1; f <= 3; f++) {
    double a = at[f] / FPS, axis_y = sin(0.5 * a);
    for (int k = 0; k < 3; k++) goal.position[k] = start.position[k] + (k == 0 ? a : 0.0);
    const double turn_q[4] = { cos(0.5 * a), 0.0, axis_y, 0.0 };
    double q[4];
    q[0] = turn_q[0] * start.orientation[0] - turn_q[2] * start.orientation[2];
    q[1] = turn_q[0] * start.orientation[1] + turn_q[2] * start.orientation[3];
    q[2] = turn_q[0] * start.orientation[2] + turn_q[2] * start.orientation[0];
    q[3] = turn_q[0] * start.orientation[3] - turn_q[2] * start.orientation[1];
    for (int k = 0; k < 4; k++) goal.orientation[k] = q[k];
    if (f == 3)
      assert_int_equal(mr_world_frame_target_peak(r.w, r.frame, &goal, f / FPS, &speed, &turn),
                       MR_OK);
    assert_int_equal(mr_world_set_frame_target(r.w, r.frame, &goal, f / FPS), MR_OK);
    if (f < 3) {
      assert_int_equal(mr_world_step_to(r.w, f / FPS, NULL), MR_OK);
      continue;
    }
    for (int i = 1; i <= 200; i++) {
      assert_int_equal(mr_world_step_to(r.w, (2 + i / 200.0) / FPS, NULL), MR_OK);
      double v[3], om[3];
      mr_world_frame_rates(r.w, r.frame, v, om);
      top = fmax(top, norm3(v));
      top_turn = fmax(top_turn, norm3(om));
    }
  }
  print_message("speed %.4g <= %.4g, turn rate %.4g <= %.4g\n", top, speed, top_turn, turn);
  assert_true(top > 1.3 && top_turn > 1.3); /* the bulge past both ends */
  assert_true(top <= speed && top > speed / 1.6);
  assert_true(top_turn <= turn && top_turn > turn / 1.6);
  mr_world_destroy(r.w);
}

typedef void (*timed_track)(double t, mr_pose *p, double v[3], double om[3]);

/* The largest difference between the frame's pose and rates at the world's
 * time t and the track's there: position, orientation's vector part,
 * velocity, angular velocity. */
static double off_track(mr_world *w, int frame, double t, timed_track track_at) {
  mr_pose want, got;
  double wv[3], ww[3], v[3], om[3], worst = 0.0;
  track_at(t, &want, wv, ww);
  assert_int_equal(mr_world_frame_pose(w, frame, &got), MR_OK);
  assert_int_equal(mr_world_frame_rates(w, frame, v, om), MR_OK);
  for (int k = 0; k < 3; k++) {
    worst = fmax(worst, fabs(got.position[k] - want.position[k]));
    worst = fmax(worst, fabs(got.orientation[k + 1] - want.orientation[k + 1]));
    worst = fmax(worst, fabs(v[k] - wv[k]));
    worst = fmax(worst, fabs(om[k] - ww[k]));
  }
  return worst;
}

/* A track quadratic in time, p = (3t², −2t², 0), turning by 4t² rad about
 * a fixed axis, with targets at uneven times. The parabola through the last
 * two targets and the new one is then the track itself, so each segment's
 * end rate is exact, and from the third segment on (the first leaves from
 * rest, the second inherits its wrong end rate) the cubic path is the track:
 * its pose and rates at any time inside, and its acceleration (6, −4, 0)
 * m/s² and 8 rad/s². The uneven times weigh the two chords unequally. */
static void quadratic_track(double t, mr_pose *p, double v[3], double om[3]) {
  const double axis[3] = { 0.0, 0.6, 0.8 };
  *p = mr_pose_identity();
  p->position[0] = 3.0 * t * t;
  p->position[1] = -2.0 * t * t;
  p->orientation[0] = cos(2.0 * t * t);
  for (int k = 0; k < 3; k++) {
    p->orientation[k + 1] = axis[k] * sin(2.0 * t * t);
    om[k] = axis[k] * 8.0 * t;
  }
  v[0] = 6.0 * t;
  v[1] = -4.0 * t;
  v[2] = 0.0;
}

static void a_quadratic_track_is_followed_exactly_at_uneven_targets(void **state) {
  (void)state;
  const mr_pose rest = mr_pose_identity();
  int frame;
  mr_world *w = frame_world(MR_FRAME_SMOOTH, &rest, &frame);
  const double at[] = { 0.05, 0.08, 0.15, 0.17, 0.25, 0.3 };
  double worst = 0.0;
  int checked = 0;
  for (int s = 0; s < 6; s++) {
    mr_pose goal;
    double gv[3], gw[3];
    quadratic_track(at[s], &goal, gv, gw);
    if (s >= 2) {
      double accel, turn_accel;
      assert_int_equal(mr_world_frame_target_accel(w, frame, &goal, at[s], &accel, &turn_accel),
                       MR_OK);
      assert_true(fabs(accel - sqrt(52.0)) < 1e-9 * sqrt(52.0));
      assert_true(fabs(turn_accel - 8.0) < 1e-9 * 8.0);
    }
    assert_int_equal(mr_world_set_frame_target(w, frame, &goal, at[s]), MR_OK);
    const double t0 = s > 0 ? at[s - 1] : 0.0;
    for (int i = 1; i <= 4; i++) {
      double t = t0 + 0.25 * i * (at[s] - t0);
      assert_int_equal(mr_world_step_to(w, t, NULL), MR_OK);
      if (s < 2) continue;
      worst = fmax(worst, off_track(w, frame, t, quadratic_track));
      checked++;
    }
  }
  print_message("quadratic track: worst difference %.3g over %d samples\n", worst, checked);
  assert_int_equal(checked, 16);
  assert_true(worst < 1e-10);
  mr_world_destroy(w);
}

/* A track cubic in time from rest, p = (2t³ − t², t³, 0), turning by
 * 3t³ + t² rad about a fixed axis. Given the track's own rates at each
 * target (mr_world_set_frame_target_rates), the cubic path is the track
 * from the first segment on, at uneven targets; the parabola's slopes,
 * which are exact only for a quadratic, are not. */
static void cubic_track(double t, mr_pose *p, double v[3], double om[3]) {
  const double axis[3] = { 0.0, 0.6, 0.8 }, angle = 3.0 * t * t * t + t * t;
  *p = mr_pose_identity();
  p->position[0] = 2.0 * t * t * t - t * t;
  p->position[1] = t * t * t;
  p->orientation[0] = cos(0.5 * angle);
  for (int k = 0; k < 3; k++) {
    p->orientation[k + 1] = axis[k] * sin(0.5 * angle);
    om[k] = axis[k] * (9.0 * t * t + 2.0 * t);
  }
  v[0] = 6.0 * t * t - 2.0 * t;
  v[1] = 3.0 * t * t;
  v[2] = 0.0;
}

/* The worst difference from the cubic track at four times inside each of
 * the segments to uneven targets, the targets set with the track's rates
 * or without. */
static double cubic_worst(int with_rates) {
  const mr_pose rest = mr_pose_identity();
  int frame;
  mr_world *w = frame_world(MR_FRAME_SMOOTH, &rest, &frame);
  const double at[] = { 0.05, 0.08, 0.15, 0.17, 0.25, 0.3 };
  double worst = 0.0, t0 = 0.0;
  for (int s = 0; s < 6; s++) {
    mr_pose goal;
    double gv[3], gw[3];
    cubic_track(at[s], &goal, gv, gw);
    if (with_rates)
      assert_int_equal(mr_world_set_frame_target_rates(w, frame, &goal, gv, gw, at[s]), MR_OK);
    else
      assert_int_equal(mr_world_set_frame_target(w, frame, &goal, at[s]), MR_OK);
    for (int i = 1; i <= 4; i++) {
      double t = t0 + 0.25 * i * (at[s] - t0);
      assert_int_equal(mr_world_step_to(w, t, NULL), MR_OK);
      worst = fmax(worst, off_track(w, frame, t, cubic_track));
    }
    t0 = at[s];
  }
  mr_world_destroy(w);
  return worst;
}

static void a_cubic_track_is_followed_exactly_at_its_own_rates(void **state) {
  (void)state;
  const double given = cubic_worst(1), parabola = cubic_worst(0);
  print_message("cubic track: worst difference %.3g at its own rates, %.3g at the parabola's\n",
                given, parabola);
  assert_true(given < 1e-10);
  assert_true(parabola > 1e-3);
}

/* The bound on the path to a target with given end rates reads those
 * rates: arriving at 5 m/s and 4 rad/s after a short, slow chord, the
 * path's speed and turn rate reach them, and no sample passes the bound.
 * Rates that are not finite are refused, and the frame keeps its path. */
static void given_rates_are_bounded_and_checked(void **state) {
  (void)state;
  const mr_pose rest = mr_pose_identity();
  int frame;
  mr_world *w = frame_world(MR_FRAME_SMOOTH, &rest, &frame);
  mr_pose goal = rest;
  goal.position[0] = 0.01;
  const double v1[3] = { 0.0, 5.0, 0.0 }, w1[3] = { 4.0, 0.0, 0.0 };
  double speed, turn, top = 0.0, top_turn = 0.0;
  assert_int_equal(mr_world_frame_target_rates_peak(w, frame, &goal, v1, w1, 0.1, &speed, &turn),
                   MR_OK);
  const double nan3[3] = { 0.0, NAN, 0.0 };
  assert_int_equal(mr_world_set_frame_target_rates(w, frame, &goal, nan3, w1, 0.1),
                   MR_ERR_NONFINITE);
  assert_non_null(strstr(mr_world_last_error(w), "mr_world_set_frame_target_rates"));
  assert_int_equal(mr_world_frame_target_rates_peak(w, frame, &goal, v1, nan3, 0.1, &speed, &turn),
                   MR_ERR_NONFINITE);
  assert_int_equal(mr_world_set_frame_target_rates(w, frame, &goal, NULL, w1, 0.1), MR_ERR_ARG);
  assert_int_equal(mr_world_set_frame_target_rates(w, frame, &goal, v1, w1, 0.1), MR_OK);
  for (int i = 1; i <= 200; i++) {
    double v[3], om[3];
    assert_int_equal(mr_world_step_to(w, 0.1 * i / 200.0, NULL), MR_OK);
    mr_world_frame_rates(w, frame, v, om);
    top = fmax(top, norm3(v));
    top_turn = fmax(top_turn, norm3(om));
  }
  print_message("speed %.4g <= %.4g, turn rate %.4g <= %.4g\n", top, speed, top_turn, turn);
  assert_true(fabs(top - 5.0) < 1e-9 && top <= speed);
  assert_true(fabs(top_turn - 4.0) < 1e-9 && top_turn <= turn);
  mr_world_destroy(w);
}

/* A tumbling track: a turn about z that swings to and fro after a steady
 * roll about x, so the rates at a segment's two ends are not parallel. */
static mr_pose tumble(double t) {
  mr_pose p = mr_pose_identity();
  p.position[0] = 0.3 * sin(4.0 * t);
  p.position[1] = 1.0 + 0.2 * t * t;
  p.position[2] = 0.1 * cos(5.0 * t);
  const double a = 0.5 * 1.2 * sin(3.0 * t), b = 0.5 * 2.5 * t;
  const double z[4] = { cos(a), 0.0, 0.0, sin(a) }, x[4] = { cos(b), sin(b), 0.0, 0.0 };
  qmul(z, x, p.orientation);
  return p;
}

/* A frame on the tumbling track, stepped through three targets 1/30 s
 * apart, at 3/30 s; with a point carried at (0.3, −0.2, 0.1) from its
 * origin when point is not NULL. */
#define STEP (1.0 / 30.0)
static mr_world *tumbling(int *frame, int *point) {
  const mr_pose start = tumble(0.0);
  mr_world *w = frame_world(MR_FRAME_SMOOTH, &start, frame);
  if (point) {
    mr_particle_def p = mr_default_particle_def();
    p.frame = *frame;
    p.position[0] = start.position[0] + 0.3;
    p.position[1] = start.position[1] - 0.2;
    p.position[2] = start.position[2] + 0.1;
    assert_int_equal(mr_world_add_particle(w, &p, point), MR_OK);
  }
  for (int f = 1; f <= 3; f++) {
    mr_pose goal = tumble(f * STEP);
    assert_int_equal(mr_world_set_frame_target(w, *frame, &goal, f * STEP), MR_OK);
    assert_int_equal(mr_world_step_to(w, f * STEP, NULL), MR_OK);
  }
  return w;
}

/* The frame's velocity and angular velocity at the world's time t. */
static void rates_at(mr_world *w, int frame, double t, double v[3], double om[3]) {
  assert_int_equal(mr_world_step_to(w, t, NULL), MR_OK);
  assert_int_equal(mr_world_frame_rates(w, frame, v, om), MR_OK);
}

/* mr_world_frame_target_accel reports the acceleration and angular
 * acceleration of the path the target makes at its start, middle and end:
 * they are the derivatives of the rates the frame then reports there
 * (second-order differences over 50 µs), on a tumbling segment, whose
 * start rate is carried by the turns the path makes after it. */
static void target_accel_is_the_derivative_of_the_rates(void **state) {
  (void)state;
  int frame;
  mr_world *w = tumbling(&frame, NULL);
  const double step = STEP, d = 5e-5;
  const double t0 = 3 * step, t1 = 4 * step, tm = 0.5 * (t0 + t1);
  mr_pose goal = tumble(t1);
  double accel, turn_accel;
  assert_int_equal(mr_world_frame_target_accel(w, frame, &goal, t1, &accel, &turn_accel), MR_OK);
  assert_int_equal(mr_world_set_frame_target(w, frame, &goal, t1), MR_OK);
  /* Rates at t0, t0 + d, t0 + 2d, tm ± d, t1 − 2d, t1 − d, t1. */
  const double at[8] = { t0, t0 + d, t0 + 2 * d, tm - d, tm + d, t1 - 2 * d, t1 - d, t1 };
  double v[8][3], om[8][3];
  for (int i = 0; i < 8; i++) rates_at(w, frame, at[i], v[i], om[i]);
  double a[3][3], b[3][3], top = 0.0, top_turn = 0.0;
  for (int k = 0; k < 3; k++) {
    a[0][k] = (-3 * v[0][k] + 4 * v[1][k] - v[2][k]) / (2 * d);
    a[1][k] = (v[4][k] - v[3][k]) / (2 * d);
    a[2][k] = (3 * v[7][k] - 4 * v[6][k] + v[5][k]) / (2 * d);
    b[0][k] = (-3 * om[0][k] + 4 * om[1][k] - om[2][k]) / (2 * d);
    b[1][k] = (om[4][k] - om[3][k]) / (2 * d);
    b[2][k] = (3 * om[7][k] - 4 * om[6][k] + om[5][k]) / (2 * d);
  }
  for (int i = 0; i < 3; i++) {
    top = fmax(top, norm3(a[i]));
    top_turn = fmax(top_turn, norm3(b[i]));
  }
  print_message("accel %.9g (differences %.9g), turn %.9g (differences %.9g)\n", accel, top,
                turn_accel, top_turn);
  assert_true(top > 1.0 && top_turn > 1.0);
  assert_true(fabs(accel - top) < 1e-5 * top);
  assert_true(fabs(turn_accel - top_turn) < 1e-5 * top_turn);
  mr_world_destroy(w);
}

/* The point's place and velocity with the frames placed at t. */
static void placed(mr_world *w, int i, double t, double x[3], double v[3]) {
  mr_frames_place(w, t, w->x, w->v);
  memcpy(x, &w->x[3 * i], 3 * sizeof *x);
  memcpy(v, &w->v[3 * i], 3 * sizeof *v);
}

/* mr_frame_point_motion's velocity and acceleration are the derivatives of
 * where the frame carries the point (central differences over 10 µs), and
 * mr_frame_point_velocity's velocity is its velocity, at
 * three times inside a tumbling segment, away from its ends, where the
 * path's own terms do not vanish: the centripetal part ω × (ω × r), and
 * the angular acceleration of turns about turning axes. */
static void point_motion_is_the_derivative_of_its_path(void **state) {
  (void)state;
  int frame, point;
  mr_world *w = tumbling(&frame, &point);
  mr_pose goal = tumble(4 * STEP);
  assert_int_equal(mr_world_set_frame_target(w, frame, &goal, 4 * STEP), MR_OK);
  const double d = 1e-5, within[3] = { 0.3, 0.5, 0.8 };
  double worst_v = 0.0, worst_a = 0.0, top_a = 0.0;
  for (int s = 0; s < 3; s++) {
    const double t = (3.0 + within[s]) * STEP;
    double x0[3], v0[3], x1[3], v1[3], x[3], vm[3], v[3], a[3];
    placed(w, point, t - d, x0, v0);
    placed(w, point, t + d, x1, v1);
    placed(w, point, t, x, vm);
    mr_frame_point_motion(w, point, t, w->x, v, a);
    double vo[3]; /* the velocity alone, which rates read: the same bits */
    mr_frame_point_velocity(w, point, t, w->x, vo);
    assert_memory_equal(vo, v, sizeof vo);
    for (int k = 0; k < 3; k++) {
      worst_v = fmax(worst_v, fabs(v[k] - (x1[k] - x0[k]) / (2 * d)));
      worst_a = fmax(worst_a, fabs(a[k] - (v1[k] - v0[k]) / (2 * d)));
      top_a = fmax(top_a, fabs(a[k]));
    }
  }
  print_message("point motion: velocity off by %.3g m/s, acceleration by %.3g of %.3g m/s²\n",
                worst_v, worst_a, top_a);
  assert_true(top_a > 1.0);
  assert_true(worst_v < 1e-7);
  assert_true(worst_a < 1e-5 * top_a);
  mr_world_destroy(w);
}

/* The end of a segment can be where it accelerates hardest: a frame sent
 * 0.3 m from rest in 0.1 s, then 0.5 m further in the next 0.1 s, leaves
 * the second segment at its first's end rate (4.5 m/s) and arrives at the
 * parabola's slope (6 m/s); its acceleration then rises linearly from
 * 0 at the start through 15 to 30 m/s² (0.3 m / (0.1 s)²) at the end. The
 * bound reports the end's, and the rates the frame then has just before
 * the end agree with it. */
static void target_accel_reads_the_end_of_the_segment(void **state) {
  (void)state;
  const mr_pose rest = mr_pose_identity();
  int frame;
  mr_world *w = frame_world(MR_FRAME_SMOOTH, &rest, &frame);
  mr_pose goal = mr_pose_identity();
  goal.position[0] = 0.3;
  assert_int_equal(mr_world_set_frame_target(w, frame, &goal, 0.1), MR_OK);
  assert_int_equal(mr_world_step_to(w, 0.1, NULL), MR_OK);
  goal.position[0] = 0.8;
  double accel, turn_accel;
  assert_int_equal(mr_world_frame_target_accel(w, frame, &goal, 0.2, &accel, &turn_accel), MR_OK);
  print_message("segment's acceleration bound %.9g m/s²\n", accel);
  assert_true(fabs(accel - 30.0) < 1e-9 * 30.0);
  assert_true(turn_accel == 0.0);
  assert_int_equal(mr_world_set_frame_target(w, frame, &goal, 0.2), MR_OK);
  const double d = 5e-5;
  double v[3][3], om[3];
  for (int i = 0; i < 3; i++) rates_at(w, frame, 0.2 - (2 - i) * d, v[i], om);
  const double end = (3 * v[2][0] - 4 * v[1][0] + v[0][0]) / (2 * d);
  print_message("acceleration at the end from the rates %.9g m/s²\n", end);
  assert_true(fabs(end - accel) < 1e-5 * accel);
  mr_world_destroy(w);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(velocity_is_continuous_where_targets_follow),
    cmocka_unit_test(rates_are_the_derivatives_of_the_pose),
    cmocka_unit_test(peak_bounds_the_path),
    cmocka_unit_test(a_quadratic_track_is_followed_exactly_at_uneven_targets),
    cmocka_unit_test(a_cubic_track_is_followed_exactly_at_its_own_rates),
    cmocka_unit_test(given_rates_are_bounded_and_checked),
    cmocka_unit_test(target_accel_is_the_derivative_of_the_rates),
    cmocka_unit_test(point_motion_is_the_derivative_of_its_path),
    cmocka_unit_test(target_accel_reads_the_end_of_the_segment),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
