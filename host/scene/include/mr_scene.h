/* Scene files: a marionette world declared in YAML (host/scenes/FORMAT.md).
 *
 * mr_scene_load() reads and checks a file into an mr_scene, a plain
 * description with every item's file position kept. mr_scene_build() turns
 * it into a physics world with only the passes the scene declares. Errors
 * never print: they fill an mr_scene_error whose text reads
 * "FILE:LINE:COLUMN: what was expected". */
#ifndef MR_SCENE_H
#define MR_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mr_scene_status {
  MR_SCENE_OK = 0,
  MR_SCENE_ERR_IO,     /* missing or unreadable file */
  MR_SCENE_ERR_SYNTAX, /* not YAML, or not one document */
  MR_SCENE_ERR_SCHEMA, /* unknown key, wrong type, missing key */
  MR_SCENE_ERR_VALUE,  /* NaN, negative mass, coincident particles, ... */
  MR_SCENE_ERR_BUILD,  /* the physics library refused the world */
  MR_SCENE_ERR_NOMEM
} mr_scene_status;

typedef struct mr_scene_error {
  mr_scene_status status;
  int line;   /* 1-based; 0 when the error concerns the whole file */
  int column; /* 1-based; 0 when the error concerns the whole file */
  char message[320];
  /* "FILE:LINE:COLUMN: message", or "FILE: message" without a position. */
  char text[1024];
} mr_scene_error;

/* A position in the scene file. */
typedef struct mr_scene_pos {
  int line;
  int column;
} mr_scene_pos;

/* The effects a scene may call for, one per physics pass family. The world
 * is built with exactly these; an item whose effect is not declared is a
 * load error. */
typedef enum mr_scene_effect {
  MR_SCENE_FX_GRAVITY = 1u << 0,
  MR_SCENE_FX_DRAG = 1u << 1,        /* the paper's particle friction (§7) */
  MR_SCENE_FX_SPRINGS = 1u << 2,     /* spring/damper pairs (§5.1) */
  MR_SCENE_FX_STRINGS = 1u << 3,     /* frame-to-puppet strings (§6.2) */
  MR_SCENE_FX_ANTIGRAVITY = 1u << 4, /* acted/trigger pairs (§6.2) */
  MR_SCENE_FX_TRIGGERED = 1u << 5,   /* triggered action force (§6.2) */
  MR_SCENE_FX_SINE_SPRINGS = 1u << 6,/* capped sine-shaped springs (§6.2) */
  MR_SCENE_FX_CONSTRAINTS = 1u << 7, /* distance, pins, rigid groups (§5.2) */
  MR_SCENE_FX_FLOOR = 1u << 8,       /* floor collisions and contact (§4.4) */
  MR_SCENE_FX_SELF_COLLISION = 1u << 9, /* sphere trees within a puppet */
  MR_SCENE_FX_STRING_CORRECTION = 1u << 10, /* §6.2, [19] */
  MR_SCENE_FX_CONTROL = 1u << 11     /* the kinematic control frame (§6.2) */
} mr_scene_effect;

enum { MR_SCENE_FX_COUNT = 12 };

/* Name of bit i (0..MR_SCENE_FX_COUNT-1) as written in scene files. */
const char *mr_scene_effect_name(unsigned bit_index);

enum { MR_SCENE_NAME_MAX = 48 };

typedef struct mr_scene_particle {
  char name[MR_SCENE_NAME_MAX];
  double position[3];
  double velocity[3];
  double mass;
  double radius;
  bool pinned; /* held where it starts by a pin constraint */
  mr_scene_pos pos;
} mr_scene_particle;

/* A reference to a point: a particle, or a control-frame point. The two
 * share one namespace in a scene. */
typedef struct mr_scene_ref {
  bool control;
  size_t index;
} mr_scene_ref;

/* |p_a - p_b| = length (§5.2). */
typedef struct mr_scene_distance {
  size_t a, b;
  double length;
  mr_scene_pos pos;
} mr_scene_distance;

typedef struct mr_scene_spring {
  size_t a, b;
  double rest, stiffness, damping;
  mr_scene_pos pos;
} mr_scene_spring;

/* A string from control-frame point `control` to particle `particle`: it
 * pulls, never pushes. */
typedef struct mr_scene_string {
  size_t control, particle;
  double rest, stiffness, damping;
  mr_scene_pos pos;
} mr_scene_string;

/* §6.2: force rises as a shifted sine to max_force at `reach`, then holds. */
typedef struct mr_scene_sine_spring {
  mr_scene_ref a, b;
  double rest, max_force, reach, damping;
  mr_scene_pos pos;
} mr_scene_sine_spring;

/* Antigravity on `acted`, scaled by the distance to `trigger` (§6.2). */
typedef struct mr_scene_antigravity {
  mr_scene_ref acted, trigger;
  double fraction;  /* of the puppet's weight */
  double max_scale; /* cap on d/d0 */
  mr_scene_pos pos;
} mr_scene_antigravity;

/* Triggered action force (§6.2). */
typedef struct mr_scene_triggered {
  mr_scene_ref acted, control, trigger;
  double gain, max_force;
  mr_scene_pos pos;
} mr_scene_triggered;

typedef struct mr_scene_group {
  char name[MR_SCENE_NAME_MAX];
  size_t *members;
  size_t count;
  mr_scene_pos pos;
} mr_scene_group;

/* A collision part for the sphere tree (§4.4). */
typedef struct mr_scene_part {
  size_t *members;
  size_t count;
  double radius;
  int segment_spheres;
  double restitution;
  double friction; /* Coulomb mu against other parts */
  mr_scene_pos pos;
} mr_scene_part;

typedef struct mr_scene_control_point {
  char name[MR_SCENE_NAME_MAX];
  double offset[3]; /* in the frame's own coordinates */
  mr_scene_pos pos;
} mr_scene_control_point;

/* A control-frame pose: position, and rotation as x-y-z Euler angles in
 * degrees applied in that order. */
typedef struct mr_scene_pose {
  double position[3];
  double rotation_deg[3];
} mr_scene_pose;

typedef struct mr_scene_keyframe {
  double t;
  mr_scene_pose pose;
  mr_scene_pos pos;
} mr_scene_keyframe;

typedef enum mr_scene_track_kind {
  MR_SCENE_TRACK_NONE,
  MR_SCENE_TRACK_KEYFRAMES, /* piecewise, smoothstep-eased between keys */
  MR_SCENE_TRACK_OSCILLATE  /* pose + ramp * amplitude * sin(2 pi f t + phase) */
} mr_scene_track_kind;

typedef struct mr_scene_track {
  mr_scene_track_kind kind;
  bool linear; /* keyframes: linear instead of eased */
  mr_scene_keyframe *keys;
  size_t n_keys;
  double amplitude[3];     /* oscillate: metres per axis */
  double amplitude_deg[3]; /* oscillate: degrees per axis */
  double frequency_hz;
  double phase_deg;
  double start; /* oscillate: time it starts */
  double ramp;  /* oscillate: seconds over which the amplitude grows */
} mr_scene_track;

typedef struct mr_scene_floor {
  bool present;
  double height;
  double restitution;
  double friction; /* Coulomb mu */
  mr_scene_pos pos;
} mr_scene_floor;

/* Numbers left NaN (or 0 for counts, "" for names) take the physics
 * library's defaults, which are the paper's (§4.5, §7). */
typedef struct mr_scene_settings {
  char integrator[24];
  char method[24];
  double ks, kd;
  double tolerance;
  long max_iterations;
  double dt_initial, dt_min, dt_max;
  double threshold_min, threshold_max; /* relative deviation, 1e-4 = 0.01 % */
  double divergence;                   /* reset above this (§7) */
  double deviation_length;
  long max_steps;
  double contact_slop, rest_speed;
  double string_max_stretch;
  long string_iterations;
} mr_scene_settings;

/* Expected outcome, checked by `marionette sim --check`. Unset numbers are
 * NaN, unset counts -1. */
typedef struct mr_scene_expect {
  bool present;
  bool finite;
  double max_deviation;
  long resets_min, resets_max;
  double min_mean_dt;
  /* The largest length/rest ratio any string reaches at an accepted step
   * must be at least this: proof that a stretch case really stretched. */
  double min_string_stretch;
  char load_error[256]; /* the load must fail with text containing this */
  bool has_load_error;
  /* Creep and jitter: after `settle` seconds, no listed particle moves
   * farther than creep from where it was at `settle`, and none is faster
   * than jitter (m/s) at any accepted step. */
  size_t *watch;
  size_t n_watch;
  double settle, creep, jitter;
  /* The state hash at the end of a run of sim.duration: determinism
   * pinned, not only repeated. */
  bool has_state_hash;
  uint64_t state_hash;
  mr_scene_pos pos;
} mr_scene_expect;

typedef struct mr_scene {
  char *path;
  char name[96];
  unsigned effects; /* mr_scene_effect bits */
  double gravity[3];
  double drag; /* N s/m */
  mr_scene_settings settings;
  double duration; /* default simulated time for `marionette sim` */
  double fps;      /* rate at which the control track is sampled */

  mr_scene_particle *particles;
  size_t n_particles;
  mr_scene_distance *distances;
  size_t n_distances;
  mr_scene_group *groups;
  size_t n_groups;
  mr_scene_spring *springs;
  size_t n_springs;
  mr_scene_string *strings;
  size_t n_strings;
  mr_scene_sine_spring *sine_springs;
  size_t n_sine_springs;
  mr_scene_antigravity *antigravities;
  size_t n_antigravities;
  mr_scene_triggered *triggered;
  size_t n_triggered;
  mr_scene_part *parts;
  size_t n_parts;
  mr_scene_floor floor;

  mr_scene_control_point *control_points;
  size_t n_control_points;
  mr_scene_pose control_pose; /* at t = 0 before the track */
  mr_scene_track track;

  mr_scene_expect expect;
} mr_scene;

/* Reads and checks path. On failure returns non-zero, fills *err and leaves
 * *scene empty (safe to mr_scene_free). */
mr_scene_status mr_scene_load(const char *path, mr_scene *scene, mr_scene_error *err);

/* The same from text in memory; name is used in error texts. */
mr_scene_status mr_scene_load_text(const char *name, const char *text, size_t len,
                                   mr_scene *scene, mr_scene_error *err);

void mr_scene_free(mr_scene *scene);

/* expect.load_error of a file that may itself fail to load (hard case 8):
 * 0 and the text in out, or -1 when the file has none or is not YAML. */
int mr_scene_expected_load_error(const char *path, char *out, size_t size);

/* Index of a particle or control point by name, or (size_t)-1. */
size_t mr_scene_find_particle(const mr_scene *scene, const char *name);
size_t mr_scene_find_control_point(const mr_scene *scene, const char *name);

/* The control frame's pose at time t from the scene's track (the pose
 * alone when there is no track). */
void mr_scene_control_pose_at(const mr_scene *scene, double t, mr_scene_pose *out);

/* World position of control point i under pose. */
void mr_scene_control_point_world(const mr_scene *scene, size_t i,
                                  const mr_scene_pose *pose, double out[3]);

#ifdef __cplusplus
}
#endif

#endif
