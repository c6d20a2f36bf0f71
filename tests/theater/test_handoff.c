/* The hand-offs between the physics thread and the drawing thread: the
 * latest-wins triple buffer and the bounded command queue, each alone and
 * then between two real threads (run under ThreadSanitizer by make
 * test-tsan). */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <pthread.h>
#include <string.h>
#include <time.h>

#include "mr_handoff.h"

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Three slots, always three different ones; the reader gets the newest
 * published, and nothing when nothing new came. */
static void the_reader_takes_only_the_newest_frame(void **state) {
  (void)state;
  mr_triple tb;
  mr_triple_init(&tb);
  int slot[3] = { -1, -1, -1 };
  assert_false(mr_triple_take(&tb));
  for (int v = 1; v <= 3; v++) {
    assert_int_not_equal(mr_triple_back(&tb), mr_triple_front(&tb));
    slot[mr_triple_back(&tb)] = v;
    mr_triple_publish(&tb);
  }
  assert_true(mr_triple_take(&tb));
  assert_int_equal(slot[mr_triple_front(&tb)], 3); /* 1 and 2 were overtaken */
  assert_false(mr_triple_take(&tb));
  assert_int_equal(slot[mr_triple_front(&tb)], 3); /* still the reader's */
  slot[mr_triple_back(&tb)] = 4;
  mr_triple_publish(&tb);
  assert_true(mr_triple_take(&tb));
  assert_int_equal(slot[mr_triple_front(&tb)], 4);
  assert_int_not_equal(mr_triple_back(&tb), mr_triple_front(&tb));
  assert_int_equal(tb.published, 4); /* every publish counts, overtaken or not */
  assert_int_equal(tb.taken, 2);     /* a take that found nothing new does not */
}

enum { WORDS = 64, FRAMES = 200000 };

typedef struct shared {
  mr_triple tb;
  uint64_t slot[3][WORDS]; /* every word of a frame holds its number */
} shared;

static void *writer(void *arg) {
  shared *s = arg;
  for (uint64_t n = 1; n <= FRAMES; n++) {
    uint64_t *w = s->slot[mr_triple_back(&s->tb)];
    for (int i = 0; i < WORDS; i++) w[i] = n;
    mr_triple_publish(&s->tb);
  }
  return NULL;
}

/* A writer publishing 200 000 frames as fast as it can: every frame the
 * reader takes is whole (never half of one and half of the next) and
 * newer than the one before, and the last one comes through. */
static void frames_cross_threads_whole_and_in_order(void **state) {
  (void)state;
  static shared s;
  memset(&s, 0, sizeof s);
  mr_triple_init(&s.tb);
  pthread_t t;
  assert_int_equal(pthread_create(&t, NULL, writer, &s), 0);
  uint64_t last = 0, taken = 0;
  while (last < FRAMES) {
    if (!mr_triple_take(&s.tb)) continue;
    const uint64_t *w = s.slot[mr_triple_front(&s.tb)];
    for (int i = 1; i < WORDS; i++) assert_int_equal(w[i], w[0]);
    assert_true(w[0] > last);
    last = w[0];
    taken++;
  }
  assert_int_equal(pthread_join(t, NULL), 0);
  print_message("%llu of %d frames taken, the rest overtaken\n", (unsigned long long)taken, FRAMES);
  assert_int_equal(last, FRAMES);
}

/* First in, first out; a pop never waits; a wait with nothing queued
 * ends at its deadline (at once for a NaN or -INFINITY one, which must not
 * wait forever), and at once when a command is there. */
static void commands_come_out_in_order_and_waits_end_at_their_deadline(void **state) {
  (void)state;
  mr_cmdq *q = NULL;
  assert_int_equal(mr_cmdq_create(0, &q), -1);
  assert_int_equal(mr_cmdq_create(3, &q), 0);
  int c = -1;
  assert_false(mr_cmdq_pop(q, &c));
  double t0 = now_s();
  assert_false(mr_cmdq_wait(q, t0 + 0.05));
  assert_true(now_s() - t0 >= 0.049);
  assert_false(mr_cmdq_wait(q, NAN));
  assert_false(mr_cmdq_wait(q, -INFINITY));
  for (int i = 0; i < 3; i++) mr_cmdq_push(q, 10 + i);
  assert_true(mr_cmdq_wait(q, INFINITY));
  for (int i = 0; i < 3; i++) {
    assert_true(mr_cmdq_pop(q, &c));
    assert_int_equal(c, 10 + i);
  }
  assert_false(mr_cmdq_pop(q, &c));
  uint64_t pushed, popped;
  mr_cmdq_counts(q, &pushed, &popped);
  assert_int_equal(pushed, 3);
  assert_int_equal(popped, 3);
  mr_cmdq_destroy(q);
}

enum { COMMANDS = 100000 };

static void *sender(void *arg) {
  for (int i = 0; i < COMMANDS; i++) mr_cmdq_push(arg, i);
  return NULL;
}

/* A sender pushing 100 000 commands into a queue of 4 held at most: it
 * waits while the queue is full, and the taker gets every one, in order. */
static void a_full_queue_holds_the_sender_and_loses_nothing(void **state) {
  (void)state;
  mr_cmdq *q = NULL;
  assert_int_equal(mr_cmdq_create(4, &q), 0);
  pthread_t t;
  assert_int_equal(pthread_create(&t, NULL, sender, q), 0);
  int expect = 0, c;
  while (expect < COMMANDS) {
    if (!mr_cmdq_pop(q, &c)) {
      mr_cmdq_wait(q, now_s() + 0.01);
      continue;
    }
    assert_int_equal(c, expect);
    expect++;
  }
  assert_int_equal(pthread_join(t, NULL), 0);
  uint64_t pushed, popped;
  mr_cmdq_counts(q, &pushed, &popped);
  assert_int_equal(pushed, COMMANDS);
  assert_int_equal(popped, COMMANDS);
  mr_cmdq_destroy(q);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(the_reader_takes_only_the_newest_frame),
    cmocka_unit_test(frames_cross_threads_whole_and_in_order),
    cmocka_unit_test(commands_come_out_in_order_and_waits_end_at_their_deadline),
    cmocka_unit_test(a_full_queue_holds_the_sender_and_loses_nothing),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
