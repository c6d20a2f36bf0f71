/* mr_window under Xvfb (ctest starts it through xvfb-run): SDL's events,
 * pushed into its queue as the X server or a controller would deliver
 * them, come out as the window's own values (a key, a mouse drag, the
 * wheel, a virtual game controller plugged in and moved); the context
 * it makes speaks the OpenGL asked for, read through its own loader; and
 * with no display it fails saying why. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include <SDL.h>

#include "mr_window.h"

enum { W = 200, H = 120 }; /* not the default 1280 x 720 */

static mr_window *opened; /* closed by the teardown when a test fails */

static mr_window *open_window(mr_window_gl gl) {
  const char *display = getenv("DISPLAY");
  if (!display || !*display) fail_msg("no DISPLAY: run under xvfb-run -a");
  mr_window_def def = mr_default_window_def();
  def.width = W;
  def.height = H;
  def.gl = gl;
  def.vsync = false;
  def.title = "mr_window test";
  mr_window *w = NULL;
  char msg[600] = "";
  if (mr_window_create(&def, &w, msg, sizeof msg) != MR_WINDOW_OK) fail_msg("%s", msg);
  opened = w;
  return w;
}

static void close_window(mr_window *w) {
  mr_window_destroy(w);
  opened = NULL;
}

/* A failed test leaves its window open: closed here, so that SDL's video
 * is down again for the next test. */
static int teardown(void **state) {
  (void)state;
  close_window(opened);
  return 0;
}

/* Whatever the X server sent since the window opened, passed over. */
static void drain(mr_window *w) {
  mr_window_event ev;
  while (mr_window_poll(w, &ev)) {
  }
}

/* The next event that is not the window's own resize; fails if none.
 * One poll pass ends where SDL's queue stood when it began (events SDL
 * queues meanwhile wait for the next pass), so a few passes are made. */
static mr_window_event next(mr_window *w) {
  mr_window_event ev;
  for (int pass = 0; pass < 4; pass++) {
    while (mr_window_poll(w, &ev)) {
      if (ev.kind != MR_WINDOW_EVENT_RESIZE) return ev;
    }
  }
  fail_msg("no event where one was pushed");
  return ev;
}

static void push_key(Uint32 type, SDL_Keycode sym, Uint8 repeat) {
  SDL_Event e;
  memset(&e, 0, sizeof e);
  e.type = type;
  e.key.state = type == SDL_KEYDOWN ? SDL_PRESSED : SDL_RELEASED;
  e.key.repeat = repeat;
  e.key.keysym.sym = sym;
  assert_int_equal(SDL_PushEvent(&e), 1);
}

static void push_button(Uint32 type, Uint8 button, int x, int y) {
  SDL_Event e;
  memset(&e, 0, sizeof e);
  e.type = type;
  e.button.button = button;
  e.button.state = type == SDL_MOUSEBUTTONDOWN ? SDL_PRESSED : SDL_RELEASED;
  e.button.x = x;
  e.button.y = y;
  assert_int_equal(SDL_PushEvent(&e), 1);
}

static void push_motion(Uint32 held, int x, int y, int dx, int dy) {
  SDL_Event e;
  memset(&e, 0, sizeof e);
  e.type = SDL_MOUSEMOTION;
  e.motion.state = held;
  e.motion.x = x;
  e.motion.y = y;
  e.motion.xrel = dx;
  e.motion.yrel = dy;
  assert_int_equal(SDL_PushEvent(&e), 1);
}

static void test_keys_come_out_as_the_windows_own_codes_and_repeats_are_passed_over(void **state) {
  (void)state;
  mr_window *w = open_window(MR_WINDOW_GL_AUTO);
  drain(w);
  push_key(SDL_KEYDOWN, SDLK_p, 0);
  push_key(SDL_KEYDOWN, SDLK_p, 1); /* held: a repeat, not a second press */
  push_key(SDL_KEYUP, SDLK_p, 0);
  push_key(SDL_KEYDOWN, SDLK_F11, 0);
  push_key(SDL_KEYDOWN, SDLK_PAGEDOWN, 0);
  push_key(SDL_KEYDOWN, SDLK_RSHIFT, 0);
  push_key(SDL_KEYDOWN, SDLK_ESCAPE, 0);
  push_key(SDL_KEYDOWN, SDLK_CAPSLOCK, 0);
  const struct {
    int key;
    bool down;
  } want[] = { { 'p', true },
               { 'p', false },
               { MR_WINDOW_KEY_F11, true },
               { MR_WINDOW_KEY_PAGE_DOWN, true },
               { MR_WINDOW_KEY_SHIFT, true },
               { MR_WINDOW_KEY_ESCAPE, true },
               { MR_WINDOW_KEY_OTHER, true } };
  for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
    mr_window_event ev = next(w);
    assert_int_equal(ev.kind, MR_WINDOW_EVENT_KEY);
    assert_int_equal(ev.key, want[i].key);
    assert_int_equal(ev.down, want[i].down);
  }
  mr_window_event ev;
  assert_int_equal(mr_window_poll(w, &ev), 0);
  close_window(w);
}

static void test_a_mouse_drag_and_the_wheel_come_out_as_moves_with_the_button_held(void **state) {
  (void)state;
  mr_window *w = open_window(MR_WINDOW_GL_AUTO);
  drain(w);
  push_button(SDL_MOUSEBUTTONDOWN, SDL_BUTTON_LEFT, 50, 40);
  push_motion(SDL_BUTTON_LMASK, 57, 37, 7, -3);
  push_motion(SDL_BUTTON_LMASK | SDL_BUTTON_RMASK, 60, 37, 3, 0);
  push_button(SDL_MOUSEBUTTONUP, SDL_BUTTON_LEFT, 60, 37);
  SDL_Event e;
  memset(&e, 0, sizeof e);
  e.type = SDL_MOUSEWHEEL;
  e.wheel.y = 2;
  e.wheel.direction = SDL_MOUSEWHEEL_FLIPPED; /* "natural" scrolling: turned back */
  assert_int_equal(SDL_PushEvent(&e), 1);

  mr_window_event ev = next(w);
  assert_int_equal(ev.kind, MR_WINDOW_EVENT_MOUSE_BUTTON);
  assert_int_equal(ev.button, 1);
  assert_true(ev.down);
  assert_true(ev.x == 50 && ev.y == 40);
  ev = next(w);
  assert_int_equal(ev.kind, MR_WINDOW_EVENT_MOUSE_MOVE);
  assert_int_equal(ev.buttons, 1);
  assert_true(ev.x == 57 && ev.y == 37 && ev.dx == 7 && ev.dy == -3);
  ev = next(w);
  assert_int_equal(ev.kind, MR_WINDOW_EVENT_MOUSE_MOVE);
  assert_int_equal(ev.buttons, 1 | 4); /* bit 2: the right button */
  assert_true(ev.dx == 3 && ev.dy == 0);
  ev = next(w);
  assert_int_equal(ev.kind, MR_WINDOW_EVENT_MOUSE_BUTTON);
  assert_false(ev.down);
  ev = next(w);
  assert_int_equal(ev.kind, MR_WINDOW_EVENT_MOUSE_WHEEL);
  assert_true(ev.dy == -2);
  close_window(w);
}

/* A virtual controller, as SDL makes one for tests: plugged in, it is
 * opened and reported with its id; its stick and a button follow. */
static void
test_a_game_controller_plugged_in_is_opened_and_its_stick_and_buttons_reported(void **state) {
  (void)state;
  /* Xvfb has no window manager to give the window focus, and SDL holds
   * back a controller's moves from a window without it. */
  SDL_SetHint(SDL_HINT_JOYSTICK_ALLOW_BACKGROUND_EVENTS, "1");
  mr_window *w = open_window(MR_WINDOW_GL_AUTO);
  drain(w);
  SDL_VirtualJoystickDesc desc;
  memset(&desc, 0, sizeof desc);
  desc.version = SDL_VIRTUAL_JOYSTICK_DESC_VERSION;
  desc.type = SDL_JOYSTICK_TYPE_GAMECONTROLLER;
  desc.naxes = SDL_CONTROLLER_AXIS_MAX;
  desc.nbuttons = SDL_CONTROLLER_BUTTON_MAX;
  desc.name = "mr_window test pad";
  int index = SDL_JoystickAttachVirtualEx(&desc);
  if (index < 0) fail_msg("SDL_JoystickAttachVirtualEx: %s", SDL_GetError());
  mr_window_event ev = next(w);
  assert_int_equal(ev.kind, MR_WINDOW_EVENT_PAD_ADDED);
  int pad = ev.pad;
  SDL_Joystick *js = SDL_JoystickFromInstanceID(pad);
  assert_non_null(js);
  assert_int_equal(SDL_JoystickSetVirtualAxis(js, SDL_CONTROLLER_AXIS_LEFTX, -32768), 0);
  assert_int_equal(SDL_JoystickSetVirtualButton(js, SDL_CONTROLLER_BUTTON_A, 1), 0);
  SDL_JoystickUpdate();
  SDL_GameControllerUpdate();
  bool axis = false, button = false;
  for (int pass = 0; pass < 4 && !(axis && button); pass++) {
    while (mr_window_poll(w, &ev)) {
      if (ev.kind == MR_WINDOW_EVENT_PAD_AXIS && ev.axis == MR_WINDOW_PAD_LEFT_X) {
        assert_int_equal(ev.pad, pad);
        assert_true(ev.value == -1.0); /* -32768 / 32767, held to -1 */
        axis = true;
      } else if (ev.kind == MR_WINDOW_EVENT_PAD_BUTTON) {
        assert_int_equal(ev.button, SDL_CONTROLLER_BUTTON_A);
        assert_true(ev.down);
        button = true;
      }
    }
  }
  assert_true(axis && button);
  /* Unplugged, SDL lets go of what was held (moves back to rest), then
   * reports it gone. */
  assert_int_equal(SDL_JoystickDetachVirtual(index), 0);
  do ev = next(w);
  while (ev.kind == MR_WINDOW_EVENT_PAD_AXIS || ev.kind == MR_WINDOW_EVENT_PAD_BUTTON);
  assert_int_equal(ev.kind, MR_WINDOW_EVENT_PAD_REMOVED);
  assert_int_equal(ev.pad, pad);
  close_window(w);
}

/* The context's GL_VERSION, read through the window's own loader. */
static const char *gl_version(void) {
  typedef const unsigned char *(*get_string_fn)(unsigned int);
  mr_window_proc p = mr_window_gl_proc("glGetString");
  assert_non_null(p);
  get_string_fn get_string;
  memcpy(&get_string, &p, sizeof get_string);
  const char *v = (const char *)get_string(0x1F02 /* GL_VERSION */);
  assert_non_null(v);
  return v;
}

static void test_the_context_speaks_desktop_core_or_es_as_asked(void **state) {
  (void)state;
  mr_window *w = open_window(MR_WINDOW_GL_CORE);
  assert_int_equal(mr_window_gl_of(w), MR_WINDOW_GL_CORE);
  const char *v = gl_version();
  print_message("core: %s\n", v);
  int major = 0, minor = 0;
  assert_int_equal(sscanf(v, "%d.%d", &major, &minor), 2); /* "4.5 (Core Profile) Mesa" */
  assert_true(major * 10 + minor >= 33);
  int dw = 0, dh = 0;
  mr_window_drawable_size(w, &dw, &dh);
  assert_true(dw == W && dh == H);
  mr_window_swap(w);
  close_window(w);

  w = open_window(MR_WINDOW_GL_ES3);
  assert_int_equal(mr_window_gl_of(w), MR_WINDOW_GL_ES3);
  v = gl_version();
  print_message("es3: %s\n", v);
  assert_memory_equal(v, "OpenGL ES 3.", strlen("OpenGL ES 3."));
  assert_int_equal(mr_window_make_current(w), 0);
  assert_string_equal(mr_window_driver(w), "x11");
  close_window(w);
}

static void test_the_window_goes_fullscreen_and_back(void **state) {
  (void)state;
  mr_window *w = open_window(MR_WINDOW_GL_AUTO);
  assert_false(mr_window_fullscreen(w));
  assert_int_equal(mr_window_set_fullscreen(w, true), MR_WINDOW_OK);
  assert_true(mr_window_fullscreen(w));
  assert_int_equal(mr_window_set_fullscreen(w, false), MR_WINDOW_OK);
  assert_false(mr_window_fullscreen(w));
  close_window(w);
}

static void test_no_display_fails_saying_why_and_a_def_not_from_its_maker_is_refused(void **state) {
  (void)state;
  mr_window_def def;
  memset(&def, 0, sizeof def);
  mr_window *w = (mr_window *)&def; /* must be cleared */
  char msg[600] = "";
  assert_int_equal(mr_window_create(&def, &w, msg, sizeof msg), MR_WINDOW_ERR_ARG);
  assert_null(w);
  assert_non_null(strstr(msg, "default maker"));

  char display[256];
  snprintf(display, sizeof display, "%s", getenv("DISPLAY") ? getenv("DISPLAY") : "");
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
  def = mr_default_window_def();
  /* X11 named, with no display to open. */
  setenv("SDL_VIDEODRIVER", "x11", 1);
  assert_int_equal(mr_window_create(&def, &w, msg, sizeof msg), MR_WINDOW_ERR_SCREEN);
  assert_null(w);
  print_message("x11, no display: %s\n", msg);
  assert_non_null(strstr(msg, "SDL_Init: "));
  /* Nothing named: the console's KMS/DRM, which a box without /dev/dri
   * cannot open. */
  unsetenv("SDL_VIDEODRIVER");
  if (access("/dev/dri", F_OK) != 0) {
    assert_int_equal(mr_window_create(&def, &w, msg, sizeof msg), MR_WINDOW_ERR_SCREEN);
    print_message("no display: %s\n", msg);
    assert_non_null(strstr(msg, "no screen: "));
    assert_non_null(strstr(msg, "KMS/DRM"));
  }
  setenv("DISPLAY", display, 1);
}

/* SDL's video held for the window tests: the program opens one window
 * per process, these tests a dozen, and SDL's probing of its drivers,
 * started again after each window's quit, now and then ended on its
 * offscreen driver under Xvfb. Held, each window reuses the driver the
 * first one found; the window's own quit is then SDL's to count down. */
static int hold_video(void **state) {
  (void)state;
  return SDL_InitSubSystem(SDL_INIT_VIDEO) == 0 ? 0 : -1;
}

static int let_go_of_video(void **state) {
  (void)state;
  SDL_QuitSubSystem(SDL_INIT_VIDEO);
  return 0;
}

int main(void) {
  /* Last, with nothing held: SDL's video must really start and fail. */
  const struct CMUnitTest alone[] = {
    cmocka_unit_test_teardown(
        test_no_display_fails_saying_why_and_a_def_not_from_its_maker_is_refused, teardown),
  };
  const struct CMUnitTest windows[] = {
    cmocka_unit_test_teardown(
        test_keys_come_out_as_the_windows_own_codes_and_repeats_are_passed_over, teardown),
    cmocka_unit_test_teardown(
        test_a_mouse_drag_and_the_wheel_come_out_as_moves_with_the_button_held, teardown),
    cmocka_unit_test_teardown(
        test_a_game_controller_plugged_in_is_opened_and_its_stick_and_buttons_reported, teardown),
    cmocka_unit_test_teardown(test_the_context_speaks_desktop_core_or_es_as_asked, teardown),
    cmocka_unit_test_teardown(test_the_window_goes_fullscreen_and_back, teardown),
  };
  int failed = cmocka_run_group_tests(windows, hold_video, let_go_of_video);
  return failed + cmocka_run_group_tests(alone, NULL, NULL);
}
