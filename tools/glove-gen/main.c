/* glove-gen: synthetic glove streams for testers. See --help and
 * tools/README.md. */
#include <errno.h>
#include <getopt.h>
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

#define MAX_GLOVES 16

static volatile sig_atomic_t g_stop;
static int g_quiet; /* -q: no messages but errors */

static void on_signal(int sig) {
  (void)sig;
  g_stop = 1;
}

static void usage(FILE *f) {
  fprintf(f,
          "usage: glove-gen [options]\n"
          "Writes synthetic glove streams (the wire format of protocol/SPEC.md): SAMPLE\n"
          "frames at --rate, INFO first and then once a second, with optional faults.\n"
          "\n"
          "Output (repeat -o for several gloves, each its own stream, uid and hand):\n"
          "  -o, --output SPEC       - (stdout, the default), file:PATH or PATH, pty,\n"
          "                          tcp:HOST:PORT, tcp-listen:[HOST:]PORT, serial:DEV[@BAUD]\n"
          "      --path-file FILE    once every output is open, write one line per output:\n"
          "                          the pty slave path, the listening HOST:PORT, or the spec\n"
          "      --wait SECS         how long a pty or tcp-listen output waits for its\n"
          "                          reader (default: forever)\n"
          "      --linger SECS       at the end, how long to wait for a pty reader to read\n"
          "                          what was sent (default 5)\n"
          "Timing:\n"
          "  -r, --rate HZ           SAMPLE frames per second (default 250; any rate > 0)\n"
          "  -n, --count N           SAMPLE slots per glove (lost ones included)\n"
          "  -d, --duration SECS     the same in seconds of stream time; without either,\n"
          "                          the script's duration, else no end\n"
          "      --fast              as fast as the output takes the bytes (default: real\n"
          "                          time, paced by the monotonic clock)\n"
          "Content:\n"
          "  -s, --script FILE       motion script (tools/README.md); default: each finger\n"
          "                          a slow sine of its own frequency\n"
          "      --seed N            seed for motion and faults (default 1): same seed,\n"
          "                          same bytes\n"
          "      --hand left|right   hand of the next glove (repeatable; default right,\n"
          "                          left, right, ...)\n"
          "      --uid HEX           uid word 0 of glove 0 (glove k gets HEX+k)\n"
          "      --baud N            baud rate announced in INFO (default 115200)\n"
          "      --spec-hash HEX     encode everything with this spec hash, as a device\n"
          "                          built from another definition would (no faults)\n"
          "Faults (RATE is a probability per SAMPLE slot, 0..1; at most one per frame):\n"
          "      --faults RATE       all nine kinds below, RATE split evenly\n"
          "      --drop RATE         frame not sent                      -> lost\n"
          "      --dup RATE          frame sent twice                    -> duplicates\n"
          "      --reorder RATE      frame swapped with the next         -> reordered\n"
          "      --flip RATE         1..3 bits flipped                   -> crc_errors, lost\n"
          "      --truncate RATE     frame cut short                     -> framing_errors, lost\n"
          "      --garbage RATE      burst of noise before the frame     -> oversize\n"
          "      --wrong-hash RATE   frame encoded with a foreign hash   -> spec_mismatch, lost\n"
          "                          (plus one foreign INFO the first time -> spec_mismatch)\n"
          "      --unknown RATE      frame of an undefined type first    -> unknown_type\n"
          "      --stall RATE        unplug/replug: nothing sent for a while -> lost\n"
          "      --stall-frames MIN[:MAX]  frames lost per stall (default 10:100)\n"
          "Commands (on a pty, tcp or serial output the host may send them):\n"
          "      --ignore-commands K leave the host's first K commands unanswered, to\n"
          "                          see it retry; the rest are answered as the firmware\n"
          "                          answers them (SET_RATE only keeps --rate)\n"
          "Records:\n"
          "      --truth FILE        expected decoder counters (key=value) and the intact\n"
          "                          SAMPLEs (sample SEQ T_US CH0..CH4), one per -o, in order\n"
          "      --record FILE.mrec  record the bytes sent, one per -o, in order\n"
          "      --progress          progress on stderr (default when stderr is a terminal)\n"
          "  -q, --quiet             no messages but errors\n"
          "      --version           the version, and exit\n"
          "  -h, --help              this text\n"
          "Exit: 0 done (or stopped by SIGINT/SIGTERM, or the reader left), 1 error,\n"
          "2 bad usage (also: an output spec that does not parse, a device that is not\n"
          "there, or stdout is a terminal).\n");
}

static int die_usage(const char *fmt, const char *arg) {
  fprintf(stderr, "glove-gen: ");
  fprintf(stderr, fmt, arg);
  fprintf(stderr, " (see --help)\n");
  return 2;
}

/* getopt's own messages start with argv[0], often a long path, and take two
 * lines with ours; this names the option alone. */
static int bad_option(int c, char **argv) {
  const char *arg = argv[optind - 1];
  if (c == ':')
    fprintf(stderr, "glove-gen: option '%s' needs a value (see --help)\n", arg);
  else if (optopt && strncmp(arg, "--", 2) != 0)
    fprintf(stderr, "glove-gen: unknown option '-%c' (see --help)\n", optopt);
  else
    fprintf(stderr, "glove-gen: unknown option '%s' (see --help)\n", arg);
  return 2;
}

static int parse_double(const char *s, double *out) {
  char *end;
  errno = 0;
  *out = strtod(s, &end);
  return !(errno || end == s || *end || !isfinite(*out));
}

static int parse_u64(const char *s, uint64_t *out, int base) {
  char *end;
  if (*s == '-') return 0;
  errno = 0;
  *out = strtoull(s, &end, base);
  return !(errno || end == s || *end);
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

int main(int argc, char **argv) {
  enum {
    O_PATH_FILE = 256,
    O_VERSION,
    O_WAIT,
    O_LINGER,
    O_FAST,
    O_SEED,
    O_HAND,
    O_UID,
    O_BAUD,
    O_SPEC_HASH,
    O_FAULTS,
    O_STALL_FRAMES,
    O_TRUTH,
    O_RECORD,
    O_PROGRESS,
    O_IGNORE,
    O_FAULT0
  };
  static const struct option opts[] = {
    { "output", required_argument, 0, 'o' },
    { "path-file", required_argument, 0, O_PATH_FILE },
    { "wait", required_argument, 0, O_WAIT },
    { "linger", required_argument, 0, O_LINGER },
    { "rate", required_argument, 0, 'r' },
    { "count", required_argument, 0, 'n' },
    { "duration", required_argument, 0, 'd' },
    { "fast", no_argument, 0, O_FAST },
    { "script", required_argument, 0, 's' },
    { "seed", required_argument, 0, O_SEED },
    { "hand", required_argument, 0, O_HAND },
    { "uid", required_argument, 0, O_UID },
    { "baud", required_argument, 0, O_BAUD },
    { "spec-hash", required_argument, 0, O_SPEC_HASH },
    { "faults", required_argument, 0, O_FAULTS },
    { "drop", required_argument, 0, O_FAULT0 + GG_F_DROP },
    { "dup", required_argument, 0, O_FAULT0 + GG_F_DUP },
    { "reorder", required_argument, 0, O_FAULT0 + GG_F_REORDER },
    { "flip", required_argument, 0, O_FAULT0 + GG_F_FLIP },
    { "truncate", required_argument, 0, O_FAULT0 + GG_F_TRUNCATE },
    { "garbage", required_argument, 0, O_FAULT0 + GG_F_GARBAGE },
    { "wrong-hash", required_argument, 0, O_FAULT0 + GG_F_WRONG_HASH },
    { "stall", required_argument, 0, O_FAULT0 + GG_F_STALL },
    { "unknown", required_argument, 0, O_FAULT0 + GG_F_UNKNOWN },
    { "stall-frames", required_argument, 0, O_STALL_FRAMES },
    { "truth", required_argument, 0, O_TRUTH },
    { "record", required_argument, 0, O_RECORD },
    { "progress", no_argument, 0, O_PROGRESS },
    { "ignore-commands", required_argument, 0, O_IGNORE },
    { "quiet", no_argument, 0, 'q' },
    { "help", no_argument, 0, 'h' },
    { "version", no_argument, 0, O_VERSION },
    { 0, 0, 0, 0 }
  };
  static glove gloves[MAX_GLOVES];
  const char *specs[MAX_GLOVES], *truths[MAX_GLOVES], *records[MAX_GLOVES];
  unsigned hands[MAX_GLOVES];
  int n_out = 0, n_truth = 0, n_rec = 0, n_hand = 0;
  const char *script = NULL, *path_file = NULL;
  double rate = 250, duration = -1, wait_s = -1, linger_s = 5, all_faults = 0;
  double rates[GG_F_COUNT] = { 0 };
  uint64_t count = 0, seed = 1, uid0 = 0, baud = 115200, spec_hash = GP_SPEC_HASH;
  uint32_t stall_min = 10, stall_max = 100;
  int have_count = 0, fast = 0, progress = isatty(STDERR_FILENO), quiet = 0, c, rc = 0;
  int have_uid = 0;
  uint64_t ignore_cmds = 0;
  uint64_t t0, next_progress;
  uint8_t buf[GG_SLOT_MAX];

  opterr = 0; /* bad_option says it in one line, without the program's path */
  while ((c = getopt_long(argc, argv, ":o:r:n:d:s:qh", opts, NULL)) != -1) {
    double d;
    uint64_t u;
    switch (c) {
    case 'o':
      if (n_out == MAX_GLOVES) return die_usage("at most 16 outputs%s", "");
      specs[n_out++] = optarg;
      break;
    case O_PATH_FILE:
      path_file = optarg;
      break;
    case O_WAIT:
      if (!parse_double(optarg, &wait_s) || wait_s < 0)
        return die_usage("--wait '%s' is not a number of seconds", optarg);
      break;
    case O_LINGER:
      if (!parse_double(optarg, &linger_s) || linger_s < 0)
        return die_usage("--linger '%s' is not a number of seconds", optarg);
      break;
    case 'r':
      if (!parse_double(optarg, &rate) || rate <= 0 || rate > 1e6)
        return die_usage("--rate '%s' is not a rate in Hz (0 < HZ <= 1000000)", optarg);
      break;
    case 'n':
      if (!parse_u64(optarg, &count, 10) || count == 0)
        return die_usage("--count '%s' is not a positive integer", optarg);
      have_count = 1;
      break;
    case 'd':
      if (!parse_double(optarg, &duration) || duration <= 0)
        return die_usage("--duration '%s' is not a positive number of seconds", optarg);
      break;
    case O_FAST:
      fast = 1;
      break;
    case 's':
      script = optarg;
      break;
    case O_SEED:
      if (!parse_u64(optarg, &seed, 0)) return die_usage("--seed '%s' is not an integer", optarg);
      break;
    case O_HAND:
      if (n_hand == MAX_GLOVES) return die_usage("at most 16 hands%s", "");
      if (strcmp(optarg, "left") == 0)
        hands[n_hand++] = GP_HAND_LEFT;
      else if (strcmp(optarg, "right") == 0)
        hands[n_hand++] = GP_HAND_RIGHT;
      else
        return die_usage("--hand '%s' is not left or right", optarg);
      break;
    case O_IGNORE:
      if (!parse_u64(optarg, &ignore_cmds, 10) || ignore_cmds > 1000000)
        return die_usage("--ignore-commands '%s' is not a count of commands", optarg);
      break;
    case O_UID:
      if (!parse_u64(optarg, &uid0, 16) || uid0 > 0xFFFFFFFFu)
        return die_usage("--uid '%s' is not a 32-bit hex number", optarg);
      have_uid = 1;
      break;
    case O_BAUD:
      if (!parse_u64(optarg, &baud, 10) || baud == 0 || baud > 0xFFFFFFFFu)
        return die_usage("--baud '%s' is not a positive integer", optarg);
      break;
    case O_SPEC_HASH:
      if (!parse_u64(optarg, &spec_hash, 16) || spec_hash > 0xFFFFFFFFu)
        return die_usage("--spec-hash '%s' is not a 32-bit hex number", optarg);
      break;
    case O_FAULTS:
      if (!parse_double(optarg, &all_faults) || all_faults < 0 || all_faults > 1)
        return die_usage("--faults '%s' is not a rate in 0..1", optarg);
      break;
    case O_STALL_FRAMES: {
      char *colon = strchr(optarg, ':');
      uint64_t lo, hi;
      if (colon) *colon = 0;
      if (!parse_u64(optarg, &lo, 10) || (colon && !parse_u64(colon + 1, &hi, 10)))
        return die_usage("--stall-frames expects MIN[:MAX]%s", "");
      if (!colon) hi = lo;
      if (lo < 1 || hi < lo || hi > 1000)
        return die_usage("--stall-frames needs 1 <= MIN <= MAX <= 1000%s", "");
      stall_min = (uint32_t)lo;
      stall_max = (uint32_t)hi;
      break;
    }
    case O_TRUTH:
      if (n_truth == MAX_GLOVES) return die_usage("at most 16 truth files%s", "");
      truths[n_truth++] = optarg;
      break;
    case O_RECORD:
      if (n_rec == MAX_GLOVES) return die_usage("at most 16 recordings%s", "");
      records[n_rec++] = optarg;
      break;
    case O_PROGRESS:
      progress = 1;
      break;
    case 'q':
      quiet = 1;
      break;
    case O_VERSION:
      printf("glove-gen %s\n", MR_VERSION);
      return 0;
    case 'h':
      usage(stdout);
      return 0;
    default:
      if (c >= O_FAULT0 && c < O_FAULT0 + GG_F_COUNT) {
        if (!parse_double(optarg, &d) || d < 0 || d > 1)
          return die_usage("fault rate '%s' is not in 0..1", optarg);
        rates[c - O_FAULT0] = d;
        break;
      }
      return bad_option(c, argv);
    }
    (void)u;
  }
  if (optind < argc) return die_usage("unexpected argument '%s'", argv[optind]);
  if (n_out == 0) specs[n_out++] = "-";
  /* Binary on a terminal garbles the screen and can leave it in a strange
   * mode, so refuse, as compressors do, and say how to get the bytes. */
  for (int i = 0; i < n_out; i++) {
    if (strcmp(specs[i], "-") == 0 && isatty(STDOUT_FILENO)) {
      fprintf(stderr, "glove-gen: not writing a binary stream to a terminal; pipe it "
                      "(glove-gen | glove-dump) or give -o FILE\n");
      return 2;
    }
  }
  if (n_truth && n_truth != n_out) return die_usage("give one --truth per output%s", "");
  if (n_rec && n_rec != n_out) return die_usage("give one --record per output%s", "");
  {
    double sum = 0;
    for (int f = 0; f < GG_F_COUNT; f++) {
      rates[f] += all_faults / GG_F_COUNT;
      sum += rates[f];
    }
    if (sum > 1) return die_usage("fault rates add up to more than 1%s", "");
    if (sum > 0 && spec_hash != GP_SPEC_HASH)
      return die_usage("faults need the host's spec hash; drop --spec-hash%s", "");
  }
  if (quiet) progress = 0;
  g_quiet = quiet;

  signal(SIGPIPE, SIG_IGN);
  signal(SIGINT, on_signal);
  signal(SIGTERM, on_signal);

  for (int i = 0; i < n_out; i++) {
    glove *g = &gloves[i];
    char err[600];
    uint64_t gseed = seed * 0x100000001B3ull + (uint64_t)i;
    g->spec = specs[i];
    g->truth_path = n_truth ? truths[i] : NULL;
    g->record_path = n_rec ? records[i] : NULL;
    if (script) {
      if (gg_motion_load(&g->motion, script, gseed, err, sizeof err) != 0) {
        fprintf(stderr, "glove-gen: %s\n", err);
        return 1;
      }
    } else {
      gg_motion_default(&g->motion, gseed);
    }
  }
  if (!have_count) {
    double secs = duration > 0 ? duration : gloves[0].motion.duration_s;
    count = secs > 0 ? (uint64_t)llround(secs * rate) : UINT64_MAX;
    if (count == 0) count = 1;
  }

  for (int i = 0; i < n_out; i++) {
    glove *g = &gloves[i];
    mr_io_error err;
    gg_stream_config cfg;
    g->duplex = is_duplex(g->spec);
    int mode = g->duplex ? MR_IO_READ | MR_IO_WRITE : MR_IO_WRITE;
    /* Checked first, as glove-dump checks its source: a device that is not
     * there is the user's usage too. */
    if (mr_io_spec_check(g->spec, mode, NULL, 0, &err) != 0 ||
        mr_io_open(&g->io, g->spec, mode, &err) != 0) {
      /* An output spec that does not parse is the user's usage. */
      fprintf(stderr, "glove-gen: %s%s\n", err.msg,
              err.status == MR_IO_ERR_SPEC ? " (see --help)" : "");
      rc = err.status == MR_IO_ERR_SPEC ? 2 : 1;
      goto out;
    }
    g->open = 1;
    if (!quiet && (g->io.kind == MR_IO_PTY || g->io.kind == MR_IO_TCP_LISTEN))
      fprintf(stderr, "glove-gen: glove %d: %s %s\n", i,
              g->io.kind == MR_IO_PTY ? "pty" : "listening on", mr_io_path(&g->io));
    memset(&cfg, 0, sizeof cfg);
    cfg.rate_hz = rate;
    cfg.count = count;
    cfg.spec_hash = (uint32_t)spec_hash;
    cfg.hand = (uint8_t)(i < n_hand ? hands[i] : (i % 2 ? GP_HAND_LEFT : GP_HAND_RIGHT));
    cfg.uid[0] = (uint32_t)((have_uid ? uid0 : 0x4D520000u) + (uint64_t)i);
    cfg.uid[1] = (uint32_t)(seed * 2654435761u);
    cfg.uid[2] = (uint32_t)(seed >> 32) ^ 0x474C4F56u;
    cfg.baud = (uint32_t)baud;
    memcpy(cfg.rates, rates, sizeof rates);
    cfg.stall_min = stall_min;
    cfg.stall_max = stall_max;
    cfg.seed = seed * 0x100000001B3ull + (uint64_t)i;
    if (g->truth_path && !(g->truth = fopen(g->truth_path, "w"))) {
      fprintf(stderr, "glove-gen: %s: cannot create: %s\n", g->truth_path, strerror(errno));
      rc = 1;
      goto out;
    }
    if (g->truth)
      fprintf(g->truth, "# glove-gen truth: intact SAMPLE frames (sample SEQ T_US CH0..CH4), "
                        "then the expected decoder counters\n");
    if (g->record_path) {
      if (mr_rec_writer_open(&g->rec, g->record_path, (uint32_t)spec_hash, mr_io_unix_ns(), &err) !=
          0) {
        fprintf(stderr, "glove-gen: %s\n", err.msg);
        rc = 1;
        goto out;
      }
      g->recording = 1;
    }
    gg_stream_init(&g->stream, &cfg, &g->motion, g->truth);
    gg_answer_init(&g->answer, (unsigned)ignore_cmds);
  }
  if (path_file) {
    /* Written whole and renamed into place, so a script polling for it
     * never reads half a file. */
    char tmp[4200];
    FILE *f;
    snprintf(tmp, sizeof tmp, "%s.tmp", path_file);
    f = fopen(tmp, "w");
    if (!f) {
      fprintf(stderr, "glove-gen: %s: cannot create: %s\n", tmp, strerror(errno));
      rc = 1;
      goto out;
    }
    for (int i = 0; i < n_out; i++) fprintf(f, "%s\n", mr_io_path(&gloves[i].io));
    if (fclose(f) != 0 || rename(tmp, path_file) != 0) {
      fprintf(stderr, "glove-gen: %s: cannot write: %s\n", path_file, strerror(errno));
      rc = 1;
      goto out;
    }
  }
  for (int i = 0; i < n_out; i++) {
    glove *g = &gloves[i];
    long long waited_ms = 0;
    for (;;) {
      mr_io_error err;
      mr_io_status st = g->io.kind == MR_IO_PTY ? mr_io_wait_peer(&g->io, 200, &err)
                                                : mr_io_accept(&g->io, 200, &err);
      if (st == MR_IO_OK) break;
      if (mr_io_failed(st)) {
        fprintf(stderr, "glove-gen: glove %d: %s\n", i, err.msg);
        rc = 1;
        goto out;
      }
      waited_ms += 200;
      if (g_stop) goto out;
      if (wait_s >= 0 && waited_ms >= wait_s * 1000) {
        fprintf(stderr, "glove-gen: glove %d: %s: no reader within %g s\n", i, mr_io_path(&g->io),
                wait_s);
        rc = 1;
        goto out;
      }
    }
  }

  t0 = mr_io_monotonic_ns();
  next_progress = t0 + 1000000000ull;
  for (uint64_t slot = 0; !g_stop; slot++) {
    int all_done = 1;
    uint64_t t_slot = t0 + (uint64_t)llround((double)slot * 1e9 / rate);
    if (!fast) sleep_until_ns(t_slot);
    if (g_stop) break;
    for (int i = 0; i < n_out; i++) {
      glove *g = &gloves[i];
      int done;
      size_t n;
      if (g->gone) continue;
      n = gg_stream_next(&g->stream, buf, &done);
      if (done) continue;
      all_done = 0;
      gg_answer_observe(&g->answer, &g->stream);
      /* Recordings carry stream time when fast, so a replay keeps the pace. */
      uint64_t t_rec = fast ? t_slot - t0 : mr_io_monotonic_ns() - t0;
      int sent = n ? send_bytes(g, i, buf, n, t_rec) : 0;
      if (sent != 0 && g_stop) break;
      if (sent < 0) rc = 1;
      if (g->duplex) answer_host(g, i, t_rec);
    }
    if (all_done) break;
    if (progress && mr_io_monotonic_ns() >= next_progress) {
      next_progress += 1000000000ull;
      if (count == UINT64_MAX)
        fprintf(stderr, "\rglove-gen: %llu frames", (unsigned long long)slot);
      else
        fprintf(stderr, "\rglove-gen: %llu/%llu frames (%.0f%%)", (unsigned long long)slot,
                (unsigned long long)count, 100.0 * (double)slot / (double)count);
    }
  }
  if (progress) fprintf(stderr, "\n");

  for (int i = 0; i < n_out; i++) {
    glove *g = &gloves[i];
    size_t n = gg_stream_finish(&g->stream, buf);
    mr_io_error err;
    if (g->gone) continue;
    if (n && send_bytes(g, i, buf, n, mr_io_monotonic_ns() - t0) != 0) continue;
    if (g->io.kind == MR_IO_PTY) {
      mr_io_status st = mr_io_drain(&g->io, (int)(linger_s * 1000), &err);
      if (st == MR_IO_TIMEOUT && !quiet)
        fprintf(stderr, "glove-gen: glove %d: %s: the reader left bytes unread after %g s\n", i,
                mr_io_path(&g->io), linger_s);
    }
  }

out:
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
