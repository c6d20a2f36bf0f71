/* The placement of frame points (frame.c): a placement is kept and copied
 * when the frames are placed again at the same time, and each point's
 * offset is turned again only when its frame's orientation changed. What
 * is kept must never outlive what it was computed from: a frame moved
 * again at the same time, a point added to a placed frame, a frame that
 * turns between placements. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "mr_physics.h"

/* A pose at (x, 1, 0), turned by angle about the tilted axis (0.6, 0.8, 0). */
static mr_pose pose_at(double x, double angle) {
  mr_pose p = mr_pose_identity();
  p.position[0] = x;
  p.position[1] = 1.0;
  p.orientation[0] = cos(0.5 * angle);
  p.orientation[1] = 0.6 * sin(0.5 * angle);
  p.orientation[2] = 0.8 * sin(0.5 * angle);
  return p;
}

static mr_world *world_with(uint32_t effects) {
  mr_world_def def = mr_default_world_def();
  def.effects = effects;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  return w;
}

static int add_frame(mr_world *w, const mr_pose *pose) {
  mr_frame_def fd = mr_default_frame_def();
  fd.pose = *pose;
  int id;
  assert_int_equal(mr_world_add_frame(w, &fd, &id), MR_OK);
  return id;
}

static int add_point(mr_world *w, int frame, double x, double y, double z) {
  mr_particle_def p = mr_default_particle_def();
  p.frame = frame;
  p.position[0] = x;
  p.position[1] = y;
  p.position[2] = z;
  int id;
  assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
  return id;
}

/* Where the point with offset local sits on the frame's pose now. */
static void expect_on_frame(const mr_world *w, int frame, int point, const double local[3],
                            double tol) {
  mr_pose at;
  double want[3], x[3], v[3];
  assert_int_equal(mr_world_frame_pose(w, frame, &at), MR_OK);
  mr_pose_apply(&at, local, want);
  assert_int_equal(mr_world_particle_state(w, point, x, v), MR_OK);
  for (int k = 0; k < 3; k++) assert_true(fabs(x[k] - want[k]) <= tol);
}

/* Two targets due now, one after the other: the second placement is at
 * the time of the first, and must still see the frame where the second
 * target put it. */
static void points_follow_a_frame_moved_twice_at_the_same_time(void **state) {
  (void)state;
  mr_world *w = world_with(MR_EFFECT_FRAMES);
  mr_pose start = pose_at(0.0, 0.0), b = pose_at(0.5, 0.7), c = pose_at(-0.25, -1.1);
  int f = add_frame(w, &start), pt = add_point(w, f, 0.3, 1.0, 0.0);
  const double local[3] = { 0.3, 0.0, 0.0 };
  assert_int_equal(mr_world_set_frame_target(w, f, &b, 0.0), MR_OK);
  expect_on_frame(w, f, pt, local, 1e-12);
  assert_int_equal(mr_world_set_frame_target(w, f, &c, 0.0), MR_OK);
  expect_on_frame(w, f, pt, local, 1e-12);
  double x[3], v[3];
  assert_int_equal(mr_world_particle_state(w, pt, x, v), MR_OK);
  assert_true(fabs(x[0] - 0.5) > 0.5); /* c's place, far from b's */
  mr_world_destroy(w);
}

/* World `late` places its frame (a target due now) before its second
 * point is added; world `early` is built in one go with the frame already
 * there. A spring ties a ball to the second point, so where a step's
 * first stage finds that point shows in the ball: both must step to the
 * same bits. */
static void build_late_or_early(mr_world *w, int late) {
  mr_pose start = pose_at(0.0, 0.0), there = pose_at(0.2, 0.9);
  int f = add_frame(w, late ? &start : &there);
  add_point(w, f, 0.3, 1.0, 0.0);
  if (late) assert_int_equal(mr_world_set_frame_target(w, f, &there, 0.0), MR_OK);
  int tip = add_point(w, f, 0.1, 0.6, 0.2);
  mr_particle_def p = mr_default_particle_def();
  p.mass = 0.5;
  p.position[0] = 0.1;
  p.position[1] = 0.1;
  int ball;
  assert_int_equal(mr_world_add_particle(w, &p, &ball), MR_OK);
  mr_spring_def s = mr_default_spring_def();
  s.a = tip;
  s.b = ball;
  s.rest_length = 0.2;
  s.stiffness = 300.0;
  assert_int_equal(mr_world_add_spring(w, &s, NULL), MR_OK);
}

static void a_point_added_to_a_placed_frame_is_placed_at_the_next_step(void **state) {
  (void)state;
  mr_world *late = world_with(MR_EFFECT_FRAMES | MR_EFFECT_SPRINGS);
  mr_world *early = world_with(MR_EFFECT_FRAMES | MR_EFFECT_SPRINGS);
  build_late_or_early(late, 1);
  build_late_or_early(early, 0);
  assert_int_equal(mr_world_step(late, NULL), MR_OK);
  assert_int_equal(mr_world_step(early, NULL), MR_OK);
  for (int i = 1; i < 3; i++) { /* the tip and the ball (the first point's offsets differ) */
    double xl[3], vl[3], xe[3], ve[3];
    assert_int_equal(mr_world_particle_state(late, i, xl, vl), MR_OK);
    assert_int_equal(mr_world_particle_state(early, i, xe, ve), MR_OK);
    assert_memory_equal(xl, xe, sizeof xl);
    assert_memory_equal(vl, ve, sizeof vl);
  }
  double x[3], v[3];
  assert_int_equal(mr_world_particle_state(early, 2, x, v), MR_OK);
  assert_true(v[1] > 0.1); /* the spring pulled the ball up */
  mr_world_destroy(late);
  mr_world_destroy(early);
}

/* A frame turning a full turn over 2 s in 120 targets: after every step
 * its point is where the frame's pose puts it, so each placement turned
 * the offset by the orientation of its own time. */
static void a_turning_frame_turns_its_points_at_every_step(void **state) {
  (void)state;
  mr_world *w = world_with(MR_EFFECT_FRAMES);
  mr_pose start = pose_at(0.0, 0.0);
  int f = add_frame(w, &start), pt = add_point(w, f, 0.3, 1.0, 0.1);
  const double local[3] = { 0.3, 0.0, 0.1 };
  for (int i = 1; i <= 120; i++) {
    mr_pose goal = pose_at(0.01 * i, 6.283185307179586 * i / 120.0);
    assert_int_equal(mr_world_set_frame_target(w, f, &goal, i / 60.0), MR_OK);
    assert_int_equal(mr_world_step_to(w, (i - 0.5) / 60.0, NULL), MR_OK);
    expect_on_frame(w, f, pt, local, 1e-12);
    assert_int_equal(mr_world_step_to(w, i / 60.0, NULL), MR_OK);
    expect_on_frame(w, f, pt, local, 1e-12);
  }
  mr_world_destroy(w);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(points_follow_a_frame_moved_twice_at_the_same_time),
    cmocka_unit_test(a_point_added_to_a_placed_frame_is_placed_at_the_next_step),
    cmocka_unit_test(a_turning_frame_turns_its_points_at_every_step),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
