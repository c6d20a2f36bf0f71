/* tt_alloc_*: see alloc.h. */
#include "alloc.h"

#include <errno.h>
#include <stddef.h>

static int counting;
static long allocations;
static long fail_at;

void tt_alloc_count(long fail) {
  allocations = 0;
  fail_at = fail;
  counting = 1;
}

long tt_alloc_stop(void) {
  counting = 0;
  fail_at = 0;
  return allocations;
}

long tt_allocations(void) {
  return allocations;
}

int tt_alloc_refused(void) {
  return counting && ++allocations == fail_at;
}

#define COUNTED(ret, name, params, args) \
  ret __real_##name params;              \
  ret __wrap_##name params;              \
  ret __wrap_##name params {             \
    if (tt_alloc_refused()) return NULL; \
    return __real_##name args;           \
  }
COUNTED(void *, malloc, (size_t n), (n))
COUNTED(void *, calloc, (size_t n, size_t size), (n, size))
COUNTED(void *, realloc, (void *p, size_t n), (p, n))
COUNTED(void *, aligned_alloc, (size_t align, size_t n), (align, n))

int __real_posix_memalign(void **p, size_t align, size_t n);
int __wrap_posix_memalign(void **p, size_t align, size_t n);
int __wrap_posix_memalign(void **p, size_t align, size_t n) {
  if (tt_alloc_refused()) return ENOMEM;
  return __real_posix_memalign(p, align, n);
}
