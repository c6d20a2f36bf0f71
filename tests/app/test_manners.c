/* `marionette` on the command line: --version on every program, the glove
 * program started by hand, a missing
 * scene is the first thing it hears of, the keyboard's glove records a take
 * that replays as it played, and a show without a stage says that it drew
 * nothing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "proc.h"

/* The backend the stage is drawn with (OSMesa under the sanitizers). */
#ifndef MR_APP_TEST_BACKEND
#define MR_APP_TEST_BACKEND "auto"
#endif

static char *marionette, *stage, *export_program, *glove;

#define STICK MR_SOURCE_DIR "/host/scenes/stick.yaml"

static void run(char *const argv[], tt_output *o) {
  assert_int_equal(tt_capture(argv, o), 0);
}

/* Each program prints its name and the project's version (project() in
 * the top CMakeLists.txt), and exits 0. */
static void every_program_prints_the_projects_version(void **state) {
  (void)state;
  char *programs[] = { marionette, stage, export_program, glove };
  const char *names[] = { "marionette", "marionette-stage", "marionette-export",
                          "marionette-glove" };
  for (int i = 0; i < 4; i++) {
    char *argv[] = { programs[i], "--version", NULL };
    tt_output o;
    run(argv, &o);
    char want[100];
    snprintf(want, sizeof want, "%s %s\n", names[i], MR_PROJECT_VERSION);
    assert_int_equal(o.status, 0);
    assert_string_equal(o.out, want);
    assert_string_equal(o.err, "");
    tt_output_free(&o);
  }
}

/* The glove program is reached through marionette: started by hand with
 * anything but its two commands, it says so in one line (bad usage). */
static void the_glove_program_alone_points_at_marionette(void **state) {
  (void)state;
  char *argv[] = { glove, "sim", NULL };
  tt_output o;
  run(argv, &o);
  assert_int_equal(o.status, 2);
  assert_non_null(strstr(o.err, "marionette list-ports"));
  assert_int_equal(strchr(o.err, '\n') - o.err + 1, (long)strlen(o.err)); /* one line */
  assert_string_equal(o.out, "");
  tt_output_free(&o);
}

/* list-ports takes --wait and --no-probe, refuses a wait past a minute
 * and an option it does not know, each in one line naming it. */
static void list_ports_takes_its_options_and_names_a_bad_one(void **state) {
  (void)state;
  char *good[] = { marionette, "list-ports", "--no-probe", "--wait", "0.5", NULL };
  tt_output o;
  run(good, &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_string_equal(o.err, "");
  tt_output_free(&o);
  static const struct {
    const char *a, *b, *said;
  } bad[] = {
    { "--wait", "99", "expected --wait between 0 and 60 s, got '99'" },
    { "--bogus", "2", "unknown option '--bogus'" },
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    char *argv[] = { marionette, "list-ports", (char *)bad[i].a, (char *)bad[i].b, NULL };
    run(argv, &o);
    assert_int_equal(o.status, 2);
    assert_int_equal(strchr(o.err, '\n') - o.err + 1, (long)strlen(o.err)); /* one line */
    if (strstr(o.err, bad[i].said) == NULL) fail_msg("'%s' does not say '%s'", o.err, bad[i].said);
    tt_output_free(&o);
  }
}

/* Without a glove and without a display, a scene that is not there is
 * named (exit 1), not the missing glove; a scene that is there still
 * hears that it needs a glove (bad usage, 2). */
static void a_missing_scene_is_the_first_error(void **state) {
  (void)state;
  char *missing[] = { marionette, "run", "/nonexistent/scene.yaml", NULL };
  tt_output o;
  run(missing, &o);
  assert_int_equal(o.status, 1);
  assert_non_null(strstr(o.err, "/nonexistent/scene.yaml"));
  assert_null(strstr(o.err, "--glove"));
  assert_int_equal(strchr(o.err, '\n') - o.err + 1, (long)strlen(o.err)); /* one line */
  tt_output_free(&o);
  char *gloveless[] = { marionette, "run", STICK, NULL };
  run(gloveless, &o);
  assert_int_equal(o.status, 2);
  assert_non_null(strstr(o.err, "expected --glove SOURCE or --replay TAKE"));
  tt_output_free(&o);
}

/* Two seconds of the keyboard's glove (right held 0.3 s to 1.3 s),
 * headless, recorded into dir/keys.mrec, each frame's hash into
 * dir/live.txt; the show's summary in o. */
static void record_the_keyboard(const char *dir, tt_output *o) {
  char take[600], hashes[600];
  snprintf(take, sizeof take, "%s", tt_path(dir, "keys.mrec"));
  snprintf(hashes, sizeof hashes, "%s", tt_path(dir, "live.txt"));
  char *argv[] = { marionette,    "run",    "--backend", MR_APP_TEST_BACKEND, STICK, "--keys",
                   "0.3:right/1", "--time", "2",         "--record",          take,  "--hashes",
                   hashes,        "--size", "160x96",    "--samples",         "1",   "--headless",
                   "-q",          NULL };
  run(argv, o);
  if (o->status != 0) fail_msg("status %d: %s", o->status, o->err);
}

/* A take of the keyboard's glove replays every frame bit for bit, with
 * as many samples as the glove sent; a second --record for the one
 * keyboard glove is bad usage. */
static void the_keyboards_glove_records_a_take_that_replays(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  tt_output live;
  record_the_keyboard(dir, &live);
  char take[600], hashes[600], sent[64], got[64];
  snprintf(take, sizeof take, "%s", tt_path(dir, "keys.mrec"));
  snprintf(hashes, sizeof hashes, "%s", tt_path(dir, "replay.txt"));
  char *argv[] = { marionette, "run",      STICK,  "--replay", take, "--time",
                   "2",        "--hashes", hashes, "-q",       NULL };
  tt_output o;
  run(argv, &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_int_equal(tt_field(live.out, "glove samples", sent, sizeof sent), 0);
  assert_int_equal(tt_field(o.out, "glove samples", got, sizeof got), 0);
  assert_true(atoi(sent) >= 20); /* 100 Hz while a key is held, 5 Hz otherwise */
  assert_string_equal(got, sent);
  char *a = tt_read_file(tt_path(dir, "live.txt"), NULL), *b = tt_read_file(hashes, NULL);
  assert_non_null(a);
  assert_non_null(b);
  assert_true(strlen(a) > 100 * 24); /* 121 frames of "t hash" */
  assert_string_equal(a, b);
  free(a);
  free(b);
  tt_output_free(&o);
  tt_output_free(&live);
  char *twice[] = { marionette, "run",      STICK, "--keys", "0.1:r", "--record",
                    take,       "--record", take,  "-q",     NULL };
  run(twice, &o);
  assert_int_equal(o.status, 2);
  assert_non_null(strstr(o.err, "at most one --record for the keyboard's glove"));
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

/* With no stage (no display, no --headless, no -o, no --keys) the summary
 * says nothing was drawn, beside the frames the scheduler showed; with a
 * stage it says no such thing, and a --sheet alone is one. */
static void a_show_without_a_stage_says_it_drew_nothing(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  tt_output live;
  record_the_keyboard(dir, &live);
  assert_null(strstr(live.out, "nothing drawn"));
  tt_output_free(&live);
  char *argv[] = { marionette, "run", STICK, "--replay", (char *)tt_path(dir, "keys.mrec"),
                   "--time",   "2",   "-q",  NULL };
  tt_output o;
  run(argv, &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  char drawn[100], shown[64];
  assert_int_equal(tt_field(o.out, "frames drawn", drawn, sizeof drawn), 0);
  assert_string_equal(drawn, "0 (headless without -o: nothing drawn)");
  assert_int_equal(tt_field(o.out, "frames shown", shown, sizeof shown), 0);
  assert_true(atoi(shown) > 100);
  tt_output_free(&o);
  /* A file to write is a stage, -o or not: the sheet alone is drawn. */
  char sheet[700];
  snprintf(sheet, sizeof sheet, "%s", tt_path(dir, "sheet.png"));
  char *drawing[] = { marionette, "run", STICK,     "--replay", (char *)tt_path(dir, "keys.mrec"),
                      "--time",   "1",   "--sheet", sheet,      "--size",
                      "160x96",   "-q",  NULL };
  run(drawing, &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  assert_non_null(strstr(o.out, "frames drawn"));
  assert_null(strstr(o.out, "nothing drawn"));
  assert_non_null(strstr(o.out, "sheet: "));
  assert_int_equal(access(sheet, F_OK), 0);
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  if (argc < 5) {
    fprintf(stderr, "usage: %s MARIONETTE STAGE EXPORT GLOVE\n", argv[0]);
    return 2;
  }
  marionette = argv[1];
  stage = argv[2];
  export_program = argv[3];
  glove = argv[4];
  /* No display: the glove's absence is an error, and nothing opens a window. */
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(every_program_prints_the_projects_version),
    cmocka_unit_test(the_glove_program_alone_points_at_marionette),
    cmocka_unit_test(list_ports_takes_its_options_and_names_a_bad_one),
    cmocka_unit_test(a_missing_scene_is_the_first_error),
    cmocka_unit_test(the_keyboards_glove_records_a_take_that_replays),
    cmocka_unit_test(a_show_without_a_stage_says_it_drew_nothing),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
