/* Where drawn frames go (host/app/frames_out.c): PNGs under the folder
 * only, one every `every` frames and numbered by that count; without a
 * folder, only the files named (here the sheet), and no PNG anywhere. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app_test.h"
#include "frames_out.h"
#include "proc.h"

enum { W = 16, H = 8 };

/* count frames of W x H into def's outputs, frame i grey at level 10 i and
 * at show time i / 30 s; the summary. */
static mr_frames_out_summary hand_in(const mr_frames_out_def *def, int count) {
  mr_frames_out *fo = NULL;
  char msg[600] = "";
  if (mr_frames_out_open(def, &fo, msg, sizeof msg) != 0) fail_msg("open: %s", msg);
  static uint8_t rgb[W * H * 3];
  for (int i = 0; i < count; i++) {
    memset(rgb, 10 * i, sizeof rgb);
    if (mr_frames_out_add(fo, rgb, i / 30.0, msg, sizeof msg) != 0)
      fail_msg("frame %d: %s", i, msg);
  }
  mr_frames_out_summary s;
  if (mr_frames_out_close(fo, &s, msg, sizeof msg) != 0) fail_msg("close: %s", msg);
  return s;
}

static mr_frames_out_def def_of(const char *dir, int every, const char *sheet) {
  mr_frames_out_def d = mr_default_frames_out_def();
  d.dir = dir;
  d.every = every;
  d.sheet = sheet;
  d.fps = 30;
  d.width = W;
  d.height = H;
  return d;
}

/* Every third of seven frames: frames 0, 3 and 6, as 0, 1 and 2. */
static void a_png_every_third_frame_is_numbered_by_that_count(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  mr_frames_out_def d = def_of(dir, 3, NULL);
  mr_frames_out_summary s = hand_in(&d, 7);
  assert_int_equal(s.frames, 7);
  assert_int_equal(s.pngs, 3);
  assert_int_equal(at_count_files(dir, "frame_"), 3);
  for (int k = 0; k < 3; k++) {
    char name[64];
    snprintf(name, sizeof name, "frame_%06d.png", k);
    int w = 0, h = 0;
    uint8_t *rgb = at_png_rgb(tt_path(dir, name), &w, &h);
    assert_non_null(rgb);
    assert_int_equal(w, W);
    assert_int_equal(h, H);
    assert_int_equal(rgb[0], 10 * 3 * k);
    free(rgb);
  }
  tt_rmdir(dir);
  free(dir);
}

/* No folder: the sheet alone, and not one PNG written (the summary says
 * none, and none lands in the working folder or the root). */
static void without_a_folder_only_the_sheet_is_written(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), sheet[700];
  snprintf(sheet, sizeof sheet, "%s", tt_path(dir, "sheet.png"));
  mr_frames_out_def d = def_of(NULL, 1, sheet);
  mr_frames_out_summary s = hand_in(&d, 5);
  assert_int_equal(s.frames, 5);
  assert_int_equal(s.pngs, 0);
  assert_int_equal(s.sheet_cells, 5);
  int w = 0, h = 0;
  assert_int_equal(at_png_size(sheet, &w, &h), 0);
  assert_true(w > W && h > H);
  assert_int_equal(at_count_files(".", "frame_"), 0);
  assert_int_not_equal(access("/frame_000000.png", F_OK), 0);
  tt_rmdir(dir);
  free(dir);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_png_every_third_frame_is_numbered_by_that_count),
    cmocka_unit_test(without_a_folder_only_the_sheet_is_written),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
