/* `marionette watch`'s playout buffer: the frames received, kept a moment
 * so that the pictures can be drawn between them. Apart from the stage so
 * that it is tested alone (tests/net/test_watch_playout.c). */
#ifndef MR_WATCH_BUFFER_H
#define MR_WATCH_BUFFER_H

#include <stddef.h>

enum { MR_WATCH_KEEP = 16 };

/* The newest frames received, oldest first by show time. */
typedef struct mr_watch_buffer {
  double t[MR_WATCH_KEEP];
  double *xyz[MR_WATCH_KEEP]; /* 3 n each, owned */
  size_t n;                   /* points per frame */
  int count, head;            /* ring: head is the oldest */
} mr_watch_buffer;

/* A frame at show time t: 0 when kept. A frame no newer than the newest
 * is dropped (-1, as when memory runs out); a frame of another number of
 * points (another scene) empties the buffer and starts it again. */
int mr_watch_buffer_push(mr_watch_buffer *b, double t, const double *xyz, size_t n);
/* The points at show time t into out (3 n): between the two frames
 * around t, linearly; the newest held past it (a loss, or a stall), the
 * oldest before it. 0 drawn between frames, 1 held, -1 no frame yet. */
int mr_watch_buffer_at(const mr_watch_buffer *b, double t, double *out);
/* The newest frame's time; -1 with none. */
double mr_watch_buffer_newest(const mr_watch_buffer *b);
void mr_watch_buffer_free(mr_watch_buffer *b);

#endif
