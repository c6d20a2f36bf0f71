/* scene-bench: the time to load a scene file and build its world, for
 * chains of 1 000 to 100 000 particles (one distance constraint per link,
 * the names and places a loader must index). The loader once compared
 * every pair, 62 s of CPU for 100 000 particles. It now hashes names and
 * places and reads the "- {...}" lines ahead of libfyaml, so the time
 * should grow about 10 times per row (the last column); at 100 000 what
 * remains is a third libfyaml, a third the reading of values, and the
 * 200 MB of models the stage gets (one per particle and constraint).
 *
 *   scene-bench [--min N] [--max N]
 *
 * --min N starts the rows at N, so that an instruction count covers only
 * the size in question:
 *   valgrind --tool=callgrind --toggle-collect=mr_scene_load_text \
 *     scene-bench --min 100000 --max 100000
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mr_scene.h"
#include "mr_scene_world.h"

static double cpu_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* A chain of n particles on a 300-wide grid, 1 cm apart. */
static char *chain(long n, size_t *len) {
  size_t cap = (size_t)n * 120 + 256, used = 0;
  char *t = malloc(cap);
  if (t == NULL) return NULL;
  used += (size_t)snprintf(t + used, cap - used,
                           "physics:\n  effects: [gravity, constraints]\n  particles:\n");
  for (long i = 0; i < n; i++)
    used += (size_t)snprintf(t + used, cap - used,
                             "    - {name: p%ld, position: [%.2f, %.2f, 0], mass: 1}\n", i,
                             (double)(i % 300) * 0.01, (double)(i / 300) * 0.01);
  used += (size_t)snprintf(t + used, cap - used, "  constraints:\n");
  for (long i = 1; i < n; i++)
    used += (size_t)snprintf(t + used, cap - used, "    - {between: [p%ld, p%ld]}\n", i - 1, i);
  *len = used;
  return t;
}

int main(int argc, char **argv) {
  long min = 1000, max = 100000;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--help") == 0) {
      printf("usage: scene-bench [--min N] [--max N]\n"
             "Times loading and building chain scenes of N particles (--min, default\n"
             "1 000) up to N (--max, default 100 000), ten times more each row.\n");
      return 0;
    }
    if (strcmp(argv[i], "--max") == 0 && i + 1 < argc && atol(argv[i + 1]) >= 1000) {
      max = atol(argv[++i]);
      continue;
    }
    if (strcmp(argv[i], "--min") == 0 && i + 1 < argc && atol(argv[i + 1]) >= 1000) {
      min = atol(argv[++i]);
      continue;
    }
    fprintf(stderr, "scene-bench: unknown argument '%s' (see --help)\n", argv[i]);
    return 2;
  }
  printf("%10s %10s %10s %10s %8s\n", "particles", "bytes", "load s", "build s", "growth");
  double last = 0;
  for (long n = min; n <= max; n *= 10) {
    size_t len = 0;
    char *text = chain(n, &len);
    if (text == NULL) {
      fprintf(stderr, "scene-bench: out of memory at %ld particles\n", n);
      return 1;
    }
    mr_scene s;
    mr_scene_error e;
    double t0 = cpu_seconds();
    if (mr_scene_load_text("chain.yaml", text, len, &s, &e) != MR_SCENE_OK) {
      fprintf(stderr, "scene-bench: %s\n", e.text);
      return 1;
    }
    double t1 = cpu_seconds();
    mr_scene_world sw;
    if (mr_scene_build(&s, &sw, &e) != MR_SCENE_OK) {
      fprintf(stderr, "scene-bench: %s\n", e.text);
      return 1;
    }
    double t2 = cpu_seconds();
    printf("%10ld %10zu %10.3f %10.3f", n, len, t1 - t0, t2 - t1);
    if (last > 0)
      printf(" %7.1fx\n", (t2 - t0) / last);
    else
      printf(" %8s\n", "-");
    last = t2 - t0;
    mr_scene_world_free(&sw);
    mr_scene_free(&s);
    free(text);
  }
  return 0;
}
