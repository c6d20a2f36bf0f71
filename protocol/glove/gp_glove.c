/* A made-up glove's INFO and SAMPLE frames (gp_glove.h): the fields a
 * glove fills, then the codec's gp_encode. */
#include "gp_glove.h"

#include <math.h>
#include <string.h>

/* The link's default rate (SPEC.md), announced unless told otherwise. */
#define DEFAULT_BAUD 115200u

gp_info gp_default_glove_info(void) {
  gp_info info;
  memset(&info, 0, sizeof info);
  info.proto_major = GP_PROTO_MAJOR;
  info.spec_hash = GP_SPEC_HASH;
  info.fw_minor = 1;
  info.hand = GP_HAND_RIGHT;
  info.n_channels = GP_SAMPLE_CH_COUNT;
  info.adc_bits = GP_SAMPLE_CH_BITS;
  info.baud = DEFAULT_BAUD;
  info.cal_state = GP_CAL_DEFAULTS;
  for (unsigned c = 0; c < GP_SAMPLE_CH_COUNT; c++) info.cal_max[c] = GP_SAMPLE_CH_MAX;
  return info;
}

void gp_glove_info_set_rate(gp_info *info, double rate_hz) {
  uint16_t hz = 0;
  if (rate_hz >= 65535)
    hz = 65535;
  else if (rate_hz > 0)
    hz = (uint16_t)lround(rate_hz);
  info->frame_rate_hz = hz;
  info->sample_rate_hz = hz;
}

size_t gp_glove_info_encode(const gp_info *info, uint8_t *wire, size_t cap) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_INFO;
  m.u.info = *info;
  return gp_encode(&m, info->spec_hash, wire, cap);
}

uint16_t gp_glove_value_count(double value) {
  if (!(value > 0)) value = 0; /* also NaN */
  if (value > 1) value = 1;
  return (uint16_t)lround(value * GP_SAMPLE_CH_MAX);
}

uint32_t gp_glove_time_us(double t_s) {
  return (uint32_t)llround(t_s * 1e6);
}

gp_sample gp_glove_sample(uint16_t seq, uint32_t t_us, const uint16_t ch[GP_SAMPLE_CH_COUNT]) {
  gp_sample s;
  memset(&s, 0, sizeof s);
  s.seq = seq;
  s.t_us = t_us;
  memcpy(s.ch, ch, sizeof s.ch);
  return s;
}

size_t gp_glove_sample_encode(const gp_sample *s, uint32_t spec_hash, uint8_t *wire, size_t cap) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SAMPLE;
  m.u.sample = *s;
  return gp_encode(&m, spec_hash, wire, cap);
}
