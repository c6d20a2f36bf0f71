/* `marionette sim SCENE`: a scene run headless, with its summary, an
 * optional per-step CSV trace, and an optional check against the scene's
 * expect: section. The wall clock is read here, never in the physics. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "app.h"
#include "mr_scene.h"
#include "mr_scene_world.h"
#include "mr_sim.h"

void mr_cmd_sim_usage(void) {
  printf("usage: marionette sim [OPTIONS] SCENE\n"
         "\n"
         "Runs the scene file SCENE without rendering, as fast as possible, and\n"
         "prints a summary: steps, rejected steps, mean/min/max time step, the\n"
         "fraction of steps at the upper bound, max and RMS relative deviation,\n"
         "resets, collisions, per-pass call counters and the state hash. The\n"
         "control frame follows the scene's track (keyframes or oscillation),\n"
         "sampled at the end of every step (arriving at the track's own velocity\n"
         "there), or at sim.fps if the scene gives one.\n"
         "The scene format: host/scenes/FORMAT.md.\n"
         "\n"
         "options:\n"
         "  -t, --time SECONDS  simulated time (default: the scene's sim.duration,\n"
         "                      10 s when the scene gives none)\n"
         "  --fps HZ            pace the run in frames at this rate, as the theater\n"
         "                      does (default: the scene's sim.fps)\n"
         "  --present MODE      with frames: land (the last step before each frame\n"
         "                      lands on its time, the paper's) or interpolate\n"
         "                      (steps at the ATS's own dt, each frame the state\n"
         "                      interpolated between the steps around it); default\n"
         "                      the scene's sim.present, else land\n"
         "  --csv FILE          write a per-step trace to FILE ('-' for stdout):\n"
         "                      t,dt,error,accepted,rejected,reset,max_speed\n"
         "  --check             verify the scene's expect: section (finite state,\n"
         "                      deviation bound, resets, creep and jitter, the\n"
         "                      state hash, or the expected load error); exit 1\n"
         "                      with one line on stderr when an expectation is\n"
         "                      not met\n"
         "  --print-hash        print only the final state hash, as the line an\n"
         "                      expect: section pins it with (state_hash: 0x...)\n"
         "  -q, --quiet         print nothing but errors and the check result\n"
         "  -h, --help          show this help\n"
         "\n"
         "exit status: 0 success, 1 scene error or failed check, 2 bad usage.\n"
         "Errors in the scene file read: marionette: FILE:LINE:COLUMN: what was expected\n");
}

typedef struct csv_sink {
  FILE *f;
  int failed;
} csv_sink;

static void on_step(void *user, const mr_sim_step *s) {
  csv_sink *c = user;
  /* %.17g: the trace must carry the exact doubles for comparisons. */
  if (fprintf(c->f, "%.17g,%.17g,%.17g,%d,%d,%d,%.17g\n", s->t, s->dt, s->error, s->accepted,
              s->rejected, s->reset, s->max_speed) < 0)
    c->failed = 1;
}

static double wall_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void print_summary(const mr_scene *scene, const mr_sim_result *r, double wall) {
  printf("scene: %s (%s)\n", scene->name, scene->path);
  printf("simulated: %.3f s\n", r->sim_time);
  printf("wall: %.3f s\n", wall);
  if (r->frames > 0) printf("frames: %" PRIu64 " at %g fps\n", r->frames, r->fps);
  if (r->frames > 0)
    printf("present: %s\n",
           mr_present_mode_name(r->interpolated ? MR_PRESENT_INTERPOLATE : MR_PRESENT_LAND));
  if (r->interpolated)
    printf("physics ahead of frames: mean %.4g s, max %.4g s\n", r->lead_mean, r->lead_max);
  printf("steps: %" PRIu64 "\n", r->steps);
  printf("rejected: %" PRIu64 "\n", r->rejected);
  printf("dt mean: %.4g s\n", r->dt_mean);
  printf("dt min: %.4g s\n", r->dt_min);
  if (r->dt_min_landing > 0) printf("dt min (landing): %.4g s\n", r->dt_min_landing);
  printf("dt max: %.4g s\n", r->dt_max);
  printf("at upper bound: %.1f %%\n", 100.0 * r->at_upper_fraction);
  printf("deviation max: %.3e\n", r->max_deviation);
  printf("deviation rms: %.3e\n", r->rms_deviation);
  printf("resets: %" PRIu64 "\n", r->resets);
  if (r->resets > 0) printf("first reset: %s\n", r->first_reset);
  printf("corrections: %" PRIu64 "\n", r->corrections);
  if (r->stable_dt > 0) printf("stable dt: %.4g s\n", r->stable_dt);
  if (r->softened_forces > 0) printf("softened forces: %" PRIu64 "\n", r->softened_forces);
  printf("collisions: %" PRIu64 "\n", r->collisions);
  printf("dependent rows: %d\n", r->dependent_rows);
  printf("finite: %s\n", r->finite ? "yes" : "no");
  printf("speed max: %.3g m/s\n", r->max_speed);
  if (scene->world.effects &
      (MR_EFFECT_PLANES | MR_EFFECT_SELF_COLLISION | MR_EFFECT_PUPPET_COLLISION))
    printf("penetration max: %.3g m\n", r->max_penetration);
  if (r->string_stretch > 0) /* some string has a rest length above 0 */
    printf("string stretch max: %.6g x rest\n", r->string_stretch);
  if (scene->expect.n_watch > 0) {
    printf("creep: %.3e m\n", r->creep);
    printf("jitter: %.3e m/s\n", r->jitter);
  }
  for (int p = 0; p < MR_PASS_COUNT; p++)
    printf("pass %s: %" PRIu64 "\n", mr_pass_name((mr_pass)p), r->pass_calls[p]);
  printf("state hash: %016" PRIx64 "\n", r->hash);
}

/* --check on a scene that failed to load: a pass only if the file says it
 * must fail, and with what. */
static int check_load_error(const char *path, const mr_scene_error *err, int quiet) {
  char expected[256];
  if (mr_scene_expected_load_error(path, expected, sizeof expected) != 0) return -1;
  if (strstr(err->text, expected) == NULL) {
    fprintf(stderr,
            "marionette: %s: check failed: expected a load error containing \"%s\", got: %s\n",
            path, expected, err->text);
    return MR_EXIT_FAIL;
  }
  if (!quiet) printf("load error: %s\n", err->text);
  printf("check: passed (%s failed to load as expected)\n", path);
  return MR_EXIT_OK;
}

static int parse_seconds(const char *s, double *out) {
  char *end = NULL;
  errno = 0;
  double v = strtod(s, &end);
  if (end == s || *end != '\0' || errno != 0 || !isfinite(v) || v <= 0 || v > 1e7) return -1;
  *out = v;
  return 0;
}

typedef struct sim_args {
  const char *path, *csv_path;
  double duration, fps;
  mr_present_mode present;
  int check, quiet, print_hash;
} sim_args;

/* --fps and --present; -1 when s is neither, else the exit status (-2:
 * good). */
static int frame_option(int argc, char **argv, int *i, sim_args *a) {
  const char *s = argv[*i];
  bool fps = strcmp(s, "--fps") == 0;
  if (!fps && strcmp(s, "--present") != 0) return -1;
  const char *v = *i + 1 < argc ? argv[++*i] : NULL;
  if (fps && (v == NULL || parse_seconds(v, &a->fps) != 0 || a->fps < 1 || a->fps > 1e4)) {
    fprintf(stderr, "marionette: sim: --fps expects a frame rate between 1 and 10000 Hz\n");
    return MR_EXIT_USAGE;
  }
  if (!fps && (v == NULL || mr_present_mode_parse(v, &a->present) != 0)) {
    fprintf(stderr, "marionette: sim: --present expects land or interpolate\n");
    return MR_EXIT_USAGE;
  }
  return -2;
}

/* Returns -1 when the arguments are good, else the exit status. */
static int parse_args(int argc, char **argv, sim_args *a) {
  memset(a, 0, sizeof *a);
  int rc;
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i];
    if (strcmp(s, "-h") == 0 || strcmp(s, "--help") == 0) {
      mr_cmd_sim_usage();
      return MR_EXIT_OK;
    } else if (strcmp(s, "-t") == 0 || strcmp(s, "--time") == 0) {
      if (i + 1 >= argc || parse_seconds(argv[i + 1], &a->duration) != 0) {
        fprintf(stderr, "marionette: sim: %s expects a positive number of seconds\n", s);
        return MR_EXIT_USAGE;
      }
      i++;
    } else if (strcmp(s, "--csv") == 0) {
      if (i + 1 >= argc) {
        fprintf(stderr, "marionette: sim: --csv expects a file name\n");
        return MR_EXIT_USAGE;
      }
      a->csv_path = argv[++i];
    } else if ((rc = frame_option(argc, argv, &i, a)) != -1) {
      if (rc != -2) return rc;
    } else if (strcmp(s, "--check") == 0) {
      a->check = 1;
    } else if (strcmp(s, "--print-hash") == 0) {
      a->print_hash = 1;
    } else if (strcmp(s, "-q") == 0 || strcmp(s, "--quiet") == 0) {
      a->quiet = 1;
    } else if (s[0] == '-' && s[1] != '\0') {
      fprintf(stderr, "marionette: sim: unknown option '%s' (see marionette sim --help)\n", s);
      return MR_EXIT_USAGE;
    } else if (a->path == NULL) {
      a->path = s;
    } else {
      fprintf(stderr, "marionette: sim: expected one scene file, got '%s' too\n", s);
      return MR_EXIT_USAGE;
    }
  }
  if (a->path == NULL) {
    fprintf(stderr, "marionette: sim: expected a scene file (see marionette sim --help)\n");
    return MR_EXIT_USAGE;
  }
  return -1;
}

/* Opens the trace and writes its header; -1 when it cannot be written. */
static int csv_open(const char *csv_path, csv_sink *sink) {
  sink->f = NULL;
  sink->failed = 0;
  if (csv_path == NULL) return 0;
  sink->f = strcmp(csv_path, "-") == 0 ? stdout : fopen(csv_path, "w");
  if (sink->f == NULL) {
    fprintf(stderr, "marionette: %s: cannot write the trace: %s\n", csv_path, strerror(errno));
    return -1;
  }
  fprintf(sink->f, "t,dt,error,accepted,rejected,reset,max_speed\n");
  return 0;
}

/* Closes the trace; MR_EXIT_FAIL when any of it failed to reach the file. */
static int csv_close(const char *csv_path, csv_sink *sink) {
  if (sink->f != NULL && sink->f != stdout && fclose(sink->f) != 0) sink->failed = 1;
  if (!sink->failed) return MR_EXIT_OK;
  fprintf(stderr, "marionette: %s: writing the trace failed\n", csv_path);
  return MR_EXIT_FAIL;
}

/* The run failed: a pass only when the scene expects exactly this refusal
 * (refused when the world was built is as good as refused on load). */
static int run_failed(const sim_args *a, const mr_scene *scene, const mr_scene_error *err) {
  if (a->check && scene->expect.has_load_error &&
      strstr(err->text, scene->expect.load_error) != NULL) {
    printf("check: passed (%s refused as expected: %s)\n", a->path, err->text);
    return MR_EXIT_OK;
  }
  fprintf(stderr, "marionette: %s\n", err->text);
  return MR_EXIT_FAIL;
}

/* What a finished run prints, and the check's verdict. */
static int report(const sim_args *a, const mr_scene *scene, const mr_sim_result *r, double wall) {
  bool csv_on_stdout = a->csv_path != NULL && strcmp(a->csv_path, "-") == 0;
  if (a->print_hash)
    printf("state_hash: 0x%016" PRIx64 "\n", r->hash);
  else if (!a->quiet && !csv_on_stdout)
    print_summary(scene, r, wall);
  if (!a->check) return MR_EXIT_OK;
  char why[512];
  if (mr_sim_check(scene, r, why, sizeof why) != 0) {
    fprintf(stderr, "marionette: %s: check failed: %s\n", a->path, why);
    return MR_EXIT_FAIL;
  }
  printf("check: passed\n");
  return MR_EXIT_OK;
}

static int run_scene(const sim_args *a, mr_scene *scene) {
  csv_sink sink;
  if (csv_open(a->csv_path, &sink) != 0) return MR_EXIT_FAIL;
  mr_sim_def opts = mr_default_sim_def();
  opts.duration = a->duration;
  opts.on_step = a->csv_path ? on_step : NULL;
  opts.user = &sink;
  opts.fps = a->fps;
  opts.present = a->present;
  mr_sim_result result;
  mr_scene_error err;
  double t0 = wall_seconds();
  mr_scene_status st = mr_sim_run(scene, &opts, &result, &err);
  double wall = wall_seconds() - t0;
  int rc = csv_close(a->csv_path, &sink);
  if (st != MR_SCENE_OK) return run_failed(a, scene, &err);
  int rc2 = report(a, scene, &result, wall);
  return rc != MR_EXIT_OK ? rc : rc2;
}

int mr_cmd_sim(int argc, char **argv) {
  sim_args a;
  int rc = parse_args(argc, argv, &a);
  if (rc >= 0) return rc;
  mr_scene scene;
  mr_scene_error err;
  /* sim never draws: the stage's framing is left out (mr_scene.h). */
  if (mr_scene_load_unframed(a.path, &scene, &err) != MR_SCENE_OK) {
    if (a.check && (rc = check_load_error(a.path, &err, a.quiet)) >= 0) return rc;
    fprintf(stderr, "marionette: %s\n", err.text);
    return MR_EXIT_FAIL;
  }
  rc = run_scene(&a, &scene);
  mr_scene_free(&scene);
  return rc;
}
