/* The theater's set sized from the show: the proscenium's opening holds
 * every puppet and control bar over the whole show, as scene_audience.c
 * estimates where they go, with room about them; it stands in front of
 * the show's front, on the side the audience sits (`camera.facing`).
 *
 * Why the opening never hides a puppet from the audience's camera: the
 * camera's eye stands on the show's middle, sideways, and between the
 * floor and the opening's top; every point of the show is behind the
 * arch's plane and inside the opening's width and height. The line from
 * the eye to such a point crosses the arch's plane between the two, and
 * the opening is a rectangle (convex) holding both ends' sideways and
 * upward places: the crossing is inside the opening. */
#include <math.h>

#include "mr_pose.h"
#include "scene_read.h"

static const double DEG = 3.14159265358979323846 / 180.0;

/* Room about the show: sideways, a fixed part and a share of its width;
 * above the bars; in front of its front. */
static const double SIDE_ROOM = 0.25, SIDE_SHARE = 0.1, TOP_ROOM = 0.25, FRONT_ROOM = 0.3;
/* A proscenium is wider than tall. */
static const double LEAST_ASPECT = 1.25;
/* Without a show: a small theater. */
static const double ALONE_WIDTH = 3, ALONE_HEIGHT = 2.2, ALONE_FRONT = 1;

/* The set's axes: right (the audience's right), and front (towards the
 * audience), both level. */
static void set_axes(const mr_stage_def *st, double right[3], double front[3]) {
  const double az = st->facing_deg * DEG;
  right[0] = mr_cos(az), right[1] = 0, right[2] = -mr_sin(az);
  front[0] = mr_sin(az), front[1] = 0, front[2] = mr_cos(az);
}

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void mr_scene_size_set(mr_scene *s, const double *all, size_t n) {
  mr_stage_def *st = &s->stage;
  if (all == NULL) n = 0;
  double right[3], front[3], lo = 0, hi = 0, top = 0, ahead = 0;
  set_axes(st, right, front);
  for (size_t i = 0; i < n; i++) {
    const double *p = all + 3 * i, x = dot3(p, right), z = dot3(p, front);
    lo = i ? fmin(lo, x) : x, hi = i ? fmax(hi, x) : x;
    top = i ? fmax(top, p[1]) : p[1], ahead = i ? fmax(ahead, z) : z;
  }
  double height = ALONE_HEIGHT, width = ALONE_WIDTH, middle = 0, plane = ALONE_FRONT;
  if (n > 0) {
    height = fmax(top - st->floor_height + TOP_ROOM, 1.0);
    width = (hi - lo) * (1 + 2 * SIDE_SHARE) + 2 * SIDE_ROOM;
    width = fmax(width, LEAST_ASPECT * height);
    middle = (lo + hi) / 2;
    plane = fmax(ahead + FRONT_ROOM, 0.4);
  }
  if (!(st->set_width > 0)) st->set_width = width, st->set_middle = middle;
  if (!(st->set_height > 0)) st->set_height = height;
  if (!(st->set_front > 0)) st->set_front = plane;
}

/* A band of the arch about the opening's top corners that the audience
 * should see: a twentieth of the opening's height above it, a
 * twenty-fifth of its width each side; and the middle of the stage's
 * front edge, where the footlights stand, so the boards' edge is seen
 * under a puppet that hangs high. (The edge's corners may go below the
 * picture: the overlay's corner is kept clear for the puppets, not for
 * the boards.) */
size_t mr_scene_set_framed(const mr_stage_def *st, double *xyz) {
  double right[3], front[3];
  set_axes(st, right, front);
  const double w = st->set_width / 2 * 1.04, y = st->floor_height + st->set_height * 1.05;
  for (int k = 0; k < 2; k++) {
    const double x = st->set_middle + (k & 1 ? w : -w);
    for (int c = 0; c < 3; c++) xyz[3 * k + c] = x * right[c] + st->set_front * front[c];
    xyz[3 * k + 1] = y;
  }
  for (int c = 0; c < 3; c++)
    xyz[6 + c] = st->set_middle * right[c] + (st->set_front + MR_SET_APRON) * front[c];
  xyz[7] = st->floor_height;
  return MR_SET_FRAMED;
}
