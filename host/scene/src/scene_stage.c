/* The stage's sections of a scene file: lights:, stage: and camera: into
 * the scene's mr_stage_def (models: is scene_models.c; what the physics
 * implies, strings and frames and spheres, is scene_rigging.c). Day and
 * night, the constellations and the lights are the paper's stage, §3.3. */
#include "scene_read.h"

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int mr_scene_read_rgb(mr_reader *r, const mr_ynode *node, const char *key, float out[3]) {
  double v[3];
  if (mr_scene_read_vec3(r, node, key, v) != 0) return -1;
  for (int i = 0; i < 3; i++) out[i] = (float)v[i];
  return 0;
}

/* An optional colour under key. */
static int read_rgb_at(mr_reader *r, const mr_ynode *map, const char *key, float out[3]) {
  const mr_ynode *v = mr_scene_yaml_get(map, key);
  return v == NULL ? 0 : mr_scene_read_rgb(r, v, key, out);
}

static int read_bool_at(mr_reader *r, const mr_ynode *map, const char *key, bool *out) {
  const mr_ynode *v = mr_scene_yaml_get(map, key);
  return v == NULL ? 0 : mr_scene_read_bool(r, v, key, out);
}

/* A sequence of at most max items, `what` naming them in the error. */
static int read_bounded(mr_reader *r, const mr_ynode *n, const char *what, size_t max) {
  if (mr_scene_read_seq(r, n, what) != 0) return -1;
  if (n->count > max)
    return mr_scene_read_fail(r, n->items[max], MR_SCENE_ERR_VALUE,
                              "expected at most %zu items in %s, got %zu", max, what, n->count);
  return 0;
}

static int read_sun(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "color",       "intensity",     "shadows",
                                      "shadow_size", "shadow_filter", NULL };
  static const mr_scene_field fields[] = {
    { "intensity", MR_SCENE_FIELD_NONNEG, offsetof(mr_lights_def, sun_intensity), 0, 0 },
    { "shadow_size", MR_SCENE_FIELD_INT, offsetof(mr_lights_def, shadow_size), 256, 8192 },
    { "shadow_filter", MR_SCENE_FIELD_INT, offsetof(mr_lights_def, shadow_filter), 1, 9 },
  };
  mr_lights_def *l = &r->scene->stage.lights;
  if (mr_scene_read_map(r, n, "lights.sun", keys) != 0 ||
      mr_scene_read_fields(r, n, fields, 3, l) != 0 ||
      read_rgb_at(r, n, "color", l->sun_color) != 0 ||
      read_bool_at(r, n, "shadows", &l->shadows) != 0)
    return -1;
  const mr_ynode *f = mr_scene_yaml_get(n, "shadow_filter");
  if (f != NULL && l->shadow_filter != 1 && l->shadow_filter != 4 && l->shadow_filter != 9)
    return mr_scene_read_fail(r, f, MR_SCENE_ERR_VALUE, "expected shadow_filter 1, 4 or 9, got %d",
                              l->shadow_filter);
  return 0;
}

static int read_spot(mr_reader *r, const mr_ynode *n, mr_spot_def *s) {
  static const char *const keys[] = { "position", "target", "angle", "color", "intensity", NULL };
  static const mr_scene_field fields[] = {
    { "position", MR_SCENE_FIELD_VEC3, offsetof(mr_spot_def, position), 0, 0 },
    { "target", MR_SCENE_FIELD_VEC3, offsetof(mr_spot_def, target), 0, 0 },
    { "angle", MR_SCENE_FIELD_POSITIVE, offsetof(mr_spot_def, angle_deg), 0, 0 },
    { "intensity", MR_SCENE_FIELD_NONNEG, offsetof(mr_spot_def, intensity), 0, 0 },
  };
  *s = mr_default_spot_def();
  s->pos = (mr_stage_pos){ n->line, n->column };
  if (mr_scene_read_map(r, n, "a spot light", keys) != 0 ||
      mr_scene_read_fields(r, n, fields, 4, s) != 0 || read_rgb_at(r, n, "color", s->color) != 0)
    return -1;
  return 0;
}

static int read_lights(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "ambient", "sun", "spots", NULL };
  mr_lights_def *l = &r->scene->stage.lights;
  const mr_ynode *v;
  if (mr_scene_read_map(r, n, "lights", keys) != 0 ||
      read_rgb_at(r, n, "ambient", l->ambient) != 0 ||
      mr_scene_read_optional(r, n, "sun", read_sun) != 0)
    return -1;
  if ((v = mr_scene_yaml_get(n, "spots")) == NULL) return 0;
  if (read_bounded(r, v, "lights.spots", MR_STAGE_MAX_SPOTS) != 0) return -1;
  for (size_t i = 0; i < v->count; i++) {
    if (read_spot(r, v->items[i], &l->spots[i]) != 0) return -1;
    l->n_spots = (int)i + 1;
  }
  return 0;
}

/* stage.size: [width, height] in pixels. */
static int read_size(mr_reader *r, const mr_ynode *v) {
  mr_stage_def *d = &r->scene->stage;
  if (v->kind != MR_YNODE_SEQ || v->count != 2)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA,
                              "expected [width, height] in pixels for stage.size");
  long wh[2];
  for (int i = 0; i < 2; i++) {
    if (mr_scene_read_long(r, v->items[i], "stage.size", &wh[i]) != 0) return -1;
    if (wh[i] < 16 || wh[i] > 16384)
      return mr_scene_read_fail(r, v->items[i], MR_SCENE_ERR_VALUE,
                                "expected stage.size between 16 and 16384 pixels, got %ld", wh[i]);
  }
  d->width = (int)wh[0];
  d->height = (int)wh[1];
  return 0;
}

/* floor: and backdrop: are false, true, or a mapping of their settings. */
static int read_switch(mr_reader *r, const mr_ynode *v, const char *what, bool *on) {
  if (v->kind == MR_YNODE_MAP) {
    *on = true;
    return 1;
  }
  return mr_scene_read_bool(r, v, what, on);
}

static int read_floor_and_backdrop(mr_reader *r, const mr_ynode *n) {
  static const char *const floor_keys[] = { "size", "color", "color2", "board", NULL };
  static const char *const back_keys[] = { "distance", "color", NULL };
  static const mr_scene_field size = { "size", MR_SCENE_FIELD_POSITIVE,
                                       offsetof(mr_stage_def, floor_size), 0, 0 };
  static const mr_scene_field dist = { "distance", MR_SCENE_FIELD_POSITIVE,
                                       offsetof(mr_stage_def, backdrop_distance), 0, 0 };
  static const mr_scene_field board = { "board", MR_SCENE_FIELD_POSITIVE,
                                        offsetof(mr_stage_def, board_width), 0, 0 };
  mr_stage_def *d = &r->scene->stage;
  const mr_ynode *v = mr_scene_yaml_get(n, "floor");
  int rc;
  if (v != NULL && (rc = read_switch(r, v, "stage.floor", &d->floor)) != 0) {
    if (rc < 0 || mr_scene_read_map(r, v, "stage.floor", floor_keys) != 0 ||
        mr_scene_read_field(r, v, &size, d) != 0 || mr_scene_read_field(r, v, &board, d) != 0 ||
        read_rgb_at(r, v, "color", d->floor_color) != 0 ||
        read_rgb_at(r, v, "color2", d->floor_color2) != 0)
      return -1;
  }
  v = mr_scene_yaml_get(n, "backdrop");
  if (v != NULL && (rc = read_switch(r, v, "stage.backdrop", &d->backdrop)) != 0) {
    if (rc < 0 || mr_scene_read_map(r, v, "stage.backdrop", back_keys) != 0 ||
        mr_scene_read_field(r, v, &dist, d) != 0 ||
        read_rgb_at(r, v, "color", d->backdrop_color) != 0)
      return -1;
  }
  return 0;
}

/* The theater's set: stage.proscenium, .wings and .footlights, each
 * false, true, or a mapping of its settings (which turns it on); and
 * stage.bridge, true or false. */
static int read_proscenium(mr_reader *r, const mr_ynode *v, mr_stage_def *d) {
  static const char *const keys[] = {
    "width", "height", "distance", "middle", "color", "trim", NULL
  };
  static const mr_scene_field fields[] = {
    { "width", MR_SCENE_FIELD_POSITIVE, offsetof(mr_stage_def, set_width), 0, 0 },
    { "height", MR_SCENE_FIELD_POSITIVE, offsetof(mr_stage_def, set_height), 0, 0 },
    { "distance", MR_SCENE_FIELD_POSITIVE, offsetof(mr_stage_def, set_front), 0, 0 },
    { "middle", MR_SCENE_FIELD_NUMBER, offsetof(mr_stage_def, set_middle), 0, 0 },
  };
  int rc = read_switch(r, v, "stage.proscenium", &d->proscenium);
  if (rc <= 0) return rc;
  if (mr_scene_read_map(r, v, "stage.proscenium", keys) != 0 ||
      mr_scene_read_fields(r, v, fields, 4, d) != 0 ||
      read_rgb_at(r, v, "color", d->proscenium_color) != 0 ||
      read_rgb_at(r, v, "trim", d->trim_color) != 0)
    return -1;
  return 0;
}

static int read_set(mr_reader *r, const mr_ynode *n) {
  static const char *const wing_keys[] = { "color", NULL };
  static const char *const foot_keys[] = { "color", "intensity", NULL };
  static const mr_scene_field intensity = { "intensity", MR_SCENE_FIELD_NONNEG,
                                            offsetof(mr_stage_def, footlight_intensity), 0, 0 };
  mr_stage_def *d = &r->scene->stage;
  const mr_ynode *v;
  int rc;
  if ((v = mr_scene_yaml_get(n, "proscenium")) != NULL && read_proscenium(r, v, d) != 0) return -1;
  v = mr_scene_yaml_get(n, "wings");
  if (v != NULL && (rc = read_switch(r, v, "stage.wings", &d->wings)) != 0) {
    if (rc < 0 || mr_scene_read_map(r, v, "stage.wings", wing_keys) != 0 ||
        read_rgb_at(r, v, "color", d->wing_color) != 0)
      return -1;
  }
  v = mr_scene_yaml_get(n, "footlights");
  if (v != NULL && (rc = read_switch(r, v, "stage.footlights", &d->footlights)) != 0) {
    if (rc < 0 || mr_scene_read_map(r, v, "stage.footlights", foot_keys) != 0 ||
        mr_scene_read_field(r, v, &intensity, d) != 0 ||
        read_rgb_at(r, v, "color", d->footlight_color) != 0)
      return -1;
  }
  return read_bool_at(r, n, "bridge", &d->bridge);
}

/* [azimuth, elevation, brightness] into the scene's star list. */
static int read_star(mr_reader *r, const mr_ynode *v, mr_star *out) {
  static const char *const what[3] = { "azimuth", "star elevation", "brightness" };
  if (v->kind != MR_YNODE_SEQ || v->count != 3)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA,
                              "expected a star as [azimuth, elevation, brightness]");
  double x[3];
  for (int i = 0; i < 3; i++)
    if (mr_scene_read_number(r, v->items[i], what[i], &x[i]) != 0) return -1;
  *out = mr_stage_star_at(x[0], x[1], x[2]);
  return 0;
}

/* stage.constellations: the scene's own sky, instead of the built-in one. */
static int read_constellations(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "name", "stars", NULL };
  enum { MAX_STARS = 100000 };
  mr_stage_def *d = &r->scene->stage;
  if (mr_scene_read_seq(r, n, "stage.constellations") != 0) return -1;
  for (size_t c = 0; c < n->count; c++) {
    char name[MR_SCENE_NAME_MAX];
    const mr_ynode *it = n->items[c], *stars;
    if (mr_scene_read_named(r, it, "a constellation", keys, "a constellation", name) == NULL ||
        (stars = mr_scene_read_need(r, it, "stars", "a constellation")) == NULL ||
        mr_scene_read_seq(r, stars, "a constellation's stars") != 0)
      return -1;
    if (d->n_stars + stars->count > MAX_STARS)
      return mr_scene_read_fail(r, stars, MR_SCENE_ERR_VALUE, "expected at most %d stars in all",
                                MAX_STARS);
    mr_star *list =
        realloc((mr_star *)d->star_list, (d->n_stars + stars->count + 1) * sizeof *list);
    if (list == NULL) return mr_scene_read_fail(r, stars, MR_SCENE_ERR_NOMEM, "out of memory");
    d->star_list = list;
    for (size_t i = 0; i < stars->count; i++, d->n_stars++)
      if (read_star(r, stars->items[i], &list[d->n_stars]) != 0) return -1;
  }
  return 0;
}

static int read_sky(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "day", "night", "stars", NULL };
  mr_stage_def *d = &r->scene->stage;
  if (mr_scene_read_map(r, n, "stage.sky", keys) != 0 ||
      read_rgb_at(r, n, "day", d->sky_day) != 0 || read_rgb_at(r, n, "night", d->sky_night) != 0 ||
      read_bool_at(r, n, "stars", &d->stars) != 0)
    return -1;
  return 0;
}

/* stage.strings: {show, color}. */
static int read_rigging(mr_reader *r, const mr_ynode *n, const char *key, bool *show,
                        float rgb[3]) {
  static const char *const keys[] = { "show", "color", NULL };
  const mr_ynode *v = mr_scene_yaml_get(n, key);
  if (v == NULL) return 0;
  char what[32];
  snprintf(what, sizeof what, "stage.%s", key);
  if (mr_scene_read_map(r, v, what, keys) != 0 || read_bool_at(r, v, "show", show) != 0 ||
      read_rgb_at(r, v, "color", rgb) != 0)
    return -1;
  return 0;
}

static const char *style_word(int i) {
  return mr_frame_style_name((mr_frame_style)i);
}

static int style_parse(const char *word, int *out) {
  mr_frame_style st;
  if (mr_frame_style_parse(word, &st) != 0) return -1;
  *out = (int)st;
  return 0;
}

/* stage.frames: {show, color, style, thickness}; a solid frame's bars
 * are laid by scene_rigging.c. */
static int read_frames(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "show", "color", "style", "thickness", NULL };
  static const mr_scene_field thick = { "thickness", MR_SCENE_FIELD_POSITIVE,
                                        offsetof(mr_stage_def, frame_thickness), 0, 0 };
  mr_stage_def *d = &r->scene->stage;
  int style = (int)d->frame_style;
  if (mr_scene_read_map(r, n, "stage.frames", keys) != 0 ||
      read_bool_at(r, n, "show", &d->show_frames) != 0 ||
      read_rgb_at(r, n, "color", d->frame_color) != 0 ||
      mr_scene_read_choice(r, n, "style", style_parse, style_word, &style) != 0 ||
      mr_scene_read_field(r, n, &thick, d) != 0)
    return -1;
  d->frame_style = (mr_frame_style)style;
  return 0;
}

static int read_stage_section(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "size", "time_of_day", "floor", "backdrop", "sky", "strings",
                                      "frames", "spheres", "constellations",
                                      /* the theater's set */
                                      "proscenium", "wings", "footlights", "bridge", "curtain",
                                      "follow_spot", NULL };
  static const mr_scene_field tod = { "time_of_day", MR_SCENE_FIELD_UNIT,
                                      offsetof(mr_stage_def, time_of_day), 0, 0 };
  mr_stage_def *d = &r->scene->stage;
  d->pos = (mr_stage_pos){ n->line, n->column };
  if (mr_scene_read_map(r, n, "stage", keys) != 0 ||
      mr_scene_read_optional(r, n, "size", read_size) != 0 ||
      mr_scene_read_field(r, n, &tod, d) != 0 || read_floor_and_backdrop(r, n) != 0 ||
      read_set(r, n) != 0 || mr_scene_read_optional(r, n, "sky", read_sky) != 0 ||
      mr_scene_read_optional(r, n, "constellations", read_constellations) != 0 ||
      read_rigging(r, n, "strings", &d->show_strings, d->string_color) != 0 ||
      mr_scene_read_optional(r, n, "frames", read_frames) != 0 ||
      read_bool_at(r, n, "spheres", &d->show_spheres) != 0 || mr_scene_read_curtain(r, n) != 0)
    return -1;
  return 0;
}

static int read_orbit(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "target", "distance", "azimuth", "elevation", "fov", NULL };
  static const mr_scene_field fields[] = {
    { "target", MR_SCENE_FIELD_VEC3, offsetof(mr_stage_def, orbit_target), 0, 0 },
    { "distance", MR_SCENE_FIELD_POSITIVE, offsetof(mr_stage_def, orbit_distance), 0, 0 },
    { "azimuth", MR_SCENE_FIELD_NUMBER, offsetof(mr_stage_def, orbit_azimuth_deg), 0, 0 },
    { "elevation", MR_SCENE_FIELD_NUMBER, offsetof(mr_stage_def, orbit_elevation_deg), 0, 0 },
    { "fov", MR_SCENE_FIELD_POSITIVE, offsetof(mr_stage_def, fov_deg), 0, 0 },
  };
  if (mr_scene_read_map(r, n, "camera.orbit", keys) != 0) return -1;
  return mr_scene_read_fields(r, n, fields, 5, &r->scene->stage);
}

/* A view's up is +y: one standing on its target, or straight above or
 * below it, gives the camera no direction or no sideways axis, and the
 * renderer would refuse every frame of it. The bound is relative, as in
 * the renderer's own check. */
static int view_looks(mr_reader *r, const mr_ynode *n, const mr_camera_def *c) {
  const mr_ynode *at = mr_scene_yaml_get(n, "target");
  if (at == NULL) at = mr_scene_yaml_get(n, "position");
  if (at == NULL) at = n;
  double d[3], dd = 0;
  for (int i = 0; i < 3; i++) {
    d[i] = c->target[i] - c->position[i];
    dd += d[i] * d[i];
  }
  if (dd == 0)
    return mr_scene_read_fail(r, at, MR_SCENE_ERR_VALUE,
                              "view '%s' has its target at its position; expected a target "
                              "away from the camera",
                              c->name);
  if (d[0] * d[0] + d[2] * d[2] <= 1e-12 * dd)
    return mr_scene_read_fail(r, at, MR_SCENE_ERR_VALUE,
                              "view '%s' looks straight %s; expected a target off the vertical "
                              "through its position (a view's up is +y)",
                              c->name, d[1] > 0 ? "up" : "down");
  return 0;
}

static int read_view(mr_reader *r, const mr_ynode *n, int k) {
  static const char *const keys[] = { "name", "position", "target", "fov", NULL };
  static const mr_scene_field fields[] = {
    { "position", MR_SCENE_FIELD_VEC3, offsetof(mr_camera_def, position), 0, 0 },
    { "target", MR_SCENE_FIELD_VEC3, offsetof(mr_camera_def, target), 0, 0 },
    { "fov", MR_SCENE_FIELD_POSITIVE, offsetof(mr_camera_def, fov_deg), 0, 0 },
  };
  mr_stage_def *d = &r->scene->stage;
  mr_camera_def *c = &d->cameras[k];
  *c = mr_default_camera_def();
  c->pos = (mr_stage_pos){ n->line, n->column };
  const mr_ynode *name = mr_scene_read_named(r, n, "a camera view", keys, "a view", c->name);
  if (name == NULL || mr_scene_read_fields(r, n, fields, 3, c) != 0 || view_looks(r, n, c) != 0)
    return -1;
  for (int j = 0; j < k; j++)
    if (strcmp(d->cameras[j].name, c->name) == 0)
      return mr_scene_read_fail(r, name, MR_SCENE_ERR_VALUE,
                                "a second view named '%s' (the first is at line %d); expected "
                                "unique names",
                                c->name, d->cameras[j].pos.line);
  return 0;
}

/* `camera: follow` is `camera: {follow: true}`. */
static int read_camera(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "orbit", "views", "follow", "facing", NULL };
  static const mr_scene_field fields[] = {
    { "facing", MR_SCENE_FIELD_NUMBER, offsetof(mr_stage_def, facing_deg), 0, 0 },
  };
  mr_stage_def *d = &r->scene->stage;
  const mr_ynode *v;
  if (n->kind == MR_YNODE_SCALAR) {
    if (n->quoted || strcmp(n->text, "follow") != 0)
      return mr_scene_read_fail(r, n, MR_SCENE_ERR_VALUE,
                                "expected follow or a mapping for camera, got '%s'", n->text);
    d->follow = true;
    return 0;
  }
  if (mr_scene_read_map(r, n, "camera", keys) != 0 ||
      mr_scene_read_fields(r, n, fields, 1, d) != 0 ||
      read_bool_at(r, n, "follow", &d->follow) != 0 ||
      mr_scene_read_optional(r, n, "orbit", read_orbit) != 0)
    return -1;
  if ((v = mr_scene_yaml_get(n, "views")) == NULL) return 0;
  if (read_bounded(r, v, "camera.views", MR_STAGE_MAX_CAMERAS) != 0) return -1;
  for (size_t i = 0; i < v->count; i++) {
    if (read_view(r, v->items[i], (int)i) != 0) return -1;
    d->n_cameras = (int)i + 1;
  }
  return 0;
}

int mr_scene_read_stage(mr_reader *r, const mr_ynode *root) {
  if (mr_scene_read_optional(r, root, "lights", read_lights) != 0 ||
      mr_scene_read_optional(r, root, "stage", read_stage_section) != 0 ||
      mr_scene_read_optional(r, root, "camera", read_camera) != 0 ||
      mr_scene_read_optional(r, root, "models", mr_scene_read_models) != 0)
    return -1;
  return mr_scene_stage_rigging(r, root);
}

void mr_scene_stage_free(mr_scene *s) {
  mr_stage_def *d = &s->stage;
  for (size_t i = 0; d->models != NULL && i < d->n_models; i++) {
    free((int *)d->models[i].bones);
    free((double *)d->models[i].bones_rest);
  }
  free(d->models);
  free((mr_star *)d->star_list);
  free((int *)d->strings);
  free((int *)d->frame_points);
  free((int *)d->frame_point_count);
  d->models = NULL;
  d->star_list = NULL;
  d->strings = d->frame_points = d->frame_point_count = NULL;
  d->n_models = d->n_stars = d->n_strings = d->n_frames = 0;
}
