/* The `physics:` section: effects, the world's settings, particles,
 * distance constraints and the floor, read into the physics library's own
 * definition structs. Forces are in scene_forces.c, groups and parts in
 * scene_groups.c, the control frame in scene_control.c. */
#include "scene_read.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define WORLD(field) offsetof(mr_world_def, field)

static double dist3(const double a[3], const double b[3]) {
  double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Scene files call two effects by the thing a scene declares (a floor, a
 * control frame) rather than by the physics' name for the mechanism; the
 * physics' names are read too, and every other effect goes by them. */
static const struct {
  const char *word;
  uint32_t bit;
} file_words[] = { { "floor", MR_EFFECT_PLANES }, { "control", MR_EFFECT_FRAMES } };

const char *mr_scene_effect_name(uint32_t bit) {
  for (size_t i = 0; i < sizeof file_words / sizeof file_words[0]; i++)
    if (file_words[i].bit == bit) return file_words[i].word;
  return mr_effect_name(bit);
}

static const char *effect_at(int i) {
  return i < MR_EFFECT_COUNT ? mr_scene_effect_name(1u << i) : "unknown";
}

/* A file word, else the physics' own name ('_' reads as '-'). */
static int parse_effect(const char *word, uint32_t *bit) {
  for (size_t i = 0; i < sizeof file_words / sizeof file_words[0]; i++)
    if (strcmp(word, file_words[i].word) == 0) {
      *bit = file_words[i].bit;
      return 0;
    }
  return mr_effect_parse(word, bit);
}

static int read_effects(mr_reader *r, const mr_ynode *node) {
  if (mr_scene_read_seq(r, node, "physics.effects") != 0) return -1;
  uint32_t fx = 0;
  for (size_t i = 0; i < node->count; i++) {
    const mr_ynode *e = node->items[i];
    uint32_t bit = 0;
    if (e->kind != MR_YNODE_SCALAR || parse_effect(e->text, &bit) != 0) {
      char list[320];
      mr_scene_list_names(list, sizeof list, effect_at);
      return mr_scene_read_fail(r, e, MR_SCENE_ERR_VALUE,
                                "unknown effect '%s'; expected one of: %s",
                                e->kind == MR_YNODE_SCALAR ? e->text : "?", list);
    }
    if (fx & bit)
      return mr_scene_read_fail(r, e, MR_SCENE_ERR_VALUE, "effect '%s' is listed twice", e->text);
    fx |= bit;
  }
  r->scene->world.effects = fx;
  return 0;
}

/* §4.5 and §7: the ATS. Keys left out keep the library's defaults, which
 * are the paper's. */
static int read_ats(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {
    "dt_initial", "dt_min",           "dt_max",    "threshold_min", "threshold_max",
    "divergence", "deviation_length", "max_steps", "error_length",  "error_speed",
    "max_speed",  "dt_floor",         NULL
  };
  static const mr_scene_field fields[] = {
    { "dt_initial", MR_SCENE_FIELD_POSITIVE, WORLD(dt_initial), 0, 0 },
    { "dt_min", MR_SCENE_FIELD_POSITIVE, WORLD(dt_min), 0, 0 },
    { "dt_max", MR_SCENE_FIELD_POSITIVE, WORLD(dt_max), 0, 0 },
    { "threshold_min", MR_SCENE_FIELD_POSITIVE, WORLD(deviation_low), 0, 0 },
    { "threshold_max", MR_SCENE_FIELD_POSITIVE, WORLD(deviation_high), 0, 0 },
    { "divergence", MR_SCENE_FIELD_POSITIVE, WORLD(divergence_bound), 0, 0 },
    { "deviation_length", MR_SCENE_FIELD_POSITIVE, WORLD(deviation_length), 0, 0 },
    { "max_steps", MR_SCENE_FIELD_INT, WORLD(max_steps_per_call), 1, 100000000 },
    { "error_length", MR_SCENE_FIELD_NONNEG, WORLD(error_length), 0, 0 },
    { "error_speed", MR_SCENE_FIELD_NONNEG, WORLD(error_speed), 0, 0 },
    { "max_speed", MR_SCENE_FIELD_POSITIVE, WORLD(max_speed), 0, 0 },
    { "dt_floor", MR_SCENE_FIELD_POSITIVE, WORLD(dt_floor), 0, 0 }
  };
  mr_world_def *d = &r->scene->world;
  if (mr_scene_read_map(r, n, "physics.ats", keys) != 0 ||
      mr_scene_read_fields(r, n, fields, sizeof fields / sizeof fields[0], d) != 0)
    return -1;
  const mr_ynode *v;
  if (d->dt_min > d->dt_max)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_VALUE, "expected dt_min <= dt_max, got %g > %g",
                              d->dt_min, d->dt_max);
  if ((v = mr_scene_yaml_get(n, "dt_floor")) != NULL && d->dt_floor > d->dt_min)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected dt_floor <= dt_min (%g), got %g",
                              d->dt_min, d->dt_floor);
  if ((v = mr_scene_yaml_get(n, "dt_initial")) != NULL &&
      (d->dt_initial < d->dt_min || d->dt_initial > d->dt_max))
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected dt_min <= dt_initial <= dt_max (%g..%g), got %g", d->dt_min,
                              d->dt_max, d->dt_initial);
  if (d->deviation_low > d->deviation_high)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_VALUE,
                              "expected threshold_min <= threshold_max, got %g > %g",
                              d->deviation_low, d->deviation_high);
  if ((v = mr_scene_yaml_get(n, "divergence")) != NULL && d->divergence_bound <= d->deviation_high)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected divergence above threshold_max (%g), got %g",
                              d->deviation_high, d->divergence_bound);
  return 0;
}

/* The integrators' and solve methods' own name tables, typed for
 * mr_scene_read_choice. */
static const char *integrator_at(int i) {
  return mr_integrator_name((mr_integrator)i);
}
static const char *method_at(int i) {
  return mr_solve_method_name((mr_solve_method)i);
}
static int parse_integrator(const char *word, int *out) {
  mr_integrator x;
  int rc = mr_integrator_parse(word, &x);
  *out = rc == 0 ? (int)x : *out;
  return rc;
}
static int parse_method(const char *word, int *out) {
  mr_solve_method x;
  int rc = mr_solve_method_parse(word, &x);
  *out = rc == 0 ? (int)x : *out;
  return rc;
}

static int read_solver(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "integrator", "method",         "ks", "kd",
                                      "tolerance",  "max_iterations", NULL };
  static const mr_scene_field fields[] = {
    { "ks", MR_SCENE_FIELD_NONNEG, WORLD(ks), 0, 0 },
    { "kd", MR_SCENE_FIELD_NONNEG, WORLD(kd), 0, 0 },
    { "tolerance", MR_SCENE_FIELD_POSITIVE, WORLD(solver_tolerance), 0, 0 },
    { "max_iterations", MR_SCENE_FIELD_INT, WORLD(solver_max_iterations), 1, 1000000 }
  };
  mr_world_def *d = &r->scene->world;
  int integrator = (int)d->integrator, method = (int)d->solver;
  if (mr_scene_read_map(r, n, "physics.solver", keys) != 0 ||
      mr_scene_read_choice(r, n, "integrator", parse_integrator, integrator_at, &integrator) != 0 ||
      mr_scene_read_choice(r, n, "method", parse_method, method_at, &method) != 0 ||
      mr_scene_read_fields(r, n, fields, sizeof fields / sizeof fields[0], d) != 0)
    return -1;
  d->integrator = (mr_integrator)integrator;
  d->solver = (mr_solve_method)method;
  return 0;
}

static int read_contact(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "slop", "rest_speed", NULL };
  static const mr_scene_field fields[] = {
    { "slop", MR_SCENE_FIELD_POSITIVE, WORLD(contact_slop), 0, 0 },
    { "rest_speed", MR_SCENE_FIELD_NONNEG, WORLD(rest_speed), 0, 0 }
  };
  if (mr_scene_read_map(r, n, "physics.contact", keys) != 0 ||
      mr_scene_read_need_effect(
          r, n, MR_EFFECT_PLANES | MR_EFFECT_SELF_COLLISION | MR_EFFECT_PUPPET_COLLISION,
          "contact settings are") != 0)
    return -1;
  return mr_scene_read_fields(r, n, fields, 2, &r->scene->world);
}

static int read_string_correction(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "max_stretch", "iterations", NULL };
  static const mr_scene_field fields[] = {
    { "max_stretch", MR_SCENE_FIELD_POSITIVE, WORLD(string_max_stretch), 0, 0 },
    { "iterations", MR_SCENE_FIELD_INT, WORLD(string_correction_iterations), 1, 1000 }
  };
  if (mr_scene_read_map(r, n, "physics.string_correction", keys) != 0 ||
      mr_scene_read_need_effect(r, n, MR_EFFECT_STRING_CORRECTION, "string correction is") != 0)
    return -1;
  return mr_scene_read_fields(r, n, fields, 2, &r->scene->world);
}

/* gravity and drag: each needs its effect; without the gravity effect the
 * world has none. */
static int read_gravity_and_drag(mr_reader *r, const mr_ynode *n) {
  static const mr_scene_field drag = { "drag", MR_SCENE_FIELD_NONNEG, WORLD(drag), 0, 0 };
  mr_world_def *d = &r->scene->world;
  const mr_ynode *v;
  if ((v = mr_scene_yaml_get(n, "gravity")) != NULL &&
      (mr_scene_read_need_effect(r, v, MR_EFFECT_GRAVITY, "gravity is") != 0 ||
       mr_scene_read_vec3(r, v, "gravity", d->gravity) != 0))
    return -1;
  if (!(d->effects & MR_EFFECT_GRAVITY)) memset(d->gravity, 0, sizeof d->gravity);
  if ((v = mr_scene_yaml_get(n, "drag")) != NULL)
    return mr_scene_read_need_effect(r, v, MR_EFFECT_DRAG, "drag is") != 0 ||
                   mr_scene_read_field(r, n, &drag, d) != 0
               ? -1
               : 0;
  if (d->effects & MR_EFFECT_DRAG)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_SCHEMA,
                              "effect 'drag' is listed; expected key 'drag' (N s/m) in physics");
  return 0;
}

static int read_particle(mr_reader *r, const mr_ynode *it, void *slot) {
  static const char *const keys[] = { "name",   "position", "velocity", "mass",
                                      "radius", "pinned",   NULL };
  static const mr_scene_field fields[] = {
    { "velocity", MR_SCENE_FIELD_VEC3, offsetof(mr_particle_def, velocity), 0, 0 },
    { "radius", MR_SCENE_FIELD_NONNEG, offsetof(mr_particle_def, radius), 0, 0 }
  };
  mr_scene_particle *p = slot;
  const mr_ynode *v;
  p->def = mr_default_particle_def();
  char bare[MR_SCENE_NAME_MAX];
  if ((v = mr_scene_read_named(r, it, "a particle", keys, "particle name", bare)) == NULL)
    return -1;
  if (mr_scene_qualify(r, bare, p->name) != 0)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected '%s.%s' to fit in %d characters; shorten the puppet's or "
                              "the particle's name",
                              r->puppet, bare, MR_SCENE_NAME_MAX - 1);
  if ((v = mr_scene_read_need(r, it, "position", "a particle")) == NULL ||
      mr_scene_read_vec3(r, v, "position", p->def.position) != 0 ||
      mr_scene_read_fields(r, it, fields, 2, &p->def) != 0)
    return -1;
  for (int k = 0; k < 3; k++) p->def.position[k] += r->offset[k];
  p->def.puppet = r->puppet_id;
  if ((v = mr_scene_yaml_get(it, "pinned")) != NULL &&
      (mr_scene_read_bool(r, v, "pinned", &p->pinned) != 0 ||
       (p->pinned &&
        mr_scene_read_need_effect(r, v, MR_EFFECT_CONSTRAINTS, "a pinned particle is") != 0)))
    return -1;
  if ((v = mr_scene_read_need(r, it, "mass", "a particle")) == NULL ||
      mr_scene_read_quantity(r, v, "mass", &p->def.mass) != 0)
    return -1;
  if (!(p->def.mass > 0))
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected a positive mass in kg for particle '%s', got %g", p->name,
                              p->def.mass);
  if (mr_scene_range_check(r, v, "mass", p->def.mass) != 0) return -1;
  p->pos = mr_scene_read_pos(it);
  return 0;
}

int mr_scene_read_particles(mr_reader *r, const mr_ynode *n) {
  mr_scene *s = r->scene;
  if (n->kind == MR_YNODE_SEQ && n->count == 0)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_VALUE, "expected at least one particle");
  if (mr_scene_read_items(r, n, r->puppet ? "a puppet's particles" : "physics.particles", 0, NULL,
                          sizeof *s->particles, (void **)&s->particles, &s->n_particles,
                          read_particle) != 0)
    return -1;
  return mr_scene_index_particles(r);
}

static int read_distance(mr_reader *r, const mr_ynode *it, void *slot) {
  static const char *const keys[] = { "between", "length", NULL };
  const mr_scene *s = r->scene;
  mr_scene_distance *c = slot;
  mr_distance_def *d = &c->def;
  const mr_ynode *v;
  *d = mr_default_distance_def();
  if (mr_scene_read_map(r, it, "a constraint", keys) != 0 ||
      (v = mr_scene_read_need(r, it, "between", "a constraint")) == NULL)
    return -1;
  if (v->kind != MR_YNODE_SEQ || v->count != 2)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA,
                              "expected [particle, particle] for between");
  if (mr_scene_read_particle(r, v->items[0], &d->a) != 0 ||
      mr_scene_read_particle(r, v->items[1], &d->b) != 0)
    return -1;
  if (d->a == d->b)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "zero-length constraint: both ends are '%s'; expected two particles",
                              s->particles[d->a].name);
  d->length = dist3(s->particles[d->a].def.position, s->particles[d->b].def.position);
  const mr_ynode *len = mr_scene_yaml_get(it, "length");
  if (len != NULL && mr_scene_read_number(r, len, "length", &d->length) != 0) return -1;
  if (!(d->length > MR_SCENE_COINCIDENT_M))
    return mr_scene_read_fail(r, len ? len : it, MR_SCENE_ERR_VALUE,
                              "zero-length constraint between '%s' and '%s'; expected a length "
                              "above %g m",
                              s->particles[d->a].name, s->particles[d->b].name,
                              MR_SCENE_COINCIDENT_M);
  c->pos = mr_scene_read_pos(it);
  return 0;
}

static int read_floor(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "height", "restitution", "friction", NULL };
  static const mr_scene_field fields[] = {
    { "height", MR_SCENE_FIELD_NUMBER, offsetof(mr_plane_def, offset), 0, 0 },
    { "restitution", MR_SCENE_FIELD_UNIT, offsetof(mr_plane_def, restitution), 0, 0 },
    { "friction", MR_SCENE_FIELD_NONNEG, offsetof(mr_plane_def, friction), 0, 0 }
  };
  mr_scene_floor *f = &r->scene->floor;
  if (mr_scene_read_map(r, n, "physics.floor", keys) != 0 ||
      mr_scene_read_need_effect(r, n, MR_EFFECT_PLANES, "a floor is") != 0)
    return -1;
  f->present = true;
  f->pos = mr_scene_read_pos(n);
  if (mr_scene_read_fields(r, n, fields, 3, &f->def) != 0) return -1;
  for (size_t i = 0; i < r->scene->n_particles; i++) {
    const mr_scene_particle *p = &r->scene->particles[i];
    double bottom = p->def.position[1] - p->def.radius;
    if (bottom < f->def.offset - MR_SCENE_COINCIDENT_M)
      return mr_scene_read_fail_at(r, p->pos.line, p->pos.column, MR_SCENE_ERR_VALUE,
                                   "particle '%s' starts below the floor (y - radius = %g < %g); "
                                   "expected it on or above the floor",
                                   p->name, bottom, f->def.offset);
  }
  return 0;
}

/* The keys physics: may hold: the fixed ones around the force table's. */
static void physics_keys(const char **keys, size_t max) {
  static const char *const head[] = { "effects", "gravity",   "drag",    "ats",         "solver",
                                      "contact", "particles", "control", "constraints", "groups" };
  static const char *const tail[] = { "floor", "parts", "string_correction", "puppets", NULL };
  enum { N_TAIL = sizeof tail / sizeof tail[0] };
  size_t n = 0;
  for (size_t i = 0; i < sizeof head / sizeof head[0]; i++) keys[n++] = head[i];
  n += mr_scene_force_keys(keys + n, max - n - N_TAIL);
  for (size_t i = 0; i < N_TAIL; i++) keys[n++] = tail[i];
}

int mr_scene_read_optional(mr_reader *r, const mr_ynode *n, const char *key,
                           int (*fn)(mr_reader *, const mr_ynode *)) {
  const mr_ynode *v = mr_scene_yaml_get(n, key);
  return v != NULL ? fn(r, v) : 0;
}

int mr_scene_read_constraints(mr_reader *r, const mr_ynode *n) {
  mr_scene *s = r->scene;
  return mr_scene_read_items(r, n, r->puppet ? "a puppet's constraints" : "physics.constraints",
                             MR_EFFECT_CONSTRAINTS, "constraints are", sizeof *s->distances,
                             (void **)&s->distances, &s->n_distances, read_distance);
}

static int read_control(mr_reader *r, const mr_ynode *n) {
  if (mr_scene_read_need_effect(r, n, MR_EFFECT_FRAMES, "a control frame is") != 0) return -1;
  return mr_scene_read_control(r, n);
}

int mr_scene_read_physics(mr_reader *r, const mr_ynode *n) {
  const char *keys[40];
  physics_keys(keys, sizeof keys / sizeof keys[0]);
  if (mr_scene_read_map(r, n, "physics", keys) != 0) return -1;
  const mr_ynode *v = mr_scene_read_need(r, n, "effects", "physics");
  if (v == NULL || read_effects(r, v) != 0 || read_gravity_and_drag(r, n) != 0) return -1;
  if (mr_scene_read_optional(r, n, "ats", read_ats) != 0 ||
      mr_scene_read_optional(r, n, "solver", read_solver) != 0 ||
      mr_scene_read_optional(r, n, "contact", read_contact) != 0 ||
      mr_scene_read_optional(r, n, "string_correction", read_string_correction) != 0)
    return -1;
  /* Fixed order, whatever the order in the file: later items name earlier
   * ones, and every particle has its world id before the control points
   * take theirs after them. */
  const mr_ynode *puppets = mr_scene_yaml_get(n, "puppets");
  if ((v = mr_scene_yaml_get(n, "particles")) != NULL && mr_scene_read_particles(r, v) != 0)
    return -1;
  if (v == NULL && puppets == NULL)
    return mr_scene_read_need(r, n, "particles", "physics") ? 0 : -1;
  if (puppets != NULL && mr_scene_read_puppet_particles(r, puppets) != 0) return -1;
  if (mr_scene_read_optional(r, n, "control", read_control) != 0 ||
      (puppets != NULL && mr_scene_read_puppet_controls(r, puppets) != 0) ||
      mr_scene_read_optional(r, n, "constraints", mr_scene_read_constraints) != 0 ||
      mr_scene_read_optional(r, n, "groups", mr_scene_read_groups) != 0 ||
      mr_scene_read_forces(r, n) != 0 ||
      (puppets != NULL && mr_scene_read_puppet_items(r, puppets) != 0) ||
      mr_scene_read_optional(r, n, "floor", read_floor) != 0 ||
      mr_scene_read_optional(r, n, "parts", mr_scene_read_parts) != 0)
    return -1;
  return 0;
}
