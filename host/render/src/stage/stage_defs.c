/* The stage's definitions: default makers and the names a scene file uses. */
#include "mr_stage.h"

#include <string.h>

static void set3f(float out[3], float a, float b, float c) {
  out[0] = a;
  out[1] = b;
  out[2] = c;
}

static void set3(double out[3], double a, double b, double c) {
  out[0] = a;
  out[1] = b;
  out[2] = c;
}

mr_material_def mr_default_material_def(void) {
  mr_material_def m;
  memset(&m, 0, sizeof m);
  m.cookie = MR_DEF_COOKIE;
  m.base_color[0] = m.base_color[1] = m.base_color[2] = 0.8f;
  m.base_color[3] = 1.0f;
  m.roughness = 0.6f;
  return m;
}

mr_model_def mr_default_model_def(void) {
  mr_model_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  d.shape = MR_SHAPE_SPHERE;
  set3(d.scale, 1, 1, 1);
  d.place = mr_pose_identity();
  for (int k = 0; k < MR_STAGE_MAX_MATERIALS; k++) d.materials[k] = mr_default_material_def();
  d.display = MR_DISPLAY_PARTICLE;
  /* No particle until one is named: mr_stage_create refuses -1. */
  d.particles[0] = d.particles[1] = d.particles[2] = -1;
  d.orient = MR_RIGID_INITIAL;
  d.influences = MR_SKIN_MAX_INFLUENCES;
  d.cast_shadow = true;
  return d;
}

mr_spot_def mr_default_spot_def(void) {
  mr_spot_def s;
  memset(&s, 0, sizeof s);
  s.cookie = MR_DEF_COOKIE;
  set3(s.position, 0, 3, 2);
  set3(s.target, 0, 0.5, 0);
  s.angle_deg = 25;
  set3f(s.color, 1, 1, 1);
  s.intensity = 1;
  return s;
}

mr_camera_def mr_default_camera_def(void) {
  mr_camera_def c;
  memset(&c, 0, sizeof c);
  c.cookie = MR_DEF_COOKIE;
  set3(c.position, 0, 1, 3);
  set3(c.target, 0, 0.6, 0);
  c.fov_deg = 45;
  return c;
}

static void default_lights(mr_lights_def *l) {
  set3f(l->ambient, 0.25f, 0.25f, 0.3f);
  set3f(l->sun_color, 1.0f, 0.96f, 0.9f);
  l->sun_intensity = 1;
  l->shadows = true;
  l->shadow_size = 0;
  l->shadow_filter = 0;
  for (int k = 0; k < MR_STAGE_MAX_SPOTS; k++) l->spots[k] = mr_default_spot_def();
}

mr_stage_def mr_default_stage_def(void) {
  mr_stage_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  default_lights(&d.lights);
  d.floor = true;
  d.floor_size = 8;
  set3f(d.floor_color, 0.55f, 0.45f, 0.35f);
  set3f(d.floor_color2, 0.45f, 0.36f, 0.28f);
  d.backdrop = true;
  d.backdrop_distance = 3;
  set3f(d.backdrop_color, 0.3f, 0.25f, 0.35f);
  d.proscenium = true;
  set3f(d.proscenium_color, 0.32f, 0.025f, 0.035f);
  set3f(d.trim_color, 0.78f, 0.55f, 0.16f);
  d.wings = true;
  set3f(d.wing_color, 0.018f, 0.016f, 0.02f);
  d.footlights = true;
  set3f(d.footlight_color, 1.0f, 0.72f, 0.42f);
  d.footlight_intensity = 1;
  d.bridge = false;
  d.board_width = 0.16;
  d.time_of_day = 0.5;
  set3f(d.sky_day, 0.45f, 0.65f, 0.9f);
  set3f(d.sky_night, 0.02f, 0.02f, 0.06f);
  d.stars = true;
  d.show_strings = true;
  set3f(d.string_color, 0.9f, 0.9f, 0.85f);
  d.show_frames = true;
  set3f(d.frame_color, 0.6f, 0.4f, 0.2f);
  d.frame_style = MR_FRAMES_SOLID;
  d.frame_thickness = 0.025;
  d.show_spheres = false;
  set3(d.orbit_target, 0, 0.6, 0);
  d.orbit_distance = 2.5;
  d.orbit_elevation_deg = 12;
  d.fov_deg = 45;
  for (int k = 0; k < MR_STAGE_MAX_CAMERAS; k++) d.cameras[k] = mr_default_camera_def();
  d.curtain.show = true;
  set3f(d.curtain.color, 0.42f, 0.02f, 0.04f);
  d.curtain.open_s = 1.5;
  d.curtain.close_s = 1.5;
  /* Off unless asked: in software its pool is lit again every frame,
   * 38 % more of a 1280x720 frame (host/render/README.md). */
  d.follow_spot.show = false;
  set3(d.follow_spot.position, 0, 3.2, 4);
  d.follow_spot.angle_deg = 8;
  set3f(d.follow_spot.color, 1.0f, 0.93f, 0.8f);
  d.follow_spot.intensity = 1.5;
  d.width = 1280;
  d.height = 720;
  return d;
}

static const char *const shape_names[] = { "file", "sphere", "box", "cylinder", "capsule", "cone" };
static const char *const mode_names[] = { "particle", "link", "rigid", "freeform" };

const char *mr_shape_name(mr_shape s) {
  return (int)s >= 0 && (size_t)s < sizeof shape_names / sizeof shape_names[0] ? shape_names[s]
                                                                               : "unknown";
}

int mr_shape_parse(const char *name, mr_shape *out) {
  for (size_t i = 0; name != NULL && i < sizeof shape_names / sizeof shape_names[0]; i++)
    if (strcmp(name, shape_names[i]) == 0) {
      *out = (mr_shape)i;
      return 0;
    }
  return -1;
}

const char *mr_display_mode_name(mr_display_mode m) {
  return (int)m >= 0 && (size_t)m < sizeof mode_names / sizeof mode_names[0] ? mode_names[m]
                                                                             : "unknown";
}

int mr_display_mode_parse(const char *name, mr_display_mode *out) {
  for (size_t i = 0; name != NULL && i < sizeof mode_names / sizeof mode_names[0]; i++)
    if (strcmp(name, mode_names[i]) == 0) {
      *out = (mr_display_mode)i;
      return 0;
    }
  return -1;
}
