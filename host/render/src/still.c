/* The still part of a frame, kept from frame to frame in software GL:
 * the sky, the backdrop and the floor as the camera and the sun see them,
 * unshadowed, colour and depth. They change only when the camera, the day
 * knob or the frame's size does (they are kept once they have stayed for
 * two frames), and they were the dearest part of a
 * 1280x720 frame (167 M of 291 M instructions for the humanoid, callgrind:
 * most pixels are floor and backdrop, each running the lit shader with the
 * sun, its shadow and the spots). Each frame the kept picture is copied
 * into the drawing framebuffer (a same-size blit, a copy of memory), and
 * the backdrop and the floor are lit again only inside the screen
 * rectangles where the casters' shadows can fall; everywhere else the
 * shadow term is exactly 1 and the kept pixel is the pixel the shader
 * would give. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "render_internal.h"

/* The key has the camera's matrix, the sun, the ambient and the sky. */
#define KEY_LEN (16 + 4 * 3)

int mr_still_create(mr_render *r, char *msg, size_t msg_size) {
  if (!r->smooth || (!r->stage.floor && !r->stage.backdrop)) return 0;
  const mr_gl *gl = &r->gl;
  gl->GenRenderbuffers(1, &r->still_color);
  gl->BindRenderbuffer(GL_RENDERBUFFER, r->still_color);
  gl->RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, r->width, r->height);
  gl->GenRenderbuffers(1, &r->still_depth);
  gl->BindRenderbuffer(GL_RENDERBUFFER, r->still_depth);
  gl->RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, r->width, r->height);
  gl->GenFramebuffers(1, &r->still_fbo);
  gl->BindFramebuffer(GL_FRAMEBUFFER, r->still_fbo);
  gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              r->still_color);
  gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r->still_depth);
  GLenum st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
  gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
  if (st == GL_FRAMEBUFFER_COMPLETE) return 0;
  snprintf(msg, msg_size, "the still scenery's framebuffer is incomplete (0x%x)", (unsigned)st);
  return -1;
}

void mr_still_destroy(mr_render *r) {
  const mr_gl *gl = &r->gl;
  if (r->still_fbo) gl->DeleteFramebuffers(1, &r->still_fbo);
  if (r->still_color) gl->DeleteRenderbuffers(1, &r->still_color);
  if (r->still_depth) gl->DeleteRenderbuffers(1, &r->still_depth);
  r->still_fbo = r->still_color = r->still_depth = 0;
  r->still_kept = false;
}

/* What the kept picture is for, this frame: 1 the kept one, 0 none (the
 * camera or the sun moved since the last frame: the frame is drawn
 * whole, as a picture kept now would serve no other frame while an orbit
 * drag or the day knob turns), -1 one to draw again (they have stayed
 * for two frames). */
static int still_state(mr_render *r, const mr_frame *f) {
  float k[KEY_LEN];
  memcpy(k, f->view_proj, 16 * sizeof(float));
  memcpy(k + 16, f->sun_dir, 3 * sizeof(float));
  memcpy(k + 19, f->sun_color, 3 * sizeof(float));
  memcpy(k + 22, f->ambient, 3 * sizeof(float));
  memcpy(k + 25, f->sky, 3 * sizeof(float));
  if (r->still_kept && memcmp(k, r->still_key, sizeof k) == 0) return 1;
  bool stayed = memcmp(k, r->still_last, sizeof k) == 0;
  memcpy(r->still_last, k, sizeof k);
  if (!stayed) return 0;
  memcpy(r->still_key, k, sizeof k);
  return -1;
}

/* The sky, the backdrop and the floor, unshadowed, into the kept
 * framebuffer. */
static void still_redraw(mr_render *r, const mr_frame *f) {
  const mr_gl *gl = &r->gl;
  gl->BindFramebuffer(GL_FRAMEBUFFER, r->still_fbo);
  gl->Viewport(0, 0, r->width, r->height);
  gl->ClearColor(mr_srgb(f->sky[0]), mr_srgb(f->sky[1]), mr_srgb(f->sky[2]), 1);
  gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl->Enable(GL_DEPTH_TEST);
  gl->DepthFunc(GL_LEQUAL);
  gl->Disable(GL_CULL_FACE);
  mr_frame lit = *f;
  lit.shadows = false;
  mr_scene_draw_scenery(r, &lit, true, true);
  gl->UseProgram(0);
  r->still_kept = true;
}

/* The world points whose shadows can fall on the scenery: each caster's
 * box corners (a skin's rest box moved by each bone), as the shadow
 * map's fit takes them. */
typedef void (*point_fn)(const float p[3], void *user);

static void corners(const mr_gpu_model *gm, mat4 m, point_fn fn, void *user) {
  for (int c = 0; c < 8; c++) {
    vec4 p = { c & 1 ? gm->hi[0] : gm->lo[0], c & 2 ? gm->hi[1] : gm->lo[1],
               c & 4 ? gm->hi[2] : gm->lo[2], 1 },
         q;
    glm_mat4_mulv(m, p, q);
    fn(q, user);
  }
}

static void caster_points(const mr_render *r, const mr_draw_list *list, point_fn fn, void *user) {
  for (size_t i = 0; i < list->n_items; i++) {
    const mr_draw_item *it = &list->items[i];
    if (it->model < 0 || (size_t)it->model >= r->n_models) continue;
    const mr_gpu_model *gm = &r->models[it->model];
    if (gm->skinned || !gm->cast_shadow || gm->n_meshes == 0) continue;
    mat4 m;
    mr_item_matrix(it, m);
    corners(gm, m, fn, user);
  }
  for (size_t i = 0; i < list->n_skins; i++) {
    const mr_draw_skin *sk = &list->skins[i];
    if (sk->model < 0 || (size_t)sk->model >= r->n_models || !sk->bones) continue;
    const mr_gpu_model *gm = &r->models[sk->model];
    if (!gm->skinned || !gm->cast_shadow || sk->n_bones < gm->n_bones) continue;
    for (int b = 0; b < gm->n_bones; b++) {
      mat4 m;
      mr_pose_matrix(&sk->bones[b], m);
      corners(gm, m, fn, user);
    }
  }
}

/* A plane the shadows fall on, axis a (1: the floor's y, 2: the
 * backdrop's z) at `at`; the box of the shadows' points on it, in the
 * other two axes (u, v). */
typedef struct plane_box {
  int axis, u, v;
  float at, sun[3], lo[2], hi[2];
  bool any, all;
} plane_box;

static void shadow_point(const float p[3], void *user) {
  plane_box *b = user;
  float s = b->sun[b->axis];
  if (s < 0.01f) { /* the sun along the plane: its shadows reach anywhere */
    b->all = true;
    return;
  }
  float t = (p[b->axis] - b->at) / s;
  if (t < 0) t = 0; /* behind the plane: a part crossing it shadows it from there */
  float q[2] = { p[b->u] - t * b->sun[b->u], p[b->v] - t * b->sun[b->v] };
  for (int k = 0; k < 2; k++) {
    if (!b->any || q[k] < b->lo[k]) b->lo[k] = q[k];
    if (!b->any || q[k] > b->hi[k]) b->hi[k] = q[k];
  }
  b->any = true;
}

/* The screen rectangle (x, y, w, h) of the world rectangle lo..hi on the
 * plane, a margin about it; the whole frame when a corner is at or
 * behind the eye. */
static void screen_rect(const mr_render *r, const mr_frame *f, const plane_box *b, int rect[4]) {
  float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
  for (int c = 0; c < 4; c++) {
    vec4 p = { 0, 0, 0, 1 }, q;
    p[b->axis] = b->at;
    p[b->u] = c & 1 ? b->hi[0] : b->lo[0];
    p[b->v] = c & 2 ? b->hi[1] : b->lo[1];
    glm_mat4_mulv((vec4 *)f->view_proj, p, q);
    if (q[3] < 0.05f) {
      rect[0] = rect[1] = 0;
      rect[2] = r->width;
      rect[3] = r->height;
      return;
    }
    float x = (q[0] / q[3] * 0.5f + 0.5f) * (float)r->width;
    float y = (q[1] / q[3] * 0.5f + 0.5f) * (float)r->height;
    x0 = fminf(x0, x), y0 = fminf(y0, y), x1 = fmaxf(x1, x), y1 = fmaxf(y1, y);
  }
  x0 = fmaxf(x0 - 2, 0), y0 = fmaxf(y0 - 2, 0);
  x1 = fminf(x1 + 2, (float)r->width), y1 = fminf(y1 + 2, (float)r->height);
  rect[0] = (int)floorf(x0), rect[1] = (int)floorf(y0);
  rect[2] = x1 > x0 ? (int)ceilf(x1) - rect[0] : 0;
  rect[3] = y1 > y0 ? (int)ceilf(y1) - rect[1] : 0;
}

/* Where on screen the casters' shadows can fall on the surface (the
 * backdrop, or the floor), clipped to the surface: a rectangle, or
 * nothing (w = 0). */
static void shadow_rect(const mr_render *r, const mr_draw_list *list, const mr_frame *f, bool floor,
                        int rect[4]) {
  const mr_stage_def *s = &r->stage;
  const float h = (float)(s->floor_size * 0.5), margin = 0.05f;
  plane_box b = { .axis = floor ? 1 : 2, .u = 0, .v = floor ? 2 : 1 };
  b.at = floor ? (float)s->floor_height : (float)-s->backdrop_distance;
  memcpy(b.sun, f->sun_dir, sizeof b.sun);
  caster_points(r, list, shadow_point, &b);
  /* The surface's own extent (meshes.c). */
  float lo[2] = { -h, floor ? -h : (float)s->floor_height };
  float hi[2] = { h, floor ? h : (float)s->floor_height + 2 * MR_BACKDROP_HALF_HEIGHT };
  for (int k = 0; k < 2 && !b.all; k++) {
    lo[k] = fmaxf(lo[k], b.lo[k] - margin);
    hi[k] = fminf(hi[k], b.hi[k] + margin);
  }
  rect[2] = rect[3] = 0;
  if ((!b.any && !b.all) || lo[0] >= hi[0] || lo[1] >= hi[1]) return;
  memcpy(b.lo, lo, sizeof lo);
  memcpy(b.hi, hi, sizeof hi);
  screen_rect(r, f, &b, rect);
}

bool mr_still_draw(mr_render *r, const mr_draw_list *list, const mr_frame *f, mr_still_rects *out) {
  memset(out, 0, sizeof *out);
  if (!r->still_fbo) return false;
  int state = still_state(r, f);
  if (state == 0) return false;
  if (state < 0) still_redraw(r, f);
  const mr_gl *gl = &r->gl;
  gl->BindFramebuffer(GL_READ_FRAMEBUFFER, r->still_fbo);
  gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, r->fbo_ms);
  gl->BlitFramebuffer(0, 0, r->width, r->height, 0, 0, r->width, r->height,
                      GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  mr_fbo_bind_draw(r);
  if (f->shadows && list) {
    if (r->stage.backdrop) shadow_rect(r, list, f, false, out->backdrop);
    if (r->stage.floor) shadow_rect(r, list, f, true, out->floor);
  }
  return true;
}
