/* The renderer's life: a backend chosen and started, the GL objects made,
 * and the frame handed out (read back, or shown in the window). What a
 * frame holds is drawn in draw.c. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render_internal.h"

static const mr_backend_ops *backend_ops(mr_render_backend b) {
  switch (b) {
  case MR_RENDER_WINDOW:
    return &mr_backend_window_ops;
  case MR_RENDER_OSMESA:
    return &mr_backend_osmesa_ops;
  case MR_RENDER_EGL:
    return &mr_backend_egl_ops;
  default:
    return NULL;
  }
}

/* AUTO: the window's context when one is given (and headless was not
 * asked), else EGL, else OSMesa. Returns how many backends to try, in
 * order. */
static int backend_order(const mr_render_def *def, mr_render_backend order[3]) {
  if (def->backend != MR_RENDER_AUTO) {
    order[0] = def->backend;
    return 1;
  }
  int n = 0;
  if (!def->headless && def->context) order[n++] = MR_RENDER_WINDOW;
  order[n++] = MR_RENDER_EGL;
  order[n++] = MR_RENDER_OSMESA;
  return n;
}

/* Starts the first backend that will; msg lists why each one before it
 * failed. */
static int backend_start(mr_render *r, const mr_render_def *def, char *msg, size_t msg_size) {
  mr_render_backend order[3];
  int n = backend_order(def, order);
  size_t used = 0;
  msg[0] = '\0';
  for (int i = 0; i < n; i++) {
    const mr_backend_ops *ops = backend_ops(order[i]);
    char why[256] = "";
    if (ops && ops->start(r, def, why, sizeof why) == 0) {
      r->ops = ops;
      r->backend = order[i];
      return 0;
    }
    if (!ops) snprintf(why, sizeof why, "no such backend");
    int k = snprintf(msg + used, msg_size - used, "%s%s: %s",
                     i ? "; " : "no backend started: ", mr_render_backend_name(order[i]), why);
    if (k > 0 && used + (size_t)k < msg_size) used += (size_t)k;
  }
  return -1;
}

/* The defaults follow where GL draws. In software (the profile of one
 * llvmpipe frame at 1280x720: 4x multisampling took over 40 % of it, the
 * 3 x 3 shadow filter a fifth) a frame has one sample and a post pass
 * smooths its edges, and the shadow filter reads the map once (one
 * bilinear 2 x 2 compare: the map fitted to the casters has texels
 * smaller than the frame's pixels, so more reads change little); on a
 * GPU, 4 samples and 9 reads. What the caller or the scene asks wins. */
static void choose_quality(mr_render *r, const mr_render_def *def) {
  r->smooth = def->samples <= 0 && r->software;
  r->samples = def->samples > 0 ? def->samples : (r->software ? 1 : 4);
  int taps = r->stage.lights.shadow_filter;
  r->shadow_taps = taps == 1 || taps == 4 || taps == 9 ? taps : (r->software ? 1 : 9);
}

static void describe_quality(mr_render *r) {
  char shadow[64] = "no shadow map";
  if (r->stage.lights.shadows)
    snprintf(shadow, sizeof shadow, "shadow map %d x %d, %d-read filter", r->shadow_size,
             r->shadow_size, r->shadow_taps);
  snprintf(r->quality, sizeof r->quality, "%d sample%s%s, %s", r->samples,
           r->samples == 1 ? "" : "s", r->smooth ? ", edges smoothed" : "", shadow);
}

/* Every GL object the renderer keeps, made once. */
static mr_render_status gl_objects_create(mr_render *r, const mr_render_def *def,
                                          const mr_stage_def *stage, const char *scene_path,
                                          char *msg, size_t msg_size) {
  r->gl.Disable(GL_DITHER);
  if (mr_fbo_create(r, msg, msg_size) != 0 || mr_shaders_create(r, msg, msg_size) != 0 ||
      mr_shadow_create(r, msg, msg_size) != 0 || mr_still_create(r, msg, msg_size) != 0 ||
      mr_sky_create(r, msg, msg_size) != 0 || mr_lines_create(r) != 0)
    return MR_RENDER_ERR_GL;
  describe_quality(r);
  if (mr_text_create(r, def->font_path, msg, msg_size) != 0) return MR_RENDER_ERR_ARG;
  mr_render_status st = MR_RENDER_ERR_GL;
  if (mr_meshes_create(r, stage, scene_path, msg, msg_size, &st) != 0) return st;
  return r->gl.GetError() == GL_NO_ERROR ? MR_RENDER_OK : MR_RENDER_ERR_GL;
}

mr_render_status mr_render_create(const mr_render_def *def, const mr_stage_def *stage,
                                  const char *scene_path, mr_render **out, char *msg,
                                  size_t msg_size) {
  char scratch[8];
  if (!msg || msg_size == 0) {
    msg = scratch;
    msg_size = sizeof scratch;
  }
  if (out) *out = NULL;
  if (!def || def->cookie != MR_DEF_COOKIE || !stage || stage->cookie != MR_DEF_COOKIE || !out ||
      (unsigned)def->gl > MR_RENDER_GL_ES3) {
    snprintf(msg, msg_size, "mr_render_create: a def not from its default maker, or NULL");
    return MR_RENDER_ERR_ARG;
  }
  mr_render *r = calloc(1, sizeof *r);
  if (!r) {
    snprintf(msg, msg_size, "out of memory");
    return MR_RENDER_ERR_NOMEM;
  }
  r->scratch = calloc(MR_SCRATCH_COUNT, sizeof *r->scratch);
  if (!r->scratch) {
    free(r);
    snprintf(msg, msg_size, "out of memory");
    return MR_RENDER_ERR_NOMEM;
  }
  r->stage = *stage;
  r->width = def->width > 0 ? def->width : (stage->width > 0 ? stage->width : 1280);
  r->height = def->height > 0 ? def->height : (stage->height > 0 ? stage->height : 720);
  if (backend_start(r, def, msg, msg_size) != 0) {
    free(r->scratch);
    free(r);
    return MR_RENDER_ERR_BACKEND;
  }
  mr_gl_describe(r);
  choose_quality(r, def);
  mr_render_status st = gl_objects_create(r, def, stage, scene_path, msg, msg_size);
  if (st != MR_RENDER_OK) {
    if (st == MR_RENDER_ERR_GL && !msg[0]) snprintf(msg, msg_size, "a GL call failed at create");
    mr_render_destroy(r);
    return st;
  }
  *out = r;
  return MR_RENDER_OK;
}

void mr_render_destroy(mr_render *r) {
  if (!r) return;
  if (r->ops && r->ops->make_current(r) == 0) {
    mr_meshes_destroy(r);
    mr_text_destroy(r);
    mr_lines_destroy(r);
    mr_sky_destroy(r);
    mr_shadow_destroy(r);
    mr_still_destroy(r);
    mr_shaders_destroy(r);
    mr_fbo_destroy(r);
  }
  if (r->ops) r->ops->stop(r);
  for (int k = 0; k < MR_SCRATCH_COUNT; k++) free(r->scratch[k].p);
  free(r->scratch);
  free(r);
}

void *mr_render_scratch(const mr_render *r, int k, size_t bytes) {
  mr_scratch *s = &r->scratch[k];
  if (bytes <= s->size) return s->p;
  size_t want = bytes > 2 * s->size ? bytes : 2 * s->size;
  void *p = realloc(s->p, want);
  if (!p) return NULL;
  s->p = p;
  s->size = want;
  return p;
}

mr_render_backend mr_render_backend_of(const mr_render *r) {
  return r ? r->backend : MR_RENDER_AUTO;
}

const char *mr_render_gl_description(const mr_render *r) {
  return r ? r->description : "";
}

const char *mr_render_quality(const mr_render *r) {
  return r ? r->quality : "";
}

bool mr_render_is_software(const mr_render *r) {
  return r && r->software;
}

void mr_render_size(const mr_render *r, int *width, int *height) {
  if (width) *width = r ? r->width : 0;
  if (height) *height = r ? r->height : 0;
}

mr_render_status mr_render_read_rgb(mr_render *r, uint8_t *rgb, size_t size) {
  if (!r || !rgb || size < (size_t)r->width * (size_t)r->height * 3) return MR_RENDER_ERR_ARG;
  if (r->ops->make_current(r) != 0) return MR_RENDER_ERR_GL;
  if (mr_fbo_read_rgb(r, rgb) != 0) return MR_RENDER_ERR_NOMEM;
  return r->gl.GetError() == GL_NO_ERROR ? MR_RENDER_OK : MR_RENDER_ERR_GL;
}

void mr_render_present(mr_render *r) {
  if (!r || r->backend != MR_RENDER_WINDOW || r->ops->make_current(r) != 0) return;
  int w = 0, h = 0;
  mr_context_drawable_size(r, &w, &h);
  if (w > 0 && h > 0) mr_fbo_blit_to_window(r, w, h);
  mr_context_present(r);
}
