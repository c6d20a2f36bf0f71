/* physics.puppets: puppets as units. Each declares its own particles,
 * constraints, groups, parts and forces, under names qualified by the
 * puppet's ("alice.hand"), so two puppets may share one design, placed
 * apart by `offset`. The world numbers the puppets, so the §6.2 forces
 * that scale with "the mass of the entire puppet" take that puppet's
 * mass, and puppet_collision can tell one puppet from another. */
#include "scene_read.h"

#include <stdlib.h>
#include <string.h>

/* The sections a puppet may hold besides its name and placement. */
static void puppet_keys(const char **keys, size_t max) {
  static const char *const head[] = { "name",   "offset", "particles", "constraints",
                                      "groups", "parts",  "control" };
  enum { N_HEAD = sizeof head / sizeof head[0] };
  size_t n = 0;
  for (; n < N_HEAD; n++) keys[n] = head[n];
  n += mr_scene_force_keys(keys + n, max - n - 1);
  keys[n] = NULL;
}

static int read_head(mr_reader *r, const mr_ynode *it, mr_scene_puppet *p, size_t index) {
  const char *keys[32];
  puppet_keys(keys, sizeof keys / sizeof keys[0]);
  const mr_ynode *v = mr_scene_read_named(r, it, "a puppet", keys, "puppet name", p->name);
  if (v == NULL) return -1;
  if (strchr(p->name, '.') != NULL)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected a puppet name without '.', got '%s': '.' joins a "
                              "puppet's name to its parts'",
                              p->name);
  for (size_t j = 0; j < index; j++)
    if (strcmp(r->scene->puppets[j].name, p->name) == 0)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                                "expected a unique puppet name, '%s' is already declared", p->name);
  p->pos = mr_scene_read_pos(it);
  memset(r->offset, 0, sizeof r->offset);
  if ((v = mr_scene_yaml_get(it, "offset")) != NULL &&
      mr_scene_read_vec3(r, v, "offset", r->offset) != 0)
    return -1;
  r->puppet = p->name;
  return 0;
}

/* Inside puppet p; placed by its offset where what is read has a place
 * (its control frame), else unmoved. */
static void enter(mr_reader *r, const mr_scene_puppet *p, const mr_ynode *it, bool placed) {
  r->puppet = p->name;
  r->puppet_id = p->id;
  memset(r->offset, 0, sizeof r->offset);
  const mr_ynode *v = mr_scene_yaml_get(it, "offset");
  if (placed && v != NULL)
    (void)mr_scene_read_vec3(r, v, "offset", r->offset); /* read_head checked it */
}

static void leave(mr_reader *r) {
  r->puppet = NULL;
  r->puppet_id = 0;
  memset(r->offset, 0, sizeof r->offset);
}

int mr_scene_read_puppet_particles(mr_reader *r, const mr_ynode *n) {
  mr_scene *s = r->scene;
  if (mr_scene_read_seq(r, n, "physics.puppets") != 0) return -1;
  if (n->count == 0)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_VALUE, "expected at least one puppet");
  s->puppets = calloc(n->count, sizeof *s->puppets);
  if (s->puppets == NULL) return mr_scene_read_fail(r, n, MR_SCENE_ERR_NOMEM, "out of memory");
  int base = s->n_particles > 0 ? 1 : 0; /* the scene's own particles are puppet 0 */
  for (size_t i = 0; i < n->count; i++) {
    mr_scene_puppet *p = &s->puppets[i];
    s->n_puppets = i + 1;
    const mr_ynode *it = n->items[i], *v;
    if (read_head(r, it, p, i) != 0) return -1;
    p->id = base + (int)i;
    p->first = s->n_particles;
    r->puppet_id = p->id;
    if ((v = mr_scene_read_need(r, it, "particles", "a puppet")) == NULL ||
        mr_scene_read_particles(r, v) != 0)
      return -1;
    p->count = s->n_particles - p->first;
    leave(r);
  }
  return 0;
}

/* A puppet's control is read as the scene's is, its point names and its
 * pose placed with the puppet ("alice.bar", moved by offset). */
int mr_scene_read_puppet_controls(mr_reader *r, const mr_ynode *n) {
  mr_scene *s = r->scene;
  for (size_t i = 0; i < n->count && i < s->n_puppets; i++) {
    const mr_ynode *v = mr_scene_yaml_get(n->items[i], "control");
    if (v == NULL) continue;
    enter(r, &s->puppets[i], n->items[i], true);
    int rc = mr_scene_read_need_effect(r, v, MR_EFFECT_FRAMES, "a control frame is") != 0 ||
                     mr_scene_read_control(r, v) != 0
                 ? -1
                 : 0;
    leave(r);
    if (rc != 0) return -1;
  }
  return 0;
}

int mr_scene_read_puppet_items(mr_reader *r, const mr_ynode *n) {
  mr_scene *s = r->scene;
  for (size_t i = 0; i < n->count && i < s->n_puppets; i++) {
    const mr_ynode *it = n->items[i];
    enter(r, &s->puppets[i], it, false);
    int rc = mr_scene_read_optional(r, it, "constraints", mr_scene_read_constraints) != 0 ||
                     mr_scene_read_optional(r, it, "groups", mr_scene_read_groups) != 0 ||
                     mr_scene_read_forces(r, it) != 0 ||
                     mr_scene_read_optional(r, it, "parts", mr_scene_read_parts) != 0
                 ? -1
                 : 0;
    leave(r);
    if (rc != 0) return -1;
  }
  return 0;
}
