/* A live show: gloves drive a scene's puppets through the control mapping,
 * paced by the frame scheduler on a clock (`marionette run`).
 *
 * Each control frame of the scene (the scene's own, and each puppet's) is
 * bound to one glove by its control.glove: the k-th glove given, the glove
 * of a uid, or the first glove of a hand (host/scenes/FORMAT.md). A frame
 * bound by uid or hand waits, at its start pose, for a glove whose INFO
 * matches. A glove may drive several frames.
 *
 * The gloves run on show time (the frame's simulated time), so a take
 * records each byte with the frame that read it, and a replay on a virtual
 * clock gives every frame the same bytes: the same states, bit for bit.
 *
 * Each frame: the gloves are read (without waiting), each bound frame's
 * glove's five values go through the scene's mapping (host/control) to a
 * pose about that frame's start pose, the frame heads there no faster than
 * its limits (mr_pose_approach), and the world is stepped to land on the
 * frame time. A glove that is lost leaves its frames where they were: the
 * puppets hold their pose. Presenting a frame is the caller's hook: the
 * program draws it on the stage (host/render) and prints a status line. */
#ifndef MR_SHOW_H
#define MR_SHOW_H

#include "mr_glove.h"
#include "mr_scene_world.h"
#include "mr_sim.h"
#include "mr_theater.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { MR_SHOW_MAX_GLOVES = 8 };

typedef struct mr_show_def {
  uint32_t cookie;  /* MR_SHOW_COOKIE, set by mr_default_show_def() */
  mr_policy policy; /* default skip */
  double duration;  /* s of show, <= 0: until stopped (or the takes' end) */
  double fps;       /* <= 0: the scene's sim.fps, else 60 */
  /* Frames landed on (the paper's) or interpolated between steps at the
   * ATS's own Δt; MR_PRESENT_SCENE (default): the scene's sim.present. */
  mr_present_mode present;
  /* The mapping to start with, by name (the scene's `mapping:`); NULL:
   * the first. */
  const char *mapping;
  /* The gloves, each a source as mr_glove takes it; at least one. */
  const char *gloves[MR_SHOW_MAX_GLOVES];
  size_t n_gloves;
  /* Takes: every byte glove i sends, with the show time it was read at,
   * into record[i] (.mrec; NULL: none). Replaying it (glove i's source a
   * file: take) feeds the same bytes to the same frames. */
  const char *record[MR_SHOW_MAX_GLOVES];
} mr_show_def;
#define MR_SHOW_COOKIE 0x6d725369u
mr_show_def mr_default_show_def(void);

/* What a frame shows, for the present hook. */
typedef struct mr_show_frame {
  double t;                      /* simulated time */
  const mr_pose *target;         /* per control frame: where its glove sends it */
  const mr_pose *pose;           /* per control frame: where it is at t */
  const int *glove_of;           /* per control frame: its glove's index, -1 unbound */
  size_t n_frames;               /* at most 16: the first 16 control frames */
  const mr_glove *const *gloves; /* their states, values and counters */
  size_t n_gloves;
  const mr_scheduler *scheduler;
  const mr_world *world;
  /* Every particle's position as the frame shows it (3 n): the world's at
   * t, or interpolated to t between the steps around it. */
  const double *xyz;
  int n_particles;
} mr_show_frame;

typedef struct mr_show_hooks {
  void (*present)(void *user, const mr_show_frame *frame); /* may be NULL */
  /* Polled once a frame: nonzero ends the show (Ctrl-C). May be NULL. */
  int (*stop)(void *user);
  /* After each frame is simulated (shown or skipped): the frame, and the
   * world's state hash, which a replay of the take reproduces bit for bit.
   * May be NULL. */
  void (*frame_done)(void *user, const mr_show_frame *frame, uint64_t hash);
  /* Polled once a frame: nonzero moves every control frame to the scene's
   * next mapping (after the last, the first), the filters kept. May be
   * NULL. */
  int (*next_mapping)(void *user);
  /* One line for the user when a glove's channel goes bad (NaN, or stuck
   * at an end past the mapping's stuck_after: held at neutral) or
   * recovers, naming the glove, its source and the finger. May be NULL. */
  void (*note)(void *user, const char *line);
  void *user;
  /* Polled once a frame: nonzero puts every puppet back where it started
   * (positions, at rest) and each control frame at its start pose; the
   * gloves then move them on from there (the window's reset key). May be
   * NULL. */
  int (*reset)(void *user);
} mr_show_hooks;

typedef struct mr_show_glove_result {
  mr_glove_counters counters;
  mr_glove_state state; /* at the end */
  uint64_t samples;     /* samples taken */
  char describe[400];   /* mr_glove_describe at the end */
} mr_show_glove_result;

typedef struct mr_show_result {
  mr_scheduler_stats frames;
  mr_show_glove_result glove[MR_SHOW_MAX_GLOVES];
  size_t n_gloves;
  int glove_of[16]; /* the first 16 control frames' gloves at the end, -1 unbound */
  /* Interpolated frames: how far the physics had run past each frame when
   * it was shown, mean and max, s: input read at a frame moves the puppet
   * only from there on, so this adds to the latency counters. */
  bool interpolated;
  double lead_mean, lead_max;
  char mapping[32]; /* the mapping in use at the end */
} mr_show_result;

/* Runs scene with def's gloves on clock until the duration passes or
 * stop() says so. Returns MR_SCENE_OK, or an error in err (the scene's
 * world refused, a bad glove source, a take that cannot be written, a
 * physics failure) naming what. */
mr_scene_status mr_show_run(const mr_scene *scene, const mr_show_def *def, const mr_clock *clock,
                            const mr_show_hooks *hooks, mr_show_result *result,
                            mr_scene_error *err);

#ifdef __cplusplus
}
#endif

#endif /* MR_SHOW_H */
