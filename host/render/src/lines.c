/* The rigging: strings (and wire control frames, §3.3) streamed each
 * frame from the draw list, as thin anti-aliased lines.
 *
 * Wide and smooth GL lines are not in the core profile nor dependable in
 * OpenGL ES, so each line is a quad facing the camera, worked out here:
 * its two ends projected (cut at the near plane first), the quad laid
 * MR_LINE_WIDTH_PX / 2 + 1 pixels either side of the line on screen. The
 * offsets are made in clip space (scaled by w), so the quad keeps the
 * line's depth and is tested against the models like the line itself.
 * The fragment shader takes each pixel's coverage from its distance to
 * the line on screen (a box filter a pixel wide over a line
 * MR_LINE_WIDTH_PX wide): a pixel on the line is covered whole, one half
 * a pixel off it half. Coverage is alpha: lines blend over what is drawn
 * (after every opaque thing, with the depth test on and depth writes off,
 * so a string behind a puppet is hidden and lines never hide each other's
 * soft edges). */
#include <math.h>
#include <stdlib.h>

#include "render_internal.h"

/* Floats a vertex: clip position (4), colour (3), the line on screen in
 * pixels (a point on it and its unit normal, 4). */
enum { LINE_FLOATS = 11, LINE_VERTS = 6 };

int mr_lines_create(mr_render *r) {
  const mr_gl *gl = &r->gl;
  GLsizei stride = LINE_FLOATS * sizeof(float);
  gl->GenVertexArrays(1, &r->line_vao);
  gl->BindVertexArray(r->line_vao);
  gl->GenBuffers(1, &r->line_vbo);
  gl->BindBuffer(GL_ARRAY_BUFFER, r->line_vbo);
  gl->VertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, stride, NULL);
  gl->EnableVertexAttribArray(0);
  gl->VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, (const void *)(4 * sizeof(float)));
  gl->EnableVertexAttribArray(1);
  gl->VertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, stride, (const void *)(7 * sizeof(float)));
  gl->EnableVertexAttribArray(2);
  gl->BindVertexArray(0);
  return 0;
}

void mr_lines_destroy(mr_render *r) {
  if (r->line_vbo) r->gl.DeleteBuffers(1, &r->line_vbo);
  if (r->line_vao) r->gl.DeleteVertexArrays(1, &r->line_vao);
  r->line_vbo = r->line_vao = 0;
}

static void clip_of(const mr_frame *f, const double p[3], vec4 out) {
  vec4 q = { (float)p[0], (float)p[1], (float)p[2], 1 };
  glm_mat4_mulv((vec4 *)f->view_proj, q, out);
}

/* The part of a -> b in front of the near plane (z >= -w in clip space):
 * false when none is. */
static bool clip_near(vec4 a, vec4 b) {
  float da = a[2] + a[3], db = b[2] + b[3];
  if (da < 0 && db < 0) return false;
  if (da < 0 || db < 0) {
    float t = da / (da - db);
    vec4 c;
    glm_vec4_lerp(a, b, t, c);
    glm_vec4_copy(c, da < 0 ? a : b);
  }
  return a[3] > 1e-6f && b[3] > 1e-6f;
}

/* The six vertices of line l's quad into v; false when it is not in
 * front of the eye. */
static bool line_quad(const mr_render *r, const mr_frame *f, const mr_draw_line *l, float *v) {
  vec4 c[2];
  clip_of(f, l->a, c[0]);
  clip_of(f, l->b, c[1]);
  if (!clip_near(c[0], c[1])) return false;
  float w = (float)r->width, h = (float)r->height, px[2][2];
  for (int e = 0; e < 2; e++) {
    px[e][0] = (c[e][0] / c[e][3] * 0.5f + 0.5f) * w;
    px[e][1] = (c[e][1] / c[e][3] * 0.5f + 0.5f) * h;
  }
  float dx = px[1][0] - px[0][0], dy = px[1][1] - px[0][1], len = sqrtf(dx * dx + dy * dy);
  float n[2] = { len > 1e-6f ? -dy / len : 0, len > 1e-6f ? dx / len : 1 };
  float reach = 0.5f * MR_LINE_WIDTH_PX + 1.0f;
  static const int corner[LINE_VERTS][2] = { { 0, 1 }, { 0, -1 }, { 1, 1 },
                                             { 1, 1 }, { 0, -1 }, { 1, -1 } };
  for (int k = 0; k < LINE_VERTS; k++) {
    const float *p = c[corner[k][0]];
    float side = (float)corner[k][1] * reach;
    float *o = v + LINE_FLOATS * k;
    o[0] = p[0] + n[0] * side * 2.0f / w * p[3];
    o[1] = p[1] + n[1] * side * 2.0f / h * p[3];
    o[2] = p[2];
    o[3] = p[3];
    for (int i = 0; i < 3; i++) o[4 + i] = l->rgb[i];
    o[7] = px[0][0];
    o[8] = px[0][1];
    o[9] = n[0];
    o[10] = n[1];
  }
  return true;
}

void mr_lines_draw(mr_render *r, const mr_draw_line *lines, size_t n, const mr_frame *f) {
  if (n == 0 || !lines) return;
  float *v = mr_render_scratch(r, MR_SCRATCH_LINES, n * LINE_VERTS * LINE_FLOATS * sizeof(float));
  if (!v) return;
  size_t drawn = 0;
  for (size_t i = 0; i < n; i++)
    drawn += line_quad(r, f, &lines[i], v + drawn * LINE_VERTS * LINE_FLOATS);
  const mr_gl *gl = &r->gl;
  if (drawn > 0) {
    gl->BindBuffer(GL_ARRAY_BUFFER, r->line_vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(drawn * LINE_VERTS * LINE_FLOATS * sizeof(float)),
                   v, GL_STREAM_DRAW);
    gl->UseProgram(r->prog_line);
    mr_uniform_f(r, r->prog_line, "u_width", MR_LINE_WIDTH_PX);
    gl->Enable(GL_BLEND);
    gl->BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    gl->DepthMask(GL_FALSE);
    gl->BindVertexArray(r->line_vao);
    gl->DrawArrays(GL_TRIANGLES, 0, (GLsizei)(drawn * LINE_VERTS));
    gl->BindVertexArray(0);
    gl->DepthMask(GL_TRUE);
    gl->Disable(GL_BLEND);
    gl->UseProgram(0);
  }
}
