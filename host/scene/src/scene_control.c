/* The control frame (§6.1-6.2): points the strings hang from, its start
 * pose, and a scripted track that stands in for the glove. The frame is
 * moved by setting its pose (§6.2, approach 1), so the track only has to
 * give a pose for every time. */
#include "scene_read.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static int read_pose(mr_reader *r, const mr_ynode *n, const char *what, mr_scene_pose *p) {
  if (mr_scene_read_vec3_key(r, n, "position", p->position) != 0 ||
      mr_scene_read_vec3_key(r, n, "rotation", p->rotation_deg) != 0)
    return -1;
  (void)what;
  return 0;
}

static int read_points(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"name", "offset", NULL};
  mr_scene *s = r->scene;
  if (mr_scene_read_seq(r, n, "control.points") != 0)
    return -1;
  s->control_points = calloc(n->count ? n->count : 1, sizeof *s->control_points);
  if (s->control_points == NULL)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_NOMEM, "out of memory");
  for (size_t i = 0; i < n->count; i++) {
    const mr_ynode *it = n->items[i];
    mr_scene_control_point *c = &s->control_points[i];
    const mr_ynode *v;
    if (mr_scene_read_map(r, it, "a control point", keys) != 0)
      return -1;
    if ((v = mr_scene_read_need(r, it, "name", "a control point")) == NULL ||
        mr_scene_read_name(r, v, "control point name", c->name) != 0)
      return -1;
    if (mr_scene_find_particle(s, c->name) != (size_t)-1)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                     "expected a control point name unused by particles, '%s' is a particle",
                     c->name);
    if (mr_scene_find_control_point(s, c->name) != (size_t)-1)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                     "expected a unique control point name, '%s' is already declared",
                     c->name);
    if ((v = mr_scene_read_need(r, it, "offset", "a control point")) == NULL ||
        mr_scene_read_vec3(r, v, "offset", c->offset) != 0)
      return -1;
    c->pos = mr_scene_read_pos(it);
    s->n_control_points = i + 1;
  }
  return 0;
}

static int read_keyframes(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"t", "position", "rotation", NULL};
  mr_scene *s = r->scene;
  mr_scene_track *tr = &s->track;
  if (mr_scene_read_seq(r, n, "control.track.keyframes") != 0)
    return -1;
  if (n->count == 0)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_VALUE, "expected at least one keyframe");
  tr->keys = calloc(n->count, sizeof *tr->keys);
  if (tr->keys == NULL)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_NOMEM, "out of memory");
  tr->kind = MR_SCENE_TRACK_KEYFRAMES;
  for (size_t i = 0; i < n->count; i++) {
    const mr_ynode *it = n->items[i];
    mr_scene_keyframe *k = &tr->keys[i];
    const mr_ynode *v;
    if (mr_scene_read_map(r, it, "a keyframe", keys) != 0)
      return -1;
    if ((v = mr_scene_read_need(r, it, "t", "a keyframe")) == NULL || mr_scene_read_number(r, v, "t", &k->t) != 0)
      return -1;
    if (k->t < 0)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected t >= 0, got %g", k->t);
    if (i > 0 && !(k->t > tr->keys[i - 1].t))
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                     "expected keyframe times in increasing order, got %g after %g", k->t,
                     tr->keys[i - 1].t);
    k->pose = s->control_pose;
    if (read_pose(r, it, "a keyframe", &k->pose) != 0)
      return -1;
    k->pos = mr_scene_read_pos(it);
    tr->n_keys = i + 1;
  }
  return 0;
}

static int read_oscillate(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"amplitude", "rotation", "frequency", "phase",
                                     "start",     "ramp",     NULL};
  mr_scene_track *tr = &r->scene->track;
  if (mr_scene_read_map(r, n, "control.track.oscillate", keys) != 0)
    return -1;
  tr->kind = MR_SCENE_TRACK_OSCILLATE;
  if (mr_scene_read_need(r, n, "frequency", "control.track.oscillate") == NULL)
    return -1;
  if (mr_scene_read_vec3_key(r, n, "amplitude", tr->amplitude) != 0 ||
      mr_scene_read_vec3_key(r, n, "rotation", tr->amplitude_deg) != 0 ||
      mr_scene_read_positive_key(r, n, "frequency", &tr->frequency_hz) != 0 ||
      mr_scene_read_number_key(r, n, "phase", &tr->phase_deg) != 0 ||
      mr_scene_read_nonneg_key(r, n, "start", &tr->start) != 0 ||
      mr_scene_read_nonneg_key(r, n, "ramp", &tr->ramp) != 0)
    return -1;
  return 0;
}

static int read_track(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"keyframes", "interpolation", "oscillate", NULL};
  if (mr_scene_read_map(r, n, "control.track", keys) != 0)
    return -1;
  const mr_ynode *k = mr_scene_yaml_get(n, "keyframes");
  const mr_ynode *o = mr_scene_yaml_get(n, "oscillate");
  const mr_ynode *v = mr_scene_yaml_get(n, "interpolation");
  if (k != NULL && o != NULL)
    return mr_scene_read_fail(r, o, MR_SCENE_ERR_SCHEMA,
                   "expected either keyframes or oscillate in control.track, not both");
  if (k == NULL && o == NULL)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_SCHEMA,
                   "expected keyframes or oscillate in control.track");
  if (v != NULL) {
    if (k == NULL)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA, "interpolation applies to keyframes only");
    if (v->kind == MR_YNODE_SCALAR && strcmp(v->text, "linear") == 0)
      r->scene->track.linear = true;
    else if (!(v->kind == MR_YNODE_SCALAR && strcmp(v->text, "smooth") == 0))
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected interpolation linear or smooth");
  }
  return k != NULL ? read_keyframes(r, k) : read_oscillate(r, o);
}

int mr_scene_read_control(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = {"points", "pose", "track", NULL};
  static const char *const pose_keys[] = {"position", "rotation", NULL};
  if (mr_scene_read_map(r, n, "physics.control", keys) != 0)
    return -1;
  const mr_ynode *v = mr_scene_read_need(r, n, "points", "physics.control");
  if (v == NULL || read_points(r, v) != 0)
    return -1;
  if ((v = mr_scene_yaml_get(n, "pose")) != NULL) {
    if (mr_scene_read_map(r, v, "control.pose", pose_keys) != 0 ||
        read_pose(r, v, "control.pose", &r->scene->control_pose) != 0)
      return -1;
  }
  if ((v = mr_scene_yaml_get(n, "track")) != NULL && read_track(r, v) != 0)
    return -1;
  return 0;
}

static void lerp_pose(const mr_scene_pose *a, const mr_scene_pose *b, double u,
                      mr_scene_pose *o) {
  for (int i = 0; i < 3; i++) {
    o->position[i] = a->position[i] + (b->position[i] - a->position[i]) * u;
    o->rotation_deg[i] = a->rotation_deg[i] + (b->rotation_deg[i] - a->rotation_deg[i]) * u;
  }
}

void mr_scene_control_pose_at(const mr_scene *s, double t, mr_scene_pose *out) {
  const mr_scene_track *tr = &s->track;
  *out = s->control_pose;
  if (tr->kind == MR_SCENE_TRACK_KEYFRAMES && tr->n_keys > 0) {
    const mr_scene_keyframe *k = tr->keys;
    size_t n = tr->n_keys;
    if (t <= k[0].t) {
      *out = k[0].pose;
      return;
    }
    if (t >= k[n - 1].t) {
      *out = k[n - 1].pose;
      return;
    }
    size_t i = 1;
    while (k[i].t < t)
      i++;
    double u = (t - k[i - 1].t) / (k[i].t - k[i - 1].t);
    /* Smoothstep eases in and out of each key so the frame's velocity is
     * continuous: a pose jump is a hard case of its own (§7), not the
     * default. */
    if (!tr->linear)
      u = u * u * (3.0 - 2.0 * u);
    lerp_pose(&k[i - 1].pose, &k[i].pose, u, out);
  } else if (tr->kind == MR_SCENE_TRACK_OSCILLATE && t > tr->start) {
    double ramp = tr->ramp > 0 ? fmin(1.0, (t - tr->start) / tr->ramp) : 1.0;
    double w = sin(2.0 * PI * tr->frequency_hz * (t - tr->start) + tr->phase_deg * PI / 180.0);
    for (int i = 0; i < 3; i++) {
      out->position[i] += ramp * tr->amplitude[i] * w;
      out->rotation_deg[i] += ramp * tr->amplitude_deg[i] * w;
    }
  }
}

void mr_scene_control_point_world(const mr_scene *s, size_t i, const mr_scene_pose *p,
                                  double out[3]) {
  const double *o = s->control_points[i].offset;
  double ax = p->rotation_deg[0] * PI / 180.0;
  double ay = p->rotation_deg[1] * PI / 180.0;
  double az = p->rotation_deg[2] * PI / 180.0;
  /* x first, then y, then z: v' = Rz Ry Rx v. */
  double x = o[0], y = o[1], z = o[2];
  double y1 = y * cos(ax) - z * sin(ax), z1 = y * sin(ax) + z * cos(ax);
  double x2 = x * cos(ay) + z1 * sin(ay), z2 = -x * sin(ay) + z1 * cos(ay);
  double x3 = x2 * cos(az) - y1 * sin(az), y3 = x2 * sin(az) + y1 * cos(az);
  out[0] = p->position[0] + x3;
  out[1] = p->position[1] + y3;
  out[2] = p->position[2] + z2;
}
