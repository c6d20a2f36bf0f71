/* Pieces the headless run (sim.c) and the live show (show.c) share.
 * Private to mr_theater. */
#ifndef MR_THEATER_INTERNAL_H
#define MR_THEATER_INTERNAL_H

#include "mr_scene_world.h"
#include "mr_show.h"

/* Control frame k heads for `goal`, reached at t (§6.2), but from where it
 * is now no faster than the scene's control.max_speed and max_turn_rate
 * allow (mr_pose_approach): a jump is spread over the frames that follow.
 * Measured from the frame's pose at the world's time, the rule holds
 * whether a step lands on t or stops short of it. */
void mr_theater_head_frame(const mr_scene *s, mr_scene_world *sw, size_t k, mr_pose goal, double t);
/* The same for the pose of frame k's own track at t, arriving at the
 * track's own rates there when the path keeps the limits (a track is known
 * in time, so the path between targets follows it however far apart the
 * steps put them); otherwise as mr_theater_head_frame. */
void mr_theater_track_frame(const mr_scene *s, mr_scene_world *sw, size_t k, double t);
/* The same for a frame a glove drives, which also changes its velocity no
 * faster than control.max_accel and its turn rate no faster than
 * max_turn_accel allow. The goal's own motion, which the frame
 * matches, is taken from the goals one after another: *follow keeps the
 * last one and its rate (zeroed: none yet). */
typedef struct mr_glove_follow {
  mr_pose goal;       /* the last goal that differed from the one before */
  double t;           /* when it came */
  double u[3], uw[3]; /* how fast the goal moved to it, m/s and rad/s */
  int seen;
} mr_glove_follow;
void mr_theater_follow_glove(const mr_scene *s, mr_scene_world *sw, size_t k,
                             mr_glove_follow *follow, mr_pose goal, double t);

/* Interpolated presentation (interp.c): mark the world's state before the
 * steps that pass a frame time, then ask for the state at that time. */
typedef struct mr_interp {
  int n;                  /* particles */
  double *before, *after; /* positions at the two ends of the last step */
  double *frame;          /* the interpolated positions, 3 n */
  double t_before;
  double lead; /* how far the physics ran past the frame time, s */
} mr_interp;
int mr_interp_open(mr_interp *ip, int n); /* -1: out of memory */
void mr_interp_close(mr_interp *ip);
void mr_interp_mark(mr_interp *ip, const mr_world *w);
const double *mr_interp_at(mr_interp *ip, const mr_world *w, double t);

/* A frame's arrays for n_frames control frames and n_particles particles
 * (show_frame.c); 0 or -1 (nothing kept) when memory runs out. */
int mr_show_frame_alloc(mr_show_frame *f, size_t n_frames, int n_particles);

/* A take beneath a live glove (show_layer.c): the take replays on show
 * time as a glove of its own; the channels armed come from the live
 * glove, the rest from the take. */
typedef struct mr_layer {
  mr_glove *take; /* NULL: nothing beneath */
  unsigned armed; /* bit c: channel c from the live glove */
} mr_layer;
/* The take at path beneath; 0, or -1 and one line in msg. */
int mr_layer_open(mr_layer *l, const char *path, unsigned armed, char *msg, size_t size);
void mr_layer_close(mr_layer *l);
/* The take read up to show time t. */
void mr_layer_poll(mr_layer *l, double t);
/* The live glove's reading with the take's values on the channels not
 * armed: its sample count counts both gloves' samples (new when either
 * sent one), its host time the newer one's. Whether there is anything to
 * follow: the take live, or an armed live glove live. */
bool mr_layer_read(const mr_layer *l, const mr_glove *live, mr_glove_reading *out);
/* The take beneath has played to its end. */
bool mr_layer_over(const mr_layer *l);

/* Arming and punches, asked between ticks and done as a frame starts. */
typedef struct mr_punch {
  unsigned arm_asked[MR_SHOW_MAX_GLOVES];
  bool arm_pending[MR_SHOW_MAX_GLOVES];
  unsigned punches_asked;
  bool recording, punched_out;
  double def_in, def_out;     /* mr_show_def's punch times, < 0: none */
  double punch_in, punch_out; /* the frames' times, -1: not yet */
  unsigned punched[MR_SHOW_MAX_GLOVES];
} mr_punch;
void mr_punch_init(mr_punch *p, double punch_in, double punch_out);
void mr_punch_ask_arm(mr_punch *p, size_t glove, unsigned armed);
/* At frame t: the arming asked (refused while recording), the punches
 * asked, and the definition's punch times come; each told through note. */
void mr_punch_asks(mr_punch *p, mr_layer *layers, size_t n, double t,
                   void (*note)(void *user, const char *line), void *user);

#endif
