/* `marionette watch`: the stage the frames are drawn on (a window, or
 * headless into frames as render's); the playout buffer is watch_buffer.h. */
#ifndef MR_WATCH_VIEW_H
#define MR_WATCH_VIEW_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "frames_out.h"
#include "mr_scene.h"
#include "stage_opts.h"
#include "stage_view.h"
#include "watch_buffer.h"

/* Where the frames are drawn. */
typedef struct mr_watch_stage {
  mr_stageview sv;
  mr_frames_out *fo; /* -o DIR, or NULL */
  bool window, quit;
  uint64_t drawn;
} mr_watch_stage;

/* The stage of scene in a window (window) or headless, with so's size,
 * camera, day and -o outputs at fps. 0, or -1 with one line in msg (and
 * *usage set when the options were wrong). */
int mr_watch_stage_open(mr_watch_stage *ws, const mr_scene *scene, mr_stage_opts *so, bool window,
                        double fps, char *msg, size_t msg_size, int *usage);
/* The points drawn at show time t, and written out. -1 with msg. */
int mr_watch_stage_draw(mr_watch_stage *ws, double t, const double *xyz, size_t n, char *msg,
                        size_t msg_size);
/* The window's events: quit, Esc or q ask to stop (ws->quit). */
void mr_watch_stage_pump(mr_watch_stage *ws);
/* Closes; -1 with msg when frames were not all written. */
int mr_watch_stage_close(mr_watch_stage *ws, mr_frames_out_summary *s, char *msg, size_t msg_size);

#endif
