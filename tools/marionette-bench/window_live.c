/* The show as a puppeteer runs it: `marionette run` of the humanoid in a
 * window at 1280x720, driven by glove-gen at 250 Hz over a pty, for 20 s
 * of wall time (5 with --quick), once on an idle machine and once with as
 * many busy processes as there are cores beside it (a box that also
 * streams, records or serves). Without a display the window is opened on
 * a virtual X server (xvfb-run), as a box without a GPU draws in software.
 *
 * The figures are the program's own summary: the real-time factor (show
 * time over wall time), the show time given up to catch up, the frames
 * drawn a second, and the latency from a glove sample to the frame that
 * shows it, p50 and p99. */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"

extern char **environ;

enum { MAX_BUSY = 64 };

/* A process that only spins, until killed. */
static pid_t busy_start(void) {
  pid_t pid = fork();
  if (pid == 0) {
    volatile unsigned long spin = 0;
    for (;;) spin++;
  }
  return pid;
}

static void stop(pid_t pid, int sig) {
  if (pid <= 0) return;
  kill(pid, sig);
  waitpid(pid, NULL, 0);
}

/* The number after "key: " in text, or NAN. */
static double field(const char *text, const char *key) {
  char pat[96];
  snprintf(pat, sizeof pat, "\n%s: ", key);
  const char *p = strstr(text, pat);
  return p ? strtod(p + strlen(pat), NULL) : NAN;
}

static char *slurp(const char *path) {
  FILE *f = fopen(path, "rb");
  if (f == NULL) return NULL;
  size_t cap = 1 << 16, n = 0;
  char *text = malloc(cap + 2);
  text[n++] = '\n'; /* so the first line matches "\nkey: " too */
  for (size_t got; text && (got = fread(text + n, 1, cap - n, f)) > 0; n += got) {
    if (n + got < cap) continue;
    char *more = realloc(text, 2 * cap + 2);
    if (more == NULL) break;
    text = more;
    cap *= 2;
  }
  fclose(f);
  if (text) text[n] = '\0';
  return text;
}

/* `marionette run` of scene on glove pty `path`, its output into out/log;
 * the exit status, or -1. */
static int run_show(const char *scene, const char *path, double seconds, const char *log) {
  char glove[600], secs[32];
  snprintf(glove, sizeof glove, "pty:%s", path);
  snprintf(secs, sizeof secs, "%g", seconds);
  char *direct[] = { MARIONETTE_PATH, "run",      (char *)scene, "--glove", glove, "-t", secs,
                     "--size",        "1280x720", NULL };
  char *virtual_x[] = { "xvfb-run",      "-a",  "-s",          "-screen 0 1280x720x24",
                        MARIONETTE_PATH, "run", (char *)scene, "--glove",
                        glove,           "-t",  secs,          "--size",
                        "1280x720",      NULL };
  const char *display = getenv("DISPLAY");
  char **argv = display != NULL && *display != '\0' ? direct : virtual_x;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid;
  int rc = posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* One show beside `busy` spinning processes; a line of figures. */
static int one_show(bench *b, const char *scene, double seconds, int busy) {
  pid_t spin[MAX_BUSY];
  int n_spin = 0;
  for (; n_spin < busy && n_spin < MAX_BUSY; n_spin++) spin[n_spin] = busy_start();
  char path[512], log[1024];
  snprintf(log, sizeof log, "%s/window-%d-busy.log", b->out, busy);
  pid_t gen = bench_glove_gen_start(b, "window", seconds * 4 + 30, path, sizeof path);
  int status = gen < 0 ? -1 : run_show(scene, path, seconds, log);
  stop(gen, SIGTERM);
  for (int i = 0; i < n_spin; i++) stop(spin[i], SIGKILL);
  char *text = slurp(log);
  double rt = text ? field(text, "real-time factor") : NAN;
  if (status != 0 || text == NULL || !(rt > 0)) {
    bench_say(b, "window, %d busy: the run failed (status %d); its output is in %s\n", busy, status,
              log);
    free(text);
    return -1;
  }
  double shown = field(text, "frames shown"), sim = field(text, "simulated");
  /* The run prints the time given up only when some was. */
  double given = field(text, "time given up to catch up");
  if (isnan(given)) given = 0.0;
  double p50 = field(text, "latency p50"), p99 = field(text, "latency p99");
  /* Wall time is show time over the real-time factor. */
  double fps = shown / (sim / rt);
  char label[48] = "idle";
  if (busy > 0) snprintf(label, sizeof label, "%d busy processes beside", busy);
  bench_say(b, "%-26s %9.3f %12.3f %10.1f %9.1f %9.1f\n", label, rt, given, fps, p50, p99);
  free(text);
  return 0;
}

int bench_window(bench *b) {
  const char *display = getenv("DISPLAY");
  if ((display == NULL || *display == '\0') && system("command -v xvfb-run >/dev/null 2>&1") != 0) {
    bench_say(b, "\nwindow: skipped (no display and no xvfb-run)\n");
    return 0;
  }
  const double seconds = b->quick ? 5.0 : 20.0;
  char scene[1024];
  snprintf(scene, sizeof scene, "%s/host/scenes/humanoid.yaml", b->root);
  long cores = sysconf(_SC_NPROCESSORS_ONLN);
  int busy = cores > 0 && cores <= MAX_BUSY ? (int)cores : 2;
  bench_say(b,
            "\n== the show in a window (humanoid, 1280x720, glove-gen over a pty, %g s) ==\n"
            "%-26s %9s %12s %10s %9s %9s\n",
            seconds, "machine", "real-time", "given up, s", "drawn fps", "p50, ms", "p99, ms");
  bench_progress("window", "idle, %g s", seconds);
  int rc = one_show(b, scene, seconds, 0);
  bench_progress("window", "%d busy processes beside it, %g s", busy, seconds);
  if (one_show(b, scene, seconds, busy) != 0) rc = -1;
  return rc;
}
