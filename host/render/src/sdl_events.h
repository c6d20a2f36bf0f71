/* SDL's events as the renderer's mr_event (sdl_events.c). */
#ifndef MR_RENDER_SDL_EVENTS_H
#define MR_RENDER_SDL_EVENTS_H

#include <SDL.h>

#include "mr_render.h"

enum { MR_SDL_MAX_PADS = 8 };

/* The game controllers opened as they were plugged in. */
typedef struct mr_sdl_pads {
  SDL_GameController *open[MR_SDL_MAX_PADS];
} mr_sdl_pads;

void mr_sdl_pads_close(mr_sdl_pads *pads);
/* 1 with ev filled when e is one the renderer reports, else 0. */
int mr_sdl_translate(mr_sdl_pads *pads, const SDL_Event *e, mr_event *ev);

#endif
