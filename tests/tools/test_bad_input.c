/* Bad input, the way testers feed it on purpose: every damaged take gives
 * one line naming the file and the damage, and a non-zero exit, the same
 * from glove-dump and from `marionette run --replay`, and neither hangs;
 * a glove source the user got wrong is bad usage (exit 2) in both, found
 * before the show starts. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "gp.h"
#include "mr_io.h"
#include "tools_proc.h"

static const char *g_marionette = "marionette";
static char *g_dir;
static uint8_t g_take[64 * 1024]; /* a good take, as written */
static size_t g_take_len;
static size_t g_chunk_at[64]; /* where each chunk starts */
static int g_chunks;

static void put_le(uint8_t *p, uint64_t v, int n) {
  for (int i = 0; i < n; i++) p[i] = (uint8_t)(v >> (8 * i));
}

/* A take of 40 SAMPLEs at 100 Hz, one per chunk, INFO first. */
static int setup(void **state) {
  (void)state;
  g_dir = tt_tmpdir();
  if (g_dir == NULL) return -1;
  const char *path = tt_path(g_dir, "good.mrec");
  mr_rec_writer w;
  mr_io_error err;
  if (mr_rec_writer_open(&w, path, GP_SPEC_HASH, 0, &err) != 0) return -1;
  for (int i = 0; i <= 40; i++) {
    gp_msg m;
    uint8_t wire[GP_MAX_WIRE + 2];
    memset(&m, 0, sizeof m);
    if (i == 0) {
      m.type = GP_INFO;
      m.u.info.proto_major = 1;
      m.u.info.spec_hash = GP_SPEC_HASH;
      m.u.info.n_channels = 5;
      m.u.info.adc_bits = 12;
      m.u.info.frame_rate_hz = 100;
    } else {
      m.type = GP_SAMPLE;
      m.u.sample.seq = (uint16_t)i;
      m.u.sample.t_us = 10000u * (uint32_t)i;
      for (int k = 0; k < 5; k++) m.u.sample.ch[k] = (uint16_t)(1000 + 50 * i + k);
    }
    size_t n = gp_encode(&m, GP_SPEC_HASH, wire, sizeof wire);
    if (n == 0 || mr_rec_writer_add(&w, 10000000ull * (uint64_t)i, wire, n, &err) != 0) return -1;
  }
  if (mr_rec_writer_close(&w, &err) != 0) return -1;
  char *b = tt_read_file(path, &g_take_len);
  if (b == NULL || g_take_len > sizeof g_take) return -1;
  memcpy(g_take, b, g_take_len);
  free(b);
  for (size_t at = MR_REC_HEADER_LEN; at < g_take_len && g_chunks < 64; g_chunks++) {
    g_chunk_at[g_chunks] = at;
    at += MR_REC_CHUNK_HEADER_LEN + (g_take[at + 8] | (size_t)g_take[at + 9] << 8);
  }
  return g_chunks == 41 ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  tt_rmdir(g_dir);
  free(g_dir);
  return 0;
}

static const char *save(const char *name, const uint8_t *b, size_t n) {
  const char *path = tt_path(g_dir, name);
  FILE *f = fopen(path, "wb");
  assert_non_null(f);
  assert_int_equal(fwrite(b, 1, n, f), n);
  assert_int_equal(fclose(f), 0);
  return path;
}

static int count(const char *text, const char *what) {
  int n = 0;
  for (const char *p = text; (p = strstr(p, what)) != NULL; p += strlen(what)) n++;
  return n;
}

/* The line of err that holds what, without its program prefix ("NAME: "). */
static void line_with(const char *err, const char *what, char *out, size_t size) {
  const char *hit = strstr(err, what);
  out[0] = '\0';
  if (hit == NULL) return;
  const char *start = hit;
  while (start > err && start[-1] != '\n') start--;
  const char *colon = strstr(start, ": ");
  if (colon != NULL && colon < hit) start = colon + 2;
  const char *end = strchr(hit, '\n');
  snprintf(out, size, "%.*s", (int)(end ? end - start : (long)strlen(start)), start);
}

/* Runs argv (at most 60 s: a hang fails) and returns its status; stdout and
 * stderr in *o. */
static int run(const char *const argv[], tt_output *o) {
  const char *out = tt_path(g_dir, "out"), *err = tt_path(g_dir, "err");
  int st = tt_run(argv, out, err, 60);
  o->out = tt_read_file(out, NULL);
  o->err = tt_read_file(err, NULL);
  assert_non_null(o->out);
  assert_non_null(o->err);
  if (st < 0) fail_msg("%s %s did not end within 60 s: %s", argv[0], argv[1], o->err);
  return st;
}

/* One damaged take: glove-dump and the replay each exit non-zero with one
 * line naming the file and holding want, the same line in both. */
static void expect_take_error(const char *name, const uint8_t *b, size_t n, const char *want) {
  const char *path = save(name, b, n);
  char scene[4200], file_msg[600], dump_line[600], run_line[600];
  snprintf(scene, sizeof scene, "%s/host/scenes/stick.yaml", MR_SOURCE_DIR);
  snprintf(file_msg, sizeof file_msg, "%s: byte ", name);
  tt_output d, r;
  const char *dump[] = { tt_glove_dump, "-q", path, NULL };
  const char *replay[] = { g_marionette, "run", scene, "--replay", path, NULL };
  int ds = run(dump, &d), rs = run(replay, &r);
  line_with(d.err, file_msg, dump_line, sizeof dump_line);
  line_with(r.err, file_msg, run_line, sizeof run_line);
  if (ds != 1 || count(d.err, name) != 1 || !strstr(dump_line, want))
    fail_msg("glove-dump %s: exit %d, stderr '%s' (want 1 and one line with '%s')", name, ds, d.err,
             want);
  if (rs != 1 || count(r.err, file_msg) != 1 || !strstr(run_line, want))
    fail_msg("marionette run --replay %s: exit %d, stderr '%s' (want 1 and one line with '%s')",
             name, rs, r.err, want);
  if (strcmp(strstr(dump_line, name), strstr(run_line, name)) != 0)
    fail_msg("%s: glove-dump says '%s', the replay '%s'", name, dump_line, run_line);
  free(d.out);
  free(d.err);
  free(r.out);
  free(r.err);
}

static void tools_bad_input_a_damaged_header_is_one_line_and_exit_1_in_both(void **state) {
  uint8_t b[sizeof g_take];
  (void)state;
  memcpy(b, g_take, g_take_len);
  put_le(b + 8, 9, 2);
  expect_take_error("v9.mrec", b, g_take_len, "byte 8: unknown version 9");
  memcpy(b, g_take, g_take_len);
  put_le(b + 10, 8, 2);
  expect_take_error("hl8.mrec", b, g_take_len, "byte 10: header length 8 is below 32");
  put_le(b + 10, 65535, 2);
  expect_take_error("hl65535.mrec", b, g_take_len, "header cut short (65535 bytes declared)");
  expect_take_error("cut20.mrec", g_take, 20, "byte 20: header cut short (20 of 32 bytes)");
  memcpy(b, g_take, g_take_len);
  memcpy(b, "MRSTREAX", 8);
  expect_take_error("magic.mrec", b, g_take_len, "byte 0: not a stream recording");
  expect_take_error("empty.mrec", g_take, 0, "byte 0: empty file");
}

static void tools_bad_input_a_damaged_chunk_is_one_line_and_exit_1_in_both(void **state) {
  uint8_t b[sizeof g_take];
  char want[120];
  size_t at = g_chunk_at[20];
  (void)state;
  memcpy(b, g_take, g_take_len);
  put_le(b + at + 8, 0, 4);
  snprintf(want, sizeof want, "byte %zu: chunk length 0 (must be 1..1048576)", at + 8);
  expect_take_error("len0.mrec", b, g_take_len, want);
  put_le(b + at + 8, 0xFFFFFFFFu, 4);
  snprintf(want, sizeof want, "byte %zu: chunk length 4294967295", at + 8);
  expect_take_error("lenmax.mrec", b, g_take_len, want);
  memcpy(b, g_take, g_take_len);
  put_le(b + at, 190000000ull - 1, 8); /* before chunk 19's 190 ms */
  snprintf(want, sizeof want, "byte %zu: chunk time 189999999 ns goes back", at);
  expect_take_error("back.mrec", b, g_take_len, want);
  expect_take_error("lastcut.mrec", g_take, g_take_len - 5, "last chunk cut short");
}

/* One flipped bit in a time field (2^60 ns): no hang, one line. */
static void tools_bad_input_a_jump_in_take_time_ends_both_at_once(void **state) {
  uint8_t b[sizeof g_take];
  char want[120];
  size_t at = g_chunk_at[20];
  (void)state;
  memcpy(b, g_take, g_take_len);
  b[at + 7] ^= 0x10; /* bit 60 of chunk 20's time */
  snprintf(want, sizeof want, "byte %zu: chunk time %llu ns jumps", at,
           (unsigned long long)(200000000ull + (1ull << 60)));
  expect_take_error("jump.mrec", b, g_take_len, want);
}

/* Sources the user got wrong: exit 2 and one line from both programs, and
 * the show never starts (no status line, no summary). */
static void tools_bad_input_bad_glove_sources_are_usage_errors_before_the_show(void **state) {
  char scene[4200], dir_src[4200];
  (void)state;
  snprintf(scene, sizeof scene, "%s/host/scenes/stick.yaml", MR_SOURCE_DIR);
  snprintf(dir_src, sizeof dir_src, "take:%s", g_dir);
  static const struct {
    const char *source, *want;
  } bad[] = {
    { "tcp:127.0.0.1:99999", "tcp:127.0.0.1:99999: port '99999' is not 1..65535" },
    { "tcp-listen:-5", "tcp-listen:-5: port '-5' is not 0..65535" },
    { "serial:/dev/x@-9600", "serial:/dev/x@-9600: baud rate '-9600' is not 1..100000000" },
    { "serial:/dev/null@99999999999", "baud rate '99999999999' is not 1..100000000" },
    { "serial:/dev/ttyNOSUCH7", "serial:/dev/ttyNOSUCH7: no such device" },
    { "pty:/dev/pts/9999", "pty:/dev/pts/9999: no such device" },
    { "take:/nonexistent/t.mrec", "/nonexistent/t.mrec: no such file" },
    { NULL, "is a directory" },
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    const char *src = bad[i].source ? bad[i].source : dir_src;
    tt_output d, r;
    const char *dump[] = { tt_glove_dump, src, NULL };
    const char *show[] = { g_marionette, "run", scene, "-t", "5", "--glove", src, NULL };
    int ds = run(dump, &d), rs = run(show, &r);
    if (ds != 2 || count(d.err, "\n") != 1 || !strstr(d.err, bad[i].want))
      fail_msg("glove-dump %s: exit %d, stderr '%s' (want 2 and '%s')", src, ds, d.err,
               bad[i].want);
    if (rs != 2 || count(r.err, "\n") != 1 || !strstr(r.err, bad[i].want) || r.out[0] != '\0')
      fail_msg("marionette run --glove %s: exit %d, stderr '%s', stdout '%.80s' (want 2, '%s', "
               "and no show)",
               src, rs, r.err, r.out, bad[i].want);
    free(d.out);
    free(d.err);
    free(r.out);
    free(r.err);
  }
}

int main(int argc, char **argv) {
  tt_take_args(argc, argv);
  if (argc > 3) g_marionette = argv[3];
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(tools_bad_input_a_damaged_header_is_one_line_and_exit_1_in_both),
    cmocka_unit_test(tools_bad_input_a_damaged_chunk_is_one_line_and_exit_1_in_both),
    cmocka_unit_test(tools_bad_input_a_jump_in_take_time_ends_both_at_once),
    cmocka_unit_test(tools_bad_input_bad_glove_sources_are_usage_errors_before_the_show),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
