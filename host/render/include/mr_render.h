/* mr_render: the stage drawn with one GL path, on OpenGL 3.3 core or
 * OpenGL ES 3.0.
 *
 * Every frame is drawn into the renderer's own framebuffer object,
 * multisampled and resolved (or, in software, smoothed by a post pass),
 * then shown in a window (SDL2) or read back (OSMesa, EGL surfaceless). The renderer takes an mr_stage_def at create (its
 * models are loaded then) and, each frame, an mr_draw_list of poses and an
 * mr_render_view; it knows nothing of physics. No SDL or GL type appears
 * here. Libraries never print: errors fill msg. */
#ifndef MR_RENDER_H
#define MR_RENDER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mr_stage.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MR_RENDER_COOKIE 0x6d725264u

typedef enum mr_render_backend {
  MR_RENDER_AUTO = 0, /* a window when a display is there, else EGL, else OSMesa;
                         headless (def.headless): EGL, else OSMesa */
  MR_RENDER_WINDOW,   /* SDL2 */
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

typedef struct mr_render_def {
  uint32_t cookie; /* MR_RENDER_COOKIE, set by mr_default_render_def() */
  mr_render_backend backend;
  mr_render_gl gl;   /* default AUTO */
  bool headless;     /* AUTO picks only headless backends */
  int width, height; /* <= 0: the stage's size */
  /* Multisampling, samples a pixel. 0 (default): 4 where a GPU draws; in
   * software (Mesa's llvmpipe or softpipe), where it costs most of a
   * frame, 1, and the edges are smoothed by a post pass instead. N >= 1:
   * N samples (1: none), and no post pass. */
  int samples;
  bool fullscreen;       /* window only */
  bool vsync;            /* window only, default true */
  const char *title;     /* window only */
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
/* The orbit camera: eye at distance from target, turned by azimuth about
 * y and raised by elevation (degrees). */
void mr_render_view_orbit(mr_render_view *v, const double target[3], double distance,
                          double azimuth_deg, double elevation_deg);

/* Draws one frame into the renderer's framebuffer. */
mr_render_status mr_render_draw(mr_render *r, const mr_draw_list *list, const mr_render_view *view);
/* The last frame drawn as 8-bit RGB, top row first: size >= 3 w h. */
mr_render_status mr_render_read_rgb(mr_render *r, uint8_t *rgb, size_t size);
/* Window: shows the last frame drawn. Headless: nothing. */
void mr_render_present(mr_render *r);
mr_render_status mr_render_set_fullscreen(mr_render *r, bool on);

/* ---------------------------------------------------- the window's input */

typedef enum mr_event_kind {
  MR_EVENT_NONE = 0,
  MR_EVENT_QUIT,
  MR_EVENT_KEY,          /* key, down */
  MR_EVENT_MOUSE_MOVE,   /* x, y, dx, dy (pixels), buttons held */
  MR_EVENT_MOUSE_BUTTON, /* button, down, x, y */
  MR_EVENT_MOUSE_WHEEL,  /* dy: steps, up positive */
  MR_EVENT_PAD_ADDED,    /* a game controller plugged in (pad: its id) */
  MR_EVENT_PAD_REMOVED,
  MR_EVENT_PAD_AXIS,   /* axis, value: sticks -1..1, triggers 0..1 */
  MR_EVENT_PAD_BUTTON, /* button, down */
  MR_EVENT_RESIZE      /* width, height */
} mr_event_kind;

/* Keys: printable keys are their lower-case ASCII code; the rest these. */
enum {
  MR_KEY_ESCAPE = 27,
  MR_KEY_SPACE = ' ',
  MR_KEY_F1 = 0x100,
  MR_KEY_F11 = 0x10a,
  MR_KEY_F12 = 0x10b,
  MR_KEY_LEFT = 0x110,
  MR_KEY_RIGHT,
  MR_KEY_UP,
  MR_KEY_DOWN,
  MR_KEY_PAGE_UP,
  MR_KEY_PAGE_DOWN,
  MR_KEY_SHIFT,
  MR_KEY_OTHER = 0x1ff
};

/* Game controller axes and buttons, as SDL's game controller names them. */
enum {
  MR_PAD_LEFT_X = 0,
  MR_PAD_LEFT_Y,
  MR_PAD_RIGHT_X,
  MR_PAD_RIGHT_Y,
  MR_PAD_TRIGGER_LEFT,
  MR_PAD_TRIGGER_RIGHT
};

typedef struct mr_event {
  mr_event_kind kind;
  int key;     /* MR_EVENT_KEY */
  bool down;   /* KEY, MOUSE_BUTTON, PAD_BUTTON */
  int button;  /* mouse: 1 left, 2 middle, 3 right; pad: SDL's number */
  int buttons; /* MOUSE_MOVE: held, bit 0 left, 1 middle, 2 right */
  double x, y, dx, dy;
  int axis;          /* PAD_AXIS */
  double value;      /* PAD_AXIS */
  int pad;           /* PAD_*: which controller */
  int width, height; /* RESIZE */
} mr_event;

/* The next pending window event into ev; 0 when there is none (always 0
 * headless). Never waits. */
int mr_render_poll(mr_render *r, mr_event *ev);

#ifdef __cplusplus
}
#endif

#endif /* MR_RENDER_H */
