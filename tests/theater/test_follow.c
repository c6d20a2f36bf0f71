/* Two gloves drive two puppets, and each control frame follows its own
 * glove's motion. Two glove-gen streams on real ptys, one with 10 % faults,
 * play a left and a right hand for 10 s; `marionette run` drives the duet
 * scene, whose puppets are bound to gloves by hand. The gloves are given
 * right hand first, so binding by order would swap them.
 *
 * The poses the run reports are compared with the poses the control
 * mapping gives for glove-gen's truth samples (the intact ones, at their
 * device times): after the best time shift (the path's latency), each
 * frame is close to its own glove's poses (within 1.5° for the unbroken
 * stream; the faulty one stalls, and its frame eases back after each
 * stall) and far from the other glove's. The samples taken and the errors counted equal the truth's.
 * Each glove's take, replayed with the other's, gives the show's states. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mr_control.h"
#include "mr_scene.h"
#include "proc.h"
#include "tools_truth.h"

static const char *glove_gen, *marionette;

#define DUET MR_SOURCE_DIR "/host/scenes/duet.yaml"

enum { MAX_ROWS = 2000, FRAMES = 2 };

/* Each finger its own slow sine; the two hands differ in every channel. */
static const char *const scripts[2] = {
  "thumb sine mid=0.5 amp=0.35 freq=0.31\n"
  "index sine mid=0.5 amp=0.30 freq=0.23 phase=40\n"
  "middle sine mid=0.5 amp=0.35 freq=0.17 phase=80\n"
  "ring sine mid=0.5 amp=0.30 freq=0.27 phase=20\n"
  "little sine mid=0.5 amp=0.30 freq=0.19 phase=60\n",
  "thumb sine mid=0.5 amp=0.35 freq=0.21 phase=180\n"
  "index sine mid=0.5 amp=0.30 freq=0.29 phase=220\n"
  "middle sine mid=0.5 amp=0.35 freq=0.13 phase=260\n"
  "ring sine mid=0.5 amp=0.30 freq=0.33 phase=200\n"
  "little sine mid=0.5 amp=0.30 freq=0.24 phase=240\n",
};

typedef struct trajectory {
  double t[MAX_ROWS * 3];
  mr_pose p[MAX_ROWS * 3];
  size_t n;
} trajectory;

static char pty_source[2][320], truth_path[2][300], link_path[2][300];

/* glove-gen for one hand, streaming for `secs` once marionette opens it. */
static pid_t start_hand(const char *dir, int h, const char *hand, const char *faults) {
  char name[32], script[300], pf[300], err[300];
  snprintf(name, sizeof name, "hand%d.txt", h);
  snprintf(script, sizeof script, "%s", tt_path(dir, name));
  FILE *f = fopen(script, "w");
  assert_non_null(f);
  fputs(scripts[h], f);
  fclose(f);
  snprintf(name, sizeof name, "pty%d.path", h);
  snprintf(pf, sizeof pf, "%s", tt_path(dir, name));
  snprintf(name, sizeof name, "truth%d", h);
  snprintf(truth_path[h], sizeof truth_path[h], "%s", tt_path(dir, name));
  snprintf(name, sizeof name, "gen%d.err", h);
  snprintf(err, sizeof err, "%s", tt_path(dir, name));
  const char *argv[] = { glove_gen, "-o", "pty",      "--path-file", pf,     "--duration", "10",
                         "--wait",  "30", "--linger", "5",           "-q",   "-s",         script,
                         "--hand",  hand, "--truth",  truth_path[h], faults, NULL };
  pid_t gen = tt_spawn(argv, NULL, err);
  assert_true(gen > 0);
  assert_int_equal(tt_await_file(gen, pf, err, 30), 0);
  char *path = tt_read_file(pf, NULL);
  assert_non_null(path);
  path[strcspn(path, "\n")] = '\0';
  /* Reached through a link the test removes once the stream is over, as
   * udev removes a glove's name when it is unplugged: the show, which
   * outlives the stream, retries the name and never meets the next user
   * of a freed /dev/pts number (another test's glove). */
  snprintf(name, sizeof name, "hand%d", h);
  snprintf(link_path[h], sizeof link_path[h], "%s", tt_path(dir, name));
  assert_int_equal(symlink(path, link_path[h]), 0);
  snprintf(pty_source[h], sizeof pty_source[h], "pty:%s", link_path[h]);
  free(path);
  return gen;
}

/* The poses file: per line t, then 7 numbers per control frame. */
static void read_poses(const char *path, trajectory out[FRAMES]) {
  char *text = tt_read_file(path, NULL);
  assert_non_null(text);
  for (int k = 0; k < FRAMES; k++) out[k].n = 0;
  for (char *line = strtok(text, "\n"); line != NULL; line = strtok(NULL, "\n")) {
    double v[1 + 7 * FRAMES];
    char *p = line;
    int got = 0;
    for (; got < 1 + 7 * FRAMES; got++) {
      char *end;
      v[got] = strtod(p, &end);
      if (end == p) break;
      p = end;
    }
    assert_int_equal(got, 1 + 7 * FRAMES);
    for (int k = 0; k < FRAMES && out[k].n < MAX_ROWS; k++) {
      trajectory *tr = &out[k];
      tr->t[tr->n] = v[0];
      memcpy(tr->p[tr->n].position, v + 1 + 7 * k, 3 * sizeof(double));
      memcpy(tr->p[tr->n].orientation, v + 4 + 7 * k, 4 * sizeof(double));
      tr->n++;
    }
  }
  free(text);
}

/* The mapping (as the theater makes it for frame k) fed glove h's intact
 * samples at their device times. */
static void expected_poses(const mr_scene *s, size_t k, int h, trajectory *out) {
  mr_mapping_def def = mr_default_mapping_def();
  def.neutral = s->frames[k].pose;
  mr_control *c = NULL;
  assert_int_equal(mr_control_create(&def, 1, &c, NULL, 0), MR_CONTROL_OK);
  char *text = tt_read_file(truth_path[h], NULL);
  assert_non_null(text);
  size_t n = 0;
  tt_sample *v = tt_truth_samples(text, &n);
  assert_non_null(v);
  assert_true(n > 1000); /* 2500 slots, less the faulty stream's stalls */
  out->n = 0;
  for (size_t i = 0; i < n && out->n < MAX_ROWS * 3; i++) {
    double values[5];
    for (int ch = 0; ch < 5; ch++) values[ch] = v[i].ch[ch] / 4095.0;
    double t = v[i].t_us * 1e-6;
    if (out->n > 0 && !(t > out->t[out->n - 1])) continue; /* reordered: the glove skips it too */
    assert_int_equal(mr_control_update(c, values, t, &out->p[out->n], NULL), MR_CONTROL_OK);
    out->t[out->n++] = t;
  }
  free(v);
  free(text);
  mr_control_destroy(c);
}

/* The angle between two orientations, degrees. */
static double angle_deg(const mr_pose *a, const mr_pose *b) {
  double d = 0;
  for (int i = 0; i < 4; i++) d += a->orientation[i] * b->orientation[i];
  return 2.0 * acos(fmin(1.0, fabs(d))) * 180.0 / 3.14159265358979323846;
}

/* The expected pose at time t: the last one at or before it. */
static const mr_pose *at(const trajectory *e, double t) {
  size_t lo = 0, hi = e->n;
  while (hi - lo > 1) {
    size_t mid = (lo + hi) / 2;
    if (e->t[mid] <= t)
      lo = mid;
    else
      hi = mid;
  }
  return &e->p[lo];
}

static double distance(const mr_pose *a, const mr_pose *b) {
  double d[3] = { a->position[0] - b->position[0], a->position[1] - b->position[1],
                  a->position[2] - b->position[2] };
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* RMS angle (degrees) and distance (m) between the run's frames, from 2 s
 * to 9 s of show, and the expectation delayed by `delay`. */
static double rms_at(const trajectory *run, const trajectory *e, double delay, double *rms_m) {
  double sum = 0, sum_m = 0;
  int n = 0;
  for (size_t i = 0; i < run->n; i++) {
    if (run->t[i] < 2.0 || run->t[i] > 9.0) continue;
    const mr_pose *want = at(e, run->t[i] - delay);
    double a = angle_deg(&run->p[i], want), m = distance(&run->p[i], want);
    sum += a * a;
    sum_m += m * m;
    n++;
  }
  *rms_m = n > 0 ? sqrt(sum_m / n) : INFINITY;
  return n > 0 ? sqrt(sum / n) : INFINITY;
}

/* The RMS angle at the delay in 0..1 s that makes it least (the path's
 * latency, unknown to the test), with the RMS distance there. */
static double follow_error(const trajectory *run, const trajectory *e, double *delay,
                           double *rms_m) {
  double best = INFINITY;
  for (int ms = 0; ms <= 1000; ms += 2) {
    double m;
    double rms = rms_at(run, e, ms * 1e-3, &m);
    if (rms < best) {
      best = rms;
      *delay = ms * 1e-3;
      *rms_m = m;
    }
  }
  return best;
}

static long long field(const char *text, const char *key) {
  char v[64];
  if (tt_field(text, key, v, sizeof v) != 0) fail_msg("no '%s' in:\n%s", key, text);
  return strtoll(v, NULL, 10);
}

/* Glove h's summary lines ("glove" or "glove 2") against its truth. */
static void counters_match(const char *out, const char *key, int h) {
  char *truth = tt_read_file(truth_path[h], NULL);
  assert_non_null(truth);
  size_t n = 0;
  tt_sample *v = tt_truth_samples(truth, &n);
  char k[64];
  snprintf(k, sizeof k, "%s samples", key);
  /* A reordered sample arrives after a newer one: counted, not taken. */
  assert_int_equal(field(out, k), (long long)n - tt_kv(truth, "reordered"));
  snprintf(k, sizeof k, "%s crc errors", key);
  assert_int_equal(field(out, k), tt_kv(truth, "crc_errors"));
  free(v);
  free(truth);
}

/* The two takes of the show replay, on a virtual clock, to the same state
 * at every frame. */
static void takes_replay_identically(const char *dir, const char *live_hashes) {
  char take0[300], take1[300], hashes[300];
  snprintf(take0, sizeof take0, "%s", tt_path(dir, "right.mrec"));
  snprintf(take1, sizeof take1, "%s", tt_path(dir, "left.mrec"));
  snprintf(hashes, sizeof hashes, "%s", tt_path(dir, "replay.hashes"));
  char *argv[] = { (char *)marionette, "run",  DUET,       "--replay", take0, "--replay", take1,
                   "--time",           "12.5", "--hashes", hashes,     "-q",  NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  if (o.status != 0) fail_msg("replay: status %d: %s", o.status, o.err);
  tt_output_free(&o);
  size_t n1 = 0, n2 = 0;
  char *a = tt_read_file(live_hashes, &n1), *b = tt_read_file(hashes, &n2);
  assert_non_null(a);
  assert_non_null(b);
  assert_true(n1 > 750 * 18);
  assert_int_equal(n1, n2);
  assert_memory_equal(a, b, n1);
  free(a);
  free(b);
}

static void two_gloves_drive_two_puppets_each_its_own(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), poses[300], take0[300], take1[300], hashes[300];
  snprintf(poses, sizeof poses, "%s", tt_path(dir, "poses"));
  snprintf(take0, sizeof take0, "%s", tt_path(dir, "right.mrec"));
  snprintf(take1, sizeof take1, "%s", tt_path(dir, "left.mrec"));
  snprintf(hashes, sizeof hashes, "%s", tt_path(dir, "live.hashes"));
  /* Right hand first: by order, glove 1 would drive alice. */
  pid_t right = start_hand(dir, 1, "right", "--seed=7");
  pid_t left = start_hand(dir, 0, "left", "--faults=0.1");
  char *argv[] = {
    (char *)marionette, "run",  DUET,       "--glove", pty_source[1], "--glove",  pty_source[0],
    "--time",           "12.5", "-q",       "--poses", poses,         "--record", take0,
    "--record",         take1,  "--hashes", hashes,    NULL
  };
  char out_path[300], err_path[300];
  snprintf(out_path, sizeof out_path, "%s", tt_path(dir, "show.out"));
  snprintf(err_path, sizeof err_path, "%s", tt_path(dir, "show.err"));
  pid_t show = tt_spawn((const char *const *)argv, out_path, err_path);
  assert_true(show > 0);
  tt_wait(right, 30);
  tt_wait(left, 30);
  unlink(link_path[0]);
  unlink(link_path[1]);
  tt_output o = { tt_wait(show, 60), tt_read_file(out_path, NULL), tt_read_file(err_path, NULL) };
  assert_non_null(o.out);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_non_null(strstr(o.out, "control frame of alice: glove 2\n"));
  assert_non_null(strstr(o.out, "control frame of bob: glove 1\n"));
  counters_match(o.out, "glove", 1);
  counters_match(o.out, "glove 2", 0);
  assert_int_equal(field(o.out, "resets"), 0);

  mr_scene s;
  mr_scene_error err;
  assert_int_equal(mr_scene_load(DUET, &s, &err), MR_SCENE_OK);
  static trajectory run[FRAMES], expect[FRAMES][2];
  read_poses(poses, run);
  assert_true(run[0].n > 600); /* 60 fps for 12.5 s */
  for (size_t k = 0; k < FRAMES; k++)
    for (int h = 0; h < 2; h++) expected_poses(&s, k, h, &expect[k][h]);
  for (size_t k = 0; k < FRAMES; k++) {
    int own = k == 0 ? 0 : 1; /* alice is the left hand, glove-gen 0 */
    double d_own = 0, d_other = 0, m_own = 0, m_other = 0;
    double e_own = follow_error(&run[k], &expect[k][own], &d_own, &m_own);
    double e_other = follow_error(&run[k], &expect[k][1 - own], &d_other, &m_other);
    print_message("frame %zu: %.3f deg and %.2f mm RMS from its glove (delay %.3f s); %.1f deg "
                  "and %.1f mm from the other\n",
                  k, e_own, m_own * 1e3, d_own, e_other, m_other * 1e3);
    /* The left hand's stream stalls (glove-gen's --stall, in --faults:
     * 40 to 400 ms unplugged); at the replug its frame eases to the glove
     * within control.max_accel and max_turn_accel instead of jumping
     * there, and lags the glove meanwhile. The right hand's, unbroken,
     * follows closely (0.6° and 2 mm on a quiet machine, 0.7° and 3 mm
     * beside a full test run: its samples then come in bursts too). */
    assert_true(e_own < (own == 0 ? 6.0 : 1.5));
    assert_true(m_own < (own == 0 ? 0.02 : 0.006));
    assert_true(e_other > 5.0 * e_own);
  }
  mr_scene_free(&s);
  tt_output_free(&o);
  takes_replay_identically(dir, hashes);
  tt_rmdir(dir);
  free(dir);
}

/* Two puppets bound to the same hand take two gloves of that hand, one
 * each (a glove no other frame took is preferred), not both the first:
 * the duet with both puppets bound to the right hand, two right-hand
 * gloves recorded to files. */
static void two_puppets_of_one_hand_take_a_glove_each(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), scene[300], src[2][320];
  char *text = tt_read_file(DUET, NULL);
  assert_non_null(text);
  const char *left = strstr(text, "glove: {hand: left}");
  assert_non_null(left);
  snprintf(scene, sizeof scene, "%s", tt_path(dir, "duet_right.yaml"));
  FILE *f = fopen(scene, "w");
  assert_non_null(f);
  fprintf(f, "%.*sglove: {hand: right}%s", (int)(left - text), text,
          left + strlen("glove: {hand: left}"));
  assert_int_equal(fclose(f), 0);
  free(text);
  for (int g = 0; g < 2; g++) {
    char name[16], seed[8];
    snprintf(name, sizeof name, "right%d.bin", g);
    snprintf(seed, sizeof seed, "%d", g + 1);
    const char *file = tt_path(dir, name);
    snprintf(src[g], sizeof src[g], "file:%s", file);
    char *gen[] = { (char *)glove_gen, "-o",    (char *)file, "--fast", "-d", "2",
                    "--hand",          "right", "--seed",     seed,     NULL };
    tt_output o;
    assert_int_equal(tt_capture(gen, &o), 0);
    if (o.status != 0) fail_msg("glove-gen: %s", o.err);
    tt_output_free(&o);
  }
  char *run[] = { (char *)marionette, "run", scene, "--glove", src[0], "--glove", src[1],
                  "--time",           "1",   "-q",  NULL };
  tt_output o;
  assert_int_equal(tt_capture(run, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  if (strstr(o.out, "control frame of alice: glove 1\n") == NULL ||
      strstr(o.out, "control frame of bob: glove 2\n") == NULL)
    fail_msg("expected alice on glove 1 and bob on glove 2:\n%s", o.out);
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  signal(SIGPIPE, SIG_IGN);
  glove_gen = argc > 1 ? argv[1] : "glove-gen";
  marionette = argc > 2 ? argv[2] : "marionette";
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(two_gloves_drive_two_puppets_each_its_own),
    cmocka_unit_test(two_puppets_of_one_hand_take_a_glove_each),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
