/* The latest-wins triple buffer. `middle` holds the slot between the two
 * sides and a bit saying the writer put it there since the reader last
 * took: each side swaps its own slot with it in one atomic exchange, so
 * neither ever waits, and the three slots stay three different ones. The
 * exchange releases what the writer wrote and acquires it for the
 * reader. */
#include "mr_handoff.h"

#define FRESH 4u
#define SLOT  3u

void mr_triple_init(mr_triple *tb) {
  tb->back = 0;
  atomic_init(&tb->middle, 1u);
  tb->front = 2;
  tb->published = tb->taken = 0;
}

unsigned mr_triple_back(const mr_triple *tb) {
  return tb->back;
}

unsigned mr_triple_front(const mr_triple *tb) {
  return tb->front;
}

void mr_triple_publish(mr_triple *tb) {
  unsigned old = atomic_exchange_explicit(&tb->middle, tb->back | FRESH, memory_order_acq_rel);
  tb->back = old & SLOT;
  tb->published++;
}

bool mr_triple_take(mr_triple *tb) {
  if ((atomic_load_explicit(&tb->middle, memory_order_relaxed) & FRESH) == 0) return false;
  unsigned old = atomic_exchange_explicit(&tb->middle, tb->front, memory_order_acq_rel);
  tb->front = old & SLOT;
  tb->taken++;
  return true;
}
