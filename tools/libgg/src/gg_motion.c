/* Motion scripts: parsing and evaluation. The format is in tools/README.md;
 * in short, one line per channel selection:
 *
 *   duration 30
 *   all    sine mid=0.5 amp=0.3 freq=0.5 to=4 over=20
 *   thumb  keys ease=inout 0:0.1 1.5:0.9 3:0.1 loop=1
 *   index  step from=0.2 to=0.8 at=1 period=2
 *   ring   walk start=0.5 sigma=0.3
 *   little csv file=take1.csv
 *
 * Values are 0..1 of the ADC range; times are seconds of stream time. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gg_motion.h"
#include "gg_track.h"
#include "gp_glove.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static const char *const finger_names[GG_CHANNELS] = { "thumb", "index", "middle", "ring",
                                                       "little" };

static void gen_init(gg_gen *g) {
  memset(g, 0, sizeof *g);
  g->shape = GG_CONST;
  g->value = 0.5;
}

static void gen_free(gg_gen *g) {
  free(g->keys);
  gg_track_release(g->track);
  gen_init(g);
}

static void motion_init(gg_motion *m, uint64_t seed) {
  memset(m, 0, sizeof *m);
  for (int i = 0; i < GG_CHANNELS; i++) gen_init(&m->ch[i]);
  gg_rng_seed(&m->rng, seed ^ 0x6D6F74696F6E0000ull);
}

void gg_motion_default(gg_motion *m, uint64_t seed) {
  motion_init(m, seed);
  /* Fingers at different slow rates, as a hand opening and closing. */
  for (int i = 0; i < GG_CHANNELS; i++) {
    gg_gen *g = &m->ch[i];
    g->shape = GG_SINE;
    g->mid = 0.5;
    g->amp = 0.35;
    g->freq = 0.3 + 0.11 * i;
    g->phase = 0.9 * i;
  }
}

void gg_motion_free(gg_motion *m) {
  for (int i = 0; i < GG_CHANNELS; i++) gen_free(&m->ch[i]);
}

/* --- parsing ----------------------------------------------------------------- */

typedef struct tok {
  const char *s;
  size_t len;
  int col;
} tok;

typedef struct ctx {
  const char *path;
  int line;
  char *err;
  size_t errcap;
  char dir[1024]; /* the script's folder, for relative track paths */
} ctx;

static int fail(ctx *c, int col, const char *fmt, ...) {
  va_list ap;
  int n = snprintf(c->err, c->errcap, "%s:%d:%d: ", c->path, c->line, col);
  va_start(ap, fmt);
  if (n >= 0 && (size_t)n < c->errcap) vsnprintf(c->err + n, c->errcap - (size_t)n, fmt, ap);
  va_end(ap);
  return -1;
}

static int tok_is(const tok *t, const char *w) {
  return t->len == strlen(w) && strncmp(t->s, w, t->len) == 0;
}

static int parse_num(ctx *c, const tok *t, const char *s, size_t len, double *out) {
  char buf[64];
  char *end;
  double v;
  if (len == 0 || len >= sizeof buf) return fail(c, t->col, "expected a number");
  memcpy(buf, s, len);
  buf[len] = 0;
  errno = 0;
  v = strtod(buf, &end);
  if (errno || *end || !isfinite(v)) return fail(c, t->col, "'%s' is not a finite number", buf);
  *out = v;
  return 0;
}

static int parse_ease(ctx *c, const tok *t, const char *s, size_t len, gg_ease *out) {
  static const struct {
    const char *name;
    gg_ease e;
  } names[] = {
    { "linear", GG_EASE_LINEAR }, { "hold", GG_EASE_HOLD },   { "in", GG_EASE_IN },
    { "out", GG_EASE_OUT },       { "inout", GG_EASE_INOUT }, { "sine", GG_EASE_SINE }
  };
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
    if (strlen(names[i].name) == len && strncmp(s, names[i].name, len) == 0) {
      *out = names[i].e;
      return 0;
    }
  return fail(c, t->col, "unknown easing '%.*s' (linear, hold, in, out, inout, sine)", (int)len, s);
}

/* "all", a finger name, a channel number, "1-3", or a comma list of those. */
static int parse_channels(ctx *c, const tok *t, int sel[GG_CHANNELS]) {
  const char *p = t->s, *end = t->s + t->len;
  memset(sel, 0, sizeof(int) * GG_CHANNELS);
  while (p < end) {
    const char *q = memchr(p, ',', (size_t)(end - p));
    size_t n;
    int found = 0;
    if (!q) q = end;
    n = (size_t)(q - p);
    if (n == 3 && strncmp(p, "all", 3) == 0) {
      for (int i = 0; i < GG_CHANNELS; i++) sel[i] = 1;
      found = 1;
    }
    for (int i = 0; i < GG_CHANNELS && !found; i++)
      if (strlen(finger_names[i]) == n && strncmp(p, finger_names[i], n) == 0) sel[i] = found = 1;
    if (!found && n == 1 && p[0] >= '0' && p[0] <= '4') sel[p[0] - '0'] = found = 1;
    if (!found && n == 3 && p[1] == '-' && p[0] >= '0' && p[0] <= '4' && p[2] >= p[0] &&
        p[2] <= '4') {
      for (int i = p[0] - '0'; i <= p[2] - '0'; i++) sel[i] = 1;
      found = 1;
    }
    if (!found)
      return fail(c, t->col + (int)(p - t->s),
                  "unknown channel '%.*s' (all, thumb, index, middle, ring, little, 0..4, 1-3)",
                  (int)n, p);
    p = q + 1;
  }
  return 0;
}

/* Splits a key=value token; *val is NULL when there is no '='. */
static void split_kv(const tok *t, size_t *klen, const char **val, size_t *vlen) {
  const char *eq = memchr(t->s, '=', t->len);
  *klen = eq ? (size_t)(eq - t->s) : t->len;
  *val = eq ? eq + 1 : NULL;
  *vlen = eq ? t->len - *klen - 1 : 0;
}

static int key_is(const tok *t, size_t klen, const char *w) {
  return klen == strlen(w) && strncmp(t->s, w, klen) == 0;
}

static int parse_keys(ctx *c, const tok *toks, int nt, gg_gen *g) {
  gg_ease def = GG_EASE_LINEAR;
  size_t cap = 0;
  /* Options first, so that ease= applies to every key on the line. */
  for (int i = 0; i < nt; i++) {
    size_t kl, vl;
    const char *v;
    split_kv(&toks[i], &kl, &v, &vl);
    if (!v) continue;
    if (key_is(&toks[i], kl, "ease")) {
      if (parse_ease(c, &toks[i], v, vl, &def) != 0) return -1;
    } else if (key_is(&toks[i], kl, "loop")) {
      double d;
      if (parse_num(c, &toks[i], v, vl, &d) != 0) return -1;
      g->loop = d != 0;
    } else {
      return fail(c, toks[i].col, "unknown option '%.*s' for keys (ease, loop)", (int)kl,
                  toks[i].s);
    }
  }
  for (int i = 0; i < nt; i++) {
    const tok *t = &toks[i];
    const char *c1, *c2;
    gg_key k;
    if (memchr(t->s, '=', t->len)) continue;
    c1 = memchr(t->s, ':', t->len);
    if (!c1) return fail(c, t->col, "expected a key TIME:VALUE[:EASE]");
    c2 = memchr(c1 + 1, ':', t->len - (size_t)(c1 + 1 - t->s));
    if (parse_num(c, t, t->s, (size_t)(c1 - t->s), &k.t) != 0) return -1;
    if (parse_num(c, t, c1 + 1, (size_t)((c2 ? c2 : t->s + t->len) - c1 - 1), &k.v) != 0) return -1;
    k.ease = def;
    if (c2 && parse_ease(c, t, c2 + 1, (size_t)(t->s + t->len - c2 - 1), &k.ease) != 0) return -1;
    if (g->n_keys && k.t <= g->keys[g->n_keys - 1].t)
      return fail(c, t->col, "key time %g is not after the previous key's %g", k.t,
                  g->keys[g->n_keys - 1].t);
    if (g->n_keys == cap) {
      gg_key *nk;
      cap = cap ? cap * 2 : 8;
      nk = realloc(g->keys, cap * sizeof *nk);
      if (!nk) return fail(c, t->col, "out of memory");
      g->keys = nk;
    }
    g->keys[g->n_keys++] = k;
  }
  if (g->n_keys == 0) return fail(c, toks[-1].col, "keys needs at least one TIME:VALUE");
  return 0;
}

typedef struct opt {
  const char *name;
  double *dst;
} opt;

static int parse_opts(ctx *c, const tok *toks, int nt, const opt *opts, const char *shape,
                      const char *names) {
  for (int i = 0; i < nt; i++) {
    size_t kl, vl;
    const char *v;
    const opt *o;
    split_kv(&toks[i], &kl, &v, &vl);
    if (!v) return fail(c, toks[i].col, "expected NAME=VALUE for %s (%s)", shape, names);
    for (o = opts; o->name; o++)
      if (key_is(&toks[i], kl, o->name)) break;
    if (!o->name)
      return fail(c, toks[i].col, "unknown option '%.*s' for %s (%s)", (int)kl, toks[i].s, shape,
                  names);
    if (parse_num(c, &toks[i], v, vl, o->dst) != 0) return -1;
  }
  return 0;
}

static int parse_track(ctx *c, const tok *toks, int nt, const tok *kind, gg_gen *g,
                       gg_track **track, double *column) {
  char file[1024] = "", full[2100], err[512];
  double loop = 1;
  int file_col = kind->col;
  for (int i = 0; i < nt; i++) {
    size_t kl, vl;
    const char *v;
    split_kv(&toks[i], &kl, &v, &vl);
    if (v && key_is(&toks[i], kl, "file") && vl < sizeof file) {
      memcpy(file, v, vl);
      file[vl] = 0;
      file_col = toks[i].col;
    } else if (v && key_is(&toks[i], kl, "loop")) {
      if (parse_num(c, &toks[i], v, vl, &loop) != 0) return -1;
    } else if (v && key_is(&toks[i], kl, "column")) {
      if (parse_num(c, &toks[i], v, vl, column) != 0) return -1;
      if (*column < 0 || *column > 4 || *column != floor(*column))
        return fail(c, toks[i].col, "column must be 0..4");
    } else {
      return fail(c, toks[i].col, "unknown option '%.*s' for %.*s (file, column, loop)", (int)kl,
                  toks[i].s, (int)kind->len, kind->s);
    }
  }
  if (!file[0]) return fail(c, kind->col, "%.*s needs file=PATH", (int)kind->len, kind->s);
  if (file[0] == '/' || !c->dir[0])
    snprintf(full, sizeof full, "%s", file);
  else
    snprintf(full, sizeof full, "%s/%s", c->dir, file);
  *track = tok_is(kind, "csv") ? gg_track_load_csv(full, err, sizeof err)
                               : gg_track_load_mrec(full, err, sizeof err);
  if (!*track) return fail(c, file_col, "%s", err);
  g->loop = loop != 0;
  return 0;
}

static int parse_duration(ctx *c, gg_motion *m, const tok *toks, int nt) {
  if (nt != 2) return fail(c, toks[0].col, "expected 'duration SECONDS'");
  if (parse_num(c, &toks[1], toks[1].s, toks[1].len, &m->duration_s) != 0) return -1;
  if (m->duration_s <= 0) return fail(c, toks[1].col, "duration must be positive");
  return 0;
}

/* The options of each shape (toks: those after the shape's name) into g. */
static int parse_sine(ctx *c, const tok *kind, const tok *toks, int nt, gg_gen *g) {
  double phase_deg = 0;
  opt o[] = { { "mid", &g->mid },     { "amp", &g->amp },      { "freq", &g->freq },
              { "to", &g->freq_end }, { "over", &g->sweep_s }, { "phase", &phase_deg },
              { NULL, NULL } };
  g->shape = GG_SINE;
  g->mid = 0.5;
  g->amp = 0.4;
  g->freq = 1;
  g->freq_end = -1;
  if (parse_opts(c, toks, nt, o, "sine", "mid, amp, freq, to, over, phase") != 0) return -1;
  if (g->freq_end < 0) g->freq_end = g->freq;
  if (g->sweep_s < 0) return fail(c, kind->col, "over must not be negative");
  g->phase = phase_deg * M_PI / 180.0;
  return 0;
}

static int parse_step(ctx *c, const tok *kind, const tok *toks, int nt, gg_gen *g) {
  opt o[] = { { "from", &g->from },     { "to", &g->to },     { "at", &g->at },
              { "period", &g->period }, { "duty", &g->duty }, { NULL, NULL } };
  g->shape = GG_STEP;
  g->to = 1;
  g->at = 1;
  g->duty = 0.5;
  if (parse_opts(c, toks, nt, o, "step", "from, to, at, period, duty") != 0) return -1;
  if (g->period < 0 || g->duty < 0 || g->duty > 1)
    return fail(c, kind->col, "step needs period >= 0 and duty in 0..1");
  return 0;
}

static int parse_walk(ctx *c, const tok *kind, const tok *toks, int nt, gg_gen *g) {
  opt o[] = { { "start", &g->start },
              { "sigma", &g->sigma },
              { "min", &g->lo },
              { "max", &g->hi },
              { NULL, NULL } };
  g->shape = GG_WALK;
  g->start = 0.5;
  g->sigma = 0.3;
  g->hi = 1;
  if (parse_opts(c, toks, nt, o, "walk", "start, sigma, min, max") != 0) return -1;
  if (!(g->lo < g->hi) || g->sigma < 0)
    return fail(c, kind->col, "walk needs min < max and sigma >= 0");
  g->walk_v = g->start < g->lo ? g->lo : g->start > g->hi ? g->hi : g->start;
  return 0;
}

/* The motion named by kind, with its options toks, into g (and a track's
 * file into *track and *column). */
static int parse_motion(ctx *c, const tok *kind, const tok *toks, int nt, gg_gen *g,
                        gg_track **track, double *column) {
  if (tok_is(kind, "const")) {
    opt o[] = { { "value", &g->value }, { NULL, NULL } };
    g->shape = GG_CONST;
    return parse_opts(c, toks, nt, o, "const", "value");
  }
  if (tok_is(kind, "keys")) {
    g->shape = GG_KEYS;
    if (parse_keys(c, toks, nt, g) != 0) {
      free(g->keys);
      return -1;
    }
    return 0;
  }
  if (tok_is(kind, "sine")) return parse_sine(c, kind, toks, nt, g);
  if (tok_is(kind, "step")) return parse_step(c, kind, toks, nt, g);
  if (tok_is(kind, "walk")) return parse_walk(c, kind, toks, nt, g);
  if (tok_is(kind, "csv") || tok_is(kind, "mrec")) {
    g->shape = GG_TRACK;
    return parse_track(c, toks, nt, kind, g, track, column);
  }
  return fail(c, kind->col, "unknown motion '%.*s' (const, keys, sine, step, walk, csv, mrec)",
              (int)kind->len, kind->s);
}

/* Each selected channel gets its own copy of g (keys copied, the track
 * shared). */
static int give_channels(ctx *c, gg_motion *m, const int sel[GG_CHANNELS], const gg_gen *g,
                         gg_track *track, double column, const tok *kind) {
  for (int i = 0; i < GG_CHANNELS; i++) {
    gg_gen *dst = &m->ch[i];
    if (!sel[i]) continue;
    gen_free(dst);
    *dst = *g;
    if (g->keys) {
      dst->keys = malloc(g->n_keys * sizeof *g->keys);
      if (!dst->keys) return fail(c, kind->col, "out of memory");
      memcpy(dst->keys, g->keys, g->n_keys * sizeof *g->keys);
    }
    if (track) {
      dst->track = gg_track_retain(track);
      dst->column = column >= 0 ? (int)column : i;
    }
  }
  return 0;
}

static int parse_line(ctx *c, gg_motion *m, const tok *toks, int nt) {
  int sel[GG_CHANNELS];
  gg_gen g;
  gg_track *track = NULL;
  double column = -1;
  if (tok_is(&toks[0], "duration")) return parse_duration(c, m, toks, nt);
  if (parse_channels(c, &toks[0], sel) != 0) return -1;
  if (nt < 2)
    return fail(c, toks[0].col + (int)toks[0].len, "expected a motion after the channels");
  gen_init(&g);
  if (parse_motion(c, &toks[1], toks + 2, nt - 2, &g, &track, &column) != 0) return -1;
  if (give_channels(c, m, sel, &g, track, column, &toks[1]) != 0) return -1;
  free(g.keys);
  gg_track_release(track);
  return 0;
}

int gg_motion_load(gg_motion *m, const char *path, uint64_t seed, char *err, size_t errcap) {
  FILE *f = fopen(path, "r");
  char line[4096];
  ctx c;
  const char *slash;
  motion_init(m, seed);
  memset(&c, 0, sizeof c);
  c.path = path;
  c.err = err;
  c.errcap = errcap;
  slash = strrchr(path, '/');
  if (slash && (size_t)(slash - path) < sizeof c.dir) {
    memcpy(c.dir, path, (size_t)(slash - path));
    c.dir[slash - path] = 0;
    if (!c.dir[0]) strcpy(c.dir, "/");
  }
  if (!f) {
    snprintf(err, errcap, "%s: cannot open: %s", path, strerror(errno));
    return -1;
  }
  while (fgets(line, sizeof line, f)) {
    tok toks[64];
    int nt = 0;
    char *p = line, *hash = strchr(line, '#');
    c.line++;
    if (!strchr(line, '\n') && !feof(f)) {
      fclose(f);
      gg_motion_free(m);
      return fail(&c, 1, "line longer than %zu characters", sizeof line - 2);
    }
    if (hash) *hash = 0;
    while (*p) {
      while (*p && isspace((unsigned char)*p)) p++;
      if (!*p) break;
      if (nt == 64) {
        fclose(f);
        gg_motion_free(m);
        return fail(&c, (int)(p - line) + 1, "more than 64 words on a line");
      }
      toks[nt].s = p;
      toks[nt].col = (int)(p - line) + 1;
      while (*p && !isspace((unsigned char)*p)) p++;
      toks[nt].len = (size_t)(p - toks[nt].s);
      nt++;
    }
    if (nt && parse_line(&c, m, toks, nt) != 0) {
      fclose(f);
      gg_motion_free(m);
      return -1;
    }
  }
  fclose(f);
  return 0;
}

/* --- evaluation -------------------------------------------------------------- */

static double ease(gg_ease e, double u) {
  switch (e) {
  case GG_EASE_LINEAR:
    return u;
  case GG_EASE_HOLD:
    return u >= 1 ? 1 : 0;
  case GG_EASE_IN:
    return u * u;
  case GG_EASE_OUT:
    return 1 - (1 - u) * (1 - u);
  case GG_EASE_INOUT:
    return u * u * (3 - 2 * u);
  case GG_EASE_SINE:
    return 0.5 - 0.5 * cos(M_PI * u);
  }
  return u;
}

static double eval_keys(const gg_gen *g, double t) {
  const gg_key *k = g->keys;
  size_t n = g->n_keys, lo = 0, hi;
  double span = k[n - 1].t - k[0].t;
  if (g->loop && span > 0 && t > k[n - 1].t) t = k[0].t + fmod(t - k[0].t, span);
  if (t <= k[0].t) return k[0].v;
  if (t >= k[n - 1].t) return k[n - 1].v;
  hi = n - 1;
  while (hi - lo > 1) {
    size_t mid = (lo + hi) / 2;
    if (k[mid].t <= t)
      lo = mid;
    else
      hi = mid;
  }
  return k[lo].v + (k[hi].v - k[lo].v) * ease(k[hi].ease, (t - k[lo].t) / (k[hi].t - k[lo].t));
}

static double eval_sine(const gg_gen *g, double t) {
  double cycles;
  /* A linear chirp: the frequency runs from freq to `to` over `over` seconds,
   * so the phase is the integral of a straight line. */
  if (g->sweep_s > 0 && t < g->sweep_s)
    cycles = g->freq * t + (g->freq_end - g->freq) * t * t / (2 * g->sweep_s);
  else if (g->sweep_s > 0)
    cycles = (g->freq + g->freq_end) * g->sweep_s / 2 + g->freq_end * (t - g->sweep_s);
  else
    cycles = g->freq * t;
  return g->mid + g->amp * sin(2 * M_PI * cycles + g->phase);
}

static double eval_step(const gg_gen *g, double t) {
  if (t < g->at) return g->from;
  if (g->period <= 0) return g->to;
  return fmod(t - g->at, g->period) < g->duty * g->period ? g->to : g->from;
}

/* A standard normal draw (Box-Muller), from the motion's own generator. */
static double normal(gg_rng *r) {
  double u1 = gg_rng_unit(r), u2 = gg_rng_unit(r);
  if (u1 < 1e-300) u1 = 1e-300;
  return sqrt(-2 * log(u1)) * cos(2 * M_PI * u2);
}

static double eval_walk(gg_gen *g, gg_rng *r, double dt) {
  double v = g->walk_v + g->sigma * sqrt(dt) * normal(r);
  /* Reflect at the bounds, so the walk does not stick to them. */
  for (int i = 0; i < 4 && (v < g->lo || v > g->hi); i++)
    v = v < g->lo ? 2 * g->lo - v : 2 * g->hi - v;
  if (v < g->lo) v = g->lo;
  if (v > g->hi) v = g->hi;
  g->walk_v = v;
  return v;
}

void gg_motion_eval(gg_motion *m, double t_s, uint16_t out[GG_CHANNELS]) {
  double dt = m->started && t_s > m->last_t ? t_s - m->last_t : 0;
  m->started = 1;
  m->last_t = t_s;
  for (int i = 0; i < GG_CHANNELS; i++) {
    gg_gen *g = &m->ch[i];
    double v = 0;
    switch (g->shape) {
    case GG_CONST:
      v = g->value;
      break;
    case GG_KEYS:
      v = eval_keys(g, t_s);
      break;
    case GG_SINE:
      v = eval_sine(g, t_s);
      break;
    case GG_STEP:
      v = eval_step(g, t_s);
      break;
    case GG_WALK:
      v = dt > 0 ? eval_walk(g, &m->rng, dt) : g->walk_v;
      break;
    case GG_TRACK:
      v = gg_track_eval(g->track, g->column, t_s, g->loop);
      break;
    }
    out[i] = gp_glove_value_count(v); /* clamped to 0..1, NaN as 0 */
  }
}
