/* The window backend: an SDL2 window with an OpenGL 3.3 core context, or
 * an OpenGL ES 3.0 one where the desktop's is not offered (def.gl AUTO;
 * CORE and ES3 ask for one only). The frame is drawn into the renderer's
 * framebuffer object like every other backend's, then blitted to the
 * window (fbo.c), so the window and headless frames come from one path.
 * SDL's GL attributes take effect only when set before SDL_CreateWindow
 * (SDL loads its GL library, desktop or ES, with the window), so a second
 * try is a second window.
 *
 * With no X or Wayland display (a console box started at boot) the screen
 * is the console's, through SDL's KMS/DRM driver; left to itself, SDL
 * would end its search on a driver that opens no screen (offscreen) and
 * draw into nothing. A driver that shows nothing is refused, unless the
 * user named it in SDL_VIDEODRIVER. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <SDL.h>

#include "render_internal.h"
#include "sdl_events.h"

typedef struct sdl_state {
  SDL_Window *window;
  SDL_GLContext ctx;
  mr_sdl_pads pads;
} sdl_state;

static mr_gl_proc sdl_get(const char *name) {
  void *p = SDL_GL_GetProcAddress(name);
  mr_gl_proc out;
  memcpy(&out, &p, sizeof out);
  return out;
}

static int sdl_make_current(mr_render *r) {
  sdl_state *s = r->bk;
  return SDL_GL_MakeCurrent(s->window, s->ctx) == 0 ? 0 : -1;
}

static void sdl_stop(mr_render *r) {
  sdl_state *s = r->bk;
  if (!s) return;
  mr_sdl_pads_close(&s->pads);
  if (s->ctx) SDL_GL_DeleteContext(s->ctx);
  if (s->window) SDL_DestroyWindow(s->window);
  SDL_QuitSubSystem(SDL_INIT_VIDEO | SDL_INIT_GAMECONTROLLER);
  free(s);
  r->bk = NULL;
}

static int sdl_fail(mr_render *r, char *msg, size_t msg_size, const char *what) {
  snprintf(msg, msg_size, "%s: %s", what, SDL_GetError());
  sdl_stop(r);
  return -1;
}

static void sdl_set_attributes(bool es) {
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, es ? 0 : 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK,
                      es ? SDL_GL_CONTEXT_PROFILE_ES : SDL_GL_CONTEXT_PROFILE_CORE);
  SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
  /* The window only receives blits: no depth, no multisampling of its own. */
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
static int sdl_video_init(char *msg, size_t msg_size) {
  bool console = !env_set("DISPLAY") && !env_set("WAYLAND_DISPLAY");
  bool named = env_set("SDL_VIDEODRIVER");
  /* The hint outlives this window: a later one with a display must not
   * inherit it. */
  if (console && !named)
    SDL_SetHint(SDL_HINT_VIDEODRIVER, "kmsdrm");
  else
    SDL_ResetHint(SDL_HINT_VIDEODRIVER);
  if (SDL_InitSubSystem(SDL_INIT_VIDEO | SDL_INIT_GAMECONTROLLER) != 0) {
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
    SDL_QuitSubSystem(SDL_INIT_VIDEO | SDL_INIT_GAMECONTROLLER);
    return -1;
  }
  return 0;
}

/* A window with a context of the OpenGL es says; 0, or -1 with why and
 * neither left. */
static int sdl_window(mr_render *r, const mr_render_def *def, bool es, char *why, size_t why_size) {
  sdl_state *s = r->bk;
  sdl_set_attributes(es);
  Uint32 flags = SDL_WINDOW_OPENGL | SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI;
  if (def->fullscreen) flags |= SDL_WINDOW_FULLSCREEN_DESKTOP;
  s->window = SDL_CreateWindow(def->title ? def->title : "marionette", SDL_WINDOWPOS_CENTERED,
                               SDL_WINDOWPOS_CENTERED, r->width, r->height, flags);
  if (!s->window) {
    snprintf(why, why_size, "SDL_CreateWindow: %s", SDL_GetError());
    return -1;
  }
  s->ctx = SDL_GL_CreateContext(s->window);
  if (s->ctx) return 0;
  snprintf(why, why_size, "no OpenGL %s context: %s", es ? "ES 3.0" : "3.3 core", SDL_GetError());
  SDL_DestroyWindow(s->window);
  s->window = NULL;
  return -1;
}

static int sdl_start(mr_render *r, const mr_render_def *def, char *msg, size_t msg_size) {
  sdl_state *s = calloc(1, sizeof *s);
  if (!s) {
    snprintf(msg, msg_size, "out of memory");
    return -1;
  }
  r->gles = false;
  if (sdl_video_init(msg, msg_size) != 0) {
    free(s);
    return -1;
  }
  r->bk = s;
  char why_core[200] = "", why_es[200] = "";
  int rc = -1;
  if (def->gl != MR_RENDER_GL_ES3) rc = sdl_window(r, def, false, why_core, sizeof why_core);
  if (rc != 0 && def->gl != MR_RENDER_GL_CORE) {
    rc = sdl_window(r, def, true, why_es, sizeof why_es);
    r->gles = rc == 0;
  }
  if (rc != 0) {
    snprintf(msg, msg_size, "%s%s%s", why_core, why_core[0] && why_es[0] ? "; " : "", why_es);
    sdl_stop(r);
    return -1;
  }
  if (sdl_make_current(r) != 0) return sdl_fail(r, msg, msg_size, "SDL_GL_MakeCurrent");
  SDL_GL_SetSwapInterval(def->vsync ? 1 : 0);
  if (mr_gl_load(&r->gl, sdl_get, msg, msg_size) != 0) {
    sdl_stop(r);
    return -1;
  }
  return 0;
}

void mr_sdl_swap(mr_render *r) {
  sdl_state *s = r->bk;
  SDL_GL_SwapWindow(s->window);
}

void mr_sdl_drawable_size(mr_render *r, int *w, int *h) {
  sdl_state *s = r->bk;
  SDL_GL_GetDrawableSize(s->window, w, h);
}

int mr_sdl_set_fullscreen(mr_render *r, bool on) {
  sdl_state *s = r->bk;
  return SDL_SetWindowFullscreen(s->window, on ? SDL_WINDOW_FULLSCREEN_DESKTOP : 0) == 0 ? 0 : -1;
}

int mr_sdl_poll(mr_render *r, mr_event *ev) {
  sdl_state *s = r->bk;
  SDL_Event e;
  while (SDL_PollEvent(&e)) {
    if (mr_sdl_translate(&s->pads, &e, ev)) return 1;
  }
  return 0;
}

const mr_backend_ops mr_backend_sdl_ops = { MR_RENDER_WINDOW, sdl_start, sdl_make_current,
                                            sdl_stop };
