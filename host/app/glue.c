/* The window's context handed to the renderer (glue.h). */
#include "glue.h"

static int make_current(void *self) {
  return mr_window_make_current(self);
}

static void drawable_size(void *self, int *width, int *height) {
  mr_window_drawable_size(self, width, height);
}

static void present(void *self) {
  mr_window_swap(self);
}

mr_render_context mr_glue_context(mr_window *w) {
  mr_render_context c = { .self = w,
                          .get_proc = mr_window_gl_proc,
                          .make_current = make_current,
                          .drawable_size = drawable_size,
                          .present = present,
                          .gles = mr_window_gl_of(w) == MR_WINDOW_GL_ES3 };
  return c;
}

mr_window_gl mr_glue_gl(mr_render_gl gl) {
  switch (gl) {
  case MR_RENDER_GL_CORE:
    return MR_WINDOW_GL_CORE;
  case MR_RENDER_GL_ES3:
    return MR_WINDOW_GL_ES3;
  default:
    return MR_WINDOW_GL_AUTO;
  }
}
