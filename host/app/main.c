/* marionette: the theater's program. `sim` runs a scene headless; `run`
 * is the theater, a glove driving the puppet in real time; `render` draws
 * a scene's track or a take into pictures. The commands that draw live in
 * the stage program, export in the export program and the glove's own
 * commands in the glove program, which this one becomes for them
 * (stage_exec.c): this one starts with none of their libraries. */
#include <stdio.h>
#include <string.h>

#include "app.h"

static void usage(FILE *f) {
  fprintf(f, "usage: marionette COMMAND [ARGS]\n"
             "\n"
             "A real-time virtual marionette theater.\n"
             "\n"
             "commands:\n"
             "  sim SCENE   run a scene without rendering, as fast as possible, and\n"
             "              print a summary (steps, time steps, deviations, resets,\n"
             "              pass counters, state hash); see `marionette sim --help`\n"
             "  run SCENE [--glove SOURCE]\n"
             "              the theater: a glove (or, in a window, the keyboard,\n"
             "              mouse or a gamepad) drives the puppet in real time, on\n"
             "              the stage; see `marionette run --help`\n"
             "  render SCENE\n"
             "              draw the scene's track, or a take, headless into PNG\n"
             "              frames, an MP4 and a contact sheet; see\n"
             "              `marionette render --help`\n"
             "  watch URL   a remote audience: draws the show that `marionette run\n"
             "              --publish URL` sends through an MQTT broker; see\n"
             "              `marionette watch --help`\n"
             "  export [TAKE...] --scene SCENE -o OUT.glb\n"
             "              the show as a glTF 2.0 binary with its animation\n"
             "              (and a PC2 point cache, a CSV); see\n"
             "              `marionette export --help`\n"
             "  take SUBCOMMAND BOOK\n"
             "              the take list: add, punch, split, trim, delete,\n"
             "              restore, rename, smooth, offset, scale, show; see\n"
             "              `marionette take --help`\n"
             "  list-ports  the serial ports, and the gloves on them\n"
             "  calibrate --glove SOURCE\n"
             "              walk through a glove's calibration and save it on\n"
             "              the glove; see `marionette calibrate --help`\n"
             "\n"
             "options:\n"
             "  -h, --help  show this help\n"
             "  --version   print the version and exit\n");
}

int main(int argc, char **argv) {
  if (argc < 2) {
    /* Bad usage is one line, like every other usage error; --help has the rest. */
    fprintf(stderr,
            "marionette: expected a command: sim, run, render, watch, export, take, list-ports or "
            "calibrate (see "
            "marionette --help)\n");
    return MR_EXIT_USAGE;
  }
  const char *cmd = argv[1];
  if (strcmp(cmd, "-h") == 0 || strcmp(cmd, "--help") == 0 || strcmp(cmd, "help") == 0) {
    usage(stdout);
    return MR_EXIT_OK;
  }
  if (strcmp(cmd, "--version") == 0) {
    printf("marionette %s\n", MR_VERSION);
    return MR_EXIT_OK;
  }
  if (strcmp(cmd, "sim") == 0) return mr_cmd_sim(argc - 1, argv + 1);
  /* The drawing commands run in the stage program (stage_exec.c). */
  if (strcmp(cmd, "run") == 0 || strcmp(cmd, "render") == 0 || strcmp(cmd, "watch") == 0)
    return mr_stage_exec(MR_STAGE_PROGRAM, argv);
  /* export loads models (Assimp) but no GL: a program of its own. */
  if (strcmp(cmd, "export") == 0) return mr_stage_exec(MR_EXPORT_PROGRAM, argv);
  if (strcmp(cmd, "take") == 0) return mr_cmd_take(argc - 1, argv + 1);
  /* A glove may be a broker's: the glove program links the MQTT client. */
  if (strcmp(cmd, "list-ports") == 0 || strcmp(cmd, "calibrate") == 0)
    return mr_stage_exec(MR_GLOVE_PROGRAM, argv);
  fprintf(
      stderr,
      "marionette: unknown command '%s'; expected one of: sim, run, render, watch, export, take, "
      "list-ports, "
      "calibrate (see --help)\n",
      cmd);
  return MR_EXIT_USAGE;
}
