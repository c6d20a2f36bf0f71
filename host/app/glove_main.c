/* marionette-glove: the commands of `marionette` that open a glove,
 * `list-ports` and `calibrate`, in a program of their own. A glove source
 * may be a broker (mqtt://, mqtts://), so the glove library links the MQTT
 * client and, through it, TLS; the dynamic loader's work on those costs
 * more than twice what `marionette sim` pays to start without them (6.9 M
 * instructions against 2.0 M). `marionette` replaces itself with this
 * program for those commands (stage_exec.c), argv[1] the command. */
#include <stdio.h>
#include <string.h>

#include "app.h"

int main(int argc, char **argv) {
  if (argc >= 2 && strcmp(argv[1], "--version") == 0) {
    printf("marionette-glove %s\n", MR_VERSION);
    return MR_EXIT_OK;
  }
  if (argc >= 2 && strcmp(argv[1], "list-ports") == 0) return mr_cmd_ports(argc - 1, argv + 1);
  if (argc >= 2 && strcmp(argv[1], "calibrate") == 0) return mr_cmd_calibrate(argc - 1, argv + 1);
  fprintf(stderr, "marionette-glove: started by `marionette list-ports` and `marionette "
                  "calibrate`; use those (see marionette --help)\n");
  return MR_EXIT_USAGE;
}
