/* What the take library's files share. */
#ifndef TAKE_INTERNAL_H
#define TAKE_INTERNAL_H

#include "mr_take.h"

/* Fills *err (status and a printf-style message); always returns -1. */
int mr_take_fail(mr_take_error *err, mr_take_status st, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Finds the chunks' frames again after data or chunks changed. */
void mr_take_rec_scan(mr_take_rec *r);

#endif
