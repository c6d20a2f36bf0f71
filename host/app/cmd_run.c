/* `marionette run SCENE --glove SRC...`: the theater. Gloves drive the
 * scene's puppets in real time on the wall clock, drawn on the stage: in a
 * window when there is a display, else headless into frames. Without a
 * glove, in a window, the keyboard, mouse and a gamepad play one. A status
 * line a second shows the show, and a summary ends it. Ctrl-C ends it
 * cleanly. */
#define _POSIX_C_SOURCE 200809L

#include <inttypes.h>
#include <math.h>
#include <stdbool.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "app.h"
#include "mr_scene.h"
#include "mr_show.h"
#include "mr_show_runner.h"
#include "run_takes.h"
#include "stage_opts.h"
#include "state_pub.h"
#include "take_ref.h"
#include "window.h"

static volatile sig_atomic_t stop_asked, mappings_asked;

static void on_signal(int sig) {
  if (sig == SIGUSR1)
    mappings_asked++;
  else
    stop_asked = 1;
}

typedef struct status {
  int quiet;
  double next_line;
  FILE *hashes; /* --hashes: one line a frame */
  FILE *poses;  /* --poses: one line a frame */
  int hash_failed;
  mr_live *lv;           /* the stage, or NULL */
  mr_show_runner *r;     /* the show */
  sig_atomic_t mappings; /* SIGUSR1s sent on as commands */
  bool quit_sent;
  mr_app_state_pub *pub; /* --publish and --particles, or NULL */
} status;

/* On the thread that ticks the show: st->hashes and st->poses are its. */
static void frame_done(void *user, const mr_show_frame *f) {
  status *st = user;
  mr_app_state_pub_frame(st->pub, f);
  if (st->hashes != NULL && fprintf(st->hashes, "%.6f %016" PRIx64 "\n", f->t, f->hash) < 0)
    st->hash_failed = 1;
  if (st->poses == NULL) return;
  int bad = fprintf(st->poses, "%.6f", f->t) < 0;
  for (size_t k = 0; k < f->n_frames; k++) {
    const mr_pose *p = &f->pose[k];
    bad |= fprintf(st->poses, "  %.6f %.6f %.6f %.7f %.7f %.7f %.7f", p->position[0],
                   p->position[1], p->position[2], p->orientation[0], p->orientation[1],
                   p->orientation[2], p->orientation[3]) < 0;
  }
  if (bad || fputc('\n', st->poses) == EOF) st->hash_failed = 1;
}

/* Frames shown: drawn on the stage when there is one (the physics thread
 * publishes every frame; the stage draws what it can), else the
 * scheduler's. */
static uint64_t frames_shown(const status *st, const mr_scheduler_stats *s) {
  return st->lv != NULL && st->r != NULL ? st->lv->drawn : s->frames_presented;
}

/* A frame shown: on the stage, and a status line a second. */
static void present(void *user, const mr_show_frame *f) {
  status *st = user;
  if (st->lv != NULL) mr_live_present(st->lv, f);
  if (st->quiet || f->t < st->next_line) return;
  st->next_line = floor(f->t) + 1.0;
  const mr_scheduler_stats *s = &f->stats;
  uint64_t shown = frames_shown(st, s);
  printf("t %.0f s: %" PRIu64 " frames shown, %" PRIu64 " skipped, %" PRIu64 " steps, %" PRIu64
         " resets, latency p50 %.1f ms",
         f->t, shown, s->frames_simulated > shown ? s->frames_simulated - shown : 0, s->steps,
         s->resets, s->latency_p50 * 1e3);
  for (size_t g = 0; g < f->n_gloves; g++) {
    const mr_show_glove_view *v = &f->gloves[g];
    printf("; %s", v->describe);
    /* The newest sample's delay past the fastest one seen: the link's
     * jitter, which the clock offset leaves when it takes out the fixed
     * part. */
    const mr_glove_reading r = v->reading;
    double late = r.host_t - r.device_t - v->clock_offset;
    if (r.samples > 0 && isfinite(late)) printf(", %.1f ms late", late * 1e3);
  }
  printf("\n");
  fflush(stdout);
}

static void note(void *user, const char *line) {
  (void)user;
  fprintf(stderr, "marionette run: %s\n", line);
}

/* The stage's events and keys, and the signals, as commands: Ctrl-C and
 * q quit; SIGUSR1 is the next mapping (a theater box's operator sends it
 * with `systemctl kill -s USR1`). The number of events. */
static int pump(status *st) {
  int events = st->lv != NULL ? mr_live_pump(st->lv) : 0;
  if (!st->quit_sent && (stop_asked || (st->lv != NULL && mr_live_should_quit(st->lv)))) {
    st->quit_sent = true;
    mr_show_runner_send(st->r, MR_SHOW_CMD_QUIT);
  }
  for (; st->mappings != mappings_asked; st->mappings++)
    mr_show_runner_send(st->r, MR_SHOW_CMD_NEXT_MAPPING);
  return events;
}

static void pump_hook(void *user) {
  pump(user);
}

/* Glove 1's lines are "glove: ...", as with one glove; glove k's
 * "glove k: ...". */
static void glove_summary(const mr_show_result *r, size_t g) {
  char key[32] = "glove";
  if (g > 0) snprintf(key, sizeof key, "glove %zu", g + 1);
  const mr_show_glove_result *o = &r->glove[g];
  printf("%s: %s\n", key, mr_glove_state_name(o->state));
  printf("%s samples: %" PRIu64 "\n", key, o->samples);
  printf("%s losses: %" PRIu64 "\n", key, o->counters.losses);
  printf("%s crc errors: %" PRIu32 "\n", key, o->counters.decoder.crc_errors);
  if (o->state != MR_GLOVE_LIVE) printf("%s state: %s\n", key, o->describe);
  if (!o->over_net) return;
  /* The link's own losses, which the decoder never sees: messages the
   * broker's side dropped before they became bytes. */
  printf("%s broker messages: %" PRIu64 "\n", key, o->net.messages);
  printf("%s broker drops: %" PRIu64 " oversized, %" PRIu64 " empty, %" PRIu64 " behind\n", key,
         o->net.oversized, o->net.empty, o->net.queue_full);
  printf("%s broker messages from a second publisher: %" PRIu64 "\n", key, o->net.foreign);
  printf("%s broker reconnects: %" PRIu64 "\n", key, o->net.losses);
}

static void summary(const status *st, const mr_scene *scene, const mr_show_result *r) {
  uint64_t shown = frames_shown(st, &r->frames), sim = r->frames.frames_simulated;
  printf("frames simulated: %" PRIu64 "\n", sim);
  printf("frames shown: %" PRIu64 "\n", shown);
  /* Without a stage the frames went through the scheduler, onto nothing. */
  if (st->lv == NULL) printf("frames drawn: 0 (headless without -o: nothing drawn)\n");
  printf("frames skipped: %" PRIu64 "\n", sim > shown ? sim - shown : 0);
  printf("steps: %" PRIu64 "\n", r->frames.steps);
  printf("rejected steps: %" PRIu64 "\n", r->frames.rejected);
  printf("resets: %" PRIu64 "\n", r->frames.resets);
  printf("simulated: %.3f s\n", r->frames.sim_time);
  printf("real-time factor: %.3f\n", r->frames.real_time_factor);
  if (r->frames.dropped_time > 0)
    printf("time given up to catch up: %.3f s\n", r->frames.dropped_time);
  printf("latency p50: %.1f ms\n", r->frames.latency_p50 * 1e3);
  printf("latency p99: %.1f ms\n", r->frames.latency_p99 * 1e3);
  printf("present: %s\n",
         mr_present_mode_name(r->interpolated ? MR_PRESENT_INTERPOLATE : MR_PRESENT_LAND));
  printf("mapping: %s\n", r->mapping);
  if (r->interpolated)
    printf("physics ahead of frames: mean %.1f ms, max %.1f ms (input lag added)\n",
           r->lead_mean * 1e3, r->lead_max * 1e3);
  for (size_t g = 0; g < r->n_gloves; g++) glove_summary(r, g);
  for (size_t k = 0; k < scene->n_frames && k < r->n_frames; k++) {
    const char *who = scene->frames[k].puppet[0] ? scene->frames[k].puppet : "the scene";
    if (r->glove_of[k] >= 0)
      printf("control frame of %s: glove %d\n", who, r->glove_of[k] + 1);
    else
      printf("control frame of %s: no glove (held at its start pose)\n", who);
  }
}

static int bad_usage(const char *fmt, const char *arg) {
  fprintf(stderr, "marionette run: ");
  fprintf(stderr, fmt, arg);
  fprintf(stderr, " (see marionette run --help)\n");
  return MR_EXIT_USAGE;
}

/* The command line, read. */
typedef struct args {
  const char *scene, *hashes, *poses, *keys, *thread;
  const char *publish, *particles; /* state_pub.h */
  size_t n_live, n_replay, n_record;
  int real_time, quiet, help, headless, fullscreen, no_osd;
  mr_stage_opts so;
  mr_show_def def;
  char take_source[MR_SHOW_MAX_GLOVES][MR_GLOVE_SOURCE_MAX];
  mr_run_takes takes; /* --takes, --over, --arm, --punch, --name, --speed */
} args;

/* A glove's source into the show's list; -1 (after the message) past 8. */
static int add_glove(args *a, const char *source) {
  if (a->def.n_gloves == MR_SHOW_MAX_GLOVES)
    return bad_usage("expected at most 8 gloves, got another: '%s'", source), -1;
  a->def.gloves[a->def.n_gloves++] = source;
  return 0;
}

/* An option's value into a; -1 (after the message) on a bad one. */
static int take_value(args *a, const char *opt, const char *v) {
  if (strcmp(opt, "--glove") == 0) {
    a->n_live++;
    return add_glove(a, v);
  } else if (strcmp(opt, "--record") == 0) {
    if (a->n_record == MR_SHOW_MAX_GLOVES)
      return bad_usage("expected at most 8 takes, got another: '%s'", v), -1;
    a->def.record[a->n_record++] = v;
  } else if (strcmp(opt, "--replay") == 0) {
    const char *paths[MR_SHOW_MAX_GLOVES]; /* a .mrec, or a book's take: its files */
    int n = mr_app_take_paths("marionette run", v, paths, MR_SHOW_MAX_GLOVES);
    for (int k = 0; k < n; k++) {
      char *src = a->take_source[a->def.n_gloves < MR_SHOW_MAX_GLOVES ? a->def.n_gloves : 0];
      snprintf(src, MR_GLOVE_SOURCE_MAX, "take:%s", paths[k]);
      a->n_replay++;
      if (add_glove(a, src) != 0) return -1;
    }
    return n < 0 ? -1 : 0;
  } else if (strcmp(opt, "--hashes") == 0) {
    a->hashes = v;
  } else if (strcmp(opt, "--poses") == 0) {
    a->poses = v;
  } else if (strcmp(opt, "--publish") == 0 || strcmp(opt, "--particles") == 0) {
    bool publish = strcmp(opt, "--publish") == 0;
    if (publish && strncmp(v, "mqtt://", 7) != 0 && strncmp(v, "mqtts://", 8) != 0)
      return bad_usage("expected --publish mqtt[s]://HOST/TOPIC, got '%s'", v), -1;
    *(publish ? &a->publish : &a->particles) = v;
  } else if (strcmp(opt, "--thread") == 0) {
    if (strcmp(v, "on") != 0 && strcmp(v, "off") != 0)
      return bad_usage("expected --thread on or off, got '%s'", v), -1;
    a->thread = v;
  } else if (strcmp(opt, "--mapping") == 0) {
    a->def.mapping = v;
  } else if (strcmp(opt, "--present") == 0) {
    if (mr_present_mode_parse(v, &a->def.present) != 0)
      return bad_usage("expected --present land or interpolate, got '%s'", v), -1;
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

/* A window: a display (X11 or Wayland), and no --headless. --fullscreen
 * asks for one anyway: a theater box started at boot has no DISPLAY, and
 * SDL finds the screen through the console (KMS) itself. */
static bool window_wanted(const args *a) {
  if (a->headless) return false;
  if (a->fullscreen) return true;
  const char *x = getenv("DISPLAY"), *w = getenv("WAYLAND_DISPLAY");
  return (x != NULL && x[0] != '\0') || (w != NULL && w[0] != '\0');
}

static int parse(int argc, char **argv, args *a) {
  static const char *const valued[] = { "--glove",     "--policy",  "-t",       "--time",
                                        "--record",    "--replay",  "--hashes", "--poses",
                                        "--present",   "--mapping", "--thread", "--publish",
                                        "--particles", NULL };
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    int staged = mr_stage_opts_take(&a->so, "run", argc, argv, &i, true);
    if (staged < 0) return MR_EXIT_USAGE;
    if (staged > 0) continue;
    bool takes_value = false;
    for (int k = 0; valued[k] != NULL; k++) takes_value |= strcmp(o, valued[k]) == 0;
    if (strcmp(o, "-h") == 0 || strcmp(o, "--help") == 0) {
      a->help = 1;
    } else if (strcmp(o, "-q") == 0 || strcmp(o, "--quiet") == 0) {
      a->quiet = 1;
    } else if (strcmp(o, "--real-time") == 0) {
      a->real_time = 1;
    } else if (strcmp(o, "--headless") == 0) {
      a->headless = 1;
    } else if (strcmp(o, "--fullscreen") == 0) {
      a->fullscreen = 1;
    } else if (strcmp(o, "--no-osd") == 0) {
      a->no_osd = 1;
    } else if (strcmp(o, "--keys") == 0) {
      if (i + 1 >= argc) return bad_usage("option '%s' needs a value", o);
      a->keys = argv[++i];
    } else if (mr_run_takes_option_is(o)) {
      char msg[200];
      if (i + 1 >= argc) return bad_usage("option '%s' needs a value", o);
      if (mr_run_takes_option(&a->takes, o, argv[++i], msg, sizeof msg) != 0)
        return bad_usage("%s", msg);
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
  /* No scene: the box's show, else the installed default show. */
  if (a->scene == NULL) a->scene = access(MR_BOX_SHOW, F_OK) == 0 ? MR_BOX_SHOW : MR_DEFAULT_SHOW;
  return 0;
}

/* The options together, checked once the scene is loaded (a missing scene
 * is the first thing to hear of). Without --glove or --replay the
 * keyboard's glove plays (a window or --keys), and a --record takes its
 * bytes as it would a glove's. 0, or the exit status after one line. */
static int check_together(const args *a) {
  bool keyboard = a->def.n_gloves == 0;
  if (keyboard && !window_wanted(a) && a->keys == NULL)
    return bad_usage("expected --glove SOURCE or --replay TAKE%s", "");
  if (a->n_live > 0 && a->n_replay > 0)
    return bad_usage("expected gloves or takes, not both: a take replays on show time%s", "");
  if (a->n_replay > 0 && a->n_record > 0)
    return bad_usage("expected --record with a glove, not with --replay%s", "");
  if (keyboard && a->n_record > 1)
    return bad_usage("expected at most one --record for the keyboard's glove%s", "");
  if (!keyboard && a->n_record > a->n_live)
    return bad_usage("expected at most one --record per --glove%s", "");
  if (a->real_time && a->n_replay == 0)
    return bad_usage("expected --real-time with --replay%s", "");
  return 0;
}

/* Each glove source, checked before the show: one the user got wrong is
 * bad usage. 0, or the exit status after one line. */
static int check_gloves(const args *a) {
  for (size_t i = 0; i < a->def.n_gloves; i++) {
    mr_glove_source_report rep;
    if (mr_glove_source_check(a->def.gloves[i], &rep) == MR_IO_ERR_SPEC)
      return bad_usage("%s", rep.msg);
    if (rep.status != MR_IO_OK)
      return fprintf(stderr, "marionette run: %s\n", rep.msg), MR_EXIT_FAIL;
    if (rep.note[0] != '\0') fprintf(stderr, "marionette run: %s\n", rep.note);
  }
  return 0;
}

/* --hashes and --poses, opened; -1 (after the message) when one cannot be. */
static int open_outputs(const args *a, status *st) {
  if (a->hashes != NULL && (st->hashes = fopen(a->hashes, "w")) == NULL) {
    fprintf(stderr, "marionette run: cannot write %s\n", a->hashes);
    return -1;
  }
  if (a->poses != NULL && (st->poses = fopen(a->poses, "w")) == NULL) {
    fprintf(stderr, "marionette run: cannot write %s\n", a->poses);
    if (st->hashes != NULL) fclose(st->hashes);
    return -1;
  }
  return 0;
}

/* Closes them; -1 when a line was lost. */
static int close_outputs(status *st) {
  int bad = st->hash_failed;
  if (st->hashes != NULL) bad |= fclose(st->hashes) != 0;
  if (st->poses != NULL) bad |= fclose(st->poses) != 0;
  return bad ? -1 : 0;
}

/* The stage for this run: in a window (a display, live time), headless
 * (--headless, files to write or --keys), or none (the status line only).
 * 0, or the exit status after one line. */
static int open_stage(args *a, const mr_scene *scene, bool virtual_time, mr_live *lv, status *st) {
  bool window = window_wanted(a) && !virtual_time;
  if (!window && !a->headless && !mr_stage_opts_writes(&a->so) && a->keys == NULL) return 0;
  mr_live_def d = { window,
                    a->fullscreen,
                    a->def.n_gloves == 0,
                    a->keys,
                    60.0,
                    a->no_osd != 0,
                    a->def.duration > 0 ? a->def.duration : -1.0,
                    a->takes.speed };
  if (a->def.fps > 0)
    d.fps = a->def.fps;
  else if (scene->fps > 0)
    d.fps = scene->fps;
  int usage = 0;
  char msg[700];
  if (mr_live_open(lv, scene, &d, &a->so, &usage, msg, sizeof msg) != 0) {
    if (usage) return msg[0] != '\0' ? bad_usage("%s", msg) : MR_EXIT_USAGE;
    fprintf(stderr, "marionette: %s\n", msg);
    return MR_EXIT_FAIL;
  }
  if (d.manual) add_glove(a, lv->glove_source);
  st->lv = lv;
  return 0;
}

/* The show's end: what the gloves say, and whether all was written. */
static int show_status(const args *a, status *st, mr_show_status rc, const mr_show_result *r,
                       const mr_show_error *err) {
  if (st->lv != NULL) mr_live_hold(st->lv, r->frames.sim_time);
  int stage_rc = st->lv != NULL ? mr_live_close(st->lv, false) : 0;
  if (close_outputs(st) != 0 && rc == MR_SHOW_OK) {
    fprintf(stderr, "marionette run: could not write all of %s\n",
            a->hashes != NULL ? a->hashes : a->poses);
    return MR_EXIT_FAIL;
  }
  if (rc != MR_SHOW_OK) {
    fprintf(stderr, "marionette: %s\n", err->text);
    return MR_EXIT_FAIL;
  }
  for (size_t g = 0; g < r->n_gloves; g++)
    if (r->glove[g].state == MR_GLOVE_MISMATCH) {
      fprintf(stderr, "marionette run: %s\n", r->glove[g].describe);
      return MR_EXIT_MISMATCH;
    }
  return stage_rc != 0 ? MR_EXIT_FAIL : MR_EXIT_OK;
}

/* How long the drawing thread naps when there is nothing new to draw: a
 * frame period at 240 Hz, so a new frame waits little and an idle stage
 * costs the physics no core. */
#define NAP_S 0.004

/* This thread while the physics runs on its own: events become commands,
 * and the newest frame is drawn (or, without a stage, its status line
 * printed) whenever there is one, as fast as the renderer goes; paused,
 * the view still answers (orbit, zoom, cameras, screenshots). */
static void draw_loop(status *st) {
  while (!mr_show_runner_done(st->r)) {
    int events = pump(st);
    const mr_show_frame *f = NULL;
    if (mr_show_runner_latest(st->r, &f)) {
      present(st, f);
    } else if (st->lv != NULL && (events > 0 || st->lv->shot_asked)) {
      mr_live_redraw(st->lv);
    } else {
      struct timespec nap = { 0, (long)(NAP_S * 1e9) };
      nanosleep(&nap, NULL);
    }
  }
  const mr_show_frame *f = NULL;
  if (mr_show_runner_latest(st->r, &f) && f != NULL) present(st, f);
}

/* On this thread the scheduler shows a frame a tick after it was made,
 * so the frame the show ended on is never shown, and under load the last
 * few may have been skipped: the stage draws it now, so that the pictures
 * end where the show did (the curtain closed), as the drawing loop ends
 * on the newest frame when the physics has a thread of its own. */
static void draw_last(status *st) {
  const mr_show_frame *f = NULL;
  if (st->lv == NULL || !mr_show_runner_latest(st->r, &f) || f == NULL) return;
  if (st->lv->drawn == 0 || f->t > st->lv->show_t) present(st, f);
}

/* The physics on a thread of its own in a window (or with --thread on),
 * else on this one. */
static bool threaded(const args *a, const status *st) {
  if (a->thread != NULL) return strcmp(a->thread, "on") == 0;
  return st->lv != NULL && st->lv->window;
}

/* One show, from time 0, to its end. */
static mr_show_status one_show(args *a, const mr_scene *scene, status *st, const mr_clock *clock,
                               const mr_show_hooks *hooks, const mr_show_runner_def *rd,
                               mr_show_result *r, mr_show_error *err) {
  st->quit_sent = false;
  st->next_line = 0;
  if (st->lv != NULL) mr_live_set_takes(st->lv, a->takes.beneath_name);
  mr_show_status rc = mr_show_runner_start(scene, &a->def, clock, hooks, rd, &st->r, err);
  if (rc != MR_SHOW_OK) return rc;
  if (st->lv != NULL) st->lv->runner = st->r;
  if (rd->threaded) {
    draw_loop(st);
  } else {
    while (mr_show_runner_tick(st->r) == MR_SHOW_OK) {
    }
    draw_last(st);
  }
  return mr_show_runner_finish(st->r, r, err);
}

/* After a show with a take book: its takes stored (*stored: the exit
 * status that makes), and whether another show starts over the take
 * beneath, as the window asked (a punch-out, or a step through the
 * book), unless it is quitting. */
static bool another_show(args *a, status *st, const mr_show_result *r, int *stored) {
  char line[900];
  int step = st->lv != NULL ? st->lv->take_step : 0;
  if (st->lv != NULL) st->lv->take_step = 0;
  if (a->takes.book_dir == NULL) return false;
  int rc = mr_run_takes_store(&a->takes, r, &a->def, line, sizeof line);
  fprintf(stderr, "marionette run: %s\n", line);
  if (rc != MR_EXIT_OK) *stored = rc;
  if (st->lv == NULL || stop_asked || st->lv->quit || st->lv->failed) return false;
  if (step != 0) {
    mr_run_takes_step(&a->takes, step, &a->def, line, sizeof line);
    fprintf(stderr, "marionette run: %s\n", line);
    return true;
  }
  return r->punch_out >= 0;
}

static int run_show(args *a, mr_scene *scene, status *st) {
  bool virtual_time = a->n_replay > 0 && !a->real_time;
  mr_virtual_clock vc = { 0.0 };
  mr_clock clock = virtual_time ? mr_clock_virtual(&vc) : mr_clock_wall();
  if (virtual_time) st->quiet = 1; /* as fast as it goes: no seconds to mark */
  static mr_live lv;               /* large */
  memset(&lv, 0, sizeof lv);
  int rc_stage = open_stage(a, scene, virtual_time, &lv, st);
  if (rc_stage != 0) return rc_stage;
  mr_show_runner_def rd = mr_default_show_runner_def();
  rd.threaded = threaded(a, st);
  rd.speed = a->takes.speed;
  /* On its own thread the physics is behind only when the machine starved
   * it, not because a render took long, and a frame of it costs a fraction
   * of a millisecond: it chases up to half a second rather than give the
   * show's time up. */
  if (rd.threaded) a->def.max_catch_up = 30;
  rd.pump = pump_hook;
  rd.user = st;
  /* Threaded, the hooks run on the physics thread: only frame_done's
   * files and the notes (stderr, line-buffered by stdio) are there. */
  mr_show_hooks hooks = { rd.threaded ? NULL : present, NULL, frame_done, note, st };
  mr_show_result r;
  memset(&r, 0, sizeof r);
  mr_show_error err;
  mr_show_status rc;
  int stored = MR_EXIT_OK;
  for (;;) {
    rc = one_show(a, scene, st, &clock, &hooks, &rd, &r, &err);
    if (rc != MR_SHOW_OK || !another_show(a, st, &r, &stored)) break;
    mr_live_next_pass(st->lv, r.frames.sim_time); /* another_show: st->lv is there */
    mr_show_result_free(&r);
    if (virtual_time) vc.t = 0.0;
  }
  if (rc == MR_SHOW_OK) summary(st, scene, &r);
  int exit_status = show_status(a, st, rc, &r, &err);
  if (exit_status == MR_EXIT_OK) exit_status = stored;
  mr_show_result_free(&r);
  return exit_status;
}

int mr_cmd_run(int argc, char **argv) {
  args a;
  memset(&a, 0, sizeof a);
  a.def = mr_default_show_def();
  a.takes.speed = 1.0;
  mr_stage_opts_init(&a.so);
  int rc_usage = parse(argc, argv, &a);
  if (rc_usage != 0) return rc_usage;
  if (a.help) {
    mr_cmd_run_usage();
    return MR_EXIT_OK;
  }
  status st;
  memset(&st, 0, sizeof st);
  st.quiet = a.quiet;
  mr_scene scene;
  mr_scene_error err;
  if (mr_scene_load(a.scene, &scene, &err) != MR_SCENE_OK) {
    fprintf(stderr, "marionette: %s\n", err.text);
    return MR_EXIT_FAIL;
  }
  int rc_gloves = check_together(&a);
  if (rc_gloves == 0) rc_gloves = check_gloves(&a);
  char msg[700];
  if (rc_gloves == 0 &&
      (rc_gloves = mr_run_takes_prepare(&a.takes, &a.def, a.def.n_gloves, msg, sizeof msg)) != 0) {
    if (rc_gloves == MR_EXIT_USAGE)
      bad_usage("%s", msg);
    else
      fprintf(stderr, "marionette run: %s\n", msg);
    mr_run_takes_close(&a.takes);
  }
  if (rc_gloves != 0) return mr_scene_free(&scene), rc_gloves;
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
  sigaction(SIGUSR1, &sa, NULL);
  if (open_outputs(&a, &st) != 0) {
    mr_run_takes_close(&a.takes);
    mr_scene_free(&scene);
    return MR_EXIT_FAIL;
  }
  /* --publish and --particles: the show's state out (state_pub.c). */
  double fps = a.def.fps > 0 ? a.def.fps : scene.fps > 0 ? scene.fps : 60.0;
  if ((a.publish != NULL || a.particles != NULL) &&
      mr_app_state_pub_open(a.publish, a.particles, &scene, fps, &st.pub, msg, sizeof msg) != 0) {
    fprintf(stderr, "marionette run: %s\n", msg);
    close_outputs(&st);
    mr_run_takes_close(&a.takes);
    mr_scene_free(&scene);
    return MR_EXIT_FAIL;
  }
  int rc = run_show(&a, &scene, &st);
  mr_run_takes_close(&a.takes);
  if (mr_app_state_pub_close(st.pub, stdout) != 0 && rc == MR_EXIT_OK) rc = MR_EXIT_FAIL;
  mr_scene_free(&scene);
  return rc;
}
