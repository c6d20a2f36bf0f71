/* The control side's rate limits (control.max_speed, max_turn_rate): the
 * frame follows its input at most that fast, although its path between
 * targets is curved (its velocity is continuous, so it can bulge past the
 * chord's rate inside a segment). The theater draws the goal back until
 * the physics' bound on the path keeps the limits (frame.c). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "mr_scene.h"
#include "mr_scene_world.h"
#include "mr_sim.h"
#include "theater_internal.h"

/* A scene of one particle and one control point, 0.3 m out on a frame
 * at (0, 1, 0); a test adds its own lines to the frame's section. */
#define ONE_POINT                                            \
  "format: 1\n"                                              \
  "physics:\n"                                               \
  "  effects: [control]\n"                                   \
  "  particles: [{name: w, position: [0, 0, 0], mass: 1}]\n" \
  "  control:\n"                                             \
  "    points: [{name: p, offset: [0.3, 0, 0]}]\n"           \
  "    pose: {position: [0, 1, 0]}\n"

/* A frame limited to 2 m/s and 90°/s whose input jumps 1 m sideways and
 * turns 120° within 10 ms at t = 0.2 s, and back at t = 1 s: the frame is driven
 * at 60 targets a second as the theater does, and its speed and turn
 * rate, sampled 20 times inside every segment, never pass the limits,
 * while it does reach them (it is not simply slowed down). */
static void frame_keeps_its_speed_and_turn_limits_on_a_curved_path(void **state) {
  (void)state;
  static const char text[] = "format: 1\n"
                             "physics:\n"
                             "  effects: [control]\n"
                             "  particles: [{name: w, position: [0, 0, 0], mass: 1}]\n"
                             "  control:\n"
                             "    max_speed: 2\n"
                             "    max_turn_rate: 90\n"
                             "    points: [{name: p, offset: [0.3, 0, 0]}]\n"
                             "    pose: {position: [0, 1, 0]}\n"
                             "    track:\n"
                             "      interpolation: linear\n"
                             "      keyframes:\n"
                             "        - {t: 0.0, position: [0, 1, 0]}\n"
                             "        - {t: 0.19, position: [0, 1, 0]}\n"
                             "        - {t: 0.2, position: [1, 1, 0], rotation: [0, 120, 0]}\n"
                             "        - {t: 0.99, position: [1, 1, 0], rotation: [0, 120, 0]}\n"
                             "        - {t: 1.0, position: [0, 1, 0]}\n";
  mr_scene sc;
  mr_scene_error err;
  mr_scene_world sw;
  assert_int_equal(mr_scene_load_text("limits.yaml", text, sizeof text - 1, &sc, &err),
                   MR_SCENE_OK);
  assert_int_equal(mr_scene_build(&sc, &sw, &err), MR_SCENE_OK);
  double top = 0.0, top_turn = 0.0;
  for (int f = 1; f <= 120; f++) {
    double t = f / 60.0;
    mr_pose goal;
    mr_scene_frame_pose_at(&sc, 0, t, &goal);
    mr_theater_head_frame(&sc, &sw, 0, goal, t);
    for (int i = 1; i <= 20; i++) {
      assert_true(mr_world_step_to(sw.world, (f - 1 + i / 20.0) / 60.0, NULL) >= 0);
      double v[3], w[3];
      assert_int_equal(mr_world_frame_rates(sw.world, sw.frames[0], v, w), MR_OK);
      top = fmax(top, sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
      top_turn = fmax(top_turn, sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]));
    }
  }
  print_message("speed %.6f m/s (limit 2), turn rate %.6f rad/s (limit %.6f)\n", top, top_turn,
                3.14159265358979323846 / 2);
  assert_true(top <= 2.0 * (1 + 1e-12) && top > 1.9);
  assert_true(top_turn <= 3.14159265358979323846 / 2 * (1 + 1e-12) && top_turn > 1.4);
  mr_scene_world_free(&sw);
  mr_scene_free(&sc);
}

/* A frame a glove drives, limited to 4 m/s² and 180°/s², whose input
 * jumps 0.6 m sideways and turns 90° between two frames at t = 0.2 s: its
 * velocity and turn rate, sampled 20 times inside every segment, change no
 * faster than the limits allow, and do reach them; it still arrives. A
 * track-driven frame (the test above) is not held to them. */
static void glove_frame_keeps_its_acceleration_limits(void **state) {
  (void)state;
  static const char text[] = ONE_POINT "    max_accel: 4\n"
                                       "    max_turn_accel: 180\n";
  const double pi = 3.14159265358979323846, sub = 1.0 / 1200.0;
  mr_scene sc;
  mr_scene_error err;
  mr_scene_world sw;
  assert_int_equal(mr_scene_load_text("accel.yaml", text, sizeof text - 1, &sc, &err), MR_SCENE_OK);
  assert_int_equal(mr_scene_build(&sc, &sw, &err), MR_SCENE_OK);
  const double still[3] = { 0, 0, 0 }, turned[3] = { 0, 90, 0 };
  const double here[3] = { 0, 1, 0 }, there[3] = { 0.6, 1, 0 };
  double top = 0.0, top_turn = 0.0, v0[3] = { 0 }, w0[3] = { 0 };
  mr_glove_follow follow;
  memset(&follow, 0, sizeof follow);
  for (int f = 1; f <= 180; f++) {
    double t = f / 60.0;
    mr_pose goal =
        t < 0.2 ? mr_pose_from_euler_deg(here, still) : mr_pose_from_euler_deg(there, turned);
    mr_theater_follow_glove(&sc, &sw, 0, &follow, goal, t);
    for (int i = 1; i <= 20; i++) {
      assert_true(mr_world_step_to(sw.world, (f - 1 + i / 20.0) / 60.0, NULL) >= 0);
      double v[3], w[3], dv[3], dw[3];
      assert_int_equal(mr_world_frame_rates(sw.world, sw.frames[0], v, w), MR_OK);
      for (int k = 0; k < 3; k++) {
        dv[k] = (v[k] - v0[k]) / sub;
        dw[k] = (w[k] - w0[k]) / sub;
      }
      memcpy(v0, v, sizeof v0);
      memcpy(w0, w, sizeof w0);
      top = fmax(top, sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]));
      top_turn = fmax(top_turn, sqrt(dw[0] * dw[0] + dw[1] * dw[1] + dw[2] * dw[2]));
    }
  }
  print_message("acceleration %.6f m/s² (limit 4), turn %.6f rad/s² (limit %.6f)\n", top, top_turn,
                pi);
  assert_true(top <= 4.0 * (1 + 1e-6) && top > 3.0);
  assert_true(top_turn <= pi * (1 + 1e-6) && top_turn > 0.75 * pi);
  mr_pose end;
  assert_int_equal(mr_world_frame_pose(sw.world, sw.frames[0], &end), MR_OK);
  print_message("end %.6f %.6f %.6f\n", end.position[0], end.position[1], end.position[2]);
  assert_true(fabs(end.position[0] - 0.6) < 1e-3);
  mr_scene_world_free(&sw);
  mr_scene_free(&sc);
}

/* A hand's motion, well within the default limits (0.1 m at 0.3 Hz, a
 * 30° turn at 0.25 Hz), reaches the frame unchanged: once the bar, at rest
 * at the start while the hand already moves, has caught up (within half a
 * second), at every frame time the frame is where the glove put it (a
 * frame behind would be 3 mm and 0.8° off). */
static void glove_motion_within_the_limits_passes_unchanged(void **state) {
  (void)state;
  static const char text[] = ONE_POINT;
  const double pi = 3.14159265358979323846;
  mr_scene sc;
  mr_scene_error err;
  mr_scene_world sw;
  assert_int_equal(mr_scene_load_text("hand.yaml", text, sizeof text - 1, &sc, &err), MR_SCENE_OK);
  assert_int_equal(mr_scene_build(&sc, &sw, &err), MR_SCENE_OK);
  mr_glove_follow follow;
  memset(&follow, 0, sizeof follow);
  double worst = 0.0, worst_turn = 0.0;
  for (int f = 1; f <= 600; f++) {
    double t = f / 60.0, axis[3];
    double pos[3] = { 0.1 * sin(2 * pi * 0.3 * t), 1, 0 };
    double rot[3] = { 0, 30 * sin(2 * pi * 0.25 * t), 0 };
    mr_pose goal = mr_pose_from_euler_deg(pos, rot), now;
    mr_theater_follow_glove(&sc, &sw, 0, &follow, goal, t);
    assert_true(mr_world_step_to(sw.world, t, NULL) >= 0);
    assert_int_equal(mr_world_frame_pose(sw.world, sw.frames[0], &now), MR_OK);
    if (t < 0.5) continue;
    worst = fmax(worst, fabs(now.position[0] - pos[0]));
    worst_turn = fmax(worst_turn, mr_pose_turn(now.orientation, goal.orientation, axis));
  }
  print_message("farthest from the glove's pose: %.3g m, %.3g rad\n", worst, worst_turn);
  assert_true(worst < 1e-9 && worst_turn < 1e-6);
  mr_scene_world_free(&sw);
  mr_scene_free(&sc);
}

/* The farthest the frame strays from its track (position, and the turn
 * times the 0.3 m to its point) at 20 times inside every segment, when it
 * is driven to targets h apart by mr_theater_track_frame, or, when
 * parabola, by mr_theater_head_frame with the track's poses alone. */
static double track_worst(const mr_scene *sc, double h, int parabola) {
  mr_scene_world sw;
  mr_scene_error err;
  assert_int_equal(mr_scene_build(sc, &sw, &err), MR_SCENE_OK);
  double worst = 0.0;
  for (int f = 1; f * h <= 1.0 + 1e-9; f++) {
    double t = f * h, axis[3];
    if (parabola) {
      mr_pose goal;
      mr_scene_frame_pose_at(sc, 0, t, &goal);
      mr_theater_head_frame(sc, &sw, 0, goal, t);
    } else {
      mr_theater_track_frame(sc, &sw, 0, t);
    }
    for (int i = 1; i <= 20; i++) {
      double ti = (f - 1 + i / 20.0) * h;
      assert_true(mr_world_step_to(sw.world, ti, NULL) >= 0);
      mr_pose want, got;
      mr_scene_frame_pose_at(sc, 0, ti, &want);
      assert_int_equal(mr_world_frame_pose(sw.world, sw.frames[0], &got), MR_OK);
      double d[3] = { got.position[0] - want.position[0], got.position[1] - want.position[1],
                      got.position[2] - want.position[2] };
      if (t > 0.2) /* the first segments leave from rest, as the track does not */
        worst = fmax(worst, fmax(sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]),
                                 0.3 * mr_pose_turn(got.orientation, want.orientation, axis)));
    }
  }
  mr_scene_world_free(&sw);
  return worst;
}

/* A frame the sim drives on its own track at the end of each step the ATS
 * chooses arrives at the track's rates (mr_theater_track_frame), so its
 * path between targets is the track's to fourth order however far apart
 * they are: halving their spacing cuts the farthest it strays about
 * sixteenfold, and at 50 ms it strays under 0.1 mm on a 2 Hz swing of
 * 0.1 m with a 20° turn. Through the track's poses alone (the parabola's
 * slopes), it strays 10 times further and converges at third order only. */
static void a_track_frame_follows_its_track_to_fourth_order(void **state) {
  (void)state;
  static const char text[] = ONE_POINT
      "    track:\n"
      "      oscillate: {amplitude: [0.1, 0.05, 0], rotation: [0, 20, 0], frequency: 2}\n";
  mr_scene sc;
  mr_scene_error err;
  assert_int_equal(mr_scene_load_text("swing.yaml", text, sizeof text - 1, &sc, &err), MR_SCENE_OK);
  const double at50 = track_worst(&sc, 0.05, 0), at25 = track_worst(&sc, 0.025, 0);
  const double p50 = track_worst(&sc, 0.05, 1), p25 = track_worst(&sc, 0.025, 1);
  print_message("farthest from the track: %.3g m at 50 ms, %.3g m at 25 ms (ratio %.1f); through "
                "its poses alone %.3g and %.3g (ratio %.1f)\n",
                at50, at25, at50 / at25, p50, p25, p50 / p25);
  assert_true(at50 < 1e-4 && at50 / at25 > 12.0);
  assert_true(p50 > 10 * at50 && p50 / p25 < 10.0);
  mr_scene_free(&sc);
}

/* A track that jumps faster than the limits is followed as
 * mr_theater_head_frame follows it: the limits hold on the way. */
static void a_track_frame_keeps_the_limits_where_its_track_jumps(void **state) {
  (void)state;
  static const char text[] = ONE_POINT "    max_speed: 2\n"
                                       "    track:\n"
                                       "      interpolation: linear\n"
                                       "      keyframes:\n"
                                       "        - {t: 0.0, position: [0, 1, 0]}\n"
                                       "        - {t: 0.19, position: [0, 1, 0]}\n"
                                       "        - {t: 0.2, position: [1, 1, 0]}\n";
  mr_scene sc;
  mr_scene_error err;
  mr_scene_world sw;
  assert_int_equal(mr_scene_load_text("jump.yaml", text, sizeof text - 1, &sc, &err), MR_SCENE_OK);
  assert_int_equal(mr_scene_build(&sc, &sw, &err), MR_SCENE_OK);
  double top = 0.0;
  for (int f = 1; f <= 60; f++) {
    mr_theater_track_frame(&sc, &sw, 0, f / 60.0);
    for (int i = 1; i <= 20; i++) {
      double v[3], w[3];
      assert_true(mr_world_step_to(sw.world, (f - 1 + i / 20.0) / 60.0, NULL) >= 0);
      assert_int_equal(mr_world_frame_rates(sw.world, sw.frames[0], v, w), MR_OK);
      top = fmax(top, sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    }
  }
  mr_pose end;
  assert_int_equal(mr_world_frame_pose(sw.world, sw.frames[0], &end), MR_OK);
  print_message("speed %.6f m/s (limit 2), at x = %.4f in the end\n", top, end.position[0]);
  assert_true(top <= 2.0 * (1 + 1e-12) && top > 1.9);
  assert_true(fabs(end.position[0] - 1.0) < 1e-6);
  mr_scene_world_free(&sw);
  mr_scene_free(&sc);
}

/* A track frame asked to be somewhere at the world's own time is not put
 * there at once: with no time to move it, the limits keep it where it is,
 * as mr_theater_head_frame does. */
static void a_track_frame_does_not_jump_at_the_worlds_own_time(void **state) {
  (void)state;
  static const char text[] = ONE_POINT "    track:\n"
                                       "      keyframes:\n"
                                       "        - {t: 0.0, position: [0, 1, 0]}\n"
                                       "        - {t: 0.5, position: [1, 1, 0]}\n";
  mr_scene sc;
  mr_scene_error err;
  mr_scene_world sw;
  assert_int_equal(mr_scene_load_text("now.yaml", text, sizeof text - 1, &sc, &err), MR_SCENE_OK);
  assert_int_equal(mr_scene_build(&sc, &sw, &err), MR_SCENE_OK);
  assert_true(mr_world_step_to(sw.world, 0.5, NULL) >= 0);
  mr_theater_track_frame(&sc, &sw, 0, 0.5);
  mr_pose now;
  assert_int_equal(mr_world_frame_pose(sw.world, sw.frames[0], &now), MR_OK);
  print_message("at x = %.6f after a target at the world's time\n", now.position[0]);
  assert_true(fabs(now.position[0]) < 1e-12);
  mr_scene_world_free(&sw);
  mr_scene_free(&sc);
}

/* The control point's position at every frame `marionette sim` presents. */
typedef struct point_path {
  int id, n;
  double xyz[400][3];
} point_path;

static void keep_point(void *user, double t, const double *xyz, int n) {
  (void)t;
  point_path *pp = user;
  assert_true(pp->id < n);
  if (pp->n < 400) memcpy(pp->xyz[pp->n++], &xyz[3 * pp->id], sizeof pp->xyz[0]);
}

/* The angle between two points seen from c. */
static double angle_at(const double c[3], const double a[3], const double b[3]) {
  double u[3], v[3], uv = 0, uu = 0, vv = 0;
  for (int k = 0; k < 3; k++) {
    u[k] = a[k] - c[k];
    v[k] = b[k] - c[k];
    uv += u[k] * v[k];
    uu += u[k] * u[k];
    vv += v[k] * v[k];
  }
  return acos(fmax(-1.0, fmin(1.0, uv / sqrt(uu * vv))));
}

/* `marionette sim` (mr_sim_run at 60 fps) drives a track frame through the
 * same allowance: a track that turns the frame 120° about its own origin
 * within 10 ms, under max_turn_rate 45 (not the default 1440), turns its
 * control point no more than 0.75° from one frame to the next, and brings
 * it round the whole 120° in the end. */
static void marionette_sim_keeps_a_track_frame_within_its_max_turn_rate(void **state) {
  (void)state;
  static const char text[] = "format: 1\n"
                             "physics:\n"
                             "  effects: [control]\n"
                             "  particles: [{name: w, position: [0, 0, 0], mass: 1}]\n"
                             "  control:\n"
                             "    max_turn_rate: 45\n"
                             "    points: [{name: p, offset: [0.3, 0, 0]}]\n"
                             "    pose: {position: [0, 1, 0]}\n"
                             "    track:\n"
                             "      interpolation: linear\n"
                             "      keyframes:\n"
                             "        - {t: 0.0, position: [0, 1, 0]}\n"
                             "        - {t: 0.19, position: [0, 1, 0]}\n"
                             "        - {t: 0.2, position: [0, 1, 0], rotation: [0, 120, 0]}\n";
  const double pi = 3.14159265358979323846, origin[3] = { 0, 1, 0 };
  mr_scene sc;
  mr_scene_error err;
  mr_scene_world sw;
  assert_int_equal(mr_scene_load_text("turn.yaml", text, sizeof text - 1, &sc, &err), MR_SCENE_OK);
  assert_int_equal(mr_scene_build(&sc, &sw, &err), MR_SCENE_OK);
  static point_path pp;
  memset(&pp, 0, sizeof pp);
  pp.id = sw.control_ids[0];
  mr_scene_world_free(&sw);
  mr_sim_def o = mr_default_sim_def();
  o.duration = 3.5;
  o.fps = 60;
  o.present = MR_PRESENT_LAND;
  o.on_frame = keep_point;
  o.user = &pp;
  mr_sim_result r;
  if (mr_sim_run(&sc, &o, &r, &err) != MR_SCENE_OK) fail_msg("%s", err.text);
  double top = 0.0;
  for (int i = 1; i < pp.n; i++) top = fmax(top, angle_at(origin, pp.xyz[i - 1], pp.xyz[i]));
  double reached = angle_at(origin, pp.xyz[0], pp.xyz[pp.n - 1]) * 180 / pi;
  print_message("%d frames: most turn in a frame %.6f° (allowance 0.75°), %.4f° reached\n", pp.n,
                top * 180 / pi, reached);
  assert_true(pp.n > 200);
  assert_true(top <= 0.75 * pi / 180 * (1 + 1e-9));
  assert_true(top > 0.7 * pi / 180);
  assert_true(fabs(reached - 120.0) < 1e-6);
  mr_scene_free(&sc);
}

/* Two new goals a glove gives at one frame time, 1 cm and then 0.6 m
 * away (no time between them, so no speed can be read off them): the
 * second is taken as a jump, not an infinite speed: the frame, limited
 * to 4 m/s², sets off in that very frame and arrives, its pose finite all
 * the way. */
static void two_goals_at_one_time_are_a_jump_not_a_speed(void **state) {
  (void)state;
  static const char text[] = ONE_POINT "    max_accel: 4\n";
  mr_scene sc;
  mr_scene_error err;
  mr_scene_world sw;
  assert_int_equal(mr_scene_load_text("twice.yaml", text, sizeof text - 1, &sc, &err), MR_SCENE_OK);
  assert_int_equal(mr_scene_build(&sc, &sw, &err), MR_SCENE_OK);
  const double still[3] = { 0, 0, 0 }, here[3] = { 0, 1, 0 }, near[3] = { 0.01, 1, 0 };
  const double there[3] = { 0.6, 1, 0 };
  const mr_pose a = mr_pose_from_euler_deg(here, still), a2 = mr_pose_from_euler_deg(near, still);
  const mr_pose b = mr_pose_from_euler_deg(there, still);
  mr_glove_follow follow;
  memset(&follow, 0, sizeof follow);
  mr_pose now;
  for (int f = 1; f <= 180; f++) {
    double t = f / 60.0;
    if (f == 10) mr_theater_follow_glove(&sc, &sw, 0, &follow, a2, t); /* then b, at once */
    mr_theater_follow_glove(&sc, &sw, 0, &follow, f < 10 ? a : b, t);
    assert_true(mr_world_step_to(sw.world, t, NULL) >= 0);
    assert_int_equal(mr_world_frame_pose(sw.world, sw.frames[0], &now), MR_OK);
    if (f == 10 && !(now.position[0] > 1e-4))
      fail_msg("the frame of the jump moved %.3g m towards the goal", now.position[0]);
    if (!mr_pose_is_finite(&now)) fail_msg("frame %d: the pose is not finite", f);
  }
  print_message("end %.6f %.6f %.6f\n", now.position[0], now.position[1], now.position[2]);
  assert_true(fabs(now.position[0] - 0.6) < 1e-3);
  mr_scene_world_free(&sw);
  mr_scene_free(&sc);
}

/* The speed of a glove's goal is read off goals that come within 40 ms of
 * each other: 3 cm in 30 ms is one motion at 1 m/s; 4.5 cm in 45 ms (a
 * stall between samples) is not, and its speed is taken as unknown, 0. */
static void a_goal_speed_is_read_only_across_a_short_gap(void **state) {
  (void)state;
  static const char text[] = ONE_POINT;
  static const struct { double gap, speed; } cases[] = { { 0.03, 1.0 }, { 0.045, 0.0 } };
  const double still[3] = { 0, 0, 0 };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    mr_scene sc;
    mr_scene_error err;
    mr_scene_world sw;
    assert_int_equal(mr_scene_load_text("gap.yaml", text, sizeof text - 1, &sc, &err), MR_SCENE_OK);
    assert_int_equal(mr_scene_build(&sc, &sw, &err), MR_SCENE_OK);
    mr_glove_follow follow;
    memset(&follow, 0, sizeof follow);
    const double here[3] = { 0, 1, 0 }, there[3] = { cases[i].gap, 1, 0 };
    mr_theater_follow_glove(&sc, &sw, 0, &follow, mr_pose_from_euler_deg(here, still), 0.1);
    mr_theater_follow_glove(&sc, &sw, 0, &follow, mr_pose_from_euler_deg(there, still),
                            0.1 + cases[i].gap);
    if (!(fabs(follow.u[0] - cases[i].speed) < 1e-9))
      fail_msg("goals %.3f s apart: speed %.9f m/s, expected %.1f", cases[i].gap, follow.u[0],
               cases[i].speed);
    mr_scene_world_free(&sw);
    mr_scene_free(&sc);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(frame_keeps_its_speed_and_turn_limits_on_a_curved_path),
    cmocka_unit_test(glove_frame_keeps_its_acceleration_limits),
    cmocka_unit_test(glove_motion_within_the_limits_passes_unchanged),
    cmocka_unit_test(a_track_frame_follows_its_track_to_fourth_order),
    cmocka_unit_test(a_track_frame_keeps_the_limits_where_its_track_jumps),
    cmocka_unit_test(a_track_frame_does_not_jump_at_the_worlds_own_time),
    cmocka_unit_test(marionette_sim_keeps_a_track_frame_within_its_max_turn_rate),
    cmocka_unit_test(two_goals_at_one_time_are_a_jump_not_a_speed),
    cmocka_unit_test(a_goal_speed_is_read_only_across_a_short_gap),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
