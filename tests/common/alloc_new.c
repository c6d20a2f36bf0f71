/* operator new and new[] through the counter of alloc.c, for the tests
 * whose libraries hold C++ (mr_test_wrap_alloc(TARGET CXX)). */
#include <stddef.h>

int tt_alloc_refused(void);

void *__real__Znwm(size_t n);
void *__wrap__Znwm(size_t n);
void *__wrap__Znwm(size_t n) { /* operator new */
  return tt_alloc_refused() ? NULL : __real__Znwm(n);
}

void *__real__Znam(size_t n);
void *__wrap__Znam(size_t n);
void *__wrap__Znam(size_t n) { /* operator new[] */
  return tt_alloc_refused() ? NULL : __real__Znam(n);
}
