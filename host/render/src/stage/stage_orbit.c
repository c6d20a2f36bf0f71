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

/* As glm_lookat and glm_perspective: forward f = (target - eye) / |.|,
 * right s = f x up / |.|, up u = s x f; x_ndc = s.d / (f.d tan(fov/2)
 * aspect), y_ndc = u.d / (f.d tan(fov/2)), d = p - eye. */
double mr_view_project(const double eye[3], const double target[3], double fov_deg, double aspect,
                       const double p[3], double ndc[2]) {
  double f[3], d[3];
  for (int i = 0; i < 3; i++) {
    f[i] = target[i] - eye[i];
    d[i] = p[i] - eye[i];
  }
  double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  for (int i = 0; i < 3; i++) f[i] /= fl;
  double s[3] = { -f[2], 0, f[0] }; /* f x (0, 1, 0) */
  double sl = sqrt(s[0] * s[0] + s[2] * s[2]);
  s[0] /= sl;
  s[2] /= sl;
  const double u[3] = { s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2],
                        s[0] * f[1] - s[1] * f[0] };
  const double depth = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
  const double t = tan(fov_deg * DEG / 2);
  ndc[0] = (s[0] * d[0] + s[2] * d[2]) / (depth * t * aspect);
  ndc[1] = (u[0] * d[0] + u[1] * d[1] + u[2] * d[2]) / (depth * t);
  return depth;
}

void mr_box_middle(const double *xyz, size_t n, double mid[3]) {
  for (int c = 0; c < 3; c++) {
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++) {
      lo = fmin(lo, xyz[3 * i + c]);
      hi = fmax(hi, xyz[3 * i + c]);
    }
    mid[c] = n > 0 ? (lo + hi) / 2 : 0;
  }
}

mr_follow mr_follow_start(double time) {
  mr_follow f = { .time = time > 0 ? time : MR_FOLLOW_TIME };
  return f;
}

/* x'' = w^2 (g - x) - 2 w x', w = 1 / time. With e = x - g held over dt:
 * e(dt) = (e + (v + w e) dt) exp(-w dt), v(dt) = (v - w (v + w e) dt)
 * exp(-w dt). */
void mr_follow_step(mr_follow *f, const double goal[3], double dt) {
  if (!f->started) {
    for (int i = 0; i < 3; i++) {
      f->pos[i] = goal[i];
      f->vel[i] = 0;
    }
    f->started = true;
    return;
  }
  if (!(dt > 0)) return;
  const double w = 1.0 / f->time, k = exp(-w * dt);
  for (int i = 0; i < 3; i++) {
    const double e = f->pos[i] - goal[i], v = f->vel[i], c = v + w * e;
    f->pos[i] = goal[i] + (e + c * dt) * k;
    f->vel[i] = (v - w * c * dt) * k;
  }
}

/* DejaVu Sans Mono's advance is 0.52 of the pixel height stb_truetype
 * bakes it at (ascent to descent); 0.55 leaves room for a font of
 * def.font_path a little wider. */
double mr_osd_font_px(int height) {
  return fmax(11.0, height / 56.0);
}

void mr_osd_rect(int width, int height, int rows, int columns, double rect[4]) {
  (void)width;
  const double px = mr_osd_font_px(height), pad = 0.4 * px, margin = 0.6 * px;
  rect[2] = 2 * pad + columns * 0.55 * px;
  rect[3] = 2 * pad + rows * 1.2 * px;
  rect[0] = margin;
  rect[1] = height - margin - rect[3];
}
