/* Layered playback and slow motion in the show (issue 23, items 1 and 2),
 * on virtual clocks: a take beneath a live glove gives the channels not
 * armed, the live glove the armed ones; and a take performed at a quarter
 * speed replays at full speed as its input with every time scaled by a
 * quarter. Each comparison is against a take built here independently,
 * frame hash for frame hash. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mr_io.h"
#include "mr_scene.h"
#include "mr_show.h"
#include "mr_show_runner.h"
#include "proc.h"

/* --- takes and streams ---------------------------------------------------- */

/* One glove's bytes: chunks with their times (ns), as a take holds them. */
enum { MAX_CHUNKS = 1200 };
typedef struct stream {
  int n;
  uint64_t t_ns[MAX_CHUNKS];
  uint8_t bytes[MAX_CHUNKS][GP_MAX_WIRE + 2];
  size_t len[MAX_CHUNKS];
  double v[MAX_CHUNKS][5]; /* a sample's values */
  uint16_t seq;
} stream;

static void put(stream *s, uint64_t t_ns, const gp_msg *m) {
  assert_true(s->n < MAX_CHUNKS);
  s->len[s->n] = gp_encode(m, GP_SPEC_HASH, s->bytes[s->n], sizeof s->bytes[s->n]);
  assert_true(s->len[s->n] > 0);
  s->t_ns[s->n++] = t_ns;
}

/* The INFO of a right glove calibrated so that a raw r reads r / 4000. */
static void put_info(stream *s, uint64_t t_ns) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_INFO;
  m.u.info.proto_major = 1;
  m.u.info.spec_hash = GP_SPEC_HASH;
  m.u.info.uid[0] = 0x00c0ffeeu;
  m.u.info.hand = GP_HAND_RIGHT;
  m.u.info.n_channels = 5;
  m.u.info.adc_bits = 12;
  m.u.info.frame_rate_hz = 100;
  m.u.info.cal_state = GP_CAL_VALID;
  for (int k = 0; k < 5; k++) m.u.info.cal_max[k] = 4000;
  put(s, t_ns, &m);
}

static void put_sample(stream *s, uint64_t t_ns, const double v[5]) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SAMPLE;
  m.u.sample.seq = ++s->seq;
  m.u.sample.t_us = (uint32_t)(t_ns / 1000u);
  for (int k = 0; k < 5; k++) m.u.sample.ch[k] = (uint16_t)llround(v[k] * 4000);
  memcpy(s->v[s->n], v, sizeof s->v[s->n]);
  put(s, t_ns, &m);
}

/* The stream into a take at path, every time times num / den. */
static void write_take(const stream *s, const char *path, uint64_t num, uint64_t den) {
  mr_rec_writer w;
  mr_io_error err;
  if (mr_rec_writer_open(&w, path, GP_SPEC_HASH, 0, &err) != 0) fail_msg("%s", err.msg);
  for (int i = 0; i < s->n; i++) {
    assert_true(s->t_ns[i] * num % den == 0);
    if (mr_rec_writer_add(&w, s->t_ns[i] * num / den, s->bytes[i], s->len[i], &err) != 0)
      fail_msg("%s", err.msg);
  }
  if (mr_rec_writer_close(&w, &err) != 0) fail_msg("%s", err.msg);
}

/* --- the show ------------------------------------------------------------- */

enum { MAX_FRAMES = 400 };

typedef struct seen {
  int n;
  double t[MAX_FRAMES];
  uint64_t hash[MAX_FRAMES];
  mr_pose target[MAX_FRAMES];
  unsigned armed[MAX_FRAMES];
  bool layered[MAX_FRAMES];
  mr_glove_state state[MAX_FRAMES];
  mr_show_glove_view last; /* glove 1 as the last frame showed it */
  char describe[400];      /* glove 1 in the show's result */
} seen;

static void frame_done(void *user, const mr_show_frame *f) {
  seen *s = user;
  if (s->n >= MAX_FRAMES) return;
  s->t[s->n] = f->t;
  s->hash[s->n] = f->hash;
  s->target[s->n] = f->target[0];
  s->armed[s->n] = f->gloves[0].armed;
  s->layered[s->n] = f->gloves[0].layered;
  s->state[s->n] = f->gloves[0].state;
  s->last = f->gloves[0];
  s->n++;
}

/* The project's puppet: its frame, strings and limbs tell the values
 * apart in the state hash. */
#define PUPPET MR_SOURCE_DIR "/host/scenes/puppet.yaml"

static void load(mr_scene *sc) {
  mr_scene_error err;
  if (mr_scene_load(PUPPET, sc, &err) != MR_SCENE_OK) fail_msg("%s", err.text);
}

static mr_show_def show_def(double duration) {
  mr_show_def d = mr_default_show_def();
  d.fps = 60;
  d.duration = duration;
  d.present = MR_PRESENT_LAND;
  return d;
}

/* A take replayed at full speed on a virtual clock, through the runner on
 * one thread (the path `marionette run --replay` takes). */
static void replay(const mr_scene *sc, const char *take, double duration, seen *s) {
  char source[400];
  snprintf(source, sizeof source, "take:%s", take);
  mr_show_def d = show_def(duration);
  d.gloves[0] = source;
  d.n_gloves = 1;
  mr_virtual_clock vc = { 0.0 };
  mr_clock base = mr_clock_virtual(&vc);
  mr_show_runner_def rd = mr_default_show_runner_def();
  rd.threaded = false;
  mr_show_hooks h = { NULL, NULL, frame_done, NULL, s };
  mr_show_runner *r = NULL;
  mr_show_error err;
  if (mr_show_runner_start(sc, &d, &base, &h, &rd, &r, &err) != MR_SHOW_OK)
    fail_msg("%s", err.text);
  while (mr_show_runner_tick(r) == MR_SHOW_OK) {
  }
  mr_show_result res;
  if (mr_show_runner_finish(r, &res, &err) != MR_SHOW_OK) fail_msg("%s", err.text);
  mr_show_result_free(&res);
}

static void same_frames(const seen *a, const seen *b, const char *what) {
  assert_int_equal(a->n, b->n);
  int moved = 0;
  for (int i = 0; i < a->n; i++) {
    if (a->t[i] != b->t[i] || a->hash[i] != b->hash[i])
      fail_msg("%s: frame %d at %.4f s: hash %016llx, expected %016llx", what, i, a->t[i],
               (unsigned long long)a->hash[i], (unsigned long long)b->hash[i]);
    moved += i > 0 && a->hash[i] != a->hash[i - 1];
  }
  /* The comparison means something only if the puppet moved. */
  assert_true(moved > a->n / 2);
}

/* --- layered playback ----------------------------------------------------- */

static double wave(int c, double t) {
  return 0.5 + 0.3 * sin(2.0 * 3.14159265358979 * (0.7 + 0.2 * c) * t + c);
}

/* Samples every 10 ms for 2 s: beneath, the wave; the performer, the
 * wave's opposite. */
static void two_takes(stream *under, stream *over) {
  memset(under, 0, sizeof *under);
  memset(over, 0, sizeof *over);
  put_info(under, 0);
  put_info(over, 0);
  for (int i = 1; i <= 200; i++) {
    uint64_t t_ns = (uint64_t)i * 10000000u;
    double u[5], o[5];
    for (int c = 0; c < 5; c++) {
      u[c] = wave(c, (double)i * 0.01);
      o[c] = 1.0 - u[c];
    }
    put_sample(under, t_ns, u);
    put_sample(over, t_ns, o);
  }
}

/* The expected input, built apart: before `switch_ns` the channels of
 * `before` from the performer and the rest from beneath, from then on
 * those of `after`. */
static void expected(stream *out, const stream *under, const stream *over, unsigned before,
                     unsigned after, uint64_t switch_ns) {
  memset(out, 0, sizeof *out);
  put_info(out, 0);
  for (int i = 1; i < under->n; i++) {
    unsigned armed = under->t_ns[i] < switch_ns ? before : after;
    double v[5];
    for (int c = 0; c < 5; c++) v[c] = (armed & (1u << c)) ? over->v[i][c] : under->v[i][c];
    put_sample(out, under->t_ns[i], v);
  }
}

/* The show over `under_path` with the performer's take as its live glove
 * (a take is read on show time, so this runs the same every time), thumb
 * and index armed; at `arm_at` (< 0: never) every channel is armed, asked
 * between two ticks. */
static void layered_armed(const mr_scene *sc, const char *under_path, const char *over_path,
                          unsigned armed, double arm_at, seen *s) {
  char source[400];
  snprintf(source, sizeof source, "take:%s", over_path);
  mr_show_def d = show_def(1.5);
  d.gloves[0] = source;
  d.n_gloves = 1;
  d.beneath[0] = under_path;
  d.armed[0] = armed;
  mr_virtual_clock vc = { 0.0 };
  mr_clock c = mr_clock_virtual(&vc);
  mr_show_hooks h = { NULL, NULL, frame_done, NULL, s };
  mr_show *show = NULL;
  mr_show_error err;
  if (mr_show_create(sc, &d, &c, &h, &show, &err) != MR_SHOW_OK) fail_msg("%s", err.text);
  bool armed_all = false;
  mr_show_status st;
  while ((st = mr_show_tick(show)) == MR_SHOW_OK) {
    if (!armed_all && arm_at >= 0 && s->n > 0 && s->t[s->n - 1] >= arm_at) {
      mr_show_arm(show, 0, 0x1f);
      armed_all = true;
    }
  }
  assert_int_equal(st, MR_SHOW_ENDED);
  mr_show_result res;
  if (mr_show_destroy(show, &res, &err) != MR_SHOW_OK) fail_msg("%s", err.text);
  mr_show_result_free(&res);
}

static void layered(const mr_scene *sc, const char *under_path, const char *over_path,
                    double arm_at, seen *s) {
  layered_armed(sc, under_path, over_path, 0x3, arm_at, s);
}

/* Whether the frame's goal moved between frames i - 1 and i. */
static bool goal_moved(const seen *s, int i) {
  const mr_pose *a = &s->target[i - 1], *b = &s->target[i];
  for (int k = 0; k < 3; k++)
    if (a->position[k] != b->position[k]) return true;
  for (int k = 0; k < 4; k++)
    if (a->orientation[k] != b->orientation[k]) return true;
  return false;
}

/* The take beneath ends (0.8 s) while the performer plays on, the thumb
 * alone armed: the live glove still drives the thumb, so the frame's goal
 * keeps moving to the end of the show. */
static void an_armed_thumb_plays_on_after_the_take_beneath_ends(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), under_path[600], over_path[600];
  static stream under, over;
  two_takes(&under, &over);
  under.n = 81; /* its hello and 0.8 s of samples */
  snprintf(under_path, sizeof under_path, "%s", tt_path(dir, "under.mrec"));
  snprintf(over_path, sizeof over_path, "%s", tt_path(dir, "over.mrec"));
  write_take(&under, under_path, 1, 1);
  write_take(&over, over_path, 1, 1);
  mr_scene sc;
  load(&sc);
  static seen got;
  memset(&got, 0, sizeof got);
  layered_armed(&sc, under_path, over_path, 0x1, -1.0, &got);
  int late = 0, moved = 0;
  for (int i = 1; i < got.n; i++)
    if (got.t[i] >= 1.2) {
      late++;
      moved += goal_moved(&got, i);
    }
  assert_true(late > 15);
  if (moved < late - 1) fail_msg("the goal moved in %d of the last %d frames", moved, late);
  mr_scene_free(&sc);
  tt_rmdir(dir);
  free(dir);
}

/* Thumb and index armed over a take: the frames are those of a take whose
 * thumb and index are the performer's and the rest the take's. Arming all
 * five after the frame at 0.7 s takes effect from the next frame on, and
 * every frame's snapshot says which were armed. */
static void armed_channels_follow_the_live_glove_and_the_rest_the_take_beneath(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  static stream under, over, mix;
  two_takes(&under, &over);
  char under_path[600];
  snprintf(under_path, sizeof under_path, "%s", tt_path(dir, "under.mrec"));
  char over_path[600];
  snprintf(over_path, sizeof over_path, "%s", tt_path(dir, "over.mrec"));
  char mix_path[600];
  snprintf(mix_path, sizeof mix_path, "%s", tt_path(dir, "mix.mrec"));
  write_take(&under, under_path, 1, 1);
  write_take(&over, over_path, 1, 1);
  mr_scene sc;
  load(&sc);
  static seen got, want;
  memset(&got, 0, sizeof got);
  memset(&want, 0, sizeof want);
  layered(&sc, under_path, over_path, -1.0, &got);
  expected(&mix, &under, &over, 0x3, 0x3, UINT64_MAX);
  write_take(&mix, mix_path, 1, 1);
  replay(&sc, mix_path, 1.5, &want);
  same_frames(&got, &want, "thumb and index armed");
  for (int i = 0; i < got.n; i++) assert_true(got.layered[i] && got.armed[i] == 0x3);

  /* All five armed between two ticks: the next frame simulated is the
   * first to follow the performer alone. */
  memset(&got, 0, sizeof got);
  memset(&want, 0, sizeof want);
  layered(&sc, under_path, over_path, 0.7, &got);
  int first = -1;
  for (int i = 0; i < got.n && first < 0; i++)
    if (got.armed[i] == 0x1f) first = i;
  assert_true(first > 0 && got.t[first - 1] >= 0.7 && got.t[first - 2] < 0.7);
  uint64_t switch_ns = (uint64_t)llround(got.t[first - 1] * 1e9) + 1;
  expected(&mix, &under, &over, 0x3, 0x1f, switch_ns);
  write_take(&mix, mix_path, 1, 1);
  replay(&sc, mix_path, 1.5, &want);
  same_frames(&got, &want, "all armed from the frame after 0.7 s");
  mr_scene_free(&sc);
  tt_rmdir(dir);
  free(dir);
}

/* --- slow motion ---------------------------------------------------------- */

/* The performer's full-speed take W, written into a pipe at W's own times
 * on the base clock as the runner waits on it: the glove reads it as it
 * comes, as a live glove. */
typedef struct feeder {
  const stream *w;
  int next, fd;
  mr_virtual_clock *base;
} feeder;

static void feed(void *user) {
  feeder *f = user;
  uint64_t now_ns = (uint64_t)llround(f->base->t * 1e9);
  for (; f->next < f->w->n && f->w->t_ns[f->next] <= now_ns; f->next++)
    assert_int_equal(write(f->fd, f->w->bytes[f->next], f->w->len[f->next]),
                     (ssize_t)f->w->len[f->next]);
}

/* 6 s of a performer at 100 Hz, none of whose times falls on a frame's
 * at a quarter of them: 0.25 (0.01 i + 0.0037) s is 0.0025 i + 0.000925,
 * at least 0.09 ms from every 1/60 s. The times are whole multiples of
 * 4 ns, so a quarter of each is exact. */
static void performer(stream *w) {
  memset(w, 0, sizeof *w);
  put_info(w, 1700000u);
  for (int i = 0; i < 600; i++) {
    uint64_t t_ns = (uint64_t)i * 10000000u + 3700000u;
    double v[5];
    for (int c = 0; c < 5; c++) v[c] = wave(c, (double)t_ns * 1e-9);
    put_sample(w, t_ns, v);
  }
}

/* W performed at 25 % speed into R, through a pipe read as a live glove
 * on the show's pace; R replayed at full speed equals, frame for frame,
 * W with every time taken by a quarter (S) replayed the same way. The
 * glove's clock ran at the performer's pace: its clock offset stayed that
 * of the pipe (not drifting by three quarters of every second), its
 * latency under a base frame, it was never lost, and the show's latency
 * figures are on that pace too. */
static void a_take_performed_at_a_quarter_speed_replays_as_its_input_scaled(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  static stream w;
  performer(&w);
  char r_path[600];
  snprintf(r_path, sizeof r_path, "%s", tt_path(dir, "R.mrec"));
  char s_path[600];
  snprintf(s_path, sizeof s_path, "%s", tt_path(dir, "S.mrec"));
  write_take(&w, s_path, 1, 4);
  int fds[2];
  assert_int_equal(pipe(fds), 0);
  char source[64];
  snprintf(source, sizeof source, "file:/proc/self/fd/%d", fds[0]);
  mr_scene sc;
  load(&sc);
  mr_show_def d = show_def(1.4);
  d.gloves[0] = source;
  d.n_gloves = 1;
  d.record[0] = r_path;
  mr_virtual_clock vc = { 0.0 };
  mr_clock base = mr_clock_virtual(&vc);
  feeder fd = { &w, 0, fds[1], &vc };
  mr_show_runner_def rd = mr_default_show_runner_def();
  rd.threaded = false;
  rd.speed = 0.25;
  rd.pump = feed;
  rd.user = &fd;
  static seen live, got, want;
  memset(&live, 0, sizeof live);
  mr_show_hooks h = { NULL, NULL, frame_done, NULL, &live };
  mr_show_runner *r = NULL;
  mr_show_error err;
  if (mr_show_runner_start(&sc, &d, &base, &h, &rd, &r, &err) != MR_SHOW_OK)
    fail_msg("%s", err.text);
  while (mr_show_runner_tick(r) == MR_SHOW_OK) {
  }
  mr_show_result res;
  if (mr_show_runner_finish(r, &res, &err) != MR_SHOW_OK) fail_msg("%s", err.text);
  print_message("base %.3f s for %.3f s of show; glove offset %.4f s, losses %llu\n", vc.t,
                res.frames.sim_time, live.last.clock_offset,
                (unsigned long long)res.glove[0].counters.losses);
  assert_true(vc.t >= 4 * 1.4 - 1e-9);
  assert_int_equal(res.glove[0].counters.losses, 0);
  assert_int_equal(live.last.state, MR_GLOVE_LIVE);
  /* Read a base frame (1/15 s) late at most, on the performer's clock. */
  assert_true(live.last.clock_offset >= -0.004 && live.last.clock_offset < 0.07);
  double late = live.last.reading.host_t - live.last.reading.device_t - live.last.clock_offset;
  assert_true(late >= 0 && late < 0.07);
  /* The show's input-to-frame latency on the same pace: a frame is shown a
   * frame period of show time after its input was read, 1/15 s of the
   * performer's at 25 % (in show seconds it read a quarter of that). */
  print_message("latency p50 %.4f s, p99 %.4f s\n", res.frames.latency_p50, res.frames.latency_p99);
  assert_true(fabs(res.frames.latency_p50 - 1.0 / 15) < 0.005);
  mr_show_result_free(&res);
  close(fds[0]);
  close(fds[1]);

  memset(&got, 0, sizeof got);
  memset(&want, 0, sizeof want);
  replay(&sc, r_path, 1.4, &got);
  replay(&sc, s_path, 1.4, &want);
  same_frames(&got, &want, "R against S");
  same_frames(&live, &want, "the slow show against S");
  mr_scene_free(&sc);
  tt_rmdir(dir);
  free(dir);
}

/* The performer at 25 % through a pipe, as above, for `secs` of show;
 * what the frames saw into s. */
static void perform_slowly(const mr_scene *sc, const stream *w, double secs, seen *s) {
  int fds[2];
  assert_int_equal(pipe(fds), 0);
  char source[64];
  snprintf(source, sizeof source, "file:/proc/self/fd/%d", fds[0]);
  mr_show_def d = show_def(secs);
  d.gloves[0] = source;
  d.n_gloves = 1;
  mr_virtual_clock vc = { 0.0 };
  mr_clock base = mr_clock_virtual(&vc);
  feeder fd = { w, 0, fds[1], &vc };
  mr_show_runner_def rd = mr_default_show_runner_def();
  rd.threaded = false;
  rd.speed = 0.25;
  rd.pump = feed;
  rd.user = &fd;
  mr_show_hooks h = { NULL, NULL, frame_done, NULL, s };
  mr_show_runner *r = NULL;
  mr_show_error err;
  if (mr_show_runner_start(sc, &d, &base, &h, &rd, &r, &err) != MR_SHOW_OK)
    fail_msg("%s", err.text);
  while (mr_show_runner_tick(r) == MR_SHOW_OK) {
  }
  mr_show_result res;
  if (mr_show_runner_finish(r, &res, &err) != MR_SHOW_OK) fail_msg("%s", err.text);
  snprintf(s->describe, sizeof s->describe, "%s", res.glove[0].describe);
  mr_show_result_free(&res);
  close(fds[0]);
  close(fds[1]);
}

/* At 25 %, a glove silent from 1 s to 2.5 s of its own time is lost half
 * a second (its lost_after) of its own time into the silence, not two
 * seconds in (half a second of show time), and live again when it sends
 * again. */
static void at_a_quarter_speed_a_silent_glove_is_lost_on_its_own_time(void **state) {
  (void)state;
  static stream w;
  memset(&w, 0, sizeof w);
  put_info(&w, 1700000u);
  for (int i = 0; i < 400; i++) {
    uint64_t t_ns = (uint64_t)i * 10000000u + 3700000u;
    if (t_ns > 1000000000u && t_ns < 2500000000u) continue;
    double v[5];
    for (int c = 0; c < 5; c++) v[c] = wave(c, (double)t_ns * 1e-9);
    put_sample(&w, t_ns, v);
  }
  mr_scene sc;
  load(&sc);
  static seen s;
  memset(&s, 0, sizeof s);
  perform_slowly(&sc, &w, 0.95, &s);
  int lost = -1, back = -1;
  for (int i = 0; i < s.n; i++) {
    if (lost < 0 && s.state[i] == MR_GLOVE_LOST) lost = i;
    if (lost >= 0 && back < 0 && s.state[i] == MR_GLOVE_LIVE) back = i;
  }
  assert_true(lost > 0);
  print_message("lost at %.4f s of show (%.3f s of its own), live again at %.4f s\n", s.t[lost],
                4 * s.t[lost], back > 0 ? s.t[back] : -1.0);
  /* Its last sample came at 0.9937 s of its own time, lost 0.5 s after:
   * the first frame past it on the glove's clock (1/15 s a frame). */
  assert_true(4 * s.t[lost] > 0.9937 + 0.5 && 4 * s.t[lost] < 0.9937 + 0.5 + 1.0 / 15 + 1e-9);
  assert_true(back > lost && 4 * s.t[back] >= 2.5 && 4 * s.t[back] < 2.5 + 1.0 / 15 + 1e-9);
  mr_scene_free(&sc);
}

/* At 25 %, a glove silent from 1 s of its own time to the show's end
 * (0.95 s of show, 3.8 s of its own) is told in the result as lost on its
 * own clock: since 1.49 s, 2.3 s before the end, not at a time before
 * the glove's last news. */
static void at_a_quarter_speed_the_result_tells_a_lost_glove_on_its_own_time(void **state) {
  (void)state;
  static stream w;
  memset(&w, 0, sizeof w);
  put_info(&w, 1700000u);
  for (int i = 0; i < 100; i++) {
    double v[5];
    uint64_t t_ns = (uint64_t)i * 10000000u + 3700000u;
    for (int c = 0; c < 5; c++) v[c] = wave(c, (double)t_ns * 1e-9);
    put_sample(&w, t_ns, v);
  }
  mr_scene sc;
  load(&sc);
  static seen s;
  memset(&s, 0, sizeof s);
  perform_slowly(&sc, &w, 0.95, &s);
  print_message("%s\n", s.describe);
  if (strstr(s.describe, "lost 2.3 s ago") == NULL)
    fail_msg("expected lost 2.3 s ago: %s", s.describe);
  mr_scene_free(&sc);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(armed_channels_follow_the_live_glove_and_the_rest_the_take_beneath),
    cmocka_unit_test(an_armed_thumb_plays_on_after_the_take_beneath_ends),
    cmocka_unit_test(a_take_performed_at_a_quarter_speed_replays_as_its_input_scaled),
    cmocka_unit_test(at_a_quarter_speed_a_silent_glove_is_lost_on_its_own_time),
    cmocka_unit_test(at_a_quarter_speed_the_result_tells_a_lost_glove_on_its_own_time),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
