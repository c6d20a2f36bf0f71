/* glove-gen's options: --help's text, each option read and checked, and
 * the checks of them together. See tools/README.md. */
#include "options.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "gp.h"

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

static const struct option long_opts[] = {
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

/* What a parser returns for an option that is not its own; else -1 to go
 * on, or the exit code. */
#define NOT_MINE (-2)

void options_init(options *o) {
  memset(o, 0, sizeof *o);
  o->rate = 250;
  o->duration = o->wait_s = -1;
  o->linger_s = 5;
  o->seed = 1;
  o->baud = 115200;
  o->spec_hash = GP_SPEC_HASH;
  o->stall_min = 10;
  o->stall_max = 100;
  o->progress = isatty(STDERR_FILENO);
}

/* Where the streams go, and what is written beside them. */
static int parse_output_option(options *o, int c) {
  switch (c) {
  case 'o':
    if (o->n_out == MAX_GLOVES) return die_usage("at most 16 outputs%s", "");
    o->specs[o->n_out++] = optarg;
    return -1;
  case O_PATH_FILE:
    o->path_file = optarg;
    return -1;
  case O_WAIT:
    if (!parse_double(optarg, &o->wait_s) || o->wait_s < 0)
      return die_usage("--wait '%s' is not a number of seconds", optarg);
    return -1;
  case O_LINGER:
    if (!parse_double(optarg, &o->linger_s) || o->linger_s < 0)
      return die_usage("--linger '%s' is not a number of seconds", optarg);
    return -1;
  case O_TRUTH:
    if (o->n_truth == MAX_GLOVES) return die_usage("at most 16 truth files%s", "");
    o->truths[o->n_truth++] = optarg;
    return -1;
  case O_RECORD:
    if (o->n_rec == MAX_GLOVES) return die_usage("at most 16 recordings%s", "");
    o->records[o->n_rec++] = optarg;
    return -1;
  case O_PROGRESS:
    o->progress = 1;
    return -1;
  case 'q':
    o->quiet = 1;
    return -1;
  default:
    return NOT_MINE;
  }
}

/* The stream's timing, and what the glove is and announces. */
static int parse_stream_option(options *o, int c) {
  switch (c) {
  case 'r':
    if (!parse_double(optarg, &o->rate) || o->rate <= 0 || o->rate > 1e6)
      return die_usage("--rate '%s' is not a rate in Hz (0 < HZ <= 1000000)", optarg);
    return -1;
  case 'n':
    if (!parse_u64(optarg, &o->count, 10) || o->count == 0)
      return die_usage("--count '%s' is not a positive integer", optarg);
    o->have_count = 1;
    return -1;
  case 'd':
    if (!parse_double(optarg, &o->duration) || o->duration <= 0)
      return die_usage("--duration '%s' is not a positive number of seconds", optarg);
    return -1;
  case O_FAST:
    o->fast = 1;
    return -1;
  case 's':
    o->script = optarg;
    return -1;
  case O_SEED:
    if (!parse_u64(optarg, &o->seed, 0)) return die_usage("--seed '%s' is not an integer", optarg);
    return -1;
  case O_UID:
    if (!parse_u64(optarg, &o->uid0, 16) || o->uid0 > 0xFFFFFFFFu)
      return die_usage("--uid '%s' is not a 32-bit hex number", optarg);
    o->have_uid = 1;
    return -1;
  case O_BAUD:
    if (!parse_u64(optarg, &o->baud, 10) || o->baud == 0 || o->baud > 0xFFFFFFFFu)
      return die_usage("--baud '%s' is not a positive integer", optarg);
    return -1;
  case O_SPEC_HASH:
    if (!parse_u64(optarg, &o->spec_hash, 16) || o->spec_hash > 0xFFFFFFFFu)
      return die_usage("--spec-hash '%s' is not a 32-bit hex number", optarg);
    return -1;
  case O_IGNORE:
    if (!parse_u64(optarg, &o->ignore_cmds, 10) || o->ignore_cmds > 1000000)
      return die_usage("--ignore-commands '%s' is not a count of commands", optarg);
    return -1;
  default:
    return NOT_MINE;
  }
}

static int parse_hand(options *o) {
  if (o->n_hand == MAX_GLOVES) return die_usage("at most 16 hands%s", "");
  if (strcmp(optarg, "left") == 0)
    o->hands[o->n_hand++] = GP_HAND_LEFT;
  else if (strcmp(optarg, "right") == 0)
    o->hands[o->n_hand++] = GP_HAND_RIGHT;
  else
    return die_usage("--hand '%s' is not left or right", optarg);
  return -1;
}

static int parse_stall_frames(options *o) {
  char *colon = strchr(optarg, ':');
  uint64_t lo, hi;
  if (colon) *colon = 0;
  if (!parse_u64(optarg, &lo, 10) || (colon && !parse_u64(colon + 1, &hi, 10)))
    return die_usage("--stall-frames expects MIN[:MAX]%s", "");
  if (!colon) hi = lo;
  if (lo < 1 || hi < lo || hi > 1000)
    return die_usage("--stall-frames needs 1 <= MIN <= MAX <= 1000%s", "");
  o->stall_min = (uint32_t)lo;
  o->stall_max = (uint32_t)hi;
  return -1;
}

/* The faults, each kind's rate and the stalls' length. */
static int parse_fault_option(options *o, int c) {
  double d;
  if (c == O_FAULTS) {
    if (!parse_double(optarg, &o->all_faults) || o->all_faults < 0 || o->all_faults > 1)
      return die_usage("--faults '%s' is not a rate in 0..1", optarg);
    return -1;
  }
  if (c == O_STALL_FRAMES) return parse_stall_frames(o);
  if (c < O_FAULT0 || c >= O_FAULT0 + GG_F_COUNT) return NOT_MINE;
  if (!parse_double(optarg, &d) || d < 0 || d > 1)
    return die_usage("fault rate '%s' is not in 0..1", optarg);
  o->rates[c - O_FAULT0] = d;
  return -1;
}

/* One option into o: -1 to go on, else the exit code (0 after --help or
 * --version). */
static int parse_option(options *o, int c, char **argv) {
  int rc = parse_output_option(o, c);
  if (rc == NOT_MINE) rc = parse_stream_option(o, c);
  if (rc == NOT_MINE) rc = parse_fault_option(o, c);
  if (rc != NOT_MINE) return rc;
  switch (c) {
  case O_HAND:
    return parse_hand(o);
  case O_VERSION:
    printf("glove-gen %s\n", MR_VERSION);
    return 0;
  case 'h':
    usage(stdout);
    return 0;
  default:
    return bad_option(c, argv);
  }
}

/* What the options say together, once all are read: -1 to go on, else the
 * exit code. */
static int check_options(options *o, int argc, char **argv) {
  if (optind < argc) return die_usage("unexpected argument '%s'", argv[optind]);
  if (o->n_out == 0) o->specs[o->n_out++] = "-";
  /* Binary on a terminal garbles the screen and can leave it in a strange
   * mode, so refuse, as compressors do, and say how to get the bytes. */
  for (int i = 0; i < o->n_out; i++) {
    if (strcmp(o->specs[i], "-") == 0 && isatty(STDOUT_FILENO)) {
      fprintf(stderr, "glove-gen: not writing a binary stream to a terminal; pipe it "
                      "(glove-gen | glove-dump) or give -o FILE\n");
      return 2;
    }
  }
  if (o->n_truth && o->n_truth != o->n_out) return die_usage("give one --truth per output%s", "");
  if (o->n_rec && o->n_rec != o->n_out) return die_usage("give one --record per output%s", "");
  double sum = 0;
  for (int f = 0; f < GG_F_COUNT; f++) {
    o->rates[f] += o->all_faults / GG_F_COUNT;
    sum += o->rates[f];
  }
  if (sum > 1) return die_usage("fault rates add up to more than 1%s", "");
  if (sum > 0 && o->spec_hash != GP_SPEC_HASH)
    return die_usage("faults need the host's spec hash; drop --spec-hash%s", "");
  if (o->quiet) o->progress = 0;
  return -1;
}

int parse_args(options *o, int argc, char **argv) {
  int c, rc;
  opterr = 0; /* bad_option says it in one line, without the program's path */
  while ((c = getopt_long(argc, argv, ":o:r:n:d:s:qh", long_opts, NULL)) != -1)
    if ((rc = parse_option(o, c, argv)) >= 0) return rc;
  return check_options(o, argc, argv);
}
