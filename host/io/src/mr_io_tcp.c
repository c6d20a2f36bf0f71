/* TCP: connect to HOST:PORT, or listen on one and serve one peer at a
 * time: a connection that comes while a peer is served is accepted and
 * closed at once, so it reads the end of the stream instead of waiting
 * unanswered in the backlog. */
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "mr_io_internal.h"

static int bound_port(int fd) {
  struct sockaddr_storage ss;
  socklen_t len = sizeof ss;
  if (getsockname(fd, (struct sockaddr *)&ss, &len) != 0) return -1;
  if (ss.ss_family == AF_INET) return ntohs(((struct sockaddr_in *)&ss)->sin_port);
  if (ss.ss_family == AF_INET6) return ntohs(((struct sockaddr_in6 *)&ss)->sin6_port);
  return -1;
}

static void set_stream_opts(int fd) {
  int one = 1;
  /* Frames are small and latency matters more than packet count. */
  setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
}

/* Resolves host:port and returns a socket connected to the first address
 * that takes a connection, or, when listening, bound and listening on the
 * first that can be bound. Returns -1 with errno from the last attempt, or
 * with *gai set when the name does not resolve. */
static int open_stream(const char *host, const char *port, int listening, int *gai) {
  struct addrinfo hints, *res = NULL, *ai;
  int fd = -1, one = 1, last_errno = 0;
  memset(&hints, 0, sizeof hints);
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = listening ? AI_PASSIVE : 0;
  *gai = getaddrinfo(host, port, &hints, &res);
  if (*gai != 0) return -1;
  for (ai = res; ai; ai = ai->ai_next) {
    fd = socket(ai->ai_family, ai->ai_socktype | SOCK_CLOEXEC, ai->ai_protocol);
    if (fd < 0) {
      last_errno = errno;
      continue;
    }
    if (listening) {
      setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
      /* The system's largest backlog: a burst of connections waits whole
       * in the queue to be closed. With 16, a burst of 50 left 16 peers
       * whose handshake the kernel dropped while the queue was full
       * connected on their side and never answered, for good. */
      if (bind(fd, ai->ai_addr, ai->ai_addrlen) == 0 && listen(fd, SOMAXCONN) == 0) break;
    } else if (connect(fd, ai->ai_addr, ai->ai_addrlen) == 0) {
      break;
    }
    last_errno = errno;
    close(fd);
    fd = -1;
  }
  freeaddrinfo(res);
  if (fd < 0) errno = last_errno;
  return fd;
}

int mr_io_tcp_connect(mr_io *io, const char *host, const char *port, mr_io_error *err) {
  int gai;
  int fd = open_stream(host, port, 0, &gai);
  if (gai != 0)
    return mr_io_err_set(err, MR_IO_ERR_SPEC, "tcp:%s:%s: %s", host, port, gai_strerror(gai));
  if (fd < 0) return mr_io_err_sys(err, "tcp:%s:%s: cannot connect", host, port);
  set_stream_opts(fd);
  io->fd = fd;
  io->kind = MR_IO_TCP;
  io->port = atoi(port);
  snprintf(io->path, sizeof io->path, "%s:%s", host, port);
  return 0;
}

int mr_io_tcp_listen(mr_io *io, const char *host, const char *port, mr_io_error *err) {
  int gai;
  int fd = open_stream(host, port, 1, &gai);
  if (gai != 0)
    return mr_io_err_set(err, MR_IO_ERR_SPEC, "tcp-listen:%s:%s: %s", host, port,
                         gai_strerror(gai));
  if (fd < 0) return mr_io_err_sys(err, "tcp-listen:%s:%s: cannot listen", host, port);
  fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK); /* refusing never blocks */
  io->listen_fd = fd;
  io->fd = -1;
  io->kind = MR_IO_TCP_LISTEN;
  io->port = bound_port(fd);
  snprintf(io->path, sizeof io->path, "%s:%d", host, io->port);
  return 0;
}

mr_io_status mr_io_accept(mr_io *io, int timeout_ms, mr_io_error *err) {
  struct pollfd p;
  int r, fd;
  if (io->kind != MR_IO_TCP_LISTEN) return MR_IO_OK;
  p.fd = io->listen_fd;
  p.events = POLLIN;
  p.revents = 0;
  r = poll(&p, 1, timeout_ms);
  if (r < 0 && errno == EINTR) return MR_IO_TIMEOUT;
  if (r < 0) {
    mr_io_err_sys(err, "%s: poll", io->path);
    return MR_IO_ERR_SYSTEM;
  }
  if (r == 0) return MR_IO_TIMEOUT;
  fd = accept(io->listen_fd, NULL, NULL);
  if (fd < 0) {
    if (errno == EINTR || errno == EAGAIN || errno == ECONNABORTED) return MR_IO_TIMEOUT;
    mr_io_err_sys(err, "%s: accept", io->path);
    return MR_IO_ERR_SYSTEM;
  }
  fcntl(fd, F_SETFD, FD_CLOEXEC);
  set_stream_opts(fd);
  /* One peer at a time. The listening socket stays open (a second client
   * waits in the backlog) so that mr_io_rearm can take the next peer on the
   * same port after this one leaves. */
  io->fd = fd;
  io->kind = MR_IO_TCP;
  return MR_IO_OK;
}

int mr_io_tcp_refuse_extra(mr_io *io) {
  int n = 0, fd;
  while ((fd = accept(io->listen_fd, NULL, NULL)) >= 0) {
    close(fd);
    n++;
  }
  return n;
}

int mr_io_rearm(mr_io *io) {
  if (io->kind != MR_IO_TCP || io->listen_fd < 0) return -1;
  close(io->fd);
  io->fd = -1;
  io->kind = MR_IO_TCP_LISTEN;
  return 0;
}
