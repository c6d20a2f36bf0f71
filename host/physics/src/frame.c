/* Control frames (§6.1, §6.2): the frame's particles are moved kinematically
 * to the pose the glove gives. Between the time a target is set (t0) and
 * the time it is due (t1) the pose is interpolated, so the particles move
 * continuously and carry a velocity; every integrator stage places them at
 * its own time. */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

mr_frame_def mr_default_frame_def(void) {
  mr_frame_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  d.pose = mr_pose_identity();
  return d;
}

static mr_status pose_check(mr_world *w, const mr_pose *p, const char *what, mr_pose *out) {
  *out = *p;
  if (mr_pose_normalize(out) == 0) return MR_OK;
  if (!mr_finite3(p->position) || !mr_finite3(p->orientation) || !isfinite(p->orientation[3]))
    return mr_fail(w, MR_ERR_NONFINITE, "%s: pose has NaN or Inf", what);
  return mr_fail(w, MR_ERR_DEGENERATE, "%s: orientation quaternion is zero", what);
}

/* The frame's velocity and angular velocity at t: those of the
 * interpolation from `from` at t0 to `to` at t1 inside it, 0 outside.
 * `ends` counts t0 and t1 as inside (a taut string's frame end, whose
 * step from t0 to t1 moves with the segment at both of its ends). */
void mr_frame_rates(const mr_frame *fr, double t, int ends, double vel[3], double omega[3]) {
  double span = fr->t1 - fr->t0;
  double s = span > 0 ? (t - fr->t0) / span : 1.0;
  int moving = span > 0 && (ends ? s >= 0 && s <= 1 : s > 0 && s < 1);
  for (int k = 0; k < 3; k++) {
    vel[k] = moving ? (fr->to.position[k] - fr->from.position[k]) / span : 0.0;
    omega[k] = 0.0;
  }
  if (moving) {
    /* Slerp turns at a constant rate about one axis. */
    double axis[3];
    double angle = mr_pose_turn(fr->from.orientation, fr->to.orientation, axis);
    if (angle > 0)
      for (int k = 0; k < 3; k++) omega[k] = axis[k] * (angle / span);
  }
}

/* The frame's pose at t, and its velocity and angular velocity: the
 * interpolation from `from` at t0 to `to` at t1, held outside [t0, t1]. */
void mr_frame_eval(const mr_frame *fr, double t, mr_pose *pose, double vel[3], double omega[3]) {
  double span = fr->t1 - fr->t0;
  double s = span > 0 ? (t - fr->t0) / span : 1.0;
  if (s <= 0) s = 0;
  if (s >= 1) s = 1;
  *pose = mr_pose_interpolate(&fr->from, &fr->to, s);
  mr_frame_rates(fr, t, 0, vel, omega);
}

/* Frame f's pose and rates at t into its 13 entries of frame_state. */
static void frame_state_at(mr_world *w, int f, double t) {
  double *st = &w->frame_state[13 * f];
  mr_pose pose;
  mr_frame_eval(&MR_AT(w->frames, mr_frame, f), t, &pose, st + 7, st + 10);
  memcpy(st, pose.position, 3 * sizeof *st);
  memcpy(st + 3, pose.orientation, 4 * sizeof *st);
}

/* Particle i carried by its frame, from the frame's state: x = p + R l,
 * v = v_f + ω × R l. */
static void carried(const mr_world *w, int i, double *x, double *v) {
  const double *st = &w->frame_state[13 * w->frame[i]];
  const double *p = st, *qq = st + 3, *fv = st + 7, *fo = st + 10;
  double r[3];
  mr_pose_rotate(qq, &w->local[3 * i], r);
  for (int k = 0; k < 3; k++) x[3 * i + k] = p[k] + r[k];
  v[3 * i + 0] = fv[0] + fo[1] * r[2] - fo[2] * r[1];
  v[3 * i + 1] = fv[1] + fo[2] * r[0] - fo[0] * r[2];
  v[3 * i + 2] = fv[2] + fo[0] * r[1] - fo[1] * r[0];
}

void mr_frames_place(mr_world *w, double t, double *x, double *v) {
  if (!w->has_frames) return;
  w->pass_calls[MR_PASS_FRAMES]++;
  /* Each frame's pose once, then its particles. */
  for (int f = 0; f < w->frames.n; f++) frame_state_at(w, f, t);
  for (int j = 0; j < w->kin.n; j++) carried(w, MR_AT(w->kin, int, j), x, v);
}

/* A control point just added is placed alone, with its own frame's state:
 * placing every frame's points again for each one added made building a
 * crowd of n puppets O(n²) (0.41 s for 1 000 stick puppets, 0.005 s now).
 * Counted as the frames pass it stands for. */
void mr_frame_place_one(mr_world *w, int i) {
  w->pass_calls[MR_PASS_FRAMES]++;
  frame_state_at(w, w->frame[i], w->t);
  carried(w, i, w->x, w->v);
}

mr_status mr_world_add_frame(mr_world *w, const mr_frame_def *def, int *out_id) {
  const char *what = "mr_world_add_frame";
  mr_status s = MR_ADD_CHECK(w, def, MR_EFFECT_FRAMES, what);
  mr_frame fr;
  if (s == MR_OK) s = pose_check(w, &def->pose, what, &fr.from);
  if (s != MR_OK) return s;
  int cap = w->frames.cap;
  if (mr_grow((void **)&w->frame_state, &cap, w->frames.n + 1, 13 * sizeof(double)) != 0)
    return mr_fail(w, MR_ERR_NOMEM, "%s: out of memory", what);
  fr.to = fr.from;
  fr.t0 = fr.t1 = w->t;
  return mr_add_push(w, &w->frames, &fr, sizeof fr, out_id, what);
}

mr_status mr_world_set_frame_target(mr_world *w, int frame, const mr_pose *pose, double t) {
  if (!w || !pose) return mr_fail(w, MR_ERR_ARG, "mr_world_set_frame_target: NULL argument");
  if (frame < 0 || frame >= w->frames.n)
    return mr_fail(w, MR_ERR_ID, "mr_world_set_frame_target: frame %d does not exist", frame);
  if (!isfinite(t))
    return mr_fail(w, MR_ERR_NONFINITE, "mr_world_set_frame_target: time is NaN or Inf");
  mr_pose p;
  mr_status s = pose_check(w, pose, "mr_world_set_frame_target", &p);
  if (s != MR_OK) return s;
  mr_frame *fr = &MR_AT(w->frames, mr_frame, frame);
  double vel[3], om[3];
  mr_pose now;
  mr_frame_eval(fr, w->t, &now, vel, om);
  fr->from = now;
  fr->to = p;
  fr->t0 = w->t;
  fr->t1 = t > w->t ? t : w->t;
  if (t <= w->t) {
    /* §6.1 method 1: placed at once. */
    fr->from = p;
    mr_frames_place(w, w->t, w->x, w->v);
  }
  return MR_OK;
}

mr_status mr_world_frame_pose(const mr_world *w, int frame, mr_pose *out) {
  if (!w || !out) return MR_ERR_ARG;
  if (frame < 0 || frame >= w->frames.n) return MR_ERR_ID;
  double vel[3], om[3];
  mr_frame_eval(&MR_AT(w->frames, mr_frame, frame), w->t, out, vel, om);
  return MR_OK;
}
