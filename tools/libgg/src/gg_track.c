#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gg_track.h"
#include "gp.h"
#include "mr_io.h"

static gg_track *track_new(void) {
  gg_track *t = calloc(1, sizeof *t);
  if (t) t->refs = 1;
  return t;
}

static int track_push(gg_track *t, size_t *cap, double time_s, const double v[GG_CHANNELS]) {
  if (t->n == *cap) {
    size_t nc = *cap ? *cap * 2 : 1024;
    double *nt = realloc(t->t, nc * sizeof *nt);
    double *nv;
    if (!nt) return -1;
    t->t = nt;
    nv = realloc(t->v, nc * GG_CHANNELS * sizeof *nv);
    if (!nv) return -1;
    t->v = nv;
    *cap = nc;
  }
  t->t[t->n] = time_s;
  memcpy(&t->v[t->n * GG_CHANNELS], v, GG_CHANNELS * sizeof *v);
  t->n++;
  return 0;
}

gg_track *gg_track_retain(gg_track *t) {
  if (t) t->refs++;
  return t;
}

void gg_track_release(gg_track *t) {
  if (!t || --t->refs > 0) return;
  free(t->t);
  free(t->v);
  free(t);
}

/* Where the header put the time and each channel, and the time's unit. */
typedef struct csv_cols {
  int tcol, chcol[GG_CHANNELS];
  double tscale; /* seconds per unit of the time column */
} csv_cols;

/* Cuts line at its commas, in place: the field count (at most max kept). */
static int split_fields(char *line, char **fields, int max) {
  int nf = 0;
  char *p = line;
  for (;;) {
    if (nf < max) fields[nf++] = p;
    p = strchr(p, ',');
    if (!p) break;
    *p++ = 0;
  }
  return nf;
}

/* Columns are found by name in the header: t_us (µs) or t / t_s (seconds),
 * and ch0..ch4 in ADC counts, which is what glove-dump --csv writes. */
static int read_header(csv_cols *k, char **fields, int nf, const char *where, char *err,
                       size_t errcap) {
  for (int i = 0; i < nf; i++) {
    if (strcmp(fields[i], "t_us") == 0) {
      k->tcol = i;
      k->tscale = 1e-6;
    } else if (strcmp(fields[i], "t") == 0 || strcmp(fields[i], "t_s") == 0) {
      k->tcol = i;
      k->tscale = 1;
    } else if (strncmp(fields[i], "ch", 2) == 0 && fields[i][2] >= '0' && fields[i][2] <= '4' &&
               !fields[i][3]) {
      k->chcol[fields[i][2] - '0'] = i;
    }
  }
  if (k->tcol < 0) {
    snprintf(err, errcap, "%s:1: header has no time column (t_us, t or t_s)", where);
    return -1;
  }
  for (int c = 0; c < GG_CHANNELS; c++)
    if (k->chcol[c] < 0) {
      snprintf(err, errcap, "%s:1: header has no ch%d column", where, c);
      return -1;
    }
  return 0;
}

/* One row's time (seconds) and channel values (0..1). */
static int read_row(const csv_cols *k, char **fields, int nf, double *tv, double v[GG_CHANNELS],
                    const char *where, char *err, size_t errcap) {
  int col = 1;
  for (int i = 0; i < nf; i++) {
    int want = i == k->tcol;
    int c;
    for (c = 0; c < GG_CHANNELS && !want; c++) want = k->chcol[c] == i;
    if (want) {
      char *end;
      double x;
      errno = 0;
      x = strtod(fields[i], &end);
      if (errno || end == fields[i] || *end || !isfinite(x)) {
        snprintf(err, errcap, "%s:%d: '%s' is not a finite number", where, col, fields[i]);
        return -1;
      }
      if (i == k->tcol) *tv = x * k->tscale;
      for (c = 0; c < GG_CHANNELS; c++)
        if (k->chcol[c] == i) v[c] = x / GG_ADC_MAX;
    }
    col += (int)strlen(fields[i]) + 1;
  }
  int need = k->tcol;
  for (int c = 0; c < GG_CHANNELS; c++)
    if (k->chcol[c] > need) need = k->chcol[c];
  if (nf <= need) {
    snprintf(err, errcap, "%s:%d: row has %d columns, the header more", where, col, nf);
    return -1;
  }
  return 0;
}

gg_track *gg_track_load_csv(const char *path, char *err, size_t errcap) {
  FILE *f = fopen(path, "r");
  char line[4096], where[4200];
  int lineno = 0, have_header = 0;
  csv_cols k = { -1, { -1, -1, -1, -1, -1 }, 1 };
  double t0 = 0, last = -INFINITY;
  size_t cap = 0;
  gg_track *t;
  if (!f) {
    snprintf(err, errcap, "%s: cannot open: %s", path, strerror(errno));
    return NULL;
  }
  t = track_new();
  if (!t) goto oom;
  while (fgets(line, sizeof line, f)) {
    char *fields[64];
    lineno++;
    line[strcspn(line, "\r\n")] = 0;
    if (!line[0] || line[0] == '#') continue;
    int nf = split_fields(line, fields, 64);
    snprintf(where, sizeof where, "%s:%d", path, lineno);
    if (!have_header) {
      if (read_header(&k, fields, nf, where, err, errcap) != 0) goto fail;
      have_header = 1;
      continue;
    }
    double v[GG_CHANNELS], tv = 0;
    if (read_row(&k, fields, nf, &tv, v, where, err, errcap) != 0) goto fail;
    if (t->n == 0) t0 = tv;
    if (tv - t0 < last) {
      snprintf(err, errcap, "%s:1: time goes backwards", where);
      goto fail;
    }
    last = tv - t0;
    if (track_push(t, &cap, tv - t0, v) != 0) goto oom;
  }
  fclose(f);
  if (t->n == 0) {
    snprintf(err, errcap, "%s:%d:1: no rows", path, lineno);
    gg_track_release(t);
    return NULL;
  }
  return t;
oom:
  snprintf(err, errcap, "%s: out of memory", path);
fail:
  fclose(f);
  gg_track_release(t);
  return NULL;
}

/* Decodes the SAMPLE frames of a recording; their device time (unwrapped)
 * becomes the track's time. A cut-short last chunk keeps what came before,
 * and is reported on stderr. */
gg_track *gg_track_load_mrec(const char *path, char *err, size_t errcap) {
  mr_rec_reader r;
  mr_io_error e;
  gp_decoder *d = malloc(sizeof *d);
  gg_track *t = track_new();
  size_t cap = 0;
  uint64_t t_ns;
  const uint8_t *data;
  size_t len;
  uint32_t last_us = 0;
  double time_s = 0;
  int rc;
  if (!d || !t) {
    snprintf(err, errcap, "%s: out of memory", path);
    goto fail_nofile;
  }
  if (mr_rec_reader_open(&r, path, &e) != 0) {
    snprintf(err, errcap, "%s", e.msg);
    goto fail_nofile;
  }
  gp_decoder_init(d, GP_SPEC_HASH);
  while ((rc = mr_rec_reader_next(&r, &t_ns, &data, &len, &e)) == 1) {
    while (len) {
      gp_msg msg;
      gp_event ev;
      size_t used = gp_decoder_feed(d, data, len, &msg, &ev);
      data += used;
      len -= used;
      if (ev == GP_EV_FRAME && msg.type == GP_SAMPLE) {
        double v[GG_CHANNELS];
        if (t->n) time_s += (uint32_t)(msg.u.sample.t_us - last_us) * 1e-6;
        last_us = msg.u.sample.t_us;
        for (int c = 0; c < GG_CHANNELS; c++) v[c] = msg.u.sample.ch[c] / (double)GG_ADC_MAX;
        if (track_push(t, &cap, time_s, v) != 0) {
          snprintf(err, errcap, "%s: out of memory", path);
          mr_rec_reader_close(&r);
          goto fail_nofile;
        }
      }
    }
  }
  mr_rec_reader_close(&r);
  if (rc < 0 && e.status != MR_IO_ERR_TRUNCATED) {
    snprintf(err, errcap, "%s", e.msg);
    goto fail_nofile;
  }
  /* A recorder that was killed leaves the last chunk short: the samples
   * before it are good, but say what is missing rather than hide it. */
  if (rc < 0) fprintf(stderr, "glove-gen: %s (the samples before it are used)\n", e.msg);
  if (t->n == 0) {
    snprintf(err, errcap, "%s: no SAMPLE frames in the recording", path);
    goto fail_nofile;
  }
  free(d);
  return t;
fail_nofile:
  free(d);
  gg_track_release(t);
  return NULL;
}

double gg_track_eval(const gg_track *t, int column, double t_s, int loop) {
  size_t lo = 0, hi = t->n - 1;
  double span = t->t[t->n - 1];
  if (loop && span > 0 && t_s > span) t_s = fmod(t_s, span);
  if (t_s <= t->t[0]) return t->v[column];
  if (t_s >= span) return t->v[(t->n - 1) * GG_CHANNELS + (size_t)column];
  while (hi - lo > 1) {
    size_t mid = (lo + hi) / 2;
    if (t->t[mid] <= t_s)
      lo = mid;
    else
      hi = mid;
  }
  {
    double a = t->v[lo * GG_CHANNELS + (size_t)column], b = t->v[hi * GG_CHANNELS + (size_t)column];
    double dt = t->t[hi] - t->t[lo];
    return dt > 0 ? a + (b - a) * (t_s - t->t[lo]) / dt : b;
  }
}
