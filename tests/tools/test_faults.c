/* A 100 000-frame stream with 10 % faults of every kind: every intact frame
 * decodes, nothing corrupted is accepted, and every decoder counter equals
 * what glove-gen says it injected. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gp.h"
#include "tools_proc.h"
#include "tools_truth.h"

#define FRAMES "100000"

static char *g_dir;

static int setup(void **state) {
  (void)state;
  g_dir = tt_tmpdir();
  return g_dir ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  tt_rmdir(g_dir);
  free(g_dir);
  return 0;
}

static void generate(const char *seed, const char *out, const char *truth, const char *rec) {
  char o[1100];
  const char *argv[] = { tt_glove_gen,     "--fast", "-n",       FRAMES, "--faults", "0.10",
                         "--stall-frames", "1:20",   "--seed",   seed,   "-o",       o,
                         "--truth",        truth,    "--record", rec,    NULL };
  snprintf(o, sizeof o, "file:%s", out);
  assert_int_equal(tt_run(argv, NULL, tt_path(g_dir, "gen.err"), 120), 0);
}

static void tools_faults_every_counter_equals_what_was_injected(void **state) {
  const char *bin = strdup(tt_path(g_dir, "s.bin")), *truth_path = strdup(tt_path(g_dir, "t.txt"));
  size_t len, n_truth, n_got = 0, infos = 0;
  char *truth, *stream;
  tt_sample *want, *got;
  gp_decoder *d = malloc(sizeof *d);
  (void)state;
  generate("11", bin, truth_path, tt_path(g_dir, "s.mrec"));
  truth = tt_read_file(truth_path, NULL);
  stream = tt_read_file(bin, &len);
  assert_non_null(truth);
  assert_non_null(stream);

  /* Every kind of fault really happened, and about 10 % of slots in all. */
  {
    static const char *const kinds[] = { "drop",    "dup",        "reorder", "flip",   "truncate",
                                         "garbage", "wrong-hash", "stall",   "unknown" };
    long long total = 0;
    for (size_t i = 0; i < 9; i++) {
      char key[64];
      snprintf(key, sizeof key, "injected.%s", kinds[i]);
      assert_true(tt_kv(truth, key) > 100);
      total += tt_kv(truth, key);
    }
    assert_in_range(total, 9000, 11000);
  }

  want = tt_truth_samples(truth, &n_truth);
  assert_non_null(want);
  assert_int_equal((long long)n_truth, tt_kv(truth, "samples_intact"));
  got = malloc(n_truth * sizeof *got + sizeof *got);
  assert_non_null(got);

  gp_decoder_init(d, GP_SPEC_HASH);
  for (size_t off = 0; off < len;) {
    gp_msg m;
    gp_event ev;
    off += gp_decoder_feed(d, (const uint8_t *)stream + off, len - off, &m, &ev);
    if ((ev == GP_EV_FRAME || ev == GP_EV_FRAME_LATE) && m.type == GP_SAMPLE) {
      /* More accepted SAMPLEs than intact ones would mean a corrupted one
       * got through. */
      assert_true(n_got < n_truth);
      got[n_got].seq = m.u.sample.seq;
      got[n_got].t_us = m.u.sample.t_us;
      for (unsigned c = 0; c < GP_SAMPLE_CH_COUNT; c++) got[n_got].ch[c] = m.u.sample.ch[c];
      n_got++;
    } else if (ev == GP_EV_FRAME && m.type == GP_INFO) {
      infos++;
    }
  }
  /* Every intact frame decodes, in the order it was sent, with its values. */
  assert_int_equal(n_got, n_truth);
  for (size_t i = 0; i < n_truth; i++) {
    assert_int_equal(got[i].seq, want[i].seq);
    assert_int_equal(got[i].t_us, want[i].t_us);
    assert_memory_equal(got[i].ch, want[i].ch, sizeof want[i].ch);
  }
  assert_int_equal((long long)infos, tt_kv(truth, "infos"));

  {
    const uint64_t have[TT_N_COUNTERS] = {
      d->c.frames,       d->c.crc_errors,    d->c.framing_errors, d->c.oversize,
      d->c.unknown_type, d->c.spec_mismatch, d->c.lost,           d->c.duplicates,
      d->c.reordered,    d->c.seq_restarts,  d->c.bytes
    };
    for (size_t k = 0; k < TT_N_COUNTERS; k++) {
      long long expect = tt_kv(truth, tt_counter_keys[k]);
      if ((long long)have[k] != expect)
        fail_msg("%s: decoder %llu, injected %lld", tt_counter_keys[k], (unsigned long long)have[k],
                 expect);
    }
    assert_true(d->c.lost > 0 && d->c.reordered > 0 && d->c.duplicates > 0);
  }
  free(d);
  free(got);
  free(want);
  free(stream);
  free(truth);
  free((void *)bin);
  free((void *)truth_path);
}

/* glove-dump reports the same counters, from the raw bytes and from the
 * recording glove-gen made of them. */
static void tools_faults_glove_dump_counters_match_truth_raw_and_recorded(void **state) {
  char *truth = tt_read_file(tt_path(g_dir, "t.txt"), NULL);
  const char *inputs[2] = { "s.bin", "s.mrec" };
  (void)state;
  assert_non_null(truth);
  for (int i = 0; i < 2; i++) {
    char in[1024], counters[1024];
    char *text;
    snprintf(in, sizeof in, "%s", tt_path(g_dir, inputs[i]));
    snprintf(counters, sizeof counters, "%s", tt_path(g_dir, "c.txt"));
    {
      const char *argv[] = {
        tt_glove_dump, "-q", "--keep-going", "--counters", counters, in, NULL
      };
      /* 3: the stream holds frames from a foreign spec (wrong-hash faults). */
      assert_int_equal(tt_run(argv, NULL, tt_path(g_dir, "dump.err"), 120), 3);
    }
    text = tt_read_file(counters, NULL);
    assert_non_null(text);
    for (size_t k = 0; k < TT_N_COUNTERS; k++) {
      if (tt_kv(text, tt_counter_keys[k]) != tt_kv(truth, tt_counter_keys[k]))
        fail_msg("%s %s: glove-dump %lld, truth %lld", inputs[i], tt_counter_keys[k],
                 tt_kv(text, tt_counter_keys[k]), tt_kv(truth, tt_counter_keys[k]));
    }
    free(text);
  }
  free(truth);
}

/* The same seed gives the same bytes; another seed does not. */
static void tools_faults_same_seed_same_bytes(void **state) {
  char a[1024], b[1024], c[1024];
  size_t la, lb, lc;
  char *sa, *sb, *sc;
  (void)state;
  snprintf(a, sizeof a, "%s", tt_path(g_dir, "s.bin"));
  snprintf(b, sizeof b, "%s", tt_path(g_dir, "s2.bin"));
  snprintf(c, sizeof c, "%s", tt_path(g_dir, "s3.bin"));
  generate("11", b, tt_path(g_dir, "t2.txt"), tt_path(g_dir, "s2.mrec"));
  generate("12", c, tt_path(g_dir, "t3.txt"), tt_path(g_dir, "s3.mrec"));
  sa = tt_read_file(a, &la);
  sb = tt_read_file(b, &lb);
  sc = tt_read_file(c, &lc);
  assert_non_null(sa);
  assert_non_null(sb);
  assert_non_null(sc);
  assert_int_equal(la, lb);
  assert_memory_equal(sa, sb, la);
  assert_true(la != lc || memcmp(sa, sc, la) != 0);
  free(sa);
  free(sb);
  free(sc);
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(tools_faults_every_counter_equals_what_was_injected),
    cmocka_unit_test(tools_faults_glove_dump_counters_match_truth_raw_and_recorded),
    cmocka_unit_test(tools_faults_same_seed_same_bytes),
  };
  tt_take_args(argc, argv);
  return cmocka_run_group_tests(tests, setup, teardown);
}
