/* `marionette run` as a puppeteer meets it: glove-gen plays a glove on a
 * real pty, the theater reads it in real time and drives the example
 * puppet; the stream ending mid-show loses the glove without stopping the
 * show; a glove built from another protocol definition is named and ends
 * with the documented status. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include "proc.h"

static const char *glove_gen, *marionette;

#define PUPPET MR_SOURCE_DIR "/host/scenes/puppet.yaml"

/* glove-gen on a new pty for `secs` of stream (extra arguments after);
 * the pty's path in path (static). */
static pid_t start_glove(const char *dir, const char *secs, const char *extra, char *source,
                         size_t size) {
  const char *const args[] = { "--duration", secs, extra, NULL };
  pid_t gen = tt_glove_on_pty(glove_gen, dir, args, source, size);
  assert_true(gen > 0);
  return gen;
}

static void run_show(const char *source, const char *secs, tt_output *o) {
  char *argv[] = { (char *)marionette, "run",        PUPPET, "--glove", (char *)source,
                   "--time",           (char *)secs, "-q",   NULL };
  assert_int_equal(tt_capture(argv, o), 0);
}

static long long field(const char *text, const char *key) {
  char v[64];
  if (tt_field(text, key, v, sizeof v) != 0) fail_msg("no '%s' in:\n%s", key, text);
  return strtoll(v, NULL, 10);
}

/* Two seconds of show at 60 fps from a 250 Hz glove: the frames simulated
 * and shown, the glove live throughout, its samples taken. */
static void a_glove_drives_the_puppet_in_real_time(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300];
  pid_t gen = start_glove(dir, "4", NULL, source, sizeof source);
  tt_output o;
  run_show(source, "2", &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  char glove[64];
  assert_int_equal(tt_field(o.out, "glove", glove, sizeof glove), 0);
  assert_string_equal(glove, "live");
  /* 121 frames (0 to 2 s at 60 fps) unless a loaded test machine made
   * the scheduler give lag up; the sanitizer build runs this too. */
  assert_true(field(o.out, "frames simulated") >= 100);
  assert_true(field(o.out, "frames simulated") <= 121);
  assert_true(field(o.out, "frames shown") >= 50);
  assert_true(field(o.out, "glove samples") >= 250); /* 250 Hz for 2 s, less the start */
  assert_int_equal(field(o.out, "glove losses"), 0);
  assert_int_equal(field(o.out, "resets"), 0);
  /* Read at a frame's start, shown at the next: within two periods. */
  char lat[32];
  assert_int_equal(tt_field(o.out, "latency p99", lat, sizeof lat), 0);
  assert_true(strtod(lat, NULL) > 0 && strtod(lat, NULL) <= 2e3 / 60 + 1);
  tt_output_free(&o);
  tt_wait(gen, 30);
  tt_rmdir(dir);
  free(dir);
}

/* The glove stops after one second of a three-second show: it is lost, the
 * show goes on to its end and says so. The show reaches the pty through a
 * link that is taken away once it is open, as a device node goes with its
 * device: the kernel may give the pty's number to another test's pty
 * meanwhile, and a retry must not find a stranger's stream there. */
static void a_glove_lost_mid_show_does_not_stop_it(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300], link_path[300], via[320], out_path[300];
  pid_t gen = start_glove(dir, "1", NULL, source, sizeof source);
  snprintf(link_path, sizeof link_path, "%s", tt_path(dir, "glove"));
  assert_int_equal(symlink(source + 4, link_path), 0);
  snprintf(via, sizeof via, "pty:%s", link_path);
  snprintf(out_path, sizeof out_path, "%s", tt_path(dir, "show.out"));
  const char *argv[] = { marionette, "run", PUPPET, "--glove", via, "--time", "3", "-q", NULL };
  pid_t show = tt_spawn(argv, out_path, NULL);
  assert_true(show > 0);
  usleep(500000); /* opened at the first frame */
  unlink(link_path);
  assert_int_equal(tt_wait(show, 60), 0);
  char *out = tt_read_file(out_path, NULL);
  assert_non_null(out);
  char glove[64];
  assert_int_equal(tt_field(out, "glove", glove, sizeof glove), 0);
  assert_string_equal(glove, "lost");
  assert_int_equal(field(out, "glove losses"), 1);
  assert_true(field(out, "frames simulated") >= 150);
  free(out);
  tt_wait(gen, 30);
  tt_rmdir(dir);
  free(dir);
}

/* A glove built from another definition: exit 3, named in the summary. */
static void a_foreign_glove_ends_with_status_3(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300];
  pid_t gen = start_glove(dir, "3", "--spec-hash=12345678", source, sizeof source);
  tt_output o;
  run_show(source, "1.5", &o);
  assert_int_equal(o.status, 3);
  assert_non_null(strstr(o.out, "glove: spec mismatch\n"));
  tt_output_free(&o);
  tt_wait(gen, 30);
  tt_rmdir(dir);
  free(dir);
}

/* A faulty stream (every fault glove-gen knows, 10 % of frames: flipped
 * bits, cut frames, garbage, duplicates, reordering, foreign frames, stalls)
 * does not stop the show: the faults are counted and the glove read on. */
static void a_faulty_stream_is_counted_and_the_show_goes_on(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300];
  pid_t gen = start_glove(dir, "4", "--faults=0.1", source, sizeof source);
  tt_output o;
  run_show(source, "2", &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_true(field(o.out, "glove samples") >= 150);
  assert_true(field(o.out, "glove crc errors") > 0);
  assert_int_equal(field(o.out, "resets"), 0);
  char want[400];
  snprintf(want, sizeof want, "marionette run: glove on %s: ", source);
  const char *line = strstr(o.err, want);
  assert_non_null(line);
  line = strstr(o.err, " corrupt frames in ");
  if (line == NULL) fail_msg("no corrupt frames line in:\n%s", o.err);
  assert_true(field(o.out, "frames simulated") >= 100);
  tt_output_free(&o);
  tt_wait(gen, 30);
  tt_rmdir(dir);
  free(dir);
}

/* A sensor that reads 0 throughout (torn off), and one at full scale
 * (shorted) is held at neutral after the mapping's stuck_after (2 s), told in
 * one line naming the glove, its source and the finger, and the show goes
 * on with the other four fingers. */
static void a_stuck_channel_is_named_and_the_show_goes_on(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300], script[600];
  const char *path = tt_path(dir, "stuck.txt");
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fputs("index const value=0\nlittle const value=1\n", f);
  fclose(f);
  snprintf(script, sizeof script, "--script=%s", path);
  pid_t gen = start_glove(dir, "5", script, source, sizeof source);
  tt_output o;
  run_show(source, "3.5", &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  char want[512];
  snprintf(want, sizeof want,
           "marionette run: glove 1 on %s: channel 1 (index finger) is stuck at 0 or at full "
           "scale: held at neutral",
           source);
  if (strstr(o.err, want) == NULL) fail_msg("expected '%s' in:\n%s", want, o.err);
  assert_non_null(strstr(o.err, "channel 4 (little finger) is stuck at 0 or at full scale"));
  assert_null(strstr(o.err, "channel 0")); /* the others read on */
  assert_true(field(o.out, "frames simulated") >= 200);
  tt_output_free(&o);
  tt_wait(gen, 30);
  tt_rmdir(dir);
  free(dir);
}

/* A source that never answers (a TCP peer that takes the connection and
 * sends nothing) is named, with what is wrong, and the show goes on. */
static void a_silent_source_is_named_and_the_show_goes_on(void **state) {
  (void)state;
  int ls = socket(AF_INET, SOCK_STREAM, 0);
  assert_true(ls >= 0);
  struct sockaddr_in a = { .sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
  socklen_t len = sizeof a;
  assert_int_equal(bind(ls, (struct sockaddr *)&a, sizeof a), 0);
  assert_int_equal(listen(ls, 4), 0);
  assert_int_equal(getsockname(ls, (struct sockaddr *)&a, &len), 0);
  char source[64];
  snprintf(source, sizeof source, "tcp:127.0.0.1:%d", ntohs(a.sin_port));
  tt_output o;
  run_show(source, "2.5", &o);
  close(ls);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  char want[200];
  snprintf(want, sizeof want, "marionette run: glove on %s: lost ", source);
  if (strstr(o.err, want) == NULL) fail_msg("expected '%s' in:\n%s", want, o.err);
  assert_non_null(strstr(o.err, "(no bytes for longer than lost_after); retrying every 0.5 s"));
  assert_true(field(o.out, "frames simulated") >= 140);
  assert_int_equal(field(o.out, "glove samples"), 0);
  tt_output_free(&o);
}

/* `marionette calibrate` walks through the seven steps on a glove-gen
 * glove, saves the capture on it, and prints the range it stored; a glove
 * that never answers, or a source that ends before any glove streams,
 * ends it with one line, status 1. */
static void calibrate_saves_the_range_on_the_glove(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300];
  pid_t gen = start_glove(dir, "6", NULL, source, sizeof source);
  char *argv[] = { (char *)marionette, "calibrate", "--glove", source, "--step-time", "0.3", NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_non_null(strstr(o.out, "7/7  Bend the little finger alone"));
  const char *saved = strstr(o.out, "saved on the glove (raw ADC counts):\n");
  assert_non_null(saved);
  unsigned lo = 0, hi = 0;
  assert_int_equal(sscanf(strstr(saved, "thumb"), "thumb %u .. %u", &lo, &hi), 2);
  assert_true(lo < hi && hi <= 4095);
  tt_output_free(&o);
  tt_wait(gen, 30);
  gen = start_glove(dir, "6", "--ignore-commands=1000", source, sizeof source);
  argv[3] = source;
  assert_int_equal(tt_capture(argv, &o), 0);
  assert_int_equal(o.status, 1);
  if (strstr(o.err, "marionette calibrate: CAL_START was not answered after 5 tries (glove on ") ==
      NULL)
    fail_msg("got: %s", o.err);
  tt_output_free(&o);
  kill(gen, SIGTERM);
  tt_wait(gen, 30);
  /* A source that ends before any glove streams: one line saying so, as
   * soon as it ended, not after the 5 s a glove is waited for (the line
   * says how long ago the stream ended). */
  char *none[] = { (char *)marionette, "calibrate", "--glove", "file:/dev/null", NULL };
  assert_int_equal(tt_capture(none, &o), 0);
  assert_int_equal(o.status, 1);
  const char *ended = strstr(o.err, "ended ");
  if (strstr(o.err,
             "marionette calibrate: no glove is streaming there (glove on file:/dev/null: ") ==
          NULL ||
      ended == NULL || strstr(o.err, "the stream ended") == NULL ||
      strchr(o.err, '\n')[1] != '\0' || !(strtod(ended + 6, NULL) < 4.0))
    fail_msg("got: %s", o.err);
  tt_output_free(&o);
  char *bad[] = { (char *)marionette, "calibrate", "--step-time", "-1", NULL };
  assert_int_equal(tt_capture(bad, &o), 0);
  assert_int_equal(o.status, 2);
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

/* A scene with two mappings starts on the one asked for (the second, and
 * the first), moves to the next on SIGUSR1 during the show and says so; a
 * name the scene lacks is refused with the names it has. */
static void mappings_switch_during_the_show(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300], scene[300], out[300], err[300];
  char *text = tt_read_file(PUPPET, NULL);
  assert_non_null(text);
  snprintf(scene, sizeof scene, "%s", tt_path(dir, "two.yaml"));
  FILE *f = fopen(scene, "w");
  assert_non_null(f);
  fprintf(f,
          "%s\nmapping:\n  - name: walk\n  - name: head-only\n    axes:\n"
          "      turn_y: {channel: 2}\n",
          text);
  fclose(f);
  free(text);
  pid_t gen = start_glove(dir, "4", NULL, source, sizeof source);
  snprintf(out, sizeof out, "%s", tt_path(dir, "show.out"));
  snprintf(err, sizeof err, "%s", tt_path(dir, "show.err"));
  const char *argv[] = { marionette, "run",       scene,       "--glove", source, "--time",
                         "3",        "--mapping", "head-only", "-q",      NULL };
  pid_t show = tt_spawn(argv, out, err);
  assert_true(show > 0);
  usleep(1500000);
  kill(show, SIGUSR1);
  assert_int_equal(tt_wait(show, 30), 0);
  char *said = tt_read_file(err, NULL), *summary = tt_read_file(out, NULL);
  assert_non_null(said);
  assert_non_null(summary);
  if (strstr(said, "marionette run: mapping 'walk' (1 of 2)\n") == NULL) fail_msg("%s", said);
  assert_non_null(strstr(summary, "mapping: walk\n"));
  free(said);
  free(summary);
  tt_wait(gen, 30);
  /* A source that is there (a missing one is bad usage, found first). */
  char *bad[] = { (char *)marionette, "run",       scene,   "--glove",
                  "/dev/null",        "--mapping", "dance", NULL };
  tt_output o;
  assert_int_equal(tt_capture(bad, &o), 0);
  assert_int_equal(o.status, 1);
  assert_non_null(strstr(o.err, "no mapping 'dance' in the scene; it has: walk, head-only"));
  tt_output_free(&o);
  /* The first of the scene's mappings, asked for by name, is taken. */
  char *first[] = { (char *)marionette, "run", scene, "--glove", "/dev/null", "--mapping", "walk",
                    "--time",           "0.2", "-q",  NULL };
  assert_int_equal(tt_capture(first, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_non_null(strstr(o.out, "mapping: walk\n"));
  tt_output_free(&o);
  /* A scene of no mappings of its own has the paper's alone. */
  bad[2] = PUPPET;
  assert_int_equal(tt_capture(bad, &o), 0);
  assert_int_equal(o.status, 1);
  if (strstr(o.err, "no mapping 'dance' in the scene; it has: only the default\n") == NULL)
    fail_msg("%s", o.err);
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

/* A take recorded live replays on a virtual clock to the same state at
 * every one of its 121 frames, bit for bit: on one thread (the default
 * without a window) and with the physics on a thread of its own, as in a
 * window. */
static void a_take_replays_to_identical_frames_on_one_thread_or_two(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300];
  pid_t gen = start_glove(dir, "4", NULL, source, sizeof source);
  const char *take = tt_path(dir, "take.mrec");
  char take_path[300], live[300], again[300], threaded[300];
  snprintf(take_path, sizeof take_path, "%s", take);
  snprintf(live, sizeof live, "%s", tt_path(dir, "live.hashes"));
  snprintf(again, sizeof again, "%s", tt_path(dir, "replay.hashes"));
  snprintf(threaded, sizeof threaded, "%s", tt_path(dir, "threaded.hashes"));
  char *rec[] = { (char *)marionette, "run",     PUPPET,     "--glove", source, "--time", "2", "-q",
                  "--record",         take_path, "--hashes", live,      NULL };
  tt_output o;
  assert_int_equal(tt_capture(rec, &o), 0);
  if (o.status != 0) fail_msg("live: status %d: %s", o.status, o.err);
  tt_output_free(&o);
  tt_wait(gen, 30);
  char *play[] = { (char *)marionette, "run", PUPPET, "--replay", take_path, "--time", "2", "-q",
                   "--hashes",         again, NULL };
  assert_int_equal(tt_capture(play, &o), 0);
  if (o.status != 0) fail_msg("replay: status %d: %s", o.status, o.err);
  assert_true(field(o.out, "glove samples") >= 250);
  tt_output_free(&o);
  char *two[] = { (char *)marionette, "run", PUPPET,     "--replay", take_path, "--time", "2", "-q",
                  "--thread",         "on",  "--hashes", threaded,   NULL };
  assert_int_equal(tt_capture(two, &o), 0);
  if (o.status != 0) fail_msg("threaded replay: status %d: %s", o.status, o.err);
  tt_output_free(&o);
  size_t n1 = 0, n2 = 0, n3 = 0;
  char *a = tt_read_file(live, &n1), *b = tt_read_file(again, &n2),
       *c = tt_read_file(threaded, &n3);
  assert_non_null(a);
  assert_non_null(b);
  assert_non_null(c);
  int lines = 0;
  for (size_t i = 0; i < n1; i++) lines += a[i] == '\n';
  assert_true(lines >= 100); /* a frame a line */
  assert_int_equal(n1, n2);
  assert_memory_equal(a, b, n1);
  assert_int_equal(n1, n3);
  assert_memory_equal(a, c, n1);
  free(a);
  free(b);
  free(c);
  tt_rmdir(dir);
  free(dir);
}

/* A show killed mid-take (SIGKILL: nothing is flushed or closed) leaves a
 * take that replays up to its last whole chunk. */
static void a_killed_show_leaves_a_playable_take(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300];
  pid_t gen = start_glove(dir, "10", NULL, source, sizeof source);
  char take_path[300];
  snprintf(take_path, sizeof take_path, "%s", tt_path(dir, "cut.mrec"));
  const char *rec[] = { marionette, "run", PUPPET,     "--glove", source, "--time",
                        "10",       "-q",  "--record", take_path, NULL };
  pid_t show = tt_spawn(rec, NULL, tt_path(dir, "show.err"));
  assert_true(show > 0);
  usleep(1500000);
  kill(show, SIGKILL);
  assert_int_equal(tt_wait(show, 10), 128 + SIGKILL);
  kill(gen, SIGTERM);
  tt_wait(gen, 10);
  char *play[] = { (char *)marionette, "run", PUPPET, "--replay", take_path, "-q", NULL };
  tt_output o;
  assert_int_equal(tt_capture(play, &o), 0);
  if (o.status != 0) fail_msg("replay: status %d: %s", o.status, o.err);
  assert_true(field(o.out, "glove samples") >= 100);
  char glove[64];
  assert_int_equal(tt_field(o.out, "glove", glove, sizeof glove), 0);
  assert_string_equal(glove, "lost"); /* the take ended: the show ends there */
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

/* Frames interpolated between the steps: the physics runs ahead of the
 * frame by up to a step, and the summary says how far, on average and at
 * most (a step is at most the scene's dt_max, 50 ms); landing says
 * nothing of it. */
static void interpolated_frames_say_how_far_the_physics_ran_ahead(void **state) {
  (void)state;
  char *argv[] = { (char *)marionette, "run",         PUPPET, "--glove", "/dev/null", "--time", "1",
                   "--present",        "interpolate", "-q",   NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_non_null(strstr(o.out, "present: interpolate\n"));
  const char *at = strstr(o.out, "physics ahead of frames: mean ");
  if (at == NULL) fail_msg("%s", o.out);
  double mean = -1, max = -1;
  assert_int_equal(sscanf(at, "physics ahead of frames: mean %lf ms, max %lf ms", &mean, &max), 2);
  if (!(mean > 0 && mean <= max && max <= 50.0))
    fail_msg("ahead by %g ms on average, %g ms at most", mean, max);
  tt_output_free(&o);
  argv[8] = "land";
  assert_int_equal(tt_capture(argv, &o), 0);
  assert_int_equal(o.status, 0);
  assert_non_null(strstr(o.out, "present: land\n"));
  assert_null(strstr(o.out, "physics ahead"));
  tt_output_free(&o);
}

/* The ports are listed whatever this machine has (none is a fine answer),
 * and a glove looked for on every USB port when there is none is a state
 * the show runs through, saying why. */
static void ports_are_listed_and_auto_finds_no_glove_clearly(void **state) {
  (void)state;
  char *argv[] = { (char *)marionette, "list-ports", "--no-probe", NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  assert_int_equal(o.status, 0);
  assert_true(strncmp(o.out, "no serial ports\n", 16) == 0 || strncmp(o.out, "port ", 5) == 0);
  tt_output_free(&o);
  char *bad[] = { (char *)marionette, "list-ports", "--wait", "-1", NULL };
  assert_int_equal(tt_capture(bad, &o), 0);
  assert_int_equal(o.status, 2);
  tt_output_free(&o);
  char *show[] = { (char *)marionette, "run",    PUPPET, "--glove",
                   "serial:auto",      "--time", "1.2",  NULL };
  assert_int_equal(tt_capture(show, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_non_null(strstr(o.out, "glove on serial:auto: connecting (no glove on any of "));
  assert_non_null(strstr(o.out, "glove: connecting\n"));
  tt_output_free(&o);
}

static void bad_usage_exits_2_with_one_line(void **state) {
  (void)state;
  char *argv[] = { (char *)marionette, "run", PUPPET, NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  assert_int_equal(o.status, 2);
  assert_string_equal(o.err,
                      "marionette run: expected --glove SOURCE or --replay TAKE (see marionette "
                      "run --help)\n");
  tt_output_free(&o);
  char *mixed[] = { (char *)marionette, "run",      PUPPET,   "--glove",
                    "pty:/x",           "--replay", "t.mrec", NULL };
  assert_int_equal(tt_capture(mixed, &o), 0);
  assert_int_equal(o.status, 2);
  assert_non_null(strstr(o.err, "expected gloves or takes, not both"));
  tt_output_free(&o);
  char *takes[] = { (char *)marionette, "run",    PUPPET,     "--glove", "pty:/x",
                    "--record",         "a.mrec", "--record", "b.mrec",  NULL };
  assert_int_equal(tt_capture(takes, &o), 0);
  assert_int_equal(o.status, 2);
  assert_non_null(strstr(o.err, "expected at most one --record per --glove"));
  tt_output_free(&o);
  /* A glove source that does not parse is bad usage too. */
  char *bad[] = { (char *)marionette, "run", PUPPET, "--glove", "pty:", NULL };
  assert_int_equal(tt_capture(bad, &o), 0);
  assert_int_equal(o.status, 2);
  assert_non_null(strstr(o.err, "glove source 'pty:': expected serial:DEV"));
  tt_output_free(&o);
}

int main(int argc, char **argv) {
  glove_gen = argc > 1 ? argv[1] : "glove-gen";
  marionette = argc > 2 ? argv[2] : "marionette";
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_glove_drives_the_puppet_in_real_time),
    cmocka_unit_test(a_glove_lost_mid_show_does_not_stop_it),
    cmocka_unit_test(a_foreign_glove_ends_with_status_3),
    cmocka_unit_test(a_faulty_stream_is_counted_and_the_show_goes_on),
    cmocka_unit_test(a_stuck_channel_is_named_and_the_show_goes_on),
    cmocka_unit_test(a_silent_source_is_named_and_the_show_goes_on),
    cmocka_unit_test(calibrate_saves_the_range_on_the_glove),
    cmocka_unit_test(mappings_switch_during_the_show),
    cmocka_unit_test(interpolated_frames_say_how_far_the_physics_ran_ahead),
    cmocka_unit_test(a_take_replays_to_identical_frames_on_one_thread_or_two),
    cmocka_unit_test(a_killed_show_leaves_a_playable_take),
    cmocka_unit_test(ports_are_listed_and_auto_finds_no_glove_clearly),
    cmocka_unit_test(bad_usage_exits_2_with_one_line),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
