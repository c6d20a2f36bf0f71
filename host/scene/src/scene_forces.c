/* Applied forces (§5.1, §6.2), one table keyed by the physics' force kinds
 * (MR_FORCE_KINDS in mr_physics.h). A rest length the file leaves out is the
 * distance at the start (the physics' default); other numbers left out keep
 * the physics' defaults.
 *
 * To add a force kind: its line in MR_FORCE_KINDS and its evaluation in the
 * physics, then here its reader, its row in `kinds` (which also adds it to
 * a world) and its member of mr_scene_force's union in mr_scene.h. */
#include "scene_read.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#define FIELD(type, field) offsetof(type, field)

/* The point a force acts on: a particle, never a control point. */
static int read_acted(mr_reader *r, const mr_ynode *it, const char *what, int *id) {
  const mr_ynode *v = mr_scene_read_need(r, it, "acted", what);
  if (v == NULL || mr_scene_read_point(r, v, id) != 0) return -1;
  if (mr_scene_is_control_id(r->scene, *id))
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected a particle to act on, not a control point");
  return 0;
}

/* The point under `key`, which must differ from `other` (`label` names it). */
static int read_other(mr_reader *r, const mr_ynode *it, const char *key, const char *what,
                      int other, const char *label, int *id) {
  const mr_ynode *v = mr_scene_read_need(r, it, key, what);
  if (v == NULL || mr_scene_read_point(r, v, id) != 0) return -1;
  if (*id == other)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected %s to be a different point",
                              label);
  return 0;
}

static int read_spring(mr_reader *r, const mr_ynode *it, mr_scene_force *f) {
  static const mr_scene_field fields[] = {
    { "rest", MR_SCENE_FIELD_NONNEG, FIELD(mr_spring_def, rest_length), 0, 0 },
    { "stiffness", MR_SCENE_FIELD_NONNEG, FIELD(mr_spring_def, stiffness), 0, 0 },
    { "damping", MR_SCENE_FIELD_NONNEG, FIELD(mr_spring_def, damping), 0, 0 }
  };
  mr_spring_def *d = &f->def.spring;
  *d = mr_default_spring_def();
  if (mr_scene_read_between(r, it, "a spring", &d->a, &d->b) != 0) return -1;
  if (mr_scene_is_control_id(r->scene, d->a) || mr_scene_is_control_id(r->scene, d->b))
    return mr_scene_read_fail(
        r, mr_scene_yaml_get(it, "between"), MR_SCENE_ERR_VALUE,
        "expected two particles for a spring (use strings for control points)");
  return mr_scene_read_fields(r, it, fields, 3, d);
}

/* The physics' string modes (spring, taut), typed for mr_scene_read_choice. */
static const char *string_mode_at(int i) {
  return mr_string_mode_name((mr_string_mode)i);
}
static int parse_string_mode(const char *word, int *out) {
  mr_string_mode m;
  int rc = mr_string_mode_parse(word, &m);
  *out = rc == 0 ? (int)m : *out;
  return rc;
}

static int read_string(mr_reader *r, const mr_ynode *it, mr_scene_force *f) {
  static const mr_scene_field fields[] = {
    { "rest", MR_SCENE_FIELD_NONNEG, FIELD(mr_string_def, rest_length), 0, 0 },
    { "stiffness", MR_SCENE_FIELD_POSITIVE, FIELD(mr_string_def, stiffness), 0, 0 },
    { "damping", MR_SCENE_FIELD_NONNEG, FIELD(mr_string_def, damping), 0, 0 }
  };
  mr_string_def *d = &f->def.string;
  *d = mr_default_string_def();
  const mr_ynode *v;
  int mode = (int)d->mode;
  if ((v = mr_scene_read_need(r, it, "from", "a string")) == NULL ||
      mr_scene_read_control_point(r, v, &d->frame_particle) != 0 ||
      (v = mr_scene_read_need(r, it, "to", "a string")) == NULL ||
      mr_scene_read_particle(r, v, &d->puppet_particle) != 0 ||
      mr_scene_read_choice(r, it, "mode", parse_string_mode, string_mode_at, &mode) != 0)
    return -1;
  d->mode = (mr_string_mode)mode;
  return mr_scene_read_fields(r, it, fields, 3, d);
}

static int read_sine_spring(mr_reader *r, const mr_ynode *it, mr_scene_force *f) {
  static const mr_scene_field fields[] = {
    { "rest", MR_SCENE_FIELD_NONNEG, FIELD(mr_sine_spring_def, rest_length), 0, 0 },
    { "max_force", MR_SCENE_FIELD_POSITIVE, FIELD(mr_sine_spring_def, max_force), 0, 0 },
    { "reach", MR_SCENE_FIELD_POSITIVE, FIELD(mr_sine_spring_def, reach), 0, 0 },
    { "damping", MR_SCENE_FIELD_NONNEG, FIELD(mr_sine_spring_def, damping), 0, 0 }
  };
  mr_sine_spring_def *d = &f->def.sine_spring;
  *d = mr_default_sine_spring_def();
  if (mr_scene_read_between(r, it, "a sine spring", &d->a, &d->b) != 0) return -1;
  return mr_scene_read_fields(r, it, fields, 4, d);
}

static int read_antigravity(mr_reader *r, const mr_ynode *it, mr_scene_force *f) {
  static const mr_scene_field fields[] = {
    { "fraction", MR_SCENE_FIELD_NONNEG, FIELD(mr_antigravity_def, fraction), 0, 0 },
    { "max_scale", MR_SCENE_FIELD_POSITIVE, FIELD(mr_antigravity_def, max_scale), 0, 0 }
  };
  static const char *const what = "an antigravity force";
  mr_antigravity_def *d = &f->def.antigravity;
  *d = mr_default_antigravity_def();
  if (read_acted(r, it, what, &d->acted) != 0 ||
      read_other(r, it, "trigger", what, d->acted, "the trigger", &d->trigger) != 0)
    return -1;
  return mr_scene_read_fields(r, it, fields, 2, d);
}

static int read_triggered(mr_reader *r, const mr_ynode *it, mr_scene_force *f) {
  static const mr_scene_field fields[] = {
    { "gain", MR_SCENE_FIELD_NONNEG, FIELD(mr_triggered_def, gain), 0, 0 },
    { "max_force", MR_SCENE_FIELD_POSITIVE, FIELD(mr_triggered_def, max_force), 0, 0 }
  };
  static const char *const what = "a triggered force";
  mr_triggered_def *d = &f->def.triggered;
  *d = mr_default_triggered_def();
  if (read_acted(r, it, what, &d->acted) != 0 ||
      read_other(r, it, "control", what, d->acted, "control", &d->control) != 0 ||
      read_other(r, it, "trigger", what, d->control, "the trigger", &d->trigger) != 0)
    return -1;
  return mr_scene_read_fields(r, it, fields, 2, d);
}

/* The add calls, one per kind, each taking its member of the union. */
static mr_status add_spring(mr_world *w, const mr_scene_force *f, int *id) {
  return mr_world_add_spring(w, &f->def.spring, id);
}
static mr_status add_string(mr_world *w, const mr_scene_force *f, int *id) {
  return mr_world_add_string(w, &f->def.string, id);
}
static mr_status add_sine_spring(mr_world *w, const mr_scene_force *f, int *id) {
  return mr_world_add_sine_spring(w, &f->def.sine_spring, id);
}
static mr_status add_antigravity(mr_world *w, const mr_scene_force *f, int *id) {
  return mr_world_add_antigravity(w, &f->def.antigravity, id);
}
static mr_status add_triggered(mr_world *w, const mr_scene_force *f, int *id) {
  return mr_world_add_triggered(w, &f->def.triggered, id);
}

typedef struct force_kind {
  uint32_t kind;        /* the physics' effect bit of the kind */
  const char *key;      /* the section under physics: */
  const char *what;     /* one item, for messages */
  const char *declared; /* "... declared but effect ... is not listed" */
  const char *keys[8];  /* the keys an item may have */
  int (*read)(mr_reader *r, const mr_ynode *item, mr_scene_force *f);
  mr_status (*add)(mr_world *w, const mr_scene_force *f, int *id);
  const char *refused; /* "the physics refused ..." */
} force_kind;

static const force_kind kinds[] = {
  { MR_EFFECT_SPRINGS,
    "springs",
    "a spring",
    "springs are",
    { "between", "rest", "stiffness", "damping", NULL },
    read_spring,
    add_spring,
    "the spring" },
  { MR_EFFECT_STRINGS,
    "strings",
    "a string",
    "strings are",
    { "from", "to", "rest", "stiffness", "damping", "mode", NULL },
    read_string,
    add_string,
    "the string" },
  { MR_EFFECT_SINE_SPRINGS,
    "sine_springs",
    "a sine spring",
    "sine springs are",
    { "between", "rest", "max_force", "reach", "damping", NULL },
    read_sine_spring,
    add_sine_spring,
    "the sine spring" },
  { MR_EFFECT_ANTIGRAVITY,
    "antigravity",
    "an antigravity force",
    "antigravity is",
    { "acted", "trigger", "fraction", "max_scale", NULL },
    read_antigravity,
    add_antigravity,
    "the antigravity force" },
  { MR_EFFECT_TRIGGERED,
    "triggered",
    "a triggered force",
    "triggered action forces are",
    { "acted", "control", "trigger", "gain", "max_force", NULL },
    read_triggered,
    add_triggered,
    "the triggered force" },
};
enum { N_KINDS = sizeof kinds / sizeof kinds[0] };

static const force_kind *kind_of(uint32_t kind) {
  for (int i = 0; i < N_KINDS; i++)
    if (kinds[i].kind == kind) return &kinds[i];
  return NULL;
}

mr_status mr_scene_force_add(mr_world *w, const mr_scene_force *f, int *id, const char **what) {
  const force_kind *k = kind_of(f->kind);
  *what = k != NULL ? k->refused : "the force";
  return k != NULL ? k->add(w, f, id) : MR_ERR_ARG;
}

size_t mr_scene_force_keys(const char **out, size_t max) {
  size_t n = 0;
  for (; n < N_KINDS && n < max; n++) out[n] = kinds[n].key;
  return n;
}

static int read_force(mr_reader *r, const mr_ynode *it, const force_kind *k) {
  mr_scene *s = r->scene;
  mr_scene_force *f = &s->forces[s->n_forces++];
  f->kind = k->kind;
  f->pos = mr_scene_read_pos(it);
  if (mr_scene_read_map(r, it, k->what, k->keys) != 0) return -1;
  return k->read(r, it, f);
}

/* One array for every kind, filled kind by kind in table order (within
 * the scene's own forces, then within each puppet's). */
int mr_scene_read_forces(mr_reader *r, const mr_ynode *physics) {
  mr_scene *s = r->scene;
  size_t total = 0;
  for (int i = 0; i < N_KINDS; i++) {
    const mr_ynode *n = mr_scene_yaml_get(physics, kinds[i].key);
    total += n != NULL && n->kind == MR_YNODE_SEQ ? n->count : 0;
  }
  /* Appends: each puppet adds its forces after the scene's own. */
  mr_scene_force *grown = realloc(s->forces, (s->n_forces + total + 1) * sizeof *s->forces);
  if (grown == NULL) return mr_scene_read_fail(r, physics, MR_SCENE_ERR_NOMEM, "out of memory");
  s->forces = grown;
  memset(s->forces + s->n_forces, 0, (total + 1) * sizeof *s->forces);
  for (int i = 0; i < N_KINDS; i++) {
    const mr_ynode *n = mr_scene_yaml_get(physics, kinds[i].key);
    if (n == NULL) continue;
    if (mr_scene_read_seq(r, n, kinds[i].key) != 0 ||
        (n->count > 0 && mr_scene_read_need_effect(r, n, kinds[i].kind, kinds[i].declared) != 0))
      return -1;
    for (size_t j = 0; j < n->count; j++)
      if (read_force(r, n->items[j], &kinds[i]) != 0) return -1;
  }
  return 0;
}
