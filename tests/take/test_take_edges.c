/* The take room (mr_take) at its edges: chunks that cut frames, the
 * bounds of punch, split, trim, offset and smoothing, names at their
 * longest and channel lists. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <sys/stat.h>

#include "mr_take.h"
#include "proc.h"
#include "take_gen.h"
#include "take_rig.h"

/* --- chunks that cut frames ------------------------------------------------- */

/* Writes to dir/cut.mrec, and reads into r, a take of A's calibration
 * whose chunks cut its frames unevenly (times in ms): the INFO at 0; sample 0 but its delimiter at 10,
 * the delimiter alone at 30; sample 1's first 10 bytes at 40, the rest at
 * 50; samples 2 and 3 in one chunk at 60; sample 4 at 70. Sample s holds
 * 1000 + 100 s + 10 k in finger k. */
static void cut_take(const char *dir, mr_take_rec *r) {
  const char *path = tt_path(dir, "cut.mrec");
  gen_init(&A, 200, 3800, 0);
  mr_rec_writer w;
  mr_io_error ie;
  if (mr_rec_writer_open_scene(&w, path, GP_SPEC_HASH, 0, 0, &ie) != 0) fail_msg("%s", ie.msg);
  uint8_t s[5][GP_MAX_WIRE], info[GP_MAX_WIRE], two[2 * GP_MAX_WIRE];
  size_t n[5], ni = gp_glove_info_encode(&A.info, info, sizeof info);
  for (int i = 0; i < 5; i++) {
    uint16_t ch[5];
    for (int k = 0; k < 5; k++) ch[k] = (uint16_t)(1000 + 100 * i + 10 * k);
    gp_sample smp = gp_glove_sample((uint16_t)i, (uint32_t)(10000 * i), ch);
    n[i] = gp_glove_sample_encode(&smp, GP_SPEC_HASH, s[i], sizeof s[i]);
  }
  memcpy(two, s[2], n[2]);
  memcpy(two + n[2], s[3], n[3]);
  const struct {
    uint64_t ms;
    const uint8_t *b;
    size_t n;
  } c[] = { { 0, info, ni },   { 10, s[0], n[0] - 1 },       { 30, s[0] + n[0] - 1, 1 },
            { 40, s[1], 10 },  { 50, s[1] + 10, n[1] - 10 }, { 60, two, n[2] + n[3] },
            { 70, s[4], n[4] } };
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++)
    if (mr_rec_writer_add(&w, c[i].ms * 1000000u, c[i].b, c[i].n, &ie) != 0) fail_msg("%s", ie.msg);
  if (mr_rec_writer_close(&w, &ie) != 0) fail_msg("%s", ie.msg);
  mr_take_error err;
  if (mr_take_rec_load(path, r, &err) != 0) fail_msg("%s", err.msg);
}

/* A frame is read at the chunk holding its delimiter, even when that chunk
 * is the delimiter alone; the newest SAMPLE at or before a time counts one
 * read at that very time, and of two read at once the later. */
static void a_frame_is_read_at_the_chunk_holding_its_delimiter(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  mr_take_rec r;
  mr_take_error err;
  cut_take(dir, &r);
  static const uint64_t ms[] = { 0, 30, 50, 60, 60, 70 };
  static const size_t chunk[] = { 0, 2, 4, 5, 5, 6 };
  assert_int_equal(r.n_frames, 6);
  for (size_t i = 0; i < r.n_frames; i++) {
    assert_int_equal(r.frames[i].t_ns, ms[i] * 1000000u);
    assert_int_equal(r.frames[i].chunk, chunk[i]);
  }
  assert_int_equal(mr_take_rec_sample_at(&r, 29999999u), -1);
  assert_int_equal(mr_take_rec_sample_at(&r, 30000000u), 1);
  assert_int_equal(mr_take_rec_sample_at(&r, 60000000u), 4);
  uint16_t ch[MR_TAKE_CHANNELS] = { 0 };
  assert_int_equal(mr_take_rec_set_sample(&r, 0, ch, &err), -1);
  says(&err, "frame 0 is not a SAMPLE");
  assert_int_equal(mr_take_rec_set_sample(&r, r.n_frames, ch, &err), -1);
  says(&err, "frame 6 is not a SAMPLE");
  mr_take_rec_free(&r);
  tt_rmdir(dir);
  free(dir);
}

/* Trimmed from 45 ms, the take starts on a frame: the chunk at 50 ms holds
 * only the end of sample 1 and is dropped whole, so the INFO leads, then
 * samples 2 and 3 at 15 ms and sample 4 at 25 ms. */
static void a_trim_that_starts_inside_a_frame_drops_its_end(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  mr_take_rec r, t;
  mr_take_error err;
  cut_take(dir, &r);
  if (mr_take_trim_rec(&r, 0.045, INFINITY, &t, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(t.n_chunks, 3);
  assert_int_equal(t.chunks[1].t_ns, 15000000u);
  assert_int_equal(t.chunks[2].t_ns, 25000000u);
  assert_int_equal(t.len, r.chunks[0].len + r.chunks[5].len + r.chunks[6].len);
  assert_memory_equal(t.data + t.chunks[1].off, r.data + r.chunks[5].off, r.chunks[5].len);
  assert_int_equal(t.n_frames, 4);
  assert_int_equal(t.frames[1].msg.u.sample.seq, 2);
  mr_take_rec_free(&r);
  mr_take_rec_free(&t);
  tt_rmdir(dir);
  free(dir);
}

/* An offset of 10 ms on the index finger: each SAMPLE takes the index
 * value of the newest read at or before 10 ms earlier (one read exactly
 * then counts), the first SAMPLE's when none is; the middle finger, offset
 * 0, is untouched even where two SAMPLEs are read at once. */
static void an_offset_takes_the_sample_read_exactly_then_and_the_first_before_any(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  mr_take_rec r;
  mr_take_error err;
  cut_take(dir, &r);
  const double off[MR_TAKE_CHANNELS] = { 0, 0.01, 0, 0, 0 };
  if (mr_take_offset_rec(&r, off, &err) != 0) fail_msg("%s", err.msg);
  /* Samples read at 30, 50, 60, 60, 70 ms take samples 0, 0, 1, 1, 3. */
  static const int from[] = { 0, 0, 1, 1, 3 };
  for (int s = 0; s < 5; s++) {
    assert_int_equal(r.frames[s + 1].msg.u.sample.ch[1], 1000 + 100 * from[s] + 10);
    assert_int_equal(r.frames[s + 1].msg.u.sample.ch[2], 1000 + 100 * s + 20);
  }
  mr_take_rec_free(&r);
  tt_rmdir(dir);
  free(dir);
}

/* Called on a take directly, the edits refuse what the book refuses: a
 * punch-in not before its punch-out, a min_cutoff of 0; and scaling that
 * would stretch a silence past an hour, while one of exactly an hour is
 * taken. */
static void the_edits_refuse_an_empty_punch_a_zero_cutoff_and_a_silence_past_an_hour(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  mr_take_rec r, over;
  mr_take_error err;
  cut_take(dir, &r);
  if (mr_take_rec_copy(&over, &r, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(mr_take_punch_rec(&r, &over, 1u, 0.04, 0.04, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "the punch-in time 0.04 s must come before the punch-out time 0.04 s");
  assert_int_equal(mr_take_smooth_rec(&r, 1u, 0.0, 0.0, 1.0, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "got 0, 0, 1");
  mr_take_rec t;
  assert_int_equal(mr_take_trim_rec(&r, -0.5, 1.0, &t, &err), -1);
  says(&err, "the start time must be a time 0..1e6 s, got -0.5");
  mr_take_rec_free(&r);
  mr_take_rec_free(&over);
  /* Two chunks 2400 s apart: by 1.5 the silence is an hour, by 1.6 more. */
  mr_rec_writer w;
  mr_io_error ie;
  const uint8_t byte = 1;
  if (mr_rec_writer_open(&w, tt_path(dir, "gap.mrec"), GP_SPEC_HASH, 0, &ie) != 0 ||
      mr_rec_writer_add(&w, 0, &byte, 1, &ie) != 0 ||
      mr_rec_writer_add(&w, 2400000000000u, &byte, 1, &ie) != 0 ||
      mr_rec_writer_close(&w, &ie) != 0)
    fail_msg("%s", ie.msg);
  if (mr_take_rec_load(tt_path(dir, "gap.mrec"), &r, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(mr_take_scale_rec(&r, 1.6, &err), -1);
  says(&err, "scaled by 1.6, the take would hold a silence over an hour");
  if (mr_take_scale_rec(&r, 1.5, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(r.chunks[1].t_ns, 3600000000000u);
  mr_take_rec_free(&r);
  tt_rmdir(dir);
  free(dir);
}

/* The edges of the book's operations: a take of no known scene is punched
 * into one of a known scene; an armed glove the over take has not changes
 * nothing; a punch-out past 1e6 s, an offset past an hour, a split at 0 or
 * at the take's end and a negative start are refused, each saying what;
 * an offset of exactly an hour is taken. */
static void the_edges_of_punch_split_trim_and_offset(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  B.scene = 0;
  mr_take_book b;
  book_ab(dir, &b);
  mr_take_error err;
  punch(&b, "ab", 2.0, 4.0); /* b's scene is not known */
  char pa[MR_TAKE_PATH_MAX];
  snprintf(pa, sizeof pa, "%s", tt_path(dir, "a.mrec"));
  const char *two[] = { pa, pa };
  if (mr_take_book_add(&b, "aa", two, 2, false, NULL, &err) != 0) fail_msg("%s", err.msg);
  mr_take_punch_def d = mr_default_take_punch_def();
  d.base = "aa";
  d.over = "b";
  d.name = "aab";
  d.arms[0] = (mr_take_arm){ 1, 1 };
  d.n_arms = 1;
  d.t_in = 1.0;
  d.t_out = 2.0;
  if (mr_take_book_punch(&b, &d, NULL, &err) != 0) fail_msg("%s", err.msg);
  char paths[MR_TAKE_MAX_GLOVES][MR_TAKE_PATH_MAX];
  size_t n, len_a, len;
  if (mr_take_book_paths(&b, "aab", paths, MR_TAKE_MAX_GLOVES, &n, &err) != 0)
    fail_msg("%s", err.msg);
  char *want = file_bytes(pa, &len_a), *got = file_bytes(paths[1], &len);
  assert_int_equal(len, len_a);
  assert_memory_equal(got, want, len);
  free(want);
  free(got);
  d.base = "a";
  d.name = NULL;
  d.arms[0] = (mr_take_arm){ 0, 1 };
  d.t_out = 2e6;
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "the punch-out time must be a time 0..1e6 s, got 2e+06");
  d.t_in = -0.5;
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  says(&err, "expected 0 <= punch-in < punch-out, got -0.5");
  assert_int_equal(mr_take_book_split(&b, "a", 0.0, NULL, NULL, NULL, &err), -1);
  says(&err, "the split time must be a time > 0 s, got 0");
  assert_int_equal(mr_take_book_split(&b, "a", 6.0, NULL, NULL, NULL, &err), -1);
  says(&err, "take 'a' lasts 6 s: nothing after 6 s");
  assert_int_equal(mr_take_book_trim(&b, "a", -0.5, 1.0, NULL, NULL, &err), -1);
  says(&err, "expected 0 <= from < to, got -0.5 and 1 s");
  double off[MR_TAKE_MAX_GLOVES][MR_TAKE_CHANNELS] = { { 0 } };
  off[0][3] = 3600.0;
  off[0][4] = -3600.0;
  if (mr_take_book_offset(&b, "a", off, "hour", NULL, &err) != 0) fail_msg("%s", err.msg);
  X = A;
  for (size_t i = 0; i < A.n; i++) {
    X.ch[i][3] = A.ch[0][3];
    X.ch[i][4] = A.ch[A.n - 1][4];
  }
  mr_take_rec r;
  load_take(&b, "hour", &r);
  holds(&r, &X);
  mr_take_rec_free(&r);
  off[0][3] = 3600.5;
  assert_int_equal(mr_take_book_offset(&b, "a", off, NULL, NULL, &err), -1);
  says(&err, "an offset must be -3600..3600 s, got 3600.5 for 0:3");
  assert_int_equal(b.n, 6);
  book_done(&b, dir);
}

/* A take's name holds at most 63 bytes and a book's directory at most 447;
 * a take whose first glove was recorded against a scene and second
 * against none is added, as of that scene. */
static void names_at_their_longest_and_a_glove_of_no_scene(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  B.scene = 0;
  mr_take_book b;
  book_ab(dir, &b);
  mr_take_error err;
  char name[MR_TAKE_NAME_MAX + 1];
  memset(name, 'n', MR_TAKE_NAME_MAX);
  name[MR_TAKE_NAME_MAX] = '\0';
  assert_int_equal(mr_take_book_check_name(&b, name, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_NAME);
  says(&err, "at most 63 bytes");
  name[MR_TAKE_NAME_MAX - 1] = '\0';
  assert_int_equal(mr_take_book_check_name(&b, name, &err), 0);
  char pa[MR_TAKE_PATH_MAX], pb[MR_TAKE_PATH_MAX];
  snprintf(pa, sizeof pa, "%s", tt_path(dir, "a.mrec"));
  snprintf(pb, sizeof pb, "%s", tt_path(dir, "b.mrec"));
  const char *ab[] = { pa, pb };
  if (mr_take_book_add(&b, name, ab, 2, false, NULL, &err) != 0) fail_msg("%s", err.msg);
  assert_true(mr_take_book_find(&b, name)->scene_hash == 0x5ce9e5ce9e000001ull);
  mr_take_book_close(&b);
  char longest[MR_TAKE_PATH_MAX];
  memset(longest, 'd', MR_TAKE_PATH_MAX - 64);
  longest[0] = '/';
  longest[MR_TAKE_PATH_MAX - 64] = '\0';
  assert_int_equal(mr_take_book_open(longest, false, &b, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "expected a book's directory");
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

/* A channel list: gloves 0..7, fingers 0..4 or a finger's whole name, and
 * no more channels than there is room for. */
static void a_channel_list_takes_gloves_0_to_7_and_fingers_by_number_or_whole_name(void **state) {
  (void)state;
  mr_take_arm arms[2];
  size_t n;
  mr_take_error err;
  if (mr_take_arms_parse("7:little,0:4", arms, 2, &n, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(n, 2);
  assert_int_equal(arms[0].glove, 7);
  assert_int_equal(arms[0].finger, 4);
  assert_int_equal(arms[1].glove, 0);
  assert_int_equal(arms[1].finger, 4);
  assert_int_equal(mr_take_arms_parse("8:1", arms, 2, &n, &err), -1);
  says(&err, "glove 0..7), got '8:1'");
  assert_int_equal(mr_take_arms_parse("0:5", arms, 2, &n, &err), -1);
  says(&err, "got '5'");
  assert_int_equal(mr_take_arms_parse("0:thu", arms, 2, &n, &err), -1);
  says(&err, "got 'thu'");
  assert_int_equal(mr_take_arms_parse("0:1,0:2,0:3", arms, 2, &n, &err), -1);
  says(&err, "more than 2 channels");
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_frame_is_read_at_the_chunk_holding_its_delimiter),
    cmocka_unit_test(a_trim_that_starts_inside_a_frame_drops_its_end),
    cmocka_unit_test(an_offset_takes_the_sample_read_exactly_then_and_the_first_before_any),
    cmocka_unit_test(the_edits_refuse_an_empty_punch_a_zero_cutoff_and_a_silence_past_an_hour),
    cmocka_unit_test(the_edges_of_punch_split_trim_and_offset),
    cmocka_unit_test(names_at_their_longest_and_a_glove_of_no_scene),
    cmocka_unit_test(a_channel_list_takes_gloves_0_to_7_and_fingers_by_number_or_whole_name),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
