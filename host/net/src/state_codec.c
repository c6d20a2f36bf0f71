/* The hand-written half of the show-state codec: quantising positions to
 * 16 bits per axis, and the SCENE's file records (STATE.md). The message
 * layouts themselves are generated from state.def. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mr_state.h"

void mr_state_quantise(const double *xyz, size_t n, float origin[3], float step[3], uint16_t *q) {
  for (int a = 0; a < 3; a++) {
    double lo = n > 0 ? xyz[a] : 0.0, hi = lo;
    for (size_t i = 1; i < n; i++) {
      double v = xyz[3 * i + (size_t)a];
      if (v < lo) lo = v;
      if (v > hi) hi = v;
    }
    /* The origin rounded down to a float, so that no value lies below it. */
    origin[a] = (float)lo;
    if ((double)origin[a] > lo) origin[a] = nextafterf(origin[a], -INFINITY);
    /* The step from the float origin, so that the highest value still
     * lands on 65535 however the origin rounded. */
    double span = hi - (double)origin[a];
    float s = span > 0 ? (float)(span / 65535.0) : 0.0f;
    while (s > 0 && (double)origin[a] + 65535.0 * (double)s < hi) s = nextafterf(s, INFINITY);
    step[a] = s;
    for (size_t i = 0; i < n; i++) {
      double k = s > 0 ? floor((xyz[3 * i + (size_t)a] - (double)origin[a]) / (double)s + 0.5) : 0;
      q[3 * i + (size_t)a] = (uint16_t)(k < 0 ? 0 : k > 65535 ? 65535 : k);
    }
  }
}

void mr_state_point(const mr_state_frame *m, size_t i, double out[3]) {
  for (int a = 0; a < 3; a++)
    out[a] = (double)m->origin[a] + (double)m->q[3 * i + (size_t)a] * (double)m->step[a];
}

/* A name safe to write under a folder: not empty, not absolute, no ".."
 * part, no backslash. */
static bool safe_name(const char *name, size_t len) {
  if (len == 0 || len >= MR_STATE_NAME_MAX || name[0] == '/') return false;
  if (memchr(name, '\0', len) != NULL || memchr(name, '\\', len) != NULL) return false;
  for (size_t i = 0; i < len; i++) {
    bool starts = i == 0 || name[i - 1] == '/';
    if (starts && i + 1 < len && name[i] == '.' && name[i + 1] == '.' &&
        (i + 2 == len || name[i + 2] == '/'))
      return false;
  }
  return true;
}

static void put_le(uint8_t *p, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; i++) p[i] = (uint8_t)(v >> (8 * i));
}

static uint64_t get_le(const uint8_t *p, int bytes) {
  uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; i--) v = (v << 8) | p[i];
  return v;
}

int mr_state_bundle_add(mr_state_bundle *b, const char *name, const void *data, size_t len) {
  size_t nl = strlen(name);
  if (!safe_name(name, nl) || len > UINT32_MAX || b->n_files == UINT16_MAX) return -1;
  size_t need = b->size + 2 + nl + 4 + len;
  if (need > b->cap) {
    size_t cap = b->cap > 0 ? b->cap : 4096;
    while (cap < need) cap *= 2;
    uint8_t *p = realloc(b->data, cap);
    if (p == NULL) return -1;
    b->data = p;
    b->cap = cap;
  }
  uint8_t *p = b->data + b->size;
  put_le(p, nl, 2);
  memcpy(p + 2, name, nl);
  put_le(p + 2 + nl, len, 4);
  if (len > 0) memcpy(p + 6 + nl, data, len);
  b->size = need;
  b->n_files++;
  return 0;
}

void mr_state_bundle_free(mr_state_bundle *b) {
  free(b->data);
  memset(b, 0, sizeof *b);
}

uint64_t mr_state_bundle_hash(const uint8_t *files, size_t size) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < size; i++) {
    h ^= files[i];
    h *= 0x100000001b3ull;
  }
  return h;
}

int mr_state_bundle_next(const uint8_t *files, size_t size, size_t *off, mr_state_file *f) {
  size_t at = *off;
  if (at >= size) return 0;
  if (size - at < 2) return -1;
  size_t nl = (size_t)get_le(files + at, 2);
  if (size - at - 2 < nl + 4 || !safe_name((const char *)files + at + 2, nl)) return -1;
  size_t len = (size_t)get_le(files + at + 2 + nl, 4);
  if (size - at - 6 - nl < len) return -1;
  memcpy(f->name, files + at + 2, nl);
  f->name[nl] = '\0';
  f->data = files + at + 6 + nl;
  f->len = len;
  *off = at + 6 + nl + len;
  return 1;
}
