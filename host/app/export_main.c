/* marionette-export: `marionette export`, in a program of its own. It
 * loads the scene's models through the renderer's loader (Assimp) but
 * starts no GL, so it links neither GL nor SDL; `marionette` itself,
 * which must start quickly for `sim`, links no Assimp. `marionette`
 * replaces itself with this program for export (stage_exec.c). */
#include <stdio.h>
#include <string.h>

#include "app.h"

int main(int argc, char **argv) {
  if (argc >= 2 && strcmp(argv[1], "--version") == 0) {
    printf("marionette-export %s\n", MR_VERSION);
    return MR_EXIT_OK;
  }
  if (argc >= 2 && strcmp(argv[1], "export") == 0) return mr_cmd_export(argc - 1, argv + 1);
  fprintf(stderr, "marionette-export: started by `marionette export`; use that (see "
                  "marionette --help)\n");
  return MR_EXIT_USAGE;
}
