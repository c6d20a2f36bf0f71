#include "tools_proc.h"

const char *tt_glove_gen = "glove-gen";
const char *tt_glove_dump = "glove-dump";

void tt_take_args(int argc, char **argv) {
  if (argc > 1) tt_glove_gen = argv[1];
  if (argc > 2) tt_glove_dump = argv[2];
}
