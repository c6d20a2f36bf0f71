/* Integrators for q̇ = v, v̇ = a(t, q, v). RK4 is the default (§4.2: its
 * O(h⁴) error is what the ATS rule's fourth root assumes); explicit Euler,
 * semi-implicit Euler and midpoint are here to show what accuracy costs. */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Two elements a step: the same operation on each, and the pairs (the
 * arrays distinct) become one vector operation each. */
static void axpy(int n, double *restrict out, const double *restrict x, double h,
                 const double *restrict y) {
  int i = 0;
  for (; i + 1 < n; i += 2) {
    out[i] = x[i] + h * y[i];
    out[i + 1] = x[i + 1] + h * y[i + 1];
  }
  if (i < n) out[i] = x[i] + h * y[i];
}

/* ------------------------------------------------------------ the memo */

static void point_free(mr_eval_point *m) {
  free(m->x);
  free(m->v);
  free(m->a);
  free(m->frames);
  free(m->contacts);
  memset(m, 0, sizeof *m);
}

void mr_eval_memo_free(mr_eval_memo *m) {
  point_free(&m->last);
  point_free(&m->start);
  memset(m, 0, sizeof *m);
}

/* An evaluation is a function of t, the state (x, v) with the frames
 * placed, the contacts held during the step, h when friction rounds ran,
 * the world's elements (ensure_ready clears the memo when they change),
 * and, for taut strings only, the frames' paths: a taut row takes the
 * frame end's rates from the segment under way (taut_string.c), which a
 * new target changes without moving the frame. Every other reading of a
 * frame goes through the placed x and v. Anything that moves the state
 * between steps, a projection, an impulse, the string correction, a
 * reset, a frame placed at once, shows in these, and the memo is then not
 * used. */
static int same_state(const mr_world *w, const mr_eval_point *m, double t, double h,
                      const double *x, const double *v) {
  const size_t bytes = (size_t)(3 * w->n) * sizeof(double);
  return m->valid && m->t == t && (!m->used_h || m->h == h) && m->n_frames == w->frames.n &&
         m->n_contacts == w->contacts.n && memcmp(m->x, x, bytes) == 0 &&
         memcmp(m->v, v, bytes) == 0 &&
         (m->n_contacts == 0 ||
          memcmp(m->contacts, w->contacts.c, (size_t)m->n_contacts * sizeof(mr_contact)) == 0);
}

static int same_paths(const mr_world *w, const mr_eval_point *m) {
  return m->n_frames == 0 || w->n_taut == 0 ||
         memcmp(m->frames, w->frames.data, (size_t)m->n_frames * sizeof(mr_frame)) == 0;
}

static int point_matches(const mr_world *w, const mr_eval_point *m, double t, double h,
                         const double *x, const double *v) {
  return same_state(w, m, t, h, x, v) && same_paths(w, m);
}

/* Keeps the evaluation a = f(t, x, v) just made in m. Its arrays grow to
 * the world's reserved sizes, so that only the first step allocates. */
static void point_keep(mr_world *w, mr_eval_point *m, double t, double h, const double *x,
                       const double *v, const double *a) {
  const int n3 = 3 * w->n, nc = w->contacts.n > w->contacts.cap ? w->contacts.n : w->contacts.cap;
  int cap = m->cap_n;
  m->valid = 0;
  if (n3 == 0) return; /* an empty world: nothing worth keeping, and no arrays to keep it in */
  if (mr_grow((void **)&m->x, &cap, n3, sizeof(double)) != 0) return;
  cap = m->cap_n;
  if (mr_grow((void **)&m->v, &cap, n3, sizeof(double)) != 0) return;
  cap = m->cap_n;
  if (mr_grow((void **)&m->a, &cap, n3, sizeof(double)) != 0) return;
  m->cap_n = cap;
  if (mr_grow((void **)&m->frames, &m->cap_frames, w->frames.n, sizeof(mr_frame)) != 0 ||
      mr_grow((void **)&m->contacts, &m->cap_contacts, nc, sizeof(mr_contact)) != 0)
    return;
  const size_t bytes = (size_t)n3 * sizeof(double);
  memcpy(m->x, x, bytes);
  memcpy(m->v, v, bytes);
  memcpy(m->a, a, bytes);
  if (w->frames.n > 0 && w->n_taut > 0) /* point_matches reads them for taut strings alone */
    memcpy(m->frames, w->frames.data, (size_t)w->frames.n * sizeof(mr_frame));
  if (w->contacts.n > 0)
    memcpy(m->contacts, w->contacts.c, (size_t)w->contacts.n * sizeof(mr_contact));
  m->n_frames = w->frames.n;
  m->n_contacts = w->contacts.n;
  m->t = t;
  m->h = h;
  m->used_h = w->eval_used_h;
  m->system = w->system;
  m->valid = 1;
}

/* mr_eval through the memo: a kept answer when (t, x, v, ...) is its
 * point, bit for bit, else a new evaluation, then kept. A step's first
 * stage (first) is kept as the start, where every try of the step begins,
 * and is looked for there too; any other as the last. */
static int eval_memo(mr_world *w, double t, double h, double *x, double *v, double *a, int first) {
  mr_eval_memo *m = &w->memo;
  if (!m->valid) m->last.valid = m->start.valid = 0;
  m->valid = 1;
  if (m->last.valid || (first && m->start.valid)) {
    mr_frames_place(w, t, x, v);
    const int in_last = point_matches(w, &m->last, t, h, x, v);
    if (in_last || (first && point_matches(w, &m->start, t, h, x, v))) {
      if (in_last && first) { /* the last step's end: now this step's start */
        const mr_eval_point p = m->start;
        m->start = m->last;
        m->last = p;
      }
      memcpy(a, (in_last && !first ? m->last : m->start).a, (size_t)(3 * w->n) * sizeof *a);
      mr_taut_set_time(w, t);
      m->recalled++;
      return 0;
    }
  }
  /* The last step's end, its frames on new paths: its system serves
   * (eval.c). */
  int again =
      first && m->last.valid && m->last.system == w->system && same_state(w, &m->last, t, h, x, v)
          ? mr_eval_new_path(w, t, h, x, v, a)
          : 0;
  if (again < 0 || (again == 0 && mr_eval(w, t, h, x, v, a) != 0)) return -1;
  point_keep(w, first ? &m->start : &m->last, t, h, x, v, a);
  return 0;
}

/* The scaled size of one particle's local error (ex, ev). */
static double particle_error(const mr_world *w, const double ex[3], const double ev[3]) {
  double px = sqrt(ex[0] * ex[0] + ex[1] * ex[1] + ex[2] * ex[2]);
  double pv = sqrt(ev[0] * ev[0] + ev[1] * ev[1] + ev[2] * ev[2]);
  double e = 0.0;
  if (w->def.error_length > 0) e = px / w->def.error_length;
  if (w->def.error_speed > 0) {
    double s = pv / w->def.error_speed;
    if (s > e || s != s) e = s;
  }
  return px != px ? px : e;
}

/* The local error estimate of the step just taken, the largest over the
 * dynamic particles of |δx|/error_length and |δv|/error_speed.
 *
 * RK4 (§4.2) carries an embedded third-order solution for the price of one
 * more evaluation, at the step's end (k5 = f(t + h, y1)): the weights
 * b̂ = (1/6, 1/3, 1/3, 0, 1/6) on the nodes c = (0, ½, ½, 1, 1) meet the
 * order-3 conditions Σb̂ = 1, Σb̂c = ½, Σb̂c² = ⅓, Σb̂(Ac) = 1/6, so
 * y1 − ŷ1 = h/6 (k4 − k5) estimates the third-order solution's error, an
 * upper bound on RK4's own (the §4.5 fourth root keeps its meaning). The
 * first- and second-order integrators compare with the trapezoid rule
 * instead, δ = h/2 (f(y1) − f(y0)), the same one evaluation.
 * kv, ka: the stage whose difference with the end is taken (k4, or k1);
 * scale: h/6 or h/2. a_end is scratch for f(y1). */
static int local_error(mr_world *w, double t, double h, double *x1, double *v1, const double *kv,
                       const double *ka, double scale, double *a_end, double *err) {
  if (eval_memo(w, t + h, h, x1, v1, a_end, 0) != 0) return -1;
  double e = 0.0;
  const double *inv_mass = w->inv_mass;
  for (int i = 0; i < w->n; i++) {
    if (!(inv_mass[i] > 0)) continue;
    const double *kvi = kv + 3 * i, *v1i = v1 + 3 * i, *kai = ka + 3 * i, *ai = a_end + 3 * i;
    const double ex[3] = { scale * (kvi[0] - v1i[0]), scale * (kvi[1] - v1i[1]),
                           scale * (kvi[2] - v1i[2]) };
    const double ev[3] = { scale * (kai[0] - ai[0]), scale * (kai[1] - ai[1]),
                           scale * (kai[2] - ai[2]) };
    double p = particle_error(w, ex, ev);
    if (p > e || p != p) e = p;
  }
  *err = e;
  return 0;
}

/* RK4's weighted sums of the stages k (kv1 ka1 ... kv4 ka4, 3n each) into
 * x1 and v1, two elements a step as axpy(). */
static void rk4_combine(int n3, double h6, const double *restrict xs, const double *restrict k,
                        double *restrict x1, double *restrict v1) {
  const double *kv1 = k, *ka1 = k + n3, *kv2 = k + 2 * n3, *ka2 = k + 3 * n3;
  const double *kv3 = k + 4 * n3, *ka3 = k + 5 * n3, *kv4 = k + 6 * n3, *ka4 = k + 7 * n3;
  int i = 0;
  for (; i + 1 < n3; i += 2) {
    x1[i] = xs[i] + h6 * (kv1[i] + 2.0 * kv2[i] + 2.0 * kv3[i] + kv4[i]);
    x1[i + 1] = xs[i + 1] + h6 * (kv1[i + 1] + 2.0 * kv2[i + 1] + 2.0 * kv3[i + 1] + kv4[i + 1]);
    v1[i] = kv1[i] + h6 * (ka1[i] + 2.0 * ka2[i] + 2.0 * ka3[i] + ka4[i]);
    v1[i + 1] = kv1[i + 1] + h6 * (ka1[i + 1] + 2.0 * ka2[i + 1] + 2.0 * ka3[i + 1] + ka4[i + 1]);
  }
  for (; i < n3; i++) {
    x1[i] = xs[i] + h6 * (kv1[i] + 2.0 * kv2[i] + 2.0 * kv3[i] + kv4[i]);
    v1[i] = kv1[i] + h6 * (ka1[i] + 2.0 * ka2[i] + 2.0 * ka3[i] + ka4[i]);
  }
}

/* err: the scaled local error estimate (above), or NULL when the caller
 * does not need one (it then costs nothing). */
int mr_integrate(mr_world *w, double t, double h, const double *x0, const double *v0, double *x1,
                 double *v1, double *err) {
  int n3 = 3 * w->n;
  size_t bytes = (size_t)n3 * sizeof(double);
  double *xs = w->scratch.xs, *vs = w->scratch.vs;
  double *k = w->scratch.k; /* kv1 ka1 kv2 ka2 kv3 ka3 kv4 ka4 */
  double *kv1 = k, *ka1 = k + n3, *kv2 = k + 2 * n3, *ka2 = k + 3 * n3;
  double *kv3 = k + 4 * n3, *ka3 = k + 5 * n3, *kv4 = k + 6 * n3, *ka4 = k + 7 * n3;
  memcpy(kv1, v0, bytes);
  memcpy(xs, x0, bytes);
  if (eval_memo(w, t, h, xs, kv1, ka1, 1) != 0) return -1;
  switch (w->def.integrator) {
  case MR_INTEGRATOR_EULER:
    axpy(n3, x1, xs, h, kv1);
    axpy(n3, v1, kv1, h, ka1);
    break;
  case MR_INTEGRATOR_SEMI_IMPLICIT_EULER:
    axpy(n3, v1, kv1, h, ka1);
    axpy(n3, x1, xs, h, v1);
    break;
  case MR_INTEGRATOR_MIDPOINT:
    axpy(n3, vs, kv1, 0.5 * h, ka1);
    axpy(n3, x1, xs, 0.5 * h, kv1);
    if (mr_eval(w, t + 0.5 * h, h, x1, vs, ka2) != 0) return -1;
    axpy(n3, x1, xs, h, vs);
    axpy(n3, v1, kv1, h, ka2);
    break;
  case MR_INTEGRATOR_RK4:
  default: {
    double *xa = x1; /* stage positions; x1 is written last */
    axpy(n3, xa, xs, 0.5 * h, kv1);
    axpy(n3, kv2, kv1, 0.5 * h, ka1);
    if (mr_eval(w, t + 0.5 * h, h, xa, kv2, ka2) != 0) return -1;
    axpy(n3, xa, xs, 0.5 * h, kv2);
    axpy(n3, kv3, kv1, 0.5 * h, ka2);
    if (mr_eval(w, t + 0.5 * h, h, xa, kv3, ka3) != 0) return -1;
    axpy(n3, xa, xs, h, kv3);
    axpy(n3, kv4, kv1, h, ka3);
    if (mr_eval(w, t + h, h, xa, kv4, ka4) != 0) return -1;
    rk4_combine(n3, h / 6.0, xs, k, x1, v1);
    break;
  }
  }
  mr_frames_place(w, t + h, x1, v1);
  if (!err || (w->def.error_length <= 0 && w->def.error_speed <= 0)) {
    if (err) *err = 0.0;
    return 0;
  }
  if (w->def.integrator == MR_INTEGRATOR_RK4) /* k1 is spent: f(y1) goes there */
    return local_error(w, t, h, x1, v1, kv4, ka4, h / 6.0, ka1, err);
  return local_error(w, t, h, x1, v1, kv1, ka1, 0.5 * h, ka4, err);
}
