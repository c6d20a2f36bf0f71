/* The stream recording format (*.mrec): a 32-byte header, then chunks of raw
 * wire bytes each stamped with its time since the start. Everything is
 * little-endian; every complaint names the byte offset it is about. */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mr_io_internal.h"

static void put_le(uint8_t *p, uint64_t v, int n) {
  for (int i = 0; i < n; i++) p[i] = (uint8_t)(v >> (8 * i));
}

static uint64_t get_le(const uint8_t *p, int n) {
  uint64_t v = 0;
  for (int i = n - 1; i >= 0; i--) v = (v << 8) | p[i];
  return v;
}

static int write_all(int fd, const void *buf, size_t len) {
  const uint8_t *p = buf;
  while (len) {
    ssize_t n = write(fd, p, len);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return -1;
    p += n;
    len -= (size_t)n;
  }
  return 0;
}

int mr_rec_is_recording(const void *buf, size_t len) {
  return len >= 8 && memcmp(buf, MR_REC_MAGIC, 8) == 0;
}

int mr_rec_writer_open(mr_rec_writer *w, const char *path, uint32_t spec_hash,
                       uint64_t start_unix_ns, mr_io_error *err) {
  return mr_rec_writer_open_scene(w, path, spec_hash, start_unix_ns, 0, err);
}

int mr_rec_writer_open_scene(mr_rec_writer *w, const char *path, uint32_t spec_hash,
                             uint64_t start_unix_ns, uint64_t scene_hash, mr_io_error *err) {
  uint8_t h[MR_REC_HEADER_LEN];
  memset(w, 0, sizeof *w);
  w->fd = -1;
  memcpy(h, MR_REC_MAGIC, 8);
  put_le(h + 8, MR_REC_VERSION, 2);
  put_le(h + 10, MR_REC_HEADER_LEN, 2);
  put_le(h + 12, spec_hash, 4);
  put_le(h + 16, start_unix_ns, 8);
  put_le(h + 24, scene_hash, 8);
  w->fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (w->fd < 0) return mr_io_err_sys(err, "%s: cannot create", path);
  strncpy(w->path, path, sizeof w->path - 1);
  if (write_all(w->fd, h, sizeof h) != 0) {
    mr_io_err_sys(err, "%s: cannot write the header", path);
    close(w->fd);
    w->fd = -1;
    return -1;
  }
  w->offset = sizeof h;
  return 0;
}

int mr_rec_writer_add(mr_rec_writer *w, uint64_t t_ns, const void *data, size_t len,
                      mr_io_error *err) {
  uint8_t h[MR_REC_CHUNK_HEADER_LEN];
  if (w->fd < 0) return mr_io_err_set(err, MR_IO_ERR_ARG, "%s: recording is not open", w->path);
  if (len == 0 || len > MR_REC_MAX_CHUNK)
    return mr_io_err_set(err, MR_IO_ERR_ARG, "%s: byte %llu: chunk length %zu (must be 1..%u)",
                         w->path, (unsigned long long)w->offset, len, MR_REC_MAX_CHUNK);
  if (t_ns < w->last_t_ns)
    return mr_io_err_set(err, MR_IO_ERR_ARG,
                         "%s: byte %llu: chunk time %llu ns is before the previous %llu ns",
                         w->path, (unsigned long long)w->offset, (unsigned long long)t_ns,
                         (unsigned long long)w->last_t_ns);
  if (t_ns - w->last_t_ns > MR_REC_MAX_GAP_NS)
    return mr_io_err_set(err, MR_IO_ERR_ARG,
                         "%s: byte %llu: chunk time %llu ns is %.0f s after the previous %llu ns "
                         "(a take holds at most %llu s of silence)",
                         w->path, (unsigned long long)w->offset, (unsigned long long)t_ns,
                         (double)(t_ns - w->last_t_ns) * 1e-9, (unsigned long long)w->last_t_ns,
                         MR_REC_MAX_GAP_NS / 1000000000ull);
  put_le(h, t_ns, 8);
  put_le(h + 8, len, 4);
  if (write_all(w->fd, h, sizeof h) != 0 || write_all(w->fd, data, len) != 0)
    return mr_io_err_sys(err, "%s: byte %llu: cannot write a chunk", w->path,
                         (unsigned long long)w->offset);
  w->offset += sizeof h + len;
  w->last_t_ns = t_ns;
  w->chunks++;
  return 0;
}

int mr_rec_writer_close(mr_rec_writer *w, mr_io_error *err) {
  int rc = 0;
  if (w->fd < 0) return 0;
  if (fsync(w->fd) != 0 && errno != EINVAL && errno != EROFS)
    rc = mr_io_err_sys(err, "%s: cannot flush", w->path);
  if (close(w->fd) != 0 && rc == 0) rc = mr_io_err_sys(err, "%s: cannot close", w->path);
  w->fd = -1;
  return rc;
}

/* Reads up to len bytes, the caller's sniffed prefix first. Returns how many
 * arrived before end of file, or -1 on a read error. */
static ssize_t read_full(mr_rec_reader *r, void *buf, size_t len) {
  uint8_t *p = buf;
  size_t got = 0;
  if (r->prefix_len) {
    size_t n = len < r->prefix_len ? len : r->prefix_len;
    memcpy(p, r->prefix, n);
    r->prefix += n;
    r->prefix_len -= n;
    got = n;
  }
  while (got < len) {
    ssize_t n = read(r->fd, p + got, len - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return -1;
    if (n == 0) break;
    got += (size_t)n;
  }
  r->offset += got;
  return (ssize_t)got;
}

int mr_rec_reader_open_fd(mr_rec_reader *r, int fd, const char *name, const void *prefix,
                          size_t prefix_len, mr_io_error *err) {
  uint8_t h[MR_REC_HEADER_LEN];
  ssize_t got;
  memset(r, 0, sizeof *r);
  r->fd = fd;
  r->prefix = prefix;
  r->prefix_len = prefix_len;
  strncpy(r->name, name ? name : "recording", sizeof r->name - 1);
  got = read_full(r, h, sizeof h);
  if (got < 0) return mr_io_err_sys(err, "%s: byte 0: cannot read the header", r->name);
  if (got == 0)
    return mr_io_err_set(err, MR_IO_ERR_FORMAT,
                         "%s: byte 0: empty file, not a stream recording (no %s magic)", r->name,
                         MR_REC_MAGIC);
  if (got < 8 || memcmp(h, MR_REC_MAGIC, 8) != 0)
    return mr_io_err_set(err, MR_IO_ERR_FORMAT, "%s: byte 0: not a stream recording (no %s magic)",
                         r->name, MR_REC_MAGIC);
  if (got < (ssize_t)sizeof h)
    return mr_io_err_set(err, MR_IO_ERR_FORMAT, "%s: byte %zd: header cut short (%zd of %u bytes)",
                         r->name, got, got, MR_REC_HEADER_LEN);
  r->header.version = (uint16_t)get_le(h + 8, 2);
  r->header.header_len = (uint16_t)get_le(h + 10, 2);
  r->header.spec_hash = (uint32_t)get_le(h + 12, 4);
  r->header.start_unix_ns = get_le(h + 16, 8);
  r->header.scene_hash = get_le(h + 24, 8);
  if (r->header.version != MR_REC_VERSION)
    return mr_io_err_set(err, MR_IO_ERR_FORMAT,
                         "%s: byte 8: unknown version %u (this reader knows %u)", r->name,
                         r->header.version, MR_REC_VERSION);
  if (r->header.header_len < MR_REC_HEADER_LEN)
    return mr_io_err_set(err, MR_IO_ERR_FORMAT, "%s: byte 10: header length %u is below %u",
                         r->name, r->header.header_len, MR_REC_HEADER_LEN);
  /* A longer header comes from a later minor revision: skip what we do not
   * know. */
  for (size_t skip = r->header.header_len - MR_REC_HEADER_LEN; skip;) {
    uint8_t tmp[256];
    size_t n = skip < sizeof tmp ? skip : sizeof tmp;
    got = read_full(r, tmp, n);
    if (got < 0)
      return mr_io_err_sys(err, "%s: byte %llu: cannot read", r->name,
                           (unsigned long long)r->offset);
    if ((size_t)got < n)
      return mr_io_err_set(err, MR_IO_ERR_FORMAT,
                           "%s: byte %llu: header cut short (%u bytes declared)", r->name,
                           (unsigned long long)r->offset, r->header.header_len);
    skip -= n;
  }
  return 0;
}

int mr_rec_reader_open(mr_rec_reader *r, const char *path, mr_io_error *err) {
  int fd = open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    memset(r, 0, sizeof *r);
    r->fd = -1;
    return mr_io_err_sys(err, "%s: cannot open", path);
  }
  if (mr_rec_reader_open_fd(r, fd, path, NULL, 0, err) != 0) {
    close(fd);
    r->fd = -1;
    return -1;
  }
  r->owns_fd = 1;
  return 0;
}

int mr_rec_reader_next(mr_rec_reader *r, uint64_t *t_ns, const uint8_t **data, size_t *len,
                       mr_io_error *err) {
  uint8_t h[MR_REC_CHUNK_HEADER_LEN];
  uint64_t at = r->offset, t;
  uint32_t n;
  ssize_t got = read_full(r, h, sizeof h);
  if (got < 0)
    return mr_io_err_sys(err, "%s: byte %llu: cannot read", r->name, (unsigned long long)at);
  if (got == 0) return 0;
  if ((size_t)got < sizeof h)
    return mr_io_err_set(err, MR_IO_ERR_TRUNCATED,
                         "%s: byte %llu: last chunk cut short: %zd of its %u header bytes, "
                         "at least %zu bytes missing",
                         r->name, (unsigned long long)at, got, MR_REC_CHUNK_HEADER_LEN,
                         MR_REC_CHUNK_HEADER_LEN - (size_t)got + 1);
  t = get_le(h, 8);
  n = (uint32_t)get_le(h + 8, 4);
  if (n == 0 || n > MR_REC_MAX_CHUNK)
    return mr_io_err_set(err, MR_IO_ERR_FORMAT, "%s: byte %llu: chunk length %u (must be 1..%u)",
                         r->name, (unsigned long long)(at + 8), n, MR_REC_MAX_CHUNK);
  if (t < r->last_t_ns)
    return mr_io_err_set(
        err, MR_IO_ERR_FORMAT, "%s: byte %llu: chunk time %llu ns goes back before %llu ns",
        r->name, (unsigned long long)at, (unsigned long long)t, (unsigned long long)r->last_t_ns);
  if (t - r->last_t_ns > MR_REC_MAX_GAP_NS)
    return mr_io_err_set(err, MR_IO_ERR_FORMAT,
                         "%s: byte %llu: chunk time %llu ns jumps %.0f s past %llu ns (a take "
                         "holds at most %llu s of silence)",
                         r->name, (unsigned long long)at, (unsigned long long)t,
                         (double)(t - r->last_t_ns) * 1e-9, (unsigned long long)r->last_t_ns,
                         MR_REC_MAX_GAP_NS / 1000000000ull);
  if (r->data_cap < n) {
    uint8_t *p = realloc(r->data, n);
    if (!p)
      return mr_io_err_set(err, MR_IO_ERR_SYSTEM, "%s: byte %llu: out of memory for %u bytes",
                           r->name, (unsigned long long)at, n);
    r->data = p;
    r->data_cap = n;
  }
  got = read_full(r, r->data, n);
  if (got < 0)
    return mr_io_err_sys(err, "%s: byte %llu: cannot read", r->name,
                         (unsigned long long)(at + sizeof h));
  if ((size_t)got < n)
    return mr_io_err_set(err, MR_IO_ERR_TRUNCATED,
                         "%s: byte %llu: last chunk cut short: %zd of %u bytes, %llu missing",
                         r->name, (unsigned long long)at, got, n,
                         (unsigned long long)(n - (size_t)got));
  r->last_t_ns = t;
  r->chunks++;
  *t_ns = t;
  *data = r->data;
  *len = n;
  return 1;
}

void mr_rec_reader_close(mr_rec_reader *r) {
  if (r->owns_fd && r->fd >= 0) close(r->fd);
  free(r->data);
  r->data = NULL;
  r->data_cap = 0;
  r->fd = -1;
}
