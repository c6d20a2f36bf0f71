/* The sun's shadow: a depth map seen from the sun through an orthographic
 * box fitted to what casts (the models with cast_shadow, as posed this
 * frame), so its texels go where the shadows can be, not over the whole
 * floor. It is drawn again only when the sun or a caster has moved: the
 * frame's key (the sun's matrix and every caster's) is kept and compared.
 * The lit pass compares against it, percentage-closer filtered
 * (shader_src.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render_internal.h"

/* "Sized to the view": the smallest power of two at least half the
 * frame's longer side on a GPU, a quarter in software, 256 to 2048
 * texels; the scene's shadow_size wins. The map covers the casters only,
 * so a quarter still gives about a texel a pixel where a puppet fills
 * the frame's height, and a 1280x720 frame drawn in software spends
 * 17 M fewer instructions (of 322 M) drawing it again each frame. */
static int shadow_side(const mr_render *r, int max_side) {
  int side = r->stage.lights.shadow_size;
  if (side < 1) {
    int want = (r->width > r->height ? r->width : r->height) / (r->software ? 4 : 2);
    for (side = 256; side < want && side < 2048; side *= 2) {
    }
  }
  return side > max_side ? max_side : side;
}

int mr_shadow_create(mr_render *r, char *msg, size_t msg_size) {
  const mr_gl *gl = &r->gl;
  GLint max_side = 0;
  gl->GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
  /* Without shadows the map is one texel, so the shader's sampler always
   * has a depth texture behind it. */
  int side = r->stage.lights.shadows ? shadow_side(r, max_side) : 1;
  r->shadow_size = side;
  gl->GenTextures(1, &r->shadow_tex);
  gl->BindTexture(GL_TEXTURE_2D, r->shadow_tex);
  gl->TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, side, side, 0, GL_DEPTH_COMPONENT,
                 GL_UNSIGNED_INT, NULL);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  gl->GenFramebuffers(1, &r->shadow_fbo);
  gl->BindFramebuffer(GL_FRAMEBUFFER, r->shadow_fbo);
  gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, r->shadow_tex, 0);
  const GLenum none = GL_NONE; /* glDrawBuffers: glDrawBuffer is desktop only */
  gl->DrawBuffers(1, &none);
  gl->ReadBuffer(GL_NONE);
  GLenum st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
  gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
  if (st != GL_FRAMEBUFFER_COMPLETE) {
    snprintf(msg, msg_size, "the shadow map's framebuffer is incomplete (0x%x)", (unsigned)st);
    return -1;
  }
  return 0;
}

void mr_shadow_destroy(mr_render *r) {
  if (r->shadow_fbo) r->gl.DeleteFramebuffers(1, &r->shadow_fbo);
  if (r->shadow_tex) r->gl.DeleteTextures(1, &r->shadow_tex);
  r->shadow_fbo = r->shadow_tex = 0;
  free(r->shadow_key);
  r->shadow_key = NULL;
  r->shadow_key_len = 0;
  r->shadow_drawn = false;
}

/* The sun's view of a box of half-side R about the stage's middle, R the
 * floor's half diagonal (and at least reaching the backdrop): the depth
 * range holds the whole stage. */
static float light_view(const mr_render *r, const mr_frame *f, mat4 view) {
  const mr_stage_def *s = &r->stage;
  float R = (float)(s->floor_size * 0.5 * 1.4143);
  if (s->backdrop && R < (float)s->backdrop_distance + 0.5f) R = (float)s->backdrop_distance + 0.5f;
  if (R < 2) R = 2;
  vec3 centre = { 0, (float)s->floor_height, 0 }, eye, up = { 0, 0, 1 };
  glm_vec3_scale((float *)f->sun_dir, 2 * R, eye);
  glm_vec3_add(eye, centre, eye);
  /* Up must not be along the sun: z is never, while the sun stays in
   * the x-y plane tilted towards +z (sky.c). */
  if (fabsf(f->sun_dir[2]) > 0.99f) {
    up[1] = 1;
    up[2] = 0;
  }
  glm_lookat(eye, centre, up, view);
  return R;
}

/* What a frame's shadow depends on, gathered as it is worked out: each
 * caster's model and matrix, and the sun's matrix. A key that lost a
 * part to a failed allocation never matches. */
typedef struct key {
  float *data;
  size_t len, cap;
  bool lost;
} key;

static void key_add(key *k, const float *v, size_t n) {
  if (k->lost) return;
  if (k->len + n > k->cap) {
    size_t cap = (k->len + n) * 2;
    float *d = realloc(k->data, cap * sizeof *d);
    if (!d) {
      k->lost = true;
      return;
    }
    k->data = d;
    k->cap = cap;
  }
  memcpy(k->data + k->len, v, n * sizeof *v);
  k->len += n;
}

/* Grows the box [lo, hi] (x, y in the sun's view) by the model's box
 * moved by m (the sun's view times the model matrix). */
static void grow(const mr_gpu_model *gm, mat4 m, float lo[2], float hi[2]) {
  for (int c = 0; c < 8; c++) {
    vec4 p = { c & 1 ? gm->hi[0] : gm->lo[0], c & 2 ? gm->hi[1] : gm->lo[1],
               c & 4 ? gm->hi[2] : gm->lo[2], 1 },
         q;
    glm_mat4_mulv(m, p, q);
    for (int k = 0; k < 2; k++) {
      if (q[k] < lo[k]) lo[k] = q[k];
      if (q[k] > hi[k]) hi[k] = q[k];
    }
  }
}

/* The casters' box in the sun's view, and their matrices into the key.
 * A skin's vertices are blends of its bones' moves of its rest pose, so
 * they lie in the box of its rest box moved by each bone. Returns how
 * many casters there are. */
static size_t casters_box(const mr_render *r, const mr_draw_list *list, mat4 view, float lo[2],
                          float hi[2], key *k) {
  size_t n = 0;
  for (size_t i = 0; i < list->n_items; i++) {
    const mr_draw_item *it = &list->items[i];
    if (it->model < 0 || (size_t)it->model >= r->n_models) continue;
    const mr_gpu_model *gm = &r->models[it->model];
    if (gm->skinned || !gm->cast_shadow || gm->n_meshes == 0) continue;
    mat4 m, vm;
    mr_item_matrix(it, m);
    key_add(k, &(float){ (float)it->model }, 1);
    key_add(k, (const float *)m, 16);
    glm_mat4_mul(view, m, vm);
    grow(gm, vm, lo, hi);
    n++;
  }
  for (size_t i = 0; i < list->n_skins; i++) {
    const mr_draw_skin *sk = &list->skins[i];
    if (sk->model < 0 || (size_t)sk->model >= r->n_models) continue;
    const mr_gpu_model *gm = &r->models[sk->model];
    if (!gm->skinned || !gm->cast_shadow || sk->n_bones < gm->n_bones || !sk->bones) continue;
    key_add(k, &(float){ (float)sk->model }, 1);
    for (int b = 0; b < gm->n_bones; b++) {
      mat4 m, vm;
      mr_pose_matrix(&sk->bones[b], m);
      key_add(k, (const float *)m, 16);
      glm_mat4_mul(view, m, vm);
      grow(gm, vm, lo, hi);
    }
    n++;
  }
  return n;
}

/* The sun's matrix: its view, and a square box about the casters with a
 * margin for the filter, never wider than the stage's. 0 when nothing
 * casts. */
static int light_matrix(const mr_render *r, const mr_draw_list *list, mr_frame *f, key *k) {
  mat4 view, proj;
  float R = light_view(r, f, view);
  float lo[2] = { R, R }, hi[2] = { -R, -R };
  if (casters_box(r, list, view, lo, hi, k) == 0) return 0;
  float half = 0.5f * fmaxf(hi[0] - lo[0], hi[1] - lo[1]);
  half = half * 1.04f + 0.02f;
  if (half > R) half = R;
  float cx = 0.5f * (lo[0] + hi[0]), cy = 0.5f * (lo[1] + hi[1]);
  glm_ortho(cx - half, cx + half, cy - half, cy + half, 0.01f, 4 * R, proj);
  glm_mat4_mul(proj, view, f->light_vp);
  key_add(k, (const float *)f->light_vp, 16);
  return 1;
}

/* Keeps this frame's key; true when it equals the one the map was last
 * drawn for. */
static bool key_unchanged(mr_render *r, key *k) {
  bool same = r->shadow_drawn && !k->lost && r->shadow_key && k->len == r->shadow_key_len &&
              memcmp(k->data, r->shadow_key, k->len * sizeof *k->data) == 0;
  free(r->shadow_key);
  r->shadow_key = k->lost ? NULL : k->data;
  r->shadow_key_len = k->lost ? 0 : k->len;
  if (k->lost) free(k->data);
  return same;
}

void mr_shadow_draw(mr_render *r, const mr_draw_list *list, mr_frame *f) {
  const mr_gl *gl = &r->gl;
  glm_mat4_identity(f->light_vp);
  if (!f->shadows || !list) return;
  key k = { 0 };
  if (!light_matrix(r, list, f, &k)) {
    free(k.data);
    f->shadows = false;
    return;
  }
  if (key_unchanged(r, &k)) return;
  r->shadow_drawn = false;
  gl->ActiveTexture(GL_TEXTURE1);
  gl->BindTexture(GL_TEXTURE_2D, 0);
  gl->BindFramebuffer(GL_FRAMEBUFFER, r->shadow_fbo);
  gl->Viewport(0, 0, r->shadow_size, r->shadow_size);
  gl->Clear(GL_DEPTH_BUFFER_BIT);
  gl->Enable(GL_DEPTH_TEST);
  gl->Enable(GL_POLYGON_OFFSET_FILL);
  gl->PolygonOffset(2.0f, 4.0f);
  mr_scene_draw_casters(r, list, f);
  gl->Disable(GL_POLYGON_OFFSET_FILL);
  gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
  r->shadow_drawn = true;
}
