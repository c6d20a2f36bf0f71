/* The edge-smoothing post pass (software GL, one sample a pixel), run
 * only where an edge can be. The drawn frame is copied whole into the
 * output framebuffer (a same-size blit, a copy of memory in software
 * GL), then the smoothing shader is drawn over the regions whose pixels
 * it can change: the screen box of everything the draw list moves (items,
 * skins, rigging), and thin strips along the outlines of the floor and
 * the backdrop. Elsewhere the frame is flat scenery or sky, where the
 * shader leaves a pixel as it is (or all but: the checkerboard's squares
 * differ by less than its threshold), and it was the dearest pass of a
 * 1280x720 frame after the scenery's lighting (about a quarter of the
 * frame's instructions, counted by callgrind). */
#include <math.h>
#include <string.h>

#include "render_internal.h"

/* Pixels around an edge that the shader reads or changes: its 4
 * neighbours and two reads 1.5 pixels along the edge. */
#define MARGIN_PX 3.0f

typedef struct regions {
  float v[MR_POST_MAX_VERTS * 2]; /* triangles, in normalised device coordinates */
  int n;
  bool full; /* something reaches behind the eye: the whole frame */
} regions;

/* The screen box of the points seen so far, in pixels. */
typedef struct box {
  float lo[2], hi[2];
  bool any;
} box;

static void clip_of(const mat4 vp, const float p[3], vec4 out) {
  vec4 q = { p[0], p[1], p[2], 1 };
  glm_mat4_mulv((vec4 *)vp, q, out);
}

/* Adds a world point to the box; a point at or behind the near plane
 * makes the region the whole frame. */
static void box_add_point(const mr_render *r, const mr_frame *f, const float p[3], box *b,
                          regions *g) {
  vec4 c;
  clip_of(f->view_proj, p, c);
  if (c[3] < 0.05f) {
    g->full = true;
    return;
  }
  float x = (c[0] / c[3] * 0.5f + 0.5f) * (float)r->width;
  float y = (c[1] / c[3] * 0.5f + 0.5f) * (float)r->height;
  if (!b->any || x < b->lo[0]) b->lo[0] = x;
  if (!b->any || y < b->lo[1]) b->lo[1] = y;
  if (!b->any || x > b->hi[0]) b->hi[0] = x;
  if (!b->any || y > b->hi[1]) b->hi[1] = y;
  b->any = true;
}

/* A point into b[0] and, when the sun casts, its shadow on the floor's
 * plane into b[1] and on the backdrop's into b[2] (shadow edges are edges
 * too; three boxes cover less than the one about them). */
static void box_add(const mr_render *r, const mr_frame *f, const float p[3], box b[3], regions *g) {
  box_add_point(r, f, p, &b[0], g);
  const float *sun = f->sun_dir;
  const mr_stage_def *s = &r->stage;
  if (!f->shadows) return;
  float t[2] = { sun[1] > 0.01f ? (p[1] - (float)s->floor_height) / sun[1] : -1,
                 sun[2] > 0.01f ? (p[2] + (float)s->backdrop_distance) / sun[2] : -1 };
  for (int k = 0; k < 2; k++) {
    if (t[k] <= 0 || t[k] > 100) continue;
    float q[3] = { p[0] - t[k] * sun[0], p[1] - t[k] * sun[1], p[2] - t[k] * sun[2] };
    box_add_point(r, f, q, &b[1 + k], g);
  }
}

/* The 8 corners of a model's box moved by m. */
static void box_add_model(const mr_render *r, const mr_frame *f, const mr_gpu_model *gm, mat4 m,
                          box b[3], regions *g) {
  for (int k = 0; k < 8 && !g->full; k++) {
    vec4 p = { k & 1 ? gm->hi[0] : gm->lo[0], k & 2 ? gm->hi[1] : gm->lo[1],
               k & 4 ? gm->hi[2] : gm->lo[2], 1 },
         q;
    glm_mat4_mulv(m, p, q);
    box_add(r, f, q, b, g);
  }
}

/* Everything the draw list moves: items, skins (their rest box moved by
 * each bone, as the shadow's fit does), rigging lines. */
static void moving_box(const mr_render *r, const mr_draw_list *list, const mr_frame *f, box b[3],
                       regions *g) {
  for (size_t i = 0; i < list->n_items && !g->full; i++) {
    const mr_draw_item *it = &list->items[i];
    if (it->model < 0 || (size_t)it->model >= r->n_models) continue;
    mat4 m;
    mr_item_matrix(it, m);
    box_add_model(r, f, &r->models[it->model], m, b, g);
  }
  for (size_t i = 0; i < list->n_skins && !g->full; i++) {
    const mr_draw_skin *sk = &list->skins[i];
    if (sk->model < 0 || (size_t)sk->model >= r->n_models || !sk->bones) continue;
    for (int k = 0; k < sk->n_bones && !g->full; k++) {
      mat4 m;
      mr_pose_matrix(&sk->bones[k], m);
      box_add_model(r, f, &r->models[sk->model], m, b, g);
    }
  }
  for (size_t i = 0; i < list->n_lines && !g->full; i++) {
    const mr_draw_line *l = &list->lines[i];
    float a[3] = { (float)l->a[0], (float)l->a[1], (float)l->a[2] };
    float e[3] = { (float)l->b[0], (float)l->b[1], (float)l->b[2] };
    box_add_point(r, f, a, &b[0], g); /* lines cast no shadow */
    box_add_point(r, f, e, &b[0], g);
  }
}

/* A quad given by its 4 corners in pixels, as two triangles. */
static void add_quad(const mr_render *r, regions *g, const float q[4][2]) {
  static const int order[6] = { 0, 1, 2, 0, 2, 3 };
  if (g->n + 6 > MR_POST_MAX_VERTS) {
    g->full = true;
    return;
  }
  for (int k = 0; k < 6; k++) {
    g->v[2 * g->n] = q[order[k]][0] / (float)r->width * 2 - 1;
    g->v[2 * g->n + 1] = q[order[k]][1] / (float)r->height * 2 - 1;
    g->n++;
  }
}

static void add_box(const mr_render *r, regions *g, const box *b) {
  float x0 = b->lo[0] - MARGIN_PX, y0 = b->lo[1] - MARGIN_PX;
  float x1 = b->hi[0] + MARGIN_PX, y1 = b->hi[1] + MARGIN_PX;
  const float q[4][2] = { { x0, y0 }, { x1, y0 }, { x1, y1 }, { x0, y1 } };
  add_quad(r, g, q);
}

/* A strip MARGIN_PX either side of the segment from a to b (world),
 * clipped to the near plane (z > -w) first. */
static void add_strip(const mr_render *r, const mr_frame *f, const float a[3], const float b[3],
                      regions *g) {
  vec4 c[2];
  clip_of(f->view_proj, a, c[0]);
  clip_of(f->view_proj, b, c[1]);
  float da = c[0][2] + c[0][3], db = c[1][2] + c[1][3];
  if (da < 0 && db < 0) return;
  if (da < 0 || db < 0) {
    float t = da / (da - db);
    int out = da < 0 ? 0 : 1;
    vec4 p;
    glm_vec4_lerp(c[0], c[1], t, p);
    glm_vec4_copy(p, c[out]);
  }
  float s[2][2];
  for (int k = 0; k < 2; k++) {
    if (c[k][3] < 1e-6f) {
      g->full = true;
      return;
    }
    s[k][0] = (c[k][0] / c[k][3] * 0.5f + 0.5f) * (float)r->width;
    s[k][1] = (c[k][1] / c[k][3] * 0.5f + 0.5f) * (float)r->height;
  }
  float dx = s[1][0] - s[0][0], dy = s[1][1] - s[0][1], len = sqrtf(dx * dx + dy * dy);
  if (!(len < 1e6f)) {
    g->full = true;
    return;
  }
  float ux = len > 1e-3f ? dx / len : 1, uy = len > 1e-3f ? dy / len : 0;
  float ax = ux * MARGIN_PX, ay = uy * MARGIN_PX; /* along */
  float nx = -ay, ny = ax;                        /* across */
  const float q[4][2] = { { s[0][0] - ax - nx, s[0][1] - ay - ny },
                          { s[1][0] + ax - nx, s[1][1] + ay - ny },
                          { s[1][0] + ax + nx, s[1][1] + ay + ny },
                          { s[0][0] - ax + nx, s[0][1] - ay + ny } };
  add_quad(r, g, q);
}

/* A rectangle's 4 sides: corners c +- u +- v. */
static void add_outline(const mr_render *r, const mr_frame *f, const float c[3], const float u[3],
                        const float v[3], regions *g) {
  float p[4][3];
  static const float su[4] = { -1, 1, 1, -1 }, sv[4] = { -1, -1, 1, 1 };
  for (int k = 0; k < 4; k++)
    for (int j = 0; j < 3; j++) p[k][j] = c[j] + su[k] * u[j] + sv[k] * v[j];
  for (int k = 0; k < 4 && !g->full; k++) add_strip(r, f, p[k], p[(k + 1) % 4], g);
}

/* The floor's and the backdrop's outlines (meshes.c's quads). */
static void scenery_strips(const mr_render *r, const mr_frame *f, regions *g) {
  const mr_stage_def *s = &r->stage;
  const float h = (float)(s->floor_size * 0.5);
  if (s->floor) {
    const float c[3] = { 0, (float)s->floor_height, 0 }, u[3] = { h, 0, 0 }, v[3] = { 0, 0, h };
    add_outline(r, f, c, u, v, g);
  }
  if (s->backdrop) {
    const float c[3] = { 0, (float)s->floor_height + MR_BACKDROP_HALF_HEIGHT,
                         (float)-s->backdrop_distance },
                u[3] = { h, 0, 0 }, v[3] = { 0, MR_BACKDROP_HALF_HEIGHT, 0 };
    add_outline(r, f, c, u, v, g);
  }
}

static void regions_make(const mr_render *r, const mr_draw_list *list, const mr_frame *f,
                         regions *g) {
  memset(g, 0, sizeof *g);
  box b[3] = { 0 };
  if (list) moving_box(r, list, f, b, g);
  for (int k = 0; k < 3; k++)
    if (b[k].any && !g->full) add_box(r, g, &b[k]);
  if (!g->full) scenery_strips(r, f, g);
  if (g->full) {
    const float q[4][2] = { { 0, 0 },
                            { (float)r->width, 0 },
                            { (float)r->width, (float)r->height },
                            { 0, (float)r->height } };
    g->n = 0;
    g->full = false;
    add_quad(r, g, q);
  }
}

void mr_post_smooth(mr_render *r, const mr_draw_list *list, const mr_frame *f) {
  const mr_gl *gl = &r->gl;
  regions g;
  regions_make(r, list, f, &g);
  gl->Disable(GL_DEPTH_TEST);
  gl->Disable(GL_BLEND);
  gl->UseProgram(r->prog_smooth);
  mr_uniform_i(r, r->prog_smooth, "u_frame", 0);
  gl->Uniform2f(gl->GetUniformLocation(r->prog_smooth, "u_texel"), 1.0f / (float)r->width,
                1.0f / (float)r->height);
  gl->ActiveTexture(GL_TEXTURE0);
  gl->BindTexture(GL_TEXTURE_2D, r->tex_frame);
  gl->BindVertexArray(r->post_vao);
  gl->BindBuffer(GL_ARRAY_BUFFER, r->post_vbo);
  gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(g.n * 2 * sizeof(float)), g.v, GL_STREAM_DRAW);
  gl->DrawArrays(GL_TRIANGLES, 0, g.n);
  gl->BindVertexArray(0);
  /* The stars, each a few pixels of the sky, wherever they are. */
  gl->UseProgram(r->prog_smooth_stars);
  mr_uniform_i(r, r->prog_smooth_stars, "u_frame", 0);
  gl->Uniform2f(gl->GetUniformLocation(r->prog_smooth_stars, "u_texel"), 1.0f / (float)r->width,
                1.0f / (float)r->height);
  mr_sky_star_points(r, r->prog_smooth_stars, f, 2 * MARGIN_PX);
  gl->BindTexture(GL_TEXTURE_2D, 0);
  gl->UseProgram(0);
}
