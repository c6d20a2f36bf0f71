/* The glove's firmware core: sampling schedule, filtering, framing, commands,
 * INFO and STATUS, calibration, LED and button. Portable C11 with no hardware
 * access and no dynamic memory: a board calls fw_core_init once and
 * fw_core_poll from its main loop, and provides fw_hal.h.
 *
 * §3.2 of the paper: the glove transduces and transmits the stretch of the
 * strings attached to the user's fingers, five degrees of freedom per glove.
 */
#ifndef FW_CORE_H
#define FW_CORE_H

#include <stdint.h>

#include "fw_cal.h"
#include "fw_config.h"
#include "fw_filter.h"
#include "fw_rx.h"

typedef struct fw_core {
  fw_filter filter;
  fw_cal cal;
  fw_rx rx;
  uint32_t uid[3];

  uint32_t frame_rate_hz;
  uint32_t baud;
  uint32_t pending_baud; /* switched to once the ACK has left the wire */
  uint8_t streaming;

  /* schedule, in ticks of the sampling timer */
  uint8_t have_tick;
  uint32_t last_tick;
  uint32_t frame_phase; /* ticks since the last SAMPLE boundary */
  uint32_t info_phase;
  uint16_t seq;
  uint8_t seq_started;   /* the first SAMPLE since boot (GP_SAMPLE_F_START) is out */
  uint16_t ch[FW_N_CH];  /* newest filtered counts */
  uint8_t pending_flags; /* CLIPPED / OVERRUN since the last SAMPLE */

  /* button (debounced) */
  uint8_t button;
  uint8_t button_raw;
  uint32_t button_count;

  /* STATUS counters */
  uint32_t frames_sent;
  uint32_t overruns;
  uint32_t dropped_frames;
  uint32_t cmd_errors;
} fw_core;

/* Loads the calibration, reads the uid, and starts with the defaults of
 * fw_config.h: streaming on, FW_FRAME_RATE_HZ, FW_BAUD. The board has already
 * set the link to FW_BAUD. */
void fw_core_init(fw_core *c);
/* One pass of the main loop: takes the sampled blocks, sends what is due,
 * answers commands, feeds the watchdog. Never blocks. */
void fw_core_poll(fw_core *c);

#endif
