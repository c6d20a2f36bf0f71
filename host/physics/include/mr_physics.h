/* mr_physics: the constrained particle solver of the marionette theater.
 *
 * Particles with mass, forces (gravity, springs, dampers, drag, strings and
 * the paper's puppet forces), constraints solved with Lagrange multipliers
 * (§5.2, eq. 8), impulses at collisions (§5.3, eq. 9), RK4 with an adaptive
 * time step (§4.5), plane and sphere-tree collisions (§4.4, §5.4) and a
 * divergence reset (§7). The mathematics is in host/physics/README.md.
 *
 * Manners:
 *  - Things are made from definition structs filled by a default maker
 *    (mr_default_world_def(), ...), so a new field never breaks a caller.
 *    The maker stamps a cookie that every create/add call checks, so a
 *    struct zeroed by hand (mr_spring_def d = {0}) is refused with
 *    MR_ERR_ARG instead of making a spring of zero length and stiffness.
 *  - Names: mr_default_x_def() makes a definition, mr_world_add_x() adds it,
 *    mr_x_verb() does the rest. A read of the world is mr_world_<noun>(): a
 *    scalar is returned; anything larger goes to an out pointer and the call
 *    returns an mr_status.
 *  - Ids are small non-negative ints, in creation order, one range per kind.
 *  - Every function that can fail returns an mr_status; the world keeps a
 *    message naming what and where (mr_world_last_error). Nothing prints,
 *    nothing aborts. Bad input (NaN, negative mass, coincident particles,
 *    zero-length constraints, unknown ids) is refused when it is added.
 *  - Time is always an argument: the library never reads a clock, so the
 *    same world and the same inputs give bit-identical states.
 *  - Units are SI (m, kg, s, N) unless a name says otherwise.
 *  - Only the effects a world declares exist in it: the step runs a list of
 *    passes built at creation; adding an element of an undeclared effect is
 *    refused with MR_ERR_NOT_DECLARED.
 */
#ifndef MR_PHYSICS_H
#define MR_PHYSICS_H

#include <stddef.h>
#include <stdint.h>

#include "mr_def.h"
#include "mr_pose.h"
#include "mr_solve_method.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- status */

typedef enum mr_status {
  MR_OK = 0,
  /* Not failures: the call did its work and has something to report. */
  MR_DIVERGED = 1,  /* the state went NaN/Inf or past the divergence bound
                        and was reset to its start configuration (§7) */
  MR_DEPENDENT = 2, /* dependent (redundant) constraint rows were found;
                        their multipliers are zero, forces stay bounded */
  /* Failures: nothing was changed. */
  MR_ERR_ARG = -1, /* NULL pointer, bad count, out-of-range value */
  MR_ERR_NOMEM = -2,
  MR_ERR_ID = -3,           /* unknown particle/frame/... id */
  MR_ERR_NONFINITE = -4,    /* NaN or Inf in an input */
  MR_ERR_DEGENERATE = -5,   /* coincident particles, zero length, zero normal,
                               coplanar rigid group, ... */
  MR_ERR_NOT_DECLARED = -6, /* the world did not declare that effect */
  MR_ERR_TIME = -7,         /* t_target earlier than the world time */
  MR_ERR_LIMIT = -8,        /* max_steps_per_call reached before t_target */
  MR_ERR_SOLVER = -9        /* the linear solver could not run (out of
                               memory, or the method is not built in) */
} mr_status;

const char *mr_status_name(mr_status s); /* "ok", "diverged", ... */

/* ---------------------------------------------------------- definitions */

/* ---------------------------------------------------------- force kinds */

/* The applied-force kinds (§5.1, §6.2), in the order their passes run. Each
 * line X(ID, stem, name) makes the effect bit MR_EFFECT_ID, the pass
 * MR_PASS_ID, the name both go by in files and reports, and the world's
 * storage for the kind's elements; `stem` names the kind's pass function
 * (stem_pass) in src/forces.c.
 *
 * To add a force kind, touch three places:
 *   1. a line here;
 *   2. its definition struct, mr_default_x_def() and mr_world_add_x() in
 *      the "forces" section below, and its evaluation in src/forces.c (its
 *      element struct, stem_pass, the maker and the add call);
 *   3. its reader in the scene library, which fills the definition from
 *      mr_default_x_def() and calls mr_world_add_x().
 * Nothing else lists the kinds: names, passes, counters and storage follow. */
#define MR_FORCE_KINDS(X)                                                              \
  X(GRAVITY, gravity, "gravity")                /* m g on every dynamic particle */    \
  X(DRAG, drag, "drag")                         /* viscous friction −drag·v */      \
  X(SPRINGS, springs, "springs")                /* springs and dampers */              \
  X(STRINGS, strings, "strings")                /* frame → puppet strings (§6.2) */ \
  X(ANTIGRAVITY, antigravity, "antigravity")    /* §6.2 antigravity forces */         \
  X(TRIGGERED, triggered, "triggered")          /* §6.2 triggered action forces */    \
  X(SINE_SPRINGS, sine_springs, "sine-springs") /* §6.2 capped sine-shaped springs */

/* The effects that are not applied forces, X(ID, stem, name) alike. */
#define MR_OTHER_EFFECTS(X)                                                                       \
  X(CONSTRAINTS, constraints, "constraints")          /* distance, pin, curve, rigid groups */    \
  X(PLANES, planes, "planes")                         /* floor and other planes (§4.4) */        \
  X(SELF_COLLISION, self_collision, "self-collision") /* sphere trees in one puppet */            \
  X(PUPPET_COLLISION, puppet_collision, "puppet-collision")    /* sphere trees between puppets */ \
  X(STRING_CORRECTION, string_correction, "string-correction") /* §6.2 / [19] */                 \
  X(FRAMES, frames, "frames")                                  /* kinematic control frames */

#define MR_EFFECTS(X) MR_FORCE_KINDS(X) MR_OTHER_EFFECTS(X)

/* --------------------------------------------------------------- effects */

/* What a world simulates (mr_world_def.effects, OR of MR_EFFECT_* bits). A
 * pass whose effect is not declared is not in the world's pass list at all. */
enum mr_effect_bit {
#define MR_X_(id, stem, name) MR_EFFECT_BIT_##id,
  MR_EFFECTS(MR_X_)
#undef MR_X_
      MR_EFFECT_COUNT
};
enum {
#define MR_X_(id, stem, name) MR_EFFECT_##id = 1u << MR_EFFECT_BIT_##id,
  MR_EFFECTS(MR_X_)
#undef MR_X_
      MR_EFFECT_ALL = (1u << MR_EFFECT_COUNT) - 1u
};

/* The name of one effect bit ("gravity", "sine-springs", ...), or "unknown"
 * for anything that is not exactly one known bit. */
const char *mr_effect_name(uint32_t effect);
/* Returns 0 and the bit, or -1 for an unknown name. '_' reads as '-', so
 * "sine_springs" and "sine-springs" are the same name. */
int mr_effect_parse(const char *name, uint32_t *out);

/* ---------------------------------------------------------------- passes */

/* The passes a step can run, in the order they run; mr_world_pass_calls
 * counts each one. */
typedef enum mr_pass {
  MR_PASS_FRAMES, /* place control-frame particles at time t */
#define MR_X_(id, stem, name) MR_PASS_##id,
  MR_FORCE_KINDS(MR_X_)
#undef MR_X_
      MR_PASS_CONSTRAINTS,  /* rows of C, J, J̇q̇ for the solve */
  MR_PASS_SOLVE,            /* J M⁻¹ Jᵀ λ = b, eq. 8 (and eq. 9) */
  MR_PASS_PLANES,           /* particle–plane detection and contacts */
  MR_PASS_SELF_COLLISION,   /* sphere-tree traversal within puppets */
  MR_PASS_PUPPET_COLLISION, /* sphere-tree traversal between puppets */
  MR_PASS_STRING_CORRECTION,
  MR_PASS_COUNT
} mr_pass;

const char *mr_pass_name(mr_pass p);               /* "gravity", "solve", ...; "unknown" */
int mr_pass_parse(const char *name, mr_pass *out); /* 0, or -1 if unknown */

/* ----------------------------------------------------------- integrators */

#define MR_INTEGRATORS(X)                                                           \
  X(RK4, "rk4")                                 /* default, §4.2 */                \
  X(EULER, "euler")                             /* explicit Euler */                \
  X(SEMI_IMPLICIT_EULER, "semi-implicit-euler") /* velocity first, then position */ \
  X(MIDPOINT, "midpoint")

typedef enum mr_integrator {
#define MR_X_(id, name) MR_INTEGRATOR_##id,
  MR_INTEGRATORS(MR_X_)
#undef MR_X_
      MR_INTEGRATOR_COUNT
} mr_integrator;

const char *mr_integrator_name(mr_integrator i);               /* "rk4", ...; "unknown" */
int mr_integrator_parse(const char *name, mr_integrator *out); /* 0, or -1 if unknown */

/* ----------------------------------------------------------------- world */

typedef struct mr_world mr_world; /* opaque */

typedef struct mr_world_def {
  uint32_t cookie;          /* MR_DEF_COOKIE, set by mr_default_world_def() */
  double gravity[3];        /* m/s²; default (0, −9.81, 0): y is up */
  uint32_t effects;         /* MR_EFFECT_* bits; default GRAVITY|CONSTRAINTS */
  mr_integrator integrator; /* default RK4 */

  /* Adaptive time step (§4.5, §7). */
  double dt_initial;       /* first step, s; default 0.02 */
  double dt_min, dt_max;   /* bounds, s; default 0.01, 0.05 */
  double dt_floor;         /* s, ≤ dt_min: a mode too fast for dt_min (its
                              local error estimate over the threshold) may
                              take steps down to this; springs too stiff for
                              it are softened. 0 (default): dt_min/100;
                              dt_floor = dt_min = dt_max: fixed steps */
  double deviation_low;    /* grow Δt below this relative deviation;
                                 default 1e-4 (0.01 %) */
  double deviation_high;   /* reject and shrink above it; default 1e-2 */
  double deviation_length; /* length dividing absolute deviations of pins
                                 and curves, m; default 1 */
  double divergence_bound; /* relative deviation treated as divergence
                                 (§7); default 0.5 */
  int max_steps_per_call;  /* guard for mr_world_step_to; default 1000000 */

  /* Integration error (beyond the paper, README "Error control"): an
   * embedded estimate of each step's local error in positions and velocities,
   * divided by these scales, is held to the same thresholds as the
   * deviation; the worse of the two sets Δt. 0 switches the estimate off. */
  double error_length; /* m; default 1 */
  double error_speed;  /* m/s; default 1 */
  /* A particle faster than this is divergence (§7), as NaN is; default
   * 1000 (world.c says why). */
  double max_speed;

  /* The constraint solve (§4.3, §5.2). */
  mr_solve_method solver;    /* default MR_SOLVE_LDLT */
  double solver_tolerance;   /* iterative methods; default 1e-10 */
  int solver_max_iterations; /* iterative methods; default 1000 */
  double ks, kd;             /* correction gains of eq. 7/8 (1/s², 1/s);
                                 default 100, 20 (critically damped) */

  double drag; /* viscous friction, N·s/m; default 0.1 */

  /* Contacts (§4.4, §5.4). */
  double contact_slop; /* |χ| within this is "touching", m; default 1e-4 */
  double rest_speed;   /* impacts slower than this are inelastic and
                                 become resting contacts, m/s; default 0.05 */

  /* String correction (§6.2, [19]). */
  double string_max_stretch;        /* allowed relative over-length; default 0.1 */
  int string_correction_iterations; /* default 10 */
} mr_world_def;

mr_world_def mr_default_world_def(void);

/* Creates a world. On failure *out_world is NULL and msg (if not NULL)
 * holds a line naming the bad field. */
mr_status mr_world_create(const mr_world_def *def, mr_world **out_world, char *msg,
                          size_t msg_size);
void mr_world_destroy(mr_world *w);
/* The settings the world runs with, as it took them from its definition:
 * for checking what a loader built. MR_ERR_ARG for a NULL argument. */
mr_status mr_world_get_def(const mr_world *w, mr_world_def *out);

/* The message of the last failure or report on this world ("" if none). */
const char *mr_world_last_error(const mr_world *w);

/* ------------------------------------------------------------- particles */

typedef struct mr_particle_def {
  uint32_t cookie;    /* MR_DEF_COOKIE, set by mr_default_particle_def() */
  double mass;        /* kg, > 0 (ignored for frame particles); default 1 */
  double position[3]; /* m, world coordinates */
  double velocity[3]; /* m/s */
  double radius;      /* collision radius / model extent, m, ≥ 0; default 0 */
  int puppet;         /* puppet this particle belongs to, ≥ 0; default 0 */
  int frame;          /* control frame carrying it kinematically, or −1
                           (default). Its offset in the frame is taken from
                           position and the frame's current pose. */
} mr_particle_def;

mr_particle_def mr_default_particle_def(void);
mr_status mr_world_add_particle(mr_world *w, const mr_particle_def *def, int *out_id);

int mr_world_particle_count(const mr_world *w);
/* Position / velocity of one particle (out may be NULL). */
mr_status mr_world_particle_state(const mr_world *w, int id, double pos[3], double vel[3]);
/* Copies xyz of the first min(count, n) particles into xyz[3·i..]; returns
 * the number copied. */
int mr_world_positions(const mr_world *w, double *xyz, int count);
/* Overwrites a dynamic particle's state (e.g. a scene's initial kick). */
mr_status mr_world_set_particle_state(mr_world *w, int id, const double pos[3],
                                      const double vel[3]);

/* --------------------------------------------------------- control frame */

/* Poses are mr_pose (mr_pose.h): a position and a unit quaternion. */

/* How a frame moves from one target to the next: MR_FRAME_SMOOTH (the
 * default) on a curve whose velocity is continuous across targets, or
 * MR_FRAME_LINEAR straight at the chord's constant rate (position linear,
 * orientation slerp), its velocity jumping at every target. */
typedef enum mr_frame_path { MR_FRAME_SMOOTH, MR_FRAME_LINEAR } mr_frame_path;

typedef struct mr_frame_def {
  uint32_t cookie;    /* MR_DEF_COOKIE, set by mr_default_frame_def() */
  mr_pose pose;       /* initial pose; default identity */
  mr_frame_path path; /* default MR_FRAME_SMOOTH */
} mr_frame_def;

mr_frame_def mr_default_frame_def(void);
/* Needs MR_EFFECT_FRAMES. */
mr_status mr_world_add_frame(mr_world *w, const mr_frame_def *def, int *out_id);
/* Moves the frame from its pose at the world's current time to `pose`,
 * reached at time t and held afterwards. The path is a cubic Hermite curve
 * (position and orientation) that leaves at the frame's current velocity
 * and angular velocity and arrives at the slope of the parabola through
 * the last target, the pose now and this one, so the velocity is
 * continuous across targets set one after another and the path's
 * acceleration follows a smooth track's. Its particles follow
 * kinematically, with the matching velocity, inside every integrator
 * stage (MR_FRAME_LINEAR: straight at constant rates instead). t ≤ the
 * world time places it at once and at rest (§6.1 method 1). Call it before
 * mr_world_step_to(w, t, ...). */
mr_status mr_world_set_frame_target(mr_world *w, int frame, const mr_pose *pose, double t);
/* The same, arriving at the velocity vel (m/s) and angular velocity omega
 * (rad/s, world axes) given instead of the parabola's slopes: for a track
 * known in time, whose own rates make the path between targets that of
 * the track to fourth order, however far apart the targets are. */
mr_status mr_world_set_frame_target_rates(mr_world *w, int frame, const mr_pose *pose,
                                          const double vel[3], const double omega[3], double t);
/* Bounds on the speed (m/s) and the turn rate (rad/s) of the path that
 * mr_world_set_frame_target(w, frame, pose, t) would make now: the path
 * never moves faster than they say. A rate limiter scales the target back
 * until they are within its limits. */
mr_status mr_world_frame_target_peak(const mr_world *w, int frame, const mr_pose *pose, double t,
                                     double *speed, double *turn_rate);
/* The same bounds for the path mr_world_set_frame_target_rates would make. */
mr_status mr_world_frame_target_rates_peak(const mr_world *w, int frame, const mr_pose *pose,
                                           const double vel[3], const double omega[3], double t,
                                           double *speed, double *turn_rate);
/* The largest acceleration (m/s²) and angular acceleration (rad/s²) of
 * that same path, at its two ends and its middle: exact for the position
 * (a cubic's acceleration is linear in time), a sample for the turn. */
mr_status mr_world_frame_target_accel(const mr_world *w, int frame, const mr_pose *pose, double t,
                                      double *accel, double *turn_accel);
mr_status mr_world_frame_pose(const mr_world *w, int frame, mr_pose *out);
/* The frame's velocity (m/s) and angular velocity (rad/s, world axes) at
 * the world's current time. */
mr_status mr_world_frame_rates(const mr_world *w, int frame, double vel[3], double omega[3]);

/* ---------------------------------------------------------------- forces */

/* Spring and damper along the line a–b (Hooke plus relative-velocity
 * damping): F_a = −(stiffness (d − rest) + damping ḋ) û, F_b = −F_a.
 * A damper is a spring with stiffness 0. Needs MR_EFFECT_SPRINGS. */
typedef struct mr_spring_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_spring_def() */
  int a, b;
  double rest_length; /* m; < 0 (default) = the current distance */
  double stiffness;   /* N/m; default 100 */
  double damping;     /* N·s/m; default 1 */
} mr_spring_def;
mr_spring_def mr_default_spring_def(void);
mr_status mr_world_add_spring(mr_world *w, const mr_spring_def *def, int *out_id);

/* How a string holds its length.
 *  - MR_STRING_SPRING (the paper's §6.2): a spring/damper that only pulls,
 *    stretching under load (held back, if declared, by
 *    MR_EFFECT_STRING_CORRECTION): 1.05–1.4× its rest on the example
 *    tracks, which an audience sees as rubber.
 *  - MR_STRING_TAUT (default): a unilateral length limit |x_p − x_f| ≤ rest, a row of
 *    the same complementarity solve as a resting contact (§5.4): active
 *    only when taut, released when it would push, an inelastic impulse
 *    (eq. 9) when it snaps taut. stiffness and damping are not used; the
 *    ATS holds its over-length to the deviation thresholds. */
typedef enum mr_string_mode { MR_STRING_SPRING, MR_STRING_TAUT } mr_string_mode;
/* "spring", "taut"; parse gives −1 for an unknown name. */
const char *mr_string_mode_name(mr_string_mode m);
int mr_string_mode_parse(const char *name, mr_string_mode *out);

/* A string from a control-frame particle to a puppet particle (§6.1, §6.2):
 * a spring/damper that only pulls (slack when shorter than rest_length), or
 * a length limit (mode). Needs MR_EFFECT_STRINGS; spring strings are
 * corrected by MR_EFFECT_STRING_CORRECTION. */
typedef struct mr_string_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_string_def() */
  int frame_particle, puppet_particle;
  double rest_length;  /* < 0 (default) = current distance */
  double stiffness;    /* default 500 (spring mode) */
  double damping;      /* default 5 (spring mode) */
  mr_string_mode mode; /* default MR_STRING_TAUT (needs rest_length > 0) */
} mr_string_def;
mr_string_def mr_default_string_def(void);
mr_status mr_world_add_string(mr_world *w, const mr_string_def *def, int *out_id);

/* Antigravity (§6.2): on `acted`, opposite gravity, carrying `fraction` of
 * the puppet's weight scaled by the trigger distance:
 *   F = −g · fraction · M_puppet · min(d/d0, max_scale),
 * d = |x_trigger − x_acted|, d0 = d when added. Needs MR_EFFECT_ANTIGRAVITY. */
typedef struct mr_antigravity_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_antigravity_def() */
  int acted, trigger;
  double fraction;  /* default 0.5 */
  double max_scale; /* default 2 */
} mr_antigravity_def;
mr_antigravity_def mr_default_antigravity_def(void);
mr_status mr_world_add_antigravity(mr_world *w, const mr_antigravity_def *def, int *out_id);

/* Triggered action force (§6.2): when the control–trigger distance changes
 * from its value when added, `acted` is pushed towards `control`:
 *   F = clamp(gain · M_puppet · (d − d0), ±max_force) · û(acted → control),
 * d = |x_control − x_trigger|. Needs MR_EFFECT_TRIGGERED. */
typedef struct mr_triggered_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_triggered_def() */
  int acted, control, trigger;
  double gain;      /* N/(kg·m); default 10 */
  double max_force; /* N; default 100 */
} mr_triggered_def;
mr_triggered_def mr_default_triggered_def(void);
mr_status mr_world_add_triggered(mr_world *w, const mr_triggered_def *def, int *out_id);

/* Capped sine-shaped spring (§6.2): force rises as a shifted sine between
 * 0° and 90° and holds its maximum past `reach`:
 *   |F| = max_force · sin(π/2 · min(|d − rest|/reach, 1)), plus damping ḋ,
 * along the line, restoring. Needs MR_EFFECT_SINE_SPRINGS. */
typedef struct mr_sine_spring_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_sine_spring_def() */
  int a, b;
  double rest_length; /* < 0 (default) = current distance */
  double max_force;   /* N; default 50 */
  double reach;       /* m; default 0.1 */
  double damping;     /* N·s/m; default 1 */
} mr_sine_spring_def;
mr_sine_spring_def mr_default_sine_spring_def(void);
mr_status mr_world_add_sine_spring(mr_world *w, const mr_sine_spring_def *def, int *out_id);

/* ----------------------------------------------------------- constraints */
/* All need MR_EFFECT_CONSTRAINTS. Each returns its id in its own kind. */

/* C = |x_a − x_b| − length. */
typedef struct mr_distance_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_distance_def() */
  int a, b;
  double length; /* > 0; < 0 (default) = current distance */
} mr_distance_def;
mr_distance_def mr_default_distance_def(void);
mr_status mr_world_add_distance(mr_world *w, const mr_distance_def *def, int *out_id);

/* C = x − point (3 rows). */
typedef struct mr_pin_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_pin_def() */
  int particle;
  double point[3];
  int at_current; /* nonzero (default): point = current position */
} mr_pin_def;
mr_pin_def mr_default_pin_def(void);
mr_status mr_world_add_pin(mr_world *w, const mr_pin_def *def, int *out_id);

/* A time-dependent 3D curve (§6.1 method 3): C = x − c(t), with
 * ∂C/∂t = −ċ(t), ∂²C/∂t² = −c̈(t). Either keyframes (times strictly
 * increasing, copied) or a callback. Before the first / after the last key
 * the curve holds its end point. */
typedef enum mr_curve_interp {
  MR_CURVE_CATMULL_ROM = 0, /* C¹ cubic through the keys, at rest at the
                                first and last key (default) */
  MR_CURVE_LINEAR           /* polyline: ċ piecewise constant, c̈ = 0 */
} mr_curve_interp;
typedef void (*mr_curve_fn)(void *user, double t, double pos[3], double vel[3], double acc[3]);
typedef struct mr_curve_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_curve_def() */
  int particle;
  int key_count;        /* ≥ 1 when fn is NULL */
  const double *times;  /* key_count */
  const double *points; /* 3·key_count */
  mr_curve_interp interp;
  mr_curve_fn fn; /* if not NULL, used instead of the keys */
  void *user;
} mr_curve_def;
mr_curve_def mr_default_curve_def(void);
mr_status mr_world_add_curve(mr_world *w, const mr_curve_def *def, int *out_id);

/* Rigid group (§5.1): the first four particles (not coplanar) form a
 * tetrahedral clique of six distance constraints; every later particle is
 * linked to exactly three earlier ones that are not coplanar with it (the
 * nearest such), so no constraint is dependent. Two or three particles give
 * a link or a triangle. */
typedef struct mr_rigid_group_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_rigid_group_def() */
  const int *particles;
  int count; /* ≥ 2 */
} mr_rigid_group_def;
mr_rigid_group_def mr_default_rigid_group_def(void);
/* Whether count points (xyz, 3 per point, in the group's order) can be a
 * rigid group (§5.1): no two within 1e-9 m, the first three not collinear,
 * the first four a tetrahedron, and every later point off the plane of
 * some three before it. Shape is measured scale-free: |sin| of the angle
 * at the first point for three, |det| over the product of the three edges
 * from the point being placed for four, each at least MR_GROUP_MIN_SHAPE.
 * The world's add call and a scene loader use this one test, so what one
 * accepts the other does. On a fault, *i and *j name the points (for
 * COINCIDENT both; otherwise the point that fails, in *i); −1 where there
 * is no point to name. */
#define MR_GROUP_MIN_SHAPE 1e-3
typedef enum mr_shape_fault {
  MR_SHAPE_OK = 0,
  MR_SHAPE_COINCIDENT, /* points *j and *i */
  MR_SHAPE_COLLINEAR,  /* the first three */
  MR_SHAPE_FLAT_START, /* the first four */
  MR_SHAPE_FLAT_MEMBER /* point *i lies in the plane of every three before it */
} mr_shape_fault;
mr_shape_fault mr_rigid_group_shape(const double *xyz, int count, int *i, int *j);
mr_status mr_world_add_rigid_group(mr_world *w, const mr_rigid_group_def *def, int *out_id);

/* Number of scalar constraint rows (k). */
int mr_world_constraint_rows(const mr_world *w);

/* The largest mass ratio the constraint solve honours between two dynamic
 * particles joined by a distance constraint (or a rigid group's): a nearly
 * dependent row is regularised at 1e-4 of its effective mass (README,
 * "Near-singular constraints"), and the heavier particle's share of a row
 * is 1/ratio of it. Scene readers refuse a scene past it, naming the two
 * particles. */
#define MR_MAX_MASS_RATIO 1e4

/* ------------------------------------------------------------ collisions */

/* Plane n·x = offset (n normalised on entry); particles stay on the side n
 * points to, at distance ≥ their radius. Needs MR_EFFECT_PLANES. */
typedef struct mr_plane_def {
  uint32_t cookie;    /* MR_DEF_COOKIE, set by mr_default_plane_def() */
  double normal[3];   /* default (0, 1, 0): the floor */
  double offset;      /* default 0 */
  double restitution; /* 0..1; default 0.5 */
  double friction;    /* Coulomb μ ≥ 0; default 0.3 */
} mr_plane_def;
mr_plane_def mr_default_plane_def(void);
mr_status mr_world_add_plane(mr_world *w, const mr_plane_def *def, int *out_id);

/* A part of a puppet for its sphere tree (§4.4, Hubbard): one leaf sphere
 * per particle (radius max(particle radius, radius)), plus
 * segment_spheres evenly spaced between the two particles of a two-particle
 * part (a limb drawn in link mode). All particles of a part must belong to
 * one puppet. Parts sharing a particle or joined by a constraint are
 * adjacent and never tested against each other. Needs
 * MR_EFFECT_SELF_COLLISION or MR_EFFECT_PUPPET_COLLISION. */
typedef struct mr_part_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_part_def() */
  const int *particles;
  int count;           /* ≥ 1 */
  double radius;       /* m; default 0 */
  int segment_spheres; /* default 0 */
  double restitution;  /* default 0.5 */
  double friction;     /* Coulomb μ ≥ 0 against other parts' spheres
                               (the mean of the two parts'); default 0.3 */
} mr_part_def;
mr_part_def mr_default_part_def(void);
mr_status mr_world_add_part(mr_world *w, const mr_part_def *def, int *out_id);

/* -------------------------------------------------------------- stepping */

typedef struct mr_step_report {
  int steps;       /* accepted steps taken by this call */
  int rejected;    /* steps rejected by the deviation rule */
  int collisions;  /* impulse events */
  int divergences; /* resets to the start configuration */
  int dependent;   /* dependent constraint rows seen (max over solves) */
  int corrections; /* steps at the lower bound projected back onto the
                      constraints because their deviation was too large */
} mr_step_report;

/* Advances the world to exactly t_target (the last step is shortened to land
 * on it, §4.6). Returns MR_OK, MR_DIVERGED (the world was reset and carried
 * on; see the report), MR_DEPENDENT (dependent rows were found and zeroed),
 * or an error (MR_ERR_TIME, MR_ERR_LIMIT). report may be NULL. */
mr_status mr_world_step_to(mr_world *w, double t_target, mr_step_report *report);

/* Takes one step of the planned Δt (mr_world_next_dt), or a shorter one if
 * it is rejected or stopped at a contact time: for benchmarks and tests that
 * watch the ATS step by step. */
mr_status mr_world_step(mr_world *w, mr_step_report *report);

double mr_world_time(const mr_world *w);
double mr_world_next_dt(const mr_world *w); /* Δt the ATS will try next */

typedef struct mr_stats {
  uint64_t steps, rejected, collisions, divergences;
  uint64_t solves, solver_failures, solver_iterations;
  int dependent_rows;             /* of the latest solve */
  int resting_contacts;           /* at the latest step */
  uint64_t corrections;           /* see mr_step_report */
  uint64_t softened_forces;       /* springs and strings too stiff for a step of
                                     dt_min/100 on their masses, softened to
                                     that step's stability limit */
  double last_dt, min_dt, max_dt; /* accepted steps the ATS chose */
  double min_dt_landing;          /* accepted steps shortened only to land
                                     on a requested time (INFINITY if none) */
  double stable_dt;               /* RK4's stability limit for the stiffest
                                     spring, string or drag (INFINITY if none);
                                     Δt never exceeds it */
  double last_error, max_error;   /* relative deviation after a step */
  double max_integration_error;   /* the largest scaled local error estimate
                                     of an accepted step */
  double max_multiplier;          /* largest |λ| of the latest force solve: the
                                 bound on constraint forces */
  double max_penetration;         /* the deepest two bodies went into each other
                                     at any accepted step's end or on the straight
                                     path between its ends, m, when deeper than
                                     the contact slop (0 if never) */
  uint64_t located;               /* contacts located in time within a step
                                     (§4.5): apart at its start, gone through
                                     by its end */
  uint64_t location_integrations; /* the trial integrations those took */
  int blocks;                     /* the independent systems the latest solve
                                     was split into (puppets that do not touch
                                     each other: host/physics/README.md); 1 when
                                     it was solved whole */
} mr_stats;
/* The counters so far. MR_ERR_ARG for a NULL argument. */
mr_status mr_world_stats(const mr_world *w, mr_stats *out);
/* How many times pass p ran (0 forever if the world did not declare it). */
uint64_t mr_world_pass_calls(const mr_world *w, mr_pass p);
/* The largest relative constraint deviation of the current state (§4.5). */
double mr_world_deviation(const mr_world *w);
/* How deep, in m, the deepest pair of bodies the world's collision effects
 * watch (particle and plane, sphere and sphere) is into each other in the
 * current state; 0 when none touch, NaN when out of memory. */
double mr_world_penetration(mr_world *w);
/* The sphere trees (§4.4) refitted to the current state: the smallest
 * margin by which a parent sphere encloses each of its children, m (≥ 0,
 * to rounding, when every parent encloses its children; INFINITY without
 * trees). For tests: a tree whose parents miss part of a child misses the
 * contacts inside it. */
double mr_world_tree_slack(mr_world *w);
/* The largest L/rest − 1 over the world's strings in the current state
 * (negative when all are slack; 0 without strings). */
double mr_world_string_stretch(const mr_world *w);
/* FNV-1a (64-bit) over the bytes of time, positions and velocities. */
uint64_t mr_world_state_hash(const mr_world *w);

/* ------------------------------------------------------------------- ATS */

/* The §4.5 rule as a pure function, exposed so it can be tested and reused.
 * error > high: reject, Δt_new = Δt_old·min((high/error)^¼, ½) (unless
 * Δt_old is already dt_min: then accept). error < low: Δt_new = Δt_old·(low/error)^¼.
 * Otherwise keep Δt. The result is clamped to [dt_min, dt_max]. */
typedef struct mr_ats_params {
  double dt_min, dt_max, low, high;
} mr_ats_params;
typedef struct mr_ats_decision {
  int accept;
  double dt_next;
} mr_ats_decision;
mr_ats_decision mr_ats_next(const mr_ats_params *p, double dt_old, double error);
/* The Δt the local error estimate asks for after an accepted step:
 * Δt_old·0.9·(low/estimate)^¼, changed at most ×0.2 to ×5, clamped to
 * [dt_min, dt_max]. */
double mr_ats_aim(const mr_ats_params *p, double dt_old, double estimate);

#ifdef __cplusplus
}
#endif

#endif /* MR_PHYSICS_H */
