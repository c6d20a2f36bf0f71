/* The range of every quantity a scene file gives, by its key. A value
 * outside is refused with its place, before it can ask for a run of 1e300
 * steps or a frame rate of 1e308 Hz. The bounds are far beyond any puppet
 * theater, yet small enough that nothing the physics computes from them
 * overflows or underflows: lengths within 1e6 m, masses between 1e-9 and
 * 1e6 kg, times between 1e-9 s and 1e6 s (11.6 days). host/scenes/FORMAT.md
 * lists this table; a test keeps the two equal. */
#include "scene_read.h"

#include <math.h>
#include <string.h>

static const mr_scene_range ranges[] = {
  /* sim */
  { "duration", 1e-6, 1e6, "s" },
  { "fps", 1, 1e4, "Hz" },
  /* ats */
  { "dt_initial", 1e-9, 1e3, "s" },
  { "dt_min", 1e-9, 1e3, "s" },
  { "dt_max", 1e-9, 1e3, "s" },
  { "dt_floor", 1e-12, 1e3, "s" },
  { "threshold_min", 1e-12, 1, "" },
  { "threshold_max", 1e-12, 1, "" },
  { "divergence", 1e-12, 1e3, "" },
  { "deviation_length", 1e-9, 1e6, "m" },
  { "error_length", 0, 1e6, "m" },
  { "error_speed", 0, 1e6, "m/s" },
  { "max_speed", 1e-6, 1e8, "m/s" },
  /* solver, contact, string correction */
  { "ks", 0, 1e9, "1/s²" },
  { "kd", 0, 1e9, "1/s" },
  { "tolerance", 1e-16, 1, "" },
  { "slop", 1e-9, 1, "m" },
  { "rest_speed", 0, 1e3, "m/s" },
  { "max_stretch", 1e-9, 1e3, "" },
  /* world */
  { "gravity", -1e4, 1e4, "m/s²" },
  { "drag", 0, 1e6, "N s/m" },
  /* particles and constraints */
  { "position", -1e6, 1e6, "m" },
  { "velocity", -1e5, 1e5, "m/s" },
  { "mass", 1e-9, 1e6, "kg" },
  { "radius", 0, 1e3, "m" },
  { "length", 0, 1e6, "m" },
  { "offset", -1e6, 1e6, "m" },
  /* forces */
  { "stiffness", 0, 1e9, "N/m" },
  { "damping", 0, 1e6, "N s/m" },
  { "rest", 0, 1e6, "m" },
  { "max_force", 0, 1e9, "N" },
  { "reach", 0, 1e6, "m" },
  { "fraction", 0, 1e3, "" },
  { "max_scale", 0, 1e3, "" },
  { "gain", 0, 1e9, "1/s²" },
  /* floor and parts */
  { "height", -1e6, 1e6, "m" },
  { "restitution", 0, 1, "" },
  { "friction", 0, 1e3, "" },
  /* control */
  { "rotation", -1e6, 1e6, "°" },
  { "max_turn_rate", 1e-6, 1e8, "°/s" },
  { "max_accel", 1e-6, 1e9, "m/s²" },
  { "max_turn_accel", 1e-6, 1e10, "°/s²" },
  { "t", 0, 1e6, "s" },
  { "amplitude", -1e6, 1e6, "m" },
  { "quadrature", -1e6, 1e6, "m" },
  { "frequency", 1e-6, 1e4, "Hz" },
  { "phase", -1e6, 1e6, "°" },
  { "start", 0, 1e6, "s" },
  { "ramp", 0, 1e6, "s" },
  /* expect */
  { "max_deviation", 0, 1e3, "" },
  { "min_mean_dt", 0, 1e6, "s" },
  { "min_string_stretch", 0, 1e6, "" },
  { "max_string_stretch", 0, 1e6, "" },
  { "max_penetration", 0, 1e6, "m" },
  { "settle", 0, 1e6, "s" },
  { "creep", 0, 1e6, "m" },
  { "jitter", 0, 1e8, "m/s" },
  /* models (position and rotation as above) */
  { "scale", 1e-6, 1e6, "" },
  { "color", 0, 1, "" },
  { "roughness", 0, 1, "" },
  { "metallic", 0, 1, "" },
  { "emissive", 0, 100, "" },
  /* lights */
  { "ambient", 0, 1, "" },
  { "intensity", 0, 1e3, "" },
  { "angle", 0.1, 89, "°" },
  { "target", -1e6, 1e6, "m" },
  /* stage */
  { "time_of_day", 0, 1, "" },
  { "size", 1e-3, 1e6, "m" },
  { "color2", 0, 1, "" },
  { "distance", 1e-3, 1e6, "m" },
  { "day", 0, 1, "" },
  { "night", 0, 1, "" },
  { "azimuth", -360, 360, "°" },
  { "open", 0, 1e6, "s" },
  { "close", 0, 1e6, "s" },
  { "width", 1e-3, 1e6, "m" },
  /* The orbit camera: at ±90 it would look along its up (+y) and draw
   * only sky. A star may sit overhead. */
  { "elevation", -89, 89, "°" },
  { "star elevation", -90, 90, "°" },
  { "brightness", 0, 1, "" },
  /* camera */
  { "fov", 1, 170, "°" },
};
enum { N_RANGES = sizeof ranges / sizeof ranges[0] };

/* Any other number: a bound on size only. */
static const mr_scene_range other = { "", -1e9, 1e9, "" };

const mr_scene_range *mr_scene_range_of(const char *key) {
  for (int i = 0; i < N_RANGES; i++)
    if (ranges[i].key[0] == key[0] && strcmp(ranges[i].key, key) == 0) return &ranges[i];
  return &other;
}

const mr_scene_range *mr_scene_range_at(int i) {
  return i >= 0 && i < N_RANGES ? &ranges[i] : NULL;
}

int mr_scene_range_check(mr_reader *r, const mr_ynode *node, const char *key, double v) {
  const mr_scene_range *g = mr_scene_range_of(key);
  if (v >= g->lo && v <= g->hi) return 0;
  return mr_scene_read_fail(r, node, MR_SCENE_ERR_VALUE,
                            "expected %s between %g and %g%s%s, got %g", key, g->lo, g->hi,
                            g->unit[0] ? " " : "", g->unit, v);
}
