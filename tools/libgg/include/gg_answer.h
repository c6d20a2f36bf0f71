/* A synthetic glove's answers to the host's commands (protocol/SPEC.md, 6),
 * as the firmware gives them: ACK or NACK with the command's tag, then the
 * INFO or STATUS a command asks for, and the change it makes to the
 * stream (streaming, calibration). A tester can have the first K commands
 * ignored, to see the host retry. */
#ifndef GG_ANSWER_H
#define GG_ANSWER_H

#include <stddef.h>
#include <stdint.h>

#include "gg_stream.h"
#include "gp.h"

typedef struct gg_answer {
  gp_decoder dec;       /* the host's frames */
  unsigned ignore_left; /* commands still to let pass unanswered */
  int capturing;        /* CAL_START seen: channel extremes are gathered */
  uint16_t seen_min[GG_CHANNELS], seen_max[GG_CHANNELS];
  uint64_t commands, acks, nacks, ignored;
  uint64_t frames_sent; /* for STATUS */
} gg_answer;

void gg_answer_init(gg_answer *a, unsigned ignore_first);

/* Widens a calibration capture by the SAMPLE just made (call after each
 * slot). */
void gg_answer_observe(gg_answer *a, const gg_stream *s);

/* Feeds bytes from the host. Each whole command is carried out on s and
 * answered into out (cap bytes; at least 4 GP_MAX_WIRE a command is
 * enough); returns how many reply bytes were written. */
size_t gg_answer_feed(gg_answer *a, gg_stream *s, const uint8_t *in, size_t n, uint8_t *out,
                      size_t cap);

#endif
