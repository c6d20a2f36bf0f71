/* `marionette run` with a take book (issue 23): a take performed over
 * another with two channels armed and punched in, from the command line
 * and in the window under Xvfb by its keys; the book then holds the raw
 * take and the take library's merge of it, byte for byte. And the bad
 * inputs: each exits 2 with one line. The performers are takes written
 * here and replayed (--replay) or played live by the keyboard's glove. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "app_test.h"
#include "mr_io.h"
#include "mr_take.h"
#include "proc.h"

#ifndef MR_APP_TEST_BACKEND
#define MR_APP_TEST_BACKEND "auto"
#endif

static char *marionette;

#define STICK MR_SOURCE_DIR "/host/scenes/stick.yaml"

/* A performer's take: INFO, then 100 Hz samples for `secs` s, each
 * finger a wave of its own, shifted by phase. */
static void performer(const char *path, double secs, double phase) {
  mr_rec_writer w;
  mr_io_error err;
  if (mr_rec_writer_open(&w, path, GP_SPEC_HASH, 0, &err) != 0) fail_msg("%s", err.msg);
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_INFO;
  m.u.info.proto_major = 1;
  m.u.info.spec_hash = GP_SPEC_HASH;
  m.u.info.hand = GP_HAND_RIGHT;
  m.u.info.n_channels = 5;
  m.u.info.adc_bits = 12;
  m.u.info.frame_rate_hz = 100;
  uint8_t wire[GP_MAX_WIRE + 2];
  size_t n = gp_encode(&m, GP_SPEC_HASH, wire, sizeof wire);
  assert_int_equal(mr_rec_writer_add(&w, 0, wire, n, &err), 0);
  for (int i = 1; i <= (int)(secs * 100); i++) {
    memset(&m, 0, sizeof m);
    m.type = GP_SAMPLE;
    m.u.sample.seq = (uint16_t)i;
    m.u.sample.t_us = (uint32_t)i * 10000u;
    for (int c = 0; c < 5; c++)
      m.u.sample.ch[c] = (uint16_t)(2048 + 1500 * sin(0.9 * (c + 1) * i * 0.01 + phase));
    n = gp_encode(&m, GP_SPEC_HASH, wire, sizeof wire);
    assert_int_equal(mr_rec_writer_add(&w, (uint64_t)i * 10000000u, wire, n, &err), 0);
  }
  assert_int_equal(mr_rec_writer_close(&w, &err), 0);
}

static char *run(char **argv, tt_output *o) {
  assert_int_equal(tt_capture(argv, o), 0);
  return o->err;
}

/* The book's take named name: its one file loaded. */
static void load_take(const mr_take_book *b, const char *name, mr_take_rec *r) {
  char paths[1][MR_TAKE_PATH_MAX];
  size_t n = 0;
  mr_take_error err;
  if (mr_take_book_paths(b, name, paths, 1, &n, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(n, 1);
  if (mr_take_rec_load(paths[0], r, &err) != 0) fail_msg("%s", err.msg);
}

/* The book holds base, raw and merged, and merged is base with raw's
 * channels in mask punched in over [t_in, t_out), as the take library
 * makes it from the two files: byte for byte. */
static void book_holds_the_merge(const char *book, const char *base, const char *raw,
                                 const char *merged, unsigned mask, double t_in, double t_out) {
  mr_take_book b;
  mr_take_error err;
  if (mr_take_book_open(book, false, &b, &err) != 0) fail_msg("%s", err.msg);
  mr_take_rec rb, rr, rm;
  load_take(&b, base, &rb);
  load_take(&b, raw, &rr);
  load_take(&b, merged, &rm);
  const mr_take_entry *e = mr_take_book_find(&b, merged);
  assert_non_null(e);
  assert_int_equal(e->how, MR_TAKE_PUNCHED);
  assert_true(fabs(e->t0 - t_in) < 1e-9 && fabs(e->t1 - t_out) < 1e-9);
  /* The raw take is kept whole: it starts before the punch-in. */
  assert_true(rr.n_frames > 0 && rr.chunks[0].t_ns < mr_take_ns(t_in));
  if (mr_take_punch_rec(&rb, &rr, mask, t_in, t_out, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(rb.len, rm.len);
  assert_int_equal(rb.n_chunks, rm.n_chunks);
  assert_memory_equal(rb.data, rm.data, rb.len);
  /* And it differs from the base: the punch did something. */
  mr_take_rec orig;
  load_take(&b, base, &orig);
  assert_true(memcmp(orig.data, rm.data, rm.len) != 0);
  mr_take_rec_free(&orig);
  mr_take_rec_free(&rb);
  mr_take_rec_free(&rr);
  mr_take_rec_free(&rm);
  mr_take_book_close(&b);
}

/* Take `name` into the book, recorded from a replayed performer. */
static void record_take(const char *dir, const char *book, const char *name) {
  char perf[600], file[64], stored[128];
  snprintf(file, sizeof file, "perf-%s.mrec", name);
  snprintf(perf, sizeof perf, "%s", tt_path(dir, file));
  performer(perf, 6.0, 0.0);
  char *argv[] = { marionette,   "run",    STICK,        "--replay", perf, "--takes",
                   (char *)book, "--name", (char *)name, "-t",       "5",  NULL };
  tt_output o;
  run(argv, &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  snprintf(stored, sizeof stored, "take '%s' (the raw input) stored in", name);
  assert_non_null(strstr(o.err, stored));
  tt_output_free(&o);
}

static void record_a(const char *dir, const char *book) {
  record_take(dir, book, "A");
}

/* run --over A --arm 0:thumb,0:index --punch 2:4 --name B: the book holds
 * B-raw, the performer's whole input, and B, its thumb and index over A
 * from 2 to 4 s; the note names them. */
static void run_punch_stores_the_raw_take_and_the_merge_of_its_armed_channels(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), book[600], perf[600];
  snprintf(book, sizeof book, "%s", tt_path(dir, "book"));
  record_a(dir, book);
  snprintf(perf, sizeof perf, "%s", tt_path(dir, "perf-b.mrec"));
  performer(perf, 6.0, 1.5);
  char *argv[] = { marionette, "run", STICK,   "--replay",        perf,      "--takes", book,
                   "--over",   "A",   "--arm", "0:thumb,0:index", "--punch", "2:4",     "--name",
                   "B",        NULL };
  tt_output o;
  run(argv, &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  print_message("%s", o.err);
  assert_non_null(strstr(o.err, "take 'B-raw' (the raw input) stored in"));
  assert_non_null(strstr(o.err, "take 'B' is its armed channels over 'A' from 2.000 to 4.000 s"));
  /* The show ended with the punch-out. */
  assert_non_null(strstr(o.out, "simulated: 4.000 s"));
  tt_output_free(&o);
  book_holds_the_merge(book, "A", "B-raw", "B", 0x3, 2.0, 4.0);
  tt_rmdir(dir);
  free(dir);
}

/* run --over A with a channel armed but no punch: no take stored, and
 * the input recorded on the way into the book's folder is gone with it,
 * the book as it was (A's file and the list). */
static void a_pass_over_a_take_that_never_punches_in_leaves_the_book_as_it_was(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), book[600], perf[600];
  snprintf(book, sizeof book, "%s", tt_path(dir, "book"));
  record_a(dir, book);
  const int before = at_count_files(book, "");
  snprintf(perf, sizeof perf, "%s", tt_path(dir, "perf-b.mrec"));
  performer(perf, 2.0, 1.5);
  char *argv[] = { marionette, "run", STICK,   "--replay", perf, "--takes", book,
                   "--over",   "A",   "--arm", "0:thumb",  "-t", "1",       NULL };
  tt_output o;
  run(argv, &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_non_null(strstr(o.err, "nothing punched in over 'A': no take stored"));
  tt_output_free(&o);
  assert_int_equal(at_count_files(book, ".recording-"), 0);
  assert_int_equal(at_count_files(book, ""), before);
  tt_rmdir(dir);
  free(dir);
}

/* Two takes of one book replayed side by side, BOOK:A and BOOK:B: each
 * glove plays its own take's file. */
static void two_takes_of_a_book_replay_side_by_side(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), book[600], ref_a[640], ref_b[640];
  snprintf(book, sizeof book, "%s", tt_path(dir, "book"));
  record_take(dir, book, "A");
  record_take(dir, book, "B");
  snprintf(ref_a, sizeof ref_a, "%s:A", book);
  snprintf(ref_b, sizeof ref_b, "%s:B", book);
  char *argv[] = {
    marionette, "run", STICK, "--replay", ref_a, "--replay", ref_b, "-t", "0.5", NULL
  };
  tt_output o;
  run(argv, &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  for (int k = 1; k <= 2; k++) {
    char live[700];
    snprintf(live, sizeof live, "glove on take:%s/t%04d-g0.mrec: live", book, k);
    if (strstr(o.err, live) == NULL) fail_msg("no '%s' in:\n%s", live, o.err);
  }
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

/* Bad input, each one line on stderr and exit status 2. */
static void bad_take_options_exit_2_with_one_line(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), book[600], perf[600];
  snprintf(book, sizeof book, "%s", tt_path(dir, "book"));
  record_a(dir, book);
  snprintf(perf, sizeof perf, "%s", tt_path(dir, "perf-b.mrec"));
  performer(perf, 1.0, 1.5);
  static const struct {
    const char *opt, *value, *said;
  } cases[] = {
    { "--over", "NOPE", "no take 'NOPE' in the book" },
    { "--speed", "0.3", "expected --speed 1, 0.5 or 0.25, got '0.3'" },
    { "--punch", "4:2", "expected --punch IN:OUT in seconds with 0 <= IN < OUT, got '4:2'" },
    { "--arm", "0:7", "--arm:" },
    { "--arm", "1:thumb", "expected --arm channels of glove 0 to 0 (1 given), got glove 1" },
  };
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    bool over = strcmp(cases[i].opt, "--over") == 0;
    char *argv[] = { marionette,
                     "run",
                     STICK,
                     "--replay",
                     perf,
                     "--takes",
                     book,
                     "--over",
                     over ? "NOPE" : "A",
                     (char *)cases[i].opt,
                     (char *)cases[i].value,
                     NULL };
    if (over) argv[9] = NULL;
    tt_output o;
    run(argv, &o);
    print_message("%s %s: %s", cases[i].opt, cases[i].value, o.err);
    assert_int_equal(o.status, 2);
    assert_int_equal(at_lines(o.err), 1);
    assert_non_null(strstr(o.err, cases[i].said));
    tt_output_free(&o);
  }
  /* A take of the book that is not there, in each command that plays
   * takes: refused, not played without it. */
  char ref[640], out[640], said[1400];
  snprintf(ref, sizeof ref, "%s:NOPE", book);
  snprintf(out, sizeof out, "%s", tt_path(dir, "out"));
  snprintf(said, sizeof said, "take %s: %s: no take named 'NOPE'", ref, book);
  char *runs[][12] = {
    { marionette, "run", STICK, "--replay", ref, "-t", "0.5", NULL },
    { marionette, "render", STICK, "--take", ref, "-o", out, "--time", "0.2", NULL },
    { marionette, "export", ref, "--scene", STICK, "-o", out, NULL },
  };
  for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++) {
    tt_output o;
    run(runs[i], &o);
    print_message("%s %s: %s", runs[i][1], ref, o.err);
    assert_int_equal(o.status, 2);
    assert_int_equal(at_lines(o.err), 1);
    assert_non_null(strstr(o.err, said));
    tt_output_free(&o);
  }
  tt_rmdir(dir);
  free(dir);
}

/* The window tests perform at 25 %: the keys are pressed by the drawing
 * thread on show time, and under the sanitizers on a loaded machine that
 * thread fell so far behind the physics' that a show of 1.5 s ended
 * before its keys came (the merge is the same at any speed). */

/* xvfb-run's path into xvfb, or the test skipped when it is missing.
 * Under the sanitizers, no leak check: the window's GL driver is unloaded
 * before it, leaving stacks no suppression can name (as in
 * test_run_stage.c). */
static void xvfb_or_skip(char *xvfb, size_t size) {
  if (at_which("xvfb-run", xvfb, size) != 0) {
    print_message("xvfb-run is not installed: the window is not tried\n");
    skip();
  }
#ifdef MR_APP_TEST_SANITIZE
  setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
#endif
}

/* Under Xvfb, over take A with the keyboard's glove: F2 and F3 arm its
 * thumb and index, F8 punches in at 0.5 s and out at 1.2 s; the book then
 * holds the raw take and the merge of those two channels over A between
 * the punch frames, and the show starts again over the merged take, where
 * F10 steps to the book's next take. */
static void in_the_window_keys_arm_two_channels_and_punch_a_take_into_the_book(void **state) {
  (void)state;
  char xvfb[512];
  xvfb_or_skip(xvfb, sizeof xvfb);
  char *dir = tt_tmpdir(), book[600];
  snprintf(book, sizeof book, "%s", tt_path(dir, "book"));
  record_a(dir, book);
  char *argv[] = { xvfb,
                   "-a",
                   "-s",
                   "-screen 0 640x480x24",
                   marionette,
                   "run",
                   STICK,
                   "--takes",
                   book,
                   "--over",
                   "A",
                   "--name",
                   "W",
                   "--speed",
                   "0.25",
                   "--keys",
                   "0.2:f2,0.3:f3,0.4:i/1.5,0.5:f8,1.2:f8,1.4:f10",
                   "--size",
                   "160x96",
                   "--time",
                   "1.5",
                   NULL };
  tt_output o;
  run(argv, &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  print_message("%s", o.err);
  assert_non_null(strstr(o.out, "stage: in a window (SDL)"));
  assert_non_null(strstr(o.err, "glove 1: armed: thumb index"));
  assert_non_null(strstr(o.err, "take 'W-raw' (the raw input) stored in"));
  const char *said = strstr(o.err, "take 'W' is its armed channels over 'A' from ");
  assert_non_null(said);
  double t_in = 0, t_out = 0;
  assert_int_equal(sscanf(said + strlen("take 'W' is its armed channels over 'A' from "),
                          "%lf to %lf", &t_in, &t_out),
                   2);
  /* The keys play on the show time of the frames drawn, so a loaded
   * machine presses them later, never earlier. */
  assert_true(t_in >= 0.5 && t_out >= 1.2 && t_out > t_in);
  /* F10 in the show over W: the next take of the book, after the last the
   * first. */
  assert_non_null(strstr(o.err, "take beneath: 'A' (the show starts again from 0)"));
  tt_output_free(&o);
  /* The frames' times, to the ms the note gives them: the book's own. */
  mr_take_book b;
  mr_take_error err;
  assert_int_equal(mr_take_book_open(book, false, &b, &err), 0);
  const mr_take_entry *e = mr_take_book_find(&b, "W");
  assert_non_null(e);
  t_in = e->t0;
  t_out = e->t1;
  mr_take_book_close(&b);
  book_holds_the_merge(book, "A", "W-raw", "W", 0x3, t_in, t_out);
  tt_rmdir(dir);
  free(dir);
}

/* -o DIR over a take: the show punched out at 1 s starts again over the
 * merged take and runs to 1.5 s, and its frames follow the first pass's
 * in the folder: the PNG numbers go on (none is written twice) and the
 * MP4 lasts both passes, 2.5 s at 60 frames a second, not the last one's
 * 1.5 s. */
static void frames_written_over_a_second_pass_follow_the_first(void **state) {
  (void)state;
  char ffmpeg[512];
  if (at_which("ffmpeg", ffmpeg, sizeof ffmpeg) != 0) {
    print_message("ffmpeg is not installed: the video's length is not tried\n");
    skip();
  }
  char *dir = tt_tmpdir(), book[600], perf[600], out[600];
  snprintf(book, sizeof book, "%s", tt_path(dir, "book"));
  snprintf(out, sizeof out, "%s", tt_path(dir, "out"));
  record_a(dir, book);
  snprintf(perf, sizeof perf, "%s", tt_path(dir, "perf-b.mrec"));
  performer(perf, 2.0, 1.5);
  char *argv[] = {
    marionette, "run", STICK,   "--replay", perf,      "--takes",   book,
    "--over",   "A",   "--arm", "0:thumb",  "--punch", "0.5:1",     "-t",
    "1.5",      "-o",  out,     "--size",   "64x48",   "--backend", MR_APP_TEST_BACKEND,
    NULL
  };
  tt_output o;
  run(argv, &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  print_message("%s%s", o.out, o.err);
  assert_non_null(strstr(o.err, "from 0.500 to 1.000 s"));
  const char *said = strstr(o.out, "png frames: ");
  assert_non_null(said);
  unsigned long pngs = strtoul(said + strlen("png frames: "), NULL, 10);
  assert_int_equal(at_count_files(out, "frame_"), pngs);
  assert_true(pngs > 91); /* more than the second pass alone draws */
  assert_non_null(strstr(o.out, "mp4: 151 frames"));
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

/* The book's take name, glove g's file of n loaded. */
static void load_glove(const mr_take_book *b, const char *name, size_t g, size_t n,
                       mr_take_rec *r) {
  char paths[2][MR_TAKE_PATH_MAX];
  size_t got = 0;
  mr_take_error err;
  if (mr_take_book_paths(b, name, paths, 2, &got, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(got, n);
  if (mr_take_rec_load(paths[g], r, &err) != 0) fail_msg("%s", err.msg);
}

/* Under Xvfb, two gloves (two performers replayed on the wall clock)
 * over a take of two: F7 selects the second glove, F2 then arms its
 * thumb, F8 punches in and out. The merged take is the first glove's file
 * of the take beneath as it was, and the second's with the thumb punched
 * in: the library's merge of mask 0x1, byte for byte. */
static void in_the_window_f7_then_f2_arms_the_second_gloves_thumb(void **state) {
  (void)state;
  char xvfb[512];
  xvfb_or_skip(xvfb, sizeof xvfb);
  char *dir = tt_tmpdir(), book[600], p[4][600];
  snprintf(book, sizeof book, "%s", tt_path(dir, "book"));
  for (int i = 0; i < 4; i++) {
    char name[32];
    snprintf(name, sizeof name, "perf-%d.mrec", i);
    snprintf(p[i], sizeof p[i], "%s", tt_path(dir, name));
    performer(p[i], 2.0, 0.7 * i);
  }
  char *arg_a[] = { marionette, "run", STICK,    "--replay", p[0], "--replay", p[1],
                    "--takes",  book,  "--name", "A",        "-t", "1.5",      NULL };
  tt_output o;
  run(arg_a, &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  tt_output_free(&o);
  char *argv[] = { xvfb,       "-a",
                   "-s",       "-screen 0 640x480x24",
                   marionette, "run",
                   STICK,      "--replay",
                   p[2],       "--replay",
                   p[3],       "--real-time",
                   "--takes",  book,
                   "--over",   "A",
                   "--name",   "W",
                   "--speed",  "0.25",
                   "--keys",   "0.2:f7,0.3:f2,0.5:f8,0.9:f8",
                   "--size",   "160x96",
                   "--time",   "1.1",
                   NULL };
  run(argv, &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  print_message("%s", o.err);
  assert_non_null(strstr(o.err, "glove 2: armed: thumb"));
  assert_null(strstr(o.err, "glove 1: armed:"));
  assert_non_null(strstr(o.err, "take 'W' is its armed channels over 'A' from "));
  tt_output_free(&o);
  mr_take_book b;
  mr_take_error err;
  assert_int_equal(mr_take_book_open(book, false, &b, &err), 0);
  const mr_take_entry *e = mr_take_book_find(&b, "W");
  assert_non_null(e);
  mr_take_rec base[2], raw, merged[2];
  for (size_t g = 0; g < 2; g++) {
    load_glove(&b, "A", g, 2, &base[g]);
    load_glove(&b, "W", g, 2, &merged[g]);
  }
  load_glove(&b, "W-raw", 1, 2, &raw);
  assert_int_equal(base[0].len, merged[0].len);
  assert_memory_equal(base[0].data, merged[0].data, base[0].len);
  assert_true(memcmp(base[1].data, merged[1].data, merged[1].len) != 0);
  if (mr_take_punch_rec(&base[1], &raw, 0x1, e->t0, e->t1, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(base[1].len, merged[1].len);
  assert_memory_equal(base[1].data, merged[1].data, merged[1].len);
  for (size_t g = 0; g < 2; g++) {
    mr_take_rec_free(&base[g]);
    mr_take_rec_free(&merged[g]);
  }
  mr_take_rec_free(&raw);
  mr_take_book_close(&b);
  tt_rmdir(dir);
  free(dir);
}

static double wall_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* --speed 0.5: a second of show, headless with the keyboard's glove on
 * the wall clock, takes at least two seconds. Only the lower bound is
 * asserted: a loaded machine makes a run longer, never shorter. */
static void the_speed_option_runs_show_time_at_half_the_wall_clock(void **state) {
  (void)state;
  char *argv[] = { marionette, "run",        "--backend", MR_APP_TEST_BACKEND,
                   STICK,      "--keys",     "0.2:i",     "--time",
                   "1",        "--headless", "--size",    "64x64",
                   "--speed",  "0.5",        "-q",        NULL };
  double t0 = wall_s();
  tt_output o;
  run(argv, &o);
  double wall = wall_s() - t0;
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  print_message("1 s of show at half speed: %.2f s of wall\n", wall);
  assert_non_null(strstr(o.out, "simulated: 1.000 s"));
  assert_true(wall >= 2.0);
  tt_output_free(&o);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s MARIONETTE\n", argv[0]);
    return 2;
  }
  marionette = argv[1];
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(run_punch_stores_the_raw_take_and_the_merge_of_its_armed_channels),
    cmocka_unit_test(a_pass_over_a_take_that_never_punches_in_leaves_the_book_as_it_was),
    cmocka_unit_test(two_takes_of_a_book_replay_side_by_side),
    cmocka_unit_test(bad_take_options_exit_2_with_one_line),
    cmocka_unit_test(in_the_window_keys_arm_two_channels_and_punch_a_take_into_the_book),
    cmocka_unit_test(in_the_window_f7_then_f2_arms_the_second_gloves_thumb),
    cmocka_unit_test(frames_written_over_a_second_pass_follow_the_first),
    cmocka_unit_test(the_speed_option_runs_show_time_at_half_the_wall_clock),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
