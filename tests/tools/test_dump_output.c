/* What glove-dump writes: lines stdout cannot take make it stop with an
 * error, bytes of a frame the stream ended inside are named, and --record
 * keeps exactly the bytes it read. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "gp.h"
#include "mr_io.h"
#include "tools_proc.h"

static char *g_dir;

static int setup(void **state) {
  (void)state;
  g_dir = tt_tmpdir();
  if (!g_dir) return -1;
  char out[1100];
  snprintf(out, sizeof out, "file:%s", tt_path(g_dir, "s.bin"));
  const char *argv[] = { tt_glove_gen, "--fast", "-n", "200", "-q", "-o", out, NULL };
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
  const char *argv[] = { tt_glove_dump, in, NULL };
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
  const char *argv[] = { tt_glove_dump, "-q", cutp, NULL };
  assert_int_equal(tt_run(argv, NULL, errp, 60), 0);
  char *err = tt_read_file(errp, NULL);
  assert_non_null(err);
  snprintf(want, sizeof want, "its last %zu bytes (from byte %zu) were not decoded", cut - last0,
           last0);
  if (!strstr(err, want)) fail_msg("stderr lacks '%s':\n%s", want, err);
  /* The frames before it are all there: 200 SAMPLEs less the cut one, one INFO. */
  assert_int_equal(tt_kv(err, "frames"), 200);
  assert_int_equal(tt_kv(err, "framing_errors"), 0);
  free(err);
  /* The whole stream ends on a delimiter: nothing to report. */
  const char *argv2[] = { tt_glove_dump, "-q", tt_path(g_dir, "s.bin"), NULL };
  assert_int_equal(tt_run(argv2, NULL, errp, 60), 0);
  err = tt_read_file(errp, NULL);
  assert_non_null(err);
  assert_null(strstr(err, "inside a frame"));
  free(err);
  free(whole);
}

static void tools_dump_output_record_keeps_every_byte_read(void **state) {
  (void)state;
  char in[1024], rec[1024], c1[1024], c2[1024];
  snprintf(in, sizeof in, "%s", tt_path(g_dir, "f.bin"));
  snprintf(rec, sizeof rec, "%s", tt_path(g_dir, "f.mrec"));
  snprintf(c1, sizeof c1, "%s", tt_path(g_dir, "f1.txt"));
  snprintf(c2, sizeof c2, "%s", tt_path(g_dir, "f2.txt"));
  {
    char o[1100];
    snprintf(o, sizeof o, "file:%s", in);
    const char *argv[] = { tt_glove_gen, "--fast", "-q",     "-n", "3000",
                           "--faults",   "0.1",    "--seed", "5",  "--stall-frames",
                           "1:5",        "-o",     o,        NULL };
    assert_int_equal(tt_run(argv, NULL, NULL, 60), 0);
  }
  {
    const char *argv[] = {
      tt_glove_dump, "-q", "--keep-going", "--record", rec, "--counters", c1, in, NULL
    };
    assert_int_equal(tt_run(argv, NULL, NULL, 60), 3); /* wrong-hash faults */
  }
  /* The chunks, joined, are the input byte for byte, in non-decreasing time. */
  size_t len, got_len = 0;
  char *want = tt_read_file(in, &len);
  uint8_t *got = malloc(len + 1);
  mr_rec_reader r;
  mr_io_error err;
  uint64_t t_ns, last = 0;
  const uint8_t *data;
  size_t n;
  int rc;
  assert_non_null(want);
  assert_non_null(got);
  assert_int_equal(mr_rec_reader_open(&r, rec, &err), 0);
  assert_int_equal(r.header.spec_hash, GP_SPEC_HASH);
  while ((rc = mr_rec_reader_next(&r, &t_ns, &data, &n, &err)) == 1) {
    assert_true(got_len + n <= len);
    assert_true(t_ns >= last);
    memcpy(got + got_len, data, n);
    got_len += n;
    last = t_ns;
  }
  mr_rec_reader_close(&r);
  assert_int_equal(rc, 0);
  assert_int_equal(got_len, len);
  assert_memory_equal(got, want, len);
  /* And replaying it counts the same. */
  {
    const char *argv[] = { tt_glove_dump, "-q", "--keep-going", "--counters", c2, rec, NULL };
    assert_int_equal(tt_run(argv, NULL, NULL, 60), 3);
  }
  char *a = tt_read_file(c1, NULL), *b = tt_read_file(c2, NULL);
  assert_non_null(a);
  assert_non_null(b);
  assert_true(tt_kv(a, "frames") > 2000);
  assert_string_equal(a, b);
  free(a);
  free(b);
  free(got);
  free(want);
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(tools_dump_output_full_stdout_is_an_error),
    cmocka_unit_test(tools_dump_output_stream_cut_inside_a_frame_is_reported),
    cmocka_unit_test(tools_dump_output_record_keeps_every_byte_read),
  };
  tt_take_args(argc, argv);
  return cmocka_run_group_tests(tests, setup, teardown);
}
