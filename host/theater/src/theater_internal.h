/* Pieces the headless run (sim.c) and the live show (show.c) share.
 * Private to mr_theater. */
#ifndef MR_THEATER_INTERNAL_H
#define MR_THEATER_INTERNAL_H

#include "mr_scene_world.h"

/* Control frame k heads for `goal`, reached at t (§6.2), but from where it
 * is now no faster than the scene's control.max_speed and max_turn_rate
 * allow (mr_pose_approach): a jump is spread over the frames that follow.
 * Measured from the frame's pose at the world's time, the rule holds
 * whether a step lands on t or stops short of it. */
void mr_theater_head_frame(const mr_scene *s, mr_scene_world *sw, size_t k, mr_pose goal, double t);

#endif
