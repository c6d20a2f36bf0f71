/* mr_pose: where a rigid thing is and which way it faces.
 *
 * A pose is a position (m) and an orientation as a unit quaternion
 * (w, x, y, z). Physics, control and render all use this one type; Euler
 * angles exist only where a file is read (mr_pose_from_euler_deg), once.
 *
 * A quaternion q turns a vector v into q v q*. Composition reads like
 * matrices: mr_pose_compose(a, b) applies b first, then a.
 */
#ifndef MR_POSE_H
#define MR_POSE_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mr_pose {
  double position[3];    /* m */
  double orientation[4]; /* unit quaternion (w, x, y, z) */
} mr_pose;

/* At the origin, facing the identity (1, 0, 0, 0). */
mr_pose mr_pose_identity(void);

/* 1 when every component is finite, else 0. */
int mr_pose_is_finite(const mr_pose *pose);

/* Scales the orientation to unit length. Returns 0, or -1 (pose untouched)
 * when a component is NaN or Inf or the quaternion is (nearly) zero. */
int mr_pose_normalize(mr_pose *pose);

/* out = q v q* for a unit quaternion q (out may alias v). */
void mr_pose_rotate(const double q[4], const double v[3], double out[3]);

/* out = q* v q: the inverse turn (out may alias v). */
void mr_pose_unrotate(const double q[4], const double v[3], double out[3]);

/* A point given in the pose's frame, in world coordinates. */
void mr_pose_apply(const mr_pose *pose, const double local[3], double world[3]);

/* b first, then a: position a.p + R(a) b.p, orientation a.q b.q. */
mr_pose mr_pose_compose(const mr_pose *a, const mr_pose *b);
/* The Hamilton product a b of two quaternions (w, x, y, z): b's turn
 * first, then a's; out may alias a or b. */
void mr_pose_quat_multiply(const double a[4], const double b[4], double out[4]);

/* The pose a fraction s (0..1) of the way from a to b: position linear,
 * orientation by slerp the short way round (so q and −q give the same
 * path). Both orientations must be unit. */
mr_pose mr_pose_interpolate(const mr_pose *a, const mr_pose *b, double s);

/* The turn from unit quaternion q0 to q1, the short way: returns its angle
 * (radians, 0..π) and writes its unit axis (zero when there is no turn). A
 * slerp over a time span T turns at the constant rate angle/T about it. */
double mr_pose_turn(const double q0[4], const double q1[4], double axis[3]);

/* The pose a rate-limited follower reaches heading from `from` to `to`
 * when it may move at most max_move (m) and turn at most max_turn (rad):
 * the position goes straight towards the goal, the orientation by slerp
 * the short way, each the whole way when within its allowance, else its
 * allowed part. A goal that is not finite leaves `from` as it is. This is
 * the rule that keeps a jump in the input (a glove reconnecting, a track
 * that teleports) from reaching the physics in one step (§7). */
mr_pose mr_pose_approach(const mr_pose *from, const mr_pose *to, double max_move, double max_turn);

/* A pose from a file's position and x-y-z Euler angles in degrees: x is
 * applied first, then y, then z (q = qz qy qx, v' = Rz Ry Rx v), as the
 * scene files have always meant them. */
mr_pose mr_pose_from_euler_deg(const double position[3], const double rotation_deg[3]);

/* Sine, cosine and arc cosine that give the same bits on every CPU,
 * compiler and C library (libm's may differ in the last bit from one to
 * the next, and they reach the state): within about one ulp of the true
 * value, from + − × ÷ and sqrt alone. mr_sin and mr_cos take |x| up to
 * MR_TRIG_MAX_RAD, inside which the reduction by π/2 keeps its precision (a 1 Hz
 * oscillation reaches it after 15 days); beyond it, and for NaN or an
 * infinity, they return NaN rather than a value whose last bits would
 * depend on how the reduction lost them. mr_acos returns NaN outside
 * [−1, 1], and 0 and π at 1 and −1 exactly. */
#define MR_TRIG_MAX_RAD 0x1p23
double mr_sin(double x);
double mr_cos(double x);
double mr_acos(double x);

#ifdef __cplusplus
}
#endif

#endif /* MR_POSE_H */
