/* The window: SDL's video (an X or Wayland display, else the console's
 * KMS/DRM), one window and the OpenGL context made with it: desktop 3.3
 * core, or ES 3.0 where the desktop's is not offered (def.gl AUTO; CORE
 * and ES3 ask for one only). SDL's GL attributes take effect only when set
 * before SDL_CreateWindow (SDL loads its GL library, desktop or ES, with
 * the window), so a second try is a second window.
 *
 * With no X or Wayland display (a console box started at boot) the screen
 * is the console's, through SDL's KMS/DRM driver; left to itself, SDL
 * would end its search on a driver that opens no screen (offscreen) and
 * draw into nothing. A driver that shows nothing is refused, unless the
 * user named it in SDL_VIDEODRIVER. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "window_internal.h"

#define VIDEO_AND_PADS (SDL_INIT_VIDEO | SDL_INIT_GAMECONTROLLER)

mr_window_def mr_default_window_def(void) {
  mr_window_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  d.width = 1280;
  d.height = 720;
  d.gl = MR_WINDOW_GL_AUTO;
  d.vsync = true;
  d.title = "marionette";
  return d;
}

static void set_attributes(bool es) {
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, es ? 0 : 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK,
                      es ? SDL_GL_CONTEXT_PROFILE_ES : SDL_GL_CONTEXT_PROFILE_CORE);
  SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
  /* What draws here only blits its own frame in: no depth, no
   * multisampling of the window's own. */
  SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 0);
  SDL_GL_SetAttribute(SDL_GL_MULTISAMPLEBUFFERS, 0);
  SDL_GL_SetAttribute(SDL_GL_RED_SIZE, 8);
  SDL_GL_SetAttribute(SDL_GL_GREEN_SIZE, 8);
  SDL_GL_SetAttribute(SDL_GL_BLUE_SIZE, 8);
}

static bool env_set(const char *name) {
  const char *v = getenv(name);
  return v != NULL && v[0] != '\0';
}

/* SDL's video, on the console's KMS/DRM when there is no X or Wayland
 * display and the user named no driver. 0, or -1 with msg. */
static int video_init(char *msg, size_t msg_size) {
  bool console = !env_set("DISPLAY") && !env_set("WAYLAND_DISPLAY");
  bool named = env_set("SDL_VIDEODRIVER");
  /* The hint outlives this window: a later one with a display must not
   * inherit it. */
  if (console && !named)
    SDL_SetHint(SDL_HINT_VIDEODRIVER, "kmsdrm");
  else
    SDL_ResetHint(SDL_HINT_VIDEODRIVER);
  if (SDL_InitSubSystem(VIDEO_AND_PADS) != 0) {
    if (console && !named)
      snprintf(msg, msg_size,
               "no screen: no X or Wayland display (DISPLAY, WAYLAND_DISPLAY) and SDL's console "
               "driver (KMS/DRM) did not open: %s",
               SDL_GetError());
    else
      snprintf(msg, msg_size, "SDL_Init: %s", SDL_GetError());
    return -1;
  }
  const char *driver = SDL_GetCurrentVideoDriver();
  if (!named && driver && (strcmp(driver, "offscreen") == 0 || strcmp(driver, "dummy") == 0)) {
    snprintf(msg, msg_size, "SDL's only video driver here is '%s', which shows nothing", driver);
    SDL_QuitSubSystem(VIDEO_AND_PADS);
    return -1;
  }
  return 0;
}

/* A window with a context of the OpenGL es says; 0, or -1 with why and
 * neither left. */
static int open_window(mr_window *w, const mr_window_def *def, bool es, char *why,
                       size_t why_size) {
  set_attributes(es);
  Uint32 flags = SDL_WINDOW_OPENGL | SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI;
  if (def->fullscreen) flags |= SDL_WINDOW_FULLSCREEN_DESKTOP;
  w->window = SDL_CreateWindow(def->title ? def->title : "marionette", SDL_WINDOWPOS_CENTERED,
                               SDL_WINDOWPOS_CENTERED, def->width, def->height, flags);
  if (!w->window) {
    snprintf(why, why_size, "SDL_CreateWindow: %s", SDL_GetError());
    return -1;
  }
  w->ctx = SDL_GL_CreateContext(w->window);
  if (w->ctx) return 0;
  snprintf(why, why_size, "no OpenGL %s context: %s", es ? "ES 3.0" : "3.3 core", SDL_GetError());
  SDL_DestroyWindow(w->window);
  w->window = NULL;
  return -1;
}

/* The desktop's context, else (AUTO) or only (ES3) the ES one. */
static int open_with_context(mr_window *w, const mr_window_def *def, char *msg, size_t msg_size) {
  char why_core[200] = "", why_es[200] = "";
  int rc = -1;
  if (def->gl != MR_WINDOW_GL_ES3) rc = open_window(w, def, false, why_core, sizeof why_core);
  if (rc != 0 && def->gl != MR_WINDOW_GL_CORE) {
    rc = open_window(w, def, true, why_es, sizeof why_es);
    w->gles = rc == 0;
  }
  if (rc != 0)
    snprintf(msg, msg_size, "%s%s%s", why_core, why_core[0] && why_es[0] ? "; " : "", why_es);
  return rc;
}

mr_window_status mr_window_create(const mr_window_def *def, mr_window **out, char *msg,
                                  size_t msg_size) {
  char scratch[8];
  if (!msg || msg_size == 0) {
    msg = scratch;
    msg_size = sizeof scratch;
  }
  if (out) *out = NULL;
  if (!def || def->cookie != MR_DEF_COOKIE || !out || (unsigned)def->gl > MR_WINDOW_GL_ES3 ||
      def->width <= 0 || def->height <= 0) {
    snprintf(msg, msg_size, "mr_window_create: a def not from its default maker, or NULL");
    return MR_WINDOW_ERR_ARG;
  }
  mr_window *w = calloc(1, sizeof *w);
  if (!w) {
    snprintf(msg, msg_size, "out of memory");
    return MR_WINDOW_ERR_NOMEM;
  }
  if (video_init(msg, msg_size) != 0) {
    free(w);
    return MR_WINDOW_ERR_SCREEN;
  }
  if (open_with_context(w, def, msg, msg_size) != 0) {
    SDL_QuitSubSystem(VIDEO_AND_PADS);
    free(w);
    return MR_WINDOW_ERR_GL;
  }
  if (mr_window_make_current(w) != 0) {
    snprintf(msg, msg_size, "SDL_GL_MakeCurrent: %s", SDL_GetError());
    mr_window_destroy(w);
    return MR_WINDOW_ERR_GL;
  }
  SDL_GL_SetSwapInterval(def->vsync ? 1 : 0);
  w->fullscreen = def->fullscreen;
  *out = w;
  return MR_WINDOW_OK;
}

void mr_window_destroy(mr_window *w) {
  if (!w) return;
  mr_window_pads_close(&w->pads);
  if (w->ctx) SDL_GL_DeleteContext(w->ctx);
  if (w->window) SDL_DestroyWindow(w->window);
  SDL_QuitSubSystem(VIDEO_AND_PADS);
  free(w);
}

mr_window_gl mr_window_gl_of(const mr_window *w) {
  if (!w) return MR_WINDOW_GL_AUTO;
  return w->gles ? MR_WINDOW_GL_ES3 : MR_WINDOW_GL_CORE;
}

/* A function pointer is copied through memcpy, which C allows between
 * pointer types of equal size (SDL hands it out as a void *). */
mr_window_proc mr_window_gl_proc(const char *name) {
  void *p = name ? SDL_GL_GetProcAddress(name) : NULL;
  mr_window_proc out;
  memcpy(&out, &p, sizeof out);
  return out;
}

int mr_window_make_current(mr_window *w) {
  if (!w) return -1;
  return SDL_GL_MakeCurrent(w->window, w->ctx) == 0 ? 0 : -1;
}

void mr_window_drawable_size(const mr_window *w, int *width, int *height) {
  int dw = 0, dh = 0;
  if (w) SDL_GL_GetDrawableSize(w->window, &dw, &dh);
  if (width) *width = dw;
  if (height) *height = dh;
}

void mr_window_swap(mr_window *w) {
  if (w) SDL_GL_SwapWindow(w->window);
}

mr_window_status mr_window_set_fullscreen(mr_window *w, bool on) {
  if (!w) return MR_WINDOW_ERR_ARG;
  if (SDL_SetWindowFullscreen(w->window, on ? SDL_WINDOW_FULLSCREEN_DESKTOP : 0) != 0)
    return MR_WINDOW_ERR_SCREEN;
  w->fullscreen = on;
  return MR_WINDOW_OK;
}

bool mr_window_fullscreen(const mr_window *w) {
  return w != NULL && w->fullscreen;
}

const char *mr_window_driver(const mr_window *w) {
  const char *d = w ? SDL_GetCurrentVideoDriver() : NULL;
  return d ? d : "";
}
