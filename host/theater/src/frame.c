#include "theater_internal.h"

#include <math.h>

/* Halvings of the goal's share when the path to it would pass a limit:
 * 2⁻²⁰ of the way is closer than the motion can show. */
#define LIMIT_HALVINGS 20

/* Whether the path the physics would make to `goal` by t keeps the
 * frame's speed and turn-rate limits (its bounds, which no point of the
 * path exceeds). */
static int within(const mr_scene_world *sw, size_t k, const mr_scene_frame *f, const mr_pose *goal,
                  double t) {
  double speed, turn;
  if (mr_world_frame_target_peak(sw->world, sw->frames[k], goal, t, &speed, &turn) != MR_OK)
    return 1;
  return speed <= f->max_speed && turn <= f->max_turn;
}

/* The approach rule (mr_pose_approach) keeps the chord from `now` to the
 * goal within the limits; the path the physics makes is curved (its
 * velocity is continuous across targets), and may pass them on the way,
 * so the goal is drawn back towards `now` until the path keeps them. */
void mr_theater_head_frame(const mr_scene *s, mr_scene_world *sw, size_t k, mr_pose goal,
                           double t) {
  if (k >= sw->n_frames || k >= s->n_frames) return;
  const mr_scene_frame *f = &s->frames[k];
  mr_pose now;
  double dt = fmax(t - mr_world_time(sw->world), 0.0);
  if (mr_world_frame_pose(sw->world, sw->frames[k], &now) == MR_OK) {
    goal = mr_pose_approach(&now, &goal, f->max_speed * dt, f->max_turn * dt);
    if (dt > 0 && !within(sw, k, f, &goal, t)) {
      double lo = 0.0, hi = 1.0;
      for (int i = 0; i < LIMIT_HALVINGS; i++) {
        double mid = 0.5 * (lo + hi);
        mr_pose g = mr_pose_interpolate(&now, &goal, mid);
        if (within(sw, k, f, &g, t))
          lo = mid;
        else
          hi = mid;
      }
      goal = mr_pose_interpolate(&now, &goal, lo);
    }
  }
  mr_world_set_frame_target(sw->world, sw->frames[k], &goal, t);
}
