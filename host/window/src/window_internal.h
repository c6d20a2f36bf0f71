/* The window's insides, shared by its files (never by callers). */
#ifndef MR_WINDOW_INTERNAL_H
#define MR_WINDOW_INTERNAL_H

#include <SDL.h>

#include "mr_window.h"

enum { MR_WINDOW_MAX_PADS = 8 };

/* The game controllers opened as they were plugged in (events.c). */
typedef struct mr_window_pads {
  SDL_GameController *open[MR_WINDOW_MAX_PADS];
} mr_window_pads;

struct mr_window {
  SDL_Window *window;
  SDL_GLContext ctx;
  bool gles, fullscreen;
  mr_window_pads pads;
};

void mr_window_pads_close(mr_window_pads *pads);
/* 1 with ev filled when e is one the window reports, else 0. */
int mr_window_translate(mr_window_pads *pads, const SDL_Event *e, mr_window_event *ev);

#endif
