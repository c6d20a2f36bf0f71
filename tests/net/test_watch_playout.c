/* marionette watch's playout buffer (host/app/watch_buffer.h): what a
 * watcher draws at a show time from the frames it received. No broker. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "watch_buffer.h"

/* Two points a frame: frame k at show time k / 60 holds (k, 2k, -k) and
 * (10 k, 0, 0.5 k). */
static void frame_of(double k, double *xyz) {
  const double p[6] = { k, 2 * k, -k, 10 * k, 0, 0.5 * k };
  memcpy(xyz, p, sizeof p);
}

static void push_frame(mr_watch_buffer *b, double k) {
  double xyz[6];
  frame_of(k, xyz);
  assert_int_equal(mr_watch_buffer_push(b, k / 60.0, xyz, 2), 0);
}

static void points_equal(const double *got, double k) {
  double want[6];
  frame_of(k, want);
  for (int j = 0; j < 6; j++) assert_float_equal(got[j], want[j], 1e-9);
}

static void between_two_frames_the_points_are_drawn_linearly_at_the_time_s_weight(void **state) {
  (void)state;
  mr_watch_buffer b;
  memset(&b, 0, sizeof b);
  double out[6];
  assert_int_equal(mr_watch_buffer_at(&b, 0.0, out), -1);
  for (int k = 0; k < 5; k++) push_frame(&b, k);
  /* A quarter of the way from frame 2 to frame 3, and 0.9 of the way
   * from 0 to 1: the frames are linear in k, so the points are frame
   * 2.25's and 0.9's. */
  assert_int_equal(mr_watch_buffer_at(&b, 2.25 / 60.0, out), 0);
  points_equal(out, 2.25);
  assert_int_equal(mr_watch_buffer_at(&b, 0.9 / 60.0, out), 0);
  points_equal(out, 0.9);
  /* On a frame's own time: that frame. */
  assert_int_equal(mr_watch_buffer_at(&b, 3.0 / 60.0, out), 0);
  points_equal(out, 3.0);
  /* Before the oldest kept: the oldest, drawn (not a hold). */
  assert_int_equal(mr_watch_buffer_at(&b, -1.0, out), 0);
  points_equal(out, 0.0);
  mr_watch_buffer_free(&b);
}

static void past_the_newest_frame_its_pose_holds_and_the_hold_is_reported(void **state) {
  (void)state;
  mr_watch_buffer b;
  memset(&b, 0, sizeof b);
  for (int k = 0; k < 4; k++) push_frame(&b, k);
  double out[6];
  /* Frames 4 and on lost: a second later frame 3 still holds. */
  assert_int_equal(mr_watch_buffer_at(&b, 3.5 / 60.0, out), 1);
  points_equal(out, 3.0);
  assert_int_equal(mr_watch_buffer_at(&b, 1.0 + 3.0 / 60.0, out), 1);
  points_equal(out, 3.0);
  /* The next frame after the gap: drawn between again. */
  push_frame(&b, 10);
  assert_int_equal(mr_watch_buffer_at(&b, 6.5 / 60.0, out), 0);
  points_equal(out, 6.5);
  mr_watch_buffer_free(&b);
}

static void a_frame_no_newer_than_the_newest_is_refused_and_changes_nothing(void **state) {
  (void)state;
  mr_watch_buffer b;
  memset(&b, 0, sizeof b);
  for (int k = 0; k < 3; k++) push_frame(&b, k);
  double late[6];
  frame_of(100, late);
  assert_int_equal(mr_watch_buffer_push(&b, 1.0 / 60.0, late, 2), -1);
  assert_int_equal(mr_watch_buffer_push(&b, 2.0 / 60.0, late, 2), -1);
  assert_float_equal(mr_watch_buffer_newest(&b), 2.0 / 60.0, 1e-12);
  double out[6];
  assert_int_equal(mr_watch_buffer_at(&b, 1.5 / 60.0, out), 0);
  points_equal(out, 1.5);
  mr_watch_buffer_free(&b);
}

static void the_oldest_frames_make_room_for_new_ones_past_the_buffer_s_size(void **state) {
  (void)state;
  mr_watch_buffer b;
  memset(&b, 0, sizeof b);
  for (int k = 0; k < MR_WATCH_KEEP + 5; k++) push_frame(&b, k);
  assert_int_equal(b.count, MR_WATCH_KEEP);
  double out[6];
  /* Frame 4 is gone: before frame 5, frame 5 is drawn. */
  assert_int_equal(mr_watch_buffer_at(&b, 4.5 / 60.0, out), 0);
  points_equal(out, 5.0);
  double k = MR_WATCH_KEEP + 3.75;
  assert_int_equal(mr_watch_buffer_at(&b, k / 60.0, out), 0);
  points_equal(out, k);
  mr_watch_buffer_free(&b);
}

static void a_frame_of_another_size_starts_the_buffer_again(void **state) {
  (void)state;
  mr_watch_buffer b;
  memset(&b, 0, sizeof b);
  for (int k = 0; k < 6; k++) push_frame(&b, k);
  /* Another scene of three points, its show time from the start (older
   * than the newest frame: kept all the same, as another show's). */
  const double three[9] = { 1, 1, 1, 2, 2, 2, 3, 3, 3 };
  assert_int_equal(mr_watch_buffer_push(&b, 0.01, three, 3), 0);
  assert_int_equal(b.count, 1);
  assert_int_equal((int)b.n, 3);
  double out[9];
  assert_int_equal(mr_watch_buffer_at(&b, 0.5, out), 1);
  assert_memory_equal(out, three, sizeof three);
  const double next[9] = { 3, 3, 3, 4, 4, 4, 5, 5, 5 };
  assert_int_equal(mr_watch_buffer_push(&b, 0.03, next, 3), 0);
  assert_int_equal(mr_watch_buffer_at(&b, 0.015, out), 0);
  for (int j = 0; j < 9; j++) assert_float_equal(out[j], three[j] + 0.25 * 2, 1e-9);
  mr_watch_buffer_free(&b);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(between_two_frames_the_points_are_drawn_linearly_at_the_time_s_weight),
    cmocka_unit_test(past_the_newest_frame_its_pose_holds_and_the_hold_is_reported),
    cmocka_unit_test(a_frame_no_newer_than_the_newest_is_refused_and_changes_nothing),
    cmocka_unit_test(the_oldest_frames_make_room_for_new_ones_past_the_buffer_s_size),
    cmocka_unit_test(a_frame_of_another_size_starts_the_buffer_again),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
