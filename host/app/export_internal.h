/* What export.c keeps and export_gltf.c writes. Private to the export. */
#ifndef MR_APP_EXPORT_INTERNAL_H
#define MR_APP_EXPORT_INTERNAL_H

#include <stdbool.h>

#include "export.h"
#include "model.h"
#include "mr_stage.h"

/* Doubles kept per model per frame: position (3), orientation (w, x, y,
 * z), scale (3). Per bone per frame: position and orientation. */
enum { EX_ITEM = 10, EX_BONE = 7 };

/* A model shown, in the stage's order. */
typedef struct ex_model {
  int model; /* index into the stage's models */
  const mr_model_def *def;
  mr_model mesh; /* as the renderer loads it, placement applied */
  bool skin;     /* a freeform model: its bones move it */
  int material;  /* worn at the first frame (-1: the file's own) */
  int bone0;     /* skin: its first bone among every skin's */
  /* skin: per mesh, per vertex 4 bones and 4 weights (unused: 0, 0) */
  int **joints;
  float **weights;
  int slot; /* !skin: its place among the posed models */
} ex_model;

struct mr_export {
  const mr_scene *scene;
  mr_stage *stage;
  size_t n_points;
  mr_model *loaded; /* every stage model, by index */
  size_t n_loaded;
  ex_model *shown; /* fixed at the first frame */
  size_t n_shown, n_posed, n_bones;
  bool started;
  size_t n_frames, cap;
  double *t;    /* per frame */
  double *item; /* per frame, per posed model: EX_ITEM */
  double *bone; /* per frame, per bone: EX_BONE */
  double *xyz;  /* per frame, the scene's particles (3 n) */
};

static inline const double *ex_item_at(const mr_export *e, size_t f, int slot) {
  return &e->item[(f * e->n_posed + (size_t)slot) * EX_ITEM];
}
static inline const double *ex_bone_at(const mr_export *e, size_t f, size_t b) {
  return &e->bone[(f * e->n_bones + b) * EX_BONE];
}

/* Vertex v of mesh k of skin model m at frame f, blended by its bones. */
void ex_skin_vertex(const mr_export *e, const ex_model *m, size_t k, size_t v, size_t f,
                    double out[3]);

#endif
