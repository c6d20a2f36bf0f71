/* A scene on the stage (issue 10, items 4 and 6): frames' positions become
 * a draw list (mr_stage), drawn by the renderer with a camera, the day knob
 * and the on-screen display. */
#define _POSIX_C_SOURCE 200809L

#include "stage_view.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glue.h"
#include "mr_scene_world.h"

/* The positions the stage takes its rest frames from: the same start a
 * run has. */
static double *start_positions(const mr_scene *scene, size_t *n, char *msg, size_t msg_size) {
  mr_scene_error err;
  double *xyz = mr_scene_start_positions(scene, n, &err);
  if (xyz == NULL) snprintf(msg, msg_size, "%s", err.text);
  return xyz;
}

static void start_camera(mr_stageview *sv) {
  const mr_stage_def *d = &sv->scene->stage;
  sv->camera = -1;
  sv->orbit = mr_orbit_of_stage(d);
  sv->time_of_day = d->time_of_day;
  sv->show_osd = true;
  sv->show_rigging = true;
  sv->follow = mr_follow_start(MR_FOLLOW_TIME);
}

void mr_stageview_track(mr_stageview *sv, double t, const double *xyz, size_t n) {
  if (!sv->scene->stage.follow || n == 0) return;
  double mid[3];
  mr_box_middle(xyz, n, mid);
  for (int c = 0; c < 3; c++)
    if (!isfinite(mid[c])) return;
  if (!sv->follow.started) {
    for (int c = 0; c < 3; c++) sv->follow_offset[c] = sv->orbit.target[c] - mid[c];
    sv->follow_t = t;
  }
  mr_follow_step(&sv->follow, mid, t - sv->follow_t);
  sv->follow_t = t;
  for (int c = 0; c < 3; c++) sv->orbit.target[c] = sv->follow.pos[c] + sv->follow_offset[c];
}

void mr_stageview_set_time(mr_stageview *sv, double t, double end) {
  if (sv->stage != NULL) mr_stage_set_time(sv->stage, t, end);
}

/* The window of wdef at the size the renderer will take, on rdef's
 * OpenGL; its context into *ctx for the renderer. */
static int open_window(mr_stageview *sv, const mr_render_def *rdef, const mr_window_def *wdef,
                       mr_render_context *ctx, char *msg, size_t msg_size) {
  const mr_stage_def *st = &sv->scene->stage;
  mr_window_def wd = *wdef;
  wd.width = rdef->width > 0 ? rdef->width : (st->width > 0 ? st->width : 1280);
  wd.height = rdef->height > 0 ? rdef->height : (st->height > 0 ? st->height : 720);
  wd.gl = mr_glue_gl(rdef->gl);
  char why[600];
  if (mr_window_create(&wd, &sv->window, why, sizeof why) != MR_WINDOW_OK) {
    snprintf(msg, msg_size, "no backend started: window: %s", why);
    return -1;
  }
  *ctx = mr_glue_context(sv->window);
  return 0;
}

/* The renderer of rdef, in the window of wdef when there is one to be. */
static int open_render(mr_stageview *sv, const mr_render_def *rdef, const mr_window_def *wdef,
                       char *msg, size_t msg_size) {
  mr_render_def rd = *rdef;
  mr_render_context ctx;
  if (wdef != NULL && rd.backend == MR_RENDER_WINDOW) {
    if (open_window(sv, rdef, wdef, &ctx, msg, msg_size) != 0) return -1;
    rd.context = &ctx;
  }
  if (mr_render_create(&rd, &sv->scene->stage, sv->scene->path, &sv->render, msg, msg_size) ==
      MR_RENDER_OK)
    return 0;
  mr_window_destroy(sv->window);
  sv->window = NULL;
  return -1;
}

int mr_stageview_open(mr_stageview *sv, const mr_scene *scene, const mr_render_def *rdef,
                      const mr_window_def *wdef, char *msg, size_t msg_size) {
  memset(sv, 0, sizeof *sv);
  sv->scene = scene;
  start_camera(sv);
  double *xyz = start_positions(scene, &sv->n_points, msg, msg_size);
  if (xyz == NULL) return -1;
  char why[400];
  mr_stage_status ss =
      mr_stage_create(&scene->stage, xyz, sv->n_points, &sv->stage, why, sizeof why);
  free(xyz);
  if (ss != MR_STAGE_OK) {
    snprintf(msg, msg_size, "%s: the stage: %s", scene->path, why);
    return -1;
  }
  if (open_render(sv, rdef, wdef, msg, msg_size) != 0) {
    mr_stage_destroy(sv->stage);
    sv->stage = NULL;
    return -1;
  }
  mr_render_size(sv->render, &sv->width, &sv->height);
  sv->rgb = malloc((size_t)sv->width * (size_t)sv->height * 3);
  if (sv->rgb == NULL) {
    snprintf(msg, msg_size, "out of memory");
    mr_stageview_close(sv);
    return -1;
  }
  return 0;
}

void mr_stageview_close(mr_stageview *sv) {
  /* The renderer first: it frees its GL objects in the window's context. */
  mr_render_destroy(sv->render);
  mr_window_destroy(sv->window);
  mr_stage_destroy(sv->stage);
  free(sv->rgb);
  sv->render = NULL;
  sv->window = NULL;
  sv->stage = NULL;
  sv->rgb = NULL;
}

static mr_render_view current_view(const mr_stageview *sv) {
  mr_render_view v = mr_default_render_view(&sv->scene->stage);
  if (sv->camera >= 0) {
    const mr_camera_def *c = &sv->scene->stage.cameras[sv->camera];
    memcpy(v.eye, c->position, sizeof v.eye);
    memcpy(v.target, c->target, sizeof v.target);
    v.fov_deg = c->fov_deg;
  } else {
    mr_render_view_orbit(&v, &sv->orbit);
  }
  v.time_of_day = sv->time_of_day;
  v.show_rigging = sv->show_rigging;
  return v;
}

static int draw_list(mr_stageview *sv, const mr_draw_list *list, char *msg, size_t msg_size) {
  mr_render_view v = current_view(sv);
  const char *lines[MR_OSD_LINES];
  if (sv->show_osd) {
    for (size_t i = 0; i < sv->n_osd; i++) lines[i] = sv->osd[i];
    v.osd = lines;
    v.n_osd = sv->n_osd;
  }
  if (mr_render_draw(sv->render, list, &v) != MR_RENDER_OK) {
    snprintf(msg, msg_size, "the renderer failed to draw a frame");
    return -1;
  }
  return 0;
}

int mr_stageview_draw(mr_stageview *sv, const double *xyz, size_t n, char *msg, size_t msg_size) {
  const mr_draw_list *list = NULL;
  size_t use = n < sv->n_points ? n : sv->n_points;
  if (use == sv->n_points && mr_stage_update(sv->stage, xyz, use, &list) == MR_STAGE_OK)
    sv->last = list;
  /* A frame the stage refused (NaN) keeps the last good list on screen. */
  if (sv->last == NULL) {
    snprintf(msg, msg_size, "the stage refused the first frame's positions");
    return -1;
  }
  return draw_list(sv, sv->last, msg, msg_size);
}

int mr_stageview_redraw(mr_stageview *sv, char *msg, size_t msg_size) {
  if (sv->last == NULL) return 0;
  return draw_list(sv, sv->last, msg, msg_size);
}

const uint8_t *mr_stageview_read(mr_stageview *sv) {
  size_t size = (size_t)sv->width * (size_t)sv->height * 3;
  if (mr_render_read_rgb(sv->render, sv->rgb, size) != MR_RENDER_OK) return NULL;
  return sv->rgb;
}

int mr_stageview_find_camera(const mr_stageview *sv, const char *name) {
  for (int k = 0; k < sv->scene->stage.n_cameras; k++)
    if (strcmp(sv->scene->stage.cameras[k].name, name) == 0) return k;
  return -1;
}

void mr_stageview_pick_camera(mr_stageview *sv, int k) {
  if (k >= -1 && k < sv->scene->stage.n_cameras) sv->camera = k;
}

/* From a scene camera, the orbit starts where that camera stands. */
static void leave_scene_camera(mr_stageview *sv) {
  if (sv->camera < 0) return;
  sv->orbit = mr_orbit_of_camera(&sv->scene->stage.cameras[sv->camera], &sv->orbit);
  sv->camera = -1;
}

void mr_stageview_orbit(mr_stageview *sv, double d_azimuth, double d_elevation) {
  leave_scene_camera(sv);
  mr_orbit_turn(&sv->orbit, d_azimuth, d_elevation);
}

void mr_stageview_zoom(mr_stageview *sv, double steps) {
  leave_scene_camera(sv);
  mr_orbit_zoom(&sv->orbit, steps);
}

void mr_stageview_set_day(mr_stageview *sv, double time_of_day) {
  double d = fmod(time_of_day, 1.0);
  sv->time_of_day = d < 0 ? d + 1.0 : d;
}

void mr_stageview_next_material(mr_stageview *sv) {
  const mr_stage_def *def = mr_stage_get_def(sv->stage);
  sv->material_turn++;
  for (size_t i = 0; i < def->n_models; i++) {
    int n = def->models[i].n_materials;
    if (n > 1) mr_stage_set_material(sv->stage, i, sv->material_turn % n);
  }
}

void mr_stageview_osd_clear(mr_stageview *sv) {
  sv->n_osd = 0;
}

void mr_stageview_osd(mr_stageview *sv, const char *fmt, ...) {
  if (sv->n_osd >= MR_OSD_LINES) return;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(sv->osd[sv->n_osd++], MR_OSD_LINE_MAX, fmt, ap);
  va_end(ap);
}
