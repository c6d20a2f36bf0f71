/* Loading a scene, and building its world, when memory runs out. Every
 * allocation the loader and the builder make is failed in turn (tests/
 * common/alloc.h), for the example scenes and the hard cases: each one
 * ends in an error that says "out of memory", with nothing left behind
 * (the sanitizers' leak check runs over this test), or is one the world
 * can do without, and then the world runs exactly as it would have. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "alloc.h"
#include "mr_scene.h"
#include "mr_scene_world.h"

#define SCENES MR_SOURCE_DIR "/host/scenes"

/* The state hash of the world built from scene after `seconds` (a
 * failure to step counts as a state of its own). */
static uint64_t run(const mr_scene_world *sw, double seconds) {
  mr_step_report rep;
  mr_status st = mr_world_step_to(sw->world, seconds, &rep);
  return st < 0 ? (uint64_t)st : mr_world_state_hash(sw->world);
}

typedef struct tally {
  long scenes, loads, builds, refused, done_without;
} tally;

/* The world a loaded scene builds, run for 50 ms. */
static uint64_t world_of(const mr_scene *sc) {
  mr_scene_world sw;
  mr_scene_error err;
  if (mr_scene_build(sc, &sw, &err) != MR_SCENE_OK) fail_msg("%s", err.text);
  const uint64_t h = run(&sw, 0.05);
  mr_scene_world_free(&sw);
  return h;
}

static void loads_when_each_allocation_fails(const char *path, tally *t) {
  mr_scene sc;
  mr_scene_error err;
  tt_alloc_count(0);
  mr_scene_status st0 = mr_scene_load(path, &sc, &err);
  const long n = tt_alloc_stop();
  const uint64_t expected = st0 == MR_SCENE_OK ? world_of(&sc) : 0;
  mr_scene_free(&sc);
  char told[sizeof err.text]; /* a hard case of a load error: the error */
  snprintf(told, sizeof told, "%s", st0 == MR_SCENE_OK ? "" : err.text);
  for (long k = 1; k <= n; k++) {
    tt_alloc_count(k);
    mr_scene_status st = mr_scene_load(path, &sc, &err);
    tt_alloc_stop();
    t->loads++;
    if (st == MR_SCENE_OK && st0 == MR_SCENE_OK) {
      /* A read ahead of the YAML parser, say, that it can do without. */
      const uint64_t got = world_of(&sc);
      mr_scene_free(&sc);
      if (got != expected)
        fail_msg("%s, allocation %ld of %ld failing: loaded, but ran to %016llx, not %016llx", path,
                 k, n, (unsigned long long)got, (unsigned long long)expected);
      t->done_without++;
      continue;
    }
    mr_scene_free(&sc);
    if (st == st0 && st != MR_SCENE_OK && strcmp(err.text, told) == 0) {
      t->done_without++;
      continue;
    }
    /* The first allocation holds the file: "... fits in memory". */
    if (st == MR_SCENE_ERR_NOMEM && strstr(err.text, " memory") != NULL) {
      t->refused++;
      continue;
    }
    fail_msg("%s, allocation %ld of %ld failing: status %d \"%s\" (without it: %d)", path, k, n,
             (int)st, st == MR_SCENE_OK ? "" : err.text, (int)st0);
  }
}

static void builds_when_each_allocation_fails(const char *path, tally *t) {
  mr_scene sc;
  mr_scene_error err;
  if (mr_scene_load(path, &sc, &err) != MR_SCENE_OK) return; /* a case of a load error */
  mr_scene_world sw;
  tt_alloc_count(0);
  if (mr_scene_build(&sc, &sw, &err) != MR_SCENE_OK) fail_msg("%s", err.text);
  const long n = tt_alloc_stop();
  const uint64_t expected = run(&sw, 0.05);
  mr_scene_world_free(&sw);
  for (long k = 1; k <= n; k++) {
    tt_alloc_count(k);
    mr_scene_status st = mr_scene_build(&sc, &sw, &err);
    tt_alloc_stop();
    t->builds++;
    if (st == MR_SCENE_OK) {
      const uint64_t got = run(&sw, 0.05);
      mr_scene_world_free(&sw);
      if (got != expected)
        fail_msg("%s, allocation %ld of %ld failing: built, but ran to %016llx, not %016llx", path,
                 k, n, (unsigned long long)got, (unsigned long long)expected);
      t->done_without++;
      continue;
    }
    if (strstr(err.text, "out of memory") == NULL)
      fail_msg("%s, allocation %ld of %ld failing: \"%s\"", path, k, n, err.text);
    t->refused++;
  }
  mr_scene_free(&sc);
}

static void each_scene_in(const char *dir, tally *t, void (*check)(const char *path, tally *t)) {
  struct dirent **names;
  int n = scandir(dir, &names, NULL, alphasort);
  assert_true(n > 0);
  for (int i = 0; i < n; i++) {
    const char *name = names[i]->d_name;
    size_t len = strlen(name);
    if (len > 5 && strcmp(name + len - 5, ".yaml") == 0) {
      char path[1024];
      snprintf(path, sizeof path, "%s/%s", dir, name);
      check(path, t);
      t->scenes++;
    }
    free(names[i]);
  }
  free(names);
}

static void every_allocation_of_a_load_may_fail(void **state) {
  (void)state;
  tally t = { 0 };
  each_scene_in(SCENES, &t, loads_when_each_allocation_fails);
  each_scene_in(SCENES "/hard", &t, loads_when_each_allocation_fails);
  print_message("%ld scenes: %ld loads with one allocation failing, %ld refused, %ld done "
                "without it\n",
                t.scenes, t.loads, t.refused, t.done_without);
  assert_true(t.scenes >= 40);
  assert_true(t.refused > 1000 && t.refused + t.done_without == t.loads);
}

static void every_allocation_of_a_build_may_fail(void **state) {
  (void)state;
  tally t = { 0 };
  each_scene_in(SCENES, &t, builds_when_each_allocation_fails);
  each_scene_in(SCENES "/hard", &t, builds_when_each_allocation_fails);
  print_message("%ld scenes: %ld builds with one allocation failing, %ld refused, %ld done "
                "without it\n",
                t.scenes, t.builds, t.refused, t.done_without);
  assert_true(t.scenes >= 40);
  assert_true(t.refused > 1000);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(every_allocation_of_a_load_may_fail),
    cmocka_unit_test(every_allocation_of_a_build_may_fail),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
