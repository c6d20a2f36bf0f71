/* No allocation inside the step: after a world's first step, stepping it
 * allocates nothing, whatever the solver method. The test binary counts
 * every malloc, calloc, realloc and aligned allocation (its own
 * definitions come before the C library's), and watches 1 000 steps of
 * host/scenes/puppet.yaml, control track, floor contacts and all, under each
 * solver method. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mr_scene.h"
#include "mr_scene_world.h"
#include "mr_sim.h"

/* ------------------------------------------------- counting allocator */

/* glibc's own entry points, which its malloc family is made of. */
void *__libc_malloc(size_t size);
void *__libc_calloc(size_t n, size_t size);
void *__libc_realloc(void *p, size_t size);
void *__libc_memalign(size_t align, size_t size);
void __libc_free(void *p);
int posix_memalign(void **out, size_t align, size_t size);

static int counting;
static unsigned long allocations;

#if !defined(__SANITIZE_ADDRESS__)
static void count(void) {
  if (counting) allocations++;
}

void *malloc(size_t size) {
  count();
  return __libc_malloc(size);
}

void *calloc(size_t n, size_t size) {
  count();
  return __libc_calloc(n, size);
}

void *realloc(void *p, size_t size) {
  count();
  return __libc_realloc(p, size);
}

void free(void *p) {
  __libc_free(p);
}

void *aligned_alloc(size_t align, size_t size) {
  count();
  return __libc_memalign(align, size);
}

int posix_memalign(void **out, size_t align, size_t size) {
  count();
  void *p = __libc_memalign(align, size);
  if (!p) return 12; /* ENOMEM */
  *out = p;
  return 0;
}
#define COUNTING_BUILT_IN 1
#else
/* AddressSanitizer owns malloc in that build; the count is taken in the
 * plain one. */
#define COUNTING_BUILT_IN 0
#endif

/* ------------------------------------------------------------- the run */

enum { WATCHED_STEPS = 1000 };

typedef struct watch {
  uint64_t steps;            /* accepted steps so far */
  uint64_t watched;          /* of them, taken while counting */
  unsigned long after_first; /* allocations from step 2 to step 1001 */
} watch;

/* Counting starts once the first step is done and stops after 1 000 more. */
static void on_step(void *user, const mr_sim_step *row) {
  watch *w = user;
  w->steps += (uint64_t)row->accepted;
  if (counting) w->watched += (uint64_t)row->accepted;
  if (counting && w->watched >= WATCHED_STEPS) {
    counting = 0;
    w->after_first = allocations;
  }
  if (!counting && w->watched == 0 && w->steps >= 1) {
    allocations = 0;
    counting = 1;
  }
}

static char *read_file(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  assert_non_null(f);
  char *text = calloc(1, 1 << 16);
  assert_non_null(text);
  *len = fread(text, 1, (1 << 16) - 1, f);
  fclose(f);
  return text;
}

/* puppet.yaml with `method: <method>` added to its solver settings. */
static char *puppet_with_method(const char *method, size_t *len) {
  size_t n;
  char *text = read_file(MR_SOURCE_DIR "/host/scenes/puppet.yaml", &n);
  const char *key = "solver: {integrator: rk4";
  char *at = strstr(text, key);
  assert_non_null(at);
  char *out = calloc(1, n + 64);
  assert_non_null(out);
  size_t head = (size_t)(at - text) + strlen(key);
  memcpy(out, text, head);
  int k = snprintf(out + head, 64, ", method: %s", method);
  memcpy(out + head + (size_t)k, text + head, n - head);
  *len = n + (size_t)k;
  free(text);
  return out;
}

static void run_method(const char *method) {
  if (!COUNTING_BUILT_IN) skip();
  size_t len;
  char *text = puppet_with_method(method, &len);
  mr_scene scene;
  mr_scene_error err;
  if (mr_scene_load_text("puppet.yaml", text, len, &scene, &err) != MR_SCENE_OK)
    fail_msg("%s", err.text);
  watch w = { 0, 0, 0 };
  /* Long enough for 1 001 steps at the upper bound of 0.05 s. */
  mr_sim_def opts = mr_default_sim_def();
  opts.duration = 60.0;
  opts.on_step = on_step;
  opts.user = &w;
  mr_sim_result r;
  allocations = 0;
  counting = 0;
  if (mr_sim_run(&scene, &opts, &r, &err) != MR_SCENE_OK) fail_msg("%s", err.text);
  counting = 0;
  printf("%s: %llu steps, %llu watched, %lu allocations after the first step, %llu collisions\n",
         method, (unsigned long long)w.steps, (unsigned long long)w.watched, w.after_first,
         (unsigned long long)r.collisions);
  assert_true(w.watched >= WATCHED_STEPS);
  assert_true(r.collisions > 0); /* the floor was reached while watching */
  assert_int_equal(w.after_first, 0);
  mr_scene_free(&scene);
  free(text);
}

static void gauss_seidel_steps_allocate_nothing_after_the_first(void **state) {
  (void)state;
  run_method("gauss-seidel");
}

static void cg_steps_allocate_nothing_after_the_first(void **state) {
  (void)state;
  run_method("cg");
}

static void ldlt_steps_allocate_nothing_after_the_first(void **state) {
  (void)state;
  run_method("ldlt");
}

static void eigen_steps_allocate_nothing_after_the_first(void **state) {
  (void)state;
  run_method("eigen");
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(gauss_seidel_steps_allocate_nothing_after_the_first),
    cmocka_unit_test(cg_steps_allocate_nothing_after_the_first),
    cmocka_unit_test(ldlt_steps_allocate_nothing_after_the_first),
    cmocka_unit_test(eigen_steps_allocate_nothing_after_the_first),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
