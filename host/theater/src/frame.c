#include "theater_internal.h"

#include <math.h>

void mr_theater_head_frame(const mr_scene *s, mr_scene_world *sw, mr_pose goal, double t) {
  mr_pose now;
  double dt = fmax(t - mr_world_time(sw->world), 0.0);
  if (mr_world_frame_pose(sw->world, sw->frame, &now) == MR_OK)
    goal = mr_pose_approach(&now, &goal, s->control_max_speed * dt, s->control_max_turn * dt);
  mr_world_set_frame_target(sw->world, sw->frame, &goal, t);
}
