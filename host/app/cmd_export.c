/* `marionette export TAKE... --scene SCENE -o show.glb` (issue 23, item
 * 4): the show that `marionette render --take` draws, played the same way
 * (the takes through the theater on a virtual clock, frames at the frame
 * rate), kept as the stage's draw lists instead of pixels and written as
 * a glTF 2.0 binary, with a PC2 point cache and a CSV of the particles on
 * request. Without a take, the scene's own track plays. No GL is started:
 * the models load through the renderer's loader alone (mr_model). */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <inttypes.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "export.h"
#include "mr_io.h"
#include "mr_scene.h"
#include "mr_show.h"
#include "mr_sim.h"
#include "take_ref.h"

void mr_cmd_export_usage(void) {
  printf("usage: marionette export [TAKE...] --scene SCENE -o OUT.glb [OPTIONS]\n"
         "\n"
         "Plays the takes (.mrec, recorded by marionette run --record, or BOOK:NAME,\n"
         "every glove of a take in a take list: marionette take) on SCENE as\n"
         "marionette render --take does, or without a take the scene's own track,\n"
         "and writes the show as a glTF 2.0 binary: a node per model shown, with\n"
         "its mesh and material, animated at the frame rate (particle and rigid\n"
         "models by translation and rotation, link models by scale too, the\n"
         "freeform mesh as a skin with a joint per particle).\n"
         "\n"
         "options:\n"
         "  --scene SCENE       the scene the takes were performed on (required)\n"
         "  -o, --output FILE   the glTF binary to write (required)\n"
         "  --points FILE       the freeform vertices as a PC2 point cache\n"
         "                      (Blender's Mesh Cache modifier reads it)\n"
         "  --csv FILE          the particles' trajectories: t,id,name,x,y,z\n"
         "  -t, --time SECONDS  how much show (default: the takes', else the\n"
         "                      scene's sim.duration, else 10 s)\n"
         "  --fps HZ            frames per second (default: the scene's, else 30;\n"
         "                      with takes, else 60, as the show they recorded)\n"
         "  -q, --quiet         no progress, only the summary and errors\n"
         "  -h, --help          show this help\n"
         "\n"
         "A take recorded on another scene is refused. A take cut off inside a\n"
         "chunk is exported up to its last whole frame, and a line says so.\n"
         "\n"
         "exit status: 0 success, 1 a scene, model, take or output failed (one\n"
         "line naming it), 2 bad usage.\n");
}

enum { MAX_TAKES = MR_SHOW_MAX_GLOVES };

typedef struct export_args {
  const char *scene, *out, *points, *csv;
  const char *takes[MAX_TAKES];
  size_t n_takes;
  double fps, duration;
  int quiet, help;
} export_args;

typedef struct job {
  const export_args *a;
  mr_export *ex;
  double fps;
  uint64_t total; /* frames expected, 0: not known ahead */
  bool tty, failed, past_cut;
  int last_tenth;
  double cut_t; /* < 0: no take is cut; else the last whole chunk's time */
  char msg[900];
} job;

static int usage_error(const char *what, const char *v) {
  fprintf(stderr, "marionette export: %s%s%s%s (see marionette export --help)\n", what,
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

static int own_option(export_args *a, const char *o, const char *v) {
  if (strcmp(o, "--scene") == 0) {
    a->scene = v;
  } else if (strcmp(o, "-o") == 0 || strcmp(o, "--output") == 0) {
    a->out = v;
  } else if (strcmp(o, "--points") == 0) {
    a->points = v;
  } else if (strcmp(o, "--csv") == 0) {
    a->csv = v;
  } else if (strcmp(o, "--fps") == 0) {
    if (parse_number(v, 1, 1000, &a->fps) != 0)
      return usage_error("expected --fps a frame rate from 1 to 1000 Hz, got", v);
  } else if (parse_number(v, 1e-6, 1e6, &a->duration) != 0) {
    return usage_error("expected --time a positive number of seconds, got", v);
  }
  return -1;
}

static int parse(int argc, char **argv, export_args *a) {
  static const char *const valued[] = { "--scene", "-o", "--output", "--points", "--csv",
                                        "--fps",   "-t", "--time",   NULL };
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
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
    } else {
      const char *paths[MAX_TAKES]; /* a .mrec, or a book's take: its files */
      int n = mr_app_take_paths("marionette export", o, paths, MAX_TAKES);
      if (n < 0) return MR_EXIT_USAGE;
      for (int k = 0; k < n; k++) {
        if (a->n_takes == MAX_TAKES)
          return usage_error("expected at most 8 takes, got another:", o);
        a->takes[a->n_takes++] = paths[k];
      }
    }
  }
  if (a->help) return -1;
  if (a->scene == NULL) return usage_error("expected --scene SCENE", NULL);
  if (a->out == NULL) return usage_error("expected -o OUT.glb", NULL);
  return -1;
}

static void progress(job *j, double t) {
  size_t n = mr_export_frames(j->ex);
  if (j->a->quiet) return;
  if (j->tty) {
    if (j->total > 0)
      fprintf(stderr, "\rexport: frame %zu of %" PRIu64 " (%d %%), t %.2f s   ", n, j->total,
              (int)(100 * n / j->total), t);
    else
      fprintf(stderr, "\rexport: frame %zu, t %.2f s   ", n, t);
    return;
  }
  int tenth = j->total > 0 ? (int)(10 * n / j->total) : (int)(t / 10.0);
  if (tenth == j->last_tenth) return;
  j->last_tenth = tenth;
  if (j->total > 0)
    fprintf(stderr, "export: %d %% (%zu of %" PRIu64 " frames)\n", 10 * tenth, n, j->total);
  else
    fprintf(stderr, "export: %zu frames, t %.0f s\n", n, t);
}

static void frame(job *j, double t, const double *xyz, size_t n) {
  if (j->failed) return;
  /* Past a cut take's last whole chunk the show runs on input it never
   * had: those frames are not the performance. */
  if (j->cut_t >= 0 && t > j->cut_t) {
    j->past_cut = true;
    return;
  }
  if (mr_export_add(j->ex, t, xyz, n, j->msg, sizeof j->msg) < 0) {
    j->failed = true;
    return;
  }
  progress(j, t);
}

static void on_sim_frame(void *user, double t, const double *xyz, int n) {
  frame(user, t, xyz, (size_t)n);
}

static void on_show_frame(void *user, const mr_show_frame *f) {
  frame(user, f->t, f->xyz, (size_t)f->n_particles);
}

static int stop_on_failure(void *user) {
  const job *j = user;
  return j->failed || j->past_cut;
}

/* The track, or the takes, through frame(). 0, or -1 with text. */
static int run_frames(job *j, const mr_scene *scene, char *text, size_t text_size) {
  const export_args *a = j->a;
  if (a->n_takes == 0) {
    mr_sim_def o = mr_default_sim_def();
    o.fps = j->fps;
    o.duration = a->duration;
    o.on_frame = on_sim_frame;
    o.user = j;
    mr_sim_result r;
    mr_scene_error err;
    mr_scene_status st = mr_sim_run(scene, &o, &r, &err);
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
  d.duration = a->duration;
  mr_virtual_clock vc = { 0.0 };
  mr_clock clock = mr_clock_virtual(&vc);
  mr_show_hooks h = { NULL, stop_on_failure, on_show_frame, NULL, j };
  mr_show_result r;
  mr_show_error err;
  mr_show_status st = mr_show_run(scene, &d, &clock, &h, &r, &err);
  mr_show_result_free(&r);
  if (st != MR_SHOW_OK) snprintf(text, text_size, "%s", err.text);
  return st == MR_SHOW_OK ? 0 : -1;
}

/* Each take read through before the show: recorded on this scene (when
 * it says which), and whole, or cut inside a chunk (then j->cut_t is
 * when its last whole chunk came, and note says so). 0, or the exit
 * status after one line. */
static int check_takes(job *j, const mr_scene *scene, char *note, size_t note_size) {
  char msg[400] = "";
  uint64_t hash = j->a->n_takes > 0 ? mr_export_scene_hash(scene, msg, sizeof msg) : 0;
  if (j->a->n_takes > 0 && hash == 0) {
    fprintf(stderr, "marionette: %s\n", msg);
    return MR_EXIT_FAIL;
  }
  j->cut_t = -1;
  for (size_t i = 0; i < j->a->n_takes; i++) {
    const char *path = j->a->takes[i];
    mr_rec_reader r;
    mr_io_error err;
    if (mr_rec_reader_open(&r, path, &err) != 0) {
      fprintf(stderr, "marionette export: take %s\n", err.msg);
      return MR_EXIT_FAIL;
    }
    if (r.header.scene_hash != 0 && r.header.scene_hash != hash) {
      fprintf(stderr,
              "marionette export: %s: the take was recorded on another scene (scene hash "
              "%016" PRIx64 "), not on %s (%016" PRIx64 ")\n",
              path, r.header.scene_hash, scene->path, hash);
      mr_rec_reader_close(&r);
      return MR_EXIT_FAIL;
    }
    uint64_t t_ns = 0, last = 0;
    const uint8_t *data;
    size_t len;
    int rc;
    while ((rc = mr_rec_reader_next(&r, &t_ns, &data, &len, &err)) == 1) last = t_ns;
    mr_rec_reader_close(&r);
    if (rc < 0 && err.status != MR_IO_ERR_TRUNCATED) {
      fprintf(stderr, "marionette export: take %s\n", err.msg);
      return MR_EXIT_FAIL;
    }
    if (rc < 0) {
      double t = (double)last * 1e-9;
      if (j->cut_t < 0 || t < j->cut_t) j->cut_t = t;
      snprintf(note, note_size, "%s: exported up to the last whole frame", err.msg);
    }
  }
  return 0;
}

static int write_outputs(job *j) {
  const export_args *a = j->a;
  if (mr_export_write_glb(j->ex, a->out, j->msg, sizeof j->msg) != 0 ||
      (a->points != NULL && mr_export_write_pc2(j->ex, a->points, j->msg, sizeof j->msg) != 0) ||
      (a->csv != NULL && mr_export_write_csv(j->ex, a->csv, j->msg, sizeof j->msg) != 0)) {
    fprintf(stderr, "marionette export: %s\n", j->msg);
    return MR_EXIT_FAIL;
  }
  return MR_EXIT_OK;
}

static void summary(const job *j, const mr_scene *scene) {
  const export_args *a = j->a;
  size_t n = mr_export_frames(j->ex);
  printf("scene: %s (%s)\n", scene->name, scene->path);
  printf("frames: %zu at %g fps (%.3f s)\n", n, j->fps, mr_export_last_time(j->ex));
  printf("gltf: %s (%zu nodes, %zu channels of %zu keys)\n", a->out, mr_export_nodes(j->ex),
         mr_export_channels(j->ex), n);
  if (a->points != NULL)
    printf("points: %s (%zu points, %zu samples)\n", a->points, mr_export_points(j->ex), n);
  if (a->csv != NULL) printf("csv: %s (%zu rows)\n", a->csv, n * scene->n_particles);
}

/* The scene loaded, the takes checked, the show run and written. */
static int export_scene(job *j, const mr_scene *scene) {
  const export_args *a = j->a;
  char note[700] = "";
  int rc = check_takes(j, scene, note, sizeof note);
  if (rc != 0) return rc;
  if (mr_export_open(scene, &j->ex, j->msg, sizeof j->msg) != 0) {
    fprintf(stderr, "marionette export: %s\n", j->msg);
    return MR_EXIT_FAIL;
  }
  double duration = a->duration > 0 ? a->duration : scene->duration > 0 ? scene->duration : 10;
  if (a->n_takes == 0 || a->duration > 0) j->total = (uint64_t)(duration * j->fps + 1e-9) + 1;
  char text[1100] = "";
  int run_rc = run_frames(j, scene, text, sizeof text);
  if (j->tty && !a->quiet && mr_export_frames(j->ex) > 0) fputc('\n', stderr);
  if (j->failed) {
    fprintf(stderr, "marionette export: %s\n", j->msg);
    rc = MR_EXIT_FAIL;
  } else if (run_rc != 0 && j->cut_t < 0) {
    fprintf(stderr, "marionette: %s\n", text);
    rc = MR_EXIT_FAIL;
  } else {
    rc = write_outputs(j);
    if (rc == MR_EXIT_OK && note[0] != '\0')
      fprintf(stderr, "marionette export: take %s, t = %.3f s\n", note, mr_export_last_time(j->ex));
    if (rc == MR_EXIT_OK) summary(j, scene);
  }
  mr_export_close(j->ex);
  return rc;
}

int mr_cmd_export(int argc, char **argv) {
  export_args a;
  memset(&a, 0, sizeof a);
  int rc = parse(argc, argv, &a);
  if (rc >= 0) return rc;
  if (a.help) {
    mr_cmd_export_usage();
    return MR_EXIT_OK;
  }
  mr_scene scene;
  mr_scene_error err;
  if (mr_scene_load(a.scene, &scene, &err) != MR_SCENE_OK) {
    fprintf(stderr, "marionette: %s\n", err.text);
    return MR_EXIT_FAIL;
  }
  job j;
  memset(&j, 0, sizeof j);
  j.a = &a;
  /* As marionette render: a take plays at the live show's rate. */
  j.fps = a.fps > 0 ? a.fps : scene.fps > 0 ? scene.fps : a.n_takes > 0 ? 60.0 : 30.0;
  j.tty = isatty(2) != 0;
  rc = export_scene(&j, &scene);
  mr_scene_free(&scene);
  return rc;
}
