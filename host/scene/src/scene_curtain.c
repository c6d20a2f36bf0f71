/* stage.curtain and stage.follow_spot: the moving part of the set, each
 * false, true, or a mapping of its settings (which turns it on). */
#include "scene_read.h"

#include <stddef.h>

/* false, true, or a mapping (on): 1 for a mapping to read, 0, or -1. */
static int read_switch(mr_reader *r, const mr_ynode *v, const char *what, bool *on) {
  if (v->kind == MR_YNODE_MAP) {
    *on = true;
    return 1;
  }
  return mr_scene_read_bool(r, v, what, on);
}

static int read_color(mr_reader *r, const mr_ynode *map, float out[3]) {
  const mr_ynode *v = mr_scene_yaml_get(map, "color");
  return v == NULL ? 0 : mr_scene_read_rgb(r, v, "color", out);
}

static int read_show(mr_reader *r, const mr_ynode *map, bool *on) {
  const mr_ynode *v = mr_scene_yaml_get(map, "show");
  return v == NULL ? 0 : mr_scene_read_bool(r, v, "show", on);
}

static int read_curtain(mr_reader *r, const mr_ynode *v) {
  static const char *const keys[] = { "show",     "color", "open",   "close",
                                      "distance", "width", "height", NULL };
  static const mr_scene_field fields[] = {
    { "open", MR_SCENE_FIELD_NONNEG, offsetof(mr_curtain_def, open_s), 0, 0 },
    { "close", MR_SCENE_FIELD_NONNEG, offsetof(mr_curtain_def, close_s), 0, 0 },
    { "distance", MR_SCENE_FIELD_POSITIVE, offsetof(mr_curtain_def, distance), 0, 0 },
    { "width", MR_SCENE_FIELD_POSITIVE, offsetof(mr_curtain_def, width), 0, 0 },
    { "height", MR_SCENE_FIELD_POSITIVE, offsetof(mr_curtain_def, height), 0, 0 },
  };
  mr_curtain_def *c = &r->scene->stage.curtain;
  int rc = read_switch(r, v, "stage.curtain", &c->show);
  if (rc <= 0) return rc;
  if (mr_scene_read_map(r, v, "stage.curtain", keys) != 0 || read_show(r, v, &c->show) != 0 ||
      read_color(r, v, c->color) != 0 || mr_scene_read_fields(r, v, fields, 5, c) != 0)
    return -1;
  return 0;
}

static int read_follow_spot(mr_reader *r, const mr_ynode *v) {
  static const char *const keys[] = { "show", "position", "angle", "color", "intensity", NULL };
  static const mr_scene_field fields[] = {
    { "position", MR_SCENE_FIELD_VEC3, offsetof(mr_follow_spot_def, position), 0, 0 },
    { "angle", MR_SCENE_FIELD_POSITIVE, offsetof(mr_follow_spot_def, angle_deg), 0, 0 },
    { "intensity", MR_SCENE_FIELD_NONNEG, offsetof(mr_follow_spot_def, intensity), 0, 0 },
  };
  mr_follow_spot_def *f = &r->scene->stage.follow_spot;
  int rc = read_switch(r, v, "stage.follow_spot", &f->show);
  if (rc <= 0) return rc;
  if (mr_scene_read_map(r, v, "stage.follow_spot", keys) != 0 || read_show(r, v, &f->show) != 0 ||
      read_color(r, v, f->color) != 0 || mr_scene_read_fields(r, v, fields, 3, f) != 0)
    return -1;
  return 0;
}

int mr_scene_read_curtain(mr_reader *r, const mr_ynode *stage) {
  const mr_ynode *v;
  if ((v = mr_scene_yaml_get(stage, "curtain")) != NULL && read_curtain(r, v) != 0) return -1;
  if ((v = mr_scene_yaml_get(stage, "follow_spot")) != NULL && read_follow_spot(r, v) != 0)
    return -1;
  return 0;
}
