#include "fixture.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <cglm/cglm.h>

#include "golden.h"

void fx_scene_init(fx_scene *s) {
  memset(s, 0, sizeof *s);
  s->stage = mr_default_stage_def();
  s->stage.width = FX_W;
  s->stage.height = FX_H;
  /* A bare stage: the curtain's red at the picture's sides and the follow
   * spot's pool would stand in what the tests look for (test_curtain.c
   * has them). */
  s->stage.curtain.show = false;
  s->stage.follow_spot.show = false;
  s->stage.models = s->models;
  /* The theater's set stands between this camera and the sphere's
   * surroundings; it has tests of its own (test_set.c), and these look
   * at the lights, the models and the camera without it. */
  s->stage.proscenium = s->stage.wings = s->stage.footlights = false;
  const float red[3] = { 0.9f, 0.05f, 0.05f };
  fx_add(s, MR_SHAPE_SPHERE, red, 0, 0.6, 0, 0.4);
  s->view = mr_default_render_view(&s->stage);
}

int fx_add(fx_scene *s, mr_shape shape, const float rgb[3], double x, double y, double z,
           double size) {
  int k = (int)s->stage.n_models;
  assert_true(k < FX_MAX_ITEMS);
  mr_model_def *m = &s->models[k];
  *m = mr_default_model_def();
  snprintf(m->name, sizeof m->name, "item%d", k);
  m->shape = shape;
  m->materials[0] = mr_default_material_def();
  for (int c = 0; c < 3; c++) m->materials[0].base_color[c] = rgb[c];
  m->n_materials = 1;
  mr_draw_item *it = &s->items[k];
  it->model = k;
  it->pose = mr_pose_identity();
  it->pose.position[0] = x;
  it->pose.position[1] = y;
  it->pose.position[2] = z;
  it->scale[0] = it->scale[1] = it->scale[2] = size;
  it->material = 0;
  s->stage.n_models = (size_t)k + 1;
  s->list.items = s->items;
  s->list.n_items = (size_t)k + 1;
  return k;
}

mr_render *fx_render(mr_render_backend b, const fx_scene *s) {
  return fx_render_with(b, MR_RENDER_GL_AUTO, s, 0);
}

mr_render *fx_render_gl(mr_render_backend b, mr_render_gl gl, const fx_scene *s) {
  return fx_render_with(b, gl, s, 0);
}

mr_render *fx_render_samples(mr_render_backend b, const fx_scene *s, int samples) {
  return fx_render_with(b, MR_RENDER_GL_AUTO, s, samples);
}

mr_render *fx_render_with(mr_render_backend b, mr_render_gl gl, const fx_scene *s, int samples) {
  mr_render_def def = mr_default_render_def();
  def.backend = b;
  def.gl = gl;
  def.samples = samples;
  def.headless = true;
  def.width = FX_W;
  def.height = FX_H;
  mr_render *r = NULL;
  char msg[512] = "";
  mr_render_status st = mr_render_create(&def, &s->stage, "fixture.yaml", &r, msg, sizeof msg);
  if (st != MR_RENDER_OK)
    fail_msg("%s (gl %s): %s", mr_render_backend_name(b), mr_render_gl_name(gl), msg);
  return r;
}

uint8_t *fx_draw(mr_render *r, const fx_scene *s) {
  uint8_t *rgb = malloc((size_t)FX_W * FX_H * 3);
  assert_non_null(rgb);
  assert_int_equal(mr_render_draw(r, &s->list, &s->view), MR_RENDER_OK);
  assert_int_equal(mr_render_read_rgb(r, rgb, (size_t)FX_W * FX_H * 3), MR_RENDER_OK);
  return rgb;
}

void fx_project(const mr_render_view *v, const double p[3], double px[2]) {
  vec3 eye, target, up;
  for (int k = 0; k < 3; k++) {
    eye[k] = (float)v->eye[k];
    target[k] = (float)v->target[k];
    up[k] = (float)v->up[k];
  }
  mat4 view, proj, vp;
  glm_lookat(eye, target, up, view);
  glm_perspective(glm_rad((float)v->fov_deg), (float)FX_W / FX_H, 0.05f, 100.0f, proj);
  glm_mat4_mul(proj, view, vp);
  vec4 q = { (float)p[0], (float)p[1], (float)p[2], 1 }, c;
  glm_mat4_mulv(vp, q, c);
  px[0] = (c[0] / c[3] * 0.5 + 0.5) * FX_W;
  px[1] = (0.5 - c[1] / c[3] * 0.5) * FX_H;
}

int fx_is_red(const uint8_t *p) {
  return p[0] > 60 && p[1] * 3 < p[0] && p[2] * 3 < p[0];
}

size_t fx_count(const uint8_t *rgb, int (*pred)(const uint8_t *), int x0, int y0, int x1, int y1,
                double centroid[2]) {
  size_t n = 0;
  double sx = 0, sy = 0;
  for (int y = y0 < 0 ? 0 : y0; y < y1 && y < FX_H; y++) {
    for (int x = x0 < 0 ? 0 : x0; x < x1 && x < FX_W; x++) {
      if (pred(rgb + 3 * ((size_t)y * FX_W + (size_t)x))) {
        n++;
        sx += x;
        sy += y;
      }
    }
  }
  if (centroid) {
    centroid[0] = n ? sx / (double)n : -1;
    centroid[1] = n ? sy / (double)n : -1;
  }
  return n;
}

double fx_mean_luma(const uint8_t *rgb, int cx, int cy, int half) {
  double sum = 0;
  int n = 0;
  for (int y = cy - half; y <= cy + half; y++) {
    for (int x = cx - half; x <= cx + half; x++) {
      if (x < 0 || y < 0 || x >= FX_W || y >= FX_H) continue;
      const uint8_t *p = rgb + 3 * ((size_t)y * FX_W + (size_t)x);
      sum += (p[0] + p[1] + p[2]) / 3.0;
      n++;
    }
  }
  return n ? sum / n : 0;
}

uint64_t fx_hash(const uint8_t *data, size_t n) {
  uint64_t h = 1469598103934665603ull; /* FNV-1a 64 */
  for (size_t i = 0; i < n; i++) h = (h ^ data[i]) * 1099511628211ull;
  return h;
}

void fx_save(const char *name, const uint8_t *rgb) {
  char path[512];
  snprintf(path, sizeof path, "%s/tests/render/%s.png", MR_BINARY_DIR, name);
  mr_png_write(path, rgb, FX_W, FX_H);
}
