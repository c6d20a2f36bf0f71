/* The rigging: strings and control frames as lines (§3.3), streamed each
 * frame from the draw list. */
#include <stdlib.h>

#include "render_internal.h"

int mr_lines_create(mr_render *r) {
  const mr_gl *gl = &r->gl;
  gl->GenVertexArrays(1, &r->line_vao);
  gl->BindVertexArray(r->line_vao);
  gl->GenBuffers(1, &r->line_vbo);
  gl->BindBuffer(GL_ARRAY_BUFFER, r->line_vbo);
  gl->VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), NULL);
  gl->EnableVertexAttribArray(0);
  gl->VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          (const void *)(3 * sizeof(float)));
  gl->EnableVertexAttribArray(1);
  gl->BindVertexArray(0);
  return 0;
}

void mr_lines_destroy(mr_render *r) {
  if (r->line_vbo) r->gl.DeleteBuffers(1, &r->line_vbo);
  if (r->line_vao) r->gl.DeleteVertexArrays(1, &r->line_vao);
  r->line_vbo = r->line_vao = 0;
}

void mr_lines_draw(mr_render *r, const mr_draw_line *lines, size_t n, const mr_frame *f) {
  if (n == 0 || !lines) return;
  float *v = malloc(n * 12 * sizeof(float));
  if (!v) return;
  for (size_t i = 0; i < n; i++) {
    float *p = v + 12 * i;
    for (int k = 0; k < 3; k++) {
      p[k] = (float)lines[i].a[k];
      p[3 + k] = lines[i].rgb[k];
      p[6 + k] = (float)lines[i].b[k];
      p[9 + k] = lines[i].rgb[k];
    }
  }
  const mr_gl *gl = &r->gl;
  gl->BindBuffer(GL_ARRAY_BUFFER, r->line_vbo);
  gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * 12 * sizeof(float)), v, GL_STREAM_DRAW);
  free(v);
  gl->UseProgram(r->prog_line);
  mr_uniform_m4(r, r->prog_line, "u_view_proj", (vec4 *)f->view_proj);
  gl->BindVertexArray(r->line_vao);
  gl->DrawArrays(GL_LINES, 0, (GLsizei)(2 * n));
  gl->BindVertexArray(0);
  gl->UseProgram(0);
}
