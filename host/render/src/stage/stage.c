/* mr_stage: a stage definition, copied and checked, over n points; its
 * draw list is made each frame in stage_update.c. */
#include "stage_internal.h"
#include "stage_math.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static mr_stage_status
fail(char *msg, size_t size, mr_stage_status st, const char *fmt, ...) {
  if (msg != NULL && size > 0) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, size, fmt, ap);
    va_end(ap);
  }
  return st;
}

/* A copy of n items of size bytes (NULL for none); *ok false when out of
 * memory. */
static void *dup_array(const void *src, size_t n, size_t size, bool *ok) {
  if (n == 0 || src == NULL) return NULL;
  void *p = malloc(n * size);
  if (p == NULL) {
    *ok = false;
    return NULL;
  }
  memcpy(p, src, n * size);
  return p;
}

static size_t count_lines(const mr_stage_def *d) {
  size_t lines = d->n_strings;
  for (size_t k = 0; k < d->n_frames; k++) {
    int c = d->frame_point_count[k];
    lines += c >= 3 ? (size_t)c : c == 2 ? 1 : 0;
  }
  return lines;
}

static size_t count_frame_points(const mr_stage_def *d) {
  size_t total = 0;
  for (size_t k = 0; k < d->n_frames; k++) total += (size_t)d->frame_point_count[k];
  return total;
}

/* Every world id the def names lies in 0..n-1, and every count is sane. */
static mr_stage_status check_model(const mr_model_def *m, size_t n, char *msg, size_t size) {
  static const int needs[] = { 1, 2, 3, 0 };
  if (m->cookie != MR_DEF_COOKIE)
    return fail(msg, size, MR_STAGE_ERR_ARG, "model '%.*s' was not made by mr_default_model_def",
                MR_STAGE_NAME_MAX, m->name);
  if ((int)m->display < 0 || m->display > MR_DISPLAY_FREEFORM)
    return fail(msg, size, MR_STAGE_ERR_ARG, "model '%s': display mode %d is unknown", m->name,
                (int)m->display);
  if (m->n_materials < 0 || m->n_materials > MR_STAGE_MAX_MATERIALS)
    return fail(msg, size, MR_STAGE_ERR_ARG, "model '%s': %d materials, expected 0 to %d", m->name,
                m->n_materials, MR_STAGE_MAX_MATERIALS);
  for (int i = 0; i < m->n_materials; i++)
    if (m->materials[i].cookie != MR_DEF_COOKIE)
      return fail(msg, size, MR_STAGE_ERR_ARG,
                  "model '%s': material %d was not made by mr_default_material_def", m->name, i);
  for (int i = 0; i < needs[m->display]; i++)
    if (m->particles[i] < 0 || (size_t)m->particles[i] >= n)
      return fail(msg, size, MR_STAGE_ERR_ARG,
                  "model '%s' (%s): point %d is not one of the stage's %zu points", m->name,
                  mr_display_mode_name(m->display), m->particles[i], n);
  if (m->display != MR_DISPLAY_FREEFORM) return MR_STAGE_OK;
  if (m->n_bones < 1 || m->bones == NULL)
    return fail(msg, size, MR_STAGE_ERR_ARG, "model '%s' (freeform): no bones", m->name);
  if (m->influences < 1 || m->influences > MR_SKIN_MAX_INFLUENCES)
    return fail(msg, size, MR_STAGE_ERR_ARG, "model '%s': %d influences, expected 1 to %d", m->name,
                m->influences, MR_SKIN_MAX_INFLUENCES);
  for (int i = 0; i < m->n_bones; i++)
    if (m->bones[i] < 0 || (size_t)m->bones[i] >= n)
      return fail(msg, size, MR_STAGE_ERR_ARG,
                  "model '%s' (freeform): bone %d is point %d, not one of the stage's %zu points",
                  m->name, i, m->bones[i], n);
  return MR_STAGE_OK;
}

static mr_stage_status check_ids(const int *ids, size_t count, size_t n, const char *what,
                                 char *msg, size_t size) {
  for (size_t i = 0; i < count; i++)
    if (ids[i] < 0 || (size_t)ids[i] >= n)
      return fail(msg, size, MR_STAGE_ERR_ARG, "%s: point %d is not one of the stage's %zu points",
                  what, ids[i], n);
  return MR_STAGE_OK;
}

static mr_stage_status check_def(const mr_stage_def *d, size_t n, char *msg, size_t size) {
  if (d->cookie != MR_DEF_COOKIE)
    return fail(msg, size, MR_STAGE_ERR_ARG, "the stage def was not made by mr_default_stage_def");
  if ((d->n_models > 0 && d->models == NULL) || (d->n_stars > 0 && d->star_list == NULL) ||
      (d->n_strings > 0 && d->strings == NULL) ||
      (d->n_frames > 0 && (d->frame_points == NULL || d->frame_point_count == NULL)))
    return fail(msg, size, MR_STAGE_ERR_ARG, "the stage def counts items it has no array for");
  if (d->lights.n_spots < 0 || d->lights.n_spots > MR_STAGE_MAX_SPOTS || d->n_cameras < 0 ||
      d->n_cameras > MR_STAGE_MAX_CAMERAS)
    return fail(msg, size, MR_STAGE_ERR_ARG, "%d spots and %d cameras, expected at most %d of each",
                d->lights.n_spots, d->n_cameras, MR_STAGE_MAX_SPOTS);
  for (int k = 0; k < d->lights.n_spots; k++)
    if (d->lights.spots[k].cookie != MR_DEF_COOKIE)
      return fail(msg, size, MR_STAGE_ERR_ARG, "spot %d was not made by mr_default_spot_def", k);
  for (int k = 0; k < d->n_cameras; k++)
    if (d->cameras[k].cookie != MR_DEF_COOKIE)
      return fail(msg, size, MR_STAGE_ERR_ARG, "camera %d was not made by mr_default_camera_def",
                  k);
  for (size_t k = 0; k < d->n_frames; k++)
    if (d->frame_point_count[k] < 0)
      return fail(msg, size, MR_STAGE_ERR_ARG, "control frame %zu has %d points", k,
                  d->frame_point_count[k]);
  mr_stage_status st;
  for (size_t i = 0; i < d->n_models; i++)
    if ((st = check_model(&d->models[i], n, msg, size)) != MR_STAGE_OK) return st;
  if ((st = check_ids(d->strings, 2 * d->n_strings, n, "a string", msg, size)) != MR_STAGE_OK)
    return st;
  return check_ids(d->frame_points, count_frame_points(d), n, "a control frame", msg, size);
}

/* The rest frame of every rigid model (§3.3: "oriented either by the
 * particles' configuration or by their initial orientation"). */
static mr_stage_status rest_frames(mr_stage *s, const double *rest, char *msg, size_t size) {
  for (size_t i = 0; i < s->def.n_models; i++) {
    const mr_model_def *m = &s->models[i];
    if (m->display != MR_DISPLAY_RIGID) continue;
    const int *p = m->particles;
    if (mr_stage_frame3(&rest[3 * p[0]], &rest[3 * p[1]], &rest[3 * p[2]],
                        &s->state[i].rest_frame) != 0)
      return fail(msg, size, MR_STAGE_ERR_VALUE,
                  "model '%s' (rigid): points %d, %d and %d coincide or lie on one line at the "
                  "start, so they give no orientation",
                  m->name, p[0], p[1], p[2]);
  }
  return MR_STAGE_OK;
}

/* The def's arrays, copied so the stage outlives its caller's. */
static bool copy_arrays(mr_stage *s, const mr_stage_def *d) {
  bool ok = true;
  s->def = *d;
  s->models = dup_array(d->models, d->n_models, sizeof *d->models, &ok);
  s->stars = dup_array(d->star_list, d->n_stars, sizeof *d->star_list, &ok);
  s->strings = dup_array(d->strings, 2 * d->n_strings, sizeof *d->strings, &ok);
  s->frame_points = dup_array(d->frame_points, count_frame_points(d), sizeof(int), &ok);
  s->frame_point_count = dup_array(d->frame_point_count, d->n_frames, sizeof(int), &ok);
  s->def.models = s->models;
  s->def.star_list = s->stars;
  s->def.strings = s->strings;
  s->def.frame_points = s->frame_points;
  s->def.frame_point_count = s->frame_point_count;
  return ok;
}

/* A freeform model's bones and their rest positions (the start positions
 * of its points when the def gives none), copied. */
static mr_stage_status copy_bones(mr_stage *s, size_t i, const double *rest, char *msg,
                                  size_t size) {
  mr_model_def *m = &s->models[i];
  mr_stage_model *st = &s->state[i];
  size_t nb = (size_t)m->n_bones;
  st->bones = malloc(nb * sizeof *st->bones);
  st->bones_rest = malloc(3 * nb * sizeof *st->bones_rest);
  if (st->bones == NULL || st->bones_rest == NULL)
    return fail(msg, size, MR_STAGE_ERR_NOMEM, "out of memory");
  memcpy(st->bones, m->bones, nb * sizeof *st->bones);
  for (size_t b = 0; b < nb; b++) {
    const double *p = m->bones_rest ? &m->bones_rest[3 * b] : &rest[3 * st->bones[b]];
    if (!mr_stage_finite3(p))
      return fail(msg, size, MR_STAGE_ERR_VALUE, "model '%s' (freeform): bone %zu rests at NaN",
                  m->name, b);
    memcpy(&st->bones_rest[3 * b], p, 3 * sizeof(double));
  }
  m->bones = st->bones;
  m->bones_rest = st->bones_rest;
  st->first_bone = s->n_bones;
  s->n_bones += nb;
  return MR_STAGE_OK;
}

/* A freeform model's skin slot, its bones at rest. */
static void make_skin_slot(mr_stage *s, size_t i) {
  const mr_model_def *m = &s->models[i];
  mr_draw_skin *k = &s->skins[s->n_skins];
  s->state[i].slot = (int)s->n_skins++;
  *k = (mr_draw_skin){ (int)i, s->bone_poses + s->state[i].first_bone, m->n_bones,
                       m->n_materials > 0 ? 0 : -1 };
  for (int b = 0; b < m->n_bones; b++)
    s->bone_poses[s->state[i].first_bone + (size_t)b] = mr_pose_identity();
  mr_stage_bones_prepare(s, i);
}

/* Items in the models' order, the collision spheres after the others:
 * the list leaves them off its end while they are hidden. */
static void make_item_slots(mr_stage *s, const double *rest) {
  const mr_stage_def *d = &s->def;
  size_t next[2] = { 0, s->n_items - s->n_sphere_items };
  for (size_t i = 0; i < d->n_models; i++) {
    const mr_model_def *m = &s->models[i];
    if (m->display == MR_DISPLAY_FREEFORM) continue;
    size_t slot = next[m->collision ? 1 : 0]++;
    mr_draw_item *it = &s->items[slot];
    s->state[i].slot = (int)slot;
    it->model = (int)i;
    it->pose = mr_pose_identity();
    memcpy(it->pose.position, &rest[3 * m->particles[0]], sizeof it->pose.position);
    it->scale[0] = it->scale[2] = 1;
    it->scale[1] = m->display == MR_DISPLAY_LINK ? 0 : 1;
    it->material = m->n_materials > 0 ? 0 : -1;
  }
}

/* The draw list's arrays, each model given its slot and first look. */
static mr_stage_status make_slots(mr_stage *s, const double *rest, char *msg, size_t size) {
  const mr_stage_def *d = &s->def;
  size_t skins = 0;
  for (size_t i = 0; i < d->n_models; i++) {
    const mr_model_def *m = &s->models[i];
    skins += m->display == MR_DISPLAY_FREEFORM;
    s->n_sphere_items += m->display != MR_DISPLAY_FREEFORM && m->collision;
  }
  s->n_items = d->n_models - skins;
  s->items = calloc(s->n_items + 1, sizeof *s->items);
  s->skins = calloc(skins + 1, sizeof *s->skins);
  s->bone_poses = calloc(s->n_bones + 1, sizeof *s->bone_poses);
  s->neighbours = calloc(MR_STAGE_BONE_NEIGHBOURS * s->n_bones + 1, sizeof *s->neighbours);
  s->fit = calloc(s->n_bones + 1, 1);
  s->lines = calloc(count_lines(d) + 1, sizeof *s->lines);
  s->shown = malloc((3 * s->n + 1) * sizeof *s->shown);
  if (!s->items || !s->skins || !s->bone_poses || !s->neighbours || !s->fit || !s->lines ||
      !s->shown)
    return fail(msg, size, MR_STAGE_ERR_NOMEM, "out of memory");
  if (s->n > 0) memcpy(s->shown, rest, 3 * s->n * sizeof *s->shown);
  for (size_t i = 0; i < d->n_models; i++)
    if (s->models[i].display == MR_DISPLAY_FREEFORM) make_skin_slot(s, i);
  make_item_slots(s, rest);
  memset(&s->list, 0, sizeof s->list);
  s->list.items = s->items, s->list.n_items = s->n_items;
  s->list.skins = s->skins, s->list.n_skins = s->n_skins;
  s->list.lines = s->lines;
  if (mr_stage_spot_prepare(s) != 0) return fail(msg, size, MR_STAGE_ERR_NOMEM, "out of memory");
  return mr_stage_show_spheres(s, d->show_spheres);
}

static mr_stage_status build(mr_stage *s, const mr_stage_def *def, const double *rest, char *msg,
                             size_t size) {
  if (!copy_arrays(s, def)) return fail(msg, size, MR_STAGE_ERR_NOMEM, "out of memory");
  s->state = calloc(def->n_models + 1, sizeof *s->state);
  if (s->state == NULL) return fail(msg, size, MR_STAGE_ERR_NOMEM, "out of memory");
  mr_stage_status st;
  for (size_t i = 0; i < def->n_models; i++)
    if (s->models[i].display == MR_DISPLAY_FREEFORM &&
        (st = copy_bones(s, i, rest, msg, size)) != MR_STAGE_OK)
      return st;
  if ((st = rest_frames(s, rest, msg, size)) != MR_STAGE_OK ||
      (st = make_slots(s, rest, msg, size)) != MR_STAGE_OK)
    return st;
  const mr_draw_list *list;
  return mr_stage_update(s, rest, s->n, &list);
}

mr_stage_status mr_stage_create(const mr_stage_def *def, const double *rest_xyz, size_t n,
                                mr_stage **out, char *msg, size_t msg_size) {
  if (msg != NULL && msg_size > 0) msg[0] = '\0';
  if (out != NULL) *out = NULL;
  if (def == NULL || out == NULL || (n > 0 && rest_xyz == NULL))
    return fail(msg, msg_size, MR_STAGE_ERR_ARG, "mr_stage_create: NULL argument");
  mr_stage_status st = check_def(def, n, msg, msg_size);
  if (st != MR_STAGE_OK) return st;
  for (size_t i = 0; i < n; i++)
    if (!mr_stage_finite3(&rest_xyz[3 * i]))
      return fail(msg, msg_size, MR_STAGE_ERR_VALUE, "point %zu starts at NaN or infinity", i);
  mr_stage *s = calloc(1, sizeof *s);
  if (s == NULL) return fail(msg, msg_size, MR_STAGE_ERR_NOMEM, "out of memory");
  s->n = n;
  if ((st = build(s, def, rest_xyz, msg, msg_size)) != MR_STAGE_OK) {
    mr_stage_destroy(s);
    return st;
  }
  *out = s;
  return MR_STAGE_OK;
}

void mr_stage_destroy(mr_stage *s) {
  if (s == NULL) return;
  for (size_t i = 0; s->state != NULL && i < s->def.n_models; i++) {
    free(s->state[i].bones);
    free(s->state[i].bones_rest);
  }
  free(s->state);
  free(s->models);
  free(s->stars);
  free(s->strings);
  free(s->frame_points);
  free(s->frame_point_count);
  free(s->shown);
  free(s->items);
  free(s->skins);
  free(s->bone_poses);
  free(s->neighbours);
  free(s->fit);
  free(s->lines);
  free(s->spot_points);
  free(s->spot_xyz);
  free(s);
}

const mr_stage_def *mr_stage_get_def(const mr_stage *s) {
  return s != NULL ? &s->def : NULL;
}

mr_stage_status mr_stage_show_spheres(mr_stage *s, bool show) {
  if (s == NULL) return MR_STAGE_ERR_ARG;
  s->def.show_spheres = show;
  s->list.n_items = show ? s->n_items : s->n_items - s->n_sphere_items;
  return MR_STAGE_OK;
}

mr_stage_status mr_stage_set_material(mr_stage *s, size_t model, int k) {
  if (s == NULL || model >= s->def.n_models) return MR_STAGE_ERR_ARG;
  const mr_model_def *m = &s->models[model];
  if (k < -1 || k >= m->n_materials) return MR_STAGE_ERR_ARG;
  int slot = s->state[model].slot;
  if (m->display == MR_DISPLAY_FREEFORM)
    s->skins[slot].material = k;
  else
    s->items[slot].material = k;
  return MR_STAGE_OK;
}
