/* The benchmark's windows along a chaotic track (tools/marionette-bench/
 * windows.c), on a small pendulum whose bar swings at 2 Hz: they start
 * where the bar is at rest, the reference's run through each window ends
 * where the next window starts from, and a setting's error is the median
 * of its windows' RMS, computed here again from runs of its own. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

static const char SWING[] = "format: 1\n"
                            "physics:\n"
                            "  effects: [gravity, strings, control]\n"
                            "  particles: [{name: bob, position: [0, 0.5, 0], mass: 0.2}]\n"
                            "  control:\n"
                            "    pose: {position: [0, 1, 0]}\n"
                            "    points: [{name: bar, offset: [0, 0, 0]}]\n"
                            "    track:\n"
                            "      oscillate: {amplitude: [0.1, 0, 0], frequency: 2, ramp: 0.5}\n"
                            "  strings: [{from: bar, to: bob}]\n";

static int ascending(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static void windows_start_at_rest_join_up_and_take_the_median(void **state) {
  (void)state;
  mr_scene sc;
  mr_scene_error err;
  assert_int_equal(mr_scene_load_text("swing.yaml", SWING, sizeof SWING - 1, &sc, &err),
                   MR_SCENE_OK);
  bench_windows w;
  /* Turning points every 0.25 s from 0.625 s (after the 0.5 s ramp),
   * every second one, up to 4 − 0.5 s. */
  assert_int_equal(bench_windows_open(&sc, 0, 4.0, 0.5, 0.5, &w), 6);
  for (int k = 0; k < w.n; k++) {
    double v[3], om[3];
    mr_scene_frame_rates_at(&sc, 0, w.start[k], v, om);
    assert_true(fabs(w.start[k] - (0.625 + 0.5 * k)) < 1e-12);
    assert_true(fabs(v[0]) < 1e-6);
  }
  /* Each window is 0.5 s long and the next starts 0.5 s later: the
   * reference through window k ends on the state window k + 1 starts from. */
  double join = 0.0;
  for (int k = 0; k + 1 < w.n; k++) {
    const double *end = &w.ref[k].ee[3 * (w.ref[k].ee_count - 1)];
    for (int c = 0; c < 3; c++) join = fmax(join, fabs(end[c] - w.states[k + 1][c]));
  }
  print_message("windows join within %.3g m; resolution %.3g m\n", join, w.resolution);
  assert_true(join < 1e-9);
  assert_true(w.resolution > 0 && w.resolution < 1e-3);
  /* RK4 at a fixed 10 ms: the median of its windows' RMS, measured here. */
  mr_scene fixed = sc;
  fixed.world.integrator = MR_INTEGRATOR_RK4;
  fixed.world.dt_initial = fixed.world.dt_min = fixed.world.dt_max = fixed.world.dt_floor = 0.01;
  double ee_max, ee_med, rms[16];
  assert_int_equal(bench_windows_error(&fixed, 0, 0.5, &w, &ee_max, &ee_med), 0);
  for (int k = 0; k < w.n; k++) {
    const double save = fixed.frames[0].track.start;
    fixed.frames[0].track.start -= w.start[k];
    bench_run run;
    assert_int_equal(bench_run_scene_from(&fixed, 0.5, 0, 0.5, w.states[k], NULL, &run), 0);
    fixed.frames[0].track.start = save;
    double big;
    bench_ee_error(&run, &w.ref[k], &big, &rms[k]);
    assert_true(big <= ee_max);
    bench_run_free(&run);
  }
  qsort(rms, (size_t)w.n, sizeof *rms, ascending);
  print_message("median %.6g m (windows: %.3g .. %.3g), largest %.3g m\n", ee_med, rms[0],
                rms[w.n - 1], ee_max);
  assert_true(rms[0] < rms[w.n - 1]);
  assert_true(ee_med == rms[w.n / 2]);
  bench_windows_free(&w);
  assert_int_equal(w.n, 0);
  mr_scene_free(&sc);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(windows_start_at_rest_join_up_and_take_the_median),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
