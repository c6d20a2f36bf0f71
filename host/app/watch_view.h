/* `marionette watch`: the frames received, kept a moment so that the
 * pictures can be drawn between them (the playout buffer), and the stage
 * they are drawn on (a window, or headless into frames as render's). */
#ifndef MR_WATCH_VIEW_H
#define MR_WATCH_VIEW_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "frames_out.h"
#include "mr_scene.h"
#include "stage_opts.h"
#include "stage_view.h"

enum { MR_WATCH_KEEP = 16 };

/* The newest frames received, oldest first by show time. */
typedef struct mr_watch_buffer {
  double t[MR_WATCH_KEEP];
  double *xyz[MR_WATCH_KEEP]; /* 3 n each, owned */
  size_t n;                   /* points per frame */
  int count, head;            /* ring: head is the oldest */
} mr_watch_buffer;

/* A frame at show time t (a frame older than the newest is dropped:
 * returns -1, as when memory runs out); 0 when kept. */
int mr_watch_buffer_push(mr_watch_buffer *b, double t, const double *xyz, size_t n);
/* The points at show time t into out (3 n): between the two frames
 * around t, linearly; the newest held past it (a loss, or a stall), the
 * oldest before it. 0 drawn between frames, 1 held, -1 no frame yet. */
int mr_watch_buffer_at(const mr_watch_buffer *b, double t, double *out);
/* The newest frame's time; -1 with none. */
double mr_watch_buffer_newest(const mr_watch_buffer *b);
void mr_watch_buffer_free(mr_watch_buffer *b);

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
