/* Frame generation and fault injection for one glove. Each fault is applied
 * exactly as tools/README.md ("Faults") maps it to decoder counters, and the
 * expected counters are kept as the frames go out, so the truth file is what
 * the decoder must report, not an estimate. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gg_stream.h"
#include "gp_glove.h"

const char *const gg_fault_names[GG_F_COUNT] = { "drop",       "dup",      "reorder",
                                                 "flip",       "truncate", "garbage",
                                                 "wrong-hash", "stall",    "unknown" };

void gg_stream_init(gg_stream *s, const gg_stream_config *cfg, gg_motion *motion, FILE *truth) {
  memset(s, 0, sizeof *s);
  s->cfg = *cfg;
  s->motion = motion;
  s->truth = truth;
  gg_rng_seed(&s->rng, cfg->seed ^ 0x6661756C74730000ull);
  do {
    s->foreign_hash = (uint32_t)gg_rng_u64(&s->rng);
  } while (s->foreign_hash == GP_SPEC_HASH || s->foreign_hash == cfg->spec_hash);
  s->streaming = 1;
  s->cal_state = GP_CAL_DEFAULTS;
  for (int i = 0; i < GG_CHANNELS; i++) s->cal_max[i] = GG_ADC_MAX;
}

static size_t put_sample(const gp_sample *x, uint32_t hash, uint8_t *out) {
  return gp_glove_sample_encode(x, hash, out, GP_MAX_WIRE);
}

static size_t put_info(const gg_stream *s, uint32_t announced, uint8_t *out) {
  gp_info info = gp_default_glove_info();
  info.spec_hash = announced;
  memcpy(info.uid, s->cfg.uid, sizeof info.uid);
  info.hand = s->cfg.hand;
  info.n_channels = GG_CHANNELS;
  gp_glove_info_set_rate(&info, s->cfg.rate_hz);
  info.baud = s->cfg.baud;
  info.cal_state = s->cal_state;
  memcpy(info.cal_min, s->cal_min, sizeof info.cal_min);
  memcpy(info.cal_max, s->cal_max, sizeof info.cal_max);
  return gp_glove_info_encode(&info, out, GP_MAX_WIRE);
}

/* An INFO sent, as the decoder will count it. */
static size_t info_sent(gg_stream *s, uint8_t *out) {
  size_t n = put_info(s, s->cfg.spec_hash, out);
  s->infos++;
  if (s->cfg.spec_hash == GP_SPEC_HASH)
    s->expect.frames++;
  else
    s->expect.spec_mismatch++;
  return n;
}

size_t gg_stream_info(gg_stream *s, uint8_t *out) {
  size_t n = info_sent(s, out);
  s->expect.bytes += n;
  return n;
}

static void truth_line(gg_stream *s, const gp_sample *x) {
  s->samples_intact++;
  if (!s->truth) return;
  fprintf(s->truth, "sample %u %u", x->seq, x->t_us);
  for (int i = 0; i < GG_CHANNELS; i++) fprintf(s->truth, " %u", x->ch[i]);
  fputc('\n', s->truth);
}

/* An intact, in-order SAMPLE: the decoder now counts every loss before it. */
static size_t put_intact(gg_stream *s, const gp_sample *x, uint8_t *out) {
  size_t n = put_sample(x, s->cfg.spec_hash, out);
  if (s->cfg.spec_hash != GP_SPEC_HASH) {
    s->expect.spec_mismatch++;
    return n;
  }
  s->expect.frames++;
  s->expect.lost += s->lost_pending;
  s->lost_pending = 0;
  truth_line(s, x);
  return n;
}

/* 1..3 distinct bits of payload+CRC, never the type byte, and never a
 * pattern that the CRC would pass under our hash or the announced one. */
static size_t put_flipped(gg_stream *s, const gp_sample *x, uint8_t *out) {
  uint8_t raw[GP_MAX_FRAME], orig[GP_MAX_FRAME];
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SAMPLE;
  m.u.sample = *x;
  size_t len = gp_frame_pack(&m, GP_SPEC_HASH, orig, sizeof orig), n;
  for (;;) {
    uint32_t bits = gg_rng_range(&s->rng, 1, 3), pos[3], crc;
    memcpy(raw, orig, len);
    for (uint32_t i = 0; i < bits; i++) {
      uint32_t p;
      int again;
      do {
        p = gg_rng_range(&s->rng, 8, (uint32_t)(len * 8 - 1));
        again = 0;
        for (uint32_t j = 0; j < i; j++) again |= pos[j] == p;
      } while (again);
      pos[i] = p;
      raw[p / 8] ^= (uint8_t)(1u << (p % 8));
    }
    crc = (uint32_t)raw[len - 4] | (uint32_t)raw[len - 3] << 8 | (uint32_t)raw[len - 2] << 16 |
          (uint32_t)raw[len - 1] << 24;
    if (crc == gp_frame_crc(GP_SPEC_HASH, raw, len - 4)) continue;
    if (s->foreign_announced && crc == gp_frame_crc(s->foreign_hash, raw, len - 4)) continue;
    break;
  }
  n = gp_cobs_encode(raw, len, out, GP_MAX_WIRE - 1);
  out[n++] = 0;
  return n;
}

static size_t put_truncated(gg_stream *s, const gp_sample *x, uint8_t *out) {
  size_t wl = put_sample(x, GP_SPEC_HASH, out);
  size_t keep = gg_rng_range(&s->rng, 1, (uint32_t)(wl - 2));
  out[keep] = 0;
  return keep + 1;
}

static size_t put_garbage(gg_stream *s, uint8_t *out) {
  size_t n = gg_rng_range(&s->rng, GP_MAX_WIRE + 1, 4 * GP_MAX_WIRE);
  for (size_t i = 0; i < n; i++) out[i] = (uint8_t)gg_rng_range(&s->rng, 1, 255);
  out[n] = 0;
  return n + 1;
}

static size_t put_unknown(gg_stream *s, uint8_t *out) {
  uint8_t raw[GP_MAX_FRAME];
  uint32_t type, crc;
  size_t plen, n;
  do {
    type = gg_rng_range(&s->rng, 0, 255);
  } while (gp_msg_find((uint8_t)type) != NULL);
  plen = gg_rng_range(&s->rng, 0, GP_MAX_PAYLOAD);
  raw[0] = (uint8_t)type;
  for (size_t i = 0; i < plen; i++) raw[1 + i] = (uint8_t)gg_rng_u64(&s->rng);
  crc = gp_frame_crc(GP_SPEC_HASH, raw, 1 + plen);
  for (int i = 0; i < 4; i++) raw[1 + plen + (size_t)i] = (uint8_t)(crc >> (8 * i));
  n = gp_cobs_encode(raw, 1 + plen + 4, out, GP_MAX_WIRE - 1);
  out[n++] = 0;
  return n;
}

static int info_due(const gg_stream *s) {
  if (s->slot == 0) return 1;
  return floor((double)s->slot / s->cfg.rate_hz) != floor((double)(s->slot - 1) / s->cfg.rate_hz);
}

/* Faults stay off the first slot (the decoder has no sequence yet) and the
 * last two (a loss is only counted when a later frame arrives). A reorder
 * also stays off the slot before them: its frame would go out after the
 * second-to-last one, faulting that slot too. */
static int pick_fault(gg_stream *s) {
  double u, acc = 0;
  int last = s->cfg.count != UINT64_MAX;
  if (s->force_intact || s->slot == 0) return -1;
  if (last && s->slot + 2 >= s->cfg.count) return -1;
  u = gg_rng_unit(&s->rng);
  for (int f = 0; f < GG_F_COUNT; f++) {
    acc += s->cfg.rates[f];
    if (u < acc) return f == GG_F_REORDER && last && s->slot + 3 >= s->cfg.count ? -1 : f;
  }
  return -1;
}

/* The SAMPLE of this slot, as the motion makes it, with the flags a glove
 * sets. The motion runs every streaming slot, stalled or not, so a fault
 * never changes the motion that follows. */
static gp_sample slot_sample(gg_stream *s, double t_s) {
  uint16_t ch[GG_CHANNELS];
  gg_motion_eval(s->motion, t_s, ch);
  memcpy(s->last_ch, ch, sizeof s->last_ch);
  gp_sample x = gp_glove_sample(s->seq, gp_glove_time_us(t_s), ch);
  if (s->cal_state == GP_CAL_VALID) x.flags |= GP_SAMPLE_F_CALIBRATED;
  for (int i = 0; i < GG_CHANNELS; i++)
    if (ch[i] == 0 || ch[i] == GG_ADC_MAX) x.flags |= GP_SAMPLE_F_CLIPPED;
  /* Like the firmware, the first SAMPLE says the glove has just started. */
  if (s->slot == 0) x.flags |= GP_SAMPLE_F_START;
  return x;
}

/* A stall starts: the device keeps counting through the gap; nothing at
 * all is sent, in this slot or the next k - 1. */
static void start_stall(gg_stream *s) {
  uint64_t k = gg_rng_range(&s->rng, s->cfg.stall_min, s->cfg.stall_max);
  if (s->cfg.count != UINT64_MAX && k > s->cfg.count - 2 - s->slot) k = s->cfg.count - 2 - s->slot;
  s->injected[GG_F_STALL]++;
  s->stall_frames += k;
  s->lost_pending += k;
  s->stall_left = k - 1;
}

/* The SAMPLE out intact; then a reordered one held back arrives late, after
 * the newer frame it was swapped with. */
static size_t put_in_turn(gg_stream *s, const gp_sample *x, uint8_t *out) {
  size_t n = put_intact(s, x, out);
  if (s->held && s->force_intact) {
    memcpy(out + n, s->held_wire, s->held_len);
    n += s->held_len;
    s->expect.frames++;
    truth_line(s, &s->held_sample);
    s->held = 0;
    s->force_intact = 0;
  }
  return n;
}

/* The slot's SAMPLE with a fault applied (or none: fault < 0), and what the
 * decoder will count for it. */
static size_t put_faulted(gg_stream *s, int fault, const gp_sample *x, uint8_t *out) {
  size_t n = 0;
  switch (fault) {
  case GG_F_DROP:
    s->lost_pending++;
    break;
  case GG_F_DUP:
    n += put_intact(s, x, out + n);
    n += put_sample(x, s->cfg.spec_hash, out + n);
    s->expect.duplicates++;
    break;
  case GG_F_REORDER:
    s->held_len = put_sample(x, s->cfg.spec_hash, s->held_wire);
    s->held_sample = *x;
    s->held = 1;
    s->force_intact = 1;
    s->expect.reordered++;
    break;
  case GG_F_FLIP:
    n += put_flipped(s, x, out + n);
    s->expect.crc_errors++;
    s->lost_pending++;
    break;
  case GG_F_TRUNCATE:
    n += put_truncated(s, x, out + n);
    s->expect.framing_errors++;
    s->lost_pending++;
    break;
  case GG_F_GARBAGE:
    n += put_garbage(s, out + n);
    s->expect.oversize++;
    n += put_intact(s, x, out + n);
    break;
  case GG_F_WRONG_HASH:
    if (!s->foreign_announced) {
      n += put_info(s, s->foreign_hash, out + n);
      s->foreign_announced = 1;
      s->expect.spec_mismatch++;
    }
    n += put_sample(x, s->foreign_hash, out + n);
    s->expect.spec_mismatch++;
    s->lost_pending++;
    break;
  case GG_F_UNKNOWN:
    n += put_unknown(s, out + n);
    s->expect.unknown_type++;
    n += put_intact(s, x, out + n);
    break;
  default:
    n += put_in_turn(s, x, out + n);
    break;
  }
  return n;
}

size_t gg_stream_next(gg_stream *s, uint8_t *out, int *done) {
  size_t n = 0;
  double t_s = (double)s->slot / s->cfg.rate_hz;
  *done = 0;
  if (s->cfg.count != UINT64_MAX && s->slot >= s->cfg.count) {
    *done = 1;
    return 0;
  }
  if (!s->streaming) {
    /* STREAM_OFF: time passes, INFO keeps the host seeing the glove, and
     * the sequence waits, as the firmware's does. */
    n = info_due(s) ? info_sent(s, out) : 0;
    s->expect.bytes += n;
    s->slot++;
    return n;
  }
  gp_sample x = slot_sample(s, t_s);
  int fault = s->stall_left ? -1 : pick_fault(s);
  if (s->stall_left)
    s->stall_left--;
  else if (fault == GG_F_STALL)
    start_stall(s);
  else {
    if (info_due(s)) n += info_sent(s, out + n);
    if (fault >= 0) s->injected[fault]++;
    n += put_faulted(s, fault, &x, out + n);
    s->expect.bytes += n;
  }
  s->slot++;
  s->seq++;
  return n;
}

size_t gg_stream_finish(gg_stream *s, uint8_t *out) {
  size_t n = 0;
  if (s->held) {
    /* Stopped before the frame it was to swap with: it goes out in order,
     * so the reorder never happened. */
    n = put_intact(s, &s->held_sample, out);
    s->expect.reordered--;
    s->injected[GG_F_REORDER]--;
    s->held = 0;
    s->force_intact = 0;
    s->expect.bytes += n;
  }
  /* Losses with no later frame to reveal them are never counted, and slots
   * a stall had yet to swallow never happened. */
  s->lost_pending = 0;
  s->stall_frames -= s->stall_left;
  s->stall_left = 0;
  return n;
}

void gg_stream_write_expect(const gg_stream *s, FILE *f) {
  const gg_expect *e = &s->expect;
  fprintf(f,
          "# expected decoder counters\n"
          "frames=%llu\ncrc_errors=%llu\nframing_errors=%llu\noversize=%llu\n"
          "unknown_type=%llu\nspec_mismatch=%llu\nlost=%llu\nduplicates=%llu\n"
          "reordered=%llu\nseq_restarts=%llu\nbytes=%llu\n",
          (unsigned long long)e->frames, (unsigned long long)e->crc_errors,
          (unsigned long long)e->framing_errors, (unsigned long long)e->oversize,
          (unsigned long long)e->unknown_type, (unsigned long long)e->spec_mismatch,
          (unsigned long long)e->lost, (unsigned long long)e->duplicates,
          (unsigned long long)e->reordered, (unsigned long long)e->seq_restarts,
          (unsigned long long)e->bytes);
  fprintf(f, "# what was injected\n");
  for (int i = 0; i < GG_F_COUNT; i++)
    fprintf(f, "injected.%s=%llu\n", gg_fault_names[i], (unsigned long long)s->injected[i]);
  fprintf(f, "injected.stall_frames=%llu\nslots=%llu\nsamples_intact=%llu\ninfos=%llu\n",
          (unsigned long long)s->stall_frames, (unsigned long long)s->slot,
          (unsigned long long)s->samples_intact, (unsigned long long)s->infos);
}

uint8_t *gg_sample_burst(long frames, size_t *len) {
  size_t cap = (size_t)(frames > 0 ? frames : 1) * GP_MAX_WIRE;
  uint8_t *stream = malloc(cap);
  *len = 0;
  if (stream == NULL) return NULL;
  uint32_t r = 1; /* a linear congruential sequence: fixed, no seed */
  for (long i = 0; i < frames; i++) {
    uint16_t ch[GP_SAMPLE_CH_COUNT];
    for (unsigned c = 0; c < GP_SAMPLE_CH_COUNT; c++) {
      r = r * 1664525u + 1013904223u;
      ch[c] = (uint16_t)(r >> 20);
    }
    gp_sample x = gp_glove_sample((uint16_t)i, (uint32_t)(i * 4000), ch);
    *len += gp_glove_sample_encode(&x, GP_SPEC_HASH, stream + *len, cap - *len);
  }
  return stream;
}
