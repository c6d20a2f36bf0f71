/* The Black Pill's clock plan for both crystals it ships with (25 MHz on
 * WeAct's boards, 8 MHz on many clones): the PLL values clock_f411.h
 * derives, checked here against RM0383's limits with arithmetic of the
 * test's own, down to the register word board.c writes and the USART1
 * divisor for every baud rate SET_RATE accepts. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "clock_plan.h"

/* RCC_PLLCFGR fields (RM0383, 6.3.2). */
static unsigned field(uint32_t w, unsigned shift, unsigned bits) {
  return (w >> shift) & ((1u << bits) - 1u);
}

/* The word's fields are the plan's M, N, P, Q and clock source. */
static void check_word(uint32_t w, uint32_t m, const clock_plan *p, unsigned src_hse) {
  assert_int_equal(field(w, 0, 6), m);
  assert_int_equal(field(w, 6, 9), p->plln);
  assert_int_equal(field(w, 16, 2) * 2u + 2u, p->pllp);
  assert_int_equal(field(w, 22, 1), src_hse);
  assert_int_equal(field(w, 24, 4), p->pllq);
}

/* The PLL fed with in_hz through M, within RM0383's ranges, gives 96 MHz
 * and 48 MHz exactly. */
static void check_pll(uint32_t in_hz, uint32_t m, const clock_plan *p) {
  double vco_in = (double)in_hz / m, vco = vco_in * p->plln;
  assert_true(m >= 2 && m <= 63);
  assert_true(p->plln >= 50 && p->plln <= 432);
  assert_true(vco_in >= 1e6 && vco_in <= 2e6);
  assert_true(vco >= 100e6 && vco <= 432e6);
  assert_true(p->pllq >= 2 && p->pllq <= 15);
  assert_true((uint64_t)in_hz * p->plln == (uint64_t)96000000u * m * p->pllp);
  assert_true((uint64_t)in_hz * p->plln == (uint64_t)48000000u * m * p->pllq);
}

/* Every rate SET_RATE accepts gets the nearest divisor and lands within
 * 0.2 %; returns the worst error in ppm. */
static unsigned check_bauds(const clock_plan *p) {
  static const uint32_t want[] = { 9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600 };
  assert_int_equal(p->n_bauds, sizeof want / sizeof want[0]);
  unsigned worst = 0;
  for (unsigned i = 0; i < p->n_bauds; i++) {
    assert_int_equal(p->baud[i], want[i]);
    assert_int_equal(p->brr[i], (uint32_t)lround((double)p->sysclk_hz / want[i]));
    double got = (double)p->sysclk_hz / p->brr[i];
    unsigned ppm = (unsigned)lround(fabs(got - want[i]) / want[i] * 1e6);
    if (ppm > 2000) fail_msg("%u baud comes out at %.0f (%u ppm off)", want[i], got, ppm);
    if (ppm > worst) worst = ppm;
  }
  return worst;
}

static void check_plan(const clock_plan *p, uint32_t hse, uint32_t m, uint32_t n, uint32_t m_hsi) {
  assert_int_equal(p->hse_hz, hse);
  assert_int_equal(p->pllm, m);
  assert_int_equal(p->plln, n);
  assert_int_equal(p->pllp, 2);
  assert_int_equal(p->pllq, 4);
  assert_int_equal(p->pllm_hsi, m_hsi);
  assert_int_equal(p->sysclk_hz, 96000000u);
  check_pll(hse, p->pllm, p);
  check_pll(16000000u, p->pllm_hsi, p);
  check_word(p->pllcfgr_hse, p->pllm, p, 1);
  check_word(p->pllcfgr_hsi, p->pllm_hsi, p, 0);
  /* 96 MHz: 115200 baud is 833 (0.04 % fast); the worst, 460800 and
   * 921600, are 0.16 % fast. */
  assert_int_equal(p->brr[4], 833);
  assert_int_equal(check_bauds(p), 1603);
}

/* 25 MHz / 25 = 1 MHz into the VCO, x 192 = 192 MHz, / 2 = 96 MHz. */
static void firmware_clock_25mhz_crystal_gives_96mhz_and_every_baud(void **state) {
  (void)state;
  check_plan(&clock_plan_hse25, 25000000u, 25, 192, 16);
}

/* 8 MHz / 4 = 2 MHz into the VCO (the jitter RM0383 recommends), x 96 =
 * 192 MHz, / 2 = 96 MHz. */
static void firmware_clock_8mhz_crystal_gives_96mhz_and_every_baud(void **state) {
  (void)state;
  check_plan(&clock_plan_hse8, 8000000u, 4, 96, 8);
}

/* What hardware/troubleshooting.md tells a maker with the wrong image: the
 * 25 MHz image on an 8 MHz crystal feeds its VCO 0.32 MHz and (if the PLL
 * locks at all) runs at 30.72 MHz, so 115200 baud comes out near 36900; the
 * 8 MHz image on a 25 MHz crystal asks for a 600 MHz VCO and a 300 MHz
 * core. */
static void firmware_clock_the_wrong_image_runs_the_pll_out_of_range(void **state) {
  (void)state;
  const clock_plan *p25 = &clock_plan_hse25, *p8 = &clock_plan_hse8;
  double in = 8e6 / p25->pllm, sys = in * p25->plln / p25->pllp;
  assert_true(in < 1e6);
  assert_true(in * p25->plln < 100e6);
  assert_int_equal(lround(sys), 30720000);
  assert_int_equal(lround(sys / p25->brr[4]), 36879);
  in = 25e6 / p8->pllm;
  assert_true(in > 2e6);
  assert_int_equal(lround(in * p8->plln), 600000000);
  assert_int_equal(lround(in * p8->plln / p8->pllp), 300000000);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(firmware_clock_25mhz_crystal_gives_96mhz_and_every_baud),
    cmocka_unit_test(firmware_clock_8mhz_crystal_gives_96mhz_and_every_baud),
    cmocka_unit_test(firmware_clock_the_wrong_image_runs_the_pll_out_of_range),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
