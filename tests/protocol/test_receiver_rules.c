/* SPEC.md's receiver rules at their edges: another definition's frames of
 * any length, the size limits, frames too short for their type, a sequence
 * gap of exactly the window, restarts from any number, and a receiver that
 * joins a stream mid-way. */
#include "decoder_feed.h"

/* Payload lengths the foreign-frame tests reach: far past GP_MAX_WIRE, and
 * past COBS's 254-byte groups. */
#define LONGEST 700u

/* A raw frame of any type and payload, CRC'd with hash (0: unseeded), framed
 * after a delimiter so the decoder is in step. */
static size_t raw_wire(uint8_t type, const uint8_t *payload, size_t plen, uint32_t hash, uint8_t *w,
                       size_t cap) {
  uint8_t raw[LONGEST + 8];
  assert_true(plen <= LONGEST);
  raw[0] = type;
  memcpy(raw + 1, payload, plen);
  uint32_t crc = hash ? gp_frame_crc(hash, raw, 1 + plen) : gp_crc32c(0, raw, 1 + plen);
  for (int k = 0; k < 4; k++) raw[1 + plen + (size_t)k] = (uint8_t)(crc >> (8 * k));
  w[0] = 0;
  size_t n = gp_cobs_encode(raw, 1 + plen + 4, w + 1, cap - 2);
  assert_true(n > 0);
  w[1 + n] = 0;
  return n + 2;
}

static gp_event one_frame(gp_decoder *d, const uint8_t *w, size_t n, gp_msg *out) {
  gp_event last = GP_EV_NONE;
  while (n) {
    gp_event ev;
    size_t used = gp_decoder_feed(d, w, n, out, &ev);
    if (ev != GP_EV_NONE) last = ev;
    w += used;
    n -= used;
  }
  return last;
}

static void a_foreign_info_of_every_length_is_a_spec_mismatch(void **state) {
  (void)state;
  const uint32_t foreign = 0xDEADBEEFu;
  /* Payloads from the frozen prefix (5 bytes) through the 58 raw bytes a
   * receiver decodes whole, and on past the wire limit, where it follows the
   * run with bounded memory. Every 7th byte is 0, so COBS groups vary. */
  for (size_t plen = 5; plen <= LONGEST; plen++) {
    uint8_t p[LONGEST] = { GP_PROTO_MAJOR, 0xEF, 0xBE, 0xAD, 0xDE };
    for (size_t i = 5; i < plen; i++) p[i] = i % 7u == 0 ? 0 : (uint8_t)(i * 37u + 1u);
    uint8_t w[2 * LONGEST];
    size_t n = raw_wire(GP_INFO, p, plen, 0, w, sizeof w);
    gp_decoder d;
    gp_decoder_init(&d, GP_SPEC_HASH);
    gp_msg out;
    assert_int_equal(one_frame(&d, w, n, &out), GP_EV_SPEC_MISMATCH);
    assert_int_equal(d.c.spec_mismatch, 1);
    assert_int_equal(d.c.framing_errors + d.c.crc_errors + d.c.oversize, 0);
    assert_int_equal(out.u.info.spec_hash, foreign);
    assert_int_equal(d.peer_hash, foreign);
  }
}

static void a_foreign_sample_of_every_length_is_a_spec_mismatch(void **state) {
  (void)state;
  const uint32_t foreign = 0xDEADBEEFu;
  uint8_t w[2 * LONGEST];
  uint8_t p[64] = { GP_PROTO_MAJOR, 0xEF, 0xBE, 0xAD, 0xDE };
  for (size_t plen = 0; plen <= LONGEST; plen++) {
    gp_decoder d;
    gp_decoder_init(&d, GP_SPEC_HASH);
    gp_msg out;
    assert_int_equal(one_frame(&d, w, raw_wire(GP_INFO, p, 5, 0, w, sizeof w), &out),
                     GP_EV_SPEC_MISMATCH);
    uint8_t q[LONGEST];
    for (size_t i = 0; i < plen; i++) q[i] = i % 5u == 0 ? 0 : (uint8_t)(i * 11u + 3u);
    assert_int_equal(one_frame(&d, w, raw_wire(GP_SAMPLE, q, plen, foreign, w, sizeof w), &out),
                     GP_EV_SPEC_MISMATCH);
    assert_int_equal(d.c.spec_mismatch, 2);
    assert_int_equal(d.c.frames + d.c.framing_errors + d.c.crc_errors + d.c.oversize, 0);
  }
}

static void a_58_byte_raw_frame_is_judged_as_the_spec_says(void **state) {
  (void)state;
  /* One byte longer than GP_MAX_FRAME: decoded, and a framing error when it
   * is ours (rule 6) whatever its type and CRC. */
  uint8_t p[64];
  memset(p, 0x5A, sizeof p);
  /* An INFO announcing our own hash, so rule 4 does not take it. */
  for (int k = 0; k < 4; k++) p[1 + k] = (uint8_t)(GP_SPEC_HASH >> (8 * k));
  const size_t plen = GP_MAX_FRAME + 1u - 1u - GP_CRC_LEN;
  const uint8_t types[] = { GP_SAMPLE, GP_INFO, 0x7E };
  for (size_t k = 0; k < sizeof types; k++) {
    uint8_t w[GP_MAX_WIRE + 8];
    size_t n = raw_wire(types[k], p, plen, GP_SPEC_HASH, w, sizeof w);
    assert_int_equal(n - 2, GP_MAX_WIRE); /* 59 bytes between the delimiters */
    gp_decoder d;
    gp_decoder_init(&d, GP_SPEC_HASH);
    gp_msg out;
    assert_int_equal(one_frame(&d, w, n, &out), GP_EV_FRAMING_ERROR);
    assert_int_equal(d.c.oversize + d.c.unknown_type + d.c.frames, 0);
  }
  /* One byte more on the wire is oversize, for our own INFO too, and for a
   * run past the limit whose CRC is good under nobody's hash. */
  uint8_t w[GP_MAX_WIRE + 8];
  gp_decoder d;
  gp_msg out;
  const uint8_t longer[] = { 0x7E, GP_INFO };
  for (size_t k = 0; k < sizeof longer; k++) {
    size_t n = raw_wire(longer[k], p, plen + 1, GP_SPEC_HASH, w, sizeof w);
    gp_decoder_init(&d, GP_SPEC_HASH);
    assert_int_equal(one_frame(&d, w, n, &out), GP_EV_OVERSIZE);
    assert_int_equal(d.c.oversize, 1);
    assert_int_equal(d.c.spec_mismatch, 0);
  }
}

static void a_long_run_that_is_no_foreign_frame_is_one_oversize(void **state) {
  (void)state;
  /* Starts like an INFO, a peer is known, and the bytes run on for 500:
   * followed to the delimiter, then one oversize, and the stream goes on. */
  uint8_t w[GP_MAX_WIRE + 8];
  uint8_t p[8] = { GP_PROTO_MAJOR, 0xEF, 0xBE, 0xAD, 0xDE };
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  gp_msg out;
  size_t n_info = raw_wire(GP_INFO, p, 5, 0, w, sizeof w);
  assert_int_equal(one_frame(&d, w, n_info, &out), GP_EV_SPEC_MISMATCH);
  uint8_t junk[502];
  memset(junk, 0x37, sizeof junk);
  junk[0] = 0xFF;
  junk[1] = GP_INFO;
  junk[sizeof junk - 1] = 0;
  tally t = { 0 };
  feed(&d, junk, sizeof junk, &t);
  assert_int_equal(d.c.oversize, 1);
  assert_int_equal(d.c.spec_mismatch, 1);
  uint16_t seqs[] = { 1, 2 };
  send_samples(&d, &t, seqs, 2);
  assert_int_equal(t.ev[GP_EV_FRAME], 2);
  uint8_t one[GP_MAX_WIRE];
  assert_int_equal(d.c.bytes, n_info + sizeof junk + 2 * sample(1, GP_SPEC_HASH, one));
}

static void a_sample_one_byte_long_with_a_valid_crc_is_a_framing_error(void **state) {
  (void)state;
  const uint8_t p[1] = { 0x01 };
  uint8_t w[GP_MAX_WIRE + 8];
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  gp_msg out;
  assert_int_equal(one_frame(&d, w, raw_wire(GP_SAMPLE, p, 1, GP_SPEC_HASH, w, sizeof w), &out),
                   GP_EV_FRAMING_ERROR);
  assert_int_equal(d.c.framing_errors, 1);
  assert_int_equal(d.c.frames + d.c.crc_errors, 0);
  assert_false(d.have_seq);
}

static void a_four_byte_frame_of_unknown_type_is_a_framing_error(void **state) {
  (void)state;
  /* Type and three bytes: shorter than type and CRC (rule 3). */
  const uint8_t w[] = { 0x00, 0x05, 0x7E, 0x11, 0x22, 0x33, 0x00 };
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  gp_msg out;
  assert_int_equal(one_frame(&d, w, sizeof w, &out), GP_EV_FRAMING_ERROR);
  assert_int_equal(d.c.framing_errors, 1);
  assert_int_equal(d.c.crc_errors + d.c.unknown_type, 0);
}

static void a_cut_off_info_is_a_framing_error_not_a_crc_error(void **state) {
  (void)state;
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_INFO;
  m.u.info.proto_major = GP_PROTO_MAJOR;
  m.u.info.spec_hash = GP_SPEC_HASH;
  uint8_t raw[GP_MAX_FRAME];
  size_t len = gp_frame_pack(&m, GP_SPEC_HASH, raw, sizeof raw);
  /* Every cut that leaves at least type and CRC's worth of bytes. */
  for (size_t keep = 1u + GP_CRC_LEN; keep < len; keep++) {
    uint8_t w[GP_MAX_WIRE + 2] = { 0 };
    size_t n = gp_cobs_encode(raw, keep, w + 1, GP_MAX_WIRE);
    w[n + 1] = 0;
    gp_decoder d;
    gp_decoder_init(&d, GP_SPEC_HASH);
    gp_msg out;
    assert_int_equal(one_frame(&d, w, n + 2, &out), GP_EV_FRAMING_ERROR);
    assert_int_equal(d.c.crc_errors, 0);
  }
}

static void a_jump_of_exactly_the_window_then_a_late_frame_inside_it_is_reordered(void **state) {
  (void)state;
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  tally t = { 0 };
  /* 0..10 seen, then 10 -> 74 skips 63 numbers: the whole window moves on,
   * so nothing from before may still look seen. 73 and 11 come late, from
   * inside the gap (a window that kept its old bits would call 73, 72, ...
   * seen, and a shift by 64 is undefined behaviour). */
  uint16_t seqs[] = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 74, 73, 11, 73 };
  send_samples(&d, &t, seqs, 15);
  assert_int_equal(d.c.duplicates, 1); /* the second 73 only */
  assert_int_equal(d.c.reordered, 2);
  assert_int_equal(d.c.lost, 63 - 2);
  assert_int_equal(d.c.frames, 14);
  assert_int_equal(d.c.seq_restarts, 0);
}

static size_t start_sample(uint16_t seq, uint32_t t_us, uint8_t *wire) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SAMPLE;
  m.u.sample.seq = seq;
  m.u.sample.t_us = t_us;
  m.u.sample.flags = GP_SAMPLE_F_START;
  return gp_encode(&m, GP_SPEC_HASH, wire, GP_MAX_WIRE);
}

static void a_restart_from_any_number_is_a_restart_with_nothing_lost(void **state) {
  (void)state;
  const uint16_t from[] = { 0, 30, 100, 32768, 40000, 65535 };
  for (size_t k = 0; k < sizeof from / sizeof from[0]; k++) {
    gp_decoder d;
    gp_decoder_init(&d, GP_SPEC_HASH);
    tally t = { 0 };
    /* The glove had counted up to from[k] (wrapping when it is below 3),
     * then reset: START on its new seq 0, then 1, 2. */
    uint16_t before[] = { (uint16_t)(from[k] - 2), (uint16_t)(from[k] - 1), from[k] };
    send_samples(&d, &t, before, 3);
    uint8_t w[GP_MAX_WIRE];
    feed(&d, w, start_sample(0, 1000, w), &t);
    uint16_t after[] = { 1, 2 };
    send_samples(&d, &t, after, 2);
    assert_int_equal(d.c.seq_restarts, 1);
    assert_int_equal(d.c.lost, 0);
    assert_int_equal(d.c.reordered + d.c.duplicates, 0);
    assert_int_equal(d.c.frames, 6);
  }
}

static void a_copy_of_the_start_frame_is_a_duplicate_not_a_restart(void **state) {
  (void)state;
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  tally t = { 0 };
  uint8_t w[GP_MAX_WIRE];
  feed(&d, w, start_sample(0, 1000, w), &t);
  feed(&d, w, start_sample(0, 1000, w), &t);
  /* A glove reset after its first frame: same number, a later clock. */
  feed(&d, w, start_sample(0, 5000, w), &t);
  assert_int_equal(d.c.duplicates, 1);
  assert_int_equal(d.c.seq_restarts, 1);
  assert_int_equal(d.c.frames, 2);
}

/* After a new link (a reconnect) the glove counts from 0 again with no
 * START flag, the old high only 20 ahead: a restart, every frame delivered,
 * none a duplicate. A glove that kept counting shows its gap as lost, and
 * the link only matters to its first SAMPLE: a copy after it is one. A
 * start frame sent again over a new link is a restart, not its copy. */
static void after_a_new_link_a_sequence_from_below_is_a_restart_not_duplicates(void **state) {
  (void)state;
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  tally t = { 0 };
  uint16_t first[21];
  for (uint16_t i = 0; i <= 20; i++) first[i] = i;
  send_samples(&d, &t, first, 21);
  gp_decoder_new_link(&d);
  const uint16_t again[] = { 0, 1, 2, 2 };
  send_samples(&d, &t, again, 4);
  assert_int_equal(d.c.seq_restarts, 1);
  assert_int_equal(d.c.duplicates, 1);
  assert_int_equal(d.c.lost + d.c.reordered, 0);
  assert_int_equal(t.ev[GP_EV_FRAME], 24);
  /* Kept counting through the unplug: 3 .. 9 lost, no restart. */
  gp_decoder_new_link(&d);
  const uint16_t on[] = { 10, 11 };
  send_samples(&d, &t, on, 2);
  assert_int_equal(d.c.lost, 7);
  assert_int_equal(d.c.seq_restarts, 1);
  /* The same high again on a new link is the glove counting again. */
  gp_decoder_new_link(&d);
  const uint16_t same[] = { 11 };
  send_samples(&d, &t, same, 1);
  assert_int_equal(d.c.seq_restarts, 2);
  assert_int_equal(d.c.duplicates, 1);
  /* A glove that boots to the very same start frame over each new link:
   * no copy, a restart each time. */
  uint8_t w[GP_MAX_WIRE];
  feed(&d, w, start_sample(0, 1000, w), &t);
  gp_decoder_new_link(&d);
  feed(&d, w, start_sample(0, 1000, w), &t);
  assert_int_equal(d.c.seq_restarts, 4);
  assert_int_equal(d.c.duplicates, 1);
}

static void joining_a_stream_mid_way_costs_no_error_and_empty_frames_count_nowhere(void **state) {
  (void)state;
  uint8_t stream[8 * GP_MAX_WIRE];
  size_t n = 0;
  for (uint16_t s = 0; s < 4; s++) n += sample(s, GP_SPEC_HASH, stream + n);
  size_t first = n / 4;
  /* Joined at every byte of the first frame: its tail is no error, and the
   * next three frames arrive. */
  for (size_t k = 1; k < first; k++) {
    gp_decoder d;
    gp_decoder_init(&d, GP_SPEC_HASH);
    tally t = { 0 };
    feed(&d, stream + k, n - k, &t);
    assert_int_equal(d.c.framing_errors + d.c.crc_errors + d.c.oversize, 0);
    assert_int_equal(d.c.frames, 3);
    assert_int_equal(d.c.bytes, n - k);
  }
  /* Empty frames between and around frames: only bytes counts them. */
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  tally t = { 0 };
  const uint8_t zeros[5] = { 0 };
  feed(&d, zeros, sizeof zeros, &t);
  feed(&d, stream, n, &t);
  feed(&d, zeros, sizeof zeros, &t);
  gp_counters want = { 0 };
  want.frames = 4;
  want.bytes = n + 2 * sizeof zeros;
  assert_memory_equal(&d.c, &want, sizeof want);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_foreign_info_of_every_length_is_a_spec_mismatch),
    cmocka_unit_test(a_foreign_sample_of_every_length_is_a_spec_mismatch),
    cmocka_unit_test(a_58_byte_raw_frame_is_judged_as_the_spec_says),
    cmocka_unit_test(a_long_run_that_is_no_foreign_frame_is_one_oversize),
    cmocka_unit_test(a_sample_one_byte_long_with_a_valid_crc_is_a_framing_error),
    cmocka_unit_test(a_four_byte_frame_of_unknown_type_is_a_framing_error),
    cmocka_unit_test(a_cut_off_info_is_a_framing_error_not_a_crc_error),
    cmocka_unit_test(a_jump_of_exactly_the_window_then_a_late_frame_inside_it_is_reordered),
    cmocka_unit_test(a_restart_from_any_number_is_a_restart_with_nothing_lost),
    cmocka_unit_test(a_copy_of_the_start_frame_is_a_duplicate_not_a_restart),
    cmocka_unit_test(after_a_new_link_a_sequence_from_below_is_a_restart_not_duplicates),
    cmocka_unit_test(joining_a_stream_mid_way_costs_no_error_and_empty_frames_count_nowhere),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
