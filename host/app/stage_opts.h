/* The command-line options `marionette render` and `marionette run` share
 * for what is drawn and where it goes. */
#ifndef MR_STAGE_OPTS_H
#define MR_STAGE_OPTS_H

#include <stdbool.h>

#include "frames_out.h"
#include "mr_render.h"
#include "stage_view.h"

typedef struct mr_stage_opts {
  const char *out; /* -o DIR */
  int every;       /* --every N, default 1 */
  const char *mp4, *sheet;
  bool no_mp4, no_sheet;
  int width, height; /* --size WxH; 0: the scene's */
  int samples;       /* --samples N; 0: the renderer's default */
  const char *camera;
  double day;   /* --day, NaN: the scene's */
  bool spheres; /* --spheres: the collision spheres drawn too */
  mr_render_backend backend;
  mr_render_gl gl; /* --gl auto|core|es3, default auto */
  char mp4_buf[600], sheet_buf[600];
} mr_stage_opts;

void mr_stage_opts_init(mr_stage_opts *o);

/* argv[*i] if it is one of these options, with its value (*i moves past
 * it): 1 taken, 0 not one of these, -1 a bad value (one line printed,
 * naming cmd). allow_window: --backend may name window. */
int mr_stage_opts_take(mr_stage_opts *o, const char *cmd, int argc, char **argv, int *i,
                       bool allow_window);

/* Whether the options ask for files: -o DIR, or --mp4 or --sheet FILE
 * alone (that file only), not turned off by --no-mp4 or --no-sheet. */
bool mr_stage_opts_writes(const mr_stage_opts *o);

/* The outputs under -o DIR: frames, DIR/show.mp4 when ffmpeg is on PATH
 * (else a note in note, empty otherwise), DIR/sheet.png; without -o, only
 * the --mp4 and --sheet files named. */
mr_frames_out_def mr_stage_opts_outputs(mr_stage_opts *o, double fps, int width, int height,
                                        char *note, size_t note_size);

/* --camera and --day onto an open view; -1 (after one line naming cmd and
 * the scene's cameras) for a camera the scene has not. */
int mr_stage_opts_apply(const mr_stage_opts *o, const char *cmd, mr_stageview *sv);

/* The OPTIONS lines of both commands' --help for these options. */
extern const char mr_stage_opts_help[];

#endif
