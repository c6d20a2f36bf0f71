/* glove-gen listening on 127.0.0.1 (a port the kernel picks), glove-dump
 * connecting: every frame and counter arrives, and the end of the
 * connection is a hang-up, not an error. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "tools_roundtrip.h"

static void tools_tcp_roundtrip_frames_and_counters_survive_loopback(void **state) {
  char *dir = tt_tmpdir(), path_file[1100], truth[1100], counters[1100], csv_path[1100];
  char addr[300], *p, *truth_text, *csv, *counters_text, *err_text;
  pid_t gen;
  int dump_rc;
  (void)state;
  assert_non_null(dir);
  snprintf(path_file, sizeof path_file, "%s", tt_path(dir, "addr"));
  snprintf(truth, sizeof truth, "%s", tt_path(dir, "truth.txt"));
  snprintf(counters, sizeof counters, "%s", tt_path(dir, "counters.txt"));
  snprintf(csv_path, sizeof csv_path, "%s", tt_path(dir, "out.csv"));
  {
    const char *argv[] = { tt_glove_gen,  "-n",      "20000",  "--fast", "--faults",
                           "0.05",        "--seed",  "9",      "-o",     "tcp-listen:127.0.0.1:0",
                           "--path-file", path_file, "--wait", "60",     "--truth",
                           truth,         NULL };
    gen = tt_spawn(argv, NULL, tt_path(dir, "gen.err"));
    assert_true(gen > 0);
  }
  assert_int_equal(tt_await_file(gen, path_file, tt_path(dir, "gen.err"), 60), 0);
  p = tt_read_file(path_file, NULL);
  assert_non_null(p);
  assert_int_equal(strncmp(p, "127.0.0.1:", 10), 0);
  snprintf(addr, sizeof addr, "tcp:%.*s", (int)strcspn(p, "\n"), p);
  free(p);
  {
    const char *argv[] = { tt_glove_dump, "--csv", "--keep-going", "--counters", counters,
                           "--idle",      "60",    addr,           NULL };
    dump_rc = tt_run(argv, csv_path, tt_path(dir, "dump.err"), 120);
  }
  assert_int_equal(tt_wait(gen, 60), 0);
  truth_text = tt_read_file(truth, NULL);
  csv = tt_read_file(csv_path, NULL);
  counters_text = tt_read_file(counters, NULL);
  err_text = tt_read_file(tt_path(dir, "dump.err"), NULL);
  assert_non_null(truth_text);
  assert_non_null(csv);
  assert_non_null(counters_text);
  assert_non_null(err_text);
  assert_int_equal(dump_rc, tt_kv(truth_text, "spec_mismatch") > 0 ? 3 : 0);
  assert_non_null(strstr(err_text, "hang-up"));
  tt_check_csv(csv, truth_text);
  tt_check_counters(counters_text, truth_text);
  free(truth_text);
  free(csv);
  free(counters_text);
  free(err_text);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(tools_tcp_roundtrip_frames_and_counters_survive_loopback),
  };
  tt_take_args(argc, argv);
  return cmocka_run_group_tests(tests, NULL, NULL);
}
