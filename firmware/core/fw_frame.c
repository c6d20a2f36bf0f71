#include "fw_frame.h"

size_t fw_frame_sample(uint16_t seq, uint32_t t_us, const uint16_t ch[FW_N_CH], uint8_t flags,
                       uint8_t *wire, size_t cap) {
  gp_msg m = { .type = GP_SAMPLE };
  m.u.sample.seq = seq;
  m.u.sample.t_us = t_us;
  for (unsigned c = 0; c < FW_N_CH; c++) m.u.sample.ch[c] = ch[c];
  m.u.sample.flags = flags;
  return gp_encode(&m, GP_SPEC_HASH, wire, cap);
}

size_t fw_frame_info(const fw_info_state *s, uint8_t *wire, size_t cap) {
  gp_msg m = { .type = GP_INFO };
  gp_info *i = &m.u.info;
  i->proto_major = GP_PROTO_MAJOR;
  i->spec_hash = GP_SPEC_HASH;
  i->fw_major = s->fw_major;
  i->fw_minor = s->fw_minor;
  i->fw_patch = s->fw_patch;
  for (unsigned k = 0; k < 3; k++) i->uid[k] = s->uid[k];
  i->hand = s->hand;
  i->n_channels = s->n_channels;
  i->adc_bits = s->adc_bits;
  i->sample_rate_hz = (uint16_t)s->sample_rate_hz;
  i->frame_rate_hz = (uint16_t)s->frame_rate_hz;
  i->baud = s->baud;
  i->cal_state = s->cal_state;
  for (unsigned c = 0; c < FW_N_CH; c++) {
    i->cal_min[c] = s->cal_min[c];
    i->cal_max[c] = s->cal_max[c];
  }
  return gp_encode(&m, GP_SPEC_HASH, wire, cap);
}

size_t fw_frame_status(const fw_status_state *s, uint8_t *wire, size_t cap) {
  gp_msg m = { .type = GP_STATUS };
  m.u.status.t_us = s->t_us;
  m.u.status.frames_sent = s->frames_sent;
  m.u.status.overruns = s->overruns;
  m.u.status.dropped_frames = s->dropped_frames;
  m.u.status.cmd_errors = s->cmd_errors;
  m.u.status.adc_timeouts = s->adc_timeouts;
  return gp_encode(&m, GP_SPEC_HASH, wire, cap);
}

size_t fw_frame_ack(uint8_t tag, uint8_t cmd, uint8_t *wire, size_t cap) {
  gp_msg m = { .type = GP_ACK };
  m.u.ack.tag = tag;
  m.u.ack.cmd = cmd;
  return gp_encode(&m, GP_SPEC_HASH, wire, cap);
}

size_t fw_frame_nack(uint8_t tag, uint8_t cmd, uint8_t reason, uint8_t *wire, size_t cap) {
  gp_msg m = { .type = GP_NACK };
  m.u.nack.tag = tag;
  m.u.nack.cmd = cmd;
  m.u.nack.reason = reason;
  return gp_encode(&m, GP_SPEC_HASH, wire, cap);
}
