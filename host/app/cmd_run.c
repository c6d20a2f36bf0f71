/* `marionette run SCENE --glove SRC`: the theater. A glove drives the
 * scene's puppet in real time on the wall clock; until the stage exists,
 * a status line a second shows the show, and a summary ends it. Ctrl-C
 * ends it cleanly. */
#define _POSIX_C_SOURCE 200809L

#include <inttypes.h>
#include <math.h>
#include <stdbool.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "mr_scene.h"
#include "mr_show.h"

static volatile sig_atomic_t stop_asked;

static void on_signal(int sig) {
  (void)sig;
  stop_asked = 1;
}

void mr_cmd_run_usage(void) {
  printf("usage: marionette run [OPTIONS] SCENE (--glove SOURCE | --replay TAKE)\n"
         "\n"
         "The theater: the glove at SOURCE drives the puppet of the scene file SCENE\n"
         "in real time. Its five values move the control frame through the scene's\n"
         "mapping (host/scenes/FORMAT.md, \"mapping\"); the strings do the rest. The\n"
         "frame rate is the scene's sim.fps, else 60. Under load renders are skipped\n"
         "and simulated time keeps to wall time (--policy skip), or simulated time\n"
         "slows and nothing is skipped (--policy slow). Until the stage exists, one\n"
         "status line a second shows frames, skipped frames, steps, resets and the\n"
         "glove; a summary ends the show. Ctrl-C ends it cleanly.\n"
         "\n"
         "options:\n"
         "  --glove SOURCE      serial:/dev/ttyACM0[@BAUD], pty:PATH, file:PATH, -,\n"
         "                      tcp:HOST:PORT or tcp-listen:PORT (required)\n"
         "  --record TAKE       record every byte the glove sends, with the frame\n"
         "                      that read it, into TAKE (.mrec); a take stays\n"
         "                      readable up to its last whole chunk if the show is\n"
         "                      killed\n"
         "  --replay TAKE       play a take instead of a glove, on a virtual clock as\n"
         "                      fast as it goes: every frame gets the bytes it got\n"
         "                      live, so the states match the show's bit for bit\n"
         "  --real-time         with --replay: at real speed on the wall clock\n"
         "  --hashes FILE       write each frame's time and state hash to FILE\n"
         "  --policy skip|slow  what to do under load (default skip, the paper's)\n"
         "  -t, --time SECONDS  end after this much show (default: until Ctrl-C)\n"
         "  -q, --quiet         no status lines, only the summary and errors\n"
         "  -h, --help          show this help\n"
         "\n"
         "exit status: 0 the show ended, 1 the scene or the glove source failed,\n"
         "2 bad usage, 3 the glove was built from another protocol definition.\n");
}

typedef struct status {
  int quiet;
  double next_line;
  FILE *hashes; /* --hashes: one line a frame */
  int hash_failed;
} status;

static void frame_done(void *user, double t, uint64_t hash) {
  status *st = user;
  if (st->hashes != NULL && fprintf(st->hashes, "%.6f %016" PRIx64 "\n", t, hash) < 0)
    st->hash_failed = 1;
}

static void present(void *user, const mr_show_frame *f) {
  status *st = user;
  if (st->quiet || f->t < st->next_line) return;
  st->next_line = floor(f->t) + 1.0;
  mr_scheduler_stats s;
  mr_scheduler_stats_get(f->scheduler, &s);
  char glove[400];
  mr_glove_describe(f->glove, s.wall_time, glove, sizeof glove);
  printf("t %.0f s: %" PRIu64 " frames shown, %" PRIu64 " skipped, %" PRIu64 " steps, %" PRIu64
         " resets, latency p50 %.1f ms; %s\n",
         f->t, s.frames_presented, s.frames_skipped, s.steps, s.resets, s.latency_p50 * 1e3, glove);
  fflush(stdout);
}

static int stop(void *user) {
  (void)user;
  return stop_asked != 0;
}

static void summary(const mr_show_result *r) {
  printf("frames simulated: %" PRIu64 "\n", r->frames.frames_simulated);
  printf("frames shown: %" PRIu64 "\n", r->frames.frames_presented);
  printf("frames skipped: %" PRIu64 "\n", r->frames.frames_skipped);
  printf("steps: %" PRIu64 "\n", r->frames.steps);
  printf("resets: %" PRIu64 "\n", r->frames.resets);
  printf("simulated: %.3f s\n", r->frames.sim_time);
  printf("real-time factor: %.3f\n", r->frames.real_time_factor);
  printf("latency p50: %.1f ms\n", r->frames.latency_p50 * 1e3);
  printf("latency p99: %.1f ms\n", r->frames.latency_p99 * 1e3);
  printf("glove: %s\n", mr_glove_state_name(r->glove_state));
  printf("glove samples: %" PRIu64 "\n", r->samples);
  printf("glove losses: %" PRIu64 "\n", r->glove.losses);
  printf("glove crc errors: %" PRIu32 "\n", r->glove.decoder.crc_errors);
}

static int bad_usage(const char *fmt, const char *arg) {
  fprintf(stderr, "marionette run: ");
  fprintf(stderr, fmt, arg);
  fprintf(stderr, " (see marionette run --help)\n");
  return MR_EXIT_USAGE;
}

/* The command line, read. */
typedef struct args {
  const char *scene, *glove, *replay, *hashes;
  int real_time, quiet, help;
  mr_show_def def;
  char take_source[MR_GLOVE_SOURCE_MAX];
} args;

/* An option's value into a; -1 (after the message) on a bad one. */
static int take_value(args *a, const char *opt, const char *v) {
  if (strcmp(opt, "--glove") == 0) {
    a->glove = v;
  } else if (strcmp(opt, "--record") == 0) {
    a->def.record_path = v;
  } else if (strcmp(opt, "--replay") == 0) {
    a->replay = v;
  } else if (strcmp(opt, "--hashes") == 0) {
    a->hashes = v;
  } else if (strcmp(opt, "--policy") == 0) {
    if (mr_policy_parse(v, &a->def.policy) != 0)
      return bad_usage("expected --policy skip or slow, got '%s'", v), -1;
  } else {
    char *end = NULL;
    a->def.duration = strtod(v, &end);
    if (end == v || *end != '\0' || !(a->def.duration > 0) || !isfinite(a->def.duration))
      return bad_usage("expected a positive number of seconds for --time, got '%s'", v), -1;
  }
  return 0;
}

static int parse(int argc, char **argv, args *a) {
  static const char *const valued[] = { "--glove",  "--policy", "-t",       "--time",
                                        "--record", "--replay", "--hashes", NULL };
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    bool takes_value = false;
    for (int k = 0; valued[k] != NULL; k++) takes_value |= strcmp(o, valued[k]) == 0;
    if (strcmp(o, "-h") == 0 || strcmp(o, "--help") == 0) {
      a->help = 1;
    } else if (strcmp(o, "-q") == 0 || strcmp(o, "--quiet") == 0) {
      a->quiet = 1;
    } else if (strcmp(o, "--real-time") == 0) {
      a->real_time = 1;
    } else if (takes_value) {
      if (i + 1 >= argc) return bad_usage("option '%s' needs a value", o);
      if (take_value(a, o, argv[++i]) != 0) return MR_EXIT_USAGE;
    } else if (o[0] == '-') {
      return bad_usage("unknown option '%s'", o);
    } else if (a->scene == NULL) {
      a->scene = o;
    } else {
      return bad_usage("expected one scene, got a second: '%s'", o);
    }
  }
  if (a->help) return 0;
  if (a->scene == NULL) return bad_usage("expected a scene file%s", "");
  if ((a->glove == NULL) == (a->replay == NULL))
    return bad_usage("expected --glove SOURCE or --replay TAKE, one of the two%s", "");
  if (a->replay != NULL && a->def.record_path != NULL)
    return bad_usage("expected --record with a glove, not with --replay%s", "");
  if (a->real_time && a->replay == NULL)
    return bad_usage("expected --real-time with --replay%s", "");
  if (a->replay != NULL) {
    snprintf(a->take_source, sizeof a->take_source, "file:%s", a->replay);
    a->glove = a->take_source;
  }
  return 0;
}

int mr_cmd_run(int argc, char **argv) {
  args a;
  memset(&a, 0, sizeof a);
  a.def = mr_default_show_def();
  int rc_usage = parse(argc, argv, &a);
  if (rc_usage != 0) return rc_usage;
  if (a.help) {
    mr_cmd_run_usage();
    return MR_EXIT_OK;
  }
  status st = { a.quiet, 0.0, NULL, 0 };
  mr_scene scene;
  mr_scene_error err;
  if (mr_scene_load(a.scene, &scene, &err) != MR_SCENE_OK) {
    fprintf(stderr, "marionette: %s\n", err.text);
    return MR_EXIT_FAIL;
  }
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
  if (a.hashes != NULL && (st.hashes = fopen(a.hashes, "w")) == NULL) {
    fprintf(stderr, "marionette run: cannot write %s\n", a.hashes);
    mr_scene_free(&scene);
    return MR_EXIT_FAIL;
  }
  bool virtual_time = a.replay != NULL && !a.real_time;
  mr_virtual_clock vc = { 0.0 };
  mr_clock clock = virtual_time ? mr_clock_virtual(&vc) : mr_clock_wall();
  if (virtual_time) st.quiet = 1; /* as fast as it goes: no seconds to mark */
  mr_show_hooks hooks = { present, stop, frame_done, &st };
  mr_show_result r;
  mr_scene_status rc = mr_show_run(&scene, a.glove, &a.def, &clock, &hooks, &r, &err);
  mr_scene_free(&scene);
  if (st.hashes != NULL && (fclose(st.hashes) != 0 || st.hash_failed) && rc == MR_SCENE_OK) {
    fprintf(stderr, "marionette run: could not write all of %s\n", a.hashes);
    return MR_EXIT_FAIL;
  }
  if (rc != MR_SCENE_OK) {
    fprintf(stderr, "marionette: %s\n", err.text);
    return MR_EXIT_FAIL;
  }
  summary(&r);
  return r.glove_state == MR_GLOVE_MISMATCH ? MR_EXIT_MISMATCH : MR_EXIT_OK;
}
