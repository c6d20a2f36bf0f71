/* A scene on the stage: its mr_stage (frames' positions -> a draw list),
 * the renderer (in a window, mr_window's, or headless), and how it is
 * looked at (the orbit camera or one of the
 * scene's, the day knob, the on-screen display). Shared by `marionette
 * render` and `marionette run`. */
#ifndef MR_STAGE_VIEW_H
#define MR_STAGE_VIEW_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mr_render.h"
#include "mr_scene.h"
#include "mr_window.h"

enum { MR_OSD_LINES = 16, MR_OSD_LINE_MAX = 200 };

typedef struct mr_stageview {
  const mr_scene *scene;
  mr_stage *stage;
  mr_window *window; /* NULL: headless */
  mr_render *render;
  int width, height;
  /* The camera: -1 the orbit camera, else the scene's camera k. */
  int camera;
  mr_orbit orbit; /* the orbit camera (mr_stage's maths) */
  /* `camera: follow`: the orbit's target is follow.pos + follow_offset,
   * follow chasing the middle of the points' box (mr_stageview_track). */
  mr_follow follow;
  double follow_offset[3], follow_t;
  double time_of_day;
  int material_turn; /* times the models were told to change materials */
  bool show_osd, show_rigging;
  char osd[MR_OSD_LINES][MR_OSD_LINE_MAX];
  size_t n_osd;
  const mr_draw_list *last; /* the latest draw list (the stage's) */
  uint8_t *rgb;             /* 3 w h, for reading frames back */
  size_t n_points;
} mr_stageview;

/* The stage of scene (its world built once for the start positions) and a
 * renderer of rdef (its size: rdef's, else the scene's stage.size). With
 * wdef and rdef's backend the window's, a window of wdef (at the
 * renderer's size, on rdef's OpenGL) is opened first and the renderer
 * draws into its context. On failure -1 and one line in msg: a model
 * error names the scene's file:line:column and the model's path. */
int mr_stageview_open(mr_stageview *sv, const mr_scene *scene, const mr_render_def *rdef,
                      const mr_window_def *wdef, char *msg, size_t msg_size);
void mr_stageview_close(mr_stageview *sv);

/* The points at xyz (3 n: scene particles, then control points) drawn
 * with the current view. -1 with msg on a renderer failure. */
int mr_stageview_draw(mr_stageview *sv, const double *xyz, size_t n, char *msg, size_t msg_size);
/* The show's time t and its points (as mr_stageview_draw's) for the
 * camera that follows (`camera: follow`): called for every frame of the
 * show, drawn or not, so that the camera moves the same whichever frames
 * are drawn. Nothing without `camera: follow`. */
void mr_stageview_track(mr_stageview *sv, double t, const double *xyz, size_t n);
/* The show's time t and its end (< 0: not known, a live show) for the
 * frames drawn from now: the curtain's openness (mr_stage_set_time). */
void mr_stageview_set_time(mr_stageview *sv, double t, double end);
/* The latest draw list again with the current view (paused, orbiting). */
int mr_stageview_redraw(mr_stageview *sv, char *msg, size_t msg_size);
/* The last frame drawn, RGB top row first (sv->width x sv->height). */
const uint8_t *mr_stageview_read(mr_stageview *sv);

/* The scene's camera named name: its index, or -1. */
int mr_stageview_find_camera(const mr_stageview *sv, const char *name);
/* Camera k of the scene (-1: the orbit camera); out of range is ignored. */
void mr_stageview_pick_camera(mr_stageview *sv, int k);
/* The orbit camera turned by d_azimuth, d_elevation degrees (from a
 * scene camera it starts where that camera looks from), or moved in or
 * out by steps of the mouse wheel. */
void mr_stageview_orbit(mr_stageview *sv, double d_azimuth, double d_elevation);
void mr_stageview_zoom(mr_stageview *sv, double steps);
/* The day knob, kept in 0..1 (wrapping: past midnight is a new day). */
void mr_stageview_set_day(mr_stageview *sv, double time_of_day);
/* Every model that can wear several materials puts on its next one,
 * after its last the first again (§3.3: a material changes while the show
 * runs); it shows from the next frame drawn or redrawn. */
void mr_stageview_next_material(mr_stageview *sv);

/* OSD lines (printf-like); cleared by mr_stageview_osd_clear. */
void mr_stageview_osd_clear(mr_stageview *sv);
void mr_stageview_osd(mr_stageview *sv, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif
