/* The orbit camera's maths: a point on a sphere about the target, in
 * degrees of azimuth (about +y, 0 on +z) and elevation (above the
 * horizontal plane through the target). */
#include <math.h>

#include "mr_stage.h"

static const double DEG = 3.14159265358979323846 / 180.0;

mr_orbit mr_orbit_of_stage(const mr_stage_def *def) {
  mr_orbit o;
  for (int i = 0; i < 3; i++) o.target[i] = def->orbit_target[i];
  o.distance = def->orbit_distance;
  o.azimuth_deg = def->orbit_azimuth_deg;
  o.elevation_deg = def->orbit_elevation_deg;
  o.fov_deg = def->fov_deg;
  return o;
}

/* The eye e = t + r (cos el sin az, sin el, cos el cos az), inverted:
 * az = atan2(dx, dz), el = asin(dy / r). */
mr_orbit mr_orbit_of_camera(const mr_camera_def *c, const mr_orbit *start) {
  mr_orbit o = *start;
  double d[3];
  for (int i = 0; i < 3; i++) d[i] = c->position[i] - c->target[i];
  double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(r > 1e-9)) return o;
  for (int i = 0; i < 3; i++) o.target[i] = c->target[i];
  o.distance = r;
  o.azimuth_deg = atan2(d[0], d[2]) / DEG;
  o.elevation_deg = asin(d[1] / r) / DEG;
  o.fov_deg = c->fov_deg;
  return o;
}

void mr_orbit_turn(mr_orbit *o, double d_azimuth_deg, double d_elevation_deg) {
  o->azimuth_deg = fmod(o->azimuth_deg + d_azimuth_deg, 360.0);
  o->elevation_deg = fmin(89.0, fmax(-89.0, o->elevation_deg + d_elevation_deg));
}

void mr_orbit_zoom(mr_orbit *o, double steps) {
  o->distance = fmin(100.0, fmax(0.05, o->distance * pow(0.9, steps)));
}

void mr_orbit_eye(const mr_orbit *o, double eye[3]) {
  const double az = o->azimuth_deg * DEG, el = o->elevation_deg * DEG;
  eye[0] = o->target[0] + o->distance * cos(el) * sin(az);
  eye[1] = o->target[1] + o->distance * sin(el);
  eye[2] = o->target[2] + o->distance * cos(el) * cos(az);
}
