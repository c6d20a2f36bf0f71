/* The keyboard, the mouse and a gamepad as a glove (issue 10, item 5):
 * their five values go out as the protocol's frames on a pty, encoded by
 * the protocol's glove encoder (protocol/glove, as glove-gen's are), so the
 * show reads them as it reads a glove. */
#include "manual_glove.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gp_glove.h"

/* How far a full drag goes, in pixels, and the values' easing lag (s). */
#define DRAG_FULL_PX 250.0
#define EASE_S       0.1
#define SPAN         0.45

enum { CH_THUMB = 0, CH_INDEX, CH_MIDDLE, CH_RING, CH_LITTLE };

void mr_manual_init(mr_manual *m) {
  memset(m, 0, sizeof *m);
  for (int c = 0; c < MR_MANUAL_CHANNELS; c++) m->values[c] = 0.5;
}

/* A key of the layout: its channel and direction; -1 for any other key. */
static int key_channel(int key, int *dir) {
  static const struct {
    int key, channel, dir;
  } layout[] = {
    { 'j', CH_THUMB, -1 },
    { 'l', CH_THUMB, 1 },
    { 'i', CH_INDEX, 1 },
    { 'k', CH_INDEX, -1 },
    { MR_WINDOW_KEY_LEFT, CH_MIDDLE, -1 },
    { MR_WINDOW_KEY_RIGHT, CH_MIDDLE, 1 },
    { MR_WINDOW_KEY_PAGE_UP, CH_RING, 1 },
    { MR_WINDOW_KEY_PAGE_DOWN, CH_RING, -1 },
    { MR_WINDOW_KEY_UP, CH_LITTLE, 1 },
    { MR_WINDOW_KEY_DOWN, CH_LITTLE, -1 },
  };
  for (size_t i = 0; i < sizeof layout / sizeof layout[0]; i++)
    if (layout[i].key == key) {
      *dir = layout[i].dir;
      return layout[i].channel;
    }
  return -1;
}

static bool key_event(mr_manual *m, const mr_window_event *ev) {
  int dir = 0, c = key_channel(ev->key, &dir);
  if (c < 0) return false;
  m->held[c][dir > 0] = ev->down;
  m->keys[c] = (m->held[c][1] ? 1.0 : 0.0) - (m->held[c][0] ? 1.0 : 0.0);
  return true;
}

static double clamp1(double x) {
  return x < -1 ? -1 : x > 1 ? 1 : x;
}

/* Right drag: x turns (middle finger), y raises (ring; screen y grows
 * down). Letting go lets the values ease back. */
static bool mouse_event(mr_manual *m, const mr_window_event *ev) {
  if (ev->kind == MR_WINDOW_EVENT_MOUSE_BUTTON && ev->button == 3) {
    m->dragging = ev->down;
    if (!ev->down) m->mouse[CH_MIDDLE] = m->mouse[CH_RING] = 0;
    return true;
  }
  if (ev->kind == MR_WINDOW_EVENT_MOUSE_MOVE && m->dragging && (ev->buttons & 4)) {
    m->mouse[CH_MIDDLE] = clamp1(m->mouse[CH_MIDDLE] + ev->dx / DRAG_FULL_PX);
    m->mouse[CH_RING] = clamp1(m->mouse[CH_RING] - ev->dy / DRAG_FULL_PX);
    return true;
  }
  return false;
}

/* Sticks -1..1 (y down positive, as SDL gives it), triggers 0..1. A small
 * dead zone keeps a resting stick from drifting the puppet. */
static bool pad_event(mr_manual *m, const mr_window_event *ev) {
  if (ev->kind == MR_WINDOW_EVENT_PAD_ADDED || ev->kind == MR_WINDOW_EVENT_PAD_REMOVED) {
    m->pads += ev->kind == MR_WINDOW_EVENT_PAD_ADDED ? 1 : -1;
    if (m->pads <= 0) {
      m->pads = 0;
      memset(m->pad, 0, sizeof m->pad);
      m->trigger[0] = m->trigger[1] = 0;
    }
    return true;
  }
  if (ev->kind != MR_WINDOW_EVENT_PAD_AXIS) return ev->kind == MR_WINDOW_EVENT_PAD_BUTTON;
  double v = fabs(ev->value) < 0.08 ? 0.0 : ev->value;
  switch (ev->axis) {
  case MR_WINDOW_PAD_LEFT_X:
    m->pad[CH_MIDDLE] = clamp1(v);
    break;
  case MR_WINDOW_PAD_LEFT_Y:
    m->pad[CH_LITTLE] = clamp1(-v);
    break;
  case MR_WINDOW_PAD_RIGHT_X:
    m->pad[CH_THUMB] = clamp1(v);
    break;
  case MR_WINDOW_PAD_RIGHT_Y:
    m->pad[CH_INDEX] = clamp1(-v);
    break;
  case MR_WINDOW_PAD_TRIGGER_LEFT:
    m->trigger[0] = v;
    break;
  case MR_WINDOW_PAD_TRIGGER_RIGHT:
    m->trigger[1] = v;
    break;
  default:
    return false;
  }
  m->pad[CH_RING] = clamp1(m->trigger[1] - m->trigger[0]);
  return true;
}

bool mr_manual_event(mr_manual *m, const mr_window_event *ev) {
  switch (ev->kind) {
  case MR_WINDOW_EVENT_KEY:
    return key_event(m, ev);
  case MR_WINDOW_EVENT_MOUSE_BUTTON:
  case MR_WINDOW_EVENT_MOUSE_MOVE:
    return mouse_event(m, ev);
  case MR_WINDOW_EVENT_PAD_ADDED:
  case MR_WINDOW_EVENT_PAD_REMOVED:
  case MR_WINDOW_EVENT_PAD_AXIS:
  case MR_WINDOW_EVENT_PAD_BUTTON:
    return pad_event(m, ev);
  default:
    return false;
  }
}

void mr_manual_goal(const mr_manual *m, double out[MR_MANUAL_CHANNELS]) {
  for (int c = 0; c < MR_MANUAL_CHANNELS; c++)
    out[c] = 0.5 + SPAN * clamp1(m->keys[c] + m->mouse[c] + m->pad[c]);
}

void mr_manual_update(mr_manual *m, double dt) {
  double goal[MR_MANUAL_CHANNELS];
  mr_manual_goal(m, goal);
  double k = dt > 0 ? 1.0 - exp(-dt / EASE_S) : 0.0;
  for (int c = 0; c < MR_MANUAL_CHANNELS; c++) m->values[c] += (goal[c] - m->values[c]) * k;
}

/* ----------------------------------------------------------- the pty glove */

int mr_pty_glove_open(mr_pty_glove *g, double rate_hz, double now, char *msg, size_t msg_size) {
  memset(g, 0, sizeof *g);
  mr_io_error err;
  if (mr_io_open(&g->io, "pty", MR_IO_READ | MR_IO_WRITE, &err) != 0) {
    snprintf(msg, msg_size, "the keyboard's glove: %s", err.msg);
    return -1;
  }
  g->open = true;
  g->rate_hz = rate_hz > 0 ? rate_hz : 100;
  g->t0 = g->next_sample = g->next_info = now;
  return 0;
}

/* The INFO a glove of this layout announces: five channels at full scale,
 * the factory calibration (the values are already 0..1), the right hand. */
static size_t put_info(const mr_pty_glove *g, uint8_t *out) {
  gp_info info = gp_default_glove_info();
  info.uid[0] = 0x6b657973u; /* "keys" */
  info.n_channels = MR_MANUAL_CHANNELS;
  info.baud = MR_IO_DEFAULT_BAUD;
  gp_glove_info_set_rate(&info, g->rate_hz);
  return gp_glove_info_encode(&info, out, GP_MAX_WIRE);
}

static size_t put_sample(mr_pty_glove *g, const double values[MR_MANUAL_CHANNELS], double now,
                         uint8_t *out) {
  uint16_t ch[GP_SAMPLE_CH_COUNT] = { 0 };
  for (int c = 0; c < MR_MANUAL_CHANNELS; c++) ch[c] = gp_glove_value_count(values[c]);
  gp_sample s = gp_glove_sample(g->seq++, gp_glove_time_us(now - g->t0), ch);
  return gp_glove_sample_encode(&s, GP_SPEC_HASH, out, GP_MAX_WIRE);
}

void mr_pty_glove_pump(mr_pty_glove *g, const double values[MR_MANUAL_CHANNELS], double now) {
  if (!g->open) return;
  mr_io_error err;
  uint8_t buf[256];
  size_t got = 0;
  /* Commands from the host are read and dropped: this glove has no
   * settings to change, and an unread pty would fill up. */
  while (mr_io_read(&g->io, buf, sizeof buf, 0, &got, &err) == MR_IO_OK && got > 0) {
  }
  if (mr_io_wait_peer(&g->io, 0, &err) != MR_IO_OK) return; /* not opened yet */
  uint8_t wire[GP_MAX_WIRE];
  if (now >= g->next_info) {
    size_t n = put_info(g, wire);
    if (mr_io_write(&g->io, wire, n, 0, NULL, &err) == MR_IO_OK) g->infos++;
    g->next_info = now + 1.0;
  }
  /* One sample for now, however many periods passed: a late frame is not
   * made up with stale ones. */
  if (now >= g->next_sample) {
    size_t n = put_sample(g, values, now, wire);
    if (mr_io_write(&g->io, wire, n, 0, NULL, &err) == MR_IO_OK) g->samples++;
    g->next_sample += 1.0 / g->rate_hz;
    if (g->next_sample < now) g->next_sample = now + 1.0 / g->rate_hz;
  }
}

void mr_pty_glove_close(mr_pty_glove *g) {
  if (g->open) mr_io_close(&g->io);
  g->open = false;
}
