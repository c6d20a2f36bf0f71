/* The still part of a frame, kept from frame to frame in software GL:
 * the sky, the theater's set, the backdrop and the floor as the camera
 * and the sun see them,
 * unshadowed, colour and depth. They change only when the camera, the day
 * knob or the frame's size does (they are kept once they have stayed for
 * two frames), and they were the dearest part of a
 * 1280x720 frame (167 M of 291 M instructions for the humanoid, callgrind:
 * most pixels are floor and backdrop, each running the lit shader with the
 * sun, its shadow and the spots). Each frame the kept picture is copied
 * into the drawing framebuffer (a same-size blit, a copy of memory), and
 * the backdrop and the floor are lit again only where the casters'
 * shadows can fall (bands of screen rows across the convex hull of their
 * boxes moved along the sun onto each surface); everywhere else the
 * shadow term is exactly 1 and the kept pixel is the pixel the shader
 * would give. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render_internal.h"

/* The key has the camera's matrix, the sun, the ambient, the sky and
 * whether the curtain is open (the kept picture holds it then; closed or
 * moving it is drawn over the kept picture every frame, scene.c). */
#define KEY_LEN (16 + 4 * 3 + 1)

int mr_still_create(mr_render *r, char *msg, size_t msg_size) {
  const mr_stage_def *s = &r->stage;
  const bool set = s->proscenium || s->wings || s->footlights || s->bridge;
  if (!r->smooth || (!s->floor && !s->backdrop && !set)) return 0;
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
  k[28] = f->curtain >= 1 ? 1.0f : 0.0f;
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
  lit.follow = false;
  /* The set first: the arch hides part of the boards and the backdrop. */
  mr_scene_draw_set(r, &lit);
  if (f->curtain >= 1) mr_scene_draw_curtain(r, &lit);
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
 * backdrop's z) at `at`; the shadows' points on it, in the other two axes
 * (u, v), each as the 4 corners of a square of side 2 margin about it
 * (the shadow filter reaches that far). */
typedef struct plane_pts {
  const mr_render *r; /* whose scratch holds the points */
  int axis, u, v;
  float at, sun[3], margin;
  float (*p)[2];
  size_t n, cap;
  bool all; /* the sun along the plane, or memory ran out: anywhere */
} plane_pts;

static void shadow_point(const float p[3], void *user) {
  plane_pts *b = user;
  float s = b->sun[b->axis];
  if (s < 0.01f) { /* the sun along the plane: its shadows reach anywhere */
    b->all = true;
    return;
  }
  if (b->all) return;
  if (b->n + 4 > b->cap) {
    size_t cap = b->cap ? 2 * b->cap : 256;
    float(*q)[2] = mr_render_scratch(b->r, MR_SCRATCH_POINTS, cap * sizeof *q);
    if (!q) {
      b->all = true;
      return;
    }
    b->p = q, b->cap = cap;
  }
  float t = (p[b->axis] - b->at) / s;
  if (t < 0) t = 0; /* behind the plane: a part crossing it shadows it from there */
  float u = p[b->u] - t * b->sun[b->u], v = p[b->v] - t * b->sun[b->v];
  for (int k = 0; k < 4; k++) {
    b->p[b->n][0] = u + (k & 1 ? b->margin : -b->margin);
    b->p[b->n][1] = v + (k & 2 ? b->margin : -b->margin);
    b->n++;
  }
}

static int by_u_then_v(const void *a, const void *b) {
  const float *x = a, *y = b;
  if (x[0] != y[0]) return x[0] < y[0] ? -1 : 1;
  return (x[1] > y[1]) - (x[1] < y[1]);
}

static float turn(const float o[2], const float a[2], const float b[2]) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* The convex hull of b's points, counter-clockwise, into b->p; its
 * count (monotone chain; the points are sorted in place). */
static size_t hull(plane_pts *b, float (*h)[2]) {
  size_t n = b->n, k = 0;
  qsort(b->p, n, sizeof *b->p, by_u_then_v);
  for (size_t i = 0; i < n; i++) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], b->p[i]) <= 0) k--;
    memcpy(h[k++], b->p[i], sizeof *h);
  }
  for (size_t i = n - 1, lo = k + 1; i-- > 0;) {
    while (k >= lo && turn(h[k - 2], h[k - 1], b->p[i]) <= 0) k--;
    memcpy(h[k++], b->p[i], sizeof *h);
  }
  return k > 1 ? k - 1 : k;
}

/* The polygon poly (n corners, room for n + 1 more) cut by the line
 * where coordinate c is `at`, keeping the side sign * (x - at) <= 0. */
static size_t clip(float (*poly)[2], size_t n, int c, float at, float sign, float (*out)[2]) {
  size_t m = 0;
  for (size_t i = 0; i < n; i++) {
    const float *a = poly[i], *e = poly[(i + 1) % n];
    float da = sign * (a[c] - at), de = sign * (e[c] - at);
    if (da <= 0) memcpy(out[m++], a, sizeof *out);
    if ((da < 0 && de > 0) || (da > 0 && de < 0)) {
      float t = da / (da - de);
      out[m][0] = a[0] + t * (e[0] - a[0]);
      out[m][1] = a[1] + t * (e[1] - a[1]);
      m++;
    }
  }
  return m;
}

/* The screen's x extent of the polygon's part between rows ya and yb. */
static bool band_extent(float (*s)[2], size_t n, float ya, float yb, float *x0, float *x1) {
  bool any = false;
  for (size_t i = 0; i < n; i++) {
    const float *a = s[i], *e = s[(i + 1) % n];
    float dy = e[1] - a[1], lo = 0, hi = 1;
    if (fabsf(dy) < 1e-6f) {
      if (a[1] < ya || a[1] > yb) continue;
    } else {
      float ta = (ya - a[1]) / dy, tb = (yb - a[1]) / dy;
      lo = fmaxf(0, fminf(ta, tb)), hi = fminf(1, fmaxf(ta, tb));
      if (lo > hi) continue;
    }
    for (int k = 0; k < 2; k++) {
      float x = a[0] + (k ? hi : lo) * (e[0] - a[0]);
      *x0 = any ? fminf(*x0, x) : x, *x1 = any ? fmaxf(*x1, x) : x;
      any = true;
    }
  }
  return any;
}

/* The screen polygon cut into bands of rows, a rectangle each (a 2-pixel
 * margin about it), clipped to the frame. Returns how many. */
static int bands(const mr_render *r, float (*s)[2], size_t n, int rects[][4]) {
  float y0 = s[0][1], y1 = s[0][1];
  for (size_t i = 1; i < n; i++) y0 = fminf(y0, s[i][1]), y1 = fmaxf(y1, s[i][1]);
  int top = (int)ceilf(fminf(y1 + 2, (float)r->height)), bottom = (int)floorf(fmaxf(y0 - 2, 0));
  if (top <= bottom) return 0;
  int nb = (top - bottom + 15) / 16, m = 0; /* at least 16 rows a band */
  if (nb > MR_STILL_BANDS) nb = MR_STILL_BANDS;
  for (int k = 0; k < nb; k++) {
    int ya = bottom + (top - bottom) * k / nb, yb = bottom + (top - bottom) * (k + 1) / nb;
    float x0, x1;
    if (!band_extent(s, n, (float)ya - 2, (float)yb + 2, &x0, &x1)) continue;
    x0 = fmaxf(x0 - 2, 0), x1 = fminf(x1 + 2, (float)r->width);
    if (x1 <= x0) continue;
    rects[m][0] = (int)floorf(x0), rects[m][1] = ya;
    rects[m][2] = (int)ceilf(x1) - rects[m][0], rects[m][3] = yb - ya;
    m++;
  }
  return m;
}

/* The hull on the plane (u, v) onto the screen; false when a corner is at
 * or behind the eye. */
static bool to_screen(const mr_render *r, const mr_frame *f, const plane_pts *b, float (*h)[2],
                      size_t n, float (*s)[2]) {
  for (size_t i = 0; i < n; i++) {
    vec4 p = { 0, 0, 0, 1 }, q;
    p[b->axis] = b->at, p[b->u] = h[i][0], p[b->v] = h[i][1];
    glm_mat4_mulv((vec4 *)f->view_proj, p, q);
    if (q[3] < 0.05f) return false;
    s[i][0] = (q[0] / q[3] * 0.5f + 0.5f) * (float)r->width;
    s[i][1] = (q[1] / q[3] * 0.5f + 0.5f) * (float)r->height;
  }
  return true;
}

/* Where on screen the points b gathered on the surface (the backdrop, or
 * the floor) lie: their convex hull (the whole surface when b->all),
 * clipped to the surface, in bands of rows (a long shadow thrown aslant
 * by a low sun fills a fraction of its screen box). Returns how many
 * rectangles. */
static int plane_rects(const mr_render *r, const mr_frame *f, plane_pts *b, bool floor,
                       int rects[][4]) {
  const mr_stage_def *s = &r->stage;
  const float h = (float)(s->floor_size * 0.5);
  /* The surface's own extent (meshes.c). */
  float lo[2] = { -h, floor ? -h : (float)s->floor_height };
  float hi[2] = { h, floor ? h : (float)s->floor_height + 2 * MR_BACKDROP_HALF_HEIGHT };
  int m = 0;
  size_t room = (b->all ? 4 : b->n) + 8;
  float(*p)[2] = mr_render_scratch(r, MR_SCRATCH_POLYGON, 2 * room * sizeof *p);
  float(*q)[2] = p ? p + room : NULL;
  if (p && (b->all || b->n > 0)) {
    size_t n = 4;
    if (b->all) {
      const float c[4][2] = {
        { lo[0], lo[1] }, { hi[0], lo[1] }, { hi[0], hi[1] }, { lo[0], hi[1] }
      };
      memcpy(p, c, sizeof c);
    } else {
      n = hull(b, p);
    }
    for (int c = 0; c < 2 && n > 0; c++) {
      n = clip(p, n, c, hi[c], 1, q);
      n = clip(q, n, c, lo[c], -1, p);
    }
    if (n >= 3 && to_screen(r, f, b, p, n, q)) {
      m = bands(r, q, n, rects);
    } else if (n >= 3) {
      rects[0][0] = rects[0][1] = 0, rects[0][2] = r->width, rects[0][3] = r->height;
      m = 1;
    }
  } else if (!p && (b->all || b->n > 0)) {
    rects[0][0] = rects[0][1] = 0, rects[0][2] = r->width, rects[0][3] = r->height;
    m = 1;
  }
  return m;
}

/* Where on screen the casters' shadows can fall on the surface: their
 * boxes' corners moved along the sun onto it. */
static int shadow_rects(const mr_render *r, const mr_draw_list *list, const mr_frame *f, bool floor,
                        int rects[][4]) {
  const mr_stage_def *s = &r->stage;
  plane_pts b = { .r = r, .axis = floor ? 1 : 2, .u = 0, .v = floor ? 2 : 1, .margin = 0.05f };
  b.at = floor ? (float)s->floor_height : (float)-s->backdrop_distance;
  memcpy(b.sun, f->sun_dir, sizeof b.sun);
  caster_points(r, list, shadow_point, &b);
  return plane_rects(r, f, &b, floor, rects);
}

/* Where on screen the follow spot's cone meets the surface: SPOT_RAYS
 * rays along its edge (a little wider than the cone, so the polygon
 * through their ends holds the ellipse they sample), each to where it
 * meets the surface's plane. A ray that never meets it (the cone opens
 * past the plane's horizon) lights it anywhere. */
enum { SPOT_RAYS = 24 };
static int spot_rects(const mr_render *r, const mr_frame *f, bool floor, int rects[][4]) {
  const mr_stage_def *s = &r->stage;
  plane_pts b = { .r = r, .axis = floor ? 1 : 2, .u = 0, .v = floor ? 2 : 1, .margin = 0.05f };
  b.at = floor ? (float)s->floor_height : (float)-s->backdrop_distance;
  b.sun[b.axis] = 1; /* shadow_point's move: none, t is 0 on the plane */
  const float *o = f->follow_pos, *d = f->follow_dir;
  float a = (float)(s->follow_spot.angle_deg * 1.04 * GLM_PI / 180.0);
  /* Two axes across the cone. */
  vec3 e1, e2, any = { fabsf(d[0]) < 0.9f ? 1.0f : 0.0f, fabsf(d[0]) < 0.9f ? 0.0f : 1.0f, 0 };
  glm_vec3_crossn((float *)d, any, e1);
  glm_vec3_crossn((float *)d, e1, e2);
  for (int k = 0; k < SPOT_RAYS && !b.all; k++) {
    float phi = 2 * GLM_PIf * (float)k / SPOT_RAYS, ray[3], p[3];
    for (int c = 0; c < 3; c++)
      ray[c] = cosf(a) * d[c] + sinf(a) * (cosf(phi) * e1[c] + sinf(phi) * e2[c]);
    float along = ray[b.axis], t = along != 0 ? (b.at - o[b.axis]) / along : -1;
    if (!(t > 0)) {
      b.all = true;
      break;
    }
    for (int c = 0; c < 3; c++) p[c] = o[c] + t * ray[c];
    p[b.axis] = b.at;
    shadow_point(p, &b);
  }
  return plane_rects(r, f, &b, floor, rects);
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
    if (r->stage.backdrop) out->n_backdrop = shadow_rects(r, list, f, false, out->backdrop);
    if (r->stage.floor) out->n_floor = shadow_rects(r, list, f, true, out->floor);
  }
  if (f->follow) {
    if (r->stage.backdrop) out->n_spot_backdrop = spot_rects(r, f, false, out->spot_backdrop);
    if (r->stage.floor) out->n_spot_floor = spot_rects(r, f, true, out->spot_floor);
  }
  return true;
}
