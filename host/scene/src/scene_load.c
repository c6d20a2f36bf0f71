/* The top level of a scene file: the file itself, its sections, defaults. */
#include "scene_read.h"

#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Sections the theater will add to the same files; refusing them now keeps a
 * newer file from being half-understood by this version. */
static const char *const theater_sections[] = { "glove", "render", "audio", NULL };

static void defaults(mr_scene *s) {
  memset(s, 0, sizeof *s);
  s->world = mr_default_world_def();
  s->floor.def = mr_default_plane_def();
  s->duration = 10.0;
  s->fps = 0.0;
  s->max_steps = MR_SCENE_MAX_STEPS;
  s->stage = mr_default_stage_def();
  mr_scene_expect *e = &s->expect;
  e->finite = true;
  e->max_deviation = e->min_mean_dt = e->min_string_stretch = NAN;
  e->max_speed = e->max_penetration = e->max_string_stretch = NAN;
  e->settle = e->creep = e->jitter = NAN;
  e->resets_min = e->resets_max = -1;
}

/* sim.present: land (the paper's) or interpolate. */
static int read_present(mr_reader *r, const mr_ynode *v) {
  bool land = v->kind == MR_YNODE_SCALAR && strcmp(v->text, "land") == 0;
  bool interpolate = v->kind == MR_YNODE_SCALAR && strcmp(v->text, "interpolate") == 0;
  if (!land && !interpolate)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected present land or interpolate");
  r->scene->interpolate = interpolate;
  return 0;
}

static int read_sim(mr_reader *r, const mr_ynode *sim) {
  static const char *const keys[] = { "duration", "fps", "max_steps", "present", NULL };
  static const mr_scene_field fields[] = {
    { "duration", MR_SCENE_FIELD_POSITIVE, offsetof(mr_scene, duration), 0, 0 },
    { "fps", MR_SCENE_FIELD_POSITIVE, offsetof(mr_scene, fps), 0, 0 }
  };
  if (mr_scene_read_map(r, sim, "sim", keys) != 0 ||
      mr_scene_read_fields(r, sim, fields, 2, r->scene) != 0)
    return -1;
  const mr_ynode *v = mr_scene_yaml_get(sim, "present");
  if (v != NULL && read_present(r, v) != 0) return -1;
  if ((v = mr_scene_yaml_get(sim, "max_steps")) == NULL) return 0;
  long n;
  if (mr_scene_read_long(r, v, "max_steps", &n) != 0) return -1;
  if (n < 1 || n > 1000000000L)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected max_steps between 1 and 1000000000, got %ld", n);
  r->scene->max_steps = n;
  return 0;
}

/* The ratio of particles a and b (both dynamic), heavier over lighter. */
static void worse_pair(const mr_scene *s, int a, int b, double *worst, int *heavy, int *light) {
  if (a < 0 || b < 0 || (size_t)a >= s->n_particles || (size_t)b >= s->n_particles) return;
  double ma = s->particles[a].def.mass, mb = s->particles[b].def.mass;
  double r = ma >= mb ? ma / mb : mb / ma;
  if (r > *worst) {
    *worst = r;
    *heavy = ma >= mb ? a : b;
    *light = ma >= mb ? b : a;
  }
}

/* A mass ratio across a constraint (or within a rigid group) that the
 * solve cannot honour (MR_MAX_MASS_RATIO, mr_physics.h) is a load error
 * naming the two particles, not a run that resets forever. */
static int check_mass_ratios(mr_reader *r) {
  const mr_scene *s = r->scene;
  double worst = 1.0;
  int heavy = -1, light = -1;
  for (size_t i = 0; i < s->n_distances; i++)
    worse_pair(s, s->distances[i].def.a, s->distances[i].def.b, &worst, &heavy, &light);
  for (size_t g = 0; g < s->n_groups; g++) {
    const mr_rigid_group_def *d = &s->groups[g].def;
    for (int i = 0; i < d->count; i++)
      for (int j = i + 1; j < d->count; j++)
        worse_pair(s, d->particles[i], d->particles[j], &worst, &heavy, &light);
  }
  if (!(worst > MR_MAX_MASS_RATIO)) return 0;
  const mr_scene_particle *h = &s->particles[heavy], *l = &s->particles[light];
  return mr_scene_read_fail_at(
      r, l->pos.line, l->pos.column, MR_SCENE_ERR_VALUE,
      "particle '%s' (%g kg) is joined to particle '%s' (%g kg, line %d): a mass ratio of %.3g, "
      "past the %g the constraint solve can honour; expected masses closer together",
      l->name, l->def.mass, h->name, h->def.mass, h->pos.line, worst, MR_MAX_MASS_RATIO);
}

static int read_root(mr_reader *r, const mr_ynode *root) {
  mr_scene *s = r->scene;
  if (root == NULL)
    return mr_scene_read_fail_at(r, 1, 1, MR_SCENE_ERR_SCHEMA,
                                 "expected a mapping with a 'physics' section, the file is empty");
  if (root->kind != MR_YNODE_MAP)
    return mr_scene_read_fail(
        r, root, MR_SCENE_ERR_SCHEMA,
        "expected a mapping with a 'physics' section at the top level, got a %s",
        mr_scene_yaml_kind_name(root->kind));
  for (size_t i = 0; i < root->count; i++) {
    const mr_ynode *key = root->items[2 * i];
    for (const char *const *t = theater_sections; *t; t++)
      if (strcmp(key->text, *t) == 0)
        return mr_scene_read_fail(
            r, key, MR_SCENE_ERR_SCHEMA,
            "section '%s' is reserved for the theater and not supported "
            "by this version; expected one of: format, name, sim, physics, mapping, expect, "
            "models, lights, stage, camera",
            key->text);
  }
  static const char *const keys[] = { "format", "name",   "sim",   "physics", "mapping", "expect",
                                      "models", "lights", "stage", "camera",  NULL };
  if (mr_scene_read_map(r, root, "the scene", keys) != 0) return -1;
  const mr_ynode *v = mr_scene_yaml_get(root, "format");
  if (v != NULL) {
    long format = 0;
    if (mr_scene_read_long(r, v, "format", &format) != 0) return -1;
    if (format != 1)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                                "expected format: 1 (the only version this program reads), got %ld",
                                format);
  }
  if ((v = mr_scene_yaml_get(root, "name")) != NULL) {
    if (v->kind != MR_YNODE_SCALAR)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA, "expected a text for name");
    snprintf(s->name, sizeof s->name, "%s", v->text);
  }
  if ((v = mr_scene_yaml_get(root, "sim")) != NULL && read_sim(r, v) != 0) return -1;
  const mr_ynode *physics = mr_scene_read_need(r, root, "physics", "the scene");
  if (physics == NULL) return -1;
  if (mr_scene_read_physics(r, physics) != 0 || check_mass_ratios(r) != 0) return -1;
  if (mr_scene_read_optional(r, root, "mapping", mr_scene_read_mappings) != 0) return -1;
  if ((v = mr_scene_yaml_get(root, "expect")) != NULL && mr_scene_read_expect(r, v) != 0) return -1;
  return mr_scene_read_stage(r, root);
}

static mr_scene_status load_text(const char *name, const char *text, size_t len, mr_scene *scene,
                                 mr_scene_error *err, int unframed) {
  defaults(scene);
  memset(err, 0, sizeof *err);
  mr_reader r = { .file = name, .err = err, .scene = scene, .unframed = unframed };
  scene->path = malloc(strlen(name) + 1);
  if (scene->path == NULL) {
    mr_scene_read_fail_at(&r, 0, 0, MR_SCENE_ERR_NOMEM, "out of memory");
    return err->status;
  }
  strcpy(scene->path, name);
  if (scene->name[0] == '\0') snprintf(scene->name, sizeof scene->name, "%s", name);

  mr_ydoc doc;
  mr_yerror yerr;
  if (mr_scene_yaml_parse(text, len, &doc, &yerr) != 0) {
    mr_scene_read_fail_at(&r, yerr.line, yerr.column, MR_SCENE_ERR_SYNTAX, "%s", yerr.message);
    mr_scene_free(scene);
    return err->status;
  }
  int rc = read_root(&r, doc.root);
  mr_scene_yaml_free(&doc);
  mr_scene_index_free(&r);
  if (rc != 0) {
    mr_scene_free(scene);
    return err->status ? err->status : MR_SCENE_ERR_SCHEMA;
  }
  return MR_SCENE_OK;
}

mr_scene_status mr_scene_load_text(const char *name, const char *text, size_t len, mr_scene *scene,
                                   mr_scene_error *err) {
  return load_text(name, text, len, scene, err, 0);
}

static mr_scene_status load(const char *path, mr_scene *scene, mr_scene_error *err, int unframed) {
  defaults(scene);
  memset(err, 0, sizeof *err);
  mr_reader r = { .file = path, .err = err, .scene = scene };
  FILE *f = fopen(path, "rb");
  if (f == NULL) {
    mr_scene_read_fail_at(&r, 0, 0, MR_SCENE_ERR_IO, "expected a readable scene file: %s",
                          strerror(errno));
    return err->status;
  }
  size_t cap = 1 << 16, len = 0;
  char *buf = malloc(cap);
  int io_error = 0;
  while (buf != NULL) {
    if (len == cap) {
      char *b = cap < ((size_t)64 << 20) ? realloc(buf, cap * 2) : NULL;
      if (b == NULL) {
        free(buf);
        buf = NULL;
        break;
      }
      buf = b;
      cap *= 2;
    }
    size_t n = fread(buf + len, 1, cap - len, f);
    len += n;
    if (n == 0) {
      io_error = ferror(f) ? errno : 0;
      break;
    }
  }
  fclose(f);
  if (buf == NULL) {
    mr_scene_read_fail_at(&r, 0, 0, MR_SCENE_ERR_NOMEM,
                          "expected a scene file under 64 MiB that fits in memory");
    return err->status;
  }
  if (io_error != 0) {
    free(buf);
    mr_scene_read_fail_at(&r, 0, 0, MR_SCENE_ERR_IO, "expected a readable scene file: %s",
                          strerror(io_error));
    return err->status;
  }
  mr_scene_status st = load_text(path, buf, len, scene, err, unframed);
  free(buf);
  return st;
}

mr_scene_status mr_scene_load(const char *path, mr_scene *scene, mr_scene_error *err) {
  return load(path, scene, err, 0);
}

mr_scene_status mr_scene_load_unframed(const char *path, mr_scene *scene, mr_scene_error *err) {
  return load(path, scene, err, 1);
}

void mr_scene_free(mr_scene *s) {
  free(s->path);
  free(s->particles);
  free(s->distances);
  for (size_t i = 0; i < s->n_groups; i++) free((int *)s->groups[i].def.particles);
  free(s->groups);
  for (size_t i = 0; i < s->n_parts; i++) free((int *)s->parts[i].def.particles);
  free(s->parts);
  free(s->puppets);
  free(s->mappings);
  free(s->forces);
  free(s->control_points);
  for (size_t k = 0; k < s->n_frames; k++) free(s->frames[k].track.keys);
  free(s->frames);
  free(s->expect.watch);
  mr_scene_stage_free(s);
  memset(s, 0, sizeof *s);
}

size_t mr_scene_find_particle(const mr_scene *s, const char *name) {
  for (size_t i = 0; i < s->n_particles; i++)
    if (strcmp(s->particles[i].name, name) == 0) return i;
  return (size_t)-1;
}

size_t mr_scene_find_control_point(const mr_scene *s, const char *name) {
  for (size_t i = 0; i < s->n_control_points; i++)
    if (strcmp(s->control_points[i].name, name) == 0) return i;
  return (size_t)-1;
}
