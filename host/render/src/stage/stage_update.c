/* The draw list of one frame: the paper's display modes (§3.3) as poses,
 * and the rigging as lines. */
#include "stage_internal.h"
#include "stage_math.h"

#include <math.h>
#include <string.h>

static const double *point(const double *xyz, int id) {
  return &xyz[3 * (size_t)id];
}

/* §3.3 (1), particle display mode: "the attached model is transformed
 * according to the movement of the particle". Only moved, never turned:
 * a single point has no orientation. */
static int pose_particle(const mr_model_def *m, const double *xyz, mr_draw_item *it) {
  const double *p = point(xyz, m->particles[0]);
  if (!mr_stage_finite3(p)) return -1;
  it->pose = mr_pose_identity();
  memcpy(it->pose.position, p, sizeof it->pose.position);
  it->scale[0] = it->scale[1] = it->scale[2] = 1;
  return 0;
}

/* §3.3 (2), link display mode: "stretched, scaled, and positioned to fit
 * the distance between the particles", oriented "by the direction between
 * the particles". The model's y axis turns onto a -> b by the shortest
 * turn (a direction fixes no twist about itself; the shortest turn is the
 * one that never spins the model about its own axis), and y is scaled to
 * the distance. */
static int pose_link(const mr_model_def *m, const double *xyz, mr_draw_item *it) {
  const double *a = point(xyz, m->particles[0]), *b = point(xyz, m->particles[1]);
  if (!mr_stage_finite3(a) || !mr_stage_finite3(b)) return -1;
  static const double up[3] = { 0, 1, 0 };
  double d[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  double q[4];
  if (mr_stage_quat_arc(up, d, q) != 0) return -1; /* coincident: keep the last pose */
  memcpy(it->pose.position, a, sizeof it->pose.position);
  memcpy(it->pose.orientation, q, sizeof q);
  it->scale[0] = it->scale[2] = 1;
  it->scale[1] = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  return 0;
}

/* §3.3 (3), rigid group mode: "oriented either by the particles'
 * configuration or by their initial orientation". Configuration: the
 * model sits in the three particles' frame (mr_stage_frame3). Initial:
 * the model was placed in world coordinates at the start and moves by the
 * turn and move that take the rest frame to the frame now. */
static int pose_rigid(const mr_model_def *m, const mr_pose *rest, const double *xyz,
                      mr_draw_item *it) {
  const int *p = m->particles;
  const double *a = point(xyz, p[0]), *b = point(xyz, p[1]), *c = point(xyz, p[2]);
  if (!mr_stage_finite3(a) || !mr_stage_finite3(b) || !mr_stage_finite3(c)) return -1;
  mr_pose now;
  if (mr_stage_frame3(a, b, c, &now) != 0) return -1;
  it->pose = m->orient == MR_RIGID_CONFIGURATION ? now : mr_stage_pose_between(rest, &now);
  it->scale[0] = it->scale[1] = it->scale[2] = 1;
  return 0;
}

static void update_models(mr_stage *s, const double *xyz) {
  for (size_t i = 0; i < s->def.n_models; i++) {
    const mr_model_def *m = &s->models[i];
    mr_stage_model *st = &s->state[i];
    if (m->display == MR_DISPLAY_FREEFORM) {
      mr_stage_bones_update(s, i, xyz); /* §3.3 (4): stage_skin.c */
      continue;
    }
    /* Each mode computes into a scratch item: a frame that fails (a point
     * not finite, two points on one spot) leaves the last pose drawn. */
    mr_draw_item *it = &s->items[st->slot], next = *it;
    int rc = m->display == MR_DISPLAY_PARTICLE ? pose_particle(m, xyz, &next)
             : m->display == MR_DISPLAY_LINK   ? pose_link(m, xyz, &next)
                                               : pose_rigid(m, &st->rest_frame, xyz, &next);
    if (rc == 0 && mr_pose_is_finite(&next.pose) && isfinite(next.scale[1])) *it = next;
  }
}

static void line(mr_stage *s, int a, int b, const float rgb[3]) {
  mr_draw_line *l = &s->lines[s->list.n_lines++];
  memcpy(l->a, point(s->shown, a), sizeof l->a);
  memcpy(l->b, point(s->shown, b), sizeof l->b);
  memcpy(l->rgb, rgb, sizeof l->rgb);
}

/* The rigging: each string from its control point to its particle, and,
 * drawn as wire, each control frame's points joined in order, closed
 * round when there are three or more (a solid frame's bars are models of
 * the scene's). Lines join the points where they were last finite. */
static void update_lines(mr_stage *s) {
  const mr_stage_def *d = &s->def;
  s->list.n_lines = 0;
  if (d->show_strings)
    for (size_t k = 0; k < d->n_strings; k++)
      line(s, d->strings[2 * k], d->strings[2 * k + 1], d->string_color);
  if (!d->show_frames || d->frame_style != MR_FRAMES_WIRE) return;
  const int *pts = d->frame_points;
  for (size_t k = 0; k < d->n_frames; k++) {
    int c = d->frame_point_count[k];
    for (int i = 0; i + 1 < c; i++) line(s, pts[i], pts[i + 1], d->frame_color);
    if (c >= 3) line(s, pts[c - 1], pts[0], d->frame_color);
    pts += c;
  }
}

mr_stage_status mr_stage_update(mr_stage *s, const double *xyz, size_t n,
                                const mr_draw_list **out) {
  if (s == NULL || out == NULL || n != s->n || (n > 0 && xyz == NULL)) return MR_STAGE_ERR_ARG;
  for (size_t i = 0; i < n; i++)
    if (mr_stage_finite3(&xyz[3 * i])) memcpy(&s->shown[3 * i], &xyz[3 * i], 3 * sizeof(double));
  update_models(s, xyz);
  update_lines(s);
  mr_stage_spot_update(s);
  *out = &s->list;
  return MR_STAGE_OK;
}
