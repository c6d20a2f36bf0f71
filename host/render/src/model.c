/* The model loader: a built-in shape, or a model file through Assimp's C
 * API (glTF 2.0, OBJ, 3DS, FBX, ...), into meshes in CPU memory with their
 * materials and base-colour textures, placed as the scene says. */
#include "model.h"

#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#include "mr_pose.h"
#include "shapes.h"

/* The shapes' surface until a scene gives one: mr_default_material_def's
 * values, kept here so that the loader stands alone. */
static const mr_material_def default_material = {
  MR_DEF_COOKIE, { 0.8f, 0.8f, 0.8f, 1.0f }, 0.6f, 0.0f, { 0 }
};

static int fail(char *msg, size_t msg_size, const char *fmt, ...) {
  if (msg && msg_size) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, msg_size, fmt, ap);
    va_end(ap);
  }
  return -1;
}

static float clamp01(float x) {
  return x > 0 ? (x < 1 ? x : 1) : 0; /* NaN too goes to 0 */
}

/* One float of a material. Assimp's own aiGetMaterialFloat is a C99
 * inline definition with no external one, which links only when the
 * compiler chooses to inline it (not at -O0). */
static int get_float(const struct aiMaterial *am, const char *key, unsigned type, unsigned index,
                     ai_real *out) {
  return aiGetMaterialFloatArray(am, key, type, index, out, NULL) == aiReturn_SUCCESS;
}

/* The metal-rough model when the file has it (glTF), else Phong's diffuse
 * and shininess kept as mr_stage.h says. */
static void read_material(const struct aiMaterial *am, mr_material_def *out) {
  struct aiColor4D c;
  ai_real f;
  *out = default_material;
  if (aiGetMaterialColor(am, AI_MATKEY_BASE_COLOR, &c) == aiReturn_SUCCESS ||
      aiGetMaterialColor(am, AI_MATKEY_COLOR_DIFFUSE, &c) == aiReturn_SUCCESS) {
    out->base_color[0] = clamp01(c.r);
    out->base_color[1] = clamp01(c.g);
    out->base_color[2] = clamp01(c.b);
    out->base_color[3] = clamp01(c.a);
  }
  if (get_float(am, AI_MATKEY_OPACITY, &f))
    out->base_color[3] = clamp01((float)f) * out->base_color[3];
  if (get_float(am, AI_MATKEY_ROUGHNESS_FACTOR, &f))
    out->roughness = clamp01((float)f);
  else if (get_float(am, AI_MATKEY_SHININESS, &f) && f >= 0)
    out->roughness = clamp01((float)sqrt(2.0 / (f + 2.0)));
  if (get_float(am, AI_MATKEY_METALLIC_FACTOR, &f)) out->metallic = clamp01((float)f);
  if (aiGetMaterialColor(am, AI_MATKEY_COLOR_EMISSIVE, &c) == aiReturn_SUCCESS) {
    out->emissive[0] = clamp01(c.r);
    out->emissive[1] = clamp01(c.g);
    out->emissive[2] = clamp01(c.b);
  }
}

/* An embedded texture: "*N" names the scene's N-th, else one whose own
 * file name matches (glTF and FBX keep them so). */
static const struct aiTexture *embedded_texture(const struct aiScene *sc, const char *name) {
  if (name[0] == '*') {
    char *end;
    long k = strtol(name + 1, &end, 10);
    return (*end == '\0' && k >= 0 && (unsigned long)k < sc->mNumTextures) ? sc->mTextures[k]
                                                                           : NULL;
  }
  for (unsigned i = 0; i < sc->mNumTextures; i++)
    if (strcmp(sc->mTextures[i]->mFilename.data, name) == 0) return sc->mTextures[i];
  return NULL;
}

/* Decodes an embedded texture: compressed bytes (PNG, JPEG) through
 * stb_image, or raw texels (B, G, R, A), into RGBA rows top first. */
static uint8_t *decode_embedded(const struct aiTexture *t, int *w, int *h) {
  if (t->mHeight == 0) {
    int n;
    if (t->mWidth > (unsigned)INT32_MAX) return NULL;
    return stbi_load_from_memory((const stbi_uc *)t->pcData, (int)t->mWidth, w, h, &n, 4);
  }
  if (t->mWidth > 16384 || t->mHeight > 16384) return NULL;
  size_t n = (size_t)t->mWidth * t->mHeight;
  uint8_t *px = malloc(4 * n);
  if (!px) return NULL;
  for (size_t i = 0; i < n; i++) {
    px[4 * i] = t->pcData[i].r;
    px[4 * i + 1] = t->pcData[i].g;
    px[4 * i + 2] = t->pcData[i].b;
    px[4 * i + 3] = t->pcData[i].a;
  }
  *w = (int)t->mWidth, *h = (int)t->mHeight;
  return px;
}

/* A texture file named by the model: relative to the model's folder,
 * with any Windows separators turned round. *why says what went wrong. */
static uint8_t *load_texture_file(const char *model_path, const char *name, int *w, int *h,
                                  const char **why) {
  char path[2 * MR_STAGE_PATH_MAX];
  const char *slash = strrchr(model_path, '/');
  int dir_len = (name[0] == '/' || !slash) ? 0 : (int)(slash - model_path + 1);
  int n = snprintf(path, sizeof path, "%.*s%s", dir_len, model_path, name);
  if (n < 0 || (size_t)n >= sizeof path) {
    *why = "path too long";
    return NULL;
  }
  for (char *p = path + dir_len; *p; p++)
    if (*p == '\\') *p = '/';
  FILE *f = fopen(path, "rb");
  if (!f) {
    *why = strerror(errno);
    return NULL;
  }
  int comp;
  uint8_t *px = stbi_load_from_file(f, w, h, &comp, 4);
  fclose(f);
  if (!px) *why = stbi_failure_reason();
  return px;
}

/* The material's base-colour (else diffuse) texture, if it has one. */
static int read_texture(const struct aiScene *sc, const struct aiMaterial *am,
                        const char *model_path, mr_mesh *mesh, char *msg, size_t msg_size) {
  struct aiString name;
  if (aiGetMaterialTexture(am, aiTextureType_BASE_COLOR, 0, &name, NULL, NULL, NULL, NULL, NULL,
                           NULL) != aiReturn_SUCCESS &&
      aiGetMaterialTexture(am, aiTextureType_DIFFUSE, 0, &name, NULL, NULL, NULL, NULL, NULL,
                           NULL) != aiReturn_SUCCESS)
    return 0;
  const struct aiTexture *t = embedded_texture(sc, name.data);
  int w = 0, h = 0;
  const char *why = NULL;
  uint8_t *px;
  if (t) {
    px = decode_embedded(t, &w, &h);
    if (!px) why = stbi_failure_reason();
  } else {
    px = load_texture_file(model_path, name.data, &w, &h, &why);
  }
  if (!px) return fail(msg, msg_size, "texture '%s': %s", name.data, why ? why : "cannot be read");
  mesh->texture = px;
  mesh->texture_width = w;
  mesh->texture_height = h;
  return 0;
}

/* Copies one of Assimp's triangle meshes: after aiProcess_SortByPType a
 * mesh holding triangles holds nothing else, but faces are checked all
 * the same. */
static int copy_mesh(const struct aiMesh *am, mr_mesh *m) {
  size_t nt = 0;
  for (unsigned f = 0; f < am->mNumFaces; f++) nt += am->mFaces[f].mNumIndices == 3;
  if (mr_mesh_alloc(m, am->mNumVertices, nt, am->mTextureCoords[0] != NULL) != 0) return -1;
  for (size_t v = 0; v < am->mNumVertices; v++) {
    const struct aiVector3D *p = &am->mVertices[v];
    struct aiVector3D n = am->mNormals ? am->mNormals[v] : (struct aiVector3D){ 0, 1, 0 };
    m->positions[3 * v] = (float)p->x;
    m->positions[3 * v + 1] = (float)p->y;
    m->positions[3 * v + 2] = (float)p->z;
    m->normals[3 * v] = (float)n.x;
    m->normals[3 * v + 1] = (float)n.y;
    m->normals[3 * v + 2] = (float)n.z;
    if (m->uvs) {
      m->uvs[2 * v] = (float)am->mTextureCoords[0][v].x;
      m->uvs[2 * v + 1] = (float)am->mTextureCoords[0][v].y;
    }
  }
  size_t k = 0;
  for (unsigned f = 0; f < am->mNumFaces; f++) {
    const struct aiFace *face = &am->mFaces[f];
    if (face->mNumIndices != 3) continue;
    for (int i = 0; i < 3; i++) m->indices[k++] = face->mIndices[i];
  }
  return 0;
}

static int is_triangle_mesh(const struct aiMesh *am) {
  return (am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) && am->mNumVertices > 0;
}

/* Every triangle mesh of the scene, with its material and texture. */
static int copy_scene(const struct aiScene *sc, const char *path, mr_model *out, char *msg,
                      size_t msg_size) {
  size_t n = 0;
  for (unsigned i = 0; i < sc->mNumMeshes; i++) n += is_triangle_mesh(sc->mMeshes[i]);
  if (n == 0) return fail(msg, msg_size, "no triangles");
  out->meshes = calloc(n, sizeof *out->meshes);
  if (!out->meshes) return fail(msg, msg_size, "out of memory");
  for (unsigned i = 0; i < sc->mNumMeshes; i++) {
    const struct aiMesh *am = sc->mMeshes[i];
    if (!is_triangle_mesh(am)) continue;
    mr_mesh *m = &out->meshes[out->n_meshes];
    if (copy_mesh(am, m) != 0) return fail(msg, msg_size, "out of memory");
    out->n_meshes++;
    m->material = default_material;
    if (am->mMaterialIndex < sc->mNumMaterials) {
      const struct aiMaterial *mat = sc->mMaterials[am->mMaterialIndex];
      read_material(mat, &m->material);
      if (read_texture(sc, mat, path, m, msg, msg_size) != 0) return -1;
    }
  }
  return 0;
}

static int load_file(const char *path, mr_model *out, char *msg, size_t msg_size) {
  /* Assimp's own message for a missing file names it; ours says why only. */
  FILE *f = fopen(path, "rb");
  if (!f) return fail(msg, msg_size, "cannot open: %s", strerror(errno));
  fclose(f);
  /* PreTransformVertices bakes the node hierarchy into the vertices, so
   * every mesh is in the model's own coordinates; FlipUVs puts v = 0 on
   * the texture's top row, the row stb_image gives first. */
  const struct aiScene *sc = aiImportFile(
      path, aiProcess_Triangulate | aiProcess_GenSmoothNormals | aiProcess_JoinIdenticalVertices |
                aiProcess_PreTransformVertices | aiProcess_SortByPType | aiProcess_FlipUVs);
  if (!sc) return fail(msg, msg_size, "not a model Assimp reads: %s", aiGetErrorString());
  int rc = copy_scene(sc, path, out, msg, msg_size);
  aiReleaseImport(sc);
  return rc;
}

/* Positions that are not numbers are refused: nothing sensible can be
 * drawn from them. A normal that is not one (Assimp makes NaN for a
 * triangle of no area) only loses its shading: it is set to +y. */
_Static_assert(MR_SHAPE_LEVELS - 1 <= sizeof((mr_model *)0)->lods / sizeof(mr_mesh),
               "a model holds every coarser level of a shape");

/* Mesh k of the model, its coarser levels after its meshes. */
static mr_mesh *mesh_at(mr_model *m, size_t k) {
  return k < m->n_meshes ? &m->meshes[k] : &m->lods[k - m->n_meshes];
}

static int check_finite(mr_model *m, char *msg, size_t msg_size) {
  for (size_t k = 0; k < m->n_meshes + m->n_lods; k++) {
    mr_mesh *mesh = mesh_at(m, k);
    for (size_t v = 0; v < mesh->n_vertices; v++) {
      const float *p = &mesh->positions[3 * v];
      float *n = &mesh->normals[3 * v];
      if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
        return fail(msg, msg_size, "vertex %zu of mesh %zu is not a finite number", v, k);
      if (!isfinite(n[0]) || !isfinite(n[1]) || !isfinite(n[2]) ||
          n[0] * n[0] + n[1] * n[1] + n[2] * n[2] < 1e-12f)
        n[0] = 0, n[1] = 1, n[2] = 0;
    }
    for (size_t i = 0; i < mesh->n_indices; i++)
      if (mesh->indices[i] >= mesh->n_vertices)
        return fail(msg, msg_size, "mesh %zu names vertex %u of %zu", k, mesh->indices[i],
                    mesh->n_vertices);
  }
  return 0;
}

/* Scale, then turn, then move. A normal goes through the inverse
 * transpose, here R S⁻¹ (R is orthonormal, S diagonal), and is made unit
 * again; a scale that mirrors (odd count of negative factors) would turn
 * faces inside out, so their winding is reversed. */
static void place_model(mr_model *m, const double s[3], const mr_pose *pose) {
  int mirror = s[0] * s[1] * s[2] < 0;
  for (size_t k = 0; k < m->n_meshes + m->n_lods; k++) {
    mr_mesh *mesh = mesh_at(m, k);
    for (size_t v = 0; v < mesh->n_vertices; v++) {
      float *p = &mesh->positions[3 * v], *n = &mesh->normals[3 * v];
      double ps[3] = { p[0] * s[0], p[1] * s[1], p[2] * s[2] }, pw[3];
      double ns[3] = { n[0] / s[0], n[1] / s[1], n[2] / s[2] }, nw[3];
      mr_pose_apply(pose, ps, pw);
      mr_pose_rotate(pose->orientation, ns, nw);
      double len = sqrt(nw[0] * nw[0] + nw[1] * nw[1] + nw[2] * nw[2]);
      for (int i = 0; i < 3; i++) {
        p[i] = (float)pw[i];
        n[i] = len > 0 ? (float)(nw[i] / len) : (i == 1);
      }
    }
    for (size_t t = 0; mirror && t + 2 < mesh->n_indices; t += 3) {
      uint32_t tmp = mesh->indices[t + 1];
      mesh->indices[t + 1] = mesh->indices[t + 2];
      mesh->indices[t + 2] = tmp;
    }
  }
}

static void compute_bounds(mr_model *m) {
  for (int i = 0; i < 3; i++) m->bounds_min[i] = INFINITY, m->bounds_max[i] = -INFINITY;
  for (size_t k = 0; k < m->n_meshes; k++)
    for (size_t v = 0; v < m->meshes[k].n_vertices; v++)
      for (int i = 0; i < 3; i++) {
        float x = m->meshes[k].positions[3 * v + i];
        if (x < m->bounds_min[i]) m->bounds_min[i] = x;
        if (x > m->bounds_max[i]) m->bounds_max[i] = x;
      }
}

static int check_placement(const mr_model_def *def, mr_pose *pose, char *msg, size_t msg_size) {
  for (int i = 0; i < 3; i++)
    if (!isfinite(def->scale[i]) || def->scale[i] == 0)
      return fail(msg, msg_size, "scale must be finite and not 0");
  *pose = def->place;
  if (mr_pose_normalize(pose) != 0 || !mr_pose_is_finite(pose))
    return fail(msg, msg_size, "placement is not a finite pose");
  return 0;
}

int mr_model_load(const mr_model_def *def, mr_model *out, char *msg, size_t msg_size) {
  if (!out) return fail(msg, msg_size, "no model to load into");
  memset(out, 0, sizeof *out);
  if (!def) return fail(msg, msg_size, "no model definition");
  if (def->shape == MR_SHAPE_FILE && !memchr(def->path, '\0', sizeof def->path))
    return fail(msg, msg_size, "path longer than %d bytes", MR_STAGE_PATH_MAX - 1);
  mr_pose pose;
  if (check_placement(def, &pose, msg, msg_size) != 0) return -1;
  int rc;
  if (def->shape == MR_SHAPE_FILE) {
    rc = load_file(def->path, out, msg, msg_size);
  } else {
    out->meshes = calloc(1, sizeof *out->meshes);
    rc = out->meshes && mr_shape_mesh(def->shape, out->meshes) == 0
             ? 0
             : fail(msg, msg_size, "not a built-in shape, or out of memory");
    if (rc == 0) out->n_meshes = 1, out->meshes[0].material = default_material;
    for (int k = 1; rc == 0 && k < MR_SHAPE_LEVELS; k++) {
      rc = mr_shape_mesh_lod(def->shape, k, &out->lods[k - 1]) == 0
               ? 0
               : fail(msg, msg_size, "out of memory");
      if (rc == 0) out->n_lods++, out->lods[k - 1].material = default_material;
    }
  }
  if (rc == 0) rc = check_finite(out, msg, msg_size);
  if (rc != 0) {
    mr_model_free(out);
    return -1;
  }
  place_model(out, def->scale, &pose);
  compute_bounds(out);
  return 0;
}

mr_mesh mr_mesh_of(float *positions, float *normals, size_t n_vertices, uint32_t *indices,
                   size_t n_indices, mr_material_def material) {
  mr_mesh m;
  memset(&m, 0, sizeof m);
  m.positions = positions;
  m.normals = normals;
  m.n_vertices = n_vertices;
  m.indices = indices;
  m.n_indices = n_indices;
  m.material = material;
  return m;
}

void mr_model_free(mr_model *m) {
  if (!m) return;
  for (size_t k = 0; k < m->n_meshes; k++) mr_mesh_release(&m->meshes[k]);
  for (size_t k = 0; k < m->n_lods; k++) mr_mesh_release(&m->lods[k]);
  free(m->meshes);
  memset(m, 0, sizeof *m);
}
