/* Scene files: a marionette world declared in YAML (host/scenes/FORMAT.md).
 *
 * mr_scene_load() reads and checks a file into an mr_scene: the physics
 * library's own definition structs (mr_world_def, mr_particle_def, ...),
 * each started from its default maker and changed only where the file says
 * so, with the file position of every item kept. mr_scene_world.h builds
 * and runs the world.
 *
 * Ids inside the definitions are world ids: particle i of the scene is
 * world particle i, and control point j is world particle n_particles + j.
 *
 * Errors never print: they fill an mr_scene_error whose text reads
 * "FILE:LINE:COLUMN: what was expected". */
#ifndef MR_SCENE_H
#define MR_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mr_control.h"
#include "mr_physics.h"
#include "mr_pose.h"
#include "mr_stage.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mr_scene_status {
  MR_SCENE_OK = 0,
  MR_SCENE_ERR_IO = -1,     /* missing or unreadable file */
  MR_SCENE_ERR_SYNTAX = -2, /* not YAML, or not one document */
  MR_SCENE_ERR_SCHEMA = -3, /* unknown key, wrong type, missing key */
  MR_SCENE_ERR_VALUE = -4,  /* NaN, negative mass, coincident particles, ... */
  MR_SCENE_ERR_BUILD = -5,  /* the physics library refused the world */
  MR_SCENE_ERR_NOMEM = -6
} mr_scene_status;

typedef struct mr_scene_error {
  mr_scene_status status;
  int line;   /* 1-based; 0 when the error concerns the whole file */
  int column; /* 1-based; 0 when the error concerns the whole file */
  char message[320];
  /* "FILE:LINE:COLUMN: message", or "FILE: message" without a position. */
  char text[1024];
} mr_scene_error;

/* Where an item starts in the file. */
typedef struct mr_scene_pos {
  int line;
  int column;
} mr_scene_pos;

enum { MR_SCENE_NAME_MAX = 48 };

typedef struct mr_scene_particle {
  char name[MR_SCENE_NAME_MAX];
  mr_particle_def def;
  bool pinned; /* held where it starts by a pin constraint */
  mr_scene_pos pos;
} mr_scene_particle;

typedef struct mr_scene_distance {
  mr_distance_def def; /* length: as the file says, else the start distance */
  mr_scene_pos pos;
} mr_scene_distance;

/* A rigid group (§5.1); def.particles belongs to the scene. */
typedef struct mr_scene_group {
  char name[MR_SCENE_NAME_MAX];
  mr_rigid_group_def def;
  mr_scene_pos pos;
} mr_scene_group;

/* One applied force (§5.1, §6.2) of the kind `kind`, the effect bit the
 * physics' force table gives it (MR_EFFECT_SPRINGS, ...); def holds that
 * kind's definition. */
typedef struct mr_scene_force {
  uint32_t kind;
  union {
    mr_spring_def spring;
    mr_string_def string;
    mr_sine_spring_def sine_spring;
    mr_antigravity_def antigravity;
    mr_triggered_def triggered;
  } def;
  mr_scene_pos pos;
} mr_scene_force;

/* A collision part for the sphere tree (§4.4); def.particles belongs to
 * the scene. */
typedef struct mr_scene_part {
  mr_part_def def;
  mr_scene_pos pos;
} mr_scene_part;

/* A puppet (physics.puppets): a unit of particles with its own whole mass
 * for the §6.2 forces and its own sphere tree. Its particles are
 * particles[first .. first + count), named "puppet.particle". */
typedef struct mr_scene_puppet {
  char name[MR_SCENE_NAME_MAX];
  int id; /* the world's puppet number */
  size_t first, count;
  mr_scene_pos pos;
} mr_scene_puppet;

/* A glove mapping (the scene's `mapping:`), for the control library. */
typedef struct mr_scene_mapping {
  mr_mapping_def def;
  mr_scene_pos pos;
} mr_scene_mapping;

typedef struct mr_scene_floor {
  bool present;
  mr_plane_def def;
  mr_scene_pos pos;
} mr_scene_floor;

/* A control frame's point (§6.1-6.2): a kinematic particle the strings
 * hang from, moved by setting the frame's pose. */
typedef struct mr_scene_control_point {
  char name[MR_SCENE_NAME_MAX];
  double offset[3]; /* in the frame's own coordinates */
  size_t frame;     /* index into mr_scene.frames */
  mr_scene_pos pos;
} mr_scene_control_point;

typedef struct mr_scene_keyframe {
  double t;
  mr_pose pose;
  mr_scene_pos pos;
} mr_scene_keyframe;

typedef enum mr_scene_track_kind {
  MR_SCENE_TRACK_NONE,
  MR_SCENE_TRACK_KEYFRAMES, /* piecewise, smoothstep-eased between keys */
  MR_SCENE_TRACK_OSCILLATE  /* the start pose moved by s(t) times an amplitude */
} mr_scene_track_kind;

typedef struct mr_scene_track {
  mr_scene_track_kind kind;
  bool linear; /* keyframes: linear instead of eased */
  mr_scene_keyframe *keys;
  size_t n_keys;
  /* oscillate: s(t) = ramp(t) sin(2 pi f (t - start) + phase) scales the
   * displacement and the turn, both given at s = 1. */
  double amplitude[3];  /* m */
  double quadrature[3]; /* m, moved by c(t), the cosine a quarter period ahead */
  double turn[4];       /* the rotation at s = 1, in the frame's own axes */
  double frequency_hz;
  double phase_rad;
  double start; /* s */
  double ramp;  /* s over which the amplitude grows linearly */
} mr_scene_track;

/* Which glove drives a control frame (`control.glove`): the k-th glove the
 * theater was given, the glove with a uid, or the first glove of a hand. */
typedef enum mr_scene_bind {
  MR_SCENE_BIND_ORDER = 0,
  MR_SCENE_BIND_UID,
  MR_SCENE_BIND_HAND
} mr_scene_bind;

typedef struct mr_scene_glove_bind {
  mr_scene_bind by;
  int order;       /* BIND_ORDER: 0-based */
  uint32_t uid[3]; /* BIND_UID: the INFO's uid words */
  int uid_words;   /* 1: uid[0] only (as a status line shows it); 3: all */
  int hand;        /* BIND_HAND: 0 left, 1 right (the protocol's GP_HAND_*) */
} mr_scene_glove_bind;

/* A control frame: the scene's own (physics.control) or a puppet's. Its
 * points are control_points[first_point .. first_point + n_points). */
typedef struct mr_scene_frame {
  char puppet[MR_SCENE_NAME_MAX]; /* the puppet it belongs to, "" for the scene's */
  size_t first_point, n_points;
  mr_pose pose; /* at t = 0 before the track */
  /* How fast the frame may follow its track or glove (max_speed, m/s;
   * max_turn_rate, read in deg/s, kept in rad/s): a jump in the input is
   * spread over as many frames as these allow (mr_pose_approach). */
  double max_speed, max_turn;
  /* How hard a glove may start and stop the frame (max_accel, m/s²;
   * max_turn_accel, read in deg/s², kept in rad/s²): a glove's jump (its
   * first reading, a reconnection, a frame given up to catch up) would
   * otherwise start the bar at max_speed at once and throw the puppet on
   * its taut strings. A track is the scene's own motion: not limited. */
  double max_accel, max_turn_accel;
  mr_scene_track track;
  mr_scene_glove_bind glove;
  mr_scene_pos pos;
} mr_scene_frame;

/* Expected outcome, checked by `marionette sim --check`. Unset numbers are
 * NaN, unset counts -1. */
typedef struct mr_scene_expect {
  bool present;
  bool finite;
  double max_deviation;
  long resets_min, resets_max;
  double min_mean_dt;
  double min_string_stretch; /* some string reaches this many times its rest */
  double max_string_stretch; /* no string ever longer than this times its rest */
  double max_speed;          /* no particle faster than this, m/s */
  double max_penetration;    /* no two bodies deeper into each other, m */
  char load_error[256];      /* the load must fail with text containing this */
  bool has_load_error;
  /* Creep and jitter: after `settle` seconds no watched particle moves
   * farther than creep from where it was at `settle`, nor faster than
   * jitter (m/s). */
  int *watch; /* world ids */
  size_t n_watch;
  double settle, creep, jitter;
  /* The state hash at the end of a run of sim.duration. */
  bool has_state_hash;
  uint64_t state_hash;
  mr_scene_pos pos;
} mr_scene_expect;

/* The default guard on one run's step tries (sim.max_steps). */
#define MR_SCENE_MAX_STEPS 2000000L
/* The defaults of control.max_speed (m/s) and control.max_turn_rate
 * (deg/s): above the fastest a hand moves a control bar (Fig. 10's extreme
 * is 11 m/s), far below a teleport (2 m in a 60 Hz frame is 120 m/s). */
#define MR_SCENE_CONTROL_MAX_SPEED    20.0
#define MR_SCENE_CONTROL_MAX_TURN_DEG 1440.0
/* The defaults of control.max_accel (m/s²) and control.max_turn_accel
 * (deg/s²): a bar that never drops away faster than gravity pulls the
 * puppet after it keeps its strings taut, so the puppet is not thrown
 * over the bar; the turn's share at a bar end 0.3 m out is about half g.
 * A hand moving the bar through the default mapping's range needs under
 * 2 m/s² and 400°/s². */
#define MR_SCENE_CONTROL_MAX_ACCEL          10.0
#define MR_SCENE_CONTROL_MAX_TURN_ACCEL_DEG 1000.0

typedef struct mr_scene {
  char *path;
  char name[96];
  mr_world_def world; /* effects, gravity, drag, ATS, solver, contacts */
  double duration;    /* default simulated time for `marionette sim` */
  double fps;         /* rate at which the control track is sampled; 0: every step */
  /* sim.present: frames shown from steps landed on each frame time (the
   * paper's, false), or from steps at the ATS's own Δt with the state
   * interpolated between the two around each frame time (true). */
  bool interpolate;
  long max_steps; /* a run stops past this many step tries (accepted and
                         rejected): MR_SCENE_MAX_STEPS unless sim.max_steps */

  mr_scene_particle *particles;
  size_t n_particles;
  mr_scene_distance *distances;
  size_t n_distances;
  mr_scene_group *groups;
  size_t n_groups;
  mr_scene_force *forces; /* in file order within each kind */
  size_t n_forces;
  mr_scene_part *parts;
  size_t n_parts;
  mr_scene_floor floor;
  mr_scene_puppet *puppets; /* none when the file declares no puppets: its
                               particles are then one puppet, number 0 */
  size_t n_puppets;

  mr_scene_mapping *mappings; /* none: the default mapping (mr_default_mapping_def) */
  size_t n_mappings;

  mr_scene_frame *frames; /* physics.control first, then the puppets' */
  size_t n_frames;
  mr_scene_control_point *control_points; /* every frame's, frame by frame */
  size_t n_control_points;

  mr_scene_expect expect;

  /* What the stage shows (the scene's models:, lights:, stage: and
   * camera:, host/scenes/FORMAT.md), its world ids as above. Every array
   * it points to belongs to the scene. Without a models: section: a thin
   * capsule per distance constraint and a small sphere per particle. */
  mr_stage_def stage;
} mr_scene;

/* Reads and checks path. On failure returns non-zero, fills *err and leaves
 * *scene empty (safe to mr_scene_free). */
mr_scene_status mr_scene_load(const char *path, mr_scene *scene, mr_scene_error *err);

/* As mr_scene_load, but the stage is left unframed: the set's size and the
 * audience's camera, which come from sampling the whole track and which
 * only drawing reads, stay as the file gives them (unset where it gives
 * none). The same file is checked the same way and gives the same world.
 * For a program that simulates and never draws (`marionette sim`): the
 * framing costs more than the rest of a short run (a whole `marionette sim
 * --time 0.001 humanoid.yaml` process: 13.7 M instructions, 7.2 M without
 * it). */
mr_scene_status mr_scene_load_unframed(const char *path, mr_scene *scene, mr_scene_error *err);

/* The same from text in memory; name is used in error texts. */
mr_scene_status mr_scene_load_text(const char *name, const char *text, size_t len, mr_scene *scene,
                                   mr_scene_error *err);

void mr_scene_free(mr_scene *scene);

/* expect.load_error of a file that may itself fail to load (hard case 8):
 * 0 and the text in out, or -1 when the file has none or is not YAML. */
int mr_scene_expected_load_error(const char *path, char *out, size_t size);

/* Index of a particle or control point by name, or (size_t)-1. */
size_t mr_scene_find_particle(const mr_scene *scene, const char *name);
size_t mr_scene_find_control_point(const mr_scene *scene, const char *name);

/* Control frame k's pose at time t from its track (its start pose when it
 * has none; the identity when the scene has no frame k). */
void mr_scene_frame_pose_at(const mr_scene *scene, size_t k, double t, mr_pose *out);
/* How fast that pose moves at t: velocity (m/s) and angular velocity
 * (rad/s, world axes); zero for a frame without a track. */
void mr_scene_frame_rates_at(const mr_scene *scene, size_t k, double t, double vel[3],
                             double omega[3]);

/* World position of control point i under pose. */
void mr_scene_control_point_world(const mr_scene *scene, size_t i, const mr_pose *pose,
                                  double out[3]);

#ifdef __cplusplus
}
#endif

#endif
