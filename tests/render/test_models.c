/* Models on real pixels: a missing model file is named with its scene
 * position; a freeform skin moves with its bones (256 of them); a model
 * wears the material the draw list asks for; the on-screen display draws
 * its text, and a missing font is named. */
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

static void test_a_missing_model_file_is_named_with_its_scene_position(void **state) {
  (void)state;
  fx_scene s;
  fx_scene_init(&s);
  s.models[0].shape = MR_SHAPE_FILE;
  snprintf(s.models[0].path, sizeof s.models[0].path, "/nonexistent/models/head.obj");
  snprintf(s.models[0].name, sizeof s.models[0].name, "head");
  s.models[0].pos.line = 12;
  s.models[0].pos.column = 5;
  mr_render_def def = mr_default_render_def();
  def.backend = MR_RENDER_OSMESA;
  mr_render *r = NULL;
  char msg[512] = "";
  assert_int_equal(mr_render_create(&def, &s.stage, "scenes/show.yaml", &r, msg, sizeof msg),
                   MR_RENDER_ERR_MODEL);
  assert_null(r);
  const char *want = "scenes/show.yaml:12:5: model 'head': /nonexistent/models/head.obj: ";
  if (strncmp(msg, want, strlen(want)) != 0) fail_msg("msg: %s", msg);
  assert_true(strlen(msg) > strlen(want)); /* and why */
}

enum { N_BONES = 256 };

/* A red bar 0.16 m thick from y = 0.2 to 1.0, bound to 256 bones along
 * its axis; every bone moved by (dx, 0, 0) above height `from`. */
typedef struct skin_fixture {
  fx_scene s;
  double rest[3 * N_BONES];
  int ids[N_BONES];
  mr_pose bones[N_BONES];
  mr_draw_skin skin;
} skin_fixture;

static void skin_init(skin_fixture *k) {
  fx_scene_init(&k->s);
  mr_model_def *m = &k->s.models[0];
  m->shape = MR_SHAPE_BOX;
  m->display = MR_DISPLAY_FREEFORM;
  m->scale[0] = m->scale[2] = 0.16;
  m->scale[1] = 0.8;
  m->place = mr_pose_identity();
  m->place.position[1] = 0.6;
  for (int i = 0; i < N_BONES; i++) {
    k->rest[3 * i] = 0;
    k->rest[3 * i + 1] = 0.2 + 0.8 * i / (N_BONES - 1.0);
    k->rest[3 * i + 2] = 0;
    k->ids[i] = i;
  }
  m->bones = k->ids;
  m->bones_rest = k->rest;
  m->n_bones = N_BONES;
  m->influences = 4;
  k->s.list.n_items = 0;
  k->skin.model = 0;
  k->skin.bones = k->bones;
  k->skin.n_bones = N_BONES;
  k->skin.material = 0;
  k->s.list.skins = &k->skin;
  k->s.list.n_skins = 1;
}

static void skin_move(skin_fixture *k, double dx, double from) {
  for (int i = 0; i < N_BONES; i++) {
    k->bones[i] = mr_pose_identity();
    if (k->rest[3 * i + 1] >= from) k->bones[i].position[0] = dx;
  }
}

static double projected_x(const fx_scene *s, double x, double y) {
  const double p[3] = { x, y, 0 };
  double px[2];
  fx_project(&s->view, p, px);
  return px[0];
}

static void skin_moves(mr_render_backend b) {
  skin_fixture *k = calloc(1, sizeof *k);
  skin_init(k);
  mr_render *r = fx_render(b, &k->s);
  double c[2];
  skin_move(k, 0, 0);
  uint8_t *rest = fx_draw(r, &k->s);
  fx_count(rest, fx_is_red, 0, 0, FX_W, FX_H, c);
  assert_true(fabs(c[0] - projected_x(&k->s, 0, 0.6)) < 2);
  /* All bones 0.5 m to +x: the whole bar goes there. */
  skin_move(k, 0.5, 0);
  uint8_t *moved = fx_draw(r, &k->s);
  fx_save("skin_moved", moved);
  fx_count(moved, fx_is_red, 0, 0, FX_W, FX_H, c);
  if (fabs(c[0] - projected_x(&k->s, 0.5, 0.6)) > 3)
    fail_msg("moved bar at x %.1f, expected %.1f", c[0], projected_x(&k->s, 0.5, 0.6));
  /* Only the bones above 0.6 m: the bottom stays, the top goes. */
  skin_move(k, 0.5, 0.6);
  uint8_t *bent = fx_draw(r, &k->s);
  fx_save("skin_bent", bent);
  double low[2], high[2];
  const double pl[3] = { 0, 0.3, 0 }, ph[3] = { 0.5, 0.9, 0 };
  fx_project(&k->s.view, pl, low);
  fx_project(&k->s.view, ph, high);
  assert_true(fx_is_red(bent + 3 * ((size_t)low[1] * FX_W + (size_t)low[0])));
  assert_true(fx_is_red(bent + 3 * ((size_t)high[1] * FX_W + (size_t)high[0])));
  assert_false(fx_is_red(rest + 3 * ((size_t)high[1] * FX_W + (size_t)high[0])));
  free(rest);
  free(moved);
  free(bent);
  mr_render_destroy(r);
  free(k);
}

static void test_a_freeform_skin_moves_its_vertices_with_256_bones(void **state) {
  (void)state;
  for (size_t i = 0; i < 2; i++) skin_moves(backends[i]);
}

static int is_blue(const uint8_t *p) {
  return p[2] > 60 && p[0] * 3 < p[2] && p[1] * 3 < p[2];
}

static void test_an_item_wears_the_material_the_draw_list_asks_for(void **state) {
  (void)state;
  fx_scene s;
  fx_scene_init(&s);
  s.models[0].materials[1] = mr_default_material_def();
  const float blue[3] = { 0.05f, 0.05f, 0.9f };
  memcpy(s.models[0].materials[1].base_color, blue, sizeof blue);
  s.models[0].n_materials = 2;
  mr_render *r = fx_render(MR_RENDER_EGL, &s);
  uint8_t *red = fx_draw(r, &s);
  s.items[0].material = 1;
  uint8_t *blu = fx_draw(r, &s);
  s.items[0].material = -1; /* a shape's own: the default grey */
  uint8_t *own = fx_draw(r, &s);
  size_t n_red = fx_count(red, fx_is_red, 0, 0, FX_W, FX_H, NULL);
  assert_true(n_red > 100);
  assert_int_equal(fx_count(red, is_blue, 0, 0, FX_W, FX_H, NULL), 0);
  assert_int_equal(fx_count(blu, fx_is_red, 0, 0, FX_W, FX_H, NULL), 0);
  assert_true(fx_count(blu, is_blue, 0, 0, FX_W, FX_H, NULL) > n_red * 9 / 10);
  assert_int_equal(fx_count(own, fx_is_red, 0, 0, FX_W, FX_H, NULL), 0);
  assert_int_equal(fx_count(own, is_blue, 0, 0, FX_W, FX_H, NULL), 0);
  free(red);
  free(blu);
  free(own);
  mr_render_destroy(r);
}

/* The overlay is drawn inside mr_osd_rect's box, in the bottom left
 * corner, and nowhere else: the box darkens the picture, the glyphs are
 * bright inside it, every pixel outside it is untouched. */
static void test_the_osd_draws_text_only_inside_its_box_bottom_left(void **state) {
  (void)state;
  fx_scene s;
  fx_scene_init(&s);
  mr_render *r = fx_render(MR_RENDER_OSMESA, &s);
  uint8_t *plain = fx_draw(r, &s);
  const char *lines[] = { "t 12.34 s", "fps 60" };
  s.view.osd = lines;
  s.view.n_osd = 2;
  uint8_t *osd = fx_draw(r, &s);
  fx_save("osd", osd);
  double box[4];
  mr_osd_rect(FX_W, FX_H, 2, 9, box);
  assert_true(box[0] < FX_W / 10 && box[1] + box[3] > FX_H * 9 / 10);
  assert_true(box[2] < FX_W / 2 && box[3] < FX_H / 4);
  int x0 = (int)box[0], y0 = (int)box[1], x1 = (int)(box[0] + box[2]) + 1;
  int y1 = (int)(box[1] + box[3]) + 1;
  assert_true(fx_mean_luma(osd, x0 + 2, y1 - 3, 1) < 0.8 * fx_mean_luma(plain, x0 + 2, y1 - 3, 1));
  int bright = 0, changed_outside = 0;
  for (int y = 0; y < FX_H; y++)
    for (int x = 0; x < FX_W; x++) {
      size_t i = 3 * ((size_t)y * FX_W + (size_t)x);
      bool inside = x >= x0 && x <= x1 && y >= y0 && y <= y1;
      if (inside)
        bright += osd[i + 1] > 200;
      else
        changed_outside += memcmp(osd + i, plain + i, 3) != 0;
    }
  assert_true(bright > 30);
  assert_int_equal(changed_outside, 0);
  free(plain);
  free(osd);
  mr_render_destroy(r);
}

static void test_a_missing_font_is_an_error_naming_its_path(void **state) {
  (void)state;
  fx_scene s;
  fx_scene_init(&s);
  mr_render_def def = mr_default_render_def();
  def.backend = MR_RENDER_OSMESA;
  def.font_path = "/nonexistent/fonts/Mono.ttf";
  mr_render *r = NULL;
  char msg[512] = "";
  assert_int_not_equal(mr_render_create(&def, &s.stage, NULL, &r, msg, sizeof msg), MR_RENDER_OK);
  assert_null(r);
  assert_non_null(strstr(msg, "/nonexistent/fonts/Mono.ttf"));
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_a_missing_model_file_is_named_with_its_scene_position),
    cmocka_unit_test(test_a_freeform_skin_moves_its_vertices_with_256_bones),
    cmocka_unit_test(test_an_item_wears_the_material_the_draw_list_asks_for),
    cmocka_unit_test(test_the_osd_draws_text_only_inside_its_box_bottom_left),
    cmocka_unit_test(test_a_missing_font_is_an_error_naming_its_path),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
