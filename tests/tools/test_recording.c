/* The .mrec format: what is written reads back identical; every malformation
 * is rejected naming its byte offset; a cut-short last chunk keeps the
 * chunks before it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mr_io.h"
#include "tools_proc.h"

static char *g_dir;

static int setup(void **state) {
  (void)state;
  g_dir = tt_tmpdir();
  return g_dir ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  tt_rmdir(g_dir);
  free(g_dir);
  return 0;
}

static void put_le(uint8_t *p, uint64_t v, int n) {
  for (int i = 0; i < n; i++) p[i] = (uint8_t)(v >> (8 * i));
}

/* A hand-built file: header fields as given, then chunks. */
typedef struct raw_file {
  uint8_t b[4096];
  size_t n;
} raw_file;

static void raw_header(raw_file *f, const char *magic, unsigned version, unsigned header_len) {
  memset(f, 0, sizeof *f);
  memcpy(f->b, magic, 8);
  put_le(f->b + 8, version, 2);
  put_le(f->b + 10, header_len, 2);
  put_le(f->b + 12, 0xA0A8FACAu, 4);
  put_le(f->b + 16, 1700000000000000000ull, 8);
  f->n = 32;
}

static size_t raw_chunk(raw_file *f, uint64_t t, uint32_t len_field, size_t data_len) {
  size_t at = f->n;
  put_le(f->b + f->n, t, 8);
  put_le(f->b + f->n + 8, len_field, 4);
  f->n += 12;
  for (size_t i = 0; i < data_len; i++) f->b[f->n++] = (uint8_t)(i * 7 + 1);
  return at;
}

static const char *save(const raw_file *f, size_t n) {
  const char *path = tt_path(g_dir, "bad.mrec");
  FILE *fp = fopen(path, "wb");
  assert_non_null(fp);
  assert_int_equal(fwrite(f->b, 1, n, fp), n);
  fclose(fp);
  return path;
}

/* Reads all chunks; returns how many were complete and the final status. */
static int read_all(const char *path, int *final_rc, mr_io_error *err) {
  mr_rec_reader r;
  uint64_t t;
  const uint8_t *d;
  size_t len;
  int n = 0, rc;
  if (mr_rec_reader_open(&r, path, err) != 0) {
    *final_rc = -1;
    return -1;
  }
  while ((rc = mr_rec_reader_next(&r, &t, &d, &len, err)) == 1) n++;
  *final_rc = rc;
  mr_rec_reader_close(&r);
  return n;
}

static void expect_open_error(const raw_file *f, size_t n, const char *where) {
  mr_rec_reader r;
  mr_io_error err;
  assert_int_equal(mr_rec_reader_open(&r, save(f, n), &err), -1);
  assert_int_equal(err.status, MR_IO_ERR_FORMAT);
  if (!strstr(err.msg, where)) fail_msg("'%s' does not name '%s'", err.msg, where);
}

static void tools_recording_write_then_read_back_identical(void **state) {
  const char *path = tt_path(g_dir, "ok.mrec");
  mr_rec_writer w;
  mr_rec_reader r;
  mr_io_error err;
  uint8_t *data = malloc(MR_REC_MAX_CHUNK + 8); /* chunk i starts at data + i */
  size_t lens[] = { 1, 21, 21, 300, 4096, MR_REC_MAX_CHUNK, 2 };
  uint64_t times[] = { 0, 0, 4000000, 4000000, 8000001, 9000000000ull, 9000000001ull };
  uint64_t t;
  const uint8_t *d;
  size_t len;
  (void)state;
  assert_non_null(data);
  for (size_t i = 0; i < MR_REC_MAX_CHUNK + 8; i++) data[i] = (uint8_t)(i * 31 + (i >> 8));
  assert_int_equal(mr_rec_writer_open(&w, path, 0xA0A8FACAu, 1234567890123ull, &err), 0);
  for (size_t i = 0; i < 7; i++)
    assert_int_equal(mr_rec_writer_add(&w, times[i], data + i, lens[i], &err), 0);
  assert_int_equal(mr_rec_writer_close(&w, &err), 0);

  assert_int_equal(mr_rec_reader_open(&r, path, &err), 0);
  assert_int_equal(r.header.version, 1);
  assert_int_equal(r.header.header_len, 32);
  assert_int_equal(r.header.spec_hash, 0xA0A8FACAu);
  assert_int_equal(r.header.start_unix_ns, 1234567890123ull);
  for (size_t i = 0; i < 7; i++) {
    assert_int_equal(mr_rec_reader_next(&r, &t, &d, &len, &err), 1);
    assert_int_equal(t, times[i]);
    assert_int_equal(len, lens[i]);
    assert_memory_equal(d, data + i, len);
  }
  assert_int_equal(mr_rec_reader_next(&r, &t, &d, &len, &err), 0);
  mr_rec_reader_close(&r);
  free(data);
}

static void tools_recording_writer_refuses_bad_chunks_and_stays_usable(void **state) {
  const char *path = tt_path(g_dir, "w.mrec");
  mr_rec_writer w;
  mr_io_error err;
  uint8_t b[4] = { 1, 2, 3, 4 };
  int final_rc;
  (void)state;
  assert_int_equal(mr_rec_writer_open(&w, path, 1, 0, &err), 0);
  assert_int_equal(mr_rec_writer_add(&w, 10, b, 4, &err), 0);
  assert_int_equal(mr_rec_writer_add(&w, 11, b, 0, &err), -1);
  assert_int_equal(err.status, MR_IO_ERR_ARG);
  assert_int_equal(mr_rec_writer_add(&w, 11, b, MR_REC_MAX_CHUNK + 1, &err), -1);
  assert_int_equal(mr_rec_writer_add(&w, 9, b, 4, &err), -1);
  assert_non_null(strstr(err.msg, "byte 48"));
  assert_int_equal(mr_rec_writer_add(&w, 12, b, 4, &err), 0);
  assert_int_equal(mr_rec_writer_close(&w, &err), 0);
  assert_int_equal(read_all(path, &final_rc, &err), 2);
  assert_int_equal(final_rc, 0);
}

static void tools_recording_header_malformations_name_their_offset(void **state) {
  raw_file f;
  (void)state;
  raw_header(&f, "MRSTREAX", 1, 32);
  expect_open_error(&f, f.n, "byte 0:");
  raw_header(&f, "MRSTREAM", 2, 32);
  expect_open_error(&f, f.n, "byte 8:");
  raw_header(&f, "MRSTREAM", 1, 31);
  expect_open_error(&f, f.n, "byte 10:");
  raw_header(&f, "MRSTREAM", 1, 32);
  expect_open_error(&f, 20, "byte 20:");
  expect_open_error(&f, 0, "byte 0:");
  /* A longer header (a later revision) cut short inside its extra bytes. */
  raw_header(&f, "MRSTREAM", 1, 40);
  expect_open_error(&f, 36, "byte 36:");
}

static void tools_recording_longer_header_is_skipped(void **state) {
  raw_file f;
  mr_io_error err;
  int final_rc;
  (void)state;
  raw_header(&f, "MRSTREAM", 1, 40);
  f.n = 40;
  raw_chunk(&f, 5, 3, 3);
  assert_int_equal(read_all(save(&f, f.n), &final_rc, &err), 1);
  assert_int_equal(final_rc, 0);
}

static void tools_recording_chunk_malformations_name_their_offset(void **state) {
  raw_file f;
  mr_io_error err;
  int final_rc;
  size_t at;
  char where[64];
  (void)state;

  raw_header(&f, "MRSTREAM", 1, 32);
  raw_chunk(&f, 0, 5, 5);
  at = raw_chunk(&f, 1, 0, 0);
  assert_int_equal(read_all(save(&f, f.n), &final_rc, &err), 1);
  assert_int_equal(final_rc, -1);
  assert_int_equal(err.status, MR_IO_ERR_FORMAT);
  snprintf(where, sizeof where, "byte %zu:", at + 8);
  assert_non_null(strstr(err.msg, where));

  raw_header(&f, "MRSTREAM", 1, 32);
  raw_chunk(&f, 0, 5, 5);
  at = raw_chunk(&f, 1, MR_REC_MAX_CHUNK + 1, 0);
  assert_int_equal(read_all(save(&f, f.n), &final_rc, &err), 1);
  assert_int_equal(err.status, MR_IO_ERR_FORMAT);
  snprintf(where, sizeof where, "byte %zu:", at + 8);
  assert_non_null(strstr(err.msg, where));

  raw_header(&f, "MRSTREAM", 1, 32);
  raw_chunk(&f, 100, 5, 5);
  raw_chunk(&f, 200, 5, 5);
  at = raw_chunk(&f, 199, 5, 5);
  assert_int_equal(read_all(save(&f, f.n), &final_rc, &err), 2);
  assert_int_equal(err.status, MR_IO_ERR_FORMAT);
  snprintf(where, sizeof where, "byte %zu:", at);
  assert_non_null(strstr(err.msg, where));
}

static void tools_recording_truncated_last_chunk_keeps_the_rest(void **state) {
  raw_file f;
  mr_io_error err;
  int final_rc;
  size_t at;
  char where[64];
  (void)state;
  raw_header(&f, "MRSTREAM", 1, 32);
  raw_chunk(&f, 0, 21, 21);
  raw_chunk(&f, 10, 21, 21);
  at = raw_chunk(&f, 20, 100, 100);

  /* 40 of the last chunk's 100 data bytes: 60 missing. */
  assert_int_equal(read_all(save(&f, at + 12 + 40), &final_rc, &err), 2);
  assert_int_equal(final_rc, -1);
  assert_int_equal(err.status, MR_IO_ERR_TRUNCATED);
  snprintf(where, sizeof where, "byte %zu:", at);
  assert_non_null(strstr(err.msg, where));
  assert_non_null(strstr(err.msg, "60 missing"));

  /* Only the last data byte missing. */
  assert_int_equal(read_all(save(&f, at + 12 + 99), &final_rc, &err), 2);
  assert_int_equal(err.status, MR_IO_ERR_TRUNCATED);
  assert_non_null(strstr(err.msg, "99 of 100 bytes, 1 missing"));

  /* Cut inside the chunk header: its 7 other bytes and at least one data
   * byte missing. */
  assert_int_equal(read_all(save(&f, at + 5), &final_rc, &err), 2);
  assert_int_equal(err.status, MR_IO_ERR_TRUNCATED);
  assert_non_null(strstr(err.msg, where));
  assert_non_null(strstr(err.msg, "5 of its 12 header bytes, at least 8 bytes missing"));
}

/* A silence of exactly an hour is a take's limit: written and read back,
 * while one nanosecond more is refused by the writer and the reader, each
 * naming the limit. */
static void tools_recording_a_silence_of_exactly_an_hour_is_the_limit(void **state) {
  const char *path = tt_path(g_dir, "hour.mrec");
  mr_rec_writer w;
  mr_io_error err;
  uint8_t b[4] = { 1, 2, 3, 4 };
  raw_file f;
  int final_rc;
  (void)state;
  assert_int_equal(mr_rec_writer_open(&w, path, 1, 0, &err), 0);
  assert_int_equal(mr_rec_writer_add(&w, 5, b, 4, &err), 0);
  assert_int_equal(mr_rec_writer_add(&w, 5 + MR_REC_MAX_GAP_NS + 1, b, 4, &err), -1);
  assert_non_null(strstr(err.msg, "a take holds at most 3600 s of silence"));
  assert_int_equal(mr_rec_writer_add(&w, 5 + MR_REC_MAX_GAP_NS, b, 4, &err), 0);
  assert_int_equal(mr_rec_writer_close(&w, &err), 0);
  assert_int_equal(read_all(path, &final_rc, &err), 2);
  assert_int_equal(final_rc, 0);

  raw_header(&f, "MRSTREAM", 1, 32);
  raw_chunk(&f, 5, 3, 3);
  raw_chunk(&f, 5 + MR_REC_MAX_GAP_NS, 3, 3);
  raw_chunk(&f, 6 + 2 * MR_REC_MAX_GAP_NS, 3, 3);
  assert_int_equal(read_all(save(&f, f.n), &final_rc, &err), 2);
  assert_int_equal(final_rc, -1);
  assert_int_equal(err.status, MR_IO_ERR_FORMAT);
  assert_non_null(strstr(err.msg, "byte 62:"));
  assert_non_null(strstr(err.msg, "a take holds at most 3600 s of silence"));
}

/* A caller that sniffed the magic hands its bytes back as a prefix. */
static void tools_recording_reader_takes_a_sniffed_prefix(void **state) {
  raw_file f;
  mr_rec_reader r;
  mr_io_error err;
  uint64_t t;
  const uint8_t *d;
  size_t len;
  int fd;
  uint8_t sniff[8];
  (void)state;
  raw_header(&f, "MRSTREAM", 1, 32);
  raw_chunk(&f, 7, 4, 4);
  fd = open(save(&f, f.n), O_RDONLY);
  assert_true(fd >= 0);
  assert_int_equal(read(fd, sniff, 8), 8);
  assert_true(mr_rec_is_recording(sniff, 8));
  assert_int_equal(mr_rec_reader_open_fd(&r, fd, "sniffed", sniff, 8, &err), 0);
  assert_int_equal(mr_rec_reader_next(&r, &t, &d, &len, &err), 1);
  assert_int_equal(t, 7);
  assert_int_equal(len, 4);
  assert_memory_equal(d, f.b + 44, 4);
  assert_int_equal(mr_rec_reader_next(&r, &t, &d, &len, &err), 0);
  mr_rec_reader_close(&r);
  close(fd);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(tools_recording_write_then_read_back_identical),
    cmocka_unit_test(tools_recording_writer_refuses_bad_chunks_and_stays_usable),
    cmocka_unit_test(tools_recording_header_malformations_name_their_offset),
    cmocka_unit_test(tools_recording_longer_header_is_skipped),
    cmocka_unit_test(tools_recording_chunk_malformations_name_their_offset),
    cmocka_unit_test(tools_recording_truncated_last_chunk_keeps_the_rest),
    cmocka_unit_test(tools_recording_a_silence_of_exactly_an_hour_is_the_limit),
    cmocka_unit_test(tools_recording_reader_takes_a_sniffed_prefix),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
