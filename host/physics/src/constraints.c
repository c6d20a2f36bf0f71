/* Geometric and time constraints (§5.1, §5.2, §6.1 method 3). Each kind
 * writes, per scalar row i, its Jacobian row J_i = ∂C_i/∂q (into mr_jac),
 * C_i, Ċ_i = J_i q̇ + ∂C_i/∂t and the acceleration bias
 * J̇_i q̇ + ∂²C_i/∂t², the pieces of eq. 8:
 *
 *   J M⁻¹ Jᵀ λ = −J̇q̇ − J M⁻¹ F_a − K_s C − K_d Ċ − ∂²C/∂t².
 */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The pieces of eq. 8's right-hand side a distance row can fold in while
 * it has its numbers (a_free NULL: none). */
typedef struct eq8_terms {
  const double *a_free; /* M⁻¹ F_a, 3n */
  double ks, kd;
  double *rhs;
} eq8_terms;

/* Distance between a and b, d = x_a − x_b, L = |d|, u = d/L:
 *   C   = L − length
 *   J   = [ uᵀ (at a), −uᵀ (at b) ]
 *   Ċ   = u·(v_a − v_b)
 *   J̇q̇  = (|v_a − v_b|² − (u·(v_a − v_b))²) / L      (∂C/∂t = 0)
 * J's entries from e on, two a row, already name a and b (rows_pattern).
 * With eq8, its row of §5.2, eq. 8's b = −J̇q̇ − J M⁻¹ F_a − K_s C − K_d Ċ,
 * J M⁻¹ F_a summed as mr_jac_mul sums it, so the bits are the same. */
static void distance_rows(mr_world *w, int e, const double *x, const double *v, double *c,
                          double *cdot, double *bias, const eq8_terms *eq8) {
  const int n = w->distances.n;
  const mr_distance *dist = w->distances.data;
  double(*jd)[3] = w->J.d;
  const double *af = eq8 ? eq8->a_free : NULL, ks = eq8 ? eq8->ks : 0, kd = eq8 ? eq8->kd : 0;
  double *rhs = eq8 ? eq8->rhs : NULL;
  for (int r = 0; r < n; r++, e += 2) {
    const mr_distance *d = &dist[r];
    const int ia = 3 * d->a, ib = 3 * d->b;
    const double *xa = x + ia, *xb = x + ib, *va = v + ia, *vb = v + ib;
    /* Written out: -O2 leaves 3-loops rolled. */
    const double dx[3] = { xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2] };
    const double dv[3] = { va[0] - vb[0], va[1] - vb[1], va[2] - vb[2] };
    double len = sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
    /* A collapsed link has no direction; keep the row (zero) so the row
     * count is fixed and the solver reports it as dependent. */
    double inv = len > 1e-12 ? 1.0 / len : 0.0;
    const double u[3] = { dx[0] * inv, dx[1] * inv, dx[2] * inv };
    jd[e][0] = u[0];
    jd[e][1] = u[1];
    jd[e][2] = u[2];
    jd[e + 1][0] = -u[0];
    jd[e + 1][1] = -u[1];
    jd[e + 1][2] = -u[2];
    double rate = u[0] * dv[0] + u[1] * dv[1] + u[2] * dv[2];
    double cr = len - d->length;
    double br = (dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2] - rate * rate) * inv;
    c[r] = cr;
    cdot[r] = rate;
    bias[r] = br;
    if (!af) continue;
    const double *aa = af + ia, *ab = af + ib;
    double jv = 0.0;
    jv += u[0] * aa[0] + u[1] * aa[1] + u[2] * aa[2];
    jv += -u[0] * ab[0] + -u[1] * ab[1] + -u[2] * ab[2];
    rhs[r] = -br - jv - ks * cr - kd * rate;
  }
}

/* Pin to a point p: C = x − p (3 rows), J = I, Ċ = v, J̇q̇ = 0. */
static int pin_rows(mr_world *w, const double *x, const double *v, double *c, double *cdot,
                    double *bias) {
  int r = 0;
  for (int i = 0; i < w->pins.n; i++) {
    const mr_pin *p = &MR_AT(w->pins, mr_pin, i);
    for (int k = 0; k < 3; k++, r++) {
      c[r] = x[3 * p->particle + k] - p->point[k];
      cdot[r] = v[3 * p->particle + k];
      bias[r] = 0.0;
    }
  }
  return r;
}

/* Point on a time-dependent curve c(t): C = x − c(t), J = I,
 * Ċ = v − ċ(t) (∂C/∂t = −ċ), J̇q̇ + ∂²C/∂t² = −c̈(t). */
static int curve_rows(mr_world *w, double t, const double *x, const double *v, double *c,
                      double *cdot, double *bias) {
  int r = 0;
  for (int i = 0; i < w->curves.n; i++) {
    const mr_curve *cv = &MR_AT(w->curves, mr_curve, i);
    double p[3], pv[3], pa[3];
    mr_curve_eval(cv, t, p, pv, pa);
    for (int k = 0; k < 3; k++, r++) {
      c[r] = x[3 * cv->particle + k] - p[k];
      cdot[r] = v[3 * cv->particle + k] - pv[k];
      bias[r] = -pa[k];
    }
  }
  return r;
}

/* The rows of a particle held to a point, one per axis: J = I, so each
 * row names the particle once with a unit vector. */
static void axis_rows(mr_world *w, int e, int particle) {
  for (int k = 0; k < 3; k++) {
    w->J.particle[e + k] = particle;
    for (int m = 0; m < 3; m++) w->J.d[e + k][m] = k == m ? 1.0 : 0.0;
  }
}

/* J's rows of the constraints: which particles each names, and the pins'
 * and curves' unit vectors, are the same on every build, and nothing but
 * this file writes J's first rows (other rows are added after them). They
 * are written when the constraints change, w->rows_pattern says for how
 * many elements (elements are only ever added), and each build after that
 * sets the row count alone. Returns the first entry of the distance rows
 * (0), or −1 when out of memory. */
static int rows_pattern(mr_world *w) {
  const int nd = w->distances.n, np = w->pins.n, nc = w->curves.n, elements = nd + np + nc;
  if (w->J.rows != 0) return -1; /* only ever called on a J just reset */
  if (w->rows_pattern == elements) {
    w->J.rows = mr_constraint_row_count(w);
    return 0;
  }
  int e = mr_jac_add_rows(&w->J, nd, 2);
  if (e != 0) return -1;
  for (int r = 0; r < nd; r++) {
    const mr_distance *d = &MR_AT(w->distances, mr_distance, r);
    w->J.particle[2 * r] = d->a;
    w->J.particle[2 * r + 1] = d->b;
  }
  for (int i = 0; i < np + nc; i++) {
    int at = mr_jac_add_rows(&w->J, 3, 1);
    if (at < 0) return -1;
    axis_rows(w, at,
              i < np ? MR_AT(w->pins, mr_pin, i).particle
                     : MR_AT(w->curves, mr_curve, i - np).particle);
  }
  w->rows_pattern = elements;
  return 0;
}

int mr_constraint_row_count(const mr_world *w) {
  return w->distances.n + 3 * w->pins.n + 3 * w->curves.n;
}

int mr_world_constraint_rows(const mr_world *w) {
  return w ? mr_constraint_row_count(w) : 0;
}

static int rows_with(mr_world *w, double t, const double *x, const double *v, double *c,
                     double *cdot, double *bias, const eq8_terms *eq8) {
  w->pass_calls[MR_PASS_CONSTRAINTS]++;
  int e = rows_pattern(w);
  if (e < 0) return -1;
  distance_rows(w, e, x, v, c, cdot, bias, eq8);
  int r0 = w->distances.n;
  int r1 = pin_rows(w, x, v, c + r0, cdot + r0, bias + r0);
  int r2 = curve_rows(w, t, x, v, c + r0 + r1, cdot + r0 + r1, bias + r0 + r1);
  return r0 + r1 + r2;
}

int mr_constraints_rows(mr_world *w, double t, const double *x, const double *v, double *c,
                        double *cdot, double *bias) {
  return rows_with(w, t, x, v, c, cdot, bias, NULL);
}

int mr_constraints_rows_eq8(mr_world *w, double t, const double *x, const double *v,
                            const double *a_free) {
  const eq8_terms eq8 = { a_free, w->def.ks, w->def.kd, w->rhs };
  return rows_with(w, t, x, v, w->row_c, w->row_cdot, w->row_bias, &eq8);
}

static double worse(double e, double d) {
  /* NaN must win, so a non-finite state is never read as "no error". */
  return (d > e || d != d) ? d : e;
}

/* §4.5: the largest relative deviation from the geometric constraints. */
double mr_constraints_deviation(const mr_world *w, double t, const double *x) {
  double e = 0.0;
  for (int i = 0; i < w->distances.n; i++) {
    const mr_distance *d = &MR_AT(w->distances, mr_distance, i);
    const double *xa = x + 3 * d->a, *xb = x + 3 * d->b;
    const double dx[3] = { xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2] };
    double len = sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
    e = worse(e, fabs(len - d->length) / d->length);
  }
  for (int i = 0; i < w->pins.n; i++) {
    const mr_pin *p = &MR_AT(w->pins, mr_pin, i);
    const double *q = &x[3 * p->particle];
    double dd = sqrt((q[0] - p->point[0]) * (q[0] - p->point[0]) +
                     (q[1] - p->point[1]) * (q[1] - p->point[1]) +
                     (q[2] - p->point[2]) * (q[2] - p->point[2]));
    e = worse(e, dd / w->def.deviation_length);
  }
  for (int i = 0; i < w->curves.n; i++) {
    const mr_curve *cv = &MR_AT(w->curves, mr_curve, i);
    double p[3], pv[3], pa[3];
    mr_curve_eval(cv, t, p, pv, pa);
    const double *q = &x[3 * cv->particle];
    double dd = sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) +
                     (q[2] - p[2]) * (q[2] - p[2]));
    e = worse(e, dd / w->def.deviation_length);
  }
  return e;
}

double mr_world_deviation(const mr_world *w) {
  return w ? mr_constraints_deviation(w, w->t, w->x) : 0.0;
}

/* ------------------------------------------------------------ definitions */

mr_distance_def mr_default_distance_def(void) {
  return (mr_distance_def){ .cookie = MR_DEF_COOKIE, .length = -1.0 };
}

mr_pin_def mr_default_pin_def(void) {
  return (mr_pin_def){ .cookie = MR_DEF_COOKIE, .at_current = 1 };
}

mr_curve_def mr_default_curve_def(void) {
  return (mr_curve_def){ .cookie = MR_DEF_COOKIE, .interp = MR_CURVE_CATMULL_ROM };
}

/* A constraint must move something: a row on frame particles only has no
 * mass to act on. */
static int dynamic(const mr_world *w, int p) {
  return w->inv_mass[p] > 0.0;
}

/* A pin or a curve holds one particle, which must exist and not ride on a
 * control frame. */
static mr_status check_moving(mr_world *w, int p, const char *what) {
  if (mr_check_particle(w, p, what) != 0) return MR_ERR_ID;
  if (!dynamic(w, p))
    return mr_fail(w, MR_ERR_ARG, "%s: particle %d is on a control frame", what, p);
  return MR_OK;
}

int mr_distance_add_internal(mr_world *w, int a, int b, double length, int *out_id) {
  mr_distance d = { a, b, length };
  return mr_add_push(w, &w->distances, &d, sizeof d, out_id, "distance") == MR_OK ? 0 : -1;
}

mr_status mr_world_add_distance(mr_world *w, const mr_distance_def *def, int *out_id) {
  const char *what = "mr_world_add_distance";
  mr_status s = MR_ADD_CHECK(w, def, MR_EFFECT_CONSTRAINTS, what);
  if (s != MR_OK) return s;
  if (mr_check_particle(w, def->a, what) != 0 || mr_check_particle(w, def->b, what) != 0)
    return MR_ERR_ID;
  if (def->a == def->b)
    return mr_fail(w, MR_ERR_ARG, "%s: both ends are particle %d", what, def->a);
  if (!dynamic(w, def->a) && !dynamic(w, def->b))
    return mr_fail(w, MR_ERR_ARG, "%s: particles %d and %d are both on control frames", what,
                   def->a, def->b);
  if (!isfinite(def->length)) return mr_fail(w, MR_ERR_NONFINITE, "%s: length is NaN or Inf", what);
  const double *xa = &w->x[3 * def->a], *xb = &w->x[3 * def->b];
  double cur = sqrt((xa[0] - xb[0]) * (xa[0] - xb[0]) + (xa[1] - xb[1]) * (xa[1] - xb[1]) +
                    (xa[2] - xb[2]) * (xa[2] - xb[2]));
  double len = def->length < 0 ? cur : def->length;
  /* §5.2: J = uᵀ needs a direction; a zero length or coincident ends have
   * none, and C = |d| − 0 is not differentiable there. */
  if (!(cur > 1e-9))
    return mr_fail(w, MR_ERR_DEGENERATE, "%s: particles %d and %d coincide", what, def->a, def->b);
  if (!(len > 1e-9))
    return mr_fail(w, MR_ERR_DEGENERATE, "%s: zero length between particles %d and %d", what,
                   def->a, def->b);
  mr_distance d = { def->a, def->b, len };
  return mr_add_push(w, &w->distances, &d, sizeof d, out_id, what);
}

mr_status mr_world_add_pin(mr_world *w, const mr_pin_def *def, int *out_id) {
  const char *what = "mr_world_add_pin";
  mr_status s = MR_ADD_CHECK(w, def, MR_EFFECT_CONSTRAINTS, what);
  if (s == MR_OK) s = check_moving(w, def->particle, what);
  if (s != MR_OK) return s;
  if (!def->at_current && !mr_finite3(def->point))
    return mr_fail(w, MR_ERR_NONFINITE, "%s: point is NaN or Inf", what);
  mr_pin p;
  p.particle = def->particle;
  memcpy(p.point, def->at_current ? &w->x[3 * def->particle] : def->point, sizeof p.point);
  return mr_add_push(w, &w->pins, &p, sizeof p, out_id, what);
}

/* Keys in order and finite; 0 or the failure. */
static mr_status check_keys(mr_world *w, const mr_curve_def *def, const char *what) {
  int n = def->key_count;
  if (n < 1 || !def->times || !def->points)
    return mr_fail(w, MR_ERR_ARG, "%s: needs a callback or at least one key", what);
  for (int i = 0; i < n; i++) {
    if (!isfinite(def->times[i]) || !mr_finite3(&def->points[3 * i]))
      return mr_fail(w, MR_ERR_NONFINITE, "%s: key %d is NaN or Inf", what, i);
    if (i > 0 && !(def->times[i] > def->times[i - 1]))
      return mr_fail(w, MR_ERR_ARG, "%s: key %d: times must increase (%g after %g)", what, i,
                     def->times[i], def->times[i - 1]);
  }
  return MR_OK;
}

mr_status mr_world_add_curve(mr_world *w, const mr_curve_def *def, int *out_id) {
  const char *what = "mr_world_add_curve";
  mr_status s = MR_ADD_CHECK(w, def, MR_EFFECT_CONSTRAINTS, what);
  if (s == MR_OK) s = check_moving(w, def->particle, what);
  if (s != MR_OK) return s;
  if ((unsigned)def->interp > MR_CURVE_LINEAR)
    return mr_fail(w, MR_ERR_ARG, "%s: unknown interpolation %d", what, (int)def->interp);
  mr_curve c = { def->particle, 0, NULL, NULL, def->interp, def->fn, def->user };
  if (!def->fn) {
    if ((s = check_keys(w, def, what)) != MR_OK) return s;
    int n = def->key_count;
    c.key_count = n;
    c.times = malloc((size_t)n * sizeof *c.times);
    c.points = malloc((size_t)n * 3 * sizeof *c.points);
    if (!c.times || !c.points) {
      free(c.times);
      free(c.points);
      return mr_fail(w, MR_ERR_NOMEM, "%s: out of memory", what);
    }
    memcpy(c.times, def->times, (size_t)n * sizeof *c.times);
    memcpy(c.points, def->points, (size_t)n * 3 * sizeof *c.points);
  }
  s = mr_add_push(w, &w->curves, &c, sizeof c, out_id, what);
  if (s != MR_OK) {
    free(c.times);
    free(c.points);
  }
  return s;
}
