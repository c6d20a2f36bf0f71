/* The command queue: a ring under one mutex, with a condition for "not
 * full" (a push waits on it) and one for "not empty" (the physics thread
 * waits on it between frames, on CLOCK_MONOTONIC). Every hold of the lock
 * is a few stores, so the drawing thread never waits behind a frame. */
#define _POSIX_C_SOURCE 200809L
#include "mr_handoff.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <time.h>

struct mr_cmdq {
  pthread_mutex_t lock;
  pthread_cond_t not_full, not_empty;
  int *ring;
  size_t capacity, head, count;
  uint64_t pushed, popped;
};

int mr_cmdq_create(size_t capacity, mr_cmdq **out) {
  *out = NULL;
  if (capacity == 0) return -1;
  mr_cmdq *q = calloc(1, sizeof *q);
  if (q == NULL || (q->ring = calloc(capacity, sizeof *q->ring)) == NULL) {
    free(q);
    return -1;
  }
  q->capacity = capacity;
  pthread_condattr_t ca;
  int bad = pthread_condattr_init(&ca);
  bad |= pthread_condattr_setclock(&ca, CLOCK_MONOTONIC);
  bad |= pthread_mutex_init(&q->lock, NULL);
  bad |= pthread_cond_init(&q->not_full, &ca);
  bad |= pthread_cond_init(&q->not_empty, &ca);
  pthread_condattr_destroy(&ca);
  if (bad != 0) {
    free(q->ring);
    free(q);
    return -1;
  }
  *out = q;
  return 0;
}

void mr_cmdq_destroy(mr_cmdq *q) {
  if (q == NULL) return;
  pthread_mutex_destroy(&q->lock);
  pthread_cond_destroy(&q->not_full);
  pthread_cond_destroy(&q->not_empty);
  free(q->ring);
  free(q);
}

void mr_cmdq_push(mr_cmdq *q, int cmd) {
  pthread_mutex_lock(&q->lock);
  while (q->count == q->capacity) pthread_cond_wait(&q->not_full, &q->lock);
  q->ring[(q->head + q->count) % q->capacity] = cmd;
  q->count++;
  q->pushed++;
  pthread_cond_signal(&q->not_empty);
  pthread_mutex_unlock(&q->lock);
}

bool mr_cmdq_pop(mr_cmdq *q, int *cmd) {
  pthread_mutex_lock(&q->lock);
  bool got = q->count > 0;
  if (got) {
    *cmd = q->ring[q->head];
    q->head = (q->head + 1) % q->capacity;
    q->count--;
    q->popped++;
    pthread_cond_signal(&q->not_full);
  }
  pthread_mutex_unlock(&q->lock);
  return got;
}

bool mr_cmdq_wait(mr_cmdq *q, double deadline) {
  /* Only +INFINITY means no deadline: a NaN from a broken clock must not
   * hang the show's thread, so it (and -INFINITY) is a time long past. */
  if (!(deadline == INFINITY) && !isfinite(deadline)) deadline = 0.0;
  struct timespec ts = { 0, 0 };
  if (isfinite(deadline)) {
    double whole = floor(deadline);
    ts.tv_sec = (time_t)whole;
    ts.tv_nsec = (long)((deadline - whole) * 1e9);
    if (ts.tv_nsec > 999999999L) ts.tv_nsec = 999999999L;
  }
  pthread_mutex_lock(&q->lock);
  while (q->count == 0) {
    int rc = isfinite(deadline) ? pthread_cond_timedwait(&q->not_empty, &q->lock, &ts)
                                : pthread_cond_wait(&q->not_empty, &q->lock);
    if (rc != 0) break; /* the deadline came */
  }
  bool got = q->count > 0;
  pthread_mutex_unlock(&q->lock);
  return got;
}

void mr_cmdq_counts(mr_cmdq *q, uint64_t *pushed, uint64_t *popped) {
  pthread_mutex_lock(&q->lock);
  if (pushed != NULL) *pushed = q->pushed;
  if (popped != NULL) *popped = q->popped;
  pthread_mutex_unlock(&q->lock);
}
