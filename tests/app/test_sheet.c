/* The contact sheet's choice of frames (host/app/sheet.c): whatever the
 * number of frames and however unevenly show time falls on them (renders
 * skipped under load), the cells begin with the first frame offered, end
 * with the last, and step through show time evenly in between; the
 * sheet written is a PNG of those cells; and each cell's label reads on
 * any picture. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sheet.h"

enum { W = 32, H = 18, CELLS = 24 };

/* A sheet offered count frames, frame i at time time_of(i). */
static mr_sheet *offered(int count, double (*time_of)(int)) {
  mr_sheet *sh = mr_sheet_create(W, H, CELLS);
  assert_non_null(sh);
  static uint8_t rgb[W * H * 3];
  for (int i = 0; i < count; i++) {
    memset(rgb, i & 0xff, sizeof rgb);
    mr_sheet_offer(sh, rgb, time_of(i));
  }
  return sh;
}

/* The cells' times: the first and last frame's, in order, and no step
 * wider than three even ones and the widest gap between frames (the sheet
 * holds frames up to about two even steps apart, and where the frames
 * themselves are sparse it can do no better than they). */
static void check_cells(mr_sheet *sh, int count, double (*time_of)(int), double widest_gap) {
  int picks[CELLS];
  int n = mr_sheet_pick(sh, picks, CELLS);
  int want = count < CELLS ? count : CELLS;
  assert_int_equal(n, want);
  assert_int_equal(mr_sheet_cells(sh), want);
  double t0 = time_of(0), t1 = time_of(count - 1);
  if (n > 0) {
    assert_true(mr_sheet_time(sh, picks[0]) == t0);
    assert_true(mr_sheet_time(sh, picks[n - 1]) == t1);
  }
  double even = n > 1 ? (t1 - t0) / (n - 1) : 0;
  for (int k = 1; k < n; k++) {
    double step = mr_sheet_time(sh, picks[k]) - mr_sheet_time(sh, picks[k - 1]);
    assert_true(step > 0);
    if (!(step <= 3 * even + widest_gap))
      fail_msg("%d frames: cell %d is %.3f s after the one before; an even step is %.3f s", count,
               k, step, even);
  }
}

static double at_60_fps(int i) {
  return i / 60.0;
}

/* Every count from 1 to 1000 frames at 60 fps: first, last, even. */
static void the_sheet_shows_the_first_and_the_last_frame_of_any_show(void **state) {
  (void)state;
  for (int count = 1; count <= 1000; count++) {
    mr_sheet *sh = offered(count, at_60_fps);
    check_cells(sh, count, at_60_fps, 1 / 60.0);
    mr_sheet_destroy(sh);
  }
}

/* A show drawn fast for its first ten seconds (60 fps) and slowly after
 * (4 fps, renders skipped): the cells still step evenly through show
 * time, not through the frames, so the fast part does not fill the
 * sheet. */
static double slow_after_ten_seconds(int i) {
  return i < 600 ? i / 60.0 : 10.0 + (i - 600) / 4.0;
}

static void the_sheet_steps_evenly_through_show_time_when_renders_were_skipped(void **state) {
  (void)state;
  for (int count = 601; count <= 700; count += 3) {
    mr_sheet *sh = offered(count, slow_after_ten_seconds);
    check_cells(sh, count, slow_after_ten_seconds, 0.25);
    mr_sheet_destroy(sh);
  }
}

/* The sheet written: a PNG of 6 columns of the cells. */
static void the_sheet_is_written_as_a_png(void **state) {
  (void)state;
  mr_sheet *sh = offered(100, at_60_fps);
  char path[] = "/tmp/mr-sheet-XXXXXX";
  int fd = mkstemp(path);
  assert_true(fd >= 0);
  assert_int_equal(mr_sheet_write(sh, path), 0);
  uint8_t head[24];
  FILE *f = fopen(path, "rb");
  assert_non_null(f);
  assert_int_equal(fread(head, 1, sizeof head, f), sizeof head);
  fclose(f);
  remove(path);
  assert_memory_equal(head, "\x89PNG", 4);
  uint32_t w = (uint32_t)head[16] << 24 | head[17] << 16 | head[18] << 8 | head[19];
  uint32_t h = (uint32_t)head[20] << 24 | head[21] << 16 | head[22] << 8 | head[23];
  assert_int_equal(w, 6 * (W + 4) + 4);
  assert_int_equal(h, 4 * (H + 4) + 4);
  mr_sheet_destroy(sh);
}

/* A cell's label: a box a third as bright as the picture under it, a
 * pixel wider on each side than its characters, and the characters in
 * white over it; nothing outside the box changes. */
static void a_label_darkens_its_box_to_a_third_and_writes_white_over_it(void **state) {
  (void)state;
  enum { LW = 120, LH = 40, X = 10, Y = 8 };
  static uint8_t rgb[LW * LH * 3];
  const uint8_t under[3] = { 90, 120, 150 };
  for (int i = 0; i < LW * LH; i++) memcpy(&rgb[3 * i], under, 3);
  mr_sheet_text(rgb, LW, LH, X, Y, 14, "1.25 s");
  /* The box's top row holds no glyph: it shows where the box ends. */
  int end = X;
  while (end < LW && rgb[(Y * LW + end) * 3 + 2] != under[2]) end++;
  assert_true(end > X + 6 * 4); /* six characters, each a few pixels wide */
  for (int x = X; x < end; x++) {
    const uint8_t *p = &rgb[(Y * LW + x) * 3];
    if (p[0] != 30 || p[1] != 40 || p[2] != 50)
      fail_msg("box pixel (%d, %d): %d %d %d, not 30 40 50", x, Y, p[0], p[1], p[2]);
  }
  const int outside[][2] = { { X - 1, Y }, { end, Y }, { X, Y - 1 }, { X, Y + 18 } };
  for (size_t k = 0; k < sizeof outside / sizeof outside[0]; k++) {
    const uint8_t *p = &rgb[(outside[k][1] * LW + outside[k][0]) * 3];
    if (memcmp(p, under, 3) != 0)
      fail_msg("pixel (%d, %d) outside the box changed: %d %d %d", outside[k][0], outside[k][1],
               p[0], p[1], p[2]);
  }
  int brightest = 0;
  for (int y = Y; y < Y + 18; y++)
    for (int x = X; x < end; x++)
      if (rgb[(y * LW + x) * 3] > brightest) brightest = rgb[(y * LW + x) * 3];
  assert_true(brightest > 200);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(the_sheet_shows_the_first_and_the_last_frame_of_any_show),
    cmocka_unit_test(the_sheet_steps_evenly_through_show_time_when_renders_were_skipped),
    cmocka_unit_test(the_sheet_is_written_as_a_png),
    cmocka_unit_test(a_label_darkens_its_box_to_a_third_and_writes_white_over_it),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
