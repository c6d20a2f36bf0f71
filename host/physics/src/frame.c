/* Control frames (§6.1, §6.2): the frame's particles are moved kinematically
 * to the pose the glove gives. Between the time a target is set (t0) and
 * the time it is due (t1) the pose follows a path whose velocity is
 * continuous across targets, so a taut string is not snapped at each one;
 * every integrator stage places the particles on it at its own time.
 *
 * The path is a cubic Hermite curve, with s = (t − t0)/T, T = t1 − t0:
 *
 *   p(t) = p0 + Δ h01(s) + T m0 h10(s) + T m1 h11(s),
 *   h01 = 3s² − 2s³, h10 = s³ − 2s² + s, h11 = s³ − s²,
 *
 * m0 the velocity the frame has when the target is set (so the velocity
 * is continuous) and m1 the slope at t1 of the parabola through the last
 * two targets and this one (exact to second order for a smooth track, so
 * the path's acceleration follows the track's as the steps shrink, and it
 * leans on no earlier tangent, so no error is carried from one segment to
 * the next). The orientation is the same curve on rotations, a product of
 * turns about fixed axes so that its rates are exact:
 *
 *   q(t) = A B C q0,  A = exp(ρ h01 / 2),  B = exp(ω1' T h11 / 2),
 *   C = exp(ω0 T h10 / 2),
 *
 * ρ the short turn from q0 to q1 (world axes), ω0 the angular velocity at
 * t0, ω1' = A(t1)⁻¹ ω1 for the end rate ω1. With u1 = R_A ω1', u2 = R_A R_B
 * ω0, and dots for time derivatives of h01, T h11, T h10:
 *
 *   ω = ρ ḣ01 + u1 ḣ11 + u2 ḣ10,
 *   ω̇ = ρ ḧ01 + u1 ḧ11 + u2 ḧ10 + ρ ḣ01 × (u1 ḣ11 + u2 ḣ10) + ḣ11 ḣ10 u1 × u2.
 *
 * Outside [t0, t1] the pose is held. The velocity is a quadratic Bézier
 * curve with control points m0, 3Δ/T − m0 − m1, m1: its speed never
 * exceeds the largest of the three; the turn rate is bounded alike, plus
 * (4/27) T |ω0| |ω1| for B's turn of C's axis (mr_world_frame_target_peak). */
#include "internal.h"

#include <math.h>
#include <stdint.h>
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

/* The turn by the rotation vector r (angle |r| about r/|r|) as a unit
 * quaternion; below 1e-12 rad the first-order limit. */
static void quat_exp(const double r[3], double q[4]) {
  double a = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  double c = 1.0, s = 0.5;
  if (a > 1e-12) {
    c = mr_cos(0.5 * a);
    s = mr_sin(0.5 * a) / a;
  }
  q[0] = c;
  for (int k = 0; k < 3; k++) q[k + 1] = s * r[k];
}

/* Frame path at t into st (MR_FRAME_STATE entries: p, q, ṗ, ω, p̈, ω̇). */
void mr_frame_motion(const mr_frame *fr, double t, double *st) {
  double T = fr->t1 - fr->t0;
  memset(st, 0, MR_FRAME_STATE * sizeof *st);
  if (!(T > 0 && t >= fr->t0 && t <= fr->t1)) {
    /* Held: at `to` from t1 on; before t0 (never stepped to) at `from`. */
    const mr_pose *p = T > 0 && t < fr->t0 ? &fr->from : &fr->to;
    memcpy(st, p->position, 3 * sizeof *st);
    memcpy(st + 3, p->orientation, 4 * sizeof *st);
    return;
  }
  double s = (t - fr->t0) / T, s2 = s * s;
  /* h01, h10, h11 (T h10, T h11 for positions), their rates and accelerations. */
  double g = s2 * (3.0 - 2.0 * s), gd = 6.0 * s * (1.0 - s) / T, gdd = (6.0 - 12.0 * s) / (T * T);
  double k = T * s * (s2 - 2.0 * s + 1.0), kd = s * (3.0 * s - 4.0) + 1.0,
         kdd = (6.0 * s - 4.0) / T;
  double j = T * s2 * (s - 1.0), jd = s * (3.0 * s - 2.0), jdd = (6.0 * s - 2.0) / T;
  double ra[3], rb[3], rc[3];
  for (int i = 0; i < 3; i++) {
    double d = fr->to.position[i] - fr->from.position[i];
    st[i] = fr->from.position[i] + d * g + fr->v0[i] * k + fr->v1[i] * j;
    st[7 + i] = d * gd + fr->v0[i] * kd + fr->v1[i] * jd;
    st[13 + i] = d * gdd + fr->v0[i] * kdd + fr->v1[i] * jdd;
    ra[i] = fr->turn[i] * g;
    rb[i] = fr->w1[i] * j;
    rc[i] = fr->w0[i] * k;
  }
  if (!fr->turning) { /* the identity turns: the same bits, none of the work */
    memcpy(st + 3, fr->from.orientation, 4 * sizeof *st);
    return;
  }
  double qa[4], qb[4], qc[4], qab[4], qabc[4], u1[3], u2[3], wj[3], x1[3], x2[3];
  quat_exp(ra, qa);
  quat_exp(rb, qb);
  quat_exp(rc, qc);
  mr_pose_quat_multiply(qa, qb, qab);
  mr_pose_quat_multiply(qab, qc, qabc);
  mr_pose_quat_multiply(qabc, fr->from.orientation, st + 3);
  mr_pose_rotate(qa, fr->w1, u1);
  mr_pose_rotate(qab, fr->w0, u2);
  for (int i = 0; i < 3; i++) wj[i] = u1[i] * jd + u2[i] * kd;
  mr_cross3(fr->turn, wj, x1);
  mr_cross3(u1, u2, x2);
  for (int i = 0; i < 3; i++) {
    st[10 + i] = fr->turn[i] * gd + wj[i];
    st[16 + i] = fr->turn[i] * gdd + u1[i] * jdd + u2[i] * kdd + x1[i] * gd + x2[i] * (jd * kd);
  }
}

/* The frame's pose at t, and its velocity and angular velocity. */
void mr_frame_eval(const mr_frame *fr, double t, mr_pose *pose, double vel[3], double omega[3]) {
  double st[MR_FRAME_STATE];
  mr_frame_motion(fr, t, st);
  memcpy(pose->position, st, 3 * sizeof *st);
  memcpy(pose->orientation, st + 3, 4 * sizeof *st);
  memcpy(vel, st + 7, 3 * sizeof *st);
  memcpy(omega, st + 10, 3 * sizeof *st);
}

/* Frame f's path at t into its entries of frame_state. */
static void frame_state_at(mr_world *w, int f, double t) {
  mr_frame_motion(&MR_AT(w->frames, mr_frame, f), t, &w->frame_state[MR_FRAME_STATE * f]);
}

/* a and b (4 doubles each) hold the same bits. */
static int same_bits4(const double a[4], const double b[4]) {
  uint64_t x[4], y[4];
  memcpy(x, a, sizeof x);
  memcpy(y, b, sizeof y);
  return ((x[0] ^ y[0]) | (x[1] ^ y[1]) | (x[2] ^ y[2]) | (x[3] ^ y[3])) == 0;
}

/* Particle i carried by its frame, from the frame's state: x = p + R l,
 * v = v_f + ω × R l, into xv (x, then v). r = R l is taken from kept[0..2]
 * when kept[3..6] holds the bits of the frame's orientation it was turned
 * by (a frame that does not turn turns each offset once), else computed
 * and kept there; kept may be NULL (nothing is kept). */
static void carried(const mr_world *w, int i, double xv[6], double kept[7]) {
  const double *st = &w->frame_state[MR_FRAME_STATE * w->frame[i]];
  const double *p = st, *qq = st + 3, *fv = st + 7, *fo = st + 10;
  double own[3], *r = kept ? kept : own;
  if (!kept || !same_bits4(kept + 3, qq)) {
    mr_pose_rotate(qq, &w->local[3 * i], r);
    if (kept) memcpy(kept + 3, qq, 4 * sizeof *qq);
  }
  xv[0] = p[0] + r[0];
  xv[1] = p[1] + r[1];
  xv[2] = p[2] + r[2];
  xv[3] = fv[0] + fo[1] * r[2] - fo[2] * r[1];
  xv[4] = fv[1] + fo[2] * r[0] - fo[0] * r[2];
  xv[5] = fv[2] + fo[0] * r[1] - fo[1] * r[0];
}

/* Per carried particle in w->kin_placed: its x and v at frame_state_t,
 * then its offset turned by its frame and the orientation that turned it
 * (carried()). A new entry is zeroed: no orientation is all zero bits, so
 * its offset is turned at its first placement. */
#define KIN_PLACED 13

/* Every frame's state at t, then each carried particle's x and v into
 * w->kin_placed. 0, or −1 when kin_placed cannot grow (then nothing is
 * kept: frame_state_t is NaN). */
static int place_all(mr_world *w, double t) {
  const int nk = w->kin.n, *kin = w->kin.data;
  for (int f = 0; f < w->frames.n; f++) frame_state_at(w, f, t);
  w->frame_state_t = NAN;
  if (mr_grow((void **)&w->kin_placed, &w->cap_kin_placed, nk, KIN_PLACED * sizeof(double)) != 0)
    return -1;
  for (int j = 0; j < nk; j++) {
    double *e = &w->kin_placed[KIN_PLACED * j];
    carried(w, kin[j], e, e + 6);
  }
  w->frame_state_t = t;
  return 0;
}

/* The frames' paths depend on t alone, and an evaluation places them at
 * a time it placed them at just before (a step's end is the next step's
 * start, RK4's two middle stages share theirs, the memo places before it
 * looks): the placement at frame_state_t is kept, and placing there again
 * copies it. Whatever changes a path, or adds a frame or a carried
 * particle, sets frame_state_t to NaN. */
void mr_frames_place(mr_world *w, double t, double *x, double *v) {
  if (!w->has_frames) return;
  w->pass_calls[MR_PASS_FRAMES]++;
  const int nk = w->kin.n, *kin = w->kin.data;
  if (!(t == w->frame_state_t) && place_all(w, t) != 0) {
    for (int j = 0; j < nk; j++) { /* out of memory: placed, not kept */
      double xv[6];
      carried(w, kin[j], xv, NULL);
      memcpy(&x[3 * kin[j]], xv, 3 * sizeof *xv);
      memcpy(&v[3 * kin[j]], xv + 3, 3 * sizeof *xv);
    }
    return;
  }
  const double *placed = w->kin_placed;
  for (int j = 0; j < nk; j++) {
    double *xi = &x[3 * kin[j]], *vi = &v[3 * kin[j]];
    const double *p = &placed[KIN_PLACED * j];
    xi[0] = p[0];
    xi[1] = p[1];
    xi[2] = p[2];
    vi[0] = p[3];
    vi[1] = p[4];
    vi[2] = p[5];
  }
}

/* A control point just added is placed alone, with its own frame's state:
 * placing every frame's points again for each one added made building a
 * crowd of n puppets O(n²) (0.41 s for 1 000 stick puppets, 0.005 s now).
 * Counted as the frames pass it stands for. Only its frame's state is
 * fresh, so no time is recorded for the whole. The room to keep its
 * placement is made here, so that a step allocates none (place_all grows
 * it again if this could not). */
void mr_frame_place_one(mr_world *w, int i) {
  w->pass_calls[MR_PASS_FRAMES]++;
  double xv[6];
  frame_state_at(w, w->frame[i], w->t);
  w->frame_state_t = NAN;
  (void)mr_grow((void **)&w->kin_placed, &w->cap_kin_placed, w->kin.n, KIN_PLACED * sizeof(double));
  carried(w, i, xv, NULL);
  memcpy(&w->x[3 * i], xv, 3 * sizeof *xv);
  memcpy(&w->v[3 * i], xv + 3, 3 * sizeof *xv);
}

/* The point motion of frame particle i at t: its frame's state (the one
 * kept for w->frame_state_t, else worked out into own), the arm r from
 * the frame's origin and ω × r. Returns the state. */
static const double *point_arm(const mr_world *w, int i, double t, const double *x, double *own,
                               double r[3], double wr[3]) {
  const double *st = &w->frame_state[MR_FRAME_STATE * w->frame[i]];
  if (!(t == w->frame_state_t)) {
    mr_frame_motion(&MR_AT(w->frames, mr_frame, w->frame[i]), t, own);
    st = own;
  }
  for (int k = 0; k < 3; k++) r[k] = x[3 * i + k] - st[k];
  mr_cross3(st + 10, r, wr);
  return st;
}

/* The acceleration of frame particle i, at the time of w->frame_state
 * (computed there when it is at another): p̈ + ω̇ × r + ω × (ω × r), with
 * its velocity v_f + ω × r. */
void mr_frame_point_motion(const mr_world *w, int i, double t, const double *x, double v[3],
                           double a[3]) {
  double own[MR_FRAME_STATE], r[3], wr[3], wwr[3], ar[3];
  const double *st = point_arm(w, i, t, x, own, r, wr);
  mr_cross3(st + 10, wr, wwr);
  mr_cross3(st + 16, r, ar);
  for (int k = 0; k < 3; k++) {
    v[k] = st[7 + k] + wr[k];
    a[k] = st[13 + k] + ar[k] + wwr[k];
  }
}

/* The velocity alone: a rate needs no acceleration (same bits as above). */
void mr_frame_point_velocity(const mr_world *w, int i, double t, const double *x, double v[3]) {
  double own[MR_FRAME_STATE], r[3], wr[3];
  const double *st = point_arm(w, i, t, x, own, r, wr);
  for (int k = 0; k < 3; k++) v[k] = st[7 + k] + wr[k];
}

mr_status mr_world_add_frame(mr_world *w, const mr_frame_def *def, int *out_id) {
  const char *what = "mr_world_add_frame";
  mr_status s = MR_ADD_CHECK(w, def, MR_EFFECT_FRAMES, what);
  mr_frame fr;
  memset(&fr, 0, sizeof fr);
  if (s == MR_OK) s = pose_check(w, &def->pose, what, &fr.from);
  if (s != MR_OK) return s;
  int cap = w->frames.cap;
  if (mr_grow((void **)&w->frame_state, &cap, w->frames.n + 1, MR_FRAME_STATE * sizeof(double)) !=
      0)
    return mr_fail(w, MR_ERR_NOMEM, "%s: out of memory", what);
  if (def->path != MR_FRAME_SMOOTH && def->path != MR_FRAME_LINEAR)
    return mr_fail(w, MR_ERR_ARG, "%s: path %d is neither smooth nor linear", what, (int)def->path);
  fr.linear = def->path == MR_FRAME_LINEAR;
  fr.home = fr.to = fr.from;
  fr.t0 = fr.t1 = w->t;
  w->frame_state_t = NAN; /* the new frame has no state yet */
  return mr_add_push(w, &w->frames, &fr, sizeof fr, out_id, what);
}

static mr_status frame_at(mr_world *w, int frame, const char *what) {
  if (!w) return MR_ERR_ARG;
  if (frame < 0 || frame >= w->frames.n)
    return mr_fail(w, MR_ERR_ID, "%s: frame %d does not exist", what, frame);
  return MR_OK;
}

static double norm3(const double v[3]) {
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* The segment's end rates: the velocity as it is, the angular velocity
 * before the whole turn, ω1' = A(t1)⁻¹ ω1 (A(t1) is the whole turn). */
static void given_rates(mr_frame *o, const double vel[3], const double omega[3]) {
  double qa[4];
  memcpy(o->v1, vel, sizeof o->v1);
  quat_exp(o->turn, qa);
  mr_pose_unrotate(qa, omega, o->w1);
}

/* The end rates of a segment from the world's time to `o->t1`: the slopes
 * at t1 of the parabola through the last target (fr's start, when the
 * world is inside or at the end of fr), the pose now and the goal. With no
 * last target (fr held, or just set), the rate now stands for the chord
 * before it. */
static void end_rates(const mr_world *w, const mr_frame *fr, mr_frame *o) {
  double h2 = o->t1 - o->t0, h1 = w->t - fr->t0, c1[3], r1[3], axis[3], v1[3], w1[3];
  if (fr->t1 > fr->t0 && h1 > 0 && w->t <= fr->t1) {
    double angle = mr_pose_turn(fr->from.orientation, o->from.orientation, axis);
    for (int k = 0; k < 3; k++) {
      c1[k] = (o->from.position[k] - fr->from.position[k]) / h1;
      r1[k] = axis[k] * angle / h1;
    }
  } else {
    h1 = h2;
    memcpy(c1, o->v0, sizeof c1);
    memcpy(r1, o->w0, sizeof r1);
  }
  double r = h2 / (h1 + h2);
  for (int k = 0; k < 3; k++) {
    double c2 = (o->to.position[k] - o->from.position[k]) / h2, r2 = o->turn[k] / h2;
    v1[k] = c2 + r * (c2 - c1[k]);
    w1[k] = r2 + r * (r2 - r1[k]);
  }
  given_rates(o, v1, w1);
}

/* Both tangents the chord: h01 + h10 + h11 = s, a straight line at a
 * constant rate, and a turn about one axis at a constant rate. */
static void linear_rates(mr_frame *o, double T) {
  for (int k = 0; k < 3; k++) {
    o->v0[k] = o->v1[k] = (o->to.position[k] - o->from.position[k]) / T;
    o->w0[k] = o->w1[k] = o->turn[k] / T;
  }
}

/* The segment a target `goal` due at t makes of frame fr at the world's
 * time: from the pose now at the velocity now; placed at once and at rest
 * when t is not later than now (§6.1 method 1). It arrives at the rates
 * given (vel and omega both, or neither: the parabola's slopes). */
static void plan_segment(const mr_world *w, const mr_frame *fr, const mr_pose *goal, double t,
                         const double *vel, const double *omega, mr_frame *o) {
  double st[MR_FRAME_STATE], axis[3];
  memset(o, 0, sizeof *o);
  o->home = fr->home;
  o->linear = fr->linear;
  o->to = *goal;
  o->t0 = o->t1 = w->t;
  if (!(t > w->t)) {
    o->from = *goal;
    return;
  }
  o->t1 = t;
  mr_frame_motion(fr, w->t, st);
  memcpy(o->from.position, st, 3 * sizeof *st);
  memcpy(o->from.orientation, st + 3, 4 * sizeof *st);
  memcpy(o->v0, st + 7, 3 * sizeof *st);
  memcpy(o->w0, st + 10, 3 * sizeof *st);
  double angle = mr_pose_turn(o->from.orientation, goal->orientation, axis);
  for (int k = 0; k < 3; k++) o->turn[k] = axis[k] * angle;
  if (o->linear)
    linear_rates(o, t - w->t);
  else if (vel && omega)
    given_rates(o, vel, omega);
  else
    end_rates(w, fr, o);
  for (int k = 0; k < 3; k++) o->turning |= o->turn[k] != 0 || o->w0[k] != 0 || o->w1[k] != 0;
}

static mr_status set_target(mr_world *w, int frame, const mr_pose *pose, const double *vel,
                            const double *omega, double t, const char *what) {
  if (!w || !pose) return mr_fail(w, MR_ERR_ARG, "%s: NULL argument", what);
  mr_status s = frame_at(w, frame, what);
  if (s != MR_OK) return s;
  if (!isfinite(t)) return mr_fail(w, MR_ERR_NONFINITE, "%s: time is NaN or Inf", what);
  if (vel && omega && !(mr_finite3(vel) && mr_finite3(omega)))
    return mr_fail(w, MR_ERR_NONFINITE, "%s: velocity or angular velocity is NaN or Inf", what);
  mr_pose p;
  if ((s = pose_check(w, pose, what, &p)) != MR_OK) return s;
  mr_frame *fr = &MR_AT(w->frames, mr_frame, frame), o;
  plan_segment(w, fr, &p, t, vel, omega, &o);
  *fr = o;
  w->frame_state_t = NAN; /* its path changes from now on */
  if (!(t > w->t)) mr_frames_place(w, w->t, w->x, w->v);
  return MR_OK;
}

mr_status mr_world_set_frame_target(mr_world *w, int frame, const mr_pose *pose, double t) {
  return set_target(w, frame, pose, NULL, NULL, t, "mr_world_set_frame_target");
}

mr_status mr_world_set_frame_target_rates(mr_world *w, int frame, const mr_pose *pose,
                                          const double vel[3], const double omega[3], double t) {
  const char *what = "mr_world_set_frame_target_rates";
  if (!vel || !omega) return mr_fail(w, MR_ERR_ARG, "%s: NULL argument", what);
  return set_target(w, frame, pose, vel, omega, t, what);
}

static mr_status target_peak(const mr_world *w, int frame, const mr_pose *pose, const double *vel,
                             const double *omega, double t, double *speed, double *turn_rate) {
  if (!w || !pose || !speed || !turn_rate) return MR_ERR_ARG;
  if (frame < 0 || frame >= w->frames.n) return MR_ERR_ID;
  mr_pose p = *pose;
  if (!isfinite(t) || mr_pose_normalize(&p) != 0) return MR_ERR_NONFINITE;
  if (vel && omega && !(mr_finite3(vel) && mr_finite3(omega))) return MR_ERR_NONFINITE;
  mr_frame o;
  plan_segment(w, &MR_AT(w->frames, mr_frame, frame), &p, t, vel, omega, &o);
  double T = o.t1 - o.t0, mid[3], wmid[3];
  *speed = *turn_rate = 0.0;
  if (!(T > 0)) return MR_OK;
  for (int k = 0; k < 3; k++) {
    mid[k] = 3.0 * (o.to.position[k] - o.from.position[k]) / T - o.v0[k] - o.v1[k];
    wmid[k] = 3.0 * o.turn[k] / T - o.w0[k] - o.w1[k];
  }
  *speed = fmax(fmax(norm3(o.v0), norm3(mid)), norm3(o.v1));
  *turn_rate = fmax(fmax(norm3(o.w0), norm3(wmid)), norm3(o.w1)) +
               (4.0 / 27.0) * T * norm3(o.w0) * norm3(o.w1);
  return MR_OK;
}

mr_status mr_world_frame_target_peak(const mr_world *w, int frame, const mr_pose *pose, double t,
                                     double *speed, double *turn_rate) {
  return target_peak(w, frame, pose, NULL, NULL, t, speed, turn_rate);
}

mr_status mr_world_frame_target_rates_peak(const mr_world *w, int frame, const mr_pose *pose,
                                           const double vel[3], const double omega[3], double t,
                                           double *speed, double *turn_rate) {
  if (!vel || !omega) return MR_ERR_ARG;
  return target_peak(w, frame, pose, vel, omega, t, speed, turn_rate);
}

mr_status mr_world_frame_target_accel(const mr_world *w, int frame, const mr_pose *pose, double t,
                                      double *accel, double *turn_accel) {
  if (!w || !pose || !accel || !turn_accel) return MR_ERR_ARG;
  if (frame < 0 || frame >= w->frames.n) return MR_ERR_ID;
  mr_pose p = *pose;
  if (!isfinite(t) || mr_pose_normalize(&p) != 0) return MR_ERR_NONFINITE;
  mr_frame o;
  plan_segment(w, &MR_AT(w->frames, mr_frame, frame), &p, t, NULL, NULL, &o);
  *accel = *turn_accel = 0.0;
  if (!(o.t1 > o.t0)) return MR_OK;
  for (int i = 0; i <= 2; i++) {
    double st[MR_FRAME_STATE];
    mr_frame_motion(&o, o.t0 + 0.5 * i * (o.t1 - o.t0), st);
    *accel = fmax(*accel, norm3(st + 13));
    *turn_accel = fmax(*turn_accel, norm3(st + 16));
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

mr_status mr_world_frame_rates(const mr_world *w, int frame, double vel[3], double omega[3]) {
  if (!w || !vel || !omega) return MR_ERR_ARG;
  if (frame < 0 || frame >= w->frames.n) return MR_ERR_ID;
  double st[MR_FRAME_STATE];
  mr_frame_motion(&MR_AT(w->frames, mr_frame, frame), w->t, st);
  memcpy(vel, st + 7, 3 * sizeof *st);
  memcpy(omega, st + 10, 3 * sizeof *st);
  return MR_OK;
}
