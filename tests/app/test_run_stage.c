/* `marionette run` on the stage: headless, glove-gen on a real pty drives
 * the puppet and the frames follow the glove; in a window under Xvfb the
 * show opens, draws and takes a screenshot through its key; without a
 * glove, the keyboard's glove moves the control frame through the
 * mapping. */
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
#include "proc.h"

/* The backend the stage is drawn with (OSMesa under the sanitizers). */
#ifndef MR_APP_TEST_BACKEND
#define MR_APP_TEST_BACKEND "auto"
#endif

static const char *glove_gen;
static char *marionette;

#define STICK MR_SOURCE_DIR "/host/scenes/stick.yaml"

/* glove-gen on a new pty, every finger held at value (a script), for secs;
 * the source in source. */
static pid_t start_glove(const char *dir, const char *value, char *source, size_t size) {
  char script[600], arg[640];
  snprintf(script, sizeof script, "%s", tt_path(dir, "motion.txt"));
  FILE *f = fopen(script, "w");
  assert_non_null(f);
  static const char *const fingers[] = { "thumb", "index", "middle", "ring", "little" };
  for (int i = 0; i < 5; i++) fprintf(f, "%s const value=%s\n", fingers[i], value);
  fclose(f);
  snprintf(arg, sizeof arg, "--script=%s", script);
  const char *const args[] = { "--duration", "8", arg, NULL };
  pid_t gen = tt_glove_on_pty(glove_gen, dir, args, source, size);
  assert_true(gen > 0);
  return gen;
}

/* Two seconds of headless show at 160 x 96 with the glove held at value;
 * the last frame's pixels (free them). */
static uint8_t *show_with_glove_at(const char *value, const char *out, int *frames) {
  char *dir = tt_tmpdir(), source[300];
  pid_t gen = start_glove(dir, value, source, sizeof source);
  char *argv[] = { marionette, "run",        "--backend", MR_APP_TEST_BACKEND,
                   STICK,      "--glove",    source,      "--time",
                   "2",        "--headless", "-o",        (char *)out,
                   "--size",   "160x96",     "--samples", "1",
                   "--no-mp4", "-q",         NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  char state[64];
  assert_int_equal(tt_field(o.out, "glove", state, sizeof state), 0);
  assert_string_equal(state, "live");
  tt_output_free(&o);
  tt_wait(gen, 30);
  tt_rmdir(dir);
  free(dir);
  *frames = at_count_files(out, "frame_");
  assert_true(*frames >= 3);
  char name[64];
  snprintf(name, sizeof name, "frame_%06d.png", *frames - 1);
  int w = 0, h = 0;
  uint8_t *rgb = at_png_rgb(tt_path(out, name), &w, &h);
  assert_non_null(rgb);
  assert_int_equal(w, 160);
  assert_int_equal(h, 96);
  return rgb;
}

/* The glove held at 0.15 and at 0.85 turns, tilts and moves the bar to
 * opposite ends of the mapping: the puppet is drawn elsewhere. */
static void a_headless_show_draws_what_the_glove_on_a_pty_does(void **state) {
  (void)state;
  char *a = tt_tmpdir(), *b = tt_tmpdir();
  int na = 0, nb = 0;
  uint8_t *low = show_with_glove_at("0.15", a, &na), *high = show_with_glove_at("0.85", b, &nb);
  int differ = 0;
  for (int i = 0; i < 160 * 96; i++) {
    int d = 0;
    for (int c = 0; c < 3; c++) d += abs((int)low[3 * i + c] - (int)high[3 * i + c]);
    differ += d > 30;
  }
  /* The stick figure is a small part of the picture; a few dozen pixels
   * at least must have changed. */
  if (differ < 40) fail_msg("only %d pixels differ between the two glove poses", differ);
  assert_true(at_count_files(a, "sheet.png") == 1);
  free(low);
  free(high);
  tt_rmdir(a);
  tt_rmdir(b);
  free(a);
  free(b);
}

/* The control frame's yaw from a --poses line: 2 atan2(y, w) of its
 * orientation (w x y z), in degrees. */
static double yaw_at(const char *poses, double t) {
  const char *p = poses;
  while (p != NULL && *p != '\0') {
    double lt, x, y, z, qw, qx, qy, qz;
    if (sscanf(p, "%lf %lf %lf %lf %lf %lf %lf %lf", &lt, &x, &y, &z, &qw, &qx, &qy, &qz) == 8 &&
        lt >= t - 1e-9)
      return 2 * atan2(qy, qw) * 180 / M_PI;
    p = strchr(p, '\n');
    if (p != NULL) p++;
  }
  fail_msg("no pose at %g s", t);
  return NAN;
}

/* Without --glove, --keys holds the right arrow from 0.5 s to 2 s: the
 * keyboard's glove (a pty of its own, the protocol's frames) turns the bar
 * towards the default mapping's +45 degrees, and it comes back after. */
static void the_keyboards_glove_turns_the_control_frame(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  char poses[600];
  snprintf(poses, sizeof poses, "%s", tt_path(dir, "poses.txt"));
  char *argv[] = { marionette,      "run",       "--backend", MR_APP_TEST_BACKEND, STICK, "--keys",
                   "0.5:right/1.5", "--time",    "3.5",       "--poses",           poses, "--size",
                   "160x96",        "--samples", "1",         "--headless",        "-q",  NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_non_null(strstr(o.out, "keys glove: "));
  char *text = tt_read_file(poses, NULL);
  assert_non_null(text);
  double before = yaw_at(text, 0.3), held = yaw_at(text, 1.8), after = yaw_at(text, 3.4);
  print_message("yaw before %.1f, held %.1f, after %.1f degrees\n", before, held, after);
  assert_true(fabs(before) < 1.0);
  assert_true(fabs(held) > 30.0 && fabs(held) < 45.5); /* 0.9 of 45, eased */
  assert_true(fabs(after) < 5.0);
  free(text);
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

static double wall_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* 1.5 s of show with the keys given, headless and small; the wall time it
 * took. */
static double show_with_keys(const char *keys, tt_output *o) {
  char *argv[] = { marionette,  "run",        "--backend",  MR_APP_TEST_BACKEND,
                   STICK,       "--keys",     (char *)keys, "--time",
                   "1.5",       "--headless", "--size",     "64x64",
                   "--samples", "1",          "-q",         NULL };
  double t0 = wall_s();
  assert_int_equal(tt_capture(argv, o), 0);
  double wall = wall_s() - t0;
  if (o->status != 0) fail_msg("status %d: %s", o->status, o->err);
  assert_non_null(strstr(o->out, "simulated: 1.500 s"));
  return wall;
}

/* The keys act on show time: space stops it (2 s of pause make 1.5 s of
 * show last at least 3.5 s), s twice slows it to a quarter (the first
 * press halves it; at least 6 s), r puts
 * the puppets back and says so. Only lower bounds are asserted: a loaded
 * machine makes every run longer, never shorter, so a comparison with the
 * plain run would fail when that run alone is slowed. */
static void pause_slow_motion_and_reset_act_on_the_show(void **state) {
  (void)state;
  tt_output o;
  double paused = show_with_keys("0.5:space,2.5:space", &o);
  tt_output_free(&o);
  double slow = show_with_keys("0:s,0.01:s", &o);
  tt_output_free(&o);
  double plain = show_with_keys("1:r", &o);
  print_message("wall: plain %.2f s, paused %.2f s, slow %.2f s\n", plain, paused, slow);
  assert_non_null(strstr(o.err, "marionette run: reset: the puppets are back where they started"));
  tt_output_free(&o);
  assert_true(paused >= 3.4);
  assert_true(slow >= 5.5);
}

/* A take recorded by run --record from glove-gen renders to the same
 * frames twice: the replay runs on a virtual clock, byte for byte. */
static void a_recorded_take_renders_the_same_frames_twice(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300], take[600], out[2][600];
  pid_t gen = start_glove(dir, "0.8", source, sizeof source);
  snprintf(take, sizeof take, "%s", tt_path(dir, "show.mrec"));
  char *rec[] = { marionette, "run",    STICK, "--glove", source, "--record",
                  take,       "--time", "1",   "-q",      NULL };
  tt_output o;
  assert_int_equal(tt_capture(rec, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  tt_output_free(&o);
  tt_wait(gen, 30);
  for (int k = 0; k < 2; k++) {
    snprintf(out[k], sizeof out[k], "%s", tt_path(dir, k == 0 ? "one" : "two"));
    char *argv[] = { marionette, "render",   "--backend", MR_APP_TEST_BACKEND,
                     STICK,      "--take",   take,        "-o",
                     out[k],     "--size",   "64x48",     "--samples",
                     "1",        "--no-mp4", "-q",        NULL };
    assert_int_equal(tt_capture(argv, &o), 0);
    if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
    tt_output_free(&o);
  }
  int n = at_count_files(out[0], "frame_");
  assert_true(n >= 55); /* a second of show at 60 frames/s, and the take's tail */
  assert_int_equal(at_count_files(out[1], "frame_"), n);
  for (int i = 0; i < n; i += 7) {
    char name[64], a[700];
    snprintf(name, sizeof name, "frame_%06d.png", i);
    snprintf(a, sizeof a, "%s/%s", out[0], name);
    size_t la = 0, lb = 0;
    char *x = tt_read_file(a, &la), *y = tt_read_file(tt_path(out[1], name), &lb);
    assert_true(x != NULL && y != NULL && la == lb && memcmp(x, y, la) == 0);
    free(x);
    free(y);
  }
  tt_rmdir(out[0]);
  tt_rmdir(out[1]);
  tt_rmdir(dir);
  free(dir);
}

/* A number field of the summary ("simulated: 3.000 s" gives 3). */
static double summary_number(const char *out, const char *key) {
  char v[64];
  assert_int_equal(tt_field(out, key, v, sizeof v), 0);
  return strtod(v, NULL);
}

/* Headless, renders that cost more than a frame period are skipped, and
 * the MP4 still lasts as long as the show, within one frame: the frame
 * shown last is repeated over the skipped ones (ffprobe says how long the
 * video plays). */
static void the_headless_video_lasts_as_long_as_the_show(void **state) {
  (void)state;
  char ffprobe[512], ffmpeg[512];
  if (at_which("ffprobe", ffprobe, sizeof ffprobe) != 0 ||
      at_which("ffmpeg", ffmpeg, sizeof ffmpeg) != 0)
    skip();
  char *dir = tt_tmpdir();
  /* Large and multisampled, so that drawing a frame in software takes
   * longer than the 16.7 ms a frame may. */
  char *argv[] = { marionette,   "run",        "--backend", MR_APP_TEST_BACKEND,
                   STICK,        "--keys",     "0.5:r",     "--time",
                   "3",          "--headless", "-o",        dir,
                   "--size",     "1280x720",   "--samples", "4",
                   "--no-sheet", "-q",         NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  double simulated = summary_number(o.out, "simulated");
  double shown = summary_number(o.out, "frames shown"),
         all = summary_number(o.out, "frames simulated");
  tt_output_free(&o);
  char mp4[700];
  snprintf(mp4, sizeof mp4, "%s", tt_path(dir, "show.mp4"));
  char *probe[] = { ffprobe,   "-v", "error", "-show_entries", "format=duration", "-of",
                    "csv=p=0", mp4,  NULL };
  assert_int_equal(tt_capture(probe, &o), 0);
  assert_int_equal(o.status, 0);
  double duration = strtod(o.out, NULL);
  tt_output_free(&o);
  print_message("show %.3f s, %.0f of %.0f frames drawn; the video plays %.3f s\n", simulated,
                shown, all, duration);
  if (shown >= all) print_message("no render was skipped: the repeats were not needed\n");
  assert_true(simulated >= 2.99);
  assert_true(fabs(duration - simulated) <= 1.0 / 60 + 1e-3);
  tt_rmdir(dir);
  free(dir);
}

/* --mp4 and --sheet without -o: those two files and nothing else, the
 * video as long as the show and as many frames as the summary says. */
static void without_o_the_mp4_and_the_sheet_named_are_written_alone(void **state) {
  (void)state;
  char ffprobe[512], ffmpeg[512];
  if (at_which("ffprobe", ffprobe, sizeof ffprobe) != 0 ||
      at_which("ffmpeg", ffmpeg, sizeof ffmpeg) != 0)
    skip();
  char *dir = tt_tmpdir(), mp4[700], sheet[700];
  snprintf(mp4, sizeof mp4, "%s", tt_path(dir, "v.mp4"));
  snprintf(sheet, sizeof sheet, "%s", tt_path(dir, "s.png"));
  char *argv[] = { marionette, "run",        "--backend", MR_APP_TEST_BACKEND,
                   STICK,      "--keys",     "0.3:r",     "--time",
                   "1.5",      "--mp4",      mp4,         "--sheet",
                   sheet,      "--size",     "160x96",    "--samples",
                   "1",        "--headless", "-q",        NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_null(strstr(o.out, "png frames"));
  const double encoded = summary_number(o.out, "mp4");
  tt_output_free(&o);
  char frames[64];
  assert_int_equal(at_video_stream(ffprobe, mp4, "nb_read_frames", frames, sizeof frames), 0);
  assert_true(encoded >= 1.5 * 60 - 1);
  assert_int_equal(strtol(frames, NULL, 10), (long)encoded);
  int w = 0, h = 0;
  assert_int_equal(at_png_size(sheet, &w, &h), 0);
  assert_true(w > 160 && h >= 96);
  assert_int_equal(at_count_files(dir, "frame_"), 0);
  assert_int_equal(at_count_files(dir, ""), 4); /* ., .., the video and the sheet */
  tt_rmdir(dir);
  free(dir);
}

/* A headless show of 2 s draws the frame it ends on: the status line of
 * its second 2 is printed when that frame is shown, and the scheduler
 * alone (a frame shown a tick after it is made) would never show it. At a
 * size where every render is slow (renders skipped) as at one where none
 * is. */
static void a_headless_show_draws_the_frame_it_ends_on(void **state) {
  (void)state;
  static const char *const sizes[] = { "64x36", "1280x720" };
  for (int i = 0; i < 2; i++) {
    char *dir = tt_tmpdir();
    char *argv[] = { marionette,
                     "run",
                     "--backend",
                     MR_APP_TEST_BACKEND,
                     STICK,
                     "--time",
                     "2",
                     "-o",
                     dir,
                     "--size",
                     (char *)sizes[i],
                     "--headless",
                     "--keys",
                     "0.5:right/0.5",
                     "--no-sheet",
                     NULL };
    tt_output o;
    assert_int_equal(tt_capture(argv, &o), 0);
    if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
    char shown[64], skipped[64];
    assert_int_equal(tt_field(o.out, "frames shown", shown, sizeof shown), 0);
    assert_int_equal(tt_field(o.out, "frames skipped", skipped, sizeof skipped), 0);
    print_message("%s: %s frames shown, %s skipped\n", sizes[i], shown, skipped);
    if (strstr(o.out, "t 2 s: ") == NULL)
      fail_msg("%s: the frame at 2 s was not shown:\n%s", sizes[i], o.out);
    tt_output_free(&o);
    tt_rmdir(dir);
    free(dir);
  }
}

/* Under Xvfb: the window opens, draws, the p key takes a screenshot of
 * the size asked, and q ends the show with status 0. */
static void the_window_opens_draws_and_takes_a_screenshot_under_xvfb(void **state) {
  (void)state;
  char xvfb[512];
  if (at_which("xvfb-run", xvfb, sizeof xvfb) != 0) {
    print_message("xvfb-run is not installed: the window is not tried\n");
    skip();
  }
#ifdef MR_APP_TEST_SANITIZE
  /* The window's GL driver is unloaded before the leak check, leaving
   * stacks no suppression can name; the headless tests above check the
   * program's own allocations. */
  setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
#endif
  char *dir = tt_tmpdir();
  char *argv[] = { xvfb,       "-a",     "-s",      "-screen 0 640x480x24",
                   marionette, "run",    STICK,     "--keys",
                   "2:p,3:q",  "--size", "320x180", "-o",
                   dir,        "--time", "20",      NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  const char *stage = strstr(o.out, "stage: in a window (SDL), 320x180, ");
  assert_non_null(stage);
  long drawn = strtol(stage + strlen("stage: in a window (SDL), 320x180, "), NULL, 10);
  print_message("%ld frames drawn in the window\n", drawn);
  assert_true(drawn >= 2);
  int w = 0, h = 0;
  assert_int_equal(at_png_size(tt_path(dir, "shot_000.png"), &w, &h), 0);
  assert_int_equal(w, 320);
  assert_int_equal(h, 180);
  /* q at 3 s ended a 20 s show. */
  char sim[64];
  assert_int_equal(tt_field(o.out, "simulated", sim, sizeof sim), 0);
  assert_true(strtod(sim, NULL) < 10.0);
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

/* The pixels that differ by more than 30 (summed over RGB) between two
 * PNG files of one size. */
static int pixels_apart(const char *a, const char *b) {
  int wa = 0, ha = 0, wb = 0, hb = 0;
  uint8_t *pa = at_png_rgb(a, &wa, &ha), *pb = at_png_rgb(b, &wb, &hb);
  assert_non_null(pa);
  assert_non_null(pb);
  assert_true(wa == wb && ha == hb);
  int n = 0;
  for (int i = 0; i < wa * ha; i++) {
    int d = 0;
    for (int c = 0; c < 3; c++) d += abs((int)pa[3 * i + c] - (int)pb[3 * i + c]);
    n += d > 30;
  }
  free(pa);
  free(pb);
  return n;
}

/* Under Xvfb, paused: two screenshots of scene are the same picture, and
 * a third after a key: the pixels it changed (-1: no xvfb-run). The
 * overlay is hidden (its frame rate changes from frame to frame), and
 * the shots wait 2 s for the pause: under a sanitizer on a busy box a
 * frame takes over a second, and the physics runs ahead of it. The second
 * shot and the key fall due together: the shot shows the frame before. */
static int pixels_changed_by_key(const char *scene, const char *keys) {
  char xvfb[512];
  if (at_which("xvfb-run", xvfb, sizeof xvfb) != 0) return -1;
#ifdef MR_APP_TEST_SANITIZE
  setenv("ASAN_OPTIONS", "detect_leaks=0", 1); /* as the window test above */
#endif
  char *dir = tt_tmpdir();
  char *argv[] = { xvfb,         "-a",     "-s",          "-screen 0 640x480x24",
                   marionette,   "run",    (char *)scene, "--keys",
                   (char *)keys, "--size", "320x180",     "-o",
                   dir,          "--time", "20",          NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  char s0[600], s1[600], s2[600];
  snprintf(s0, sizeof s0, "%s", tt_path(dir, "shot_000.png"));
  snprintf(s1, sizeof s1, "%s", tt_path(dir, "shot_001.png"));
  snprintf(s2, sizeof s2, "%s", tt_path(dir, "shot_002.png"));
  assert_int_equal(pixels_apart(s0, s1), 0);
  int changed = pixels_apart(s1, s2);
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
  return changed;
}

/* After m the stick figure's rods wear their red lacquer (§3.3: a
 * material changes while the show runs), which only the rods' pixels
 * show. */
static void the_m_key_changes_what_the_puppet_wears(void **state) {
  (void)state;
  int changed = pixels_changed_by_key(STICK, "0.2:h,1:space,3:p,3.5:p,3.5:m,4.5:p,5:q");
  if (changed < 0) skip();
  print_message("%d pixels changed with the materials\n", changed);
  /* The rods are thin: a few dozen pixels at this size, a small part of
   * the 57 600. */
  assert_true(changed >= 20 && changed < 3000);
}

/* The bird's collision spheres are hidden until c shows them: pale balls
 * over its body, wings and tail, a few hundred pixels at 320x180 from the
 * audience's seats (191 measured; none without the key). */
static void the_c_key_shows_the_collision_spheres(void **state) {
  (void)state;
  int changed = pixels_changed_by_key(MR_SOURCE_DIR "/host/scenes/bird.yaml",
                                      "0.2:h,1:space,3:p,3.5:p,3.5:c,4.5:p,5:q");
  if (changed < 0) skip();
  print_message("%d pixels changed with the spheres\n", changed);
  assert_true(changed >= 100 && changed < 320 * 180 / 4);
}

/* The curtain's red in the middle ninth of a screenshot (the middle
 * third of its rows and of its columns: inside the arch's opening, whose
 * own red is around it). */
static int velvet_in_the_middle(const char *path) {
  int w = 0, h = 0, n = 0;
  uint8_t *p = at_png_rgb(path, &w, &h);
  assert_non_null(p);
  for (int y = h / 3; y < 2 * h / 3; y++)
    for (int x = w / 3; x < 2 * w / 3; x++) {
      const uint8_t *q = p + 3 * ((size_t)y * (size_t)w + (size_t)x);
      n += q[0] > 40 && q[0] > 2 * q[1] && 2 * q[0] > 3 * q[2];
    }
  free(p);
  return n;
}

/* The window's show under Xvfb, keys as given, for at most 20 s: the
 * show time it ended at, and the screenshots into dir. */
static double window_show_until(const char *xvfb, const char *keys, const char *dir) {
  char *argv[] = { (char *)xvfb, "-a",       "-s",      "-screen 0 640x480x24",
                   marionette,   "run",      STICK,     "--keys",
                   (char *)keys, "--size",   "320x180", "-o",
                   (char *)dir,  "--no-osd", "--time",  "20",
                   NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  char sim[64];
  assert_int_equal(tt_field(o.out, "simulated", sim, sizeof sim), 0);
  tt_output_free(&o);
  return strtod(sim, NULL);
}

/* Under Xvfb: q at 2.5 s does not end the show at once; the curtain
 * closes over its 1.5 s (a screenshot near its end shows it over the
 * stage, one before q the stage open), then the show ends. A second q
 * ends it at once. */
static void q_plays_the_closing_curtain_and_a_second_q_stops_at_once(void **state) {
  (void)state;
  char xvfb[512];
  if (at_which("xvfb-run", xvfb, sizeof xvfb) != 0) {
    print_message("xvfb-run is not installed: the window is not tried\n");
    skip();
  }
#ifdef MR_APP_TEST_SANITIZE
  setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
#endif
  char *dir = tt_tmpdir();
  double end = window_show_until(xvfb, "2.2:p,2.5:q,3.85:p", dir);
  print_message("q at 2.5 s: the show ended at %.2f s\n", end);
  assert_true(end >= 3.85 && end < 8);
  int open = velvet_in_the_middle(tt_path(dir, "shot_000.png"));
  int closing = velvet_in_the_middle(tt_path(dir, "shot_001.png"));
  print_message("the curtain's pixels in the middle: %d open, %d closing\n", open, closing);
  assert_int_equal(open, 0);
  assert_true(closing > 320 / 3 * 180 / 3 * 3 / 4);
  double hurried = window_show_until(xvfb, "2.5:q,2.7:q", dir);
  print_message("q twice: the show ended at %.2f s\n", hurried);
  assert_true(hurried >= 2.5 && hurried < 3.5);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: %s GLOVE_GEN MARIONETTE\n", argv[0]);
    return 2;
  }
  glove_gen = argv[1];
  marionette = argv[2];
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_headless_show_draws_what_the_glove_on_a_pty_does),
    cmocka_unit_test(the_keyboards_glove_turns_the_control_frame),
    cmocka_unit_test(pause_slow_motion_and_reset_act_on_the_show),
    cmocka_unit_test(a_recorded_take_renders_the_same_frames_twice),
    cmocka_unit_test(the_headless_video_lasts_as_long_as_the_show),
    cmocka_unit_test(a_headless_show_draws_the_frame_it_ends_on),
    cmocka_unit_test(without_o_the_mp4_and_the_sheet_named_are_written_alone),
    cmocka_unit_test(the_window_opens_draws_and_takes_a_screenshot_under_xvfb),
    cmocka_unit_test(the_m_key_changes_what_the_puppet_wears),
    cmocka_unit_test(the_c_key_shows_the_collision_spheres),
    cmocka_unit_test(q_plays_the_closing_curtain_and_a_second_q_stops_at_once),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
