/* Control frames (§6.1, §6.2): the frame's particles are moved kinematically
 * to the pose the glove gives. Between the time a target is set (t0) and
 * the time it is due (t1) the pose is interpolated, so the particles move
 * continuously and carry a velocity; every integrator stage places them at
 * its own time. */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

mr_pose mr_pose_identity(void)
{
  mr_pose p;
  memset(&p, 0, sizeof p);
  p.orientation[0] = 1.0;
  return p;
}

mr_frame_def mr_default_frame_def(void)
{
  mr_frame_def d;
  d.pose = mr_pose_identity();
  return d;
}

/* v' = q v q*, expanded: v + 2w (u × v) + 2 u × (u × v), u = (x, y, z). */
void mr_quat_rotate(const double q[4], const double v[3], double out[3])
{
  const double *u = &q[1];
  double t[3] = {2 * (u[1] * v[2] - u[2] * v[1]), 2 * (u[2] * v[0] - u[0] * v[2]),
                 2 * (u[0] * v[1] - u[1] * v[0])};
  double r[3] = {v[0] + q[0] * t[0] + (u[1] * t[2] - u[2] * t[1]),
                 v[1] + q[0] * t[1] + (u[2] * t[0] - u[0] * t[2]),
                 v[2] + q[0] * t[2] + (u[0] * t[1] - u[1] * t[0])};
  out[0] = r[0];
  out[1] = r[1];
  out[2] = r[2];
}

static int pose_check(mr_world *w, const mr_pose *p, const char *what, mr_pose *out)
{
  double q2 = 0;
  for (int k = 0; k < 4; k++)
    q2 += p->orientation[k] * p->orientation[k];
  if (!mr_finite3(p->position) || !isfinite(q2))
    return mr_fail(w, MR_ERR_NONFINITE, "%s: pose has NaN or Inf", what);
  if (!(q2 > 1e-12))
    return mr_fail(w, MR_ERR_DEGENERATE, "%s: orientation quaternion is zero", what);
  *out = *p;
  double s = 1.0 / sqrt(q2);
  for (int k = 0; k < 4; k++)
    out->orientation[k] *= s;
  return MR_OK;
}

void mr_frame_eval(const mr_frame *fr, double t, double pos[3], double q[4], double vel[3],
                   double omega[3])
{
  double span = fr->t1 - fr->t0;
  double s = span > 0 ? (t - fr->t0) / span : 1.0;
  int moving = span > 0 && s > 0 && s < 1;
  if (s <= 0)
    s = 0;
  if (s >= 1)
    s = 1;
  const double *q0 = fr->from.orientation;
  double q1[4];
  memcpy(q1, fr->to.orientation, sizeof q1);
  double dot = q0[0] * q1[0] + q0[1] * q1[1] + q0[2] * q1[2] + q0[3] * q1[3];
  if (dot < 0) { /* the short way round */
    for (int k = 0; k < 4; k++)
      q1[k] = -q1[k];
    dot = -dot;
  }
  if (dot > 1)
    dot = 1;
  double theta = acos(dot); /* half the rotation angle between the poses */
  double a, b;
  if (theta < 1e-9) {
    a = 1 - s;
    b = s;
  } else {
    a = sin((1 - s) * theta) / sin(theta);
    b = sin(s * theta) / sin(theta);
  }
  double n2 = 0;
  for (int k = 0; k < 4; k++) {
    q[k] = a * q0[k] + b * q1[k];
    n2 += q[k] * q[k];
  }
  for (int k = 0; k < 4; k++)
    q[k] /= sqrt(n2);
  for (int k = 0; k < 3; k++) {
    pos[k] = (1 - s) * fr->from.position[k] + s * fr->to.position[k];
    vel[k] = moving ? (fr->to.position[k] - fr->from.position[k]) / span : 0.0;
    omega[k] = 0.0;
  }
  if (moving && theta >= 1e-9) {
    /* Slerp turns at a constant rate 2θ/span about the axis of q1 q0*. */
    double r[4] = {q1[0] * q0[0] + q1[1] * q0[1] + q1[2] * q0[2] + q1[3] * q0[3],
                   -q1[0] * q0[1] + q1[1] * q0[0] - q1[2] * q0[3] + q1[3] * q0[2],
                   -q1[0] * q0[2] + q1[1] * q0[3] + q1[2] * q0[0] - q1[3] * q0[1],
                   -q1[0] * q0[3] - q1[1] * q0[2] + q1[2] * q0[1] + q1[3] * q0[0]};
    double vn = sqrt(r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
    if (vn > 0)
      for (int k = 0; k < 3; k++)
        omega[k] = r[k + 1] / vn * (2 * theta / span);
  }
}

void mr_frames_place(mr_world *w, double t, double *x, double *v)
{
  if (!w->has_frames)
    return;
  w->pass_calls[MR_PASS_FRAMES]++;
  /* Each frame's pose once, then its particles. */
  for (int f = 0; f < w->nf; f++) {
    double *st = &w->frame_state[13 * f];
    mr_frame_eval(&w->frames[f], t, st, st + 3, st + 7, st + 10);
  }
  for (int j = 0; j < w->nkin; j++) {
    int i = w->kin[j];
    const double *st = &w->frame_state[13 * w->frame[i]];
    const double *p = st, *qq = st + 3, *fv = st + 7, *fo = st + 10;
    double r[3];
    mr_quat_rotate(qq, &w->local[3 * i], r);
    for (int k = 0; k < 3; k++)
      x[3 * i + k] = p[k] + r[k];
    v[3 * i + 0] = fv[0] + fo[1] * r[2] - fo[2] * r[1];
    v[3 * i + 1] = fv[1] + fo[2] * r[0] - fo[0] * r[2];
    v[3 * i + 2] = fv[2] + fo[0] * r[1] - fo[1] * r[0];
  }
}

mr_status mr_world_add_frame(mr_world *w, const mr_frame_def *def, int *out_id)
{
  if (!w || !def)
    return mr_fail(w, MR_ERR_ARG, "mr_world_add_frame: NULL argument");
  if (mr_require(w, MR_EFFECT_FRAMES, "mr_world_add_frame") != 0)
    return MR_ERR_NOT_DECLARED;
  mr_pose p;
  mr_status s = pose_check(w, &def->pose, "mr_world_add_frame", &p);
  if (s != MR_OK)
    return s;
  if (MR_GROW(w, w->frames, w->nf, w->cap_f) != 0)
    return mr_fail(w, MR_ERR_NOMEM, "mr_world_add_frame: out of memory");
  if (w->cap_fs < w->cap_f) {
    double *fs = realloc(w->frame_state, (size_t)w->cap_f * 13 * sizeof *fs);
    if (!fs)
      return mr_fail(w, MR_ERR_NOMEM, "mr_world_add_frame: out of memory");
    w->frame_state = fs;
    w->cap_fs = w->cap_f;
  }
  mr_frame *fr = &w->frames[w->nf];
  fr->from = fr->to = p;
  fr->t0 = fr->t1 = w->t;
  if (out_id)
    *out_id = w->nf;
  w->nf++;
  return MR_OK;
}

mr_status mr_world_set_frame_target(mr_world *w, int frame, const mr_pose *pose, double t)
{
  if (!w || !pose)
    return mr_fail(w, MR_ERR_ARG, "mr_world_set_frame_target: NULL argument");
  if (frame < 0 || frame >= w->nf)
    return mr_fail(w, MR_ERR_ID, "mr_world_set_frame_target: frame %d does not exist", frame);
  if (!isfinite(t))
    return mr_fail(w, MR_ERR_NONFINITE, "mr_world_set_frame_target: time is NaN or Inf");
  mr_pose p;
  mr_status s = pose_check(w, pose, "mr_world_set_frame_target", &p);
  if (s != MR_OK)
    return s;
  mr_frame *fr = &w->frames[frame];
  double vel[3], om[3];
  mr_pose now;
  mr_frame_eval(fr, w->t, now.position, now.orientation, vel, om);
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

mr_status mr_world_frame_pose(const mr_world *w, int frame, mr_pose *out)
{
  if (!w || !out)
    return MR_ERR_ARG;
  if (frame < 0 || frame >= w->nf)
    return MR_ERR_ID;
  double vel[3], om[3];
  mr_frame_eval(&w->frames[frame], w->t, out->position, out->orientation, vel, om);
  return MR_OK;
}
