/* glove-gen: synthetic glove streams for testers. See --help and
 * tools/README.md. The options are read in options.c; here the gloves are
 * opened, streamed slot by slot, and closed. */
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "gg_motion.h"
#include "gg_answer.h"
#include "gg_stream.h"
#include "gp.h"
#include "mr_io.h"
#include "options.h"

static volatile sig_atomic_t g_stop;
static int g_quiet; /* -q: no messages but errors */

static void on_signal(int sig) {
  (void)sig;
  g_stop = 1;
}

static void sleep_until_ns(uint64_t t) {
  struct timespec ts = { (time_t)(t / 1000000000ull), (long)(t % 1000000000ull) };
  while (!g_stop && clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) == EINTR) {
  }
}

typedef struct glove {
  const char *spec;
  const char *truth_path, *record_path;
  mr_io io;
  int open;
  gg_motion motion;
  gg_stream stream;
  gg_answer answer; /* to the host's commands, on a two-way output */
  int duplex;
  FILE *truth;
  mr_rec_writer rec;
  int recording;
  int gone; /* its reader left */
  uint64_t frames_written;
} glove;

/* Writes one slot's bytes, riding out signals; 0, 1 once the reader is gone
 * (it ended its read, as `marionette run -t` or `head` do: not an error),
 * or -1 when the output failed. */
static int send_bytes(glove *g, int idx, const uint8_t *buf, size_t len, uint64_t t_ns) {
  mr_io_error err;
  size_t off = 0;
  if (g->recording && len) {
    if (mr_rec_writer_add(&g->rec, t_ns, buf, len, &err) != 0) {
      fprintf(stderr, "glove-gen: glove %d: %s\n", idx, err.msg);
      return -1;
    }
  }
  while (off < len) {
    size_t sent = 0;
    mr_io_status st = mr_io_write(&g->io, buf + off, len - off, 1000, &sent, &err);
    off += sent;
    if (st == MR_IO_OK) break;
    if (st == MR_IO_TIMEOUT) {
      if (g_stop) return -1;
      continue;
    }
    g->gone = 1;
    if (st == MR_IO_HANGUP) {
      if (!g_quiet)
        fprintf(stderr, "glove-gen: glove %d: %s: the reader left after %llu slots; stopping\n",
                idx, mr_io_path(&g->io), (unsigned long long)g->stream.slot);
      return 1;
    }
    fprintf(stderr, "glove-gen: glove %d: %s\n", idx, err.msg);
    return -1;
  }
  return 0;
}

/* Outputs that carry bytes both ways: there the host may send commands. */
static int is_duplex(const char *spec) {
  return strcmp(spec, "pty") == 0 || strncmp(spec, "tcp:", 4) == 0 ||
         strncmp(spec, "tcp-listen:", 11) == 0 || strncmp(spec, "serial:", 7) == 0;
}

/* The host's commands that have arrived, answered at once. */
static void answer_host(glove *g, int idx, uint64_t t_ns) {
  uint8_t in[512], out[4 * 4 * GP_MAX_WIRE];
  for (int round = 0; round < 4 && !g->gone; round++) {
    size_t got = 0;
    mr_io_error err;
    mr_io_status st = mr_io_read(&g->io, in, sizeof in, 0, &got, &err);
    if (got > 0) {
      size_t n = gg_answer_feed(&g->answer, &g->stream, in, got, out, sizeof out);
      if (n > 0 && send_bytes(g, idx, out, n, t_ns) != 0) return;
    }
    if (st != MR_IO_OK || got < sizeof in) return;
  }
}

/* Each glove's motion, and the slots they run for: -1, or 1 when a script
 * does not load. */
static int load_motions(glove *gloves, options *o) {
  for (int i = 0; i < o->n_out; i++) {
    glove *g = &gloves[i];
    char err[600];
    uint64_t gseed = o->seed * 0x100000001B3ull + (uint64_t)i;
    g->spec = o->specs[i];
    g->truth_path = o->n_truth ? o->truths[i] : NULL;
    g->record_path = o->n_rec ? o->records[i] : NULL;
    if (o->script) {
      if (gg_motion_load(&g->motion, o->script, gseed, err, sizeof err) != 0) {
        fprintf(stderr, "glove-gen: %s\n", err);
        return 1;
      }
    } else {
      gg_motion_default(&g->motion, gseed);
    }
  }
  if (!o->have_count) {
    double secs = o->duration > 0 ? o->duration : gloves[0].motion.duration_s;
    o->count = secs > 0 ? (uint64_t)llround(secs * o->rate) : UINT64_MAX;
    if (o->count == 0) o->count = 1;
  }
  return -1;
}

/* Glove i's stream: its own uid, hand and fault seed. */
static gg_stream_config stream_config(const options *o, int i) {
  gg_stream_config cfg;
  memset(&cfg, 0, sizeof cfg);
  cfg.rate_hz = o->rate;
  cfg.count = o->count;
  cfg.spec_hash = (uint32_t)o->spec_hash;
  cfg.hand = (uint8_t)(i < o->n_hand ? o->hands[i] : (i % 2 ? GP_HAND_LEFT : GP_HAND_RIGHT));
  cfg.uid[0] = (uint32_t)((o->have_uid ? o->uid0 : 0x4D520000u) + (uint64_t)i);
  cfg.uid[1] = (uint32_t)(o->seed * 2654435761u);
  cfg.uid[2] = (uint32_t)(o->seed >> 32) ^ 0x474C4F56u;
  cfg.baud = (uint32_t)o->baud;
  memcpy(cfg.rates, o->rates, sizeof o->rates);
  cfg.stall_min = o->stall_min;
  cfg.stall_max = o->stall_max;
  cfg.seed = o->seed * 0x100000001B3ull + (uint64_t)i;
  return cfg;
}

/* Opens glove i's output (checked first, as glove-dump checks its source:
 * a device that is not there is the user's usage too); -1, or the exit
 * code. */
static int open_output(glove *g, int i, const options *o) {
  mr_io_error err;
  g->duplex = is_duplex(g->spec);
  int mode = g->duplex ? MR_IO_READ | MR_IO_WRITE : MR_IO_WRITE;
  if (mr_io_spec_check(g->spec, mode, NULL, 0, &err) != 0 ||
      mr_io_open(&g->io, g->spec, mode, &err) != 0) {
    /* An output spec that does not parse is the user's usage. */
    fprintf(stderr, "glove-gen: %s%s\n", err.msg,
            err.status == MR_IO_ERR_SPEC ? " (see --help)" : "");
    return err.status == MR_IO_ERR_SPEC ? 2 : 1;
  }
  g->open = 1;
  if (!o->quiet && (g->io.kind == MR_IO_PTY || g->io.kind == MR_IO_TCP_LISTEN))
    fprintf(stderr, "glove-gen: glove %d: %s %s\n", i,
            g->io.kind == MR_IO_PTY ? "pty" : "listening on", mr_io_path(&g->io));
  return -1;
}

/* Glove i ready to stream: its output, truth file and recording open; -1,
 * or the exit code. */
static int open_glove(glove *g, int i, const options *o) {
  mr_io_error err;
  int rc = open_output(g, i, o);
  if (rc >= 0) return rc;
  gg_stream_config cfg = stream_config(o, i);
  if (g->truth_path && !(g->truth = fopen(g->truth_path, "w"))) {
    fprintf(stderr, "glove-gen: %s: cannot create: %s\n", g->truth_path, strerror(errno));
    return 1;
  }
  if (g->truth)
    fprintf(g->truth, "# glove-gen truth: intact SAMPLE frames (sample SEQ T_US CH0..CH4), "
                      "then the expected decoder counters\n");
  if (g->record_path) {
    if (mr_rec_writer_open(&g->rec, g->record_path, (uint32_t)o->spec_hash, mr_io_unix_ns(),
                           &err) != 0) {
      fprintf(stderr, "glove-gen: %s\n", err.msg);
      return 1;
    }
    g->recording = 1;
  }
  gg_stream_init(&g->stream, &cfg, &g->motion, g->truth);
  gg_answer_init(&g->answer, (unsigned)o->ignore_cmds);
  return -1;
}

/* Written whole and renamed into place, so a script polling for it never
 * reads half a file. -1, or 1 when it cannot be written. */
static int write_path_file(const glove *gloves, const options *o) {
  char tmp[4200];
  FILE *f;
  snprintf(tmp, sizeof tmp, "%s.tmp", o->path_file);
  f = fopen(tmp, "w");
  if (!f) {
    fprintf(stderr, "glove-gen: %s: cannot create: %s\n", tmp, strerror(errno));
    return 1;
  }
  for (int i = 0; i < o->n_out; i++) fprintf(f, "%s\n", mr_io_path(&gloves[i].io));
  if (fclose(f) != 0 || rename(tmp, o->path_file) != 0) {
    fprintf(stderr, "glove-gen: %s: cannot write: %s\n", o->path_file, strerror(errno));
    return 1;
  }
  return -1;
}

/* Until glove i's reader is there (a pty opened, a peer accepted): -1, 0
 * when stopped by a signal, 1 when it failed or --wait ran out. */
static int wait_for_reader(glove *g, int i, const options *o) {
  long long waited_ms = 0;
  for (;;) {
    mr_io_error err;
    mr_io_status st = g->io.kind == MR_IO_PTY ? mr_io_wait_peer(&g->io, 200, &err)
                                              : mr_io_accept(&g->io, 200, &err);
    if (st == MR_IO_OK) return -1;
    if (mr_io_failed(st)) {
      fprintf(stderr, "glove-gen: glove %d: %s\n", i, err.msg);
      return 1;
    }
    waited_ms += 200;
    if (g_stop) return 0;
    if (o->wait_s >= 0 && waited_ms >= o->wait_s * 1000) {
      fprintf(stderr, "glove-gen: glove %d: %s: no reader within %g s\n", i, mr_io_path(&g->io),
              o->wait_s);
      return 1;
    }
  }
}

/* Every output open and read: -1 to stream, else the exit code. */
static int open_gloves(glove *gloves, const options *o) {
  int rc;
  for (int i = 0; i < o->n_out; i++)
    if ((rc = open_glove(&gloves[i], i, o)) >= 0) return rc;
  if (o->path_file && (rc = write_path_file(gloves, o)) >= 0) return rc;
  for (int i = 0; i < o->n_out; i++)
    if ((rc = wait_for_reader(&gloves[i], i, o)) >= 0) return rc;
  return -1;
}

static void show_progress(const options *o, uint64_t slot) {
  if (o->count == UINT64_MAX)
    fprintf(stderr, "\rglove-gen: %llu frames", (unsigned long long)slot);
  else
    fprintf(stderr, "\rglove-gen: %llu/%llu frames (%.0f%%)", (unsigned long long)slot,
            (unsigned long long)o->count, 100.0 * (double)slot / (double)o->count);
}

/* One slot of every glove still streaming, sent at t_slot: 1 when all are
 * done, else 0 (a signal leaves the rest of the slot unsent). *rc becomes 1
 * when an output fails. */
static int stream_slot(glove *gloves, const options *o, uint64_t t0, uint64_t t_slot, int *rc) {
  uint8_t buf[GG_SLOT_MAX];
  int all_done = 1;
  for (int i = 0; i < o->n_out; i++) {
    glove *g = &gloves[i];
    int done;
    if (g->gone) continue;
    size_t n = gg_stream_next(&g->stream, buf, &done);
    if (done) continue;
    all_done = 0;
    gg_answer_observe(&g->answer, &g->stream);
    /* Recordings carry stream time when fast, so a replay keeps the pace. */
    uint64_t t_rec = o->fast ? t_slot - t0 : mr_io_monotonic_ns() - t0;
    int sent = n ? send_bytes(g, i, buf, n, t_rec) : 0;
    if (sent != 0 && g_stop) return 0;
    if (sent < 0) *rc = 1;
    if (g->duplex) answer_host(g, i, t_rec);
  }
  return all_done;
}

/* The slots, in real time unless --fast, until every stream ends or a
 * signal stops them: 0, or 1 when an output failed. */
static int stream_all(glove *gloves, const options *o, uint64_t t0) {
  int rc = 0;
  uint64_t next_progress = t0 + 1000000000ull;
  for (uint64_t slot = 0; !g_stop; slot++) {
    uint64_t t_slot = t0 + (uint64_t)llround((double)slot * 1e9 / o->rate);
    if (!o->fast) sleep_until_ns(t_slot);
    if (g_stop) break;
    if (stream_slot(gloves, o, t0, t_slot, &rc)) break;
    if (o->progress && mr_io_monotonic_ns() >= next_progress) {
      next_progress += 1000000000ull;
      show_progress(o, slot);
    }
  }
  if (o->progress) fprintf(stderr, "\n");
  return rc;
}

/* What a stream still holds goes out, and a pty reader gets --linger
 * seconds to read it. */
static void finish_gloves(glove *gloves, const options *o, uint64_t t0) {
  uint8_t buf[GG_SLOT_MAX];
  for (int i = 0; i < o->n_out; i++) {
    glove *g = &gloves[i];
    size_t n = gg_stream_finish(&g->stream, buf);
    mr_io_error err;
    if (g->gone) continue;
    if (n && send_bytes(g, i, buf, n, mr_io_monotonic_ns() - t0) != 0) continue;
    if (g->io.kind == MR_IO_PTY) {
      mr_io_status st = mr_io_drain(&g->io, (int)(o->linger_s * 1000), &err);
      if (st == MR_IO_TIMEOUT && !o->quiet)
        fprintf(stderr, "glove-gen: glove %d: %s: the reader left bytes unread after %g s\n", i,
                mr_io_path(&g->io), o->linger_s);
    }
  }
}

/* Truth files and recordings closed, outputs closed: rc, or 1 when one of
 * them could not be written. */
static int close_gloves(glove *gloves, int n_out, int rc) {
  for (int i = 0; i < n_out; i++) {
    glove *g = &gloves[i];
    mr_io_error err;
    if (g->truth) {
      gg_stream_write_expect(&g->stream, g->truth);
      if (fclose(g->truth) != 0) {
        fprintf(stderr, "glove-gen: %s: cannot write: %s\n", g->truth_path, strerror(errno));
        rc = 1;
      }
    }
    if (g->recording && mr_rec_writer_close(&g->rec, &err) != 0) {
      fprintf(stderr, "glove-gen: %s\n", err.msg);
      rc = 1;
    }
    if (g->open) mr_io_close(&g->io);
    gg_motion_free(&g->motion);
  }
  return rc;
}

int main(int argc, char **argv) {
  static options o;
  static glove gloves[MAX_GLOVES];
  options_init(&o);
  int rc = parse_args(&o, argc, argv);
  if (rc >= 0) return rc;
  g_quiet = o.quiet;

  signal(SIGPIPE, SIG_IGN);
  signal(SIGINT, on_signal);
  signal(SIGTERM, on_signal);

  if ((rc = load_motions(gloves, &o)) >= 0) return rc;
  rc = open_gloves(gloves, &o);
  if (rc < 0) {
    uint64_t t0 = mr_io_monotonic_ns();
    rc = stream_all(gloves, &o, t0);
    finish_gloves(gloves, &o, t0);
  }
  return close_gloves(gloves, o.n_out, rc);
}
