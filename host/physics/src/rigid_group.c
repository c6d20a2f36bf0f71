/* Rigid groups (§5.1): particles held by fixed distances. A tetrahedral
 * clique of four non-coplanar particles is the smallest group with a unique
 * inertia; every further particle is linked to exactly three particles
 * already in the group and not coplanar with it. Three links fix a point in
 * 3D, a fourth would be redundant and make J M⁻¹ Jᵀ singular, which is why
 * §5.1 stops at three. */
#include "internal.h"

#include <math.h>
#include <stdlib.h>

static double dist(const double *x, int a, int b) {
  double d[3] = { x[3 * a] - x[3 * b], x[3 * a + 1] - x[3 * b + 1], x[3 * a + 2] - x[3 * b + 2] };
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* The point of index k of a group: ids[k] in x, or the k-th of x. */
static const double *at(const double *x, const int *ids, int k) {
  return &x[3 * (ids ? ids[k] : k)];
}

/* |det(b−a, c−a, d−a)| / (|b−a| |c−a| |d−a|): 0 when coplanar, 1 for three
 * orthogonal edges. Scale-free, so one threshold fits any model size. */
static double flatness(const double *a, const double *b, const double *c, const double *d) {
  double e[3][3];
  const double *o[3] = { b, c, d };
  double norm = 1.0;
  for (int i = 0; i < 3; i++) {
    for (int k = 0; k < 3; k++) e[i][k] = o[i][k] - a[k];
    norm *= sqrt(e[i][0] * e[i][0] + e[i][1] * e[i][1] + e[i][2] * e[i][2]);
  }
  double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
               e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
               e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  return norm > 0 ? fabs(det) / norm : 0.0;
}

/* |(b−a) × (c−a)| / (|b−a| |c−a|): 0 when collinear. */
static double straightness(const double *a, const double *b, const double *c) {
  double u[3], v[3];
  for (int k = 0; k < 3; k++) {
    u[k] = b[k] - a[k];
    v[k] = c[k] - a[k];
  }
  double cr[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                   u[0] * v[1] - u[1] * v[0] };
  double n =
      sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) * sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return n > 0 ? sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]) / n : 0.0;
}

static double gap(const double *a, const double *b) {
  double d[3] = { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

static const double min_shape = MR_GROUP_MIN_SHAPE;

/* Point i's three partners among the points before it: the nearest triple
 * not coplanar with it (short links stay well conditioned). 0, or -1 if
 * every triple is coplanar with it. best[] holds indices into the group. */
static int choose_partners(const double *x, const int *ids, int i, int best[3]) {
  double best_len = INFINITY;
  const double *p = at(x, ids, i);
  best[0] = best[1] = best[2] = -1;
  for (int a = 0; a < i; a++)
    for (int b = a + 1; b < i; b++)
      for (int c = b + 1; c < i; c++) {
        if (flatness(p, at(x, ids, a), at(x, ids, b), at(x, ids, c)) < min_shape) continue;
        double len = gap(p, at(x, ids, a)) + gap(p, at(x, ids, b)) + gap(p, at(x, ids, c));
        if (len < best_len) {
          best_len = len;
          best[0] = a;
          best[1] = b;
          best[2] = c;
        }
      }
  return best[0] < 0 ? -1 : 0;
}

static mr_shape_fault shape_of(const double *x, const int *ids, int count, int *fi, int *fj) {
  *fi = *fj = -1;
  for (int i = 0; i < count; i++)
    for (int j = 0; j < i; j++)
      if (!(gap(at(x, ids, i), at(x, ids, j)) > 1e-9)) {
        *fi = i;
        *fj = j;
        return MR_SHAPE_COINCIDENT;
      }
  if (count >= 3 && straightness(at(x, ids, 0), at(x, ids, 1), at(x, ids, 2)) < min_shape) {
    *fi = 2;
    return MR_SHAPE_COLLINEAR;
  }
  if (count >= 4 &&
      flatness(at(x, ids, 0), at(x, ids, 1), at(x, ids, 2), at(x, ids, 3)) < min_shape) {
    *fi = 3;
    return MR_SHAPE_FLAT_START;
  }
  int partners[3];
  for (int i = 4; i < count; i++)
    if (choose_partners(x, ids, i, partners) != 0) {
      *fi = i;
      return MR_SHAPE_FLAT_MEMBER;
    }
  return MR_SHAPE_OK;
}

mr_shape_fault mr_rigid_group_shape(const double *xyz, int count, int *i, int *j) {
  int a = -1, b = -1;
  mr_shape_fault f = xyz != NULL && count > 0 ? shape_of(xyz, NULL, count, &a, &b) : MR_SHAPE_OK;
  if (i) *i = a;
  if (j) *j = b;
  return f;
}

static int link(mr_world *w, int a, int b, int *n) {
  /* Two frame particles are already rigid through their frame; a row
   * between them would have no mass to act on. */
  if (w->inv_mass[a] == 0.0 && w->inv_mass[b] == 0.0) return 0;
  if (mr_distance_add_internal(w, a, b, dist(w->x, a, b), NULL) != 0) return -1;
  (*n)++;
  return 0;
}

/* The particles must exist and be distinct, and their places pass the
 * shape test a loader uses too (mr_rigid_group_shape). */
static mr_status check_shape(mr_world *w, const int *ids, int count, const char *what) {
  for (int i = 0; i < count; i++) {
    if (mr_check_particle(w, ids[i], what) != 0) return MR_ERR_ID;
    for (int j = 0; j < i; j++)
      if (ids[i] == ids[j])
        return mr_fail(w, MR_ERR_ARG, "%s: particle %d listed twice", what, ids[i]);
  }
  int i, j;
  switch (shape_of(w->x, ids, count, &i, &j)) {
  case MR_SHAPE_OK:
    return MR_OK;
  case MR_SHAPE_COINCIDENT:
    return mr_fail(w, MR_ERR_DEGENERATE, "%s: particles %d and %d coincide", what, ids[j], ids[i]);
  case MR_SHAPE_COLLINEAR:
    return mr_fail(w, MR_ERR_DEGENERATE, "%s: particles %d, %d, %d are collinear", what, ids[0],
                   ids[1], ids[2]);
  case MR_SHAPE_FLAT_START:
    return mr_fail(w, MR_ERR_DEGENERATE,
                   "%s: the first four particles (%d, %d, %d, %d) are coplanar; a rigid group "
                   "starts with a tetrahedron",
                   what, ids[0], ids[1], ids[2], ids[3]);
  default:
    return mr_fail(w, MR_ERR_DEGENERATE, "%s: particle %d is coplanar with every triple before it",
                   what, ids[i]);
  }
}

mr_status mr_rigid_group_build(mr_world *w, const int *ids, int count, int *first, int *n) {
  const char *what = "mr_world_add_rigid_group";
  *first = w->distances.n;
  *n = 0;
  mr_status s = check_shape(w, ids, count, what);
  if (s != MR_OK) return s;
  /* Choose every later particle's three partners before adding anything, so
   * a failure leaves the world unchanged. */
  int(*partners)[3] = NULL;
  if (count > 4) {
    partners = malloc((size_t)count * sizeof *partners);
    if (!partners) return mr_fail(w, MR_ERR_NOMEM, "%s: out of memory", what);
    for (int i = 4; i < count; i++)
      if (choose_partners(w->x, ids, i, partners[i]) != 0) {
        free(partners);
        return mr_fail(w, MR_ERR_DEGENERATE,
                       "%s: particle %d is coplanar with every triple before it", what, ids[i]);
      }
  }
  int clique = count < 4 ? count : 4;
  int ok = 0;
  for (int i = 0; i < clique && ok == 0; i++)
    for (int j = i + 1; j < clique && ok == 0; j++) ok = link(w, ids[i], ids[j], n);
  for (int i = 4; i < count && ok == 0; i++)
    for (int k = 0; k < 3 && ok == 0; k++) ok = link(w, ids[i], ids[partners[i][k]], n);
  free(partners);
  if (ok != 0) return mr_fail(w, MR_ERR_NOMEM, "%s: out of memory", what);
  return MR_OK;
}

mr_rigid_group_def mr_default_rigid_group_def(void) {
  return (mr_rigid_group_def){ .cookie = MR_DEF_COOKIE };
}

mr_status mr_world_add_rigid_group(mr_world *w, const mr_rigid_group_def *def, int *out_id) {
  const char *what = "mr_world_add_rigid_group";
  mr_status s = MR_ADD_CHECK(w, def, MR_EFFECT_CONSTRAINTS, what);
  if (s != MR_OK) return s;
  if (!def->particles && def->count > 0) return mr_fail(w, MR_ERR_ARG, "%s: NULL particles", what);
  if (def->count < 2)
    return mr_fail(w, MR_ERR_ARG, "%s: needs at least 2 particles (got %d)", what, def->count);
  int first, n;
  s = mr_rigid_group_build(w, def->particles, def->count, &first, &n);
  if (s != MR_OK) {
    w->distances.n = first; /* drop links added before an allocation failure */
    return s;
  }
  if (out_id) *out_id = w->n_groups;
  w->n_groups++;
  return MR_OK;
}
