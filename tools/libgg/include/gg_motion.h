/* Motion for glove-gen: what the five strings do over time, from a small
 * script (tools/README.md, "Motion scripts") or a built-in default. */
#ifndef GG_MOTION_H
#define GG_MOTION_H

#include <stddef.h>
#include <stdint.h>

#include "gg_rng.h"
#include "gp_messages.h"

/* The channel count and full scale of SAMPLE's ch field (protocol/messages.def). */
#define GG_CHANNELS ((int)GP_SAMPLE_CH_COUNT)
#define GG_ADC_MAX  ((int)GP_SAMPLE_CH_MAX)

typedef enum gg_shape {
  GG_CONST,
  GG_KEYS,  /* keyframes with easing */
  GG_SINE,  /* sine, optionally sweeping its frequency */
  GG_STEP,  /* a step, or a square wave */
  GG_WALK,  /* random walk */
  GG_TRACK, /* a recorded track (CSV or .mrec) */
} gg_shape;

typedef enum gg_ease {
  GG_EASE_LINEAR,
  GG_EASE_HOLD,
  GG_EASE_IN,
  GG_EASE_OUT,
  GG_EASE_INOUT,
  GG_EASE_SINE
} gg_ease;

typedef struct gg_key {
  double t, v;
  gg_ease ease; /* how the segment arriving at this key moves */
} gg_key;

typedef struct gg_track {
  size_t n;
  double *t; /* seconds from the track's start */
  double *v; /* n * GG_CHANNELS values, 0..1 */
  int refs;
} gg_track;

typedef struct gg_gen {
  gg_shape shape;
  double value; /* CONST */
  gg_key *keys; /* KEYS */
  size_t n_keys;
  int loop;                                        /* KEYS and TRACK: repeat instead of holding */
  double mid, amp, freq, freq_end, sweep_s, phase; /* SINE */
  double from, to, at, period, duty;               /* STEP */
  double start, sigma, lo, hi, walk_v;             /* WALK */
  gg_track *track;                                 /* TRACK */
  int column;                                      /* TRACK: which channel of the track */
} gg_gen;

typedef struct gg_motion {
  gg_gen ch[GG_CHANNELS];
  double duration_s; /* from the script's `duration`; 0: none */
  gg_rng rng;        /* WALK steps */
  double last_t;
  int started;
} gg_motion;

/* The default: each finger a slow sine of its own frequency and phase. */
void gg_motion_default(gg_motion *m, uint64_t seed);

/* Loads a script. 0, or -1 with "FILE:LINE:COL: what" in err. */
int gg_motion_load(gg_motion *m, const char *path, uint64_t seed, char *err, size_t errcap);

/* The channels at stream time t_s (seconds), in ADC counts 0..GG_ADC_MAX.
 * Call with non-decreasing t: the random walk steps from the last call. */
void gg_motion_eval(gg_motion *m, double t_s, uint16_t out[GG_CHANNELS]);

void gg_motion_free(gg_motion *m);

#endif
