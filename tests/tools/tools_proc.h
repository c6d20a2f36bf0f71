/* What the tools tests add to the shared test helpers (tests/common):
 * the paths of the programs under test, and an mr_io check that fails with
 * the library's own message. */
#ifndef TOOLS_PROC_H
#define TOOLS_PROC_H

#include "proc.h"

/* The paths of the tools, from the test's command line. */
extern const char *tt_glove_gen;
extern const char *tt_glove_dump;
void tt_take_args(int argc, char **argv);

/* An mr_io call that must succeed; on failure the test stops with the
 * call and the mr_io_error message ("pty: posix_openpt: No such file or
 * directory"), not with a bare "-1 != 0". Needs cmocka. */
#define tt_assert_io_ok(call, err)                                \
  do {                                                            \
    if ((call) != 0) fail_msg("%s failed: %s", #call, (err).msg); \
  } while (0)

#endif
