/* The Black Pill's clock plan (firmware/boards/blackpill_f411/clock_f411.h)
 * as the firmware derives it for one crystal. Each crystal's plan is
 * compiled in its own file (clock_plan_hse*.c), with FW_HSE_HZ set as the
 * firmware's Makefile sets it, so the compile-time checks run for each. */
#ifndef CLOCK_PLAN_H
#define CLOCK_PLAN_H

#include <stdint.h>

#define CLOCK_PLAN_MAX_BAUDS 16u

typedef struct clock_plan {
  uint32_t hse_hz;
  uint32_t pllm, plln, pllp, pllq, pllm_hsi;
  uint32_t pllcfgr_hse, pllcfgr_hsi; /* the register words board.c writes */
  uint32_t sysclk_hz;                /* as the header works it out */
  unsigned n_bauds;
  uint32_t baud[CLOCK_PLAN_MAX_BAUDS];
  uint32_t brr[CLOCK_PLAN_MAX_BAUDS]; /* USART1_BRR for each, at sysclk_hz */
} clock_plan;

/* Fills a plan from clock_f411.h for the FW_HSE_HZ in force. */
#define CLOCK_PLAN_BAUD(b)  b,
#define CLOCK_PLAN_BRR(b)   CLOCK_USART_BRR(CLOCK_SYSCLK_HZ, b),
#define CLOCK_PLAN_COUNT(b) +1u
#define CLOCK_PLAN_DEFINE(name)                   \
  const clock_plan name = {                       \
    .hse_hz = FW_HSE_HZ,                          \
    .pllm = CLOCK_PLLM,                           \
    .plln = CLOCK_PLLN,                           \
    .pllp = CLOCK_PLLP,                           \
    .pllq = CLOCK_PLLQ,                           \
    .pllm_hsi = CLOCK_PLLM_HSI,                   \
    .pllcfgr_hse = CLOCK_PLLCFGR_HSE,             \
    .pllcfgr_hsi = CLOCK_PLLCFGR_HSI,             \
    .sysclk_hz = CLOCK_SYSCLK_HZ,                 \
    .n_bauds = 0u FW_BAUD_LIST(CLOCK_PLAN_COUNT), \
    .baud = { FW_BAUD_LIST(CLOCK_PLAN_BAUD) },    \
    .brr = { FW_BAUD_LIST(CLOCK_PLAN_BRR) },      \
  };

extern const clock_plan clock_plan_hse25;
extern const clock_plan clock_plan_hse8;

#endif
