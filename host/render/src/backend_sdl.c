/* The window backend: an SDL2 window with an OpenGL 3.3 core context.
 * The frame is drawn into the renderer's framebuffer object like every
 * other backend's, then blitted to the window (fbo.c), so the window and
 * headless frames come from one path. SDL's GL attributes take effect
 * only when set before SDL_CreateWindow. */
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
  snprintf(msg, msg_size, "window: %s: %s", what, SDL_GetError());
  sdl_stop(r);
  return -1;
}

static void sdl_set_attributes(void) {
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_CORE);
  SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
  /* The window only receives blits: no depth, no multisampling of its own. */
  SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 0);
  SDL_GL_SetAttribute(SDL_GL_MULTISAMPLEBUFFERS, 0);
  SDL_GL_SetAttribute(SDL_GL_RED_SIZE, 8);
  SDL_GL_SetAttribute(SDL_GL_GREEN_SIZE, 8);
  SDL_GL_SetAttribute(SDL_GL_BLUE_SIZE, 8);
}

static int sdl_start(mr_render *r, const mr_render_def *def, char *msg, size_t msg_size) {
  sdl_state *s = calloc(1, sizeof *s);
  if (!s) {
    snprintf(msg, msg_size, "out of memory");
    return -1;
  }
  if (SDL_InitSubSystem(SDL_INIT_VIDEO | SDL_INIT_GAMECONTROLLER) != 0) {
    snprintf(msg, msg_size, "window: SDL_Init: %s", SDL_GetError());
    free(s);
    return -1;
  }
  r->bk = s;
  sdl_set_attributes();
  Uint32 flags = SDL_WINDOW_OPENGL | SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI;
  if (def->fullscreen) flags |= SDL_WINDOW_FULLSCREEN_DESKTOP;
  s->window = SDL_CreateWindow(def->title ? def->title : "marionette", SDL_WINDOWPOS_CENTERED,
                               SDL_WINDOWPOS_CENTERED, r->width, r->height, flags);
  if (!s->window) return sdl_fail(r, msg, msg_size, "SDL_CreateWindow");
  s->ctx = SDL_GL_CreateContext(s->window);
  if (!s->ctx) return sdl_fail(r, msg, msg_size, "no OpenGL 3.3 core context");
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
