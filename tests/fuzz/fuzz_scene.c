/* libFuzzer target for scene files: load, and when the file loads, build
 * its world and take a few steps, and make its stage and one draw list. Besides the sanitizers it checks the
 * loader's promises: a refusal is one line that names the file, and no
 * input hangs it (libFuzzer's -timeout catches a loop). The seeds are
 * every scene in the repository plus the inputs that once hung or
 * flooded the parser (tests/fuzz/corpus/scene). */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mr_scene.h"
#include "mr_scene_world.h"
#include "mr_stage.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check(int cond) {
  if (!cond) abort();
}

/* One line, starting with the name the text was given under. */
static void check_error(const mr_scene_error *e) {
  check(strncmp(e->text, "fuzz.yaml", 9) == 0);
  check(strchr(e->text, '\n') == NULL);
}

/* The stage takes every def the loader makes: its ids and counts are
 * always in range (a rigid model's points on a hair's breadth of one line
 * may still be refused as a value). */
static void check_stage(const mr_scene *s) {
  size_t n = s->n_particles + s->n_control_points;
  double *xyz = malloc((3 * n + 3) * sizeof *xyz);
  check(xyz != NULL);
  for (size_t i = 0; i < s->n_particles; i++)
    memcpy(&xyz[3 * i], s->particles[i].def.position, 3 * sizeof(double));
  for (size_t j = 0; j < s->n_control_points; j++) {
    mr_pose pose;
    mr_scene_frame_pose_at(s, s->control_points[j].frame, 0, &pose);
    mr_scene_control_point_world(s, j, &pose, &xyz[3 * (s->n_particles + j)]);
  }
  mr_stage *st = NULL;
  char msg[256];
  mr_stage_status rc = mr_stage_create(&s->stage, xyz, n, &st, msg, sizeof msg);
  check(rc == MR_STAGE_OK || rc == MR_STAGE_ERR_VALUE);
  if (rc == MR_STAGE_OK) {
    const mr_draw_list *list;
    check(mr_stage_update(st, xyz, n, &list) == MR_STAGE_OK);
    mr_stage_destroy(st);
  }
  free(xyz);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  mr_scene s;
  mr_scene_error e;
  if (mr_scene_load_text("fuzz.yaml", (const char *)data, size, &s, &e) != MR_SCENE_OK) {
    check_error(&e);
    return 0;
  }
  check_stage(&s);
  mr_scene_world sw;
  if (mr_scene_build(&s, &sw, &e) != MR_SCENE_OK) {
    check_error(&e);
  } else {
    /* A few steps of a small world: enough to reach every pass the file
     * declares, not so many that a slow scene stalls the search. */
    if (s.n_particles <= 64)
      for (int i = 0; i < 3; i++)
        if (mr_world_step(sw.world, NULL) < 0) break;
    mr_scene_world_free(&sw);
  }
  mr_scene_free(&s);
  return 0;
}
