/* The geometry of the display modes (§3.3). */
#include "stage_math.h"

#include <math.h>
#include <string.h>

bool mr_stage_finite3(const double v[3]) {
  return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double out[3]) {
  double c[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
  memcpy(out, c, sizeof c);
}

static void quat_normalise(double q[4]) {
  double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(n > 0)) {
    q[0] = 1;
    q[1] = q[2] = q[3] = 0;
    return;
  }
  for (int i = 0; i < 4; i++) q[i] /= n;
}

void mr_stage_quat_from_axes(const double x[3], const double y[3], const double z[3], double q[4]) {
  /* R's columns are x, y, z: R[i][j] is column j's component i. Shepperd's
   * method: divide by the largest of the four squared components. */
  double r00 = x[0], r11 = y[1], r22 = z[2];
  double t = r00 + r11 + r22;
  if (t > 0) {
    double s = 2 * sqrt(t + 1);
    q[0] = s / 4;
    q[1] = (y[2] - z[1]) / s;
    q[2] = (z[0] - x[2]) / s;
    q[3] = (x[1] - y[0]) / s;
  } else if (r00 > r11 && r00 > r22) {
    double s = 2 * sqrt(1 + r00 - r11 - r22);
    q[0] = (y[2] - z[1]) / s;
    q[1] = s / 4;
    q[2] = (y[0] + x[1]) / s;
    q[3] = (z[0] + x[2]) / s;
  } else if (r11 > r22) {
    double s = 2 * sqrt(1 + r11 - r00 - r22);
    q[0] = (z[0] - x[2]) / s;
    q[1] = (y[0] + x[1]) / s;
    q[2] = s / 4;
    q[3] = (z[1] + y[2]) / s;
  } else {
    double s = 2 * sqrt(1 + r22 - r00 - r11);
    q[0] = (x[1] - y[0]) / s;
    q[1] = (z[0] + x[2]) / s;
    q[2] = (z[1] + y[2]) / s;
    q[3] = s / 4;
  }
  quat_normalise(q);
}

int mr_stage_frame3(const double p0[3], const double p1[3], const double p2[3], mr_pose *out) {
  double x[3], w[3], y[3], z[3];
  for (int i = 0; i < 3; i++) {
    x[i] = p1[i] - p0[i];
    w[i] = p2[i] - p0[i];
  }
  double lx = sqrt(dot3(x, x)), lw = sqrt(dot3(w, w));
  if (!(lx > MR_STAGE_TINY_M) || !(lw > MR_STAGE_TINY_M)) return -1;
  for (int i = 0; i < 3; i++) x[i] /= lx;
  double along = dot3(w, x);
  for (int i = 0; i < 3; i++) y[i] = w[i] - along * x[i];
  double ly = sqrt(dot3(y, y));
  /* Collinear within a millionth of a radian: no plane, no frame. */
  if (!(ly > 1e-6 * lw)) return -1;
  for (int i = 0; i < 3; i++) y[i] /= ly;
  cross3(x, y, z);
  memcpy(out->position, p0, 3 * sizeof(double));
  mr_stage_quat_from_axes(x, y, z, out->orientation);
  return 0;
}

int mr_stage_quat_arc(const double from[3], const double to[3], double q[4]) {
  double la = sqrt(dot3(from, from)), lb = sqrt(dot3(to, to));
  if (!(la > MR_STAGE_TINY_M) || !(lb > MR_STAGE_TINY_M)) return -1;
  double a[3], b[3], c[3];
  for (int i = 0; i < 3; i++) {
    a[i] = from[i] / la;
    b[i] = to[i] / lb;
  }
  double d = dot3(a, b);
  if (d < -1 + 1e-12) {
    /* Half a turn about the axis of a's smallest component made normal. */
    double e[3] = { 0, 0, 0 };
    int k = fabs(a[0]) <= fabs(a[1]) && fabs(a[0]) <= fabs(a[2]) ? 0
            : fabs(a[1]) <= fabs(a[2])                           ? 1
                                                                 : 2;
    e[k] = 1;
    cross3(a, e, c);
    q[0] = 0;
    memcpy(q + 1, c, sizeof c);
    quat_normalise(q);
    return 0;
  }
  cross3(a, b, c);
  q[0] = 1 + d;
  memcpy(q + 1, c, sizeof c);
  quat_normalise(q);
  return 0;
}

/* One Jacobi rotation zeroing a[p][q] of the symmetric 4 x 4 matrix a,
 * carried into the eigenvectors' columns v. */
static void jacobi_rotate(double a[4][4], double v[4][4], int p, int q) {
  if (a[p][q] == 0) return;
  double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
  double t = (theta >= 0 ? 1 : -1) / (fabs(theta) + sqrt(theta * theta + 1));
  double c = 1 / sqrt(t * t + 1), s = t * c;
  for (int k = 0; k < 4; k++) {
    double akp = a[k][p], akq = a[k][q];
    a[k][p] = c * akp - s * akq;
    a[k][q] = s * akp + c * akq;
  }
  for (int k = 0; k < 4; k++) {
    double apk = a[p][k], aqk = a[q][k];
    a[p][k] = c * apk - s * aqk;
    a[q][k] = s * apk + c * aqk;
  }
  for (int k = 0; k < 4; k++) {
    double vkp = v[k][p], vkq = v[k][q];
    v[k][p] = c * vkp - s * vkq;
    v[k][q] = s * vkp + c * vkq;
  }
}

/* The unit eigenvector of the largest eigenvalue of symmetric a (cyclic
 * Jacobi: a fixed order of sweeps, so the same input gives the same bits). */
static void largest_eigenvector(double a[4][4], double out[4]) {
  double v[4][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } };
  for (int sweep = 0; sweep < 50; sweep++) {
    double off = 0, scale = 0;
    for (int i = 0; i < 4; i++)
      for (int j = 0; j < 4; j++) {
        if (i == j)
          scale += a[i][j] * a[i][j];
        else
          off += a[i][j] * a[i][j];
      }
    if (!(off > 1e-30 * scale)) break;
    for (int p = 0; p < 3; p++)
      for (int q = p + 1; q < 4; q++) jacobi_rotate(a, v, p, q);
  }
  int best = 0;
  for (int i = 1; i < 4; i++)
    if (a[i][i] > a[best][best]) best = i;
  for (int i = 0; i < 4; i++) out[i] = v[i][best];
  if (out[0] < 0)
    for (int i = 0; i < 4; i++) out[i] = -out[i];
  quat_normalise(out);
}

void mr_stage_fit_rotation(const double *u, const double *v, int n, double q[4]) {
  double s[3][3] = { { 0 } }; /* s[a][b] = sum_j u_j[a] v_j[b] */
  for (int j = 0; j < n; j++)
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++) s[a][b] += u[3 * j + a] * v[3 * j + b];
  double xx = s[0][0], xy = s[0][1], xz = s[0][2];
  double yx = s[1][0], yy = s[1][1], yz = s[1][2];
  double zx = s[2][0], zy = s[2][1], zz = s[2][2];
  double m[4][4] = {
    { xx + yy + zz, yz - zy, zx - xz, xy - yx },
    { yz - zy, xx - yy - zz, xy + yx, zx + xz },
    { zx - xz, xy + yx, -xx + yy - zz, yz + zy },
    { xy - yx, zx + xz, yz + zy, -xx - yy + zz },
  };
  largest_eigenvector(m, q);
}

mr_pose mr_stage_pose_between(const mr_pose *a, const mr_pose *b) {
  /* x_b = R_b R_a^T (x_a - o_a) + o_b for every point x fixed in the frame. */
  mr_pose out;
  const double *qa = a->orientation, *qb = b->orientation;
  double ca[4] = { qa[0], -qa[1], -qa[2], -qa[3] };
  out.orientation[0] = qb[0] * ca[0] - qb[1] * ca[1] - qb[2] * ca[2] - qb[3] * ca[3];
  out.orientation[1] = qb[0] * ca[1] + qb[1] * ca[0] + qb[2] * ca[3] - qb[3] * ca[2];
  out.orientation[2] = qb[0] * ca[2] - qb[1] * ca[3] + qb[2] * ca[0] + qb[3] * ca[1];
  out.orientation[3] = qb[0] * ca[3] + qb[1] * ca[2] - qb[2] * ca[1] + qb[3] * ca[0];
  quat_normalise(out.orientation);
  double r[3];
  mr_pose_rotate(out.orientation, a->position, r);
  for (int i = 0; i < 3; i++) out.position[i] = b->position[i] - r[i];
  return out;
}
