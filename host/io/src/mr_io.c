/* Opening by spec, and reads and writes with a timeout over any descriptor.
 * Every kind ends up as one fd; only open and close differ per kind. */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <time.h>
#include <unistd.h>

#include "mr_io_internal.h"

static uint64_t clock_ns(clockid_t id) {
  struct timespec ts;
  clock_gettime(id, &ts);
  return (uint64_t)ts.tv_sec * 1000000000ull + (uint64_t)ts.tv_nsec;
}

uint64_t mr_io_monotonic_ns(void) {
  return clock_ns(CLOCK_MONOTONIC);
}

uint64_t mr_io_unix_ns(void) {
  return clock_ns(CLOCK_REALTIME);
}

long long mr_io_now_ms(void) {
  return (long long)(mr_io_monotonic_ns() / 1000000u);
}

int mr_io_ms_left(long long start_ms, int timeout_ms) {
  long long left;
  if (timeout_ms < 0) return -1;
  left = start_ms + timeout_ms - mr_io_now_ms();
  return left > 0 ? (int)left : 0;
}

static void io_reset(mr_io *io) {
  memset(io, 0, sizeof *io);
  io->fd = -1;
  io->listen_fd = -1;
}

int mr_io_is_pty_slave(const char *path) {
  struct stat st;
  char real[4096];
  if (stat(path, &st) != 0 || !S_ISCHR(st.st_mode)) return 0;
  /* Unix98 pty slaves live on majors 136..143 and under /dev/pts. */
  if (major(st.st_rdev) >= 136 && major(st.st_rdev) <= 143) return 1;
  if (realpath(path, real) && strncmp(real, "/dev/pts/", 9) == 0) return 1;
  return 0;
}

static int parse_baud(const char *s, int *baud, const char *spec, mr_io_error *err) {
  char *end;
  long v;
  errno = 0;
  v = strtol(s, &end, 10);
  if (errno || end == s || *end || v <= 0 || v > 100000000)
    return mr_io_err_set(err, MR_IO_ERR_SPEC, "%s: baud rate '%s' is not 1..100000000", spec, s);
  *baud = (int)v;
  return 0;
}

/* A spec taken apart, nothing opened yet. */
typedef enum spec_kind {
  SPEC_STDIO,
  SPEC_FILE,
  SPEC_PTY,
  SPEC_TCP,
  SPEC_LISTEN,
  SPEC_SERIAL
} spec_kind;
typedef struct io_spec {
  spec_kind kind;
  char path[256]; /* file or device */
  char host[256];
  const char *port;
  int baud;
} io_spec;

/* "serial:DEV[@BAUD]" and character devices given by path. */
static int parse_serial(io_spec *p, const char *dev_at_baud, const char *spec, mr_io_error *err) {
  const char *at = strrchr(dev_at_baud, '@');
  size_t n = at ? (size_t)(at - dev_at_baud) : strlen(dev_at_baud);
  p->kind = SPEC_SERIAL;
  p->baud = MR_IO_DEFAULT_BAUD;
  if (n == 0 || n >= sizeof p->path)
    return mr_io_err_set(err, MR_IO_ERR_SPEC, "%s: expected serial:DEVICE[@BAUD]", spec);
  memcpy(p->path, dev_at_baud, n);
  p->path[n] = 0;
  return at ? parse_baud(at + 1, &p->baud, spec, err) : 0;
}

/* "tcp:HOST:PORT" and "tcp-listen:[HOST:]PORT". */
static int parse_tcp(io_spec *p, const char *spec, mr_io_error *err) {
  int listen = spec[3] == '-';
  const char *rest = spec + (listen ? 11 : 4);
  const char *colon = strrchr(rest, ':');
  p->kind = listen ? SPEC_LISTEN : SPEC_TCP;
  p->port = colon ? colon + 1 : rest;
  snprintf(p->host, sizeof p->host, "127.0.0.1");
  if (colon) {
    size_t hn = (size_t)(colon - rest);
    if (hn >= sizeof p->host)
      return mr_io_err_set(err, MR_IO_ERR_SPEC, "%s: host name too long", spec);
    memcpy(p->host, rest, hn);
    p->host[hn] = 0;
    /* [::1]:5000 */
    if (hn >= 2 && p->host[0] == '[' && p->host[hn - 1] == ']') {
      memmove(p->host, p->host + 1, hn - 2);
      p->host[hn - 2] = 0;
    }
  } else if (!listen) {
    return mr_io_err_set(err, MR_IO_ERR_SPEC, "%s: expected tcp:HOST:PORT", spec);
  }
  if (!*p->host || !*p->port)
    return mr_io_err_set(err, MR_IO_ERR_SPEC, "%s: expected %s", spec,
                         listen ? "tcp-listen:[HOST:]PORT" : "tcp:HOST:PORT");
  /* A number, checked here: getaddrinfo takes any digits and keeps the
   * low 16 bits, so 99999 would quietly become port 34463. */
  char *end;
  unsigned long pn = strtoul(p->port, &end, 10);
  if (*end || p->port[0] < '0' || p->port[0] > '9' || strlen(p->port) > 5 || pn > 65535 ||
      (!listen && pn == 0))
    return mr_io_err_set(err, MR_IO_ERR_SPEC, "%s: port '%s' is not %s", spec, p->port,
                         listen ? "0..65535" : "1..65535");
  return 0;
}

/* Character devices of Linux's "mem" major (/dev/null, /dev/zero,
 * /dev/urandom, ...) read and write as plain files; any other is taken for a
 * serial line. Deciding without opening it matters: opening a USB serial
 * port raises DTR, which resets some boards. */
static int is_mem_device(const struct stat *st) {
  return major(st->st_rdev) == 1;
}

static int parse_spec(const char *spec, int mode, io_spec *p, mr_io_error *err) {
  struct stat st;
  memset(p, 0, sizeof *p);
  if (!spec || !*spec) return mr_io_err_set(err, MR_IO_ERR_SPEC, "empty source/sink spec");
  if (!(mode & (MR_IO_READ | MR_IO_WRITE)))
    return mr_io_err_set(err, MR_IO_ERR_ARG, "%s: open mode must read or write", spec);
  if (strcmp(spec, "-") == 0) {
    if ((mode & MR_IO_READ) && (mode & MR_IO_WRITE))
      return mr_io_err_set(err, MR_IO_ERR_SPEC, "-: stdin/stdout is one direction only");
    p->kind = SPEC_STDIO;
    return 0;
  }
  if (strcmp(spec, "pty") == 0) {
    p->kind = SPEC_PTY;
    return 0;
  }
  if (strncmp(spec, "tcp:", 4) == 0 || strncmp(spec, "tcp-listen:", 11) == 0)
    return parse_tcp(p, spec, err);
  if (strncmp(spec, "serial:", 7) == 0) return parse_serial(p, spec + 7, spec, err);
  if (strncmp(spec, "file:", 5) == 0 && !spec[5])
    return mr_io_err_set(err, MR_IO_ERR_SPEC, "%s: expected file:PATH", spec);
  if (strncmp(spec, "file:", 5) != 0 && stat(spec, &st) == 0 && S_ISCHR(st.st_mode) &&
      !is_mem_device(&st))
    return parse_serial(p, spec, spec, err);
  p->kind = SPEC_FILE;
  if (snprintf(p->path, sizeof p->path, "%s", strncmp(spec, "file:", 5) == 0 ? spec + 5 : spec) >=
      (int)sizeof p->path)
    return mr_io_err_set(err, MR_IO_ERR_SPEC, "%s: path too long", spec);
  return 0;
}

static int is_loopback(const char *host) {
  return strcmp(host, "localhost") == 0 || strncmp(host, "127.", 4) == 0 ||
         strcmp(host, "::1") == 0;
}

/* A named device or file that is not there, or is a folder, is the user's
 * mistake, found before anything starts. */
static int check_path(const io_spec *p, int mode, const char *spec, mr_io_error *err) {
  struct stat st;
  if (p->kind != SPEC_SERIAL && !(p->kind == SPEC_FILE && mode == MR_IO_READ)) return 0;
  if (p->kind == SPEC_FILE) spec = p->path;
  if (stat(p->path, &st) != 0)
    return mr_io_err_set(err, MR_IO_ERR_SPEC, "%s: %s", spec,
                         errno != ENOENT                  ? strerror(errno)
                         : p->kind == SPEC_SERIAL         ? "no such device"
                         : strncmp(spec, "/dev/", 5) == 0 ? "no such file or device"
                                                          : "no such file");
  if (S_ISDIR(st.st_mode))
    return mr_io_err_set(err, MR_IO_ERR_SPEC, "%s: is a directory, not a %s", spec,
                         p->kind == SPEC_SERIAL ? "device" : "file");
  if (p->kind == SPEC_SERIAL && !S_ISCHR(st.st_mode))
    return mr_io_err_set(err, MR_IO_ERR_SPEC, "%s: not a serial device (not a character device)",
                         spec);
  return 0;
}

int mr_io_spec_check(const char *spec, int mode, char *note, size_t note_size, mr_io_error *err) {
  io_spec p;
  if (note && note_size) note[0] = 0;
  if (parse_spec(spec, mode, &p, err) != 0 || check_path(&p, mode, spec, err) != 0) return -1;
  if (p.kind == SPEC_LISTEN && !is_loopback(p.host) && note && note_size)
    snprintf(note, note_size,
             "%s: listens beyond this machine, and plain TCP has no authentication: anyone "
             "who can reach the port can drive the puppets (keep it to a trusted network)",
             spec);
  return 0;
}

static int open_file(mr_io *io, const char *path, mr_io_error *err) {
  struct stat st;
  int flags = (io->mode & MR_IO_WRITE) ? ((io->mode & MR_IO_READ) ? O_RDWR : O_WRONLY) : O_RDONLY;
  if (io->mode & MR_IO_WRITE) {
    /* A FIFO must not be truncated or replaced: open it as it is. */
    if (!(stat(path, &st) == 0 && S_ISFIFO(st.st_mode))) flags |= O_CREAT | O_TRUNC;
  }
  io->fd = open(path, flags | O_CLOEXEC, 0644);
  if (io->fd < 0) return mr_io_err_sys(err, "%s: cannot open", path);
  if (fstat(io->fd, &st) != 0 || (S_ISDIR(st.st_mode) && (errno = EISDIR))) {
    mr_io_err_sys(err, "%s: cannot read", path);
    close(io->fd);
    io->fd = -1;
    return -1;
  }
  io->kind = S_ISFIFO(st.st_mode) ? MR_IO_FIFO : MR_IO_FILE;
  snprintf(io->path, sizeof io->path, "%s", path);
  return 0;
}

int mr_io_open(mr_io *io, const char *spec, int mode, mr_io_error *err) {
  io_spec p;
  io_reset(io);
  io->mode = mode;
  io->baud = MR_IO_DEFAULT_BAUD;
  io->peer_seen = 1;
  if (parse_spec(spec, mode, &p, err) != 0) return -1;
  switch (p.kind) {
  case SPEC_STDIO:
    io->kind = MR_IO_STDIO;
    io->fd = (mode & MR_IO_READ) ? STDIN_FILENO : STDOUT_FILENO;
    snprintf(io->path, sizeof io->path, "%s", (mode & MR_IO_READ) ? "stdin" : "stdout");
    return 0;
  case SPEC_PTY:
    return mr_io_pty_create(io, err);
  case SPEC_TCP:
    return mr_io_tcp_connect(io, p.host, p.port, err);
  case SPEC_LISTEN:
    return mr_io_tcp_listen(io, p.host, p.port, err);
  case SPEC_SERIAL:
    if (mr_io_is_pty_slave(p.path)) return mr_io_tty_open(io, p.path, p.baud, err);
    return mr_io_serial_open(io, p.path, p.baud, err);
  case SPEC_FILE:
    break;
  }
  return open_file(io, p.path, err);
}

static int is_link_kind(mr_io_kind k) {
  return k == MR_IO_PTY || k == MR_IO_TTY || k == MR_IO_SERIAL || k == MR_IO_TCP;
}

static int is_gone_errno(int e) {
  return e == EIO || e == ECONNRESET || e == ENXIO || e == ENODEV || e == EPIPE || e == ETIMEDOUT ||
         e == ENOTCONN || e == ESHUTDOWN;
}

mr_io_status mr_io_read(mr_io *io, void *buf, size_t cap, int timeout_ms, size_t *got,
                        mr_io_error *err) {
  long long start = mr_io_now_ms();
  *got = 0;
  if (!(io->mode & MR_IO_READ)) {
    mr_io_err_set(err, MR_IO_ERR_ARG, "%s: not opened for reading", io->path);
    return MR_IO_ERR_ARG;
  }
  if (cap == 0) return MR_IO_OK;
  if (io->kind == MR_IO_TCP_LISTEN || (io->kind == MR_IO_PTY && !io->peer_seen)) {
    mr_io_status st = io->kind == MR_IO_PTY ? mr_io_wait_peer(io, timeout_ms, err)
                                            : mr_io_accept(io, timeout_ms, err);
    if (st != MR_IO_OK) return st;
  }
  /* A peer from "tcp-listen:" is served alone: others are refused. */
  nfds_t nfds = io->kind == MR_IO_TCP && io->listen_fd >= 0 ? 2 : 1;
  for (;;) {
    struct pollfd ps[2] = { { io->fd, POLLIN, 0 }, { io->listen_fd, POLLIN, 0 } };
    struct pollfd p;
    ssize_t n;
    int r = poll(ps, nfds, mr_io_ms_left(start, timeout_ms));
    p = ps[0];
    /* Refused only while the peer served has nothing left to read: one
     * that has gone with bytes unread is read to its end first, and the
     * peer waiting meanwhile (the same glove back at once) is the next
     * one served, not a second one of the first. */
    if (r > 0 && nfds == 2 && (ps[1].revents & POLLIN) && p.revents == 0) {
      /* None taken (out of descriptors?): stop watching, never spin. */
      if (mr_io_tcp_refuse_extra(io) == 0) nfds = 1;
      continue;
    }
    if (r < 0) {
      /* A signal ends the wait early, so that the caller can look at it. */
      if (errno == EINTR) return MR_IO_TIMEOUT;
      mr_io_err_sys(err, "%s: poll", io->path);
      return MR_IO_ERR_SYSTEM;
    }
    if (r == 0) return MR_IO_TIMEOUT;
    if (p.revents & POLLNVAL) {
      mr_io_err_set(err, MR_IO_ERR_ARG, "%s: descriptor %d is not open", io->path, io->fd);
      return MR_IO_ERR_ARG;
    }
    /* Read even on POLLHUP: bytes that arrived before the hang-up come first. */
    n = read(io->fd, buf, cap);
    if (n > 0) {
      *got = (size_t)n;
      return MR_IO_OK;
    }
    if (n == 0) return is_link_kind(io->kind) ? MR_IO_HANGUP : MR_IO_EOF;
    if (errno == EAGAIN || errno == EWOULDBLOCK) continue;
    if (errno == EINTR) return MR_IO_TIMEOUT;
    if (is_gone_errno(errno)) return MR_IO_HANGUP;
    mr_io_err_sys(err, "%s: read", io->path);
    return MR_IO_ERR_SYSTEM;
  }
}

mr_io_status mr_io_write(mr_io *io, const void *buf, size_t len, int timeout_ms, size_t *sent,
                         mr_io_error *err) {
  long long start = mr_io_now_ms();
  const uint8_t *p = buf;
  size_t done = 0;
  mr_io_status st = MR_IO_OK;
  if (!(io->mode & MR_IO_WRITE)) {
    mr_io_err_set(err, MR_IO_ERR_ARG, "%s: not opened for writing", io->path);
    st = MR_IO_ERR_ARG;
    goto out;
  }
  if (io->kind == MR_IO_TCP_LISTEN || (io->kind == MR_IO_PTY && !io->peer_seen)) {
    st = io->kind == MR_IO_PTY ? mr_io_wait_peer(io, timeout_ms, err)
                               : mr_io_accept(io, timeout_ms, err);
    if (st != MR_IO_OK) goto out;
  }
  while (done < len) {
    struct pollfd pf = { io->fd, POLLOUT, 0 };
    ssize_t n;
    int r = poll(&pf, 1, mr_io_ms_left(start, timeout_ms));
    if (r < 0) {
      if (errno == EINTR) {
        st = MR_IO_TIMEOUT;
        goto out;
      }
      mr_io_err_sys(err, "%s: poll", io->path);
      st = MR_IO_ERR_SYSTEM;
      goto out;
    }
    if (r == 0) {
      st = MR_IO_TIMEOUT;
      goto out;
    }
    /* A pty master shows POLLHUP while no one has the slave side open: the
     * bytes would only pile up unread. */
    if (is_link_kind(io->kind) && (pf.revents & (POLLHUP | POLLERR))) {
      st = MR_IO_HANGUP;
      goto out;
    }
    if (io->kind == MR_IO_TCP)
      n = send(io->fd, p + done, len - done, MSG_NOSIGNAL);
    else
      n = write(io->fd, p + done, len - done);
    if (n > 0) {
      done += (size_t)n;
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) continue;
    if (n < 0 && is_gone_errno(errno)) {
      st = MR_IO_HANGUP;
      goto out;
    }
    mr_io_err_sys(err, "%s: write", io->path);
    st = MR_IO_ERR_SYSTEM;
    goto out;
  }
out:
  if (sent) *sent = done;
  return st;
}

const char *mr_io_path(const mr_io *io) {
  return io->path;
}

const char *mr_io_status_name(mr_io_status st) {
  switch (st) {
  case MR_IO_OK:
    return "ok";
  case MR_IO_TIMEOUT:
    return "timeout";
  case MR_IO_EOF:
    return "end of stream";
  case MR_IO_HANGUP:
    return "hang-up";
  case MR_IO_ERR_SYSTEM:
    return "system error";
  case MR_IO_ERR_SPEC:
    return "bad spec";
  case MR_IO_ERR_SERIAL:
    return "serial port error";
  case MR_IO_ERR_FORMAT:
    return "malformed recording";
  case MR_IO_ERR_TRUNCATED:
    return "recording cut short";
  case MR_IO_ERR_ARG:
    return "bad argument";
  }
  return "?";
}

void mr_io_close(mr_io *io) {
  if (io->kind == MR_IO_SERIAL) {
    mr_io_serial_close(io);
  } else if (io->kind != MR_IO_STDIO && io->fd >= 0) {
    close(io->fd);
  }
  if (io->listen_fd >= 0) close(io->listen_fd);
  io->fd = -1;
  io->listen_fd = -1;
}
