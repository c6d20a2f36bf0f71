/* Frame assembly: every frame the glove sends is built here, through the
 * protocol codec (protocol/), with this firmware's spec hash. */
#ifndef FW_FRAME_H
#define FW_FRAME_H

#include <stddef.h>
#include <stdint.h>

#include "fw_config.h"
#include "gp.h"

/* What INFO announces, apart from proto_major and spec_hash, which are the
 * build's (GP_PROTO_MAJOR, GP_SPEC_HASH). */
typedef struct fw_info_state {
  uint8_t fw_major, fw_minor, fw_patch;
  uint32_t uid[3];
  uint8_t hand;
  uint8_t n_channels;
  uint8_t adc_bits;
  uint32_t sample_rate_hz;
  uint32_t frame_rate_hz;
  uint32_t baud;
  uint8_t cal_state;
  uint16_t cal_min[FW_N_CH];
  uint16_t cal_max[FW_N_CH];
} fw_info_state;

typedef struct fw_status_state {
  uint32_t t_us;
  uint32_t frames_sent;
  uint32_t overruns;
  uint32_t dropped_frames;
  uint32_t cmd_errors;
  uint32_t adc_timeouts;
} fw_status_state;

/* Each returns the wire length (COBS + delimiter), at most GP_MAX_WIRE, or 0
 * if cap is too small. */
size_t fw_frame_sample(uint16_t seq, uint32_t t_us, const uint16_t ch[FW_N_CH], uint8_t flags,
                       uint8_t *wire, size_t cap);
size_t fw_frame_info(const fw_info_state *s, uint8_t *wire, size_t cap);
size_t fw_frame_status(const fw_status_state *s, uint8_t *wire, size_t cap);
size_t fw_frame_ack(uint8_t tag, uint8_t cmd, uint8_t *wire, size_t cap);
size_t fw_frame_nack(uint8_t tag, uint8_t cmd, uint8_t reason, uint8_t *wire, size_t cap);

#endif
