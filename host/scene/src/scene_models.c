/* models: what the stage draws, each bound to particles in one of the
 * paper's display modes (§3.3): particle, link, rigid group, and freeform
 * (the mode the paper left unfinished). */
#include "scene_read.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int mr_scene_stage_reserve_models(mr_reader *r, const mr_ynode *at, size_t more) {
  mr_stage_def *d = &r->scene->stage;
  if (r->models_cap - d->n_models >= more) return 0;
  size_t cap = d->n_models + more;
  mr_model_def *m = cap <= SIZE_MAX / sizeof *m ? realloc(d->models, cap * sizeof *m) : NULL;
  if (m == NULL) return mr_scene_read_fail(r, at, MR_SCENE_ERR_NOMEM, "out of memory");
  d->models = m;
  r->models_cap = cap;
  return 0;
}

mr_model_def *mr_scene_stage_add_model(mr_reader *r, const mr_ynode *at) {
  mr_stage_def *d = &r->scene->stage;
  /* A model is about a kilobyte: grown by half, not by one (a copy of
   * the whole array per model), nor doubled (up to twice the memory). */
  if (d->n_models == r->models_cap &&
      mr_scene_stage_reserve_models(r, at, d->n_models < 8 ? 8 : d->n_models / 2) != 0)
    return NULL;
  d->models[d->n_models] = mr_default_model_def();
  return &d->models[d->n_models++];
}

/* The built-in shapes: a file is a key of its own, not a shape. */
static const char *shape_word(int i) {
  return mr_shape_name((mr_shape)(i + 1));
}

static int shape_parse(const char *word, int *out) {
  mr_shape s;
  if (mr_shape_parse(word, &s) != 0 || s == MR_SHAPE_FILE) return -1;
  *out = (int)s;
  return 0;
}

static const char *mode_word(int i) {
  return mr_display_mode_name((mr_display_mode)i);
}

static int mode_parse(const char *word, int *out) {
  mr_display_mode m;
  if (mr_display_mode_parse(word, &m) != 0) return -1;
  *out = (int)m;
  return 0;
}

static const char *orient_word(int i) {
  return i == MR_RIGID_CONFIGURATION ? "configuration"
         : i == MR_RIGID_INITIAL     ? "initial"
                                     : "unknown";
}

static int orient_parse(const char *word, int *out) {
  if (strcmp(word, "configuration") == 0)
    *out = MR_RIGID_CONFIGURATION;
  else if (strcmp(word, "initial") == 0)
    *out = MR_RIGID_INITIAL;
  else
    return -1;
  return 0;
}

/* file: found along the model search path (scene_search.c). */
static int read_file(mr_reader *r, const mr_ynode *v, mr_model_def *m) {
  if (v->kind != MR_YNODE_SCALAR || v->text[0] == '\0')
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA, "expected a model file's path for file");
  if (mr_scene_model_find(r->scene->path, v->text, m->path, sizeof m->path, m->looked,
                          sizeof m->looked) != 0)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected a model path under %d characters (with the scene's "
                              "folder)",
                              MR_STAGE_PATH_MAX);
  m->shape = MR_SHAPE_FILE;
  return 0;
}

/* shape: or file:, exactly one; then scale, position and rotation. */
static int read_mesh(mr_reader *r, const mr_ynode *it, mr_model_def *m) {
  const mr_ynode *shape = mr_scene_yaml_get(it, "shape"), *file = mr_scene_yaml_get(it, "file");
  if ((shape == NULL) == (file == NULL))
    return mr_scene_read_fail(r, shape ? file : it, MR_SCENE_ERR_SCHEMA,
                              "model '%s' has %s; expected exactly one of shape (a built-in "
                              "mesh) or file (a model file)",
                              m->name, shape ? "both shape and file" : "neither shape nor file");
  int s = 0;
  if (shape != NULL) {
    if (mr_scene_read_choice(r, it, "shape", shape_parse, shape_word, &s) != 0) return -1;
    m->shape = (mr_shape)s;
  } else if (read_file(r, file, m) != 0) {
    return -1;
  }
  const mr_ynode *v = mr_scene_yaml_get(it, "scale");
  if (v != NULL && v->kind == MR_YNODE_SEQ) {
    if (mr_scene_read_vec3(r, v, "scale", m->scale) != 0) return -1;
  } else if (v != NULL) {
    if (mr_scene_read_number(r, v, "scale", &m->scale[0]) != 0) return -1;
    m->scale[1] = m->scale[2] = m->scale[0];
  }
  double position[3] = { 0, 0, 0 }, rotation[3] = { 0, 0, 0 };
  if ((v = mr_scene_yaml_get(it, "position")) != NULL &&
      mr_scene_read_vec3(r, v, "position", position) != 0)
    return -1;
  if ((v = mr_scene_yaml_get(it, "rotation")) != NULL &&
      mr_scene_read_vec3(r, v, "rotation", rotation) != 0)
    return -1;
  m->place = mr_pose_from_euler_deg(position, rotation);
  return 0;
}

/* A material: {color: [r, g, b] or [r, g, b, a], roughness, metallic, emissive}. */
static int read_material(mr_reader *r, const mr_ynode *n, mr_material_def *k) {
  static const char *const keys[] = { "color", "roughness", "metallic", "emissive", NULL };
  static const char *const unit[2] = { "roughness", "metallic" };
  *k = mr_default_material_def();
  if (mr_scene_read_map(r, n, "a material", keys) != 0) return -1;
  const mr_ynode *v = mr_scene_yaml_get(n, "color");
  if (v != NULL) {
    if (v->kind != MR_YNODE_SEQ || (v->count != 3 && v->count != 4))
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA,
                                "expected [r, g, b] or [r, g, b, a] for a material's color");
    for (size_t i = 0; i < v->count; i++) {
      double c;
      if (mr_scene_read_number(r, v->items[i], "color", &c) != 0) return -1;
      k->base_color[i] = (float)c;
    }
  }
  for (int i = 0; i < 2; i++) {
    double x;
    if ((v = mr_scene_yaml_get(n, unit[i])) == NULL) continue;
    if (mr_scene_read_number(r, v, unit[i], &x) != 0) return -1;
    *(i == 0 ? &k->roughness : &k->metallic) = (float)x;
  }
  if ((v = mr_scene_yaml_get(n, "emissive")) != NULL &&
      mr_scene_read_rgb(r, v, "emissive", k->emissive) != 0)
    return -1;
  return 0;
}

static int read_materials(mr_reader *r, const mr_ynode *it, mr_model_def *m) {
  const mr_ynode *one = mr_scene_yaml_get(it, "material"),
                 *many = mr_scene_yaml_get(it, "materials");
  if (one != NULL && many != NULL)
    return mr_scene_read_fail(r, many, MR_SCENE_ERR_SCHEMA,
                              "model '%s' has both material and materials; expected one", m->name);
  if (one != NULL) {
    m->n_materials = 1;
    return read_material(r, one, &m->materials[0]);
  }
  if (many == NULL) return 0;
  if (mr_scene_read_seq(r, many, "materials") != 0) return -1;
  if (many->count < 1 || many->count > MR_STAGE_MAX_MATERIALS)
    return mr_scene_read_fail(r, many, MR_SCENE_ERR_VALUE,
                              "expected 1 to %d materials for model '%s', got %zu",
                              MR_STAGE_MAX_MATERIALS, m->name, many->count);
  for (size_t i = 0; i < many->count; i++) {
    if (read_material(r, many->items[i], &m->materials[i]) != 0) return -1;
    m->n_materials = (int)i + 1;
  }
  return 0;
}

/* Where point id (a particle or a control point) is at the start. */
static void start_of(const mr_scene *s, int id, double out[3]) {
  if (!mr_scene_is_control_id(s, id)) {
    memcpy(out, s->particles[id].def.position, 3 * sizeof(double));
    return;
  }
  size_t j = (size_t)id - s->n_particles;
  mr_pose pose;
  mr_scene_frame_pose_at(s, s->control_points[j].frame, 0, &pose);
  mr_scene_control_point_world(s, j, &pose, out);
}

/* The keys that belong to one display mode only. */
static const struct {
  const char *key;
  mr_display_mode mode;
} mode_keys[] = { { "particle", MR_DISPLAY_PARTICLE }, { "between", MR_DISPLAY_LINK },
                  { "group", MR_DISPLAY_RIGID },       { "particles", MR_DISPLAY_RIGID },
                  { "orientation", MR_DISPLAY_RIGID }, { "bones", MR_DISPLAY_FREEFORM },
                  { "puppet", MR_DISPLAY_FREEFORM },   { "influences", MR_DISPLAY_FREEFORM } };

static int check_mode_keys(mr_reader *r, const mr_ynode *it, const mr_model_def *m) {
  for (size_t i = 0; i < it->count; i++) {
    const mr_ynode *key = it->items[2 * i];
    for (size_t k = 0; k < sizeof mode_keys / sizeof mode_keys[0]; k++)
      if (strcmp(key->text, mode_keys[k].key) == 0 && mode_keys[k].mode != m->display)
        return mr_scene_read_fail(r, key, MR_SCENE_ERR_SCHEMA,
                                  "key '%s' is for display %s; model '%s' is displayed %s",
                                  key->text, mr_display_mode_name(mode_keys[k].mode), m->name,
                                  mr_display_mode_name(m->display));
  }
  return 0;
}

/* A link: two distinct points. */
static int read_link(mr_reader *r, const mr_ynode *it, mr_model_def *m) {
  const mr_ynode *v = mr_scene_read_need(r, it, "between", "a link model");
  if (v == NULL) return -1;
  if (v->kind != MR_YNODE_SEQ || v->count != 2)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "link model '%s' needs two points; expected between: [a, b]%s",
                              m->name, v->kind == MR_YNODE_SEQ && v->count == 1 ? ", got one" : "");
  if (mr_scene_read_point(r, v->items[0], &m->particles[0]) != 0 ||
      mr_scene_read_point(r, v->items[1], &m->particles[1]) != 0)
    return -1;
  if (m->particles[0] == m->particles[1])
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "link model '%s' has both ends on '%s'; expected two points", m->name,
                              mr_scene_point_name(r->scene, m->particles[0]));
  return 0;
}

/* Three points that are no two on one spot and not on one line at the
 * start, or the rigid model has no orientation (§3.3). */
static int check_rigid(mr_reader *r, const mr_ynode *at, const mr_model_def *m) {
  double p[3][3], a[3], b[3], c[3];
  for (int i = 0; i < 3; i++) start_of(r->scene, m->particles[i], p[i]);
  for (int i = 0; i < 3; i++) {
    a[i] = p[1][i] - p[0][i];
    b[i] = p[2][i] - p[0][i];
  }
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
  double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  double lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  double lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  const char *how = la < MR_SCENE_COINCIDENT_M || lb < MR_SCENE_COINCIDENT_M ? "coincide"
                    : !(lc > 1e-6 * la * lb)                                 ? "lie on one line"
                                                                             : NULL;
  if (how == NULL) return 0;
  return mr_scene_read_fail(r, at, MR_SCENE_ERR_VALUE,
                            "rigid model '%s': '%s', '%s' and '%s' %s at the start; expected "
                            "three points that span a plane",
                            m->name, mr_scene_point_name(r->scene, m->particles[0]),
                            mr_scene_point_name(r->scene, m->particles[1]),
                            mr_scene_point_name(r->scene, m->particles[2]), how);
}

static int read_rigid_group(mr_reader *r, const mr_ynode *v, mr_model_def *m) {
  const mr_scene *s = r->scene;
  char name[MR_SCENE_NAME_MAX];
  if (mr_scene_read_name(r, v, "a group", name) != 0) return -1;
  for (size_t g = 0; g < s->n_groups; g++) {
    if (strcmp(s->groups[g].name, name) != 0) continue;
    if (s->groups[g].def.count < 3)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                                "group '%s' has %d particles; a rigid model needs three", name,
                                s->groups[g].def.count);
    memcpy(m->particles, s->groups[g].def.particles, 3 * sizeof(int));
    return 0;
  }
  return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                            "expected the name of a group declared under groups, got '%s'", name);
}

static int read_rigid(mr_reader *r, const mr_ynode *it, mr_model_def *m) {
  const mr_ynode *g = mr_scene_yaml_get(it, "group"), *p = mr_scene_yaml_get(it, "particles");
  if ((g == NULL) == (p == NULL))
    return mr_scene_read_fail(r, g ? p : it, MR_SCENE_ERR_SCHEMA,
                              "rigid model '%s' has %s; expected exactly one of group or "
                              "particles",
                              m->name,
                              g ? "both group and particles" : "neither group nor particles");
  int orient = (int)m->orient;
  if (mr_scene_read_choice(r, it, "orientation", orient_parse, orient_word, &orient) != 0)
    return -1;
  m->orient = (mr_rigid_orient)orient;
  if (g != NULL) return read_rigid_group(r, g, m) != 0 ? -1 : check_rigid(r, g, m);
  if (p->kind != MR_YNODE_SEQ || p->count != 3)
    return mr_scene_read_fail(r, p, MR_SCENE_ERR_VALUE,
                              "rigid model '%s' needs three points; expected particles: [a, b, c]",
                              m->name);
  for (int i = 0; i < 3; i++)
    if (mr_scene_read_point(r, p->items[i], &m->particles[i]) != 0) return -1;
  return check_rigid(r, p, m);
}

/* Freeform: the bones, by name or a whole puppet, at their start places. */
static int read_freeform(mr_reader *r, const mr_ynode *it, mr_model_def *m) {
  static const mr_scene_field inf = { "influences", MR_SCENE_FIELD_INT,
                                      offsetof(mr_model_def, influences), 1,
                                      MR_SKIN_MAX_INFLUENCES };
  const mr_scene *s = r->scene;
  const mr_ynode *b = mr_scene_yaml_get(it, "bones"), *p = mr_scene_yaml_get(it, "puppet");
  if ((b == NULL) == (p == NULL))
    return mr_scene_read_fail(r, b ? p : it, MR_SCENE_ERR_SCHEMA,
                              "freeform model '%s' has %s; expected exactly one of bones or "
                              "puppet",
                              m->name, b ? "both bones and puppet" : "neither bones nor puppet");
  if (mr_scene_read_field(r, it, &inf, m) != 0) return -1;
  int *ids = NULL, n = 0;
  if (b != NULL) {
    int rc = mr_scene_read_particle_list(r, b, "a freeform model's bones", &ids, &n);
    m->bones = ids;
    if (rc != 0) return -1;
    if (n < 1)
      return mr_scene_read_fail(r, b, MR_SCENE_ERR_VALUE,
                                "freeform model '%s' needs at least one bone", m->name);
  } else {
    char name[MR_SCENE_NAME_MAX];
    size_t k = 0;
    if (mr_scene_read_name(r, p, "a puppet", name) != 0) return -1;
    while (k < s->n_puppets && strcmp(s->puppets[k].name, name) != 0) k++;
    if (k == s->n_puppets)
      return mr_scene_read_fail(r, p, MR_SCENE_ERR_VALUE,
                                "expected the name of a puppet declared under puppets, got '%s'",
                                name);
    n = (int)s->puppets[k].count;
    m->bones = ids = malloc((n > 0 ? (size_t)n : 1) * sizeof *ids);
    if (ids == NULL) return mr_scene_read_fail(r, p, MR_SCENE_ERR_NOMEM, "out of memory");
    for (int i = 0; i < n; i++) ids[i] = (int)(s->puppets[k].first + (size_t)i);
  }
  double *rest = malloc(3 * (n > 0 ? (size_t)n : 1) * sizeof *rest);
  m->bones_rest = rest;
  if (rest == NULL) return mr_scene_read_fail(r, it, MR_SCENE_ERR_NOMEM, "out of memory");
  for (int i = 0; i < n; i++) start_of(s, ids[i], &rest[3 * i]);
  m->n_bones = n;
  return 0;
}

static int read_binding(mr_reader *r, const mr_ynode *it, mr_model_def *m) {
  int mode = (int)m->display;
  if (mr_scene_read_choice(r, it, "display", mode_parse, mode_word, &mode) != 0) return -1;
  m->display = (mr_display_mode)mode;
  if (check_mode_keys(r, it, m) != 0) return -1;
  switch (m->display) {
  case MR_DISPLAY_PARTICLE: {
    const mr_ynode *v = mr_scene_read_need(r, it, "particle", "a particle model");
    return v == NULL ? -1 : mr_scene_read_point(r, v, &m->particles[0]);
  }
  case MR_DISPLAY_LINK:
    return read_link(r, it, m);
  case MR_DISPLAY_RIGID:
    return read_rigid(r, it, m);
  case MR_DISPLAY_FREEFORM:
    return read_freeform(r, it, m);
  }
  return -1;
}

static int read_model(mr_reader *r, const mr_ynode *it) {
  static const char *const keys[] = { "name",       "shape",       "file",     "scale",
                                      "position",   "rotation",    "material", "materials",
                                      "display",    "particle",    "between",  "group",
                                      "particles",  "orientation", "bones",    "puppet",
                                      "influences", "shadow",      NULL };
  const mr_stage_def *d = &r->scene->stage;
  char name[MR_SCENE_NAME_MAX];
  const mr_ynode *v = mr_scene_read_named(r, it, "a model", keys, "a model", name);
  if (v == NULL) return -1;
  for (size_t i = 0; i < d->n_models; i++)
    if (strcmp(d->models[i].name, name) == 0)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                                "a second model named '%s' (the first is at line %d); expected "
                                "unique names",
                                name, d->models[i].pos.line);
  mr_model_def *m = mr_scene_stage_add_model(r, it);
  if (m == NULL) return -1;
  snprintf(m->name, sizeof m->name, "%s", name);
  m->pos = (mr_stage_pos){ it->line, it->column };
  const mr_ynode *shadow = mr_scene_yaml_get(it, "shadow");
  if (read_mesh(r, it, m) != 0 || read_materials(r, it, m) != 0 || read_binding(r, it, m) != 0 ||
      (shadow != NULL && mr_scene_read_bool(r, shadow, "shadow", &m->cast_shadow) != 0))
    return -1;
  return 0;
}

int mr_scene_read_models(mr_reader *r, const mr_ynode *models) {
  if (mr_scene_read_seq(r, models, "models") != 0) return -1;
  for (size_t i = 0; i < models->count; i++)
    if (read_model(r, models->items[i]) != 0) return -1;
  return 0;
}
