/* The Black Pill's clock tree, derived from its crystal (FW_HSE_HZ in
 * fw_config.h) and checked at compile time against RM0383 (section 6, the
 * RCC) and the STM32F411 datasheet, so a crystal the PLL cannot use fails
 * the build instead of running the chip out of range with every baud rate
 * wrong.
 *
 *   SYSCLK = HSE / M * N / P = 96 MHz      48 MHz clock = HSE / M * N / Q
 *
 * 96 MHz is what the rest of the board assumes: APB1 at /2 (at most 50 MHz),
 * its timers at 2 x 48 = 96 MHz for TIM3's 4 kHz scan trigger, the ADC at
 * /4 = 24 MHz (at most 36), three flash wait states (90 < HCLK <= 100 MHz),
 * and a USART1 that reaches every rate in FW_BAUD_LIST within 0.2 %.
 * The VCO input is 2 MHz when the crystal is a multiple of it (RM0383
 * recommends 2 MHz to limit PLL jitter), else 1 MHz (the 25 MHz crystal).
 * If the crystal does not start, the same PLL runs from HSI (16 MHz) with
 * the same VCO input, so SYSCLK is 96 MHz either way.
 */
#ifndef CLOCK_F411_H
#define CLOCK_F411_H

#include <stdint.h>

#include "fw_config.h"
#include "stm32f4_regs.h"

#define CLOCK_HSI_HZ         16000000u
#define CLOCK_SYSCLK_WANT_HZ 96000000u
#define CLOCK_48MHZ          48000000u

#define CLOCK_VCO_IN_HZ (FW_HSE_HZ % 2000000u == 0u ? 2000000u : 1000000u)
#define CLOCK_PLLM      (FW_HSE_HZ / CLOCK_VCO_IN_HZ)
#define CLOCK_PLLM_HSI  (CLOCK_HSI_HZ / CLOCK_VCO_IN_HZ)
#define CLOCK_PLLP      2u
#define CLOCK_PLLN      (CLOCK_SYSCLK_WANT_HZ * CLOCK_PLLP / CLOCK_VCO_IN_HZ)
#define CLOCK_PLLQ      (CLOCK_SYSCLK_WANT_HZ * CLOCK_PLLP / CLOCK_48MHZ)

/* RCC_PLLCFGR from the crystal, and for the HSI fallback. */
#define CLOCK_PLLCFGR_FIELDS(m) \
  (RCC_PLLCFGR_M(m) | RCC_PLLCFGR_N(CLOCK_PLLN) | RCC_PLLCFGR_P2 | RCC_PLLCFGR_Q(CLOCK_PLLQ))
#define CLOCK_PLLCFGR_HSE (CLOCK_PLLCFGR_FIELDS(CLOCK_PLLM) | RCC_PLLCFGR_SRC_HSE)
#define CLOCK_PLLCFGR_HSI CLOCK_PLLCFGR_FIELDS(CLOCK_PLLM_HSI)

/* What the PLL makes of those integers, rounding nothing away. */
#define CLOCK_VCO_HZ    ((unsigned long long)FW_HSE_HZ * CLOCK_PLLN / CLOCK_PLLM)
#define CLOCK_SYSCLK_HZ ((uint32_t)(CLOCK_VCO_HZ / CLOCK_PLLP))
#define CLOCK_PLL48_HZ  ((uint32_t)(CLOCK_VCO_HZ / CLOCK_PLLQ))

/* USART1 sits on APB2 at SYSCLK; oversampling by 16, BRR = f / baud rounded
 * (mantissa and fraction together). The error is |f / BRR - baud| / baud. */
#define CLOCK_USART_BRR(f, baud)    (((f) + (baud) / 2u) / (baud))
#define CLOCK_BAUD_PRODUCT(f, baud) ((unsigned long long)CLOCK_USART_BRR(f, baud) * (baud))
#define CLOCK_BAUD_ERROR_PPM(f, baud)                                        \
  (((f) > CLOCK_BAUD_PRODUCT(f, baud) ? (f)-CLOCK_BAUD_PRODUCT(f, baud)      \
                                      : CLOCK_BAUD_PRODUCT(f, baud) - (f)) * \
   1000000ull / CLOCK_BAUD_PRODUCT(f, baud))
/* Both ends' clocks and the line share a receiver's tolerance of a few per
 * cent; the glove takes at most 0.2 % of it (firmware/README.md, Rates). */
#define CLOCK_BAUD_MAX_ERROR_PPM 2000u

/* --- checks --------------------------------------------------------------- */
_Static_assert(FW_HSE_HZ >= 4000000u && FW_HSE_HZ <= 26000000u,
               "FW_HSE_HZ: the F411's crystal oscillator takes 4 to 26 MHz");
_Static_assert(FW_HSE_HZ % CLOCK_VCO_IN_HZ == 0u,
               "FW_HSE_HZ: the crystal must be a whole number of MHz for a 96 MHz PLL");
_Static_assert(CLOCK_PLLM >= 2u && CLOCK_PLLM <= 63u, "PLLM must be 2..63");
_Static_assert(CLOCK_PLLM_HSI >= 2u && CLOCK_PLLM_HSI * CLOCK_VCO_IN_HZ == CLOCK_HSI_HZ,
               "PLLM for the HSI fallback must give the same VCO input");
_Static_assert(CLOCK_VCO_IN_HZ >= 1000000u && CLOCK_VCO_IN_HZ <= 2000000u,
               "PLL VCO input must be 1..2 MHz");
_Static_assert(CLOCK_PLLN >= 50u && CLOCK_PLLN <= 432u, "PLLN must be 50..432");
_Static_assert(CLOCK_PLLP == 2u, "RCC_PLLCFGR_P2 encodes PLLP = 2 only");
_Static_assert(CLOCK_VCO_HZ >= 100000000ull && CLOCK_VCO_HZ <= 432000000ull,
               "PLL VCO output must be 100..432 MHz");
_Static_assert(CLOCK_PLLQ >= 2u && CLOCK_PLLQ <= 15u, "PLLQ must be 2..15");
_Static_assert(CLOCK_PLL48_HZ == CLOCK_48MHZ,
               "the PLL's 48 MHz output (USB OTG FS needs exactly 48, SDIO and RNG at most)");
_Static_assert(CLOCK_SYSCLK_HZ == CLOCK_SYSCLK_WANT_HZ, "SYSCLK must come out at 96 MHz");
_Static_assert(CLOCK_SYSCLK_HZ <= 100000000u, "SYSCLK above the F411's 100 MHz");
_Static_assert(CLOCK_SYSCLK_HZ % (FW_TICK_HZ * FW_OVERSAMPLE) == 0u,
               "TIM3 cannot divide SYSCLK into the scan rate exactly");

#define CLOCK_CHECK_BAUD(b)                                                            \
  _Static_assert(CLOCK_USART_BRR(CLOCK_SYSCLK_HZ, b) >= 16u &&                         \
                     CLOCK_USART_BRR(CLOCK_SYSCLK_HZ, b) <= 0xFFFFu,                   \
                 "USART1 BRR out of range for a rate in FW_BAUD_LIST");                \
  _Static_assert(CLOCK_BAUD_ERROR_PPM(CLOCK_SYSCLK_HZ, b) <= CLOCK_BAUD_MAX_ERROR_PPM, \
                 "USART1 misses a rate in FW_BAUD_LIST by more than 0.2 % at this SYSCLK");
FW_BAUD_LIST(CLOCK_CHECK_BAUD)

#endif
