/* `marionette run` with a take book (issue 23): --takes BOOK records the
 * show's raw take into the book; --over NAME plays that take beneath the
 * live gloves, --arm the channels the gloves give over it, --punch the
 * punch-in and punch-out times; at the punch-out the raw take and the
 * merged one (the take library's punch) go into the book. --speed
 * performs at 50 % or 25 %. In the window, keys arm channels, punch and
 * step through the book's takes (window.c); the show restarts from time 0
 * over the take beneath after a punch-out or a step. */
#ifndef MR_APP_RUN_TAKES_H
#define MR_APP_RUN_TAKES_H

#include <stdbool.h>
#include <stddef.h>

#include "mr_show.h"
#include "mr_take.h"

typedef struct mr_run_takes {
  /* The command line. */
  const char *book_dir, *over, *arm, *punch, *name;
  double speed; /* --speed: 1 (default), 0.5 or 0.25 */
  /* The book, and the take beneath (its name; "" none). */
  mr_take_book book;
  bool book_open;
  char beneath_name[MR_TAKE_NAME_MAX];
  char beneath[MR_SHOW_MAX_GLOVES][MR_TAKE_PATH_MAX];
  /* Where the show records (into the book's folder, moved in at the end)
   * unless --record said. */
  char raw[MR_SHOW_MAX_GLOVES][MR_TAKE_PATH_MAX];
  bool own_raw;
  size_t n_live;
  int pass; /* shows run so far: the raw files' names differ */
} mr_run_takes;

/* Whether opt is one of these options (each takes a value). */
bool mr_run_takes_option_is(const char *opt);
/* opt's value taken: 0, or -1 with the message in msg (bad usage). */
int mr_run_takes_option(mr_run_takes *t, const char *opt, const char *value, char *msg,
                        size_t size);
/* The options together, the book opened and the take beneath found, into
 * def (beneath, armed, punch times, record); n_live the live gloves (the
 * keyboard's counts as one). MR_EXIT_OK, or MR_EXIT_USAGE (an unknown
 * take, a channel past the gloves) or MR_EXIT_FAIL with one line in msg. */
int mr_run_takes_prepare(mr_run_takes *t, mr_show_def *def, size_t n_live, char *msg, size_t size);
/* After a show: its raw take into the book, and, when it punched in, the
 * merged take (the channels armed at the punch-in, between its punch
 * times; the show's end when it never punched out). Then the merged take
 * is the one beneath for the next show. One line for the user in line
 * (names, or why not); MR_EXIT_OK or MR_EXIT_FAIL. */
int mr_run_takes_store(mr_run_takes *t, const mr_show_result *r, mr_show_def *def, char *line,
                       size_t size);
/* The previous (dir < 0) or next take of the book beneath; -1 with a line
 * when the book has none. */
int mr_run_takes_step(mr_run_takes *t, int dir, mr_show_def *def, char *line, size_t size);
void mr_run_takes_close(mr_run_takes *t);

#endif
