/* A take argument of run --replay, render --take and export: a .mrec, or
 * BOOK:NAME, the files of take NAME in the take list BOOK (host/take). */
#ifndef MR_APP_TAKE_REF_H
#define MR_APP_TAKE_REF_H

#include <stddef.h>

/* Puts arg's files in out (at most cap): arg itself, or a book take's
 * files in glove order (kept until the program ends). Their number, or -1
 * after one line on stderr that starts with prog. */
int mr_app_take_paths(const char *prog, const char *arg, const char **out, size_t cap);

#endif
