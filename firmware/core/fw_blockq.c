#include "fw_blockq.h"

void fw_blockq_init(fw_blockq *q) {
  atomic_init(&q->head, 0u);
  atomic_init(&q->tail, 0u);
}

uint16_t *fw_blockq_slot(fw_blockq *q) {
  unsigned head = atomic_load_explicit(&q->head, memory_order_relaxed);
  unsigned tail = atomic_load_explicit(&q->tail, memory_order_acquire);
  if (head - tail >= FW_BLOCKQ_DEPTH) return 0;
  return q->counts[head % FW_BLOCKQ_DEPTH];
}

void fw_blockq_commit(fw_blockq *q, uint32_t tick) {
  unsigned head = atomic_load_explicit(&q->head, memory_order_relaxed);
  q->tick[head % FW_BLOCKQ_DEPTH] = tick;
  /* Release: the counts and tick are visible before the consumer sees head. */
  atomic_store_explicit(&q->head, head + 1u, memory_order_release);
}

int fw_blockq_take(fw_blockq *q, uint16_t out[FW_BLOCK_LEN], uint32_t *tick) {
  unsigned tail = atomic_load_explicit(&q->tail, memory_order_relaxed);
  unsigned head = atomic_load_explicit(&q->head, memory_order_acquire);
  if (head == tail) return 0;
  unsigned slot = tail % FW_BLOCKQ_DEPTH;
  for (unsigned i = 0; i < FW_BLOCK_LEN; i++) out[i] = q->counts[slot][i];
  *tick = q->tick[slot];
  atomic_store_explicit(&q->tail, tail + 1u, memory_order_release);
  return 1;
}
