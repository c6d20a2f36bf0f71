/* A live show on the stage (`marionette run`): in a window, with its keys,
 * mouse and gamepad, or headless into frames. The show's clock is wrapped
 * so that pause, single step and slow motion stop or slow show time
 * itself: the scheduler, the gloves and the latency counters all run on
 * it, so nothing else needs to know. */
#ifndef MR_WINDOW_H
#define MR_WINDOW_H

#include <stdbool.h>
#include <stdint.h>

#include "frames_out.h"
#include "manual_glove.h"
#include "mr_show.h"
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
  /* The show's clock: wall time, paused or slowed. */
  mr_clock wall;
  double show_base, wall_base, rate; /* rate 1, or slow motion's */
  bool paused, step_asked;
  /* What the keys asked for. */
  bool quit, reset_asked, shot_asked, fullscreen, dragging;
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
  uint64_t osd_presented, osd_steps;
  double fps, dt_mean;
  uint64_t drawn;
  bool failed;
  char msg[700];
  char glove_source[300]; /* pty:PATH of the manual glove */
  const char *out;        /* -o DIR */
} mr_live;

/* How a live show is staged. */
typedef struct mr_live_def {
  bool window;      /* else headless */
  bool fullscreen;  /* window only */
  bool manual;      /* the keyboard, mouse and gamepad play glove 1 */
  const char *keys; /* --keys, or NULL */
  double fps;       /* the show's, for the MP4 */
  bool no_osd;      /* the on-screen display starts hidden */
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
 * space, esc, left, right, up, down, pgup, pgdn, f1, f11, f12. 0 or -1. */
int mr_live_parse_keys(mr_live *lv, const char *list);

/* The show's clock over the wall clock (lv must not move after this). */
mr_clock mr_live_clock(mr_live *lv);

/* One event from the window or a script: the glove's keys go to the
 * manual glove (when it is on), the rest are the stage's. */
void mr_live_event(mr_live *lv, const mr_event *ev);

/* Events, scripted keys and the manual glove, handled now. */
void mr_live_pump(mr_live *lv);

/* The show's present hook's work: the OSD, the frame drawn, shown or
 * written, a screenshot if asked. */
void mr_live_present(mr_live *lv, const mr_show_frame *f);

/* A screenshot's path: dir/shot_NNN.png. */
int mr_live_screenshot(mr_live *lv);

#endif
