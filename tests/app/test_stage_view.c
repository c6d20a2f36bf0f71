/* The stage view's follow camera (`camera: follow`, host/app/stage_view.c)
 * beside a real headless renderer: the orbit's target keeps the offset it
 * had from the middle of the points' box and chases that middle when the
 * puppet moves, on every axis, without jumping there; a scene without
 * follow keeps its target. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "mr_scene_world.h"
#include "mr_stage.h"
#include "stage_view.h"

#define STICK MR_SOURCE_DIR "/host/scenes/stick.yaml"

#ifndef MR_APP_TEST_BACKEND
#define MR_APP_TEST_BACKEND "auto"
#endif

/* Where the puppet moves to: along all three axes at once, by different
 * amounts, so that an axis the camera leaves behind shows. */
static const double MOVE[3] = { 0.4, -0.25, 0.3 };

/* stick.yaml with follow as asked, on a 64x48 headless renderer; its
 * start positions into *xyz (n points). */
static void open_view(mr_stageview *sv, mr_scene *sc, bool follow, double **xyz, size_t *n) {
  mr_scene_error err;
  if (mr_scene_load(STICK, sc, &err) != MR_SCENE_OK) fail_msg("%s", err.text);
  sc->stage.follow = follow;
  mr_render_def rd = mr_default_render_def();
  assert_int_equal(mr_render_backend_parse(MR_APP_TEST_BACKEND, &rd.backend), 0);
  rd.headless = true;
  rd.width = 64;
  rd.height = 48;
  rd.samples = 1;
  char msg[600];
  if (mr_stageview_open(sv, sc, &rd, NULL, msg, sizeof msg) != 0) fail_msg("%s", msg);
  *xyz = mr_scene_start_positions(sc, n, &err);
  if (*xyz == NULL) fail_msg("%s", err.text);
  assert_int_equal(*n, sv->n_points);
}

/* The points at t = 0 where they start, then moved by MOVE and held there,
 * tracked every 1/60 s up to `until`; the orbit's target before the move
 * into before[], after 0.1 s into early[], at the end into end[]. */
static void move_and_track(mr_stageview *sv, double *xyz, size_t n, double until, double before[3],
                           double early[3], double end[3]) {
  double start[3];
  memcpy(start, sv->orbit.target, sizeof start);
  mr_stageview_track(sv, 0.0, xyz, n);
  memcpy(before, sv->orbit.target, 3 * sizeof *before);
  /* The first sight of the puppet moves nothing: the camera keeps its
   * place and takes its offset from the middle there. */
  for (int c = 0; c < 3; c++)
    if (fabs(before[c] - start[c]) > 1e-12)
      fail_msg("axis %d: the first track moved the target from %.6g to %.6g", c, start[c],
               before[c]);
  for (size_t i = 0; i < n; i++)
    for (int c = 0; c < 3; c++) xyz[3 * i + c] += MOVE[c];
  for (int k = 1; k <= (int)lround(until * 60.0); k++) {
    mr_stageview_track(sv, k / 60.0, xyz, n);
    if (k == 6) memcpy(early, sv->orbit.target, 3 * sizeof *early);
  }
  memcpy(end, sv->orbit.target, 3 * sizeof *end);
}

static void the_follow_camera_chases_the_puppet_on_every_axis(void **state) {
  (void)state;
  mr_scene sc;
  mr_stageview sv;
  double *xyz, before[3], early[3], end[3];
  size_t n;
  open_view(&sv, &sc, true, &xyz, &n);
  move_and_track(&sv, xyz, n, 4.0, before, early, end);
  for (int c = 0; c < 3; c++) {
    const double moved_early = early[c] - before[c], moved = end[c] - before[c];
    /* Under way after 0.1 s, as a critically damped follower of time
     * constant 0.3 s is from rest: 1 − (1 + x) e^−x of the way, x = 1/3
     * (4.5 %), give or take a tenth of that. */
    const double x = 0.1 / MR_FOLLOW_TIME, share = 1.0 - (1.0 + x) * exp(-x);
    if (!(fabs(moved_early / MOVE[c] - share) < 0.1 * share))
      fail_msg("axis %d: after 0.1 s the target moved %.4g of %.4g m", c, moved_early, MOVE[c]);
    /* There after 4 s, the start's offset from the middle kept. */
    if (fabs(moved - MOVE[c]) > 1e-3)
      fail_msg("axis %d: after 4 s the target moved %.6g m, the puppet %.6g m", c, moved, MOVE[c]);
  }
  free(xyz);
  mr_stageview_close(&sv);
  mr_scene_free(&sc);
}

static void without_follow_the_target_stays(void **state) {
  (void)state;
  mr_scene sc;
  mr_stageview sv;
  double *xyz, before[3], early[3], end[3];
  size_t n;
  open_view(&sv, &sc, false, &xyz, &n);
  move_and_track(&sv, xyz, n, 1.0, before, early, end);
  for (int c = 0; c < 3; c++) assert_true(end[c] == before[c]);
  free(xyz);
  mr_stageview_close(&sv);
  mr_scene_free(&sc);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(the_follow_camera_chases_the_puppet_on_every_axis),
    cmocka_unit_test(without_follow_the_target_stays),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
