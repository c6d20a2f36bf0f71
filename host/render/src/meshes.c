/* Meshes on the GPU: each model of the stage loaded once at create
 * (mr_model_load) and uploaded, with, for a freeform model, each vertex's
 * bones and weights (mr_stage_skin_bind); the floor and the backdrop are
 * meshes too. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "render_internal.h"
#include "shapes.h"

enum { BUF_POS, BUF_NORMAL, BUF_UV, BUF_BONES, BUF_WEIGHTS, BUF_INDEX };

static void upload_floats(mr_render *r, mr_gpu_mesh *g, int slot, const float *data, size_t n,
                          int per) {
  const mr_gl *gl = &r->gl;
  gl->GenBuffers(1, &g->buffers[slot]);
  gl->BindBuffer(GL_ARRAY_BUFFER, g->buffers[slot]);
  gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * (size_t)per * sizeof(float)), data,
                 GL_STATIC_DRAW);
  gl->VertexAttribPointer((GLuint)slot, per, GL_FLOAT, GL_FALSE, 0, NULL);
  gl->EnableVertexAttribArray((GLuint)slot);
}

static void upload_texture(mr_render *r, mr_gpu_mesh *g, const mr_mesh *m) {
  const mr_gl *gl = &r->gl;
  gl->GenTextures(1, &g->texture);
  gl->BindTexture(GL_TEXTURE_2D, g->texture);
  gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  /* The loader's rows run top first; glTF and OBJ texture coordinates put
   * v = 0 at the top row too, so the rows go up as they come. */
  gl->TexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, m->texture_width, m->texture_height, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, m->texture);
  gl->GenerateMipmap(GL_TEXTURE_2D);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
}

/* A mesh's buffers; bones and weights are 4 per vertex, or NULL. */
static void upload_mesh(mr_render *r, mr_gpu_mesh *g, const mr_mesh *m, const int *bones,
                        const float *weights) {
  const mr_gl *gl = &r->gl;
  gl->GenVertexArrays(1, &g->vao);
  gl->BindVertexArray(g->vao);
  upload_floats(r, g, BUF_POS, m->positions, m->n_vertices, 3);
  upload_floats(r, g, BUF_NORMAL, m->normals, m->n_vertices, 3);
  if (m->uvs) upload_floats(r, g, BUF_UV, m->uvs, m->n_vertices, 2);
  if (bones) {
    gl->GenBuffers(1, &g->buffers[BUF_BONES]);
    gl->BindBuffer(GL_ARRAY_BUFFER, g->buffers[BUF_BONES]);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m->n_vertices * 4 * sizeof(int)), bones,
                   GL_STATIC_DRAW);
    gl->VertexAttribIPointer(BUF_BONES, 4, GL_INT, 0, NULL);
    gl->EnableVertexAttribArray(BUF_BONES);
    upload_floats(r, g, BUF_WEIGHTS, weights, m->n_vertices, 4);
  }
  gl->GenBuffers(1, &g->buffers[BUF_INDEX]);
  gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->buffers[BUF_INDEX]);
  gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(m->n_indices * sizeof(uint32_t)), m->indices,
                 GL_STATIC_DRAW);
  g->n_indices = (GLsizei)m->n_indices;
  gl->BindVertexArray(0);
  g->material = m->material;
  if (m->texture && m->uvs) upload_texture(r, g, m);
}

void mr_mesh_upload(mr_render *r, mr_gpu_mesh *g, const mr_mesh *m) {
  upload_mesh(r, g, m, NULL, NULL);
}

void mr_mesh_free(mr_render *r, mr_gpu_mesh *g) {
  const mr_gl *gl = &r->gl;
  for (int i = 0; i < 6; i++)
    if (g->buffers[i]) gl->DeleteBuffers(1, &g->buffers[i]);
  if (g->vao) gl->DeleteVertexArrays(1, &g->vao);
  if (g->texture) gl->DeleteTextures(1, &g->texture);
  memset(g, 0, sizeof *g);
}

/* Each vertex's bones: `influences` nearest, padded to 4 with weight 0.
 * 0, -1 when they cannot be bound, -2 when memory runs out. */
static int skin_mesh(mr_render *r, mr_gpu_mesh *g, const mr_mesh *m, const mr_model_def *def) {
  int k = def->influences < 1 ? 1 : def->influences;
  if (k > MR_SKIN_MAX_INFLUENCES) k = MR_SKIN_MAX_INFLUENCES;
  size_t n = m->n_vertices;
  int *idx = calloc(n * (size_t)k, sizeof *idx), *idx4 = calloc(n * 4, sizeof *idx4);
  float *w = calloc(n * (size_t)k, sizeof *w), *w4 = calloc(n * 4, sizeof *w4);
  int rc = idx && idx4 && w && w4 ? -1 : -2;
  if (rc == -1 && mr_stage_skin_bind(m->positions, n, def->bones_rest, def->n_bones, k, idx, w) ==
                      MR_STAGE_OK) {
    for (size_t v = 0; v < n; v++) {
      for (int j = 0; j < k; j++) {
        idx4[v * 4 + (size_t)j] = idx[v * (size_t)k + (size_t)j];
        w4[v * 4 + (size_t)j] = w[v * (size_t)k + (size_t)j];
      }
    }
    upload_mesh(r, g, m, idx4, w4);
    rc = 0;
  }
  free(idx);
  free(idx4);
  free(w);
  free(w4);
  return rc;
}

/* The box that holds every vertex: the shadow's box is fitted to the
 * casters' (shadow.c). An empty model's is the origin. */
static void bounds(mr_gpu_model *gm, const mr_model *model) {
  bool any = false;
  for (int k = 0; k < 3; k++) gm->lo[k] = gm->hi[k] = 0;
  for (size_t i = 0; i < model->n_meshes; i++) {
    const mr_mesh *m = &model->meshes[i];
    for (size_t v = 0; v < m->n_vertices; v++) {
      for (int k = 0; k < 3; k++) {
        float x = m->positions[3 * v + (size_t)k];
        if (!any || x < gm->lo[k]) gm->lo[k] = x;
        if (!any || x > gm->hi[k]) gm->hi[k] = x;
      }
      any = true;
    }
  }
}

static int upload_model(mr_render *r, mr_gpu_model *gm, const mr_model *model,
                        const mr_model_def *def, char *why, size_t why_size) {
  gm->meshes = calloc(model->n_meshes ? model->n_meshes : 1, sizeof *gm->meshes);
  if (!gm->meshes) {
    snprintf(why, why_size, "out of memory");
    return -1;
  }
  gm->n_meshes = model->n_meshes;
  gm->skinned = def->display == MR_DISPLAY_FREEFORM;
  gm->cast_shadow = def->cast_shadow;
  gm->n_bones = def->n_bones;
  gm->n_materials = def->n_materials;
  memcpy(gm->materials, def->materials, sizeof gm->materials);
  bounds(gm, model);
  gm->n_lods = gm->skinned ? 0 : (int)model->n_lods;
  for (int k = 0; k < gm->n_lods; k++) {
    upload_mesh(r, &gm->lods[k], &model->lods[k], NULL, NULL);
    gm->lods[k].closed = true;
  }
  for (size_t i = 0; i < model->n_meshes; i++) {
    if (!gm->skinned) {
      upload_mesh(r, &gm->meshes[i], &model->meshes[i], NULL, NULL);
      gm->meshes[i].closed =
          def->shape != MR_SHAPE_FILE || mr_mesh_is_closed_outward(&model->meshes[i]);
    } else {
      int rc = def->bones_rest && def->n_bones >= 1
                   ? skin_mesh(r, &gm->meshes[i], &model->meshes[i], def)
                   : -1;
      if (rc == -2) snprintf(why, why_size, "out of memory");
      if (rc == -1) snprintf(why, why_size, "cannot bind the mesh to its %d bones", def->n_bones);
      if (rc != 0) return -1;
    }
  }
  return 0;
}

/* "SCENE:LINE:COLUMN: model 'NAME': PATH: why", then the other places the
 * scene looked for the file when none had it. */
static void model_error(char *msg, size_t msg_size, const char *scene_path, const mr_model_def *def,
                        const char *why) {
  const char *what = def->shape == MR_SHAPE_FILE ? def->path : mr_shape_name(def->shape);
  if (scene_path && def->pos.line > 0)
    snprintf(msg, msg_size, "%s:%d:%d: model '%s': %s: %s", scene_path, def->pos.line,
             def->pos.column, def->name, what, why);
  else if (scene_path)
    snprintf(msg, msg_size, "%s: model '%s': %s: %s", scene_path, def->name, what, why);
  else
    snprintf(msg, msg_size, "model '%s': %s: %s", def->name, what, why);
  size_t n = msg_size ? strlen(msg) : 0;
  if (def->shape == MR_SHAPE_FILE && def->looked[0] && n + 1 < msg_size)
    snprintf(msg + n, msg_size - n, "; also looked in %s", def->looked);
}

/* A flat rectangle: centre c, half-extents along unit axes u and v,
 * facing n. */
static void upload_quad(mr_render *r, mr_gpu_mesh *g, const float c[3], const float u[3],
                        const float v[3], const float n[3]) {
  float pos[12], nor[12];
  const float su[4] = { -1, 1, 1, -1 }, sv[4] = { -1, -1, 1, 1 };
  for (int i = 0; i < 4; i++) {
    for (int k = 0; k < 3; k++) {
      pos[3 * i + k] = c[k] + su[i] * u[k] + sv[i] * v[k];
      nor[3 * i + k] = n[k];
    }
  }
  /* Counter-clockwise seen from where n points: the lit shader turns the
   * normal of a back face round. */
  vec3 uxv;
  glm_vec3_cross((float *)u, (float *)v, uxv);
  uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
  if (glm_vec3_dot(uxv, (float *)n) < 0) {
    idx[1] = 2;
    idx[2] = 1;
    idx[4] = 3;
    idx[5] = 2;
  }
  mr_mesh m = mr_mesh_of(pos, nor, 4, idx, 6, mr_default_material_def());
  upload_mesh(r, g, &m, NULL, NULL);
}

/* The floor's outline (a fan of triangles) at height y, facing up. */
static void upload_floor(mr_render *r, mr_gpu_mesh *g, float xz[5][2], size_t n, float y) {
  float pos[15], nor[15];
  uint32_t idx[9];
  for (size_t i = 0; i < n; i++) {
    pos[3 * i] = xz[i][0], pos[3 * i + 1] = y, pos[3 * i + 2] = xz[i][1];
    nor[3 * i] = 0, nor[3 * i + 1] = 1, nor[3 * i + 2] = 0;
  }
  /* The outline runs counter-clockwise seen from below (x, then z): turn
   * each triangle round to face up. */
  for (size_t t = 0; t + 2 < n; t++)
    idx[3 * t] = 0, idx[3 * t + 1] = (uint32_t)(t + 2), idx[3 * t + 2] = (uint32_t)(t + 1);
  mr_mesh m = mr_mesh_of(pos, nor, n, idx, 3 * (n - 2), mr_default_material_def());
  upload_mesh(r, g, &m, NULL, NULL);
}

/* The floor, floor_size a side at floor_height, cut at the stage's front
 * edge when the theater's set has one (set.c); the backdrop, a wall as
 * wide as the floor and 1.6 m tall, backdrop_distance behind the origin,
 * low enough that the sky shows above it from the orbit camera. */
static void scenery_create(mr_render *r, const mr_stage_def *s) {
  const float h = (float)(s->floor_size * 0.5);
  if (s->floor) {
    float xz[5][2];
    size_t n = mr_set_floor_outline(s, h, xz);
    if (n >= 3) upload_floor(r, &r->floor, xz, n, (float)s->floor_height);
  }
  if (s->backdrop) {
    const float half_h = MR_BACKDROP_HALF_HEIGHT;
    const float c[3] = { 0, (float)s->floor_height + half_h, (float)-s->backdrop_distance },
                u[3] = { h, 0, 0 }, v[3] = { 0, half_h, 0 }, n[3] = { 0, 0, 1 };
    upload_quad(r, &r->backdrop, c, u, v, n);
  }
}

static int bone_texture_create(mr_render *r, const mr_stage_def *stage, char *msg,
                               size_t msg_size) {
  GLint max_side = 0;
  r->gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
  for (size_t i = 0; i < stage->n_models; i++) {
    const mr_model_def *d = &stage->models[i];
    if (d->display == MR_DISPLAY_FREEFORM && d->n_bones > max_side) {
      model_error(msg, msg_size, NULL, d, "more bones than a texture holds");
      return -1;
    }
  }
  r->gl.GenTextures(1, &r->bone_tex);
  r->gl.BindTexture(GL_TEXTURE_2D, r->bone_tex);
  r->gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  r->gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return 0;
}

int mr_meshes_create(mr_render *r, const mr_stage_def *stage, const char *scene_path, char *msg,
                     size_t msg_size, mr_render_status *status) {
  *status = MR_RENDER_ERR_GL;
  if (bone_texture_create(r, stage, msg, msg_size) != 0) return -1;
  scenery_create(r, stage);
  if (mr_set_create(r, msg, msg_size) != 0) {
    *status = MR_RENDER_ERR_NOMEM;
    return -1;
  }
  if (mr_curtain_create(r, stage) != 0) {
    *status = MR_RENDER_ERR_NOMEM;
    snprintf(msg, msg_size, "the front curtain: out of memory");
    return -1;
  }
  r->models = calloc(stage->n_models ? stage->n_models : 1, sizeof *r->models);
  if (!r->models) {
    *status = MR_RENDER_ERR_NOMEM;
    snprintf(msg, msg_size, "out of memory");
    return -1;
  }
  r->n_models = stage->n_models;
  for (size_t i = 0; i < stage->n_models; i++) {
    const mr_model_def *def = &stage->models[i];
    mr_model model;
    char why[384] = "";
    memset(&model, 0, sizeof model);
    if (mr_model_load(def, &model, why, sizeof why) != 0) {
      *status = MR_RENDER_ERR_MODEL;
      model_error(msg, msg_size, scene_path, def, why);
      return -1;
    }
    int rc = upload_model(r, &r->models[i], &model, def, why, sizeof why);
    mr_model_free(&model);
    if (rc != 0) {
      *status = MR_RENDER_ERR_MODEL;
      model_error(msg, msg_size, scene_path, def, why);
      return -1;
    }
  }
  return 0;
}

void mr_meshes_destroy(mr_render *r) {
  for (size_t i = 0; i < r->n_models; i++) {
    for (size_t k = 0; k < r->models[i].n_meshes; k++) mr_mesh_free(r, &r->models[i].meshes[k]);
    for (int k = 0; k < r->models[i].n_lods; k++) mr_mesh_free(r, &r->models[i].lods[k]);
    free(r->models[i].meshes);
  }
  free(r->models);
  r->models = NULL;
  r->n_models = 0;
  mr_mesh_free(r, &r->floor);
  mr_mesh_free(r, &r->backdrop);
  mr_mesh_free(r, &r->curtain);
  mr_set_destroy(r);
  if (r->bone_tex) r->gl.DeleteTextures(1, &r->bone_tex);
  r->bone_tex = 0;
}

void mr_mesh_draw(mr_render *r, const mr_gpu_mesh *m) {
  if (!m->vao) return;
  r->gl.BindVertexArray(m->vao);
  r->gl.DrawElements(GL_TRIANGLES, m->n_indices, GL_UNSIGNED_INT, NULL);
  r->gl.BindVertexArray(0);
}

/* A shape's outline is a polygon of n segments about a circle of r
 * pixels, off it by at most r (1 - cos(pi / n)). */
#define MAX_OFF_PX 0.5f

const mr_gpu_mesh *mr_mesh_level(const mr_gpu_model *gm, size_t k, mat4 m, const mr_lod_scale *s) {
  if (gm->n_lods == 0 || k != 0 || !s) return &gm->meshes[k];
  /* The round part's radius: the widest of its x and z, which the shapes
   * turn about y (a link stretches y only). */
  float rx = (gm->hi[0] - gm->lo[0]) * glm_vec3_norm(m[0]);
  float rz = (gm->hi[2] - gm->lo[2]) * glm_vec3_norm(m[2]);
  float radius = 0.5f * fmaxf(rx, rz), px = INFINITY;
  vec4 c = { 0.5f * (gm->lo[0] + gm->hi[0]), 0.5f * (gm->lo[1] + gm->hi[1]),
             0.5f * (gm->lo[2] + gm->hi[2]), 1 },
       w;
  glm_mat4_mulv(m, c, w);
  float d = glm_vec3_distance(w, (float *)s->eye) - radius;
  if (d > 0.05f) px = radius * s->k / d;
  /* A shadow is seen on the frame: as fine as its pixels there, or as
   * the map's texels where they are coarser. */
  if (s->k_map > 0) px = fminf(px, radius * s->k_map);
  int level = 0;
  while (level < gm->n_lods &&
         px * (1.0f - cosf(GLM_PIf / (float)mr_shape_segments(level + 1))) <= MAX_OFF_PX)
    level++;
  return level == 0 ? &gm->meshes[0] : &gm->lods[level - 1];
}

/* mr_pose (double, w x y z) to a cglm matrix (float; cglm's quaternions
 * are x y z w). */
void mr_pose_matrix(const mr_pose *p, mat4 out) {
  versor q;
  glm_quat_init(q, (float)p->orientation[1], (float)p->orientation[2], (float)p->orientation[3],
                (float)p->orientation[0]);
  glm_quat_mat4(q, out);
  out[3][0] = (float)p->position[0];
  out[3][1] = (float)p->position[1];
  out[3][2] = (float)p->position[2];
}

void mr_item_matrix(const mr_draw_item *item, mat4 out) {
  mr_pose_matrix(&item->pose, out);
  vec3 s = { (float)item->scale[0], (float)item->scale[1], (float)item->scale[2] };
  glm_scale(out, s);
}

void mr_bones_upload(mr_render *r, const mr_draw_skin *skin) {
  float *data = mr_render_scratch(r, MR_SCRATCH_BONES, (size_t)skin->n_bones * 16 * sizeof(float));
  if (!data) return;
  for (int i = 0; i < skin->n_bones; i++) {
    mat4 m;
    mr_pose_matrix(&skin->bones[i], m);
    memcpy(data + 16 * i, m, sizeof m);
  }
  r->gl.BindTexture(GL_TEXTURE_2D, r->bone_tex);
  r->gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  r->gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, 4, skin->n_bones, 0, GL_RGBA, GL_FLOAT, data);
}
