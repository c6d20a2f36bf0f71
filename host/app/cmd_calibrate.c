/* `marionette calibrate --glove SRC`: walks the puppeteer through a
 * calibration (hardware/calibration.md): CAL_START, an open hand, a fist,
 * then each finger alone, with the range each string has covered shown as
 * it grows, and CAL_SAVE, after which the glove announces the range it
 * stored. Each step ends on Enter, or after --step-time seconds. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "mr_glove.h"
#include "mr_io.h"

static volatile sig_atomic_t stop_asked;

static void on_signal(int sig) {
  (void)sig;
  stop_asked = 1;
}

void mr_cmd_calibrate_usage(void) {
  printf("usage: marionette calibrate --glove SOURCE [--step-time SECONDS]\n"
         "\n"
         "Calibrates a glove: it starts a capture on the glove (CAL_START), asks for\n"
         "an open hand, a fist, then each finger bent alone, showing the range each\n"
         "string has covered so far, and saves the capture on the glove (CAL_SAVE).\n"
         "The glove then announces the range it stored, which is printed. Each step\n"
         "ends when Enter is pressed.\n"
         "\n"
         "options:\n"
         "  --glove SOURCE        serial:/dev/ttyACM0[@BAUD], serial:auto, pty:PATH,\n"
         "                        tcp:HOST:PORT, tcp-listen:PORT or\n"
         "                        mqtt[s]://[USER@]HOST[:PORT]/TOPIC (required)\n"
         "  --step-time SECONDS   end each step after this long instead of on Enter\n"
         "                        (for scripts)\n"
         "  -h, --help            show this help\n"
         "\n"
         "exit status: 0 saved, 1 the glove did not answer or refused (the line says\n"
         "which and why), 2 bad usage, 3 the glove was built from another protocol\n"
         "definition.\n");
}

static const char *const steps[] = { "Open your hand wide and hold it",
                                     "Make a tight fist",
                                     "Open the hand, then bend the thumb alone",
                                     "Bend the index finger alone",
                                     "Bend the middle finger alone",
                                     "Bend the ring finger alone",
                                     "Bend the little finger alone" };

typedef struct calib {
  mr_glove *g;
  double t0;
  bool tty; /* stdout: the range line is redrawn in place */
  double lo[MR_GLOVE_CHANNELS], hi[MR_GLOVE_CHANNELS];
  uint64_t seen;
} calib;

static double now_s(const calib *c) {
  return (double)mr_io_monotonic_ns() * 1e-9 - c->t0;
}

/* Polls the glove for about 50 ms and widens the ranges by what came. */
static void poll_glove(calib *c) {
  mr_glove_poll(c->g, now_s(c), 50);
  mr_glove_reading r;
  mr_glove_latest(c->g, &r);
  if (r.samples == c->seen) return;
  c->seen = r.samples;
  for (int k = 0; k < MR_GLOVE_CHANNELS; k++) {
    c->lo[k] = fmin(c->lo[k], r.values[k]);
    c->hi[k] = fmax(c->hi[k], r.values[k]);
  }
}

static int fail(const calib *c, const char *why) {
  char said[400];
  fprintf(stderr, "marionette calibrate: %s (%s)\n", why,
          mr_glove_describe(c->g, now_s(c), said, sizeof said));
  return mr_glove_get_state(c->g) == MR_GLOVE_MISMATCH ? MR_EXIT_MISMATCH : MR_EXIT_FAIL;
}

/* Sends a command and polls until it is answered; 0 when ACKed, else the
 * exit status after one line saying what happened. */
static int command(calib *c, uint8_t type) {
  mr_glove_cmd cmd = { type, 0, 0 };
  char msg[300], why[400];
  int tag = mr_glove_command(c->g, &cmd, now_s(c), msg, sizeof msg);
  if (tag < 0) return fail(c, msg);
  mr_glove_cmd_result r = mr_glove_command_result(c->g, tag);
  while (r.state == MR_GLOVE_CMD_PENDING && !stop_asked) {
    poll_glove(c);
    r = mr_glove_command_result(c->g, tag);
  }
  if (r.state == MR_GLOVE_CMD_ACKED) return 0;
  if (stop_asked) return fail(c, "stopped before the glove answered; nothing was saved");
  if (r.state == MR_GLOVE_CMD_NACKED)
    snprintf(why, sizeof why, "the glove refused %s: %s%s", mr_glove_cmd_name(type),
             mr_glove_nack_reason_name(r.nack_reason),
             type == GP_CAL_SAVE && r.nack_reason == GP_NACK_BAD_ARGUMENT
                 ? " (a string hardly moved: check its sensor and go again)"
                 : "");
  else
    snprintf(why, sizeof why, "%s was not answered after %d tries", mr_glove_cmd_name(type),
             r.sends);
  return fail(c, why);
}

static void show_ranges(const calib *c) {
  printf(c->tty ? "\r  covered:" : "  covered:");
  for (int k = 0; k < MR_GLOVE_CHANNELS; k++)
    printf(" %3.0f-%3.0f%%", 100 * fmin(c->lo[k], c->hi[k]), 100 * c->hi[k]);
  if (!c->tty) printf("\n");
  fflush(stdout);
}

/* Enter on stdin, without blocking the glove's reading. */
static bool enter_pressed(void) {
  struct pollfd p = { STDIN_FILENO, POLLIN, 0 };
  if (poll(&p, 1, 0) <= 0) return false;
  char line[256];
  return fgets(line, sizeof line, stdin) != NULL || true;
}

static int walk(calib *c, double step_time) {
  for (size_t i = 0; i < sizeof steps / sizeof steps[0]; i++) {
    printf("%zu/%zu  %s%s\n", i + 1, sizeof steps / sizeof steps[0], steps[i],
           step_time > 0 ? "" : ", then press Enter.");
    fflush(stdout);
    double end = now_s(c) + step_time, next_show = 0;
    while (!stop_asked && (step_time > 0 ? now_s(c) < end : !enter_pressed())) {
      poll_glove(c);
      if (now_s(c) >= next_show && c->tty) {
        show_ranges(c);
        next_show = now_s(c) + 0.2;
      }
      if (mr_glove_get_state(c->g) == MR_GLOVE_LOST) return fail(c, "the glove went away");
    }
    if (c->tty) printf("\n");
    show_ranges(c);
    if (stop_asked) return fail(c, "stopped; nothing was saved");
  }
  return 0;
}

static int parse(int argc, char **argv, const char **source, double *step_time) {
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    if (strcmp(o, "-h") == 0 || strcmp(o, "--help") == 0) {
      mr_cmd_calibrate_usage();
      return MR_EXIT_OK;
    }
    bool valued = strcmp(o, "--glove") == 0 || strcmp(o, "--step-time") == 0;
    if (!valued || i + 1 >= argc) {
      fprintf(stderr, "marionette calibrate: %s '%s' (see marionette calibrate --help)\n",
              valued ? "expected a value after" : "unknown argument", o);
      return MR_EXIT_USAGE;
    }
    const char *v = argv[++i];
    if (strcmp(o, "--glove") == 0) {
      *source = v;
      continue;
    }
    char *end = NULL;
    *step_time = strtod(v, &end);
    if (end == v || *end != '\0' || !(*step_time > 0 && *step_time <= 600)) {
      fprintf(stderr, "marionette calibrate: expected --step-time between 0 and 600 s, got '%s'\n",
              v);
      return MR_EXIT_USAGE;
    }
  }
  if (*source == NULL) {
    fprintf(stderr, "marionette calibrate: expected --glove SOURCE (see marionette calibrate "
                    "--help)\n");
    return MR_EXIT_USAGE;
  }
  return -1;
}

/* The range the glove stored, from the INFO that follows CAL_SAVE. */
static int report(calib *c) {
  double end = now_s(c) + 2;
  const gp_info *info = mr_glove_info(c->g);
  while ((info == NULL || info->cal_state != GP_CAL_VALID) && now_s(c) < end) {
    poll_glove(c);
    info = mr_glove_info(c->g);
  }
  if (info == NULL || info->cal_state != GP_CAL_VALID)
    return fail(c, "the glove acknowledged CAL_SAVE but announced no saved range");
  static const char *const finger[] = { "thumb", "index", "middle", "ring", "little" };
  printf("saved on the glove (raw ADC counts):\n");
  for (int k = 0; k < MR_GLOVE_CHANNELS; k++)
    printf("  %-6s %5u .. %5u\n", finger[k], (unsigned)info->cal_min[k],
           (unsigned)info->cal_max[k]);
  return MR_EXIT_OK;
}

int mr_cmd_calibrate(int argc, char **argv) {
  const char *source = NULL;
  double step_time = 0;
  int rc = parse(argc, argv, &source, &step_time);
  if (rc >= 0) return rc;
  mr_glove_def d = mr_default_glove_def();
  snprintf(d.source, sizeof d.source, "%s", source);
  calib c;
  memset(&c, 0, sizeof c);
  char msg[400];
  if (mr_glove_create(&d, &c.g, msg, sizeof msg) != MR_GLOVE_OK) {
    fprintf(stderr, "marionette calibrate: %s\n", msg);
    return MR_EXIT_FAIL;
  }
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
  c.t0 = (double)mr_io_monotonic_ns() * 1e-9;
  c.tty = isatty(STDOUT_FILENO) != 0;
  for (int k = 0; k < MR_GLOVE_CHANNELS; k++) c.lo[k] = INFINITY, c.hi[k] = -INFINITY;
  /* A source that has ended (a file read to its end) will never stream:
   * its reads return at once, and waiting out the 5 s spun a core. */
  while (mr_glove_get_state(c.g) != MR_GLOVE_LIVE && now_s(&c) < 5 && !stop_asked &&
         !mr_glove_ended(c.g)) {
    poll_glove(&c);
    if (mr_glove_get_state(c.g) == MR_GLOVE_MISMATCH) break;
  }
  if (mr_glove_get_state(c.g) != MR_GLOVE_LIVE)
    rc = fail(&c, "no glove is streaming there");
  else if ((rc = command(&c, GP_CAL_START)) == 0 && (rc = walk(&c, step_time)) == 0 &&
           (rc = command(&c, GP_CAL_SAVE)) == 0)
    rc = report(&c);
  mr_glove_destroy(c.g);
  return rc;
}
