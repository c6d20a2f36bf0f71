/* The on-screen display: a monospaced font (DejaVu Sans Mono, as Debian
 * ships it, or def.font_path) baked by stb_truetype into an atlas at
 * create, and at most MR_OSD_ROWS lines of MR_OSD_COLUMNS characters drawn
 * in the bottom left corner over a translucent box, the box mr_osd_rect
 * gives (mr_stage.h), so that the audience's camera can frame the show
 * clear of it. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_truetype.h>

#include "render_internal.h"

#define MR_DEFAULT_FONT "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf"

enum { ATLAS = 512, FIRST_CHAR = 32, N_CHARS = 95 };

typedef struct mr_text {
  GLuint tex, vao, vbo;
  stbtt_bakedchar chars[N_CHARS];
  float px;
} mr_text;

/* The whole file, or NULL and why not. */
static unsigned char *read_file(const char *path, size_t *size, const char **why) {
  *size = 0;
  FILE *f = fopen(path, "rb");
  if (!f) {
    *why = strerror(errno);
    return NULL;
  }
  unsigned char *data = NULL;
  long n = -1;
  *why = "it is empty or cannot be measured";
  if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) > 0 && fseek(f, 0, SEEK_SET) == 0) {
    data = malloc((size_t)n);
    *why = "out of memory";
    if (data && fread(data, 1, (size_t)n, f) != (size_t)n) {
      free(data);
      data = NULL;
      *why = "it could not be read whole";
    }
  }
  fclose(f);
  if (data) *size = (size_t)n;
  return data;
}

/* Bakes the printable ASCII glyphs; returns the atlas or NULL. */
static unsigned char *bake(mr_text *t, const char *path, char *msg, size_t msg_size) {
  size_t size = 0;
  const char *why = NULL;
  unsigned char *font = read_file(path, &size, &why);
  if (!font) {
    snprintf(msg, msg_size, "the on-screen font '%s' cannot be read: %s", path, why);
    return NULL;
  }
  unsigned char *atlas = calloc(ATLAS, ATLAS);
  stbtt_fontinfo info;
  if (!atlas) {
    snprintf(msg, msg_size, "the on-screen font '%s': out of memory", path);
  } else if (stbtt_GetFontOffsetForIndex(font, 0) < 0 ||
             !stbtt_InitFont(&info, font, stbtt_GetFontOffsetForIndex(font, 0)) ||
             stbtt_BakeFontBitmap(font, 0, t->px, atlas, ATLAS, ATLAS, FIRST_CHAR, N_CHARS,
                                  t->chars) <= 0) {
    snprintf(msg, msg_size, "the on-screen font '%s' is not a TrueType font stb_truetype reads",
             path);
    free(atlas);
    atlas = NULL;
  }
  free(font);
  return atlas;
}

int mr_text_create(mr_render *r, const char *font_path, char *msg, size_t msg_size) {
  mr_text *t = calloc(1, sizeof *t);
  if (!t) {
    snprintf(msg, msg_size, "out of memory");
    return -1;
  }
  r->text = t;
  t->px = (float)mr_osd_font_px(r->height);
  unsigned char *atlas = bake(t, font_path ? font_path : MR_DEFAULT_FONT, msg, msg_size);
  if (!atlas) return -1;
  const mr_gl *gl = &r->gl;
  gl->GenTextures(1, &t->tex);
  gl->BindTexture(GL_TEXTURE_2D, t->tex);
  gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl->TexImage2D(GL_TEXTURE_2D, 0, GL_R8, ATLAS, ATLAS, 0, GL_RED, GL_UNSIGNED_BYTE, atlas);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  free(atlas);
  gl->GenVertexArrays(1, &t->vao);
  gl->BindVertexArray(t->vao);
  gl->GenBuffers(1, &t->vbo);
  gl->BindBuffer(GL_ARRAY_BUFFER, t->vbo);
  gl->VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 4 * sizeof(float), NULL);
  gl->EnableVertexAttribArray(0);
  gl->VertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 4 * sizeof(float),
                          (const void *)(2 * sizeof(float)));
  gl->EnableVertexAttribArray(1);
  gl->BindVertexArray(0);
  return 0;
}

void mr_text_destroy(mr_render *r) {
  mr_text *t = r->text;
  if (!t) return;
  if (t->tex) r->gl.DeleteTextures(1, &t->tex);
  if (t->vbo) r->gl.DeleteBuffers(1, &t->vbo);
  if (t->vao) r->gl.DeleteVertexArrays(1, &t->vao);
  free(t);
  r->text = NULL;
}

/* Two triangles, x0 y0 to x1 y1 (pixels, y down), uv s0 t0 to s1 t1. */
static float *quad(float *v, float x0, float y0, float x1, float y1, float s0, float t0, float s1,
                   float t1) {
  const float q[24] = { x0, y0, s0, t0, x1, y0, s1, t0, x1, y1, s1, t1,
                        x0, y0, s0, t0, x1, y1, s1, t1, x0, y1, s0, t1 };
  memcpy(v, q, sizeof q);
  return v + 24;
}

/* The box's quad first (mr_osd_rect's), then each glyph's; returns the
 * quads written. Lines past MR_OSD_ROWS and characters past
 * MR_OSD_COLUMNS are left out. */
static size_t layout(const mr_text *t, int width, int height, const char *const *lines, size_t n,
                     float *v) {
  const float pad = t->px * 0.4f, line_h = t->px * 1.2f;
  size_t columns = 0;
  for (size_t i = 0; i < n; i++) {
    size_t len = lines[i] ? strlen(lines[i]) : 0;
    if (len > columns) columns = len;
  }
  if (columns > MR_OSD_COLUMNS) columns = MR_OSD_COLUMNS;
  double box[4];
  mr_osd_rect(width, height, (int)n, (int)columns, box);
  float *p = quad(v, (float)box[0], (float)box[1], (float)(box[0] + box[2]),
                  (float)(box[1] + box[3]), 0, 0, 0, 0);
  size_t quads = 1;
  for (size_t i = 0; i < n; i++) {
    float x = (float)box[0] + pad;
    float y = (float)box[1] + pad + t->px * 0.85f + line_h * (float)i;
    const char *c = lines[i] ? lines[i] : "";
    for (size_t j = 0; c[j] && j < MR_OSD_COLUMNS; j++) {
      int k = (unsigned char)c[j] - FIRST_CHAR;
      if (k < 0 || k >= N_CHARS) k = '?' - FIRST_CHAR;
      stbtt_aligned_quad q;
      stbtt_GetBakedQuad(t->chars, ATLAS, ATLAS, k, &x, &y, &q, 1);
      p = quad(p, q.x0, q.y0, q.x1, q.y1, q.s0, q.t0, q.s1, q.t1);
      quads++;
    }
  }
  return quads;
}

void mr_text_draw(mr_render *r, const char *const *lines, size_t n) {
  mr_text *t = r->text;
  if (!t || !lines || n == 0) return;
  if (n > MR_OSD_ROWS) n = MR_OSD_ROWS;
  size_t chars = 0;
  for (size_t i = 0; i < n; i++) chars += lines[i] ? strlen(lines[i]) : 0;
  float *v = malloc((chars + 1) * 24 * sizeof(float));
  if (!v) return;
  size_t quads = layout(t, r->width, r->height, lines, n, v);
  const mr_gl *gl = &r->gl;
  gl->BindBuffer(GL_ARRAY_BUFFER, t->vbo);
  gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(quads * 24 * sizeof(float)), v, GL_STREAM_DRAW);
  free(v);
  GLuint p = r->prog_text;
  gl->UseProgram(p);
  r->gl.Uniform2f(gl->GetUniformLocation(p, "u_screen"), (float)r->width, (float)r->height);
  mr_uniform_i(r, p, "u_font", 0);
  gl->ActiveTexture(GL_TEXTURE0);
  gl->BindTexture(GL_TEXTURE_2D, t->tex);
  gl->Disable(GL_DEPTH_TEST);
  gl->Enable(GL_BLEND);
  gl->BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  gl->BindVertexArray(t->vao);
  const float box[4] = { 0, 0, 0, 0.55f }, ink[4] = { 1, 1, 0.92f, 1 };
  mr_uniform_i(r, p, "u_solid", 1);
  mr_uniform_v4(r, p, "u_color", box);
  gl->DrawArrays(GL_TRIANGLES, 0, 6);
  mr_uniform_i(r, p, "u_solid", 0);
  mr_uniform_v4(r, p, "u_color", ink);
  gl->DrawArrays(GL_TRIANGLES, 6, (GLsizei)((quads - 1) * 6));
  gl->BindVertexArray(0);
  gl->Disable(GL_BLEND);
  gl->UseProgram(0);
}
