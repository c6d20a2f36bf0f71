/* The filter's documented numbers (fw_filter.h): a 4x oversampling mean, then
 * an EMA with alpha = 1/8 that reaches 50 % of a step after 6 ticks, 90 %
 * after 18, 99 % after 35, and lags a ramp by 7 ticks. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "fw_filter.h"

static void fill(uint16_t block[FW_BLOCK_LEN], uint16_t v) {
  for (unsigned i = 0; i < FW_BLOCK_LEN; i++) block[i] = v;
}

/* Ticks after a step until the output first reaches pct % of it. */
static unsigned ticks_to(unsigned pct) {
  fw_filter f;
  uint16_t block[FW_BLOCK_LEN], out[FW_N_CH];
  fw_filter_init(&f);
  fill(block, 1000);
  for (int i = 0; i < 100; i++) fw_filter_block(&f, block, out);
  fill(block, 3000);
  for (unsigned n = 1; n <= 200; n++) {
    fw_filter_block(&f, block, out);
    for (unsigned c = 1; c < FW_N_CH; c++) assert_int_equal(out[c], out[0]);
    if ((unsigned)(out[0] - 1000) * 100u >= 2000u * pct) return n;
  }
  return 0;
}

static void firmware_filter_step_settles_as_documented(void **state) {
  (void)state;
  assert_int_equal(FW_FILTER_SHIFT, 3);
  assert_int_equal(ticks_to(50), 6);
  assert_int_equal(ticks_to(90), 18);
  assert_int_equal(ticks_to(99), 35);
}

static void firmware_filter_falling_step_mirrors_rising(void **state) {
  (void)state;
  fw_filter f;
  uint16_t block[FW_BLOCK_LEN], out[FW_N_CH];
  fw_filter_init(&f);
  fill(block, 3000);
  fw_filter_block(&f, block, out);
  fill(block, 1000);
  unsigned n90 = 0;
  for (unsigned n = 1; n <= 100 && !n90; n++) {
    fw_filter_block(&f, block, out);
    if ((unsigned)(3000 - out[0]) * 100u >= 2000u * 90u) n90 = n;
  }
  assert_int_equal(n90, 18);
}

static void firmware_filter_lags_a_ramp_by_seven_ticks(void **state) {
  (void)state;
  fw_filter f;
  uint16_t block[FW_BLOCK_LEN], out[FW_N_CH];
  fw_filter_init(&f);
  /* 8 counts a tick: the steady-state lag of an EMA is (1-a)/a = 7 ticks,
   * i.e. 56 counts behind the input. */
  for (unsigned n = 0; n < 300; n++) {
    uint16_t x = (uint16_t)(500 + 8 * n);
    fill(block, x);
    fw_filter_block(&f, block, out);
    if (n > 100) {
      int lag = (int)x - (int)out[0];
      assert_in_range(lag, 55, 57);
    }
  }
}

static void firmware_filter_reaches_the_exact_level(void **state) {
  (void)state;
  fw_filter f;
  uint16_t block[FW_BLOCK_LEN], out[FW_N_CH];
  fw_filter_init(&f);
  fill(block, 100);
  fw_filter_block(&f, block, out);
  fill(block, 2345);
  for (int i = 0; i < 200; i++) fw_filter_block(&f, block, out);
  assert_int_equal(out[0], 2345);
  assert_int_equal(out[4], 2345);
}

static void firmware_filter_averages_the_oversamples(void **state) {
  (void)state;
  fw_filter f;
  uint16_t block[FW_BLOCK_LEN], out[FW_N_CH];
  fw_filter_init(&f);
  /* Channel c's oversamples are 100+c*10 + {0,1,2,3}: mean +1.5, rounds up.
   * The first block primes the filter, so its output is the mean itself. */
  for (unsigned s = 0; s < FW_OVERSAMPLE; s++)
    for (unsigned c = 0; c < FW_N_CH; c++) block[s * FW_N_CH + c] = (uint16_t)(100 + c * 10 + s);
  assert_int_equal(fw_filter_block(&f, block, out), 0);
  for (unsigned c = 0; c < FW_N_CH; c++) assert_int_equal(out[c], 100 + c * 10 + 2);
}

static void firmware_filter_flags_clipping(void **state) {
  (void)state;
  fw_filter f;
  uint16_t block[FW_BLOCK_LEN], out[FW_N_CH];
  fw_filter_init(&f);
  fill(block, 2000);
  assert_int_equal(fw_filter_block(&f, block, out), 0);
  block[FW_N_CH + 3] = (uint16_t)FW_ADC_MAX;
  assert_int_equal(fw_filter_block(&f, block, out), 1);
  fill(block, 2000);
  block[2] = 0;
  assert_int_equal(fw_filter_block(&f, block, out), 1);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(firmware_filter_step_settles_as_documented),
      cmocka_unit_test(firmware_filter_falling_step_mirrors_rising),
      cmocka_unit_test(firmware_filter_lags_a_ramp_by_seven_ticks),
      cmocka_unit_test(firmware_filter_reaches_the_exact_level),
      cmocka_unit_test(firmware_filter_averages_the_oversamples),
      cmocka_unit_test(firmware_filter_flags_clipping),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
