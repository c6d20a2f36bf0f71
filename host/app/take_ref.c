#include "take_ref.h"

#include <stdio.h>

#include "mr_take.h"

int mr_app_take_paths(const char *prog, const char *arg, const char **out, size_t cap) {
  /* Every path a program resolves, for its whole run: at most 8 takes of
   * at most 8 gloves each. */
  static char pool[MR_TAKE_MAX_GLOVES * MR_TAKE_MAX_GLOVES][MR_TAKE_PATH_MAX];
  static size_t used;
  size_t n = 0;
  mr_take_error err;
  size_t room = sizeof pool / sizeof pool[0] - used;
  int rc = mr_take_resolve(arg, pool + used, room < cap ? room : cap, &n, &err);
  if (rc < 0) {
    fprintf(stderr, "%s: take %s: %s\n", prog, arg, err.msg);
    return -1;
  }
  if (rc == 0) {
    if (cap == 0) return 0;
    out[0] = arg;
    return 1;
  }
  for (size_t k = 0; k < n; k++) out[k] = pool[used + k];
  used += n;
  return (int)n;
}
