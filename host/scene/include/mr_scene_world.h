/* A loaded scene turned into a physics world, and a headless run of it.
 *
 * mr_scene_build() creates an mr_world with exactly the effects the scene
 * declares and adds its items in file order; a refusal from the physics
 * library is reported at the item's file:line:column. mr_scene_run() drives
 * the world through the scene's control track for a stretch of simulated
 * time, as fast as it can, and gathers what `marionette sim` prints. */
#ifndef MR_SCENE_WORLD_H
#define MR_SCENE_WORLD_H

#include "mr_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mr_scene_world {
  mr_world *world;
  int frame;         /* control frame id, -1 without one */
  int *particle_ids; /* scene particle i -> world particle id (i) */
  int *control_ids;  /* control point j -> world particle id (n_particles + j) */
  size_t n_particles, n_control;
} mr_scene_world;

mr_scene_status mr_scene_build(const mr_scene *scene, mr_scene_world *out, mr_scene_error *err);
void mr_scene_world_free(mr_scene_world *sw);

/* One row of the per-step trace. */
typedef struct mr_scene_step {
  double t;         /* world time after the step */
  double dt;        /* length of the accepted step */
  double error;     /* relative deviation after it (§4.5) */
  int accepted;     /* accepted steps in this call (1, or more after a
                      rejection shrank Δt) */
  int rejected;     /* rejected tries before them */
  int reset;        /* resets to the start in this call (the world diverged) */
  double max_speed; /* fastest particle after the step, m/s */
} mr_scene_step;

typedef void (*mr_scene_step_fn)(void *user, const mr_scene_step *step);

typedef struct mr_scene_run_opts {
  double duration;          /* simulated seconds; <= 0: the scene's */
  mr_scene_step_fn on_step; /* may be NULL */
  void *user;
} mr_scene_run_opts;

typedef struct mr_scene_run_result {
  double sim_time;
  uint64_t steps, rejected, resets, collisions;
  double dt_mean, dt_min, dt_max; /* dt_min: the ATS's choice (mr_stats.min_dt) */
  double dt_min_landing;          /* shortest step cut to land on a frame; 0 if none */
  double stable_dt;               /* mr_stats.stable_dt; 0 if no limit */
  uint64_t corrections;           /* steps projected back onto the constraints */
  uint64_t softened_forces;       /* mr_stats.softened_forces */
  double at_upper_fraction;       /* steps with Δt at the ATS's upper bound */
  double max_deviation, rms_deviation;
  int dependent_rows; /* most dependent rows seen in one call */
  uint64_t pass_calls[MR_PASS_COUNT];
  uint64_t hash; /* mr_world_state_hash at the end */
  bool finite;   /* every state finite after every step */
  /* Rest checks (expect.rest): largest displacement of a watched particle
   * from its position at `settle`, and its largest speed after `settle`. */
  double creep, jitter;
  double string_stretch;  /* largest length/rest of any string after any step */
  double max_speed;       /* fastest particle after any step, m/s */
  double max_penetration; /* deepest contact after any step (mr_world_penetration), m */
  mr_status last_status;  /* of the last step call */
  char first_reset[256];  /* the physics' account of the first reset */
} mr_scene_run_result;

/* Builds the scene's world and runs it. Returns MR_SCENE_OK, or an error
 * (build refused, or the physics failed outright: the message says when). */
mr_scene_status mr_scene_run(const mr_scene *scene, const mr_scene_run_opts *opts,
                             mr_scene_run_result *result, mr_scene_error *err);

/* Compares a run with the scene's expect: section. Returns 0 when every
 * expectation holds, else -1 with the first unmet one in why. */
int mr_scene_check(const mr_scene *scene, const mr_scene_run_result *result, char *why,
                   size_t why_size);

#ifdef __cplusplus
}
#endif

#endif
