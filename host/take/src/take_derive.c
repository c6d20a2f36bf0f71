/* Takes made from takes in the book: punch-in, split, trim, smoothing, a
 * time offset, time scaling. Each reads its sources' files, writes new
 * files under a fresh id (never over an existing file) and adds an entry
 * naming its sources. */
#include "take_internal.h"
#include "take_book.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "mr_def.h"

/* Makes glove k's new recording from in (loaded from the source's file). */
typedef int (*derive_fn)(const mr_take_rec *in, size_t k, mr_take_rec *out, void *ctx,
                         mr_take_error *err);

/* Writes r as the book's file name: to a temporary first, then linked to
 * its name, which fails rather than replace a file that exists. */
static int write_new(const mr_take_book *b, const char *name, const mr_take_rec *r,
                     mr_take_error *err) {
  char path[MR_TAKE_PATH_MAX + MR_TAKE_NAME_MAX], tmp[sizeof path + 32];
  snprintf(path, sizeof path, "%s/%s", b->dir, name);
  snprintf(tmp, sizeof tmp, "%s/.%s.%ld.tmp", b->dir, name, (long)getpid());
  if (mr_take_rec_write(r, tmp, err) != 0) {
    unlink(tmp);
    return -1;
  }
  int rc = link(tmp, path);
  int e = errno;
  unlink(tmp);
  if (rc != 0) return mr_take_fail(err, MR_TAKE_ERR_IO, "%s: cannot add: %s", path, strerror(e));
  return 0;
}

static void add_note(mr_take_made *m, const char *note) {
  if (note[0] == '\0' || m->note[0] != '\0') return;
  snprintf(m->note, sizeof m->note, "%s", note);
}

/* The new entry e (already appended) from the source src's files through fn.
 * On failure the entry and its files are gone again. */
static int derive(mr_take_book *b, const mr_take_entry *src, mr_take_entry *e, derive_fn fn,
                  void *ctx, mr_take_made *made, mr_take_error *err) {
  e->duration = 0;
  e->scene_hash = src->scene_hash;
  for (size_t k = 0; k < e->n_files; k++) {
    char path[MR_TAKE_PATH_MAX + MR_TAKE_NAME_MAX];
    snprintf(path, sizeof path, "%s/%s", b->dir, src->files[k]);
    mr_take_rec in, out;
    if (mr_take_rec_load(path, &in, err) != 0) {
      mr_take_book_drop_last(b);
      return -1;
    }
    add_note(made, in.note);
    int rc = fn(&in, k, &out, ctx, err);
    mr_take_rec_free(&in);
    if (rc == 0) {
      double d = mr_take_rec_duration(&out);
      if (d > e->duration) e->duration = d;
      rc = write_new(b, e->files[k], &out, err);
      mr_take_rec_free(&out);
    }
    if (rc != 0) {
      mr_take_book_drop_last(b);
      return -1;
    }
  }
  return 0;
}

/* Starts a take made from the take named source: its entry, or NULL. */
static mr_take_entry *start(mr_take_book *b, const char *source, const char *name, mr_take_how how,
                            const mr_take_entry **src, mr_take_error *err) {
  *src = mr_take_book_get(b, source, err);
  if (*src == NULL) return NULL;
  size_t at = (size_t)(*src - b->takes);
  mr_take_entry *e = mr_take_book_append(b, name, (*src)->n_files, how, err);
  *src = &b->takes[at]; /* the list may have moved */
  if (e != NULL) e->source_id = (*src)->id;
  return e;
}

/* 0 when glove g, finger k is a channel of take t, else the error naming
 * what (an armed channel, a channel): a channel past the take's gloves
 * would be written into the new take's lineage and change nothing. */
static int channel_of(const mr_take_entry *t, const char *what, int g, int k, mr_take_error *err) {
  if (g >= 0 && (size_t)g < t->n_files && k >= 0 && k < MR_TAKE_CHANNELS) return 0;
  return mr_take_fail(err, MR_TAKE_ERR_ARG,
                      "%s %d:%d: take '%s' has gloves 0..%zu and fingers 0..4", what, g, k, t->name,
                      t->n_files - 1);
}

/* Saves the list with the new entries; on failure drops n of them. */
static int finish(mr_take_book *b, size_t n, mr_take_made *made, mr_take_made *out,
                  mr_take_error *err) {
  if (mr_take_json_write(b, err) != 0) {
    for (size_t i = 0; i < n; i++) mr_take_book_drop_last(b);
    return -1;
  }
  if (out != NULL) *out = *made;
  return 0;
}

/* --- punch-in --------------------------------------------------------------- */

typedef struct punch_ctx {
  const mr_take_book *b;
  const mr_take_entry *over;
  const mr_take_punch_def *d;
  mr_take_made *made;
} punch_ctx;

static int punch_one(const mr_take_rec *in, size_t k, mr_take_rec *out, void *ctx,
                     mr_take_error *err) {
  const punch_ctx *p = ctx;
  unsigned mask = 0;
  for (size_t i = 0; i < p->d->n_arms; i++)
    if ((size_t)p->d->arms[i].glove == k) mask |= 1u << p->d->arms[i].finger;
  if (mr_take_rec_copy(out, in, err) != 0) return -1;
  mr_take_rec over;
  bool have = k < p->over->n_files && mask != 0;
  if (have) {
    char path[MR_TAKE_PATH_MAX + MR_TAKE_NAME_MAX];
    snprintf(path, sizeof path, "%s/%s", p->b->dir, p->over->files[k]);
    if (mr_take_rec_load(path, &over, err) != 0) {
      mr_take_rec_free(out);
      return -1;
    }
    add_note(p->made, over.note);
  }
  int rc = mr_take_punch_rec(out, have ? &over : NULL, mask, p->d->t_in, p->d->t_out, err);
  if (have) mr_take_rec_free(&over);
  if (rc != 0) mr_take_rec_free(out);
  return rc;
}

static int check_punch(const mr_take_book *b, const mr_take_punch_def *d, const mr_take_entry *base,
                       const mr_take_entry *over, mr_take_error *err) {
  if (!(isfinite(d->t_in) && isfinite(d->t_out) && d->t_in >= 0 && d->t_in < d->t_out))
    return mr_take_fail(err, MR_TAKE_ERR_ARG,
                        "expected 0 <= punch-in < punch-out, got %g and "
                        "%g s",
                        d->t_in, d->t_out);
  if (d->n_arms == 0 || d->n_arms > MR_TAKE_MAX_ARMS)
    return mr_take_fail(err, MR_TAKE_ERR_ARG, "expected 1..%d armed channels, got %zu",
                        MR_TAKE_MAX_ARMS, d->n_arms);
  for (size_t i = 0; i < d->n_arms; i++)
    if (channel_of(base, "armed channel", d->arms[i].glove, d->arms[i].finger, err) != 0) return -1;
  if (base->scene_hash != 0 && over->scene_hash != 0 && base->scene_hash != over->scene_hash)
    return mr_take_fail(err, MR_TAKE_ERR_SCENE,
                        "%s: take '%s' was recorded against scene "
                        "%016llx, take '%s' against scene %016llx",
                        b->dir, base->name, (unsigned long long)base->scene_hash, over->name,
                        (unsigned long long)over->scene_hash);
  return 0;
}

int mr_take_book_punch(mr_take_book *b, const mr_take_punch_def *d, mr_take_made *made,
                       mr_take_error *err) {
  if (d == NULL || d->cookie != MR_DEF_COOKIE)
    return mr_take_fail(err, MR_TAKE_ERR_ARG, "a punch needs mr_default_take_punch_def()");
  const mr_take_entry *over = mr_take_book_get(b, d->over, err), *base;
  if (over == NULL) return -1;
  int over_id = over->id;
  base = mr_take_book_get(b, d->base, err);
  if (base == NULL || check_punch(b, d, base, over, err) != 0) return -1;
  mr_take_entry *e = start(b, d->base, d->name, MR_TAKE_PUNCHED, &base, err);
  if (e == NULL) return -1;
  over = mr_take_book_find_id(b, over_id);
  e->over_id = over_id;
  e->t0 = d->t_in;
  e->t1 = d->t_out;
  e->n_arms = d->n_arms;
  memcpy(e->arms, d->arms, d->n_arms * sizeof *d->arms);
  mr_take_made m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "%s", e->name);
  punch_ctx ctx = { b, over, d, &m };
  if (derive(b, base, e, punch_one, &ctx, &m, err) != 0) return -1;
  return finish(b, 1, &m, made, err);
}

/* --- split and trim --------------------------------------------------------- */

typedef struct span {
  double t0, t1;
} span;

static int trim_one(const mr_take_rec *in, size_t k, mr_take_rec *out, void *ctx,
                    mr_take_error *err) {
  (void)k;
  const span *s = ctx;
  return mr_take_trim_rec(in, s->t0, s->t1, out, err);
}

static int trim_entry(mr_take_book *b, const char *source, span s, mr_take_how how, int part,
                      const char *name, mr_take_made *m, mr_take_error *err) {
  const mr_take_entry *src;
  mr_take_entry *e = start(b, source, name, how, &src, err);
  if (e == NULL) return -1;
  e->t0 = how == MR_TAKE_SPLIT && part == 2 ? s.t0 : how == MR_TAKE_SPLIT ? s.t1 : s.t0;
  e->t1 = s.t1;
  e->part = part;
  snprintf(part == 2 ? m->name2 : m->name, sizeof m->name, "%s", e->name);
  return derive(b, src, e, trim_one, &s, m, err);
}

static int check_at(double t, const char *what, mr_take_error *err) {
  if (!isfinite(t) || t <= 0.0 || t > 1e6)
    return mr_take_fail(err, MR_TAKE_ERR_ARG, "%s must be a time > 0 s, got %g", what, t);
  return 0;
}

int mr_take_book_split(mr_take_book *b, const char *source, double at, const char *name1,
                       const char *name2, mr_take_made *made, mr_take_error *err) {
  if (check_at(at, "the split time", err) != 0) return -1;
  const mr_take_entry *src = mr_take_book_get(b, source, err);
  if (src == NULL) return -1;
  if (at >= src->duration)
    return mr_take_fail(err, MR_TAKE_ERR_ARG, "take '%s' lasts %g s: nothing after %g s", source,
                        src->duration, at);
  mr_take_made m;
  memset(&m, 0, sizeof m);
  if (trim_entry(b, source, (span){ 0.0, at }, MR_TAKE_SPLIT, 1, name1, &m, err) != 0) return -1;
  if (trim_entry(b, source, (span){ at, INFINITY }, MR_TAKE_SPLIT, 2, name2, &m, err) != 0) {
    mr_take_book_drop_last(b);
    return -1;
  }
  return finish(b, 2, &m, made, err);
}

int mr_take_book_trim(mr_take_book *b, const char *source, double t0, double t1, const char *name,
                      mr_take_made *made, mr_take_error *err) {
  if (!isfinite(t0) || !isfinite(t1) || t0 < 0.0 || !(t0 < t1))
    return mr_take_fail(err, MR_TAKE_ERR_ARG, "expected 0 <= from < to, got %g and %g s", t0, t1);
  mr_take_made m;
  memset(&m, 0, sizeof m);
  if (trim_entry(b, source, (span){ t0, t1 }, MR_TAKE_TRIMMED, 0, name, &m, err) != 0) return -1;
  return finish(b, 1, &m, made, err);
}

/* --- filters and scaling ---------------------------------------------------- */

static unsigned mask_of(const mr_take_arm *arms, size_t n, size_t glove) {
  if (n == 0) return (1u << MR_TAKE_CHANNELS) - 1u;
  unsigned mask = 0;
  for (size_t i = 0; i < n; i++)
    if ((size_t)arms[i].glove == glove) mask |= 1u << arms[i].finger;
  return mask;
}

static int smooth_one(const mr_take_rec *in, size_t k, mr_take_rec *out, void *ctx,
                      mr_take_error *err) {
  const mr_take_smooth_def *d = ctx;
  if (mr_take_rec_copy(out, in, err) != 0) return -1;
  int rc = mr_take_smooth_rec(out, mask_of(d->channels, d->n_channels, k), d->min_cutoff, d->beta,
                              d->d_cutoff, err);
  if (rc != 0) mr_take_rec_free(out);
  return rc;
}

int mr_take_book_smooth(mr_take_book *b, const char *source, const mr_take_smooth_def *d,
                        const char *name, mr_take_made *made, mr_take_error *err) {
  if (d == NULL || d->cookie != MR_DEF_COOKIE)
    return mr_take_fail(err, MR_TAKE_ERR_ARG, "smoothing needs mr_default_take_smooth_def()");
  if (!(isfinite(d->min_cutoff) && d->min_cutoff > 0) || !(isfinite(d->beta) && d->beta >= 0) ||
      !(isfinite(d->d_cutoff) && d->d_cutoff > 0))
    return mr_take_fail(err, MR_TAKE_ERR_ARG,
                        "smoothing needs min-cutoff > 0, beta >= 0 and "
                        "d-cutoff > 0, got %g, %g and %g",
                        d->min_cutoff, d->beta, d->d_cutoff);
  if (d->n_channels > MR_TAKE_MAX_ARMS)
    return mr_take_fail(err, MR_TAKE_ERR_ARG, "expected at most %d channels to smooth, got %zu",
                        MR_TAKE_MAX_ARMS, d->n_channels);
  /* A source not in the book is start()'s to report. */
  const mr_take_entry *src = mr_take_book_get(b, source, err);
  for (size_t i = 0; src != NULL && i < d->n_channels; i++)
    if (channel_of(src, "channel", d->channels[i].glove, d->channels[i].finger, err) != 0)
      return -1;
  mr_take_entry *e = start(b, source, name, MR_TAKE_SMOOTHED, &src, err);
  if (e == NULL) return -1;
  e->min_cutoff = d->min_cutoff;
  e->beta = d->beta;
  e->d_cutoff = d->d_cutoff;
  e->n_arms = d->n_channels;
  memcpy(e->arms, d->channels, d->n_channels * sizeof *d->channels);
  mr_take_made m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "%s", e->name);
  if (derive(b, src, e, smooth_one, (void *)d, &m, err) != 0) return -1;
  return finish(b, 1, &m, made, err);
}

static int offset_one(const mr_take_rec *in, size_t k, mr_take_rec *out, void *ctx,
                      mr_take_error *err) {
  const double(*offset)[MR_TAKE_CHANNELS] = ctx;
  if (mr_take_rec_copy(out, in, err) != 0) return -1;
  int rc = mr_take_offset_rec(out, offset[k], err);
  if (rc != 0) mr_take_rec_free(out);
  return rc;
}

int mr_take_book_offset(mr_take_book *b, const char *source,
                        const double offset[MR_TAKE_MAX_GLOVES][MR_TAKE_CHANNELS], const char *name,
                        mr_take_made *made, mr_take_error *err) {
  for (int g = 0; g < MR_TAKE_MAX_GLOVES; g++)
    for (int k = 0; k < MR_TAKE_CHANNELS; k++)
      if (!isfinite(offset[g][k]) || fabs(offset[g][k]) > 3600.0)
        return mr_take_fail(err, MR_TAKE_ERR_ARG,
                            "an offset must be -3600..3600 s, got %g for "
                            "%d:%d",
                            offset[g][k], g, k);
  const mr_take_entry *src = mr_take_book_get(b, source, err); /* if NULL: start() says so */
  for (int g = 0; src != NULL && g < MR_TAKE_MAX_GLOVES; g++)
    for (int k = 0; k < MR_TAKE_CHANNELS; k++)
      if (offset[g][k] != 0.0 && channel_of(src, "channel", g, k, err) != 0) return -1;
  mr_take_entry *e = start(b, source, name, MR_TAKE_OFFSET, &src, err);
  if (e == NULL) return -1;
  for (int g = 0; g < MR_TAKE_MAX_GLOVES; g++)
    for (int k = 0; k < MR_TAKE_CHANNELS; k++) {
      e->offset[g][k] = offset[g][k];
      if (offset[g][k] != 0.0) e->arms[e->n_arms++] = (mr_take_arm){ g, k };
    }
  mr_take_made m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "%s", e->name);
  if (derive(b, src, e, offset_one, (void *)offset, &m, err) != 0) return -1;
  return finish(b, 1, &m, made, err);
}

static int scale_one(const mr_take_rec *in, size_t k, mr_take_rec *out, void *ctx,
                     mr_take_error *err) {
  (void)k;
  if (mr_take_rec_copy(out, in, err) != 0) return -1;
  int rc = mr_take_scale_rec(out, *(const double *)ctx, err);
  if (rc != 0) mr_take_rec_free(out);
  return rc;
}

int mr_take_book_scale(mr_take_book *b, const char *source, double factor, const char *name,
                       mr_take_made *made, mr_take_error *err) {
  if (!isfinite(factor) || !(factor > 0.0) || factor > 1e6)
    return mr_take_fail(err, MR_TAKE_ERR_ARG,
                        "the time factor must be a number > 0 (at most "
                        "1e6), got %g",
                        factor);
  const mr_take_entry *src;
  mr_take_entry *e = start(b, source, name, MR_TAKE_SCALED, &src, err);
  if (e == NULL) return -1;
  e->factor = factor;
  mr_take_made m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "%s", e->name);
  if (derive(b, src, e, scale_one, &factor, &m, err) != 0) return -1;
  return finish(b, 1, &m, made, err);
}
