/* Allocations counted, and one of them made to fail, in a test linked
 * with mr_test_wrap_alloc() (tests/CMakeLists.txt): the linker's --wrap
 * sends every call to malloc, calloc, realloc, aligned_alloc and
 * posix_memalign (and, with CXX, operator new and new[]) from the test
 * and the libraries linked into it through a counter first. Calls made inside
 * shared libraries (libc's own, a YAML parser's) are not seen. It works
 * under the sanitizers too. */
#ifndef MR_TEST_ALLOC_H
#define MR_TEST_ALLOC_H

/* Counts from 0 from here on; the fail_at-th allocation (from 1) returns
 * NULL (posix_memalign ENOMEM), and only it; 0: none fails. */
void tt_alloc_count(long fail_at);

/* Stops counting and failing. Returns the allocations counted. */
long tt_alloc_stop(void);

/* The allocations counted so far. */
long tt_allocations(void);

/* Counts one allocation: whether it is the one to fail (the wrappers'). */
int tt_alloc_refused(void);

#endif
