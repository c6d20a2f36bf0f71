/* Time-dependent 3D curves for §6.1 method 3: c(t), ċ(t), c̈(t) from
 * keyframes (C¹ Catmull–Rom cubic, or a polyline) or from a callback. */
#include "internal.h"

#include <string.h>

/* Index i of the segment [times[i], times[i+1]) holding t. */
static int segment(const double *times, int n, double t) {
  int lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    int mid = (lo + hi) / 2;
    if (times[mid] <= t)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

/* Tangent at key i, dP/dt, from its neighbours. The first and last keys
 * get zero: the curve starts from rest and comes to rest, so holding the end
 * point afterwards asks for no jump in velocity, which a constraint can only
 * follow with a jolt. */
static void tangent(const mr_curve *c, int i, double m[3]) {
  if (i == 0 || i == c->key_count - 1) {
    m[0] = m[1] = m[2] = 0.0;
    return;
  }
  double dt = c->times[i + 1] - c->times[i - 1];
  for (int k = 0; k < 3; k++) m[k] = (c->points[3 * (i + 1) + k] - c->points[3 * (i - 1) + k]) / dt;
}

void mr_curve_eval(const mr_curve *c, double t, double pos[3], double vel[3], double acc[3]) {
  if (c->fn) {
    c->fn(c->user, t, pos, vel, acc);
    return;
  }
  int n = c->key_count;
  memset(vel, 0, 3 * sizeof(double));
  memset(acc, 0, 3 * sizeof(double));
  if (n == 1 || t <= c->times[0]) {
    memcpy(pos, c->points, 3 * sizeof(double));
    return;
  }
  if (t >= c->times[n - 1]) {
    memcpy(pos, &c->points[3 * (n - 1)], 3 * sizeof(double));
    return;
  }
  int i = segment(c->times, n, t);
  double h = c->times[i + 1] - c->times[i];
  double s = (t - c->times[i]) / h;
  const double *p0 = &c->points[3 * i], *p1 = &c->points[3 * (i + 1)];
  if (c->interp == MR_CURVE_LINEAR) {
    for (int k = 0; k < 3; k++) {
      pos[k] = p0[k] + s * (p1[k] - p0[k]);
      vel[k] = (p1[k] - p0[k]) / h;
    }
    return;
  }
  double m0[3], m1[3];
  tangent(c, i, m0);
  tangent(c, i + 1, m1);
  /* Cubic Hermite basis in s and its s-derivatives. */
  double s2 = s * s, s3 = s2 * s;
  double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  double d00 = 6 * s2 - 6 * s, d10 = 3 * s2 - 4 * s + 1, d01 = -6 * s2 + 6 * s,
         d11 = 3 * s2 - 2 * s;
  double e00 = 12 * s - 6, e10 = 6 * s - 4, e01 = -12 * s + 6, e11 = 6 * s - 2;
  for (int k = 0; k < 3; k++) {
    pos[k] = h00 * p0[k] + h10 * h * m0[k] + h01 * p1[k] + h11 * h * m1[k];
    vel[k] = (d00 * p0[k] + d10 * h * m0[k] + d01 * p1[k] + d11 * h * m1[k]) / h;
    acc[k] = (e00 * p0[k] + e10 * h * m0[k] + e01 * p1[k] + e11 * h * m1[k]) / (h * h);
  }
}
