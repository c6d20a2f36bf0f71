#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "mr_io_internal.h"

int mr_io_err_set(mr_io_error *err, mr_io_status status, const char *fmt, ...) {
  if (err) {
    va_list ap;
    err->status = status;
    err->sys_errno = 0;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
  }
  return -1;
}

int mr_io_err_sys(mr_io_error *err, const char *fmt, ...) {
  int e = errno;
  if (err) {
    va_list ap;
    size_t n;
    err->status = MR_IO_ERR_SYSTEM;
    err->sys_errno = e;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    n = strlen(err->msg);
    snprintf(err->msg + n, sizeof err->msg - n, ": %s", strerror(e));
  }
  errno = e;
  return -1;
}
