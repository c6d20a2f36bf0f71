/* A headless run of a scene: `marionette sim`.
 *
 * mr_sim_run() builds the scene's world and drives it through the scene's
 * control track for a stretch of simulated time, as fast as it can, and
 * gathers what `marionette sim` prints. With sim.fps the frames are paced
 * by the theater's scheduler on a virtual clock (mr_theater.h), the same
 * loop a show runs on the wall clock; without it the track is sampled at
 * the end of every step and the ATS alone chooses Δt. Frames land the last
 * step on their time (the paper's), or, with sim.present: interpolate,
 * the physics steps at its own Δt and each frame shows the state
 * interpolated between the two steps around its time. */
#ifndef MR_SIM_H
#define MR_SIM_H

#include "mr_def.h"
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

/* How frames are presented (with sim.fps). */
typedef enum mr_present_mode {
  MR_PRESENT_SCENE = 0,  /* as the scene's sim.present says */
  MR_PRESENT_LAND,       /* the paper's: the last step before each frame lands on it */
  MR_PRESENT_INTERPOLATE /* steps at the ATS's Δt; frames interpolated between them */
} mr_present_mode;
const char *mr_present_mode_name(mr_present_mode m);
int mr_present_mode_parse(const char *name, mr_present_mode *out);

/* A frame as presented: its time and every particle's position (3 n), the
 * world's state at t, or the state interpolated to t. */
typedef void (*mr_sim_frame_fn)(void *user, double t, const double *xyz, int n);

typedef struct mr_sim_def {
  uint32_t cookie;          /* MR_DEF_COOKIE, set by mr_default_sim_def() */
  double duration;          /* simulated seconds; <= 0 (default): the scene's */
  double fps;               /* frames per second; <= 0 (default): the scene's sim.fps */
  mr_sim_step_fn on_step;   /* may be NULL (default) */
  void *user;               /* for the hooks */
  mr_present_mode present;  /* with sim.fps; default MR_PRESENT_SCENE */
  mr_sim_frame_fn on_frame; /* with sim.fps; may be NULL (default) */
  /* 6 numbers per scene particle, its position then its velocity (m,
   * m/s): the state the run starts from instead of the scene's, which
   * still gives every length; NULL (default): the scene's own. So a run
   * can go on from where another stopped (its end_state), with the
   * scene's tracks moved in time to match. */
  const double *start_state;
  /* Where the run leaves its end state, 6 numbers per scene particle as
   * above; NULL (default): not written. */
  double *end_state;
} mr_sim_def;
mr_sim_def mr_default_sim_def(void);

typedef struct mr_sim_result {
  double sim_time;
  uint64_t frames;   /* frames the scheduler paced (sim.fps), 0 without */
  double fps;        /* their rate */
  bool interpolated; /* frames presented by interpolation between steps */
  /* With interpolation: how far the physics had run past each frame's
   * time when it was presented (the input lag the mode adds), s. */
  double lead_mean, lead_max;
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
  double max_penetration; /* deepest contact after any step call (mr_world_penetration), or
                             within any step (mr_stats.max_penetration), m */
  mr_status last_status;  /* of the last step call */
  char first_reset[256];  /* the physics' account of the first reset */
} mr_sim_result;

/* Builds the scene's world and runs it. Returns MR_SCENE_OK, or an error
 * (build refused, or the physics failed outright: the message says when). */
mr_scene_status mr_sim_run(const mr_scene *scene, const mr_sim_def *opts, mr_sim_result *result,
                           mr_scene_error *err);

/* Compares a run with the scene's expect: section. Returns 0 when every
 * expectation holds, else -1 with the first unmet one in msg. */
int mr_sim_check(const mr_scene *scene, const mr_sim_result *result, char *msg, size_t msg_size);

#ifdef __cplusplus
}
#endif

#endif
