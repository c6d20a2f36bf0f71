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

#endif
