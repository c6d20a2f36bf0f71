/* A live show: a glove drives a scene's puppet through the control
 * mapping, paced by the frame scheduler on a clock (`marionette run`).
 *
 * The glove runs on show time (the frame's simulated time), so a take
 * records each byte with the frame that read it, and a replay on a virtual
 * clock gives every frame the same bytes: the same states, bit for bit.
 *
 * Each frame: the glove is read (without waiting), its five values go
 * through the scene's mapping (host/control) to a pose, the control frame
 * heads there no faster than the scene's limits (mr_pose_approach), and the
 * world is stepped to land on the frame time. A glove that is lost leaves
 * the frame where it was: the puppet holds its pose. Until the stage
 * exists, presenting a frame is the caller's hook (a status line). */
#ifndef MR_SHOW_H
#define MR_SHOW_H

#include "mr_glove.h"
#include "mr_scene_world.h"
#include "mr_theater.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mr_show_def {
  uint32_t cookie;  /* MR_SHOW_COOKIE, set by mr_default_show_def() */
  mr_policy policy; /* default skip */
  double duration;  /* s of show, <= 0: until stopped (or a take's end) */
  double fps;       /* <= 0: the scene's sim.fps, else 60 */
  /* A take: every byte the glove sends, with the show time it was read at,
   * into this .mrec file (NULL: none). Replaying it (the glove's source a
   * file: take) feeds the same bytes to the same frames. */
  const char *record_path;
} mr_show_def;
#define MR_SHOW_COOKIE 0x6d725368u
mr_show_def mr_default_show_def(void);

/* What a frame shows, for the present hook. */
typedef struct mr_show_frame {
  double t;              /* simulated time */
  mr_pose control;       /* the control frame's target pose */
  const mr_glove *glove; /* its state, values and counters */
  const mr_scheduler *scheduler;
  const mr_world *world;
} mr_show_frame;

typedef struct mr_show_hooks {
  void (*present)(void *user, const mr_show_frame *frame); /* may be NULL */
  /* Polled once a frame: nonzero ends the show (Ctrl-C). May be NULL. */
  int (*stop)(void *user);
  /* After each frame is simulated: its time and the world's state hash,
   * which a replay of the take reproduces bit for bit. May be NULL. */
  void (*frame_done)(void *user, double t, uint64_t hash);
  void *user;
} mr_show_hooks;

typedef struct mr_show_result {
  mr_scheduler_stats frames;
  mr_glove_counters glove;
  mr_glove_state glove_state; /* at the end */
  uint64_t samples;           /* glove samples taken */
} mr_show_result;

/* Runs scene with one glove (source as mr_glove takes it) on clock until
 * the duration passes or stop() says so. Returns MR_SCENE_OK, or an error
 * in err (the scene's world refused, a bad glove source, a physics failure)
 * naming what. */
mr_scene_status mr_show_run(const mr_scene *scene, const char *glove_source, const mr_show_def *def,
                            const mr_clock *clock, const mr_show_hooks *hooks,
                            mr_show_result *result, mr_scene_error *err);

#ifdef __cplusplus
}
#endif

#endif /* MR_SHOW_H */
