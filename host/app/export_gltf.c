/* The kept show as a glTF 2.0 binary (.glb): the JSON through cJSON (a
 * packaged library rather than strings put together here), one binary
 * buffer with every view on a 4-byte boundary, as glTF asks.
 *
 * Nodes: one per model shown, named as the scene names it, with its mesh
 * (placement applied) and material; a particle or rigid-group model is
 * animated by translation and rotation, a link model by its scale too
 * (the stretch, along y). A freeform model is a skinned mesh whose joints,
 * its children, are its bones: bone i's pose takes world at rest to world
 * now, the mesh is at rest in world coordinates, so every inverse bind
 * matrix is the identity. Every channel has a key on every frame. */
#define _POSIX_C_SOURCE 200809L

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export_internal.h"

enum { GL_FLOAT_T = 5126, GL_UINT_T = 5125, GL_USHORT_T = 5123 };
enum { GL_ARRAY = 34962, GL_ELEMENTS = 34963 };

/* The binary buffer and the JSON arrays that describe it. */
typedef struct glb {
  uint8_t *data;
  size_t n, cap;
  cJSON *root, *views, *accessors;
  int failed;
} glb;

static int reserve(glb *g, size_t more) {
  if (g->n + more <= g->cap) return 0;
  size_t cap = g->cap ? g->cap : 1 << 16;
  while (cap < g->n + more) cap *= 2;
  uint8_t *d = realloc(g->data, cap);
  if (d == NULL) return -1;
  g->data = d;
  g->cap = cap;
  return 0;
}

/* bytes appended as a view on a 4-byte boundary; its index, -1. */
static int add_view(glb *g, const void *bytes, size_t len, int target) {
  size_t pad = (4 - g->n % 4) % 4;
  if (reserve(g, pad + len) != 0) return g->failed = 1, -1;
  memset(g->data + g->n, 0, pad);
  g->n += pad;
  cJSON *v = cJSON_CreateObject();
  cJSON_AddNumberToObject(v, "buffer", 0);
  cJSON_AddNumberToObject(v, "byteOffset", (double)g->n);
  cJSON_AddNumberToObject(v, "byteLength", (double)len);
  if (target != 0) cJSON_AddNumberToObject(v, "target", target);
  cJSON_AddItemToArray(g->views, v);
  memcpy(g->data + g->n, bytes, len);
  g->n += len;
  return cJSON_GetArraySize(g->views) - 1;
}

static int add_accessor(glb *g, int view, int comp, size_t count, const char *type) {
  cJSON *a = cJSON_CreateObject();
  cJSON_AddNumberToObject(a, "bufferView", view);
  cJSON_AddNumberToObject(a, "componentType", comp);
  cJSON_AddNumberToObject(a, "count", (double)count);
  cJSON_AddStringToObject(a, "type", type);
  cJSON_AddItemToArray(g->accessors, a);
  return cJSON_GetArraySize(g->accessors) - 1;
}

/* count elements of k floats, with their min and max. */
static int add_floats(glb *g, const float *x, size_t count, int k, const char *type, int target) {
  int view = add_view(g, x, count * (size_t)k * sizeof(float), target);
  if (view < 0) return -1;
  int a = add_accessor(g, view, GL_FLOAT_T, count, type);
  float lo[16], hi[16];
  for (int c = 0; c < k; c++) lo[c] = INFINITY, hi[c] = -INFINITY;
  for (size_t i = 0; i < count; i++)
    for (int c = 0; c < k; c++) {
      float v = x[i * (size_t)k + (size_t)c];
      lo[c] = v < lo[c] ? v : lo[c];
      hi[c] = v > hi[c] ? v : hi[c];
    }
  cJSON *acc = cJSON_GetArrayItem(g->accessors, a);
  cJSON_AddItemToObject(acc, "min", cJSON_CreateFloatArray(lo, k));
  cJSON_AddItemToObject(acc, "max", cJSON_CreateFloatArray(hi, k));
  return a;
}

static cJSON *material_json(const mr_material_def *m, const char *name) {
  cJSON *mat = cJSON_CreateObject();
  cJSON_AddStringToObject(mat, "name", name);
  cJSON *pbr = cJSON_AddObjectToObject(mat, "pbrMetallicRoughness");
  cJSON_AddItemToObject(pbr, "baseColorFactor", cJSON_CreateFloatArray(m->base_color, 4));
  cJSON_AddNumberToObject(pbr, "metallicFactor", m->metallic);
  cJSON_AddNumberToObject(pbr, "roughnessFactor", m->roughness);
  if (m->emissive[0] > 0 || m->emissive[1] > 0 || m->emissive[2] > 0)
    cJSON_AddItemToObject(mat, "emissiveFactor", cJSON_CreateFloatArray(m->emissive, 3));
  if (m->base_color[3] < 1) cJSON_AddStringToObject(mat, "alphaMode", "BLEND");
  return mat;
}

/* The joints and weights of a skinned primitive. */
static int add_skin_attributes(glb *g, const ex_model *m, size_t k, cJSON *attr) {
  size_t n = m->mesh.meshes[k].n_vertices;
  uint16_t *j = malloc(4 * n * sizeof *j + 1);
  if (j == NULL) return -1;
  for (size_t i = 0; i < 4 * n; i++) j[i] = (uint16_t)m->joints[k][i];
  int view = add_view(g, j, 4 * n * sizeof *j, GL_ARRAY);
  free(j);
  if (view < 0) return -1;
  cJSON_AddNumberToObject(attr, "JOINTS_0", add_accessor(g, view, GL_USHORT_T, n, "VEC4"));
  int w = add_floats(g, m->weights[k], n, 4, "VEC4", GL_ARRAY);
  if (w < 0) return -1;
  cJSON_AddNumberToObject(attr, "WEIGHTS_0", w);
  return 0;
}

/* Model m's meshes as one glTF mesh, a primitive each with its material. */
static int add_mesh(glb *g, const ex_model *m, cJSON *meshes, cJSON *materials) {
  cJSON *mesh = cJSON_CreateObject();
  cJSON_AddStringToObject(mesh, "name", m->def->name);
  cJSON *prims = cJSON_AddArrayToObject(mesh, "primitives");
  cJSON_AddItemToArray(meshes, mesh);
  for (size_t k = 0; k < m->mesh.n_meshes; k++) {
    const mr_mesh *me = &m->mesh.meshes[k];
    cJSON *p = cJSON_CreateObject();
    cJSON_AddItemToArray(prims, p);
    cJSON *attr = cJSON_AddObjectToObject(p, "attributes");
    int pos = add_floats(g, me->positions, me->n_vertices, 3, "VEC3", GL_ARRAY);
    int nor = add_floats(g, me->normals, me->n_vertices, 3, "VEC3", GL_ARRAY);
    int iv = add_view(g, me->indices, me->n_indices * sizeof(uint32_t), GL_ELEMENTS);
    if (pos < 0 || nor < 0 || iv < 0) return -1;
    cJSON_AddNumberToObject(attr, "POSITION", pos);
    cJSON_AddNumberToObject(attr, "NORMAL", nor);
    if (m->skin && add_skin_attributes(g, m, k, attr) != 0) return -1;
    cJSON_AddNumberToObject(p, "indices", add_accessor(g, iv, GL_UINT_T, me->n_indices, "SCALAR"));
    cJSON_AddNumberToObject(p, "mode", 4);
    const mr_material_def *mat = m->material >= 0 && m->material < m->def->n_materials
                                     ? &m->def->materials[m->material]
                                     : &me->material;
    char name[MR_STAGE_NAME_MAX + 32];
    snprintf(name, sizeof name, "%s.%zu", m->def->name, k);
    cJSON_AddItemToArray(materials, material_json(mat, name));
    cJSON_AddNumberToObject(p, "material", cJSON_GetArraySize(materials) - 1);
  }
  return cJSON_GetArraySize(meshes) - 1;
}

/* A node's rest transform: its pose (and scale) at the first frame. */
static void put_trs(cJSON *node, const double *k, bool scale) {
  float tr[3] = { (float)k[0], (float)k[1], (float)k[2] };
  float q[4] = { (float)k[4], (float)k[5], (float)k[6], (float)k[3] };
  cJSON_AddItemToObject(node, "translation", cJSON_CreateFloatArray(tr, 3));
  cJSON_AddItemToObject(node, "rotation", cJSON_CreateFloatArray(q, 4));
  if (scale) {
    float s[3] = { (float)k[7], (float)k[8], (float)k[9] };
    cJSON_AddItemToObject(node, "scale", cJSON_CreateFloatArray(s, 3));
  }
}

/* A channel of a node's path, its keys taken from every frame's doubles
 * at `at` (stride doubles apart): k of them, or a quaternion (w, x, y, z)
 * turned into glTF's (x, y, z, w), made unit in float. */
typedef struct track {
  const double *at;
  size_t stride;
  int k;
  bool quat;
} track;

static int add_channel(glb *g, const mr_export *e, cJSON *anim, int times, int node,
                       const char *path, track tr) {
  size_t nf = e->n_frames;
  float *x = malloc(nf * (size_t)tr.k * sizeof *x + 1);
  if (x == NULL) return -1;
  for (size_t f = 0; f < nf; f++) {
    const double *d = tr.at + f * tr.stride;
    float *o = &x[f * (size_t)tr.k];
    if (tr.quat) {
      double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + d[3] * d[3]);
      o[0] = (float)(d[1] / len), o[1] = (float)(d[2] / len);
      o[2] = (float)(d[3] / len), o[3] = (float)(d[0] / len);
    } else {
      for (int c = 0; c < tr.k; c++) o[c] = (float)d[c];
    }
  }
  int out = add_floats(g, x, nf, tr.k, tr.k == 4 ? "VEC4" : "VEC3", 0);
  free(x);
  if (out < 0) return -1;
  cJSON *samplers = cJSON_GetObjectItem(anim, "samplers");
  cJSON *s = cJSON_CreateObject();
  cJSON_AddNumberToObject(s, "input", times);
  cJSON_AddNumberToObject(s, "output", out);
  cJSON_AddStringToObject(s, "interpolation", "LINEAR");
  cJSON_AddItemToArray(samplers, s);
  cJSON *c = cJSON_CreateObject();
  cJSON_AddNumberToObject(c, "sampler", cJSON_GetArraySize(samplers) - 1);
  cJSON *target = cJSON_AddObjectToObject(c, "target");
  cJSON_AddNumberToObject(target, "node", node);
  cJSON_AddStringToObject(target, "path", path);
  cJSON_AddItemToArray(cJSON_GetObjectItem(anim, "channels"), c);
  return 0;
}

/* The joints of skin model m: nodes after its own, its children. */
static int add_joints(glb *g, const mr_export *e, const ex_model *m, cJSON *nodes, cJSON *model,
                      cJSON *skins, cJSON *anim, int times) {
  int nb = m->def->n_bones, first = cJSON_GetArraySize(nodes);
  cJSON *children = cJSON_AddArrayToObject(model, "children");
  cJSON *skin = cJSON_CreateObject();
  cJSON *joints = cJSON_AddArrayToObject(skin, "joints");
  for (int b = 0; b < nb; b++) {
    cJSON *node = cJSON_CreateObject();
    int id = m->def->bones[b];
    char name[MR_STAGE_NAME_MAX + 80];
    if (id >= 0 && (size_t)id < e->scene->n_particles)
      snprintf(name, sizeof name, "%s/%s", m->def->name, e->scene->particles[id].name);
    else
      snprintf(name, sizeof name, "%s/bone%d", m->def->name, b);
    cJSON_AddStringToObject(node, "name", name);
    put_trs(node, ex_bone_at(e, 0, (size_t)(m->bone0 + b)), false);
    cJSON_AddItemToArray(nodes, node);
    cJSON_AddItemToArray(children, cJSON_CreateNumber(first + b));
    cJSON_AddItemToArray(joints, cJSON_CreateNumber(first + b));
    const double *at = ex_bone_at(e, 0, (size_t)(m->bone0 + b));
    size_t stride = e->n_bones * EX_BONE;
    if (add_channel(g, e, anim, times, first + b, "translation", (track){ at, stride, 3, false }) ||
        add_channel(g, e, anim, times, first + b, "rotation", (track){ at + 3, stride, 4, true }))
      return -1;
  }
  float *ibm = calloc((size_t)nb * 16 + 1, sizeof *ibm);
  if (ibm == NULL) return -1;
  for (int b = 0; b < nb; b++)
    for (int d = 0; d < 4; d++) ibm[16 * b + 5 * d] = 1;
  int view = add_view(g, ibm, (size_t)nb * 16 * sizeof *ibm, 0);
  free(ibm);
  if (view < 0) return -1;
  cJSON_AddNumberToObject(skin, "inverseBindMatrices",
                          add_accessor(g, view, GL_FLOAT_T, (size_t)nb, "MAT4"));
  cJSON_AddStringToObject(skin, "name", m->def->name);
  cJSON_AddItemToArray(skins, skin);
  cJSON_AddNumberToObject(model, "skin", cJSON_GetArraySize(skins) - 1);
  return 0;
}

static int add_model(glb *g, const mr_export *e, const ex_model *m, cJSON *roots, cJSON *anim,
                     int times) {
  cJSON *r = g->root;
  cJSON *nodes = cJSON_GetObjectItem(r, "nodes");
  int mesh = add_mesh(g, m, cJSON_GetObjectItem(r, "meshes"), cJSON_GetObjectItem(r, "materials"));
  if (mesh < 0) return -1;
  cJSON *node = cJSON_CreateObject();
  int id = cJSON_GetArraySize(nodes);
  cJSON_AddStringToObject(node, "name", m->def->name);
  cJSON_AddNumberToObject(node, "mesh", mesh);
  cJSON_AddItemToArray(nodes, node);
  cJSON_AddItemToArray(roots, cJSON_CreateNumber(id));
  if (m->skin)
    return add_joints(g, e, m, nodes, node, cJSON_GetObjectItem(r, "skins"), anim, times);
  bool link = m->def->display == MR_DISPLAY_LINK;
  const double *at = ex_item_at(e, 0, m->slot);
  size_t stride = e->n_posed * EX_ITEM;
  put_trs(node, at, true);
  if (add_channel(g, e, anim, times, id, "translation", (track){ at, stride, 3, false }) ||
      add_channel(g, e, anim, times, id, "rotation", (track){ at + 3, stride, 4, true }))
    return -1;
  if (link && add_channel(g, e, anim, times, id, "scale", (track){ at + 7, stride, 3, false }))
    return -1;
  return 0;
}

/* The whole JSON document, the buffer filled alongside. */
static int build(glb *g, const mr_export *e) {
  cJSON *r = g->root = cJSON_CreateObject();
  cJSON *asset = cJSON_AddObjectToObject(r, "asset");
  cJSON_AddStringToObject(asset, "version", "2.0");
  cJSON_AddStringToObject(asset, "generator", "marionette export");
  cJSON_AddNumberToObject(r, "scene", 0);
  cJSON *scene = cJSON_CreateObject();
  cJSON_AddStringToObject(scene, "name", e->scene->name);
  cJSON *roots = cJSON_AddArrayToObject(scene, "nodes");
  cJSON_AddItemToArray(cJSON_AddArrayToObject(r, "scenes"), scene);
  cJSON_AddArrayToObject(r, "nodes");
  cJSON_AddArrayToObject(r, "meshes");
  cJSON_AddArrayToObject(r, "materials");
  cJSON_AddArrayToObject(r, "skins");
  cJSON *anim = cJSON_CreateObject();
  cJSON_AddStringToObject(anim, "name", "show");
  cJSON_AddArrayToObject(anim, "channels");
  cJSON_AddArrayToObject(anim, "samplers");
  cJSON_AddItemToArray(cJSON_AddArrayToObject(r, "animations"), anim);
  g->accessors = cJSON_AddArrayToObject(r, "accessors");
  g->views = cJSON_AddArrayToObject(r, "bufferViews");
  float *t = malloc(e->n_frames * sizeof *t + 1);
  if (t == NULL) return -1;
  for (size_t f = 0; f < e->n_frames; f++) t[f] = (float)e->t[f];
  int times = add_floats(g, t, e->n_frames, 1, "SCALAR", 0);
  free(t);
  if (times < 0) return -1;
  for (size_t i = 0; i < e->n_shown; i++)
    if (add_model(g, e, &e->shown[i], roots, anim, times) != 0) return -1;
  if (cJSON_GetArraySize(cJSON_GetObjectItem(r, "skins")) == 0)
    cJSON_DeleteItemFromObject(r, "skins");
  cJSON *buf = cJSON_CreateObject();
  cJSON_AddNumberToObject(buf, "byteLength", (double)((g->n + 3) / 4 * 4));
  cJSON_AddItemToArray(cJSON_AddArrayToObject(r, "buffers"), buf);
  return g->failed ? -1 : 0;
}

static int put_u32(FILE *f, uint32_t v) {
  uint8_t b[4] = { (uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24) };
  return fwrite(b, 1, 4, f) == 4 ? 0 : -1;
}

/* The header, the JSON chunk padded with spaces, the BIN chunk with
 * zeros, each to a multiple of 4 bytes. */
static int write_file(FILE *f, const char *json, const glb *g) {
  size_t jn = strlen(json), jp = (4 - jn % 4) % 4;
  size_t bn = g->n, bp = (4 - bn % 4) % 4;
  size_t total = 12 + 8 + jn + jp + 8 + bn + bp;
  if (total > UINT32_MAX) return -1;
  static const char spaces[3] = { ' ', ' ', ' ' }, zeros[3] = { 0, 0, 0 };
  int bad = put_u32(f, 0x46546C67u) | put_u32(f, 2) | put_u32(f, (uint32_t)total);
  bad |= put_u32(f, (uint32_t)(jn + jp)) | put_u32(f, 0x4E4F534Au);
  bad |= fwrite(json, 1, jn, f) != jn || fwrite(spaces, 1, jp, f) != jp;
  bad |= put_u32(f, (uint32_t)(bn + bp)) | put_u32(f, 0x004E4942u);
  bad |= fwrite(g->data, 1, bn, f) != bn || fwrite(zeros, 1, bp, f) != bp;
  return bad ? -1 : 0;
}

int mr_export_write_glb(const mr_export *e, const char *path, char *msg, size_t msg_size) {
  if (e->n_frames == 0) {
    snprintf(msg, msg_size, "%s: no frame to export", path);
    return -1;
  }
  glb g;
  memset(&g, 0, sizeof g);
  char *json = NULL;
  int rc = build(&g, e);
  if (rc == 0) json = cJSON_PrintUnformatted(g.root);
  if (rc != 0 || json == NULL) {
    snprintf(msg, msg_size, "%s: out of memory", path);
    rc = -1;
  } else {
    FILE *f = fopen(path, "wb");
    if (f == NULL) {
      snprintf(msg, msg_size, "%s: cannot create: %s", path, strerror(errno));
      rc = -1;
    } else {
      rc = write_file(f, json, &g);
      if (fclose(f) != 0) rc = -1;
      if (rc != 0) snprintf(msg, msg_size, "%s: cannot write: %s", path, strerror(errno));
    }
  }
  cJSON_free(json);
  cJSON_Delete(g.root);
  free(g.data);
  return rc;
}
