/* Control frames (§6.1-6.2): points the strings hang from, a start pose,
 * a scripted track that stands in for the glove, and which glove drives it
 * in the theater. The scene may have one (physics.control) and each puppet
 * its own. A frame is moved by setting its pose (§6.2, approach 1), so the
 * track only has to give a pose for every time. Rotations in the file are
 * x-y-z Euler degrees; they become quaternions here, once, as they are
 * read. */
#include "scene_read.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* The frame being read: the last one added. */
static mr_scene_frame *cur(mr_reader *r) {
  return &r->scene->frames[r->scene->n_frames - 1];
}

/* position and rotation keys of n over *p; a key left out keeps p's. */
static int read_pose(mr_reader *r, const mr_ynode *n, mr_pose *p) {
  static const double zero[3] = { 0, 0, 0 };
  const mr_ynode *v;
  double deg[3];
  if ((v = mr_scene_yaml_get(n, "position")) != NULL &&
      mr_scene_read_vec3(r, v, "position", p->position) != 0)
    return -1;
  if ((v = mr_scene_yaml_get(n, "rotation")) == NULL) return 0;
  if (mr_scene_read_vec3(r, v, "rotation", deg) != 0) return -1;
  mr_pose turn = mr_pose_from_euler_deg(zero, deg);
  memcpy(p->orientation, turn.orientation, sizeof p->orientation);
  return 0;
}

static int read_point(mr_reader *r, const mr_ynode *it, void *slot) {
  static const char *const keys[] = { "name", "offset", NULL };
  const mr_scene *s = r->scene;
  mr_scene_control_point *c = slot;
  const mr_ynode *v;
  char bare[MR_SCENE_NAME_MAX];
  if ((v = mr_scene_read_named(r, it, "a control point", keys, "control point name", bare)) == NULL)
    return -1;
  if (mr_scene_qualify(r, bare, c->name) != 0)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected '%s.%s' to fit in %d characters; shorten the puppet's or "
                              "the control point's name",
                              r->puppet, bare, MR_SCENE_NAME_MAX - 1);
  c->frame = s->n_frames - 1;
  if (mr_scene_lookup_particle(r, c->name) != (size_t)-1)
    return mr_scene_read_fail(
        r, v, MR_SCENE_ERR_VALUE,
        "expected a control point name unused by particles, '%s' is a particle", c->name);
  if (mr_scene_find_control_point(s, c->name) < s->n_control_points - 1)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected a unique control point name, '%s' is already declared",
                              c->name);
  if ((v = mr_scene_read_need(r, it, "offset", "a control point")) == NULL ||
      mr_scene_read_vec3(r, v, "offset", c->offset) != 0)
    return -1;
  c->pos = mr_scene_read_pos(it);
  return 0;
}

static int read_keyframe(mr_reader *r, const mr_ynode *it, void *slot) {
  static const char *const keys[] = { "t", "position", "rotation", NULL };
  const mr_scene_track *tr = &cur(r)->track;
  mr_scene_keyframe *k = slot;
  const mr_ynode *v;
  if (mr_scene_read_map(r, it, "a keyframe", keys) != 0 ||
      (v = mr_scene_read_need(r, it, "t", "a keyframe")) == NULL ||
      mr_scene_read_number(r, v, "t", &k->t) != 0)
    return -1;
  if (k->t < 0)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected t >= 0, got %g", k->t);
  if (tr->n_keys > 1 && !(k->t > k[-1].t))
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected keyframe times in increasing order, got %g after %g", k->t,
                              k[-1].t);
  k->pose = cur(r)->pose;
  k->pos = mr_scene_read_pos(it);
  if (read_pose(r, it, &k->pose) != 0) return -1;
  /* A puppet's track moves with the puppet, as its particles do. */
  if (mr_scene_yaml_get(it, "position") != NULL)
    for (int i = 0; i < 3; i++) k->pose.position[i] += r->offset[i];
  return 0;
}

static int read_keyframes(mr_reader *r, const mr_ynode *n) {
  mr_scene_track *tr = &cur(r)->track;
  if (n->kind == MR_YNODE_SEQ && n->count == 0)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_VALUE, "expected at least one keyframe");
  tr->kind = MR_SCENE_TRACK_KEYFRAMES;
  return mr_scene_read_items(r, n, "control.track.keyframes", 0, NULL, sizeof *tr->keys,
                             (void **)&tr->keys, &tr->n_keys, read_keyframe);
}

static int read_oscillate(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "amplitude", "quadrature", "rotation", "frequency",
                                      "phase",     "start",      "ramp",     NULL };
  static const mr_scene_field fields[] = {
    { "amplitude", MR_SCENE_FIELD_VEC3, offsetof(mr_scene_track, amplitude), 0, 0 },
    { "quadrature", MR_SCENE_FIELD_VEC3, offsetof(mr_scene_track, quadrature), 0, 0 },
    { "frequency", MR_SCENE_FIELD_POSITIVE, offsetof(mr_scene_track, frequency_hz), 0, 0 },
    { "phase", MR_SCENE_FIELD_NUMBER, offsetof(mr_scene_track, phase_rad), 0, 0 },
    { "start", MR_SCENE_FIELD_NONNEG, offsetof(mr_scene_track, start), 0, 0 },
    { "ramp", MR_SCENE_FIELD_NONNEG, offsetof(mr_scene_track, ramp), 0, 0 }
  };
  mr_scene_track *tr = &cur(r)->track;
  mr_pose turn = mr_pose_identity();
  if (mr_scene_read_map(r, n, "control.track.oscillate", keys) != 0 ||
      mr_scene_read_need(r, n, "frequency", "control.track.oscillate") == NULL ||
      mr_scene_read_fields(r, n, fields, sizeof fields / sizeof fields[0], tr) != 0 ||
      read_pose(r, n, &turn) != 0)
    return -1;
  tr->kind = MR_SCENE_TRACK_OSCILLATE;
  tr->phase_rad = tr->phase_rad * PI / 180.0; /* read in degrees */
  memcpy(tr->turn, turn.orientation, sizeof tr->turn);
  return 0;
}

static int read_track(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "keyframes", "interpolation", "oscillate", NULL };
  if (mr_scene_read_map(r, n, "control.track", keys) != 0) return -1;
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
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA,
                                "interpolation applies to keyframes only");
    if (v->kind == MR_YNODE_SCALAR && strcmp(v->text, "linear") == 0)
      cur(r)->track.linear = true;
    else if (!(v->kind == MR_YNODE_SCALAR && strcmp(v->text, "smooth") == 0))
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                                "expected interpolation linear or smooth");
  }
  return k != NULL ? read_keyframes(r, k) : read_oscillate(r, o);
}

/* A glove's uid as list-ports and the status line print it: 8 hex digits
 * (the first word) or 24 (all three), with or without 0x. */
static int read_uid(mr_reader *r, const mr_ynode *v, mr_scene_glove_bind *b) {
  const char *t = v->kind == MR_YNODE_SCALAR ? v->text : "";
  if (t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) t += 2;
  size_t len = strlen(t);
  bool hex = len == 8 || len == 24;
  for (size_t i = 0; i < len && hex; i++) hex = isxdigit((unsigned char)t[i]) != 0;
  if (!hex)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "expected a glove uid of 8 or 24 hex digits (as marionette "
                              "list-ports prints it), got '%s'",
                              v->kind == MR_YNODE_SCALAR ? v->text : "a collection");
  b->by = MR_SCENE_BIND_UID;
  b->uid_words = (int)(len / 8);
  for (int w = 0; w < b->uid_words; w++) {
    char word[9];
    memcpy(word, t + 8 * w, 8);
    word[8] = '\0';
    b->uid[w] = (uint32_t)strtoul(word, NULL, 16);
  }
  return 0;
}

/* control.glove: which of the theater's gloves drives this frame. */
static int read_glove(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "order", "uid", "hand", NULL };
  mr_scene_glove_bind *b = &cur(r)->glove;
  if (mr_scene_read_map(r, n, "control.glove", keys) != 0) return -1;
  if (n->count != 1)
    return mr_scene_read_fail(r, n, MR_SCENE_ERR_SCHEMA,
                              "expected one of order, uid or hand in control.glove, got %zu keys",
                              n->count);
  const mr_ynode *v;
  if ((v = mr_scene_yaml_get(n, "order")) != NULL) {
    long k;
    if (mr_scene_read_long(r, v, "order", &k) != 0) return -1;
    if (k < 1 || k > 64)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                                "expected order between 1 and 64 (the first glove is 1), got %ld",
                                k);
    b->by = MR_SCENE_BIND_ORDER;
    b->order = (int)k - 1;
    return 0;
  }
  if ((v = mr_scene_yaml_get(n, "hand")) != NULL) {
    bool left = v->kind == MR_YNODE_SCALAR && strcmp(v->text, "left") == 0;
    if (!left && !(v->kind == MR_YNODE_SCALAR && strcmp(v->text, "right") == 0))
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected hand left or right");
    b->by = MR_SCENE_BIND_HAND;
    b->hand = left ? 0 : 1;
    return 0;
  }
  return read_uid(r, mr_scene_yaml_get(n, "uid"), b);
}

/* A positive number of degrees (per second, or per second squared) at
 * `key`, if there, into *out in radians. */
static int read_degrees(mr_reader *r, const mr_ynode *n, const char *key, double *out) {
  const mr_ynode *v = mr_scene_yaml_get(n, key);
  if (v == NULL) return 0;
  double deg;
  if (mr_scene_read_quantity(r, v, key, &deg) != 0) return -1;
  if (!(deg > 0))
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected a positive number for %s, got %g",
                              key, deg);
  if (mr_scene_range_check(r, v, key, deg) != 0) return -1;
  *out = deg * PI / 180.0;
  return 0;
}

/* physics.control, or a puppet's control: a new frame, its points, start
 * pose, track, speed limits and glove. */
int mr_scene_read_control(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "points",         "pose",      "track",
                                      "max_speed",      "max_accel", "max_turn_rate",
                                      "max_turn_accel", "glove",     NULL };
  static const mr_scene_field speed = { "max_speed", MR_SCENE_FIELD_POSITIVE,
                                        offsetof(mr_scene_frame, max_speed), 0, 0 };
  static const mr_scene_field accel = { "max_accel", MR_SCENE_FIELD_POSITIVE,
                                        offsetof(mr_scene_frame, max_accel), 0, 0 };
  static const char *const pose_keys[] = { "position", "rotation", NULL };
  mr_scene *s = r->scene;
  if (mr_scene_read_map(r, n, r->puppet ? "a puppet's control" : "physics.control", keys) != 0)
    return -1;
  mr_scene_frame *fs = realloc(s->frames, (s->n_frames + 1) * sizeof *fs);
  if (fs == NULL) return mr_scene_read_fail(r, n, MR_SCENE_ERR_NOMEM, "out of memory");
  s->frames = fs;
  mr_scene_frame *f = &fs[s->n_frames];
  mr_scene_frame_defaults(f);
  f->glove.order = (int)s->n_frames; /* unbound: the k-th frame takes the k-th glove */
  snprintf(f->puppet, sizeof f->puppet, "%s", r->puppet ? r->puppet : "");
  f->pos = mr_scene_read_pos(n);
  f->first_point = s->n_control_points;
  s->n_frames++;
  memcpy(f->pose.position, r->offset, sizeof r->offset);
  const mr_ynode *v = mr_scene_read_need(r, n, "points", "physics.control");
  if (v == NULL ||
      mr_scene_read_items(r, v, "control.points", 0, NULL, sizeof *s->control_points,
                          (void **)&s->control_points, &s->n_control_points, read_point) != 0)
    return -1;
  f = cur(r); /* the points' realloc leaves frames alone, but be plain about it */
  f->n_points = s->n_control_points - f->first_point;
  if ((v = mr_scene_yaml_get(n, "pose")) != NULL) {
    if (mr_scene_read_map(r, v, "control.pose", pose_keys) != 0 || read_pose(r, v, &f->pose) != 0)
      return -1;
    if (mr_scene_yaml_get(v, "position") != NULL)
      for (int i = 0; i < 3; i++) f->pose.position[i] += r->offset[i];
  }
  if ((v = mr_scene_yaml_get(n, "track")) != NULL && read_track(r, v) != 0) return -1;
  if ((v = mr_scene_yaml_get(n, "glove")) != NULL && read_glove(r, v) != 0) return -1;
  if (mr_scene_read_field(r, n, &speed, f) != 0 || mr_scene_read_field(r, n, &accel, f) != 0)
    return -1;
  if (read_degrees(r, n, "max_turn_rate", &f->max_turn) != 0) return -1;
  return read_degrees(r, n, "max_turn_accel", &f->max_turn_accel);
}

void mr_scene_frame_defaults(mr_scene_frame *f) {
  memset(f, 0, sizeof *f);
  f->pose = mr_pose_identity();
  memcpy(f->track.turn, f->pose.orientation, sizeof f->track.turn);
  f->max_speed = MR_SCENE_CONTROL_MAX_SPEED;
  f->max_turn = MR_SCENE_CONTROL_MAX_TURN_DEG * PI / 180.0;
  f->max_accel = MR_SCENE_CONTROL_MAX_ACCEL;
  f->max_turn_accel = MR_SCENE_CONTROL_MAX_TURN_ACCEL_DEG * PI / 180.0;
}

/* Between keys: smoothstep eases in and out of each key so the frame's
 * velocity is continuous (a pose jump is a hard case of its own, §7, not
 * the default); position linear, orientation by slerp. */
static mr_pose keyframes_at(const mr_scene_track *tr, double t) {
  const mr_scene_keyframe *k = tr->keys;
  size_t n = tr->n_keys;
  if (t <= k[0].t) return k[0].pose;
  if (t >= k[n - 1].t) return k[n - 1].pose;
  size_t i = 1;
  while (k[i].t < t) i++;
  double u = (t - k[i - 1].t) / (k[i].t - k[i - 1].t);
  if (!tr->linear) u = u * u * (3.0 - 2.0 * u);
  return mr_pose_interpolate(&k[i - 1].pose, &k[i].pose, u);
}

/* s(t) times the amplitude, the turn in the frame's own axes; s < 0 turns
 * the other way (the slerp runs backwards from the identity). */
static mr_pose oscillate_at(const mr_scene_track *tr, const mr_pose *start, double t) {
  mr_pose o = *start;
  if (!(t > tr->start)) return o;
  double ramp = tr->ramp > 0 ? fmin(1.0, (t - tr->start) / tr->ramp) : 1.0;
  /* The phase is taken in whole cycles first, so a show that runs for days
   * keeps its argument small (mr_sin takes |x| up to 2²³ rad, and a large
   * argument would cost the sine its low bits anyway). */
  double cycles = tr->frequency_hz * (t - tr->start);
  double arg = 2.0 * PI * (cycles - floor(cycles)) + tr->phase_rad;
  double w = mr_sin(arg), c = mr_cos(arg) - 1.0; /* c(start) = 0: no jump at the start */
  mr_pose id = mr_pose_identity(), full = mr_pose_identity();
  memcpy(full.orientation, tr->turn, sizeof full.orientation);
  mr_pose turn = mr_pose_interpolate(&id, &full, ramp * w);
  o = mr_pose_compose(start, &turn);
  for (int i = 0; i < 3; i++)
    o.position[i] += ramp * tr->amplitude[i] * w + ramp * tr->quadrature[i] * c;
  return o;
}

void mr_scene_frame_pose_at(const mr_scene *s, size_t k, double t, mr_pose *out) {
  if (k >= s->n_frames) {
    *out = mr_pose_identity();
    return;
  }
  const mr_scene_frame *f = &s->frames[k];
  const mr_scene_track *tr = &f->track;
  if (tr->kind == MR_SCENE_TRACK_KEYFRAMES && tr->n_keys > 0)
    *out = keyframes_at(tr, t);
  else if (tr->kind == MR_SCENE_TRACK_OSCILLATE)
    *out = oscillate_at(tr, &f->pose, t);
  else
    *out = f->pose;
}

/* Central differences over ±RATE_DT: the error is RATE_DT² times the
 * track's third derivative, under 1e-9 of the rate for any track a frame
 * can follow, and the rounding 1e-16 of a pose over RATE_DT. At a kink
 * (a linear keyframe, the end of a ramp) they give the mean of the two
 * sides. */
#define RATE_DT 1e-6

void mr_scene_frame_rates_at(const mr_scene *s, size_t k, double t, double vel[3],
                             double omega[3]) {
  mr_pose a, b;
  mr_scene_frame_pose_at(s, k, t - RATE_DT, &a);
  mr_scene_frame_pose_at(s, k, t + RATE_DT, &b);
  double axis[3], angle = mr_pose_turn(a.orientation, b.orientation, axis);
  for (int i = 0; i < 3; i++) {
    vel[i] = (b.position[i] - a.position[i]) / (2 * RATE_DT);
    omega[i] = axis[i] * angle / (2 * RATE_DT);
  }
}

void mr_scene_control_point_world(const mr_scene *s, size_t i, const mr_pose *pose, double out[3]) {
  mr_pose_apply(pose, s->control_points[i].offset, out);
}
