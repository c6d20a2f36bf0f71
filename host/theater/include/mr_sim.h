/* A headless run of a scene: `marionette sim`.
 *
 * mr_sim_run() builds the scene's world and drives it through the scene's
 * control track for a stretch of simulated time, as fast as it can, and
 * gathers what `marionette sim` prints. With sim.fps the frames are paced
 * by the theater's scheduler on a virtual clock (mr_theater.h), the same
 * loop a show runs on the wall clock; without it the track is sampled at
 * the end of every step and the ATS alone chooses Δt. */
#ifndef MR_SIM_H
#define MR_SIM_H

#include "mr_scene_world.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One row of the per-step trace. */
typedef struct mr_sim_step {
  double t;         /* world time after the step */
  double dt;        /* length of the accepted step */
  double error;     /* relative deviation after it (§4.5) */
  int accepted;     /* accepted steps in this call (1, or more after a
                      rejection shrank Δt) */
  int rejected;     /* rejected tries before them */
  int reset;        /* resets to the start in this call (the world diverged) */
  double max_speed; /* fastest particle after the step, m/s */
} mr_sim_step;

typedef void (*mr_sim_step_fn)(void *user, const mr_sim_step *step);

typedef struct mr_sim_opts {
  double duration;        /* simulated seconds; <= 0: the scene's */
  mr_sim_step_fn on_step; /* may be NULL */
  void *user;
} mr_sim_opts;

typedef struct mr_sim_result {
  double sim_time;
  uint64_t frames; /* frames the scheduler paced (sim.fps), 0 without */
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
} mr_sim_result;

/* Builds the scene's world and runs it. Returns MR_SCENE_OK, or an error
 * (build refused, or the physics failed outright: the message says when). */
mr_scene_status mr_sim_run(const mr_scene *scene, const mr_sim_opts *opts, mr_sim_result *result,
                           mr_scene_error *err);

/* Compares a run with the scene's expect: section. Returns 0 when every
 * expectation holds, else -1 with the first unmet one in why. */
int mr_sim_check(const mr_scene *scene, const mr_sim_result *result, char *why, size_t why_size);

#ifdef __cplusplus
}
#endif

#endif
