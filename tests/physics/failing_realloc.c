/* failing_realloc.h: glibc's own entry point does the work. */
#include "failing_realloc.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

static long left = -1; /* calls still to succeed; −1: all of them */
static int fired;

#if !defined(__SANITIZE_ADDRESS__)
void *__libc_realloc(void *p, size_t size);

void *realloc(void *p, size_t size) {
  if (left == 0) {
    left = -1;
    fired = 1;
    return NULL;
  }
  if (left > 0) left--;
  return __libc_realloc(p, size);
}

int failing_realloc_works(void) {
  return 1;
}
#else
int failing_realloc_works(void) {
  return 0;
}
#endif

void failing_realloc_after(long n) {
  left = n;
  fired = 0;
}

int failing_realloc_fired(void) {
  return fired;
}

int failing_realloc_each(mr_world *(*make)(void *user), void *user, double t) {
  mr_world *w = make(user);
  assert_int_equal(mr_world_step_to(w, t, NULL), MR_OK);
  const uint64_t whole = mr_world_state_hash(w);
  mr_world_destroy(w);
  int count = 0;
  for (long n = 0;; n++) {
    assert_true(n < 100000); /* a step of that many reallocations is a leak */
    w = make(user);
    failing_realloc_after(n);
    const mr_status st = mr_world_step_to(w, t, NULL);
    const int failed = failing_realloc_fired();
    failing_realloc_after(-1);
    if (st == MR_OK) {
      assert_true(mr_world_state_hash(w) == whole);
    } else {
      assert_true(failed);
      assert_int_equal(st, MR_ERR_NOMEM);
      assert_non_null(strstr(mr_world_last_error(w), "out of memory"));
      count++;
    }
    mr_world_destroy(w);
    if (!failed) break; /* n is past the step's last reallocation */
  }
  return count;
}
