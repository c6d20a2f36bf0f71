/* Meshes in CPU memory, between the model loader (Assimp, or the built-in
 * shapes) and the GL side, which uploads them. Placement (mr_model_def's
 * scale, then place) is already applied to positions and normals. */
#ifndef MR_RENDER_MODEL_H
#define MR_RENDER_MODEL_H

#include <stddef.h>
#include <stdint.h>

#include "mr_stage.h"

typedef struct mr_mesh {
  float *positions; /* 3 n_vertices */
  float *normals;   /* 3 n_vertices, unit */
  float *uvs;       /* 2 n_vertices, or NULL; v = 0 on the texture's top row */
  size_t n_vertices;
  uint32_t *indices; /* 3 per triangle */
  size_t n_indices;
  mr_material_def material; /* the file's own */
  /* Base colour texture, 8-bit RGBA, top row first; NULL: none. */
  uint8_t *texture;
  int texture_width, texture_height;
} mr_mesh;

typedef struct mr_model {
  mr_mesh *meshes;
  size_t n_meshes;
  /* A built-in shape's coarser levels of meshes[0] (shapes.h), placed as
   * it is: lods[k] is level k + 1. Empty for a model file. */
  mr_mesh lods[2];
  size_t n_lods;
  float bounds_min[3], bounds_max[3]; /* after placement */
} mr_model;

/* Loads def's mesh: a built-in shape, or def->path through Assimp (glTF
 * 2.0, OBJ, 3DS, FBX and whatever else Assimp reads), triangulated, with
 * normals (generated when the file has none), materials and textures
 * (embedded, or files beside the model read through stb_image). Returns 0,
 * or -1 with msg saying why ("cannot open", "not a model Assimp reads:
 * ...", "no triangles", "texture 'x.png': ...") without the file's name,
 * which the caller adds. */
int mr_model_load(const mr_model_def *def, mr_model *out, char *msg, size_t msg_size);
void mr_model_free(mr_model *m);

/* A mesh over arrays made elsewhere (the scenery's, the set's, the
 * curtain's): no uvs, no texture; it points at them, owns nothing. */
mr_mesh mr_mesh_of(float *positions, float *normals, size_t n_vertices, uint32_t *indices,
                   size_t n_indices, mr_material_def material);

#endif
