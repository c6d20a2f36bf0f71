#include "theater_internal.h"

#include <math.h>
#include <string.h>

/* Halvings of the goal's share when the path to it would pass a limit:
 * 2⁻²⁰ of the way is closer than the motion can show. */
#define LIMIT_HALVINGS 20

/* Whether the path the physics would make to `goal` by t keeps the
 * frame's speed and turn-rate limits (its bounds, which no point of the
 * path exceeds). */
static int within(const mr_scene_world *sw, size_t k, const mr_scene_frame *f, const mr_pose *goal,
                  double t) {
  double speed, turn;
  if (mr_world_frame_target_peak(sw->world, sw->frames[k], goal, t, &speed, &turn) != MR_OK)
    return 1;
  return speed <= f->max_speed && turn <= f->max_turn;
}

typedef int (*keeps_fn)(const mr_scene_world *sw, size_t k, const mr_scene_frame *f,
                        const mr_pose *goal, double t);

/* The goal drawn back towards `from` by halvings, as far as the path to it
 * keeps the limits `keeps` tests (goal itself does not). */
static mr_pose draw_back(const mr_scene_world *sw, size_t k, const mr_scene_frame *f,
                         const mr_pose *from, const mr_pose *goal, double t, keeps_fn keeps) {
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < LIMIT_HALVINGS; i++) {
    double mid = 0.5 * (lo + hi);
    mr_pose g = mr_pose_interpolate(from, goal, mid);
    if (keeps(sw, k, f, &g, t))
      lo = mid;
    else
      hi = mid;
  }
  return mr_pose_interpolate(from, goal, lo);
}

/* The approach rule (mr_pose_approach) keeps the chord from `now` to the
 * goal within the limits; the path the physics makes is curved (its
 * velocity is continuous across targets), and may pass them on the way,
 * so the goal is drawn back towards `now` until the path keeps them. */
void mr_theater_head_frame(const mr_scene *s, mr_scene_world *sw, size_t k, mr_pose goal,
                           double t) {
  if (k >= sw->n_frames || k >= s->n_frames) return;
  const mr_scene_frame *f = &s->frames[k];
  mr_pose now;
  double dt = fmax(t - mr_world_time(sw->world), 0.0);
  if (mr_world_frame_pose(sw->world, sw->frames[k], &now) == MR_OK) {
    goal = mr_pose_approach(&now, &goal, f->max_speed * dt, f->max_turn * dt);
    if (dt > 0 && !within(sw, k, f, &goal, t)) goal = draw_back(sw, k, f, &now, &goal, t, within);
  }
  mr_world_set_frame_target(sw->world, sw->frames[k], &goal, t);
}

static int within_rates(const mr_scene_world *sw, size_t k, const mr_scene_frame *f,
                        const mr_pose *goal, const double vel[3], const double omega[3], double t) {
  double speed, turn;
  if (mr_world_frame_target_rates_peak(sw->world, sw->frames[k], goal, vel, omega, t, &speed,
                                       &turn) != MR_OK)
    return 0;
  return speed <= f->max_speed && turn <= f->max_turn;
}

/* The path's bound passes the chord's rate (a mean of its velocity's
 * control points), so a path within the limits needs no approach. */
void mr_theater_track_frame(const mr_scene *s, mr_scene_world *sw, size_t k, double t) {
  if (k >= sw->n_frames || k >= s->n_frames) return;
  mr_pose goal;
  double vel[3], omega[3];
  mr_scene_frame_pose_at(s, k, t, &goal);
  mr_scene_frame_rates_at(s, k, t, vel, omega);
  if (t > mr_world_time(sw->world) && within_rates(sw, k, &s->frames[k], &goal, vel, omega, t) &&
      mr_world_set_frame_target_rates(sw->world, sw->frames[k], &goal, vel, omega, t) == MR_OK)
    return;
  mr_theater_head_frame(s, sw, k, goal, t);
}

/* ------------------------------------------------------- a glove's limits */

static double norm(const double v[3]) {
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* The unit quaternion of the turn by rotation vector r (world axes). */
static void turn_quat(const double r[3], double q[4]) {
  double a = norm(r), c = 1.0, s = 0.5;
  if (a > 1e-12) {
    c = mr_cos(0.5 * a);
    s = mr_sin(0.5 * a) / a;
  }
  q[0] = c;
  for (int i = 0; i < 3; i++) q[i + 1] = s * r[i];
}

/* One rate (a velocity or an angular velocity, v0 now) over dt, for a
 * goal moving at u that coasting at v0 would miss by e at the step's end:
 * the rate it heads for is u, plus as fast towards the goal as lets it
 * still stop there braking at half of `accel` (√(a |e|): the curve's
 * bends, which draw the goal back, may spend the other half), that part
 * closing the miss over three steps rather than one (the goals a glove
 * gives jitter from frame to frame, and closing each at once would shake
 * the bar), the whole never past max; the change is at most accel·dt. Tracking a goal that moves steadily, e is 0 and the
 * rate u. The mean of the rates over dt, which moves it, into mean. */
static void limited_rate(const double v0[3], const double e[3], const double u[3], double max,
                         double accel, double dt, double mean[3]) {
  double dist = norm(e), toward = fmin(sqrt(accel * dist), dist / dt), want[3], dv[3];
  for (int i = 0; i < 3; i++) want[i] = u[i] + (dist > 0 ? e[i] / dist * toward : 0.0);
  double wn = norm(want);
  for (int i = 0; i < 3; i++) dv[i] = (wn > max ? want[i] * max / wn : want[i]) - v0[i];
  double n = norm(dv), cap = accel * dt;
  double s = n > cap ? cap / n : 1.0;
  for (int i = 0; i < 3; i++) mean[i] = v0[i] + 0.5 * s * dv[i];
}

/* The pose now moved on by the rates (v, w) over dt. */
static mr_pose moved(const mr_pose *now, const double v[3], const double w[3], double dt) {
  mr_pose o = *now;
  double r[3], q[4];
  for (int i = 0; i < 3; i++) {
    o.position[i] += v[i] * dt;
    r[i] = w[i] * dt;
  }
  turn_quat(r, q);
  mr_pose_quat_multiply(q, now->orientation, o.orientation);
  return o;
}

/* Two goals further apart than this in time are not one motion: the
 * glove stalled between them (a loose plug, a lost radio link), or the
 * hand held still, and the way between is a jump, not a speed. A glove's
 * goals come every frame while it streams. */
#define GOAL_GAP 0.04

/* How fast the goal moves (u, uw turning), from goals that follow one
 * another within GOAL_GAP (limited_rate caps it with the rest, and its
 * change with the acceleration); nothing is known of a goal that
 * is the first or follows a gap. A goal unchanged since the last keeps the
 * rate until GOAL_GAP has passed (the samples come unevenly against the
 * frames), then the rate is 0: a quiet glove's frame holds its pose. */
static void goal_rates(mr_glove_follow *fl, const mr_pose *goal, double t, double u[3],
                       double uw[3]) {
  double axis[3], span = t - fl->t;
  int fresh = !fl->seen || memcmp(goal, &fl->goal, sizeof *goal) != 0;
  if (fresh && !(fl->seen && span > 0 && span <= GOAL_GAP)) {
    memset(fl->u, 0, sizeof fl->u);
    memset(fl->uw, 0, sizeof fl->uw);
  } else if (fresh) {
    double angle = mr_pose_turn(fl->goal.orientation, goal->orientation, axis);
    for (int i = 0; i < 3; i++) {
      fl->u[i] = (goal->position[i] - fl->goal.position[i]) / span;
      fl->uw[i] = axis[i] * angle / span;
    }
  }
  if (fresh) {
    fl->goal = *goal;
    fl->t = t;
    fl->seen = 1;
  }
  int moving = t - fl->t <= GOAL_GAP;
  for (int i = 0; i < 3; i++) {
    u[i] = moving ? fl->u[i] : 0.0;
    uw[i] = moving ? fl->uw[i] : 0.0;
  }
}

static int accel_within(const mr_scene_world *sw, size_t k, const mr_scene_frame *f,
                        const mr_pose *goal, double t) {
  double a, turn;
  if (mr_world_frame_target_accel(sw->world, sw->frames[k], goal, t, &a, &turn) != MR_OK) return 1;
  return a <= f->max_accel * (1 + 1e-9) && turn <= f->max_turn_accel * (1 + 1e-9);
}

/* A glove's pose is where the hand is, and it may jump: the frame heads
 * there changing its velocity by at most max_accel (and its turn rate by
 * max_turn_accel) a second. The curve the physics lays through the goals
 * bends more where the acceleration changes, so the goal is then drawn
 * back towards where the frame would coast, until the curve keeps them. */
void mr_theater_follow_glove(const mr_scene *s, mr_scene_world *sw, size_t k,
                             mr_glove_follow *follow, mr_pose goal, double t) {
  if (k >= sw->n_frames || k >= s->n_frames) return;
  const mr_scene_frame *f = &s->frames[k];
  double dt = t - mr_world_time(sw->world), v[3], w[3], axis[3], d[3], r[3], vm[3], wm[3];
  double u[3], uw[3];
  goal_rates(follow, &goal, t, u, uw);
  mr_pose now;
  if (dt > 0 && mr_world_frame_pose(sw->world, sw->frames[k], &now) == MR_OK &&
      mr_world_frame_rates(sw->world, sw->frames[k], v, w) == MR_OK) {
    mr_pose coast = moved(&now, v, w, dt);
    if (accel_within(sw, k, f, &goal, t)) { /* within the limits: unchanged */
      mr_theater_head_frame(s, sw, k, goal, t);
      return;
    }
    double angle = mr_pose_turn(coast.orientation, goal.orientation, axis);
    for (int i = 0; i < 3; i++) {
      d[i] = goal.position[i] - coast.position[i];
      r[i] = axis[i] * angle;
    }
    limited_rate(v, d, u, f->max_speed, f->max_accel, dt, vm);
    limited_rate(w, r, uw, f->max_turn, f->max_turn_accel, dt, wm);
    goal = moved(&now, vm, wm, dt);
    if (!accel_within(sw, k, f, &goal, t))
      goal = draw_back(sw, k, f, &coast, &goal, t, accel_within);
  }
  mr_theater_head_frame(s, sw, k, goal, t);
}
