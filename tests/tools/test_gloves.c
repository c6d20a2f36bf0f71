/* Several gloves from one glove-gen: each output is its own stream, with its
 * own uid, hand and faults, and its own truth that the decoder
 * matches counter for counter. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "gp.h"
#include "tools_proc.h"
#include "tools_truth.h"

#define N_GLOVES 3

static void tools_gloves_each_output_is_its_own_glove(void **state) {
  char *dir = tt_tmpdir();
  char out[N_GLOVES][1100], truth[N_GLOVES][1100];
  uint32_t uid0[N_GLOVES];
  uint8_t hand[N_GLOVES];
  (void)state;
  assert_non_null(dir);
  for (int k = 0; k < N_GLOVES; k++) {
    char name[32];
    snprintf(name, sizeof name, "g%d.bin", k);
    snprintf(out[k], sizeof out[k], "file:%s", tt_path(dir, name));
    snprintf(name, sizeof name, "g%d.truth", k);
    snprintf(truth[k], sizeof truth[k], "%s", tt_path(dir, name));
  }
  {
    /* Two hands given, the third by default (right, left, right, ...). */
    const char *argv[] = { tt_glove_gen, "--fast",  "-q",     "-n",      "3000",   "--faults",
                           "0.05",       "--seed",  "9",      "--uid",   "0x1000", "--hand",
                           "left",       "--hand",  "left",   "-o",      out[0],   "-o",
                           out[1],       "-o",      out[2],   "--truth", truth[0], "--truth",
                           truth[1],     "--truth", truth[2], NULL };
    assert_int_equal(tt_run(argv, NULL, tt_path(dir, "gen.err"), 60), 0);
  }
  for (int k = 0; k < N_GLOVES; k++) {
    size_t len;
    char *stream = tt_read_file(out[k] + 5, &len);
    char *want = tt_read_file(truth[k], NULL);
    gp_decoder *d = malloc(sizeof *d);
    int have_info = 0, have_sample = 0;
    assert_non_null(stream);
    assert_non_null(want);
    assert_non_null(d);
    gp_decoder_init(d, GP_SPEC_HASH);
    for (size_t off = 0; off < len;) {
      gp_msg m;
      gp_event ev;
      off += gp_decoder_feed(d, (const uint8_t *)stream + off, len - off, &m, &ev);
      if (ev == GP_EV_FRAME && m.type == GP_INFO && !have_info) {
        uid0[k] = m.u.info.uid[0];
        hand[k] = m.u.info.hand;
        have_info = 1;
      }
      if (ev == GP_EV_FRAME && m.type == GP_SAMPLE) have_sample = 1;
    }
    assert_true(have_info && have_sample);
    {
      const uint64_t got[TT_N_COUNTERS] = {
        d->c.frames,       d->c.crc_errors,    d->c.framing_errors, d->c.oversize,
        d->c.unknown_type, d->c.spec_mismatch, d->c.lost,           d->c.duplicates,
        d->c.reordered,    d->c.seq_restarts,  d->c.bytes
      };
      for (size_t i = 0; i < TT_N_COUNTERS; i++)
        if ((long long)got[i] != tt_kv(want, tt_counter_keys[i]))
          fail_msg("glove %d %s: decoder %llu, truth %lld", k, tt_counter_keys[i],
                   (unsigned long long)got[i], tt_kv(want, tt_counter_keys[i]));
      assert_true(d->c.lost > 0 && d->c.crc_errors > 0);
    }
    free(d);
    free(stream);
    free(want);
  }
  for (int k = 0; k < N_GLOVES; k++) assert_int_equal(uid0[k], 0x1000u + (uint32_t)k);
  assert_int_equal(hand[0], GP_HAND_LEFT);
  assert_int_equal(hand[1], GP_HAND_LEFT);
  assert_int_equal(hand[2], GP_HAND_RIGHT);
  /* Each glove has its own seed: their faults, so their bytes, differ. */
  {
    size_t la, lb;
    char *a = tt_read_file(out[0] + 5, &la), *b = tt_read_file(out[1] + 5, &lb);
    assert_true(la != lb || memcmp(a, b, la) != 0);
    free(a);
    free(b);
  }
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(tools_gloves_each_output_is_its_own_glove),
  };
  tt_take_args(argc, argv);
  return cmocka_run_group_tests(tests, NULL, NULL);
}
