/* Pseudo-terminals: creating one (the glove's side) and opening a slave path
 * as a serial line (the host's side), both through termios. */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "mr_io_internal.h"

static speed_t baud_to_speed(int baud) {
  switch (baud) {
  case 9600:
    return B9600;
  case 19200:
    return B19200;
  case 38400:
    return B38400;
  case 57600:
    return B57600;
  case 115200:
    return B115200;
  case 230400:
    return B230400;
  case 460800:
    return B460800;
  case 921600:
    return B921600;
  case 1000000:
    return B1000000;
  case 2000000:
    return B2000000;
  default:
    return 0;
  }
}

/* Raw 8N1: no echo, no line editing, no CR/LF translation, no flow control,
 * reads return whatever has arrived. */
static int set_raw(int fd, int baud, const char *path, mr_io_error *err) {
  struct termios t;
  speed_t sp = baud_to_speed(baud);
  if (tcgetattr(fd, &t) != 0) return mr_io_err_sys(err, "%s: tcgetattr", path);
  cfmakeraw(&t);
  t.c_cflag |= CLOCAL | CREAD;
  t.c_cflag &= ~(tcflag_t)(CSTOPB | PARENB | CRTSCTS);
  t.c_iflag &= ~(tcflag_t)(IXON | IXOFF | IXANY);
  t.c_cc[VMIN] = 1;
  t.c_cc[VTIME] = 0;
  if (sp) {
    cfsetispeed(&t, sp);
    cfsetospeed(&t, sp);
  }
  if (tcsetattr(fd, TCSANOW, &t) != 0) return mr_io_err_sys(err, "%s: tcsetattr", path);
  return 0;
}

int mr_io_pty_create(mr_io *io, mr_io_error *err) {
  const char *name;
  int slave;
  io->fd = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  /* In a container or chroot without devpts this is the first thing that
   * fails, with a bare "No such device": name the likely cause. */
  if (io->fd < 0)
    return mr_io_err_sys(err, "pty: cannot create a pseudo-terminal (is devpts mounted on "
                              "/dev/pts?)");
  if (grantpt(io->fd) != 0 || unlockpt(io->fd) != 0 || !(name = ptsname(io->fd))) {
    mr_io_err_sys(err, "pty: grantpt/unlockpt/ptsname");
    goto fail;
  }
  snprintf(io->path, sizeof io->path, "%s", name);
  /* The slave's termios decide how bytes written to the master reach the
   * reader, so make it raw before anything is written, or CRs would turn
   * into LFs and bytes would echo back. The setting outlives this close
   * while the master stays open (measured on Linux). Closing it also raises
   * POLLHUP on the master until a peer opens the slave: mr_io_wait_peer. */
  slave = open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (slave < 0) {
    mr_io_err_sys(err, "%s: cannot open the new pty's slave side", name);
    goto fail;
  }
  if (set_raw(slave, MR_IO_DEFAULT_BAUD, name, err) != 0) {
    close(slave);
    goto fail;
  }
  close(slave);
  io->kind = MR_IO_PTY;
  io->peer_seen = 0;
  return 0;
fail:
  close(io->fd);
  io->fd = -1;
  return -1;
}

int mr_io_tty_open(mr_io *io, const char *path, int baud, mr_io_error *err) {
  int flags = (io->mode & MR_IO_WRITE) ? O_RDWR : O_RDONLY;
  io->fd = open(path, flags | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (io->fd < 0) return mr_io_err_sys(err, "%s: cannot open", path);
  if (set_raw(io->fd, baud, path, err) != 0) {
    close(io->fd);
    io->fd = -1;
    return -1;
  }
  io->kind = MR_IO_TTY;
  io->baud = baud;
  snprintf(io->path, sizeof io->path, "%s", path);
  return 0;
}

static void sleep_ms(int ms) {
  struct timespec ts = { ms / 1000, (long)(ms % 1000) * 1000000L };
  nanosleep(&ts, NULL);
}

static int master_hup(const mr_io *io) {
  struct pollfd p = { io->fd, POLLOUT, 0 };
  return poll(&p, 1, 0) == 1 && (p.revents & POLLHUP);
}

mr_io_status mr_io_wait_peer(mr_io *io, int timeout_ms, mr_io_error *err) {
  long long start = mr_io_now_ms();
  (void)err;
  if (io->kind != MR_IO_PTY || io->peer_seen) return MR_IO_OK;
  /* poll() cannot wait for POLLHUP to clear, so look every few ms. */
  for (;;) {
    int left;
    if (!master_hup(io)) {
      io->peer_seen = 1;
      return MR_IO_OK;
    }
    left = mr_io_ms_left(start, timeout_ms);
    if (left == 0) return MR_IO_TIMEOUT;
    sleep_ms(left < 0 || left > 10 ? 10 : left);
  }
}

/* Bytes written to the master wait in two places before the reader sees
 * them: the slave's flip buffer, moved on by a kernel worker, and then the
 * line discipline's read buffer, which FIONREAD counts. A poll on the slave
 * with nothing readable makes the kernel run that worker to completion
 * first (n_tty_poll calls tty_buffer_flush_work), so a FIONREAD of 0 right
 * after it means both are empty. Without the poll, a FIONREAD of 0 only says
 * the worker has not caught up: under load it could stay behind for longer
 * than any fixed grace period, and closing the master then discarded the
 * end of the stream. */
static mr_io_status queued_bytes(mr_io *io, int *queued, mr_io_error *err) {
  struct pollfd p;
  int fd = open(io->path, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    mr_io_err_sys(err, "%s: cannot open to check the queue", io->path);
    return MR_IO_ERR_SYSTEM;
  }
  p.fd = fd;
  p.events = POLLIN;
  p.revents = 0;
  if (poll(&p, 1, 0) < 0 || ioctl(fd, FIONREAD, queued) != 0) {
    mr_io_err_sys(err, "%s: FIONREAD", io->path);
    close(fd);
    return MR_IO_ERR_SYSTEM;
  }
  close(fd);
  return MR_IO_OK;
}

mr_io_status mr_io_drain(mr_io *io, int timeout_ms, mr_io_error *err) {
  long long start = mr_io_now_ms();
  if (io->kind != MR_IO_PTY) return MR_IO_OK;
  /* Under load the reader can empty the line discipline while the flip
   * buffer still holds bytes the worker has not moved (measured: the end
   * of a stream lost in about one CI run in three on two busy cores), so
   * one empty reading is not enough: three in a row, 2 ms apart. */
  int empty = 0;
  for (;;) {
    int queued = 0, left;
    mr_io_status st;
    if (master_hup(io)) return MR_IO_HANGUP;
    st = queued_bytes(io, &queued, err);
    if (st != MR_IO_OK) return st;
    empty = queued == 0 ? empty + 1 : 0;
    if (empty >= 3) return MR_IO_OK;
    left = mr_io_ms_left(start, timeout_ms);
    if (left == 0) return MR_IO_TIMEOUT;
    sleep_ms(left < 0 || left > 2 ? 2 : left);
  }
}
