/* Takes (.mrec): a glove's bytes as recorded, each chunk fed when the
 * caller's time reaches the time it was recorded at. A take is named as a
 * file source, or found on a stream (stdin, a FIFO) by its magic. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glove_internal.h"

bool mr_glove_take_done(const mr_glove *g) {
  return g != NULL && g->is_take && g->take_done;
}

static void take_failed(mr_glove *g, const mr_io_err *err) {
  snprintf(g->last_error, sizeof g->last_error, "%s", err->msg);
  g->take_error = err->status;
}

/* The take named by the source, opened at the first poll. */
static int open_named(mr_glove *g, double now) {
  mr_io_err err;
  const char *path = strncmp(g->def.source, "file:", 5) == 0 ? g->def.source + 5 : g->def.source;
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

int mr_glove_take_from_stream(mr_glove *g, const uint8_t *prefix, size_t len, double now) {
  mr_io_err err;
  /* The reader takes these bytes before the descriptor's: they must live
   * as long as it reads. */
  free(g->take_prefix);
  g->take_prefix = malloc(len ? len : 1);
  if (g->take_prefix == NULL) {
    snprintf(g->last_error, sizeof g->last_error, "out of memory");
    g->take_done = g->is_take = true;
    return -1;
  }
  memcpy(g->take_prefix, prefix, len);
  g->is_take = true;
  g->last_bytes = now;
  if (mr_rec_reader_open_fd(&g->take, g->io.fd, mr_io_path(&g->io), g->take_prefix, len, &err) !=
      0) {
    take_failed(g, &err);
    g->take_done = true;
    return -1;
  }
  g->take_open = true;
  return 0;
}

int mr_glove_take_play(mr_glove *g, double now) {
  int taken = 0;
  if (!g->take_open && (g->take_done || open_named(g, now) != 0)) return 0;
  for (;;) {
    if (!g->have_chunk) {
      mr_io_err err;
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
    /* In whole ns, rounded as a recorder rounds `now`, so a chunk read at
     * a frame's time plays at that frame, not the next. */
    if (g->chunk_t_ns > (uint64_t)llround(fmax(now, 0.0) * 1e9)) return taken;
    g->have_chunk = false;
    g->last_bytes = now;
    if (g->tap != NULL) g->tap(g->tap_user, now, g->chunk, g->chunk_len);
    taken += mr_glove_feed(g, g->chunk, g->chunk_len, now);
  }
}
