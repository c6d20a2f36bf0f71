/* A glove that disconnects and comes back: glove-dump listens, reports the
 * hang-up, keeps every frame it already had, takes the glove back on the
 * same port, and its counters are those of both streams together. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "tools_roundtrip.h"

static void run_glove(const char *addr, const char *seed, const char *truth) {
  const char *argv[] = { tt_glove_gen,     "-n",  "3000",   "--fast", "--faults", "0.05",
                         "--stall-frames", "1:5", "--seed", seed,     "-o",       addr,
                         "--truth",        truth, NULL };
  assert_int_equal(tt_run(argv, NULL, NULL, 60), 0);
}

static void tools_reconnect_counters_span_both_connections(void **state) {
  char *dir = tt_tmpdir(), path_file[1100], t1[1100], t2[1100], counters[1100];
  char csv_path[1100], addr[300], both_path[1100];
  char *p, *a, *b, *csv, *got, *err;
  pid_t dump;
  int rc;
  (void)state;
  assert_non_null(dir);
  snprintf(path_file, sizeof path_file, "%s", tt_path(dir, "addr"));
  snprintf(t1, sizeof t1, "%s", tt_path(dir, "t1.txt"));
  snprintf(t2, sizeof t2, "%s", tt_path(dir, "t2.txt"));
  snprintf(both_path, sizeof both_path, "%s", tt_path(dir, "both.txt"));
  snprintf(counters, sizeof counters, "%s", tt_path(dir, "counters.txt"));
  snprintf(csv_path, sizeof csv_path, "%s", tt_path(dir, "out.csv"));
  {
    /* After the second glove leaves, nobody comes back: 2 s later it stops. */
    const char *argv[] = {
      tt_glove_dump, "--csv",  "--keep-going", "--reconnect", "2",
      "--counters",  counters, "--path-file",  path_file,     "tcp-listen:127.0.0.1:0",
      NULL
    };
    dump = tt_spawn(argv, csv_path, tt_path(dir, "dump.err"));
    assert_true(dump > 0);
  }
  assert_int_equal(tt_await_file(dump, path_file, tt_path(dir, "dump.err"), 60), 0);
  p = tt_read_file(path_file, NULL);
  assert_non_null(p);
  snprintf(addr, sizeof addr, "tcp:%.*s", (int)strcspn(p, "\n"), p);
  free(p);
  run_glove(addr, "21", t1);
  run_glove(addr, "22", t2);
  rc = tt_wait(dump, 60);

  a = tt_read_file(t1, NULL);
  b = tt_read_file(t2, NULL);
  csv = tt_read_file(csv_path, NULL);
  got = tt_read_file(counters, NULL);
  err = tt_read_file(tt_path(dir, "dump.err"), NULL);
  assert_non_null(a);
  assert_non_null(b);
  assert_non_null(csv);
  assert_non_null(got);
  assert_non_null(err);
  assert_int_equal(rc, tt_kv(a, "spec_mismatch") + tt_kv(b, "spec_mismatch") > 0 ? 3 : 0);
  /* Two hang-ups reported, one wait for the next peer in between. */
  {
    const char *q = strstr(err, "hang-up");
    assert_non_null(q);
    assert_non_null(strstr(q + 1, "hang-up"));
    assert_non_null(strstr(err, "waiting for the next peer"));
  }

  /* Every frame of both gloves, in order; the counters add up, and the
   * second glove starting again at seq 0 is one restart. */
  {
    FILE *f = fopen(both_path, "w");
    char *both;
    assert_non_null(f);
    fputs(a, f);
    fputs(b, f);
    fclose(f);
    both = tt_read_file(both_path, NULL);
    assert_non_null(both);
    tt_check_csv(csv, both);
    free(both);
  }
  for (size_t k = 0; k < TT_N_COUNTERS; k++) {
    const char *key = tt_counter_keys[k];
    long long want = tt_kv(a, key) + tt_kv(b, key) + (strcmp(key, "seq_restarts") == 0);
    if (tt_kv(got, key) != want)
      fail_msg("%s: glove-dump %lld, both gloves %lld", key, tt_kv(got, key), want);
  }
  free(a);
  free(b);
  free(csv);
  free(got);
  free(err);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(tools_reconnect_counters_span_both_connections),
  };
  tt_take_args(argc, argv);
  return cmocka_run_group_tests(tests, NULL, NULL);
}
