/* The OSMesa backend: a software context with no display at all.
 *
 * Measured on Mesa 22.3.6: OSMesaCreateContextAttribs with OSMESA_PROFILE
 * = OSMESA_CORE_PROFILE gives a 4.5 core profile; the default
 * (compatibility) profile stops at 3.0, too old for the 3.3 shaders. The
 * context's own buffer is a few pixels: every frame is drawn into the
 * renderer's framebuffer object (fbo.c), never into it. OSMesa makes no
 * OpenGL ES context at all: def.gl ES3 is refused here, by name. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* After gl.h: GL/gl.h (which osmesa.h includes) would otherwise hide
 * glcorearb.h's OpenGL 1.1 pointer types. */
#include "render_internal.h"

#include <GL/osmesa.h>

enum { OSMESA_BUFFER_SIDE = 4 };

typedef struct osmesa_state {
  OSMesaContext ctx;
  uint8_t buffer[OSMESA_BUFFER_SIDE * OSMESA_BUFFER_SIDE * 4];
} osmesa_state;

static mr_gl_proc osmesa_get(const char *name) {
  OSMESAproc p = OSMesaGetProcAddress(name);
  mr_gl_proc out;
  memcpy(&out, &p, sizeof out);
  return out;
}

static int osmesa_make_current(mr_render *r) {
  osmesa_state *s = r->bk;
  return OSMesaMakeCurrent(s->ctx, s->buffer, GL_UNSIGNED_BYTE, OSMESA_BUFFER_SIDE,
                           OSMESA_BUFFER_SIDE)
             ? 0
             : -1;
}

static void osmesa_stop(mr_render *r) {
  osmesa_state *s = r->bk;
  if (!s) return;
  if (s->ctx) OSMesaDestroyContext(s->ctx);
  free(s);
  r->bk = NULL;
}

static int osmesa_start(mr_render *r, const mr_render_def *def, char *msg, size_t msg_size) {
  r->gles = false;
  if (def->gl == MR_RENDER_GL_ES3) {
    snprintf(msg, msg_size,
             "OSMesa has no OpenGL ES, only desktop OpenGL (OpenGL ES 3.0 needs the egl or "
             "window backend)");
    return -1;
  }
  osmesa_state *s = calloc(1, sizeof *s);
  if (!s) {
    snprintf(msg, msg_size, "out of memory");
    return -1;
  }
  r->bk = s;
  const int attribs[] = { OSMESA_FORMAT,
                          OSMESA_RGBA,
                          OSMESA_DEPTH_BITS,
                          24,
                          OSMESA_PROFILE,
                          OSMESA_CORE_PROFILE,
                          OSMESA_CONTEXT_MAJOR_VERSION,
                          3,
                          OSMESA_CONTEXT_MINOR_VERSION,
                          3,
                          0 };
  s->ctx = OSMesaCreateContextAttribs(attribs, NULL);
  if (!s->ctx) {
    snprintf(msg, msg_size, "OSMesa: no OpenGL 3.3 core context");
    osmesa_stop(r);
    return -1;
  }
  if (osmesa_make_current(r) != 0) {
    snprintf(msg, msg_size, "OSMesa: cannot make the context current");
    osmesa_stop(r);
    return -1;
  }
  if (mr_gl_load(&r->gl, osmesa_get, msg, msg_size) != 0) {
    osmesa_stop(r);
    return -1;
  }
  return 0;
}

const mr_backend_ops mr_backend_osmesa_ops = { MR_RENDER_OSMESA, osmesa_start, osmesa_make_current,
                                               osmesa_stop };
