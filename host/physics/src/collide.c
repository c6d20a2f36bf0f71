/* Contacts (§4.4, §5.4): the state function χ = (p₂ − p₁)·n̂ (eq. 10) and
 * its derivatives for the two kinds of contact the world knows:
 *
 *  - particle against plane n·x = offset (n unit, fixed):
 *      χ = n·x − offset − r,  J = nᵀ,  χ̇ = n·v,  J̇q̇ = 0;
 *  - two leaf spheres with centres c₁, c₂ (each a fixed blend of one or two
 *    particles, c = Σ wᵢ xᵢ), radii r₁, r₂, d = c₂ − c₁, n = d/|d|:
 *      χ = |d| − r₁ − r₂,  J = (−wᵢ nᵀ at c₁'s particles, +wⱼ nᵀ at c₂'s),
 *      χ̇ = n·ḋ,  J̇q̇ = (|ḋ|² − (n·ḋ)²)/|d|   (the ṅ term of eq. 12).
 */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

mr_plane_def mr_default_plane_def(void) {
  return (mr_plane_def){ .cookie = MR_DEF_COOKIE,
                         .normal = { 0.0, 1.0, 0.0 },
                         .offset = 0.0,
                         .restitution = 0.5,
                         .friction = 0.3 };
}

mr_status mr_world_add_plane(mr_world *w, const mr_plane_def *def, int *out_id) {
  const char *what = "mr_world_add_plane";
  mr_status s = MR_ADD_CHECK(w, def, MR_EFFECT_PLANES, what);
  if (s != MR_OK) return s;
  if (!mr_finite3(def->normal) || !isfinite(def->offset) || !isfinite(def->restitution) ||
      !isfinite(def->friction))
    return mr_fail(w, MR_ERR_NONFINITE, "%s: NaN or Inf in the plane", what);
  double len = sqrt(def->normal[0] * def->normal[0] + def->normal[1] * def->normal[1] +
                    def->normal[2] * def->normal[2]);
  if (!(len > 1e-12)) return mr_fail(w, MR_ERR_DEGENERATE, "%s: normal is zero", what);
  if (def->restitution < 0 || def->restitution > 1 || def->friction < 0)
    return mr_fail(w, MR_ERR_ARG, "%s: need 0 <= restitution <= 1 and friction >= 0", what);
  mr_plane p;
  for (int k = 0; k < 3; k++) p.n[k] = def->normal[k] / len;
  p.offset = def->offset;
  p.restitution = def->restitution;
  p.friction = def->friction;
  return mr_add_push(w, &w->planes, &p, sizeof p, out_id, what);
}

int mr_contact_push(mr_contact_list *l, mr_contact_kind kind, int a, int b, double e, double mu) {
  if (mr_grow((void **)&l->c, &l->cap, l->n + 1, sizeof *l->c) != 0) return -1;
  l->c[l->n++] = (mr_contact){ kind, a, b, e, mu };
  return 0;
}

void mr_contact_list_free(mr_contact_list *l) {
  free(l->c);
  l->c = NULL;
  l->n = l->cap = 0;
}

static double plane_gap(const mr_world *w, int p, const mr_plane *pl, const double *x) {
  const double *q = &x[3 * p];
  return pl->n[0] * q[0] + pl->n[1] * q[1] + pl->n[2] * q[2] - pl->offset - w->radius[p];
}

/* The smaller of two gaps, NaN when either is: fmin() would pass over a
 * NaN end of a step and call it clear. */
static double least(double a, double b) {
  return a != a || b != b ? NAN : fmin(a, b);
}

/* ------------------------------------------------- swept tests (§4.4)
 *
 * Contacts are looked for at a step's ends, yet a body fast enough crosses
 * another between them (two 1 cm spheres closing at 80 m/s: in 0.5 ms).
 * Between its ends each particle is taken on the cubic Hermite path
 * through (x0, v0) and (x1, v1), RK4's own to high order, and so is any
 * blend or difference of particles (a leaf centre, the vector between two
 * centres, a string). With v̄ = Δx/h, such a path strays from its chord
 * x0 + s Δx, s in [0, 1], by
 *
 *   h s(1−s) [(1−s)(v0 − v̄) − s(v1 − v̄)],  at most  e = h/4 max(|v0 − v̄|, |v1 − v̄|),
 *
 * the bulge (a part swinging through θ on radius r: e = r θ²/8; two parts
 * falling side by side: 0). The swept gap is then
 *  - plane: n·x along the path is a cubic in s, and its least value on
 *    [0, 1] (at an end or where its derivative vanishes) is exact;
 *  - two spheres: the centre distance |d0 + s Δd| along the chord is
 *    least at s* = −d0·Δd/|Δd|², clamped to [0, 1], lowered by the bulge of
 *    the path of d;
 *  - string: its length |d(s)| along the chord is convex, so greatest at
 *    an end; the bulge is left out, see mr_contact_swept_gap. */
static double bulge_of(const double d0[3], const double d1[3], const double u0[3],
                       const double u1[3], double h) {
  if (!(h > 0)) return 0.0;
  double a = 0.0, b = 0.0;
  for (int k = 0; k < 3; k++) {
    double bar = (d1[k] - d0[k]) / h, da = u0[k] - bar, db = u1[k] - bar;
    a += da * da;
    b += db * db;
  }
  return 0.25 * h * sqrt(a != a || b != b ? NAN : fmax(a, b));
}

static void leaf_velocity(const mr_leaf *l, const double *v, double out[3]);

double mr_leaf_bulge(const mr_world *w, const mr_leaf *l, const mr_sweep *sw) {
  double c0[3], c1[3], u0[3], u1[3];
  mr_leaf_center(w, l, sw->x0, c0);
  mr_leaf_center(w, l, sw->x1, c1);
  leaf_velocity(l, sw->v0, u0);
  leaf_velocity(l, sw->v1, u1);
  return bulge_of(c0, c1, u0, u1, sw->h);
}

/* The least of f(s) = f0 + (Δ + A) s − (2A + B) s² + (A + B) s³ on [0, 1]:
 * the Hermite cubic with ends f0, f0 + Δ and end slopes A + ..., B (h times
 * the rates less the chord's). */
static double cubic_min(double f0, double delta, double A, double B) {
  if (A != A || B != B) return NAN;
  double c1 = delta + A, c2 = -(2.0 * A + B), c3 = A + B;
  double best = fmin(f0, f0 + delta), s[2];
  int n = 0;
  if (fabs(c3) > 1e-300) {
    double disc = c2 * c2 - 3.0 * c3 * c1;
    if (disc >= 0) {
      s[n++] = (-c2 - sqrt(disc)) / (3.0 * c3);
      s[n++] = (-c2 + sqrt(disc)) / (3.0 * c3);
    }
  } else if (fabs(c2) > 1e-300) {
    s[n++] = -c1 / (2.0 * c2);
  }
  for (int i = 0; i < n; i++)
    if (s[i] > 0 && s[i] < 1) best = fmin(best, f0 + s[i] * (c1 + s[i] * (c2 + s[i] * c3)));
  return best;
}

static double plane_swept_gap(const mr_world *w, int p, const mr_plane *pl, const mr_sweep *sw,
                              int bulge) {
  double g0 = plane_gap(w, p, pl, sw->x0), g1 = plane_gap(w, p, pl, sw->x1);
  if (!bulge || !(sw->h > 0)) return least(g0, g1);
  const double *n = pl->n, *u0 = &sw->v0[3 * p], *u1 = &sw->v1[3 * p];
  double delta = g1 - g0;
  double A = sw->h * (n[0] * u0[0] + n[1] * u0[1] + n[2] * u0[2]) - delta;
  double B = sw->h * (n[0] * u1[0] + n[1] * u1[1] + n[2] * u1[2]) - delta;
  return cubic_min(g0, delta, A, B);
}

static double spheres_swept_gap(const mr_world *w, const mr_contact *c, const mr_sweep *sw,
                                int bulge) {
  const mr_leaf *la = &MR_AT(w->leaves, mr_leaf, c->a), *lb = &MR_AT(w->leaves, mr_leaf, c->b);
  double a0[3], a1[3], b0[3], b1[3], d0[3], d1[3], dd[3], q = 0.0, p = 0.0;
  mr_leaf_center(w, la, sw->x0, a0);
  mr_leaf_center(w, la, sw->x1, a1);
  mr_leaf_center(w, lb, sw->x0, b0);
  mr_leaf_center(w, lb, sw->x1, b1);
  for (int k = 0; k < 3; k++) {
    d0[k] = b0[k] - a0[k];
    d1[k] = b1[k] - a1[k];
    dd[k] = d1[k] - d0[k];
    q += dd[k] * dd[k];
    p += d0[k] * dd[k];
  }
  double s = q > 0 ? fmin(fmax(-p / q, 0.0), 1.0) : 0.0, len = 0.0;
  for (int k = 0; k < 3; k++) len += (d0[k] + s * dd[k]) * (d0[k] + s * dd[k]);
  double g = sqrt(len) - la->r - lb->r;
  if (!bulge) return g;
  double ua[3], ub[3], u0[3], u1[3];
  leaf_velocity(la, sw->v0, ua);
  leaf_velocity(lb, sw->v0, ub);
  for (int k = 0; k < 3; k++) u0[k] = ub[k] - ua[k];
  leaf_velocity(la, sw->v1, ua);
  leaf_velocity(lb, sw->v1, ub);
  for (int k = 0; k < 3; k++) u1[k] = ub[k] - ua[k];
  return g - bulge_of(d0, d1, u0, u1, sw->h);
}

/* A string's bulge is left out: taut strings go slack and snap back many
 * times a second under a swinging bar, and a slack string within its
 * bulge of taut (a bar at 3 Hz: about 1 mm at Δt = 0.01 s) would have each
 * step cut to it. What the straight paths leave out, at most that bulge of
 * over-length within a step, is projected back after it (§6.2). */
static double string_swept_gap(const mr_world *w, int i, const mr_sweep *sw) {
  return least(mr_taut_gap(w, i, sw->x0), mr_taut_gap(w, i, sw->x1));
}

double mr_contact_swept_gap(const mr_world *w, const mr_contact *c, const mr_sweep *sw, int bulge) {
  if (c->kind == MR_CONTACT_STRING) return string_swept_gap(w, c->a, sw);
  if (c->kind == MR_CONTACT_PLANE)
    return plane_swept_gap(w, c->a, &MR_AT(w->planes, mr_plane, c->b), sw, bulge);
  return spheres_swept_gap(w, c, sw, bulge);
}

double mr_sphere_pair_swept_gap(const mr_world *w, int leaf_a, int leaf_b, const mr_sweep *sw) {
  const mr_contact c = { MR_CONTACT_SPHERES, leaf_a, leaf_b, 0.0, 0.0 };
  return spheres_swept_gap(w, &c, sw, 1);
}

/* §4.4: planes such as the floor are tested against each particle. */
static int detect_planes(mr_world *w, const double *x, const mr_sweep *sw, double gap,
                         mr_contact_list *out) {
  w->pass_calls[MR_PASS_PLANES]++;
  for (int j = 0; j < w->planes.n; j++) {
    const mr_plane *pl = &MR_AT(w->planes, mr_plane, j);
    for (int i = 0; i < w->n; i++) {
      if (w->inv_mass[i] == 0.0) continue;
      double chi = sw ? plane_swept_gap(w, i, pl, sw, 1) : plane_gap(w, i, pl, x);
      if (chi <= gap || chi != chi)
        if (mr_contact_push(out, MR_CONTACT_PLANE, i, j, pl->restitution, pl->friction) != 0)
          return -1;
    }
  }
  return 0;
}

int mr_collide_build_passes(mr_world *w) {
  w->n_detect_passes = 0;
  if (w->def.effects & MR_EFFECT_PLANES) {
    w->detect_passes[w->n_detect_passes] = detect_planes;
    w->detect_pass_ids[w->n_detect_passes++] = MR_PASS_PLANES;
  }
  if (w->def.effects & MR_EFFECT_SELF_COLLISION) {
    w->detect_passes[w->n_detect_passes] = mr_detect_self;
    w->detect_pass_ids[w->n_detect_passes++] = MR_PASS_SELF_COLLISION;
  }
  if (w->def.effects & MR_EFFECT_PUPPET_COLLISION) {
    w->detect_passes[w->n_detect_passes] = mr_detect_puppets;
    w->detect_pass_ids[w->n_detect_passes++] = MR_PASS_PUPPET_COLLISION;
  }
  return 0;
}

int mr_colliders(const mr_world *w) {
  return w->n_detect_passes > 0 || w->n_taut > 0;
}

int mr_contacts_detect(mr_world *w, const double *x, double gap, mr_contact_list *out) {
  out->n = 0;
  for (int p = 0; p < w->n_detect_passes; p++)
    if (w->detect_passes[p](w, x, NULL, gap, out) != 0) return -1;
  return w->n_taut > 0 ? mr_taut_detect(w, x, gap, out) : 0;
}

int mr_contacts_sweep(mr_world *w, const mr_sweep *sw, double gap, mr_contact_list *out) {
  out->n = 0;
  for (int p = 0; p < w->n_detect_passes; p++)
    if (w->detect_passes[p](w, sw->x1, sw, gap, out) != 0) return -1;
  const mr_list *l = MR_FORCES(w, STRINGS);
  for (int i = 0; i < l->n && w->n_taut > 0; i++) {
    if (!MR_AT(*l, mr_string, i).taut) continue;
    double chi = string_swept_gap(w, i, sw);
    if (chi <= gap || chi != chi)
      if (mr_contact_push(out, MR_CONTACT_STRING, i, -1, 0.0, 0.0) != 0) return -1;
  }
  return 0;
}

double mr_world_penetration(mr_world *w) {
  if (w == NULL || w->n_detect_passes == 0) return 0.0;
  /* A list of its own, so the contacts the next step works from stay as
   * they are; kept, so a run that measures every step allocates nothing
   * once it has grown. */
  mr_contact_list *list = &w->measured;
  double deepest = 0.0;
  if (mr_contacts_detect(w, w->x, 0.0, list) != 0) deepest = NAN;
  for (int i = 0; i < list->n && !isnan(deepest); i++)
    if (list->c[i].kind != MR_CONTACT_STRING) /* an over-length, not a depth */
      deepest = fmax(deepest, -mr_contact_gap(w, &list->c[i], w->x));
  return deepest;
}

static void sphere_geometry(const mr_world *w, const mr_contact *c, const double *x, double d[3],
                            double *len) {
  double ca[3], cb[3];
  mr_leaf_center(w, &MR_AT(w->leaves, mr_leaf, c->a), x, ca);
  mr_leaf_center(w, &MR_AT(w->leaves, mr_leaf, c->b), x, cb);
  for (int k = 0; k < 3; k++) d[k] = cb[k] - ca[k];
  *len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

double mr_contact_gap(const mr_world *w, const mr_contact *c, const double *x) {
  if (c->kind == MR_CONTACT_STRING) return mr_taut_gap(w, c->a, x);
  if (c->kind == MR_CONTACT_PLANE) return plane_gap(w, c->a, &MR_AT(w->planes, mr_plane, c->b), x);
  double d[3], len;
  sphere_geometry(w, c, x, d, &len);
  return len - MR_AT(w->leaves, mr_leaf, c->a).r - MR_AT(w->leaves, mr_leaf, c->b).r;
}

static void leaf_velocity(const mr_leaf *l, const double *v, double out[3]) {
  for (int k = 0; k < 3; k++) out[k] = (1.0 - l->s) * v[3 * l->p0 + k] + l->s * v[3 * l->p1 + k];
}

/* Adds s·(weight)·n at the particles of leaf l. */
static int leaf_jac(mr_world *w, const mr_leaf *l, const double n[3], double s) {
  double g0[3], g1[3];
  for (int k = 0; k < 3; k++) {
    g0[k] = s * (1.0 - l->s) * n[k];
    g1[k] = s * l->s * n[k];
  }
  if (mr_jac_add(&w->J, l->p0, g0) != 0) return -1;
  if (l->s > 0 && mr_jac_add(&w->J, l->p1, g1) != 0) return -1;
  return 0;
}

double mr_contact_rate(const mr_world *w, const mr_contact *c, const double *x, const double *v) {
  if (c->kind == MR_CONTACT_STRING) return mr_taut_rate(w, c->a, x, v);
  if (c->kind == MR_CONTACT_PLANE) {
    const double *n = MR_AT(w->planes, mr_plane, c->b).n, *q = &v[3 * c->a];
    return n[0] * q[0] + n[1] * q[1] + n[2] * q[2];
  }
  double d[3], len, va[3], vb[3];
  sphere_geometry(w, c, x, d, &len);
  if (!(len > 1e-12)) return 0.0;
  leaf_velocity(&MR_AT(w->leaves, mr_leaf, c->a), v, va);
  leaf_velocity(&MR_AT(w->leaves, mr_leaf, c->b), v, vb);
  return (d[0] * (vb[0] - va[0]) + d[1] * (vb[1] - va[1]) + d[2] * (vb[2] - va[2])) / len;
}

int mr_contact_row(mr_world *w, const mr_contact *c, const double *x, const double *v, double *chi,
                   double *chidot, double *jdqd) {
  if (c->kind == MR_CONTACT_STRING) return mr_taut_row(w, c->a, x, v, chi, chidot, jdqd);
  if (mr_jac_begin_row(&w->J) < 0) return -1;
  if (c->kind == MR_CONTACT_PLANE) {
    const mr_plane *pl = &MR_AT(w->planes, mr_plane, c->b);
    if (mr_jac_add(&w->J, c->a, pl->n) != 0) return -1;
    const double *q = &v[3 * c->a];
    *chidot = pl->n[0] * q[0] + pl->n[1] * q[1] + pl->n[2] * q[2];
    *jdqd = 0.0;
    *chi = plane_gap(w, c->a, pl, x);
    return 0;
  }
  const mr_leaf *la = &MR_AT(w->leaves, mr_leaf, c->a), *lb = &MR_AT(w->leaves, mr_leaf, c->b);
  double d[3], len;
  sphere_geometry(w, c, x, d, &len);
  double n[3] = { 0, 0, 0 };
  if (len > 1e-12)
    for (int k = 0; k < 3; k++) n[k] = d[k] / len;
  if (leaf_jac(w, la, n, -1.0) != 0 || leaf_jac(w, lb, n, 1.0) != 0) return -1;
  double va[3], vb[3], dv[3];
  leaf_velocity(la, v, va);
  leaf_velocity(lb, v, vb);
  for (int k = 0; k < 3; k++) dv[k] = vb[k] - va[k];
  double rate = n[0] * dv[0] + n[1] * dv[1] + n[2] * dv[2];
  *chidot = rate;
  *jdqd = len > 1e-12 ? (dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2] - rate * rate) / len : 0.0;
  *chi = len - la->r - lb->r;
  return 0;
}

/* The particles carrying a contact, with their weights: side a first (the
 * plane has none), then side b. Returns their number (at most 4). */
static int carriers(const mr_world *w, const mr_contact *c, int p[4], double wt[4]) {
  if (c->kind == MR_CONTACT_PLANE) {
    p[0] = c->a;
    wt[0] = 1.0;
    return 1;
  }
  int n = 0;
  const mr_leaf *side[2] = { &MR_AT(w->leaves, mr_leaf, c->a), &MR_AT(w->leaves, mr_leaf, c->b) };
  for (int k = 0; k < 2; k++) {
    double sign = k == 0 ? -1.0 : 1.0;
    p[n] = side[k]->p0;
    wt[n++] = sign * (1.0 - side[k]->s);
    if (side[k]->s > 0) {
      p[n] = side[k]->p1;
      wt[n++] = sign * side[k]->s;
    }
  }
  return n;
}

void mr_contact_normal(const mr_world *w, const mr_contact *c, const double *x, double n[3]) {
  if (c->kind == MR_CONTACT_PLANE) {
    for (int k = 0; k < 3; k++) n[k] = MR_AT(w->planes, mr_plane, c->b).n[k];
    return;
  }
  double d[3], len;
  sphere_geometry(w, c, x, d, &len);
  for (int k = 0; k < 3; k++) n[k] = len > 1e-12 ? d[k] / len : 0.0;
}

double mr_contact_slip(const mr_world *w, const mr_contact *c, const double *x, const double *q,
                       double out[3]) {
  int p[4];
  double wt[4], n[3], rel[3] = { 0, 0, 0 }, inv = 0.0;
  out[0] = out[1] = out[2] = 0.0;
  if (c->kind == MR_CONTACT_STRING) return 0.0; /* a string has no friction */
  int np = carriers(w, c, p, wt);
  for (int i = 0; i < np; i++) {
    for (int k = 0; k < 3; k++) rel[k] += wt[i] * q[3 * p[i] + k];
    inv += wt[i] * wt[i] * w->inv_mass[p[i]];
  }
  mr_contact_normal(w, c, x, n);
  double rn = rel[0] * n[0] + rel[1] * n[1] + rel[2] * n[2];
  for (int k = 0; k < 3; k++) out[k] = rel[k] - rn * n[k];
  return inv;
}

void mr_contact_spread(const mr_world *w, const mr_contact *c, const double f[3], double s,
                       double *out) {
  int p[4];
  double wt[4];
  if (c->kind == MR_CONTACT_STRING) return;
  int np = carriers(w, c, p, wt);
  for (int i = 0; i < np; i++) {
    double k = s * wt[i];
    for (int j = 0; j < 3; j++) out[3 * p[i] + j] += k * f[j];
  }
}

int mr_contact_carriers(const mr_world *w, const mr_contact *c, int p[4]) {
  double wt[4];
  return c->kind == MR_CONTACT_STRING ? 0 : carriers(w, c, p, wt);
}
