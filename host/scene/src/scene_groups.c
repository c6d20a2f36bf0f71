/* Rigid groups (§5.1): particles held by static distance constraints. */
#include "scene_read.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Below this normalised volume (or area) the members are taken as coplanar
 * (or collinear), where distance constraints no longer fix the shape. */
#define GENERAL_POSITION_MIN 1e-3
#define GROUP_MAX 64

static void sub3(const double a[3], const double b[3], double o[3]) {
  o[0] = a[0] - b[0];
  o[1] = a[1] - b[1];
  o[2] = a[2] - b[2];
}

static double norm3(const double a[3]) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

static void cross3(const double a[3], const double b[3], double o[3]) {
  o[0] = a[1] * b[2] - a[2] * b[1];
  o[1] = a[2] * b[0] - a[0] * b[2];
  o[2] = a[0] * b[1] - a[1] * b[0];
}

/* |sin| of the angle at p between q and s: 0 when collinear. */
static double triangle_quality(const double p[3], const double q[3], const double s[3]) {
  double u[3], v[3], c[3];
  sub3(q, p, u);
  sub3(s, p, v);
  cross3(u, v, c);
  double d = norm3(u) * norm3(v);
  return d > 0 ? norm3(c) / d : 0;
}

/* |det(a-p, b-p, c-p)| over the product of the edge lengths: 0 when p lies
 * in the plane of a, b, c. */
static double tetra_quality(const double p[3], const double a[3], const double b[3],
                            const double c[3]) {
  double u[3], v[3], w[3], x[3];
  sub3(a, p, u);
  sub3(b, p, v);
  sub3(c, p, w);
  cross3(v, w, x);
  double d = norm3(u) * norm3(v) * norm3(w);
  return d > 0 ? fabs(u[0] * x[0] + u[1] * x[1] + u[2] * x[2]) / d : 0;
}

/* §5.1: each new member joins three earlier members that are not coplanar
 * with it, so a group's constraints are independent. The physics library
 * picks the three; here the file is checked so that a degenerate group is
 * reported at its line. */
static int check_member(mr_reader *r, const mr_scene_group *g, size_t k, const mr_ynode *at) {
  const mr_scene *s = r->scene;
  const size_t *m = g->members;
  const double *pk = s->particles[m[k]].position;
  if (k == 2 && triangle_quality(s->particles[m[0]].position,
                                 s->particles[m[1]].position, pk) < GENERAL_POSITION_MIN)
    return mr_scene_read_fail(r, at, MR_SCENE_ERR_VALUE,
                   "group '%s': '%s', '%s' and '%s' are collinear; expected members in "
                   "general position (§5.1)",
                   g->name, s->particles[m[0]].name, s->particles[m[1]].name,
                   s->particles[m[2]].name);
  if (k < 3)
    return 0;
  double best = 0;
  for (size_t i = 0; i < k; i++)
    for (size_t j = i + 1; j < k; j++)
      for (size_t l = j + 1; l < k; l++)
        best = fmax(best, tetra_quality(pk, s->particles[m[i]].position,
                                        s->particles[m[j]].position,
                                        s->particles[m[l]].position));
  if (best < GENERAL_POSITION_MIN)
    return mr_scene_read_fail(r, at, MR_SCENE_ERR_VALUE,
                   "group '%s': '%s' is coplanar with every three earlier members; "
                   "expected members in general position (§5.1)",
                   g->name, s->particles[m[k]].name);
  return 0;
}

int mr_scene_read_groups(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"name", "particles", NULL};
  mr_scene *s = r->scene;
  if (mr_scene_read_seq(r, n, "physics.groups") != 0)
    return -1;
  if (n->count > 0 && mr_scene_read_need_effect(r, n, MR_SCENE_FX_CONSTRAINTS, "rigid groups are") != 0)
    return -1;
  s->groups = calloc(n->count ? n->count : 1, sizeof *s->groups);
  if (s->groups == NULL)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_NOMEM, "out of memory");
  for (size_t gi = 0; gi < n->count; gi++) {
    const mr_ynode *it = n->items[gi];
    mr_scene_group *g = &s->groups[gi];
    s->n_groups = gi + 1;
    const mr_ynode *v;
    if (mr_scene_read_map(r, it, "a group", keys) != 0)
      return -1;
    if ((v = mr_scene_read_need(r, it, "name", "a group")) == NULL ||
        mr_scene_read_name(r, v, "group name", g->name) != 0)
      return -1;
    for (size_t j = 0; j < gi; j++)
      if (strcmp(s->groups[j].name, g->name) == 0)
        return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                       "expected a unique group name, '%s' is already declared", g->name);
    g->pos = mr_scene_read_pos(it);
    if ((v = mr_scene_read_need(r, it, "particles", "a group")) == NULL ||
        mr_scene_read_particle_list(r, v, "a group", &g->members, &g->count) != 0)
      return -1;
    if (v->count < 2 || v->count > GROUP_MAX)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                     "expected 2 to %d particles in group '%s', got %zu", GROUP_MAX, g->name,
                     v->count);
    for (size_t k = 0; k < g->count; k++)
      if (check_member(r, g, k, v->items[k]) != 0)
        return -1;
  }
  return 0;
}

int mr_scene_read_parts(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"particles", "radius", "segment_spheres", "restitution",
                                     "friction", NULL};
  mr_scene *s = r->scene;
  if (mr_scene_read_seq(r, n, "physics.parts") != 0)
    return -1;
  if (n->count > 0 &&
      mr_scene_read_need_effect(r, n, MR_SCENE_FX_SELF_COLLISION, "collision parts are") != 0)
    return -1;
  s->parts = calloc(n->count ? n->count : 1, sizeof *s->parts);
  if (s->parts == NULL)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_NOMEM, "out of memory");
  for (size_t i = 0; i < n->count; i++) {
    const mr_ynode *it = n->items[i];
    mr_scene_part *p = &s->parts[i];
    s->n_parts = i + 1;
    const mr_ynode *v;
    if (mr_scene_read_map(r, it, "a part", keys) != 0)
      return -1;
    p->pos = mr_scene_read_pos(it);
    if ((v = mr_scene_read_need(r, it, "particles", "a part")) == NULL ||
        mr_scene_read_particle_list(r, v, "a part", &p->members, &p->count) != 0)
      return -1;
    if (p->count == 0)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected at least one particle in a part");
    p->radius = p->restitution = p->friction = NAN;
    p->segment_spheres = -1;
    double seg = -1;
    if (mr_scene_read_nonneg_key(r, it, "radius", &p->radius) != 0 ||
        mr_scene_read_nonneg_key(r, it, "restitution", &p->restitution) != 0 ||
        mr_scene_read_nonneg_key(r, it, "friction", &p->friction) != 0 ||
        mr_scene_read_nonneg_key(r, it, "segment_spheres", &seg) != 0)
      return -1;
    if (!isnan(p->restitution) && p->restitution > 1)
      return mr_scene_read_fail(r, mr_scene_yaml_get(it, "restitution"), MR_SCENE_ERR_VALUE,
                     "expected restitution between 0 and 1, got %g", p->restitution);
    if (seg >= 0) {
      if (seg != floor(seg) || seg > 64)
        return mr_scene_read_fail(r, mr_scene_yaml_get(it, "segment_spheres"), MR_SCENE_ERR_VALUE,
                       "expected a whole number of segment spheres from 0 to 64");
      if (seg > 0 && p->count != 2)
        return mr_scene_read_fail(r, mr_scene_yaml_get(it, "segment_spheres"), MR_SCENE_ERR_VALUE,
                       "segment spheres need a part of exactly two particles");
      p->segment_spheres = (int)seg;
    }
  }
  return 0;
}
