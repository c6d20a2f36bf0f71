/* mr_window: a window on the screen (SDL2), or the console's screen
 * through SDL's KMS/DRM driver, with its events (keys, mouse, wheel,
 * resizes, game controllers) and the OpenGL context it is made with.
 *
 * The window makes the context (desktop OpenGL 3.3 core, else OpenGL
 * ES 3.0, or the one asked for), makes it current and swaps its buffers;
 * it draws nothing and makes no GL call of its own. Whoever draws (the
 * renderer) loads its GL entry points through mr_window_gl_proc. No SDL
 * or GL type appears here. Libraries never print: errors fill msg.
 * Every call is made from the thread that created the window. */
#ifndef MR_WINDOW_H
#define MR_WINDOW_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mr_def.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Which OpenGL the window's context speaks. */
typedef enum mr_window_gl {
  MR_WINDOW_GL_AUTO = 0, /* desktop OpenGL 3.3 core, else OpenGL ES 3.0 */
  MR_WINDOW_GL_CORE,     /* desktop OpenGL 3.3 core only */
  MR_WINDOW_GL_ES3       /* OpenGL ES 3.0 only */
} mr_window_gl;

typedef struct mr_window_def {
  uint32_t cookie;   /* MR_DEF_COOKIE, set by mr_default_window_def() */
  int width, height; /* default 1280 x 720 */
  mr_window_gl gl;   /* default AUTO */
  bool fullscreen;   /* the whole screen (the desktop's size) */
  bool vsync;        /* a swap waits for the screen's refresh; default true */
  const char *title; /* default "marionette" */
} mr_window_def;
mr_window_def mr_default_window_def(void);

typedef enum mr_window_status {
  MR_WINDOW_OK = 0,
  MR_WINDOW_ERR_ARG = -1,
  MR_WINDOW_ERR_SCREEN = -2, /* no video driver opened a screen */
  MR_WINDOW_ERR_GL = -3,     /* no OpenGL context of the kind asked for */
  MR_WINDOW_ERR_NOMEM = -4
} mr_window_status;

typedef struct mr_window mr_window;

/* Opens the window and makes its context, current on this thread. With
 * no X or Wayland display and no SDL_VIDEODRIVER named, the screen is the
 * console's (SDL's KMS/DRM driver); a driver that shows nothing
 * (offscreen, dummy) is refused unless SDL_VIDEODRIVER named it. */
mr_window_status mr_window_create(const mr_window_def *def, mr_window **out, char *msg,
                                  size_t msg_size);
/* Closes the window, its context and its game controllers. */
void mr_window_destroy(mr_window *w);

/* ------------------------------------------------------- the GL context */

/* The OpenGL the context speaks: MR_WINDOW_GL_CORE or MR_WINDOW_GL_ES3. */
mr_window_gl mr_window_gl_of(const mr_window *w);
/* A GL entry point of the library the window's context came from, by name
 * ("glClear"); NULL when it has none. Valid while a window is open. */
typedef void (*mr_window_proc)(void);
mr_window_proc mr_window_gl_proc(const char *name);
/* Makes the window's context current on this thread: 0, or -1. */
int mr_window_make_current(mr_window *w);
/* The size of what the context draws into, in pixels (larger than the
 * window's size on a high-density screen). */
void mr_window_drawable_size(const mr_window *w, int *width, int *height);
/* Shows the back buffer (a buffer swap; with vsync it waits). */
void mr_window_swap(mr_window *w);

/* ---------------------------------------------------------- the screen */

mr_window_status mr_window_set_fullscreen(mr_window *w, bool on);
bool mr_window_fullscreen(const mr_window *w);
/* SDL's video driver in use: "x11", "wayland", "kmsdrm", ... */
const char *mr_window_driver(const mr_window *w);

/* ------------------------------------------------------------ its input */

typedef enum mr_window_event_kind {
  MR_WINDOW_EVENT_NONE = 0,
  MR_WINDOW_EVENT_QUIT,
  MR_WINDOW_EVENT_KEY,          /* key, down */
  MR_WINDOW_EVENT_MOUSE_MOVE,   /* x, y, dx, dy (pixels), buttons held */
  MR_WINDOW_EVENT_MOUSE_BUTTON, /* button, down, x, y */
  MR_WINDOW_EVENT_MOUSE_WHEEL,  /* dy: steps, up positive */
  MR_WINDOW_EVENT_PAD_ADDED,    /* a game controller plugged in (pad: its id) */
  MR_WINDOW_EVENT_PAD_REMOVED,
  MR_WINDOW_EVENT_PAD_AXIS,   /* axis, value: sticks -1..1, triggers 0..1 */
  MR_WINDOW_EVENT_PAD_BUTTON, /* button, down */
  MR_WINDOW_EVENT_RESIZE      /* width, height */
} mr_window_event_kind;

/* Keys: printable keys are their lower-case ASCII code; the rest these. */
enum {
  MR_WINDOW_KEY_ESCAPE = 27,
  MR_WINDOW_KEY_SPACE = ' ',
  MR_WINDOW_KEY_F1 = 0x100,
  MR_WINDOW_KEY_F11 = 0x10a,
  MR_WINDOW_KEY_F12 = 0x10b,
  MR_WINDOW_KEY_LEFT = 0x110,
  MR_WINDOW_KEY_RIGHT,
  MR_WINDOW_KEY_UP,
  MR_WINDOW_KEY_DOWN,
  MR_WINDOW_KEY_PAGE_UP,
  MR_WINDOW_KEY_PAGE_DOWN,
  MR_WINDOW_KEY_SHIFT,
  MR_WINDOW_KEY_OTHER = 0x1ff
};

/* Game controller axes, as SDL's game controller names them. */
enum {
  MR_WINDOW_PAD_LEFT_X = 0,
  MR_WINDOW_PAD_LEFT_Y,
  MR_WINDOW_PAD_RIGHT_X,
  MR_WINDOW_PAD_RIGHT_Y,
  MR_WINDOW_PAD_TRIGGER_LEFT,
  MR_WINDOW_PAD_TRIGGER_RIGHT
};

typedef struct mr_window_event {
  mr_window_event_kind kind;
  int key;     /* KEY */
  bool down;   /* KEY, MOUSE_BUTTON, PAD_BUTTON */
  int button;  /* mouse: 1 left, 2 middle, 3 right; pad: SDL's number */
  int buttons; /* MOUSE_MOVE: held, bit 0 left, 1 middle, 2 right */
  double x, y, dx, dy;
  int axis;          /* PAD_AXIS */
  double value;      /* PAD_AXIS */
  int pad;           /* PAD_*: which controller */
  int width, height; /* RESIZE */
} mr_window_event;

/* The next pending event into ev; 0 when there is none. Never waits. Key
 * repeats and events the window does not report are passed over. */
int mr_window_poll(mr_window *w, mr_window_event *ev);

#ifdef __cplusplus
}
#endif

#endif /* MR_WINDOW_H */
