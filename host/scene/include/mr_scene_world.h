/* A loaded scene turned into a physics world.
 *
 * mr_scene_build() creates an mr_world with exactly the effects the scene
 * declares and adds its items in file order; a refusal from the physics
 * library is reported at the item's file:line:column. Running it is the
 * theater's (mr_sim.h). */
#ifndef MR_SCENE_WORLD_H
#define MR_SCENE_WORLD_H

#include "mr_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mr_scene_world {
  mr_world *world;
  int *frames; /* scene frame k -> world frame id */
  size_t n_frames;
  int *particle_ids; /* scene particle i -> world particle id (i) */
  int *control_ids;  /* control point j -> world particle id (n_particles + j) */
  size_t n_particles, n_control;
} mr_scene_world;

mr_scene_status mr_scene_build(const mr_scene *scene, mr_scene_world *out, mr_scene_error *err);
void mr_scene_world_free(mr_scene_world *sw);

/* Every world particle's position as a run starts (3 n, world ids: the
 * scene's particles, then its control points), from the world as built:
 * the rest frames the stage takes its display modes from. NULL with err
 * filled when the world cannot be built or memory runs out; else the
 * caller frees it. */
double *mr_scene_start_positions(const mr_scene *scene, size_t *n, mr_scene_error *err);

#ifdef __cplusplus
}
#endif

#endif
