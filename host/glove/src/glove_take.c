/* Takes (.mrec): a glove's bytes as recorded, each chunk fed when the
 * caller's time reaches the time it was recorded at. A take is named as a
 * file source, or found on a stream (stdin, a FIFO) by its magic. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "glove_internal.h"

bool mr_glove_take_done(const mr_glove *g) {
  return g != NULL && g->is_take && g->take_done;
}

static void take_failed(mr_glove *g, const mr_io_error *err) {
  snprintf(g->last_error, sizeof g->last_error, "%s", err->msg);
  g->take_error = err->status;
}

/* The take named by the source, opened at the first poll. */
static int open_named(mr_glove *g, double now) {
  mr_io_error err;
  const char *src = g->def.source;
  const char *path = strncmp(src, "file:", 5) == 0 || strncmp(src, "take:", 5) == 0 ? src + 5 : src;
  if (mr_rec_reader_open(&g->take, path, &err) != 0) {
    take_failed(g, &err);
    g->take_done = true;
    return -1;
  }
  g->take_open = true;
  g->counters.opens++;
  g->last_bytes = now;
  return 0;
}

void mr_glove_take_from_stream(mr_glove *g, const uint8_t *prefix, size_t len, double now) {
  mr_io_error err;
  /* The reader takes these bytes before the descriptor's: they must live
   * as long as it reads. */
  free(g->take_prefix);
  g->take_prefix = malloc(len ? len : 1);
  if (g->take_prefix == NULL) {
    snprintf(g->last_error, sizeof g->last_error, "out of memory");
    g->take_done = g->is_take = true;
    return;
  }
  memcpy(g->take_prefix, prefix, len);
  g->is_take = true;
  g->last_bytes = now;
  if (mr_rec_reader_open_fd(&g->take, g->io.fd, mr_io_path(&g->io), g->take_prefix, len, &err) !=
      0) {
    take_failed(g, &err);
    g->take_done = true;
    return;
  }
  g->take_open = true;
}

/* In whole ns, rounded as a recorder rounds `now`, so a chunk read at a
 * frame's time plays at that frame, not the next. A `now` beyond what a
 * uint64 of ns holds makes every chunk due. */
static bool chunk_due(const mr_glove *g, double now) {
  if (now >= 1.8e10) return true;
  return g->chunk_t_ns <= (uint64_t)llround(fmax(now, 0.0) * 1e9);
}

void mr_glove_take_wait(const mr_glove *g, double now, int timeout_ms) {
  if (timeout_ms <= 0 || !g->have_chunk || g->take_done || chunk_due(g, now)) return;
  double wait_s = (double)g->chunk_t_ns * 1e-9 - now;
  if (wait_s > timeout_ms * 1e-3) wait_s = timeout_ms * 1e-3;
  struct timespec ts = { (time_t)wait_s, (long)((wait_s - floor(wait_s)) * 1e9) };
  nanosleep(&ts, NULL);
}

int mr_glove_take_play(mr_glove *g, double now) {
  int taken = 0;
  if (!g->take_open && (g->take_done || open_named(g, now) != 0)) return 0;
  for (;;) {
    if (!g->have_chunk) {
      mr_io_error err;
      int rc = mr_rec_reader_next(&g->take, &g->chunk_t_ns, &g->chunk, &g->chunk_len, &err);
      if (rc != 1) {
        /* The end, or a take cut short (a show killed mid-chunk): what was
         * whole has been played. */
        if (rc < 0) take_failed(g, &err);
        g->take_done = true;
        mr_rec_reader_close(&g->take);
        g->take_open = false;
        return taken;
      }
      g->have_chunk = true;
    }
    if (!chunk_due(g, now)) return taken;
    g->have_chunk = false;
    g->last_bytes = now;
    if (g->tap != NULL) g->tap(g->tap_user, now, g->chunk, g->chunk_len);
    taken += mr_glove_feed(g, g->chunk, g->chunk_len, now);
  }
}
