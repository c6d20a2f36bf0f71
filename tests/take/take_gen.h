/* Takes made up for the take tests: a glove's INFO and SAMPLEs encoded by
 * the protocol's glove encoder (gp_glove, as glove-gen does) and written
 * as .mrec chunks, with each SAMPLE's read time kept, so that a test can
 * build what an operation should give from the samples themselves. */
#ifndef TAKE_GEN_H
#define TAKE_GEN_H

#include <stddef.h>
#include <stdint.h>

#include "gp_glove.h"

enum { GEN_MAX = 2000 };

typedef struct gen_take {
  gp_info info;    /* its calibration, announced at 0 s */
  gp_info info2;   /* announced at info2_at (gen_init: the same as info) */
  double info2_at; /* s; a second INFO, 0 for none */
  uint64_t scene;  /* the header's scene hash */
  size_t n;        /* samples */
  double t0, dt;   /* sample i is due at t0 + i dt */
  uint16_t ch[GEN_MAX][5];
  uint64_t read_ns[GEN_MAX]; /* filled by gen_write: when sample i is read */
} gen_take;

/* A calibrated glove: every channel lo..hi, 100 Hz. */
void gen_init(gen_take *g, uint16_t lo, uint16_t hi, uint64_t scene);
/* Writes g to path: one chunk per frame, except every 50th SAMPLE (from
 * the 8th), cut in two chunks 4 ms apart (read at the second). */
void gen_write(gen_take *g, const char *path);
/* The host's value of raw counts r in g's calibration, and back. */
double gen_value(const gen_take *g, int k, uint16_t r);
uint16_t gen_raw(const gen_take *g, int k, double v);
/* The newest sample of g read at or before t_ns, or -1. */
long gen_at(const gen_take *g, uint64_t t_ns);

#endif
