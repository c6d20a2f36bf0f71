/* A show's draw lists kept frame by frame, and written out for the tools
 * where animation is finished (`marionette export`, issue 23, item 4): a
 * glTF 2.0 binary (.glb) with the stage's meshes and their animation, a
 * PC2 point cache of the freeform vertices, and a CSV of the particles'
 * trajectories.
 *
 * The models are loaded as the renderer loads them (mr_model_load: the
 * built-in shapes and model files through Assimp, placement applied) but
 * nothing here starts GL. Each frame, the particles' positions go through
 * the stage (mr_stage_update) and its draw list is kept: per model a pose
 * and a scale, per freeform model its bones' poses. */
#ifndef MR_APP_EXPORT_H
#define MR_APP_EXPORT_H

#include <stddef.h>
#include <stdint.h>

#include "mr_scene.h"

typedef struct mr_export mr_export;

/* The stage of scene (which must outlive it) with every model loaded. 0,
 * or -1 with msg naming what failed: "SCENE:LINE:COLUMN: model 'NAME':
 * FILE: why", and where else it was looked for. */
int mr_export_open(const mr_scene *scene, mr_export **out, char *msg, size_t msg_size);
void mr_export_close(mr_export *e);

/* One frame at show time t (strictly after the one before; a frame that
 * is not is dropped, returning 1): the world's positions xyz (3 n). 0, 1,
 * or -1 with msg. */
int mr_export_add(mr_export *e, double t, const double *xyz, size_t n, char *msg, size_t msg_size);

/* Frames kept, and the time of the last. */
size_t mr_export_frames(const mr_export *e);
double mr_export_last_time(const mr_export *e);
/* Nodes the glTF file holds: one per model shown, and one per bone of
 * each freeform model (its joints). Animation channels, likewise. */
size_t mr_export_nodes(const mr_export *e);
size_t mr_export_channels(const mr_export *e);
/* Vertices a PC2 file holds a frame: every freeform model's, in order. */
size_t mr_export_points(const mr_export *e);

/* The files. 0, or -1 with msg naming the file and why. */
int mr_export_write_glb(const mr_export *e, const char *path, char *msg, size_t msg_size);
int mr_export_write_pc2(const mr_export *e, const char *path, char *msg, size_t msg_size);
int mr_export_write_csv(const mr_export *e, const char *path, char *msg, size_t msg_size);

/* The hash a take names its scene by (mr_rec_header's scene_hash): the
 * state hash of the scene's world as built. 0 with msg when the world
 * cannot be built. */
uint64_t mr_export_scene_hash(const mr_scene *scene, char *msg, size_t msg_size);

#endif
