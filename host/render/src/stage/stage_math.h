/* The geometry of the display modes (§3.3): frames from particles,
 * rotations between directions, and the rotation that best fits a set of
 * displacements. Private to mr_stage, yet prefixed: a static library
 * exports every name that is not static. */
#ifndef MR_STAGE_MATH_H
#define MR_STAGE_MATH_H

#include <stdbool.h>

#include "mr_pose.h"

/* Below this a length is no direction. */
#define MR_STAGE_TINY_M 1e-9

bool mr_stage_finite3(const double v[3]);

/* The rigid-group frame of three points (§3.3): origin p0, x along
 * p1 - p0, y along p2 - p0 made normal to x, z = x × y. -1 (out untouched)
 * when two points coincide or the three are collinear. */
int mr_stage_frame3(const double p0[3], const double p1[3], const double p2[3], mr_pose *out);

/* The unit quaternion of the rotation whose matrix has columns x, y, z
 * (orthonormal, right-handed). */
void mr_stage_quat_from_axes(const double x[3], const double y[3], const double z[3], double q[4]);

/* The shortest turn taking direction `from` to direction `to` (neither
 * need be unit). Opposite directions turn half round an axis normal to
 * `from`. -1 (q untouched) when either is shorter than MR_STAGE_TINY_M. */
int mr_stage_quat_arc(const double from[3], const double to[3], double q[4]);

/* The rotation R maximising sum_j v_j · R u_j over n pairs (u, v: 3 n
 * each): Horn's closed form, the unit eigenvector of the largest
 * eigenvalue of his symmetric 4 x 4 matrix (J. Opt. Soc. Am. A 4(4),
 * 1987). Exact when the v_j are a rotation of the u_j and the u_j span
 * at least a plane. */
void mr_stage_fit_rotation(const double *u, const double *v, int n, double q[4]);

/* b first, then a^-1: the pose taking a's frame to b's (b a^-1). */
mr_pose mr_stage_pose_between(const mr_pose *a, const mr_pose *b);

#endif
