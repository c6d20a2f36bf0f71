/* glove-gen -> pseudo-terminal -> glove-dump: glove-gen creates the pty and
 * names its slave side; glove-dump opens that as a serial device. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <signal.h>
#include <sys/stat.h>
#include <time.h>

#include "tools_roundtrip.h"

#define GEN_ARGS                                                                                   \
  "-n", "6000", "--rate", "2000", "--fast", "--faults", "0.05", "--stall-frames", "1:5", "--seed", \
      "5"

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
    const char *argv[] = { tt_glove_gen, GEN_ARGS, "-o", ref_out, "--truth", ref_truth, NULL };
    assert_int_equal(tt_run(argv, NULL, NULL, 60), 0);
  }
  ref_text = tt_read_file(ref_truth, NULL);
  assert_non_null(ref_text);
  assert_true(tt_kv(ref_text, "frames") > 5000);

  {
    const char *argv[] = { tt_glove_gen, GEN_ARGS, "-o",      "pty", "--path-file", path_file,
                           "--wait",     "60",     "--truth", truth, NULL };
    gen = tt_spawn(argv, NULL, tt_path(dir, "gen.err"));
    assert_true(gen > 0);
  }
  assert_int_equal(tt_await_file(gen, path_file, tt_path(dir, "gen.err"), 60), 0);
  p = tt_read_file(path_file, NULL);
  assert_non_null(p);
  assert_int_equal(strncmp(p, "/dev/pts/", 9), 0);
  snprintf(dev, sizeof dev, "serial:%.*s@115200", (int)strcspn(p, "\n"), p);
  free(p);
  {
    char count[32];
    const char *argv[] = { tt_glove_dump, "--csv",  "--keep-going", "--count", count, "--counters",
                           counters,      "--idle", "60",           dev,       NULL };
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

/* The glove is unplugged mid-stream (glove-gen killed outright): glove-dump
 * reports the hang-up, exits cleanly, and every frame it printed is the
 * stream's own, in order, with none missing before the unplug. */
static void tools_pty_roundtrip_unplug_mid_stream_keeps_frames_read(void **state) {
  char *dir = tt_tmpdir(), ref_out[1100], ref_truth[1100], path_file[1100], csv_path[1100];
  char dev[300], *p, *ref, *csv, *err;
  pid_t gen, dump;
  struct stat st;
  int waited = 0, rc;
  size_t rows = 0, n_ref;
  tt_sample *want;
  (void)state;
  assert_non_null(dir);
  snprintf(ref_out, sizeof ref_out, "file:%s", tt_path(dir, "ref.bin"));
  snprintf(ref_truth, sizeof ref_truth, "%s", tt_path(dir, "ref.txt"));
  snprintf(path_file, sizeof path_file, "%s", tt_path(dir, "pty.path"));
  snprintf(csv_path, sizeof csv_path, "%s", tt_path(dir, "out.csv"));
  {
    const char *argv[] = { tt_glove_gen, "-n", "100000", "--rate",  "500",     "--seed", "6",
                           "--fast",     "-o", ref_out,  "--truth", ref_truth, NULL };
    assert_int_equal(tt_run(argv, NULL, NULL, 60), 0);
  }
  {
    /* Real time: 200 s of stream, far more than the test waits for. */
    const char *argv[] = {
      tt_glove_gen, "-n",  "100000",      "--rate",  "500",    "--seed", "6",
      "-o",         "pty", "--path-file", path_file, "--wait", "60",     NULL
    };
    gen = tt_spawn(argv, NULL, tt_path(dir, "gen.err"));
    assert_true(gen > 0);
  }
  assert_int_equal(tt_await_file(gen, path_file, tt_path(dir, "gen.err"), 60), 0);
  p = tt_read_file(path_file, NULL);
  assert_non_null(p);
  snprintf(dev, sizeof dev, "%.*s", (int)strcspn(p, "\n"), p);
  free(p);
  {
    const char *argv[] = { tt_glove_dump, "--csv", dev, NULL };
    dump = tt_spawn(argv, csv_path, tt_path(dir, "dump.err"));
    assert_true(dump > 0);
  }
  /* Some frames through (a few KiB of CSV, past stdout's buffering), then
   * pull the plug. */
  while ((stat(csv_path, &st) != 0 || st.st_size < 12000) && waited++ < 6000) {
    struct timespec ts = { 0, 10000000L };
    nanosleep(&ts, NULL);
  }
  assert_true(st.st_size >= 12000);
  assert_int_equal(kill(gen, SIGKILL), 0);
  assert_int_equal(tt_wait(gen, 30), 128 + SIGKILL);
  rc = tt_wait(dump, 30);
  assert_int_equal(rc, 0);

  err = tt_read_file(tt_path(dir, "dump.err"), NULL);
  csv = tt_read_file(csv_path, NULL);
  ref = tt_read_file(ref_truth, NULL);
  assert_non_null(err);
  assert_non_null(csv);
  assert_non_null(ref);
  assert_non_null(strstr(err, "hang-up"));
  assert_non_null(strstr(err, "frames="));
  want = tt_truth_samples(ref, &n_ref);
  assert_non_null(want);
  for (p = strchr(csv, '\n') + 1; *p; p = strchr(p, '\n') + 1) {
    unsigned u[9];
    assert_int_equal(tt_parse_uints(p, ',', u, 9), 9);
    assert_true(rows < n_ref);
    assert_int_equal(u[0], want[rows].seq);
    assert_int_equal(u[1], want[rows].t_us);
    assert_memory_equal(u + 2, want[rows].ch, sizeof want[rows].ch);
    rows++;
  }
  assert_true(rows >= 300);
  assert_true(rows < n_ref);
  free(want);
  free(err);
  free(csv);
  free(ref);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(tools_pty_roundtrip_frames_and_counters_survive_the_pty),
    cmocka_unit_test(tools_pty_roundtrip_unplug_mid_stream_keeps_frames_read),
  };
  tt_take_args(argc, argv);
  return cmocka_run_group_tests(tests, NULL, NULL);
}
