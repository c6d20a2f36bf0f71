/* glove-gen's motion scripts: each shape gives the values its formula says,
 * and a bad script is refused naming file, line and column. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <fcntl.h>
#include <unistd.h>

#include "gg_motion.h"
#include "gg_stream.h"
#include "gp.h"
#include "mr_io.h"
#include "tools_proc.h"

static char *g_dir;

static int setup(void **state) {
  (void)state;
  g_dir = tt_tmpdir();
  return g_dir ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  tt_rmdir(g_dir);
  free(g_dir);
  return 0;
}

static const char *write_file(const char *name, const char *text) {
  const char *path = tt_path(g_dir, name);
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fputs(text, f);
  fclose(f);
  return path;
}

static int counts(double v) {
  return (int)lround(v * GG_ADC_MAX);
}

static void load(gg_motion *m, const char *text) {
  char err[600];
  const char *path = write_file("m.txt", text);
  if (gg_motion_load(m, path, 1, err, sizeof err) != 0) fail_msg("%s", err);
}

static void tools_motion_shapes_follow_their_formulas(void **state) {
  gg_motion m;
  uint16_t ch[GG_CHANNELS];
  (void)state;
  load(&m, "# one shape per finger\n"
           "duration 12.5\n"
           "thumb  keys 0:0 1:1 2:0.5:inout\n"
           "index  step from=0.2 to=0.8 at=1\n"
           "middle sine mid=0.5 amp=0.4 freq=1 to=3 over=2\n"
           "ring   const value=0.25\n"
           "little step from=0 to=1 at=0 period=1 duty=0.5\n");
  assert_true(fabs(m.duration_s - 12.5) < 1e-12);

  gg_motion_eval(&m, 0.5, ch);
  assert_int_equal(ch[0], counts(0.5));
  assert_int_equal(ch[1], counts(0.2));
  /* The chirp's phase is the integral of its frequency: at 0.5 s,
   * 1*0.5 + (3-1)*0.25/(2*2) = 0.625 cycles. */
  assert_int_equal(ch[2], counts(0.5 + 0.4 * sin(2 * M_PI * 0.625)));
  assert_int_equal(ch[3], counts(0.25));
  assert_int_equal(ch[4], counts(0));

  gg_motion_eval(&m, 1.25, ch);
  /* smoothstep(0.25) = 0.15625 of the way from 1 down to 0.5. */
  assert_int_equal(ch[0], counts(1 - 0.5 * 0.15625));
  assert_int_equal(ch[1], counts(0.8));
  assert_int_equal(ch[4], counts(1));

  gg_motion_eval(&m, 3, ch);
  assert_int_equal(ch[0], counts(0.5)); /* held after the last key */
  /* After the sweep: (1+3)*2/2 = 4 cycles at 2 s, then 3 Hz. */
  assert_int_equal(ch[2], counts(0.5 + 0.4 * sin(2 * M_PI * (4 + 3 * 1.0))));
  gg_motion_free(&m);
}

static void tools_motion_keys_loop_and_clamp(void **state) {
  gg_motion m;
  uint16_t ch[GG_CHANNELS];
  (void)state;
  load(&m, "all keys loop=1 0:-0.5 1:1.5\n");
  gg_motion_eval(&m, 0, ch);
  assert_int_equal(ch[0], 0);  /* clamped to the ADC range */
  gg_motion_eval(&m, 1.5, ch); /* looped: same as 0.5 */
  assert_int_equal(ch[4], counts(0.5));
  gg_motion_eval(&m, 0.99, ch);
  assert_int_equal(ch[2], GG_ADC_MAX);
  gg_motion_free(&m);
}

static void tools_motion_walk_is_bounded_and_seeded(void **state) {
  gg_motion a, b, c;
  char err[600];
  const char *path = write_file("walk.txt", "0-4 walk start=0.5 sigma=2 min=0.2 max=0.6\n");
  uint16_t va[GG_CHANNELS], vb[GG_CHANNELS], vc[GG_CHANNELS];
  int differs = 0, moved = 0;
  (void)state;
  assert_int_equal(gg_motion_load(&a, path, 7, err, sizeof err), 0);
  assert_int_equal(gg_motion_load(&b, path, 7, err, sizeof err), 0);
  assert_int_equal(gg_motion_load(&c, path, 8, err, sizeof err), 0);
  for (int i = 0; i < 5000; i++) {
    double t = i / 250.0;
    gg_motion_eval(&a, t, va);
    gg_motion_eval(&b, t, vb);
    gg_motion_eval(&c, t, vc);
    assert_memory_equal(va, vb, sizeof va);
    differs |= memcmp(va, vc, sizeof va) != 0;
    moved |= va[0] != counts(0.5);
    for (int k = 0; k < GG_CHANNELS; k++) assert_in_range(va[k], counts(0.2), counts(0.6));
  }
  assert_true(differs);
  assert_true(moved);
  gg_motion_free(&a);
  gg_motion_free(&b);
  gg_motion_free(&c);
}

static void tools_motion_csv_track_interpolates(void **state) {
  gg_motion m;
  uint16_t ch[GG_CHANNELS];
  (void)state;
  write_file("take.csv", "seq,t_us,ch0,ch1,ch2,ch3,ch4,flags,late\n"
                         "0,1000000,0,100,200,300,400,0,0\n"
                         "1,2000000,1000,100,200,300,4095,0,0\n");
  /* Relative to the script's folder. */
  load(&m, "all csv file=take.csv loop=0\nring csv file=take.csv column=0\n");
  gg_motion_eval(&m, 0.5, ch);
  assert_int_equal(ch[0], 500);
  assert_int_equal(ch[1], 100);
  assert_int_equal(ch[3], 500);
  assert_int_equal(ch[4], (400 + GG_ADC_MAX) / 2 + 1); /* 2247.5 rounds up */
  gg_motion_eval(&m, 5, ch);
  assert_int_equal(ch[0], 1000);
  gg_motion_free(&m);
}

/* A .mrec recording as a track: its SAMPLEs timed by their device clock
 * (across its 32-bit wrap), other frames and noise skipped. */
static size_t sample_wire(uint16_t seq, uint32_t t_us, uint8_t *w) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SAMPLE;
  m.u.sample.seq = seq;
  m.u.sample.t_us = t_us;
  for (int c = 0; c < GG_CHANNELS; c++) m.u.sample.ch[c] = (uint16_t)(100 * seq + c);
  return gp_encode(&m, GP_SPEC_HASH, w, GP_MAX_WIRE);
}

static void write_take(const char *name, int cut_last) {
  mr_rec_writer w;
  mr_io_error err;
  uint8_t buf[8 * GP_MAX_WIRE];
  size_t n = 0;
  gp_msg info;
  assert_int_equal(mr_rec_writer_open(&w, tt_path(g_dir, name), GP_SPEC_HASH, 0, &err), 0);
  memset(&info, 0, sizeof info);
  info.type = GP_INFO;
  info.u.info.spec_hash = GP_SPEC_HASH;
  n += gp_encode(&info, GP_SPEC_HASH, buf, GP_MAX_WIRE);
  for (uint16_t k = 0; k < 3; k++) n += sample_wire(k, 0xFFFFF000u + 4000u * k, buf + n);
  assert_int_equal(mr_rec_writer_add(&w, 1000, buf, n, &err), 0);
  n = 0;
  buf[n++] = 0x42; /* noise: one bad frame */
  buf[n++] = 0;
  for (uint16_t k = 3; k < 5; k++) n += sample_wire(k, 0xFFFFF000u + 4000u * k, buf + n);
  assert_int_equal(mr_rec_writer_add(&w, 2000, buf, n, &err), 0);
  n = sample_wire(5, 0xFFFFF000u + 4000u * 5, buf);
  assert_int_equal(mr_rec_writer_add(&w, 3000, buf, n, &err), 0);
  assert_int_equal(mr_rec_writer_close(&w, &err), 0);
  if (cut_last) {
    size_t len;
    free(tt_read_file(tt_path(g_dir, name), &len));
    assert_int_equal(truncate(tt_path(g_dir, name), (off_t)(len - 5)), 0);
  }
}

static void tools_motion_mrec_track_follows_the_recorded_samples(void **state) {
  gg_motion m;
  uint16_t ch[GG_CHANNELS];
  (void)state;
  write_take("take.mrec", 0);
  load(&m, "all mrec file=take.mrec loop=0\nring mrec file=take.mrec column=0 loop=0\n");
  gg_motion_eval(&m, 0, ch);
  assert_int_equal(ch[0], 0);
  assert_int_equal(ch[4], 4);
  gg_motion_eval(&m, 0.002, ch); /* halfway from sample 0 to 1 */
  assert_int_equal(ch[0], 50);
  assert_int_equal(ch[1], 51);
  assert_int_equal(ch[3], 50);
  gg_motion_eval(&m, 0.010, ch); /* halfway from 2 to 3, across the clock's wrap */
  assert_int_equal(ch[2], 252);
  gg_motion_eval(&m, 0.020, ch); /* the last sample */
  assert_int_equal(ch[0], 500);
  gg_motion_eval(&m, 5, ch);
  assert_int_equal(ch[4], 504);
  gg_motion_free(&m);
}

/* A recording whose last chunk was cut short (its recorder was killed) still
 * gives the samples before it, and says what was missing. */
static void tools_motion_mrec_track_cut_short_keeps_what_came_before(void **state) {
  gg_motion m;
  uint16_t ch[GG_CHANNELS];
  char *said;
  int saved = dup(2), to = open(tt_path(g_dir, "warn.txt"), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  (void)state;
  write_take("cut.mrec", 1);
  assert_true(saved >= 0 && to >= 0);
  fflush(stderr);
  dup2(to, 2);
  load(&m, "all mrec file=cut.mrec loop=0\n");
  fflush(stderr);
  dup2(saved, 2);
  close(saved);
  close(to);
  gg_motion_eval(&m, 5, ch);
  assert_int_equal(ch[0], 400); /* sample 4, the last complete one */
  gg_motion_free(&m);
  said = tt_read_file(tt_path(g_dir, "warn.txt"), NULL);
  assert_non_null(said);
  if (!strstr(said, "cut.mrec: byte ") || !strstr(said, "5 missing"))
    fail_msg("the cut was not reported: '%s'", said);
  free(said);
}

static void expect_error(const char *text, const char *where) {
  gg_motion m;
  char err[600], want[1200];
  const char *path = write_file("bad.txt", text);
  assert_int_equal(gg_motion_load(&m, path, 1, err, sizeof err), -1);
  snprintf(want, sizeof want, "%s:%s", path, where);
  if (strncmp(err, want, strlen(want)) != 0) fail_msg("'%s' is not at '%s'", err, want);
}

static void tools_motion_errors_name_file_line_and_column(void **state) {
  (void)state;
  expect_error("all sine\npinky sine\n", "2:1:");
  expect_error("all sine amp=x\n", "1:10:");
  expect_error("\n\nthumb keys 1:0 0.5:1\n", "3:16:");
  expect_error("all wobble\n", "1:5:");
  expect_error("thumb sine freq=nan\n", "1:12:");
  expect_error("thumb,ring,7 const\n", "1:12:");
  expect_error("duration -3\n", "1:10:");
  expect_error("all csv file=missing.csv\n", "1:9:");
  expect_error("all step size=2\n", "1:10:");
}

static void tools_motion_default_stays_in_range_and_moves(void **state) {
  gg_motion m;
  uint16_t ch[GG_CHANNELS], first[GG_CHANNELS];
  int moved = 0;
  (void)state;
  gg_motion_default(&m, 1);
  gg_motion_eval(&m, 0, first);
  for (int i = 1; i < 1000; i++) {
    gg_motion_eval(&m, i / 100.0, ch);
    for (int k = 0; k < GG_CHANNELS; k++) assert_true(ch[k] <= GG_ADC_MAX);
    moved |= memcmp(ch, first, sizeof ch) != 0;
  }
  assert_true(moved);
  gg_motion_free(&m);
}

/* --- gg_stream's truth: what it says the decoder counts is what it counts -- */

typedef struct run_result {
  gp_decoder dec;
  uint16_t seqs[512]; /* SAMPLEs delivered, in order */
  size_t n_seqs;
  unsigned start_flags; /* SAMPLEs delivered with GP_SAMPLE_F_START */
  gg_stream s;
} run_result;

static void decode_into(run_result *r, const uint8_t *p, size_t n) {
  while (n) {
    gp_msg m;
    gp_event ev;
    size_t used = gp_decoder_feed(&r->dec, p, n, &m, &ev);
    if ((ev == GP_EV_FRAME || ev == GP_EV_FRAME_LATE) && m.type == GP_SAMPLE && r->n_seqs < 512) {
      if (m.u.sample.flags & GP_SAMPLE_F_START) r->start_flags |= 1u << (r->n_seqs ? 1 : 0);
      r->seqs[r->n_seqs++] = m.u.sample.seq;
    }
    p += used;
    n -= used;
  }
}

/* Runs up to stop_after slots of a stream (count slots, or no end), then
 * finishes it as an interrupted or completed run does. */
static void run_stream(run_result *r, int fault, uint64_t count, uint64_t stop_after,
                       uint32_t stall_frames) {
  static uint8_t buf[GG_SLOT_MAX];
  gg_motion motion;
  gg_stream_config cfg;
  memset(&cfg, 0, sizeof cfg);
  cfg.rate_hz = 250;
  cfg.count = count;
  cfg.spec_hash = GP_SPEC_HASH;
  cfg.baud = 115200;
  cfg.rates[fault] = 1.0;
  cfg.stall_min = cfg.stall_max = stall_frames;
  cfg.seed = 7;
  gg_motion_default(&motion, 7);
  memset(r, 0, sizeof *r);
  gp_decoder_init(&r->dec, GP_SPEC_HASH);
  gg_stream_init(&r->s, &cfg, &motion, NULL);
  for (uint64_t k = 0; k < stop_after; k++) {
    int done;
    size_t n = gg_stream_next(&r->s, buf, &done);
    if (done) break;
    decode_into(r, buf, n);
  }
  decode_into(r, buf, gg_stream_finish(&r->s, buf));
  gg_motion_free(&motion);
}

static void assert_truth_is_what_the_decoder_counted(const run_result *r) {
  const gg_expect *e = &r->s.expect;
  const gp_counters *c = &r->dec.c;
  assert_int_equal(e->frames, c->frames);
  assert_int_equal(e->crc_errors, c->crc_errors);
  assert_int_equal(e->framing_errors, c->framing_errors);
  assert_int_equal(e->oversize, c->oversize);
  assert_int_equal(e->unknown_type, c->unknown_type);
  assert_int_equal(e->spec_mismatch, c->spec_mismatch);
  assert_int_equal(e->lost, c->lost);
  assert_int_equal(e->duplicates, c->duplicates);
  assert_int_equal(e->reordered, c->reordered);
  assert_int_equal(e->seq_restarts, c->seq_restarts);
  assert_int_equal(e->bytes, c->bytes);
}

static void tools_stream_stopped_while_a_reorder_is_held_counts_no_reorder(void **state) {
  (void)state;
  run_result *r = malloc(sizeof *r);
  assert_non_null(r);
  /* Slot 0 is never faulted; slot 1 is reordered and held; stop there. */
  run_stream(r, GG_F_REORDER, UINT64_MAX, 2, 1);
  assert_int_equal(r->s.injected[GG_F_REORDER], 0);
  assert_int_equal(r->s.expect.reordered, 0);
  assert_int_equal(r->n_seqs, 2);
  assert_truth_is_what_the_decoder_counted(r);
  /* Stopped one slot later, the swap did happen and is counted once. */
  run_stream(r, GG_F_REORDER, UINT64_MAX, 3, 1);
  assert_int_equal(r->s.expect.reordered, 1);
  assert_truth_is_what_the_decoder_counted(r);
  free(r);
}

static void tools_stream_never_faults_the_first_or_the_last_two_slots(void **state) {
  (void)state;
  run_result *r = malloc(sizeof *r);
  assert_non_null(r);
  const uint64_t count = 40;
  for (int f = 0; f < GG_F_COUNT; f++) {
    run_stream(r, f, count, count, 5);
    /* Every fault at rate 1: still the first slot and the last two arrive
     * intact and in order, as tools/README.md says. */
    assert_true(r->n_seqs >= 3);
    assert_int_equal(r->seqs[0], 0);
    /* Like a glove that has just booted: START on the first SAMPLE only. */
    assert_int_equal(r->start_flags, 1);
    assert_int_equal(r->seqs[r->n_seqs - 2], count - 2);
    assert_int_equal(r->seqs[r->n_seqs - 1], count - 1);
    assert_true(r->s.injected[f] > 0);
    assert_truth_is_what_the_decoder_counted(r);
  }
  free(r);
}

static void tools_stream_a_stall_never_swallows_the_last_slots(void **state) {
  (void)state;
  run_result *r = malloc(sizeof *r);
  assert_non_null(r);
  /* A stall longer than the stream is cut so that the last two slots still
   * go out, and every frame it swallowed is counted lost. */
  run_stream(r, GG_F_STALL, 30, 30, 100);
  assert_int_equal(r->s.injected[GG_F_STALL], 1);
  assert_int_equal(r->s.stall_frames, 30 - 3);
  assert_int_equal(r->n_seqs, 3);
  assert_int_equal(r->seqs[1], 28);
  assert_int_equal(r->seqs[2], 29);
  assert_int_equal(r->dec.c.lost, 27);
  assert_int_equal(r->s.slot, 30);
  assert_truth_is_what_the_decoder_counted(r);
  /* Stopped inside a stall: it swallowed only the slots that were reached,
   * and the decoder, seeing no later frame, counts none of them lost. */
  run_stream(r, GG_F_STALL, UINT64_MAX, 10, 100);
  assert_int_equal(r->s.injected[GG_F_STALL], 1);
  assert_int_equal(r->s.stall_frames, 10 - 1);
  assert_int_equal(r->s.slot, 10);
  assert_int_equal(r->n_seqs, 1);
  assert_truth_is_what_the_decoder_counted(r);
  free(r);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(tools_motion_shapes_follow_their_formulas),
    cmocka_unit_test(tools_motion_keys_loop_and_clamp),
    cmocka_unit_test(tools_motion_walk_is_bounded_and_seeded),
    cmocka_unit_test(tools_motion_csv_track_interpolates),
    cmocka_unit_test(tools_motion_mrec_track_follows_the_recorded_samples),
    cmocka_unit_test(tools_motion_mrec_track_cut_short_keeps_what_came_before),
    cmocka_unit_test(tools_motion_errors_name_file_line_and_column),
    cmocka_unit_test(tools_motion_default_stays_in_range_and_moves),
    cmocka_unit_test(tools_stream_stopped_while_a_reorder_is_held_counts_no_reorder),
    cmocka_unit_test(tools_stream_never_faults_the_first_or_the_last_two_slots),
    cmocka_unit_test(tools_stream_a_stall_never_swallows_the_last_slots),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
