/* `marionette watch URL`: a remote audience. The scene retained on
 * TOPIC/scene is loaded (its files written to a folder of its own), and
 * the frames published on TOPIC (marionette run --publish) are drawn as
 * they come, a moment behind, between the two frames around each picture's
 * time; on a loss the last pose holds. A status line a second gives the
 * lag and the losses; a summary ends it. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "app.h"
#include "mr_state.h"
#include "watch_view.h"

static volatile sig_atomic_t stop_asked;

static void on_signal(int sig) {
  (void)sig;
  stop_asked = 1;
}

void mr_cmd_watch_usage(void) {
  printf("usage: marionette watch [OPTIONS] URL\n"
         "\n"
         "A remote audience: shows the show that marionette run --publish URL sends\n"
         "through a broker, mqtt[s]://[USER@]HOST[:PORT]/TOPIC (host/net/README.md).\n"
         "The scene comes from the broker (retained on TOPIC/scene, with its models),\n"
         "so a watcher may join at any time; each frame of TOPIC is drawn a moment\n"
         "behind (--delay), between the two frames around the picture's time; on a\n"
         "loss the last pose holds. With a display it is drawn in a window; with\n"
         "--headless (or no display) into PNG frames under -o DIR as marionette\n"
         "render writes them (or only the --mp4 or --sheet file named), and without\n"
         "a file to write only decoded. A status line a second\n"
         "gives the frames, the losses and the lag; a summary ends it. Ctrl-C, q\n"
         "or Esc ends it.\n"
         "\n"
         "options:\n"
         "%s"
         "  -t, --time SECONDS  end after this long (default: until Ctrl-C)\n"
         "  --wait SECONDS      how long to wait for the scene (default 10)\n"
         "  --delay SECONDS     how far behind the newest frame to draw (default 0.05)\n"
         "  --dump FILE         write each frame received: its seq, time, the\n"
         "                      quantisation step (x y z) and every particle's x y z\n"
         "  --headless          draw offscreen even with a display\n"
         "  -q, --quiet         no status lines, only the summary and errors\n"
         "  -h, --help          show this help\n"
         "\n"
         "exit status: 0 watched, 1 no scene came, the broker refused, or the stage\n"
         "failed, 2 bad usage, 3 the show was published from another definition of\n"
         "the state messages (another spec hash).\n",
         mr_stage_opts_help);
}

typedef struct watch_args {
  const char *url, *dump;
  double time, wait, delay;
  int headless, quiet, help;
  mr_stage_opts so;
} watch_args;

typedef struct watcher {
  watch_args *a;
  mr_state_in *in;
  mr_scene scene;
  bool have_scene, staged, anchored, told_refusal;
  uint64_t scene_hash;
  double fps, anchor; /* anchor: wall time minus the show time drawn */
  char dir[600];      /* where the scene's files were written */
  char **written;     /* those files, to remove at the end */
  size_t n_written;
  mr_watch_buffer buf;
  mr_watch_stage ws;
  double *points; /* room for points_n */
  size_t points_n;
  FILE *dump;
  double *lags;
  size_t n_lags, cap_lags;
  uint64_t held, draws;
  char msg[700];
} watcher;

static double wall_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int usage_error(const char *what, const char *v) {
  fprintf(stderr, "marionette watch: %s%s%s%s (see marionette watch --help)\n", what,
          v != NULL ? " '" : "", v != NULL ? v : "", v != NULL ? "'" : "");
  return MR_EXIT_USAGE;
}

static int number(const char *o, const char *v, double lo, double *out) {
  char *end = NULL;
  errno = 0;
  double x = strtod(v, &end);
  if (end == v || *end != '\0' || errno != 0 || !(x >= lo) || !isfinite(x)) {
    char what[80];
    snprintf(what, sizeof what, "expected %s a number of seconds, got", o);
    return usage_error(what, v);
  }
  *out = x;
  return -1;
}

/* -1 when the arguments are good, else the exit status. */
static int parse(int argc, char **argv, watch_args *a) {
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    int taken = mr_stage_opts_take(&a->so, "watch", argc, argv, &i, true);
    if (taken < 0) return MR_EXIT_USAGE;
    if (taken > 0) continue;
    bool valued = strcmp(o, "-t") == 0 || strcmp(o, "--time") == 0 || strcmp(o, "--wait") == 0 ||
                  strcmp(o, "--delay") == 0 || strcmp(o, "--dump") == 0;
    int rc = -1;
    if (strcmp(o, "-h") == 0 || strcmp(o, "--help") == 0) {
      a->help = 1;
    } else if (strcmp(o, "-q") == 0 || strcmp(o, "--quiet") == 0) {
      a->quiet = 1;
    } else if (strcmp(o, "--headless") == 0) {
      a->headless = 1;
    } else if (valued && i + 1 >= argc) {
      return usage_error("expected a value after", o);
    } else if (strcmp(o, "--dump") == 0) {
      a->dump = argv[++i];
    } else if (strcmp(o, "--wait") == 0) {
      rc = number(o, argv[++i], 0, &a->wait);
    } else if (strcmp(o, "--delay") == 0) {
      rc = number(o, argv[++i], 0, &a->delay);
    } else if (valued) {
      rc = number(o, argv[++i], 1e-3, &a->time);
    } else if (o[0] == '-' && o[1] != '\0') {
      return usage_error("unknown option", o);
    } else if (a->url == NULL) {
      a->url = o;
    } else {
      return usage_error("expected one URL, got a second:", o);
    }
    if (rc >= 0) return rc;
  }
  if (!a->help && a->url == NULL) return usage_error("expected the show's URL", NULL);
  if (!a->help && strncmp(a->url, "mqtt://", 7) != 0 && strncmp(a->url, "mqtts://", 8) != 0)
    return usage_error("expected mqtt[s]://HOST/TOPIC, got", a->url);
  return -1;
}

/* One file of the scene under w->dir, its folders made. */
static int write_one(watcher *w, const mr_state_file *f) {
  char path[1000];
  snprintf(path, sizeof path, "%s/%s", w->dir, f->name);
  char *slash = strrchr(path, '/');
  *slash = '\0';
  int rc = mr_make_dir(path);
  *slash = '/';
  FILE *out = rc == 0 ? fopen(path, "wb") : NULL;
  if (out == NULL) return snprintf(w->msg, sizeof w->msg, "cannot write %.600s", path), -1;
  bool bad = f->len > 0 && fwrite(f->data, 1, f->len, out) != f->len;
  bad |= fclose(out) != 0;
  char **more = realloc(w->written, (w->n_written + 1) * sizeof *more);
  if (more != NULL) {
    w->written = more;
    w->written[w->n_written] = strdup(path);
    if (w->written[w->n_written] != NULL) w->n_written++;
  }
  if (bad) return snprintf(w->msg, sizeof w->msg, "cannot write %.600s", path), -1;
  return 0;
}

/* The files written, and the folders they made, removed. */
static void remove_scene_files(watcher *w) {
  for (size_t i = 0; i < w->n_written; i++) {
    char *p = w->written[i];
    unlink(p);
    for (char *s = strrchr(p, '/'); s != NULL && strlen(p) > strlen(w->dir); s = strrchr(p, '/')) {
      *s = '\0';
      if (rmdir(p) != 0) break;
    }
    free(p);
  }
  free(w->written);
  w->written = NULL;
  w->n_written = 0;
  if (w->dir[0] != '\0') rmdir(w->dir);
}

/* The SCENE's files written to a folder of their own and the scene (the
 * first file) loaded from there, as a show loads it beside its models. */
static int load_scene(watcher *w, const mr_state_scene *s) {
  const char *tmp = getenv("TMPDIR");
  snprintf(w->dir, sizeof w->dir, "%s/marionette-watch-XXXXXX", tmp != NULL ? tmp : "/tmp");
  if (mkdtemp(w->dir) == NULL) {
    snprintf(w->msg, sizeof w->msg, "cannot make a folder for the scene: %s", strerror(errno));
    w->dir[0] = '\0';
    return -1;
  }
  size_t off = 0;
  mr_state_file f;
  char first[MR_STATE_NAME_MAX] = "";
  int got;
  while ((got = mr_state_bundle_next(s->files, s->size, &off, &f)) == 1) {
    if (first[0] == '\0') snprintf(first, sizeof first, "%s", f.name);
    if (write_one(w, &f) != 0) return -1;
  }
  if (got < 0 || first[0] == '\0')
    return snprintf(w->msg, sizeof w->msg, "the scene's files are malformed"), -1;
  char path[1200];
  snprintf(path, sizeof path, "%s/%s", w->dir, first);
  mr_scene_error err;
  if (mr_scene_load(path, &w->scene, &err) != MR_SCENE_OK)
    return snprintf(w->msg, sizeof w->msg, "the published scene: %.600s", err.text), -1;
  w->have_scene = true;
  w->scene_hash = s->scene_hash;
  w->fps = s->fps > 0 && s->fps <= 1000 ? s->fps : 60.0;
  return 0;
}

/* The line a refused message earns, once. */
static void tell_refusal(watcher *w, const mr_state_event *ev) {
  if (w->told_refusal) return;
  w->told_refusal = true;
  fprintf(stderr,
          "marionette watch: %s: a state message built from another definition (spec hash "
          "0x%08" PRIX32 ", this program's 0x%08X): refused; the show and the watcher must be "
          "built from the same host/net/state.def\n",
          w->a->url, ev->hash, MR_STATE_SPEC_HASH);
}

/* Waits for the scene. 0; else the exit status after one line. */
static int await_scene(watcher *w) {
  double end = wall_now() + w->a->wait;
  mr_io_error err;
  while (!w->have_scene && !stop_asked) {
    double left = end - wall_now();
    if (left <= 0) break;
    mr_state_event ev;
    if (mr_state_in_read(w->in, (int)ceil(left * 1e3), &ev, &err) != MR_IO_OK) {
      fprintf(stderr, "marionette watch: %s\n", err.msg);
      return MR_EXIT_FAIL;
    }
    if (ev.kind == MR_STATE_REFUSED) {
      tell_refusal(w, &ev);
      if (ev.type == MR_STATE_SCENE) return MR_EXIT_MISMATCH;
    } else if (ev.kind == MR_STATE_GOT_SCENE && load_scene(w, &ev.scene) != 0) {
      fprintf(stderr, "marionette watch: %s\n", w->msg);
      return MR_EXIT_FAIL;
    }
  }
  if (w->have_scene) return 0;
  fprintf(stderr,
          "marionette watch: %s: no scene within %g s (is marionette run --publish sending to "
          "it?)\n",
          w->a->url, w->a->wait);
  return MR_EXIT_FAIL;
}

static void dump_frame(watcher *w, const mr_state_event *ev) {
  const mr_state_frame *m = &ev->frame;
  fprintf(w->dump, "%" PRIu32 " %.6f %.9g %.9g %.9g", m->seq, ev->t, (double)m->step[0],
          (double)m->step[1], (double)m->step[2]);
  for (size_t i = 0; i < 3 * (size_t)m->n_points; i++) fprintf(w->dump, " %.9g", ev->xyz[i]);
  fputc('\n', w->dump);
}

static void keep_lag(watcher *w, double lag) {
  if (w->n_lags == w->cap_lags) {
    size_t cap = w->cap_lags > 0 ? 2 * w->cap_lags : 1024;
    double *p = cap <= 10000000 ? realloc(w->lags, cap * sizeof *p) : NULL;
    if (p == NULL) return;
    w->lags = p;
    w->cap_lags = cap;
  }
  w->lags[w->n_lags++] = lag;
}

/* A frame received: dumped, kept for drawing, its lag noted; the clock
 * that picks what is drawn anchored on it when it was not (or had
 * drifted a second from it: a stall, a restarted show). */
static void on_frame(watcher *w, const mr_state_event *ev, double now) {
  if (w->dump != NULL) dump_frame(w, ev);
  keep_lag(w, ev->lag);
  mr_watch_buffer_push(&w->buf, ev->t, ev->xyz, ev->frame.n_points);
  double drawn_t = now - w->anchor;
  if (!w->anchored || fabs(drawn_t - (ev->t - w->a->delay)) > 1.0) {
    w->anchor = now - ev->t + w->a->delay;
    w->anchored = true;
  }
}

/* One picture at the show time the clock says. */
static int draw(watcher *w, double now) {
  if (!w->staged || w->buf.count == 0) return 0;
  if (w->points == NULL || w->points_n != w->buf.n) { /* the buffer may start again */
    free(w->points);
    w->points = malloc(3 * (w->buf.n + 1) * sizeof(double));
    w->points_n = w->buf.n;
  }
  if (w->points == NULL) return snprintf(w->msg, sizeof w->msg, "out of memory"), -1;
  double t = now - w->anchor;
  int got = mr_watch_buffer_at(&w->buf, t, w->points);
  if (got < 0) return 0;
  w->draws++;
  if (got == 1) w->held++;
  return mr_watch_stage_draw(&w->ws, t, w->points, w->buf.n, w->msg, sizeof w->msg);
}

static void status_line(const watcher *w, double elapsed) {
  mr_state_in_counters c;
  mr_state_in_get_counters(w->in, &c);
  double lag = w->n_lags > 0 ? w->lags[w->n_lags - 1] : 0.0;
  printf("t %.0f s: %" PRIu64 " frames received, %" PRIu64 " lost, %" PRIu64 " corrupt, %" PRIu64
         " drawn (%" PRIu64 " held), lag %.1f ms\n",
         elapsed, c.frames, c.lost, c.corrupt, w->draws, w->held, lag * 1e3);
  fflush(stdout);
}

/* One event handled, waiting up to timeout_ms for it: 1 handled, 0 none
 * came, -1 (after the line) when the link failed for good. */
static int handle(watcher *w, int timeout_ms) {
  mr_state_event ev;
  mr_io_error err;
  if (mr_state_in_read(w->in, timeout_ms, &ev, &err) != MR_IO_OK) {
    fprintf(stderr, "marionette watch: %s\n", err.msg);
    return -1;
  }
  if (ev.kind == MR_STATE_GOT_FRAME)
    on_frame(w, &ev, wall_now());
  else if (ev.kind == MR_STATE_REFUSED)
    tell_refusal(w, &ev);
  else if (ev.kind == MR_STATE_GOT_SCENE && ev.scene.scene_hash != w->scene_hash && !w->a->quiet)
    fprintf(stderr,
            "marionette watch: %s: another scene was published; this watcher shows the "
            "first (start it again for the new one)\n",
            w->a->url);
  else if (ev.kind == MR_STATE_BROKER_LOST && !w->a->quiet)
    fprintf(stderr,
            "marionette watch: %s: the broker went away; reconnecting (the last pose "
            "holds)\n",
            w->a->url);
  return ev.kind != MR_STATE_NOTHING;
}

/* Everything received so far handled (a bounded number): 0, or -1. */
static int drain(watcher *w) {
  int got = 1;
  for (int k = 0; got == 1 && k < 100000; k++) got = handle(w, 0);
  return got < 0 ? -1 : 0;
}

/* Frames in, pictures out at the scene's rate, until the time is up: what
 * came is all taken before each picture, so a slow picture costs pictures
 * (skipped, as the show's scheduler skips), never frames. */
static int watch_loop(watcher *w) {
  double start = wall_now(), period = 1.0 / w->fps, next = start, next_line = start + 1.0;
  double end = w->a->time > 0 ? start + w->a->time : INFINITY;
  for (double now = start; !stop_asked && !w->ws.quit && now < end; now = wall_now()) {
    if (drain(w) != 0) return MR_EXIT_FAIL;
    now = wall_now();
    if (now >= next) {
      mr_watch_stage_pump(&w->ws);
      if (draw(w, now) != 0) {
        fprintf(stderr, "marionette watch: %s\n", w->msg);
        return MR_EXIT_FAIL;
      }
      next += period;
      if (next < now) next = now + period;
    } else if (handle(w, (int)ceil((fmin(next, end) - now) * 1e3)) < 0) {
      return MR_EXIT_FAIL;
    }
    if (!w->a->quiet && now >= next_line) {
      status_line(w, now - start);
      next_line += 1.0;
    }
  }
  return drain(w) != 0 ? MR_EXIT_FAIL : MR_EXIT_OK;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

static void summary(watcher *w) {
  mr_state_in_counters c;
  mr_state_in_get_counters(w->in, &c);
  printf("scene: %s (hash %016" PRIx64 ")\n", w->scene.name, w->scene_hash);
  printf("frames received: %" PRIu64 "\n", c.frames);
  printf("frames lost: %" PRIu64 "\n", c.lost);
  printf("messages corrupt: %" PRIu64 "\n", c.corrupt);
  printf("messages refused: %" PRIu64 " (another spec hash)\n", c.refused);
  printf("messages stale: %" PRIu64 "\n", c.stale);
  printf("messages oversized: %" PRIu64 "\n", c.oversized);
  printf("messages dropped behind: %" PRIu64 "\n", c.queue_full);
  printf("broker losses: %" PRIu64 "\n", c.broker_lost);
  printf("bytes received: %" PRIu64 "\n", c.bytes);
  printf("pictures: %" PRIu64 " (%" PRIu64 " held the last pose)\n", w->draws, w->held);
  if (w->n_lags > 0) {
    qsort(w->lags, w->n_lags, sizeof *w->lags, cmp_double);
    printf("lag p50: %.1f ms\n", 1e3 * w->lags[(w->n_lags - 1) / 2]);
    printf("lag p99: %.1f ms\n", 1e3 * w->lags[(size_t)floor(0.99 * (double)(w->n_lags - 1))]);
    printf("lag max: %.1f ms\n", 1e3 * w->lags[w->n_lags - 1]);
  }
}

/* The stage, when there is one to draw on: a window (a display, no
 * --headless), or files to write. 0, or the exit status after one line. */
static int open_stage(watcher *w) {
  const char *x = getenv("DISPLAY"), *wl = getenv("WAYLAND_DISPLAY");
  bool window = !w->a->headless && ((x != NULL && x[0]) || (wl != NULL && wl[0]));
  if (!window && !mr_stage_opts_writes(&w->a->so)) return 0;
  int usage = 0;
  if (mr_watch_stage_open(&w->ws, &w->scene, &w->a->so, window, w->fps, w->msg, sizeof w->msg,
                          &usage) != 0) {
    if (usage) return w->msg[0] ? usage_error(w->msg, NULL) : MR_EXIT_USAGE;
    fprintf(stderr, "marionette watch: %s\n", w->msg);
    return MR_EXIT_FAIL;
  }
  w->staged = true;
  return 0;
}

static int watch(watcher *w) {
  int rc = await_scene(w);
  if (rc == 0) rc = open_stage(w);
  if (rc != 0) return rc;
  rc = watch_loop(w);
  if (w->staged) {
    mr_frames_out_summary s;
    char msg[700] = "";
    if (mr_watch_stage_close(&w->ws, &s, msg, sizeof msg) != 0 && rc == 0) {
      fprintf(stderr, "marionette watch: %s\n", msg);
      rc = MR_EXIT_FAIL;
    }
    if (s.pngs > 0) printf("png frames: %" PRIu64 " in %s\n", s.pngs, w->a->so.out);
  }
  summary(w);
  return rc;
}

int mr_cmd_watch(int argc, char **argv) {
  static watch_args a; /* large */
  memset(&a, 0, sizeof a);
  a.wait = 10.0;
  a.delay = 0.05;
  mr_stage_opts_init(&a.so);
  int rc = parse(argc, argv, &a);
  if (rc >= 0) return rc;
  if (a.help) return mr_cmd_watch_usage(), MR_EXIT_OK;
  static watcher w;
  memset(&w, 0, sizeof w);
  w.a = &a;
  if (a.dump != NULL && (w.dump = fopen(a.dump, "w")) == NULL)
    return fprintf(stderr, "marionette watch: cannot write %s\n", a.dump), MR_EXIT_FAIL;
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
  mr_state_in_def d = mr_default_state_in_def();
  d.url = a.url;
  mr_io_error err;
  if (mr_state_in_open(&d, &w.in, &err) != 0) {
    fprintf(stderr, "marionette watch: %s\n", err.msg);
    rc = MR_EXIT_FAIL;
  } else {
    rc = watch(&w);
  }
  if (w.dump != NULL && fclose(w.dump) != 0 && rc == MR_EXIT_OK) {
    fprintf(stderr, "marionette watch: could not write all of %s\n", a.dump);
    rc = MR_EXIT_FAIL;
  }
  mr_state_in_close(w.in);
  mr_watch_buffer_free(&w.buf);
  if (w.have_scene) mr_scene_free(&w.scene);
  remove_scene_files(&w);
  free(w.points);
  free(w.lags);
  return rc;
}
