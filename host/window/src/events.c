/* SDL's events translated to mr_window_event: keys to ASCII or
 * MR_WINDOW_KEY_*, the mouse, the window's size, and game controllers,
 * each opened when it is plugged in (SDL reports controllers present at
 * start as plugged in). */
#include "window_internal.h"

#include <string.h>

void mr_window_pads_close(mr_window_pads *pads) {
  for (int i = 0; i < MR_WINDOW_MAX_PADS; i++) {
    if (pads->open[i]) SDL_GameControllerClose(pads->open[i]);
    pads->open[i] = NULL;
  }
}

static int key_of(SDL_Keycode k) {
  if (k >= SDLK_F1 && k <= SDLK_F12) return MR_WINDOW_KEY_F1 + (int)(k - SDLK_F1);
  switch (k) {
  case SDLK_LEFT:
    return MR_WINDOW_KEY_LEFT;
  case SDLK_RIGHT:
    return MR_WINDOW_KEY_RIGHT;
  case SDLK_UP:
    return MR_WINDOW_KEY_UP;
  case SDLK_DOWN:
    return MR_WINDOW_KEY_DOWN;
  case SDLK_PAGEUP:
    return MR_WINDOW_KEY_PAGE_UP;
  case SDLK_PAGEDOWN:
    return MR_WINDOW_KEY_PAGE_DOWN;
  case SDLK_LSHIFT:
  case SDLK_RSHIFT:
    return MR_WINDOW_KEY_SHIFT;
  default:
    break;
  }
  if (k >= 'A' && k <= 'Z') return k - 'A' + 'a';
  if (k >= 32 && k < 127) return (int)k;
  if (k == SDLK_ESCAPE || k == SDLK_RETURN || k == SDLK_TAB || k == SDLK_BACKSPACE) return (int)k;
  return MR_WINDOW_KEY_OTHER;
}

static int pad_added(mr_window_pads *pads, int device, mr_window_event *ev) {
  SDL_GameController *gc = SDL_GameControllerOpen(device);
  if (!gc) return 0;
  int slot = -1;
  for (int i = 0; i < MR_WINDOW_MAX_PADS && slot < 0; i++)
    if (!pads->open[i]) slot = i;
  if (slot < 0) {
    SDL_GameControllerClose(gc);
    return 0;
  }
  pads->open[slot] = gc;
  ev->kind = MR_WINDOW_EVENT_PAD_ADDED;
  ev->pad = (int)SDL_JoystickInstanceID(SDL_GameControllerGetJoystick(gc));
  return 1;
}

static int pad_removed(mr_window_pads *pads, SDL_JoystickID id, mr_window_event *ev) {
  SDL_GameController *gc = SDL_GameControllerFromInstanceID(id);
  for (int i = 0; i < MR_WINDOW_MAX_PADS; i++) {
    if (gc && pads->open[i] == gc) {
      SDL_GameControllerClose(gc);
      pads->open[i] = NULL;
    }
  }
  ev->kind = MR_WINDOW_EVENT_PAD_REMOVED;
  ev->pad = (int)id;
  return 1;
}

static int translate_mouse(const SDL_Event *e, mr_window_event *ev) {
  if (e->type == SDL_MOUSEMOTION) {
    ev->kind = MR_WINDOW_EVENT_MOUSE_MOVE;
    ev->x = e->motion.x;
    ev->y = e->motion.y;
    ev->dx = e->motion.xrel;
    ev->dy = e->motion.yrel;
    /* SDL's masks are already bit 0 left, 1 middle, 2 right. */
    ev->buttons = (int)(e->motion.state & 7u);
    return 1;
  }
  if (e->type == SDL_MOUSEBUTTONDOWN || e->type == SDL_MOUSEBUTTONUP) {
    ev->kind = MR_WINDOW_EVENT_MOUSE_BUTTON;
    ev->button = e->button.button;
    ev->down = e->type == SDL_MOUSEBUTTONDOWN;
    ev->x = e->button.x;
    ev->y = e->button.y;
    return 1;
  }
  if (e->type == SDL_MOUSEWHEEL) {
    ev->kind = MR_WINDOW_EVENT_MOUSE_WHEEL;
    ev->dy = e->wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -e->wheel.y : e->wheel.y;
    return 1;
  }
  return 0;
}

static int translate_pad(mr_window_pads *pads, const SDL_Event *e, mr_window_event *ev) {
  switch (e->type) {
  case SDL_CONTROLLERDEVICEADDED:
    return pad_added(pads, e->cdevice.which, ev);
  case SDL_CONTROLLERDEVICEREMOVED:
    return pad_removed(pads, e->cdevice.which, ev);
  case SDL_CONTROLLERAXISMOTION: {
    ev->kind = MR_WINDOW_EVENT_PAD_AXIS;
    ev->pad = (int)e->caxis.which;
    ev->axis = e->caxis.axis;
    double v = e->caxis.value / 32767.0;
    ev->value = v < -1 ? -1 : v;
    return 1;
  }
  case SDL_CONTROLLERBUTTONDOWN:
  case SDL_CONTROLLERBUTTONUP:
    ev->kind = MR_WINDOW_EVENT_PAD_BUTTON;
    ev->pad = (int)e->cbutton.which;
    ev->button = e->cbutton.button;
    ev->down = e->type == SDL_CONTROLLERBUTTONDOWN;
    return 1;
  default:
    return 0;
  }
}

int mr_window_translate(mr_window_pads *pads, const SDL_Event *e, mr_window_event *ev) {
  memset(ev, 0, sizeof *ev);
  switch (e->type) {
  case SDL_QUIT:
    ev->kind = MR_WINDOW_EVENT_QUIT;
    return 1;
  case SDL_KEYDOWN:
  case SDL_KEYUP:
    if (e->key.repeat) return 0;
    ev->kind = MR_WINDOW_EVENT_KEY;
    ev->key = key_of(e->key.keysym.sym);
    ev->down = e->type == SDL_KEYDOWN;
    return 1;
  case SDL_WINDOWEVENT:
    if (e->window.event != SDL_WINDOWEVENT_SIZE_CHANGED) return 0;
    ev->kind = MR_WINDOW_EVENT_RESIZE;
    ev->width = e->window.data1;
    ev->height = e->window.data2;
    return 1;
  default:
    break;
  }
  if (translate_mouse(e, ev)) return 1;
  return translate_pad(pads, e, ev);
}

int mr_window_poll(mr_window *w, mr_window_event *ev) {
  if (!w || !ev) return 0;
  SDL_Event e;
  while (SDL_PollEvent(&e)) {
    if (mr_window_translate(&w->pads, &e, ev)) return 1;
  }
  return 0;
}
