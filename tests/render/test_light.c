/* Light on real pixels: the day knob's sky and stars, the sun's shadow,
 * a spot's cone. Each through OSMesa and EGL. */
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

static uint8_t srgb8(float c) {
  double s = c <= 0.0031308 ? c * 12.92 : 1.055 * pow(c, 1 / 2.4) - 0.055;
  return (uint8_t)(s * 255 + 0.5);
}

/* A view from low down, looking up over the backdrop at the sky ahead
 * (where the built-in Orion stands). */
static void look_up(mr_render_view *v) {
  const double eye[3] = { 0, 0.4, 2.8 }, target[3] = { 0, 1.4, 0 };
  memcpy(v->eye, eye, sizeof eye);
  memcpy(v->target, target, sizeof target);
}

/* Brighter than the sky around it in every channel, by more than the
 * tolerance: a star (the top half of these views is sky and backdrop). */
static uint8_t sky_ref[3];
static int is_star(const uint8_t *p) {
  return p[0] > sky_ref[0] + 30 && p[1] > sky_ref[1] + 30 && p[2] > sky_ref[2] + 20;
}

static void day_and_night(mr_render_backend b) {
  fx_scene s;
  fx_scene_init(&s);
  look_up(&s.view);
  mr_render *r = fx_render(b, &s);
  s.view.time_of_day = 0.5;
  uint8_t *day = fx_draw(r, &s);
  s.view.time_of_day = 0.0;
  uint8_t *night = fx_draw(r, &s);
  fx_save("light_night", night);
  /* The top row is sky: the day colour at noon, the night's at midnight. */
  const uint8_t *pd = day + 3 * (FX_W / 2), *pn = night + 3 * (FX_W / 2);
  for (int c = 0; c < 3; c++) {
    assert_true(abs(pd[c] - srgb8(s.stage.sky_day[c])) <= 2);
  }
  /* At night the sky is the night colour except where a star shines. */
  size_t dark = 0;
  for (int x = 0; x < FX_W; x++) {
    const uint8_t *p = night + 3 * x;
    int near = 1;
    for (int c = 0; c < 3; c++) near &= abs(p[c] - srgb8(s.stage.sky_night[c])) <= 2;
    dark += near;
  }
  assert_true(dark > FX_W * 9 / 10);
  /* Stars: none by day, some by night, all above the backdrop's top. */
  memcpy(sky_ref, pd, 3);
  assert_int_equal(fx_count(day, is_star, 0, 0, FX_W, FX_H, NULL), 0);
  memcpy(sky_ref, pn, 3);
  double c[2];
  size_t stars = fx_count(night, is_star, 0, 0, FX_W, FX_H, c);
  if (stars < 5) fail_msg("%zu star pixels", stars);
  const double top[3] = { 0, 1.6, -3 };
  double pt[2];
  fx_project(&s.view, top, pt);
  assert_true(fx_count(night, is_star, 0, (int)pt[1] + 1, FX_W, FX_H, NULL) == 0);
  free(day);
  free(night);
  mr_render_destroy(r);
}

static void test_the_day_knob_turns_the_sky_to_night_and_brings_out_stars(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) day_and_night(backends[i]);
}

/* A box above the floor at noon; the floor where its shadow falls is
 * darker with shadows on than off, and far from it the same. */
static void shadow(mr_render_backend b) {
  fx_scene s;
  fx_scene_init(&s);
  s.models[0].shape = MR_SHAPE_BOX;
  s.items[0].pose.position[1] = 0.5;
  const double under[3] = { 0.12, 0, -0.3 }, far[3] = { 1.0, 0, 0.8 };
  double pu[2], pf[2];
  fx_project(&s.view, under, pu);
  fx_project(&s.view, far, pf);
  mr_render *r = fx_render(b, &s);
  uint8_t *on = fx_draw(r, &s);
  fx_save("light_shadow", on);
  mr_render_destroy(r);
  s.stage.lights.shadows = false;
  r = fx_render(b, &s);
  uint8_t *off = fx_draw(r, &s);
  mr_render_destroy(r);
  double lu_on = fx_mean_luma(on, (int)pu[0], (int)pu[1], 1);
  double lu_off = fx_mean_luma(off, (int)pu[0], (int)pu[1], 1);
  double lf_on = fx_mean_luma(on, (int)pf[0], (int)pf[1], 1);
  double lf_off = fx_mean_luma(off, (int)pf[0], (int)pf[1], 1);
  if (!(lu_on < 0.75 * lu_off))
    fail_msg("under the box: %.1f with shadows, %.1f without", lu_on, lu_off);
  assert_true(fabs(lf_on - lf_off) <= 1.0);
  free(on);
  free(off);
}

static void test_the_sun_casts_a_shadow_under_an_item(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) shadow(backends[i]);
}

/* At night a spot lights the floor inside its cone, fading at its edge,
 * and leaves the floor outside it as it was. */
static void spot(mr_render_backend b) {
  fx_scene s;
  fx_scene_init(&s);
  s.stage.n_models = 0;
  s.list.n_items = 0;
  s.view.time_of_day = 0.0;
  mr_render *r = fx_render(b, &s);
  uint8_t *dark = fx_draw(r, &s);
  mr_render_destroy(r);
  mr_spot_def sp = mr_default_spot_def();
  const double pos[3] = { 0, 2.5, 0.5 }, target[3] = { 0, 0, 0.5 };
  memcpy(sp.position, pos, sizeof pos);
  memcpy(sp.target, target, sizeof target);
  sp.angle_deg = 15; /* radius on the floor: 2.5 tan 15° = 0.67 m */
  s.stage.lights.spots[0] = sp;
  s.stage.lights.n_spots = 1;
  r = fx_render(b, &s);
  uint8_t *lit = fx_draw(r, &s);
  fx_save("light_spot", lit);
  mr_render_destroy(r);
  const double in[3] = { 0, 0, 0.5 }, edge[3] = { 0.6, 0, 0.5 }, out[3] = { 1.2, 0, 0.5 };
  double pi[2], pe[2], po[2];
  fx_project(&s.view, in, pi);
  fx_project(&s.view, edge, pe);
  fx_project(&s.view, out, po);
  double gain_in =
      fx_mean_luma(lit, (int)pi[0], (int)pi[1], 1) - fx_mean_luma(dark, (int)pi[0], (int)pi[1], 1);
  double gain_edge =
      fx_mean_luma(lit, (int)pe[0], (int)pe[1], 1) - fx_mean_luma(dark, (int)pe[0], (int)pe[1], 1);
  double gain_out =
      fx_mean_luma(lit, (int)po[0], (int)po[1], 1) - fx_mean_luma(dark, (int)po[0], (int)po[1], 1);
  if (!(gain_in > 60 && gain_edge > 2 && gain_edge < gain_in * 0.8 && fabs(gain_out) <= 1))
    fail_msg("spot gains: centre %.1f, edge %.1f, outside %.1f", gain_in, gain_edge, gain_out);
  free(dark);
  free(lit);
}

static void test_a_spot_lights_its_cone_with_a_soft_edge(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) spot(backends[i]);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_the_day_knob_turns_the_sky_to_night_and_brings_out_stars),
    cmocka_unit_test(test_the_sun_casts_a_shadow_under_an_item),
    cmocka_unit_test(test_a_spot_lights_its_cone_with_a_soft_edge),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
