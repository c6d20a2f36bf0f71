/* glove-dump: decodes a glove stream from a file, a recording, stdin, a pty,
 * TCP or a serial device, and accounts for every byte. See --help and
 * tools/README.md. The glove is the host's own (mr_glove): its source,
 * decoder, takes and reconnection; this program prints what it meets. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "gd_print.h"
#include "gd_relay.h"
#include "gp.h"
#include "mr_glove.h"
#include "mr_io.h"

enum { EXIT_USAGE = 2, EXIT_MISMATCH = 3, EXIT_SIGINT = 130 };

static volatile sig_atomic_t g_stop;

static void on_signal(int sig) {
  (void)sig;
  g_stop = 1;
}

static void usage(FILE *f) {
  fprintf(f, "usage: glove-dump [options] [SOURCE]\n"
             "Decodes a glove stream into one line per frame (or CSV) and prints the\n"
             "decoder's counters at the end, on SIGINT too.\n"
             "\n"
             "SOURCE (default -):\n"
             "  -                      stdin\n"
             "  PATH or file:PATH      raw stream bytes, or a .mrec recording (by its magic,\n"
             "                         or by its name: a *.mrec file must be a recording)\n"
             "  take:PATH              a .mrec recording, whatever its name\n"
             "  /dev/ttyUSB0, /dev/pts/N, serial:DEV[@BAUD]\n"
             "                         a serial device 8N1 (a pty is opened through termios)\n"
             "  tcp:HOST:PORT          connect\n"
             "  tcp-listen:[HOST:]PORT wait for one peer at a time, on 127.0.0.1 unless\n"
             "                         HOST is named (then a warning: no authentication)\n"
             "  mqtt[s]://[USER@]HOST[:PORT]/TOPIC[?cafile=PATH&password-file=PATH]\n"
             "                         a glove's topic on an MQTT broker (TLS with mqtts);\n"
             "                         the password from password-file= or MR_MQTT_PASSWORD\n"
             "                         (host/net/README.md)\n"
             "\n"
             "Output:\n"
             "      --csv              SAMPLE frames as CSV (seq,t_us,ch0..ch4,flags,late)\n"
             "  -q, --quiet            no frame lines, only the counters\n"
             "      --no-events        no lines for bad frames (\"! crc error at byte N\")\n"
             "      --counters FILE    also write the counters to FILE (key=value)\n"
             "      --record FILE.mrec record the raw input, as read, with its timing\n"
             "      --publish URL      relay the glove to a broker (URL as for an mqtt://\n"
             "                         SOURCE): its frames go on TOPIC, its answers on\n"
             "                         TOPIC/reply; commands on TOPIC/cmd come down to it\n"
             "Input:\n"
             "      --baud N           baud for a serial device given without @BAUD (115200)\n"
             "      --realtime         replay a .mrec at its recorded pace (default: at once)\n"
             "      --reconnect SECS   after a hang-up (device unplugged, peer gone), keep\n"
             "                         trying to reopen SOURCE for SECS (0: forever); a\n"
             "                         tcp-listen SOURCE waits for the next peer on the\n"
             "                         same port; the counters carry on across the gap\n"
             "      --idle SECS        stop when nothing arrives for SECS\n"
             "  -n, --count N          stop after N valid frames\n"
             "      --keep-going       go on decoding after a spec mismatch (still exit 3)\n"
             "      --path-file FILE   once SOURCE is open, write where it is (for\n"
             "                         tcp-listen:[HOST:]0, the port the kernel picked)\n"
             "      --list             list serial ports with their USB ids and exit\n"
             "  -h, --help             this text\n"
             "      --version          the version, and exit\n"
             "\n"
             "Exit: 0 end of stream or hang-up (or the reader of stdout left), 1 error\n"
             "(cannot open, read error, a recording malformed or cut short: its whole\n"
             "chunks are decoded first, stdout not writable), 2 bad usage (also a SOURCE\n"
             "that does not parse, a device or file that is not there), 3 spec mismatch,\n"
             "130 SIGINT.\n"
             "A spec mismatch prints exactly:\n"
             "  glove-dump: spec mismatch (device 0xDEVICE, host 0xHOST)\n");
}

/* getopt's own messages start with argv[0], often a long path, and take two
 * lines with ours; this names the option alone. */
static int bad_option(int c, char **argv) {
  const char *arg = argv[optind - 1];
  if (c == ':')
    fprintf(stderr, "glove-dump: option '%s' needs a value (see --help)\n", arg);
  else if (optopt && strncmp(arg, "--", 2) != 0)
    fprintf(stderr, "glove-dump: unknown option '-%c' (see --help)\n", optopt);
  else
    fprintf(stderr, "glove-dump: unknown option '%s' (see --help)\n", arg);
  return EXIT_USAGE;
}

static int list_ports(void) {
  mr_serial_info ports[64];
  size_t n;
  mr_io_error err;
  if (mr_serial_list(ports, 64, &n, &err) != 0) {
    fprintf(stderr, "glove-dump: %s\n", err.msg);
    return 1;
  }
  if (n == 0) printf("no serial ports found\n");
  for (size_t i = 0; i < n && i < 64; i++) {
    const mr_serial_info *p = &ports[i];
    if (p->is_usb)
      printf("%-16s usb %04x:%04x serial=%s  %s%s%s\n", p->name, (unsigned)p->usb_vid,
             (unsigned)p->usb_pid, p->serial[0] ? p->serial : "-", p->manufacturer,
             p->manufacturer[0] ? " " : "", p->product[0] ? p->product : p->description);
    else
      printf("%-16s %s\n", p->name, p->description);
  }
  return 0;
}

typedef struct dump {
  mr_glove *g;
  int csv, quiet, events, keep_going, realtime;
  int mismatch, stop;
  uint64_t max_frames;
  double reconnect, idle;
  mr_rec_writer rec;
  int recording;
  gd_relay *relay; /* --publish */
  int two;         /* two publishers on the topic, told */
  uint64_t t0_ns;
  int out_errno;   /* set when stdout refused the lines: they would be lost */
  char where[300]; /* the source as last open, for messages after it closed */
} dump;

static double now_s(const dump *D) {
  return (double)(mr_io_monotonic_ns() - D->t0_ns) * 1e-9;
}

/* Lines that cannot be written (a full disk, a reader that went away) are
 * lost: stop and say so instead of decoding on into nothing. */
static int stdout_failed(dump *D) {
  if (!D->out_errno && ferror(stdout)) D->out_errno = errno ? errno : EIO;
  return D->out_errno != 0;
}

/* Every frame and error the glove's decoder meets, as a line. */
static void on_event(void *user, gp_event ev, const gp_msg *m, uint64_t byte) {
  dump *D = user;
  bool lines = D->events && !D->quiet && !D->csv;
  if ((ev == GP_EV_FRAME || ev == GP_EV_FRAME_LATE) && !D->quiet) {
    if (!D->csv)
      gd_print_msg(stdout, m, ev == GP_EV_FRAME_LATE ? " late" : NULL);
    else if (m->type == GP_SAMPLE)
      gd_print_csv_sample(stdout, &m->u.sample, ev == GP_EV_FRAME_LATE);
  } else if (ev == GP_EV_SPEC_MISMATCH) {
    if (!D->mismatch) {
      uint32_t peer = m != NULL ? m->u.info.spec_hash : mr_glove_foreign_hash(D->g);
      fprintf(stderr, "glove-dump: spec mismatch (device 0x%08X, host 0x%08X)\n", (unsigned)peer,
              (unsigned)GP_SPEC_HASH);
      fflush(stderr);
      D->mismatch = 1;
    }
    if (lines) printf("! spec mismatch at byte %llu\n", (unsigned long long)byte);
    if (!D->keep_going) D->stop = 1;
  } else if (ev == GP_EV_DUPLICATE && lines) {
    printf("! duplicate seq=%u at byte %llu\n", m->u.sample.seq, (unsigned long long)byte);
  } else if (ev != GP_EV_FRAME && ev != GP_EV_FRAME_LATE && ev != GP_EV_DUPLICATE && lines) {
    printf("! %s at byte %llu\n", gp_event_name(ev), (unsigned long long)byte);
  }
  if (stdout_failed(D)) D->stop = 1;
}

/* The raw input, as read, with the time it was read. */
static void on_bytes(void *user, double now, const uint8_t *bytes, size_t len) {
  dump *D = user;
  (void)now;
  mr_io_error err;
  if (D->relay != NULL) gd_relay_bytes(D->relay, bytes, len);
  if (!D->recording) return;
  if (mr_rec_writer_add(&D->rec, mr_io_monotonic_ns() - D->t0_ns, bytes, len, &err) != 0) {
    fprintf(stderr, "glove-dump: %s\n", err.msg);
    D->recording = 0;
  }
}

/* Written whole and renamed into place, so a script polling for it never
 * reads half a line. */
static int write_path_file(const char *path, const char *what) {
  char tmp[4200];
  FILE *f;
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  f = fopen(tmp, "w");
  if (f) {
    int bad = fprintf(f, "%s\n", what) < 0;
    bad |= fclose(f) != 0;
    if (bad) f = NULL;
  }
  if (!f || rename(tmp, path) != 0) {
    fprintf(stderr, "glove-dump: %s: cannot write: %s\n", path, strerror(errno));
    return -1;
  }
  return 0;
}

/* What the source did since the last look: a hang-up, a return. */
static void tell(dump *D, mr_glove_counters *seen) {
  mr_glove_counters c;
  mr_glove_get_counters(D->g, &c);
  if (c.losses > seen->losses && !mr_glove_ended(D->g)) {
    fprintf(stderr,
            "glove-dump: %s: hang-up after %llu bytes (device unplugged or the other end "
            "closed)\n",
            D->where, (unsigned long long)c.decoder.bytes);
    if (mr_glove_io_path(D->g)[0] != '\0')
      fprintf(stderr, "glove-dump: %s: waiting for the next peer\n", D->where);
    else
      fprintf(stderr, "glove-dump: %s: waiting for it to come back%s\n", D->where,
              D->reconnect > 0 ? "" : " (Ctrl-C to stop)");
  }
  if (c.opens > seen->opens && seen->opens > 0)
    fprintf(stderr, "glove-dump: %s: reopened\n", D->where);
  *seen = c;
}

/* A glove over a broker: its link's counters as key=value lines. */
static void print_net(FILE *f, const mr_glove *g) {
  mr_net_counters n;
  if (!mr_glove_net_counters(g, &n)) return;
  fprintf(f,
          "net_messages=%llu\nnet_oversized=%llu\nnet_queue_full=%llu\nnet_empty=%llu\n"
          "net_unstamped=%llu\nnet_foreign=%llu\nnet_losses=%llu\n",
          (unsigned long long)n.messages, (unsigned long long)n.oversized,
          (unsigned long long)n.queue_full, (unsigned long long)n.empty,
          (unsigned long long)n.unstamped, (unsigned long long)n.foreign,
          (unsigned long long)n.losses);
}

/* Two publishers on a glove's topic, told once. */
static void tell_publishers(dump *D) {
  char a[160], b[160];
  if (D->two || !mr_glove_net_publishers(D->g, a, b, sizeof a)) return;
  D->two = 1;
  fprintf(stderr, "glove-dump: %s: two publishers on one glove topic: %s and %s\n", D->where, a, b);
}

/* Reads until the stream ends, a limit is reached or a signal comes. */
static int run(dump *D, const char *path_file) {
  mr_glove_counters seen;
  memset(&seen, 0, sizeof seen);
  uint64_t last_bytes = 0;
  double last_data = 0;
  int rc = 0;
  while (!D->stop && !g_stop) {
    /* A take plays at once unless --realtime: its chunks are all due. */
    double now = mr_glove_is_take(D->g) && !D->realtime ? 1e12 : now_s(D);
    mr_glove_poll(D->g, now, 200);
    const char *at = mr_glove_io_path(D->g);
    if (at[0] != '\0' && D->where[0] == '\0' && path_file && write_path_file(path_file, at) != 0)
      return 1;
    if (at[0] != '\0') snprintf(D->where, sizeof D->where, "%s", at);
    tell(D, &seen);
    tell_publishers(D);
    if (D->relay != NULL && gd_relay_poll(D->relay, D->g) != 0) return 1;
    if (seen.opens == 0 && seen.open_failures > 0) return -1; /* never opened */
    if (D->max_frames && seen.decoder.frames >= D->max_frames) break;
    if (mr_glove_ended(D->g)) break;
    if (seen.decoder.bytes != last_bytes) {
      last_bytes = seen.decoder.bytes;
      last_data = now_s(D);
    } else if (D->idle >= 0 && now_s(D) - last_data >= D->idle) {
      fprintf(stderr, "glove-dump: %s: nothing for %g s, stopping\n", D->where, D->idle);
      break;
    }
  }
  return rc;
}

/* The end: what the source said last, the counters, the recording. */
static int finish(dump *D, int rc, const char *spec, const char *counters_path) {
  mr_io_status st;
  const char *why = mr_glove_last_error(D->g, &st);
  mr_glove_counters c;
  mr_glove_get_counters(D->g, &c);
  if (rc < 0) {
    /* A SOURCE that does not parse is the user's usage, not a failure. */
    fprintf(stderr, "glove-dump: %s%s\n", why, st == MR_IO_ERR_SPEC ? " (see --help)" : "");
    return st == MR_IO_ERR_SPEC ? EXIT_USAGE : 1;
  }
  if (mr_glove_ended(D->g) && c.losses > 0 && !mr_glove_is_take(D->g) &&
      strstr(why, "ended") == NULL)
    fprintf(stderr,
            "glove-dump: %s: hang-up after %llu bytes (device unplugged or the other end "
            "closed)%s%s\n",
            D->where[0] ? D->where : spec, (unsigned long long)c.decoder.bytes,
            D->reconnect >= 0 ? ": " : "", D->reconnect >= 0 ? why : "");
  if (mr_glove_is_take(D->g) && (st == MR_IO_ERR_TRUNCATED || st == MR_IO_ERR_FORMAT)) {
    fprintf(stderr, "glove-dump: %s\n", why);
    /* The chunks before the damage were decoded, and what follows is
     * lost: an error, also for a last chunk cut short. */
    rc = 1;
  }
  /* Bytes after the last delimiter are a frame that never ended: the
   * decoder holds them, and no event will ever name them. */
  size_t held = mr_glove_unfinished(D->g);
  if (mr_glove_ended(D->g) && held > 0)
    fprintf(stderr,
            "glove-dump: %s: the stream ended inside a frame: its last %zu bytes (from byte "
            "%llu) were not decoded\n",
            spec, held, (unsigned long long)(c.decoder.bytes - held));
  if (fflush(stdout) != 0 && !D->out_errno) D->out_errno = errno ? errno : EIO;
  /* The reader of stdout left (`glove-dump ... | head`): what it wanted it
   * got, so the dump ends quietly, as cat does. */
  bool reader_left = stdout_failed(D) && D->out_errno == EPIPE;
  if (stdout_failed(D) && !reader_left) {
    fprintf(stderr, "glove-dump: stdout: cannot write the decoded frames: %s\n",
            strerror(D->out_errno));
    rc = 1;
  }
  if (!reader_left) {
    fprintf(stderr, "glove-dump: counters\n");
    gd_print_counters(stderr, &c.decoder);
    print_net(stderr, D->g);
  }
  if (counters_path) {
    FILE *f = fopen(counters_path, "w");
    if (!f) {
      fprintf(stderr, "glove-dump: %s: cannot create: %s\n", counters_path, strerror(errno));
      rc = 1;
    } else {
      gd_print_counters(f, &c.decoder);
      print_net(f, D->g);
      if (fclose(f) != 0) rc = 1;
    }
  }
  mr_io_error err;
  if (D->recording && mr_rec_writer_close(&D->rec, &err) != 0) {
    fprintf(stderr, "glove-dump: %s\n", err.msg);
    rc = 1;
  }
  return rc;
}

/* The command line, read. */
typedef struct args {
  const char *spec, *counters_path, *record_path, *path_file, *publish;
  char spec_buf[512];
} args;

enum {
  O_CSV = 256,
  O_NO_EVENTS,
  O_COUNTERS,
  O_RECORD,
  O_BAUD,
  O_REALTIME,
  O_RECONNECT,
  O_IDLE,
  O_KEEP_GOING,
  O_LIST,
  O_PATH_FILE,
  O_PUBLISH,
  O_VERSION
};

static const struct option long_opts[] = { { "csv", no_argument, 0, O_CSV },
                                           { "quiet", no_argument, 0, 'q' },
                                           { "no-events", no_argument, 0, O_NO_EVENTS },
                                           { "counters", required_argument, 0, O_COUNTERS },
                                           { "record", required_argument, 0, O_RECORD },
                                           { "baud", required_argument, 0, O_BAUD },
                                           { "realtime", no_argument, 0, O_REALTIME },
                                           { "reconnect", required_argument, 0, O_RECONNECT },
                                           { "idle", required_argument, 0, O_IDLE },
                                           { "count", required_argument, 0, 'n' },
                                           { "keep-going", no_argument, 0, O_KEEP_GOING },
                                           { "list", no_argument, 0, O_LIST },
                                           { "path-file", required_argument, 0, O_PATH_FILE },
                                           { "publish", required_argument, 0, O_PUBLISH },
                                           { "help", no_argument, 0, 'h' },
                                           { "version", no_argument, 0, O_VERSION },
                                           { 0, 0, 0, 0 } };

/* --idle or --reconnect (c says which) into D: -1, or the exit status. */
static int parse_seconds(int c, dump *D) {
  char *end;
  double v = strtod(optarg, &end);
  if (*end || end == optarg || !(v >= 0) || !isfinite(v)) {
    fprintf(stderr, "glove-dump: %s '%s' is not a number of seconds\n",
            c == O_IDLE ? "--idle" : "--reconnect", optarg);
    return EXIT_USAGE;
  }
  if (c == O_IDLE)
    D->idle = v;
  else
    D->reconnect = v;
  return -1;
}

static int parse_count(dump *D) {
  char *end;
  unsigned long long v = strtoull(optarg, &end, 10);
  if (*end || end == optarg || v == 0 || optarg[0] == '-') {
    fprintf(stderr, "glove-dump: --count '%s' is not a positive integer\n", optarg);
    return EXIT_USAGE;
  }
  D->max_frames = v;
  return -1;
}

static int parse_baud(long *baud) {
  char *end;
  *baud = strtol(optarg, &end, 10);
  if (*end || *baud <= 0) {
    fprintf(stderr, "glove-dump: --baud '%s' is not a positive integer\n", optarg);
    return EXIT_USAGE;
  }
  return -1;
}

/* One option into D, a and *baud: -1 when the run goes on, else the exit
 * status. */
static int parse_option(int c, char **argv, dump *D, args *a, long *baud) {
  switch (c) {
  case O_CSV:
    D->csv = 1;
    return -1;
  case 'q':
    D->quiet = 1;
    return -1;
  case O_NO_EVENTS:
    D->events = 0;
    return -1;
  case O_COUNTERS:
    a->counters_path = optarg;
    return -1;
  case O_RECORD:
    a->record_path = optarg;
    return -1;
  case O_BAUD:
    return parse_baud(baud);
  case O_REALTIME:
    D->realtime = 1;
    return -1;
  case O_RECONNECT:
  case O_IDLE:
    return parse_seconds(c, D);
  case 'n':
    return parse_count(D);
  case O_KEEP_GOING:
    D->keep_going = 1;
    return -1;
  case O_PATH_FILE:
    a->path_file = optarg;
    return -1;
  case O_PUBLISH:
    a->publish = optarg;
    return -1;
  case O_LIST:
    return list_ports();
  case 'h':
    usage(stdout);
    return 0;
  case O_VERSION:
    printf("glove-dump %s\n", MR_VERSION);
    return 0;
  default:
    return bad_option(c, argv);
  }
}

/* A serial device named without @BAUD gets --baud's rate. */
static void apply_baud(args *a, long baud) {
  struct stat st;
  int is_dev =
      strncmp(a->spec, "serial:", 7) == 0 || (stat(a->spec, &st) == 0 && S_ISCHR(st.st_mode));
  if (is_dev) {
    snprintf(a->spec_buf, sizeof a->spec_buf, "%s%s@%ld",
             strncmp(a->spec, "serial:", 7) == 0 ? "" : "serial:", a->spec, baud);
    a->spec = a->spec_buf;
  }
}

/* Options into D and a; -1 when the run goes on, else the exit status. */
static int parse(int argc, char **argv, dump *D, args *a) {
  long baud = 0;
  int c, rc;
  a->spec = "-";
  D->reconnect = -1;
  D->idle = -1;
  D->events = 1;
  opterr = 0; /* bad_option says it in one line, without the program's path */
  while ((c = getopt_long(argc, argv, ":qn:h", long_opts, NULL)) != -1)
    if ((rc = parse_option(c, argv, D, a, &baud)) >= 0) return rc;
  if (optind < argc) a->spec = argv[optind++];
  if (optind < argc) {
    fprintf(stderr, "glove-dump: one SOURCE only, got also '%s' (see --help)\n", argv[optind]);
    return EXIT_USAGE;
  }
  if (baud && !strchr(a->spec, '@')) apply_baud(a, baud);
  return -1;
}

int main(int argc, char **argv) {
  static dump D;
  static args A;
  mr_io_error err;
  struct sigaction sa;
  int rc = parse(argc, argv, &D, &A);
  if (rc >= 0) return rc;
  const char *spec = A.spec, *counters_path = A.counters_path, *record_path = A.record_path,
             *path_file = A.path_file;

  /* No SA_RESTART: a signal must cut a blocking wait short. */
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
  signal(SIGPIPE, SIG_IGN);

  mr_glove_def gd = mr_default_glove_def();
  if (strlen(spec) >= sizeof gd.source) {
    fprintf(stderr, "glove-dump: SOURCE is longer than %zu characters\n", sizeof gd.source - 1);
    return EXIT_USAGE;
  }
  memcpy(gd.source, spec, strlen(spec) + 1);
  /* A dump waits as long as it is asked to: silence is not a loss, and a
   * hang-up ends it unless --reconnect says how long to wait. */
  gd.lost_after = 1e9;
  gd.reconnect = D.reconnect < 0 ? -1 : D.reconnect;
  /* A source the user got wrong is bad usage, found before anything is
   * opened; a take that is no take is an error. */
  mr_glove_source_report rep;
  if (mr_glove_source_check(spec, &rep) != MR_IO_OK) {
    fprintf(stderr, "glove-dump: %s%s\n", rep.msg,
            rep.status == MR_IO_ERR_SPEC ? " (see --help)" : "");
    return rep.status == MR_IO_ERR_SPEC ? EXIT_USAGE : 1;
  }
  if (rep.note[0] != '\0') fprintf(stderr, "glove-dump: %s\n", rep.note);
  char msg[400];
  if (mr_glove_create(&gd, &D.g, msg, sizeof msg) != MR_GLOVE_OK) {
    fprintf(stderr, "glove-dump: %s (see --help)\n", msg);
    return EXIT_USAGE;
  }
  mr_glove_set_observer(D.g, on_event, &D);
  D.t0_ns = mr_io_monotonic_ns();
  if (record_path) {
    if (mr_rec_writer_open(&D.rec, record_path, GP_SPEC_HASH, mr_io_unix_ns(), &err) != 0) {
      fprintf(stderr, "glove-dump: %s\n", err.msg);
      mr_glove_destroy(D.g);
      return 1;
    }
    D.recording = 1;
    mr_glove_set_tap(D.g, on_bytes, &D);
  }
  if (A.publish != NULL) {
    if ((rc = gd_relay_open(&D.relay, A.publish)) != 0) {
      mr_glove_destroy(D.g);
      return rc;
    }
    mr_glove_set_tap(D.g, on_bytes, &D);
  }
  if (D.csv && !D.quiet) gd_print_csv_header(stdout);
  rc = finish(&D, run(&D, path_file), spec, counters_path);
  gd_relay_close(D.relay, stderr);
  mr_glove_destroy(D.g);
  if (g_stop) return EXIT_SIGINT;
  if (D.mismatch) return EXIT_MISMATCH;
  return rc;
}
