/* The streaming decoder's rules (SPEC.md, "Receiver rules"): resync, every
 * kind of error counted as itself, sequence accounting, spec mismatch. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "decoder_feed.h"
#include "gp.h"

static void byte_at_a_time_equals_whole_buffer(void **state) {
  (void)state;
  uint8_t stream[4096];
  size_t n = 0;
  for (uint16_t s = 0; s < 100; s++) n += sample(s, GP_SPEC_HASH, stream + n);
  gp_decoder a, b;
  gp_decoder_init(&a, GP_SPEC_HASH);
  gp_decoder_init(&b, GP_SPEC_HASH);
  tally ta = { 0 }, tb = { 0 };
  feed(&a, stream, n, &ta);
  for (size_t i = 0; i < n; i++) feed(&b, stream + i, 1, &tb);
  assert_int_equal(ta.ev[GP_EV_FRAME], 100);
  assert_memory_equal(&ta, &tb, sizeof ta);
  assert_memory_equal(&a.c, &b.c, sizeof a.c);
  assert_int_equal(a.c.bytes, n);
}

static void garbage_then_frames_resynchronises_at_the_next_delimiter(void **state) {
  (void)state;
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  tally t = { 0 };
  const uint8_t junk[] = { 0x13, 0x37, 0x42, 0x99, 0x01, 0xFE };
  feed(&d, junk, sizeof junk, &t); /* no delimiter yet: swallowed into the next frame */
  uint16_t seqs[] = { 0, 1 };
  send_samples(&d, &t, seqs, 2);
  /* The junk ran into frame 0, which is lost; frame 1 is intact. Before the
   * first delimiter the junk may be the tail of a frame joined mid-way, so
   * it is no error (SPEC.md, rule 1). */
  assert_int_equal(t.ev[GP_EV_FRAME], 1);
  assert_int_equal(d.c.framing_errors + d.c.crc_errors, 0);
  assert_int_equal(t.seqs[0], 1);
  /* The same junk after a delimiter is an error. */
  gp_decoder_init(&d, GP_SPEC_HASH);
  memset(&t, 0, sizeof t);
  const uint8_t z = 0;
  feed(&d, &z, 1, &t);
  feed(&d, junk, sizeof junk, &t);
  send_samples(&d, &t, seqs, 2);
  assert_int_equal(t.ev[GP_EV_FRAME], 1);
  assert_int_equal(t.ev[GP_EV_FRAMING_ERROR] + t.ev[GP_EV_CRC_ERROR], 1);
  /* With a delimiter first, nothing is lost. */
  gp_decoder_init(&d, GP_SPEC_HASH);
  memset(&t, 0, sizeof t);
  const uint8_t junk0[] = { 0x13, 0x37, 0x00, 0x00 };
  feed(&d, junk0, sizeof junk0, &t);
  send_samples(&d, &t, seqs, 2);
  assert_int_equal(t.ev[GP_EV_FRAME], 2);
  assert_int_equal(d.c.framing_errors, 0);
}

static void oversize_is_reported_once_and_the_stream_recovers(void **state) {
  (void)state;
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  tally t = { 0 };
  uint8_t big[3 * GP_MAX_WIRE];
  memset(big, 0x55, sizeof big);
  feed(&d, big, sizeof big, &t);
  const uint8_t z = 0;
  feed(&d, &z, 1, &t);
  uint16_t seqs[] = { 5, 6 };
  send_samples(&d, &t, seqs, 2);
  assert_int_equal(d.c.oversize, 1);
  assert_int_equal(t.ev[GP_EV_OVERSIZE], 1);
  assert_int_equal(t.ev[GP_EV_FRAME], 2);
  /* Exactly GP_MAX_WIRE bytes is not oversize (it fails later as malformed). */
  gp_decoder_init(&d, GP_SPEC_HASH);
  memset(&t, 0, sizeof t);
  feed(&d, &z, 1, &t);
  feed(&d, big, GP_MAX_WIRE, &t);
  feed(&d, &z, 1, &t);
  assert_int_equal(d.c.oversize, 0);
  assert_int_equal(d.c.framing_errors + d.c.crc_errors, 1);
}

static void truncated_frames_are_framing_errors(void **state) {
  (void)state;
  uint8_t w[GP_MAX_WIRE];
  size_t n = sample(9, GP_SPEC_HASH, w);
  for (size_t keep = 1; keep + 1 < n; keep++) {
    gp_decoder d;
    gp_decoder_init(&d, GP_SPEC_HASH);
    tally t = { 0 };
    uint8_t cut[GP_MAX_WIRE + 1] = { 0 };
    memcpy(cut + 1, w, keep);
    cut[keep + 1] = 0;
    feed(&d, cut, keep + 2, &t);
    assert_int_equal(d.c.framing_errors, 1);
    assert_int_equal(d.c.frames, 0);
  }
}

static void gaps_duplicates_and_reordering_are_counted_as_such(void **state) {
  (void)state;
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  tally t = { 0 };
  /* 3 and 4 lost, 6 duplicated, 8 and 9 swapped, 11 arrives after 13. */
  uint16_t seqs[] = { 0, 1, 2, 5, 6, 6, 7, 9, 8, 10, 12, 13, 11, 14 };
  send_samples(&d, &t, seqs, (int)(sizeof seqs / sizeof seqs[0]));
  assert_int_equal(d.c.lost, 2);
  assert_int_equal(d.c.duplicates, 1);
  assert_int_equal(d.c.reordered, 2);
  assert_int_equal(t.ev[GP_EV_FRAME_LATE], 2);
  assert_int_equal(d.c.frames, 13);
  assert_int_equal(d.c.seq_restarts, 0);
}

static void sequence_wraps_at_65536_without_loss(void **state) {
  (void)state;
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  tally t = { 0 };
  uint16_t seqs[] = { 65533, 65534, 65535, 0, 1, 2 };
  send_samples(&d, &t, seqs, 6);
  assert_int_equal(d.c.lost, 0);
  assert_int_equal(d.c.frames, 6);
  assert_int_equal(d.c.seq_restarts, 0);
}

static void a_device_restart_is_not_counted_as_loss(void **state) {
  (void)state;
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  tally t = { 0 };
  uint16_t seqs[] = { 1000, 1001, 1002, 0, 1, 2 };
  send_samples(&d, &t, seqs, 6);
  assert_int_equal(d.c.seq_restarts, 1);
  assert_int_equal(d.c.lost, 0);
  assert_int_equal(d.c.frames, 6);
}

static void unknown_type_with_good_crc_is_reported_as_unknown(void **state) {
  (void)state;
  uint8_t raw[8] = { 0x7E, 1, 2, 3 };
  uint32_t crc = gp_frame_crc(GP_SPEC_HASH, raw, 4);
  for (int k = 0; k < 4; k++) raw[4 + k] = (uint8_t)(crc >> (8 * k));
  uint8_t w[16];
  size_t n = gp_cobs_encode(raw, 8, w, sizeof w);
  w[n++] = 0;
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  tally t = { 0 };
  feed(&d, w, n, &t);
  assert_int_equal(d.c.unknown_type, 1);
  /* The same bytes with a bad CRC are a CRC error, not an unknown type. */
  w[3] ^= 0x10;
  feed(&d, w, n, &t);
  assert_int_equal(d.c.unknown_type, 1);
  assert_int_equal(d.c.crc_errors, 1);
}

static size_t info(uint32_t announced, uint8_t *wire) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_INFO;
  m.u.info.proto_major = GP_PROTO_MAJOR;
  m.u.info.spec_hash = announced;
  m.u.info.n_channels = 5;
  return gp_encode(&m, announced, wire, GP_MAX_WIRE);
}

static void a_device_from_another_spec_is_reported_with_both_hashes(void **state) {
  (void)state;
  const uint32_t foreign = 0x12345678u;
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  tally t = { 0 };
  uint8_t w[GP_MAX_WIRE];
  feed(&d, w, info(foreign, w), &t);
  assert_int_equal(t.ev[GP_EV_SPEC_MISMATCH], 1);
  assert_true(d.peer_known);
  assert_int_equal(d.peer_hash, foreign);
  for (uint16_t s = 0; s < 10; s++) feed(&d, w, sample(s, foreign, w), &t);
  assert_int_equal(d.c.spec_mismatch, 11);
  assert_int_equal(d.c.crc_errors, 0);
  assert_int_equal(d.c.frames, 0);
  /* Our own frames still pass alongside. */
  feed(&d, w, sample(0, GP_SPEC_HASH, w), &t);
  assert_int_equal(d.c.frames, 1);
}

static void an_info_of_another_length_is_read_by_its_frozen_prefix(void **state) {
  (void)state;
  /* A future INFO with 3 more payload bytes, from another spec. */
  uint8_t raw[GP_MAX_FRAME + 8] = { GP_INFO, 7, 0xEF, 0xBE, 0xAD, 0xDE, 1, 2, 3 };
  size_t len = 9;
  uint32_t crc = gp_frame_crc(0, raw, len);
  for (int k = 0; k < 4; k++) raw[len + k] = (uint8_t)(crc >> (8 * k));
  uint8_t w[GP_MAX_WIRE + 8];
  size_t n = gp_cobs_encode(raw, len + 4, w, sizeof w);
  w[n++] = 0;
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  gp_msg out;
  gp_event ev;
  gp_decoder_feed(&d, w, n, &out, &ev);
  assert_int_equal(ev, GP_EV_SPEC_MISMATCH);
  assert_int_equal(out.u.info.proto_major, 7);
  assert_int_equal(out.u.info.spec_hash, 0xDEADBEEFu);
  /* The same short INFO claiming our own hash is malformed. */
  raw[2] = (uint8_t)GP_SPEC_HASH;
  raw[3] = (uint8_t)(GP_SPEC_HASH >> 8);
  raw[4] = (uint8_t)(GP_SPEC_HASH >> 16);
  raw[5] = (uint8_t)(GP_SPEC_HASH >> 24);
  crc = gp_frame_crc(0, raw, len);
  for (int k = 0; k < 4; k++) raw[len + k] = (uint8_t)(crc >> (8 * k));
  n = gp_cobs_encode(raw, len + 4, w, sizeof w);
  w[n++] = 0;
  gp_decoder_init(&d, GP_SPEC_HASH);
  const uint8_t z = 0;
  gp_decoder_feed(&d, &z, 1, &out, &ev);
  gp_decoder_feed(&d, w, n, &out, &ev);
  assert_int_equal(ev, GP_EV_FRAMING_ERROR);
}

static void every_byte_is_counted_and_nothing_read_out_of_bounds(void **state) {
  (void)state;
  uint32_t r = 99;
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  uint8_t noise[20000];
  for (size_t i = 0; i < sizeof noise; i++) {
    r = r * 1103515245u + 12345u;
    noise[i] = (r >> 16) % 8 == 0 ? 0 : (uint8_t)(r >> 8);
  }
  tally t = { 0 };
  feed(&d, noise, sizeof noise, &t);
  assert_int_equal(d.c.bytes, sizeof noise);
  assert_int_equal(d.c.frames, 0);
  uint16_t seqs[] = { 1, 2, 3 };
  const uint8_t z = 0;
  feed(&d, &z, 1, &t);
  send_samples(&d, &t, seqs, 3);
  assert_int_equal(t.ev[GP_EV_FRAME], 3);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(byte_at_a_time_equals_whole_buffer),
    cmocka_unit_test(garbage_then_frames_resynchronises_at_the_next_delimiter),
    cmocka_unit_test(oversize_is_reported_once_and_the_stream_recovers),
    cmocka_unit_test(truncated_frames_are_framing_errors),
    cmocka_unit_test(gaps_duplicates_and_reordering_are_counted_as_such),
    cmocka_unit_test(sequence_wraps_at_65536_without_loss),
    cmocka_unit_test(a_device_restart_is_not_counted_as_loss),
    cmocka_unit_test(unknown_type_with_good_crc_is_reported_as_unknown),
    cmocka_unit_test(a_device_from_another_spec_is_reported_with_both_hashes),
    cmocka_unit_test(an_info_of_another_length_is_read_by_its_frozen_prefix),
    cmocka_unit_test(every_byte_is_counted_and_nothing_read_out_of_bounds),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
