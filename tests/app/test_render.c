/* `marionette render` as a maker meets it: it writes the frames asked for,
 * of the size asked for, with a contact sheet and an MP4 whose frame count
 * ffprobe confirms; the same scene and options give the same PNG bytes;
 * bad usage is one line and status 2; a missing model is one line naming
 * the scene's file:line:column and the model's path, status 1. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_test.h"
#include "proc.h"

/* The backend the stage is drawn with (OSMesa under the sanitizers). */
#ifndef MR_APP_TEST_BACKEND
#define MR_APP_TEST_BACKEND "auto"
#endif

static char *marionette;

#define PUPPET MR_SOURCE_DIR "/host/scenes/puppet.yaml"

/* A second of the example puppet at 10 frames/s, 160 x 96, into dir,
 * with up to two more arguments. */
static void render_into(const char *dir, const char *extra, const char *extra2, tt_output *o) {
  char *argv[] = { marionette,     "render",    PUPPET,   "--backend", MR_APP_TEST_BACKEND,
                   "-o",           (char *)dir, "--time", "1",         "--fps",
                   "10",           "--size",    "160x96", "-q",        (char *)extra,
                   (char *)extra2, NULL };
  assert_int_equal(tt_capture(argv, o), 0);
  if (o->status != 0) fail_msg("status %d: %s", o->status, o->err);
}

static void frames_of_the_size_asked_a_sheet_and_a_video_are_written(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  tt_output o;
  render_into(dir, NULL, NULL, &o);
  /* Frames at 0, 0.1, ... 1.0 s: eleven. */
  assert_int_equal(at_count_files(dir, "frame_"), 11);
  int w = 0, h = 0;
  assert_int_equal(at_png_size(tt_path(dir, "frame_000010.png"), &w, &h), 0);
  assert_int_equal(w, 160);
  assert_int_equal(h, 96);
  assert_int_equal(at_png_size(tt_path(dir, "sheet.png"), &w, &h), 0);
  assert_true(w > 160 && h >= 96); /* a grid of thumbnails */
  assert_non_null(strstr(o.out, "frames: 11 at 10 fps"));
  char ffprobe[512];
  if (at_which("ffprobe", ffprobe, sizeof ffprobe) == 0) {
    char got[200];
    assert_int_equal(at_video_stream(ffprobe, tt_path(dir, "show.mp4"),
                                     "width,height,nb_read_frames", got, sizeof got),
                     0);
    assert_string_equal(got, "160,96,11\n");
  } else {
    print_message("ffprobe is not installed: the MP4's frames are not counted\n");
  }
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

static int same_file(const char *a, const char *b) {
  size_t na = 0, nb = 0;
  char *x = tt_read_file(a, &na), *y = tt_read_file(b, &nb);
  int same = x != NULL && y != NULL && na == nb && memcmp(x, y, na) == 0;
  free(x);
  free(y);
  return same;
}

static void the_same_scene_and_options_give_the_same_png_bytes(void **state) {
  (void)state;
  char *a = tt_tmpdir(), *b = tt_tmpdir();
  tt_output o;
  render_into(a, "--no-mp4", NULL, &o);
  tt_output_free(&o);
  render_into(b, "--no-mp4", NULL, &o);
  tt_output_free(&o);
  char name[64];
  for (int i = 0; i <= 10; i++) {
    snprintf(name, sizeof name, "frame_%06d.png", i);
    char pa[600];
    snprintf(pa, sizeof pa, "%s", tt_path(a, name));
    if (!same_file(pa, tt_path(b, name))) fail_msg("%s differs between two runs", name);
  }
  /* The frames are of the show, not one picture eleven times (the first
   * and the last both show the closed curtain of a one-second show). */
  assert_false(same_file(tt_path(a, "frame_000000.png"), tt_path(a, "frame_000005.png")));
  tt_rmdir(a);
  tt_rmdir(b);
  free(a);
  free(b);
}

/* --every 3 keeps frames 0, 3, 6, 9; --frame 0.45 draws the frame at
 * 0.5 s alone, the same picture as the sixth of the whole run (the
 * curtain as far open in both: it follows show time and the end). */
static void every_and_frame_choose_which_frames_are_written(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), *one = tt_tmpdir();
  tt_output o;
  render_into(dir, "--every", "3", &o);
  assert_int_equal(at_count_files(dir, "frame_"), 4);
  tt_output_free(&o);
  render_into(dir, "--no-mp4", NULL, &o);
  tt_output_free(&o);
  char png[600];
  snprintf(png, sizeof png, "%s", tt_path(one, "half.png"));
  render_into(png, "--frame", "0.45", &o);
  assert_non_null(strstr(o.out, "frame: t 0.500 s"));
  assert_true(same_file(png, tt_path(dir, "frame_000005.png")));
  tt_output_free(&o);
  tt_rmdir(dir);
  tt_rmdir(one);
  free(dir);
  free(one);
}

/* The bird at its start, 320 x 180, into png; --spheres when asked. */
static void bird_into(const char *png, bool spheres) {
  char *argv[] = { marionette,
                   "render",
                   MR_SOURCE_DIR "/host/scenes/bird.yaml",
                   "--backend",
                   MR_APP_TEST_BACKEND,
                   "-o",
                   (char *)png,
                   "--frame",
                   "3",
                   "--size",
                   "640x360",
                   "-q",
                   spheres ? "--spheres" : NULL,
                   NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  tt_output_free(&o);
}

/* Pixels that differ by more than a little between two pictures. */
static int pixels_apart(const char *a, const char *b) {
  int wa = 0, ha = 0, wb = 0, hb = 0;
  uint8_t *pa = at_png_rgb(a, &wa, &ha), *pb = at_png_rgb(b, &wb, &hb);
  assert_true(pa != NULL && pb != NULL && wa == wb && ha == hb);
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

/* The bird's collision spheres are not drawn unless asked for: with
 * --spheres its body, wings and tail wear pale balls, a few hundred
 * pixels at this size, and nothing else in the picture moves. At 3 s,
 * when the curtain that hides the show's first moments is open. */
static void collision_spheres_are_drawn_only_with_the_spheres_option(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  char plain[600], again[600], balls[600];
  snprintf(plain, sizeof plain, "%s", tt_path(dir, "plain.png"));
  snprintf(again, sizeof again, "%s", tt_path(dir, "again.png"));
  snprintf(balls, sizeof balls, "%s", tt_path(dir, "spheres.png"));
  bird_into(plain, false);
  bird_into(again, false);
  bird_into(balls, true);
  assert_int_equal(pixels_apart(plain, again), 0);
  int shown = pixels_apart(plain, balls);
  print_message("%d pixels show the spheres\n", shown);
  assert_true(shown > 150 && shown < 640 * 360 / 8);
  tt_rmdir(dir);
  free(dir);
}

/* Without ffmpeg on PATH: frames and the sheet, no MP4, and a note. */
static void without_ffmpeg_there_is_a_note_and_no_video(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  char *path = getenv("PATH") != NULL ? strdup(getenv("PATH")) : NULL;
  setenv("PATH", "/nonexistent", 1);
  tt_output o;
  char *argv[] = { marionette, "render", "--backend", MR_APP_TEST_BACKEND,
                   PUPPET,     "-o",     dir,         "--time",
                   "0.2",      "--size", "64x48",     NULL };
  int rc = tt_capture(argv, &o);
  if (path != NULL) setenv("PATH", path, 1);
  free(path);
  assert_int_equal(rc, 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_non_null(strstr(o.err, "marionette render: no MP4: ffmpeg is not installed"));
  assert_non_null(strstr(o.out, "mp4: none (ffmpeg is not installed"));
  assert_int_equal(at_count_files(dir, "show.mp4"), 0);
  assert_int_equal(at_count_files(dir, "sheet.png"), 1);
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

/* render SCENE with options a b: status 2 and one line, holding said. */
static void expect_usage_of(const char *scene, const char *a, const char *b, const char *said) {
  /* The test's backend first: a bad --backend after it is the one read. */
  char *argv[] = { marionette,          "render",  (char *)scene, "--backend",
                   MR_APP_TEST_BACKEND, (char *)a, (char *)b,     NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  assert_int_equal(o.status, 2);
  assert_int_equal(at_lines(o.err), 1);
  assert_non_null(strstr(o.err, "marionette render: "));
  if (strstr(o.err, said) == NULL) fail_msg("'%s' does not say '%s'", o.err, said);
  tt_output_free(&o);
}

static void expect_usage(const char *a, const char *b) {
  expect_usage_of(PUPPET, a, b, "");
}

static void bad_usage_is_one_line_and_status_2(void **state) {
  (void)state;
  expect_usage("--bogus", NULL);
  expect_usage("--size", "12x8");
  expect_usage("--fps", "0");
  expect_usage("--backend", "window"); /* render is headless */
  expect_usage("--camera", "nowhere");
  expect_usage_of(PUPPET, "--size", "640", "got '640'");
  /* A scene's cameras are named, each once, when --camera names none. */
  expect_usage_of(MR_SOURCE_DIR "/host/scenes/bird.yaml", "--camera", "nowhere",
                  "expected --camera one of the scene's cameras (front, above), got 'nowhere'");
  /* A path too long for the names made under it is refused whole, never
   * cut short and written somewhere else. */
  char longpath[460];
  memset(longpath, 'x', sizeof longpath - 1);
  longpath[0] = '/';
  longpath[sizeof longpath - 1] = '\0';
  expect_usage("-o", longpath);
}

/* The loader only resolves a model's path; the renderer finds it missing
 * and says where the scene asked for it. */
static void a_missing_model_names_its_place_and_path_with_status_1(void **state) {
  (void)state;
  const char text[] = "format: 1\n"
                      "name: missing model\n"
                      "physics:\n"
                      "  effects: [gravity]\n"
                      "  particles:\n"
                      "    - {name: a, position: [0, 1, 0], mass: 1}\n"
                      "models:\n"
                      "  - name: head\n"
                      "    file: models/not_there.obj\n"
                      "    particle: a\n";
  const char *path = tt_tmp_file("app_missing_model.yaml", text, sizeof text - 1);
  char *dir = tt_tmpdir();
  char *argv[] = { marionette, "render", "--backend", MR_APP_TEST_BACKEND, (char *)path, "-o", dir,
                   "--time",   "0.2",    NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  assert_int_equal(o.status, 1);
  assert_int_equal(at_lines(o.err), 1);
  char want[700];
  snprintf(want, sizeof want, "%s:8:5: model 'head': ", path);
  if (strstr(o.err, want) == NULL) fail_msg("expected '%s' in: %s", want, o.err);
  assert_non_null(strstr(o.err, "models/not_there.obj"));
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s MARIONETTE\n", argv[0]);
    return 2;
  }
  marionette = argv[1];
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(frames_of_the_size_asked_a_sheet_and_a_video_are_written),
    cmocka_unit_test(the_same_scene_and_options_give_the_same_png_bytes),
    cmocka_unit_test(every_and_frame_choose_which_frames_are_written),
    cmocka_unit_test(without_ffmpeg_there_is_a_note_and_no_video),
    cmocka_unit_test(collision_spheres_are_drawn_only_with_the_spheres_option),
    cmocka_unit_test(bad_usage_is_one_line_and_status_2),
    cmocka_unit_test(a_missing_model_names_its_place_and_path_with_status_1),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
