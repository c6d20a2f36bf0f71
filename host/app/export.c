/* A show's draw lists kept for export (export.h): the models loaded as the
 * renderer loads them, the stage's poses frame by frame, the particles'
 * paths; and the two lighter copies, the PC2 point cache and the CSV. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export_internal.h"
#include "mr_physics.h"
#include "mr_scene_world.h"

static int fail(char *msg, size_t msg_size, const char *fmt, ...) {
  if (msg != NULL && msg_size > 0) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, msg_size, fmt, ap);
    va_end(ap);
  }
  return -1;
}

/* As the renderer names a model that will not load: where the scene
 * says it, the model, the file, why, and where else it was looked for. */
static void model_error(char *msg, size_t msg_size, const char *scene_path, const mr_model_def *def,
                        const char *why) {
  const char *what = def->shape == MR_SHAPE_FILE ? def->path : mr_shape_name(def->shape);
  if (def->pos.line > 0)
    snprintf(msg, msg_size, "%s:%d:%d: model '%s': %s: %s", scene_path, def->pos.line,
             def->pos.column, def->name, what, why);
  else
    snprintf(msg, msg_size, "%s: model '%s': %s: %s", scene_path, def->name, what, why);
  size_t n = strlen(msg);
  if (def->shape == MR_SHAPE_FILE && def->looked[0] != '\0' && n + 1 < msg_size)
    snprintf(msg + n, msg_size - n, "; also looked in %s", def->looked);
}

uint64_t mr_export_scene_hash(const mr_scene *scene, char *msg, size_t msg_size) {
  mr_scene_world sw;
  mr_scene_error err;
  if (mr_scene_build(scene, &sw, &err) != MR_SCENE_OK) {
    fail(msg, msg_size, "%s", err.text);
    return 0;
  }
  uint64_t h = mr_world_state_hash(sw.world);
  mr_scene_world_free(&sw);
  return h;
}

static int load_models(mr_export *e, char *msg, size_t msg_size) {
  const mr_stage_def *sd = &e->scene->stage;
  e->loaded = calloc(sd->n_models > 0 ? sd->n_models : 1, sizeof *e->loaded);
  if (e->loaded == NULL) return fail(msg, msg_size, "out of memory");
  for (size_t i = 0; i < sd->n_models; i++) {
    char why[384] = "";
    if (mr_model_load(&sd->models[i], &e->loaded[i], why, sizeof why) != 0) {
      model_error(msg, msg_size, e->scene->path, &sd->models[i], why);
      return -1;
    }
    e->n_loaded = i + 1;
  }
  return 0;
}

int mr_export_open(const mr_scene *scene, mr_export **out, char *msg, size_t msg_size) {
  *out = NULL;
  mr_export *e = calloc(1, sizeof *e);
  if (e == NULL) return fail(msg, msg_size, "out of memory");
  e->scene = scene;
  mr_scene_error err;
  double *xyz = mr_scene_start_positions(scene, &e->n_points, &err);
  if (xyz == NULL) {
    fail(msg, msg_size, "%s", err.text);
    mr_export_close(e);
    return -1;
  }
  char why[400];
  mr_stage_status ss = mr_stage_create(&scene->stage, xyz, e->n_points, &e->stage, why, sizeof why);
  free(xyz);
  if (ss != MR_STAGE_OK) {
    fail(msg, msg_size, "%s: the stage: %s", scene->path, why);
    mr_export_close(e);
    return -1;
  }
  if (load_models(e, msg, msg_size) != 0) {
    mr_export_close(e);
    return -1;
  }
  *out = e;
  return 0;
}

static void free_shown(ex_model *m) {
  for (size_t k = 0; m->joints != NULL && k < m->mesh.n_meshes; k++) free(m->joints[k]);
  for (size_t k = 0; m->weights != NULL && k < m->mesh.n_meshes; k++) free(m->weights[k]);
  free(m->joints);
  free(m->weights);
}

void mr_export_close(mr_export *e) {
  if (e == NULL) return;
  for (size_t i = 0; i < e->n_shown; i++) free_shown(&e->shown[i]);
  for (size_t i = 0; i < e->n_loaded; i++) mr_model_free(&e->loaded[i]);
  free(e->shown);
  free(e->loaded);
  mr_stage_destroy(e->stage);
  free(e->t);
  free(e->item);
  free(e->bone);
  free(e->xyz);
  free(e);
}

/* A freeform model's vertices each bound to the 4 nearest of its bones,
 * as the renderer binds them (mr_stage_skin_bind, padded to 4). */
static int bind_skin(ex_model *m) {
  size_t nm = m->mesh.n_meshes;
  m->joints = calloc(nm, sizeof *m->joints);
  m->weights = calloc(nm, sizeof *m->weights);
  if (m->joints == NULL || m->weights == NULL) return -1;
  int k = m->def->influences < 1 ? 1 : m->def->influences;
  if (k > MR_SKIN_MAX_INFLUENCES) k = MR_SKIN_MAX_INFLUENCES;
  for (size_t i = 0; i < nm; i++) {
    const mr_mesh *mesh = &m->mesh.meshes[i];
    size_t n = mesh->n_vertices;
    int *idx = calloc(n * (size_t)k + 1, sizeof *idx);
    float *w = calloc(n * (size_t)k + 1, sizeof *w);
    m->joints[i] = calloc(4 * n + 1, sizeof(int));
    m->weights[i] = calloc(4 * n + 1, sizeof(float));
    int rc = idx != NULL && w != NULL && m->joints[i] != NULL && m->weights[i] != NULL
                 ? (int)mr_stage_skin_bind(mesh->positions, n, m->def->bones_rest, m->def->n_bones,
                                           k, idx, w)
                 : -1;
    for (size_t v = 0; rc == 0 && v < n; v++)
      for (int j = 0; j < k; j++) {
        m->joints[i][4 * v + (size_t)j] = idx[v * (size_t)k + (size_t)j];
        m->weights[i][4 * v + (size_t)j] = w[v * (size_t)k + (size_t)j];
      }
    free(idx);
    free(w);
    if (rc != 0) return -1;
  }
  return 0;
}

/* Model i of the stage, shown by the first draw list as item or skin. */
static void show_model(mr_export *e, const mr_stage_def *sd, size_t i, int material,
                       const mr_draw_skin *skin) {
  ex_model *m = &e->shown[e->n_shown++];
  m->model = (int)i;
  m->def = &sd->models[i];
  m->mesh = e->loaded[i];
  m->material = material;
  m->skin = skin != NULL;
  m->slot = skin != NULL ? -1 : (int)e->n_posed++;
  if (skin != NULL) {
    m->bone0 = (int)e->n_bones;
    e->n_bones += (size_t)skin->n_bones;
  }
}

/* The models the first draw list shows fix the file's nodes, in the
 * scene's order. */
static int start(mr_export *e, const mr_draw_list *dl, char *msg, size_t msg_size) {
  const mr_stage_def *sd = mr_stage_get_def(e->stage);
  e->shown = calloc(dl->n_items + dl->n_skins + 1, sizeof *e->shown);
  if (e->shown == NULL) return fail(msg, msg_size, "out of memory");
  for (size_t i = 0; i < sd->n_models; i++) {
    for (size_t k = 0; k < dl->n_items; k++)
      if ((size_t)dl->items[k].model == i) show_model(e, sd, i, dl->items[k].material, NULL);
    for (size_t k = 0; k < dl->n_skins; k++)
      if ((size_t)dl->skins[k].model == i)
        show_model(e, sd, i, dl->skins[k].material, &dl->skins[k]);
  }
  for (size_t i = 0; i < e->n_shown; i++) {
    ex_model *m = &e->shown[i];
    if (m->skin && bind_skin(m) != 0)
      return fail(msg, msg_size, "%s: model '%s': cannot bind the mesh to its %d bones",
                  e->scene->path, m->def->name, m->def->n_bones);
  }
  e->started = true;
  return 0;
}

static int grow(mr_export *e) {
  if (e->n_frames < e->cap) return 0;
  size_t cap = e->cap ? 2 * e->cap : 256;
  size_t np = e->scene->n_particles;
  double *t = realloc(e->t, cap * sizeof *t);
  if (t != NULL) e->t = t;
  double *item = realloc(e->item, (cap * e->n_posed * EX_ITEM + 1) * sizeof *item);
  if (item != NULL) e->item = item;
  double *bone = realloc(e->bone, (cap * e->n_bones * EX_BONE + 1) * sizeof *bone);
  if (bone != NULL) e->bone = bone;
  double *xyz = realloc(e->xyz, (cap * np * 3 + 1) * sizeof *xyz);
  if (xyz != NULL) e->xyz = xyz;
  if (t == NULL || item == NULL || bone == NULL || xyz == NULL) return -1;
  e->cap = cap;
  return 0;
}

/* A pose kept with its quaternion on the side of the one before, so that
 * the keys interpolate the short way; unit as kept. */
static void keep_pose(double *dst, const mr_pose *p, const double *prev) {
  double q[4], len = 0;
  for (int c = 0; c < 4; c++) len += p->orientation[c] * p->orientation[c];
  len = sqrt(len);
  double dot = 0;
  for (int c = 0; c < 4; c++) {
    q[c] = p->orientation[c] / len;
    if (prev != NULL) dot += q[c] * prev[3 + c];
  }
  for (int c = 0; c < 3; c++) dst[c] = p->position[c];
  for (int c = 0; c < 4; c++) dst[3 + c] = dot < 0 ? -q[c] : q[c];
}

static void keep_frame(mr_export *e, const mr_draw_list *dl) {
  size_t f = e->n_frames;
  for (size_t i = 0; i < dl->n_items; i++)
    for (size_t s = 0; s < e->n_shown; s++) {
      const ex_model *m = &e->shown[s];
      if (m->skin || m->model != dl->items[i].model) continue;
      double *dst = &e->item[(f * e->n_posed + (size_t)m->slot) * EX_ITEM];
      keep_pose(dst, &dl->items[i].pose, f > 0 ? dst - e->n_posed * EX_ITEM : NULL);
      for (int c = 0; c < 3; c++) dst[7 + c] = dl->items[i].scale[c];
    }
  for (size_t i = 0; i < dl->n_skins; i++)
    for (size_t s = 0; s < e->n_shown; s++) {
      const ex_model *m = &e->shown[s];
      if (!m->skin || m->model != dl->skins[i].model) continue;
      for (int b = 0; b < dl->skins[i].n_bones; b++) {
        double *dst = &e->bone[(f * e->n_bones + (size_t)(m->bone0 + b)) * EX_BONE];
        keep_pose(dst, &dl->skins[i].bones[b], f > 0 ? dst - e->n_bones * EX_BONE : NULL);
      }
    }
}

int mr_export_add(mr_export *e, double t, const double *xyz, size_t n, char *msg, size_t msg_size) {
  if (e->n_frames > 0 && !(t > e->t[e->n_frames - 1])) return 1;
  if (n != e->n_points)
    return fail(msg, msg_size, "a frame of %zu points, the stage has %zu", n, e->n_points);
  mr_stage_set_time(e->stage, t, -1);
  const mr_draw_list *dl = NULL;
  if (mr_stage_update(e->stage, xyz, n, &dl) != MR_STAGE_OK)
    return fail(msg, msg_size, "the stage refused the frame at t = %.3f s", t);
  if (!e->started && start(e, dl, msg, msg_size) != 0) return -1;
  if (grow(e) != 0) return fail(msg, msg_size, "out of memory");
  size_t f = e->n_frames;
  /* A frame starts as the one before: a model the list leaves out stays. */
  if (f > 0) {
    memcpy(&e->item[f * e->n_posed * EX_ITEM], &e->item[(f - 1) * e->n_posed * EX_ITEM],
           e->n_posed * EX_ITEM * sizeof(double));
    memcpy(&e->bone[f * e->n_bones * EX_BONE], &e->bone[(f - 1) * e->n_bones * EX_BONE],
           e->n_bones * EX_BONE * sizeof(double));
  }
  keep_frame(e, dl);
  e->t[f] = t;
  size_t np = e->scene->n_particles;
  memcpy(&e->xyz[f * np * 3], xyz, np * 3 * sizeof(double));
  e->n_frames++;
  return 0;
}

size_t mr_export_frames(const mr_export *e) {
  return e->n_frames;
}

double mr_export_last_time(const mr_export *e) {
  return e->n_frames > 0 ? e->t[e->n_frames - 1] : 0.0;
}

size_t mr_export_nodes(const mr_export *e) {
  return e->n_shown + e->n_bones;
}

size_t mr_export_channels(const mr_export *e) {
  size_t n = 0;
  for (size_t i = 0; i < e->n_shown; i++)
    if (!e->shown[i].skin) n += e->shown[i].def->display == MR_DISPLAY_LINK ? 3 : 2;
  return n + 2 * e->n_bones;
}

size_t mr_export_points(const mr_export *e) {
  size_t n = 0;
  for (size_t i = 0; i < e->n_shown; i++)
    for (size_t k = 0; e->shown[i].skin && k < e->shown[i].mesh.n_meshes; k++)
      n += e->shown[i].mesh.meshes[k].n_vertices;
  return n;
}

void ex_skin_vertex(const mr_export *e, const ex_model *m, size_t k, size_t v, size_t f,
                    double out[3]) {
  const float *p = &m->mesh.meshes[k].positions[3 * v];
  double rest[3] = { p[0], p[1], p[2] };
  out[0] = out[1] = out[2] = 0;
  for (int j = 0; j < 4; j++) {
    float w = m->weights[k][4 * v + (size_t)j];
    if (w == 0) continue;
    const double *b = ex_bone_at(e, f, (size_t)(m->bone0 + m->joints[k][4 * v + (size_t)j]));
    mr_pose pose;
    memcpy(pose.position, b, 3 * sizeof(double));
    memcpy(pose.orientation, b + 3, 4 * sizeof(double));
    double moved[3];
    mr_pose_apply(&pose, rest, moved);
    for (int c = 0; c < 3; c++) out[c] += w * moved[c];
  }
}

static int put_i32(FILE *f, int32_t v) {
  uint8_t b[4] = { (uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24) };
  return fwrite(b, 1, 4, f) == 4 ? 0 : -1;
}

static int put_f32(FILE *f, float x) {
  uint32_t u;
  memcpy(&u, &x, 4);
  return put_i32(f, (int32_t)u);
}

/* PC2 (the Mesh Cache modifier's point cache): "POINTCACHE2\0", version 1,
 * points, start frame, sample rate (frames a sample), samples; then per
 * sample per point x, y, z, float32, little-endian. */
int mr_export_write_pc2(const mr_export *e, const char *path, char *msg, size_t msg_size) {
  size_t np = mr_export_points(e);
  if (np == 0)
    return fail(msg, msg_size, "%s: %s: the scene has no freeform model to cache", path,
                e->scene->path);
  FILE *f = fopen(path, "wb");
  if (f == NULL) return fail(msg, msg_size, "%s: cannot create: %s", path, strerror(errno));
  int bad = fwrite("POINTCACHE2", 1, 12, f) != 12;
  bad |= put_i32(f, 1) | put_i32(f, (int32_t)np);
  bad |= put_f32(f, 0.0f) | put_f32(f, 1.0f) | put_i32(f, (int32_t)e->n_frames);
  for (size_t fr = 0; fr < e->n_frames && !bad; fr++)
    for (size_t i = 0; i < e->n_shown; i++) {
      const ex_model *m = &e->shown[i];
      for (size_t k = 0; m->skin && k < m->mesh.n_meshes; k++)
        for (size_t v = 0; v < m->mesh.meshes[k].n_vertices; v++) {
          double p[3];
          ex_skin_vertex(e, m, k, v, fr, p);
          for (int c = 0; c < 3; c++) bad |= put_f32(f, (float)p[c]);
        }
    }
  if (fclose(f) != 0) bad = 1;
  return bad ? fail(msg, msg_size, "%s: cannot write: %s", path, strerror(errno)) : 0;
}

/* One row per particle per frame: time, world id, name, position. */
int mr_export_write_csv(const mr_export *e, const char *path, char *msg, size_t msg_size) {
  FILE *f = fopen(path, "w");
  if (f == NULL) return fail(msg, msg_size, "%s: cannot create: %s", path, strerror(errno));
  int bad = fprintf(f, "t,id,name,x,y,z\n") < 0;
  size_t np = e->scene->n_particles;
  for (size_t fr = 0; fr < e->n_frames && !bad; fr++)
    for (size_t i = 0; i < np; i++) {
      const double *p = &e->xyz[(fr * np + i) * 3];
      bad |= fprintf(f, "%.6f,%zu,%s,%.9g,%.9g,%.9g\n", e->t[fr], i, e->scene->particles[i].name,
                     p[0], p[1], p[2]) < 0;
    }
  if (fclose(f) != 0) bad = 1;
  return bad ? fail(msg, msg_size, "%s: cannot write: %s", path, strerror(errno)) : 0;
}
