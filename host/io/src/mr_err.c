#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "mr_io_internal.h"

int mr_err_set(mr_err *err, mr_err_code code, const char *fmt, ...) {
  if (err) {
    va_list ap;
    err->code = code;
    err->sys_errno = 0;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
  }
  return -1;
}

int mr_err_sys(mr_err *err, const char *fmt, ...) {
  int e = errno;
  if (err) {
    va_list ap;
    size_t n;
    err->code = MR_E_SYSTEM;
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
