/* Hand-offs between the physics thread and the drawing thread: a
 * latest-wins triple buffer for frames going down, a bounded command
 * queue for the window's inputs going up. C11 only (atomics, and POSIX
 * threads for the queue's waits). */
#ifndef MR_HANDOFF_H
#define MR_HANDOFF_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------- triple buffer */

/* Three slots the caller owns, one writer and one reader. The writer
 * fills its slot (mr_triple_back) and publishes it, never waiting; the
 * reader takes the newest published slot (mr_triple_front), never
 * waiting. A frame published over one not yet taken replaces it: latest
 * wins. Each side owns its slot until it publishes or takes again. */
typedef struct mr_triple {
  _Atomic unsigned middle; /* the slot in between, and whether it is news */
  unsigned back, front;
  uint64_t published, taken; /* the writer's and the reader's counts */
} mr_triple;

void mr_triple_init(mr_triple *tb);
unsigned mr_triple_back(const mr_triple *tb);  /* 0, 1 or 2: the writer's */
void mr_triple_publish(mr_triple *tb);         /* the writer's slot is the newest */
bool mr_triple_take(mr_triple *tb);            /* true: a newer slot is the reader's */
unsigned mr_triple_front(const mr_triple *tb); /* 0, 1 or 2: the reader's */

/* ------------------------------------------------------- command queue */

/* A bounded FIFO of int commands between threads. A push waits only while
 * the queue is full (the consumer drains it every frame), so no command is
 * ever lost; a pop never waits. */
typedef struct mr_cmdq mr_cmdq;

/* capacity >= 1; 0, or -1 when memory or a lock cannot be had. */
int mr_cmdq_create(size_t capacity, mr_cmdq **out);
void mr_cmdq_destroy(mr_cmdq *q);
void mr_cmdq_push(mr_cmdq *q, int cmd);
bool mr_cmdq_pop(mr_cmdq *q, int *cmd);
/* Waits until a command is queued or CLOCK_MONOTONIC reaches deadline, s
 * (INFINITY: no deadline; NaN or -INFINITY: no wait); true when one is
 * queued. */
bool mr_cmdq_wait(mr_cmdq *q, double deadline);
/* Commands pushed and popped so far. */
void mr_cmdq_counts(mr_cmdq *q, uint64_t *pushed, uint64_t *popped);

#ifdef __cplusplus
}
#endif

#endif /* MR_HANDOFF_H */
