/* A show on a thread of its own (§4.6 in a window): the physics ticks on a
 * worker thread against the clock and publishes every simulated frame, a
 * snapshot, into a latest-wins triple buffer; the caller's thread (the
 * window's) takes the newest whenever it can draw one, and sends the
 * window's inputs as commands through a bounded queue. Pause, single step
 * and slow motion act on the show's own clock (mr_scaled_clock), reset and
 * the next mapping on the show, quit ends it, each done by the physics
 * thread between frames, in the order sent.
 *
 * The same runner also runs on the caller's thread (threaded = false) for
 * tests, headless runs and replays: mr_show_runner_tick then ticks it, and
 * the commands and the frames take the same roads. One thread or two, on a
 * virtual clock a show gives the same frames bit for bit. */
#ifndef MR_SHOW_RUNNER_H
#define MR_SHOW_RUNNER_H

#include "mr_show.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mr_show_cmd {
  MR_SHOW_CMD_PAUSE = 0,    /* pause, or go on when paused */
  MR_SHOW_CMD_STEP,         /* pause, and move on by one frame */
  MR_SHOW_CMD_SLOW,         /* slow motion (slow_rate), or back to 1 */
  MR_SHOW_CMD_RESET,        /* mr_show_reset */
  MR_SHOW_CMD_NEXT_MAPPING, /* mr_show_next_mapping */
  MR_SHOW_CMD_QUIT,         /* the show ends after the frame in hand */
  MR_SHOW_CMD_SPEED,        /* the next speed: 1 -> 0.5 -> 0.25 -> 1 */
  MR_SHOW_CMD_ARM,          /* mr_show_arm (mr_show_runner_send_arm) */
  MR_SHOW_CMD_PUNCH,        /* mr_show_punch */
  MR_SHOW_CMD_COUNT
} mr_show_cmd;

typedef struct mr_show_runner_def {
  uint32_t cookie;  /* MR_DEF_COOKIE, set by mr_default_show_runner_def() */
  bool threaded;    /* default true: the physics on a thread of its own */
  double slow_rate; /* show seconds per second in slow motion, default 0.25 */
  /* Show seconds per second to start at: 1 (the default), 0.5 or 0.25 for
   * a puppeteer performing slowly. Live gloves are read on the clock's
   * pace (mr_clock_paced), so their own clocks are not slowed. */
  double speed;
  size_t queue; /* commands held at most, default 64 */
  /* One thread only: called at every tick and while the show waits (at
   * least every poll s), so that the caller's inputs come in. May be
   * NULL. */
  void (*pump)(void *user);
  void *user;
  double poll; /* default 0.004 s */
} mr_show_runner_def;
mr_show_runner_def mr_default_show_runner_def(void);

typedef struct mr_show_runner mr_show_runner;

/* The show (mr_show_create's arguments, with `base` the clock that the
 * show's scaled clock runs over), started: on its thread when threaded,
 * else ready for mr_show_runner_tick. The hooks run on the thread that
 * ticks (threaded: the physics thread, so they must touch nothing the
 * caller's thread does). */
mr_show_status mr_show_runner_start(const mr_scene *scene, const mr_show_def *def,
                                    const mr_clock *base, const mr_show_hooks *hooks,
                                    const mr_show_runner_def *rd, mr_show_runner **out,
                                    mr_show_error *err);

/* A command, queued for the physics (any one thread: the caller's). */
void mr_show_runner_send(mr_show_runner *r, mr_show_cmd cmd);
/* MR_SHOW_CMD_ARM: glove's channels armed (bit c: channel c). */
void mr_show_runner_send_arm(mr_show_runner *r, size_t glove, unsigned armed);
/* The speeds MR_SHOW_CMD_SPEED steps through, and the one after speed. */
bool mr_show_speed_valid(double speed);
double mr_show_speed_next(double speed);

/* The newest frame published, in the caller's own slot: *frame stays its
 * to read until the next call. True when it is newer than the one taken
 * last; *frame NULL until the first frame is published. */
bool mr_show_runner_latest(mr_show_runner *r, const mr_show_frame **frame);

/* Whether the show is over (its time, its takes, quit or an error). */
bool mr_show_runner_done(mr_show_runner *r);

/* One thread only: the commands queued, then one tick of the show.
 * MR_SHOW_OK, MR_SHOW_ENDED, or an error. */
mr_show_status mr_show_runner_tick(mr_show_runner *r);

/* Commands sent and commands the physics has done, of each kind (arrays
 * of MR_SHOW_CMD_COUNT; either may be NULL): the caller's thread's. Once
 * the runner is done, every command sent before the one that ended it
 * has been done. */
void mr_show_runner_counts(mr_show_runner *r, uint64_t *sent, uint64_t *done);

/* Waits for the show's end (send MR_SHOW_CMD_QUIT first to end it now),
 * then mr_show_destroy's result and error. */
mr_show_status mr_show_runner_finish(mr_show_runner *r, mr_show_result *result, mr_show_error *err);

#ifdef __cplusplus
}
#endif

#endif /* MR_SHOW_RUNNER_H */
