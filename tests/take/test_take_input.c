/* The take room (mr_take) and bad input: a malformed or cut-off take list
 * or take, other scenes, unknown names and numbers past their bounds;
 * each refused with a message that names what and where, or taken as far
 * as it is whole. */
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

/* --- bad input -------------------------------------------------------------- */

/* A malformed takes.json (not JSON; a take without files; an id that is
 * no number) and a take whose file is gone give errors naming the file
 * and what is wrong. */
static void a_malformed_list_or_a_missing_take_file_is_named(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  char book[MR_TAKE_PATH_MAX];
  strcpy(book, tt_path(dir, "book"));
  assert_int_equal(mkdir(book, 0777), 0);
  mr_take_book b;
  mr_take_error err;
  write_text(tt_path(book, "takes.json"), "{ \"format\": 1, \"next_id\": 2, \"takes\": [ ");
  assert_int_equal(mr_take_book_open(book, false, &b, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_FORMAT);
  says(&err, "takes.json: not JSON");
  write_text(tt_path(book, "takes.json"),
             "{\"format\": 1, \"next_id\": 2, \"takes\": [{\"name\": \"x\", \"id\": 1, "
             "\"duration\": 1, \"scene_hash\": \"0\", \"created_unix\": 0, \"deleted\": false, "
             "\"made\": {\"how\": \"recorded\"}}]}");
  assert_int_equal(mr_take_book_open(book, false, &b, &err), -1);
  says(&err, "takes.json: takes[0].files: expected a list");
  write_text(tt_path(book, "takes.json"),
             "{\"format\": 1, \"next_id\": 2, \"takes\": [{\"name\": \"x\", \"id\": \"one\", "
             "\"files\": [\"t0001-g0.mrec\"], \"duration\": 1, \"scene_hash\": \"0\", "
             "\"created_unix\": 0, \"deleted\": false, \"made\": {\"how\": \"recorded\"}}]}");
  assert_int_equal(mr_take_book_open(book, false, &b, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_FORMAT);
  says(&err, "takes.json: takes[0].id: expected a number");
  write_text(tt_path(book, "takes.json"),
             "{\"format\": 1, \"next_id\": 2, \"takes\": [{\"name\": \"x\", \"id\": 1, "
             "\"files\": [\"t0001-g0.mrec\"], \"duration\": 1, \"scene_hash\": \"0\", "
             "\"created_unix\": 0, \"deleted\": false, \"made\": {\"how\": \"recorded\"}}]}");
  if (mr_take_book_open(book, false, &b, &err) != 0) fail_msg("%s", err.msg);
  char paths[8][MR_TAKE_PATH_MAX];
  size_t n;
  assert_int_equal(mr_take_book_paths(&b, "x", paths, 8, &n, &err), -1);
  says(&err, "t0001-g0.mrec");
  assert_int_equal(mr_take_book_trim(&b, "x", 0, 1, NULL, NULL, &err), -1);
  says(&err, "t0001-g0.mrec");
  mr_take_book_close(&b);
  tt_rmdir(book);
  tt_rmdir(dir);
  free(dir);
}

/* Each field of takes.json is checked: a list of another format or a
 * next_id below 1, and an entry whose name is too long, whose id is not
 * whole or not below next_id or given twice, with no files, an empty scene
 * hash or an armed glove past 7, is refused naming the entry and field. */
static void each_field_of_a_take_list_is_checked(void **state) {
  (void)state;
  static const char N64[] = "nnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnn";
  static const char REC[] = "{\"how\": \"recorded\"}";
  static const char ARMS8[] =
      "{\"how\": \"punch\", \"base\": 1, \"over\": 1, \"in\": 0, \"out\": 1, "
      "\"arms\": [[8, 0]]}";
  static const char TWICE[] = ", {\"name\": \"y\", \"id\": 1, \"files\": [\"t0001-g0.mrec\"], "
                              "\"duration\": 1, \"scene_hash\": \"0\", \"created_unix\": 0, "
                              "\"deleted\": false, \"made\": {\"how\": \"recorded\"}}";
  static const char F1[] = "[\"t0001-g0.mrec\"]";
  static const struct {
    const char *format, *next_id, *name, *id, *files, *hash, *made, *more, *what;
  } cases[] = {
    { "2", "2", "x", "1", F1, "0", REC, "", "expected an object with format 1" },
    { "1", "0", "x", "1", F1, "0", REC, "", "expected an object with format 1" },
    { "1", "2", N64, "1", F1, "0", REC, "", "takes[0].name: expected a string" },
    { "1", "2", "x", "1.5", F1, "0", REC, "", "takes[0].id: expected a whole number" },
    { "1", "2", "x", "2", F1, "0", REC, "", "takes[0].id: not below next_id" },
    { "1", "2", "x", "1", F1, "0", REC, TWICE, "takes[1].name: a name or id given twice" },
    { "1", "2", "x", "1", "[]", "0", REC, "", "takes[0].files: expected a list of 1..8" },
    { "1", "2", "x", "1", F1, "", REC, "", "takes[0].scene_hash: expected 16 hex digits" },
    { "1", "2", "x", "1", F1, "0", ARMS8, "", "takes[0].arms: expected [glove 0..7, finger" },
  };
  char *dir = tt_tmpdir();
  char book[MR_TAKE_PATH_MAX], text[1200];
  strcpy(book, tt_path(dir, "book"));
  assert_int_equal(mkdir(book, 0777), 0);
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    snprintf(text, sizeof text,
             "{\"format\": %s, \"next_id\": %s, \"takes\": [{\"name\": \"%s\", \"id\": %s, "
             "\"files\": %s, \"duration\": 1, \"scene_hash\": \"%s\", \"created_unix\": 0, "
             "\"deleted\": false, \"made\": %s}%s]}",
             cases[i].format, cases[i].next_id, cases[i].name, cases[i].id, cases[i].files,
             cases[i].hash, cases[i].made, cases[i].more);
    write_text(tt_path(book, "takes.json"), text);
    mr_take_book b;
    mr_take_error err;
    if (mr_take_book_open(book, false, &b, &err) == 0) fail_msg("case %zu was read", i);
    assert_int_equal(err.status, MR_TAKE_ERR_FORMAT);
    says(&err, cases[i].what);
  }
  assert_string_equal(mr_take_how_name(MR_TAKE_SCALED), "scale");
  assert_string_equal(mr_take_how_name((mr_take_how)(MR_TAKE_SCALED + 1)), "?");
  tt_rmdir(book);
  tt_rmdir(dir);
  free(dir);
}

/* A list of many takes, its takes.json longer than twice the reader's
 * first 4 KiB, reads back whole. */
static void a_long_take_list_reads_back_whole(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  A.n = 10;
  A.info2_at = 0;
  gen_write(&A, tt_path(dir, "a.mrec"));
  char pa[MR_TAKE_PATH_MAX], book[MR_TAKE_PATH_MAX];
  snprintf(pa, sizeof pa, "%s", tt_path(dir, "a.mrec"));
  snprintf(book, sizeof book, "%s", tt_path(dir, "book"));
  const char *p[] = { pa };
  mr_take_book b;
  mr_take_error err;
  if (mr_take_book_open(book, true, &b, &err) != 0) fail_msg("%s", err.msg);
  for (int i = 0; i < 40; i++)
    if (mr_take_book_add(&b, NULL, p, 1, false, NULL, &err) != 0) fail_msg("%s", err.msg);
  mr_take_book_close(&b);
  size_t len;
  free(file_bytes(tt_path(book, "takes.json"), &len));
  assert_true(len > 8192);
  if (mr_take_book_open(book, false, &b, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(b.n, 40);
  assert_int_equal(b.next_id, 41);
  assert_int_equal(mr_take_book_find(&b, "take-40")->id, 40);
  mr_take_book_close(&b);
  tt_rmdir(book);
  tt_rmdir(dir);
  free(dir);
}

/* A take cut off mid-chunk is used up to its last whole chunk, and the
 * operation says so. */
static void a_cut_off_take_is_used_up_to_its_last_whole_chunk_and_says_so(void **state) {
  (void)state;
  mr_take_book b;
  char *dir = book_ab_tmp(&b);
  size_t len;
  char *bytes = file_bytes(tt_path(dir, "a.mrec"), &len);
  FILE *f = fopen(tt_path(dir, "cut.mrec"), "wb");
  fwrite(bytes, 1, len - 7, f);
  fclose(f);
  free(bytes);
  mr_take_error err;
  mr_take_made m;
  const char *p[] = { tt_path(dir, "cut.mrec") };
  if (mr_take_book_add(&b, "cut", p, 1, false, &m, &err) != 0) fail_msg("%s", err.msg);
  if (strstr(m.note, "last whole chunk") == NULL) fail_msg("note: '%s'", m.note);
  if (mr_take_book_trim(&b, "cut", 0.5, 9.0, NULL, &m, &err) != 0) fail_msg("%s", err.msg);
  if (strstr(m.note, "cut.mrec") == NULL && strstr(m.note, ".mrec") == NULL)
    fail_msg("note: '%s'", m.note);
  mr_take_rec r;
  load_take(&b, m.name, &r);
  assert_false(r.truncated);
  assert_int_equal(r.frames[r.n_frames - 1].msg.u.sample.seq, A.n - 2);
  mr_take_rec_free(&r);
  /* Of two gloves cut off, the note names the first. */
  const char *p2[] = { p[0], p[0] };
  if (mr_take_book_add(&b, "cut2", p2, 2, false, &m, &err) != 0) fail_msg("%s", err.msg);
  if (mr_take_book_trim(&b, "cut2", 0.5, 9.0, NULL, &m, &err) != 0) fail_msg("%s", err.msg);
  if (strstr(m.note, "-g0.mrec") == NULL) fail_msg("note: '%s'", m.note);
  book_done(&b, dir);
}

/* Takes of different scenes, unknown names, bad names and absurd numbers
 * are refused, each with a message saying what. */
static void different_scenes_unknown_names_and_absurd_numbers_are_refused(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  B.scene = 0x00000000beefcafeull;
  mr_take_book b;
  book_ab(dir, &b);
  /* The list writes each scene hash as 16 hex digits, leading zeros too. */
  size_t len;
  char *list = file_bytes(tt_path(tt_path(dir, "book"), "takes.json"), &len);
  if (strstr(list, "\"00000000beefcafe\"") == NULL) fail_msg("%s", list);
  free(list);
  mr_take_error err;
  mr_take_punch_def d = mr_default_take_punch_def();
  d.base = "a";
  d.over = "b";
  d.arms[0] = (mr_take_arm){ 0, 1 };
  d.n_arms = 1;
  d.t_in = 1;
  d.t_out = 2;
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_SCENE);
  says(&err, "5ce9e5ce9e000001");
  says(&err, "00000000beefcafe");
  /* Nor is a take of two gloves recorded against different scenes, or
   * one whose file is missing, added to the list. */
  char pa[MR_TAKE_PATH_MAX], pb[MR_TAKE_PATH_MAX];
  snprintf(pa, sizeof pa, "%s", tt_path(dir, "a.mrec"));
  snprintf(pb, sizeof pb, "%s", tt_path(dir, "b.mrec"));
  const char *both[] = { pa, pb }, *gone[] = { pa, tt_path(dir, "gone.mrec") };
  assert_int_equal(mr_take_book_add(&b, "ab", both, 2, false, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_SCENE);
  says(&err, "b.mrec: recorded against scene 00000000beefcafe");
  says(&err, "5ce9e5ce9e000001");
  assert_int_equal(mr_take_book_add(&b, "gone", gone, 2, false, NULL, &err), -1);
  says(&err, "gone.mrec");
  d.over = "nope";
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_NAME);
  says(&err, "'nope'");
  d.over = "a";
  d.t_in = 3;
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  d.t_in = NAN;
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  d.t_in = 1;
  d.arms[0].glove = 1; /* the take has one glove */
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  says(&err, "1:1");
  mr_take_punch_def raw;
  memset(&raw, 0, sizeof raw);
  assert_int_equal(mr_take_book_punch(&b, &raw, NULL, &err), -1);
  says(&err, "mr_default_take_punch_def");
  mr_take_smooth_def sraw;
  memset(&sraw, 0, sizeof sraw);
  assert_int_equal(mr_take_book_smooth(&b, "a", &sraw, NULL, NULL, &err), -1);
  says(&err, "mr_default_take_smooth_def");
  /* Channels of a glove the take has not, as the punch's armed ones. */
  mr_take_smooth_def sd = mr_default_take_smooth_def();
  sd.channels[0] = (mr_take_arm){ 1, 2 };
  sd.n_channels = 1;
  assert_int_equal(mr_take_book_smooth(&b, "a", &sd, NULL, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "channel 1:2: take 'a' has gloves 0..0");
  double off[MR_TAKE_MAX_GLOVES][MR_TAKE_CHANNELS] = { { 0 } };
  off[0][1] = 0.5;
  off[3][4] = -0.25;
  assert_int_equal(mr_take_book_offset(&b, "a", off, NULL, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "channel 3:4: take 'a' has gloves 0..0");
  assert_int_equal(mr_take_book_scale(&b, "a", -0.5, NULL, NULL, &err), -1);
  says(&err, "-0.5");
  assert_int_equal(mr_take_book_scale(&b, "a", NAN, NULL, NULL, &err), -1);
  assert_int_equal(mr_take_book_split(&b, "a", NAN, NULL, NULL, NULL, &err), -1);
  assert_int_equal(mr_take_book_split(&b, "a", 60.0, NULL, NULL, NULL, &err), -1);
  assert_int_equal(mr_take_book_trim(&b, "a", 2, 1, NULL, NULL, &err), -1);
  assert_int_equal(mr_take_book_rename(&b, "a", "x/y", &err), -1);
  assert_int_equal(mr_take_book_rename(&b, "a", "", &err), -1);
  assert_int_equal(mr_take_book_rename(&b, "a", "b", &err), -1);
  assert_int_equal(mr_take_book_restore(&b, "a", &err), -1);
  says(&err, "take 'a' is not deleted");
  size_t n;
  mr_take_arm arms[4];
  assert_int_equal(mr_take_arms_parse("0:pinky", arms, 4, &n, &err), -1);
  assert_int_equal(mr_take_arms_parse("9:1", arms, 4, &n, &err), -1);
  /* Nothing refused left a take behind. */
  assert_int_equal(b.n, 2);
  book_done(&b, dir);
}

/* Without a valid range, a take reads raw counts by its glove's ADC full
 * scale, as the host does (host/glove): 2^bits - 1 for 1..16 bits, the
 * 12-bit scale for any other number and before any INFO. */
static void a_take_reads_counts_by_the_adc_full_scale_its_info_gives(void **state) {
  (void)state;
  static const struct {
    int bits;
    double full;
  } cases[] = { { 1, 1 }, { 10, 1023 }, { 12, 4095 }, { 16, 65535 }, { 0, 4095 }, { 17, 4095 } };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    gp_info info;
    memset(&info, 0, sizeof info);
    info.adc_bits = (uint8_t)cases[i].bits;
    mr_take_cal c = mr_take_cal_of(&info);
    if (c.full != cases[i].full || mr_take_cal_value(&c, 2, 1) != 1.0 / cases[i].full)
      fail_msg("%d bits: full scale %g, expected %g", cases[i].bits, c.full, cases[i].full);
    assert_int_equal(mr_take_cal_raw(&c, 2, 1.0 / cases[i].full), 1);
  }
  mr_take_cal none = mr_take_cal_of(NULL);
  assert_true(none.full == 4095.0);
}

/* A take may have one file per glove, up to MR_TAKE_MAX_GLOVES: the most
 * is added, named and listed whole, and read back so from the list; one
 * more, or none, is refused. All 40 channels of the most gloves may be
 * armed or smoothed at once, 41 not. */
static void a_take_of_the_most_gloves_is_added_and_one_more_is_refused(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  gen_write(&A, tt_path(dir, "a.mrec"));
  char pa[MR_TAKE_PATH_MAX];
  snprintf(pa, sizeof pa, "%s", tt_path(dir, "a.mrec"));
  const char *paths[MR_TAKE_MAX_GLOVES + 1];
  for (int g = 0; g <= MR_TAKE_MAX_GLOVES; g++) paths[g] = pa;
  mr_take_book b;
  mr_take_error err;
  char book[MR_TAKE_PATH_MAX];
  snprintf(book, sizeof book, "%s", tt_path(dir, "book"));
  if (mr_take_book_open(book, true, &b, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(mr_take_book_add(&b, "nine", paths, MR_TAKE_MAX_GLOVES + 1, false, NULL, &err),
                   -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "got 9");
  assert_int_equal(mr_take_book_add(&b, "none", paths, 0, false, NULL, &err), -1);
  if (mr_take_book_add(&b, "eight", paths, MR_TAKE_MAX_GLOVES, false, NULL, &err) != 0)
    fail_msg("%s", err.msg);
  assert_int_equal(b.n, 1);
  mr_take_book_close(&b);
  if (mr_take_book_open(book, false, &b, &err) != 0) fail_msg("%s", err.msg);
  const mr_take_entry *e = mr_take_book_find(&b, "eight");
  assert_non_null(e);
  assert_int_equal(e->how, MR_TAKE_RECORDED);
  assert_int_equal(e->source_id, 0);
  char got[MR_TAKE_MAX_GLOVES][MR_TAKE_PATH_MAX];
  size_t n;
  if (mr_take_book_paths(&b, "eight", got, MR_TAKE_MAX_GLOVES, &n, &err) != 0)
    fail_msg("%s", err.msg);
  assert_int_equal(n, MR_TAKE_MAX_GLOVES);
  size_t len_a, len;
  char *want = file_bytes(pa, &len_a);
  for (int g = 0; g < MR_TAKE_MAX_GLOVES; g++) {
    char name[32];
    snprintf(name, sizeof name, "-g%d.mrec", g);
    if (strstr(got[g], name) == NULL) fail_msg("glove %d's file is %s", g, got[g]);
    char *bytes = file_bytes(got[g], &len);
    assert_int_equal(len, len_a);
    assert_memory_equal(bytes, want, len);
    free(bytes);
  }
  free(want);
  /* All 40 of its channels may be armed or smoothed at once, no more. */
  mr_take_punch_def d = mr_default_take_punch_def();
  d.base = d.over = "eight";
  d.t_in = 1.0;
  d.t_out = 2.0;
  mr_take_smooth_def sd = mr_default_take_smooth_def();
  for (int g = 0; g < MR_TAKE_MAX_GLOVES; g++)
    for (int k = 0; k < MR_TAKE_CHANNELS; k++)
      d.arms[d.n_arms++] = sd.channels[sd.n_channels++] = (mr_take_arm){ g, k };
  if (mr_take_book_punch(&b, &d, NULL, &err) != 0) fail_msg("%s", err.msg);
  if (mr_take_book_smooth(&b, "eight", &sd, NULL, NULL, &err) != 0) fail_msg("%s", err.msg);
  d.n_arms = sd.n_channels = MR_TAKE_MAX_ARMS + 1;
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  says(&err, "expected 1..40 armed channels, got 41");
  assert_int_equal(mr_take_book_smooth(&b, "eight", &sd, NULL, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "expected at most 40 channels to smooth, got 41");
  assert_int_equal(b.n, 3);
  mr_take_book_close(&b);
  tt_rmdir(book);
  tt_rmdir(dir);
  free(dir);
}

/* A value goes back to the nearest count of its calibration, clamped to
 * 0..4095 (one count past either end is that end), NaN as the low end; an
 * INFO whose range is empty (max == min) reads by the full scale. */
static void a_value_goes_back_to_the_nearest_count_within_the_adc_range(void **state) {
  (void)state;
  gp_info info = gp_default_glove_info();
  info.cal_state = GP_CAL_VALID;
  for (int k = 0; k < 5; k++) {
    info.cal_min[k] = 200;
    info.cal_max[k] = 3800;
  }
  info.cal_max[4] = 200;
  mr_take_cal c = mr_take_cal_of(&info);
  assert_true(c.ranged[1]);
  assert_int_equal(mr_take_cal_raw(&c, 1, 0.5), 2000);
  assert_int_equal(mr_take_cal_raw(&c, 1, NAN), 200);
  assert_false(c.ranged[4]);
  assert_true(mr_take_cal_value(&c, 4, 1000) == 1000.0 / 4095.0);
  assert_int_equal(mr_take_cal_raw(&c, 4, NAN), 0);
  assert_int_equal(mr_take_cal_raw(&c, 4, -1.0 / 4095.0), 0);
  assert_int_equal(mr_take_cal_raw(&c, 4, 1.0), 4095);
  assert_int_equal(mr_take_cal_raw(&c, 4, 4096.0 / 4095.0), 4095);
}

/* An INFO announcing another build's spec hash is not a frame: its range
 * is not applied, and the SAMPLEs read by the 12-bit full scale. */
static void an_info_of_another_spec_hash_is_not_a_frame(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  A.info.spec_hash ^= 1u;
  A.info2 = A.info;
  gen_write(&A, tt_path(dir, "a.mrec"));
  mr_take_rec r;
  mr_take_error err;
  if (mr_take_rec_load(tt_path(dir, "a.mrec"), &r, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(r.n_frames, A.n);
  assert_int_equal(r.frames[0].msg.type, GP_SAMPLE);
  assert_true(mr_take_rec_value(&r, 0, 1) == A.ch[0][1] / 4095.0);
  mr_take_rec_free(&r);
  tt_rmdir(dir);
  free(dir);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_malformed_list_or_a_missing_take_file_is_named),
    cmocka_unit_test(a_long_take_list_reads_back_whole),
    cmocka_unit_test(each_field_of_a_take_list_is_checked),
    cmocka_unit_test(a_cut_off_take_is_used_up_to_its_last_whole_chunk_and_says_so),
    cmocka_unit_test(different_scenes_unknown_names_and_absurd_numbers_are_refused),
    cmocka_unit_test(a_take_of_the_most_gloves_is_added_and_one_more_is_refused),
    cmocka_unit_test(a_take_reads_counts_by_the_adc_full_scale_its_info_gives),
    cmocka_unit_test(a_value_goes_back_to_the_nearest_count_within_the_adc_range),
    cmocka_unit_test(an_info_of_another_spec_hash_is_not_a_frame),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
