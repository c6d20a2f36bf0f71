/* glove-dump never loses data quietly: lines stdout cannot take make it stop
 * with an error, and bytes of a frame the stream ended inside are named. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "tools_proc.h"

static char *g_dir;

static int setup(void **state) {
  (void)state;
  g_dir = tt_tmpdir();
  if (!g_dir) return -1;
  char out[1100];
  snprintf(out, sizeof out, "file:%s", tt_path(g_dir, "s.bin"));
  const char *argv[] = {tt_glove_gen, "--fast", "-n", "200", "-q", "-o", out, NULL};
  return tt_run(argv, NULL, NULL, 60) == 0 ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  tt_rmdir(g_dir);
  free(g_dir);
  return 0;
}

static void tools_dump_output_full_stdout_is_an_error(void **state) {
  (void)state;
  char in[1024], errp[1024];
  snprintf(in, sizeof in, "%s", tt_path(g_dir, "s.bin"));
  snprintf(errp, sizeof errp, "%s", tt_path(g_dir, "full.err"));
  const char *argv[] = {tt_glove_dump, in, NULL};
  assert_int_equal(tt_run(argv, "/dev/full", errp, 60), 1);
  char *err = tt_read_file(errp, NULL);
  assert_non_null(err);
  assert_non_null(strstr(err, "glove-dump: stdout: cannot write the decoded frames"));
  free(err);
}

static void tools_dump_output_stream_cut_inside_a_frame_is_reported(void **state) {
  (void)state;
  size_t len;
  char *whole = tt_read_file(tt_path(g_dir, "s.bin"), &len);
  assert_non_null(whole);
  assert_true(len > 30 && whole[len - 1] == 0);
  /* Cut the last frame 4 bytes short of its delimiter. */
  size_t cut = len - 5, last0 = cut;
  while (last0 > 0 && whole[last0 - 1] != 0) last0--;
  char cutp[1024], errp[1024], want[128];
  snprintf(cutp, sizeof cutp, "%s", tt_path(g_dir, "cut.bin"));
  snprintf(errp, sizeof errp, "%s", tt_path(g_dir, "cut.err"));
  FILE *f = fopen(cutp, "wb");
  assert_non_null(f);
  assert_int_equal(fwrite(whole, 1, cut, f), cut);
  assert_int_equal(fclose(f), 0);
  const char *argv[] = {tt_glove_dump, "-q", cutp, NULL};
  assert_int_equal(tt_run(argv, NULL, errp, 60), 0);
  char *err = tt_read_file(errp, NULL);
  assert_non_null(err);
  snprintf(want, sizeof want, "its last %zu bytes (from byte %zu) were not decoded",
           cut - last0, last0);
  if (!strstr(err, want)) fail_msg("stderr lacks '%s':\n%s", want, err);
  /* The frames before it are all there: 200 SAMPLEs less the cut one, one INFO. */
  assert_int_equal(tt_kv(err, "frames"), 200);
  assert_int_equal(tt_kv(err, "framing_errors"), 0);
  free(err);
  /* The whole stream ends on a delimiter: nothing to report. */
  const char *argv2[] = {tt_glove_dump, "-q", tt_path(g_dir, "s.bin"), NULL};
  assert_int_equal(tt_run(argv2, NULL, errp, 60), 0);
  err = tt_read_file(errp, NULL);
  assert_non_null(err);
  assert_null(strstr(err, "inside a frame"));
  free(err);
  free(whole);
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(tools_dump_output_full_stdout_is_an_error),
      cmocka_unit_test(tools_dump_output_stream_cut_inside_a_frame_is_reported),
  };
  tt_take_args(argc, argv);
  return cmocka_run_group_tests(tests, setup, teardown);
}
