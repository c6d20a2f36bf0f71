/* The audience's camera: a scene without `camera.orbit` is seen from the
 * seats, in front of the stage on the side the puppets face (+z, or
 * `camera.facing`), a little below the middle of the show and looking a
 * little up, from just far enough that every puppet and its control bar
 * stay in the picture over the whole show, clear of the overlay's corner.
 *
 * The show's reach is estimated without running the physics: every point
 * is sampled at SAMPLES times over sim.duration, a control point where its
 * frame's track puts it, a puppet's particle carried by the rigid motion
 * of the frame it hangs from (its own, else the scene's) since the start.
 * A puppet that swings out from under its bar goes farther; MARGIN keeps
 * room for that. With `camera: follow` the camera's target follows the
 * show's middle, so only each moment's spread about where the camera
 * looks then is framed. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mr_pose.h"
#include "scene_read.h"

enum { SAMPLES = 96 };
/* The part of the picture's half-height and half-width left free at each
 * edge, and the audience's eye below the middle of the show (degrees). */
static const double MARGIN = 0.1, ELEVATION_DEG = -3.0;
static const double DEG = 3.14159265358979323846 / 180.0;

/* The frame a particle hangs from: its puppet's own, else the scene's;
 * -1 when it hangs from none (it is framed where it starts). */
static long frame_of_particle(const mr_scene *s, size_t i) {
  const char *puppet = "";
  for (size_t p = 0; p < s->n_puppets; p++)
    if (i >= s->puppets[p].first && i < s->puppets[p].first + s->puppets[p].count)
      puppet = s->puppets[p].name;
  long scene_frame = -1;
  for (size_t k = 0; k < s->n_frames; k++) {
    if (puppet[0] != '\0' && strcmp(s->frames[k].puppet, puppet) == 0) return (long)k;
    if (s->frames[k].puppet[0] == '\0' && scene_frame < 0) scene_frame = (long)k;
  }
  return scene_frame;
}

/* Every point at time t into xyz (3 n: particles, then control points). */
static void points_at(const mr_scene *s, const long *frame_of, double t, double *xyz) {
  for (size_t i = 0; i < s->n_particles; i++) {
    const double *p0 = s->particles[i].def.position;
    double *out = xyz + 3 * i;
    long k = frame_of[i];
    if (k < 0) {
      memcpy(out, p0, 3 * sizeof *out);
      continue;
    }
    mr_pose start, now;
    mr_scene_frame_pose_at(s, (size_t)k, 0, &start);
    mr_scene_frame_pose_at(s, (size_t)k, t, &now);
    double d[3], local[3];
    for (int c = 0; c < 3; c++) d[c] = p0[c] - start.position[c];
    mr_pose_unrotate(start.orientation, d, local);
    mr_pose_apply(&now, local, out);
  }
  for (size_t j = 0; j < s->n_control_points; j++) {
    mr_pose now;
    mr_scene_frame_pose_at(s, s->control_points[j].frame, t, &now);
    mr_scene_control_point_world(s, j, &now, xyz + 3 * (s->n_particles + j));
  }
}

double *mr_scene_show_points(const mr_scene *s, size_t extra, size_t *count) {
  size_t n = s->n_particles + s->n_control_points;
  long *frame_of = malloc((s->n_particles + 1) * sizeof *frame_of);
  double *all = malloc(3 * (n * (SAMPLES + 1) + extra) * sizeof *all);
  if (frame_of == NULL || all == NULL) {
    free(frame_of);
    free(all);
    return NULL;
  }
  for (size_t i = 0; i < s->n_particles; i++) frame_of[i] = frame_of_particle(s, i);
  for (int j = 0; j <= SAMPLES; j++)
    points_at(s, frame_of, s->duration * j / SAMPLES, all + 3 * n * (size_t)j);
  free(frame_of);
  *count = n * (SAMPLES + 1);
  return all;
}

/* The show's reach about mid: all (mr_scene_show_points') with each
 * moment moved by its own middle's offset from mid when the camera
 * follows. */
static void reach(const mr_scene *s, double *all, double mid[3]) {
  size_t n = s->n_particles + s->n_control_points;
  /* The camera that follows lags its goal (by 2 time v at speed v): its
   * target is where the window's follower is, run on the same moments. */
  double mid0[3];
  mr_follow follow = mr_follow_start(MR_FOLLOW_TIME);
  for (int j = 0; j <= SAMPLES; j++) {
    double *xyz = all + 3 * n * (size_t)j, m[3];
    mr_box_middle(xyz, n, m);
    if (j == 0) memcpy(mid0, m, sizeof mid0);
    if (!s->stage.follow) continue;
    mr_follow_step(&follow, m, s->duration / SAMPLES);
    for (size_t i = 0; i < n; i++)
      for (int c = 0; c < 3; c++) xyz[3 * i + c] += mid0[c] - follow.pos[c];
  }
  mr_box_middle(all, n * (SAMPLES + 1), mid);
}

/* The camera's axes for an eye on azimuth az, elevation el about the
 * target: back (target to eye), right, up, as mr_view_project's. */
typedef struct axes {
  double back[3], right[3], up[3];
} axes;

static axes axes_of(double az, double el) {
  axes a;
  a.back[0] = mr_cos(el) * mr_sin(az);
  a.back[1] = mr_sin(el);
  a.back[2] = mr_cos(el) * mr_cos(az);
  a.right[0] = mr_cos(az);
  a.right[1] = 0;
  a.right[2] = -mr_sin(az);
  /* up = right x forward, forward = -back */
  a.up[0] = -(a.right[1] * a.back[2] - a.right[2] * a.back[1]);
  a.up[1] = -(a.right[2] * a.back[0] - a.right[0] * a.back[2]);
  a.up[2] = -(a.right[0] * a.back[1] - a.right[1] * a.back[0]);
  return a;
}

static double dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The picture's bounds the points must keep to, in the picture's own -1..1
 * (y up): x within +-kx, y from lo to hi, times depth tan(fov / 2). The
 * first n_show points are the show's, kept above the overlay; the rest
 * are the set's, which the overlay may cover, so they keep only above
 * set_lo. */
typedef struct bounds {
  double kx, lo, hi, set_lo;
  size_t n_show;
} bounds;

/* Moving the target by delta along up shifts every point's y by -delta,
 * and leaves its depth d - w alone: for distance d, the shifts that keep
 * every point between lo and hi form [*need, *room]. */
static void shift_range(const double *rel, size_t n, double d, const bounds *b, double *need,
                        double *room) {
  *need = -INFINITY;
  *room = INFINITY;
  for (size_t i = 0; i < n; i++) {
    const double y = rel[3 * i + 1], depth = d - rel[3 * i + 2];
    *need = fmax(*need, y - b->hi * depth);
    *room = fmin(*room, y - (i < b->n_show ? b->lo : b->set_lo) * depth);
  }
}

/* The least distance at which every point fits (x, then y by bisection:
 * a farther eye only widens the range of shifts), and the shift into the
 * middle of that range. rel holds each point as (right, up, back). */
static double fit(const double *rel, size_t n, const bounds *b, double *shift) {
  double d = 0.5;
  for (size_t i = 0; i < n; i++) d = fmax(d, rel[3 * i + 2] + fmax(fabs(rel[3 * i]) / b->kx, 0.2));
  double need, room, hi = d;
  shift_range(rel, n, hi, b, &need, &room);
  while (need > room && hi < 1e5) {
    hi *= 2;
    shift_range(rel, n, hi, b, &need, &room);
  }
  double lo = d;
  for (int it = 0; it < 60 && hi > lo * (1 + 1e-9); it++) {
    double m = (lo + hi) / 2;
    shift_range(rel, n, m, b, &need, &room);
    if (need <= room)
      hi = m;
    else
      lo = m;
  }
  shift_range(rel, n, hi, b, &need, &room);
  *shift = (need + room) / 2;
  return hi;
}

void mr_scene_frame_audience(mr_scene *s, double *all) {
  mr_stage_def *st = &s->stage;
  size_t n = (s->n_particles + s->n_control_points) * (SAMPLES + 1);
  if (n == 0 || all == NULL) return;
  double mid[3];
  reach(s, all, mid);
  /* The proscenium's opening is framed too (not with a camera that
   * follows, which moves past it), so the audience sees the theater. */
  const size_t n_show = n;
  if (st->proscenium && !st->follow) n += mr_scene_set_framed(st, all + 3 * n);
  const double az = st->facing_deg * DEG, el = ELEVATION_DEG * DEG;
  const axes a = axes_of(az, el);
  for (size_t i = 0; i < n; i++) {
    double rel[3];
    for (int c = 0; c < 3; c++) rel[c] = all[3 * i + c] - mid[c];
    all[3 * i] = dot(rel, a.right);
    all[3 * i + 1] = dot(rel, a.up);
    all[3 * i + 2] = dot(rel, a.back);
  }
  /* The overlay's box and its corner's margin, from the bottom edge. */
  double osd[4];
  mr_osd_rect(st->width, st->height, MR_OSD_ROWS, MR_OSD_COLUMNS, osd);
  const double half = st->fov_deg * DEG / 2, t = mr_sin(half) / mr_cos(half),
               aspect = (double)st->width / st->height;
  const double osd_ndc = 2 * (st->height - osd[1]) / st->height;
  const bounds b = { t * aspect * (1 - MARGIN), t * (-1 + MARGIN + osd_ndc), t * (1 - MARGIN),
                     t * (-1 + MARGIN / 2), n_show };
  double shift = 0;
  double d = fit(all, n, &b, &shift);
  for (int c = 0; c < 3; c++) st->orbit_target[c] = mid[c] + shift * a.up[c];
  st->orbit_distance = fmin(d, 1e5);
  st->orbit_azimuth_deg = st->facing_deg;
  st->orbit_elevation_deg = ELEVATION_DEG;
}
