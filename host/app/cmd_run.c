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

/* The options of the show's state out (state_pub.c). */
static const char publish_help[] =
    "  --publish URL       publish each simulated frame to a broker,\n"
    "                      mqtt[s]://[USER@]HOST[:PORT]/TOPIC, with the scene\n"
    "                      retained on TOPIC/scene: marionette watch shows it\n"
    "  --particles FILE    write each frame's time and every particle's x y z (m)\n";

void mr_cmd_run_usage(void) {
  printf("usage: marionette run [OPTIONS] [SCENE] [--glove SOURCE | --replay TAKE]...\n"
         "\n"
         "The theater: the glove at SOURCE drives the puppet of the scene file SCENE\n"
         "in real time, on the stage. Its five values move the control frame through\n"
         "the scene's mapping (host/scenes/FORMAT.md, \"mapping\"); the strings do the\n"
         "rest. Give --glove (or --replay) once per glove: a scene whose puppets have\n"
         "control frames of their own binds each to a glove by order, uid or hand\n"
         "(FORMAT.md, \"puppets\"); by default the k-th frame takes the k-th glove. The\n"
         "frame rate is the scene's sim.fps, else 60. Under load renders are skipped\n"
         "and simulated time keeps to wall time (--policy skip), or simulated time\n"
         "slows and nothing is skipped (--policy slow). One status line a second\n"
         "shows frames, skipped frames, steps, resets and the glove; a summary ends\n"
         "the show. Ctrl-C ends it cleanly. Without SCENE the show is\n"
         "/etc/marionette/show.yaml when it exists, else the installed default show\n"
         "(PREFIX/share/marionette/scenes/humanoid.yaml).\n"
         "\n"
         "The stage: with a display (DISPLAY or WAYLAND_DISPLAY set, or --fullscreen)\n"
         "the show is drawn in a window, its on-screen display showing fps, skipped\n"
         "renders, dt, resets and each glove's state and latency. Without a display,\n"
         "or with --headless, it is drawn offscreen and written as with marionette\n"
         "render (-o DIR); without a display and without -o nothing is drawn.\n"
         "Without --glove, in a window (or with --keys), the keyboard, the mouse and\n"
         "a gamepad play a glove on a pty of its own, through the same mapping (see\n"
         "the man page for the keys).\n"
         "Keys: space pause, . single step, s slow motion, r reset, n day/night,\n"
         "[ ] turn the day knob, m the next materials, c the collision spheres,\n"
         "h or F1 the OSD, p or F12 a screenshot (-o DIR, else here), f or F11\n"
         "fullscreen, q or Esc quit (the curtain closes first; q again: at once),\n"
         "1-8 the scene's cameras, 0 the orbit camera; drag to orbit, the wheel\n"
         "zooms.\n"
         "\n"
         "options:\n"
         "  --glove SOURCE      serial:/dev/ttyACM0[@BAUD], serial:auto, pty:PATH,\n"
         "                      file:PATH, -, tcp:HOST:PORT, tcp-listen:PORT or\n"
         "                      mqtt[s]://HOST/TOPIC; repeat for several gloves (up to 8)\n"
         "  --record TAKE       record every byte a glove sends, with the frame that\n"
         "                      read it, into TAKE (.mrec): the first --record for\n"
         "                      the first glove, and so on (without --glove, the\n"
         "                      keyboard's glove); a take stays readable up\n"
         "                      to its last whole chunk if the show is killed\n"
         "  --replay TAKE       play a take (.mrec, or BOOK:NAME: marionette take)\n"
         "                      instead of a glove, on a virtual clock as fast as it\n"
         "                      goes: every frame gets the bytes it got live, so the\n"
         "                      states match the show's bit for bit; one per glove\n"
         "  --real-time         with --replay: at real speed on the wall clock\n"
         "  --hashes FILE       write each frame's time and state hash to FILE\n"
         "  --poses FILE        write each frame's time and, for each control frame,\n"
         "                      its position (m) and orientation (w x y z)\n%s"
         "  --mapping NAME      start with the scene's mapping NAME (default: its\n"
         "                      first); SIGUSR1 moves to the next one during the show\n"
         "  --policy skip|slow  what to do under load (default skip, the paper's)\n"
         "  --thread on|off     the physics on a thread of its own (default on in a\n"
         "                      window: the window draws the newest frame as fast\n"
         "                      as it can), or on the drawing thread (off)\n"
         "  --present MODE      land (each frame's last step lands on its time, the\n"
         "                      paper's) or interpolate (steps at the ATS's own dt,\n"
         "                      each frame interpolated between the steps around\n"
         "                      it: fewer steps, up to one step more input lag);\n"
         "                      default the scene's sim.present, else land\n"
         "  -t, --time SECONDS  end after this much show (default: until Ctrl-C)\n"
         "  --headless          draw offscreen even with a display\n"
         "  --fullscreen        the window fills the screen, with or without DISPLAY\n"
         "                      (the theater box: SDL finds the console's screen)\n"
         "  --no-osd            start with the on-screen display hidden (h shows it)\n"
         "  --backend B         auto (default), window, egl or osmesa\n"
         "  --keys LIST         press keys at show times, T:KEY[/HOLD],... (KEY a\n"
         "                      character or space, esc, left, right, up, down,\n"
         "                      pgup, pgdn, f1, f11, f12; HOLD seconds, default\n"
         "                      0.05): for demos and tests; without --glove the\n"
         "                      keyboard's glove plays, headless too\n"
         "%s"
         "  -q, --quiet         no status lines, only the summary and errors\n"
         "  -h, --help          show this help\n"
         "\n"
         "exit status: 0 the show ended, 1 the scene, a model, the stage or a glove\n"
         "source failed, 2 bad usage, 3 a glove was built from another protocol\n"
         "definition.\n",
         publish_help, mr_stage_opts_help);
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
 * (--headless, -o or --keys), or none (the status line only). 0, or the
 * exit status after one line. */
static int open_stage(args *a, const mr_scene *scene, bool virtual_time, mr_live *lv, status *st) {
  bool window = window_wanted(a) && !virtual_time;
  if (!window && !a->headless && a->so.out == NULL && a->keys == NULL) return 0;
  mr_live_def d = { window,
                    a->fullscreen,
                    a->def.n_gloves == 0,
                    a->keys,
                    60.0,
                    a->no_osd != 0,
                    a->def.duration > 0 ? a->def.duration : -1.0 };
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
  mr_show_status rc = mr_show_runner_start(scene, &a->def, &clock, &hooks, &rd, &st->r, &err);
  if (rc == MR_SHOW_OK) {
    lv.runner = st->r;
    if (rd.threaded) {
      draw_loop(st);
    } else {
      while (mr_show_runner_tick(st->r) == MR_SHOW_OK) {
      }
      draw_last(st);
    }
    rc = mr_show_runner_finish(st->r, &r, &err);
  }
  if (rc == MR_SHOW_OK) summary(st, scene, &r);
  int exit_status = show_status(a, st, rc, &r, &err);
  mr_show_result_free(&r);
  return exit_status;
}

int mr_cmd_run(int argc, char **argv) {
  args a;
  memset(&a, 0, sizeof a);
  a.def = mr_default_show_def();
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
  if (rc_gloves != 0) return mr_scene_free(&scene), rc_gloves;
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
  sigaction(SIGUSR1, &sa, NULL);
  if (open_outputs(&a, &st) != 0) {
    mr_scene_free(&scene);
    return MR_EXIT_FAIL;
  }
  /* --publish and --particles: the show's state out (state_pub.c). */
  char msg[700];
  double fps = a.def.fps > 0 ? a.def.fps : scene.fps > 0 ? scene.fps : 60.0;
  if ((a.publish != NULL || a.particles != NULL) &&
      mr_app_state_pub_open(a.publish, a.particles, &scene, fps, &st.pub, msg, sizeof msg) != 0) {
    fprintf(stderr, "marionette run: %s\n", msg);
    close_outputs(&st);
    mr_scene_free(&scene);
    return MR_EXIT_FAIL;
  }
  int rc = run_show(&a, &scene, &st);
  if (mr_app_state_pub_close(st.pub, stdout) != 0 && rc == MR_EXIT_OK) rc = MR_EXIT_FAIL;
  mr_scene_free(&scene);
  return rc;
}
