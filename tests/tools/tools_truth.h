/* Reading glove-gen's truth file in the tests. */
#ifndef TOOLS_TRUTH_H
#define TOOLS_TRUTH_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct tt_sample {
  uint32_t seq, t_us, ch[5];
} tt_sample;

/* The counter keys, in gp_counters order. */
static const char *const tt_counter_keys[] = {
    "frames", "crc_errors", "framing_errors", "oversize", "unknown_type", "spec_mismatch",
    "lost", "duplicates", "reordered", "seq_restarts", "bytes"};
#define TT_N_COUNTERS (sizeof tt_counter_keys / sizeof tt_counter_keys[0])

/* The "sample SEQ T_US CH0..CH4" lines of a truth file, in order. */
static inline tt_sample *tt_truth_samples(const char *text, size_t *n) {
  size_t cap = 1024;
  tt_sample *v = malloc(cap * sizeof *v);
  *n = 0;
  for (const char *p = text; v && p && *p; p = strchr(p, '\n'), p = p ? p + 1 : NULL) {
    tt_sample s;
    if (strncmp(p, "sample ", 7) != 0) continue;
    if (sscanf(p + 7, "%u %u %u %u %u %u %u", &s.seq, &s.t_us, &s.ch[0], &s.ch[1], &s.ch[2],
               &s.ch[3], &s.ch[4]) != 7)
      continue;
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
