/* Subcommands of the `marionette` program. Each takes the arguments after
 * its name and returns the process exit status. sim, list-ports and
 * calibrate are in `marionette`; run and render, which draw, in the stage
 * program `marionette-stage`; export, which loads models but draws
 * nothing, in `marionette-export`. */
#ifndef MR_APP_H
#define MR_APP_H

/* Exit statuses shared by every subcommand. */
enum {
  MR_EXIT_OK = 0,
  MR_EXIT_FAIL = 1,    /* the scene failed to load, to run, or its check */
  MR_EXIT_USAGE = 2,   /* bad command line */
  MR_EXIT_MISMATCH = 3 /* a glove built from another protocol definition */
};

int mr_cmd_sim(int argc, char **argv);
void mr_cmd_sim_usage(void);
int mr_cmd_run(int argc, char **argv);
void mr_cmd_run_usage(void);
int mr_cmd_ports(int argc, char **argv);
void mr_cmd_ports_usage(void);
int mr_cmd_calibrate(int argc, char **argv);
void mr_cmd_calibrate_usage(void);
int mr_cmd_render(int argc, char **argv);
/* `marionette watch URL`: a remote audience of a published show
 * (cmd_watch.c), in the stage program. */
int mr_cmd_watch(int argc, char **argv);
void mr_cmd_watch_usage(void);
void mr_cmd_render_usage(void);
int mr_cmd_export(int argc, char **argv);
int mr_cmd_take(int argc, char **argv);
void mr_cmd_take_usage(void);
void mr_cmd_export_usage(void);

/* In `marionette`: replaces the process with the program of that file
 * name (the stage program for "run" and "render", the export program for
 * "export"), given marionette's whole argv. Returns only on failure,
 * after one line on stderr: MR_EXIT_FAIL. */
int mr_stage_exec(const char *program, char **argv);

#endif
