/* glove-gen's command line: the options it takes and what they asked for. */
#ifndef GLOVE_GEN_OPTIONS_H
#define GLOVE_GEN_OPTIONS_H

#include <stdint.h>

#include "gg_stream.h"

#define MAX_GLOVES 16

/* What the command line asked for. */
typedef struct options {
  const char *specs[MAX_GLOVES], *truths[MAX_GLOVES], *records[MAX_GLOVES];
  unsigned hands[MAX_GLOVES];
  int n_out, n_truth, n_rec, n_hand;
  const char *script, *path_file;
  double rate, duration, wait_s, linger_s, all_faults;
  double rates[GG_F_COUNT];
  uint64_t count, seed, uid0, baud, spec_hash, ignore_cmds;
  uint32_t stall_min, stall_max;
  int have_count, fast, progress, quiet, have_uid;
} options;

/* The defaults, before the command line. */
void options_init(options *o);

/* The command line into o, checked as a whole: -1 to go on, else the exit
 * code (0 after --help or --version, 2 for bad usage, with one line on
 * stderr). */
int parse_args(options *o, int argc, char **argv);

#endif
