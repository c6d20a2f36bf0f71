/* marionette-stage: the commands of `marionette` that draw, `run`,
 * `render` and `watch`, in a program of their own that links the renderer. `marionette`
 * replaces itself with this program for those commands (stage_exec.c), so
 * it is started with marionette's own arguments, argv[1] the command. */
#include <stdio.h>
#include <string.h>

#include "app.h"

int main(int argc, char **argv) {
  if (argc >= 2 && strcmp(argv[1], "--version") == 0) {
    printf("marionette-stage %s\n", MR_VERSION);
    return MR_EXIT_OK;
  }
  if (argc >= 2 && strcmp(argv[1], "run") == 0) return mr_cmd_run(argc - 1, argv + 1);
  if (argc >= 2 && strcmp(argv[1], "render") == 0) return mr_cmd_render(argc - 1, argv + 1);
  if (argc >= 2 && strcmp(argv[1], "watch") == 0) return mr_cmd_watch(argc - 1, argv + 1);
  fprintf(stderr, "marionette-stage: started by `marionette run`, `marionette render` and "
                  "`marionette watch`; "
                  "use those (see marionette --help)\n");
  return MR_EXIT_USAGE;
}
