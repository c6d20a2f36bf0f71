/* A simulated glove for the core's host tests: a sampling timer, an ADC, a
 * serial line that drains at its baud rate, a flash page, LED and button.
 * It implements firmware/core/fw_hal.h; tests drive time with fake_step. */
#ifndef FAKE_HAL_H
#define FAKE_HAL_H

#include <stddef.h>
#include <stdint.h>

#include "fw_blockq.h"
#include "fw_cal.h"
#include "fw_core.h"
#include "gp.h"

#define FAKE_WIRE_CAP (1u << 20)

typedef struct fake_hal {
  fw_blockq q;
  uint32_t tick;           /* next tick the timer will sample */
  uint16_t level[FW_N_CH]; /* what the ADC converts, per channel */
  uint32_t adc_timeouts;
  uint32_t blocks_lost; /* blocks that found the queue full */

  /* transmit queue (FW_TXQ_BYTES) and the line behind it */
  uint8_t txq[FW_TXQ_BYTES];
  size_t txq_len;
  int tx_overflow; /* the core wrote more than tx_free allowed */
  uint32_t baud;
  uint64_t line_bits;          /* bit times owed to the line, x1000 */
  uint8_t wire[FAKE_WIRE_CAP]; /* every byte that left the line */
  size_t wire_len;
  uint32_t baud_changes;

  /* receive */
  uint8_t rx[4096];
  size_t rx_len, rx_pos;

  /* flash page */
  uint8_t flash[FW_CAL_RECORD_LEN];
  int flash_absent; /* board without storage */
  int flash_fail_write;
  uint32_t flash_writes;

  int led;
  int button;
  uint32_t uid[3];
} fake_hal;

extern fake_hal fake;

/* Resets the simulated board: erased flash, 115200 baud, all channels at
 * 2048. */
void fake_reset(void);
/* Advances one tick: samples a block (unless skip), runs polls main-loop
 * passes, and lets the line carry one tick's worth of bytes. */
void fake_step(fw_core *c, int skip_sample, unsigned polls);
/* Queues one block of the current levels stamped with tick, without moving
 * the timer on: what a board that hands the same tick over twice would do. */
void fake_sample_at(uint32_t tick);
/* fake_step with one sample and one poll, n times. */
void fake_run(fw_core *c, unsigned ticks);
/* Queues bytes as if the host had sent them. */
void fake_rx(const uint8_t *data, size_t n);

/* The frames on the wire, decoded by the protocol's own decoder. */
#define FAKE_MAX_FRAMES 40000u
typedef struct fake_frames {
  size_t n;
  gp_msg msg[FAKE_MAX_FRAMES];
  gp_event ev[FAKE_MAX_FRAMES];
  size_t end[FAKE_MAX_FRAMES]; /* wire offset just past the frame */
  gp_counters c;
} fake_frames;
extern fake_frames frames;
/* Decodes fake.wire[0 .. wire_len) into frames (from scratch). */
void fake_decode(void);
/* Index of the first frame of type at or after index from, or frames.n. */
size_t fake_find(size_t from, uint8_t type);
/* Sends a host command as its wire bytes. */
void fake_send(const gp_msg *m);

#endif
