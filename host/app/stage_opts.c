/* Options for what is drawn and where it goes, shared by render and run. */
#define _POSIX_C_SOURCE 200809L

#include "stage_opts.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char mr_stage_opts_help[] =
    "  -o, --output DIR    write the frames as DIR/frame_000000.png ..., an MP4\n"
    "                      (DIR/show.mp4, when ffmpeg is installed) and a contact\n"
    "                      sheet (DIR/sheet.png)\n"
    "  --every N           a PNG every N frames (default 1; the MP4 and the\n"
    "                      sheet still see every frame)\n"
    "  --mp4 FILE          the MP4 here instead (without -o: the MP4 alone);\n"
    "                      --no-mp4: none\n"
    "  --sheet FILE        the contact sheet here instead (without -o: the\n"
    "                      sheet alone); --no-sheet: none\n"
    "  --size WxH          the picture's size in pixels (default: the scene's\n"
    "                      stage.size, else 1280x720)\n"
    "  --samples N         multisampling: samples a pixel, 1 (none) to 16\n"
    "                      (default 4 on a GPU; in software 1, and the\n"
    "                      edges smoothed by a cheap post pass instead)\n"
    "  --camera NAME       look through the scene's camera NAME (camera.views)\n"
    "                      instead of the orbit camera\n"
    "  --day X             the day knob, 0..1: 0 and 1 midnight, 0.5 noon\n"
    "                      (default: the scene's stage.time_of_day)\n"
    "  --spheres           draw the collision spheres too (stage.spheres: true)\n"
    "  --gl API            the OpenGL to draw with: auto (default: desktop\n"
    "                      OpenGL 3.3 core, else OpenGL ES 3.0), core, or es3\n"
    "                      (OpenGL ES 3.0; the window or egl backend)\n";

void mr_stage_opts_init(mr_stage_opts *o) {
  memset(o, 0, sizeof *o);
  o->every = 1;
  o->day = NAN;
  o->backend = MR_RENDER_AUTO;
  o->gl = MR_RENDER_GL_AUTO;
}

static int bad(const char *cmd, const char *what, const char *v) {
  fprintf(stderr, "marionette %s: %s, got '%s' (see marionette %s --help)\n", cmd, what, v, cmd);
  return -1;
}

static int parse_size(const char *v, int *w, int *h) {
  char *end = NULL;
  errno = 0;
  long a = strtol(v, &end, 10);
  if (end == v || (*end != 'x' && *end != 'X')) return -1;
  const char *s = end + 1;
  long b = strtol(s, &end, 10);
  if (end == s || *end != '\0' || errno != 0 || a < 16 || b < 16 || a > 8192 || b > 8192) return -1;
  *w = (int)a;
  *h = (int)b;
  return 0;
}

/* The longest -o, --mp4 or --sheet path: the file names made under it
 * (DIR/frame_000000.png, DIR/show.mp4) then always fit their buffers, so
 * no path is ever cut short and used as if whole. */
#define MR_OUTPUT_PATH_MAX 400

/* An option with a value; -1 after the message on a bad one. */
static int take_value(mr_stage_opts *o, const char *cmd, const char *opt, const char *v,
                      bool allow_window) {
  char *end = NULL;
  bool is_path = strcmp(opt, "-o") == 0 || strcmp(opt, "--output") == 0 ||
                 strcmp(opt, "--mp4") == 0 || strcmp(opt, "--sheet") == 0;
  if (is_path && strlen(v) > MR_OUTPUT_PATH_MAX)
    return bad(cmd, "expected an output path of at most 400 bytes", v);
  if (strcmp(opt, "-o") == 0 || strcmp(opt, "--output") == 0) {
    o->out = v;
  } else if (strcmp(opt, "--every") == 0) {
    long n = strtol(v, &end, 10);
    if (end == v || *end != '\0' || n < 1 || n > 1000000)
      return bad(cmd, "expected --every a whole number of frames, at least 1", v);
    o->every = (int)n;
  } else if (strcmp(opt, "--mp4") == 0) {
    o->mp4 = v;
  } else if (strcmp(opt, "--sheet") == 0) {
    o->sheet = v;
  } else if (strcmp(opt, "--size") == 0) {
    if (parse_size(v, &o->width, &o->height) != 0)
      return bad(cmd, "expected --size WxH, each 16 to 8192 pixels", v);
  } else if (strcmp(opt, "--samples") == 0) {
    long n = strtol(v, &end, 10);
    if (end == v || *end != '\0' || n < 1 || n > 16)
      return bad(cmd, "expected --samples a whole number from 1 to 16", v);
    o->samples = (int)n;
  } else if (strcmp(opt, "--camera") == 0) {
    o->camera = v;
  } else if (strcmp(opt, "--day") == 0) {
    o->day = strtod(v, &end);
    if (end == v || *end != '\0' || !(o->day >= 0 && o->day <= 1))
      return bad(cmd, "expected --day a number from 0 to 1", v);
  } else if (strcmp(opt, "--gl") == 0) {
    if (mr_render_gl_parse(v, &o->gl) != 0) return bad(cmd, "expected --gl auto, core or es3", v);
  } else {
    bool ok = mr_render_backend_parse(v, &o->backend) == 0;
    if (!ok || (!allow_window && o->backend == MR_RENDER_WINDOW))
      return bad(cmd,
                 allow_window ? "expected --backend auto, window, egl or osmesa"
                              : "expected --backend auto, egl or osmesa",
                 v);
  }
  return 1;
}

int mr_stage_opts_take(mr_stage_opts *o, const char *cmd, int argc, char **argv, int *i,
                       bool allow_window) {
  static const char *const valued[] = { "-o",        "--output",  "--every",  "--mp4",
                                        "--sheet",   "--size",    "--camera", "--day",
                                        "--backend", "--samples", "--gl",     NULL };
  const char *opt = argv[*i];
  if (strcmp(opt, "--no-mp4") == 0) return o->no_mp4 = true, 1;
  if (strcmp(opt, "--no-sheet") == 0) return o->no_sheet = true, 1;
  if (strcmp(opt, "--spheres") == 0) return o->spheres = true, 1;
  for (int k = 0; valued[k] != NULL; k++) {
    if (strcmp(opt, valued[k]) != 0) continue;
    if (*i + 1 >= argc) {
      fprintf(stderr, "marionette %s: option '%s' needs a value (see marionette %s --help)\n", cmd,
              opt, cmd);
      return -1;
    }
    *i += 1;
    return take_value(o, cmd, opt, argv[*i], allow_window);
  }
  return 0;
}

bool mr_stage_opts_writes(const mr_stage_opts *o) {
  return o->out != NULL || (o->mp4 != NULL && !o->no_mp4) || (o->sheet != NULL && !o->no_sheet);
}

mr_frames_out_def mr_stage_opts_outputs(mr_stage_opts *o, double fps, int width, int height,
                                        char *note, size_t note_size) {
  mr_frames_out_def d = mr_default_frames_out_def();
  note[0] = '\0';
  d.dir = o->out;
  d.every = o->every;
  d.fps = fps;
  d.width = width;
  d.height = height;
  if (!o->no_mp4 && o->mp4 == NULL && o->out != NULL) {
    if (mr_on_path("ffmpeg")) {
      snprintf(o->mp4_buf, sizeof o->mp4_buf, "%s/show.mp4", o->out);
      o->mp4 = o->mp4_buf;
    } else {
      snprintf(note, note_size, "no MP4: ffmpeg is not installed (apt-get install ffmpeg)");
    }
  }
  if (!o->no_sheet && o->sheet == NULL && o->out != NULL) {
    snprintf(o->sheet_buf, sizeof o->sheet_buf, "%s/sheet.png", o->out);
    o->sheet = o->sheet_buf;
  }
  d.mp4 = o->no_mp4 ? NULL : o->mp4;
  d.sheet = o->no_sheet ? NULL : o->sheet;
  return d;
}

int mr_stage_opts_apply(const mr_stage_opts *o, const char *cmd, mr_stageview *sv) {
  if (!isnan(o->day)) mr_stageview_set_day(sv, o->day);
  if (o->spheres) mr_stage_show_spheres(sv->stage, true);
  if (o->camera == NULL) return 0;
  int k = mr_stageview_find_camera(sv, o->camera);
  if (k >= 0) {
    mr_stageview_pick_camera(sv, k);
    return 0;
  }
  const mr_stage_def *d = &sv->scene->stage;
  fprintf(stderr, "marionette %s: expected --camera one of the scene's cameras", cmd);
  for (int i = 0; i < d->n_cameras; i++)
    fprintf(stderr, "%s%s", i == 0 ? " (" : ", ", d->cameras[i].name);
  fprintf(stderr, "%s, got '%s'\n", d->n_cameras > 0 ? ")" : " (it has none)", o->camera);
  return -1;
}
