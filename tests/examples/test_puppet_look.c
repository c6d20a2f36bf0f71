/* puppet.yaml, the README's first run, reads as a puppet on real pixels
 * (OSMesa): at its start, seen from the audience's seat, its head, torso,
 * pelvis, limbs, hands and shoes are one figure joined up, not beads
 * floating apart, and every particle of it is inside something drawn. */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "mr_render.h"
#include "mr_scene.h"
#include "mr_scene_world.h"

enum { W = 640, H = 360 };

/* The figure's pixels: where the picture differs from the one drawn
 * without it. */
static bool *figure_mask(const uint8_t *rgb, const uint8_t *sky) {
  bool *m = calloc((size_t)W * H, sizeof *m);
  assert_non_null(m);
  for (size_t i = 0; i < (size_t)W * H; i++) {
    int d = 0;
    for (int c = 0; c < 3; c++) d += abs((int)rgb[3 * i + c] - (int)sky[3 * i + c]);
    m[i] = d > 24;
  }
  return m;
}

/* 4-connected pieces of the mask of at least min pixels (flood fill);
 * the largest's size into *largest. */
static int pieces(const bool *mask, int min, int *largest) {
  bool *seen = calloc((size_t)W * H, sizeof *seen);
  int *stack = malloc((size_t)W * H * sizeof *stack);
  assert_true(seen != NULL && stack != NULL);
  int count = 0;
  *largest = 0;
  for (int start = 0; start < W * H; start++) {
    if (!mask[start] || seen[start]) continue;
    int top = 0, size = 0;
    stack[top++] = start;
    seen[start] = true;
    while (top > 0) {
      int p = stack[--top], x = p % W, y = p / W;
      size++;
      int next[4] = { x > 0 ? p - 1 : -1, x + 1 < W ? p + 1 : -1, y > 0 ? p - W : -1,
                      y + 1 < H ? p + W : -1 };
      for (int k = 0; k < 4; k++)
        if (next[k] >= 0 && mask[next[k]] && !seen[next[k]]) {
          seen[next[k]] = true;
          stack[top++] = next[k];
        }
    }
    count += size >= min;
    if (size > *largest) *largest = size;
  }
  free(seen);
  free(stack);
  return count;
}

static void the_first_puppet_is_one_joined_figure_with_every_particle_inside(void **state) {
  (void)state;
  mr_scene s;
  mr_scene_error e;
  if (mr_scene_load(MR_SOURCE_DIR "/host/scenes/puppet.yaml", &s, &e) != MR_SCENE_OK)
    fail_msg("%s", e.text);
  /* The puppet alone against the sky: no floor, backdrop, shadows,
   * strings or control (the strings would join anything to anything). */
  mr_stage_def d = s.stage;
  d.floor = d.backdrop = d.lights.shadows = false;
  d.show_strings = false;
  mr_model_def *kept = calloc(d.n_models + 1, sizeof *kept);
  assert_non_null(kept);
  size_t n = 0;
  for (size_t i = 0; i < d.n_models; i++)
    if (strncmp(d.models[i].name, "bar:", 4) != 0) kept[n++] = d.models[i];
  d.models = kept;
  d.n_models = n;
  size_t points = 0;
  double *xyz = mr_scene_start_positions(&s, &points, &e);
  assert_non_null(xyz);
  mr_stage *stage = NULL;
  char msg[512];
  if (mr_stage_create(&d, xyz, points, &stage, msg, sizeof msg) != MR_STAGE_OK) fail_msg("%s", msg);
  const mr_draw_list *list;
  assert_int_equal(mr_stage_update(stage, xyz, points, &list), MR_STAGE_OK);
  mr_render_def rd = mr_default_render_def();
  rd.backend = MR_RENDER_OSMESA;
  rd.headless = true;
  rd.width = W;
  rd.height = H;
  mr_render *r = NULL;
  if (mr_render_create(&rd, &d, s.path, &r, msg, sizeof msg) != MR_RENDER_OK) fail_msg("%s", msg);
  mr_render_view v = mr_default_render_view(&d);
  v.show_rigging = false;
  uint8_t *rgb = malloc((size_t)W * H * 3), *sky = malloc((size_t)W * H * 3);
  assert_true(rgb != NULL && sky != NULL);
  mr_draw_list none = { 0 };
  assert_int_equal(mr_render_draw(r, &none, &v), MR_RENDER_OK);
  assert_int_equal(mr_render_read_rgb(r, sky, (size_t)W * H * 3), MR_RENDER_OK);
  assert_int_equal(mr_render_draw(r, list, &v), MR_RENDER_OK);
  assert_int_equal(mr_render_read_rgb(r, rgb, (size_t)W * H * 3), MR_RENDER_OK);
  bool *mask = figure_mask(rgb, sky);
  int largest = 0, count = pieces(mask, 4, &largest);
  print_message("puppet.yaml at its start: %d piece(s), the largest %d pixels\n", count, largest);
  assert_int_equal(count, 1);
  assert_true(largest > 2000);
  /* Every particle of the puppet lands on the figure. */
  for (size_t i = 0; i < s.n_particles; i++) {
    double ndc[2], aspect = (double)W / H;
    double depth = mr_view_project(v.eye, v.target, v.fov_deg, aspect, &xyz[3 * i], ndc);
    assert_true(depth > 0);
    int x = (int)((ndc[0] * 0.5 + 0.5) * W), y = (int)((0.5 - ndc[1] * 0.5) * H);
    if (!mask[(size_t)y * W + (size_t)x])
      fail_msg("particle %s is drawn by no model", s.particles[i].name);
  }
  free(mask);
  free(rgb);
  free(sky);
  mr_render_destroy(r);
  mr_stage_destroy(stage);
  free(xyz);
  free(kept);
  mr_scene_free(&s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(the_first_puppet_is_one_joined_figure_with_every_particle_inside),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
