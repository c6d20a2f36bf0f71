/* Where drawn frames go when no one watches them live: PNG files, an MP4
 * through an ffmpeg pipe and a contact sheet (`marionette render`, and
 * `marionette run --headless`). Pictures are 8-bit RGB, top row first, as
 * mr_render_read_rgb gives them. */
#ifndef MR_FRAMES_OUT_H
#define MR_FRAMES_OUT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mr_def.h"

typedef struct mr_frames_out_def {
  uint32_t cookie;   /* MR_DEF_COOKIE, set by mr_default_frames_out_def() */
  const char *dir;   /* PNG frames dir/frame_000000.png ...; NULL: none */
  int every;         /* a PNG every this many frames, default 1 */
  const char *mp4;   /* NULL: none */
  double fps;        /* the MP4's rate */
  const char *sheet; /* the contact sheet's PNG; NULL: none */
  int sheet_cells;   /* thumbnails at most, default 24 */
  int width, height; /* every frame's size */
  /* The MP4 keeps show time: a frame handed in at show time t is frame
   * round(t fps) of the video, the frame before it repeated over the
   * frames not handed in (renders skipped under load), so the video
   * lasts as long as the show. Else every frame handed in is the next. */
  bool keep_time;
} mr_frames_out_def;
mr_frames_out_def mr_default_frames_out_def(void);

/* What was written, for the summary. */
typedef struct mr_frames_out_summary {
  uint64_t frames;  /* frames handed in */
  uint64_t pngs;    /* PNG files written */
  uint64_t encoded; /* frames piped to ffmpeg, repeats included */
  int sheet_cells;  /* thumbnails on the sheet */
  bool mp4_ok;      /* ffmpeg ran and ended well */
} mr_frames_out_summary;

typedef struct mr_frames_out mr_frames_out;

/* Makes dir if need be and starts ffmpeg. -1 with msg on failure. */
int mr_frames_out_open(const mr_frames_out_def *def, mr_frames_out **out, char *msg,
                       size_t msg_size);
/* One frame at show time t. -1 with msg when a file cannot be written. */
int mr_frames_out_add(mr_frames_out *fo, const uint8_t *rgb, double t, char *msg, size_t msg_size);
/* With keep_time: the video holds the last frame up to show time t (the
 * show's end), as if frames came until then. -1 with msg when ffmpeg's
 * pipe broke. */
int mr_frames_out_hold(mr_frames_out *fo, double t, char *msg, size_t msg_size);
/* Writes the sheet, waits for ffmpeg and frees fo (NULL is fine). -1 with
 * msg when something was not written; the summary is filled either way. */
int mr_frames_out_close(mr_frames_out *fo, mr_frames_out_summary *sum, char *msg, size_t msg_size);

/* One PNG; 0 or -1. */
int mr_png_write(const char *path, const uint8_t *rgb, int width, int height);

/* A folder and its parents, as mkdir -p; 0 or -1 (errno set). */
int mr_make_dir(const char *dir);

/* Whether an executable of this name is on PATH. */
bool mr_on_path(const char *program);

#endif
