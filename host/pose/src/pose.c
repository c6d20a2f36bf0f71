/* Quaternion arithmetic for mr_pose. Every operation here is also in the
 * physics' step (the control frames), so each is written to give the same
 * bits on every run: no fused tricks, one fixed order of operations. */
#include "mr_pose.h"

#include <math.h>
#include <string.h>

mr_pose mr_pose_identity(void) {
  mr_pose p;
  memset(&p, 0, sizeof p);
  p.orientation[0] = 1.0;
  return p;
}

int mr_pose_normalize(mr_pose *p) {
  double q2 = 0;
  for (int k = 0; k < 4; k++) q2 += p->orientation[k] * p->orientation[k];
  if (!isfinite(p->position[0]) || !isfinite(p->position[1]) || !isfinite(p->position[2]) ||
      !isfinite(q2) || !(q2 > 1e-12))
    return -1;
  double s = 1.0 / sqrt(q2);
  for (int k = 0; k < 4; k++) p->orientation[k] *= s;
  return 0;
}

/* q v q*, expanded: v + 2w (u × v) + 2 u × (u × v), u = (x, y, z). */
void mr_pose_rotate(const double q[4], const double v[3], double out[3]) {
  const double *u = &q[1];
  double t[3] = { 2 * (u[1] * v[2] - u[2] * v[1]), 2 * (u[2] * v[0] - u[0] * v[2]),
                  2 * (u[0] * v[1] - u[1] * v[0]) };
  double r[3] = { v[0] + q[0] * t[0] + (u[1] * t[2] - u[2] * t[1]),
                  v[1] + q[0] * t[1] + (u[2] * t[0] - u[0] * t[2]),
                  v[2] + q[0] * t[2] + (u[0] * t[1] - u[1] * t[0]) };
  out[0] = r[0];
  out[1] = r[1];
  out[2] = r[2];
}

void mr_pose_unrotate(const double q[4], const double v[3], double out[3]) {
  const double qc[4] = { q[0], -q[1], -q[2], -q[3] };
  mr_pose_rotate(qc, v, out);
}

void mr_pose_apply(const mr_pose *p, const double local[3], double world[3]) {
  double r[3];
  mr_pose_rotate(p->orientation, local, r);
  for (int k = 0; k < 3; k++) world[k] = p->position[k] + r[k];
}

void mr_pose_quat_multiply(const double a[4], const double b[4], double out[4]) {
  double r[4] = { a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
                  a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
                  a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
                  a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0] };
  memcpy(out, r, sizeof r);
}

mr_pose mr_pose_compose(const mr_pose *a, const mr_pose *b) {
  mr_pose o;
  mr_pose_apply(a, b->position, o.position);
  mr_pose_quat_multiply(a->orientation, b->orientation, o.orientation);
  return o;
}

/* q1, turned to the same hemisphere as q0, and the half angle θ between
 * them (cos θ = q0·q1). */
static double short_way(const double q0[4], const double q1_in[4], double q1[4]) {
  memcpy(q1, q1_in, 4 * sizeof *q1);
  double dot = q0[0] * q1[0] + q0[1] * q1[1] + q0[2] * q1[2] + q0[3] * q1[3];
  if (dot < 0) {
    for (int k = 0; k < 4; k++) q1[k] = -q1[k];
    dot = -dot;
  }
  if (dot > 1) dot = 1;
  return mr_acos(dot);
}

/* slerp(q0, q1; s) = (sin((1−s)θ) q0 + sin(sθ) q1) / sin θ, renormalised so
 * rounding cannot drift it off the unit sphere; near θ = 0 the sines vanish
 * and the linear blend is the limit. */
mr_pose mr_pose_interpolate(const mr_pose *from, const mr_pose *to, double s) {
  mr_pose o;
  const double *q0 = from->orientation;
  double q1[4];
  double theta = short_way(q0, to->orientation, q1);
  double a, b;
  if (theta < 1e-9) {
    a = 1 - s;
    b = s;
  } else {
    a = mr_sin((1 - s) * theta) / mr_sin(theta);
    b = mr_sin(s * theta) / mr_sin(theta);
  }
  double n2 = 0;
  for (int k = 0; k < 4; k++) {
    o.orientation[k] = a * q0[k] + b * q1[k];
    n2 += o.orientation[k] * o.orientation[k];
  }
  for (int k = 0; k < 4; k++) o.orientation[k] /= sqrt(n2);
  for (int k = 0; k < 3; k++) o.position[k] = (1 - s) * from->position[k] + s * to->position[k];
  return o;
}

int mr_pose_is_finite(const mr_pose *p) {
  for (int k = 0; k < 3; k++)
    if (!isfinite(p->position[k])) return 0;
  for (int k = 0; k < 4; k++)
    if (!isfinite(p->orientation[k])) return 0;
  return 1;
}

mr_pose mr_pose_approach(const mr_pose *from, const mr_pose *to, double max_move, double max_turn) {
  if (!mr_pose_is_finite(to)) return *from;
  double d[3], dist = 0, axis[3];
  for (int k = 0; k < 3; k++) {
    d[k] = to->position[k] - from->position[k];
    dist += d[k] * d[k];
  }
  dist = sqrt(dist);
  double angle = mr_pose_turn(from->orientation, to->orientation, axis);
  double sp = dist <= max_move ? 1.0 : fmax(max_move, 0.0) / dist;
  double sq = angle <= max_turn ? 1.0 : fmax(max_turn, 0.0) / angle;
  /* Within its allowance a part is the goal's own, to the bit. */
  mr_pose o = sq < 1.0 ? mr_pose_interpolate(from, to, sq) : *to;
  if (sp < 1.0)
    for (int k = 0; k < 3; k++) o.position[k] = from->position[k] + sp * d[k];
  return o;
}

/* The turn is r = q1 q0*: its vector part is the axis times sin θ, and the
 * rotation angle is twice the half angle θ. */
double mr_pose_turn(const double q0[4], const double q1_in[4], double axis[3]) {
  double q1[4];
  double theta = short_way(q0, q1_in, q1);
  axis[0] = axis[1] = axis[2] = 0.0;
  if (theta < 1e-9) return 0.0;
  double r[3] = { -q1[0] * q0[1] + q1[1] * q0[0] - q1[2] * q0[3] + q1[3] * q0[2],
                  -q1[0] * q0[2] + q1[1] * q0[3] + q1[2] * q0[0] - q1[3] * q0[1],
                  -q1[0] * q0[3] - q1[1] * q0[2] + q1[2] * q0[1] + q1[3] * q0[0] };
  double vn = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  if (vn > 0)
    for (int k = 0; k < 3; k++) axis[k] = r[k] / vn;
  return 2 * theta;
}

/* Half angles h = angle/2 of the three turns, q = qz qy qx multiplied out. */
mr_pose mr_pose_from_euler_deg(const double position[3], const double rotation_deg[3]) {
  static const double pi = 3.14159265358979323846;
  mr_pose o;
  memcpy(o.position, position, sizeof o.position);
  double hx = rotation_deg[0] * pi / 360.0;
  double hy = rotation_deg[1] * pi / 360.0;
  double hz = rotation_deg[2] * pi / 360.0;
  double cx = mr_cos(hx), sx = mr_sin(hx), cy = mr_cos(hy), sy = mr_sin(hy), cz = mr_cos(hz),
         sz = mr_sin(hz);
  o.orientation[0] = cz * cy * cx + sz * sy * sx;
  o.orientation[1] = cz * cy * sx - sz * sy * cx;
  o.orientation[2] = cz * sy * cx + sz * cy * sx;
  o.orientation[3] = sz * cy * cx - cz * sy * sx;
  return o;
}
