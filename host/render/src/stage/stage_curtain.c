/* The moving part of the set: the front curtain, open as a function of
 * the show's time, and the follow spot, aimed at the puppets each frame.
 * Both are worked out from what a frame already has (its time, its
 * points), never from the frames before it, so any frame drawn alone
 * looks as it does in a run. */
#include "stage_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double DEG = 3.14159265358979323846 / 180.0;

/* 0 at x <= 0, 1 at x >= 1, and a smooth step between (no jolt as the
 * curtain starts or stops). */
static double ease(double x) {
  if (!(x > 0)) return 0;
  if (x >= 1) return 1;
  return x * x * (3 - 2 * x);
}

double mr_curtain_openness(const mr_curtain_def *c, double t, double end) {
  if (c == NULL || !c->show) return 1;
  if (!isfinite(t)) return 0;
  double open = c->open_s > 0 ? ease(t / c->open_s) : (t >= 0 ? 1 : 0);
  if (!isfinite(end) || end < 0) return open;
  double left = end - t;
  double shut = c->close_s > 0 ? ease(left / c->close_s) : (left > 0 ? 1 : 0);
  return fmin(open, shut);
}

mr_stage_status mr_stage_set_time(mr_stage *s, double t, double end) {
  if (s == NULL || !isfinite(t)) return MR_STAGE_ERR_ARG;
  s->list.curtain_closed = 1 - mr_curtain_openness(&s->def.curtain, t, end);
  return MR_STAGE_OK;
}

/* The audience's side: the unit normal towards it, and the axis to its
 * right (as the audience's camera has them, scene_audience.c). */
static void audience_axes(const mr_stage_def *d, double normal[3], double right[3]) {
  const double f = d->facing_deg * DEG;
  normal[0] = mr_sin(f), normal[1] = 0, normal[2] = mr_cos(f);
  right[0] = mr_cos(f), right[1] = 0, right[2] = -mr_sin(f);
}

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void unit3(double v[3]) {
  double n = sqrt(dot3(v, v));
  for (int k = 0; k < 3; k++) v[k] = n > 0 ? v[k] / n : 0;
}

/* How far across (along p->right, either way) and how high the view of
 * the orbit o reaches on the curtain's plane: where its four corner rays
 * meet the plane. False when a ray misses it (it looks along the plane,
 * or the curtain stands behind the eye). */
static bool view_on_plane(const mr_orbit *o, double aspect, const mr_curtain_place *p,
                          double *across, double *top) {
  double eye[3], f[3], r[3], u[3];
  mr_orbit_eye(o, eye);
  for (int k = 0; k < 3; k++) f[k] = o->target[k] - eye[k];
  unit3(f);
  r[0] = -f[2], r[1] = 0, r[2] = f[0]; /* f x (0, 1, 0) */
  unit3(r);
  u[0] = r[1] * f[2] - r[2] * f[1], u[1] = r[2] * f[0] - r[0] * f[2];
  u[2] = r[0] * f[1] - r[1] * f[0];
  const double half = o->fov_deg * DEG / 2, ty = mr_sin(half) / mr_cos(half), tx = ty * aspect;
  *across = 0, *top = -INFINITY;
  for (int c = 0; c < 4; c++) {
    double dir[3], hit[3], sx = c & 1 ? 1 : -1, sy = c & 2 ? 1 : -1;
    for (int k = 0; k < 3; k++) dir[k] = f[k] + sx * tx * r[k] + sy * ty * u[k];
    double rel[3] = { p->origin[0] - eye[0], 0, p->origin[2] - eye[2] };
    double along = dot3(dir, p->normal), t = along != 0 ? dot3(rel, p->normal) / along : -1;
    if (!(t > 0)) return false;
    for (int k = 0; k < 3; k++) hit[k] = eye[k] + t * dir[k] - p->origin[k];
    *across = fmax(*across, fabs(dot3(hit, p->right)));
    *top = fmax(*top, hit[1]);
  }
  return true;
}

/* Behind the proscenium: just upstage of its plane, wide enough that
 * open, each half gathered to 18 % of its width (to 0.41 of the whole
 * from the middle) stands behind a post and the opening stays clear; and
 * taller than the opening, its top hidden by the header. */
static mr_curtain_place behind_arch(const mr_stage_def *d, mr_curtain_place p) {
  const mr_curtain_def *c = &d->curtain;
  const double w = d->set_width > 0 ? d->set_width : MR_SET_WIDTH,
               h = d->set_height > 0 ? d->set_height : MR_SET_HEIGHT,
               plane = d->set_front > 0 ? d->set_front : MR_SET_FRONT;
  const double dist = c->distance > 0 ? c->distance : plane - 0.06;
  for (int k = 0; k < 3; k++) p.origin[k] = dist * p.normal[k] + d->set_middle * p.right[k];
  p.origin[1] = d->floor_height;
  p.width = c->width > 0 ? c->width : 1.22 * w + 0.1;
  p.height = c->height > 0 ? c->height : h + 0.3;
  return p;
}

mr_curtain_place mr_curtain_place_of(const mr_stage_def *d) {
  mr_curtain_place p;
  audience_axes(d, p.normal, p.right);
  if (d->proscenium) return behind_arch(d, p);
  const mr_curtain_def *c = &d->curtain;
  const double front = d->floor ? d->floor_size / 2 - 0.15 : 3.85;
  /* The audience's eye, and how far in front of the stage's middle it is. */
  mr_orbit o = mr_orbit_of_stage(d);
  double eye[3];
  mr_orbit_eye(&o, eye);
  const double eye_along = dot3(eye, p.normal);
  /* (In front of the stage's middle even when the orbit is turned away.) */
  double dist =
      c->distance > 0 ? c->distance : fmax(0.3, fmin(front, eye_along - 0.4 * o.distance));
  for (int k = 0; k < 3; k++) p.origin[k] = dist * p.normal[k];
  p.origin[1] = d->floor_height;
  /* A little wider than the view where it hangs (seen from the side, its
   * farther reach), so that open its gathered halves frame the picture's
   * sides as a theater's do, and never wider than the stage; and past
   * the view's top, with room to spare. */
  const double aspect = d->width > 0 && d->height > 0 ? (double)d->width / d->height : 16.0 / 9;
  const double stage_w = d->floor ? d->floor_size : 8;
  double across = stage_w / 2, top = 2.2;
  if (!view_on_plane(&o, aspect, &p, &across, &top)) across = stage_w / 2, top = 2.2;
  p.width = c->width > 0 ? c->width : fmin(stage_w, 2.3 * across);
  p.height = c->height > 0 ? c->height : fmax(2.4, top + 0.3);
  return p;
}

void mr_follow_spot_position(const mr_stage_def *d, double out[3]) {
  double normal[3], right[3];
  audience_axes(d, normal, right);
  const double *q = d->follow_spot.position;
  for (int k = 0; k < 3; k++) out[k] = q[0] * right[k] + q[2] * normal[k];
  out[1] += q[1];
}

static bool listed(const int *ids, size_t n, int id) {
  for (size_t i = 0; i < n; i++)
    if (ids[i] == id) return true;
  return false;
}

/* A model's points: its particles, or a freeform model's bones. */
static int model_points(const mr_model_def *m, const int **ids) {
  static const int needs[] = { 1, 2, 3, 0 };
  if (m->display == MR_DISPLAY_FREEFORM) {
    *ids = m->bones;
    return m->n_bones;
  }
  *ids = m->particles;
  return needs[m->display];
}

int mr_stage_spot_prepare(mr_stage *s) {
  const mr_stage_def *d = &s->def;
  size_t cap = 0, n_bars = 0;
  for (size_t k = 0; k < d->n_frames; k++) n_bars += (size_t)d->frame_point_count[k];
  for (size_t i = 0; i < d->n_models; i++) {
    const int *ids;
    cap += (size_t)model_points(&s->models[i], &ids);
  }
  s->spot_points = malloc((cap + 1) * sizeof *s->spot_points);
  s->spot_xyz = malloc(3 * (cap + 1) * sizeof *s->spot_xyz);
  if (s->spot_points == NULL || s->spot_xyz == NULL) return -1;
  s->n_spot = 0;
  for (size_t i = 0; i < d->n_models; i++) {
    const int *ids;
    int c = model_points(&s->models[i], &ids);
    for (int j = 0; j < c; j++)
      if (!listed(d->frame_points, n_bars, ids[j]) && !listed(s->spot_points, s->n_spot, ids[j]))
        s->spot_points[s->n_spot++] = ids[j];
  }
  return 0;
}

void mr_stage_spot_update(mr_stage *s) {
  mr_draw_follow_spot *f = &s->list.follow_spot;
  f->on = s->def.follow_spot.show && s->n_spot > 0;
  if (!f->on) return;
  for (size_t i = 0; i < s->n_spot; i++)
    memcpy(&s->spot_xyz[3 * i], &s->shown[3 * (size_t)s->spot_points[i]], 3 * sizeof(double));
  mr_box_middle(s->spot_xyz, s->n_spot, f->target);
  mr_follow_spot_position(&s->def, f->position);
}
