/* The streaming decoder. Bytes go in one at a time or a buffer at a time; a
 * frame ends at each 0x00. Every frame ends in exactly one event, and every
 * event has its counter, so a tester can account for each byte sent. The
 * rules, in order, are SPEC.md's "Receiver rules". Like Betaflight's MSP
 * parser it never blocks and never allocates; unlike a state machine that
 * reads a length field, it cannot be led astray by one: COBS makes the
 * delimiter the only thing that ends a frame. */
#include "gp.h"

void gp_decoder_init(gp_decoder *d, uint32_t spec_hash) {
  gp_decoder zero = { 0 };
  *d = zero;
  d->spec_hash = spec_hash;
}

void gp_decoder_new_link(gp_decoder *d) {
  d->new_link = 1;
}

const char *gp_event_name(gp_event ev) {
  switch (ev) {
  case GP_EV_NONE:
    return "none";
  case GP_EV_FRAME:
    return "frame";
  case GP_EV_FRAME_LATE:
    return "late frame";
  case GP_EV_DUPLICATE:
    return "duplicate";
  case GP_EV_CRC_ERROR:
    return "crc error";
  case GP_EV_FRAMING_ERROR:
    return "framing error";
  case GP_EV_OVERSIZE:
    return "oversize frame";
  case GP_EV_UNKNOWN_TYPE:
    return "unknown type";
  case GP_EV_SPEC_MISMATCH:
    return "spec mismatch";
  }
  return "?";
}

static uint32_t load_le32(const uint8_t *p) {
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static int crc_ok(uint32_t hash, const uint8_t *raw, size_t len) {
  return gp_frame_crc(hash, raw, len - GP_CRC_LEN) == load_le32(raw + len - GP_CRC_LEN);
}

/* A frame from a glove built from another definition is reported as a spec
 * mismatch whatever its length, so these checks come before the length rule
 * (SPEC.md, "Receiver rules" 4 and 5). INFO is read whatever spec the sender
 * was built from: its CRC does not cover the spec hash, and its first two
 * fields never move (SPEC.md, "Versioning"). */
static void announce_peer(gp_decoder *d, uint8_t proto_major, uint32_t announced, gp_msg *out) {
  d->peer_hash = announced;
  d->peer_known = 1;
  gp_msg zero = { 0 };
  *out = zero;
  out->type = GP_INFO;
  out->u.info.proto_major = proto_major;
  out->u.info.spec_hash = announced;
}

static int foreign_info(gp_decoder *d, const uint8_t *raw, size_t len, gp_msg *out) {
  const size_t frozen = 1u + 1u + 4u + GP_CRC_LEN;
  if (raw[0] != GP_UNSEEDED_TYPE || len < frozen || !crc_ok(0, raw, len)) return 0;
  uint32_t announced = load_le32(raw + 2);
  if (announced == d->spec_hash) return 0;
  /* Another layout: only the frozen prefix means anything, unless it has
   * our INFO's length. */
  announce_peer(d, raw[1], announced, out);
  if (len == 1u + GP_INFO_LEN + GP_CRC_LEN) gp_payload_unpack(raw[0], raw + 1, GP_INFO_LEN, out);
  return 1;
}

/* --- runs past GP_MAX_WIRE (rule 2) --------------------------------------- */

static void long_raw(gp_long_frame *l, uint8_t x) {
  if (l->n < sizeof l->head) l->head[l->n] = x;
  uint8_t *slot = &l->tail[l->n % GP_CRC_LEN];
  if (l->n >= GP_CRC_LEN) {
    /* The byte four back leaves the tail: it is not part of the CRC. */
    l->crc_unseeded = gp_crc32c(l->crc_unseeded, slot, 1);
    l->crc_peer = gp_crc32c(l->crc_peer, slot, 1);
  }
  *slot = x;
  l->n++;
}

static void long_byte(gp_long_frame *l, uint8_t b) {
  if (l->left == 0) { /* a COBS code byte */
    if (l->zero_due) long_raw(l, 0);
    l->left = (uint8_t)(b - 1u);
    l->zero_due = b != 0xFFu;
    return;
  }
  long_raw(l, b);
  l->left--;
}

/* Called when the buffer is full and one more byte came: follow the run if
 * it may still be an INFO or, once a peer is known, any frame of the peer's;
 * anything else is oversize at once. */
static int long_start(gp_decoder *d) {
  int info = d->buf[0] >= 2u && d->buf[1] == GP_UNSEEDED_TYPE;
  if (!info && !d->peer_known) return 0;
  gp_long_frame zero = { 0 };
  d->lf = zero;
  d->lf.active = 1;
  uint8_t seed[4] = { (uint8_t)d->peer_hash, (uint8_t)(d->peer_hash >> 8),
                      (uint8_t)(d->peer_hash >> 16), (uint8_t)(d->peer_hash >> 24) };
  d->lf.crc_peer = gp_crc32c(0, seed, sizeof seed);
  for (size_t i = 0; i < d->len; i++) long_byte(&d->lf, d->buf[i]);
  d->len = 0;
  return 1;
}

static gp_event long_end(gp_decoder *d, gp_msg *out) {
  gp_long_frame *l = &d->lf;
  l->active = 0;
  if (l->left != 0) return GP_EV_OVERSIZE; /* a code byte ran past the end */
  uint32_t got = 0;
  for (unsigned k = 0; k < GP_CRC_LEN; k++)
    got |= (uint32_t)l->tail[(l->n + k) % GP_CRC_LEN] << (8u * k);
  if (l->head[0] == GP_UNSEEDED_TYPE) {
    uint32_t announced = load_le32(l->head + 2);
    if (l->crc_unseeded == got && announced != d->spec_hash) {
      announce_peer(d, l->head[1], announced, out);
      return GP_EV_SPEC_MISMATCH;
    }
  } else if (d->peer_known && l->crc_peer == got) {
    return GP_EV_SPEC_MISMATCH;
  }
  return GP_EV_OVERSIZE;
}

/* Sequence accounting over a window of GP_SEQ_WINDOW numbers behind the
 * highest seen: bit i of seq_seen stands for seq_high - i. */
static gp_event sample_seq(gp_decoder *d, const gp_sample *s) {
  uint16_t seq = s->seq;
  int16_t delta = (int16_t)(uint16_t)(seq - d->seq_high);
  int start = (s->flags & GP_SAMPLE_F_START) != 0;
  /* A new link repeats nothing from the old one: a number at or behind
   * the high is the glove counting again. */
  int relinked = d->new_link && delta <= 0;
  d->new_link = 0;
  if (d->have_seq && (start || relinked)) {
    /* The glove's first SAMPLE since it booted. The one frame that looks the
     * same is a copy of the start frame already taken as high. */
    if (!relinked && delta == 0 && d->seq_high_start && s->t_us == d->seq_high_t_us) {
      d->c.duplicates++;
      return GP_EV_DUPLICATE;
    }
    d->c.seq_restarts++;
  } else if (d->have_seq) {
    if (delta > 0) {
      d->c.lost += (uint32_t)(delta - 1);
      /* A shift by the window's width or more is undefined: the window is
       * then simply the new high alone. */
      d->seq_seen = (unsigned)delta >= GP_SEQ_WINDOW ? 1u : (d->seq_seen << delta) | 1u;
      d->seq_high = seq;
      d->seq_high_start = 0;
      d->seq_high_t_us = s->t_us;
      return GP_EV_FRAME;
    }
    unsigned back = (unsigned)(-(int)delta);
    if (back < GP_SEQ_WINDOW) {
      uint64_t bit = (uint64_t)1 << back;
      if (d->seq_seen & bit) {
        d->c.duplicates++;
        return GP_EV_DUPLICATE;
      }
      d->seq_seen |= bit;
      d->c.reordered++;
      if (d->c.lost) d->c.lost--; /* it was counted lost when the gap opened */
      return GP_EV_FRAME_LATE;
    }
    /* Too far back for reordering, without the start flag (its frame was
     * lost): the device started counting again. */
    d->c.seq_restarts++;
  }
  d->have_seq = 1;
  d->seq_high = seq;
  d->seq_seen = 1;
  d->seq_high_start = (uint8_t)start;
  d->seq_high_t_us = s->t_us;
  return GP_EV_FRAME;
}

/* SPEC.md, "Receiver rules", 3 to 7 in order. */
static gp_event frame_end(gp_decoder *d, gp_msg *out) {
  int n = gp_cobs_decode(d->buf, d->len, d->raw, sizeof d->raw);
  if (n < (int)(1u + GP_CRC_LEN)) return GP_EV_FRAMING_ERROR;
  size_t len = (size_t)n;
  const uint8_t *raw = d->raw;
  if (foreign_info(d, raw, len, out)) return GP_EV_SPEC_MISMATCH;
  int ours = crc_ok(d->spec_hash, raw, len);
  if (!ours && d->peer_known && crc_ok(d->peer_hash, raw, len)) return GP_EV_SPEC_MISMATCH;
  const gp_msg_desc *desc = gp_msg_find(raw[0]);
  if (len > GP_MAX_FRAME || (desc && len != 1u + desc->len + GP_CRC_LEN))
    return GP_EV_FRAMING_ERROR;
  if (!ours) return GP_EV_CRC_ERROR;
  if (!desc) return GP_EV_UNKNOWN_TYPE;
  gp_payload_unpack(raw[0], raw + 1, desc->len, out);
  if (raw[0] == GP_SAMPLE) return sample_seq(d, &out->u.sample);
  return GP_EV_FRAME;
}

static void count(gp_decoder *d, gp_event ev) {
  switch (ev) {
  case GP_EV_FRAME:
  case GP_EV_FRAME_LATE:
    d->c.frames++;
    break;
  case GP_EV_CRC_ERROR:
    d->c.crc_errors++;
    break;
  case GP_EV_FRAMING_ERROR:
    d->c.framing_errors++;
    break;
  case GP_EV_OVERSIZE:
    d->c.oversize++;
    break;
  case GP_EV_UNKNOWN_TYPE:
    d->c.unknown_type++;
    break;
  case GP_EV_SPEC_MISMATCH:
    d->c.spec_mismatch++;
    break;
  case GP_EV_NONE:
  case GP_EV_DUPLICATE: /* counted where detected */
    break;
  }
}

size_t gp_decoder_feed(gp_decoder *d, const uint8_t *data, size_t n, gp_msg *out, gp_event *ev) {
  *ev = GP_EV_NONE;
  for (size_t i = 0; i < n; i++) {
    uint8_t b = data[i];
    d->c.bytes++;
    if (b != 0) {
      if (d->lf.active) {
        long_byte(&d->lf, b);
        continue;
      }
      if (d->overflow) continue;
      if (d->len == sizeof d->buf) {
        if (long_start(d)) {
          long_byte(&d->lf, b);
          continue;
        }
        /* Report an oversize frame once, as soon as it is certain, then
         * drop its bytes up to the next delimiter. */
        d->overflow = 1;
        d->len = 0;
        *ev = GP_EV_OVERSIZE;
        count(d, *ev);
        return i + 1;
      }
      d->buf[d->len++] = b;
      continue;
    }
    if (d->lf.active) {
      *ev = long_end(d, out);
      d->in_step = 1;
      count(d, *ev);
      return i + 1;
    }
    if (d->overflow) {
      d->overflow = 0;
      d->in_step = 1;
      continue;
    }
    if (d->len == 0) {
      d->in_step = 1;
      continue; /* back-to-back delimiters: idle or resync */
    }
    *ev = frame_end(d, out);
    d->len = 0;
    if (!d->in_step) {
      d->in_step = 1;
      /* Before its first 0x00 a receiver may have joined a frame mid-way:
       * a tail that is no frame is not an error (SPEC.md, rule 1). */
      if (*ev == GP_EV_FRAMING_ERROR || *ev == GP_EV_CRC_ERROR) *ev = GP_EV_NONE;
    }
    count(d, *ev);
    return i + 1;
  }
  return n;
}
