/* mr_theater: the clock and the frame scheduler of a show (§4.6).
 *
 * The stage is drawn at a fixed frame rate. Each tick presents the frame
 * computed at the tick before (one frame of delay, by design), then runs
 * the physics to the next frame's time, the last step landing on it. Under
 * load the paper's policy skips renders while simulated time stays locked
 * to wall time, and the catch-up is capped so the loop never spirals; the
 * `slow` policy instead lets simulated time fall behind and skips nothing.
 *
 * Time comes from an mr_clock: the wall clock for a show, a virtual clock
 * for tests, `marionette sim` and replays, so a run is reproducible. The
 * scheduler knows nothing of physics or drawing: it calls the hooks it is
 * given. Manners as elsewhere: definition structs from default makers,
 * mr_object_verb names, no printing, no aborting.
 */
#ifndef MR_THEATER_H
#define MR_THEATER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mr_def.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- clock */

/* A source of time in seconds and a way to wait for a time. */
typedef struct mr_clock {
  double (*now)(void *self);
  void (*wait_until)(void *self, double t); /* returns at once if t has passed */
  void *self;
} mr_clock;

/* CLOCK_MONOTONIC, and nanosleep until the time asked. */
mr_clock mr_clock_wall(void);

/* A clock that moves only when told: waiting moves it to the time waited
 * for, and work that costs time moves it by mr_virtual_clock_spend. */
typedef struct mr_virtual_clock {
  double t;
} mr_virtual_clock;
mr_clock mr_clock_virtual(mr_virtual_clock *vc);
void mr_virtual_clock_spend(mr_virtual_clock *vc, double seconds);

/* Whether c is mr_clock_wall()'s: its times are CLOCK_MONOTONIC's, which
 * a thread may wait for by other means (a condition variable). */
bool mr_clock_is_wall(const mr_clock *c);

/* A clock over another (the wall, or a virtual one in tests) that pause,
 * single step and slow motion act on: show time runs at `rate` show
 * seconds per base second and stands still while paused. A wait for a
 * show time runs until the base clock reaches the time it comes at;
 * paused, it ends only by a single step, which moves show time to the
 * time waited for (one frame, when the scheduler waits), or by `idle`.
 * One thread uses it: the one that ticks the show. */
typedef struct mr_scaled_clock {
  mr_clock base;
  double rate; /* > 0 */
  bool paused;
  unsigned steps; /* single steps asked and not yet taken */
  double show_base, base_base;
  /* Base seconds that slow motion has held back from show time, up to
   * base_base (mr_scaled_clock_pace_now). */
  double held_base;
  /* Called while a wait cannot end yet, with the base time it would end
   * at (INFINITY while paused without a step). It returns no later than
   * that, may pause, step or change the rate in between, and returns
   * nonzero to end the wait at once (the show is quitting). NULL: the
   * base clock's wait, and a paused wait without a step returns at
   * once. */
  int (*idle)(void *user, double base_deadline);
  void *user;
} mr_scaled_clock;

/* Show time 0 at the base's now, rate 1, running; idle NULL. */
void mr_scaled_clock_init(mr_scaled_clock *sc, const mr_clock *base);
mr_clock mr_clock_scaled(mr_scaled_clock *sc); /* sc must not move afterwards */
double mr_scaled_clock_now(const mr_scaled_clock *sc);
/* The show's pace: show time plus the base seconds slow motion held back
 * from it, so it runs at the base clock's pace while the show runs at any
 * rate, stands still while paused, and single steps move it with show
 * time. At rate 1 it is show time, bit for bit. Live gloves are read on
 * it (mr_show_def.glove_clock): their own clocks run at that pace. */
double mr_scaled_clock_pace_now(const mr_scaled_clock *sc);
mr_clock mr_clock_paced(mr_scaled_clock *sc); /* now only: its wait is the scaled clock's */
void mr_scaled_clock_pause(mr_scaled_clock *sc, bool paused);
void mr_scaled_clock_set_rate(mr_scaled_clock *sc, double rate); /* ignored unless > 0 */
/* Pauses (if running) and lets the next paused wait end at its time. */
void mr_scaled_clock_step(mr_scaled_clock *sc);

/* ------------------------------------------------------------ scheduler */

typedef enum mr_policy {
  MR_POLICY_SKIP = 0, /* the paper's: skip renders, keep simulated time on wall time */
  MR_POLICY_SLOW      /* skip nothing, let simulated time slow down */
} mr_policy;
const char *mr_policy_name(mr_policy p);
int mr_policy_parse(const char *name, mr_policy *out);

typedef struct mr_scheduler_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_scheduler_def() */
  double fps;      /* frames per second, > 0; default 60 */
  mr_policy policy;
  int max_catch_up; /* frames simulated in one tick at the most when behind;
                       past that the lag is dropped, so the loop never
                       spirals. Default 5 */
  /* The clock the latency figures are read on (the input noted and the
   * frame presented): a show in slow motion measures them at its gloves'
   * pace, not in slowed show seconds. .now NULL (default): the
   * scheduler's own. */
  mr_clock latency_clock;
} mr_scheduler_def;
mr_scheduler_def mr_default_scheduler_def(void);

/* What the physics did to reach one frame time. */
typedef struct mr_frame_work {
  uint64_t steps, rejected, resets;
} mr_frame_work;

typedef struct mr_scheduler_hooks {
  /* Advance the world to simulated time t (its last step landing on t) and
   * keep that state as the frame to present. Nonzero stops the show after
   * this frame (counted as simulated, never presented). */
  int (*advance)(void *user, double t, mr_frame_work *work);
  /* Draw the frame kept for simulated time t. */
  void (*present)(void *user, double t);
  void *user;
} mr_scheduler_hooks;

typedef struct mr_scheduler_stats {
  uint64_t ticks, frames_simulated, frames_presented, frames_skipped;
  uint64_t steps, rejected, resets;
  double sim_time;                 /* simulated time reached, s */
  double wall_time;                /* wall time since the first tick, s */
  double dropped_time;             /* lag given up by the catch-up cap (skip policy), s */
  double real_time_factor;         /* sim_time / wall_time; 1 when the show keeps up */
  double latency_p50, latency_p99; /* input sample to presented frame, s;
                                      0 before any input was noted */
  double last_present_wall, last_present_sim; /* of the latest presented frame */
} mr_scheduler_stats;

typedef struct mr_scheduler mr_scheduler;

typedef enum mr_theater_status {
  MR_THEATER_OK = 0,
  MR_THEATER_STOPPED = 1,  /* the advance hook asked to stop: an end, not a failure */
  MR_THEATER_ERR_ARG = -1, /* a NULL, a def not made by its maker, a bad field */
} mr_theater_status;

/* A scheduler over a clock (copied) and hooks (copied). msg names a bad
 * field. The first tick starts simulated time 0 at the clock's now. */
mr_theater_status mr_scheduler_create(const mr_scheduler_def *def, const mr_clock *clock,
                                      const mr_scheduler_hooks *hooks, mr_scheduler **out,
                                      char *msg, size_t msg_size);
void mr_scheduler_destroy(mr_scheduler *s);

/* One tick: present the frame computed last (unless the skip policy finds
 * it stale), simulate to the next frame time (more than one when behind,
 * up to max_catch_up), then wait for the next tick's time. */
mr_theater_status mr_scheduler_tick(mr_scheduler *s);

/* An input sample arrived at wall time t (the clock's): the next frame
 * simulated uses it, and the latency counters measure from t to the
 * presentation of that frame. */
void mr_scheduler_note_input(mr_scheduler *s, double t);

void mr_scheduler_get_stats(const mr_scheduler *s, mr_scheduler_stats *out);

#ifdef __cplusplus
}
#endif

#endif /* MR_THEATER_H */
