/* The show in a window, as a theater box without a GPU runs it: the
 * humanoid for 20 s (5 s with --quick) under Xvfb, at 1280x720, driven by
 * glove-gen over a pty, on an idle machine and again beside two busy
 * processes (one per core of a 2-core box). From the show's summary: the
 * real-time factor, the show time given up to catch up, and the frames
 * drawn a second of wall time. */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"

extern char **environ;

/* glove-gen on a new pty for `seconds`; its slave path once it is open. */
static pid_t start_glove(const bench *b, double seconds, char *path, size_t size) {
  char file[1024], dur[32];
  snprintf(file, sizeof file, "%s/window-pty.txt", b->out);
  snprintf(dur, sizeof dur, "%g", seconds);
  remove(file);
  char *argv[] = { GLOVE_GEN_PATH, "-o", "pty",      "--path-file", file, "--wait", "30",
                   "-d",           dur,  "--linger", "0",           "-q", NULL };
  pid_t pid;
  if (posix_spawn(&pid, argv[0], NULL, NULL, argv, environ) != 0) return -1;
  for (int i = 0; i < 500; i++) {
    FILE *f = fopen(file, "r");
    if (f != NULL && fgets(path, (int)size, f) != NULL && strchr(path, '\n')) {
      path[strcspn(path, "\n")] = '\0';
      fclose(f);
      return pid;
    }
    if (f) fclose(f);
    nanosleep(&(struct timespec){ 0, 10000000 }, NULL);
  }
  kill(pid, SIGTERM);
  waitpid(pid, NULL, 0);
  return -1;
}

/* A process that only burns a core, as a box that also streams or
 * builds has. */
static pid_t start_busy(void) {
  pid_t pid = fork();
  if (pid == 0) {
    volatile unsigned long spin = 0;
    for (;;) spin++;
  }
  return pid;
}

/* The number after "key: " in the summary, or 0. */
static double field(const char *out, const char *key) {
  char pat[64];
  snprintf(pat, sizeof pat, "\n%s: ", key);
  const char *p = strstr(out, pat);
  return p != NULL ? strtod(p + strlen(pat), NULL) : 0.0;
}

/* One show with `busy` competing processes; 0 or -1. */
static int one_show(bench *b, int busy, double seconds) {
  char pty[512], cmd[2048];
  pid_t gen = start_glove(b, seconds * 20 + 30, pty, sizeof pty);
  if (gen < 0) {
    fprintf(stderr, "marionette-bench: window: glove-gen did not start\n");
    return -1;
  }
  pid_t spin[2] = { -1, -1 };
  for (int i = 0; i < busy && i < 2; i++) spin[i] = start_busy();
  snprintf(cmd, sizeof cmd,
           "xvfb-run -a -s '-screen 0 1280x720x24' '%s' run '%s/host/scenes/humanoid.yaml' "
           "--glove 'pty:%s' --time %g --size 1280x720 -q 2>/dev/null",
           MARIONETTE_PATH, b->root, pty, seconds);
  double w0 = bench_wall_seconds();
  FILE *p = popen(cmd, "r");
  static char out[16384];
  size_t n = p != NULL ? fread(out + 1, 1, sizeof out - 2, p) : 0;
  out[0] = '\n';
  out[n + 1] = '\0';
  int rc = p != NULL ? pclose(p) : -1;
  double wall = bench_wall_seconds() - w0;
  for (int i = 0; i < 2; i++)
    if (spin[i] > 0) {
      kill(spin[i], SIGKILL);
      waitpid(spin[i], NULL, 0);
    }
  kill(gen, SIGTERM);
  waitpid(gen, NULL, 0);
  if (rc != 0) {
    fprintf(stderr, "marionette-bench: window: marionette run failed (status %d)\n", rc);
    return -1;
  }
  double rtf = field(out, "real-time factor"), sim = field(out, "simulated");
  double shown = field(out, "frames shown"), given = field(out, "time given up to catch up");
  double show_wall = rtf > 0 ? sim / rtf : wall;
  bench_say(b, "  %-22s real-time factor %.3f, given up %.3f s, %.0f frames drawn, %.1f fps\n",
            busy ? "2 busy processes:" : "idle:", rtf, given, shown,
            show_wall > 0 ? shown / show_wall : 0.0);
  return 0;
}

int bench_window(bench *b) {
  if (system("command -v xvfb-run >/dev/null 2>&1") != 0) {
    bench_say(b, "window: skipped (no xvfb-run)\n");
    return 0;
  }
  double seconds = b->quick ? 5 : 20;
  bench_say(b, "window: humanoid, %g s at 1280x720 under Xvfb, glove-gen on a pty\n", seconds);
  bench_progress("window", "idle");
  int rc = one_show(b, 0, seconds);
  bench_progress("window", "beside two busy processes");
  rc |= one_show(b, 2, seconds);
  return rc;
}
