/* What the physics implies for the stage: the strings drawn as lines and
 * the control frames as wooden bars or lines (the rigging the puppeteer
 * sees), the collision spheres, shown on request (the sphere tree's
 * leaves, §4.4), the floor where
 * the physics has it, and, for a scene without models:, models that show
 * every particle and constraint, so that every scene draws. */
#include "scene_read.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int strings_as_lines(mr_reader *r) {
  mr_scene *s = r->scene;
  size_t n = 0;
  for (size_t i = 0; i < s->n_forces; i++) n += s->forces[i].kind == MR_EFFECT_STRINGS;
  int *pairs = malloc((2 * n + 1) * sizeof *pairs);
  if (pairs == NULL) return mr_scene_read_fail_at(r, 0, 0, MR_SCENE_ERR_NOMEM, "out of memory");
  s->stage.strings = pairs;
  for (size_t i = 0; i < s->n_forces; i++) {
    if (s->forces[i].kind != MR_EFFECT_STRINGS) continue;
    *pairs++ = s->forces[i].def.string.frame_particle;
    *pairs++ = s->forces[i].def.string.puppet_particle;
  }
  s->stage.n_strings = n;
  return 0;
}

static int frames_as_lines(mr_reader *r) {
  mr_scene *s = r->scene;
  int *count = malloc((s->n_frames + 1) * sizeof *count);
  int *pts = malloc((s->n_control_points + 1) * sizeof *pts);
  s->stage.frame_point_count = count;
  s->stage.frame_points = pts;
  if (count == NULL || pts == NULL)
    return mr_scene_read_fail_at(r, 0, 0, MR_SCENE_ERR_NOMEM, "out of memory");
  for (size_t k = 0; k < s->n_frames; k++) {
    const mr_scene_frame *f = &s->frames[k];
    count[k] = (int)f->n_points;
    for (size_t i = 0; i < f->n_points; i++) *pts++ = (int)(s->n_particles + f->first_point + i);
  }
  s->stage.n_frames = s->n_frames;
  return 0;
}

/* Appends as much of text as fits in name[size] after its first *used
 * bytes, keeping it NUL-terminated. */
static void append(char *name, size_t size, size_t *used, const char *text) {
  size_t n = strlen(text);
  if (n > size - 1 - *used) n = size - 1 - *used;
  memcpy(name + *used, text, n);
  *used += n;
  name[*used] = '\0';
}

/* A model of the stage's own making: its name ("kind:a-b", cut to fit)
 * carries a ':' that no scene name can, so it never meets one of the
 * file's. Built without printf: a scene of 100 000 particles makes
 * 200 000 of them. */
static mr_model_def *own_model(mr_reader *r, const char *kind, const char *a, const char *b,
                               mr_shape shape, const float rgb[3]) {
  mr_model_def *m = mr_scene_stage_add_model(r, NULL);
  if (m == NULL) return NULL;
  size_t used = 0;
  append(m->name, sizeof m->name, &used, kind);
  append(m->name, sizeof m->name, &used, ":");
  append(m->name, sizeof m->name, &used, a);
  if (b != NULL) {
    append(m->name, sizeof m->name, &used, "-");
    append(m->name, sizeof m->name, &used, b);
  }
  m->shape = shape;
  m->n_materials = 1;
  memcpy(m->materials[0].base_color, rgb, 3 * sizeof(float));
  return m;
}

/* No models: section: a thin capsule for each distance constraint and a
 * small sphere for each particle (its collision size when it has one). */
static int default_models(mr_reader *r) {
  static const float wood[3] = { 0.55f, 0.42f, 0.3f }, joint[3] = { 0.8f, 0.66f, 0.5f };
  mr_scene *s = r->scene;
  if (mr_scene_stage_reserve_models(r, NULL, s->n_distances + s->n_particles) != 0) return -1;
  for (size_t i = 0; i < s->n_distances; i++) {
    int a = s->distances[i].def.a, b = s->distances[i].def.b;
    mr_model_def *m = own_model(r, "link", mr_scene_point_name(s, a), mr_scene_point_name(s, b),
                                MR_SHAPE_CAPSULE, wood);
    if (m == NULL) return -1;
    m->display = MR_DISPLAY_LINK;
    m->particles[0] = a;
    m->particles[1] = b;
    m->scale[0] = m->scale[2] = 0.02;
  }
  for (size_t i = 0; i < s->n_particles; i++) {
    const mr_scene_particle *p = &s->particles[i];
    mr_model_def *m = own_model(r, "joint", p->name, NULL, MR_SHAPE_SPHERE, joint);
    if (m == NULL) return -1;
    m->particles[0] = (int)i;
    double d = p->def.radius > 0 ? 2 * p->def.radius : 0.05;
    m->scale[0] = m->scale[1] = m->scale[2] = d;
  }
  return 0;
}

/* A solid control frame (stage.frames.style): a rough wooden capsule,
 * frame_thickness across, along each bar of the tree that joins its
 * points by the least wood (mr_frame_bars), laid out from the points'
 * offsets (the frame is rigid, so its start shape is its shape). */
static int frame_bars(mr_reader *r, size_t k) {
  mr_scene *s = r->scene;
  const mr_scene_frame *f = &s->frames[k];
  int n = (int)f->n_points;
  double *xyz = malloc((3 * f->n_points + 1) * sizeof *xyz);
  int *pairs = malloc((2 * f->n_points + 1) * sizeof *pairs);
  int bars = xyz && pairs ? 0 : -1;
  for (int i = 0; i < n && bars == 0; i++)
    memcpy(&xyz[3 * i], s->control_points[f->first_point + (size_t)i].offset, 3 * sizeof *xyz);
  if (bars == 0) bars = mr_frame_bars(xyz, n, pairs);
  if (bars > 0 && mr_scene_stage_reserve_models(r, NULL, (size_t)bars) != 0) bars = -2;
  for (int b = 0; b < bars; b++) {
    int ids[2] = { (int)(s->n_particles + f->first_point) + pairs[2 * b],
                   (int)(s->n_particles + f->first_point) + pairs[2 * b + 1] };
    mr_model_def *m =
        own_model(r, "bar", mr_scene_point_name(s, ids[0]), mr_scene_point_name(s, ids[1]),
                  MR_SHAPE_CAPSULE, s->stage.frame_color);
    if (m == NULL) {
      bars = -2;
      break;
    }
    m->display = MR_DISPLAY_LINK;
    m->particles[0] = ids[0];
    m->particles[1] = ids[1];
    m->scale[0] = m->scale[2] = s->stage.frame_thickness;
    m->materials[0].roughness = 0.8f;
  }
  free(xyz);
  free(pairs);
  if (bars == -1) return mr_scene_read_fail_at(r, 0, 0, MR_SCENE_ERR_NOMEM, "out of memory");
  return bars < 0 ? -1 : 0;
}

/* Every collision particle's leaf sphere, as the sphere tree sizes it:
 * the larger of the particle's radius and its part's. Always there,
 * marked collision: the stage draws them when asked (stage.spheres,
 * `--spheres`, the window's c key). */
static int collision_spheres(mr_reader *r) {
  static const float glass[3] = { 0.55f, 0.7f, 0.9f };
  mr_scene *s = r->scene;
  double *radius = calloc(s->n_particles + 1, sizeof *radius);
  if (radius == NULL) return mr_scene_read_fail_at(r, 0, 0, MR_SCENE_ERR_NOMEM, "out of memory");
  for (size_t k = 0; k < s->n_parts; k++) {
    const mr_part_def *d = &s->parts[k].def;
    for (int j = 0; j < d->count; j++) {
      int p = d->particles[j];
      double rad = fmax(s->particles[p].def.radius, d->radius);
      if (rad > radius[p]) radius[p] = rad;
    }
  }
  size_t n = 0;
  for (size_t i = 0; i < s->n_particles; i++) n += radius[i] > 0;
  int rc = mr_scene_stage_reserve_models(r, NULL, n);
  for (size_t i = 0; i < s->n_particles && rc == 0; i++) {
    if (!(radius[i] > 0)) continue;
    mr_model_def *m = own_model(r, "sphere", s->particles[i].name, NULL, MR_SHAPE_SPHERE, glass);
    if (m == NULL) {
      rc = -1;
      break;
    }
    m->particles[0] = (int)i;
    m->scale[0] = m->scale[1] = m->scale[2] = 2 * radius[i];
    m->collision = true;
  }
  free(radius);
  return rc;
}

int mr_scene_stage_rigging(mr_reader *r, const mr_ynode *root) {
  mr_scene *s = r->scene;
  if (s->floor.present) s->stage.floor_height = s->floor.def.offset;
  if (strings_as_lines(r) != 0 || frames_as_lines(r) != 0) return -1;
  if (mr_scene_yaml_get(root, "models") == NULL && default_models(r) != 0) return -1;
  if (s->stage.show_frames && s->stage.frame_style == MR_FRAMES_SOLID)
    for (size_t k = 0; k < s->n_frames; k++)
      if (frame_bars(r, k) != 0) return -1;
  if (collision_spheres(r) != 0) return -1;
  if (r->unframed) return 0;
  /* The show's reach, estimated once: the set is sized from it, and the
   * audience's camera (without camera.orbit) frames it. */
  size_t n = 0;
  double *show = NULL;
  if (s->n_particles + s->n_control_points > 0 &&
      (show = mr_scene_show_points(s, MR_SET_FRAMED, &n)) == NULL)
    return mr_scene_read_fail_at(r, 0, 0, MR_SCENE_ERR_NOMEM, "out of memory");
  mr_scene_size_set(s, show, n);
  const mr_ynode *camera = mr_scene_yaml_get(root, "camera");
  if (camera == NULL || camera->kind != MR_YNODE_MAP || mr_scene_yaml_get(camera, "orbit") == NULL)
    mr_scene_frame_audience(s, show);
  free(show);
  return 0;
}
