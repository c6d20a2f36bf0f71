/* The frames a made-up glove sends (gp_glove.h), read back by the host's
 * decoder: every field of INFO and SAMPLE arrives as it was given, values
 * and times round and clamp as the header says, and a glove built from
 * another definition is told apart. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include <math.h>

#include "gp.h"
#include "gp_glove.h"

/* Feeds one wire frame to a fresh decoder of this build: the event the
 * frame ends on, with *out filled when it carries a message. */
static gp_event decode_one(const uint8_t *wire, size_t n, gp_msg *out) {
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  const uint8_t delim = 0; /* a receiver starts in step after a 0x00 */
  gp_event ev = GP_EV_NONE;
  gp_decoder_feed(&d, &delim, 1, out, &ev);
  size_t used = 0;
  ev = GP_EV_NONE;
  while (used < n && ev == GP_EV_NONE) used += gp_decoder_feed(&d, wire + used, n - used, out, &ev);
  assert_int_equal(used, n);
  return ev;
}

static void an_info_with_every_field_changed_decodes_to_the_same_fields(void **state) {
  (void)state;
  gp_info info = gp_default_glove_info();
  info.fw_major = 2;
  info.fw_minor = 7;
  info.fw_patch = 9;
  info.uid[0] = 0x6b657973u;
  info.uid[1] = 0xdeadbeefu;
  info.uid[2] = 42;
  info.hand = GP_HAND_LEFT;
  info.baud = 9600;
  info.cal_state = GP_CAL_VALID;
  for (unsigned c = 0; c < GP_SAMPLE_CH_COUNT; c++) {
    info.cal_min[c] = (uint16_t)(100 + c);
    info.cal_max[c] = (uint16_t)(3000 + 10 * c);
  }
  gp_glove_info_set_rate(&info, 333.4);
  uint8_t wire[GP_MAX_WIRE];
  size_t n = gp_glove_info_encode(&info, wire, sizeof wire);
  assert_true(n > 0 && n <= GP_MAX_WIRE);
  gp_msg got;
  assert_int_equal(decode_one(wire, n, &got), GP_EV_FRAME);
  assert_int_equal(got.type, GP_INFO);
  const gp_info *g = &got.u.info;
  assert_int_equal(g->proto_major, GP_PROTO_MAJOR);
  assert_int_equal(g->spec_hash, GP_SPEC_HASH);
  assert_int_equal(g->fw_major, 2);
  assert_int_equal(g->fw_minor, 7);
  assert_int_equal(g->fw_patch, 9);
  assert_memory_equal(g->uid, info.uid, sizeof g->uid);
  assert_int_equal(g->hand, GP_HAND_LEFT);
  assert_int_equal(g->n_channels, GP_SAMPLE_CH_COUNT);
  assert_int_equal(g->adc_bits, GP_SAMPLE_CH_BITS);
  assert_int_equal(g->frame_rate_hz, 333);
  assert_int_equal(g->sample_rate_hz, 333);
  assert_int_equal(g->baud, 9600);
  assert_int_equal(g->cal_state, GP_CAL_VALID);
  assert_memory_equal(g->cal_min, info.cal_min, sizeof g->cal_min);
  assert_memory_equal(g->cal_max, info.cal_max, sizeof g->cal_max);
}

static void the_default_info_announces_this_build_and_the_factory_calibration(void **state) {
  (void)state;
  gp_info info = gp_default_glove_info();
  uint8_t wire[GP_MAX_WIRE];
  gp_msg got;
  assert_int_equal(decode_one(wire, gp_glove_info_encode(&info, wire, sizeof wire), &got),
                   GP_EV_FRAME);
  const gp_info *g = &got.u.info;
  assert_int_equal(g->proto_major, GP_PROTO_MAJOR);
  assert_int_equal(g->spec_hash, GP_SPEC_HASH);
  assert_int_equal(g->fw_major, 0);
  assert_int_equal(g->fw_minor, 1);
  assert_int_equal(g->fw_patch, 0);
  assert_int_equal(g->hand, GP_HAND_RIGHT);
  assert_int_equal(g->n_channels, 5);
  assert_int_equal(g->adc_bits, 12);
  assert_int_equal(g->baud, 115200);
  assert_int_equal(g->cal_state, GP_CAL_DEFAULTS);
  for (unsigned c = 0; c < GP_SAMPLE_CH_COUNT; c++) {
    assert_int_equal(g->cal_min[c], 0);
    assert_int_equal(g->cal_max[c], GP_SAMPLE_CH_MAX);
  }
}

static void a_rate_is_rounded_into_infos_field_and_held_to_its_range(void **state) {
  (void)state;
  const struct {
    double hz;
    uint16_t field;
  } cases[] = { { 100, 100 }, { 99.5, 100 }, { 99.49, 99 },      { 0.3, 0 },       { 0, 0 },
                { -5, 0 },    { NAN, 0 },    { 65534.6, 65535 }, { 65535, 65535 }, { 1e6, 65535 } };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    gp_info info = gp_default_glove_info();
    gp_glove_info_set_rate(&info, cases[i].hz);
    assert_int_equal(info.frame_rate_hz, cases[i].field);
    assert_int_equal(info.sample_rate_hz, cases[i].field);
  }
}

static void an_info_from_another_definition_is_a_spec_mismatch_naming_its_hash(void **state) {
  (void)state;
  gp_info info = gp_default_glove_info();
  info.spec_hash = GP_SPEC_HASH ^ 0x5a5a5a5au;
  uint8_t wire[GP_MAX_WIRE];
  gp_msg got;
  assert_int_equal(decode_one(wire, gp_glove_info_encode(&info, wire, sizeof wire), &got),
                   GP_EV_SPEC_MISMATCH);
  assert_int_equal(got.u.info.spec_hash, GP_SPEC_HASH ^ 0x5a5a5a5au);
}

static void values_become_counts_rounded_and_clamped(void **state) {
  (void)state;
  const struct {
    double v;
    uint16_t count;
  } cases[] = { { 0, 0 },    { 0.25, 1024 },   { 0.5, 2048 },     { 0.75, 3071 },
                { 1, 4095 }, { 0.1, 410 },     { -0.2, 0 },       { 1.3, 4095 },
                { NAN, 0 },  { -INFINITY, 0 }, { INFINITY, 4095 } };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    assert_int_equal(gp_glove_value_count(cases[i].v), cases[i].count);
}

static void seconds_become_microseconds_rounded_and_wrapping(void **state) {
  (void)state;
  assert_int_equal(gp_glove_time_us(0), 0);
  assert_int_equal(gp_glove_time_us(1.5), 1500000u);
  assert_int_equal(gp_glove_time_us(0.0000004), 0);
  assert_int_equal(gp_glove_time_us(0.0000006), 1);
  assert_int_equal(gp_glove_time_us(4294.967295), 4294967295u);
  assert_int_equal(gp_glove_time_us(4294.967296), 0);
  assert_int_equal(gp_glove_time_us(4294.967297), 1);
}

static void a_sample_decodes_to_the_same_sequence_time_channels_and_flags(void **state) {
  (void)state;
  const double values[GP_SAMPLE_CH_COUNT] = { 0.05, 0.3, 0.5, 0.77, 0.95 };
  uint16_t ch[GP_SAMPLE_CH_COUNT];
  for (unsigned c = 0; c < GP_SAMPLE_CH_COUNT; c++) ch[c] = gp_glove_value_count(values[c]);
  gp_sample s = gp_glove_sample(65535, gp_glove_time_us(12.345678), ch);
  assert_int_equal(s.flags, 0);
  s.flags = GP_SAMPLE_F_CALIBRATED | GP_SAMPLE_F_START;
  uint8_t wire[GP_MAX_WIRE];
  size_t n = gp_glove_sample_encode(&s, GP_SPEC_HASH, wire, sizeof wire);
  assert_true(n > 0 && n <= GP_MAX_WIRE);
  gp_msg got;
  assert_int_equal(decode_one(wire, n, &got), GP_EV_FRAME);
  assert_int_equal(got.type, GP_SAMPLE);
  assert_int_equal(got.u.sample.seq, 65535);
  assert_int_equal(got.u.sample.t_us, 12345678u);
  assert_int_equal(got.u.sample.flags, GP_SAMPLE_F_CALIBRATED | GP_SAMPLE_F_START);
  for (unsigned c = 0; c < GP_SAMPLE_CH_COUNT; c++) {
    assert_int_equal(got.u.sample.ch[c], ch[c]);
    assert_true(fabs(got.u.sample.ch[c] / (double)GP_SAMPLE_CH_MAX - values[c]) <= 0.5 / 4095);
  }
}

static void a_sample_under_another_hash_is_not_a_frame_for_this_build(void **state) {
  (void)state;
  const uint16_t ch[GP_SAMPLE_CH_COUNT] = { 1, 2, 3, 4, 5 };
  gp_sample s = gp_glove_sample(3, 3000, ch);
  uint8_t wire[GP_MAX_WIRE];
  gp_msg got;
  size_t n = gp_glove_sample_encode(&s, GP_SPEC_HASH ^ 1u, wire, sizeof wire);
  assert_int_not_equal(decode_one(wire, n, &got), GP_EV_FRAME);
}

static void too_small_a_buffer_encodes_nothing(void **state) {
  (void)state;
  gp_info info = gp_default_glove_info();
  const uint16_t ch[GP_SAMPLE_CH_COUNT] = { 0 };
  gp_sample s = gp_glove_sample(0, 0, ch);
  uint8_t wire[GP_MAX_WIRE];
  size_t info_n = gp_glove_info_encode(&info, wire, sizeof wire);
  size_t sample_n = gp_glove_sample_encode(&s, GP_SPEC_HASH, wire, sizeof wire);
  assert_int_equal(gp_glove_info_encode(&info, wire, info_n - 1), 0);
  assert_int_equal(gp_glove_sample_encode(&s, GP_SPEC_HASH, wire, sample_n - 1), 0);
  assert_int_equal(gp_glove_sample_encode(&s, GP_SPEC_HASH, wire, sample_n), sample_n);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(an_info_with_every_field_changed_decodes_to_the_same_fields),
    cmocka_unit_test(the_default_info_announces_this_build_and_the_factory_calibration),
    cmocka_unit_test(a_rate_is_rounded_into_infos_field_and_held_to_its_range),
    cmocka_unit_test(an_info_from_another_definition_is_a_spec_mismatch_naming_its_hash),
    cmocka_unit_test(values_become_counts_rounded_and_clamped),
    cmocka_unit_test(seconds_become_microseconds_rounded_and_wrapping),
    cmocka_unit_test(a_sample_decodes_to_the_same_sequence_time_channels_and_flags),
    cmocka_unit_test(a_sample_under_another_hash_is_not_a_frame_for_this_build),
    cmocka_unit_test(too_small_a_buffer_encodes_nothing),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
