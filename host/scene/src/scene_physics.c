/* The `physics:` section: effects, settings, particles and constraints.
 * Forces are in scene_forces.c, groups and parts in scene_groups.c, the
 * control frame in scene_control.c. */
#include "mr_solve_method.h"
#include "scene_read.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Two particles closer than this are one point: every constraint or force
 * between them has no direction (a zero row of J, §5.2). */
#define COINCIDENT_M 1e-6

static double dist3(const double a[3], const double b[3]) {
  double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return sqrt(dx * dx + dy * dy + dz * dz);
}

static int read_effects(mr_reader *r, const mr_ynode *node) {
  if (rd_seq(r, node, "physics.effects") != 0)
    return -1;
  unsigned fx = 0;
  for (size_t i = 0; i < node->count; i++) {
    const mr_ynode *e = node->items[i];
    unsigned bit = MR_SCENE_FX_COUNT;
    if (e->kind == MR_YNODE_SCALAR)
      for (unsigned b = 0; b < MR_SCENE_FX_COUNT; b++)
        if (strcmp(e->text, mr_scene_effect_name(b)) == 0)
          bit = b;
    if (bit == MR_SCENE_FX_COUNT) {
      char list[256] = "";
      size_t used = 0;
      for (unsigned b = 0; b < MR_SCENE_FX_COUNT; b++)
        used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", b ? ", " : "",
                                 mr_scene_effect_name(b));
      return rd_fail(r, e, MR_SCENE_ERR_VALUE, "unknown effect '%s'; expected one of: %s",
                     e->kind == MR_YNODE_SCALAR ? e->text : "?", list);
    }
    if (fx & (1u << bit))
      return rd_fail(r, e, MR_SCENE_ERR_VALUE, "effect '%s' is listed twice", e->text);
    fx |= 1u << bit;
  }
  r->scene->effects = fx;
  return 0;
}

static int read_long_key(mr_reader *r, const mr_ynode *n, const char *key, long lo, long hi,
                         long *out) {
  const mr_ynode *v = mr_ynode_get(n, key);
  if (v == NULL)
    return 0;
  long x;
  if (rd_long(r, v, key, &x) != 0)
    return -1;
  if (x < lo || x > hi)
    return rd_fail(r, v, MR_SCENE_ERR_VALUE, "expected %s between %ld and %ld, got %ld", key,
                   lo, hi, x);
  *out = x;
  return 0;
}

/* §4.5 and §7: the ATS. Unset values keep the library's defaults, which are
 * the paper's. */
static int read_ats(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"dt_initial",    "dt_min",     "dt_max",
                                     "threshold_min", "threshold_max", "divergence",
                                     "deviation_length", "max_steps", NULL};
  if (rd_map(r, n, "physics.ats", keys) != 0)
    return -1;
  mr_scene_settings *a = &r->scene->settings;
  if (rd_positive_key(r, n, "dt_initial", &a->dt_initial) != 0 ||
      rd_positive_key(r, n, "dt_min", &a->dt_min) != 0 ||
      rd_positive_key(r, n, "dt_max", &a->dt_max) != 0 ||
      rd_positive_key(r, n, "threshold_min", &a->threshold_min) != 0 ||
      rd_positive_key(r, n, "threshold_max", &a->threshold_max) != 0 ||
      rd_positive_key(r, n, "divergence", &a->divergence) != 0 ||
      rd_positive_key(r, n, "deviation_length", &a->deviation_length) != 0 ||
      read_long_key(r, n, "max_steps", 1, 100000000, &a->max_steps) != 0)
    return -1;
  double lo = isnan(a->dt_min) ? 0.01 : a->dt_min;
  double hi = isnan(a->dt_max) ? 0.05 : a->dt_max;
  if (lo > hi)
    return rd_fail(r, n, MR_SCENE_ERR_VALUE, "expected dt_min <= dt_max, got %g > %g", lo, hi);
  if (!isnan(a->dt_initial) && (a->dt_initial < lo || a->dt_initial > hi))
    return rd_fail(r, mr_ynode_get(n, "dt_initial"), MR_SCENE_ERR_VALUE,
                   "expected dt_min <= dt_initial <= dt_max (%g..%g), got %g", lo, hi,
                   a->dt_initial);
  double tlo = isnan(a->threshold_min) ? 1e-4 : a->threshold_min;
  double thi = isnan(a->threshold_max) ? 1e-2 : a->threshold_max;
  if (tlo > thi)
    return rd_fail(r, n, MR_SCENE_ERR_VALUE,
                   "expected threshold_min <= threshold_max, got %g > %g", tlo, thi);
  if (!isnan(a->divergence) && a->divergence <= thi)
    return rd_fail(r, mr_ynode_get(n, "divergence"), MR_SCENE_ERR_VALUE,
                   "expected divergence above threshold_max (%g), got %g", thi,
                   a->divergence);
  return 0;
}

static int read_word(mr_reader *r, const mr_ynode *n, const char *key,
                     const char *const *choices, char *out, size_t size) {
  const mr_ynode *v = mr_ynode_get(n, key);
  if (v == NULL)
    return 0;
  for (const char *const *c = choices; *c; c++)
    if (v->kind == MR_YNODE_SCALAR && strcmp(v->text, *c) == 0 && strlen(*c) < size) {
      strcpy(out, *c);
      return 0;
    }
  char list[160] = "";
  size_t used = 0;
  for (const char *const *c = choices; *c; c++)
    used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", c == choices ? "" : ", ",
                             *c);
  return rd_fail(r, v, MR_SCENE_ERR_VALUE, "expected %s to be one of: %s, got '%s'", key,
                 list, v->kind == MR_YNODE_SCALAR ? v->text : "?");
}

static int read_solver(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"integrator", "method", "ks", "kd",
                                     "tolerance",  "max_iterations", NULL};
  static const char *const integrators[] = {"rk4", "midpoint", "semi-implicit-euler",
                                            "euler", NULL};
  const char *const *methods = mr_solve_method_names();
  if (rd_map(r, n, "physics.solver", keys) != 0)
    return -1;
  mr_scene_settings *s = &r->scene->settings;
  if (read_word(r, n, "integrator", integrators, s->integrator, sizeof s->integrator) != 0 ||
      read_word(r, n, "method", methods, s->method, sizeof s->method) != 0 ||
      rd_nonneg_key(r, n, "ks", &s->ks) != 0 || rd_nonneg_key(r, n, "kd", &s->kd) != 0 ||
      rd_positive_key(r, n, "tolerance", &s->tolerance) != 0 ||
      read_long_key(r, n, "max_iterations", 1, 1000000, &s->max_iterations) != 0)
    return -1;
  return 0;
}

static int read_contact(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"slop", "rest_speed", NULL};
  if (rd_map(r, n, "physics.contact", keys) != 0 ||
      rd_need_effect(r, n, MR_SCENE_FX_FLOOR | MR_SCENE_FX_SELF_COLLISION, "contact settings are") != 0)
    return -1;
  return rd_positive_key(r, n, "slop", &r->scene->settings.contact_slop) != 0 ||
                 rd_nonneg_key(r, n, "rest_speed", &r->scene->settings.rest_speed) != 0
             ? -1
             : 0;
}

static int read_string_correction(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"max_stretch", "iterations", NULL};
  if (rd_map(r, n, "physics.string_correction", keys) != 0 ||
      rd_need_effect(r, n, MR_SCENE_FX_STRING_CORRECTION, "string correction is") != 0)
    return -1;
  return rd_positive_key(r, n, "max_stretch", &r->scene->settings.string_max_stretch) != 0 ||
                 read_long_key(r, n, "iterations", 1, 1000,
                               &r->scene->settings.string_iterations) != 0
             ? -1
             : 0;
}

static int read_particles(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"name", "position", "velocity", "mass",
                                     "radius", "pinned", NULL};
  mr_scene *s = r->scene;
  if (rd_seq(r, n, "physics.particles") != 0)
    return -1;
  if (n->count == 0)
    return rd_fail(r, n, MR_SCENE_ERR_VALUE, "expected at least one particle");
  s->particles = calloc(n->count, sizeof *s->particles);
  if (s->particles == NULL)
    return rd_fail(r, n, MR_SCENE_ERR_NOMEM, "out of memory");
  for (size_t i = 0; i < n->count; i++) {
    const mr_ynode *it = n->items[i];
    mr_scene_particle *p = &s->particles[i];
    if (rd_map(r, it, "a particle", keys) != 0)
      return -1;
    const mr_ynode *v;
    if ((v = rd_need(r, it, "name", "a particle")) == NULL ||
        rd_name(r, v, "particle name", p->name) != 0)
      return -1;
    if (mr_scene_find_particle(s, p->name) != (size_t)-1)
      return rd_fail(r, v, MR_SCENE_ERR_VALUE,
                     "expected a unique particle name, '%s' is already declared", p->name);
    if ((v = rd_need(r, it, "position", "a particle")) == NULL ||
        rd_vec3(r, v, "position", p->position) != 0)
      return -1;
    if (rd_vec3_key(r, it, "velocity", p->velocity) != 0 ||
        rd_nonneg_key(r, it, "radius", &p->radius) != 0)
      return -1;
    if ((v = mr_ynode_get(it, "pinned")) != NULL) {
      if (rd_bool(r, v, "pinned", &p->pinned) != 0)
        return -1;
      if (p->pinned && rd_need_effect(r, v, MR_SCENE_FX_CONSTRAINTS, "a pinned particle is") != 0)
        return -1;
    }
    if ((v = rd_need(r, it, "mass", "a particle")) == NULL ||
        rd_number(r, v, "mass", &p->mass) != 0)
      return -1;
    if (!(p->mass > 0))
      return rd_fail(r, v, MR_SCENE_ERR_VALUE,
                     "expected a positive mass in kg for particle '%s', got %g", p->name,
                     p->mass);
    p->pos = rd_pos(it);
    s->n_particles = i + 1;
  }
  for (size_t i = 0; i < s->n_particles; i++)
    for (size_t j = 0; j < i; j++)
      if (dist3(s->particles[i].position, s->particles[j].position) < COINCIDENT_M)
        return rd_fail_at(r, s->particles[i].pos.line, s->particles[i].pos.column,
                          MR_SCENE_ERR_VALUE,
                          "particle '%s' coincides with particle '%s' (line %d); expected "
                          "distinct positions",
                          s->particles[i].name, s->particles[j].name,
                          s->particles[j].pos.line);
  return 0;
}

static int read_constraints(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"between", "length", NULL};
  mr_scene *s = r->scene;
  if (rd_seq(r, n, "physics.constraints") != 0)
    return -1;
  if (n->count > 0 && rd_need_effect(r, n, MR_SCENE_FX_CONSTRAINTS, "constraints are") != 0)
    return -1;
  s->distances = calloc(n->count ? n->count : 1, sizeof *s->distances);
  if (s->distances == NULL)
    return rd_fail(r, n, MR_SCENE_ERR_NOMEM, "out of memory");
  for (size_t i = 0; i < n->count; i++) {
    const mr_ynode *it = n->items[i];
    mr_scene_distance *d = &s->distances[i];
    const mr_ynode *v;
    if (rd_map(r, it, "a constraint", keys) != 0 ||
        (v = rd_need(r, it, "between", "a constraint")) == NULL)
      return -1;
    if (v->kind != MR_YNODE_SEQ || v->count != 2)
      return rd_fail(r, v, MR_SCENE_ERR_SCHEMA, "expected [particle, particle] for between");
    if (rd_particle_ref(r, v->items[0], &d->a) != 0 ||
        rd_particle_ref(r, v->items[1], &d->b) != 0)
      return -1;
    if (d->a == d->b)
      return rd_fail(r, v, MR_SCENE_ERR_VALUE,
                     "zero-length constraint: both ends are '%s'; expected two particles",
                     s->particles[d->a].name);
    d->length = dist3(s->particles[d->a].position, s->particles[d->b].position);
    const mr_ynode *len = mr_ynode_get(it, "length");
    if (len != NULL && rd_number(r, len, "length", &d->length) != 0)
      return -1;
    if (!(d->length > COINCIDENT_M))
      return rd_fail(r, len ? len : it, MR_SCENE_ERR_VALUE,
                     "zero-length constraint between '%s' and '%s'; expected a length above "
                     "%g m",
                     s->particles[d->a].name, s->particles[d->b].name, COINCIDENT_M);
    d->pos = rd_pos(it);
    s->n_distances = i + 1;
  }
  return 0;
}

static int read_floor(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"height", "restitution", "friction", NULL};
  mr_scene_floor *f = &r->scene->floor;
  if (rd_map(r, n, "physics.floor", keys) != 0)
    return -1;
  if (rd_need_effect(r, n, MR_SCENE_FX_FLOOR, "a floor is") != 0)
    return -1;
  f->present = true;
  f->pos = rd_pos(n);
  f->restitution = 0.5;
  f->friction = 0.3;
  if (rd_number_key(r, n, "height", &f->height) != 0 ||
      rd_nonneg_key(r, n, "restitution", &f->restitution) != 0 ||
      rd_nonneg_key(r, n, "friction", &f->friction) != 0)
    return -1;
  if (f->restitution > 1)
    return rd_fail(r, mr_ynode_get(n, "restitution"), MR_SCENE_ERR_VALUE,
                   "expected restitution between 0 and 1, got %g", f->restitution);
  for (size_t i = 0; i < r->scene->n_particles; i++) {
    const mr_scene_particle *p = &r->scene->particles[i];
    if (p->position[1] - p->radius < f->height - COINCIDENT_M)
      return rd_fail_at(r, p->pos.line, p->pos.column, MR_SCENE_ERR_VALUE,
                        "particle '%s' starts below the floor (y - radius = %g < %g); "
                        "expected it on or above the floor",
                        p->name, p->position[1] - p->radius, f->height);
  }
  return 0;
}

int mr_scene_read_physics(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {
      "effects", "gravity",     "drag",      "ats",         "solver",
      "contact", "particles",   "control",   "constraints", "groups",
      "springs", "strings",     "sine_springs", "antigravity", "triggered",
      "floor",   "parts",       "string_correction", NULL};
  mr_scene *s = r->scene;
  if (rd_map(r, n, "physics", keys) != 0)
    return -1;
  const mr_ynode *v = rd_need(r, n, "effects", "physics");
  if (v == NULL || read_effects(r, v) != 0)
    return -1;
  if ((v = mr_ynode_get(n, "gravity")) != NULL) {
    if (rd_need_effect(r, v, MR_SCENE_FX_GRAVITY, "gravity is") != 0 ||
        rd_vec3(r, v, "gravity", s->gravity) != 0)
      return -1;
  }
  if ((v = mr_ynode_get(n, "drag")) != NULL) {
    if (rd_need_effect(r, v, MR_SCENE_FX_DRAG, "drag is") != 0 ||
        rd_nonneg_key(r, n, "drag", &s->drag) != 0)
      return -1;
  } else if (s->effects & MR_SCENE_FX_DRAG) {
    return rd_fail(r, n, MR_SCENE_ERR_SCHEMA,
                   "effect 'drag' is listed; expected key 'drag' (N s/m) in physics");
  }
  if (!(s->effects & MR_SCENE_FX_GRAVITY))
    memset(s->gravity, 0, sizeof s->gravity);
  if ((v = mr_ynode_get(n, "ats")) != NULL && read_ats(r, v) != 0)
    return -1;
  if ((v = mr_ynode_get(n, "solver")) != NULL && read_solver(r, v) != 0)
    return -1;
  if ((v = mr_ynode_get(n, "contact")) != NULL && read_contact(r, v) != 0)
    return -1;
  if ((v = mr_ynode_get(n, "string_correction")) != NULL && read_string_correction(r, v) != 0)
    return -1;
  /* Fixed order, whatever the order in the file: later items name earlier
   * ones. */
  if ((v = rd_need(r, n, "particles", "physics")) == NULL || read_particles(r, v) != 0)
    return -1;
  if ((v = mr_ynode_get(n, "control")) != NULL) {
    if (rd_need_effect(r, v, MR_SCENE_FX_CONTROL, "a control frame is") != 0 ||
        mr_scene_read_control(r, v) != 0)
      return -1;
  }
  if ((v = mr_ynode_get(n, "constraints")) != NULL && read_constraints(r, v) != 0)
    return -1;
  if ((v = mr_ynode_get(n, "groups")) != NULL && mr_scene_read_groups(r, v) != 0)
    return -1;
  if (mr_scene_read_forces(r, n) != 0)
    return -1;
  if ((v = mr_ynode_get(n, "floor")) != NULL && read_floor(r, v) != 0)
    return -1;
  if ((v = mr_ynode_get(n, "parts")) != NULL && mr_scene_read_parts(r, v) != 0)
    return -1;
  return 0;
}
