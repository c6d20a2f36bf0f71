/* The watcher's playout buffer (watch_buffer.h). */
#include "watch_buffer.h"

#include <stdlib.h>
#include <string.h>

int mr_watch_buffer_push(mr_watch_buffer *b, double t, const double *xyz, size_t n) {
  if (b->count > 0 && (n != b->n || !(t > mr_watch_buffer_newest(b)))) {
    if (n == b->n) return -1;
    mr_watch_buffer_free(b); /* another scene's size: start again */
  }
  b->n = n;
  int slot = (b->head + b->count) % MR_WATCH_KEEP;
  if (b->count == MR_WATCH_KEEP) {
    slot = b->head;
    b->head = (b->head + 1) % MR_WATCH_KEEP;
  } else {
    b->count++;
  }
  if (b->xyz[slot] == NULL) b->xyz[slot] = malloc(3 * (n > 0 ? n : 1) * sizeof(double));
  if (b->xyz[slot] == NULL) {
    b->count--;
    return -1;
  }
  memcpy(b->xyz[slot], xyz, 3 * n * sizeof(double));
  b->t[slot] = t;
  return 0;
}

double mr_watch_buffer_newest(const mr_watch_buffer *b) {
  return b->count > 0 ? b->t[(b->head + b->count - 1) % MR_WATCH_KEEP] : -1.0;
}

int mr_watch_buffer_at(const mr_watch_buffer *b, double t, double *out) {
  if (b->count == 0) return -1;
  int newest = (b->head + b->count - 1) % MR_WATCH_KEEP;
  if (t >= b->t[newest]) {
    memcpy(out, b->xyz[newest], 3 * b->n * sizeof(double));
    return 1;
  }
  if (t <= b->t[b->head]) {
    memcpy(out, b->xyz[b->head], 3 * b->n * sizeof(double));
    return 0;
  }
  for (int k = 1; k < b->count; k++) {
    int i = (b->head + k) % MR_WATCH_KEEP, h = (b->head + k - 1) % MR_WATCH_KEEP;
    if (t > b->t[i]) continue;
    double w = (t - b->t[h]) / (b->t[i] - b->t[h]);
    for (size_t j = 0; j < 3 * b->n; j++) out[j] = b->xyz[h][j] + w * (b->xyz[i][j] - b->xyz[h][j]);
    break;
  }
  return 0;
}

void mr_watch_buffer_free(mr_watch_buffer *b) {
  for (int i = 0; i < MR_WATCH_KEEP; i++) free(b->xyz[i]);
  memset(b, 0, sizeof *b);
}
