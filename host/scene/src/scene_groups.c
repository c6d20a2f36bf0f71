/* Rigid groups (§5.1): particles held by static distance constraints. */
#include "scene_read.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#define GROUP_MAX 64

/* §5.1: each new member joins three earlier members that are not coplanar
 * with it, so a group's constraints are independent. The physics' own
 * shape test (mr_rigid_group_shape) is applied to the file's positions, so
 * a group the loader passes is one the world accepts, and a degenerate one
 * is reported at its line, by its particles' names. */
static int check_shape(mr_reader *r, const mr_scene_group *g, const mr_ynode *list) {
  const mr_scene_particle *p = r->scene->particles;
  const int *m = g->def.particles;
  double xyz[3 * GROUP_MAX];
  for (int k = 0; k < g->def.count; k++)
    memcpy(&xyz[3 * k], p[m[k]].def.position, sizeof(double[3]));
  int i, j;
  mr_shape_fault f = mr_rigid_group_shape(xyz, g->def.count, &i, &j);
  if (f == MR_SHAPE_OK) return 0;
  const mr_ynode *at = i >= 0 && (size_t)i < list->count ? list->items[i] : list;
  switch (f) {
  case MR_SHAPE_COINCIDENT:
    return mr_scene_read_fail(r, at, MR_SCENE_ERR_VALUE, "group '%s': '%s' and '%s' coincide",
                              g->name, p[m[j]].name, p[m[i]].name);
  case MR_SHAPE_COLLINEAR:
    return mr_scene_read_fail(r, at, MR_SCENE_ERR_VALUE,
                              "group '%s': '%s', '%s' and '%s' are collinear; expected members "
                              "in general position (§5.1)",
                              g->name, p[m[0]].name, p[m[1]].name, p[m[2]].name);
  case MR_SHAPE_FLAT_START:
    return mr_scene_read_fail(r, at, MR_SCENE_ERR_VALUE,
                              "group '%s': '%s', '%s', '%s' and '%s' are coplanar; a group starts "
                              "with four members in general position (§5.1)",
                              g->name, p[m[0]].name, p[m[1]].name, p[m[2]].name, p[m[3]].name);
  default:
    return mr_scene_read_fail(r, at, MR_SCENE_ERR_VALUE,
                              "group '%s': '%s' is coplanar with every three earlier members; "
                              "expected members in general position (§5.1)",
                              g->name, p[m[i]].name);
  }
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
  return check_shape(r, g, v);
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
