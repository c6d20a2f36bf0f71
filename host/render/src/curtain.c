/* The moving part of the set, as the renderer draws it.
 *
 * The front curtain: each half is one strip of cloth folded into pleats
 * (a sine across it, PLEAT_M apart), made once and laid out each frame
 * by its model matrix: the half's inner edge slides towards the side as
 * the curtain opens, its width shrinking to GATHERED of itself and its
 * pleats deepening as the cloth gathers. The lit shader shades the
 * folds from their normals (the matrix's inverse transpose keeps them
 * true under the stretch); a high roughness and a deep red read as
 * velvet.
 *
 * It is lit by the ambient and the sun alone, without the sun's shadow
 * and without spots (the items' shader with none: a closed or moving
 * curtain is shaded every frame over much of the picture, and the spots
 * were a third of its cost). So the still
 * scenery (still.c) keeps it while it is open, it is drawn over the kept
 * picture while it is closed or moving, and either way a frame drawn
 * whole must give the same pixels as one drawn over the kept picture.
 *
 * The follow spot is one more spot of the lit shader (its slot is the
 * last), aimed each frame at the draw list's target. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "render_internal.h"

static const double PLEAT_M = 0.22;   /* one fold's width, closed */
static const float GATHERED = 0.18f;  /* a half's width open, of its width closed */
static const float DEPTH_M = 0.025f;  /* a fold's half-depth, closed */
static const float OVERLAP_M = 0.06f; /* the halves overlap this much at the middle, closed */
enum { COLUMNS_PER_PLEAT = 8 };

/* One half in its own unit box: x from 0 (the outer edge) to 1 (the
 * inner), y from 0 (the floor) to 1 (the top), z the fold's offset, -1
 * to 1, towards the audience. */
int mr_curtain_create(mr_render *r, const mr_stage_def *stage) {
  r->curtain_place = mr_curtain_place_of(stage);
  if (!stage->curtain.show) return 0;
  int pleats = (int)lround(r->curtain_place.width / 2 / PLEAT_M);
  if (pleats < 2) pleats = 2;
  if (pleats > 200) pleats = 200;
  size_t cols = (size_t)pleats * COLUMNS_PER_PLEAT + 1, nv = 2 * cols;
  float *pos = malloc(3 * nv * sizeof *pos), *nor = malloc(3 * nv * sizeof *nor);
  uint32_t *idx = malloc(6 * (cols - 1) * sizeof *idx);
  const int made = pos && nor && idx ? 0 : -1;
  if (made == 0) {
    const double two_pi = 6.283185307179586;
    for (size_t c = 0; c < cols; c++) {
      double x = (double)c / (double)(cols - 1), a = two_pi * pleats * x;
      /* z = sin(a); its slope along x is dz/dx = 2 pi pleats cos(a). */
      double slope = two_pi * pleats * cos(a), len = sqrt(1 + slope * slope);
      for (size_t k = 0; k < 2; k++) {
        float *p = &pos[3 * (2 * c + k)], *n = &nor[3 * (2 * c + k)];
        p[0] = (float)x, p[1] = (float)k, p[2] = (float)sin(a);
        n[0] = (float)(-slope / len), n[1] = 0, n[2] = (float)(1 / len);
      }
      if (c + 1 == cols) break;
      uint32_t v = (uint32_t)(2 * c), *t = &idx[6 * c];
      t[0] = v, t[1] = v + 2, t[2] = v + 3, t[3] = v, t[4] = v + 3, t[5] = v + 1;
    }
    mr_mesh m = mr_mesh_of(pos, nor, nv, idx, 6 * (cols - 1), mr_default_material_def());
    mr_mesh_upload(r, &r->curtain, &m);
  }
  free(pos);
  free(nor);
  free(idx);
  return made;
}

void mr_curtain_matrix(const mr_render *r, float openness, int side, mat4 out) {
  const mr_curtain_place *p = &r->curtain_place;
  const float half = (float)p->width / 2;
  float o = openness < 0 ? 0 : openness > 1 ? 1 : openness;
  float w = (half + OVERLAP_M / 2) * (1 - o * (1 - GATHERED));
  /* The cloth keeps its length: gathered into a narrower width, its
   * folds stand out farther. */
  float depth = DEPTH_M * (1 + 2.0f * o);
  glm_mat4_identity(out);
  for (int k = 0; k < 3; k++) {
    out[0][k] = (float)p->right[k] * w * (float)side;
    out[1][k] = k == 1 ? (float)p->height : 0;
    out[2][k] = (float)p->normal[k] * depth;
    out[3][k] = (float)(p->origin[k] - p->right[k] * half * side);
  }
}

void mr_follow_spot_frame(const mr_render *r, const mr_draw_list *list, mr_frame *f) {
  f->follow = false;
  glm_vec3_zero(f->follow_pos);
  glm_vec3_copy((vec3){ 0, -1, 0 }, f->follow_dir);
  f->curtain = list ? (float)(1 - list->curtain_closed) : 1;
  if (r->follow_slot < 0 || !list || !list->follow_spot.on) return;
  const mr_draw_follow_spot *s = &list->follow_spot;
  vec3 dir;
  for (int k = 0; k < 3; k++) {
    f->follow_pos[k] = (float)s->position[k];
    dir[k] = (float)(s->target[k] - s->position[k]);
  }
  if (!(glm_vec3_norm(dir) > 1e-6f)) return;
  glm_vec3_normalize_to(dir, f->follow_dir);
  f->follow = true;
}
