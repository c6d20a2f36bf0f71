/* A small stage for the renderer's tests: one model (a red sphere by
 * default) on the default stage, drawn at a small size, and helpers to
 * find things in the pixels. */
#ifndef MR_TEST_RENDER_FIXTURE_H
#define MR_TEST_RENDER_FIXTURE_H

#include <stddef.h>
#include <stdint.h>

#include "mr_render.h"

enum { FX_W = 320, FX_H = 180, FX_MAX_ITEMS = 4 };

typedef struct fx_scene {
  mr_stage_def stage;
  mr_model_def models[FX_MAX_ITEMS];
  mr_draw_item items[FX_MAX_ITEMS];
  mr_draw_list list;
  mr_render_view view;
} fx_scene;

/* The default stage without the theater's set, the default view, and
 * one item: a red sphere 0.4 m across,
 * its centre at (0, 0.6, 0), the orbit camera's target. */
void fx_scene_init(fx_scene *s);
/* Adds a model and an item of it at (x, y, z); returns its index. */
int fx_add(fx_scene *s, mr_shape shape, const float rgb[3], double x, double y, double z,
           double size);

/* A renderer of backend b for s's stage at FX_W x FX_H (asserts it starts). */
mr_render *fx_render(mr_render_backend b, const fx_scene *s);
/* The same on the OpenGL gl asks for, with def.samples set (0: the
 * default). */
mr_render *fx_render_gl(mr_render_backend b, mr_render_gl gl, const fx_scene *s);
mr_render *fx_render_samples(mr_render_backend b, const fx_scene *s, int samples);
mr_render *fx_render_with(mr_render_backend b, mr_render_gl gl, const fx_scene *s, int samples);
/* Draws and reads back; the frame is malloc'ed (3 FX_W FX_H). */
uint8_t *fx_draw(mr_render *r, const fx_scene *s);

/* Where a world point lands in the picture (pixels, top row 0). */
void fx_project(const mr_render_view *v, const double p[3], double px[2]);

int fx_is_red(const uint8_t *p);
/* Pixels that pass pred inside [x0, x1) x [y0, y1), and their centroid. */
size_t fx_count(const uint8_t *rgb, int (*pred)(const uint8_t *), int x0, int y0, int x1, int y1,
                double centroid[2]);
/* The mean of (r + g + b) / 3 over a square of side 2 half + 1. */
double fx_mean_luma(const uint8_t *rgb, int cx, int cy, int half);
uint64_t fx_hash(const uint8_t *data, size_t n);
/* Writes the frame to the build folder as NAME.png, for a look. */
void fx_save(const char *name, const uint8_t *rgb);

#endif
