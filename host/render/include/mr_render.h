/* mr_render: the stage drawn with one GL path, on OpenGL 3.3 core or
 * OpenGL ES 3.0.
 *
 * Every frame is drawn into the renderer's own framebuffer object,
 * multisampled and resolved (or, in software, smoothed by a post pass),
 * then shown in a window (in the GL context a window made, which the
 * renderer is handed: mr_render_context) or read back (OSMesa, EGL
 * surfaceless). The renderer takes an mr_stage_def at create (its models
 * are loaded then) and, each frame, an mr_draw_list of poses and an
 * mr_render_view; it knows nothing of physics nor of windows. No SDL or GL
 * type appears here. Libraries never print: errors fill msg. */
#ifndef MR_RENDER_H
#define MR_RENDER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mr_stage.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mr_render_backend {
  MR_RENDER_AUTO = 0, /* the window's context when def.context is given, else
                         EGL, else OSMesa; headless (def.headless): EGL, else
                         OSMesa */
  MR_RENDER_WINDOW,   /* the GL context of a window (def.context) */
  MR_RENDER_OSMESA,
  MR_RENDER_EGL /* surfaceless */
} mr_render_backend;
const char *mr_render_backend_name(mr_render_backend b);
int mr_render_backend_parse(const char *name, mr_render_backend *out);

/* Which OpenGL the context speaks. The renderer draws the same frame with
 * either: its shaders are one source, compiled as GLSL 3.30 core or
 * GLSL ES 3.00 (see host/render/README.md). */
typedef enum mr_render_gl {
  MR_RENDER_GL_AUTO = 0, /* desktop OpenGL 3.3 core, else OpenGL ES 3.0 */
  MR_RENDER_GL_CORE,     /* desktop OpenGL 3.3 core only */
  MR_RENDER_GL_ES3       /* OpenGL ES 3.0 only (window or EGL; OSMesa has none) */
} mr_render_gl;
/* "auto", "core", "es3". */
const char *mr_render_gl_name(mr_render_gl g);
int mr_render_gl_parse(const char *name, mr_render_gl *out);

/* A GL context someone else made, with a window to show frames in (the
 * window backend's; host/window's mr_window makes one). The renderer
 * draws only while it is current, and makes it current itself before it
 * draws, reads or shows. */
typedef void (*mr_render_proc)(void);
typedef struct mr_render_context {
  void *self;                                   /* handed back to the calls below */
  mr_render_proc (*get_proc)(const char *name); /* the context's GL entry points */
  int (*make_current)(void *self);              /* 0, or -1 */
  void (*drawable_size)(void *self, int *width, int *height);
  void (*present)(void *self); /* shows the back buffer (swaps) */
  bool gles;                   /* the context is OpenGL ES 3.x, else desktop core */
} mr_render_context;

typedef struct mr_render_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_render_def() */
  mr_render_backend backend;
  mr_render_gl gl;   /* default AUTO */
  bool headless;     /* AUTO picks only headless backends */
  int width, height; /* <= 0: the stage's size */
  /* Multisampling, samples a pixel. 0 (default): 4 where a GPU draws; in
   * software (Mesa's llvmpipe or softpipe), where it costs most of a
   * frame, 1, and the edges are smoothed by a post pass instead. N >= 1:
   * N samples (1: none), and no post pass. */
  int samples;
  /* The window's context (backend WINDOW, or AUTO not headless); copied
   * at create; it must outlive the renderer. NULL: none. */
  const mr_render_context *context;
  const char *font_path; /* NULL: the DejaVu Sans Mono the system ships */
} mr_render_def;
mr_render_def mr_default_render_def(void);

typedef enum mr_render_status {
  MR_RENDER_OK = 0,
  MR_RENDER_ERR_ARG = -1,
  MR_RENDER_ERR_BACKEND = -2, /* no backend (or not the one asked for) could start */
  MR_RENDER_ERR_MODEL = -3,   /* a model file missing or corrupt */
  MR_RENDER_ERR_GL = -4,      /* a shader, framebuffer or texture failed */
  MR_RENDER_ERR_NOMEM = -5
} mr_render_status;

typedef struct mr_render mr_render;

/* Starts a backend and loads the stage's models. A model that cannot be
 * read fails the whole create with MR_RENDER_ERR_MODEL and a msg reading
 * "SCENE:LINE:COLUMN: model 'NAME': FILE: why" (scene_path may be NULL). */
mr_render_status mr_render_create(const mr_render_def *def, const mr_stage_def *stage,
                                  const char *scene_path, mr_render **out, char *msg,
                                  size_t msg_size);
void mr_render_destroy(mr_render *r);

mr_render_backend mr_render_backend_of(const mr_render *r);
/* The GL_RENDERER and GL_VERSION strings, for logs. */
const char *mr_render_gl_description(const mr_render *r);
/* The OpenGL the renderer got: MR_RENDER_GL_CORE or MR_RENDER_GL_ES3. */
mr_render_gl mr_render_gl_of(const mr_render *r);
/* It, short, with the context's version: "OpenGL 4.5 core" or
 * "OpenGL ES 3.2", for a summary line. */
const char *mr_render_gl_version(const mr_render *r);
/* What the frame is drawn with, for logs: "1 sample, edges smoothed,
 * shadow map 1024 x 1024, 1-read filter". */
const char *mr_render_quality(const mr_render *r);
/* True when GL draws in software (GL_RENDERER names llvmpipe, softpipe
 * or swrast): the defaults then choose what is cheap there. */
bool mr_render_is_software(const mr_render *r);
void mr_render_size(const mr_render *r, int *width, int *height);

/* How a frame is looked at. */
typedef struct mr_render_view {
  double eye[3], target[3], up[3];
  double fov_deg;     /* vertical */
  double time_of_day; /* the day knob, 0..1 (mr_stage_def.time_of_day) */
  bool show_rigging;  /* strings and control frames */
  /* On-screen display: lines of text drawn top left, from a font. */
  const char *const *osd;
  size_t n_osd;
} mr_render_view;
/* The stage's orbit camera at its start, its day knob, rigging shown. */
mr_render_view mr_default_render_view(const mr_stage_def *stage);
/* The view from the orbit camera o (mr_stage's maths): its eye, target,
 * field of view, and y up. */
void mr_render_view_orbit(mr_render_view *v, const mr_orbit *o);

/* Draws one frame into the renderer's framebuffer. */
mr_render_status mr_render_draw(mr_render *r, const mr_draw_list *list, const mr_render_view *view);
/* The last frame drawn as 8-bit RGB, top row first: size >= 3 w h. */
mr_render_status mr_render_read_rgb(mr_render *r, uint8_t *rgb, size_t size);
/* Window: the last frame drawn blitted into the window's back buffer,
 * scaled to fit, then shown (context.present). Headless: nothing. */
void mr_render_present(mr_render *r);

#ifdef __cplusplus
}
#endif

#endif /* MR_RENDER_H */
