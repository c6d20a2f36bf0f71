/* The shared body of the pty and TCP round trips: glove-gen serves a link,
 * glove-dump reads it, and both the frames and the counters must equal the
 * truth of the same stream written to a file. */
#ifndef TOOLS_ROUNDTRIP_H
#define TOOLS_ROUNDTRIP_H

#include "tools_proc.h"
#include "tools_truth.h"

/* Compares glove-dump's CSV rows with the truth's intact samples. */
static inline void tt_check_csv(const char *csv, const char *truth) {
  size_t n_truth, row = 0;
  tt_sample *want = tt_truth_samples(truth, &n_truth);
  const char *p = strchr(csv, '\n');
  assert_non_null(want);
  assert_non_null(p);
  assert_true(n_truth > 100);
  assert_int_equal(strncmp(csv, "seq,t_us,ch0,ch1,ch2,ch3,ch4,flags,late", 39), 0);
  for (p = p + 1; *p; p = strchr(p, '\n') + 1) {
    unsigned u[9];
    assert_int_equal(tt_parse_uints(p, ',', u, 9), 9);
    assert_true(row < n_truth);
    assert_int_equal(u[0], want[row].seq);
    assert_int_equal(u[1], want[row].t_us);
    assert_memory_equal(u + 2, want[row].ch, sizeof want[row].ch);
    row++;
  }
  assert_int_equal(row, n_truth);
  free(want);
}

static inline void tt_check_counters(const char *counters, const char *truth) {
  for (size_t k = 0; k < TT_N_COUNTERS; k++) {
    if (tt_kv(counters, tt_counter_keys[k]) != tt_kv(truth, tt_counter_keys[k]))
      fail_msg("%s: glove-dump %lld, truth %lld", tt_counter_keys[k],
               tt_kv(counters, tt_counter_keys[k]), tt_kv(truth, tt_counter_keys[k]));
  }
}

#endif
