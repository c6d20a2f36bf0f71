/* glove-gen -> pseudo-terminal -> glove-dump: glove-gen creates the pty and
 * names its slave side; glove-dump opens that as a serial device. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "tools_roundtrip.h"

#define GEN_ARGS                                                                       \
  "-n", "6000", "--rate", "2000", "--fast", "--faults", "0.05", "--stall-frames", "1:5", \
      "--seed", "5"

static void tools_pty_roundtrip_frames_and_counters_survive_the_pty(void **state) {
  char *dir = tt_tmpdir(), ref_out[1100], path_file[1100], truth[1100], ref_truth[1100];
  char counters[1100], csv_path[1100], dev[300], *p;
  char *truth_text, *ref_text, *csv, *counters_text;
  pid_t gen;
  int dump_rc;
  (void)state;
  assert_non_null(dir);
  snprintf(ref_out, sizeof ref_out, "file:%s", tt_path(dir, "ref.bin"));
  snprintf(ref_truth, sizeof ref_truth, "%s", tt_path(dir, "ref.txt"));
  snprintf(path_file, sizeof path_file, "%s", tt_path(dir, "pty.path"));
  snprintf(truth, sizeof truth, "%s", tt_path(dir, "truth.txt"));
  snprintf(counters, sizeof counters, "%s", tt_path(dir, "counters.txt"));
  snprintf(csv_path, sizeof csv_path, "%s", tt_path(dir, "out.csv"));

  /* The same stream into a file first: its truth says how many frames the
   * pty must deliver, so glove-dump can stop on the last one. */
  {
    const char *argv[] = {tt_glove_gen, GEN_ARGS, "-o", ref_out, "--truth", ref_truth, NULL};
    assert_int_equal(tt_run(argv, NULL, NULL, 60), 0);
  }
  ref_text = tt_read_file(ref_truth, NULL);
  assert_non_null(ref_text);
  assert_true(tt_kv(ref_text, "frames") > 5000);

  {
    const char *argv[] = {tt_glove_gen, GEN_ARGS, "-o", "pty", "--path-file", path_file,
                          "--wait", "60", "--truth", truth, NULL};
    gen = tt_spawn(argv, NULL, tt_path(dir, "gen.err"));
    assert_true(gen > 0);
  }
  assert_int_equal(tt_wait_for_file(path_file, 60), 0);
  p = tt_read_file(path_file, NULL);
  assert_non_null(p);
  assert_int_equal(strncmp(p, "/dev/pts/", 9), 0);
  snprintf(dev, sizeof dev, "serial:%.*s@115200", (int)strcspn(p, "\n"), p);
  free(p);
  {
    char count[32];
    const char *argv[] = {tt_glove_dump, "--csv", "--keep-going", "--count", count,
                          "--counters", counters, "--idle", "60", dev, NULL};
    snprintf(count, sizeof count, "%lld", tt_kv(ref_text, "frames"));
    dump_rc = tt_run(argv, csv_path, tt_path(dir, "dump.err"), 120);
  }
  assert_int_equal(tt_wait(gen, 60), 0);
  /* Wrong-hash faults are in the mix: glove-dump reports the mismatch. */
  assert_int_equal(dump_rc, tt_kv(ref_text, "spec_mismatch") > 0 ? 3 : 0);

  truth_text = tt_read_file(truth, NULL);
  csv = tt_read_file(csv_path, NULL);
  counters_text = tt_read_file(counters, NULL);
  assert_non_null(truth_text);
  assert_non_null(csv);
  assert_non_null(counters_text);
  assert_string_equal(truth_text, ref_text);
  tt_check_csv(csv, truth_text);
  tt_check_counters(counters_text, truth_text);
  free(truth_text);
  free(ref_text);
  free(csv);
  free(counters_text);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(tools_pty_roundtrip_frames_and_counters_survive_the_pty),
  };
  tt_take_args(argc, argv);
  return cmocka_run_group_tests(tests, NULL, NULL);
}
