/* The frame's own framebuffers: every backend draws into a multisampled
 * one (headless contexts have no multisampled default framebuffer), which
 * is resolved with glBlitFramebuffer into a single-sampled one, then read
 * back or blitted to the window. When the edges are smoothed instead
 * (r->smooth, software GL), the first has one sample and its colour is a
 * texture, which the post pass (post.c) reads into the second. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render_internal.h"

static int fbo_check(mr_render *r, const char *which, char *msg, size_t msg_size) {
  GLenum st = r->gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
  if (st == GL_FRAMEBUFFER_COMPLETE) return 0;
  snprintf(msg, msg_size, "the %s framebuffer is incomplete (0x%x)", which, (unsigned)st);
  return -1;
}

int mr_fbo_create(mr_render *r, char *msg, size_t msg_size) {
  const mr_gl *gl = &r->gl;
  GLint max_samples = 1;
  gl->GetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (r->samples > max_samples) r->samples = max_samples;
  GLsizei samples = r->samples > 1 ? r->samples : 0;

  if (r->smooth) {
    gl->GenTextures(1, &r->tex_frame);
    gl->BindTexture(GL_TEXTURE_2D, r->tex_frame);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, r->width, r->height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                   NULL);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl->BindTexture(GL_TEXTURE_2D, 0);
    gl->GenVertexArrays(1, &r->post_vao);
    gl->BindVertexArray(r->post_vao);
    gl->GenBuffers(1, &r->post_vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, r->post_vbo);
    gl->VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), NULL);
    gl->EnableVertexAttribArray(0);
    gl->BindVertexArray(0);
  } else {
    gl->GenRenderbuffers(1, &r->rb_color_ms);
    gl->BindRenderbuffer(GL_RENDERBUFFER, r->rb_color_ms);
    gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, r->width, r->height);
  }
  gl->GenRenderbuffers(1, &r->rb_depth_ms);
  gl->BindRenderbuffer(GL_RENDERBUFFER, r->rb_depth_ms);
  gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, r->width,
                                     r->height);
  gl->GenFramebuffers(1, &r->fbo_ms);
  gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo_ms);
  if (r->smooth)
    gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->tex_frame, 0);
  else
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                r->rb_color_ms);
  gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r->rb_depth_ms);
  if (fbo_check(r, r->smooth ? "drawing" : "multisampled", msg, msg_size) != 0) return -1;

  gl->GenRenderbuffers(1, &r->rb_color_out);
  gl->BindRenderbuffer(GL_RENDERBUFFER, r->rb_color_out);
  gl->RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, r->width, r->height);
  gl->GenFramebuffers(1, &r->fbo_out);
  gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo_out);
  gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              r->rb_color_out);
  if (fbo_check(r, "resolve", msg, msg_size) != 0) return -1;
  gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
  return 0;
}

void mr_fbo_destroy(mr_render *r) {
  const mr_gl *gl = &r->gl;
  if (r->fbo_ms) gl->DeleteFramebuffers(1, &r->fbo_ms);
  if (r->fbo_out) gl->DeleteFramebuffers(1, &r->fbo_out);
  if (r->rb_color_ms) gl->DeleteRenderbuffers(1, &r->rb_color_ms);
  if (r->rb_depth_ms) gl->DeleteRenderbuffers(1, &r->rb_depth_ms);
  if (r->rb_color_out) gl->DeleteRenderbuffers(1, &r->rb_color_out);
  if (r->tex_frame) gl->DeleteTextures(1, &r->tex_frame);
  if (r->post_vao) gl->DeleteVertexArrays(1, &r->post_vao);
  if (r->post_vbo) gl->DeleteBuffers(1, &r->post_vbo);
  r->fbo_ms = r->fbo_out = r->rb_color_ms = r->rb_depth_ms = r->rb_color_out = 0;
  r->tex_frame = r->post_vao = r->post_vbo = 0;
  free(r->read_buf);
  r->read_buf = NULL;
  r->read_size = 0;
}

void mr_fbo_bind_draw(mr_render *r) {
  r->gl.BindFramebuffer(GL_FRAMEBUFFER, r->fbo_ms);
  r->gl.Viewport(0, 0, r->width, r->height);
}

void mr_fbo_resolve(mr_render *r, const mr_draw_list *list, const mr_frame *f) {
  const mr_gl *gl = &r->gl;
  gl->BindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo_ms);
  gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, r->fbo_out);
  gl->BlitFramebuffer(0, 0, r->width, r->height, 0, 0, r->width, r->height, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
  gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo_out);
  gl->Viewport(0, 0, r->width, r->height);
  if (r->smooth) mr_post_smooth(r, list, f);
}

/* Reads the bound read framebuffer's w x h as RGB, top row first (GL's
 * rows run bottom up). -1 when the staging buffer cannot be had, so the
 * caller never reports success over a buffer left unfilled. */
/* One row of RGBA as RGB. Four pixels at a time on a little-endian
 * machine (three words out of four), a byte at a time elsewhere: a frame
 * read back at 1280x720 spent 7 M instructions here, byte by byte. */
static void row_rgba_to_rgb(const uint8_t *src, uint8_t *dst, int w) {
  int x = 0;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  for (; x + 4 <= w; x += 4, src += 16, dst += 12) {
    uint32_t p[4], q[3];
    memcpy(p, src, sizeof p);
    q[0] = (p[0] & 0xffffffu) | p[1] << 24;
    q[1] = (p[1] >> 8 & 0xffffu) | p[2] << 16;
    q[2] = (p[2] >> 16 & 0xffu) | p[3] << 8;
    memcpy(dst, q, sizeof q);
  }
#endif
  for (; x < w; x++, src += 4, dst += 3) memcpy(dst, src, 3);
}

static int read_rgb_flipped(mr_render *r, int w, int h, uint8_t *rgb) {
  const mr_gl *gl = &r->gl;
  /* Kept from frame to frame: a fresh 3.7 MB each frame is fresh pages
   * for the kernel to map and clear. */
  size_t need = (size_t)w * (size_t)h * 4;
  if (need > r->read_size) {
    uint8_t *b = realloc(r->read_buf, need);
    if (!b) return -1;
    r->read_buf = b;
    r->read_size = need;
  }
  gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl->ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, r->read_buf);
  for (int y = 0; y < h; y++)
    row_rgba_to_rgb(r->read_buf + (size_t)(h - 1 - y) * (size_t)w * 4,
                    rgb + (size_t)y * (size_t)w * 3, w);
  return 0;
}

int mr_fbo_read_rgb(mr_render *r, uint8_t *rgb) {
  r->gl.BindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo_out);
  int ok = read_rgb_flipped(r, r->width, r->height, rgb);
  r->gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return ok;
}

/* The frame scaled to fit the window, its aspect kept, black around. */
void mr_fbo_blit_to_window(mr_render *r, int w, int h) {
  const mr_gl *gl = &r->gl;
  gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  /* glDrawBuffers names the window's back buffer GL_BACK in ES and
   * GL_BACK_LEFT on the desktop (glDrawBuffer is desktop only). */
  const GLenum back = r->gles ? GL_BACK : GL_BACK_LEFT;
  gl->DrawBuffers(1, &back);
  gl->Viewport(0, 0, w, h);
  gl->ClearColor(0, 0, 0, 1);
  gl->Clear(GL_COLOR_BUFFER_BIT);
  double sx = (double)w / r->width, sy = (double)h / r->height;
  double s = sx < sy ? sx : sy;
  int dw = (int)(r->width * s + 0.5), dh = (int)(r->height * s + 0.5);
  int x0 = (w - dw) / 2, y0 = (h - dh) / 2;
  gl->BindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo_out);
  gl->BlitFramebuffer(0, 0, r->width, r->height, x0, y0, x0 + dw, y0 + dh, GL_COLOR_BUFFER_BIT,
                      dw == r->width && dh == r->height ? GL_NEAREST : GL_LINEAR);
  gl->BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

int mr_render_read_window_rgb(mr_render *r, uint8_t *rgb, size_t size, int *w, int *h) {
  if (!r || r->backend != MR_RENDER_WINDOW || !r->drawn) return -1;
  if (r->ops->make_current(r) != 0) return -1;
  mr_context_drawable_size(r, w, h);
  if ((size_t)*w * (size_t)*h * 3 > size) return -1;
  mr_fbo_blit_to_window(r, *w, *h);
  r->gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  r->gl.ReadBuffer(GL_BACK);
  return read_rgb_flipped(r, *w, *h, rgb);
}
