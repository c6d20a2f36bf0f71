/* Shared between the mr_io sources; not part of the public API. */
#ifndef MR_IO_INTERNAL_H
#define MR_IO_INTERNAL_H

#include "mr_io.h"

#if defined(__GNUC__)
#define MR_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define MR_PRINTF(a, b)
#endif

/* Fill *err (if not NULL) and return -1. */
int mr_io_err_set(mr_io_error *err, mr_io_status status, const char *fmt, ...) MR_PRINTF(3, 4);
/* The same for a failed system call: appends strerror(errno). */
int mr_io_err_sys(mr_io_error *err, const char *fmt, ...) MR_PRINTF(2, 3);

int mr_io_pty_create(mr_io *io, mr_io_error *err);
int mr_io_tty_open(mr_io *io, const char *path, int baud, mr_io_error *err);
int mr_io_tcp_connect(mr_io *io, const char *host, const char *port, mr_io_error *err);
int mr_io_tcp_listen(mr_io *io, const char *host, const char *port, mr_io_error *err);
/* A peer is served: every connection waiting on the listening socket is
 * accepted and closed. How many. */
int mr_io_tcp_refuse_extra(mr_io *io);
int mr_io_serial_open(mr_io *io, const char *path, int baud, mr_io_error *err);
void mr_io_serial_close(mr_io *io);

/* Milliseconds left of a timeout started at start_ms (negative: forever). */
int mr_io_ms_left(long long start_ms, int timeout_ms);
long long mr_io_now_ms(void);

#endif
