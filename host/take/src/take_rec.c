/* One glove's recording read whole, its frames found, written back. */
#include "take_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int mr_take_fail(mr_take_error *err, mr_take_status st, const char *fmt, ...) {
  if (err == NULL) return -1;
  err->status = st;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err->msg, sizeof err->msg, fmt, ap);
  va_end(ap);
  return -1;
}

/* --- calibration ------------------------------------------------------------ */

mr_take_cal mr_take_cal_of(const gp_info *info) {
  mr_take_cal c;
  memset(&c, 0, sizeof c);
  int bits = info != NULL && info->adc_bits > 0 && info->adc_bits <= 16 ? info->adc_bits : 12;
  c.full = (double)((1u << bits) - 1u);
  for (int k = 0; info != NULL && k < MR_TAKE_CHANNELS; k++) {
    c.lo[k] = (uint16_t)info->cal_min[k];
    c.hi[k] = (uint16_t)info->cal_max[k];
    c.ranged[k] = info->cal_state == GP_CAL_VALID && info->cal_max[k] > info->cal_min[k];
  }
  return c;
}

double mr_take_cal_value(const mr_take_cal *c, int k, uint16_t raw) {
  if (c->ranged[k]) return ((double)raw - c->lo[k]) / (double)(c->hi[k] - c->lo[k]);
  return (double)raw / c->full;
}

uint16_t mr_take_cal_raw(const mr_take_cal *c, int k, double v) {
  if (isnan(v)) v = 0.0;
  double raw = c->ranged[k] ? c->lo[k] + v * (double)(c->hi[k] - c->lo[k]) : v * c->full;
  raw = round(raw);
  if (raw < 0.0) raw = 0.0;
  if (raw > GP_SAMPLE_CH_MAX) raw = GP_SAMPLE_CH_MAX;
  return (uint16_t)raw;
}

/* --- frames ----------------------------------------------------------------- */

/* The run data[0..n) (no delimiter) as a whole valid frame into *m. */
static bool frame_of(const uint8_t *run, size_t n, gp_msg *m) {
  uint8_t raw[GP_MAX_FRAME];
  if (n == 0 || n > GP_MAX_WIRE) return false;
  int len = gp_cobs_decode(run, n, raw, sizeof raw);
  if (len < 5) return false;
  const gp_msg_desc *d = gp_msg_find(raw[0]);
  if (d == NULL || (size_t)len != 1u + d->len + GP_CRC_LEN) return false;
  uint32_t want = gp_frame_crc(GP_SPEC_HASH, raw, (size_t)len - GP_CRC_LEN);
  const uint8_t *c = raw + len - GP_CRC_LEN;
  uint32_t got = (uint32_t)c[0] | (uint32_t)c[1] << 8 | (uint32_t)c[2] << 16 | (uint32_t)c[3] << 24;
  if (got != want) return false;
  if (gp_payload_unpack(raw[0], raw + 1, (size_t)len - 1 - GP_CRC_LEN, m) != 0) return false;
  return m->type != GP_INFO || m->u.info.spec_hash == GP_SPEC_HASH;
}

void mr_take_rec_scan(mr_take_rec *r) {
  r->n_frames = 0;
  mr_take_cal cal = mr_take_cal_of(NULL);
  size_t start = 0, chunk = 0;
  for (size_t i = 0; i < r->len; i++) {
    if (r->data[i] != 0) continue;
    while (chunk + 1 < r->n_chunks && i >= r->chunks[chunk].off + r->chunks[chunk].len) chunk++;
    gp_msg m;
    if (frame_of(r->data + start, i - start, &m)) {
      mr_take_frame *f = &r->frames[r->n_frames++];
      f->off = start;
      f->len = i + 1 - start;
      f->chunk = chunk;
      f->t_ns = r->chunks[chunk].t_ns;
      f->msg = m;
      if (m.type == GP_INFO) cal = mr_take_cal_of(&m.u.info);
      f->cal = cal;
    }
    start = i + 1;
  }
}

/* --- files ------------------------------------------------------------------ */

static int grow(void **p, size_t *cap, size_t need, size_t size) {
  if (need <= *cap) return 0;
  size_t c = *cap ? *cap : 64;
  while (c < need) c *= 2;
  void *q = realloc(*p, c * size);
  if (q == NULL) return -1;
  *p = q;
  *cap = c;
  return 0;
}

int mr_take_rec_load(const char *path, mr_take_rec *r, mr_take_error *err) {
  memset(r, 0, sizeof *r);
  mr_rec_reader rd;
  mr_io_error ie;
  if (mr_rec_reader_open(&rd, path, &ie) != 0)
    return mr_take_fail(err, ie.status == MR_IO_ERR_SYSTEM ? MR_TAKE_ERR_IO : MR_TAKE_ERR_FORMAT,
                        "%s", ie.msg);
  r->header = rd.header;
  size_t cap_data = 0, cap_chunks = 0;
  for (;;) {
    uint64_t t;
    const uint8_t *d;
    size_t n;
    int got = mr_rec_reader_next(&rd, &t, &d, &n, &ie);
    if (got == 0) break;
    if (got < 0 && ie.status == MR_IO_ERR_TRUNCATED) {
      r->truncated = true;
      snprintf(r->note, sizeof r->note, "%s; used up to its last whole chunk", ie.msg);
      break;
    }
    if (got < 0 || grow((void **)&r->data, &cap_data, r->len + n, 1) != 0 ||
        grow((void **)&r->chunks, &cap_chunks, r->n_chunks + 1, sizeof *r->chunks) != 0) {
      mr_rec_reader_close(&rd);
      mr_take_rec_free(r);
      if (got < 0) return mr_take_fail(err, MR_TAKE_ERR_FORMAT, "%s", ie.msg);
      return mr_take_fail(err, MR_TAKE_ERR_IO, "%s: out of memory", path);
    }
    memcpy(r->data + r->len, d, n);
    r->chunks[r->n_chunks++] = (mr_take_chunk){ t, r->len, n };
    r->len += n;
  }
  mr_rec_reader_close(&rd);
  /* A frame is at least two wire bytes (a code and the delimiter). */
  r->frames = malloc((r->len / 2 + 1) * sizeof *r->frames);
  if (r->frames == NULL) {
    mr_take_rec_free(r);
    return mr_take_fail(err, MR_TAKE_ERR_IO, "%s: out of memory", path);
  }
  mr_take_rec_scan(r);
  return 0;
}

int mr_take_rec_copy(mr_take_rec *dst, const mr_take_rec *src, mr_take_error *err) {
  *dst = *src;
  dst->data = malloc(src->len ? src->len : 1);
  dst->chunks = malloc((src->n_chunks ? src->n_chunks : 1) * sizeof *src->chunks);
  dst->frames = malloc((src->len / 2 + 1) * sizeof *src->frames);
  if (dst->data == NULL || dst->chunks == NULL || dst->frames == NULL) {
    mr_take_rec_free(dst);
    return mr_take_fail(err, MR_TAKE_ERR_IO, "out of memory copying a take");
  }
  memcpy(dst->data, src->data, src->len);
  memcpy(dst->chunks, src->chunks, src->n_chunks * sizeof *src->chunks);
  memcpy(dst->frames, src->frames, src->n_frames * sizeof *src->frames);
  return 0;
}

void mr_take_rec_free(mr_take_rec *r) {
  free(r->data);
  free(r->chunks);
  free(r->frames);
  r->data = NULL;
  r->chunks = NULL;
  r->frames = NULL;
  r->len = r->n_chunks = r->n_frames = 0;
}

int mr_take_rec_write(const mr_take_rec *r, const char *path, mr_take_error *err) {
  mr_rec_writer w;
  mr_io_error ie;
  if (mr_rec_writer_open_scene(&w, path, r->header.spec_hash, r->header.start_unix_ns,
                               r->header.scene_hash, &ie) != 0)
    return mr_take_fail(err, MR_TAKE_ERR_IO, "%s", ie.msg);
  for (size_t c = 0; c < r->n_chunks; c++) {
    const mr_take_chunk *k = &r->chunks[c];
    if (mr_rec_writer_add(&w, k->t_ns, r->data + k->off, k->len, &ie) != 0) {
      mr_io_error ignored;
      mr_rec_writer_close(&w, &ignored);
      return mr_take_fail(err, ie.status == MR_IO_ERR_ARG ? MR_TAKE_ERR_ARG : MR_TAKE_ERR_IO, "%s",
                          ie.msg);
    }
  }
  if (mr_rec_writer_close(&w, &ie) != 0) return mr_take_fail(err, MR_TAKE_ERR_IO, "%s", ie.msg);
  return 0;
}

double mr_take_rec_duration(const mr_take_rec *r) {
  return r->n_chunks ? (double)r->chunks[r->n_chunks - 1].t_ns / 1e9 : 0.0;
}

int mr_take_rec_set_sample(mr_take_rec *r, size_t i, const uint16_t ch[MR_TAKE_CHANNELS],
                           mr_take_error *err) {
  if (i >= r->n_frames || r->frames[i].msg.type != GP_SAMPLE)
    return mr_take_fail(err, MR_TAKE_ERR_ARG, "frame %zu is not a SAMPLE", i);
  mr_take_frame *f = &r->frames[i];
  gp_msg m = f->msg;
  for (int k = 0; k < MR_TAKE_CHANNELS; k++) m.u.sample.ch[k] = ch[k];
  uint8_t wire[GP_MAX_WIRE];
  size_t n = gp_encode(&m, GP_SPEC_HASH, wire, sizeof wire);
  /* COBS grows a frame under 254 bytes by exactly one byte, so a SAMPLE's
   * wire length never changes with its values. */
  if (n != f->len) return mr_take_fail(err, MR_TAKE_ERR_FORMAT, "SAMPLE %zu changed length", i);
  memcpy(r->data + f->off, wire, n);
  f->msg = m;
  return 0;
}

double mr_take_rec_value(const mr_take_rec *r, size_t i, int k) {
  const mr_take_frame *f = &r->frames[i];
  return mr_take_cal_value(&f->cal, k, (uint16_t)f->msg.u.sample.ch[k]);
}

long mr_take_rec_sample_at(const mr_take_rec *r, uint64_t t_ns) {
  long found = -1;
  for (size_t i = 0; i < r->n_frames && r->frames[i].t_ns <= t_ns; i++)
    if (r->frames[i].msg.type == GP_SAMPLE) found = (long)i;
  return found;
}

uint64_t mr_take_ns(double t_s) {
  return t_s <= 0.0 ? 0u : (uint64_t)llround(t_s * 1e9);
}
