/* The window backend: the GL context a window made (def.context, from
 * host/window's mr_window through the program's wiring). The renderer
 * neither opens the window nor links its library: it loads its GL table
 * through the context's get_proc, makes the context current before it
 * touches GL, and asks the window to show the back buffer it blitted the
 * frame into (fbo.c), so the window and headless frames come from one
 * path. Stopping leaves the context to the window, which made it. */
#include <stdio.h>
#include <stdlib.h>

#include "render_internal.h"

static int window_make_current(mr_render *r) {
  const mr_render_context *c = r->bk;
  return c->make_current(c->self) == 0 ? 0 : -1;
}

static void window_stop(mr_render *r) {
  free(r->bk);
  r->bk = NULL;
}

static int window_start(mr_render *r, const mr_render_def *def, char *msg, size_t msg_size) {
  const mr_render_context *c = def->context;
  if (!c || !c->get_proc || !c->make_current || !c->drawable_size || !c->present) {
    snprintf(msg, msg_size, "no window's GL context given (mr_render_def.context)");
    return -1;
  }
  if ((def->gl == MR_RENDER_GL_CORE && c->gles) || (def->gl == MR_RENDER_GL_ES3 && !c->gles)) {
    snprintf(msg, msg_size, "the window's context is OpenGL %s, not the %s asked for",
             c->gles ? "ES" : "core", def->gl == MR_RENDER_GL_CORE ? "3.3 core" : "ES 3.0");
    return -1;
  }
  mr_render_context *own = malloc(sizeof *own);
  if (!own) {
    snprintf(msg, msg_size, "out of memory");
    return -1;
  }
  *own = *c;
  r->bk = own;
  r->gles = c->gles;
  if (window_make_current(r) != 0) {
    snprintf(msg, msg_size, "the window's GL context could not be made current");
    window_stop(r);
    return -1;
  }
  if (mr_gl_load(&r->gl, c->get_proc, msg, msg_size) != 0) {
    window_stop(r);
    return -1;
  }
  return 0;
}

void mr_context_drawable_size(mr_render *r, int *w, int *h) {
  const mr_render_context *c = r->bk;
  *w = 0;
  *h = 0;
  c->drawable_size(c->self, w, h);
}

void mr_context_present(mr_render *r) {
  const mr_render_context *c = r->bk;
  c->present(c->self);
}

const mr_backend_ops mr_backend_window_ops = { MR_RENDER_WINDOW, window_start, window_make_current,
                                               window_stop };
