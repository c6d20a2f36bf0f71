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
 * its speed limits (mr_pose_approach) and changing its velocity no faster
 * than its acceleration limits (control.max_accel), and the world is
 * stepped to land on the frame time. A glove that is lost leaves its frames where they were: the
 * puppets hold their pose. Presenting a frame is the caller's hook: the
 * program draws it on the stage (host/render) and prints a status line.
 *
 * The show is an object ticked one frame at a time (mr_show_tick), from
 * one thread; mr_show_runner.h runs it on a thread of its own. Every frame
 * it hands out is a snapshot (mr_show_frame), values only. */
#ifndef MR_SHOW_H
#define MR_SHOW_H

#include "mr_def.h"
#include "mr_glove.h"
#include "mr_scene_world.h"
#include "mr_sim.h"
#include "mr_theater.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { MR_SHOW_MAX_GLOVES = 8 };

/* What a show's calls return. */
typedef enum mr_show_status {
  MR_SHOW_OK = 0,
  MR_SHOW_ENDED = 1,        /* mr_show_tick: the show is over (its time, its takes, stop) */
  MR_SHOW_ERR_ARG = -1,     /* a NULL, a def not made by its maker, no glove or more than 8 */
  MR_SHOW_ERR_SCENE = -2,   /* the scene's world could not be built */
  MR_SHOW_ERR_MAPPING = -3, /* no mapping of that name, or one the control side refused */
  MR_SHOW_ERR_GLOVE = -4,   /* a glove source that cannot be used */
  MR_SHOW_ERR_TAKE = -5,    /* a take that cannot be written */
  MR_SHOW_ERR_PHYSICS = -6, /* the physics stopped */
  MR_SHOW_ERR_NOMEM = -7,
  MR_SHOW_ERR_THREAD = -8 /* the physics thread could not be started */
} mr_show_status;

typedef struct mr_show_error {
  mr_show_status status;
  char message[400];
  char text[800]; /* "SCENE_PATH: message" */
} mr_show_error;

typedef struct mr_show_def {
  uint32_t cookie;  /* MR_DEF_COOKIE, set by mr_default_show_def() */
  mr_policy policy; /* default skip */
  double duration;  /* s of show, <= 0: until stopped (or the takes' end) */
  double fps;       /* <= 0: the scene's sim.fps, else 60 */
  /* Frames landed on (the paper's) or interpolated between steps at the
   * ATS's own Δt; MR_PRESENT_SCENE (default): the scene's sim.present. */
  mr_present_mode present;
  /* Frames simulated in one tick at the most when behind, past which the
   * lag is given up (mr_scheduler_def); <= 0: the scheduler's default.
   * A show on its own thread may chase further: its frames cost little. */
  int max_catch_up;
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
  /* Layered playback (issue 23). Glove i plays the take beneath[i] (.mrec;
   * NULL: none) under the live glove: each channel (finger) comes from
   * the take, replayed on show time as a --replay glove is, except the
   * channels armed (bit c of armed[i]: channel c), which come from the
   * live glove; mr_show_arm changes them during the show. The live
   * glove's bytes are recorded whole into record[i] as ever: the take
   * library merges the armed channels between the punch times. */
  const char *beneath[MR_SHOW_MAX_GLOVES];
  unsigned armed[MR_SHOW_MAX_GLOVES];
  /* Punch-in and punch-out at the first frames at or past these show
   * times (< 0, the default: only when mr_show_punch asks). The show ends
   * with the punch-out frame: its take is done. */
  double punch_in, punch_out;
  /* The clock the live gloves are read on (their loss timeouts, clock
   * offsets and latencies run on it), at the pace of their own clocks
   * when slow motion slows show time (mr_clock_paced); .now NULL, the
   * default: the show's clock. Takes are read on show time, and a live
   * glove's bytes are recorded with the show time of their frame, so a
   * take performed slowly replays at full speed. */
  mr_clock glove_clock;
} mr_show_def;
mr_show_def mr_default_show_def(void);

/* One glove as a frame shows it: copies, taken when the frame was made. */
typedef struct mr_show_glove_view {
  mr_glove_state state;
  mr_glove_reading reading; /* the newest sample */
  mr_glove_counters counters;
  double clock_offset; /* mr_glove_clock_offset */
  char describe[400];  /* mr_glove_describe at the frame's time */
  bool layered;        /* a take plays beneath it (mr_show_def.beneath) */
  unsigned armed;      /* layered: the channels from the live glove (bit c) */
} mr_show_glove_view;

/* A frame: a snapshot, values only. Nothing in it points into the show or
 * its world, so whoever holds one may keep it, hand it to another thread
 * and read it while the physics runs on. Its arrays are its own, sized
 * for the show it was made for (mr_show_frame_make). */
typedef struct mr_show_frame {
  double t;                 /* simulated time */
  uint64_t hash;            /* the world's state hash at t (frame_done only; else 0) */
  mr_scheduler_stats stats; /* the scheduler's figures as the frame was made */
  size_t n_frames;          /* control frames, every one of the scene's */
  mr_pose *target;          /* per control frame: where its glove sends it */
  mr_pose *pose;            /* per control frame: where it is at t */
  int *glove_of;            /* per control frame: its glove's index, -1 unbound */
  size_t n_gloves;
  mr_show_glove_view gloves[MR_SHOW_MAX_GLOVES];
  /* Every particle's position as the frame shows it (3 n): the world's at
   * t, or interpolated to t between the steps around it. */
  double *xyz;
  int n_particles;
  char mapping[32]; /* the mapping in use */
  /* Punched in (recording the armed channels) since punch_in; punch_out
   * once punched out; -1 before. */
  bool recording;
  double punch_in, punch_out;
} mr_show_frame;

typedef struct mr_show mr_show;

/* A frame sized for show's control frames and particles, zeroed; 0, or -1
 * when memory runs out. mr_show_frame_free gives its arrays back. */
int mr_show_frame_make(const mr_show *show, mr_show_frame *out);
void mr_show_frame_free(mr_show_frame *f);
/* src into dst, both made for the same show; -1 (dst untouched) when
 * their sizes differ. */
int mr_show_frame_copy(mr_show_frame *dst, const mr_show_frame *src);

typedef struct mr_show_hooks {
  /* A frame the scheduler shows, a snapshot the hook may read as long as
   * it runs and keep with mr_show_frame_copy. May be NULL. */
  void (*present)(void *user, const mr_show_frame *frame);
  /* Polled once a frame: nonzero ends the show. May be NULL. */
  int (*stop)(void *user);
  /* After each frame is simulated (shown or skipped): the frame, with the
   * world's state hash, which a replay of the take reproduces bit for bit.
   * May be NULL. */
  void (*frame_done)(void *user, const mr_show_frame *frame);
  /* One line for the user when a glove's channel goes bad (NaN, or stuck
   * at an end past the mapping's stuck_after: held at neutral) or
   * recovers, naming the glove, its source and the finger; and when a
   * reset or a mapping is done. May be NULL. */
  void (*note)(void *user, const char *line);
  void *user;
} mr_show_hooks;

typedef struct mr_show_glove_result {
  mr_glove_counters counters;
  mr_glove_state state; /* at the end */
  uint64_t samples;     /* samples taken */
  char describe[400];   /* mr_glove_describe at the end */
  /* A glove over a broker: its link's counters (mr_glove_net_counters). */
  bool over_net;
  mr_net_counters net;
} mr_show_glove_result;

typedef struct mr_show_result {
  mr_scheduler_stats frames;
  mr_show_glove_result glove[MR_SHOW_MAX_GLOVES];
  size_t n_gloves;
  /* Every control frame's glove at the end, -1 unbound (n_frames of them;
   * mr_show_result_free gives them back). */
  int *glove_of;
  size_t n_frames;
  /* Interpolated frames: how far the physics had run past each frame when
   * it was shown, mean and max, s: input read at a frame moves the puppet
   * only from there on, so this adds to the latency counters. */
  bool interpolated;
  double lead_mean, lead_max;
  char mapping[32]; /* the mapping in use at the end */
  /* The punch-in and punch-out frames' show times (-1: none), and each
   * glove's channels armed from the punch-in on (what the take library
   * merges, mr_take_punch). */
  double punch_in, punch_out;
  unsigned punched[MR_SHOW_MAX_GLOVES];
} mr_show_result;
void mr_show_result_free(mr_show_result *r);

/* The show of scene (which must outlive it) with def's gloves on clock
 * (copied; its self must outlive the show), hooks copied. MR_SHOW_OK, or
 * an error in err naming what (the scene's world refused, a bad glove
 * source, a mapping, a take that cannot be written). */
mr_show_status mr_show_create(const mr_scene *scene, const mr_show_def *def, const mr_clock *clock,
                              const mr_show_hooks *hooks, mr_show **out, mr_show_error *err);

/* One tick of the scheduler: the frame computed last shown (unless the
 * skip policy finds it stale), the next simulated, then the wait for the
 * next tick's time on the clock. MR_SHOW_OK; MR_SHOW_ENDED when the show
 * is over; or an error (mr_show_destroy says what). */
mr_show_status mr_show_tick(mr_show *show);

/* Asked between ticks, done as the next frame starts: every puppet back
 * where it started (positions, at rest) with each control frame at its
 * start pose, the gloves moving them on from there; and every control
 * frame moved to the scene's next mapping (after the last, the first),
 * the filters kept. Each is told through the note hook. */
void mr_show_reset(mr_show *show);
void mr_show_next_mapping(mr_show *show);
/* Asked between ticks, done as the next frame starts: glove's channels
 * armed (bit c: channel c from the live glove, the rest from the take
 * beneath), told through the note hook; refused (and told) while
 * recording, whose channels stay those armed at the punch-in. And a punch:
 * in when not recording (that frame's time is the punch-in), else out (the
 * show ends with that frame). */
void mr_show_arm(mr_show *show, size_t glove, unsigned armed);
void mr_show_punch(mr_show *show);

/* The frame as it stands (the latest simulated), into a frame made for
 * this show. */
void mr_show_snapshot(const mr_show *show, mr_show_frame *out);

/* What the show did (result, may be NULL; mr_show_result_free after) and
 * why it failed (err, may be NULL); the takes closed, everything freed.
 * Returns MR_SHOW_OK or the first error (a take that could not be closed
 * counts). */
mr_show_status mr_show_destroy(mr_show *show, mr_show_result *result, mr_show_error *err);

/* create, tick until the end, destroy: the one-thread show. */
mr_show_status mr_show_run(const mr_scene *scene, const mr_show_def *def, const mr_clock *clock,
                           const mr_show_hooks *hooks, mr_show_result *result, mr_show_error *err);

#ifdef __cplusplus
}
#endif

#endif /* MR_SHOW_H */
