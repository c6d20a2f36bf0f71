/* `marionette run` with a take book: the take beneath, the channels armed
 * over it, the punch times, and the takes stored at the end (run_takes.h).
 * The merge itself is the take library's (mr_take_book_punch). */
#define _POSIX_C_SOURCE 200809L
#include "run_takes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "mr_show_runner.h"

static const char *const OPTIONS[] = {
  "--takes", "--over", "--arm", "--punch", "--name", "--speed"
};

bool mr_run_takes_option_is(const char *opt) {
  for (size_t i = 0; i < sizeof OPTIONS / sizeof *OPTIONS; i++)
    if (strcmp(opt, OPTIONS[i]) == 0) return true;
  return false;
}

int mr_run_takes_option(mr_run_takes *t, const char *opt, const char *v, char *msg, size_t size) {
  if (strcmp(opt, "--speed") == 0) {
    char *end = NULL;
    double s = strtod(v, &end);
    if (end == v || *end != '\0' || !mr_show_speed_valid(s)) {
      snprintf(msg, size, "expected --speed 1, 0.5 or 0.25, got '%.40s'", v);
      return -1;
    }
    t->speed = s;
  } else if (strcmp(opt, "--takes") == 0) {
    t->book_dir = v;
  } else if (strcmp(opt, "--over") == 0) {
    t->over = v;
  } else if (strcmp(opt, "--arm") == 0) {
    t->arm = v;
  } else if (strcmp(opt, "--punch") == 0) {
    t->punch = v;
  } else {
    t->name = v;
  }
  return 0;
}

/* --punch IN:OUT, seconds, 0 <= IN < OUT. */
static int parse_punch(const char *text, double *in, double *out) {
  char *end = NULL;
  *in = strtod(text, &end);
  if (end == text || *end != ':') return -1;
  const char *second = end + 1;
  *out = strtod(second, &end);
  if (end == second || *end != '\0') return -1;
  return isfinite(*in) && isfinite(*out) && *in >= 0 && *out > *in ? 0 : -1;
}

/* The take called name beneath the gloves: its files, glove by glove. */
static int set_beneath(mr_run_takes *t, const char *name, mr_show_def *def, char *msg,
                       size_t size) {
  char paths[MR_SHOW_MAX_GLOVES][MR_TAKE_PATH_MAX];
  size_t n = 0;
  mr_take_error err;
  if (mr_take_book_paths(&t->book, name, paths, MR_SHOW_MAX_GLOVES, &n, &err) != 0) {
    snprintf(msg, size, "%s", err.msg);
    return -1;
  }
  snprintf(t->beneath_name, sizeof t->beneath_name, "%s", name);
  for (size_t g = 0; g < MR_SHOW_MAX_GLOVES; g++) {
    if (g < n) memcpy(t->beneath[g], paths[g], sizeof t->beneath[g]);
    def->beneath[g] = g < n && g < t->n_live ? t->beneath[g] : NULL;
  }
  return 0;
}

/* --arm G:F,...: each glove's channels, every glove one of the show's. */
static int set_armed(mr_run_takes *t, mr_show_def *def, char *msg, size_t size) {
  mr_take_arm arms[MR_TAKE_MAX_ARMS];
  size_t n = 0;
  mr_take_error err;
  if (mr_take_arms_parse(t->arm, arms, MR_TAKE_MAX_ARMS, &n, &err) != 0) {
    snprintf(msg, size, "--arm: %s", err.msg);
    return -1;
  }
  for (size_t i = 0; i < n; i++) {
    if (arms[i].glove < 0 || (size_t)arms[i].glove >= t->n_live) {
      snprintf(msg, size, "expected --arm channels of glove 0 to %zu (%zu given), got glove %d",
               t->n_live - 1, t->n_live, arms[i].glove);
      return -1;
    }
    def->armed[arms[i].glove] |= 1u << arms[i].finger;
  }
  return 0;
}

/* Each live glove recorded: where --record said, else into the book's
 * folder, to be moved in at the end. */
static void set_raw(mr_run_takes *t, mr_show_def *def) {
  t->own_raw = true;
  for (size_t g = 0; g < t->n_live; g++)
    if (def->record[g] != NULL && def->record[g] != t->raw[g]) t->own_raw = false;
  for (size_t g = 0; g < t->n_live; g++) {
    if (def->record[g] != NULL && def->record[g] != t->raw[g]) continue;
    snprintf(t->raw[g], sizeof t->raw[g], "%s/.recording-%ld-%d-g%zu.mrec", t->book_dir,
             (long)getpid(), t->pass, g);
    def->record[g] = t->raw[g];
  }
}

static int usage(char *msg, size_t size, const char *text) {
  snprintf(msg, size, "%s", text);
  return MR_EXIT_USAGE;
}

/* The names asked for: free in the book (the raw take's is NAME-raw). */
static int check_names(mr_run_takes *t, char *msg, size_t size) {
  if (t->name == NULL) return 0;
  mr_take_error err;
  char raw[MR_TAKE_NAME_MAX + 8];
  snprintf(raw, sizeof raw, "%.60s-raw", t->name);
  if (mr_take_book_check_name(&t->book, t->name, &err) != 0 ||
      (t->over != NULL && mr_take_book_check_name(&t->book, raw, &err) != 0))
    return snprintf(msg, size, "--name: %s", err.msg), MR_EXIT_USAGE;
  return 0;
}

int mr_run_takes_prepare(mr_run_takes *t, mr_show_def *def, size_t n_live, char *msg, size_t size) {
  t->n_live = n_live > 0 ? n_live : 1;
  if (t->book_dir == NULL) {
    if (t->over || t->arm || t->punch || t->name)
      return usage(msg, size, "expected --takes BOOK with --over, --arm, --punch or --name");
    return 0;
  }
  if ((t->arm != NULL || t->punch != NULL) && t->over == NULL)
    return usage(msg, size, "expected --over NAME (the take beneath) with --arm and --punch");
  if (t->punch != NULL && parse_punch(t->punch, &def->punch_in, &def->punch_out) != 0) {
    snprintf(msg, size, "expected --punch IN:OUT in seconds with 0 <= IN < OUT, got '%.40s'",
             t->punch);
    return MR_EXIT_USAGE;
  }
  if (t->arm != NULL && set_armed(t, def, msg, size) != 0) return MR_EXIT_USAGE;
  mr_take_error err;
  if (mr_take_book_open(t->book_dir, true, &t->book, &err) != 0)
    return snprintf(msg, size, "%s", err.msg), MR_EXIT_FAIL;
  t->book_open = true;
  if (t->over != NULL) {
    const mr_take_entry *e = mr_take_book_find(&t->book, t->over);
    if (e == NULL || e->deleted) {
      snprintf(msg, size, "no take '%.64s' in the book %.300s", t->over, t->book_dir);
      return MR_EXIT_USAGE;
    }
    if (set_beneath(t, t->over, def, msg, size) != 0) return MR_EXIT_FAIL;
  }
  int rc = check_names(t, msg, size);
  if (rc != 0) return rc;
  set_raw(t, def);
  return 0;
}

/* The raw take into the book: NAME-raw under a take beneath, else NAME. */
static int add_raw(mr_run_takes *t, const mr_show_def *def, mr_take_made *made, char *line,
                   size_t size) {
  char name[MR_TAKE_NAME_MAX + 8] = "";
  if (t->name != NULL)
    snprintf(name, sizeof name, "%.60s%s", t->name, t->beneath_name[0] ? "-raw" : "");
  const char *paths[MR_SHOW_MAX_GLOVES];
  for (size_t g = 0; g < t->n_live; g++) paths[g] = def->record[g];
  mr_take_error err;
  int rc =
      mr_take_book_add(&t->book, name[0] ? name : NULL, paths, t->n_live, t->own_raw, made, &err);
  if (rc != 0) snprintf(line, size, "the take was not stored: %s", err.msg);
  /* Recorded into the book's folder for a glove --record did not name. */
  if (!t->own_raw)
    for (size_t g = 0; g < t->n_live; g++)
      if (def->record[g] == t->raw[g]) unlink(t->raw[g]);
  return rc;
}

/* The merge: the channels armed at the punch-in, from the raw take, over
 * the take beneath. */
static int merge(mr_run_takes *t, const mr_show_result *r, const char *raw, mr_take_made *made,
                 mr_take_error *err) {
  mr_take_punch_def d = mr_default_take_punch_def();
  d.base = t->beneath_name;
  d.over = raw;
  d.name = t->name;
  for (size_t g = 0; g < t->n_live && g < MR_SHOW_MAX_GLOVES; g++)
    for (int f = 0; f < MR_TAKE_CHANNELS; f++)
      if (r->punched[g] & (1u << f)) {
        d.arms[d.n_arms].glove = (int)g;
        d.arms[d.n_arms++].finger = f;
      }
  d.t_in = r->punch_in;
  d.t_out = r->punch_out >= 0 ? r->punch_out : r->frames.sim_time;
  if (d.n_arms == 0) {
    snprintf(err->msg, sizeof err->msg, "no channel was armed at the punch-in");
    return -1;
  }
  return mr_take_book_punch(&t->book, &d, made, err);
}

int mr_run_takes_store(mr_run_takes *t, const mr_show_result *r, mr_show_def *def, char *line,
                       size_t size) {
  if (t->book_dir == NULL || !t->book_open) return MR_EXIT_OK;
  /* Over a take, a show that never punched in made no take. */
  if (t->beneath_name[0] != '\0' && r->punch_in < 0) {
    snprintf(line, size, "nothing punched in over '%s': no take stored", t->beneath_name);
    if (t->own_raw)
      for (size_t g = 0; g < t->n_live; g++) unlink(t->raw[g]);
    return MR_EXIT_OK;
  }
  mr_take_made raw;
  if (add_raw(t, def, &raw, line, size) != 0) return MR_EXIT_FAIL;
  int n = snprintf(line, size, "take '%s' (the raw input) stored in %s", raw.name, t->book_dir);
  if (t->beneath_name[0] != '\0' && r->punch_in >= 0) {
    mr_take_made merged;
    mr_take_error err;
    if (merge(t, r, raw.name, &merged, &err) != 0) {
      snprintf(line + n, size - (size_t)n, "; no merged take: %s", err.msg);
      return MR_EXIT_FAIL;
    }
    snprintf(line + n, size - (size_t)n,
             "; take '%s' is its armed channels over '%s' from %.3f to %.3f s", merged.name,
             t->beneath_name, r->punch_in, r->punch_out >= 0 ? r->punch_out : r->frames.sim_time);
    char msg[300];
    if (set_beneath(t, merged.name, def, msg, sizeof msg) != 0) return MR_EXIT_FAIL;
  }
  /* The next show's takes get names of their own. */
  t->name = NULL;
  t->pass++;
  def->punch_in = def->punch_out = -1.0;
  set_raw(t, def);
  return MR_EXIT_OK;
}

int mr_run_takes_step(mr_run_takes *t, int dir, mr_show_def *def, char *line, size_t size) {
  if (!t->book_open) return snprintf(line, size, "no take book (--takes BOOK)"), -1;
  size_t n = t->book.n, at = n;
  for (size_t i = 0; i < n; i++)
    if (strcmp(t->book.takes[i].name, t->beneath_name) == 0) at = i;
  for (size_t k = 1; k <= n; k++) {
    size_t i = at == n ? (dir < 0 ? n - k : k - 1) : (at + n + (dir < 0 ? n - k : k)) % n;
    const mr_take_entry *e = &t->book.takes[i];
    if (e->deleted) continue;
    if (set_beneath(t, e->name, def, line, size) != 0) return -1;
    snprintf(line, size, "take beneath: '%s' (the show starts again from 0)", e->name);
    return 0;
  }
  return snprintf(line, size, "the book %s has no takes yet", t->book_dir), -1;
}

void mr_run_takes_close(mr_run_takes *t) {
  if (t->book_open) mr_take_book_close(&t->book);
  t->book_open = false;
}
