/* Rigid groups (§5.1): particles held by static distance constraints. */
#include "scene_read.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* Below this normalised volume (or area) the members are taken as coplanar
 * (or collinear), where distance constraints no longer fix the shape. */
#define GENERAL_POSITION_MIN 1e-3
#define GROUP_MAX            64

static void sub3(const double a[3], const double b[3], double o[3]) {
  o[0] = a[0] - b[0];
  o[1] = a[1] - b[1];
  o[2] = a[2] - b[2];
}

static double norm3(const double a[3]) {
  return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

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
static int check_member(mr_reader *r, const mr_scene_group *g, int k, const mr_ynode *at) {
  const mr_scene_particle *p = r->scene->particles;
  const int *m = g->def.particles;
  const double *pk = p[m[k]].def.position;
  if (k == 2 &&
      triangle_quality(p[m[0]].def.position, p[m[1]].def.position, pk) < GENERAL_POSITION_MIN)
    return mr_scene_read_fail(r, at, MR_SCENE_ERR_VALUE,
                              "group '%s': '%s', '%s' and '%s' are collinear; expected members "
                              "in general position (§5.1)",
                              g->name, p[m[0]].name, p[m[1]].name, p[m[2]].name);
  if (k < 3) return 0;
  double best = 0;
  for (int i = 0; i < k; i++)
    for (int j = i + 1; j < k; j++)
      for (int l = j + 1; l < k; l++)
        best = fmax(best, tetra_quality(pk, p[m[i]].def.position, p[m[j]].def.position,
                                        p[m[l]].def.position));
  if (best < GENERAL_POSITION_MIN)
    return mr_scene_read_fail(r, at, MR_SCENE_ERR_VALUE,
                              "group '%s': '%s' is coplanar with every three earlier members; "
                              "expected members in general position (§5.1)",
                              g->name, p[m[k]].name);
  return 0;
}

/* The members of a group or part: a list of particles, as an owned array
 * of world ids. */
static const mr_ynode *read_members(mr_reader *r, const mr_ynode *it, const char *what,
                                    const int **ids, int *count) {
  int *m = NULL;
  const mr_ynode *v = mr_scene_read_need(r, it, "particles", what);
  int rc = v != NULL ? mr_scene_read_particle_list(r, v, what, &m, count) : -1;
  *ids = m;
  return rc == 0 ? v : NULL;
}

static int read_group(mr_reader *r, const mr_ynode *it, void *slot) {
  static const char *const keys[] = { "name", "particles", NULL };
  const mr_scene *s = r->scene;
  mr_scene_group *g = slot;
  const mr_ynode *v;
  g->def = mr_default_rigid_group_def();
  char bare[MR_SCENE_NAME_MAX];
  if ((v = mr_scene_read_named(r, it, "a group", keys, "group name", bare)) == NULL) return -1;
  if (mr_scene_qualify(r, bare, g->name) != 0)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected '%s.%s' to fit in %d characters; shorten the puppet's or "
                              "the group's name",
                              r->puppet, bare, MR_SCENE_NAME_MAX - 1);
  for (size_t j = 0; j + 1 < s->n_groups; j++)
    if (strcmp(s->groups[j].name, g->name) == 0)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                                "expected a unique group name, '%s' is already declared", g->name);
  g->pos = mr_scene_read_pos(it);
  if ((v = read_members(r, it, "a group", &g->def.particles, &g->def.count)) == NULL) return -1;
  if (v->count < 2 || v->count > GROUP_MAX)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected 2 to %d particles in group '%s', got %zu", GROUP_MAX,
                              g->name, v->count);
  for (int k = 0; k < g->def.count; k++)
    if (check_member(r, g, k, v->items[k]) != 0) return -1;
  return 0;
}

int mr_scene_read_groups(mr_reader *r, const mr_ynode *n) {
  mr_scene *s = r->scene;
  return mr_scene_read_items(r, n, r->puppet ? "a puppet's groups" : "physics.groups",
                             MR_EFFECT_CONSTRAINTS, "rigid groups are", sizeof *s->groups,
                             (void **)&s->groups, &s->n_groups, read_group);
}

static int read_part(mr_reader *r, const mr_ynode *it, void *slot) {
  static const char *const keys[] = { "particles",   "radius",   "segment_spheres",
                                      "restitution", "friction", NULL };
  static const mr_scene_field fields[] = {
    { "radius", MR_SCENE_FIELD_NONNEG, offsetof(mr_part_def, radius), 0, 0 },
    { "restitution", MR_SCENE_FIELD_UNIT, offsetof(mr_part_def, restitution), 0, 0 },
    { "friction", MR_SCENE_FIELD_NONNEG, offsetof(mr_part_def, friction), 0, 0 },
    { "segment_spheres", MR_SCENE_FIELD_INT, offsetof(mr_part_def, segment_spheres), 0, 64 }
  };
  mr_scene_part *p = slot;
  const mr_ynode *v;
  p->def = mr_default_part_def();
  if (mr_scene_read_map(r, it, "a part", keys) != 0) return -1;
  p->pos = mr_scene_read_pos(it);
  if ((v = read_members(r, it, "a part", &p->def.particles, &p->def.count)) == NULL) return -1;
  if (p->def.count == 0)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected at least one particle in a part");
  if (mr_scene_read_fields(r, it, fields, 4, &p->def) != 0) return -1;
  if (p->def.segment_spheres > 0 && p->def.count != 2)
    return mr_scene_read_fail(r, mr_scene_yaml_get(it, "segment_spheres"), MR_SCENE_ERR_VALUE,
                              "segment spheres need a part of exactly two particles");
  return 0;
}

int mr_scene_read_parts(mr_reader *r, const mr_ynode *n) {
  mr_scene *s = r->scene;
  return mr_scene_read_items(r, n, r->puppet ? "a puppet's parts" : "physics.parts",
                             MR_EFFECT_SELF_COLLISION | MR_EFFECT_PUPPET_COLLISION,
                             "collision parts are", sizeof *s->parts, (void **)&s->parts,
                             &s->n_parts, read_part);
}
