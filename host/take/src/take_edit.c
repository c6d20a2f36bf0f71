/* Edits of one glove's recording: punch-in, trim, smoothing, a time offset
 * per channel, time scaling. README.md, "Operations", defines each. */
#include "take_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mr_control.h"

static int check_time(double t, const char *what, mr_take_error *err) {
  if (!isfinite(t) || t < 0.0 || t > 1e6)
    return mr_take_fail(err, MR_TAKE_ERR_ARG, "%s must be a time 0..1e6 s, got %g", what, t);
  return 0;
}

static void channels_of(const mr_take_frame *f, uint16_t ch[MR_TAKE_CHANNELS]) {
  for (int k = 0; k < MR_TAKE_CHANNELS; k++) ch[k] = (uint16_t)f->msg.u.sample.ch[k];
}

int mr_take_punch_rec(mr_take_rec *base, const mr_take_rec *over, unsigned mask, double t_in,
                      double t_out, mr_take_error *err) {
  if (check_time(t_in, "the punch-in time", err) != 0 ||
      check_time(t_out, "the punch-out time", err) != 0)
    return -1;
  if (!(t_in < t_out))
    return mr_take_fail(err, MR_TAKE_ERR_ARG,
                        "the punch-in time %g s must come before the "
                        "punch-out time %g s",
                        t_in, t_out);
  if (over == NULL || mask == 0) return 0;
  uint64_t a = base->header.scene_hash, b = over->header.scene_hash;
  if (a != 0 && b != 0 && a != b)
    return mr_take_fail(err, MR_TAKE_ERR_SCENE,
                        "the takes were recorded against different "
                        "scenes: scene hash %016llx and %016llx",
                        (unsigned long long)a, (unsigned long long)b);
  const uint64_t in = mr_take_ns(t_in), out = mr_take_ns(t_out);
  long o = -1; /* the newest over SAMPLE at or before the base frame's time */
  size_t next = 0;
  for (size_t i = 0; i < base->n_frames; i++) {
    const mr_take_frame *f = &base->frames[i];
    if (f->msg.type != GP_SAMPLE || f->t_ns < in || f->t_ns >= out) continue;
    for (; next < over->n_frames && over->frames[next].t_ns <= f->t_ns; next++)
      if (over->frames[next].msg.type == GP_SAMPLE) o = (long)next;
    if (o < 0) continue;
    uint16_t ch[MR_TAKE_CHANNELS];
    channels_of(f, ch);
    for (int k = 0; k < MR_TAKE_CHANNELS; k++)
      if (mask & (1u << k))
        ch[k] = mr_take_cal_raw(&f->cal, k, mr_take_rec_value(over, (size_t)o, k));
    if (mr_take_rec_set_sample(base, i, ch, err) != 0) return -1;
  }
  return 0;
}

/* The first byte to keep from src at data offset off: a chunk that starts
 * inside a frame (the byte before it is not a delimiter) is kept from just
 * after that frame's delimiter, so the new take starts on a frame. */
static size_t frame_start(const mr_take_rec *src, size_t off) {
  if (off == 0 || src->data[off - 1] == 0) return off;
  while (off < src->len && src->data[off] != 0) off++;
  return off < src->len ? off + 1 : off;
}

int mr_take_trim_rec(const mr_take_rec *src, double t0, double t1, mr_take_rec *out,
                     mr_take_error *err) {
  if (check_time(t0, "the start time", err) != 0) return -1;
  if (isnan(t1) || !(t0 < t1))
    return mr_take_fail(err, MR_TAKE_ERR_ARG,
                        "the start time %g s must come before the end "
                        "time %g s",
                        t0, t1);
  const uint64_t a = mr_take_ns(t0), b = isinf(t1) ? UINT64_MAX : mr_take_ns(t1);
  memset(out, 0, sizeof *out);
  out->header = src->header;
  out->data = malloc(src->len + GP_MAX_WIRE + 1);
  out->chunks = malloc((src->n_chunks + 1) * sizeof *out->chunks);
  out->frames = malloc(((src->len + GP_MAX_WIRE) / 2 + 1) * sizeof *out->frames);
  if (out->data == NULL || out->chunks == NULL || out->frames == NULL) {
    mr_take_rec_free(out);
    return mr_take_fail(err, MR_TAKE_ERR_IO, "out of memory trimming a take");
  }
  const mr_take_frame *info = NULL;
  for (size_t i = 0; i < src->n_frames && src->frames[i].t_ns < a; i++)
    if (src->frames[i].msg.type == GP_INFO) info = &src->frames[i];
  if (info != NULL) {
    memcpy(out->data, src->data + info->off, info->len);
    out->chunks[out->n_chunks++] = (mr_take_chunk){ 0, 0, info->len };
    out->len = info->len;
  }
  size_t keep_from = 0;
  bool first = true;
  for (size_t c = 0; c < src->n_chunks; c++) {
    const mr_take_chunk *k = &src->chunks[c];
    if (k->t_ns < a || k->t_ns >= b) continue;
    if (first) keep_from = frame_start(src, k->off);
    first = false;
    size_t from = k->off > keep_from ? k->off : keep_from, end = k->off + k->len;
    if (from >= end) continue;
    memcpy(out->data + out->len, src->data + from, end - from);
    out->chunks[out->n_chunks++] = (mr_take_chunk){ k->t_ns - a, out->len, end - from };
    out->len += end - from;
  }
  mr_take_rec_scan(out);
  return 0;
}

int mr_take_smooth_rec(mr_take_rec *r, unsigned mask, double min_cutoff, double beta,
                       double d_cutoff, mr_take_error *err) {
  if (!(isfinite(min_cutoff) && min_cutoff > 0) || !(isfinite(d_cutoff) && d_cutoff > 0) ||
      !(isfinite(beta) && beta >= 0))
    return mr_take_fail(err, MR_TAKE_ERR_ARG,
                        "smoothing needs min_cutoff > 0, beta >= 0 and "
                        "d_cutoff > 0, got %g, %g, %g",
                        min_cutoff, beta, d_cutoff);
  mr_one_euro f[MR_TAKE_CHANNELS];
  for (int k = 0; k < MR_TAKE_CHANNELS; k++) mr_one_euro_init(&f[k], min_cutoff, beta, d_cutoff);
  for (size_t i = 0; i < r->n_frames && mask != 0; i++) {
    const mr_take_frame *fr = &r->frames[i];
    if (fr->msg.type != GP_SAMPLE) continue;
    uint16_t ch[MR_TAKE_CHANNELS];
    channels_of(fr, ch);
    const double t = (double)fr->t_ns / 1e9;
    for (int k = 0; k < MR_TAKE_CHANNELS; k++)
      if (mask & (1u << k))
        ch[k] =
            mr_take_cal_raw(&fr->cal, k, mr_one_euro_filter(&f[k], mr_take_rec_value(r, i, k), t));
    if (mr_take_rec_set_sample(r, i, ch, err) != 0) return -1;
  }
  return 0;
}

/* One SAMPLE's time and values, as read before an offset moves them. */
typedef struct timed {
  uint64_t t_ns;
  double v[MR_TAKE_CHANNELS];
} timed;

/* The newest of s[0..n) at or before t (ns, may be negative); the first when
 * none is. */
static const timed *at_or_before(const timed *s, size_t n, double t) {
  size_t lo = 0, hi = n; /* the first with s.t_ns > t */
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if ((double)s[mid].t_ns <= t)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo == 0 ? &s[0] : &s[lo - 1];
}

int mr_take_offset_rec(mr_take_rec *r, const double offset_s[MR_TAKE_CHANNELS],
                       mr_take_error *err) {
  for (int k = 0; k < MR_TAKE_CHANNELS; k++)
    if (!isfinite(offset_s[k]) || fabs(offset_s[k]) > 3600.0)
      return mr_take_fail(err, MR_TAKE_ERR_ARG, "an offset must be -3600..3600 s, got %g",
                          offset_s[k]);
  size_t n = 0;
  timed *s = malloc((r->n_frames + 1) * sizeof *s);
  if (s == NULL) return mr_take_fail(err, MR_TAKE_ERR_IO, "out of memory offsetting a take");
  for (size_t i = 0; i < r->n_frames; i++) {
    if (r->frames[i].msg.type != GP_SAMPLE) continue;
    s[n].t_ns = r->frames[i].t_ns;
    for (int k = 0; k < MR_TAKE_CHANNELS; k++) s[n].v[k] = mr_take_rec_value(r, i, k);
    n++;
  }
  for (size_t i = 0; i < r->n_frames && n > 0; i++) {
    const mr_take_frame *fr = &r->frames[i];
    if (fr->msg.type != GP_SAMPLE) continue;
    uint16_t ch[MR_TAKE_CHANNELS];
    channels_of(fr, ch);
    bool moved = false;
    for (int k = 0; k < MR_TAKE_CHANNELS; k++) {
      if (offset_s[k] == 0.0) continue;
      const timed *from = at_or_before(s, n, (double)fr->t_ns - offset_s[k] * 1e9);
      ch[k] = mr_take_cal_raw(&fr->cal, k, from->v[k]);
      moved = true;
    }
    if (moved && mr_take_rec_set_sample(r, i, ch, err) != 0) {
      free(s);
      return -1;
    }
  }
  free(s);
  return 0;
}

int mr_take_scale_rec(mr_take_rec *r, double factor, mr_take_error *err) {
  if (!isfinite(factor) || !(factor > 0.0) || factor > 1e6)
    return mr_take_fail(err, MR_TAKE_ERR_ARG,
                        "the time factor must be a number > 0 (at most "
                        "1e6), got %g",
                        factor);
  uint64_t last = 0;
  for (size_t c = 0; c < r->n_chunks; c++) {
    double t = round((double)r->chunks[c].t_ns * factor);
    if (t > 9.0e18 || t - (double)last > (double)MR_REC_MAX_GAP_NS)
      return mr_take_fail(err, MR_TAKE_ERR_ARG,
                          "scaled by %g, the take would hold a silence "
                          "over an hour",
                          factor);
    r->chunks[c].t_ns = last = (uint64_t)t;
  }
  for (size_t i = 0; i < r->n_frames; i++) r->frames[i].t_ns = r->chunks[r->frames[i].chunk].t_ns;
  return 0;
}
