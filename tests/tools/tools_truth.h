/* Reading glove-gen's truth file in the tests. */
#ifndef TOOLS_TRUTH_H
#define TOOLS_TRUTH_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gp_messages.h"

typedef struct tt_sample {
  uint32_t seq, t_us, ch[GP_SAMPLE_CH_COUNT];
} tt_sample;

/* The counter keys, in gp_counters order. */
static const char *const tt_counter_keys[] = { "frames",       "crc_errors",   "framing_errors",
                                               "oversize",     "unknown_type", "spec_mismatch",
                                               "lost",         "duplicates",   "reordered",
                                               "seq_restarts", "bytes" };
#define TT_N_COUNTERS (sizeof tt_counter_keys / sizeof tt_counter_keys[0])

/* Up to n unsigned numbers from p, each followed by sep (or the line's end);
 * how many were read. Not sscanf: glibc's measures the whole remaining
 * buffer on every call, which makes a 100 000-line file quadratic. */
static inline int tt_parse_uints(const char *p, char sep, unsigned *out, int n) {
  int k = 0;
  while (k < n) {
    char *end;
    unsigned long v = strtoul(p, &end, 10);
    if (end == p) break;
    out[k++] = (unsigned)v;
    if (*end != sep) break;
    p = end + 1;
  }
  return k;
}

/* The "sample SEQ T_US CH0..CH4" lines of a truth file, in order. */
static inline tt_sample *tt_truth_samples(const char *text, size_t *n) {
  size_t cap = 1024;
  tt_sample *v = malloc(cap * sizeof *v);
  *n = 0;
  for (const char *p = text; v && p && *p; p = strchr(p, '\n'), p = p ? p + 1 : NULL) {
    tt_sample s;
    enum { N = 2 + GP_SAMPLE_CH_COUNT };
    unsigned u[N];
    if (strncmp(p, "sample ", 7) != 0) continue;
    if (tt_parse_uints(p + 7, ' ', u, N) != N) continue;
    s.seq = u[0];
    s.t_us = u[1];
    memcpy(s.ch, u + 2, sizeof s.ch);
    if (*n == cap) {
      tt_sample *nv = realloc(v, (cap *= 2) * sizeof *v);
      if (!nv) {
        free(v);
        return NULL;
      }
      v = nv;
    }
    v[(*n)++] = s;
  }
  return v;
}

#endif
