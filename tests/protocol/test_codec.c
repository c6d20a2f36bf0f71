/* CRC, COBS and packing: the layers under the decoder. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "gp.h"

static uint32_t rng = 12345;
static uint32_t next_rand(void) {
  rng ^= rng << 13;
  rng ^= rng >> 17;
  rng ^= rng << 5;
  return rng;
}

static void crc32c_matches_catalogue_check_value(void **state) {
  (void)state;
  assert_int_equal(gp_crc32c(0, "123456789", 9), 0xE3069283u);
  /* Incremental pieces give the CRC of the whole. */
  uint32_t c = gp_crc32c(0, "1234", 4);
  assert_int_equal(gp_crc32c(c, "56789", 5), 0xE3069283u);
  assert_int_equal(gp_crc32c(0, "", 0), 0u);
}

static void cobs_round_trips_every_length_and_zero_pattern(void **state) {
  (void)state;
  uint8_t in[600], enc[620], dec[600];
  for (size_t len = 0; len <= 600; len++) {
    for (int pattern = 0; pattern < 4; pattern++) {
      for (size_t i = 0; i < len; i++)
        in[i] = pattern == 0   ? 0
                : pattern == 1 ? 0xAB
                : pattern == 2 ? (uint8_t)(i % 256)
                               : (uint8_t)next_rand();
      size_t n = gp_cobs_encode(in, len, enc, sizeof enc);
      assert_true(n >= len + 1 && n <= len + 1 + len / 254 + 1);
      assert_null(memchr(enc, 0, n));
      int m = gp_cobs_decode(enc, n, dec, sizeof dec);
      assert_int_equal(m, (int)len);
      assert_memory_equal(in, dec, len);
    }
  }
}

static void cobs_rejects_malformed_blocks_and_small_buffers(void **state) {
  (void)state;
  uint8_t out[16];
  const uint8_t past_end[] = { 0x05, 1, 2 };
  const uint8_t has_zero[] = { 0x03, 1, 0 };
  const uint8_t zero_code[] = { 0x00 };
  assert_int_equal(gp_cobs_decode(past_end, sizeof past_end, out, sizeof out), -1);
  assert_int_equal(gp_cobs_decode(has_zero, sizeof has_zero, out, sizeof out), -1);
  assert_int_equal(gp_cobs_decode(zero_code, 1, out, sizeof out), -1);
  const uint8_t ok[] = { 0x03, 1, 2, 0x02, 3 };
  assert_int_equal(gp_cobs_decode(ok, sizeof ok, out, 4), 4);
  assert_int_equal(gp_cobs_decode(ok, sizeof ok, out, 3), -1);
  const uint8_t data[] = { 1, 2, 0, 3 };
  assert_int_equal(gp_cobs_encode(data, sizeof data, out, 4), 0);
  assert_int_equal(gp_cobs_encode(data, sizeof data, out, 5), 5);
}

/* Fill every field of a message with random values within its width. */
static void random_msg(const gp_msg_desc *d, gp_msg *m) {
  memset(m, 0, sizeof *m);
  m->type = d->type;
  for (unsigned f = 0; f < d->n_fields; f++) {
    const gp_field_desc *fd = &d->fields[f];
    for (unsigned e = 0; e < fd->count; e++) {
      uint32_t v = next_rand();
      if (fd->bits < 32) v &= (1u << fd->bits) - 1u;
      uint8_t *p = (uint8_t *)&m->u + fd->offset + e * fd->elem_size;
      if (fd->elem_size == 1)
        *p = (uint8_t)v;
      else if (fd->elem_size == 2) {
        uint16_t x = (uint16_t)v;
        memcpy(p, &x, 2);
      } else
        memcpy(p, &v, 4);
    }
  }
}

static void every_message_type_round_trips_through_the_decoder(void **state) {
  (void)state;
  for (size_t t = 0; t < gp_msg_desc_count; t++) {
    const gp_msg_desc *d = &gp_msg_descs[t];
    for (int trial = 0; trial < 200; trial++) {
      gp_msg m, out;
      random_msg(d, &m);
      if (d->type == GP_INFO) m.u.info.spec_hash = GP_SPEC_HASH;
      if (d->type == GP_SAMPLE) m.u.sample.seq = (uint16_t)trial;
      uint8_t wire[GP_MAX_WIRE];
      size_t n = gp_encode(&m, GP_SPEC_HASH, wire, sizeof wire);
      assert_true(n >= 1u + d->len + 4u + 2u && n <= GP_MAX_WIRE);
      gp_decoder dec;
      gp_decoder_init(&dec, GP_SPEC_HASH);
      memset(&out, 0, sizeof out);
      gp_event ev;
      size_t used = gp_decoder_feed(&dec, wire, n, &out, &ev);
      assert_int_equal(used, n);
      assert_int_equal(ev, GP_EV_FRAME);
      assert_memory_equal(&m, &out, sizeof m);
    }
  }
}

static void sample_is_22_bytes_on_the_wire_and_fits_half_the_link(void **state) {
  (void)state;
  gp_msg m;
  memset(&m, 0xFF, sizeof m); /* worst case: no zero bytes to stuff */
  m.type = GP_SAMPLE;
  uint8_t wire[GP_MAX_WIRE];
  size_t n = gp_encode(&m, GP_SPEC_HASH, wire, sizeof wire);
  assert_int_equal(n, 22);
  /* 8N1: 10 bits a byte. 250 Hz on 115200 and 1000 Hz on 921600. */
  assert_true(n * 10u * 250u * 2u <= 115200u);
  assert_true(n * 10u * 1000u * 2u <= 921600u);
}

static void values_wider_than_their_field_are_truncated_not_spilled(void **state) {
  (void)state;
  gp_msg m, out;
  memset(&m, 0, sizeof m);
  m.type = GP_SAMPLE;
  m.u.sample.ch[0] = 0xFFFF; /* 12-bit field */
  m.u.sample.flags = 0xFFFF; /* 12-bit field */
  uint8_t raw[GP_MAX_FRAME];
  size_t n = gp_frame_pack(&m, GP_SPEC_HASH, raw, sizeof raw);
  assert_int_equal(n, 20);
  memset(&out, 0, sizeof out);
  assert_int_equal(gp_payload_unpack(GP_SAMPLE, raw + 1, GP_SAMPLE_LEN, &out), 0);
  assert_int_equal(out.u.sample.ch[0], 0xFFF);
  assert_int_equal(out.u.sample.ch[1], 0);
  assert_int_equal(out.u.sample.flags, 0xFFF);
}

static void unknown_types_and_small_buffers_are_refused(void **state) {
  (void)state;
  gp_msg m;
  memset(&m, 0, sizeof m);
  uint8_t buf[GP_MAX_WIRE];
  m.type = 0x7F;
  assert_int_equal(gp_encode(&m, GP_SPEC_HASH, buf, sizeof buf), 0);
  assert_int_equal(gp_payload_unpack(0x7F, buf, 1, &m), -1);
  m.type = GP_SAMPLE;
  assert_int_equal(gp_encode(&m, GP_SPEC_HASH, buf, 21), 0);
  assert_int_equal(gp_encode(&m, GP_SPEC_HASH, buf, 22), 22);
  assert_int_equal(gp_payload_unpack(GP_SAMPLE, buf, GP_SAMPLE_LEN - 1, &m), -1);
  assert_null(gp_msg_find(0x7F));
  assert_non_null(gp_msg_find(GP_INFO));
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(crc32c_matches_catalogue_check_value),
    cmocka_unit_test(cobs_round_trips_every_length_and_zero_pattern),
    cmocka_unit_test(cobs_rejects_malformed_blocks_and_small_buffers),
    cmocka_unit_test(every_message_type_round_trips_through_the_decoder),
    cmocka_unit_test(sample_is_22_bytes_on_the_wire_and_fits_half_the_link),
    cmocka_unit_test(values_wider_than_their_field_are_truncated_not_spilled),
    cmocka_unit_test(unknown_types_and_small_buffers_are_refused),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
