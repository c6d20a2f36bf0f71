/* Default makers, backend names, and the orbit camera. */
#include <string.h>

#include "render_internal.h"

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
  d.cookie = MR_DEF_COOKIE;
  d.backend = MR_RENDER_AUTO;
  d.samples = 0;
  return d;
}

/* The eye's position is mr_stage's (mr_orbit_eye): one orbit camera,
 * whether the program turns it or the renderer starts from it. */
void mr_render_view_orbit(mr_render_view *v, const mr_orbit *o) {
  for (int i = 0; i < 3; i++) v->target[i] = o->target[i];
  mr_orbit_eye(o, v->eye);
  v->up[0] = 0;
  v->up[1] = 1;
  v->up[2] = 0;
  v->fov_deg = o->fov_deg;
}

mr_render_view mr_default_render_view(const mr_stage_def *stage) {
  mr_render_view v;
  memset(&v, 0, sizeof v);
  if (stage) {
    const mr_orbit o = mr_orbit_of_stage(stage);
    mr_render_view_orbit(&v, &o);
    v.time_of_day = stage->time_of_day;
  } else {
    const mr_orbit o = {
      .target = { 0, 0.6, 0 }, .distance = 2.5, .azimuth_deg = 0, .elevation_deg = 12, .fov_deg = 45
    };
    mr_render_view_orbit(&v, &o);
    v.time_of_day = 0.5;
  }
  v.show_rigging = true;
  return v;
}
