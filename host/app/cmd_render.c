/* `marionette render SCENE`: a scene's scripted track, or a take, drawn
 * headless into PNG frames, an MP4 and a contact sheet (issue 10, item
 * 6). Frames are paced by the theater's scheduler on a virtual clock, so
 * the pictures of a run are the same on any machine and at any load. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "app.h"
#include "frames_out.h"
#include "mr_scene.h"
#include "mr_show.h"
#include "mr_sim.h"
#include "stage_opts.h"
#include "take_ref.h"
#include "stage_view.h"

void mr_cmd_render_usage(void) {
  printf("usage: marionette render [OPTIONS] SCENE\n"
         "\n"
         "Draws the scene file SCENE headless (EGL, else OSMesa) as its control\n"
         "frames follow the scene's track, or as a take recorded by marionette run\n"
         "--record plays (--take), and writes PNG frames, an MP4 through ffmpeg\n"
         "(when it is installed) and a contact sheet. Frames come at the scene's\n"
         "sim.fps (or --fps; default 30) on a virtual clock: the same scene and\n"
         "options give the same pictures, byte for byte.\n"
         "\n"
         "options:\n"
         "%s"
         "  --frame T           one picture, of the first frame at or after T\n"
         "                      seconds: -o FILE.png, or DIR/frame_T.png\n"
         "  -t, --time SECONDS  how much show (default: the scene's sim.duration,\n"
         "                      10 s when it gives none; with --take, the take)\n"
         "  --fps HZ            frames per second (default: the scene's, else 30;\n"
         "                      with --take, else 60, as the show it recorded)\n"
         "  --take TAKE         play a take (.mrec) instead of the scene's track;\n"
         "                      repeat for the takes of several gloves; BOOK:NAME\n"
         "                      is every glove of take NAME in the take list BOOK\n"
         "  --backend B         auto (default), egl or osmesa\n"
         "  -q, --quiet         no progress, only the summary and errors\n"
         "  -h, --help          show this help\n"
         "\n"
         "Without -o the frames go to SCENE-render/ (SCENE's name without .yaml).\n"
         "Progress goes to stderr: one line updated in place on a terminal, a line\n"
         "every 10 %% otherwise. A summary ends the run.\n"
         "\n"
         "exit status: 0 success, 1 the scene, a model or an output failed (one\n"
         "line naming FILE:LINE:COLUMN, and the model's file), 2 bad usage.\n",
         mr_stage_opts_help);
}

enum { MAX_TAKES = MR_SHOW_MAX_GLOVES };

typedef struct render_args {
  const char *scene;
  mr_stage_opts so;
  double fps, duration, frame_t;
  bool has_frame;
  const char *takes[MAX_TAKES];
  size_t n_takes;
  int quiet, help;
  char out_buf[600];
} render_args;

/* One render as it goes. */
typedef struct job {
  render_args *a;
  mr_stageview sv;
  mr_frames_out *fo;
  double fps;
  uint64_t drawn, total; /* total 0: not known ahead */
  int last_tenth;
  bool tty, done, failed;
  double wall0, draw_wall, last_t;
  double end; /* the show's end, for the curtain; -1: a take's, not known ahead */
  char msg[700];
  char frame_path[600];
  uint64_t hash;
} job;

static double wall_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* One line: what was expected, and what came ('%s' quoted). */
static int usage_error(const char *what, const char *v) {
  fprintf(stderr, "marionette render: %s%s%s%s (see marionette render --help)\n", what,
          v != NULL ? " '" : "", v != NULL ? v : "", v != NULL ? "'" : "");
  return MR_EXIT_USAGE;
}

static int parse_number(const char *v, double lo, double hi, double *out) {
  char *end = NULL;
  errno = 0;
  double x = strtod(v, &end);
  if (end == v || *end != '\0' || errno != 0 || !(x >= lo && x <= hi)) return -1;
  *out = x;
  return 0;
}

/* An option of render's own with its value; the exit status on a bad one,
 * -1 when good. */
static int own_option(render_args *a, const char *o, const char *v) {
  if (strcmp(o, "--frame") == 0) {
    a->has_frame = true;
    if (parse_number(v, 0, 1e6, &a->frame_t) != 0)
      return usage_error("expected --frame a time in seconds, 0 or more, got", v);
  } else if (strcmp(o, "-t") == 0 || strcmp(o, "--time") == 0) {
    if (parse_number(v, 1e-6, 1e6, &a->duration) != 0)
      return usage_error("expected --time a positive number of seconds, got", v);
  } else if (strcmp(o, "--fps") == 0) {
    if (parse_number(v, 1, 1000, &a->fps) != 0)
      return usage_error("expected --fps a frame rate from 1 to 1000 Hz, got", v);
  } else {
    const char *paths[MAX_TAKES]; /* a .mrec, or a book's take: its files */
    int n = mr_app_take_paths("marionette render", v, paths, MAX_TAKES);
    if (n < 0) return MR_EXIT_USAGE;
    for (int k = 0; k < n; k++) {
      if (a->n_takes == MAX_TAKES) return usage_error("expected at most 8 takes, got another:", v);
      a->takes[a->n_takes++] = paths[k];
    }
  }
  return -1;
}

/* -1 when the arguments are good, else the exit status. */
static int parse(int argc, char **argv, render_args *a) {
  static const char *const valued[] = { "--frame", "-t", "--time", "--fps", "--take", NULL };
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    int taken = mr_stage_opts_take(&a->so, "render", argc, argv, &i, false);
    if (taken < 0) return MR_EXIT_USAGE;
    if (taken > 0) continue;
    bool has_value = false;
    for (int k = 0; valued[k] != NULL; k++) has_value |= strcmp(o, valued[k]) == 0;
    if (strcmp(o, "-h") == 0 || strcmp(o, "--help") == 0) {
      a->help = 1;
    } else if (strcmp(o, "-q") == 0 || strcmp(o, "--quiet") == 0) {
      a->quiet = 1;
    } else if (has_value) {
      if (i + 1 >= argc) return usage_error("expected a value after", o);
      int rc = own_option(a, o, argv[++i]);
      if (rc >= 0) return rc;
    } else if (o[0] == '-' && o[1] != '\0') {
      return usage_error("unknown option", o);
    } else if (a->scene == NULL) {
      a->scene = o;
    } else {
      return usage_error("expected one scene file, got a second:", o);
    }
  }
  if (a->help) return -1;
  if (a->scene == NULL) return usage_error("expected a scene file", NULL);
  return -1;
}

/* Without -o: SCENE-render/ beside where the command runs. */
static void default_output(render_args *a) {
  if (a->so.out != NULL) return;
  const char *base = strrchr(a->scene, '/');
  base = base != NULL ? base + 1 : a->scene;
  size_t n = strcspn(base, ".");
  snprintf(a->out_buf, sizeof a->out_buf, "%.*s-render", (int)(n > 0 ? n : strlen(base)), base);
  a->so.out = a->out_buf;
}

static void progress(job *j, double t) {
  if (j->a->quiet) return;
  if (j->tty) {
    if (j->total > 0)
      fprintf(stderr, "\rrender: frame %" PRIu64 " of %" PRIu64 " (%d %%), t %.2f s   ", j->drawn,
              j->total, (int)(100 * j->drawn / j->total), t);
    else
      fprintf(stderr, "\rrender: frame %" PRIu64 ", t %.2f s   ", j->drawn, t);
    return;
  }
  int tenth = j->total > 0 ? (int)(10 * j->drawn / j->total) : (int)(t / 10.0);
  if (tenth == j->last_tenth) return;
  j->last_tenth = tenth;
  if (j->total > 0)
    fprintf(stderr, "render: %d %% (%" PRIu64 " of %" PRIu64 " frames)\n", 10 * tenth, j->drawn,
            j->total);
  else
    fprintf(stderr, "render: %" PRIu64 " frames, t %.0f s\n", j->drawn, t);
}

/* --frame: the first frame at or after T, once. */
static void one_picture(job *j, double t, const double *xyz, size_t n) {
  if (j->done || t < j->a->frame_t - 1e-9) return;
  j->done = true;
  j->last_t = t;
  const uint8_t *rgb = NULL;
  if (mr_stageview_draw(&j->sv, xyz, n, j->msg, sizeof j->msg) == 0)
    rgb = mr_stageview_read(&j->sv);
  if (rgb == NULL) {
    if (j->msg[0] == '\0') snprintf(j->msg, sizeof j->msg, "could not read the frame back");
    j->failed = true;
    return;
  }
  j->drawn = 1;
  if (mr_png_write(j->frame_path, rgb, j->sv.width, j->sv.height) != 0) {
    snprintf(j->msg, sizeof j->msg, "cannot write %s", j->frame_path);
    j->failed = true;
  }
}

static void frame(job *j, double t, const double *xyz, size_t n) {
  if (j->failed) return;
  mr_stageview_track(&j->sv, t, xyz, n);
  mr_stageview_set_time(&j->sv, t, j->end);
  if (j->a->has_frame) {
    one_picture(j, t, xyz, n);
    return;
  }
  double w0 = wall_now();
  const uint8_t *rgb = NULL;
  if (mr_stageview_draw(&j->sv, xyz, n, j->msg, sizeof j->msg) == 0)
    rgb = mr_stageview_read(&j->sv);
  if (rgb == NULL || mr_frames_out_add(j->fo, rgb, t, j->msg, sizeof j->msg) != 0) {
    if (j->msg[0] == '\0') snprintf(j->msg, sizeof j->msg, "could not read the frame back");
    j->failed = true;
    return;
  }
  j->draw_wall += wall_now() - w0;
  j->drawn++;
  j->last_t = t;
  progress(j, t);
}

static void on_sim_frame(void *user, double t, const double *xyz, int n) {
  frame(user, t, xyz, (size_t)n);
}

static void on_show_frame(void *user, const mr_show_frame *f) {
  job *j = user;
  j->hash = f->hash;
  frame(j, f->t, f->xyz, (size_t)f->n_particles);
}

static int stop_after_picture(void *user) {
  const job *j = user;
  return j->failed || (j->a->has_frame && j->done);
}

/* The track, or the takes, run with frame() on every frame. 0, or -1
 * with the error's text in text. */
static int run_frames(job *j, const mr_scene *scene, char *text, size_t text_size) {
  const render_args *a = j->a;
  if (a->n_takes == 0) {
    mr_sim_def o = mr_default_sim_def();
    o.fps = j->fps;
    o.duration = a->has_frame ? a->frame_t + 1.5 / j->fps : a->duration;
    o.on_frame = on_sim_frame;
    o.user = j;
    mr_sim_result r;
    mr_scene_error err;
    mr_scene_status st = mr_sim_run(scene, &o, &r, &err);
    j->hash = r.hash;
    if (st != MR_SCENE_OK) snprintf(text, text_size, "%s", err.text);
    return st == MR_SCENE_OK ? 0 : -1;
  }
  mr_show_def d = mr_default_show_def();
  char sources[MAX_TAKES][MR_GLOVE_SOURCE_MAX];
  for (size_t i = 0; i < a->n_takes; i++) {
    snprintf(sources[i], sizeof sources[i], "file:%s", a->takes[i]);
    d.gloves[i] = sources[i];
  }
  d.n_gloves = a->n_takes;
  d.fps = j->fps;
  d.duration = a->has_frame ? a->frame_t + 1.5 / j->fps : a->duration;
  mr_virtual_clock vc = { 0.0 };
  mr_clock clock = mr_clock_virtual(&vc);
  mr_show_hooks h = { NULL, stop_after_picture, on_show_frame, NULL, j };
  mr_show_result r;
  mr_show_error err;
  mr_show_status st = mr_show_run(scene, &d, &clock, &h, &r, &err);
  mr_show_result_free(&r);
  if (st != MR_SHOW_OK) snprintf(text, text_size, "%s", err.text);
  return st == MR_SHOW_OK ? 0 : -1;
}

/* Where --frame's picture goes: -o FILE.png, else DIR/frame_T.png. */
static int frame_target(job *j) {
  const char *out = j->a->so.out;
  size_t n = strlen(out);
  if (n > 4 && strcmp(out + n - 4, ".png") == 0) {
    snprintf(j->frame_path, sizeof j->frame_path, "%s", out);
    return 0;
  }
  mr_frames_out_def d = mr_default_frames_out_def();
  d.dir = out;
  d.width = d.height = 16;
  mr_frames_out *fo = NULL; /* makes the folder */
  if (mr_frames_out_open(&d, &fo, j->msg, sizeof j->msg) != 0) return -1;
  mr_frames_out_summary s;
  mr_frames_out_close(fo, &s, j->msg, sizeof j->msg);
  snprintf(j->frame_path, sizeof j->frame_path, "%s/frame_%.3f.png", out, j->a->frame_t);
  return 0;
}

static void summary(const job *j, const mr_scene *scene, const mr_frames_out_summary *s,
                    const char *note, double wall) {
  const render_args *a = j->a;
  printf("scene: %s (%s)\n", scene->name, scene->path);
  printf("backend: %s (%s)\n", mr_render_backend_name(mr_render_backend_of(j->sv.render)),
         mr_render_gl_description(j->sv.render));
  printf("size: %dx%d\n", j->sv.width, j->sv.height);
  printf("quality: %s\n", mr_render_quality(j->sv.render));
  if (a->has_frame) {
    printf("frame: t %.3f s\n", j->last_t);
    printf("picture: %s\n", j->frame_path);
  } else {
    printf("frames: %" PRIu64 " at %g fps (%.3f s)\n", j->drawn, j->fps, j->last_t);
    printf("png frames: %" PRIu64 " in %s\n", s->pngs, a->so.out);
    if (a->so.mp4 != NULL && !a->so.no_mp4)
      printf("mp4: %s (%" PRIu64 " frames)\n", a->so.mp4, s->encoded);
    else if (note[0] != '\0')
      printf("mp4: none (%s)\n", note + 8);
    if (a->so.sheet != NULL && !a->so.no_sheet)
      printf("sheet: %s (%d thumbnails)\n", a->so.sheet, s->sheet_cells);
    if (j->drawn > 0) printf("draw: %.1f ms a frame\n", 1e3 * j->draw_wall / (double)j->drawn);
  }
  printf("wall: %.2f s\n", wall);
  printf("state hash: %016" PRIx64 "\n", j->hash);
}

/* The renderer up, the outputs open, the frames run; the exit status. */
static int render_scene(job *j, const mr_scene *scene) {
  render_args *a = j->a;
  mr_render_def rd = mr_default_render_def();
  rd.headless = true;
  rd.backend = a->so.backend;
  rd.gl = a->so.gl;
  rd.width = a->so.width;
  rd.height = a->so.height;
  if (a->so.samples > 0) rd.samples = a->so.samples;
  if (mr_stageview_open(&j->sv, scene, &rd, NULL, j->msg, sizeof j->msg) != 0) {
    fprintf(stderr, "marionette: %s\n", j->msg);
    return MR_EXIT_FAIL;
  }
  if (mr_stage_opts_apply(&a->so, "render", &j->sv) != 0) {
    mr_stageview_close(&j->sv);
    return MR_EXIT_USAGE;
  }
  /* The picture is the stage's, not a status screen. */
  j->sv.show_osd = false;
  char note[200] = "";
  mr_frames_out_def od =
      mr_stage_opts_outputs(&a->so, j->fps, j->sv.width, j->sv.height, note, sizeof note);
  if (note[0] != '\0' && !a->has_frame && !a->quiet)
    fprintf(stderr, "marionette render: %s\n", note);
  int rc = a->has_frame ? frame_target(j) : mr_frames_out_open(&od, &j->fo, j->msg, sizeof j->msg);
  if (rc != 0) {
    fprintf(stderr, "marionette render: %s\n", j->msg);
    mr_stageview_close(&j->sv);
    return MR_EXIT_FAIL;
  }
  double duration = a->duration > 0 ? a->duration : scene->duration > 0 ? scene->duration : 10;
  if (a->n_takes == 0 || a->duration > 0) j->total = (uint64_t)floor(duration * j->fps + 1e-9) + 1;
  /* The curtain closes over the show's last seconds wherever its end is
   * known, for every frame alike: --frame T shows what a whole render's
   * frame at T shows. */
  j->end = a->n_takes == 0 || a->duration > 0 ? duration : -1;
  j->wall0 = wall_now();
  char err_text[1100] = "";
  int run_rc = run_frames(j, scene, err_text, sizeof err_text);
  if (j->tty && !a->quiet && j->drawn > 0 && !a->has_frame) fputc('\n', stderr);
  mr_frames_out_summary s;
  char out_msg[700] = "";
  int out_rc = mr_frames_out_close(j->fo, &s, out_msg, sizeof out_msg);
  rc = MR_EXIT_OK;
  if (run_rc != 0) {
    fprintf(stderr, "marionette: %s\n", err_text);
    rc = MR_EXIT_FAIL;
  } else if (j->failed || out_rc != 0) {
    fprintf(stderr, "marionette render: %s\n", j->failed ? j->msg : out_msg);
    rc = MR_EXIT_FAIL;
  } else if (a->has_frame && !j->done) {
    fprintf(stderr, "marionette render: the show ended before t = %g s\n", a->frame_t);
    rc = MR_EXIT_FAIL;
  } else {
    summary(j, scene, &s, note, wall_now() - j->wall0);
  }
  mr_stageview_close(&j->sv);
  return rc;
}

int mr_cmd_render(int argc, char **argv) {
  render_args a;
  memset(&a, 0, sizeof a);
  mr_stage_opts_init(&a.so);
  int rc = parse(argc, argv, &a);
  if (rc >= 0) return rc;
  if (a.help) {
    mr_cmd_render_usage();
    return MR_EXIT_OK;
  }
  default_output(&a);
  mr_scene scene;
  mr_scene_error err;
  if (mr_scene_load(a.scene, &scene, &err) != MR_SCENE_OK) {
    fprintf(stderr, "marionette: %s\n", err.text);
    return MR_EXIT_FAIL;
  }
  job j;
  memset(&j, 0, sizeof j);
  j.a = &a;
  /* A take replays at the live show's rate (the scene's, else 60, as
   * marionette run), so its frames are the show's frames. */
  j.fps = a.fps > 0 ? a.fps : scene.fps > 0 ? scene.fps : a.n_takes > 0 ? 60.0 : 30.0;
  j.tty = isatty(2) != 0;
  j.last_tenth = 0;
  rc = render_scene(&j, &scene);
  mr_scene_free(&scene);
  return rc;
}
