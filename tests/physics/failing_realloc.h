/* A realloc that fails on demand, for the tests of what a step does when
 * memory runs out. The world's arrays grow through realloc (mr_grow); a
 * test binary linking failing_realloc.c gets a realloc that, once told to,
 * lets n more calls succeed and fails the next. AddressSanitizer owns
 * realloc in that build, so there the tests that need it are skipped. */
#ifndef MR_TEST_FAILING_REALLOC_H
#define MR_TEST_FAILING_REALLOC_H

#include "mr_physics.h"

/* Whether this build fails on demand (not under AddressSanitizer). */
int failing_realloc_works(void);
/* The next call after n more fails; −1: none fails. Clears the record of
 * a failure. */
void failing_realloc_after(long n);
/* Whether a call failed since the last failing_realloc_after. */
int failing_realloc_fired(void);

/* Whichever of a step's reallocations fails, the step says so, or it
 * did without: for each n, a world from make(user) is stepped to t with
 * the call after n more failing, until a step takes no n-th call. The
 * step must return MR_ERR_NOMEM with a message naming memory, or MR_OK
 * with the state of the step that had all its memory, to the bit (a memo
 * it could not keep costs time, not the answer). cmocka assertions.
 * Returns how many steps failed. */
int failing_realloc_each(mr_world *(*make)(void *user), void *user, double t);

#endif
