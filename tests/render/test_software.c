/* What makes the renderer cheap in software, on real pixels through
 * OSMesa and EGL (both Mesa's llvmpipe here): one sample and a post pass
 * that smooths the edges, unless samples are asked for; a shadow map that
 * is drawn again when a caster moves; the stage's spots, however many,
 * each lighting its cone; built-in shapes culled from the outside, even
 * mirrored; the still scenery kept between frames, and drawn again when
 * the camera or the sun moves. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fixture.h"

static const mr_render_backend backends[] = { MR_RENDER_OSMESA, MR_RENDER_EGL };

static int luma(const uint8_t *rgb, int x, int y) {
  const uint8_t *p = rgb + 3 * ((size_t)y * FX_W + (size_t)x);
  return (p[0] * 299 + p[1] * 587 + p[2] * 114) / 1000;
}

/* The largest luma step from (x, y) to a pixel within one of it. */
static int contrast(const uint8_t *rgb, int x, int y) {
  int m = luma(rgb, x, y), most = 0;
  for (int dy = -1; dy <= 1; dy++) {
    for (int dx = -1; dx <= 1; dx++) {
      int u = x + dx, v = y + dy;
      if (u < 0 || v < 0 || u >= FX_W || v >= FX_H) continue;
      int d = abs(luma(rgb, u, v) - m);
      if (d > most) most = d;
    }
  }
  return most;
}

static size_t differ(const uint8_t *a, const uint8_t *b) {
  size_t n = 0;
  for (size_t i = 0; i < (size_t)FX_W * FX_H; i++) n += memcmp(a + 3 * i, b + 3 * i, 3) != 0;
  return n;
}

/* The red sphere on the default stage: drawn with the defaults, then with
 * one sample asked for (no post pass). They differ, and only at edges:
 * where the sharp frame has a luma step of 8 or more next to the pixel. */
static void smoothed(mr_render_backend b) {
  fx_scene s;
  fx_scene_init(&s);
  mr_render *r = fx_render(b, &s);
  assert_true(mr_render_is_software(r));
  if (strncmp(mr_render_quality(r), "1 sample, edges smoothed", 24) != 0)
    fail_msg("%s: quality '%s'", mr_render_backend_name(b), mr_render_quality(r));
  uint8_t *soft = fx_draw(r, &s);
  fx_save("software_smoothed", soft);
  mr_render_destroy(r);
  r = fx_render_samples(b, &s, 1);
  if (strstr(mr_render_quality(r), "smoothed") != NULL)
    fail_msg("one sample asked for, yet '%s'", mr_render_quality(r));
  uint8_t *sharp = fx_draw(r, &s);
  mr_render_destroy(r);
  size_t changed = 0;
  for (int y = 0; y < FX_H; y++) {
    for (int x = 0; x < FX_W; x++) {
      size_t i = 3 * ((size_t)y * FX_W + (size_t)x);
      if (memcmp(soft + i, sharp + i, 3) == 0) continue;
      changed++;
      if (contrast(sharp, x, y) < 8)
        fail_msg("%s: (%d, %d) changed away from any edge", mr_render_backend_name(b), x, y);
    }
  }
  /* The sphere's outline alone is some 150 pixels round. */
  if (changed < 100) fail_msg("%s: %zu pixels smoothed", mr_render_backend_name(b), changed);
  /* The middle of the sphere is no edge: the same in both. */
  assert_int_equal(luma(soft, FX_W / 2, FX_H / 2), luma(sharp, FX_W / 2, FX_H / 2));
  free(soft);
  free(sharp);
}

static void test_in_software_a_frame_has_one_sample_and_only_its_edges_are_smoothed(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) smoothed(backends[i]);
}

/* Samples asked for are drawn: 4 samples blend the sphere's outline, so
 * the frame differs from one sample's, and nothing is smoothed after. */
static void asked(mr_render_backend b) {
  fx_scene s;
  fx_scene_init(&s);
  mr_render *r = fx_render_samples(b, &s, 4);
  if (strncmp(mr_render_quality(r), "4 samples, shadow map", 21) != 0)
    fail_msg("%s: quality '%s'", mr_render_backend_name(b), mr_render_quality(r));
  uint8_t *four = fx_draw(r, &s);
  mr_render_destroy(r);
  r = fx_render_samples(b, &s, 1);
  uint8_t *one = fx_draw(r, &s);
  mr_render_destroy(r);
  size_t n = differ(four, one);
  if (n < 100) fail_msg("%s: 4 samples and 1 differ in %zu pixels", mr_render_backend_name(b), n);
  free(four);
  free(one);
}

static void test_samples_asked_for_are_drawn_in_software_too(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) asked(backends[i]);
}

/* A box above the floor at noon, at x = -0.6, then at x = +0.6 and
 * turned 30 degrees about y, then back: its shadow moves with it, the
 * moved frame is the one a new renderer draws of it (the map was drawn
 * again, not reused), and the frame back at the start is the first one,
 * bit for bit. */
static void follows(mr_render_backend b) {
  fx_scene s;
  fx_scene_init(&s);
  s.models[0].shape = MR_SHAPE_BOX;
  s.items[0].pose.position[1] = 0.5;
  mr_render *r = fx_render(b, &s);
  const double under_left[3] = { -0.48, 0, -0.3 }, under_right[3] = { 0.72, 0, -0.3 };
  double pl[2], pr[2];
  fx_project(&s.view, under_left, pl);
  fx_project(&s.view, under_right, pr);
  s.items[0].pose.position[0] = -0.6;
  uint8_t *left = fx_draw(r, &s);
  const mr_pose start = s.items[0].pose;
  s.items[0].pose.position[0] = 0.6;
  s.items[0].pose.orientation[0] = cos(3.14159265358979 / 12); /* w x y z: 30 degrees about y */
  s.items[0].pose.orientation[2] = sin(3.14159265358979 / 12);
  uint8_t *right = fx_draw(r, &s);
  fx_save("software_shadow_moved", right);
  mr_render *fresh = fx_render(b, &s);
  uint8_t *right_fresh = fx_draw(fresh, &s);
  mr_render_destroy(fresh);
  s.items[0].pose = start;
  uint8_t *again = fx_draw(r, &s);
  mr_render_destroy(r);
  double l_in_left = fx_mean_luma(left, (int)pl[0], (int)pl[1], 1);
  double l_in_right = fx_mean_luma(right, (int)pl[0], (int)pl[1], 1);
  double r_in_left = fx_mean_luma(left, (int)pr[0], (int)pr[1], 1);
  double r_in_right = fx_mean_luma(right, (int)pr[0], (int)pr[1], 1);
  if (!(l_in_left < 0.75 * l_in_right && r_in_right < 0.75 * r_in_left))
    fail_msg("%s: under the left place %.1f (box left) %.1f (box right); under the right "
             "place %.1f (box left) %.1f (box right)",
             mr_render_backend_name(b), l_in_left, l_in_right, r_in_left, r_in_right);
  size_t stale = differ(right, right_fresh);
  if (stale != 0)
    fail_msg("%s: %zu pixels differ from a new renderer's", mr_render_backend_name(b), stale);
  assert_int_equal(differ(left, again), 0);
  free(left);
  free(right);
  free(right_fresh);
  free(again);
}

static void test_the_shadow_map_is_drawn_again_when_a_caster_moves(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) follows(backends[i]);
}

/* At night, three spots on the floor at x = -1, 0 and 1, each narrow
 * enough to light only its own place: each place is lit. */
static void spots(mr_render_backend b) {
  fx_scene s;
  fx_scene_init(&s);
  s.stage.n_models = 0;
  s.list.n_items = 0;
  s.view.time_of_day = 0.0;
  mr_render *r = fx_render(b, &s);
  uint8_t *dark = fx_draw(r, &s);
  mr_render_destroy(r);
  for (int i = 0; i < 3; i++) {
    mr_spot_def sp = mr_default_spot_def();
    const double pos[3] = { i - 1.0, 2.5, 0.5 }, target[3] = { i - 1.0, 0, 0.5 };
    memcpy(sp.position, pos, sizeof pos);
    memcpy(sp.target, target, sizeof target);
    sp.angle_deg = 8; /* radius on the floor: 2.5 tan 8° = 0.35 m */
    s.stage.lights.spots[i] = sp;
  }
  s.stage.lights.n_spots = 3;
  r = fx_render(b, &s);
  uint8_t *lit = fx_draw(r, &s);
  fx_save("software_three_spots", lit);
  mr_render_destroy(r);
  for (int i = 0; i < 3; i++) {
    const double at[3] = { i - 1.0, 0, 0.5 };
    double p[2];
    fx_project(&s.view, at, p);
    double gain =
        fx_mean_luma(lit, (int)p[0], (int)p[1], 1) - fx_mean_luma(dark, (int)p[0], (int)p[1], 1);
    if (!(gain > 60)) fail_msg("%s: spot %d gains %.1f", mr_render_backend_name(b), i, gain);
  }
  free(dark);
  free(lit);
}

static void test_each_of_three_spots_lights_its_own_cone(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) spots(backends[i]);
}

/* A sphere (a built-in shape, whose back faces are culled) scaled by -1
 * in x is the same sphere: its mirrored winding turns the culling round,
 * and the frame is the unmirrored one's. */
static void mirrored(mr_render_backend b) {
  fx_scene s;
  fx_scene_init(&s);
  mr_render *r = fx_render(b, &s);
  uint8_t *plain = fx_draw(r, &s);
  s.items[0].scale[0] = -s.items[0].scale[0];
  uint8_t *mirror = fx_draw(r, &s);
  fx_save("software_mirrored", mirror);
  mr_render_destroy(r);
  size_t n = differ(plain, mirror);
  if (n > 20)
    fail_msg("%s: the mirrored sphere differs on %zu pixels", mr_render_backend_name(b), n);
  free(plain);
  free(mirror);
}

static void test_a_mirrored_shape_is_drawn_from_the_outside(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) mirrored(backends[i]);
}

/* One renderer draws a box at noon, then turned round the stage by the
 * camera, then at evening, then its box moved: the sky, backdrop and
 * floor it keeps between frames follow each change, and every frame is
 * the one a new renderer draws of it, bit for bit. */
static void kept(mr_render_backend b) {
  fx_scene s;
  fx_scene_init(&s);
  s.models[0].shape = MR_SHAPE_BOX;
  s.items[0].pose.position[1] = 0.5;
  mr_render *r = fx_render(b, &s);
  for (int step = 0; step < 4; step++) {
    if (step == 1) s.view.eye[0] += 0.8;              /* the camera */
    if (step == 2) s.view.time_of_day = 0.7;          /* the sun, low */
    if (step == 3) s.items[0].pose.position[0] = 0.5; /* the shadow */
    /* Drawn whole, then with what it kept. */
    uint8_t *moved = fx_draw(r, &s);
    uint8_t *frame = fx_draw(r, &s);
    mr_render *fresh = fx_render(b, &s);
    uint8_t *first = fx_draw(fresh, &s);
    mr_render_destroy(fresh);
    size_t n = differ(frame, first) + differ(moved, first);
    if (n != 0)
      fail_msg("%s: step %d: %zu pixels differ from a new renderer's", mr_render_backend_name(b),
               step, n);
    free(moved);
    free(frame);
    free(first);
  }
  mr_render_destroy(r);
}

static void test_the_kept_scenery_follows_the_camera_the_sun_and_the_shadows(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) kept(backends[i]);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_in_software_a_frame_has_one_sample_and_only_its_edges_are_smoothed),
    cmocka_unit_test(test_samples_asked_for_are_drawn_in_software_too),
    cmocka_unit_test(test_the_shadow_map_is_drawn_again_when_a_caster_moves),
    cmocka_unit_test(test_each_of_three_spots_lights_its_own_cone),
    cmocka_unit_test(test_a_mirrored_shape_is_drawn_from_the_outside),
    cmocka_unit_test(test_the_kept_scenery_follows_the_camera_the_sun_and_the_shadows),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
