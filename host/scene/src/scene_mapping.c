/* The `mapping:` section: how a glove's five values move the control frame
 * (host/control). A list of named mappings, the first used at the start;
 * without the section a scene with a control frame gets the paper's default
 * mapping (mr_default_mapping_def). A mapping's neutral pose is the start
 * pose of the frame it moves (control.pose; the first frame's here, each
 * frame's own in the theater), so a relaxed hand holds the puppet where the
 * scene put it. */
#include "scene_read.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#define AXIS(field) offsetof(mr_axis_def, field)

static int read_axis(mr_reader *r, const mr_ynode *n, mr_dof dof, mr_axis_def *a) {
  static const char *const keys[] = { "channel", "range", "invert", "neutral", "dead_zone", NULL };
  static const mr_scene_field fields[] = {
    { "channel", MR_SCENE_FIELD_INT, AXIS(channel), 0, MR_CONTROL_CHANNELS - 1 },
    { "neutral", MR_SCENE_FIELD_UNIT, AXIS(neutral), 0, 0 },
    { "dead_zone", MR_SCENE_FIELD_NONNEG, AXIS(dead_zone), 0, 0 }
  };
  char what[48];
  snprintf(what, sizeof what, "mapping axis %s", mr_dof_name(dof));
  const mr_ynode *v;
  if (mr_scene_read_map(r, n, what, keys) != 0 ||
      mr_scene_read_need(r, n, "channel", what) == NULL ||
      mr_scene_read_fields(r, n, fields, sizeof fields / sizeof fields[0], a) != 0)
    return -1;
  if ((v = mr_scene_yaml_get(n, "dead_zone")) != NULL && a->dead_zone > 0.5)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected dead_zone between 0 and 0.5, got %g", a->dead_zone);
  if ((v = mr_scene_yaml_get(n, "invert")) != NULL &&
      mr_scene_read_bool(r, v, "invert", &a->invert) != 0)
    return -1;
  if ((v = mr_scene_yaml_get(n, "range")) != NULL) {
    if (v->kind != MR_YNODE_SEQ || v->count != 2)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA,
                                "expected [low, high] for range (degrees for a turn, metres for a "
                                "move)");
    const char *key = dof <= MR_DOF_TURN_Z ? "rotation" : "offset";
    if (mr_scene_read_number(r, v->items[0], key, &a->low) != 0 ||
        mr_scene_read_number(r, v->items[1], key, &a->high) != 0)
      return -1;
  }
  return 0;
}

static int read_axes(mr_reader *r, const mr_ynode *n, mr_mapping_def *m) {
  if (n->kind != MR_YNODE_MAP)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_SCHEMA,
                              "expected a mapping of axes (turn_x: {channel: 1, ...}) for axes");
  /* The axes a mapping lists are all it drives. */
  for (int a = 0; a < MR_DOF_COUNT; a++) m->axes[a].channel = -1;
  for (size_t i = 0; i < n->count; i++) {
    const mr_ynode *key = n->items[2 * i], *val = n->items[2 * i + 1];
    mr_dof dof;
    if (mr_dof_parse(key->text, &dof) != 0)
      return mr_scene_read_fail(r, key, MR_SCENE_ERR_SCHEMA,
                                "unknown axis '%s'; expected one of: turn_x, turn_y, turn_z, "
                                "move_x, move_y, move_z",
                                key->text);
    mr_axis_def *a = &m->axes[dof];
    *a = mr_default_mapping_def().axes[dof]; /* its range, neutral and dead zone */
    if (read_axis(r, val, dof, a) != 0) return -1;
  }
  return 0;
}

static int read_mapping(mr_reader *r, const mr_ynode *it, void *slot) {
  static const char *const keys[] = { "name", "axes", "filter", "stuck_after", NULL };
  static const char *const filter_keys[] = { "min_cutoff", "beta", "d_cutoff", NULL };
  static const mr_scene_field filter_fields[] = {
    { "min_cutoff", MR_SCENE_FIELD_POSITIVE, offsetof(mr_mapping_def, min_cutoff), 0, 0 },
    { "beta", MR_SCENE_FIELD_NONNEG, offsetof(mr_mapping_def, beta), 0, 0 },
    { "d_cutoff", MR_SCENE_FIELD_POSITIVE, offsetof(mr_mapping_def, d_cutoff), 0, 0 }
  };
  static const mr_scene_field stuck = { "stuck_after", MR_SCENE_FIELD_POSITIVE,
                                        offsetof(mr_mapping_def, stuck_after), 0, 0 };
  mr_scene_mapping *sm = slot;
  mr_mapping_def *m = &sm->def;
  *m = mr_default_mapping_def();
  m->neutral = r->scene->n_frames > 0 ? r->scene->frames[0].pose : mr_pose_identity();
  char name[MR_SCENE_NAME_MAX];
  const mr_ynode *v = mr_scene_read_named(r, it, "a mapping", keys, "mapping name", name);
  if (v == NULL) return -1;
  if (strlen(name) >= sizeof m->name)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected a mapping name of at most %zu characters",
                              sizeof m->name - 1);
  memcpy(m->name, name, strlen(name) + 1);
  for (size_t j = 0; j + 1 < r->scene->n_mappings; j++)
    if (strcmp(r->scene->mappings[j].def.name, m->name) == 0)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                                "expected a unique mapping name, '%s' is already declared",
                                m->name);
  sm->pos = mr_scene_read_pos(it);
  if ((v = mr_scene_yaml_get(it, "axes")) != NULL && read_axes(r, v, m) != 0) return -1;
  if ((v = mr_scene_yaml_get(it, "filter")) != NULL &&
      (mr_scene_read_map(r, v, "mapping filter", filter_keys) != 0 ||
       mr_scene_read_fields(r, v, filter_fields, 3, m) != 0))
    return -1;
  return mr_scene_read_field(r, it, &stuck, m);
}

int mr_scene_read_mappings(mr_reader *r, const mr_ynode *n) {
  mr_scene *s = r->scene;
  if (mr_scene_read_need_effect(r, n, MR_EFFECT_FRAMES, "a glove mapping is") != 0) return -1;
  if (n->kind == MR_YNODE_SEQ && n->count > MR_CONTROL_MAX_MAPPINGS)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_VALUE, "expected at most %d mappings, got %zu",
                              MR_CONTROL_MAX_MAPPINGS, n->count);
  if (n->kind == MR_YNODE_SEQ && n->count == 0)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_VALUE, "expected at least one mapping");
  return mr_scene_read_items(r, n, "mapping", 0, NULL, sizeof *s->mappings, (void **)&s->mappings,
                             &s->n_mappings, read_mapping);
}
