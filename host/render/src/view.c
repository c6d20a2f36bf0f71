/* Default makers, backend names, and the orbit camera. */
#include <math.h>
#include <string.h>

#include "render_internal.h"

static const double MR_PI = 3.14159265358979323846;

static const char *const backend_names[] = { "auto", "window", "osmesa", "egl" };

const char *mr_render_backend_name(mr_render_backend b) {
  if ((int)b < 0 || (size_t)b >= sizeof backend_names / sizeof backend_names[0]) return "?";
  return backend_names[b];
}

int mr_render_backend_parse(const char *name, mr_render_backend *out) {
  if (!name || !out) return -1;
  for (size_t i = 0; i < sizeof backend_names / sizeof backend_names[0]; i++) {
    if (strcmp(name, backend_names[i]) == 0) {
      *out = (mr_render_backend)i;
      return 0;
    }
  }
  return -1;
}

mr_render_def mr_default_render_def(void) {
  mr_render_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_RENDER_COOKIE;
  d.backend = MR_RENDER_AUTO;
  d.samples = 4;
  return d;
}

void mr_render_view_orbit(mr_render_view *v, const double target[3], double distance,
                          double azimuth_deg, double elevation_deg) {
  const double az = azimuth_deg * MR_PI / 180.0, el = elevation_deg * MR_PI / 180.0;
  /* Azimuth 0 looks from +z towards -z (the backdrop); elevation raises
   * the eye above the target. */
  for (int i = 0; i < 3; i++) v->target[i] = target[i];
  v->eye[0] = target[0] + distance * cos(el) * sin(az);
  v->eye[1] = target[1] + distance * sin(el);
  v->eye[2] = target[2] + distance * cos(el) * cos(az);
  v->up[0] = 0;
  v->up[1] = 1;
  v->up[2] = 0;
}

mr_render_view mr_default_render_view(const mr_stage_def *stage) {
  mr_render_view v;
  memset(&v, 0, sizeof v);
  const double target[3] = { 0, 0.6, 0 };
  if (stage) {
    mr_render_view_orbit(&v, stage->orbit_target, stage->orbit_distance, stage->orbit_azimuth_deg,
                         stage->orbit_elevation_deg);
    v.fov_deg = stage->fov_deg;
    v.time_of_day = stage->time_of_day;
  } else {
    mr_render_view_orbit(&v, target, 2.5, 0, 12);
    v.fov_deg = 45;
    v.time_of_day = 0.5;
  }
  v.show_rigging = true;
  return v;
}
