/* glove-dump: decodes a glove stream from a file, a recording, stdin, a pty,
 * TCP or a serial device, and accounts for every byte. See --help and
 * tools/README.md. */
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
#include "gp.h"
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
             "  PATH or file:PATH      raw stream bytes, or a .mrec recording (by its magic)\n"
             "  /dev/ttyUSB0, /dev/pts/N, serial:DEV[@BAUD]\n"
             "                         a serial device 8N1 (a pty is opened through termios)\n"
             "  tcp:HOST:PORT          connect;  tcp-listen:[HOST:]PORT  wait for one peer\n"
             "\n"
             "Output:\n"
             "      --csv              SAMPLE frames as CSV (seq,t_us,ch0..ch4,flags,late)\n"
             "  -q, --quiet            no frame lines, only the counters\n"
             "      --no-events        no lines for bad frames (\"! crc error at byte N\")\n"
             "      --counters FILE    also write the counters to FILE (key=value)\n"
             "      --record FILE.mrec record the raw input, as read, with its timing\n"
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
             "\n"
             "Exit: 0 end of stream or hang-up, 1 error (cannot open, read error,\n"
             "malformed recording, stdout not writable), 2 bad usage (also a SOURCE that\n"
             "does not parse), 3 spec mismatch, 130 SIGINT.\n"
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
  mr_io_err err;
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
  gp_decoder dec;
  int csv, quiet, events, keep_going;
  int mismatch;
  uint64_t max_frames;
  mr_rec_writer rec;
  int recording;
  uint64_t t0_ns;
  int out_errno; /* set when stdout refused the lines: they would be lost */
} dump;

/* Lines that cannot be written (a full disk, a reader that went away) are
 * lost: stop and say so instead of decoding on into nothing. */
static int stdout_failed(dump *D) {
  if (!D->out_errno && ferror(stdout)) D->out_errno = errno ? errno : EIO;
  return D->out_errno != 0;
}

/* Feeds bytes through the decoder; returns 1 when dumping should stop. */
static int feed(dump *D, const uint8_t *p, size_t n) {
  while (n) {
    gp_msg m;
    gp_event ev;
    size_t used = gp_decoder_feed(&D->dec, p, n, &m, &ev);
    p += used;
    n -= used;
    switch (ev) {
    case GP_EV_NONE:
      break;
    case GP_EV_FRAME:
    case GP_EV_FRAME_LATE:
      if (D->quiet) break;
      if (D->csv) {
        if (m.type == GP_SAMPLE) gd_print_csv_sample(stdout, &m.u.sample, ev == GP_EV_FRAME_LATE);
      } else {
        gd_print_msg(stdout, &m, ev == GP_EV_FRAME_LATE ? " late" : NULL);
      }
      break;
    case GP_EV_SPEC_MISMATCH:
      if (!D->mismatch) {
        fprintf(stderr, "glove-dump: spec mismatch (device 0x%08X, host 0x%08X)\n",
                (unsigned)D->dec.peer_hash, (unsigned)GP_SPEC_HASH);
        fflush(stderr);
        D->mismatch = 1;
      }
      if (D->events && !D->quiet && !D->csv)
        printf("! spec mismatch at byte %llu\n", (unsigned long long)D->dec.c.bytes);
      if (!D->keep_going) return 1;
      break;
    case GP_EV_DUPLICATE:
      if (D->events && !D->quiet && !D->csv)
        printf("! duplicate seq=%u at byte %llu\n", m.u.sample.seq,
               (unsigned long long)D->dec.c.bytes);
      break;
    default:
      if (D->events && !D->quiet && !D->csv)
        printf("! %s at byte %llu\n", gp_event_name(ev), (unsigned long long)D->dec.c.bytes);
      break;
    }
    if (D->max_frames && D->dec.c.frames >= D->max_frames) return 1;
  }
  return stdout_failed(D);
}

static int record(dump *D, const uint8_t *p, size_t n) {
  mr_io_err err;
  if (!D->recording || !n) return 0;
  if (mr_rec_writer_add(&D->rec, mr_io_monotonic_ns() - D->t0_ns, p, n, &err) != 0) {
    fprintf(stderr, "glove-dump: %s\n", err.msg);
    D->recording = 0;
    return -1;
  }
  return 0;
}

static void sleep_ns(uint64_t ns) {
  struct timespec ts = { (time_t)(ns / 1000000000ull), (long)(ns % 1000000000ull) };
  while (!g_stop && nanosleep(&ts, &ts) == -1 && errno == EINTR) {
  }
}

/* A .mrec source: chunks in order, optionally at their recorded pace. */
static int dump_recording(dump *D, mr_io *io, const uint8_t *prefix, size_t prefix_len,
                          int realtime) {
  mr_rec_reader r;
  mr_io_err err;
  uint64_t t_ns, start = mr_io_monotonic_ns();
  const uint8_t *data;
  size_t len;
  int rc;
  if (mr_rec_reader_open_fd(&r, io->fd, mr_io_path(io), prefix, prefix_len, &err) != 0) {
    fprintf(stderr, "glove-dump: %s\n", err.msg);
    return 1;
  }
  while (!g_stop && (rc = mr_rec_reader_next(&r, &t_ns, &data, &len, &err)) == 1) {
    if (realtime) {
      uint64_t now = mr_io_monotonic_ns() - start;
      if (t_ns > now) sleep_ns(t_ns - now);
    }
    record(D, data, len);
    if (feed(D, data, len)) break;
  }
  mr_rec_reader_close(&r);
  if (!g_stop && rc < 0) {
    fprintf(stderr, "glove-dump: %s\n", err.msg);
    /* The chunks before a cut-short end were decoded: a recorder that was
     * killed leaves such a file, and that is not an error. */
    return err.status == MR_IO_ERR_TRUNCATED ? 0 : 1;
  }
  return 0;
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

static int reopen(mr_io *io, const char *spec, double secs) {
  uint64_t start = mr_io_monotonic_ns();
  mr_io_err err;
  fprintf(stderr, "glove-dump: %s: waiting for it to come back%s\n", spec,
          secs > 0 ? "" : " (Ctrl-C to stop)");
  while (!g_stop) {
    if (mr_io_open(io, spec, MR_IO_READ, &err) == 0) {
      fprintf(stderr, "glove-dump: %s: reopened\n", spec);
      return 0;
    }
    if (secs > 0 && (double)(mr_io_monotonic_ns() - start) / 1e9 >= secs) {
      fprintf(stderr, "glove-dump: %s: not back within %g s: %s\n", spec, secs, err.msg);
      return -1;
    }
    sleep_ns(250000000ull);
  }
  return -1;
}

int main(int argc, char **argv) {
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
    O_PATH_FILE
  };
  static const struct option opts[] = { { "csv", no_argument, 0, O_CSV },
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
                                        { "help", no_argument, 0, 'h' },
                                        { 0, 0, 0, 0 } };
  static dump D;
  const char *spec = "-", *counters_path = NULL, *record_path = NULL, *path_file = NULL;
  char spec_buf[512];
  double reconnect = -1, idle = -1;
  long baud = 0;
  int realtime = 0, c, rc = 0, hung_up = 0, ended = 0;
  mr_io io;
  mr_io_err err;
  struct sigaction sa;

  D.events = 1;
  opterr = 0; /* bad_option says it in one line, without the program's path */
  while ((c = getopt_long(argc, argv, ":qn:h", opts, NULL)) != -1) {
    char *end;
    switch (c) {
    case O_CSV:
      D.csv = 1;
      break;
    case 'q':
      D.quiet = 1;
      break;
    case O_NO_EVENTS:
      D.events = 0;
      break;
    case O_COUNTERS:
      counters_path = optarg;
      break;
    case O_RECORD:
      record_path = optarg;
      break;
    case O_BAUD:
      baud = strtol(optarg, &end, 10);
      if (*end || baud <= 0) {
        fprintf(stderr, "glove-dump: --baud '%s' is not a positive integer\n", optarg);
        return EXIT_USAGE;
      }
      break;
    case O_REALTIME:
      realtime = 1;
      break;
    case O_RECONNECT:
    case O_IDLE: {
      double v = strtod(optarg, &end);
      if (*end || end == optarg || !(v >= 0) || !isfinite(v)) {
        fprintf(stderr, "glove-dump: %s '%s' is not a number of seconds\n",
                c == O_IDLE ? "--idle" : "--reconnect", optarg);
        return EXIT_USAGE;
      }
      if (c == O_IDLE)
        idle = v;
      else
        reconnect = v;
      break;
    }
    case 'n': {
      unsigned long long v = strtoull(optarg, &end, 10);
      if (*end || end == optarg || v == 0 || optarg[0] == '-') {
        fprintf(stderr, "glove-dump: --count '%s' is not a positive integer\n", optarg);
        return EXIT_USAGE;
      }
      D.max_frames = v;
      break;
    }
    case O_KEEP_GOING:
      D.keep_going = 1;
      break;
    case O_PATH_FILE:
      path_file = optarg;
      break;
    case O_LIST:
      return list_ports();
    case 'h':
      usage(stdout);
      return 0;
    default:
      return bad_option(c, argv);
    }
  }
  if (optind < argc) spec = argv[optind++];
  if (optind < argc) {
    fprintf(stderr, "glove-dump: one SOURCE only, got also '%s' (see --help)\n", argv[optind]);
    return EXIT_USAGE;
  }
  if (baud && !strchr(spec, '@')) {
    struct stat st;
    int is_dev = strncmp(spec, "serial:", 7) == 0 || (stat(spec, &st) == 0 && S_ISCHR(st.st_mode));
    if (is_dev) {
      snprintf(spec_buf, sizeof spec_buf, "%s%s@%ld",
               strncmp(spec, "serial:", 7) == 0 ? "" : "serial:", spec, baud);
      spec = spec_buf;
    }
  }

  /* No SA_RESTART: a signal must cut a blocking wait short. */
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
  signal(SIGPIPE, SIG_IGN);

  gp_decoder_init(&D.dec, GP_SPEC_HASH);
  D.t0_ns = mr_io_monotonic_ns();
  if (mr_io_open(&io, spec, MR_IO_READ, &err) != 0) {
    /* A SOURCE that does not parse is the user's usage, not a failure. */
    fprintf(stderr, "glove-dump: %s%s\n", err.msg,
            err.status == MR_IO_ERR_SPEC ? " (see --help)" : "");
    return err.status == MR_IO_ERR_SPEC ? EXIT_USAGE : 1;
  }
  if (path_file && write_path_file(path_file, mr_io_path(&io)) != 0) {
    mr_io_close(&io);
    return 1;
  }
  if (record_path) {
    if (mr_rec_writer_open(&D.rec, record_path, GP_SPEC_HASH, mr_io_unix_ns(), &err) != 0) {
      fprintf(stderr, "glove-dump: %s\n", err.msg);
      mr_io_close(&io);
      return 1;
    }
    D.recording = 1;
  }
  if (D.csv && !D.quiet) gd_print_csv_header(stdout);

  {
    uint8_t buf[4096];
    size_t have = 0;
    uint64_t last_data = mr_io_monotonic_ns(), back_by = 0;
    int sniffing = io.kind == MR_IO_FILE || io.kind == MR_IO_FIFO || io.kind == MR_IO_STDIO;
    int stop = 0;
    while (!stop && !g_stop) {
      size_t got = 0;
      mr_io_status st = mr_io_read(&io, buf + have, sizeof buf - have, 200, &got, &err);
      if (st == MR_IO_OK) {
        last_data = mr_io_monotonic_ns();
        back_by = 0;
        have += got;
        if (sniffing) {
          /* A recording starts with its magic; look before decoding. */
          if (have < 8 && memcmp(buf, MR_REC_MAGIC, have) == 0) continue;
          sniffing = 0;
          if (mr_rec_is_recording(buf, have)) {
            rc = dump_recording(&D, &io, buf, have, realtime);
            have = 0;
            break;
          }
        }
        record(&D, buf, have);
        stop = feed(&D, buf, have);
        have = 0;
        continue;
      }
      if (st == MR_IO_TIMEOUT) {
        /* A listening socket reopens at once; the device is back only when
         * bytes arrive. */
        if (back_by && mr_io_monotonic_ns() >= back_by) {
          fprintf(stderr, "glove-dump: %s: nothing came back within %g s\n", spec, reconnect);
          break;
        }
        if (idle >= 0 && (double)(mr_io_monotonic_ns() - last_data) / 1e9 >= idle) {
          fprintf(stderr, "glove-dump: %s: nothing for %g s, stopping\n", mr_io_path(&io), idle);
          break;
        }
        continue;
      }
      if (have) {
        record(&D, buf, have);
        stop = feed(&D, buf, have);
        have = 0;
      }
      if (st == MR_IO_EOF) {
        ended = 1;
        break;
      }
      if (mr_io_failed(st)) {
        fprintf(stderr, "glove-dump: %s\n", err.msg);
        rc = 1;
        break;
      }
      /* Hang-up: what was read is decoded already; say so, then maybe wait. */
      fprintf(stderr,
              "glove-dump: %s: hang-up after %llu bytes (device unplugged or the other "
              "end closed)\n",
              mr_io_path(&io), (unsigned long long)D.dec.c.bytes);
      if (reconnect < 0 || stop) {
        hung_up = 1;
        mr_io_close(&io);
        break;
      }
      /* A frame cut by the unplug ends here, as one error, instead of
       * fusing with the first bytes after the replug. The delimiter is ours,
       * not the device's, so it is not counted as received. */
      if (D.dec.len || D.dec.overflow) {
        stop = feed(&D, (const uint8_t *)"\0", 1);
        D.dec.c.bytes--;
      }
      if (mr_io_rearm(&io) == 0) {
        fprintf(stderr, "glove-dump: %s: waiting for the next peer\n", mr_io_path(&io));
      } else {
        mr_io_close(&io);
        if (reopen(&io, spec, reconnect) != 0) {
          hung_up = 1;
          break;
        }
      }
      last_data = mr_io_monotonic_ns();
      if (reconnect > 0) back_by = last_data + (uint64_t)(reconnect * 1e9);
    }
    if (!hung_up) mr_io_close(&io);
  }

  /* Bytes after the last delimiter are a frame that never ended: the
   * decoder holds them, and no event will ever name them. */
  if ((ended || hung_up) && D.dec.len && !D.dec.overflow)
    fprintf(stderr,
            "glove-dump: %s: the stream ended inside a frame: its last %zu bytes (from "
            "byte %llu) were not decoded\n",
            spec, D.dec.len, (unsigned long long)(D.dec.c.bytes - D.dec.len));
  if (fflush(stdout) != 0 && !D.out_errno) D.out_errno = errno ? errno : EIO;
  if (stdout_failed(&D)) {
    fprintf(stderr, "glove-dump: stdout: cannot write the decoded frames: %s\n",
            strerror(D.out_errno));
    rc = 1;
  }
  fprintf(stderr, "glove-dump: counters\n");
  gd_print_counters(stderr, &D.dec.c);
  if (counters_path) {
    FILE *f = fopen(counters_path, "w");
    if (!f) {
      fprintf(stderr, "glove-dump: %s: cannot create: %s\n", counters_path, strerror(errno));
      rc = 1;
    } else {
      gd_print_counters(f, &D.dec.c);
      if (fclose(f) != 0) rc = 1;
    }
  }
  if (D.recording && mr_rec_writer_close(&D.rec, &err) != 0) {
    fprintf(stderr, "glove-dump: %s\n", err.msg);
    rc = 1;
  }
  if (g_stop) return EXIT_SIGINT;
  if (D.mismatch) return EXIT_MISMATCH;
  return rc;
}
