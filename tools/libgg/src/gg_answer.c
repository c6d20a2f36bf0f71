/* The glove side of the command protocol, for glove-gen. SET_RATE is
 * refused unless it keeps the frame rate: a synthetic glove's rate paces
 * the whole program (--rate); a new baud is taken and announced, as a
 * pty carries any. */
#include "gg_answer.h"

#include <string.h>

void gg_answer_init(gg_answer *a, unsigned ignore_first) {
  memset(a, 0, sizeof *a);
  gp_decoder_init(&a->dec, GP_SPEC_HASH);
  a->ignore_left = ignore_first;
}

void gg_answer_observe(gg_answer *a, const gg_stream *s) {
  if (!a->capturing) return;
  for (int i = 0; i < GG_CHANNELS; i++) {
    if (s->last_ch[i] < a->seen_min[i]) a->seen_min[i] = s->last_ch[i];
    if (s->last_ch[i] > a->seen_max[i]) a->seen_max[i] = s->last_ch[i];
  }
}

static size_t put(const gp_msg *m, gg_stream *s, uint8_t *out) {
  size_t n = gp_encode(m, s->cfg.spec_hash, out, GP_MAX_WIRE);
  s->expect.frames++;
  s->expect.bytes += n;
  return n;
}

static size_t ack(gg_answer *a, gg_stream *s, uint8_t tag, uint8_t cmd, uint8_t *out) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_ACK;
  m.u.ack.tag = tag;
  m.u.ack.cmd = cmd;
  a->acks++;
  return put(&m, s, out);
}

static size_t nack(gg_answer *a, gg_stream *s, uint8_t tag, uint8_t cmd, uint8_t reason,
                   uint8_t *out) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_NACK;
  m.u.nack.tag = tag;
  m.u.nack.cmd = cmd;
  m.u.nack.reason = reason;
  a->nacks++;
  return put(&m, s, out);
}

static size_t status(gg_answer *a, gg_stream *s, uint8_t *out) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_STATUS;
  m.u.status.t_us = (uint32_t)(s->slot * 1000000.0 / s->cfg.rate_hz);
  m.u.status.frames_sent = (uint32_t)(s->infos + s->samples_intact);
  m.u.status.cmd_errors = (uint32_t)a->nacks;
  return put(&m, s, out);
}

/* SPEC.md, CAL_SAVE: a channel that moved less than the firmware's 64
 * counts is refused (hardware/calibration.md), and the capture goes on. */
static size_t cal_save(gg_answer *a, gg_stream *s, uint8_t tag, uint8_t *out) {
  if (!a->capturing) return nack(a, s, tag, GP_CAL_SAVE, GP_NACK_BAD_STATE, out);
  for (int i = 0; i < GG_CHANNELS; i++)
    if (a->seen_max[i] < a->seen_min[i] + 64)
      return nack(a, s, tag, GP_CAL_SAVE, GP_NACK_BAD_ARGUMENT, out);
  memcpy(s->cal_min, a->seen_min, sizeof s->cal_min);
  memcpy(s->cal_max, a->seen_max, sizeof s->cal_max);
  s->cal_state = GP_CAL_VALID;
  a->capturing = 0;
  size_t n = ack(a, s, tag, GP_CAL_SAVE, out);
  return n + gg_stream_info(s, out + n);
}

static size_t cal(gg_answer *a, gg_stream *s, uint8_t type, uint8_t tag, uint8_t *out) {
  if (type == GP_CAL_SAVE) return cal_save(a, s, tag, out);
  if (type == GP_CAL_START) {
    a->capturing = 1;
    for (int i = 0; i < GG_CHANNELS; i++) {
      a->seen_min[i] = (uint16_t)GG_ADC_MAX;
      a->seen_max[i] = 0;
    }
    s->cal_state = GP_CAL_RUNNING;
  } else {
    a->capturing = 0;
    s->cal_state = GP_CAL_DEFAULTS;
    for (int i = 0; i < GG_CHANNELS; i++) {
      s->cal_min[i] = 0;
      s->cal_max[i] = (uint16_t)GG_ADC_MAX;
    }
  }
  size_t n = ack(a, s, tag, type, out);
  return n + gg_stream_info(s, out + n);
}

static size_t set_rate(gg_answer *a, gg_stream *s, const gp_set_rate *r, uint8_t *out) {
  if (r->frame_rate_hz == 0 || r->frame_rate_hz != (uint16_t)(s->cfg.rate_hz + 0.5))
    return nack(a, s, r->tag, GP_SET_RATE, GP_NACK_BAD_ARGUMENT, out);
  size_t n = ack(a, s, r->tag, GP_SET_RATE, out);
  if (r->baud != 0) s->cfg.baud = r->baud;
  return n + gg_stream_info(s, out + n);
}

static size_t command(gg_answer *a, gg_stream *s, const gp_msg *m, uint8_t *out) {
  uint8_t tag = m->u.ping.tag; /* every command's first field */
  size_t n;
  switch (m->type) {
  case GP_PING:
    return ack(a, s, tag, GP_PING, out);
  case GP_GET_INFO:
    n = ack(a, s, tag, GP_GET_INFO, out);
    return n + gg_stream_info(s, out + n);
  case GP_SET_RATE:
    return set_rate(a, s, &m->u.set_rate, out);
  case GP_STREAM_ON:
    s->streaming = 1;
    n = ack(a, s, tag, GP_STREAM_ON, out);
    return n + gg_stream_info(s, out + n);
  case GP_STREAM_OFF:
    s->streaming = 0;
    return ack(a, s, tag, GP_STREAM_OFF, out);
  case GP_CAL_START:
  case GP_CAL_SAVE:
  case GP_CAL_CLEAR:
    return cal(a, s, m->type, tag, out);
  case GP_GET_STATUS:
    n = ack(a, s, tag, GP_GET_STATUS, out);
    return n + status(a, s, out + n);
  default:
    return nack(a, s, tag, m->type, GP_NACK_UNKNOWN_COMMAND, out);
  }
}

size_t gg_answer_feed(gg_answer *a, gg_stream *s, const uint8_t *in, size_t n, uint8_t *out,
                      size_t cap) {
  size_t w = 0;
  while (n > 0) {
    gp_msg m;
    gp_event ev;
    size_t used = gp_decoder_feed(&a->dec, in, n, &m, &ev);
    in += used;
    n -= used;
    if (ev != GP_EV_FRAME || m.type < GP_PING) continue; /* noise, or our own echo */
    a->commands++;
    if (a->ignore_left > 0) {
      a->ignore_left--;
      a->ignored++;
      continue;
    }
    if (cap - w < 4 * GP_MAX_WIRE) break; /* the host retries what it misses */
    w += command(a, s, &m, out + w);
  }
  return w;
}
