/* The glove a puppeteer without one plays: keys, a right drag and a
 * gamepad make the five values as the man page's table says, eased; and
 * the pty glove's frames, written with the protocol's encoder, are read
 * by mr_glove as a glove, values and all. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "manual_glove.h"
#include "mr_glove.h"

/* cmocka's assert_double_equal came after Debian 12's cmocka. */
#define assert_near(a, b, eps) assert_true(fabs((double)(a) - (double)(b)) <= (eps))

static mr_window_event key(int k, bool down) {
  mr_window_event ev;
  memset(&ev, 0, sizeof ev);
  ev.kind = MR_WINDOW_EVENT_KEY;
  ev.key = k;
  ev.down = down;
  return ev;
}

static void goal(const mr_manual *m, double out[5]) {
  mr_manual_goal(m, out);
}

static void keys_move_their_channels_and_let_go_returns_them(void **state) {
  (void)state;
  mr_manual m;
  mr_manual_init(&m);
  double g[5];
  mr_window_event e = key(MR_WINDOW_KEY_RIGHT, true);
  assert_true(mr_manual_event(&m, &e));
  goal(&m, g);
  assert_near(g[2], 0.95, 1e-12); /* middle: yaw */
  assert_near(g[0], 0.5, 1e-12);
  e = key(MR_WINDOW_KEY_LEFT, true); /* both arrows: they cancel */
  mr_manual_event(&m, &e);
  goal(&m, g);
  assert_near(g[2], 0.5, 1e-12);
  e = key(MR_WINDOW_KEY_RIGHT, false);
  mr_manual_event(&m, &e);
  goal(&m, g);
  assert_near(g[2], 0.05, 1e-12);
  e = key(MR_WINDOW_KEY_LEFT, false);
  mr_manual_event(&m, &e);
  static const struct {
    int key, channel;
    double value;
  } table[] = { { 'l', 0, 0.95 },
                { 'j', 0, 0.05 },
                { 'i', 1, 0.95 },
                { 'k', 1, 0.05 },
                { MR_WINDOW_KEY_PAGE_UP, 3, 0.95 },
                { MR_WINDOW_KEY_PAGE_DOWN, 3, 0.05 },
                { MR_WINDOW_KEY_UP, 4, 0.95 },
                { MR_WINDOW_KEY_DOWN, 4, 0.05 } };
  for (size_t i = 0; i < sizeof table / sizeof table[0]; i++) {
    e = key(table[i].key, true);
    assert_true(mr_manual_event(&m, &e));
    goal(&m, g);
    assert_near(g[table[i].channel], table[i].value, 1e-12);
    e = key(table[i].key, false);
    mr_manual_event(&m, &e);
    goal(&m, g);
    for (int c = 0; c < 5; c++) assert_near(g[c], 0.5, 1e-12);
  }
  e = key(' ', true); /* the stage's keys are not the glove's */
  assert_false(mr_manual_event(&m, &e));
}

static void a_right_drag_and_a_gamepad_move_the_values_too(void **state) {
  (void)state;
  mr_manual m;
  mr_manual_init(&m);
  mr_window_event e;
  memset(&e, 0, sizeof e);
  e.kind = MR_WINDOW_EVENT_MOUSE_BUTTON;
  e.button = 3;
  e.down = true;
  assert_true(mr_manual_event(&m, &e));
  e.kind = MR_WINDOW_EVENT_MOUSE_MOVE;
  e.buttons = 4;
  e.dx = 125;  /* half of a full drag */
  e.dy = -250; /* up: a full raise */
  assert_true(mr_manual_event(&m, &e));
  double g[5];
  mr_manual_goal(&m, g);
  assert_near(g[2], 0.5 + 0.45 * 0.5, 1e-12);
  assert_near(g[3], 0.95, 1e-12);
  e.kind = MR_WINDOW_EVENT_MOUSE_BUTTON;
  e.down = false;
  mr_manual_event(&m, &e);
  mr_manual_goal(&m, g);
  assert_near(g[2], 0.5, 1e-12);
  memset(&e, 0, sizeof e);
  e.kind = MR_WINDOW_EVENT_PAD_ADDED;
  assert_true(mr_manual_event(&m, &e));
  e.kind = MR_WINDOW_EVENT_PAD_AXIS;
  e.axis = MR_WINDOW_PAD_LEFT_Y;
  e.value = -1; /* stick up: forward */
  mr_manual_event(&m, &e);
  e.axis = MR_WINDOW_PAD_TRIGGER_RIGHT;
  e.value = 0.5;
  mr_manual_event(&m, &e);
  e.axis = MR_WINDOW_PAD_RIGHT_X;
  e.value = 0.05; /* inside the dead zone */
  mr_manual_event(&m, &e);
  mr_manual_goal(&m, g);
  assert_near(g[4], 0.95, 1e-12);
  assert_near(g[3], 0.5 + 0.45 * 0.5, 1e-12);
  assert_near(g[0], 0.5, 1e-12);
  e.kind = MR_WINDOW_EVENT_PAD_REMOVED; /* unplugged: the pad lets go */
  mr_manual_event(&m, &e);
  mr_manual_goal(&m, g);
  for (int c = 0; c < 5; c++) assert_near(g[c], 0.5, 1e-12);
}

/* A key press eases in: after one lag (0.1 s) 63 % of the way. */
static void values_ease_towards_the_goal(void **state) {
  (void)state;
  mr_manual m;
  mr_manual_init(&m);
  mr_window_event e = key(MR_WINDOW_KEY_UP, true);
  mr_manual_event(&m, &e);
  for (int i = 0; i < 10; i++) mr_manual_update(&m, 0.01);
  assert_near(m.values[4], 0.5 + 0.45 * (1 - exp(-1.0)), 1e-9);
  for (int i = 0; i < 200; i++) mr_manual_update(&m, 0.01);
  assert_near(m.values[4], 0.95, 1e-6);
}

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* The pty glove end to end: mr_glove reads its INFO and SAMPLEs from the
 * pty and calibrates them back to the values written. */
static void the_pty_glove_is_read_as_a_glove(void **state) {
  (void)state;
  mr_pty_glove pg;
  char msg[400];
  double t0 = now_s();
  assert_int_equal(mr_pty_glove_open(&pg, 200, t0, msg, sizeof msg), 0);
  mr_glove_def d = mr_default_glove_def();
  snprintf(d.source, sizeof d.source, "pty:%s", mr_io_path(&pg.io));
  mr_glove *g = NULL;
  assert_int_equal(mr_glove_create(&d, &g, msg, sizeof msg), MR_GLOVE_OK);
  const double values[5] = { 0.1, 0.3, 0.5, 0.7, 0.9 };
  mr_glove_reading r;
  memset(&r, 0, sizeof r);
  double now = t0;
  while (now - t0 < 5.0) {
    now = now_s();
    mr_pty_glove_pump(&pg, values, now);
    mr_glove_poll(g, now - t0, 10);
    mr_glove_latest(g, &r);
    if (r.samples >= 20) break;
  }
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LIVE);
  assert_true(r.samples >= 20);
  const gp_info *info = mr_glove_info(g);
  assert_non_null(info);
  assert_int_equal(info->n_channels, 5);
  for (int c = 0; c < 5; c++) assert_near(r.values[c], values[c], 1.0 / 4095 + 1e-9);
  mr_glove_destroy(g);
  mr_pty_glove_close(&pg);
}

/* FNV-1a, 64 bits. Not CRC-32C: a whole frame followed by its own CRC-32C
 * leaves the same CRC-32C whatever its payload, so that would miss a
 * changed field. */
static uint64_t fnv1a(const uint8_t *p, size_t n) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

/* The bytes the pty glove writes for fixed values at fixed times, pinned
 * by their hash: a take recorded from the keyboard's glove holds these
 * bytes, so they must not move when its encoder does. Read from the slave
 * as the show reads it. */
static void the_pty_glove_writes_the_same_bytes_as_ever(void **state) {
  (void)state;
  mr_pty_glove pg;
  char msg[400];
  const double t0 = 1000.0;
  assert_int_equal(mr_pty_glove_open(&pg, 100, t0, msg, sizeof msg), 0);
  int fd = open(mr_io_path(&pg.io), O_RDWR | O_NOCTTY | O_NONBLOCK);
  assert_true(fd >= 0);
  struct termios t;
  assert_int_equal(tcgetattr(fd, &t), 0);
  cfmakeraw(&t);
  assert_int_equal(tcsetattr(fd, TCSANOW, &t), 0);
  /* 0.01 s apart over 1.5 s: two INFOs (at 0 and 1 s) and 151 SAMPLEs,
   * with values that reach both clamps and both roundings. */
  for (int k = 0; k <= 150; k++) {
    double v[5];
    for (int c = 0; c < 5; c++) v[c] = -0.1 + 1.2 * (double)((k * 7 + c * 13) % 101) / 100.0;
    mr_pty_glove_pump(&pg, v, t0 + 0.01 * k + 1e-7 * (k % 3));
  }
  assert_int_equal(pg.samples, 151);
  assert_int_equal(pg.infos, 2);
  uint8_t buf[8192];
  size_t len = 0;
  struct pollfd p = { .fd = fd, .events = POLLIN };
  while (len < sizeof buf && poll(&p, 1, 500) > 0) {
    ssize_t n = read(fd, buf + len, sizeof buf - len);
    if (n <= 0) break;
    len += (size_t)n;
  }
  close(fd);
  mr_pty_glove_close(&pg);
  assert_int_equal(len, 3440);
  assert_int_equal(fnv1a(buf, len), 0xec2be4e46ff1a25full);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(keys_move_their_channels_and_let_go_returns_them),
    cmocka_unit_test(a_right_drag_and_a_gamepad_move_the_values_too),
    cmocka_unit_test(values_ease_towards_the_goal),
    cmocka_unit_test(the_pty_glove_is_read_as_a_glove),
    cmocka_unit_test(the_pty_glove_writes_the_same_bytes_as_ever),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
