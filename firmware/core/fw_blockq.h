/* A queue of sampled blocks from the timer interrupt to the main loop.
 *
 * One producer (the interrupt that owns a finished block) and one consumer
 * (the main loop); no locks, so the interrupt never waits. When the main loop
 * falls FW_BLOCKQ_DEPTH ticks behind, new blocks are dropped and the core sees
 * the gap in the tick numbers and counts it as overruns.
 */
#ifndef FW_BLOCKQ_H
#define FW_BLOCKQ_H

#include <stdatomic.h>
#include <stdint.h>

#include "fw_config.h"

typedef struct fw_blockq {
  uint16_t counts[FW_BLOCKQ_DEPTH][FW_BLOCK_LEN];
  uint32_t tick[FW_BLOCKQ_DEPTH];
  atomic_uint head; /* written by the producer only */
  atomic_uint tail; /* written by the consumer only */
} fw_blockq;

void fw_blockq_init(fw_blockq *q);
/* Producer: the slot to fill for the next block, or NULL when full. A block
 * that finds no slot is simply lost: the core counts it as an overrun from
 * the gap it leaves in the tick numbers. */
uint16_t *fw_blockq_slot(fw_blockq *q);
/* Producer: publishes the filled slot as tick's block. */
void fw_blockq_commit(fw_blockq *q, uint32_t tick);
/* Consumer: copies the oldest block out. Returns 1, or 0 if empty. */
int fw_blockq_take(fw_blockq *q, uint16_t out[FW_BLOCK_LEN], uint32_t *tick);

#endif
