/* A live show on the stage (`marionette run`): in a window, with its keys,
 * mouse and gamepad, or headless into frames. The keys that act on the
 * show (pause, single step, slow motion, reset) become commands for its
 * runner (mr_show_runner.h), whose clock stops or slows show time itself;
 * the view's keys (cameras, orbit, day, OSD) act here, on the drawing
 * thread. */
#ifndef MR_APP_WINDOW_H
#define MR_APP_WINDOW_H

#include <stdbool.h>
#include <stdint.h>

#include "frames_out.h"
#include "manual_glove.h"
#include "mr_show.h"
#include "mr_show_runner.h"
#include "stage_view.h"

enum { MR_KEYS_MAX = 64 };

/* A scripted key press (`--keys`): at show time t, key down, then up
 * after hold seconds. */
typedef struct mr_key_press {
  double t, hold;
  int key;
  bool down_sent, up_sent;
} mr_key_press;

typedef struct mr_live {
  mr_stageview sv;
  bool window;
  mr_frames_out *fo; /* headless with -o */
  char shot_dir[512];
  int shots;
  mr_clock wall;
  mr_show_runner *runner; /* where the show's keys go */
  /* The show's clock as the keys left it (the runner's own follows the
   * same commands), for the OSD and the scripted keys. */
  bool paused;
  double speed; /* 1, 0.5 or 0.25 (s steps through them) */
  /* What the keys asked for. */
  bool quit, shot_asked, fullscreen, dragging;
  /* The glove made from the keyboard, mouse and gamepad. */
  bool manual_on;
  mr_manual manual;
  mr_pty_glove glove;
  double last_pump;
  mr_key_press keys[MR_KEYS_MAX];
  int n_keys;
  double show_t;     /* the latest frame's show time: --keys run on it */
  double pause_wall; /* wall time the pause began */
  /* For the OSD: rates over the latest second. */
  double osd_wall, osd_sim;
  uint64_t osd_drawn, osd_steps;
  double fps, dt_mean;
  uint64_t drawn;
  /* The curtain (stage.curtain): the show's end as it knows it (-1: not
   * known), and the closing a first q started (a second q, quit_now,
   * stops at once). */
  double curtain_end, closing_wall;
  bool closing, quit_now;
  bool failed;
  char msg[700];
  char glove_source[300]; /* pty:PATH of the manual glove */
  /* Takes (--takes BOOK): the glove whose channels F2-F6 arm, the
   * channels armed as the keys and the frames left them, the take beneath
   * ("" none), and a step through the book asked (-1, +1; 0 none). */
  size_t glove_sel, n_gloves;
  unsigned armed[MR_SHOW_MAX_GLOVES];
  bool armed_seen; /* taken from the show's first frame (--arm) */
  char beneath[64];
  int take_step;
  const char *out; /* -o DIR */
  /* With takes, a show starts again over the next take: the frames
   * written (-o) keep going on one time line, this pass's time 0 being
   * the end of the passes before it. */
  double pass_t0;
} mr_live;

/* How a live show is staged. */
typedef struct mr_live_def {
  bool window;      /* else headless */
  bool fullscreen;  /* window only */
  bool manual;      /* the keyboard, mouse and gamepad play glove 1 */
  const char *keys; /* --keys, or NULL */
  double fps;       /* the show's, for the MP4 */
  bool no_osd;      /* the on-screen display starts hidden */
  double end;       /* the show's end (--time), -1: until stopped */
  double speed;     /* the show's speed to start at (--speed); 0: 1 */
} mr_live_def;

struct mr_stage_opts;
/* The stage, the outputs (headless with -o) and the manual glove. -1 and
 * one line in msg (the exit status 2 in *usage when it was the command
 * line's fault, else 1). lv must not move afterwards. */
int mr_live_open(mr_live *lv, const mr_scene *scene, const mr_live_def *def,
                 struct mr_stage_opts *so, int *usage, char *msg, size_t msg_size);
/* Ends the outputs and prints what was written; -1 when something was not. */
int mr_live_close(mr_live *lv, bool quiet);

/* Parses --keys: "T:KEY[/HOLD],..." with KEY a character or one of
 * space, esc, left, right, up, down, pgup, pgdn, f1 to f12. 0 or -1. */
int mr_live_parse_keys(mr_live *lv, const char *list);

/* One event from the window or a script: the glove's keys go to the
 * manual glove (when it is on), the rest are the stage's. */
void mr_live_event(mr_live *lv, const mr_window_event *ev);

/* Events, scripted keys and the manual glove, handled now; the number of
 * events (a view that moved is drawn again). */
int mr_live_pump(mr_live *lv);

/* Whether the show should stop now: it failed, the window was closed, q
 * was pressed twice, or the curtain has closed after a q. The first q
 * (or Esc) starts closing the curtain over its close time of show time
 * (unpausing a paused show), bounded on the wall clock by four times
 * that and a second; without a curtain it stops at once. */
bool mr_live_should_quit(mr_live *lv);

/* A frame on the stage: the OSD, the frame drawn, shown or written, a
 * screenshot if asked. */
void mr_live_present(mr_live *lv, const mr_show_frame *f);

/* In a window: the frame drawn last again, with the view as it is now
 * (orbit, zoom, cameras; its OSD as it was), and a screenshot if asked. */
void mr_live_redraw(mr_live *lv);

/* Headless with an MP4: the video holds its last frame up to show time t,
 * the show's end. */
void mr_live_hold(mr_live *lv, double t);

/* The show ended at show time end and another starts from 0 (over the
 * next take): the frames written go on after end, so the PNG numbers, the
 * MP4 and the contact sheet follow the first pass with the next. */
void mr_live_next_pass(mr_live *lv, double end);

/* The take beneath the show about to start ("" none), for the OSD. */
void mr_live_set_takes(mr_live *lv, const char *beneath);

/* A screenshot's path: dir/shot_NNN.png. */
int mr_live_screenshot(mr_live *lv);

#endif
