/* Feeding the streaming decoder in the protocol tests: a tally of events and
 * the SAMPLE numbers delivered, and SAMPLE frames made to order. */
#ifndef DECODER_FEED_H
#define DECODER_FEED_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "gp.h"

typedef struct tally {
  int ev[GP_EV_SPEC_MISMATCH + 1];
  uint16_t seqs[256];
  int n_seqs;
} tally;

static inline void feed(gp_decoder *d, const uint8_t *p, size_t n, tally *t) {
  while (n) {
    gp_msg out;
    gp_event ev;
    size_t used = gp_decoder_feed(d, p, n, &out, &ev);
    assert_true(used >= 1 && used <= n);
    if (ev != GP_EV_NONE) t->ev[ev]++;
    if ((ev == GP_EV_FRAME || ev == GP_EV_FRAME_LATE) && out.type == GP_SAMPLE && t->n_seqs < 256)
      t->seqs[t->n_seqs++] = out.u.sample.seq;
    p += used;
    n -= used;
  }
}

static inline size_t sample(uint16_t seq, uint32_t hash, uint8_t *wire) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SAMPLE;
  m.u.sample.seq = seq;
  m.u.sample.t_us = 4000u * seq;
  for (unsigned i = 0; i < GP_SAMPLE_CH_COUNT; i++) m.u.sample.ch[i] = (uint16_t)(seq * 7 + i);
  return gp_encode(&m, hash, wire, GP_MAX_WIRE);
}

static inline void send_samples(gp_decoder *d, tally *t, const uint16_t *seqs, int n) {
  for (int i = 0; i < n; i++) {
    uint8_t w[GP_MAX_WIRE];
    feed(d, w, sample(seqs[i], GP_SPEC_HASH, w), t);
  }
}

#endif
