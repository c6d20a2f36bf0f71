/* The glove a puppeteer without one plays (issue 10, item 5): the
 * keyboard, the mouse and a gamepad each make the five 0..1 values a glove
 * sends, and an in-process glove writes them as real INFO and SAMPLE
 * frames, with the protocol's own encoder, into a pty that the show reads
 * as `pty:PATH` like any glove. So the control mapping, the latency
 * counters, takes and replays all work as with a glove.
 *
 * The layout (the default mapping's channels, §3.2):
 *   channel     glove finger  keys                 mouse (right drag)  gamepad
 *   0 turn z    thumb         j / l (roll)         -                   right stick x
 *   1 turn x    index         i / k (pitch)        -                   right stick y
 *   2 turn y    middle        left / right (yaw)   x                   left stick x
 *   3 move y    ring          page up / page down  y (up raises)       right / left trigger
 *   4 move z    little        up / down (fore/aft) -                   left stick y
 * Each source gives a deflection -1..1 per channel; their sum, clamped, is
 * value 0.5 + 0.45 deflection (so 0.05..0.95: never at the ends, which the
 * mapping would take for a stuck sensor), eased with a 0.1 s lag. */
#ifndef MR_MANUAL_GLOVE_H
#define MR_MANUAL_GLOVE_H

#include <stdbool.h>
#include <stdint.h>

#include "mr_io.h"
#include "mr_window.h"

enum { MR_MANUAL_CHANNELS = 5 };

typedef struct mr_manual {
  double keys[MR_MANUAL_CHANNELS];  /* held keys: -1, 0 or 1 */
  double mouse[MR_MANUAL_CHANNELS]; /* right drag, while held */
  double pad[MR_MANUAL_CHANNELS];   /* the gamepad's sticks and triggers */
  double trigger[2];                /* left, right: 0..1 */
  bool dragging;
  int pads;                          /* controllers plugged in */
  double values[MR_MANUAL_CHANNELS]; /* eased, 0..1 */
  bool held[MR_MANUAL_CHANNELS][2];  /* key held: [channel][0 minus, 1 plus] */
} mr_manual;

void mr_manual_init(mr_manual *m);
/* An event from the window: true when it was the glove's (a key of the
 * layout, a right drag, the gamepad), false for anything else. */
bool mr_manual_event(mr_manual *m, const mr_window_event *ev);
/* The values eased dt seconds towards where the inputs point. */
void mr_manual_update(mr_manual *m, double dt);
/* Where the inputs point now, 0.05..0.95 (the values' goal). */
void mr_manual_goal(const mr_manual *m, double out[MR_MANUAL_CHANNELS]);

/* The glove on a pty: INFO once a second, SAMPLEs at rate_hz. */
typedef struct mr_pty_glove {
  mr_io io;
  double rate_hz, t0, next_sample, next_info;
  uint16_t seq;
  uint64_t samples, infos;
  bool open;
} mr_pty_glove;

/* A new pty; its slave's path is mr_io_path(&g->io). -1 with msg. */
int mr_pty_glove_open(mr_pty_glove *g, double rate_hz, double now, char *msg, size_t msg_size);
/* Writes what is due at wall time now (seconds, any monotonic origin)
 * from values, once the show has opened the pty; reads and drops what the
 * host sends. Never waits. */
void mr_pty_glove_pump(mr_pty_glove *g, const double values[MR_MANUAL_CHANNELS], double now);
void mr_pty_glove_close(mr_pty_glove *g);

#endif
