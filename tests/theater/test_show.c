/* The show (mr_show) driven by takes written here, on a virtual clock:
 * what a glove's samples do to the control frames, sample by sample. A
 * take replays its bytes at their recorded show times, so every run is
 * the same. The reset hook, a frame's turn allowance (max_turn_rate), a
 * glove bound by its whole 24-digit uid, the corrupt frames told, a
 * silence told of a glove that never opened, never of a live one, and
 * arming and a punch in a show of eight gloves. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mr_io.h"
#include "mr_scene.h"
#include "mr_show.h"
#include "proc.h"

static const double PI = 3.14159265358979323846;

/* --- takes ---------------------------------------------------------------- */

typedef struct take {
  mr_rec_writer w;
  uint16_t seq;
} take;

/* m as a glove built from the definition spec_hash sends it. */
static void put_as(take *tk, double t, const gp_msg *m, uint32_t spec_hash) {
  uint8_t wire[GP_MAX_WIRE + 2];
  size_t n = gp_encode(m, spec_hash, wire, sizeof wire);
  assert_true(n > 0);
  mr_io_error err;
  if (mr_rec_writer_add(&tk->w, (uint64_t)llround(t * 1e9), wire, n, &err) != 0)
    fail_msg("%s", err.msg);
}

static void put(take *tk, double t, const gp_msg *m) {
  put_as(tk, t, m, GP_SPEC_HASH);
}

/* A take at path that opens with the INFO of a glove whose last uid word
 * is uid2, calibrated so that a raw reading r is the value r / 4000. */
static gp_msg info(uint32_t uid2) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_INFO;
  m.u.info.proto_major = 1;
  m.u.info.spec_hash = GP_SPEC_HASH;
  m.u.info.uid[0] = 0x00c0ffeeu;
  m.u.info.uid[1] = 0x12345678u;
  m.u.info.uid[2] = uid2;
  m.u.info.hand = GP_HAND_RIGHT;
  m.u.info.n_channels = 5;
  m.u.info.adc_bits = 12;
  m.u.info.frame_rate_hz = 100;
  m.u.info.cal_state = GP_CAL_VALID;
  for (int k = 0; k < 5; k++) m.u.info.cal_max[k] = 4000;
  return m;
}

static void take_open(take *tk, const char *path, uint32_t uid2) {
  mr_io_error err;
  if (mr_rec_writer_open(&tk->w, path, GP_SPEC_HASH, 0, &err) != 0) fail_msg("%s", err.msg);
  tk->seq = 0;
  gp_msg m = info(uid2);
  put(tk, 0.0, &m);
}

static gp_msg sample(uint16_t seq, double t, const double v[5]) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SAMPLE;
  m.u.sample.seq = seq;
  m.u.sample.t_us = (uint32_t)llround(t * 1e6);
  for (int k = 0; k < 5; k++) m.u.sample.ch[k] = (uint16_t)llround(v[k] * 4000);
  return m;
}

/* Samples every 10 ms over [from, to) holding the five values v. */
static void take_hold(take *tk, double from, double to, const double v[5]) {
  for (double t = from; t < to - 1e-9; t += 0.01) {
    gp_msg m = sample(++tk->seq, t, v);
    put(tk, t, &m);
  }
}

static void take_close(take *tk) {
  mr_io_error err;
  if (mr_rec_writer_close(&tk->w, &err) != 0) fail_msg("%s", err.msg);
}

/* --- the show ------------------------------------------------------------- */

enum { MAX_TICKS = 400 };

/* Frame 0 as each simulated frame left it. */
typedef struct seen {
  int n;
  double t[MAX_TICKS];
  mr_pose pose[MAX_TICKS], target[MAX_TICKS];
  double first_particle[MAX_TICKS][3]; /* as the frame shows it */
  int glove_of;
  int resets;
  int silent;                 /* notes that nothing a glove sends has come in */
  double silent_at;           /* the last frame simulated before the first of them */
  unsigned long long corrupt; /* corrupt frames, summed over the notes telling them */
  int corrupt_notes;
  double punch_in; /* as the last frame told it */
  int armed_notes;
  char armed[240]; /* the last of them */
} seen;

static void frame_done(void *user, const mr_show_frame *f) {
  seen *s = user;
  if (s->n >= MAX_TICKS) return;
  s->t[s->n] = f->t;
  s->pose[s->n] = f->pose[0];
  s->target[s->n] = f->target[0];
  if (f->n_particles > 0) memcpy(s->first_particle[s->n], f->xyz, sizeof s->first_particle[0]);
  s->glove_of = f->glove_of[0];
  s->punch_in = f->punch_in;
  s->n++;
}

static void note(void *user, const char *line) {
  seen *s = user;
  if (strncmp(line, "reset:", 6) == 0) s->resets++;
  if (strstr(line, "nothing a glove sends has come in") != NULL && s->silent++ == 0)
    s->silent_at = s->n > 0 ? s->t[s->n - 1] : 0.0;
  if (strstr(line, ": armed:") != NULL) {
    s->armed_notes++;
    snprintf(s->armed, sizeof s->armed, "%s", line);
  }
  const char *corrupt = strstr(line, " corrupt frames in ");
  if (corrupt != NULL) {
    const char *count = corrupt;
    while (count > line && count[-1] != ' ') count--;
    s->corrupt += strtoull(count, NULL, 10);
    s->corrupt_notes++;
  }
}

static void load(const char *text, mr_scene *sc) {
  mr_scene_error err;
  if (mr_scene_load_text("show.yaml", text, strlen(text), sc, &err) != MR_SCENE_OK)
    fail_msg("%s", err.text);
}

/* The show of sc over the gloves at sources (n of them), 60 fps on a
 * virtual clock for `duration` s. */
static mr_show *start_on(const mr_scene *sc, const char *const *sources, size_t n, double duration,
                         mr_virtual_clock *vc, seen *s) {
  mr_show_def d = mr_default_show_def();
  d.fps = 60;
  d.duration = duration;
  d.present = MR_PRESENT_LAND;
  for (size_t g = 0; g < n; g++) d.gloves[g] = sources[g];
  d.n_gloves = n;
  mr_clock c = mr_clock_virtual(vc);
  mr_show_hooks h = { NULL, NULL, frame_done, note, s };
  mr_show *show = NULL;
  mr_show_error err;
  if (mr_show_create(sc, &d, &c, &h, &show, &err) != MR_SHOW_OK) fail_msg("%s", err.text);
  return show;
}

/* The same over the takes at the paths takes. */
static mr_show *start(const mr_scene *sc, const char *const *takes, size_t n, double duration,
                      mr_virtual_clock *vc, seen *s) {
  static char sources[MR_SHOW_MAX_GLOVES][300];
  const char *on[MR_SHOW_MAX_GLOVES];
  for (size_t g = 0; g < n; g++) {
    snprintf(sources[g], sizeof sources[g], "take:%s", takes[g]);
    on[g] = sources[g];
  }
  return start_on(sc, on, n, duration, vc, s);
}

/* Ticks until frame 0 has been simulated to time `until` (or the end). */
static void run_to(mr_show *show, const seen *s, double until) {
  while (s->n == 0 || s->t[s->n - 1] < until - 1e-9) {
    mr_show_status st = mr_show_tick(show);
    if (st == MR_SHOW_ENDED) return;
    assert_int_equal(st, MR_SHOW_OK);
  }
}

static void finish(mr_show *show) {
  mr_show_result r;
  mr_show_error err;
  if (mr_show_destroy(show, &r, &err) != MR_SHOW_OK) fail_msg("%s", err.text);
  mr_show_result_free(&r);
}

static double turn_between(const mr_pose *a, const mr_pose *b) {
  double axis[3];
  return mr_pose_turn(a->orientation, b->orientation, axis);
}

#define SCENE_HEAD                                           \
  "format: 1\n"                                              \
  "physics:\n"                                               \
  "  effects: [control]\n"                                   \
  "  particles: [{name: w, position: [0, 0, 0], mass: 1}]\n" \
  "  control:\n"                                             \
  "    pose: {position: [0, 1, 0]}\n"                        \
  "    points: [{name: p, offset: [0.3, 0, 0]}]\n"

/* The glove lifts the frame 0.12 m (the ring finger at 0.9 of its default
 * ±0.15 m) and falls silent at 0.5 s, leaving the frame up there. A reset
 * at 1 s brings the frame back to its start pose, and with it the goal the
 * glove set: no sample has come since, so the frame stays at the start
 * rather than heading back to where the glove last sent it. */
static void a_reset_puts_the_gloves_goal_back_at_the_start_pose(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  const char *path = tt_path(dir, "lift.mrec");
  take tk;
  take_open(&tk, path, 1);
  const double lift[5] = { 0.5, 0.5, 0.5, 0.9, 0.5 };
  take_hold(&tk, 0.01, 0.5, lift);
  take_close(&tk);
  mr_scene sc;
  load(SCENE_HEAD, &sc);
  /* w drifts at 0.2 m/s, so the reset has a place and a speed to undo. */
  sc.particles[0].def.velocity[0] = 0.2;
  mr_virtual_clock vc = { 0.0 };
  seen s;
  memset(&s, 0, sizeof s);
  mr_show *show = start(&sc, &path, 1, 2.5, &vc, &s);
  run_to(show, &s, 1.0);
  if (!(fabs(s.first_particle[s.n - 1][0] - 0.2) < 1e-3))
    fail_msg("before the reset w is at x = %g m, not 0.2 m", s.first_particle[s.n - 1][0]);
  const mr_pose *up = &s.pose[s.n - 1];
  print_message("before the reset: frame at %.6f m, goal %.6f m\n", up->position[1],
                s.target[s.n - 1].position[1]);
  assert_true(fabs(up->position[1] - 1.12) < 1e-6);
  mr_show_reset(show);
  run_to(show, &s, 2.5);
  assert_int_equal(s.resets, 1);
  int after = 0;
  for (int i = 0; i < s.n; i++) {
    if (s.t[i] <= 1.0 + 1e-9) continue;
    after++;
    if (!(fabs(s.target[i].position[1] - 1.0) < 1e-12 && fabs(s.pose[i].position[1] - 1.0) < 1e-9))
      fail_msg("at %.3f s after the reset: goal %.6f m, frame %.6f m; expected both at 1 m", s.t[i],
               s.target[i].position[1], s.pose[i].position[1]);
    /* w, on no string and under no force, is put back at its start at
     * rest, and stays there: neither its drift nor its place is kept. */
    const double *w = s.first_particle[i];
    if (!(w[0] == 0.0 && w[1] == 0.0 && w[2] == 0.0))
      fail_msg(
          "at %.3f s after the reset: the particle at (%g, %g, %g), not at rest where it began",
          s.t[i], w[0], w[1], w[2]);
  }
  assert_true(after > 80);
  finish(show);
  mr_scene_free(&sc);
  tt_rmdir(dir);
  free(dir);
}

/* A frame allowed 30°/s (not the default 1440) whose glove rolls it 27° at
 * once (the thumb from 0.5 to 0.95 of its ±30°) turns no faster than that
 * from one frame to the next through the whole show, and gets there: the
 * acceleration limits are set out of the way, so the turn allowance alone
 * holds it back. */
static void a_glove_frame_turns_no_faster_than_its_max_turn_rate(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  const char *path = tt_path(dir, "roll.mrec");
  take tk;
  take_open(&tk, path, 1);
  const double rest[5] = { 0.5, 0.5, 0.5, 0.5, 0.5 }, roll[5] = { 0.95, 0.5, 0.5, 0.5, 0.5 };
  take_hold(&tk, 0.01, 0.3, rest);
  take_hold(&tk, 0.3, 2.0, roll);
  take_close(&tk);
  mr_scene sc;
  load(SCENE_HEAD "    max_turn_rate: 30\n"
                  "    max_accel: 1e9\n"
                  "    max_turn_accel: 1e10\n",
       &sc);
  mr_virtual_clock vc = { 0.0 };
  seen s;
  memset(&s, 0, sizeof s);
  mr_show *show = start(&sc, &path, 1, 1.9, &vc, &s);
  run_to(show, &s, 1.9);
  const double limit = 30.0 * PI / 180.0 / 60.0; /* a frame's worth */
  double top = 0.0;
  for (int i = 1; i < s.n; i++) top = fmax(top, turn_between(&s.pose[i - 1], &s.pose[i]));
  const mr_pose start_pose = sc.frames[0].pose;
  double reached = turn_between(&start_pose, &s.pose[s.n - 1]) * 180.0 / PI;
  print_message("most turn in a frame %.6f° (allowance %.6f°), %.3f° reached of 27°\n",
                top * 180 / PI, limit * 180 / PI, reached);
  assert_true(top <= limit * (1 + 1e-9));
  assert_true(top > 0.95 * limit);
  assert_true(fabs(reached - 27.0) < 0.01);
  finish(show);
  mr_scene_free(&sc);
  tt_rmdir(dir);
  free(dir);
}

/* A glove that lifts its frame 0.12 m at once, under max_accel 2 m/s² (not
 * the default 10): in the show the frame's height, frame by frame, changes
 * its speed by no more than 2 m/s² allows (its second difference over
 * 1/60 s), reaches the limit, and arrives. */
static void a_glove_frame_changes_its_speed_no_faster_than_its_max_accel(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  const char *path = tt_path(dir, "lift.mrec");
  take tk;
  take_open(&tk, path, 1);
  const double rest[5] = { 0.5, 0.5, 0.5, 0.5, 0.5 }, lift[5] = { 0.5, 0.5, 0.5, 0.9, 0.5 };
  take_hold(&tk, 0.01, 0.3, rest);
  take_hold(&tk, 0.3, 2.0, lift);
  take_close(&tk);
  mr_scene sc;
  load(SCENE_HEAD "    max_accel: 2\n", &sc);
  mr_virtual_clock vc = { 0.0 };
  seen s;
  memset(&s, 0, sizeof s);
  mr_show *show = start(&sc, &path, 1, 1.9, &vc, &s);
  run_to(show, &s, 1.9);
  double top = 0.0;
  for (int i = 2; i < s.n; i++) {
    double y0 = s.pose[i - 2].position[1], y1 = s.pose[i - 1].position[1];
    double y2 = s.pose[i].position[1];
    top = fmax(top, fabs(y2 - 2 * y1 + y0) * 60.0 * 60.0);
  }
  double end = s.pose[s.n - 1].position[1];
  print_message("largest change of speed %.6f m/s² (limit 2), height %.6f m of 1.12\n", top, end);
  assert_true(top <= 2.0 * (1 + 1e-6));
  assert_true(top > 1.5);
  assert_true(fabs(end - 1.12) < 1e-4);
  finish(show);
  mr_scene_free(&sc);
  tt_rmdir(dir);
  free(dir);
}

/* Two gloves whose uids differ only in the last of their 24 digits are two
 * gloves: a frame bound to the second's uid takes the second, whichever
 * comes first, and one bound to the first's takes the first. */
static void a_glove_is_bound_by_its_whole_uid(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  const char *paths[2] = { tt_path(dir, "one.mrec"), tt_path(dir, "two.mrec") };
  const double rest[5] = { 0.5, 0.5, 0.5, 0.5, 0.5 };
  for (int g = 0; g < 2; g++) {
    take tk;
    take_open(&tk, paths[g], 0xabcdef01u + (uint32_t)g);
    take_hold(&tk, 0.01, 0.3, rest);
    take_close(&tk);
  }
  static const char *const uids[2] = { "00c0ffee12345678abcdef01", "00C0FFEE12345678ABCDEF02" };
  for (int want = 1; want >= 0; want--) {
    char text[1024];
    snprintf(text, sizeof text, SCENE_HEAD "    glove: {uid: %s}\n", uids[want]);
    mr_scene sc;
    load(text, &sc);
    mr_virtual_clock vc = { 0.0 };
    seen s;
    memset(&s, 0, sizeof s);
    mr_show *show = start(&sc, paths, 2, 0.2, &vc, &s);
    run_to(show, &s, 0.2);
    if (s.glove_of != want)
      fail_msg("the frame bound to %s took glove %d, expected %d", uids[want], s.glove_of + 1,
               want + 1);
    finish(show);
    mr_scene_free(&sc);
  }
  tt_rmdir(dir);
  free(dir);
}

/* --- what the show tells of its gloves ------------------------------------ */

/* The show of SCENE_HEAD over the glove at source, to its end, with what
 * it told into s. */
static void show_through(const char *source, double duration, seen *s) {
  mr_scene sc;
  load(SCENE_HEAD, &sc);
  mr_virtual_clock vc = { 0.0 };
  memset(s, 0, sizeof *s);
  mr_show *show = start_on(&sc, &source, 1, duration, &vc, s);
  run_to(show, s, duration);
  finish(show);
  mr_scene_free(&sc);
}

static void show_take(const char *path, double duration, seen *s) {
  char source[600];
  snprintf(source, sizeof source, "take:%s", path);
  show_through(source, duration, s);
}

/* Three frames with a bad CRC and five from a glove of another definition
 * (its INFO, then four of its samples) among good ones: the note on the
 * corrupt frames counts all eight. The foreign ones were once taken off
 * the total rather than added, so a glove of another definition alone was
 * told as some 1.8e19 corrupt frames. */
static void corrupt_frames_are_told_foreign_ones_included(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  const char *path = tt_path(dir, "noisy.mrec");
  take tk;
  take_open(&tk, path, 1);
  const double rest[5] = { 0.5, 0.5, 0.5, 0.5, 0.5 };
  take_hold(&tk, 0.01, 0.2, rest);
  const uint32_t foreign = 0x12345678u, neither = GP_SPEC_HASH ^ 0x5a5a5a5au;
  assert_true(foreign != GP_SPEC_HASH && neither != foreign);
  for (int i = 0; i < 3; i++) {
    gp_msg m = sample(0, 0.2 + 0.01 * i, rest);
    put_as(&tk, 0.2 + 0.01 * i, &m, neither);
  }
  gp_msg hello = info(2);
  hello.u.info.spec_hash = foreign;
  put_as(&tk, 0.23, &hello, foreign);
  for (int i = 0; i < 4; i++) {
    gp_msg m = sample((uint16_t)(i + 1), 0.24 + 0.01 * i, rest);
    put_as(&tk, 0.24 + 0.01 * i, &m, foreign);
  }
  take_hold(&tk, 0.3, 2.5, rest);
  take_close(&tk);
  static seen s;
  show_take(path, 2.4, &s);
  print_message("%d notes told %llu corrupt frames\n", s.corrupt_notes, s.corrupt);
  assert_true(s.corrupt_notes > 0);
  assert_int_equal(s.corrupt, 8);
  tt_rmdir(dir);
  free(dir);
}

/* A take at dir/name of a glove holding every finger at mid-range for
 * secs s; its path. */
static const char *take_at_rest(const char *dir, const char *name, double secs) {
  const char *path = tt_path(dir, name);
  take tk;
  take_open(&tk, path, 1);
  const double rest[5] = { 0.5, 0.5, 0.5, 0.5, 0.5 };
  take_hold(&tk, 0.01, secs, rest);
  take_close(&tk);
  return path;
}

/* A glove whose port never opens is told, once, that nothing it sends has
 * come in, at 2 s and not before. */
static void a_glove_that_never_opens_is_told_silent_once_after_2_s(void **state) {
  (void)state;
  static seen s;
  show_through("pty:/nonexistent/marionette-test", 3.5, &s);
  assert_int_equal(s.silent, 1);
  if (s.silent_at < 2.0 - 1.0 / 60 - 1e-9)
    fail_msg("told silent after the frame at %.3f s, before 2 s", s.silent_at);
}

/* A glove streaming good frames past 2 s is live: it is never told that
 * nothing it sends has come in. */
static void a_live_glove_is_never_told_silent(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  const char *path = take_at_rest(dir, "live.mrec", 3.5);
  static seen s;
  show_take(path, 3.0, &s);
  assert_int_equal(s.glove_of, 0);
  assert_int_equal(s.silent, 0);
  tt_rmdir(dir);
  free(dir);
}

/* A show of as many gloves as it takes: glove 8 armed and a punch asked
 * between two ticks are both done at the next frame, and the arming is
 * told of glove 8 alone. Eight is the edge: reading the arming asked of
 * one glove past the show's reads into the punches asked. */
static void a_show_of_eight_gloves_arms_the_last_and_punches_in(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  const char *path = take_at_rest(dir, "rest.mrec", 1.0);
  const char *takes[MR_SHOW_MAX_GLOVES];
  for (int g = 0; g < MR_SHOW_MAX_GLOVES; g++) takes[g] = path;
  mr_scene sc;
  load(SCENE_HEAD, &sc);
  mr_virtual_clock vc = { 0.0 };
  static seen s;
  memset(&s, 0, sizeof s);
  mr_show *show = start(&sc, takes, MR_SHOW_MAX_GLOVES, 1.0, &vc, &s);
  run_to(show, &s, 0.5);
  double asked_after = s.t[s.n - 1];
  mr_show_arm(show, MR_SHOW_MAX_GLOVES - 1, 0x3);
  mr_show_punch(show);
  run_to(show, &s, 1.0);
  print_message("punch-in at %.4f s, asked after %.4f s; %d arming told, the last '%s'\n",
                s.punch_in, asked_after, s.armed_notes, s.armed);
  assert_true(fabs(s.punch_in - (asked_after + 1.0 / 60)) < 1e-9);
  assert_int_equal(s.armed_notes, 1);
  assert_string_equal(s.armed, "glove 8: armed: thumb index");
  finish(show);
  mr_scene_free(&sc);
  tt_rmdir(dir);
  free(dir);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_reset_puts_the_gloves_goal_back_at_the_start_pose),
    cmocka_unit_test(a_glove_frame_turns_no_faster_than_its_max_turn_rate),
    cmocka_unit_test(a_glove_frame_changes_its_speed_no_faster_than_its_max_accel),
    cmocka_unit_test(a_glove_is_bound_by_its_whole_uid),
    cmocka_unit_test(corrupt_frames_are_told_foreign_ones_included),
    cmocka_unit_test(a_glove_that_never_opens_is_told_silent_once_after_2_s),
    cmocka_unit_test(a_live_glove_is_never_told_silent),
    cmocka_unit_test(a_show_of_eight_gloves_arms_the_last_and_punches_in),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
