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

/* Runs a step from lo to hi: out[n] is channel 0's count n + 1 blocks after
 * the step (every channel is checked to agree). */
#define CURVE_TICKS 200u
static void step_curve(uint16_t lo, uint16_t hi, uint16_t out[CURVE_TICKS]) {
  fw_filter f;
  uint16_t block[FW_BLOCK_LEN], y[FW_N_CH];
  fw_filter_init(&f);
  fill(block, lo);
  fw_filter_block(&f, block, y);
  fill(block, hi);
  for (unsigned n = 0; n < CURVE_TICKS; n++) {
    fw_filter_block(&f, block, y);
    for (unsigned c = 1; c < FW_N_CH; c++) assert_int_equal(y[c], y[0]);
    out[n] = y[0];
  }
}

/* Every count of a falling step is the mirror image of the rising one, tick
 * by tick and until both have settled: the steps include ones whose
 * fixed-point state lands exactly half-way between two counts. */
static void firmware_filter_falling_step_mirrors_rising(void **state) {
  (void)state;
  static const uint16_t lows[] = { 0, 1, 1000, 2047 };
  uint16_t rise[CURVE_TICKS], fall[CURVE_TICKS];
  for (unsigned l = 0; l < sizeof lows / sizeof lows[0]; l++) {
    for (unsigned d = 1; d <= 2048; d++) {
      uint16_t lo = lows[l], hi = (uint16_t)(lo + d);
      step_curve(lo, hi, rise);
      step_curve(hi, lo, fall);
      for (unsigned n = 0; n < CURVE_TICKS; n++)
        if (rise[n] - lo != hi - fall[n])
          fail_msg("step %u..%u, tick %u: rising %u above, falling %u below", lo, hi, n + 1,
                   rise[n] - lo, hi - fall[n]);
      assert_int_equal(rise[CURVE_TICKS - 1], hi);
      assert_int_equal(fall[CURVE_TICKS - 1], lo);
    }
  }
  /* The documented step (1000 to 3000) reaches 90 % after 18 ticks both ways. */
  step_curve(3000, 1000, fall);
  unsigned n90 = 0;
  while (n90 < CURVE_TICKS && (unsigned)(3000 - fall[n90]) * 100u < 2000u * 90u) n90++;
  assert_int_equal(n90 + 1, 18);
}

/* A level half-way between two counts (oversamples 100, 101, 100, 101)
 * reads as the upper count, as the mean of a single block does, whether the
 * filter comes to it from below or from above. */
static void firmware_filter_settles_a_half_count_level_on_the_upper_count(void **state) {
  (void)state;
  static const uint16_t starts[] = { 0, 99, 100, 101, 102, 4095 };
  for (unsigned k = 0; k < sizeof starts / sizeof starts[0]; k++) {
    fw_filter f;
    uint16_t block[FW_BLOCK_LEN], out[FW_N_CH];
    fw_filter_init(&f);
    fill(block, starts[k]);
    fw_filter_block(&f, block, out);
    for (unsigned s = 0; s < FW_OVERSAMPLE; s++)
      for (unsigned c = 0; c < FW_N_CH; c++) block[s * FW_N_CH + c] = (uint16_t)(100 + s % 2u);
    for (int i = 0; i < 300; i++) fw_filter_block(&f, block, out);
    for (unsigned c = 0; c < FW_N_CH; c++)
      if (out[c] != 101) fail_msg("from %u: settled on %u, not 101", starts[k], out[c]);
  }
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
    cmocka_unit_test(firmware_filter_settles_a_half_count_level_on_the_upper_count),
    cmocka_unit_test(firmware_filter_lags_a_ramp_by_seven_ticks),
    cmocka_unit_test(firmware_filter_reaches_the_exact_level),
    cmocka_unit_test(firmware_filter_averages_the_oversamples),
    cmocka_unit_test(firmware_filter_flags_clipping),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
