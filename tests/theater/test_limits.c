/* The control side's rate limits (control.max_speed, max_turn_rate): the
 * frame follows its input at most that fast, although its path between
 * targets is curved (its velocity is continuous, so it can bulge past the
 * chord's rate inside a segment). The theater draws the goal back until
 * the physics' bound on the path keeps the limits (frame.c). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "mr_scene.h"
#include "mr_scene_world.h"
#include "theater_internal.h"

/* A frame limited to 2 m/s and 90°/s whose input jumps 1 m sideways and
 * turns 120° within 10 ms at t = 0.2 s, and back at t = 1 s: the frame is driven
 * at 60 targets a second as the theater does, and its speed and turn
 * rate, sampled 20 times inside every segment, never pass the limits,
 * while it does reach them (it is not simply slowed down). */
static void frame_keeps_its_speed_and_turn_limits_on_a_curved_path(void **state) {
  (void)state;
  static const char text[] = "format: 1\n"
                             "physics:\n"
                             "  effects: [control]\n"
                             "  particles: [{name: w, position: [0, 0, 0], mass: 1}]\n"
                             "  control:\n"
                             "    max_speed: 2\n"
                             "    max_turn_rate: 90\n"
                             "    points: [{name: p, offset: [0.3, 0, 0]}]\n"
                             "    pose: {position: [0, 1, 0]}\n"
                             "    track:\n"
                             "      interpolation: linear\n"
                             "      keyframes:\n"
                             "        - {t: 0.0, position: [0, 1, 0]}\n"
                             "        - {t: 0.19, position: [0, 1, 0]}\n"
                             "        - {t: 0.2, position: [1, 1, 0], rotation: [0, 120, 0]}\n"
                             "        - {t: 0.99, position: [1, 1, 0], rotation: [0, 120, 0]}\n"
                             "        - {t: 1.0, position: [0, 1, 0]}\n";
  mr_scene sc;
  mr_scene_error err;
  mr_scene_world sw;
  assert_int_equal(mr_scene_load_text("limits.yaml", text, sizeof text - 1, &sc, &err),
                   MR_SCENE_OK);
  assert_int_equal(mr_scene_build(&sc, &sw, &err), MR_SCENE_OK);
  double top = 0.0, top_turn = 0.0;
  for (int f = 1; f <= 120; f++) {
    double t = f / 60.0;
    mr_pose goal;
    mr_scene_frame_pose_at(&sc, 0, t, &goal);
    mr_theater_head_frame(&sc, &sw, 0, goal, t);
    for (int i = 1; i <= 20; i++) {
      assert_true(mr_world_step_to(sw.world, (f - 1 + i / 20.0) / 60.0, NULL) >= 0);
      double v[3], w[3];
      assert_int_equal(mr_world_frame_rates(sw.world, sw.frames[0], v, w), MR_OK);
      top = fmax(top, sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
      top_turn = fmax(top_turn, sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]));
    }
  }
  print_message("speed %.6f m/s (limit 2), turn rate %.6f rad/s (limit %.6f)\n", top, top_turn,
                3.14159265358979323846 / 2);
  assert_true(top <= 2.0 * (1 + 1e-12) && top > 1.9);
  assert_true(top_turn <= 3.14159265358979323846 / 2 * (1 + 1e-12) && top_turn > 1.4);
  mr_scene_world_free(&sw);
  mr_scene_free(&sc);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(frame_keeps_its_speed_and_turn_limits_on_a_curved_path),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
