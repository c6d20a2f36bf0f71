/* `marionette run --publish URL`: each simulated frame of the show out to
 * a broker (mr_state.h), its scene retained beside it, and `--particles
 * FILE`: each frame's particles written out, as a watcher's --dump writes
 * what it received. */
#ifndef MR_APP_STATE_PUB_H
#define MR_APP_STATE_PUB_H

#include <stddef.h>
#include <stdio.h>

#include "mr_scene.h"
#include "mr_show.h"
#include "mr_state.h"

typedef struct mr_app_state_pub mr_app_state_pub;

/* The scene's files (the scene file, then the models and the files they
 * name, all beside it) and a link to url (NULL: none), and particles
 * opened (NULL: none). 0, or -1 with one line in msg (a model that is not
 * beside the scene, a broker that refused). */
int mr_app_state_pub_open(const char *url, const char *particles, const mr_scene *scene, double fps,
                          mr_app_state_pub **out, char *msg, size_t msg_size);
/* One simulated frame, on the thread that simulates: never waits. */
void mr_app_state_pub_frame(mr_app_state_pub *p, const mr_show_frame *f);
/* The summary's lines (published, dropped) to out; closes and frees. -1
 * when a line of --particles was lost or the broker refused the show. */
int mr_app_state_pub_close(mr_app_state_pub *p, FILE *out);

/* The files a watcher needs to build scene's stage, into b: the scene
 * file, its model files and the files they name (an OBJ's mtllib, an
 * MTL's maps), each by its path relative to the scene's folder. 0, or -1
 * with one line in msg. Shared with the benchmark. */
int mr_app_scene_files(const mr_scene *scene, mr_state_bundle *b, char *msg, size_t msg_size);

#endif
