/* One glove's stream: frames in order, INFO at 1 Hz, and the injected faults
 * with the decoder counters they must cause (tools/README.md, "Faults"). */
#ifndef GG_STREAM_H
#define GG_STREAM_H

#include <stdint.h>
#include <stdio.h>

#include "gg_motion.h"
#include "gg_rng.h"
#include "gp.h"

typedef enum gg_fault {
  GG_F_DROP,
  GG_F_DUP,
  GG_F_REORDER,
  GG_F_FLIP,
  GG_F_TRUNCATE,
  GG_F_GARBAGE,
  GG_F_WRONG_HASH,
  GG_F_STALL,
  GG_F_UNKNOWN,
  GG_F_COUNT
} gg_fault;

/* The flag name of each fault (--drop, --dup, ...). */
extern const char *const gg_fault_names[GG_F_COUNT];

/* What the host's decoder must count for this stream, field for field like
 * gp_counters. */
typedef struct gg_expect {
  uint64_t frames, crc_errors, framing_errors, oversize, unknown_type, spec_mismatch, lost,
      duplicates, reordered, seq_restarts, bytes;
} gg_expect;

typedef struct gg_stream_config {
  double rate_hz;     /* SAMPLE frames per second */
  uint64_t count;     /* SAMPLE slots; UINT64_MAX: no end */
  uint32_t spec_hash; /* what every frame is encoded with */
  uint8_t hand;
  uint32_t uid[3];
  uint32_t baud;
  double rates[GG_F_COUNT];      /* probability per SAMPLE slot */
  uint32_t stall_min, stall_max; /* frames lost per stall */
  uint64_t seed;
} gg_stream_config;

typedef struct gg_stream {
  gg_stream_config cfg;
  gg_motion *motion; /* borrowed */
  FILE *truth;       /* intact SAMPLE lines go here as they are sent */
  gg_rng rng;        /* faults only, so motion does not depend on them */
  uint64_t slot;     /* the next SAMPLE slot: time, in frame periods */
  uint16_t seq;      /* the next SAMPLE's sequence number: slots streamed */
  int streaming;     /* SAMPLEs go out (STREAM_ON, the default); INFO always */
  uint8_t cal_state; /* GP_CAL_*, as INFO announces it */
  uint16_t cal_min[GG_CHANNELS], cal_max[GG_CHANNELS];
  uint16_t last_ch[GG_CHANNELS]; /* the newest SAMPLE's channels */
  uint64_t stall_left;
  int force_intact; /* the slot after a reorder must go out intact */
  int held;         /* a reordered SAMPLE waits to go after the next */
  uint8_t held_wire[GP_MAX_WIRE];
  size_t held_len;
  gp_sample held_sample;
  int foreign_announced; /* the decoder knows the foreign hash */
  uint32_t foreign_hash;
  uint64_t lost_pending; /* counted by the decoder once a newer SAMPLE arrives */
  gg_expect expect;
  uint64_t injected[GG_F_COUNT];
  uint64_t stall_frames;
  uint64_t infos, samples_intact;
} gg_stream;

/* Largest output of one slot: INFO, a foreign INFO, a garbage burst, and two
 * SAMPLEs (one of them sent twice). */
#define GG_SLOT_MAX (6u * GP_MAX_WIRE + 4u * GP_MAX_WIRE + 16u)

void gg_stream_init(gg_stream *s, const gg_stream_config *cfg, gg_motion *motion, FILE *truth);

/* The INFO frame this glove would send now, into out (GP_MAX_WIRE bytes),
 * counted as sent; its length. */
size_t gg_stream_info(gg_stream *s, uint8_t *out);

/* The wire bytes of the next slot into out (GG_SLOT_MAX bytes); returns how
 * many (0 in a stall or for a dropped frame). *done is set after the last
 * slot. */
size_t gg_stream_next(gg_stream *s, uint8_t *out, int *done);

/* Ends the stream early or on time: a reordered frame still held goes out
 * (returned in out) and every count is settled to what the decoder will have
 * seen. */
size_t gg_stream_finish(gg_stream *s, uint8_t *out);

/* key=value lines of the expected counters and what was injected. */
void gg_stream_write_expect(const gg_stream *s, FILE *f);

/* `frames` intact SAMPLE frames back to back, 4 ms apart, with fixed
 * pseudo-random channel values: the same bytes on every run, so the
 * decoder's cost over them (the benchmarks' figure) is repeatable. NULL
 * when memory runs out; else the caller frees it. */
uint8_t *gg_sample_burst(long frames, size_t *len);

#endif
