/* libFuzzer target for scene files: load, and when the file loads, build
 * its world and take a few steps. Besides the sanitizers it checks the
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

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check(int cond) {
  if (!cond) abort();
}

/* One line, starting with the name the text was given under. */
static void check_error(const mr_scene_error *e) {
  check(strncmp(e->text, "fuzz.yaml", 9) == 0);
  check(strchr(e->text, '\n') == NULL);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  mr_scene s;
  mr_scene_error e;
  if (mr_scene_load_text("fuzz.yaml", (const char *)data, size, &s, &e) != MR_SCENE_OK) {
    check_error(&e);
    return 0;
  }
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
