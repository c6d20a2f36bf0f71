/* The shared test helpers: a test that waits for a child's output stops as
 * soon as the child has ended, and says what the child printed. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "proc.h"

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void common_await_file_stops_when_the_child_exits_and_keeps_its_status(void **state) {
  char *dir = tt_tmpdir();
  const char *argv[] = { "/bin/sh", "-c", "echo 'no pty here' >&2; exit 3", NULL };
  char never[1100], err_path[1100];
  double t0;
  pid_t pid;
  (void)state;
  assert_non_null(dir);
  snprintf(never, sizeof never, "%s", tt_path(dir, "never"));
  snprintf(err_path, sizeof err_path, "%s", tt_path(dir, "child.err"));
  pid = tt_spawn(argv, NULL, err_path);
  assert_true(pid > 0);
  t0 = now_s();
  assert_int_equal(tt_await_file(pid, never, err_path, 60), -1);
  /* Not the 60 s the file was given: the child was gone long before. */
  assert_true(now_s() - t0 < 10);
  /* Its status is still there for the test to check. */
  assert_int_equal(tt_wait(pid, 10), 3);
  tt_rmdir(dir);
  free(dir);
}

static void common_await_file_returns_once_the_child_wrote_it(void **state) {
  char *dir = tt_tmpdir();
  char cmd[1200];
  const char *argv[] = { "/bin/sh", "-c", cmd, NULL };
  pid_t pid;
  (void)state;
  assert_non_null(dir);
  snprintf(cmd, sizeof cmd, "echo ready > %s; exit 0", tt_path(dir, "f"));
  pid = tt_spawn(argv, NULL, NULL);
  assert_true(pid > 0);
  assert_int_equal(tt_await_file(pid, tt_path(dir, "f"), NULL, 60), 0);
  assert_int_equal(tt_wait(pid, 10), 0);
  tt_rmdir(dir);
  free(dir);
}

static void common_capture_keeps_stdout_stderr_and_status_apart(void **state) {
  char *argv[] = { "/bin/sh", "-c", "echo out; echo err >&2; exit 5", NULL };
  tt_output o;
  char v[32];
  (void)state;
  assert_int_equal(tt_capture(argv, &o), 0);
  assert_int_equal(o.status, 5);
  assert_string_equal(o.out, "out\n");
  assert_string_equal(o.err, "err\n");
  assert_int_equal(tt_field("a: 1\nstate hash: 00ff\n", "state hash", v, sizeof v), 0);
  assert_string_equal(v, "00ff");
  tt_output_free(&o);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(common_await_file_stops_when_the_child_exits_and_keeps_its_status),
    cmocka_unit_test(common_await_file_returns_once_the_child_wrote_it),
    cmocka_unit_test(common_capture_keeps_stdout_stderr_and_status_apart),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
