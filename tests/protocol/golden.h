/* Reads protocol/vectors/golden.txt (format: SPEC.md, "Golden vectors"). */
#ifndef GOLDEN_H
#define GOLDEN_H

#include <stddef.h>
#include <stdint.h>

#include "gp.h"

typedef struct golden_vec {
  char name[64];
  uint32_t hash; /* the spec hash the frame was encoded with */
  uint8_t wire[2 * GP_MAX_WIRE];
  size_t wire_len;
  gp_msg msg; /* the decoded meaning */
} golden_vec;

/* Loads up to cap vectors. Returns the count, or -1 with a message naming
 * file:line in err. */
int golden_load(const char *path, golden_vec *out, int cap, char *err, size_t errlen);

#endif
