/* A stream from a glove built from another message definition is reported
 * as a spec mismatch, naming both hashes, with a non-zero exit. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gp.h"
#include "tools_proc.h"
#include "tools_truth.h"

static char *g_dir;

static int setup(void **state) {
  const char *argv[] = { tt_glove_gen, "--spec-hash", "0x12345678", "-n", "300", "--fast",
                         "-o",         NULL,          "--truth",    NULL, NULL };
  char out[1100], truth[1100];
  (void)state;
  g_dir = tt_tmpdir();
  if (!g_dir) return -1;
  snprintf(out, sizeof out, "file:%s", tt_path(g_dir, "foreign.bin"));
  snprintf(truth, sizeof truth, "%s", tt_path(g_dir, "truth.txt"));
  argv[7] = out;
  argv[9] = truth;
  return tt_run(argv, NULL, NULL, 60) == 0 ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  tt_rmdir(g_dir);
  free(g_dir);
  return 0;
}

static void tools_spec_mismatch_reported_with_both_hashes_and_exit_3(void **state) {
  char in[1100], line[128], *err, *out;
  const char *argv[] = { tt_glove_dump, in, NULL };
  (void)state;
  snprintf(in, sizeof in, "%s", tt_path(g_dir, "foreign.bin"));
  assert_int_equal(tt_run(argv, tt_path(g_dir, "out.txt"), tt_path(g_dir, "err.txt"), 60), 3);
  err = tt_read_file(tt_path(g_dir, "err.txt"), NULL);
  out = tt_read_file(tt_path(g_dir, "out.txt"), NULL);
  assert_non_null(err);
  assert_non_null(out);
  snprintf(line, sizeof line, "glove-dump: spec mismatch (device 0x12345678, host 0x%08X)\n",
           (unsigned)GP_SPEC_HASH);
  /* Exactly that line, and first: nothing was mistaken for line noise. */
  assert_int_equal(strncmp(err, line, strlen(line)), 0);
  assert_null(strstr(out, "SAMPLE"));
  assert_int_equal(tt_kv(err, "crc_errors"), 0);
  free(err);
  free(out);
}

/* With --keep-going every frame is counted as a mismatch, as glove-gen's
 * truth says, and none is accepted. */
static void tools_spec_mismatch_every_frame_counted_with_keep_going(void **state) {
  char in[1100], counters[1100], *truth, *text;
  const char *argv[] = { tt_glove_dump, "-q", "--keep-going", "--counters", counters, in, NULL };
  (void)state;
  snprintf(in, sizeof in, "%s", tt_path(g_dir, "foreign.bin"));
  snprintf(counters, sizeof counters, "%s", tt_path(g_dir, "counters.txt"));
  assert_int_equal(tt_run(argv, NULL, NULL, 60), 3);
  truth = tt_read_file(tt_path(g_dir, "truth.txt"), NULL);
  text = tt_read_file(counters, NULL);
  assert_non_null(truth);
  assert_non_null(text);
  /* 300 SAMPLEs and the two INFOs of a 1.2 s stream at 250 Hz. */
  assert_int_equal(tt_kv(truth, "spec_mismatch"), 302);
  assert_int_equal(tt_kv(text, "spec_mismatch"), 302);
  assert_int_equal(tt_kv(text, "frames"), 0);
  assert_int_equal(tt_kv(text, "crc_errors"), 0);
  for (size_t k = 0; k < TT_N_COUNTERS; k++)
    assert_int_equal(tt_kv(text, tt_counter_keys[k]), tt_kv(truth, tt_counter_keys[k]));
  free(truth);
  free(text);
}

/* The host's own stream, by contrast, exits 0 with no mismatch line. */
static void tools_spec_mismatch_not_reported_for_the_host_spec(void **state) {
  char out[1100], *err;
  const char *gen[] = { tt_glove_gen, "-n", "300", "--fast", "-o", out, NULL };
  const char *dump[] = { tt_glove_dump, "-q", out + 5, NULL };
  (void)state;
  snprintf(out, sizeof out, "file:%s", tt_path(g_dir, "own.bin"));
  assert_int_equal(tt_run(gen, NULL, NULL, 60), 0);
  assert_int_equal(tt_run(dump, NULL, tt_path(g_dir, "err2.txt"), 60), 0);
  err = tt_read_file(tt_path(g_dir, "err2.txt"), NULL);
  assert_non_null(err);
  assert_null(strstr(err, "spec mismatch"));
  assert_int_equal(tt_kv(err, "frames"), 302);
  free(err);
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(tools_spec_mismatch_reported_with_both_hashes_and_exit_3),
    cmocka_unit_test(tools_spec_mismatch_every_frame_counted_with_keep_going),
    cmocka_unit_test(tools_spec_mismatch_not_reported_for_the_host_spec),
  };
  tt_take_args(argc, argv);
  return cmocka_run_group_tests(tests, setup, teardown);
}
