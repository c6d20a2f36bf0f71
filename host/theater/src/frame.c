#include "theater_internal.h"

#include <math.h>

void mr_theater_head_frame(const mr_scene *s, mr_scene_world *sw, size_t k, mr_pose goal,
                           double t) {
  if (k >= sw->n_frames || k >= s->n_frames) return;
  const mr_scene_frame *f = &s->frames[k];
  mr_pose now;
  double dt = fmax(t - mr_world_time(sw->world), 0.0);
  if (mr_world_frame_pose(sw->world, sw->frames[k], &now) == MR_OK)
    goal = mr_pose_approach(&now, &goal, f->max_speed * dt, f->max_turn * dt);
  mr_world_set_frame_target(sw->world, sw->frames[k], &goal, t);
}
